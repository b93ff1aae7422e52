"""Drives and brakes that behave like the machines (SPEC 6.1, PHYSICS 5.1), whole cycles of the
transient engine (engine/dynamics): capstan slip, each drive pulley on its own, torque
following, dol motors, brake ramps and holding.

Every check is against a hand calculation or a law, with its tolerance in the assertion."""

from __future__ import annotations

import functools
import math
import re

import numpy as np
import pytest
from numpy.testing import assert_allclose

from beltstudy.engine.conveyor import Scenario, load_conveyor, parse_conveyor
from beltstudy.engine.dynamics import DynamicsOptions, build_system, simulate
from beltstudy.engine.run import run_one
from beltstudy.engine.statics import solve_steady
from tests.conftest import CONVEYORS
from tests.engine.conftest import dual_head, hand_conv, hand_drive, steep_incline

G = 9.81


def _euler(mu=0.35, wrap_deg=200.0):
    return math.exp(mu * math.radians(wrap_deg))


# --------------------------------------------------------------------------------------
# capstan friction with slip


def test_slipping_pulley_transmits_the_capstan_limit_motoring():
    """An open-loop drive force far above what the slack side allows: the pulley slips and
    passes T_slack (e^(mu_k theta) - 1) to the belt, T_slack the outgoing side (1 %)."""
    conv = hand_conv(drives=[hand_drive(friction=0.35, friction_kinetic=0.25)],
                     takeup={"type": "gravity", "position": "tail", "mass_kg": 3000})
    st = solve_steady(conv, model="din", n_elements=60)
    sysm = build_system(conv, Scenario(run_s=30), st, DynamicsOptions(force_start_n=150e3))
    r = simulate(sysm, t_end_s=sysm.model.cycle.t_pre + 6.0)
    ts = r.timeseries
    slipping = ts["v_drive1_m_s"] - ts["v_mean_m_s"] > 0.05  # the shaft runs ahead
    assert slipping.sum() > 10
    capstan = ts["t_head_out_kn"] * (_euler(0.25) - 1.0)
    assert_allclose(ts["f_belt1_kn"][slipping], capstan[slipping], rtol=0.01)
    assert r.summary["drive1_slip_s"] > 1.0


def test_slipping_pulley_transmits_the_capstan_limit_braking():
    """A brake on the drive's shaft far stronger than the capstan allows: the shaft stops,
    the belt slides over it and receives T_slack (e^(mu_k theta) - 1) against its motion,
    T_slack the incoming side (1 %)."""
    conv = hand_conv(drives=[hand_drive(friction_kinetic=0.25)],
                     brakes=[{"drive": 1, "force_kn": 400, "delay_s": 0.0, "ramp_s": 0.2}],
                     takeup={"type": "gravity", "position": "tail", "mass_kg": 8000})
    r = run_one(conv, Scenario(start={"time_s": 20}, run_s=5, record_dt_s=0.02,
                               stop={"mode": "brake", "time_s": 5}, elements=60),
                model="din")
    ts = r.timeseries
    # the slide of the braking, before the belt first comes down to 0.3 m/s (after it the
    # stretched carry strand may carry the belt on over the held pulley without sliding)
    # the brake's own force, after the start (before it, it holds the belt at rest)
    braked = ts["t_s"] > ts["t_s"][(ts["f_brake_kn"] > 0) & (ts["t_s"] > 2.0 + 20.0)].iloc[0]
    first_slow = ts["t_s"][braked & (ts["v_mean_m_s"] <= 0.3)].iloc[0]
    sliding = (ts["v_drive1_m_s"].abs() < 1e-9) & (ts["v_mean_m_s"] > 0.3) & (ts["t_s"] < first_slow)
    assert sliding.sum() > 5
    capstan = -ts["t_head_in_kn"] * (_euler(0.25) - 1.0)
    assert_allclose(ts["f_belt1_kn"][sliding], capstan[sliding], rtol=0.01)
    assert r.summary["drive1_slip_m"] > 0.5


def _braked_slide(dt_safety):
    """The braking slide above at a step of ``dt_safety`` of the stability limit: the records
    while the belt slides over the held pulley (t, f_belt1 [kN], T_in [kN])."""
    conv = hand_conv(drives=[hand_drive(friction_kinetic=0.25)],
                     brakes=[{"drive": 1, "force_kn": 400, "delay_s": 0.0, "ramp_s": 0.2}],
                     takeup={"type": "gravity", "position": "tail", "mass_kg": 8000})
    r = run_one(conv, Scenario(start={"time_s": 20}, run_s=5, record_dt_s=0.02,
                               stop={"mode": "brake", "time_s": 5}, elements=60),
                model="din", options=DynamicsOptions(dt_safety=dt_safety))
    ts = r.timeseries
    # the brake's own force, after the start (before it, it holds the belt at rest)
    braked = ts["t_s"] > ts["t_s"][(ts["f_brake_kn"] > 0) & (ts["t_s"] > 2.0 + 20.0)].iloc[0]
    first_slow = ts["t_s"][braked & (ts["v_mean_m_s"] <= 0.3)].iloc[0]
    sliding = (ts["v_drive1_m_s"].abs() < 1e-9) & (ts["v_mean_m_s"] > 0.3) & (ts["t_s"] < first_slow)
    return ts["t_s"][sliding].to_numpy(), ts["f_belt1_kn"][sliding].to_numpy(), \
        ts["t_head_in_kn"][sliding].to_numpy()


def test_a_sliding_pulleys_force_does_not_depend_on_the_step():
    """PHYSICS 5.2: the pulley held by its brake while the belt slides over it passes the
    kinetic capstan force T_in (e^(mu_k theta) - 1) at every step (1 %), and the slide is the
    same at 1/8, 1/4 and 1/2 of the stability limit: it starts and ends at the same time
    (within one record, 0.02 s), its impulse (the force's integral over the slide: what slows
    the belt) is within 0.5 % of the finest step's, and its force at each time from 0.1 s
    after the onset within 3 % for 95 % of the records and 6 % at any. The force follows the
    incoming tension, which comes through the free belt: the limited mesh viscosity keeps its
    fronts sharp, and a sharp front arrives a record earlier or later at another Courant
    number (measured: 95 % of the records within 1.1 % at 1/4 and 2.6 % at 1/2, the worst
    4.3 %, at a front; the ratio to T_in above holds to 1 % at every record). At the onset
    the friction falls from static, mu 0.35, to sliding, mu_k 0.25: the force on the belt
    drops by 40 % at once and rings the head element for about 0.1 s, a sudden event the mesh resolves, not the
    step (up to 12 % between the steps there)."""
    runs = {f: _braked_slide(f) for f in (0.125, 0.25, 0.5)}
    for t, f_belt, t_in in runs.values():
        assert len(t) > 5
        assert_allclose(f_belt, -t_in * (_euler(0.25) - 1.0), rtol=0.01)
    t_fine, f_fine, _ = runs[0.125]
    for f in (0.25, 0.5):
        t, f_belt, _ = runs[f]
        assert abs(t[0] - t_fine[0]) <= 0.02 + 1e-9 and abs(t[-1] - t_fine[-1]) <= 0.02 + 1e-9
        both = t <= t_fine[-1]
        f_at = np.interp(t[both], t_fine, f_fine)
        assert np.trapezoid(f_belt[both], t[both]) == pytest.approx(
            np.trapezoid(f_at, t[both]), rel=0.005)
        late = t[both] >= t_fine[0] + 0.1
        rel = np.abs(f_belt[both][late] / f_at[late] - 1.0)
        assert np.percentile(rel, 95) <= 0.03 and rel.max() <= 0.06, (np.percentile(rel, 95),
                                                                       rel.max())


def test_the_drive_force_of_a_start_that_slips_from_rest_does_not_depend_on_the_step():
    """downhill-regen's vfd drive takes over from the brake holding the loaded decline at rest
    (its loop's integrator starts from the holding force) on a pulley that cannot pass that
    force: the pulley slips at once. The drive force at that instant is the holding force, the
    peak of the start, at 1/8, 1/4 and 1/2 of the stability limit (1 %; the loop's response
    on the light slipping shaft, about 7 ms, is shorter than the steps). The take-up is given
    at 80 t, below the 102 t its auto size holds the breakaway with (the drive taking the net
    gravity pull at standstill, ``slip_breakaway``), so the pulley cannot pass the hold."""
    base = load_conveyor(CONVEYORS / "downhill-regen.yaml")
    conv = base.model_copy(update={"takeup": base.takeup.model_copy(update={"mass_kg": 80000.0})})
    st = solve_steady(conv, model="din")
    for f in (0.125, 0.25, 0.5):
        sysm = build_system(conv, Scenario(), st, DynamicsOptions(dt_safety=f))
        r = simulate(sysm, t_end_s=sysm.model.cycle.t_pre + 1.0)
        assert r.summary["drive1_slip_s"] > 0.5
        assert r.summary["drive1_force_max_kn"] == pytest.approx(
            abs(sysm.hold_force_n) / 1e3, rel=0.01)


def test_a_pulley_at_its_grip_passes_no_more_than_its_grip_at_any_step():
    """The 16.8 km overland's tail drive (a torque follower) slips for about 48 s in the
    start; for part of it (near t = 75 s at half the limit) it is at its grip with its belt
    above the follower's speed window: sticking needs a little more than T_slack
    (e^(mu theta) - 1), sliding lets the shaft fall back behind the belt. Within the step the pulley then slides at the belt's speed with the sliding force
    (PHYSICS 5.2), so at no step does a drive pulley pass more than its grip: the lowest
    tension ratio margin e^(mu theta) / (T_tight / T_slack) over the whole cycle stays at 1
    within 0.1 % (the pulley element's own inertia and resistance, which the capstan does not
    carry, are the rest), at 1/4, 1/2 and 0.9 of the stability limit. (Ending the step in
    whichever of the two states the last pass of the active set left gave 0.955 to 0.961.)"""
    conv = load_conveyor(CONVEYORS / "overland-16km.yaml")
    for f in (0.25, 0.5, 0.9):
        s = run_one(conv, Scenario(), model="din", options=DynamicsOptions(dt_safety=f)).summary
        assert s["drive2_slip_s"] > 10.0
        assert s["slip_margin_min_dyn"] > 0.999


def test_below_the_limit_a_pulley_does_not_slip():
    conv = hand_conv(drives=[hand_drive()], takeup={"type": "gravity", "position": "tail",
                                                      "mass_kg": 8000})
    r = run_one(conv, Scenario(start={"time_s": 30}, run_s=10, elements=60), model="din")
    assert r.summary["drive1_slip_s"] == 0.0
    assert r.summary["drive1_slip_margin_min"] > 1.0
    assert "slipped" not in r.summary["message"]


def test_slip_can_be_switched_off_for_verification():
    conv = hand_conv(drives=[hand_drive()], takeup={"type": "gravity", "position": "tail",
                                                      "mass_kg": 3000})
    st = solve_steady(conv, model="din", n_elements=60)
    sysm = build_system(conv, Scenario(run_s=30), st,
                        DynamicsOptions(force_start_n=150e3, slip=False))
    r = simulate(sysm, t_end_s=sysm.model.cycle.t_pre + 3.0)
    assert r.summary["drive1_slip_s"] == 0.0


# --------------------------------------------------------------------------------------
# drives


def _rigid_time_to(fraction, mass, rated, te, v_d, curve, dt=1e-4):
    """Rigid body M dv/dt = F_r y(v / v_d) - Te from rest (y piecewise linear), by hand
    (explicit midpoint steps): time to reach fraction x v_d [s]."""
    xs = np.array([p[0] for p in curve])
    ys = np.array([p[1] for p in curve])

    def acc(v):
        return (rated * np.interp(v / v_d, xs, ys) - te) / mass

    v, t = 0.0, 0.0
    while v < fraction * v_d:
        vm = v + 0.5 * dt * acc(v)
        v += dt * acc(vm)
        t += dt
    return t


def test_dol_start_matches_the_rigid_body_within_3_percent():
    """Motor on the line (default induction-motor curve), a short stiff belt that does not
    slip: the time to 90 % speed equals the rigid-body integration of the motor curve
    against the moving mass and Te (3 %)."""
    conv = hand_conv(drives=[hand_drive(control="dol", rated_power_kw=240, inertia_kg_m2=100)],
                     takeup={"type": "gravity", "position": "tail", "mass_kg": 16000},
                     belt={"width_m": 1.0, "rating_kn_m": 1000, "modulus_kn_m": 600000,
                           "carcass_mass_kg_m2": 20.0, "top_cover_mm": 0, "bottom_cover_mm": 0})
    st = solve_steady(conv, model="din", n_elements=60)
    sysm = build_system(conv, Scenario(start={"time_s": 30}, run_s=10, elements=60), st)
    r = simulate(sysm, t_end_s=sysm.model.cycle.t_pre + 25.0)
    assert r.summary["drive1_slip_s"] == 0.0
    ts = r.timeseries
    t = ts["t_s"].to_numpy() - sysm.model.cycle.t_pre
    t90 = float(t[np.argmax(ts["v_mean_m_s"].to_numpy() >= 0.9 * 4.0)])
    expected = _rigid_time_to(0.9, sysm.model.control.m_tot, 240e3 / 4.0, st.te_n, 4.0,
                              conv.drives[0].curve)
    assert t90 == pytest.approx(expected, rel=0.03)


def test_dol_fluid_coupling_lets_the_motor_run_up_first():
    """With a constant-fill fluid coupling the motor is at speed before the belt is: its
    torque grows with the square of the input speed, so the motor runs up nearly unloaded."""
    conv = hand_conv(drives=[hand_drive(control="dol", rated_power_kw=240, inertia_kg_m2=300,
                                        coupling="fluid")],
                     takeup={"type": "gravity", "position": "tail", "mass_kg": 16000})
    st = solve_steady(conv, model="din", n_elements=60)
    sysm = build_system(conv, Scenario(start={"time_s": 30}, run_s=10, elements=60), st)
    ki_r = simulate(sysm, t_end_s=sysm.model.cycle.t_pre + 40.0)
    ts = ki_r.timeseries
    assert ki_r.summary["start_time_s"] is not None
    # the coupling's stall torque bounds the force at the belt: 1.6 x rated
    assert ts["f_drive1_kn"].max() <= 1.6 * 60.0 * 1.01
    assert ts["v_mean_m_s"].iloc[-1] == pytest.approx(4.0, rel=0.05)
    # the motor's own speed behind the coupling (v_motor1_m_s): ahead of the pulley while
    # it runs up, and running with a small positive slip (a constant-fill coupling slips a
    # few percent at its rated torque)
    vm, vs = ts["v_motor1_m_s"].to_numpy(), ts["v_drive1_m_s"].to_numpy()
    assert (vm >= vs - 1e-6).all()
    half = int(np.argmax(vs >= 0.5 * 4.0))
    assert vm[half] > 0.9 * 4.0
    slip = (vm[-1] - vs[-1]) / vm[-1]
    assert 0.0 < slip < 0.1


def test_vfd_motor_speed_is_the_shaft_speed():
    """Without a coupling the motor turns with its pulley: ``v_motor1_m_s`` is the shaft's."""
    conv = hand_conv(drives=[hand_drive()],
                     takeup={"type": "gravity", "position": "tail", "mass_kg": 16000})
    r = run_one(conv, Scenario(start={"time_s": 10}, run_s=2, elements=40), model="din")
    ts = r.timeseries
    assert_allclose(ts["v_motor1_m_s"], ts["v_drive1_m_s"], rtol=0, atol=0)


def test_takeup_travel_is_reported_per_phase():
    """``takeup_travel_start_m`` and ``takeup_travel_stop_m`` are the carriage's range within
    the start (start to stop command) and the stop (stop command to the end): each equals the
    range of the recorded positions in its phase to within what the carriage moves between
    two records, neither exceeds the whole cycle's travel, and together they cover it."""
    conv = hand_conv(drives=[hand_drive()],
                     takeup={"type": "gravity", "position": "tail", "mass_kg": 16000})
    scn = Scenario(start={"time_s": 10}, run_s=5, elements=40, record_dt_s=0.02,
                   stop={"mode": "coast"})
    r = run_one(conv, scn, model="din")
    s, ts = r.summary, r.timeseries
    t, x = ts["t_s"].to_numpy(), ts["x_takeup_m"].to_numpy()
    t_cmd = r.transient.system.stop_command_s
    t_pre = r.transient.system.model.cycle.t_pre
    step = np.abs(np.diff(x)).max()  # most the carriage moves between two records
    for phase, m in (("start", (t >= t_pre) & (t <= t_cmd)), ("stop", t >= t_cmd)):
        assert s[f"takeup_travel_{phase}_m"] == pytest.approx(np.ptp(x[m]), abs=step + 1e-9)
        assert s[f"takeup_travel_{phase}_m"] <= s["takeup_travel_m"] + 1e-12
    assert s["takeup_travel_start_m"] > 0.0 and s["takeup_travel_stop_m"] > 0.0
    assert s["takeup_travel_m"] <= (s["takeup_travel_start_m"] + s["takeup_travel_stop_m"]
                                    + step + 1e-9)


def _light_dol(**over):
    """The hand conveyor on a 240 kW dol drive through a fluid coupling whose whole drive
    train is 2 kg m2 at the pulley shaft: it would reach design speed unloaded in well under a
    millisecond, far below the belt's step."""
    return hand_conv(drives=[hand_drive(control="dol", rated_power_kw=240, inertia_kg_m2=2.0,
                                        coupling="fluid", **over)],
                     takeup={"type": "gravity", "position": "tail", "mass_kg": 16000})


def test_a_light_dol_drive_train_sets_the_step_and_runs_steadily():
    """The automatic step resolves the fastest dol drive train: at most half the time its
    lightest body (shaft or motor) takes to reach design speed unloaded at rated force, m v_d /
    F_r (F_r = 240 kW / 4 m/s by hand), and the message says so. Running, the drive then
    gives the steady peripheral force (1 %) with a steady shaft (no chatter: its speed varies
    by under 0.1 % of design)."""
    conv = _light_dol()
    st = solve_steady(conv, model="din", n_elements=40)
    sysm = build_system(conv, Scenario(start={"time_s": 20}, run_s=20, stop={"mode": "coast"},
                                       elements=40), st)
    lightest = min(sysm.model.shafts.mass.min(),
                   sysm.model.drives.motor_mass[sysm.model.drives.motor_mass > 1.0].min())
    tau = lightest * 4.0 / (240e3 / 4.0)
    assert sysm.dt_s <= 0.5 * tau * (1 + 1e-12)
    assert sysm.dt_s < 0.1 * sysm.dt_limit_s  # the drive train, not the belt, sets it
    r = simulate(sysm, conveyor=conv)
    assert r.status != "failed", r.message
    assert "resolves the fastest dol drive train" in r.message
    ts = r.timeseries
    t = ts["t_s"].to_numpy()
    running = (t > sysm.stop_command_s - 5.0) & (t < sysm.stop_command_s)
    assert ts["f_drive1_kn"][running].mean() == pytest.approx(st.te_n / 1e3, rel=0.01)
    assert ts["v_drive1_m_s"][running].std() < 1e-3 * 4.0


def test_a_diverged_drive_train_is_named():
    """The same drive train on a fixed step at the belt's own scale (0.9 of its stability
    limit): the light drive train cannot follow its coupling within a step. The run fails, and
    the message names the drive's motor behind its coupling and what avoids it, instead of
    carrying a runaway motor through a result."""
    conv = _light_dol()
    st = solve_steady(conv, model="din", n_elements=40)
    auto = build_system(conv, Scenario(elements=40, stop={"mode": "coast"}), st)
    scn = Scenario(elements=40, stop={"mode": "coast"}, dt_s=0.9 * auto.dt_limit_s)
    sysm = build_system(conv, scn, st)
    assert "is longer than the fastest dol drive train" in "; ".join(sysm.notes)
    r = simulate(sysm, conveyor=conv)
    assert r.status == "failed"
    assert r.message.startswith("diverged: the motor of drive 1 (head) behind its coupling")
    assert "motor_inertia_kg_m2" in r.message and "scenario.dt_s" in r.message


def test_a_decline_the_drive_cannot_hold_runs_away_as_a_rigid_body():
    """The hand conveyor falling 150 m (a regenerating belt, Te < 0) coasting after a power
    failure with no brake: the belt accelerates at -Te / M, M every moving mass (DIN's
    resistances do not depend on speed), within 1 %; the run ends when the mean speed
    reaches twice the design speed, as a warning that says so, not a failure."""
    conv = hand_conv(profile=[{"length_m": 1000, "lift_m": -150}])
    st = solve_steady(conv, model="din", n_elements=100)
    assert st.te_n < 0.0
    sysm = build_system(conv, Scenario(start={"time_s": 20}, run_s=10, stop={"mode": "coast"},
                                       elements=100), st)
    r = simulate(sysm, conveyor=conv)
    assert r.status == "warning"
    assert "the belt ran away forwards during the stop" in r.message
    # how much would hold it: -Te at speed, and at rest the material's pull, m'_L g H =
    # 50 kg/m x 9.81 x 150 m = 73.58 kN (the belt's own weight cancels round the loop)
    said = re.search(r"the belt pulls ([\d.]+) kN forwards at speed, -Te, and ([\d.]+) kN at "
                     r"rest, its net gravity pull", r.message)
    assert said, r.message
    assert float(said.group(1)) == pytest.approx(-st.te_n / 1e3, rel=1e-3)
    assert float(said.group(2)) == pytest.approx(50.0 * 9.81 * 150.0 / 1e3, rel=1e-3)
    # a coast: no brake acts, so more brake force is no lever (a 3 km decline doubled to
    # 800 kN ran away at the same time); a brake stop is
    assert "more brake force, brakes" not in r.message
    assert ("brakes that act in the stop (stop.mode: brake: in this stop no brake acts, so more "
            "brake force would not)") in r.message
    ts = r.timeseries
    t, v = ts["t_s"].to_numpy(), ts["v_mean_m_s"].to_numpy()
    assert v[-1] == pytest.approx(2.0 * 4.0, rel=0.01)
    fast = (t > sysm.stop_command_s) & (v > 1.1 * 4.0) & (v < 1.8 * 4.0)
    a = np.polyfit(t[fast], v[fast], 1)[0]
    assert a == pytest.approx(-st.te_n / sysm.model.control.m_tot, rel=0.01)
    assert r.summary["stop_time_s"] is None


def test_dual_head_drive_running_equals_statics_and_shares_equally():
    """Torque following: the two drives give equal force within 2 % during the start and
    running; the running tensions in, between and out equal the statics within 1 %."""
    conv = dual_head(takeup={"type": "gravity", "position": "tail", "mass_kg": 9000})
    st = solve_steady(conv, model="din", n_elements=80)
    sysm = build_system(conv, Scenario(start={"time_s": 40}, run_s=40, elements=80), st)
    r = simulate(sysm, t_end_s=sysm.stop_command_s - sysm.dt_s)
    assert r.summary["drive1_slip_s"] == 0.0 and r.summary["drive2_slip_s"] == 0.0
    ts = r.timeseries
    moving = ts["t_s"] > sysm.model.cycle.t_pre + 1.0
    f1, f2 = ts["f_drive1_kn"][moving], ts["f_drive2_kn"][moving]
    assert_allclose(f1, f2, rtol=0.02, atol=0.02 * f1.abs().max())
    T = r.raw["tension"]
    e1, e2 = st.loop.drive_elements
    for j in (e1 - 1, e1, e2):
        assert T[j] == pytest.approx(st.tension_n[j], rel=0.01)


def _handover_start(n: int, handover_s=None):
    """Two head drives (vfd, half each) on a 1 km conveyor rising 100 m with 2 000 t/h at 4 m/s,
    ``n`` elements, from rest to 1.5 s after the start command of a 30 s s-curve."""
    belt = {"width_m": 1.0, "rating_kn_m": 2500, "modulus_kn_m": 60000,
            "carcass_mass_kg_m2": 20.0, "top_cover_mm": 0, "bottom_cover_mm": 0}
    conv = dual_head(profile=[{"length_m": 1000, "lift_m": 100}], belt=belt,
                     material={"capacity_t_h": 2000, "density_t_m3": 1.0})
    st = solve_steady(conv, model="din", n_elements=n)
    sysm = build_system(conv, Scenario(start={"time_s": 30}, run_s=10, elements=n,
                                       record_dt_s=0.005), st,
                        DynamicsOptions(handover_s=handover_s))
    return sysm, simulate(sysm, t_end_s=sysm.model.cycle.t_pre + 1.5)


def test_the_start_hands_the_holding_force_to_the_drives_without_a_jolt():
    """At rest the master's pulley holds the load's pull, m'_L g H = 2000 / 3.6 / 4 x 9.81 x 100
    = 136.25 kN (the belt's own weight cancels round the loop). In the start's hand-over
    (``HANDOVER_S`` = 0.3 s, docs/dynamics.md *The start from rest*) the second drive builds its
    half while the hold keeps the belt: at its end each drive gives 68.1 kN (1 %). The second
    pulley's largest speed in the first 1.5 s is the same at 60 and 240 elements within 25 %
    and below 1 % of design speed; with the pull passed to it in one step (``handover_s=0``) the
    short belt between the pulleys rings, 3 % to 5 % of design speed growing with the mesh."""
    m_l = 2000.0 / 3.6 / 4.0
    hold = m_l * 9.81 * 100.0
    peaks = {}
    for n in (60, 240):
        sysm, r = _handover_start(n)
        assert sysm.model.cycle.t_hand == pytest.approx(0.3)
        assert sysm.hold_force_n == pytest.approx(hold, rel=1e-6)
        ts = r.timeseries
        tau = ts["t_s"].to_numpy() - sysm.model.cycle.t_pre
        end = (tau > 0.25) & (tau <= 0.3)
        assert_allclose(ts["f_drive1_kn"][end].iloc[-1], 0.5 * hold / 1e3, rtol=0.01)
        assert_allclose(ts["f_drive2_kn"][end].iloc[-1], 0.5 * hold / 1e3, rtol=0.01)
        peaks[n] = ts["v_drive2_m_s"][tau > 0.0].abs().max()
        assert peaks[n] < 0.01 * 4.0
    assert peaks[240] == pytest.approx(peaks[60], rel=0.25)
    jolts = [_handover_start(n, handover_s=0.0)[1].timeseries["v_drive2_m_s"].abs().max()
             for n in (60, 240)]
    assert 0.03 * 4.0 < jolts[0] < jolts[1]


def running_stretch_m(sysm) -> float:
    """The belt length the start must move past the drive to change the at-rest strains into
    the running ones [m]: the sum over the springs of |T_run - T_rest| / EB x their length
    (where the running tension is the lower, belt flows the other way: it counts too)."""
    sp = sysm.model.springs
    return float(np.sum(np.abs(sysm.steady_tension_n - sysm.tension_rest_n) / sp.eb
                        * sp.len_m))


VFD_STARTS = (("slope-5pct", 180), ("fabric-1km", 180), ("downhill-regen", 180),
              ("overland-4km", 180), ("overland-16km", 300), ("valley-booster", 180))
#: The examples whose mean belt speed does not meet the criteria with DIN's resistance, with
#: what was measured (docs/dynamics.md, *Tracking*): DIN's friction factor, the same at every
#: speed, holds the far belt until the stretch front passes and then releases it; Non-Lin's,
#: which falls towards creep speed, meets them (its parameter runs beside).
DIN_CREEP = {
    "overland-16km": "5.5 % behind at 70 s, 4.7 % ahead at 110 s, then a swing of about "
                     "+-3 % with the gravity take-up (period about 57 s, decaying over about "
                     "1 300 s); 4.9 % after twice the 14.5 m stretch, 3.5 % after the ramp",
    "valley-booster": "2.1 % behind at 40 s, 1.8 % ahead at 50 s, then a swing of about "
                      "+-1.6 % (period about 25 s); 2.2 % after twice the 2.8 m stretch, 1.2 % "
                      "after the ramp",
}


@functools.cache
def _vfd_start(name: str, start_s: float, model: str = "din"):
    """A vfd s-curve start of an example conveyor inside its torque limit (80 elements), run
    to just before the stop command: (system, result)."""
    conv = load_conveyor(CONVEYORS / f"{name}.yaml")
    st = solve_steady(conv, model=model, n_elements=80)
    sysm = build_system(conv, Scenario(start={"time_s": start_s}, run_s=30, elements=80), st)
    return sysm, simulate(sysm, t_end_s=sysm.stop_command_s - sysm.dt_s)


@pytest.mark.parametrize("name,start_s", VFD_STARTS)
def test_vfd_master_pulley_tracks_its_reference(name, start_s):
    """docs/dynamics.md, *Tracking*: inside the torque limit, the master pulley is within 2 %
    of design speed of its reference from one wave loop time after the start command on, on
    every example conveyor; the run's ``drive{i}_speed_error_max_pct`` says the same (every
    step against the records' samples, 0.2 % of design speed)."""
    sysm, r = _vfd_start(name, start_s)
    ts = r.timeseries
    t = ts["t_s"].to_numpy() - sysm.model.cycle.t_pre
    assert ts["f_drive_kn"].abs().max() * 1e3 < float(sysm.model.drives.lim0.sum())
    m = sysm.model.control.master + 1
    v_ref = ts["v_ref_m_s"].to_numpy()
    after = t > sysm.wave_loop_time_s
    pulley = np.abs(ts[f"v_drive{m}_m_s"].to_numpy() - v_ref)[after].max() / sysm.v_design
    assert pulley < 0.02
    reported = r.summary[f"drive{m}_speed_error_max_pct"]
    assert 100 * pulley - 1e-9 <= reported <= 100 * pulley + 0.2


@pytest.mark.parametrize("name,start_s,model", [
    pytest.param(*c, "din", marks=pytest.mark.xfail(
        strict=True, reason="DIN's friction factor, the same at every speed, holds the far belt "
        f"until the stretch front passes and then releases it: {DIN_CREEP[c[0]]}; a mode the "
        "pulley held to its reference does not damp; Non-Lin's resistance meets the criteria "
        "(its parameter); the pulley tracks (test above; docs/dynamics.md, *Tracking*)"))
    if c[0] in DIN_CREEP else (*c, "din") for c in VFD_STARTS]
    + [(*c, "nonlin") for c in VFD_STARTS if c[0] in DIN_CREEP])
def test_vfd_mean_belt_speed_follows_once_the_stretch_is_paid_in(name, start_s, model):
    """docs/dynamics.md, *Tracking*: the mean belt speed within 2 % of design speed of the
    reference once the reference has travelled twice the running stretch (the belt a start
    must move past the drive to change the at-rest strains into the running ones), and within
    1 % from one wave loop time after the ramp ends. The 16.8 km overland's 300 s start
    meets them with Non-Lin's resistance (half DIN's Te there, so a 5.5 m stretch against
    14.5 m, and a swing of 0.9 % against 3.3 %), with little margin after the ramp (0.99 %
    at 80, 160 and 203 elements and at half the step); valley-booster's 180 s start with
    0.86 % and 0.29 %."""
    sysm, r = _vfd_start(name, start_s, model)
    ts = r.timeseries
    t = ts["t_s"].to_numpy() - sysm.model.cycle.t_pre
    v_ref = ts["v_ref_m_s"].to_numpy()
    travelled = np.concatenate([[0.0], np.cumsum(0.5 * (v_ref[1:] + v_ref[:-1])
                                                 * np.diff(t))])
    err = np.abs(ts["v_mean_m_s"].to_numpy() - v_ref) / sysm.v_design
    assert err[travelled >= 2.0 * running_stretch_m(sysm)].max() < 0.02
    assert err[t >= start_s + sysm.wave_loop_time_s].max() < 0.01


def _short_incline():
    """A 300 m, 8 % incline on a fabric belt with one head drive and a 2.5 t take-up."""
    return parse_conveyor({
        "name": "short-incline", "speed_m_s": 2.5,
        "belt": {"type": "EP630/4", "width_m": 0.8, "compound": "standard"},
        "material": {"capacity_t_h": 400, "density_t_m3": 1.6, "loading_speed_m_s": 0.0},
        "profile": [{"length_m": 300, "lift_m": 24}],
        "idlers": {"carry": {"spacing_m": 1.2, "roll_diameter_m": 0.127, "rolls": 3,
                             "trough_deg": 35, "cema_class": "C"},
                   "return": {"spacing_m": 3.0, "roll_diameter_m": 0.127, "rolls": 1,
                              "cema_class": "C"}},
        "drives": [{"position": "head", "wrap_deg": 210, "friction": 0.35, "share": 1.0,
                    "pulley_diameter_m": 0.63, "inertia_kg_m2": 25, "torque_limit": 1.5}],
        "takeup": {"type": "gravity", "position": "tail", "mass_kg": 2500, "travel_m": 3},
        "holdback": True})


def _master_error(r, v_design, t_from_s, t_to_s):
    """Largest |v_ref - v_master| over the records from ``t_from_s`` to ``t_to_s`` (the stop
    command), as a fraction of design speed (drive 1 is the master)."""
    ts = r.timeseries
    t = ts["t_s"].to_numpy()
    m = (t > t_from_s) & (t < t_to_s)
    return float(np.abs(ts["v_ref_m_s"] - ts["v_drive1_m_s"]).to_numpy()[m].max()) / v_design


@pytest.mark.parametrize("elements", ["auto", 404])
def test_a_start_the_speed_loop_does_not_track_is_named_with_a_start_that_does(elements):
    """docs/dynamics.md, *Tracking*: a 10 s linear start of a 300 m incline, inside the torque
    limit, keeps the master pulley 2.1 % of design speed off its reference after the first wave
    loop (the records show more than 2 %, the criterion): the run says so and names a start
    time; rerun with it, the pulley keeps within 2 % (records and report) and nothing is
    said. The same on twice the elements."""
    conv = _short_incline()
    scn = dict(run_s=20, stop={"mode": "coast"}, elements=elements)
    r = run_one(conv, Scenario(start={"time_s": 10, "control": "linear"}, **scn), model="din")
    t_loop = r.summary["wave_loop_time_s"]
    assert _master_error(r, 2.5, 2.0 + t_loop, 2.0 + 10 + 20) > 0.02
    assert r.summary["drive1_speed_error_max_pct"] > 2.0
    said = re.search(r"the speed loop did not track its reference: the master pulley \(drive 1 "
                     r"\(head\)\) was [\d.]+ m/s \(([\d.]+) % of design speed\)[^;]*; "
                     r"docs/dynamics.md, Tracking\): a longer start \(start.time_s (\d+) s or "
                     r"more", r.summary["message"])
    assert said, r.summary["message"]
    assert float(said.group(1)) > 2.0
    t_new = float(said.group(2))
    assert t_new > 10.0
    r2 = run_one(conv, Scenario(start={"time_s": t_new, "control": "linear"}, **scn),
                 model="din")
    assert _master_error(r2, 2.5, 2.0 + t_loop, 2.0 + t_new + 20) < 0.02
    assert r2.summary["drive1_speed_error_max_pct"] < 2.0
    assert "did not track" not in r2.summary["message"]


def _decline(tail_share: float):
    """A 2.2 km, 152 m decline (regenerating) with a head and a tail drive, the belt held at
    rest by a brake on the tail drive's shaft; the master is the drive with the larger
    share."""
    drive = {"wrap_deg": 200, "friction": 0.35, "pulley_diameter_m": 1.0, "torque_limit": 1.5}
    return parse_conveyor({
        "name": "decline", "speed_m_s": 4.0,
        "belt": {"type": "ST1600", "width_m": 1.2, "compound": "standard"},
        "material": {"capacity_t_h": 2200, "density_t_m3": 1.7, "loading_speed_m_s": 0.0},
        "profile": [{"length_m": 800, "lift_m": -40, "curve_radius_m": 2000},
                    {"length_m": 1400, "lift_m": -112}],
        "idlers": {"carry": {"spacing_m": 1.2, "roll_diameter_m": 0.152, "rolls": 3,
                             "trough_deg": 35, "cema_class": "D"},
                   "return": {"spacing_m": 3.0, "roll_diameter_m": 0.152, "rolls": 1,
                              "cema_class": "C"}},
        "drives": [{**drive, "position": "head", "share": 1.0 - tail_share,
                    "inertia_kg_m2": 900, "rated_power_kw": 700},
                   {**drive, "position": "tail", "share": tail_share,
                    "inertia_kg_m2": 600, "rated_power_kw": 470}],
        "takeup": {"type": "gravity", "position": "tail", "mass_kg": "auto", "travel_m": 12},
        "brakes": [{"drive": 2, "force_kn": "auto", "delay_s": 1.0}],
        "holdback": False})


def test_a_hold_a_wave_away_from_the_master_lets_the_belt_run_ahead_and_says_so():
    """docs/dynamics.md, *The start from rest*: a regenerating decline held at rest by a
    brake on its tail drive, the master at the head (share 0.6). At the hand-over the tail
    drive takes 40 % of the holding force; the rest reaches the tail only as the head loop's
    front arrives (a wave's travel), so the belt runs ahead of the reference as the brake lets
    go (the records: the mean belt speed more than 2 % of design speed above it): the run names
    it, with the holding force, the drives' part and the remedy; with the tail drive the master
    (share 0.6) the hold is handed over on one shaft, and the belt keeps within 2 %."""
    scn = Scenario(start={"time_s": 30}, run_s=10, stop={"mode": "coast"})

    def ahead(r):
        ts = r.timeseries
        t = ts["t_s"].to_numpy()
        m = (t > 2.0) & (t < 2.0 + 0.3 + r.summary["wave_loop_time_s"])
        return float((ts["v_mean_m_s"] - ts["v_ref_m_s"]).to_numpy()[m].max()) / 4.0

    r = run_one(_decline(0.4), scn, model="din")
    assert ahead(r) > 0.02
    said = re.search(r"the belt ran ahead of the start as its hold let go \(t = 2.3 s\): [^;]*?"
                     r", ([\d.]+) % of design speed ahead \(criterion: within 2 %; docs/dynamics.md, "
                     r"The start from rest\); the pulley of drive 2 \(tail\) "
                     r"held the belt at rest \(([\d.]+) kN\) and its drives took 40 % of that",
                     r.summary["message"])
    assert said, r.summary["message"]
    assert float(said.group(1)) > 2.0
    assert "the held pulley's drive made the master" in r.summary["message"]
    swapped = run_one(_decline(0.6), scn, model="din")
    assert ahead(swapped) < 0.02
    assert "ran ahead" not in swapped.summary["message"]



def test_the_speed_loop_switches_on_without_a_bump():
    """Bumpless transfer (Astrom & Hagglund, *Advanced PID Control*, 2006): at the end of the
    hand-over the speed loop's integrator takes the holding force less the proportional term
    at the master's speed, so the drives' force goes on from where the hand-over left it. On
    the decline held by its tail drive's brake the head pulley (the master) runs back during
    the hand-over under its share of the holding force; a loop that started its integrator at
    the holding force alone added ``Kp`` times that speed in one step (the drives' total force
    fell from -227.8 to -74 kN, 0.67 of the holding force). Sampled every 10 ms, the total
    drive force now changes by less than 10 % of the holding force from one sample to the next
    through the switch, as it does through the hand-over's own ramp."""
    scn = Scenario(start={"time_s": 30}, run_s=2, stop={"mode": "coast"}, record_dt_s=0.01)
    r = run_one(_decline(0.4), scn, model="din")
    ts = r.timeseries
    t = ts["t_s"].to_numpy()
    f = ts["f_drive_kn"].to_numpy()
    m = (t > 2.2) & (t < 2.5)
    assert m.sum() > 20
    hold = abs(f[m]).max()  # the holding force, built by the hand-over's end
    assert hold > 100.0
    assert np.abs(np.diff(f[m])).max() < 0.1 * hold



def test_the_speed_loop_takes_over_a_force_start_without_a_bump():
    """A force start (open loop, ``force_start_n``, verification) hands over to the speed loop
    at a controlled stop's command; bumpless, the loop's output goes on from the open-loop
    force, not from the force that held the belt at rest. On the inclined hand conveyor with
    1.1 x Te (52.8 kN) against 24.5 kN held at rest, the old switch-on dropped the drive's force
    by 8.05 kN in one sample (10 ms); sampled every 10 ms it now changes by less than 5 % of
    the open-loop force from one sample to the next through the stop command."""
    conv = hand_conv(drives=[hand_drive()], takeup={"type": "gravity", "position": "tail",
                                                      "mass_kg": 8000})
    st = solve_steady(conv, model="din", n_elements=60)
    scn = Scenario(run_s=20, elements=60, record_dt_s=0.01,
                   stop={"mode": "controlled", "time_s": 15})
    f_const = 1.1 * st.te_n
    sysm = build_system(conv, scn, st, DynamicsOptions(force_start_n=f_const))
    assert sysm.hold_force_n < 0.6 * f_const
    r = simulate(sysm)
    ts = r.timeseries
    t = ts["t_s"].to_numpy()
    f = ts["f_drive_kn"].to_numpy()
    t_cmd = sysm.model.cycle.t_pre + float(scn.start.time_s) + 20.0
    before = (t > t_cmd - 0.05) & (t < t_cmd)
    assert_allclose(f[before], f_const / 1e3, rtol=1e-9)  # the open-loop force up to it
    m = (t > t_cmd - 0.05) & (t < t_cmd + 0.1)
    assert np.abs(np.diff(f[m])).max() < 0.05 * f_const / 1e3


# --------------------------------------------------------------------------------------
# brakes


@pytest.mark.parametrize("curve", [None, [[0.0, 0.5], [3.0, 1.0]]])
def test_brake_force_builds_over_its_ramp_or_curve(curve):
    """A tail brake (plain pulley) on a brake stop: while it slides, its force follows the ramp
    (full at ramp_s after the delay) or the force curve, within 1 %."""
    brake = {"position": "tail", "force_kn": 10, "delay_s": 0.5, "ramp_s": 2.0}
    if curve:
        brake["force_curve"] = curve
    conv = hand_conv(drives=[hand_drive()], brakes=[brake],
                     takeup={"type": "gravity", "position": "tail", "mass_kg": 12000})
    r = run_one(conv, Scenario(start={"time_s": 20}, run_s=5, elements=60, record_dt_s=0.05,
                               stop={"mode": "brake", "time_s": 10}), model="din")
    ts = r.timeseries
    t_cmd = 2.0 + 20.0 + 5.0
    tau = ts["t_s"] - t_cmd - 0.5
    moving = ts["v_tail_m_s"] > 0.3
    window = moving & (tau > 0.0) & (tau < 4.0)
    assert window.sum() > 20
    if curve:
        expected = 10.0 * np.interp(tau[window], [0.0, 3.0], [0.5, 1.0])
    else:
        expected = 10.0 * np.clip(tau[window] / 2.0, 0.0, 1.0)
    assert "slipped" not in r.summary["message"]
    assert_allclose(ts["f_brake_kn"][window], expected, rtol=0.01, atol=0.2)
    # the run's largest brake force (SPEC 7.4, every step): the brake's full 10 kN, at least
    # the largest sample
    assert ts["f_brake_kn"].max() <= r.summary["f_brake_kn"] + 1e-9
    assert r.summary["f_brake_kn"] == pytest.approx(10.0, rel=1e-9)
    assert r.summary["f_holdback_kn"] is None


def test_controlled_stop_with_a_holding_brake_stays_at_rest():
    """A controlled stop on the inclined hand conveyor with a holding brake at the head (40 kN
    against a net gravity pull of 24.5 kN): the brake sets once the belt has stopped (the stop
    reference has run out and the mean speed is below 1 % of design), the drive switches off,
    and every element's speed stays below 1 mm/s from one wave loop time after the stop to
    the end."""
    conv = hand_conv(brakes=[{"position": "head", "force_kn": 40, "delay_s": 0.5,
                              "ramp_s": 1.0, "hold": True}],
                     takeup={"type": "gravity", "position": "tail", "mass_kg": 8000})
    r = run_one(conv, Scenario(start={"time_s": 30}, run_s=10, elements=60,
                               stop={"mode": "controlled", "time_s": 15}), model="din")
    s = r.summary
    ts = r.timeseries
    stopped_at = 2.0 + 30.0 + 10.0 + max(s["stop_time_s"], 15.0)  # the reference has run out
    late = ts["t_s"] >= stopped_at + s["wave_loop_time_s"]
    assert late.sum() > 20
    assert ts["v_abs_max_m_s"][late].max() < 1e-3
    assert ts["f_drive_kn"].iloc[-1] == 0.0  # the drive is off, the brake holds
    assert ts["f_brake_kn"].iloc[-1] > 0.0



@pytest.mark.parametrize("stop_s, governed", [(3.0, "grip"), (3.5, "stop_time")])
def test_auto_brake_stop_within_the_grip(stop_s, governed):
    """The 10 % incline's auto head brake (SPEC 7.2, PHYSICS 5.1): a 3 s stop is beyond the
    head pulley's grip, so the sizing says grip and the stop time it makes, which the run
    meets within 10 %; a 3.5 s stop is within it (stop_time, met within 10 %). Either way the
    pulley never slips: no slip time, no slip warning."""
    r = run_one(steep_incline(), Scenario(start={"time_s": 40}, run_s=10,
                                          stop={"mode": "brake", "time_s": stop_s}),
                model="din")
    s = r.summary
    assert s["brake_governed_by"] == governed
    if governed == "grip":
        said = float(re.search(r"brake stop then takes about ([0-9.]+) s",
                               s["message"]).group(1))
    else:
        said = stop_s
    assert s["stop_time_s"] == pytest.approx(said, rel=0.10)
    assert s["drive1_slip_s"] == 0.0
    assert "slipped" not in s["message"]


def test_tail_followers_settle_or_the_run_says_so():
    """The running-phase fuzz's limit-cycle conveyor (benchmarks/fuzz_running.py): a vfd head
    drive with two tail drives following its torque a wave's travel away, EP1000/5, 2.9 km.
    Over the running phase's last half its mean belt speed either stays within 2 % of design
    speed, or the run says ``not settled while running`` with that swing (to 1 %) and a
    period from the crossings of the mean (10 %) (PHYSICS 5.2)."""
    tail = {"position": "tail", "wrap_deg": 200, "share": 0.3, "inertia_kg_m2": 1500.0,
            "pulley_diameter_m": 1.0}
    conv = hand_conv(
        speed_m_s=4.0, belt={"type": "EP1000/5", "width_m": 1.2},
        material={"capacity_t_h": 1500, "density_t_m3": 1.6},
        profile=[{"length_m": 1500.0, "lift_m": 30.0}, {"length_m": 1400.0, "lift_m": -20.0}],
        drives=[hand_drive(share=0.4, wrap_deg=210, inertia_kg_m2=4000.0), hand_drive(**tail),
                hand_drive(**tail)],
        takeup={"type": "gravity", "position": "tail", "mass_kg": "auto"})
    r = run_one(conv, Scenario(start={"time_s": 60}, run_s=300, stop={"mode": "coast"},
                               elements=40), model="din")
    ts, msg = r.timeseries, r.summary["message"]
    t_cmd = r.transient.system.stop_command_s
    half = (ts["t_s"] >= t_cmd - 150.0) & (ts["t_s"] <= t_cmd)
    v = ts["v_mean_m_s"][half].to_numpy()
    swing = float(np.ptp(v))
    if swing <= 0.02 * 4.0:
        assert "not settled while running" not in msg
        return
    m = re.search(r"not settled while running: the mean belt speed still swings by ([\d.]+) "
                  r"m/s \(([\d.]+) % of design speed, a period of ([\d.]+) s\)", msg)
    assert m, msg
    assert float(m.group(1)) == pytest.approx(swing, rel=0.01)
    t = ts["t_s"][half].to_numpy()
    d = v - v.mean()
    cross = np.flatnonzero(np.signbit(d[:-1]) != np.signbit(d[1:]))
    crossings_per_s = (len(cross) - 1) / (t[cross[-1]] - t[cross[0]])
    assert float(m.group(3)) == pytest.approx(2.0 / crossings_per_s, rel=0.1)
    # the drives are a wave's travel apart: the words do not promise that a slower loop
    # settles it (no setting tried does on this belt, docs/dynamics.md), they say so
    assert "no speed loop setting or drive layout is known to settle every such belt" in msg
    assert "a slower speed loop (drives." not in msg


@pytest.mark.parametrize("lift_m, said_as", [
    (50.0, r"the belt runs back after the stop: .* \(the lift's pull at rest, ([\d.]+) kN at "
           r"the belt line, outpulls the resistances and nothing holds it\)"),
    (400.0, r"the belt ran back during the stop: .* \(at rest the belt pulls ([\d.]+) kN back, "
            r"its net gravity pull: what a holdback or brakes must take at the belt line\)"),
])
def test_a_belt_that_runs_back_is_told_the_pull_to_hold(lift_m, said_as):
    """The hand conveyor (1 km, m'_L 50 kg/m) rising 50 m and 400 m with no holdback and no
    brake, coasting to rest: the loaded belt runs back, slowly on 50 m (the run ends with it
    running back) and to twice the design speed on 400 m (the run is ended there), and each
    warning says how much a holdback or brakes must take, the net gravity pull at rest,
    m'_L g H = 50 kg/m x 9.81 x H: 24.53 and 196.2 kN (the belt's own weight cancels round
    the loop)."""
    conv = hand_conv(profile=[{"length_m": 1000, "lift_m": lift_m}])
    st = solve_steady(conv, model="din", n_elements=60)
    sysm = build_system(conv, Scenario(start={"time_s": 20}, run_s=10, stop={"mode": "coast"},
                                       elements=60), st)
    r = simulate(sysm, conveyor=conv)
    said = re.search(said_as, r.message)
    assert said, r.message
    assert float(said.group(1)) == pytest.approx(50.0 * 9.81 * lift_m / 1e3, rel=1e-3)
