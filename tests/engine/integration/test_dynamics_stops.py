"""Per-run stop figures (issue 27 item 5) against hand calculations:

* the stopping distance of a rigid-body stop, ``s = v0^2 / (2 a)`` (a coast held back by the
  lift alone), and of a brake stop with a delay, ``v0 t_d - a_c t_d^2 / 2 + v1^2 / (2 a_b)``;
* the holdback's force apart from the brakes': at rest it holds the net downhill pull, a brake
  on its shaft gives at most its own force and the holdback the rest;
* one "did not stop" rule: the same window for every run, named in the warning.

The mass-weighted mean speed obeys the momentum balance of the whole belt, ``M dv/dt = sum of
the external forces`` (the springs' forces cancel round the closed loop), so a stop under
forces that do not change with speed is a uniform deceleration whatever the waves do
(Newton's second law; the kinematics of a uniform deceleration).
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from beltstudy.engine.conveyor import Scenario, parse_conveyor
from beltstudy.engine.dynamics import DynamicsOptions
from beltstudy.engine.loop import G
from beltstudy.engine.run import run_one
from tests.conftest import hand_conveyor_dict
from tests.engine.integration.test_dynamics_physics import flat_conveyor

#: The hand conveyor (tests.conftest): 1 km rising H = 50 m, m'_L = 50 kg/m, 4 m/s.
H_M, ML_KG_M, V_M_S = 50.0, 50.0, 4.0
#: Its net downhill pull: the belt's own weight cancels round the loop (the carry rises what
#: the return falls), the load's does not: m'_L g H [N].
PULL_N = ML_KG_M * G * H_M
HEAD_BRAKE_KN = 10.0


def _holdback_run(brakes=(), **opts):
    conv = parse_conveyor(hand_conveyor_dict(holdback=True, brakes=list(brakes)))
    scn = Scenario(elements=100, start={"time_s": 60}, run_s=10, stop={"mode": "coast"})
    return run_one(conv, scn, model="din", options=DynamicsOptions(**opts))


def test_rigid_body_coast_held_back_by_the_lift():
    """Resistances off: the lift's pull m'_L g H alone stops the belt, a uniform deceleration
    a = m'_L g H / M (M the moving mass: belt, load, idler rolls, pulleys and shafts). The stop
    (to 1 % of design speed) takes t = 0.99 v0 / a and runs s = (v0^2 - (0.01 v0)^2) / (2 a),
    both within 1 %."""
    r = _holdback_run(resistances=False)
    m = r.transient.system.model.control.m_tot
    a = PULL_N / m
    assert r.summary["stop_time_s"] == pytest.approx(0.99 * V_M_S / a, rel=0.01)
    assert r.summary["stop_distance_m"] == pytest.approx(
        (V_M_S**2 - (0.01 * V_M_S) ** 2) / (2.0 * a), rel=0.01)


def test_brake_stop_with_a_delay_by_hand():
    """A flat loaded belt, a 40 kN brake at the head applied after a delay t_d = 1 s at once
    (no ramp): through the delay the belt coasts at a_c = Te / M, then decelerates at a_b =
    (F_b + Te) / M (Te of statics: DIN's speed-independent resistances). From the mean speed
    v0 at the stop command, v1 = v0 - a_c t_d and the stopping distance to 1 % of design speed
    s = v0 t_d - a_c t_d^2 / 2 + (v1^2 - (0.01 v)^2) / (2 a_b), within 1 %; the stop time
    t_d + (v1 - 0.01 v) / a_b within 1 %."""
    f_b, t_d = 40e3, 1.0
    conv = flat_conveyor(length_m=1000.0, speed_m_s=V_M_S, takeup_kg=20000.0,
                         material={"capacity_t_h": 600.0},
                         brakes=[{"position": "head", "force_kn": f_b / 1e3, "delay_s": t_d,
                                  "ramp_s": 0.0}])
    scn = Scenario(elements=100, start={"time_s": 30}, run_s=10,
                   stop={"mode": "brake", "time_s": 10})
    r = run_one(conv, scn, model="din")
    sys = r.transient.system
    ts = r.timeseries
    v0 = float(np.interp(sys.stop_command_s, ts["t_s"], ts["v_mean_m_s"]))
    m, te = sys.model.control.m_tot, r.steady.te_n
    a_c, a_b = te / m, (f_b + te) / m
    v1 = v0 - a_c * t_d
    v_end = 0.01 * V_M_S
    assert r.summary["stop_distance_m"] == pytest.approx(
        v0 * t_d - 0.5 * a_c * t_d**2 + (v1**2 - v_end**2) / (2.0 * a_b), rel=0.01)
    assert r.summary["stop_time_s"] == pytest.approx(t_d + (v1 - v_end) / a_b, rel=0.01)


def _main_resistance_n() -> float:
    """DIN 22101's main resistance of the hand conveyor, F_H = f g sum dx (m'_R + (m'_G +
    m'_L) cos a), f = 0.020 both strands: carry m'_R 10, m'_G 20, m'_L 50 kg/m; return m'_R 3,
    m'_G 20 kg/m; cos a of the 5 % slope [N]."""
    cos_a = math.cos(math.atan(H_M / 1000.0))
    return 0.020 * G * 1000.0 * ((10.0 + 70.0 * cos_a) + (3.0 + 20.0 * cos_a))


@pytest.mark.parametrize("brake", [False, True], ids=["holdback-only", "holdback-and-brake"])
def test_holdback_holds_the_downhill_pull_at_rest(brake):
    """A loaded incline coasts to rest and rolls back onto its holdback. What holds it at rest:
    before the start the holdback alone, exactly m'_L g H (the drive has not started; the
    resistances are regularised Coulomb laws, zero at zero speed). After the stop the belt
    still creeps back slowly as the take-up settles, and the resistances, linear below v_eps =
    1e-4 m/s, give F_H |v_mean| / v_eps of the pull: the holdback holds m'_L g H less that
    (within 2 % of m'_L g H; F_H by hand, :func:`_main_resistance_n`), below m'_L g H. Without
    a brake the brake force is 0 throughout; with a 10 kN holding brake on the head pulley
    the brake never gives more than its 10 kN and holds exactly that at rest, and the holdback
    the rest of the same balance."""
    brakes = ([{"position": "head", "force_kn": HEAD_BRAKE_KN, "delay_s": 0.5,
                "ramp_s": 0.0}] if brake else [])
    r = _holdback_run(brakes, post_rest_s=60.0)
    ts = r.timeseries
    assert r.summary["status"] == "ok", r.summary["message"]
    before = ts[ts["t_s"] < r.transient.system.model.cycle.t_pre]
    assert before["f_holdback_kn"].iloc[-1] * 1e3 == pytest.approx(PULL_N, rel=1e-9)
    end = ts.iloc[-1]
    f_brake = HEAD_BRAKE_KN if brake else 0.0
    assert ts["f_brake_kn"].max() <= f_brake + 1e-9
    assert end["f_brake_kn"] == pytest.approx(f_brake, abs=1e-9)
    creep_n = _main_resistance_n() * max(-end["v_mean_m_s"], 0.0) / 1e-4
    held_n = (end["f_holdback_kn"] + end["f_brake_kn"]) * 1e3
    assert held_n + creep_n == pytest.approx(PULL_N, rel=0.02)
    assert held_n < PULL_N
    # the summary's figure is the largest over every step of the run (the records sample
    # them): the roll back onto the holdback
    assert r.summary["f_holdback_kn"] >= ts["f_holdback_kn"].max() - 1e-9
    assert r.summary["f_holdback_kn"] * 1e3 >= PULL_N - f_brake * 1e3 - 1e-6


def test_no_holdback_no_holdback_force():
    """A conveyor without a holdback reports none (null), and its time series holds 0."""
    conv = parse_conveyor(hand_conveyor_dict())
    r = run_one(conv, Scenario(elements=60, start={"time_s": 30}, run_s=5,
                               stop={"mode": "controlled", "time_s": 10}), model="din")
    assert r.summary["f_holdback_kn"] is None
    assert (r.timeseries["f_holdback_kn"] == 0.0).all()


def test_one_stop_window_for_every_run():
    """The window in which a run must come to rest is DynamicsOptions.stop_window_s for every
    run, whatever its stop time or how long it would coast (engine 0.5.0 took 3 x the
    longer of the two plus two wave loop times: 100 s for one run, 1000 s for another). Two
    runs of very different stops report the same window; with a window shorter than their
    coasts (the lift alone stops the belt in 0.99 v M / (m'_L g H) = 17 s, DIN's resistance
    with it in about 6 s) both end there and both are named "did not stop" in the same words:
    the window, the mean speed at its end and what would stop it (a brake)."""
    conv = parse_conveyor(hand_conveyor_dict(holdback=True))
    quick = Scenario(elements=60, start={"time_s": 30}, run_s=5,
                     stop={"mode": "controlled", "time_s": 5})
    slow = Scenario(elements=60, start={"time_s": 30}, run_s=5,
                    stop={"mode": "coast", "time_s": 200})
    runs = [run_one(conv, s, model="din") for s in (quick, slow)]
    assert {r.summary["stop_window_s"] for r in runs} == {300.0}
    assert all(r.summary["stop_time_s"] is not None for r in runs)
    window = 2.0
    coast = Scenario(**{**slow.model_dump(), "stop": {"mode": "coast", "time_s": 5}})
    cut = [run_one(conv, coast, model="din", options=DynamicsOptions(stop_window_s=window)),
           run_one(conv, slow, model="din",
                   options=DynamicsOptions(stop_window_s=window, resistances=False))]
    for r in cut:
        sys = r.transient.system
        assert r.summary["stop_window_s"] == window
        assert r.summary["stop_time_s"] is None and r.summary["stop_distance_m"] is None
        assert r.timeseries["t_s"].iloc[-1] == pytest.approx(sys.stop_command_s + window,
                                                             abs=2 * sys.dt_s)
        v_end = float(r.transient.raw["v_mean"])
        assert v_end > 0.5
        words = (f"the belt did not stop within the stop window of {window:.0f} s after the "
                 f"stop command (the same for every run, docs/dynamics.md): its mean speed was "
                 f"still {v_end:.3g} m/s")
        assert words in r.summary["message"]
        assert "a brake would stop it" in r.summary["message"]


def test_a_stop_longer_than_the_window_is_refused():
    """A controlled stop that cannot end within the window is refused by name."""
    from beltstudy.engine.conveyor import InputError

    conv = parse_conveyor(hand_conveyor_dict())
    scn = Scenario(elements=60, start={"time_s": 30}, run_s=5,
                   stop={"mode": "controlled", "time_s": 400})
    with pytest.raises(InputError, match="stop window of 300 s"):
        run_one(conv, scn, model="din")
