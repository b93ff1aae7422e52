"""Vertical curves (engine/loop.py, engine/curves.py; docs/routes.md part (c)) against hand
calculations: the arc's geometry, the lift-off tension at a concave curve, the convex radius
for the troughed belt's edge and centre strains, and the input checks."""

from __future__ import annotations

import math
import re

import numpy as np
import pytest

from beltstudy.engine.conveyor import Scenario, parse_conveyor
from beltstudy.engine.curves import (
    convex_radius_min_m,
    liftoff_limits_n,
    liftoff_tension_n,
    transient_liftoff,
)
from beltstudy.engine.loop import CURVE_STEP_DEG, build_loop, rotating_parts
from beltstudy.engine.statics import solve_steady
from tests.conftest import hand_conveyor_dict

G = 9.81


def curved(radius_m=400.0, lift2_m=50.0, **over):
    """The hand conveyor (m'_G = 20 kg/m, 1 m wide) as 500 m flat, then 500 m rising
    ``lift2_m``, joined by a curve of ``radius_m``."""
    return parse_conveyor(hand_conveyor_dict(profile=[
        {"length_m": 500, "lift_m": 0, "curve_radius_m": radius_m},
        {"length_m": 500, "lift_m": lift2_m}], **over))


def test_liftoff_tension_is_r_m_g_cos_a():
    """CEMA 7th ed. ch. 9 / DIN 22101, concave curve: T = R m' g cos(a).
    R 400 m, m'_G 20 kg/m, a 0.1 rad: 400 x 20 x 9.81 x cos 0.1 = 78 087.9 N."""
    assert liftoff_tension_n(400.0, 20.0, 0.1) == pytest.approx(
        400 * 20 * 9.81 * 0.99500416527802, rel=1e-12)
    assert liftoff_tension_n(400.0, 20.0, 0.1) == pytest.approx(78087.9, abs=0.05)


def test_loop_follows_the_arc():
    """R = 400 m from grade 0 to asin(50 / 500) = 0.10017 rad: arc R delta = 40.07 m, half
    from each section; rise over the arc R (1 - cos delta) = 2.0046 m (a1 = 0); every element
    turns by at most 1 deg; the route keeps 1 000 m and 50 m."""
    conv = curved()
    loop = build_loop(conv, n_elements=200)  # 100 per strand: 10 m elements
    (c,) = loop.curves
    d = math.asin(0.1)
    assert c.kind == "concave" and c.k == 1 and c.section == 0
    arc = loop.dx_m[c.carry]
    assert arc.sum() == pytest.approx(400 * d, rel=1e-12)
    assert loop.s_m[c.carry[0]] == pytest.approx(500 - 200 * d, rel=1e-12)
    # the rise over the arc: midpoint slopes integrate R (1 - cos delta) to O(step^2)
    rise = loop.z_end_m[c.carry[-1]] - loop.z_m[c.carry[0]]
    assert rise == pytest.approx(400 * (1 - math.cos(d)), rel=2e-3)
    # slope: from a1 + step / 2 to a2 - step / 2 in equal steps of at most 1 deg
    a = np.arcsin(loop.sin_a[c.carry])
    steps = np.diff(a)
    assert steps.max() <= math.radians(CURVE_STEP_DEG) + 1e-12
    assert np.allclose(steps, steps[0], rtol=1e-9)
    assert a[0] == pytest.approx(steps[0] / 2, rel=1e-9)
    assert a[-1] == pytest.approx(d - steps[0] / 2, rel=1e-9)
    # elements no longer than the automatic 10 m; the straight rests keep their grade
    assert arc.max() <= 10.0 + 1e-9
    carry = slice(0, loop.nc)
    assert loop.dx_m[carry].sum() == pytest.approx(1000.0, rel=1e-12)
    assert loop.z_end_m[loop.nc - 1] == pytest.approx(50.0, abs=1e-9)
    assert loop.sin_a[loop.nc - 1] == pytest.approx(0.1, rel=1e-4)
    assert loop.sin_a[0] == pytest.approx(0.0, abs=1e-5)
    # the return strand runs the same arc reversed, slope negated
    assert np.array_equal(loop.sin_a[c.ret], -loop.sin_a[c.carry])
    assert np.array_equal(loop.dx_m[c.ret], loop.dx_m[c.carry])
    # a few elements more than the straight route's 100 per strand
    assert 100 < loop.nc <= 106


def test_convex_curve_and_a_section_with_curves_at_both_ends():
    """Grades 0, 5 %, 0 with curves of 500 m and 600 m: the first concave, the second convex
    (the grade decreasing); each section keeps its length and the route its lift."""
    conv = parse_conveyor(hand_conveyor_dict(profile=[
        {"length_m": 300, "lift_m": 0, "curve_radius_m": 500},
        {"length_m": 400, "lift_m": 20, "curve_radius_m": 600},
        {"length_m": 300, "lift_m": 0}]))
    loop = build_loop(conv)
    c1, c2 = loop.curves
    assert (c1.kind, c2.kind) == ("concave", "convex")
    assert c2.at_m == 700.0 and c2.end_m - c2.start_m == pytest.approx(600 * math.asin(0.05))
    assert loop.z_end_m[loop.nc - 1] == pytest.approx(20.0, abs=1e-9)
    assert loop.dx_m[:loop.nc].sum() == pytest.approx(1000.0, rel=1e-12)


def test_steady_liftoff_tension_and_verdict():
    """Lift-off tension of the empty belt at the steepest point of the arc: R m'_G g cos a
    with m'_G = 20 kg/m (hand conveyor), a the arc's slope at its head-side end, the grade
    asin(50 / 500): 400 x 20 x 9.81 x 0.994987 = 78 086.6 N; a radius below the steady
    tension's T / (m'_G g cos a) lifts the belt, with a warning naming the curve."""
    conv = curved(400.0)
    st = solve_steady(conv, model="din", n_elements=200)
    s = st.summary
    assert s["curve1_liftoff_tension_kn"] * 1e3 == pytest.approx(
        400 * 20 * G * math.cos(math.asin(0.1)), rel=1e-12)
    assert s["curve1_liftoff_tension_kn"] == pytest.approx(78.0866, abs=1e-4)
    assert s["curve1_liftoff"] is False  # steady ~ 42 kN against 78 kN
    t = s["curve1_tension_kn"]
    assert t < s["curve1_liftoff_tension_kn"]
    # the radius the steady tension needs, and a curve below it
    r_need = s["curve1_radius_min_m"]
    assert r_need == pytest.approx(t * 1e3 / (20 * G), rel=0.02)
    small = solve_steady(curved(0.8 * r_need), model="din", n_elements=200)
    assert small.summary["curve1_liftoff"] is True
    assert "curve 1 (concave" in small.message and "lifts off" in small.message
    assert small.status == "warning"


def test_a_start_that_lifts_the_belt_where_running_does_not_by_hand():
    """CEMA 7th ed. (concave curves) sizes the radius from the tension at the curve during
    starting, DIN 22101 from the most unfavourable case: the steady check also judges the
    start-up walk of slip_margin_start (drives at STARTUP_FACTOR = 1.5 x Te).

    Hand conveyor (m'_G 20, m'_L 50, m'_R 10 / 3 kg/m), 500 m flat then 500 m up 50 m, curve
    R 230 m, DIN f = 0.02, C = 1: Te = f L g (m'_Rc + m'_Rr + 2 m'_G + m'_L) + m'_L g H +
    accessories = 0.02 x 1000 x 9.81 x 103 + 50 x 9.81 x 50 + 1500 = 46 234 N (the arc's
    cos a takes ~40 N off: 0.2 %). Start-up walk from the tail take-up (it holds its running
    mean): the excess 0.5 Te accelerates every moving mass M (belt, load, idlers 103 t plus
    the pulleys' and motor's rotating parts) at a = 0.5 Te / M, and the tension at x along
    the carry rises by the inertia of the carry behind it,

        T_start(x) = T(x) + a (m'_G + m'_L + m'_Rc) x,

    at the arc's last element (x ~ 511.5 m): 0.5 x 46 234 x 80 x 511.5 / 104 522 = 9.05 kN
    (the tail pulley's half share left out: 1.5 %). Running 39.0 kN < lift-off
    R m'_G g cos a = 230 x 20 x 9.81 x 0.995 = 44.9 kN < start-up 48.1 kN: running stays
    down, the start lifts it, and the radius named is R x T_start / T_lift = 247 m."""
    conv = curved(230.0)
    st = solve_steady(conv, model="din", params={"f_carry": 0.02, "f_return": 0.02, "c": 1.0},
                      n_elements=200)
    loop, s = st.loop, st.summary
    (c,) = loop.curves
    te_hand = 0.02 * 1000 * G * (10 + 3 + 40 + 50) + 50 * G * 50 + 1500
    assert st.te_n == pytest.approx(te_hand, rel=2e-3)
    e = int(c.carry[-1])  # the arc's head-side end: the steepest point, the highest T
    t_lift = 230 * 20 * G * math.cos(math.asin(0.1))
    assert s["curve1_liftoff_tension_kn"] * 1e3 == pytest.approx(t_lift, rel=1e-12)
    assert t_lift == pytest.approx(44.90e3, abs=5)
    m_total = 103_000.0 + rotating_parts(conv, loop).total_kg
    t_start = st.tension_n[e] + 0.5 * te_hand * 80.0 * loop.s_end_m[e] / m_total
    assert s["curve1_tension_start_kn"] * 1e3 == pytest.approx(t_start, rel=0.015)
    assert s["curve1_tension_start_kn"] == pytest.approx(48.1, abs=0.1)
    # running stays down, the start lifts it
    assert s["curve1_tension_kn"] * 1e3 < t_lift < s["curve1_tension_start_kn"] * 1e3
    assert s["curve1_liftoff"] is False and s["curve1_liftoff_start"] is True
    r_start = s["curve1_radius_min_start_m"]
    assert r_start == pytest.approx(230 * s["curve1_tension_start_kn"] * 1e3 / t_lift,
                                    rel=1e-9)
    assert math.ceil(r_start) == 247
    assert st.status == "warning"
    (said,) = [w for w in st.warnings if w.startswith("curve 1 (concave")]
    for words in ("R 230 m", "at start-up", "start-up tension 48.1 kN",
                  "lift-off tension 44.9 kN", "running stays down (39.0 kN there)",
                  "a radius of at least 247 m (R x T_start / T_lift)", "a gentler start",
                  "simulate"):
        assert words in said, (words, said)
    # where running lifts the belt too, its warning names the start's larger radius
    small = solve_steady(curved(180.0), model="din",
                         params={"f_carry": 0.02, "f_return": 0.02, "c": 1.0}, n_elements=200)
    assert small.summary["curve1_liftoff"] is True
    (said,) = [w for w in small.warnings if w.startswith("curve 1 (concave")]
    r = small.summary["curve1_radius_min_start_m"]
    assert f"at start-up ({small.summary['curve1_tension_start_kn']:.1f} kN there) at least " \
        f"{math.ceil(r)} m" in said


def test_convex_radius_min_by_hand():
    """Three rolls, B = 1.0 m, 35 deg: middle roll 0.38 m (DIN 22107, engine/data/trough.csv),
    wings 0.31 m, edge height h = 0.31 sin 35 = 0.17781 m, width-mean height z_mean =
    2 x 0.31 x h / 2 / 1.0 = 0.055121 m. EB = 60 MN, T = 60 kN (eps 1e-3), admissible 150 kN
    (eps_adm 2.5e-3): R_min = max((h - z_mean) / 1.5e-3, z_mean / 1e-3) = max(81.79, 55.12)."""
    h = 0.31 * math.sin(math.radians(35))
    zm = 0.31 * h / 2 / 0.5
    r = convex_radius_min_m(60e3, 60e6, 150e3, 1.0, 3, 35.0)
    assert r == pytest.approx(max((h - zm) / 1.5e-3, zm / 1e-3), rel=1e-9)
    assert r == pytest.approx(81.79, abs=0.01)
    # low tension: the centre would go slack first
    assert convex_radius_min_m(10e3, 60e6, 150e3, 1.0, 3, 35.0) == pytest.approx(
        zm / (10e3 / 60e6), rel=1e-9)
    assert convex_radius_min_m(10e3, 60e6, 150e3, 1.0, 1, 0.0) is None


def test_convex_curve_warns_below_its_radius():
    conv = curved(40.0, lift2_m=-20.0)  # a crest: flat then falling
    st = solve_steady(conv, model="din", n_elements=200)
    s = st.summary
    assert s["curve1_kind"] == "convex" and s["curve1_liftoff"] is False
    assert s["curve1_liftoff_start"] is False  # a crest: no lift-off, running or at start
    assert s["curve1_tension_start_kn"] is None and s["curve1_radius_min_start_m"] is None
    assert s["curve1_radius_min_m"] > 40.0
    assert "curve 1 (convex, R 40 m" in st.message
    assert s["curve1_idler_load_extra_n"] == pytest.approx(
        s["curve1_tension_kn"] * 1e3 * 1.25 / 40.0, rel=1e-12)


def test_a_convex_radius_meets_the_centre_at_the_arcs_lowest_tension():
    """The centre's criterion z_mean / eps is largest where the arc's tension is lowest, the
    edge's (h - z_mean) / (eps_adm - eps) where it is highest: the minimum radius is the
    larger of the two criteria over the arc's tensions, by hand from the steady walk. The
    arc's points are where the belt enters it and each arc element's end: here the belt is
    slackest where it enters (a 4 % decline after the crest), so the entry sets the radius
    (111.40 m against 111.39 m at the lowest element end)."""
    conv = curved(40.0, lift2_m=-20.0, safety_factor_min=8.0)
    st = solve_steady(conv, model="din", n_elements=200)
    (c,) = st.loop.curves
    t_arc = st.tension_n[np.r_[c.carry[0] - 1, c.carry]]
    assert t_arc[0] < st.tension_n[c.carry].min()  # the entry is the slackest point
    belt = st.loop.belt
    adm = belt.rating_n / 8.0
    by_hand = max(convex_radius_min_m(t, belt.stiffness_n, adm, belt.width_m, 3, 35.0)
                  for t in (t_arc.min(), t_arc.max()))
    assert t_arc.min() < t_arc.max()
    assert st.summary["curve1_radius_min_m"] == pytest.approx(by_hand, rel=1e-12)
    assert st.summary["curve1_radius_min_m"] >= convex_radius_min_m(
        t_arc.max(), belt.stiffness_n, adm, belt.width_m, 3, 35.0)


def test_curve_too_long_for_its_sections_is_refused():
    """R = 2 000 m between 0 and 10 % grades: arc 200 m, 100 m from each side; a 60 m
    section cannot hold its half."""
    with pytest.raises(ValueError, match=r"profile.0\.curve_radius_m"):
        parse_conveyor(hand_conveyor_dict(profile=[
            {"length_m": 60, "lift_m": 0, "curve_radius_m": 2000},
            {"length_m": 500, "lift_m": 50}]))
    with pytest.raises(ValueError, match=r"profile.1\.curve_radius_m.*last section"):
        parse_conveyor(hand_conveyor_dict(profile=[
            {"length_m": 500, "lift_m": 0}, {"length_m": 500, "lift_m": 50,
                                             "curve_radius_m": 300}]))
    with pytest.raises(ValueError, match="same grade"):
        parse_conveyor(hand_conveyor_dict(profile=[
            {"length_m": 500, "lift_m": 0, "curve_radius_m": 300},
            {"length_m": 500, "lift_m": 0}]))


def test_a_curve_too_long_for_its_sections_names_the_largest_radius_that_fits():
    """The error said only 'a smaller radius or longer sections'. Between 0 and 10 % (delta =
    asin(0.1) = 0.100167 rad) a 60 m section holds a half arc of 60 m: R at most
    2 x 60 / 0.100167 = 1197.99 m, named rounded down (1197 m), and 1197 m is taken. Two
    curves in a 200 m section: the first's half arc, 2000 x 0.100167 / 2 = 100.17 m, leaves
    99.83 m to the second, at most 2 x 99.83 / 0.100167 = 1993.3 m."""
    def profile(length_m, radius_m):
        return [{"length_m": length_m, "lift_m": 0, "curve_radius_m": radius_m},
                {"length_m": 500, "lift_m": 50}]
    delta = math.asin(0.1)
    assert 2 * 60 / delta == pytest.approx(1197.99, abs=0.01)
    with pytest.raises(ValueError, match=r"profile.0\.curve_radius_m: .* a radius of at most "
                       r"1197 m \(the grades turn by 5\.74 deg: R \|delta\| / 2 within the "
                       r"60\.0 m left to the curve in profile\.0\)"):
        parse_conveyor(hand_conveyor_dict(profile=profile(60, 2000)))
    parse_conveyor(hand_conveyor_dict(profile=profile(60, 1197)))
    # 1993 m by length; 1991 m keeps the section's lift (its straight rest takes its half
    # of the arcs' difference from the grades: test_the_largest_radius_offered_...)
    with pytest.raises(ValueError, match=r"profile.1\.curve_radius_m: .* at most 1991 m .*"
                       r"99\.8 m left to the curve in profile\.1"):
        parse_conveyor(hand_conveyor_dict(profile=[
            {"length_m": 500, "lift_m": 0, "curve_radius_m": 2000},
            {"length_m": 200, "lift_m": 20, "curve_radius_m": 3000},
            {"length_m": 500, "lift_m": 0}]))
    assert 2 * (200 - 1000 * delta) / delta == pytest.approx(1993.3, abs=0.1)


def test_a_radius_whose_arc_is_under_a_pitch_is_not_offered():
    """Between 0 and 4 % (delta = asin(0.04) = 0.040011 rad) a 0.5 m section holds a half arc
    of 0.5 m: R at most 2 x 0.5 / 0.040011 = 24.99 m, rounded down 24 m, an arc of
    24 x 0.040011 = 0.96 m, under the 1.25 m carry pitch: no curve but a grade change on one
    idler set, so that radius is not the fix; longer sections or no curve_radius_m are."""
    delta = math.asin(0.04)
    assert math.floor(2 * 0.5 / delta) * delta == pytest.approx(0.960, abs=0.001)
    with pytest.raises(ValueError, match=r"profile.0\.curve_radius_m: .* no curve fits there: "
                       r"the largest radius that does, 24 m .* makes an arc of 0\.96 m, "
                       r"shorter than an idler pitch \(1\.25 m\)") as err:
        parse_conveyor(hand_conveyor_dict(profile=[
            {"length_m": 500, "lift_m": 0, "curve_radius_m": 400},
            {"length_m": 0.5, "lift_m": 0.02}, {"length_m": 500, "lift_m": 0}]))
    assert "a radius of at most" not in str(err.value)
    # the fix named is taken: no curve_radius_m there
    parse_conveyor(hand_conveyor_dict(profile=[
        {"length_m": 500, "lift_m": 0}, {"length_m": 0.5, "lift_m": 0.02},
        {"length_m": 500, "lift_m": 0}]))


def test_no_curve_no_change():
    """Without curve_radius_m the loop has no curves and the summary no curve fields."""
    conv = parse_conveyor(hand_conveyor_dict())
    st = solve_steady(conv, model="din")
    assert st.loop.curves == ()
    assert not any(k.startswith("curve") for k in st.summary)


def test_curve_fields_are_defined_up_to_max_curves():
    from beltstudy.engine import results as R

    R.check_summary({f"curve{R.MAX_CURVES}_liftoff": True, "curve1_radius_min_m": 1.0,
                     "liftoff_max_kn_over": -1.0})
    with pytest.raises(KeyError, match=f"curve{R.MAX_CURVES + 1}_liftoff"):
        R.check_summary({f"curve{R.MAX_CURVES + 1}_liftoff": True})
    with pytest.raises(KeyError, match="curve1_new_m"):
        R.check_summary({"curve1_new_m": 1.0})


def test_a_radius_below_a_metre_is_refused():
    """A 1e-9 m 'curve' is a kink, not a curve on idlers: its 1 deg arc elements (1.7e-11 m)
    made the transient refuse the run for too much work, naming the step and the elements
    instead of the radius. At least 1 m; 1 m itself passes the field's bound, and between 0
    and 10 % its arc (0.1 m) is then shorter than an idler pitch: built as the tightest bend
    the idler sets give, a curve of S / |delta| = 1.25 / asin(0.1) = 12.48 m (below)."""
    for bad in (1e-9, 0.5):
        with pytest.raises(ValueError, match=r"profile\.0\.curve_radius_m"):
            curved(radius_m=bad)
    conv = curved(radius_m=1.0)
    assert conv.profile[0].curve_radius_m == 1.0
    (curve,) = build_loop(conv).curves
    assert curve.radius_m == pytest.approx(1.25 / math.asin(0.1), rel=1e-6)


def _short_curve_note(i, radius, turn_deg, grades, arc, fix):
    return (f"note: profile.{i}.curve_radius_m {radius} m: the grades turn by {turn_deg} deg "
            f"({grades}), so its arc is {arc} m, shorter than the idler pitch 1.25 m: at most "
            "one idler set stands on it and the belt bends there as at a kink, not round R, so "
            "it is judged as a grade change without a curve (the circle through its survey "
            f"points); {fix}")


def test_a_curve_of_negligible_turn_is_judged_as_a_grade_change_without_it():
    """Two grades whose lifts differ by 1e-6 m over 500 m (delta = asin(2e-9) = 2e-9 rad =
    1.15e-7 deg) joined by R 100 m: an arc of R delta = 2e-7 m, far shorter than the idler
    pitch (1.25 m, carry), so the belt does not bend round R there. It was judged as a curve
    of 100 m: statics said the empty belt lifts off it (the tension there, about 33 kN, above
    R m'_G g = 100 x 20 x 9.81 = 19.62 kN) and asked for a larger radius, and simulate refused
    it for too much work (a step set by 1e-7 m elements), telling the user to move the
    curve's end; then it was refused at input. It is accepted and judged as the grade change
    without curve_radius_m: no curve, no verdict taken with R, the same tensions, and a note
    naming the field, the turn, the arc, the pitch and that no radius up to 1e6 m spans a
    pitch (1.25 / 2e-9 = 6.25e8 m). The conveyor keeps the radius it was given."""
    delta = math.asin(1e-6 / 500)
    assert 100 * delta == pytest.approx(2e-7, rel=1e-9)
    assert math.degrees(delta) == pytest.approx(1.146e-7, rel=1e-3)
    assert 1.25 / delta == pytest.approx(6.25e8, rel=1e-9)
    prof = [{"length_m": 500, "lift_m": 0, "curve_radius_m": 100},
            {"length_m": 500, "lift_m": 1e-6}]
    conv = parse_conveyor(hand_conveyor_dict(profile=prof))
    assert conv.profile[0].curve_radius_m == 100.0
    assert conv.model_dump()["profile"][0]["curve_radius_m"] == 100.0
    st = solve_steady(conv, model="din", n_elements=200)
    assert st.loop.curves == ()
    assert not [k for k in st.summary if k.startswith("curve")]
    assert not [w for w in st.warnings if "curve" in w or "lift" in w]
    # R would have judged lift-off here: the carry tension at 500 m is above R m'_G g
    nc = st.loop.nc
    at = np.flatnonzero(np.isclose(st.loop.s_m[:nc] + st.loop.dx_m[:nc], 500.0))[0]
    assert st.tension_n[at] > 100 * 20 * G
    note = _short_curve_note(
        0, 100, "1.15e-07", "profile.0 lifts 0 m over 500 m, profile.1 1e-06 m over 500 m",
        "2e-07", "the turn is too small for any curve: no radius up to 1000000 m spans a "
        "pitch (S / |delta| = 6.25e+08 m; if the grades should differ, check lift_m)")
    del prof[0]["curve_radius_m"]
    plain = solve_steady(parse_conveyor(hand_conveyor_dict(profile=prof)), model="din",
                         n_elements=200)
    assert np.array_equal(st.tension_n, plain.tension_n)
    assert st.message == "; ".join(m for m in (plain.message, note) if m)

    # the transient of a small one runs on the same loop (beltstudy simulate: run_one)
    from beltstudy.engine.conveyor import Scenario
    from beltstudy.engine.run import run_one
    from tests.conftest import WARM_UP_SCENARIO

    small = parse_conveyor(hand_conveyor_dict(profile=[
        {"length_m": 50, "lift_m": 0, "curve_radius_m": 100},
        {"length_m": 50, "lift_m": 1e-6}]))
    r = run_one(small, Scenario(**WARM_UP_SCENARIO), model="din")
    assert r.transient is not None
    msg = r.summary["message"]
    assert "note: profile.0.curve_radius_m 100 m: the grades turn by 1.15e-06 deg" in msg
    assert "move" not in msg and "automatic step" not in msg


def _judged_note(i, radius, turn_deg, grades, arc, judged, r_span):
    return (f"note: profile.{i}.curve_radius_m {radius} m: the grades turn by {turn_deg} deg "
            f"({grades}), so its arc is {arc} m, shorter than the idler pitch 1.25 m: at most "
            "one idler set stands on it and the belt bends there as at a kink, not round R, so "
            f"it is judged as a curve of S / |delta| = {judged} m, whose arc spans one pitch "
            "(the turn taken on one idler set: its resultant T |delta| against the belt's "
            "weight over a pitch, as that radius judges it); a radius of at least "
            f"{r_span} m is a curve of its own")


def test_a_curve_shorter_than_an_idler_pitch_is_judged_as_the_bend_one_set_makes():
    """Between 0 and 10 % (delta = asin(0.1) = 0.100167 rad = 5.74 deg) with the hand
    conveyor's pitches 1.25 m (carry) and 2.5 m (return): an arc spans the smaller pitch from
    R = 1.25 / 0.100167 = 12.48 m. R 12 m (arc 1.202 m) holds at most one carry idler set, so
    the belt turns there as at a kink on that set, not round 12 m: judged as the tightest
    bend the sets give, a curve of S / |delta| = 12.48 m (its arc one pitch), noted with 13 m
    as the radius that is a curve of its own; 13 m (arc 1.302 m) is a curve at 13 m. Between
    0 and 2 % (delta = 0.0200013 rad) R 50 m is an arc of 1.0 m, judged at 1.25 / 0.0200013 =
    62.5 m. Where a curve of S / |delta| does not fit the sections (a 0.6 m section at 10 %
    holds half an arc of 0.6 m, R 12 m, but not 12.48 x 0.100167 / 2 = 0.625 m) it is judged
    as the grade change without a curve and the note says the turn is too small for any
    curve there."""
    assert 1.25 / math.asin(0.1) == pytest.approx(12.479, abs=1e-3)
    assert 1.25 / math.asin(0.02) == pytest.approx(62.496, abs=1e-3)
    for prof, note, judged in (
            ([{"length_m": 500, "lift_m": 0, "curve_radius_m": 12},
              {"length_m": 500, "lift_m": 50}],
             _judged_note(0, 12, "5.74", "profile.0 lifts 0 m over 500 m, profile.1 50 m "
                          "over 500 m", "1.2", "12.48", 13), 1.25 / math.asin(0.1)),
            ([{"length_m": 500, "lift_m": 0, "curve_radius_m": 50},
              {"length_m": 500, "lift_m": 10}],
             _judged_note(0, 50, "1.15", "profile.0 lifts 0 m over 500 m, profile.1 10 m "
                          "over 500 m", "1", "62.5", 63), 1.25 / math.asin(0.02)),
            ([{"length_m": 500, "lift_m": 0, "curve_radius_m": 12},
              {"length_m": 0.6, "lift_m": 0.06}, {"length_m": 499.4, "lift_m": 49.94}],
             _short_curve_note(0, 12, "5.74", "profile.0 lifts 0 m over 500 m, profile.1 "
                               "0.06 m over 0.6 m", "1.2", "the turn is too small for any "
                               "curve on these sections: one whose arc spans a pitch, R >= 13 "
                               "m (S / |delta|), does not fit them"), None)):
        st = solve_steady(parse_conveyor(hand_conveyor_dict(profile=prof)), model="din",
                          n_elements=200)
        if judged is None:
            assert st.loop.curves == ()
        else:
            (curve,) = st.loop.curves
            assert curve.radius_m == pytest.approx(judged, rel=1e-6)
        assert st.message.endswith(note)
    (curve,) = build_loop(curved(radius_m=13.0)).curves
    assert curve.radius_m == 13.0


def test_a_tighter_concave_radius_is_never_judged_milder():
    """A concave turn from -2 % to +10 % given R 10 m: an arc of 10 x 0.1202 = 1.2 m, under
    the 1.25 m pitch. The belt runs straight to one idler set and turns by delta there, so
    the set takes T delta upwards against the empty belt's weight over a pitch, m'_G g S: it
    lifts where T delta > m'_G g S cos a, the balance of a curve of S / delta = 10.4 m. It had
    been judged as the circle through its survey points (some 4 km here) and said to stay on
    its idlers, where R 11 m (a curve) said it lifts. Every radius from 4 to 12 m is judged
    no milder than the next larger one, and the lift-off tension the run gives at R 10 m is
    the kink's balance by hand."""
    def conv_of(r):
        return parse_conveyor(hand_conveyor_dict(profile=[
            {"length_m": 500, "lift_m": -10, "curve_radius_m": r},
            {"length_m": 500, "lift_m": 50}]))
    delta = math.asin(0.1) - math.asin(-0.02)
    assert 10 * delta < 1.25 < 11 * delta
    lift_off = []
    for r in (4, 6, 8, 10, 11, 12):
        st = solve_steady(conv_of(r), model="din", n_elements=200)
        lift_off.append(st.summary["curve1_liftoff_tension_kn"])
    # a tighter radius lifts the belt at a tension no higher (no milder verdict)
    assert all(a <= b + 1e-9 for a, b in zip(lift_off, lift_off[1:], strict=False))
    st = solve_steady(conv_of(10), model="din", n_elements=200)
    # the kink's balance T delta = m'_G g S cos(a), a the steeper grade (asin 0.1), m'_G the
    # hand conveyor's 20 kg/m of empty belt and idlers (R m'_G g = 100 x 20 x 9.81 above)
    radius = 1.25 / delta
    assert st.loop.curves[0].radius_m == pytest.approx(radius, rel=1e-6)
    assert st.summary["curve1_liftoff_tension_kn"] == pytest.approx(
        20 * G * 1.25 / delta * math.cos(math.asin(0.1)) / 1e3, rel=1e-6)


def test_a_point_near_an_arc_is_told_a_place_off_the_arc():
    """R 1 000 m from 0 to 6 % (asin 0.06 = 0.0600360 rad): the arc is 60.036 m, from
    969.982 to 1030.018 m. A booster at 969.999 m lies on it; the message's 'before' and
    'after' must be off the arc (rounded outwards), not 970.0 and 1030.0, which lie on it."""
    d = hand_conveyor_dict(profile=[{"length_m": 1000, "lift_m": 0, "curve_radius_m": 1000},
                                    {"length_m": 1000, "lift_m": 60}])
    d["drives"] = [{**d["drives"][0], "share": 0.5},
                   {**d["drives"][0], "position": "carry", "at_m": 969.999, "share": 0.5}]
    with pytest.raises(ValueError, match=r"drives\.1\.at_m: 969\.999 m lies on vertical curve "
                                         r"1 .*before 969\.9 or after 1030\.1 m"):
        parse_conveyor(d)
    d["drives"][1]["at_m"] = 969.9  # the place the message names is accepted
    parse_conveyor(d)


def test_convex_curve_idlers_carry_the_tension_pressing_round_the_curve():
    """CEMA 7th ed. (idler selection, convex curves) / DIN 22101: on a convex curve each
    carry set carries g (m'_G + m'_L) S + T S / R. Hand conveyor rising 10 % for 500 m, then
    flat: a crest. Weight 9.81 x (20 + 50) x 1.25 = 858.4 N per set, inside the CEMA B rating
    of 1824 N on the straight run; at R 40 m the tension adds T x 1.25 / 40 (about 2.4 kN at
    the crest's ~76 kN), above the rating: a warning naming the curve, the load by hand, the
    pitch rating / load x S and the radius R T S / (rating - weight) that meet it."""
    def crest(radius_m):
        d = hand_conveyor_dict(profile=[
            {"length_m": 500, "lift_m": 50, "curve_radius_m": radius_m},
            {"length_m": 500, "lift_m": 0}])
        d["idlers"]["carry"]["cema_class"] = "B"
        return solve_steady(parse_conveyor(d), model="din", n_elements=200)

    st = crest(40.0)
    s = st.summary
    weight = 9.81 * (20 + 50) * 1.25
    assert s["idler_load_carry_n"] == pytest.approx(weight, rel=1e-9)  # the straight run's
    t = s["curve1_tension_kn"] * 1e3
    assert 50e3 < t < 100e3
    f_set = weight + t * 1.25 / 40.0
    assert f_set > 1824.0 > weight
    assert (f"curve 1 (convex, R 40 m at 500 m): each carry idler set carries {f_set:.0f} N "
            f"({weight:.0f} N of belt and design load over 1.25 m and "
            f"{t * 1.25 / 40.0:.0f} N of the tension") in st.message
    assert "above the CEMA B rating 1824 N" in st.message
    # the pitch that meets the rating at this tension, rounded down to the cm printed (to
    # the nearest it named 0.71 m for 1.25 x 1824 / 3219 = 0.7083 m: 1828 N at 0.71 m)
    pitch = math.floor(100 * 1.25 * 1824.0 / f_set) / 100
    assert pitch * f_set / 1.25 <= 1824.0 < (pitch + 0.01) * f_set / 1.25
    assert (f"a closer pitch of the sets on the curve (at most {pitch:.2f} m at this "
            "tension; idlers.carry.spacing_m is the whole carry's pitch") in st.message
    assert f"a radius of at least {math.ceil(40.0 * (t * 1.25 / 40.0) / (1824.0 - weight))} m" \
        in st.message
    assert st.status == "warning"
    # ISO 281 L10 of the middle roll (0.67 of the set's load on two 6203 bearings, C 9950 N,
    # 0.133 m rolls at 4 m/s): (C / P)^3 10^6 / (60 n), n = 60 v / (pi D)
    p = 0.67 * f_set / 2
    l10 = (9950.0 / p) ** 3 * 1e6 / (60 * 60 * 4.0 / (math.pi * 0.133))
    assert l10 < 30000  # CEMA's basis: the life is short too
    assert (f"; and its middle roll's bearing life L10 {l10:.0f} h (ISO 281, {2 * p:.0f} N on "
            "two bearings) is below the CEMA B basis 30000 h") in st.message
    # a radius that keeps the set within its rating: no idler warning at the curve
    wide = crest(200.0)
    assert wide.summary["curve1_tension_kn"] * 1e3 * 1.25 / 200.0 + weight < 1824.0
    assert "each carry idler set carries" not in wide.message


def test_a_valley_on_a_regenerating_decline_is_judged_at_its_tighter_return():
    """A decline falling 10 % for 500 m into a valley of R 100 m, then flat: the drive at the
    head holds the loaded belt back, so the return leaving the head is the tight side and,
    at the valley, tighter than the carry. CEMA 7th ed. ch. 9 / DIN 22101: the empty belt
    lifts where T > R m'_G g cos a (100 x 20 x 9.81 x cos a ~ 19.6 kN). The verdict, the
    tension printed beside it and the radius it needs all read the strand that lifts:
    ``curve1_tension_kn`` is the highest tension on the arc of either strand, and
    ``curve1_radius_min_m`` = that tension / (m'_G g cos a)."""
    d = hand_conveyor_dict(profile=[
        {"length_m": 500, "lift_m": -50, "curve_radius_m": 100.0},
        {"length_m": 500, "lift_m": 0}])
    st = solve_steady(parse_conveyor(d), model="din", n_elements=200)
    s = st.summary
    (c,) = st.loop.curves
    assert c.kind == "concave" and s["te_kn"] < 0.0  # regenerating
    t_carry, t_ret = st.tension_n[c.carry].max(), st.tension_n[c.ret].max()
    assert t_ret > t_carry  # the return is the tighter strand at the valley
    assert s["curve1_tension_kn"] == pytest.approx(t_ret / 1e3, rel=1e-12)
    lift = s["curve1_liftoff_tension_kn"]
    assert lift * 1e3 == pytest.approx(100 * 20 * 9.81 * math.cos(math.asin(0.1)), rel=2e-3)
    assert s["curve1_liftoff"] is (s["curve1_tension_kn"] > lift)
    # the return runs up out of the valley towards the tail, its tension rising: its highest
    # on the arc is at the arc's tail-side end, on the 10 % grade, the steepest point
    T_ret_end = st.tension_n[c.ret[0]]
    assert T_ret_end == pytest.approx(st.tension_n[c.ret].max(), rel=1e-12)
    by_hand = T_ret_end / (20 * 9.81 * math.cos(math.asin(0.1)))
    assert s["curve1_radius_min_m"] == pytest.approx(by_hand, rel=1e-12)
    # the tension printed and the radius agree: T / (m'_G g cos a) at the arc's slopes
    assert s["curve1_radius_min_m"] == pytest.approx(
        s["curve1_tension_kn"] * 1e3 / (20 * 9.81 * math.cos(math.asin(0.1))), rel=6e-3)
    # the carry's own tension stays the convex curves' (edge strain, idler load), its
    # highest on the arc, where the belt enters it included
    t_carry = st.tension_n[np.r_[c.carry[0] - 1, c.carry]].max()
    assert s["curve1_idler_load_extra_n"] == pytest.approx(t_carry * 1.25 / 100.0, rel=1e-12)


# ------------------------------------------------- grade changes without a vertical curve

def _as_survey_points(conv, step_m=4.0):
    """The same route with every vertical curve replaced by survey points: the straight
    rests, and the arc as chords of about ``step_m`` at the arc's grade in their middle."""
    prof = conv.profile
    ang = [math.asin(p.lift_m / p.length_m) for p in prof]
    rest = [p.length_m for p in prof]
    arcs = {}
    for i, p in enumerate(prof[:-1]):
        if p.curve_radius_m is not None:
            arc = p.curve_radius_m * abs(ang[i + 1] - ang[i])
            rest[i] -= arc / 2
            rest[i + 1] -= arc / 2
            arcs[i] = arc
    out = []
    for i in range(len(prof)):
        out.append({"length_m": rest[i], "lift_m": rest[i] * math.sin(ang[i])})
        if i in arcs:
            n = max(2, int(arcs[i] / step_m))
            for k in range(n):
                a = ang[i] + (ang[i + 1] - ang[i]) * (k + 0.5) / n
                out.append({"length_m": arcs[i] / n, "lift_m": arcs[i] / n * math.sin(a)})
    return out


def test_survey_radius_is_the_circle_through_three_points():
    """Points spaced l = 2 R sin(delta / 2) on a circle of radius R give R back; the circle
    through A, B, C with AB = l1, BC = l2 and the grade turning by delta at B has
    R = |AC| / (2 sin delta), |AC|^2 = l1^2 + l2^2 + 2 l1 l2 cos(delta)."""
    from beltstudy.engine.curves import survey_radius_m

    d = math.radians(0.5)
    assert survey_radius_m(2 * 400 * math.sin(d / 2), 2 * 400 * math.sin(d / 2), d) \
        == pytest.approx(400.0, rel=1e-12)
    # 10 m and 10 m, grades 2 % then 8 %: delta = asin(0.08) - asin(0.02) = 0.060064 rad
    d = math.asin(0.08) - math.asin(0.02)
    ac = math.sqrt(2 * 100 * (1 + math.cos(d)))
    assert survey_radius_m(10, 10, -d) == pytest.approx(ac / (2 * math.sin(d)), rel=1e-12)
    assert survey_radius_m(10, 10, d) == pytest.approx(166.5, abs=0.1)
    assert survey_radius_m(10, 10, 0.0) == math.inf


def test_a_valley_given_as_survey_points_gets_the_curves_verdict():
    """The route written two ways: a concave curve of R 230 m (curve_radius_m) and the same
    valley as survey points every ~4 m on that radius. The curve's start-up lift-off (running
    39 kN < lift-off 44.9 kN < start-up 48.1 kN, radius 247 m named, the case above) was
    silent for the survey points (no curve, no check); now the survey circle (230 m) is
    judged: the same verdict, the same lift-off tension (within the arc's cos a) and radius
    (2 %). At R 400 m neither lifts and neither warns."""
    params = {"f_carry": 0.02, "f_return": 0.02, "c": 1.0}
    for radius, lifts in ((230.0, True), (400.0, False)):
        conv = curved(radius)
        survey = parse_conveyor(hand_conveyor_dict(profile=_as_survey_points(conv)))
        st = solve_steady(conv, model="din", params=params, n_elements=200)
        sv = solve_steady(survey, model="din", params=params, n_elements=200)
        assert st.summary["curve1_liftoff_start"] is lifts
        assert sv.te_n == pytest.approx(st.te_n, rel=2e-3)
        assert ("grade change without a vertical curve" in sv.message) is lifts
        assert sv.status == st.status
        if lifts:
            words = sv.message
            assert "concave" in words and "at start-up the empty belt lifts off" in words
            assert f"radius {radius:.0f} m" in words
            lim = float(words.split("lift-off tension ")[1].split(" kN")[0])
            assert lim == pytest.approx(radius * 20 * G * math.cos(math.asin(0.1)) / 1e3,
                                        rel=5e-3)
            need = float(words.split("at least ")[1].split(" m")[0])
            assert need == pytest.approx(st.summary["curve1_radius_min_start_m"], rel=0.02)


def _loaded_incline_valley(profile) -> dict:
    """A 3 km loaded incline from a flat tail run (1200 t/h at 4 m/s, 1 m ST1600, gravity
    take-up at the tail, head drive), profile as given: the tension rises along the 8 %
    grade, so a valley's curve reaches higher tensions the larger its radius."""
    return {
        "name": "incline-valley", "speed_m_s": 4.0,
        "belt": {"type": "ST1600", "width_m": 1.0, "compound": "standard"},
        "material": {"capacity_t_h": 1200, "density_t_m3": 1.0, "loading_speed_m_s": 0.0},
        "profile": profile,
        "idlers": {"carry": {"spacing_m": 1.5, "roll_diameter_m": 0.152, "rolls": 3,
                             "trough_deg": 35, "cema_class": "D"},
                   "return": {"spacing_m": 3.0, "roll_diameter_m": 0.152, "rolls": 1,
                              "cema_class": "C"}},
        "drives": [{"position": "head", "wrap_deg": 210, "friction": 0.35, "share": 1.0,
                    "pulley_diameter_m": 1.0, "inertia_kg_m2": 800, "torque_limit": 1.5}],
        "takeup": {"type": "gravity", "position": "tail", "mass_kg": "auto", "travel_m": 20},
        "holdback": True,
        "accessories": {"head_kn": 1.0, "tail_kn": 0.5}}


def test_the_radius_a_survey_valley_is_told_holds_as_a_curve_and_as_survey_points():
    """A valley given as five survey chords on R 250 m, at the foot of an 8 % incline: the
    empty belt lifts there (DIN 22101 / CEMA: T > R m'_G g cos a). The radius it is told is
    judged over the arc that radius gives (about R x 0.08 long about the valley, reaching
    42 m of the loaded grade's rising tension at 538 m), not at the valley's own point only:
    told that way a 530 m curve still lifted at start-up (144.0 kN against 142.0 kN).
    Followed either way, as curve_radius_m or as survey points on it, nothing lifts, running
    or at start-up; the running radius it names keeps the running belt down. (The crest at
    1600 m is over its edge strain whatever its radius: the belt is under-rated here, and
    that warning is not this test's.)"""
    tail = [{"length_m": 400, "lift_m": 0, "curve_radius_m": 250.0},
            {"length_m": 1200, "lift_m": 96}, {"length_m": 1400, "lift_m": 14}]
    as_points = _as_survey_points(parse_conveyor(_loaded_incline_valley(tail)))
    st = solve_steady(parse_conveyor(_loaded_incline_valley(as_points)), model="din")
    (w,) = [x for x in st.warnings if "grade change" in x and "concave" in x]
    assert "the empty belt lifts off its carry idlers" in w
    need = float(w.split("needs a vertical curve of at least ")[1].split(" m")[0])
    need_run = float(w.split(" m at the running tensions")[0].rsplit("(", 1)[1])
    assert 250.0 < need_run < need
    for radius, start_holds in ((need, True), (need_run, False)):
        route = [{**tail[0], "curve_radius_m": radius}, *tail[1:]]
        curve = solve_steady(parse_conveyor(_loaded_incline_valley(route)), model="din")
        assert curve.summary["curve1_liftoff"] is False, radius  # running: held down
        assert curve.summary["curve1_liftoff_start"] is not start_holds, radius
        points = _as_survey_points(parse_conveyor(_loaded_incline_valley(route)))
        sv = solve_steady(parse_conveyor(_loaded_incline_valley(points)), model="din")
        told = [x for x in sv.warnings if "grade change" in x and "concave" in x]
        assert (told == []) is start_holds, (radius, told)
    # one metre less than the radius told lifts as a curve: the advice is the least radius
    route = [{**tail[0], "curve_radius_m": need - 1.0}, *tail[1:]]
    curve = solve_steady(parse_conveyor(_loaded_incline_valley(route)), model="din")
    assert curve.summary["curve1_liftoff_start"] is True


def test_a_sharp_grade_change_without_a_curve_by_hand():
    """Hand conveyor as 490 m flat, 10 m at 2 %, 10 m at 8 %, 490 m at 10 % (the same 1000 m
    and 50 m of lift): at 500 m the grade turns by 0.060064 rad between two 10 m runs, the
    circle through the survey points is 166.5 m and the empty belt lifts where
    T > R m'_G g cos a = 166.5 x 20 x 9.81 x cos(asin 0.08) = 32.57 kN; the running tension
    there is about 39 kN. The 490 m runs either side make the other two changes 12.5 km
    circles that hold. Split into collinear pieces the route reads alike."""
    prof = [{"length_m": 490, "lift_m": 0.0}, {"length_m": 10, "lift_m": 0.2},
            {"length_m": 10, "lift_m": 0.8}, {"length_m": 490, "lift_m": 49.0}]
    st = solve_steady(parse_conveyor(hand_conveyor_dict(profile=prof)), model="din",
                      n_elements=200)
    d = math.asin(0.08) - math.asin(0.02)
    r = math.sqrt(2 * 100 * (1 + math.cos(d))) / (2 * math.sin(d))
    lim = r * 20 * G * math.cos(math.asin(0.08))
    loop, T = st.loop, st.tension_n
    at = [j for j in range(loop.n) if loop.strand[j] == 0
          and abs(loop.x_m[j] + loop.dx_m[j] - 500.0) < 1e-6]
    t_run = float(T[at[0]])
    assert t_run > lim  # the hand case: ~39 kN against 32.57 kN
    (w,) = [x for x in st.warnings if "grade change" in x]
    assert "at 500 m (profile[1] to profile[2], concave" in w
    assert f"radius {r:.0f} m" in w and f"lift-off tension {lim / 1e3:.1f} kN" in w
    assert f"steady tension {t_run / 1e3:.1f} kN" in w
    # the same route with its straights cut into survey points: one verdict
    pieces = ([{"length_m": 49, "lift_m": 0.0}] * 10 + prof[1:3]
              + [{"length_m": 49, "lift_m": 4.9}] * 10)
    sv = solve_steady(parse_conveyor(hand_conveyor_dict(profile=pieces)), model="din",
                      n_elements=200)
    (w2,) = [x for x in sv.warnings if "grade change" in x]
    assert f"radius {r:.0f} m" in w2 and f"lift-off tension {lim / 1e3:.1f} kN" in w2


def test_a_convex_warning_names_the_strain_that_sets_its_radius_rounded_up():
    """The hand conveyor's crest (flat, then falling 20 m; R 40 m; EB 60 MN, B 1 m on three
    35 deg rolls, middle roll 0.38 m): wing 0.31 m, h = 0.31 sin 35 = 0.177808 m, z_mean =
    2 x 0.31 x h / 2 / 1 m = 0.055120 m. At the arc's ~29.69 kN the centre sets it,
    z_mean EB / T = 111.39 m: the warning said 'a radius of at least 111 m' (rounded to the
    nearest), less than the radius it needs, and named neither strain. It names the centre
    and 112 m. With S_min 15 (admissible 1000 kN / 15 = 66.67 kN) the edges set it,
    (h - z_mean) EB / (66.67 kN - T) = 0.122688 x 60e6 / (66 667 - 29 694) = 199.1 m."""
    h, z_mean = 0.31 * math.sin(math.radians(35.0)), 0.31 * 0.31 * math.sin(math.radians(35.0))
    st = solve_steady(curved(40.0, lift2_m=-20.0), model="din", n_elements=200)
    (c,) = st.loop.curves
    t_low = float(st.tension_n[c.carry].min())
    r_centre = z_mean * 60e6 / t_low
    assert r_centre == pytest.approx(111.39, abs=0.01)
    (w,) = [m for m in st.message.split("; ") if "convex" in m]
    assert "its centre line" in w and "goes slack" in w and "edges" not in w
    assert f"a radius of at least {math.ceil(r_centre)} m" in w
    assert "more tension there (a heavier take-up)" in w
    st = solve_steady(curved(40.0, lift2_m=-20.0, safety_factor_min=15.0), model="din",
                      n_elements=200)
    t_high = float(st.tension_n[c.carry].max())
    r_edge = (h - z_mean) * 60e6 / (1e6 / 15.0 - t_high)
    assert r_edge == pytest.approx(199.1, abs=0.1)
    (w,) = [m for m in st.message.split("; ") if "convex" in m]
    assert "its edges" in w and "admissible strain, that of rating / S_min = 66.7 kN" in w
    assert f"a radius of at least {math.ceil(r_edge)} m" in w and "a stronger belt" in w


def test_the_start_time_for_a_start_lift_off_keeps_every_element_of_the_curve_down():
    """transient_liftoff's rigid-body start time, t x (T_peak - T_run) / (T_lift - T_run), was
    taken at the element lifted most only. On the hand valley (R 250 m, 200 elements) the
    curve's first carry element has 7.93 kN of room below its lift-off tension in running at
    its end and its last 6.53 kN; a start (60 s) that passes the first by 5.0 kN and the last
    by 4.5 kN was told 60 x (7.93 + 5.0) / 7.93 = 98 s, which leaves the last element lifting
    (it needs 60 x (6.53 + 4.5) / 6.53 = 101 s). The time named is the larger, with the room
    it comes from."""
    st = solve_steady(curved(250.0, 50.0), model="din", n_elements=200)
    loop, run = st.loop, st.tension_n
    (c,) = loop.curves
    el, lim = liftoff_limits_n(loop, c)
    first, last = int(c.carry[0]), int(c.carry[-1])
    lim_of = dict(zip(el.tolist(), lim, strict=True))
    room = {e: lim_of[e] - run[e] for e in (first, last)}
    assert room[first] == pytest.approx(7934, abs=1) and room[last] == pytest.approx(6532, abs=1)
    hi = run.copy()
    hi[first], hi[last] = lim_of[first] + 5000.0, lim_of[last] + 4500.0
    seg = (0.0, 100.0, hi, np.full_like(hi, 30.0), run.copy(), np.full_like(hi, 30.0))
    out, warnings = transient_liftoff(loop, [seg], 60.0, 80.0, 60.0, run)
    assert out["liftoff_max_kn_over"] == pytest.approx(5.0, abs=1e-9)
    need = 60.0 * (room[last] + 4500.0) / room[last]
    assert need == pytest.approx(101.3, abs=0.1)
    (w,) = [m for m in warnings if m.startswith("lift-off in the start")]
    assert (f"a start of about {need:.0f} s (start.time_s; rigid-body estimate: running leaves "
            f"{room[last] / 1e3:.4g} kN below the lift-off tension {lim_of[last] / 1e3:.4g} kN "
            f"there, {100.0 * room[last] / lim_of[last]:.3g} %)") in w  # 4 figures, ' %'
    assert "%)" not in w.replace(" %)", "")


def test_the_largest_radius_offered_builds_and_keeps_the_lift():
    """Between 0 and 10 % in two 500 m sections the largest radius by length is 9 983 m (2 x
    500 / asin(0.1) = 9 983.3), which leaves a straight rest of 0.014 m on the flat section;
    its half of the arcs' difference from the grades (-0.021 m of lift) gave that rest a sine
    of -1.46 and the loop build a math domain error, and capping the rest's slope lost the
    lift (a 0 to 30 % curve rose 90.69 m for 90). A radius is taken, and offered, only where
    each rest keeps its section's lift within the turn the loop allows it: 9 979 m here. The
    loop then keeps every element's slope within the grades and the route's lift exact
    (g m'_L H by hand: 9.81 x 50 x 50 = 24 525 N)."""
    with pytest.raises(ValueError, match=r"need 500\.036 m of profile\.0 .* a radius of at "
                       r"most 9979 m"):
        parse_conveyor(hand_conveyor_dict(profile=[
            {"length_m": 500, "lift_m": 0, "curve_radius_m": 9984},
            {"length_m": 500, "lift_m": 50}]))
    with pytest.raises(ValueError, match=r"profile\.0\.curve_radius_m: the curve's arcs leave "
                       r"0\.\d+ m of straight grade in profile\.0, too little to keep the "
                       r"section's lift .* a radius of at most 9979 m"):
        parse_conveyor(hand_conveyor_dict(profile=[
            {"length_m": 500, "lift_m": 0, "curve_radius_m": 9983},
            {"length_m": 500, "lift_m": 50}]))
    conv = parse_conveyor(hand_conveyor_dict(profile=[
        {"length_m": 500, "lift_m": 0, "curve_radius_m": 9979},
        {"length_m": 500, "lift_m": 50}]))
    st = solve_steady(conv, model="din")
    carry = st.loop.strand == 0
    # every slope within the grades and at most the curve's own turn (asin 0.1) beyond them
    turn = math.asin(0.1)
    assert np.all(st.loop.sin_a[carry] >= math.sin(-turn) - 1e-12)
    assert np.all(st.loop.sin_a[carry] <= math.sin(2 * turn) + 1e-12)
    lift = float(np.sum(st.loop.dx_m[carry] * st.loop.sin_a[carry]))
    assert lift == pytest.approx(50.0, abs=1e-6)
    assert st.summary["te_components_kn"]["lift"] * 1e3 == pytest.approx(9.81 * 50 * 50,
                                                                          rel=1e-9)


def test_a_steep_convex_curve_is_offered_a_radius_that_keeps_the_lift():
    """0 to 30 % over two 300 m sections, convex: by length alone the largest radius is 1 969
    m, whose arcs leave 0.03 m of straight; the arcs rise 0.70 m more than the grades they
    replace, so that route rose 90.69 m for 90. The radius offered keeps the lift: built at
    it, the carry rises 90 m."""
    prof = [{"length_m": 300, "lift_m": 90, "curve_radius_m": 5000},
            {"length_m": 300, "lift_m": 0}]
    with pytest.raises(ValueError, match=r"a radius of at most (\d+) m") as err:
        parse_conveyor(hand_conveyor_dict(profile=prof))
    r = int(re.search(r"a radius of at most (\d+) m", str(err.value)).group(1))
    assert r < 1969
    prof[0]["curve_radius_m"] = r
    st = solve_steady(parse_conveyor(hand_conveyor_dict(profile=prof)), model="din")
    carry = st.loop.strand == 0
    assert float(np.sum(st.loop.dx_m[carry] * st.loop.sin_a[carry])) == pytest.approx(
        90.0, abs=1e-6)


def test_more_vertical_curves_than_their_columns_are_refused_by_name():
    """Nine vertical curves (ten 100 m sections alternating 0 and 5 m of lift, R 300 m) had
    no curve9_* columns: the run failed after its solve with a KeyError. The file is refused
    at input, naming the sections and what to do."""
    prof = [{"length_m": 100, "lift_m": 5.0 * (i % 2), "curve_radius_m": 300}
            for i in range(9)] + [{"length_m": 100, "lift_m": 5.0}]
    with pytest.raises(ValueError, match=r"profile: 9 vertical curves \(curve_radius_m on "
                       r"profile\.0, .*profile\.8\); at most 8, .* give the radius only to "
                       r"the curves to be checked"):
        parse_conveyor(hand_conveyor_dict(profile=prof))
    prof[0].pop("curve_radius_m")
    parse_conveyor(hand_conveyor_dict(profile=prof))  # eight: taken


def test_a_convex_radius_set_by_its_centre_is_said_so_at_every_tension():
    """A convex crest whose radius is set by the centre line's slack at the arc's lowest
    tension, ``z_mean / (T / EB)``: on a 1 km ST1000 belt (EB 72 000 kN) at 25.7 kN that is
    0.0551 / (25.7 / 72 000) = 154.4 m, against the edges' 71.7 m. The words recomputed the
    centre's radius as ``z_mean EB / T``, an ulp below the same number at some tensions, and
    told such a curve its edges pass the admissible strain, and less tension (which slackens
    the centre further). At every tension where the centre sets the radius, the words say the
    centre and more tension."""
    from beltstudy.engine.capacity import middle_roll_length_m
    from beltstudy.engine.conveyor import parse_conveyor
    from beltstudy.engine.curves import _convex_words, _trough_heights, convex_radius_min_m

    conv = parse_conveyor({
        "name": "crest", "speed_m_s": 4.0, "belt": {"type": "ST1000", "width_m": 1.0},
        "material": {"capacity_t_h": 800, "density_t_m3": 1.0},
        "profile": [{"length_m": 200, "lift_m": 20, "curve_radius_m": 80},
                    {"length_m": 800, "lift_m": 0}],
        "idlers": {"carry": {"spacing_m": 1.25, "roll_diameter_m": 0.152, "rolls": 3,
                             "trough_deg": 35},
                   "return": {"spacing_m": 3.0, "roll_diameter_m": 0.152, "rolls": 1}},
        "drives": [{"position": "head", "wrap_deg": 240, "friction": 0.5, "share": 1.0}],
        "takeup": {"type": "gravity", "position": "tail", "mass_kg": 1500}})
    loop = build_loop(conv)
    belt, ic, (c,) = loop.belt, conv.idlers.carry, loop.curves
    sf = 6.7
    _h, z = _trough_heights(belt.width_m, ic.rolls, ic.trough_deg,
                            middle_roll_length_m(belt.width_m, ic.rolls))
    assert z == pytest.approx(0.31 * 0.31 * math.sin(math.radians(35)), rel=1e-2)
    said = 0
    for t_low in np.linspace(20e3, 30e3, 4001):
        t_high = t_low + 300.0
        r_min = max(convex_radius_min_m(t, belt.stiffness_n, belt.rating_n / sf, belt.width_m,
                                        ic.rolls, ic.trough_deg, ic.roll_length_m)
                    for t in (t_high, t_low))
        centre = z / (t_low / belt.stiffness_n)
        if centre < r_min * (1.0 - 1e-12):
            continue  # the edges set it
        words = _convex_words(1, c, belt, ic, sf, t_low, t_high, r_min)
        assert "centre line" in words and "more tension there" in words, (t_low, words)
        said += 1
    assert said > 1000


def test_a_lift_off_while_the_belt_is_at_rest_is_said_at_rest_without_a_start_or_stop():
    """A 6 km overland's empty belt lifted at its concave curve at t = 0.1 s, before its start
    command, 22.7 kN over (held at rest the tension there is the take-up's plus the belt's
    weight above it), and was told a start of about 266 s avoids it; followed, the same
    excess at t = 0.1 s asked 616 s. The same after the belt rested in its stop ('a softer
    stop'). A peak before the start command or after the rest began is lift-off at rest: its
    levers are the radius and the tension at rest, no start or stop time. On the hand valley
    (R 250 m): a peak 5 kN over at t = 1 s (the start command at 2 s) and one 3 kN over at
    t = 95 s (at rest from 90 s); the start (2 to 62 s) and the stop keep below."""
    st = solve_steady(curved(250.0, 50.0), model="din", n_elements=200)
    loop, run = st.loop, st.tension_n
    (c,) = loop.curves
    el, lim = liftoff_limits_n(loop, c)
    first = int(c.carry[0])
    lim_first = float(dict(zip(el.tolist(), lim, strict=True))[first])
    rest = run.copy()
    rest[first] = lim_first + 5000.0
    later = run.copy()
    later[first] = lim_first + 3000.0
    segs = [(0.0, 2.0, rest, np.full_like(run, 1.0), run.copy(), np.full_like(run, 1.0)),
            (2.0, 80.0, run.copy(), np.full_like(run, 30.0), run.copy(), np.full_like(run, 30.0)),
            (80.0, 120.0, later, np.full_like(run, 95.0), run.copy(), np.full_like(run, 95.0))]
    out, warnings = transient_liftoff(loop, segs, 62.0, 80.0, 60.0, run, t_start_cmd_s=2.0,
                                      t_rested_s=90.0)
    assert out["liftoff_max_kn_over"] == pytest.approx(5.0, abs=1e-9)
    (w,) = warnings
    assert w.startswith("lift-off at rest: the empty belt leaves its carry idlers at curve 1 "), w
    assert "at t = 1.0 s, 5.0 kN over its lift-off tension" in w
    assert "a curve radius of at least" in w and "less tension there at rest" in w
    assert "start.time_s" not in w and "softer stop" not in w
    # without the rest times the same peaks are the start's and the stop's, with their levers
    _, said = transient_liftoff(loop, segs, 62.0, 80.0, 60.0, run)
    assert [m.split(":")[0] for m in said] == ["lift-off in the start", "lift-off in the stop"]


def test_a_belt_that_lifts_held_at_rest_is_told_by_the_steady_check():
    """At rest no running resistance holds the tension at a concave curve down: the take-up's
    tension and the belt's weight above it. A 6 km overland's empty belt held 225.3 kN at rest
    at its 600 m curve against 202.6 kN of lift-off tension, and only the transient run said so
    (as lift-off in the start). The steady check now judges the at-rest tensions
    (:func:`~beltstudy.engine.statics.rest_tensions`): on the hand valley (R 250 m), at-rest
    tensions 4 kN over at the curve's first carry element are told, with the radius R max
    (T_rest / T_lift) and no start or stop; where running lifts too, its warning stands alone.
    """
    from beltstudy.engine.curves import steady_checks
    from beltstudy.engine.statics import rest_tensions, rest_walk

    st = solve_steady(curved(250.0, 50.0), model="din", n_elements=200)
    loop, run, conv = st.loop, st.tension_n, st.conveyor
    (c,) = loop.curves
    el, lim = liftoff_limits_n(loop, c)
    rest = run.copy()
    first = int(c.carry[0])
    lim_first = float(dict(zip(el.tolist(), lim, strict=True))[first])
    rest[first] = lim_first + 4000.0
    _, words = steady_checks(conv, loop, run, 6.7, None, rest)
    (w,) = [m for m in words if "held at rest" in m]
    r_need = math.ceil(250.0 * float(np.max(rest[el] / lim)))
    assert w.startswith("curve 1 (concave, R 250 m at 500 m): held at rest the empty belt "
                        "lifts off its carry idlers"), w
    assert f"above the lift-off tension {lim_first / 1e3:.1f} kN" in w
    assert f"a radius of at least {r_need} m" in w and "no start or stop time changes it" in w
    assert not [m for m in steady_checks(conv, loop, run, 6.7, None, run)[1]
                if "held at rest" in m]
    # the at-rest tensions: gravity alone element by element (the holding pulley takes the
    # net pull), at the take-up's mean tension as running (a gravity take-up)
    t_rest = rest_tensions(conv, loop, run)
    walk = rest_walk(loop, int(loop.drive_elements[0]), loop.gravity_n)
    assert np.allclose(np.diff(t_rest), np.diff(walk), rtol=0, atol=1e-6)
    k = loop.i_takeup
    assert t_rest[k - 1] + t_rest[k] == pytest.approx(run[k - 1] + run[k], rel=1e-12)


#: A 400 m belt whose tail curve (R 60 m) turns a flat 30 m into a 15 % climb: its longer arc
#: at the advised radius reaches further up the grade, and the tension there rises with it.
TIGHT_TAIL = {
    "name": "tight-tail", "speed_m_s": 2.5,
    "belt": {"type": "EP630/4", "width_m": 0.8, "mass_kg_m": 12.0},
    "material": {"capacity_t_h": 400, "density_t_m3": 1.5},
    "profile": [{"length_m": 30, "lift_m": 0, "curve_radius_m": 60},
                {"length_m": 370, "lift_m": 55.5}],
    "idlers": {"carry": {"spacing_m": 1.0, "roll_diameter_m": 0.108, "rolls": 3,
                         "trough_deg": 35, "rotating_mass_kg": 9.0, "seal_drag_n": 1.0,
                         "roll_length_m": 0.315},
               "return": {"spacing_m": 3.0, "roll_diameter_m": 0.108, "rolls": 1,
                          "rotating_mass_kg": 7.0, "seal_drag_n": 0.8}},
    "drives": [{"position": "head", "wrap_deg": 210, "friction": 0.35, "share": 1.0,
                "pulley_diameter_m": 0.63, "inertia_kg_m2": 60, "rated_power_kw": 110,
                "torque_limit": 1.5}],
    "takeup": {"type": "gravity", "position": "tail", "mass_kg": "auto"},
    "holdback": True}


def test_a_concave_radius_advised_holds_when_followed():
    """The concave radius (running and at start-up) is solved again at the advised radius
    until it holds there, as the convex one is: at R 60 m the run's own arc asks 156 m
    running and 167 m at start-up (hand: T / (m'_G g cos a), 18.1 kN and 19.3 kN over
    0.1164 kN/m), and at 167 m the belt lifted at start-up (176 m needed)."""
    res = solve_steady(parse_conveyor(TIGHT_TAIL), model="din", settle=True)
    words = next(w for w in res.warnings if w.startswith("curve 1 (concave"))
    running = int(re.search(r"a radius of at least (\d+) m", words).group(1))
    start = int(re.search(r"at start-up \([\d.]+ kN there\) at least (\d+) m", words).group(1))
    assert running > 156 and start > 167, words  # beyond the run's own-arc figures
    for radius, field in ((running, "curve1_liftoff"), (start, "curve1_liftoff_start")):
        d = {**TIGHT_TAIL, "profile": [{**TIGHT_TAIL["profile"][0], "curve_radius_m": radius},
                                       TIGHT_TAIL["profile"][1]]}
        followed = solve_steady(parse_conveyor(d), model="din")
        assert not followed.summary[field], (radius, field)


#: A 5 km route of six sections whose fourth curve (concave, R 300 m, a -2 % section into
#: +4 %) lifts the empty belt running, at start-up and, higher still, held at rest: no
#: running resistance holds the at-rest tension down there.
VALLEYS = {
    "name": "valleys", "speed_m_s": 4.5,
    "belt": {"type": "ST2000", "width_m": 1.2, "compound": "standard"},
    "material": {"capacity_t_h": 1500, "density_t_m3": 1.6},
    "profile": [{"length_m": 700, "lift_m": -21, "curve_radius_m": 300.0},
                {"length_m": 500, "lift_m": 0, "curve_radius_m": 250.0},
                {"length_m": 1000, "lift_m": 60, "curve_radius_m": 150.0},
                {"length_m": 800, "lift_m": -16, "curve_radius_m": 300.0},
                {"length_m": 1200, "lift_m": 48, "curve_radius_m": 100.0},
                {"length_m": 800, "lift_m": 0}],
    "idlers": {"carry": {"spacing_m": 1.5, "roll_diameter_m": 0.152, "rolls": 3,
                         "trough_deg": 35, "cema_class": "D", "rotating_mass_kg": 22.0},
               "return": {"spacing_m": 3.0, "roll_diameter_m": 0.152, "rolls": 1,
                          "cema_class": "C", "rotating_mass_kg": 12.0}},
    "drives": [{"position": "head", "wrap_deg": 210, "friction": 0.35, "share": 0.6,
                "pulley_diameter_m": 1.25, "inertia_kg_m2": 1500, "torque_limit": 1.5},
               {"position": "carry", "at_m": 2800.0, "wrap_deg": 210, "friction": 0.35,
                "share": 0.4, "pulley_diameter_m": 1.25, "inertia_kg_m2": 1000,
                "torque_limit": 1.5}],
    "takeup": {"type": "gravity", "position": "tail", "mass_kg": "auto", "travel_m": 20}}


def test_a_lifting_curve_s_warning_names_the_at_rest_radius_where_it_is_the_largest():
    """Where running lifts the belt its warning stands alone, and named the start-up radius
    beside its own but not the one at rest: on this route curve 4 was told 455 m for the
    start, and on 455 m the belt lifted held at rest (at-rest tension about 158 kN against
    153.6 kN of lift-off tension; by hand 128.7 kN of take-up per strand and 127 kg/m x g over
    the curve's 23 m above the tail, 157.3 kN), needing 469 m: two rounds. The at-rest figures are columns too (``curve{k}_liftoff_rest``,
    ``curve{k}_radius_min_rest_m``); the radius named is solved again at that radius, and
    followed, the belt stays down running, at start-up and at rest."""
    res = solve_steady(parse_conveyor(VALLEYS), model="din", settle=True)
    s = res.summary
    assert s["curve4_liftoff"] and s["curve4_liftoff_start"] and s["curve4_liftoff_rest"]
    assert s["curve4_radius_min_rest_m"] > s["curve4_radius_min_start_m"] > \
        s["curve4_radius_min_m"]
    words = next(w for w in res.warnings if w.startswith("curve 4 (concave"))
    rest = int(re.search(r"and held at rest \([\d.]+ kN there, an estimate\) at least (\d+) m",
                         words).group(1))
    assert rest >= math.ceil(s["curve4_radius_min_rest_m"]), words
    prof = [dict(p) for p in VALLEYS["profile"]]
    prof[3]["curve_radius_m"] = float(rest)
    followed = solve_steady(parse_conveyor({**VALLEYS, "profile": prof}), model="din").summary
    assert not (followed["curve4_liftoff"] or followed["curve4_liftoff_start"]
                or followed["curve4_liftoff_rest"])
    # a convex curve has no lift-off at rest
    assert s["curve3_liftoff_rest"] is False and s["curve3_radius_min_rest_m"] is None


def test_a_lift_off_while_slipping_drives_still_pull_the_belt_up_to_speed_is_in_the_start():
    """A 2 km route (800 m level into a 5 % climb on R 330 m, a booster at 1 000 m) on a 15 s
    start: both drive pulleys slip and pull the belt up to speed only at about 27 s. Its
    lift-off at t = 22.5 s, with the belt at 3.28 of 4 m/s, was said to be in steady running
    with the radius its only lever; the start lasts until the belt first reaches 99 % of
    design speed, and the start's lever (a start whose drives do not slip) is named."""
    from beltstudy.engine.run import run_one

    conv = {
        "name": "booster-valley", "speed_m_s": 4.0,
        "belt": {"type": "ST2000", "width_m": 1.2, "compound": "standard"},
        "material": {"capacity_t_h": 1500, "density_t_m3": 1.6},
        "profile": [{"length_m": 800, "lift_m": 0, "curve_radius_m": 330.0},
                    {"length_m": 1200, "lift_m": 60}],
        "idlers": VALLEYS["idlers"],
        "drives": [{"position": "head", "wrap_deg": 210, "friction": 0.35, "share": 0.6,
                    "pulley_diameter_m": 1.25, "inertia_kg_m2": 1500, "torque_limit": 1.5},
                   {"position": "carry", "at_m": 1000, "wrap_deg": 210, "friction": 0.35,
                    "share": 0.4, "pulley_diameter_m": 1.25, "inertia_kg_m2": 1000,
                    "torque_limit": 1.5}],
        "takeup": {"type": "gravity", "position": "tail", "mass_kg": "auto", "travel_m": 20}}
    s = run_one(parse_conveyor(conv), Scenario(start={"time_s": 15.0}), model="din",
                check=False, remedy=False).summary
    t_at_speed = 2.0 + s["start_time_s"]
    assert s["liftoff_max_kn_over"] > 0.0 and 2.0 + 15.0 < s["liftoff_time_s"] < t_at_speed
    msg = s["message"]
    assert "lift-off in steady running" not in msg, msg
    words = re.search(r"lift-off in the start: [^;]*; ([^;]*) avoids it", msg)
    assert words and "a start whose drives do not slip" in words.group(1), msg


def test_the_radius_over_its_own_arc_by_hand():
    """The fixed point behind the radius a lift-off warning tells: a tension rising along the
    route as ``T(x) = T0 + g (x - x_j)`` past the junction x_j, against a lift-off of ``R w``
    (w = m'_G g cos a): the arc of radius R reaches ``x_j + R delta / 2``, so R needs
    ``R = (T0 + g R delta / 2) / w``, by hand ``R = T0 / (w - g delta / 2)``. From the radius
    the junction's own point needs (T0 / w) it comes to within 0.01 %; on a flat tension it
    stays there."""
    from beltstudy.engine.curves import _radius_over_own_arc

    t0, g, w, delta, at = 140e3, 100.0, 268.0, 0.08, 400.0

    def need(lo_m, hi_m):
        return (t0 + g * (hi_m - at)) / w

    by_hand = t0 / (w - g * delta / 2)
    r = _radius_over_own_arc(need, t0 / w, delta, at)
    assert r == pytest.approx(by_hand, rel=2e-4) and r > t0 / w * 1.01
    assert _radius_over_own_arc(lambda lo, hi: t0 / w, t0 / w, delta, at) == t0 / w


def test_a_transient_lift_off_radius_is_judged_over_the_arc_it_gives():
    """A 3 km belt's valley (R 538 m at the foot of a loaded 8 % incline) lifts in a coast
    stop. The radius its own arc's peaks need (R max T / T_lift) lifted when followed; the
    radius told is judged over the arc it gives (``_liftoff_radius``), which reaches further
    up the grade, so it is larger, and followed it lifts less than the own-arc radius does
    (on the same mesh: the run at the new radius moves its own peaks a little, which the
    words' 'rerun to confirm' and the error bar's radius cover)."""
    import yaml

    from beltstudy.engine.run import run_one

    base = yaml.safe_load(yaml.safe_dump(_loaded_incline_valley([
        {"length_m": 400, "lift_m": 0, "curve_radius_m": 538.0},
        {"length_m": 1200, "lift_m": 96, "curve_radius_m": 400},
        {"length_m": 1400, "lift_m": 14}])))
    scen = Scenario(start={"time_s": 90.0}, run_s=20.0, stop={"mode": "coast"})

    def stop_over(radius_m):
        d = {**base, "profile": [{**base["profile"][0], "curve_radius_m": radius_m},
                                 *base["profile"][1:]]}
        run = run_one(parse_conveyor(d), scen, model="din", check=False)
        return run.summary

    s = stop_over(538.0)
    assert s["liftoff_over_stop_kn"] > 0.0
    (words,) = [w for w in s["message"].split("; ") if "a curve radius of at least " in w]
    told = float(words.split("a curve radius of at least ")[1].split(" m")[0])
    # the own-arc radius: R max T / T_lift over the arc's points in the stop (the peak at
    # the arc's steep end, where the lift-off tension is the curve's lowest)
    own = 538.0 * (s["liftoff_over_stop_kn"] + s["curve1_liftoff_tension_kn"]) / s[
        "curve1_liftoff_tension_kn"]
    assert told > math.ceil(own)
    assert stop_over(told)["liftoff_over_stop_kn"] < stop_over(
        float(math.ceil(own)))["liftoff_over_stop_kn"]
