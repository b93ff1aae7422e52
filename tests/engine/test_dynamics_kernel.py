"""The numba kernel against the slow numpy reference of the same equations (STYLE: a kernel
and a reference path tested against each other), its building blocks, records and failure
handling."""

from __future__ import annotations

import time

import numpy as np
import pytest
from numpy.testing import assert_allclose

from beltstudy.engine.conveyor import Scenario, load_conveyor, load_mapping, parse_conveyor
from beltstudy.engine.dynamics import DynamicsOptions, build_system, simulate
from beltstudy.engine.dynamics import codes as C
from beltstudy.engine.dynamics.blocks import solve_arrow
from beltstudy.engine.dynamics.fastmath import vexp, vlog
from beltstudy.engine.dynamics.model import exponent_codes, implicit_blocks, with_law, with_step
from beltstudy.engine.dynamics.passes import resistance, spring
from beltstudy.engine.dynamics.records import Springs
from beltstudy.engine.dynamics.reference import _law, run_reference
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
                 lambda kr: kr.model.law.mode == C.LAW_LINEAR and kr.run["law_evals"] > 0,
                 id="fabric-nonlin-holdback-coast"),
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
                 lambda kr: len(kr.model.drives.share) == 2, id="dual-head-half-shares"),
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
    assert int(res["status"]) == ref["status"] == C.OK
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
    for key in ("start_ach", "stop_ach", "t_trip", "hold_set"):
        assert res[key] == pytest.approx(ref[key], abs=1e-9), key
    assert res["slack_dur"] == pytest.approx(ref["slack_s"], abs=1e-9)
    assert_allclose(out.drv["slip_s"], ref["slip_s"], atol=1e-9, rtol=0)
    assert_allclose(out.drv["slip_m"], ref["slip_m"], atol=1e-9, rtol=1e-9)
    assert_allclose(out.shs["slip_s"], ref["shaft_slip_s"], atol=1e-9, rtol=0)
    assert_allclose(out.shs["slip_m"], ref["shaft_slip_m"], atol=1e-9, rtol=1e-9)
    assert res["law_evals"] == ref["law_evals"]


@pytest.mark.parametrize("changes, scenario, status", [
    pytest.param(dict(profile=[{"length_m": 1000, "lift_m": -150}]), {}, C.RUNAWAY,
                 id="a-decline-runs-away"),
    pytest.param(dict(drives=[{"position": "head", "wrap_deg": 200, "friction": 0.35,
                               "share": 1.0, "pulley_diameter_m": 1.0, "inertia_kg_m2": 2.0,
                               "control": "dol", "rated_power_kw": 240, "coupling": "fluid"}],
                      takeup={"type": "gravity", "position": "tail", "mass_kg": 16000}),
                 dict(dt_s=0.013), C.DIVERGED, id="a-light-shaft-diverges"),
])
def test_kernel_and_reference_end_a_run_alike(changes, scenario, status):
    """A run that ends early ends at the same step in both, for the same reason: the belt ran
    away (mean speed past twice the design speed; the final state agrees to 1e-9), or a pulley
    shaft left the finite range (the same shaft named)."""
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
        assert int(res["div_where"]) == ref["div_where"] >= 0


def test_vectorised_log_and_exp():
    x = np.concatenate([[1e-300, 1e-12, 1.0, 2.0], np.exp(np.linspace(-20, 20, 997))])
    out = np.empty_like(x)
    vlog(x, out)
    err = np.abs(out - np.log(x)) / np.maximum(1.0, np.abs(np.log(x)))
    assert err.max() < 2e-15
    y = np.linspace(-700, 700, 1001)
    vexp(y, out[:1001])
    assert_allclose(out[:1001], np.exp(y), rtol=5e-15)
    for p in (0.3, 0.039, 1.7):  # the powers the friction laws use
        z = np.exp(np.linspace(-5, 3, 500))
        lz, pz = np.empty(500), np.empty(500)
        vlog(z, lz)
        vexp(p * lz, pz)
        assert_allclose(pz, z**p, rtol=1e-14)


def test_blocks_cover_the_pulleys_and_wrap_at_the_tail():
    conv = load_conveyor(CONVEYORS / "overland-16km.yaml")
    st = solve_steady(conv, n_elements=40)
    loop = st.loop
    implicit, blocks = implicit_blocks(loop.strand)
    n = loop.n
    # head pulley, head take-up pulley, tail pulley: their springs on both sides are implicit
    for p in (loop.i_head, loop.i_takeup, loop.i_tail):
        assert implicit[p] and implicit[p - 1]
    assert [loop.i_head - 1, loop.i_head, loop.i_takeup, loop.i_takeup + 1] in blocks
    assert [n - 2, n - 1, 0] in blocks
    assert implicit.sum() == 5


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


def test_resistance_every_exponent_code_matches_the_reference_law():
    """The kernel's resistance pass (one specialised loop per speed/sag exponent pair, the
    vectorised log/exp, sparse terms) against the reference's np.power law, for every
    exponent code including ones no shipped model uses, at rest (v = 0) and running."""
    conv = load_conveyor(CONVEYORS / "overland-16km.yaml")
    st = solve_steady(conv, model="nonlin", n_elements=60)
    sys = build_system(conv, Scenario(), st)
    n = sys.n
    rng = np.random.default_rng(1)
    exps = [0.0, 0.5, 1.0, 1.5, 2.0, 0.3, 0.039, 1.7]
    pv, ps, coef = [], [], []
    for p in (0.0, 1.0, 0.3, 2.0, 0.5, 1.7):
        for q in exps:
            pv.append(p)
            ps.append(q)
            coef.append(rng.uniform(0.5, 2.0, n))
    coef = np.array(coef)
    coef[-1, :] = 0.0
    coef[-1, [3, 17]] = 5.0  # a sparse term
    pv, ps = np.array(pv), np.array(ps)
    kr = fresh_run(with_law(sys, coef, pv, ps))
    law, nodes, wk = kr.model.law, kr.model.nodes, kr.work
    assert law.any_ps
    assert law.t_sparse[-1] == 1 and law.t_sparse[:-1].sum() == 0
    assert set(exponent_codes(pv)) | set(exponent_codes(ps)) == {0, 1, 2, 3, 4, 5}
    for v in (np.zeros(n), rng.normal(0.0, 3.0, n)):
        tt = np.maximum(rng.normal(5e4, 3e4, n), 0.0)
        resistance(law, nodes, kr.state._replace(v=v, tt=tt), wk)
        ref = _law(law, nodes, v, tt)
        assert_allclose(wk.r0, ref, rtol=1e-13, atol=1e-12 * np.abs(ref).max())


def _spring(e0, s0, de, tfl, sfl, kfl_eb, a_eb, eb):
    """The kernel's update of one spring (:func:`passes.spring`) from elastic tension e0 and
    strain tension s0 after the strain increment de: no arm, no viscosity, no carriage."""
    def one(x):
        return np.array([float(x)])

    none = np.zeros((0, 2), dtype=np.int64)
    sp = Springs(len_m=one(1.0), a_ernst=one(a_eb / eb), t_floor=one(tfl),
                 k_floor=one(kfl_eb * eb), viscosity=one(0.0), car_ind=one(0.0),
                 eps_run=one(0.0), eb=float(eb), eb_dyn=float(eb), dl=one(1.0), a_eb=one(a_eb),
                 s_floor=one(sfl), kfl_eb=one(kfl_eb), kvs=one(0.0), e_damp=0.0, g_damp=0.0,
                 seg_node=none, seg_spring=none)
    return spring(sp, 0, e0, s0, 0.0, de, 0.0)


def _chord_s(t, eb, a_eb, tfl, kfl):
    """Strain tension EB eps of Ernst's chord law by hand, linear at kfl below the floor."""
    sf = tfl - a_eb / (2.0 * tfl**2)
    return t - a_eb / (2.0 * t**2) if t >= tfl else sf - (tfl - t) * eb / kfl


def test_unloading_past_the_floor_stores_the_geometric_slack():
    """A strain increment that takes a spring from running tension to below the floor in one
    step ends on the floor line: by hand, the chord strain 0.1 below the floor's gives
    ``tfl - 0.1 kfl`` (kfl = EB tfl^3 / (tfl^3 + a EB)), slack, and the belt does not push.
    A small increment above the floor lands on the chord law itself (the tension whose chord
    strain is the new strain, solved by bisection, 1e-9)."""
    eb, a_eb, tfl = 3.456e8, 1.97e14, 3.3e3
    kfl = eb * tfl**3 / (tfl**3 + a_eb)
    sf = _chord_s(tfl, eb, a_eb, tfl, kfl)
    e0 = 2.0e5
    s0 = _chord_s(e0, eb, a_eb, tfl, kfl)
    de = (sf - s0) / eb - 0.1
    e1, s1, d1, t1 = _spring(e0, s0, de, tfl, sf, kfl / eb, a_eb, eb)
    assert s1 == pytest.approx(s0 + eb * de, rel=1e-12)
    assert e1 == pytest.approx(tfl - 0.1 * kfl, rel=1e-9)
    assert e1 < 0.0 and t1 == 0.0 and d1 == 0.0  # slack: the belt does not push
    e1, s1, _, _ = _spring(e0, s0, -1e-4, tfl, sf, kfl / eb, a_eb, eb)
    lo, hi = tfl, e0
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if _chord_s(mid, eb, a_eb, tfl, kfl) < s1 else (lo, mid)
    assert e1 == pytest.approx(0.5 * (lo + hi), rel=1e-9)


def test_a_strain_cycle_through_slack_returns_the_tension_it_started_from():
    """The elastic tension is a function of the strain (Ernst's chord law, the floor line,
    slack): a cycle of increments from running tension down through the floor into slack and
    back to the starting strain, in uneven steps, returns the starting tension (1e-9), and the
    elastic work round the cycle, sum of T de, is zero to the order of the steps (a tension
    that lagged the strain would leave work behind)."""
    eb, a_eb, tfl = 3.456e8, 1.97e14, 3.3e3
    kfl = eb * tfl**3 / (tfl**3 + a_eb)
    sf = _chord_s(tfl, eb, a_eb, tfl, kfl)
    e0 = 2.0e5
    s0 = _chord_s(e0, eb, a_eb, tfl, kfl)
    rng = np.random.default_rng(7)
    down = -rng.uniform(0.5, 1.5, 400)
    down *= ((sf - s0) / eb - 2e-3) / down.sum()  # to 2e-3 of strain below the floor
    steps = np.concatenate([down, -down[::-1][rng.permutation(400)]])
    e, s, work, work_scale = e0, s0, 0.0, 0.0
    for de in steps:
        e1, s, _, _ = _spring(e, s, de, tfl, sf, kfl / eb, a_eb, eb)
        work += 0.5 * (max(e, 0.0) + max(e1, 0.0)) * de
        work_scale += 0.5 * (max(e, 0.0) + max(e1, 0.0)) * abs(de)
        e = e1
    assert s == pytest.approx(s0, rel=1e-12)
    assert e == pytest.approx(e0, rel=1e-9)
    assert abs(work) < 1e-3 * work_scale


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


def test_block_solve_matches_a_dense_solve():
    """The blocks' band solve (tridiagonal element rows plus the take-up carriage's row and
    column) against numpy's dense solve, on random systems of the form the kernel builds:
    masses / dt on the diagonal plus springs B g g^T, g = e_(k+1) - e_k (+ e_carriage), some
    rows imposed (identity), the carriage free or at its end stop."""
    rng = np.random.default_rng(7)
    for _ in range(300):
        m = int(rng.integers(1, 7))
        car = bool(rng.integers(0, 2))
        mu = m + 1 if car else m
        A = np.diag(rng.uniform(1e3, 1e6, mu))
        for k in range(m - 1):
            g = np.zeros(mu)
            g[k + 1], g[k] = 1.0, -1.0
            if car and rng.integers(0, 2):
                g[m] = 1.0
            A += rng.uniform(0.0, 1e8) * np.outer(g, g)
        b = rng.normal(size=mu) * 1e5
        fixed = rng.uniform(size=m) < 0.25
        car_free = car and rng.uniform() >= 0.3  # a carriage at its end stop is imposed
        Aw, bw = A.copy(), b.copy()
        for k in np.flatnonzero(fixed):
            Aw[k] = 0.0
            Aw[k, k] = 1.0
        if car and not car_free:
            Aw[m] = 0.0
            Aw[m, m] = 1.0
        want = np.linalg.solve(Aw, bw)
        d = np.diag(Aw).copy()
        lo = np.array([Aw[k, k - 1] if k > 0 else 0.0 for k in range(m)] + [0.0])
        up = np.array([Aw[k, k + 1] if k + 1 < m else 0.0 for k in range(m)] + [0.0])
        cl = np.array([Aw[k, m] if car else 0.0 for k in range(m)] + [0.0])
        rw = np.array([Aw[m, k] if car else 0.0 for k in range(m)] + [0.0])
        x = bw.copy()
        assert solve_arrow(d, lo, up, cl, rw, x, m, car, car_free)
        assert_allclose(x, want, rtol=1e-9, atol=1e-12 * np.abs(want).max())
