"""The numba kernel against the slow numpy reference of the same equations (STYLE: a kernel
and a reference path tested against each other), its building blocks, records and failure
handling."""

from __future__ import annotations

import re
import time

import numpy as np
import pytest
from numpy.testing import assert_allclose

from beltstudy.engine.conveyor import Scenario, load_conveyor, load_mapping, parse_conveyor
from beltstudy.engine.dynamics import DynamicsOptions, build_system, simulate
from beltstudy.engine.dynamics import codes as C
from beltstudy.engine.dynamics.model import with_step
from beltstudy.engine.dynamics.reference import run_reference
from beltstudy.engine.dynamics.simulate import SURFACE_COLUMNS, TIMESERIES_COLUMNS, fresh_run
from beltstudy.engine.statics import solve_steady
from tests.conftest import CONVEYORS, hand_conveyor_dict


def conveyor(name: str, **changes):
    """An example conveyor with some of its top-level fields replaced."""
    data = load_mapping(CONVEYORS / f"{name}.yaml")
    data.update(changes)
    return parse_conveyor(data)


HEAD_PAIR = [dict(position="head", wrap_deg=200, friction=0.35, share=0.5,
                  pulley_diameter_m=1.25, inertia_kg_m2=800, rated_power_kw=650)] * 2
DOL_FLUID = [dict(position="head", wrap_deg=210, friction=0.35, pulley_diameter_m=0.8,
                  inertia_kg_m2=60, rated_power_kw=250, torque_limit=2.5, control="dol",
                  coupling="fluid", trip_s=0.5)]
LOW_FRICTION = [dict(position="head", wrap_deg=180, friction=0.2, pulley_diameter_m=0.8,
                     inertia_kg_m2=60, rated_power_kw=250)]
HOLDING_BRAKES = [dict(position="head", force_kn="auto", delay_s=0.5, ramp_s=1.5, hold=True),
                  dict(position="tail", force_kn=100, delay_s=0.3,
                       force_curve=[(0.0, 0.3), (1.0, 1.0)], hold=False)]
FOLLOWER_BRAKE = [dict(drive=2, force_kn=300, delay_s=0.3, ramp_s=0.5, hold=True)]
SHORT_TRAVEL = dict(type="gravity", position="head", mass_kg="auto", travel_m=1.0)
#: two head drives and a light tail follower behind a 300 kg take-up: the follower slips and
#: its speed window brings its shaft back at its torque limit
HEADS_AND_TAIL = [dict(position="head", wrap_deg=200, friction=0.35, share=0.5,
                       pulley_diameter_m=1.25, inertia_kg_m2=800, rated_power_kw=400,
                       torque_limit=1.5),
                  dict(position="head", wrap_deg=200, friction=0.35, share=0.3,
                       pulley_diameter_m=1.25, inertia_kg_m2=800, rated_power_kw=250,
                       torque_limit=1.5),
                  dict(position="tail", wrap_deg=200, friction=0.35, share=0.2,
                       pulley_diameter_m=1.25, inertia_kg_m2=100, rated_power_kw=160,
                       torque_limit=1.5)]
LIGHT_TAIL = dict(type="gravity", position="tail", mass_kg=300, travel_m=10)
#: a head drive whose torque limit is a little above Te: a torque start is still at its limit,
#: short of design speed, when a controlled stop is commanded (the ramp starts from its speed)
WEAK_HEAD = [dict(position="head", wrap_deg=210, friction=0.35, share=1.0,
                  pulley_diameter_m=1.25, inertia_kg_m2=1500, rated_power_kw=1250,
                  torque_limit=0.8)]


def _slipped_in_start(kr):
    drv = kr.out.drv
    return (drv["slip_s"] > 0).any() and drv["slip_first"].min() < kr.run["t_stopcmd"]


# each case: conveyor and changes, friction model, scenario, and what the case must exercise
# (so a model change cannot quietly take a branch out of the comparison); 40 elements, short
# scenarios: the reference takes a few seconds a case
CASES = [
    pytest.param("fabric-1km", {}, "nonlin",
                 dict(start={"control": "s-curve", "time_s": 12}, run_s=3,
                      stop={"mode": "coast"}),
                 lambda kr: kr.model.law.mode == C.LAW_LINEAR and kr.run["law_evals"] > 0
                 and kr.run["fhb_max"] > 0.0, id="fabric-nonlin-holdback-coast"),
    pytest.param("overland-16km", {}, "din",
                 dict(start={"control": "linear", "time_s": 30}, run_s=3,
                      stop={"mode": "brake", "time_s": 20}),
                 lambda kr: kr.run["hold_set"] >= 0.0,
                 id="overland-head-tail-drives-head-takeup-brake-stop"),
    pytest.param("slope-5pct", {}, "cmod",
                 dict(start={"control": "torque", "time_s": 12}, run_s=3,
                      stop={"mode": "controlled", "time_s": 10}), None,
                 id="slope-cmod-torque-start-controlled-stop"),
    pytest.param("slope-5pct", {}, "visco",
                 dict(start={"control": "s-curve", "time_s": 12}, run_s=3,
                      stop={"mode": "controlled", "time_s": 10}, formulation="support"),
                 None, id="slope-visco-support"),
    pytest.param("overland-16km", {}, "cema",
                 dict(load="empty", start={"control": "s-curve", "time_s": 30}, run_s=3,
                      stop={"mode": "coast"}), None, id="overland-cema-empty-coast"),
    pytest.param("slope-5pct", dict(drives=HEAD_PAIR), "din",
                 dict(start={"control": "s-curve", "time_s": 12}, run_s=3,
                      stop={"mode": "controlled", "time_s": 10}),
                 lambda kr: len(kr.model.drives.share) == 2 and kr.model.cycle.t_hand > 0.0,
                 id="dual-head-half-shares-handover"),
    pytest.param("fabric-1km", dict(drives=LOW_FRICTION), "din",
                 dict(start={"control": "s-curve", "time_s": 6}, run_s=3,
                      stop={"mode": "coast"}), _slipped_in_start, id="drive-slips-in-start"),
    pytest.param("fabric-1km", dict(drives=DOL_FLUID), "din",
                 dict(start={"time_s": 12}, run_s=3, stop={"mode": "coast"}),
                 lambda kr: kr.model.drives.vm.max() > 0.0 or kr.run["t_trip"] > 0.0,
                 id="dol-fluid-coupling-trip"),
    pytest.param("downhill-regen", dict(brakes=HOLDING_BRAKES), "din",
                 dict(start={"control": "linear", "time_s": 12}, run_s=3,
                      stop={"mode": "brake", "time_s": 12}),
                 lambda kr: kr.run["hold_set"] >= 0.0,
                 id="brake-stop-ramp-curve-holding-brake"),
    pytest.param("slope-5pct", dict(drives=HEAD_PAIR, holdback=False, brakes=FOLLOWER_BRAKE),
                 "din", dict(start={"control": "s-curve", "time_s": 12}, run_s=3,
                             stop={"mode": "controlled", "time_s": 10}),
                 lambda kr: kr.run["hold_set"] >= 0.0,
                 id="holding-brake-on-a-torque-follower"),
    pytest.param("overland-16km", dict(takeup=SHORT_TRAVEL), "din",
                 dict(start={"control": "linear", "time_s": 20}, run_s=3,
                      stop={"mode": "coast"}),
                 lambda kr: kr.run["endstop"] > 0,
                 id="carriage-at-its-end-stop"),
    pytest.param("slope-5pct", dict(drives=HEADS_AND_TAIL, takeup=LIGHT_TAIL), "din",
                 dict(start={"control": "s-curve", "time_s": 8}, run_s=3,
                      stop={"mode": "coast"}),
                 lambda kr: kr.out.drv["slip_s"][2] > 0.0
                 and kr.out.drv["fmax"][2] == pytest.approx(kr.model.drives.lim0[2], rel=1e-12),
                 id="slipping-follower-window-at-its-torque-limit"),
    pytest.param("slope-5pct", dict(drives=WEAK_HEAD), "din",
                 dict(start={"control": "torque", "time_s": 8}, run_s=3,
                      stop={"mode": "controlled", "time_s": 10}),
                 lambda kr: 0.0 < kr.run["v_stop0"] < kr.model.cycle.v_d,
                 id="controlled-stop-from-a-master-short-of-speed"),
    # a 20 t take-up: the head pulley slips in the torque start and still runs ahead of its
    # belt at the command, so the ramp starts from the belt's mean speed (the highest so far)
    pytest.param("slope-5pct", dict(takeup=dict(type="gravity", position="tail",
                                                mass_kg=20000, travel_m=10)), "din",
                 dict(start={"control": "torque", "time_s": 8}, run_s=1,
                      stop={"mode": "controlled", "time_s": 10}),
                 lambda kr: kr.out.drv["slip_s"][0] > 0.0
                 and 0.0 < kr.run["v_stop0"] == kr.run["vmean_hi"] < kr.model.cycle.v_d,
                 id="controlled-stop-from-the-belt-behind-a-slipping-master"),
    # a 15 deg incline with no holdback: after its coast stop the belt runs back, and the
    # rest goes on while it does (not at rest) until it runs away backwards
    pytest.param("slope-5pct", dict(profile=[{"length_m": 300, "lift_m": 78}],
                                    holdback=False), "din",
                 dict(start={"control": "s-curve", "time_s": 8}, run_s=1,
                      stop={"mode": "coast"}),
                 lambda kr: kr.run["status"] == C.RUNAWAY and kr.run["v_mean"] < 0.0
                 and kr.run["t"] > kr.run["t_stopped"] + kr.model.cycle.post_rest,
                 id="run-back-after-the-rest-to-a-runaway"),
]


@pytest.mark.parametrize("name,changes,model,scenario,exercised", CASES + [
    pytest.param("fabric-1km", {}, "nonlin",
                 dict(start={"control": "s-curve", "time_s": 12}, run_s=3,
                      stop={"mode": "coast"}, options=dict(resistance_rtol=0.0)),
                 lambda kr: kr.model.law.mode == C.LAW_EXACT,
                 id="fabric-nonlin-exact-law"),
    pytest.param("slope-5pct", {}, "nonlin",
                 dict(start={"control": "s-curve", "time_s": 12}, run_s=3,
                      stop={"mode": "controlled", "time_s": 10}),
                 lambda kr: kr.run["law_evals"] > 0,
                 id="slope-nonlin-controlled-stop"),
])
def test_kernel_matches_numpy_reference(name, changes, model, scenario, exercised):
    """Whole cycles: final state, whole-cycle envelopes, shafts, drives, carriage, drive work
    and the phase times agree to 1e-9 (of the design speed for speeds, of the largest tension
    for forces; the kernel's exp/log polynomials and band solve differ from numpy's in the
    last bits only); with an expanded law (Non-Lin, beltstudy.engine.dynamics.linlaw) both evaluate the
    same elements' laws exactly at the same steps."""
    conv = conveyor(name, **changes)
    scenario = dict(scenario)
    opts = DynamicsOptions(**scenario.pop("options", {}))
    scn = Scenario(**scenario)
    st = solve_steady(conv, model=model, load=scn.load, n_elements=40)
    sys = build_system(conv, scn, st, opts)
    kr = fresh_run(sys)
    kr.call()
    ref = run_reference(sys)
    out, state, shafts, drives = kr.out, kr.state, kr.model.shafts, kr.model.drives
    res = kr.run
    nseg = int(res["seg"]) + 1
    if exercised is not None:
        assert exercised(kr)
    t_tol = 1e-9 * float(np.abs(ref["tension"]).max())
    v_tol = 1e-9 * sys.v_design
    assert int(res["steps"]) == ref["steps"]
    assert int(res["status"]) == ref["status"] in (C.OK, C.RUNAWAY)  # (a run-back's runaway)
    assert_allclose(state.tt, ref["tension"], atol=t_tol, rtol=0)
    assert_allclose(state.te, ref["te"], atol=t_tol, rtol=0)
    assert_allclose(state.ts, ref["ts"], atol=1e-9 * float(np.abs(ref["ts"]).max()), rtol=0)
    assert_allclose(state.td, ref["td"], atol=t_tol, rtol=0)
    assert_allclose(state.v, ref["v"], atol=v_tol, rtol=0)
    assert_allclose(out.seg_env[:nseg, 0].max(axis=0), ref["t_max"], atol=t_tol, rtol=0)
    assert_allclose(out.seg_env[:nseg, 2].min(axis=0), ref["t_min"], atol=t_tol, rtol=0)
    assert res["x_tu"] == pytest.approx(ref["x_takeup"], abs=1e-9)
    assert res["u_tu"] == pytest.approx(ref["u_takeup"], abs=v_tol)
    assert res["integ"] == pytest.approx(ref["integrator"], abs=t_tol)
    assert_allclose(shafts.vs, ref["shaft_speed"], atol=v_tol, rtol=0)
    assert_allclose(shafts.slip, ref["shaft_slip"], atol=0, rtol=0)
    assert_allclose(drives.force, ref["drive_force"], atol=t_tol, rtol=0)
    assert res["w_drive"] == pytest.approx(ref["w_drive"], rel=1e-9)
    assert res["stop_dist"] == pytest.approx(ref["stop_dist"], rel=1e-9, abs=1e-9)
    # the brakes' and the holdback's forces apart: the last step's and the largest of the run
    for key in ("f_brake", "f_hb", "fbr_max", "fhb_max"):
        assert res[key] == pytest.approx(ref[key], abs=t_tol), key
    for key in ("start_ach", "stop_ach", "t_trip", "hold_set", "verr_t", "vmean_hi_t"):
        assert res[key] == pytest.approx(ref[key], abs=1e-9), key
    assert res["verr_max"] == pytest.approx(ref["verr_max"], abs=v_tol)
    assert res["vmean_hi"] == pytest.approx(ref["vmean_hi"], abs=v_tol)
    for phase in ("start", "stop"):
        travel = max(res[f"xhi_{phase}"] - res[f"xlo_{phase}"], 0.0)
        assert travel == pytest.approx(ref[f"takeup_travel_{phase}"], abs=1e-9), phase
    assert res["slack_dur"] == pytest.approx(ref["slack_s"], abs=1e-9)
    assert_allclose(out.drv["slip_s"], ref["slip_s"], atol=1e-9, rtol=0)
    assert_allclose(out.drv["slip_m"], ref["slip_m"], atol=1e-9, rtol=1e-9)
    assert_allclose(out.shs["slip_s"], ref["shaft_slip_s"], atol=1e-9, rtol=0)
    assert_allclose(out.shs["slip_m"], ref["shaft_slip_m"], atol=1e-9, rtol=1e-9)
    # the drives' load: time above the rated force and at the torque limit, the force squared
    # integrated until the belt is at rest (the RMS force, beltstudy.engine.drives)
    assert_allclose(out.drv["over_s"], ref["over_s"], atol=1e-9, rtol=0)
    assert_allclose(out.drv["over_stop_s"], ref["over_stop_s"], atol=1e-9, rtol=0)
    assert_allclose(out.drv["lim_s"], ref["lim_s"], atol=1e-9, rtol=0)
    assert_allclose(out.drv["rms_s"], ref["rms_s"], atol=1e-9, rtol=0)
    assert_allclose(out.drv["f2_int"], ref["f2_int"], rtol=1e-9,
                    atol=1e-9 * float(np.abs(ref["tension"]).max()) ** 2)
    assert res["law_evals"] == ref["law_evals"]


@pytest.mark.parametrize("changes, scenario, status", [
    pytest.param(dict(profile=[{"length_m": 1000, "lift_m": -150}]), {}, C.RUNAWAY,
                 id="a-decline-runs-away"),
    pytest.param(dict(drives=[{"position": "head", "wrap_deg": 200, "friction": 0.35,
                               "share": 1.0, "pulley_diameter_m": 1.0, "inertia_kg_m2": 2.0,
                               "control": "dol", "rated_power_kw": 240, "coupling": "fluid"}],
                      takeup={"type": "gravity", "position": "tail", "mass_kg": 16000}),
                 dict(dt_s=0.024), C.DIVERGED, id="a-light-drive-train-diverges"),
])
def test_kernel_and_reference_end_a_run_alike(changes, scenario, status):
    """A run that ends early ends at the same step in both, for the same reason: the belt ran
    away (mean speed past twice the design speed; the final state agrees to 1e-9), or a pulley
    shaft or motor left the finite range (the same body named)."""
    conv = parse_conveyor(hand_conveyor_dict(**changes))
    scn = Scenario(elements=40, start={"time_s": 20}, run_s=10, stop={"mode": "coast"},
                   **scenario)
    sys = build_system(conv, scn, solve_steady(conv, model="din", n_elements=40))
    kr = fresh_run(sys)
    kr.call()
    ref = run_reference(sys)
    res = kr.run
    assert int(res["status"]) == ref["status"] == status
    assert int(res["steps"]) == ref["steps"]
    if status == C.RUNAWAY:
        assert_allclose(kr.state.v, ref["v"], atol=1e-9 * sys.v_design, rtol=0)
    else:
        assert int(res["div_where"]) == ref["div_where"] != -1  # the drive train's body


def test_divergence_ends_the_run_failed_quickly():
    """A step three times the stability limit (bypassing the input check) diverges, and a
    non-finite value in the state is caught: the run ends with status failed and a message
    naming the divergence and the step; it neither hangs nor raises."""
    conv = load_conveyor(CONVEYORS / "fabric-1km.yaml")
    st = solve_steady(conv, n_elements=60)
    sys = build_system(conv, Scenario(), st, DynamicsOptions(damping="off"))
    sys = with_step(sys, 3.0 * sys.dt_limit_s)
    t0 = time.perf_counter()
    res = simulate(sys)
    assert time.perf_counter() - t0 < 5.0
    assert res.status == "failed"
    assert "diverged" in res.message and "dt" in res.message
    sys = build_system(conv, Scenario(), st)
    sys.model.nodes.gravity[5] = np.nan
    res = simulate(sys)
    assert res.status == "failed" and "diverged" in res.message
    assert res.raw["t_end"] < 1.0


def test_records_and_envelopes_are_consistent():
    conv = load_conveyor(CONVEYORS / "slope-5pct.yaml")
    st = solve_steady(conv, model="din", n_elements=60)
    scn = Scenario(start={"time_s": 20}, run_s=10, stop={"mode": "controlled", "time_s": 20},
                   record_dt_s=0.25)
    sys = build_system(conv, scn, st)
    res = simulate(sys, steady_summary=st.summary, conveyor=conv)
    ts = res.timeseries
    assert tuple(ts.columns[: len(TIMESERIES_COLUMNS)]) == TIMESERIES_COLUMNS
    assert tuple(res.surface.columns) == SURFACE_COLUMNS
    # samples at record_dt (the step nearest each multiple), starting at rest
    assert ts["t_s"].iloc[0] == 0.0
    assert_allclose(np.diff(ts["t_s"].to_numpy())[:-1], 0.25, atol=sys.dt_s)
    # starts and ends at rest; sampled extremes inside the envelope; the peak is the
    # envelope's
    assert ts["v_mean_m_s"].iloc[0] == 0.0 and abs(ts["v_mean_m_s"].iloc[-1]) < 0.01 * 4.5
    env = res.envelope
    assert ts["t_max_kn"].max() <= env["t_max_kn"].max() + 1e-9
    assert ts["t_min_kn"].min() >= env["t_min_kn"].min() - 1e-9
    s = res.summary
    assert s["t_max_dyn_kn"] == pytest.approx(env["t_max_kn"].max())
    assert 0.0 < s["t_max_dyn_time_s"] <= ts["t_s"].iloc[-1]
    # the envelope's times are within one record interval of the peak time
    j = int(env["t_max_kn"].idxmax())
    assert abs(env["t_max_time_s"][j] - s["t_max_dyn_time_s"]) <= 0.25 + sys.dt_s
    assert s["dyn_factor"] == pytest.approx(s["t_max_dyn_kn"] / st.summary["t_max_kn"])
    # surface rows: every sampled time with every sampled spring
    n_t = res.surface["t_s"].nunique()
    assert len(res.surface) == n_t * len(sys.model.probes.surface)


def test_rk45_on_the_same_equations_agrees():
    """scipy's RK45 (rtol 1e-6) on the continuous-time equations (every shaft stuck to its
    pulley, no holdback) and the kernel agree on the peak tension of a start within 0.5 %.
    The resistance is regularised over 1 cm/s: the engine's sharper default only changes the
    first moments of the start, and makes the ODE stiff for an explicit integrator."""
    from scipy.integrate import solve_ivp

    from beltstudy.engine.dynamics import ode

    conv = conveyor("fabric-1km", holdback=False)
    st = solve_steady(conv, model="nonlin", n_elements=20)
    scn = Scenario(start={"control": "s-curve", "time_s": 8}, run_s=60)
    sys = build_system(conv, scn, st, DynamicsOptions(pre_rest_s=0.0, slip=False,
                                                      v_eps_m_s=1e-2))
    res = simulate(sys, t_end_s=9.0)
    y0 = ode.initial_state(sys)
    scale = np.concatenate([np.full(sys.n, sys.v_design),
                            np.full(2 * sys.n, float(sys.tension_rest_n.max())), [1, 1, 1e4]])
    sol = solve_ivp(ode.rhs, (0.0, 9.0), y0, method="RK45", rtol=1e-6, atol=1e-6 * scale,
                    args=(sys,), dense_output=True)
    assert sol.success
    peak = float(ode.tension(sys, sol.sol(np.linspace(0, 9.0, 9001))).max())
    assert res.envelope["t_max_kn"].max() * 1e3 == pytest.approx(peak, rel=0.005)


def test_carriage_at_its_end_stop_is_a_warning_not_divergence():
    """A gravity take-up with too little travel for the belt's stretch (1 m on the 16.8 km
    overland): the carriage reaches its end stop early in the start and the belt runs on
    against it. The run names the end stop and the speed it hit at as a warning, never a
    numerical divergence."""
    conv = conveyor("overland-16km", takeup=SHORT_TRAVEL)
    st = solve_steady(conv, model="nonlin", n_elements=80)
    res = simulate(build_system(conv, Scenario(elements=80, run_s=5), st), conveyor=conv)
    assert res.raw["endstop_t"] > 0.0 and res.raw["endstop_speed"] > 0.0
    assert res.summary["takeup_travel_m"] == pytest.approx(SHORT_TRAVEL["travel_m"])
    assert res.status == "warning"
    assert "end stop" in res.message and "diverged" not in res.message
    # the belt stretches in the start: the carriage runs to the counterweight's low end
    assert "take-up carriage reached the running end" in res.message
    assert "rest end" not in res.message
    assert "a longer takeup.travel_m" in res.message
    # the stretch comes from the drive force, not the counterweight: no heavier take-up offered
    assert "heavier take-up, which resists" not in res.message
    # its running stretch (half the belt's elongation, two strands) is beyond the 1 m
    assert re.search(r"the running stretch alone needs ([\d.]+) m", res.message)


