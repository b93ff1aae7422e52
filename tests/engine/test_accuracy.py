"""Error bars by mesh refinement (beltstudy.engine.accuracy): the observed order, the
Richardson estimate and the grid convergence index against hand calculations on sequences
of known order (Roache 1994), the spread of a figure outside the asymptotic range, the
marginal verdicts, and a run close to slack named marginal."""

from __future__ import annotations

import math

import pytest

from beltstudy.engine import accuracy as A


def _seq(f_inf: float, c: float, p: float, meshes=(50, 100, 200, 400)) -> tuple:
    """f(n) = f_inf + c n^-p: a figure converging at order p."""
    return tuple(f_inf + c * n ** -p for n in meshes)


def test_richardson_on_a_first_order_sequence():
    f3, f2, f1, f4 = _seq(100.0, 500.0, 1.0)  # 110, 105, 102.5; 101.25 at 4n
    fe = A.figure_error("t_max_dyn_kn", (f3, f2, f1), (50, 100, 200))
    assert fe.method == "richardson"
    assert fe.order == pytest.approx(1.0, abs=1e-12)  # ln(5 / 2.5) / ln 2
    assert fe.converged == pytest.approx(100.0, abs=1e-9)  # 102.5 + (102.5 - 105) / (2 - 1)
    assert fe.err == pytest.approx(1.25 * 5.0, abs=1e-9)  # Fs |f2 - f_inf|
    assert abs(f4 - fe.value) <= fe.err  # the bar holds the 4n value (3.75 of 6.25)


def test_order_below_the_asymptotic_range_is_bounded_with_fs_3():
    f3, f2, f1, f4 = _seq(20.0, 40.0, 0.3)
    fe = A.figure_error("t_min_stop_kn", (f3, f2, f1), (50, 100, 200))
    assert fe.method == "gci3" and fe.order == pytest.approx(0.3, abs=1e-12)
    rp = 2.0 ** 0.5 - 1.0  # the order used: at least sqrt(dx)'s
    conv = f1 + (f1 - f2) / rp
    assert fe.converged == pytest.approx(conv, rel=1e-12)
    assert fe.err == pytest.approx(3.0 * abs(f2 - conv), rel=1e-12)
    assert abs(f4 - f2) <= fe.err


def test_differences_that_grow_with_the_mesh_give_a_bar_and_no_converged_value():
    """23.0, 22.0, 20.0 on 50 / 100 / 200 elements: the differences 1 and 2 grow, p = ln(1 /
    2) / ln 2 = -1. Nothing converges within these meshes: no estimate; the bar is Fs 3 with
    the order bounded to 0.5, 3 |f2 - (f1 + (f1 - f2) / (sqrt 2 - 1))| = 3 x 2 x 3.414 =
    20.49."""
    fe = A.figure_error("t_max_dyn_kn", (23.0, 22.0, 20.0), (50, 100, 200))
    assert fe.method == "growing" and fe.order == pytest.approx(-1.0, abs=1e-12)
    assert fe.converged is None
    assert fe.err == pytest.approx(3.0 * 2.0 * (1.0 + 1.0 / (2.0 ** 0.5 - 1.0)), rel=1e-12)


def test_a_fine_pair_that_agrees_by_chance_gets_the_range_of_the_three():
    """A 3.6 km overland's lowest tension in a brake stop with the load on its declines read
    37.767, 36.818 and 36.808 kN on 106, 204 and 412 elements: observed order 6.9, the fine
    pair within 0.01 kN. The bar from that pair alone (order bounded to 1, Fs 3) was
    +- 0.06 kN, and 820 elements read 36.39 kN, 7 x the bar away. Above the formal order the
    bar is at least 1.25 x the range of the three (Eca & Hoekstra 2014): 1.25 x 0.959 kN."""
    fe = A.figure_error("t_min_dyn_kn", (37.767, 36.818, 36.808), (106, 204, 412))
    assert fe.method == "gci3" and fe.order > 6.0
    assert fe.err == pytest.approx(1.25 * (37.767 - 36.808), rel=1e-12)
    assert abs(36.39 - fe.value) <= fe.err
    # within the formal order's band the range adds nothing: 30, 28, 27 (p 1) keeps Richardson
    near = A.figure_error("t_min_dyn_kn", (30.0, 28.0, 27.0), (50, 100, 200))
    assert near.method == "richardson" and near.err == pytest.approx(1.25 * 2.0, rel=1e-12)


def test_unequal_ratios_give_the_order_by_celik_s_fixed_point():
    meshes = (21, 42, 86)
    f3, f2, f1 = _seq(7.0, 30.0, 1.05, meshes + (1,))[:3]
    fe = A.figure_error("stop_time_s", (f3, f2, f1), meshes)
    assert fe.method == "richardson" and fe.order == pytest.approx(1.05, abs=1e-6)
    assert fe.converged == pytest.approx(7.0, abs=1e-6)


def test_an_order_above_the_formal_one_is_not_credited():
    f3, f2, f1, f4 = _seq(50.0, 2.0e4, 2.0)  # 58, 52, 50.5
    fe = A.figure_error("t_max_stop_kn", (f3, f2, f1), (50, 100, 200))
    assert fe.method == "gci3" and fe.order == pytest.approx(2.0)
    # p used 1 (the formal order), Fs 3: converged 50.5 - 1.5 = 49, bar 3 x |52 - 49| = 9,
    # and at least 1.25 x the range 58 - 50.5 (Eca & Hoekstra 2014): 9.375
    assert fe.converged == pytest.approx(49.0) and fe.err == pytest.approx(9.375)
    # the words give the observed order and the bounded one the bar used (they read as if
    # gci3 had taken p 2 where its bound is the formal order 1)
    low = A.figure_error("t_min_stop_kn", _seq(50.0, 2.0e4, 0.6)[:3], (50, 100, 200))
    acc = A.Accuracy((50, 100, 200), {"t_max_stop_kn": fe, "t_min_stop_kn": low})
    assert acc.methods() == ("gci3: t_max_stop_kn (p 2 observed, 1 used), t_min_stop_kn "
                             f"(p {low.order:.2g})")


def test_differences_of_opposite_sign_give_the_spread():
    fe = A.figure_error("slip_margin_min_dyn", (1.30, 1.20, 1.26), (50, 100, 200))
    assert fe.method == "spread" and fe.converged is None and fe.order is None
    assert fe.err == pytest.approx(3.0 * 0.10)  # Fs 3: the order is not established


def test_unchanged_and_missing_meshes():
    fe = A.figure_error("slack_max_m", (0.0, 0.0, 0.0), (50, 100, 200))
    assert fe.method == "unchanged" and fe.err == 0.0
    # the fine mesh missing: two meshes, the run's the finer, assumed order, Fs 3
    fe = A.figure_error("t_max_dyn_kn", (110.0, 105.0, None), (50, 100, 200))
    assert fe.method == "gci2"
    assert fe.err == pytest.approx(3.0 * 5.0 / (math.sqrt(2.0) - 1.0))
    assert A.figure_error("t_max_dyn_kn", (110.0, None, 100.0), (50, 100, 200)) is None


def test_an_extrapolation_below_zero_of_a_figure_that_cannot_be_negative_is_no_estimate():
    """A lowest tension of 40, 20 and 5 kN on 50 / 100 / 200 elements: differences 20 and 15,
    p = ln(20 / 15) / ln 2 = 0.415, bounded to 0.5 (gci3), Richardson 5 + (5 - 20) / (sqrt 2 -
    1) = -31.2 kN: a belt tension below the model's floor of 0 kN (slack). The converged
    estimate said -31.2 kN (and a marginal verdict 'converged estimate -31.2 kN'); it is now
    none, and the bar stands: 3 |20 - (-31.2)| = 153.6 kN. A lift-off excess, which may be
    negative, keeps its estimate."""
    vals = (40.0, 20.0, 5.0)
    conv = 5.0 + (5.0 - 20.0) / (math.sqrt(2.0) - 1.0)
    assert conv == pytest.approx(-31.213, abs=1e-3)
    for name in ("t_min_dyn_kn", "slack_max_m", "sag_max_dyn_pct", "stop_time_s"):
        fe = A.figure_error(name, vals, (50, 100, 200))
        assert fe.method == "gci3" and fe.order == pytest.approx(math.log(20 / 15) / math.log(2))
        assert fe.converged is None, name
        assert fe.err == pytest.approx(3.0 * (20.0 - conv), rel=1e-12)  # 153.6
    # two meshes (gci2): 47.9 kN on 10 elements, 18.2 kN on 22, order 0.5 assumed:
    # 18.2 + (18.2 - 47.9) / (2.2^0.5 - 1) = -43.26 kN, no estimate; the bar 3 |47.9 + 43.26|
    fe = A.figure_error("t_min_dyn_kn", (None, 47.9, 18.2), (None, 10, 22))
    two = 18.2 + (18.2 - 47.9) / (2.2 ** 0.5 - 1.0)
    assert fe.method == "gci2" and two == pytest.approx(-43.26, abs=0.005)
    assert fe.converged is None and fe.err == pytest.approx(3.0 * (47.9 - two), rel=1e-12)
    words = A.marginal_verdicts({"slack_max_m": 0.0}, {"t_min_dyn_kn": fe}, finest=22)
    assert len(words) == 1 and "converged estimate" not in words[0]
    # a figure that may be negative keeps its extrapolation
    fe = A.figure_error("liftoff_max_kn_over", vals, (50, 100, 200))
    assert fe.converged == pytest.approx(conv, rel=1e-12)
    # an estimate at or above 0 is kept
    fe = A.figure_error("t_min_dyn_kn", (40.0, 20.0, 10.0), (50, 100, 200))
    assert fe.method == "richardson" and fe.converged == pytest.approx(0.0, abs=1e-9)


def test_deciding_figures_are_those_the_run_reports():
    s = {"t_max_dyn_kn": 5.0, "t_min_dyn_kn": 1.0, "drive2_force_max_kn": 3.0,
         "drive1_force_max_kn": 2.0, "drive1_slip_s": 0.0, "stop_time_s": None,
         "takeup_travel_start_m": 0.2, "velocity_max_m_s": 4.0}
    assert A.deciding_figures(s) == ["t_max_dyn_kn", "t_min_dyn_kn", "drive1_force_max_kn",
                                     "drive2_force_max_kn", "takeup_travel_start_m"]


def _fe(name, value, err):
    return A.FigureError(name, value, err, None, "spread", None, (value, value, value))


def test_a_verdict_within_its_error_of_the_limit_is_marginal():
    # not slack, lowest tension 0.8 kN +- 1.5 kN: slack within the error
    words = A.marginal_verdicts({"slack_max_m": 0.0}, {"t_min_dyn_kn": _fe("t_min_dyn_kn", 0.8,
                                                                            1.5)})
    assert words == ["marginal: t_min_dyn_kn 0.8 against limit 0 +- 1.5 kN (the verdict may "
                     "flip with the mesh)"]
    assert A.marginal_verdicts({"slack_max_m": 0.0},
                               {"t_min_dyn_kn": _fe("t_min_dyn_kn", 0.8, 0.5)}) == []
    # slack by 2 cm of belt +- 5 cm
    words = A.marginal_verdicts({"slack_max_m": 0.02},
                                {"slack_max_m": _fe("slack_max_m", 0.02, 0.05)})
    assert words and words[0].startswith("marginal: slack_max_m 0.02 against limit 0 +- 0.05")
    # slip margin 1.03 +- 0.05 against 1; safety factor 5.9 +- 0.2 against 6
    words = A.marginal_verdicts({}, {"slip_margin_min_dyn": _fe("slip_margin_min_dyn", 1.03,
                                                                 0.05),
                                     "safety_factor_dyn": _fe("safety_factor_dyn", 5.9, 0.2)},
                                safety_factor_min=6.0)
    assert [w.split(" against")[0] for w in words] == [
        "marginal: slip_margin_min_dyn 1.03", "marginal: safety_factor_dyn 5.9"]



def test_a_slip_that_a_mesh_of_the_check_holds_is_marginal():
    """A 350 m 16 deg incline's controlled stop slipped 5.7e-5 m on 203 elements at a margin
    of 0.9953 +- 0.0717 and held on 103 (1.003, status ok): the slip verdict flips with the
    mesh, so it is marginal (PHYSICS 5.2). A slip on every mesh of the check is not: the
    margin of a slipping pulley sits at its floor, 1, whatever the mesh."""
    slipped = {"drive1_slip_s": 0.004}
    flips = A.FigureError("slip_margin_min_dyn", 0.9953, 0.0717, None, "spread", None,
                          (1.003, 0.9953, 0.981))
    words = A.marginal_verdicts(slipped, {"slip_margin_min_dyn": flips}, finest=409)
    assert len(words) == 1 and words[0].startswith(
        "marginal: slip_margin_min_dyn 0.9953 against limit 1 +- 0.0717 (the verdict may flip")
    every = A.FigureError("slip_margin_min_dyn", 0.9953, 0.0717, None, "spread", None,
                          (0.999, 0.9953, 0.991))
    assert A.marginal_verdicts(slipped, {"slip_margin_min_dyn": every}, finest=409) == []


def test_a_figure_the_same_on_every_mesh_is_not_marginal():
    """A decline's auto take-up is sized to hold the belt at rest at a slip margin of exactly 1
    (DIN 22101's grip with its design friction); the run's lowest margin is that held state,
    1.0000000000000002 on every mesh, so its bar is only the law's resolution (0.1 % of 1). No
    mesh flips that verdict: it is not named marginal, while the same value and bar from
    meshes that differ is."""
    vals = (1.0000000000000002,) * 3
    bars = A.bars([{"slip_margin_min_dyn": v} for v in vals], (100, 200, 400), 1e-3)
    fe = bars["slip_margin_min_dyn"]
    assert fe.method == "unchanged" and fe.err == pytest.approx(1e-3)
    assert A.marginal_verdicts({}, {"slip_margin_min_dyn": fe}) == []
    assert A.marginal_verdicts({}, {"slip_margin_min_dyn": _fe("slip_margin_min_dyn", vals[0],
                                                                1e-3)})

def test_a_marginal_verdict_says_what_would_settle_it():
    """A marginal verdict gave no lever. It now gives the finest mesh's value, the side of the
    limit its converged (Richardson) estimate lies on, and the finer mesh that narrows the bar.
    A lowest tension of 0.8 kN +- 1.5 kN on 200 elements (0.5 kN on 400, converged 0.3 kN)
    passes the slack check: the estimate is on the passing side; a sag of 2.9 % +- 0.2 %
    against 3 % converging to 3.05 % is on the failing side, as is a lift-off excess of
    -0.4 kN converging to +0.2 kN (above 0 kN the belt lifts)."""
    def fe(name, value, err, conv, values):
        return A.FigureError(name, value, err, conv, "richardson", 1.0, values)

    words = A.marginal_verdicts(
        {"slack_max_m": 0.0},
        {"t_min_dyn_kn": fe("t_min_dyn_kn", 0.8, 1.5, 0.3, (1.4, 0.8, 0.5)),
         "sag_max_dyn_pct": fe("sag_max_dyn_pct", 2.9, 0.2, 3.05, (2.6, 2.9, 2.99)),
         "liftoff_max_kn_over": fe("liftoff_max_kn_over", -0.4, 0.7, 0.2, (-1.0, -0.4, -0.1))},
        sag_limit_pct=3.0, finest=400)
    assert words == [
        "marginal: t_min_dyn_kn 0.8 against limit 0 +- 1.5 kN (the verdict may flip with the "
        "mesh; 0.5 kN on 400 elements; converged estimate 0.3 kN, which passes; a finer mesh "
        "(scenario.elements 800) narrows the bar)",
        "marginal: sag_max_dyn_pct 2.9 against limit 3 +- 0.2 % (the verdict may flip with the "
        "mesh; 2.99 % on 400 elements; converged estimate 3.05 %, which fails; a finer mesh "
        "(scenario.elements 800) narrows the bar)",
        "marginal: liftoff_max_kn_over -0.4 against limit 0 +- 0.7 kN (the verdict may flip "
        "with the mesh; -0.1 kN on 400 elements; converged estimate 0.2 kN, which fails; a "
        "finer mesh (scenario.elements 800) narrows the bar)"]
    # no estimate (a spread): the finest value and the finer mesh only
    spread = A.FigureError("safety_factor_dyn", 6.8, 0.3, None, "spread", None, (7.0, 6.8, 6.9))
    assert A.marginal_verdicts({}, {"safety_factor_dyn": spread}, safety_factor_min=6.7,
                               finest=400) == [
        "marginal: safety_factor_dyn 6.8 against limit 6.7 +- 0.3 (the verdict may flip with "
        "the mesh; 6.9 on 400 elements; a finer mesh (scenario.elements 800) narrows the bar)"]


def test_a_verdict_every_mesh_gives_and_refining_leaves_is_not_marginal():
    """A sag of 50.8 % against 1.5 % had a 'spread' bar of +- 133 % and was called marginal,
    'the verdict may flip', though every mesh failed it and the finer one by more (63.7 %).
    Where the three meshes give the same verdict and each finer one lies further from the
    limit, refining moves away from a flip: not marginal. The same values coming back
    towards the limit, or on both sides of it, stay marginal."""
    def words(values):
        fe = A.FigureError("sag_max_dyn_pct", values[1], 133.0, None, "spread", None, values)
        return A.marginal_verdicts({}, {"sag_max_dyn_pct": fe}, sag_limit_pct=1.5, finest=400)

    assert words((31.0, 50.8, 63.7)) == []
    assert words((70.0, 50.8, 40.1))[0].startswith("marginal: sag_max_dyn_pct 50.8 against "
                                                    "limit 1.5 +- 133 %")
    assert words((1.2, 50.8, 63.7))  # the coarse mesh passed it: the verdict flipped once


def test_a_lift_off_within_its_error_of_zero_is_marginal():
    """liftoff_max_kn_over (the most a concave curve's tension went over its lift-off
    tension; > 0 the belt lifted) is judged against 0 kN: a belt that lifted by 0.14 kN
    +- 2.5 kN, or stayed down by 1.0 kN +- 2.5 kN, may do the other on a finer mesh; one
    3.2 kN under the limit +- 1.5 kN, or 10 kN over it +- 2 kN, does not. A run without a
    concave curve has no such figure and no verdict."""
    def words(value, err):
        return A.marginal_verdicts({"slack_max_m": 0.0}, {
            "liftoff_max_kn_over": _fe("liftoff_max_kn_over", value, err)})

    assert words(0.14, 2.5) == ["marginal: liftoff_max_kn_over 0.14 against limit 0 +- 2.5 kN "
                                "(the verdict may flip with the mesh)"]
    assert words(-1.0, 2.5)[0].startswith("marginal: liftoff_max_kn_over -1 against limit 0")
    assert words(-3.2, 1.5) == [] and words(10.0, 2.0) == []
    assert A.marginal_verdicts({"slack_max_m": 0.0, "liftoff_max_kn_over": None}, {}) == []
    # a figure of the deciding ones, barred where the run reports it (null without a curve)
    assert "liftoff_max_kn_over" in A.deciding_figures({"liftoff_max_kn_over": -1.0})
    assert A.deciding_figures({"liftoff_max_kn_over": None}) == []


def test_a_lift_off_in_one_phase_under_the_other_s_peak_is_said_by_its_phase():
    """The cycle's lift-off margin is the larger of the start's (with running) and the stop's:
    a start margin of -0.87 kN that has converged (+- 0.004 kN) over a stop margin of -3.07 kN
    that grows with the mesh (+- 22 kN) is not marginal as the cycle's figure, yet the stop
    may lift on a finer mesh: the stop's figure says so. Where the cycle's figure is itself
    marginal, the phase of the same peak is not said twice."""
    cycle = _fe("liftoff_max_kn_over", -0.87, 0.004)
    start = _fe("liftoff_over_start_kn", -0.87, 0.004)
    stop = _fe("liftoff_over_stop_kn", -3.07, 22.0)
    words = A.marginal_verdicts({}, {f.name: f for f in (cycle, start, stop)})
    lift = [w for w in words if "liftoff" in w]
    assert lift == ["marginal: liftoff_over_stop_kn -3.07 against limit 0 +- 22 kN (the "
                    "verdict may flip with the mesh)"]
    cycle, start = (_fe(f.name, -0.5, 2.0) for f in (cycle, start))
    words = A.marginal_verdicts({}, {f.name: f for f in (cycle, start, stop)})
    assert [w.split(" against")[0] for w in words if "liftoff" in w] == [
        "marginal: liftoff_max_kn_over -0.5", "marginal: liftoff_over_stop_kn -3.07"]
    assert A.marginal_verdicts({}, {"liftoff_over_stop_kn": _fe("liftoff_over_stop_kn", -3.07,
                                                                2.0)}) == []


def test_a_lift_off_margin_carries_the_resolution_of_the_tension():
    """A margin T - T_lift inherits the absolute error of the tension T (the resistance law's
    rtol x T), not rtol x the margin, which vanishes where the verdict is close. The valley
    of test_curves_dynamics (R 250 m, 6 t take-up, 60 s start, controlled stop) on 114, 210,
    422 elements: the start's margin -3.716, -3.717, -3.718 kN (+- 0.015 kN by the meshes,
    0.0037 kN as rtol x the margin) and -3.699 kN on 846; rtol x the cycle's highest tension
    91.7 kN = 0.092 kN holds it."""
    s = {"liftoff_over_start_kn": -3.717, "t_max_dyn_kn": 91.7, "t_min_dyn_kn": 2.0}
    assert A.resolution("liftoff_over_start_kn", s, 1e-3) == pytest.approx(0.0917)
    assert A.resolution("t_min_dyn_kn", s, 1e-3) == pytest.approx(0.002)  # its own value
    fe = A.figure_error("liftoff_over_start_kn", (-3.716, -3.717, -3.718), (114, 210, 422),
                        A.resolution("liftoff_over_start_kn", s, 1e-3))
    assert abs(-3.699 - fe.value) <= fe.err


def test_a_brake_stop_close_to_slack_is_named_marginal():
    """A 450 m incline (benchmarks/conveyors/steep-incline.yaml) stopped by a 50 kN head
    brake on 42 elements: its lowest tension, behind the brake on the carry, falls with the
    mesh (about 19, 15 and 10 kN on 22, 42 and 86 elements, differences that do not shrink), so 0 kN
    (slack) lies within the bar of the run's 15 kN: the run is not slack on its mesh and
    says that the verdict is marginal instead of leaving it to flip on a finer one."""
    from beltstudy.engine import load_conveyor, parse_scenario
    from beltstudy.engine.run import run_one
    from tests.conftest import ROOT

    base = load_conveyor(ROOT / "benchmarks" / "conveyors" / "steep-incline.yaml")
    conv = base.model_copy(update={"brakes": [base.brakes[0].model_copy(
        update={"force_kn": 50.0})]})
    scn = parse_scenario({"elements": 40, "run_s": 5, "stop": {"mode": "brake"}})
    res = run_one(conv, scn, model="din", check=True)
    s = res.summary
    assert s["slack_max_m"] == 0.0 and s["t_min_dyn_kn"] > 0.0  # not slack on its own mesh
    acc = res.accuracy
    fe = acc.figures["t_min_dyn_kn"]
    f3, f2, f1 = fe.values
    assert f3 > f2 > f1 > 0.0  # converging from above, towards slack
    assert fe.err >= f2  # slack within the bar
    assert s["t_min_dyn_kn_err"] == fe.err
    assert f"marginal: t_min_dyn_kn {f2:.4g} against limit 0 +- {fe.err:.3g} kN" in s["message"]
    assert s["status"] == "warning"
    # the bar holds the value at 4 x the elements (a quarter of the step), still falling
    fine = run_one(conv, scn.model_copy(update={"elements": 4 * 42}), model="din").summary
    assert fine["t_min_dyn_kn"] < f1 and abs(fine["t_min_dyn_kn"] - f2) <= fe.err


def test_an_end_stop_within_its_error_is_marginal():
    """The take-up end stop is judged like slack: a carriage that reached a stop by its impact
    speed against 0 m/s (0.023 +- 0.18 m/s: a finer mesh may miss it), one that did not by
    its clearance against 0 m (0.08 mm +- 0.45 mm); a hard hit (0.9 +- 0.1 m/s) or a wide
    clearance (0.4 +- 0.01 m) is no marginal verdict."""
    def words(summary, fe):
        return [w for w in A.marginal_verdicts({"slack_max_m": 0.0, **summary},
                                               {fe.name: fe}) if "endstop" in w]

    hit = {"takeup_endstop_speed_m_s": 0.023, "takeup_endstop_gap_m": 0.0}
    assert words(hit, _fe("takeup_endstop_speed_m_s", 0.023, 0.18)) == [
        "marginal: takeup_endstop_speed_m_s 0.023 against limit 0 +- 0.18 m/s (the verdict "
        "may flip with the mesh)"]
    assert words({**hit, "takeup_endstop_speed_m_s": 0.9},
                 _fe("takeup_endstop_speed_m_s", 0.9, 0.1)) == []
    clear = {"takeup_endstop_speed_m_s": 0.0, "takeup_endstop_gap_m": 8e-5}
    assert words(clear, _fe("takeup_endstop_gap_m", 8e-5, 4.5e-4)) == [
        "marginal: takeup_endstop_gap_m 8e-05 against limit 0 +- 0.00045 m (the verdict may "
        "flip with the mesh)"]
    assert words({**clear, "takeup_endstop_gap_m": 0.4},
                 _fe("takeup_endstop_gap_m", 0.4, 0.01)) == []


#: A 300 m, 14 deg incline on a fabric belt with an auto head brake and a 4 m gravity take-up
#: travel (no end stop reached in a brake stop).
STEEP_14 = {
    "name": "steep-14deg-300", "speed_m_s": 2.5,
    "belt": {"type": "EP630/4", "width_m": 1.0, "compound": "standard"},
    "material": {"capacity_t_h": 500, "density_t_m3": 1.4},
    "profile": [{"length_m": 300, "lift_m": 72.58}],
    "idlers": {"carry": {"spacing_m": 1.2, "roll_diameter_m": 0.127, "rolls": 3,
                         "trough_deg": 35, "cema_class": "C"},
               "return": {"spacing_m": 3.0, "roll_diameter_m": 0.127, "rolls": 1,
                          "cema_class": "C"}},
    "drives": [{"position": "head", "wrap_deg": 210, "friction": 0.35, "share": 1.0,
                "pulley_diameter_m": 0.8, "inertia_kg_m2": 200, "rated_power_kw": 250,
                "torque_limit": 1.5}],
    "takeup": {"type": "gravity", "position": "tail", "mass_kg": "auto", "travel_m": 4.0},
    "brakes": [{"position": "head", "force_kn": "auto", "delay_s": 0.3, "ramp_s": 0.5}],
    "holdback": True,
}


def test_a_take_up_end_stop_close_to_the_carriage_is_named_marginal():
    """The carriage of STEEP_14 in a brake stop, at the defaults, with the travel cut until
    its clearance is 0.1 mm either side of the stop it runs towards: whether it reaches the
    stop flipped with the mesh (a travel of 2.3597 m reached it at 0.023 m/s on the run's
    mesh and 0.040 m/s on twice the elements, not at half the step) and no run said so. The
    travel is found from a first run: the carriage's motion does not depend on the travel
    until it reaches a stop, and a shorter travel moves both stops in by half the cut
    (docs/dynamics.md, the take-up)."""
    from beltstudy.engine import parse_conveyor, parse_scenario
    from beltstudy.engine.run import run_one

    scn = parse_scenario({"stop": {"mode": "brake"}})
    wide = run_one(parse_conveyor(STEEP_14), scn, model="din").summary
    gap = wide["takeup_endstop_gap_m"]
    assert wide["takeup_endstop_speed_m_s"] == 0.0 and 0.1 < gap < 2.0
    for cut, hits in ((2.0 * gap - 2e-4, False), (2.0 * gap + 2e-4, True)):
        conv = parse_conveyor({**STEEP_14, "takeup": {**STEEP_14["takeup"],
                                                      "travel_m": 4.0 - cut}})
        s = run_one(conv, scn, model="din", check=True).summary
        if hits:
            assert s["takeup_endstop_speed_m_s"] > 0.0 and s["takeup_endstop_gap_m"] == 0.0
            assert "take-up carriage reached" in s["message"]
            assert "marginal: takeup_endstop_speed_m_s" in s["message"]
        else:
            assert s["takeup_endstop_speed_m_s"] == 0.0
            assert s["takeup_endstop_gap_m"] == pytest.approx(1e-4, abs=1e-6)
            assert "take-up carriage reached" not in s["message"]
            assert "marginal: takeup_endstop_gap_m" in s["message"]


def test_a_fixed_step_keeps_its_fraction_of_the_stability_limit_on_every_mesh():
    """A fixed step just under the stability limit of the run's mesh (slope-5pct, 60
    elements asked, 62 used). The finer mesh asks 124 elements and the loop's cut makes 126:
    the run's step scaled by 62 / 124 was above that mesh's limit, so the bars came from two
    meshes (gci2, t_max_dyn_kn +- 0.86 kN against +- 0.42 from three). Each mesh now runs at
    the run's fraction of its own limit (the same Courant number): three meshes, and the fine
    one's value is that of a run at that fraction."""
    import re
    from dataclasses import replace

    from beltstudy.engine import load_conveyor, parse_scenario
    from beltstudy.engine.dynamics import DynamicsOptions
    from beltstudy.engine.errors import InputError
    from beltstudy.engine.run import run_one
    from tests.conftest import CONVEYORS

    conv = load_conveyor(CONVEYORS / "slope-5pct.yaml")
    scn = parse_scenario({"elements": 60, "run_s": 10, "stop": {"mode": "coast"}, "dt_s": 1.0})
    with pytest.raises(InputError) as exc:
        run_one(conv, scn, model="din")
    limit = float(re.search(r"stability limit ([\d.e-]+) s", str(exc.value)).group(1))
    res = run_one(conv, scn.model_copy(update={"dt_s": 0.99 * limit}), model="din", check=True)
    s = res.summary
    assert s["accuracy_elements"] == "32/62/126"
    assert "note: error bars from two meshes" not in s["message"]
    fe = res.accuracy.figures["t_max_dyn_kn"]
    assert fe.method != "gci2" and None not in fe.values
    fraction = s["dt_used_s"] / res.transient.system.dt_limit_s
    assert fraction == pytest.approx(0.99, rel=2e-3)
    fine = run_one(conv, scn.model_copy(update={"elements": 124, "dt_s": "auto"}), model="din",
                   options=replace(DynamicsOptions(), dt_safety=fraction)).summary
    assert fine["elements_used"] == 126
    assert fe.values[2] == fine["t_max_dyn_kn"]


def test_a_cycle_figure_s_bar_covers_the_phase_that_may_take_it_over():
    """A 1.6 km decline's slip margin was 1.31 (the rest before the start's) on 103 and 205
    elements and 1.26 on 409, a bar of +- 0.13, while the stop's own fell 1.51, 1.44, 1.26 on
    the same meshes and 1.06 on 821 elements (0.96 on 3 279: it slips). The cycle's bar now
    covers each phase's: here down to the stop's 1.44 less its bar, so the 4 x mesh's 1.06 is
    inside it, and the verdict is marginal, not a silent pass."""
    runs = [{"slip_margin_min_dyn": min(a, b), "slip_margin_min_start_dyn": a,
             "slip_margin_min_stop_dyn": b}
            for a, b in ((1.3057, 1.5089), (1.3057, 1.4434), (1.3057, 1.2591))]
    figs = A.bars(runs, (103, 205, 409), 1e-3)
    cyc, stop = figs["slip_margin_min_dyn"], figs["slip_margin_min_stop_dyn"]
    assert cyc.err == pytest.approx(1.3057 - (1.4434 - stop.err))
    assert cyc.value - cyc.err < 1.0611 < cyc.value + cyc.err  # the value on 821 elements
    assert A.marginal_verdicts({}, figs, finest=409)[0].startswith(
        "marginal: slip_margin_min_dyn 1.306 against limit 1")
    # a phase whose bar stays clear of the cycle's does not widen it
    calm = [{"slip_margin_min_dyn": a, "slip_margin_min_start_dyn": a,
             "slip_margin_min_stop_dyn": a + 0.5} for a in (1.32, 1.31, 1.305)]
    figs = A.bars(calm, (103, 205, 409), 1e-3)
    assert figs["slip_margin_min_dyn"].err == A.bars(
        [{"slip_margin_min_dyn": r["slip_margin_min_dyn"]} for r in calm], (103, 205, 409),
        1e-3)["slip_margin_min_dyn"].err


def test_a_phase_near_slack_is_marginal_when_the_other_phase_went_slack():
    """A 1 km 14 deg incline on a dol drive went slack in its coast stop (1.46 m of belt on
    the carry); in the start the return near the tail fell to 0.087 kN +- 0.52 kN on 202
    elements (a sag of 100 % past its 3 % limit, warned) and to 0 kN on 406 (slack: the
    sag verdict gone). The cycle's slack verdict holds the stop; the start's lowest tension,
    within its bar of 0 kN, is marginal. A phase that went slack itself, or one far from 0 kN,
    is not named."""
    summary = {"slack_max_m": 1.46, "t_min_start_kn": 0.087, "t_min_stop_kn": 0.0}
    figures = {"slack_max_m": _fe("slack_max_m", 1.46, 0.01),
               "t_min_start_kn": _fe("t_min_start_kn", 0.087, 0.52),
               "t_min_stop_kn": _fe("t_min_stop_kn", 0.0, 0.3)}
    words = A.marginal_verdicts(summary, figures)
    assert words == ["marginal: t_min_start_kn 0.087 against limit 0 +- 0.52 kN (the verdict "
                     "may flip with the mesh)"]
    figures["t_min_start_kn"] = _fe("t_min_start_kn", 0.087, 0.05)
    assert A.marginal_verdicts(summary, figures) == []


def test_a_coarse_mesh_cut_back_to_the_run_s_own_is_said_as_asked_and_given():
    """slope-5pct on 9 belt elements: the loop keeps an even count, 8, and adds one element
    per pulley; the coarse mesh asks the fewest, 8 belt elements, which gives the run's own
    count again, so no coarser mesh exists. The note says what was asked and what it gave
    (not "no mesh coarser than 10 elements (the fewest is 8)", which reads as a
    contradiction)."""
    from beltstudy.engine import load_conveyor, parse_scenario
    from beltstudy.engine.run import run_one
    from tests.conftest import ROOT

    conv = load_conveyor(ROOT / "studies" / "conveyors" / "slope-5pct.yaml")
    res = run_one(conv, parse_scenario({"elements": 9, "run_s": 5}), model="din", check=True)
    n = int(res.summary["elements_used"])
    assert n > A.ELEMENTS_MIN  # the pulleys on top of the 8 belt elements
    assert res.accuracy.elements[0] is None
    assert (f"no mesh coarser than {n} elements ({A.ELEMENTS_MIN} asked gave {n} with the "
            f"pulleys; the fewest is {A.ELEMENTS_MIN} belt elements)") in res.summary["message"]


def test_a_stop_within_its_bar_of_five_wave_loops_is_marginal():
    """The 5-wave-loop rule flips with the mesh too: a 2.5 km belt's controlled stop rested in
    18.7215 +- 0.0067 s against 5 x 3.74418 = 18.7209 s ('ok'), and in 18.7203 s on twice
    the elements and 18.7188 s at half the step, a high-stress stop, unnamed. A belt that
    never reached design speed (no ``start_time_s``) is not judged by the rule, nor named."""
    summary = {"slack_max_m": 0.0, "stop_time_s": 18.7215, "wave_loop_time_s": 3.74418,
               "start_time_s": 60.0}
    fe = A.FigureError("stop_time_s", 18.7215, 0.0067, None, "spread", None,
                       (18.7230, 18.7215, 18.7203))
    words = A.marginal_verdicts(summary, {"stop_time_s": fe}, finest=406)
    assert len(words) == 1
    assert words[0].startswith("marginal: stop_time_s 18.7215 against limit 18.7209 +- 0.0067 s")
    # well clear of it: nothing said
    far = A.FigureError("stop_time_s", 25.0, 0.0067, None, "spread", None, (25.0,) * 3)
    assert A.marginal_verdicts(dict(summary, stop_time_s=25.0), {"stop_time_s": far}) == []
    assert A.marginal_verdicts(dict(summary, start_time_s=None), {"stop_time_s": fe}) == []


def test_a_marginal_figure_next_to_its_limit_is_printed_to_the_figure_that_tells_them_apart():
    """A decline's slip margin of 1.00003 on 1 645 elements, converging to 0.99996 against the
    limit 1, read "slip_margin_min_dyn 1 against limit 1 ... converged estimate 1, which
    fails": four figures print both as the limit. They are printed to the figure that tells
    them from it, so the side of the limit reads as the verdict says."""
    fe = A.FigureError("slip_margin_min_dyn", 1.00003, 0.001, 0.99996, "richardson", 1.0,
                       (1.0007, 1.00018, 1.00003))
    (w,) = A.marginal_verdicts({}, {"slip_margin_min_dyn": fe}, finest=1645)
    assert w.startswith("marginal: slip_margin_min_dyn 1.00003 against limit 1 +- 0.001"), w
    assert "converged estimate 0.99996, which fails" in w, w
    assert "1.00003 on 1645 elements" in w, w
