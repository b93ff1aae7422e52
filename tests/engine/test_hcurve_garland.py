"""Horizontal curves on two-, four- and five-roll sets (engine/hcurves.py, docs/routes.md).

The band of tensions that keeps the belt in a curve was computed as for a three-roll set: a
five-roll garland of 0.25 m rolls under a 1 m belt (1.25 m of rolls, 0.125 m of room a side)
was read as one middle roll and one wing of 0.25 m at the full trough angle, whose 0.375 m of
belt overhang it (room 0), so T_min = T_max and every such curve warned; a V set (two rolls)
the same. Each roll now takes the weight of the belt's width on it."""
from __future__ import annotations

import math

import pytest

from beltstudy.engine.capacity import trough_segments
from beltstudy.engine.conveyor import parse_conveyor
from beltstudy.engine.hcurves import garland_limits_n, tension_limits_n
from beltstudy.engine.statics import solve_steady
from tests.conftest import hand_conveyor_dict

G = 9.81


def _curve(rolls, trough_deg, roll_length_m=None):
    carry = {"spacing_m": 1.25, "roll_diameter_m": 0.133, "rolls": rolls,
             "trough_deg": trough_deg, "rotating_mass_kg": 12.5, "seal_drag_n": 5.0}
    if roll_length_m is not None:
        carry["roll_length_m"] = roll_length_m
    d = hand_conveyor_dict(profile=[{"length_m": 1000, "lift_m": 0.0,
                                     "horizontal_radius_m": 1000, "superelevation_deg": 5}])
    d["idlers"] = {**d["idlers"], "carry": carry}
    return solve_steady(parse_conveyor(d), model="din", n_elements=100)


def test_a_five_roll_garland_holds_the_belt_in_its_band_by_hand():
    """Five 0.25 m rolls at 0, 22.5 and 45 deg under a 1 m belt, beta 5 deg, R 1 000 m,
    m' 70 kg/m (20 belt + 50 load): half the belt lies 0.125 m on the middle roll, 0.25 m on
    the 22.5 deg roll and 0.125 m on the 45 deg roll, which reaches 0.125 m past its edge.
    Drifted 0.125 m inwards: q = m' g / B [0.125 x 2 sin 5 + 0.25 (sin 27.5 - sin 17.5)
    cos 22.5 + 0.25 sin 50 cos 45] = 70 x 9.81 x 0.19441 = 133.50 N/m, T_max = R q =
    133.50 kN; drifted outwards the outer term is -0.25 sin 40 cos 45 and q < 0: T_min 0."""
    beta = math.radians(5)
    k_in = (0.125 * 2 * math.sin(beta)
            + 0.25 * (math.sin(math.radians(27.5)) - math.sin(math.radians(17.5)))
            * math.cos(math.radians(22.5))
            + 0.25 * math.sin(math.radians(50)) * math.cos(math.radians(45)))
    assert k_in == pytest.approx(0.19441, abs=1e-5)
    st = _curve(5, 45, 0.25)
    assert st.summary["hcurve1_tension_max_kn"] == pytest.approx(1000 * 70 * G * k_in / 1e3,
                                                                 rel=1e-9)
    assert st.summary["hcurve1_tension_min_kn"] == 0.0
    assert st.summary["hcurve1_ok"] is True
    assert "horizontal curve" not in st.message


def test_three_rolls_as_segments_give_the_three_roll_limits():
    """The segment sum is the three-roll formula where both apply: middle roll 0.38 m, wings
    0.38 m at 35 deg, B 1 m, beta 8 deg, R 1 500 m (the room a side 0.38 - 0.31 = 0.07 m)."""
    segs = trough_segments(1.0, 3, 35.0, 0.38)
    assert segs[0] == pytest.approx((0.19, 0.0)) and segs[1][0] == pytest.approx(0.31)
    for m in (20.0, 70.0):
        assert garland_limits_n(m, 1500.0, 1.0, segs, 0.07, 8.0) == pytest.approx(
            tension_limits_n(m, 1500.0, 1.0, 0.38, 0.38, 35.0, 8.0), rel=1e-12)


def test_a_v_set_uses_its_rolls_length_and_without_it_says_there_is_no_room():
    """Two 0.6 m rolls at 20 deg under a 1 m belt: 0.1 m of room a side, q = m' g / B
    [(0.5 + d) sin(20 + 5) - (0.5 - d) sin(20 - 5)] cos 20. Without roll_length_m the rolls
    are taken to span the belt exactly: one tension holds it, and the warning names the
    field that gives the room."""
    lam, beta = math.radians(20), math.radians(5)
    st = _curve(2, 20, 0.6)
    for key, d in (("hcurve1_tension_max_kn", 0.1), ("hcurve1_tension_min_kn", -0.1)):
        q = 70 * G * ((0.5 + d) * math.sin(lam + beta) - (0.5 - d) * math.sin(lam - beta)
                      ) * math.cos(lam)
        assert st.summary[key] == pytest.approx(max(1000 * q / 1e3, 0.0), rel=1e-9)
    bare = _curve(2, 20)
    assert bare.summary["hcurve1_tension_min_kn"] == pytest.approx(
        bare.summary["hcurve1_tension_max_kn"], rel=1e-12)
    assert ("idlers.carry.roll_length_m is not given, so the 2 rolls are taken to span the "
            "belt exactly (B / 2 each), leaving it no room to drift") in bare.message


def test_a_booster_inside_a_horizontal_curve_is_refused_as_on_a_vertical_arc():
    """A booster drive at 500 m inside a horizontal curve from 300 to 700 m was taken
    silently (one on a vertical arc is refused naming a place off it): a drive pulley needs
    the belt straight into and out of it. At the curve's end it is taken."""
    def with_booster(at_m):
        d = hand_conveyor_dict(profile=[{"length_m": 300, "lift_m": 0.0},
                                        {"length_m": 400, "lift_m": 0.0,
                                         "horizontal_radius_m": 1000},
                                        {"length_m": 300, "lift_m": 0.0}])
        d["drives"] = [{**d["drives"][0], "share": 0.6},
                       {"position": "carry", "at_m": at_m, "wrap_deg": 200, "friction": 0.35,
                        "share": 0.4, "pulley_diameter_m": 1.0}]
        return parse_conveyor(d)

    with pytest.raises(ValueError, match=r"drives\.1\.at_m: 500 m lies in the horizontal "
                       r"curve of profile\.1 \(300 to 700 m from the tail\); .* at or before "
                       r"300 or at or after 700 m"):
        with_booster(500)
    assert with_booster(700).drives[1].at_m == 700


def test_a_drift_wider_than_the_outer_rolls_share_leaves_the_roll_inside_it():
    """Four 0.45 m rolls under a 1 m belt at 35 deg: half the belt lies 0.45 m on the 17.5 deg
    roll and 0.05 m on the 35 deg one, which reaches 0.4 m past its edge. Drifted 0.4 m in,
    the outside edge leaves the 35 deg roll and 0.35 m of the 17.5 deg one: inside 0.45 m on
    each roll, outside 0.1 m on the 17.5 deg roll. With beta 3 deg, m' 14.65 kg/m, R 800 m:
    q = m' g / B [0.45 sin 20.5 cos 17.5 + 0.45 sin 38 cos 35 - 0.1 sin 14.5 cos 17.5],
    T_max = R q = 40.63 kN (the outside outer roll taken at 0.05 - 0.4 = -0.35 m gave
    48.49 kN, on the unsafe side)."""
    b, lam1, lam2 = math.radians(3), math.radians(17.5), math.radians(35)
    k = (0.45 * math.sin(lam1 + b) * math.cos(lam1) + 0.45 * math.sin(lam2 + b) * math.cos(lam2)
         - 0.10 * math.sin(lam1 - b) * math.cos(lam1))
    hand = 800 * 14.65 * G * k
    segs = trough_segments(1.0, 4, 35.0, 0.45)
    assert segs[0][0] == pytest.approx(0.45) and segs[1][0] == pytest.approx(0.05)
    t_min, t_max = garland_limits_n(14.65, 800.0, 1.0, segs, 0.4, 3.0)
    assert t_max == pytest.approx(hand, rel=1e-12) and hand == pytest.approx(40627, abs=1)
    assert t_min == 0.0
