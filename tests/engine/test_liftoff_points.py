"""Lift-off at a concave curve is judged at the points of its arc, each by its own tension and
its own slope (engine/curves.py, ``liftoff_limits_n``; docs/routes.md, vertical curves).

The belt leaves its idlers at a point where T > R m'_G g cos(a) (CEMA 7th ed. ch. 9, concave
curves; DIN 22101), T and a both at that point. The check took the tension at each arc
element's end against the slope at the element's middle (half an element's turn, up to
0.5 deg, flatter than the steep end of the arc), and never looked at the point where a strand
enters the arc: on the return of a valley at the foot of an incline that is the steep end.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from beltstudy.engine.conveyor import parse_conveyor
from beltstudy.engine.curves import transient_liftoff
from beltstudy.engine.statics import solve_steady
from tests.conftest import hand_conveyor_dict

G = 9.81
M_G, M_L, MR_C, MR_R = 20.0, 50.0, 10.0, 3.0  # the hand conveyor's masses per metre [kg/m]
F = 0.02  # DIN's default f on both strands
A2 = math.asin(100.0 / 400.0)  # the incline's grade: 400 m rising 100 m


def foot_of_incline(radius_m: float) -> dict:
    """The hand conveyor as 400 m flat, then 400 m rising 100 m (25 %), joined by a concave
    curve of ``radius_m``; a 4 000 kg take-up at the tail, no accessories."""
    return hand_conveyor_dict(
        profile=[{"length_m": 400, "lift_m": 0, "curve_radius_m": radius_m},
                 {"length_m": 400, "lift_m": 100}],
        takeup={"type": "gravity", "position": "tail", "mass_kg": 4000},
        accessories={"head_kn": 0.0, "tail_kn": 0.0})


def arc_end_tension_by_hand(radius_m: float) -> float:
    """Steady carry tension where the arc meets the incline [N], walked from the tail.

    The arc R a2 takes half its length from each section; it rises R (1 - cos a2), more than
    the two straight halves it replaces (R a2 / 2 x sin a2) by e, half of which the flat rest
    of section 0 gives back (a slope of -e / 2 over its l1 = 400 - R a2 / 2). Main resistance
    (DIN 22101) f g [m'_R + (m'_G + m'_L) cos a] per metre; on the arc sum(dx cos a) = R sin a2.
    The secondary resistances (C(800) - 1 = 0.12 of all main resistances) sit half at the head,
    half at the tail pulley, which is the take-up: T_in + T_out = m g there, so the carry
    leaves it at m g / 2 + (C - 1) F_H / 4."""
    r, m = radius_m, M_G + M_L
    arc = r * A2
    e = r * (1.0 - math.cos(A2)) - 0.5 * arc * math.sin(A2)
    l1 = l2 = 400.0 - 0.5 * arc
    s1 = -0.5 * e / l1
    c1 = math.sqrt(1.0 - s1 * s1)
    s2 = (l2 * math.sin(A2) - 0.5 * e) / l2
    c2 = math.sqrt(1.0 - s2 * s2)
    f_h = F * G * (l1 * (MR_C + m * c1) + MR_C * arc + m * r * math.sin(A2) + l2 * (MR_C + m * c2)
                   + l1 * (MR_R + M_G * c1) + MR_R * arc + M_G * r * math.sin(A2)
                   + l2 * (MR_R + M_G * c2))
    t = 4000.0 * G / 2.0 + 0.12 * f_h / 4.0
    t += F * G * l1 * (MR_C + m * c1) + m * G * l1 * s1  # the flat rest
    t += F * G * (MR_C * arc + m * r * math.sin(A2)) + m * G * r * (1.0 - math.cos(A2))  # arc
    return t


def test_the_steady_verdict_flips_at_the_hand_radius():
    """Lift-off where T(arc end) = R m'_G g cos a2: at R 200 m 31.116 kN against 37.994 kN;
    T(arc end) falls with R more slowly than the limit, the two meet at R 158.63 m. At
    R 158.5 m the belt lifts by 22 N (30.132 against 30.110 kN); at 158.8 m it stays down.
    Judged against the last element's middle slope (0.45 deg flatter) the limit was 30.171 kN
    at 158.5 m and the belt was said to stay down, down to 158.3 m."""
    assert arc_end_tension_by_hand(200.0) == pytest.approx(31115.6, abs=0.1)
    assert 200 * M_G * G * math.cos(A2) == pytest.approx(37994.0, abs=0.1)
    for radius, lifts in ((158.5, True), (158.8, False)):
        st = solve_steady(parse_conveyor(foot_of_incline(radius)), model="din")
        s = st.summary
        t_hand = arc_end_tension_by_hand(radius)
        t_lift = radius * M_G * G * math.cos(A2)
        assert (t_hand > t_lift) is lifts
        (c,) = st.loop.curves
        assert st.tension_n[c.carry[-1]] == pytest.approx(t_hand, rel=1e-5)
        assert s["curve1_tension_kn"] * 1e3 == pytest.approx(t_hand, rel=1e-5)
        assert s["curve1_liftoff_tension_kn"] * 1e3 == pytest.approx(t_lift, rel=1e-12)
        assert s["curve1_liftoff"] is lifts
        assert s["curve1_radius_min_m"] == pytest.approx(t_hand / (M_G * G * math.cos(A2)),
                                                         rel=1e-5)


def test_a_peak_where_the_return_enters_the_arc_is_judged():
    """The return runs down the incline into the valley: it enters the arc at its steep,
    head-side end (loop position 1176.477 m at R 200 m). A peak of the lift-off tension there,
    R m'_G g cos a2 = 37.994 kN, plus 1 kN lifts the belt by 1 kN at that point; the check
    read only the arc elements' ends, the next of which lies an element (3.16 m) further on,
    and said the belt stayed down."""
    st = solve_steady(parse_conveyor(foot_of_incline(200.0)), model="din")
    loop, run = st.loop, st.tension_n
    (c,) = loop.curves
    entry = int(c.ret[-1]) - 1  # the return element that ends where the arc begins
    # the carry's 800 m, the head pulley's arc (200 deg on a 1 m pulley: 1.745 m), then the
    # return from the head down to the arc's end at 400 + R a2 / 2 = 425.268 m from the tail
    assert loop.s_end_m[entry] == pytest.approx(
        800.0 + math.radians(200.0) * 0.5 + 800.0 - (400.0 + 100.0 * A2), abs=1e-6)
    t_lift = 200 * M_G * G * math.cos(A2)
    hi = run.copy()
    hi[entry] = t_lift + 1000.0
    seg = (0.0, 100.0, hi, np.full_like(hi, 50.0), run.copy(), np.full_like(hi, 50.0))
    out, warnings = transient_liftoff(loop, [seg], 30.0, 40.0, 30.0, run)
    assert out["liftoff_max_kn_over"] == pytest.approx(1.0, abs=1e-9)
    assert out["liftoff_at_m"] == pytest.approx(loop.s_end_m[entry], abs=1e-9)
    assert out["liftoff_time_s"] == pytest.approx(50.0)
    (w,) = [m for m in warnings if m.startswith("lift-off in the stop")]
    assert "return idlers" in w and "1.0 kN over its lift-off tension 38.0 kN" in w
