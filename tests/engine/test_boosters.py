"""Booster drives along a strand and a take-up along the return (SPEC 7.1 ``drives[i].position:
carry | return`` with ``at_m``, ``takeup.position: return`` with ``at_m``; issue 28 item 2),
against hand calculations on the hand conveyor (tests/conftest.py): 1000 m rising 50 m,
v = 4 m/s, m'_G = 20 kg/m, m'_L = 50 kg/m, m'_R = 10 kg/m carry and 3 kg/m return, DIN 22101
with C = 1 and no accessories (main resistances only), so the walk is the hand's."""

from __future__ import annotations

import math

import numpy as np
import pytest

from beltstudy.engine.conveyor import parse_conveyor
from beltstudy.engine.errors import InputError
from beltstudy.engine.loop import BOOSTER, CARRY, RETURN, TAKEUP, G, build_loop
from beltstudy.engine.statics import solve_steady
from tests.conftest import hand_conveyor_dict

MG, ML, MRC, MRR, F = 20.0, 50.0, 10.0, 3.0, 0.020
L, H = 1000.0, 50.0
COS = math.sqrt(1 - 0.05**2)
DIN = {"f_carry": F, "f_return": F, "c": 1.0}


def head(share, **over):
    return {"position": "head", "wrap_deg": 200, "friction": 0.35, "share": share,
            "pulley_diameter_m": 1.0, **over}


def booster(position, at_m, share, **over):
    return {"position": position, "at_m": at_m, "wrap_deg": 200, "friction": 0.35,
            "share": share, "pulley_diameter_m": 1.0, **over}


def conv(drives, takeup=None, **over):
    d = hand_conveyor_dict(drives=drives, accessories={"head_kn": 0.0, "tail_kn": 0.0}, **over)
    if takeup is not None:
        d["takeup"] = takeup
    return parse_conveyor(d)


def carry_walk(x0, x1, load=ML):
    """Carry tension rise from x0 to x1 [N]: f g [dx m'_R + cos a dx (m'_G + m'_L)] + g
    (m'_G + m'_L) dz, on the 5 % grade."""
    dx = x1 - x0
    return F * G * (dx * MRC + COS * dx * (MG + load)) + G * (MG + load) * 0.05 * dx


def return_walk(x0, x1):
    """Return tension rise running from x0 down to x1 < x0 [N] (the belt runs downhill)."""
    dx = x0 - x1
    return F * G * (dx * MRR + COS * dx * MG) - G * MG * 0.05 * dx


TE = carry_walk(0.0, L) + return_walk(L, 0.0)  # effective tension, the hand's [N]


def test_tension_walk_with_a_booster_at_mid_carry():
    """A booster at 500 m with 0.4 of Te: the tension drops by 0.4 Te across its pulley, the
    head by 0.6 Te; between them the walk is the hand's carry walk."""
    c = conv([head(0.6), booster("carry", 500.0, 0.4)])
    res = solve_steady(c, model="din", params=DIN)
    loop, T = res.loop, res.tension_n
    assert res.te_n == pytest.approx(TE, rel=1e-9)
    b = loop.drive_elements[1]
    assert loop.strand[b] == BOOSTER and loop.pulley_at(b).at_m == 500.0
    assert loop.x_m[b] == pytest.approx(500.0, abs=1e-9)
    # a loop position names the booster, and the carry beyond it by its route position
    assert loop.where(float(loop.s_m[b]) + 0.1) == ("booster", 500.0)
    strand, x = loop.where(float(loop.s_m[b + 1]) + 10.0)
    assert strand == "carry" and x == pytest.approx(510.0, abs=1e-9)
    # the drop across the booster and across the head drive, by their shares
    assert T[b - 1] - T[b] == pytest.approx(0.4 * TE, rel=1e-9)
    h = loop.drive_elements[0]
    assert T[h - 1] - T[h] == pytest.approx(0.6 * TE, rel=1e-9)
    # the carry walk from the tail to the booster and from the booster to the head
    t_tail = T[loop.n - 1]
    assert T[b - 1] - t_tail == pytest.approx(carry_walk(0.0, 500.0), rel=1e-9)
    assert T[h - 1] - T[b] == pytest.approx(carry_walk(500.0, L), rel=1e-9)
    # the booster's pulley element carries no load and no idlers; the carry keeps its length
    carry = loop.strand == CARRY
    assert loop.dx_m[carry].sum() == pytest.approx(L, rel=1e-12)
    assert loop.mL_kg_m[b] == 0.0 and loop.mR_kg_m[b] == 0.0
    # summary per drive: tight and slack sides of the booster
    assert res.summary["drive2_t_tight_kn"] == pytest.approx(T[b - 1] / 1e3, rel=1e-12)
    assert res.summary["drive2_t_slack_kn"] == pytest.approx(T[b] / 1e3, rel=1e-12)


def test_a_booster_on_the_return_drops_the_tension_by_its_share():
    c = conv([head(0.7), booster("return", 250.0, 0.3)])
    res = solve_steady(c, model="din", params=DIN)
    loop, T = res.loop, res.tension_n
    b = loop.drive_elements[1]
    assert loop.strand[b - 1] == RETURN and loop.strand[b + 1] == RETURN
    assert loop.x_m[b] == pytest.approx(250.0, abs=1e-9)
    assert T[b - 1] - T[b] == pytest.approx(0.3 * TE, rel=1e-9)
    # from the head's slack side down to the booster: the hand's return walk
    h = loop.drive_elements[0]
    assert T[b - 1] - T[h] == pytest.approx(return_walk(L, 250.0), rel=1e-9)


def test_takeup_at_mid_return_holds_its_tension_where_it_sits():
    """A 6 t gravity take-up at 500 m along the return: the tension on both its sides is
    m g / 2 = 29.43 kN (no resistance at its pulley), and the tail receives that plus the
    return walk from 500 m down to the tail."""
    c = conv([head(1.0)], takeup={"type": "gravity", "position": "return", "at_m": 500,
                                  "mass_kg": 6000})
    res = solve_steady(c, model="din", params=DIN)
    loop, T = res.loop, res.tension_n
    k = loop.i_takeup
    assert loop.strand[k] == TAKEUP and loop.pulley_at(k).at_m == 500.0
    assert loop.x_m[k] == pytest.approx(500.0, abs=1e-9)
    half = 6000 * G / 2
    assert T[k - 1] == pytest.approx(half, rel=1e-9) and T[k] == pytest.approx(half, rel=1e-9)
    assert res.summary["takeup_tension_kn"] == pytest.approx(half / 1e3, rel=1e-12)
    tail_in = loop.i_tail - 1  # the last return element's end
    assert T[tail_in] == pytest.approx(half + return_walk(500.0, 0.0), rel=1e-9)
    # the tail pulley is a plain pulley now, not the take-up
    assert not loop.pulley_at(loop.i_tail).takeup


def test_auto_takeup_at_mid_return_meets_every_drives_slip_limit():
    """Auto sizing with a booster and a take-up along the return: every drive pulley,
    the booster too, keeps T_tight <= e^(mu theta) T_slack running (within 1e-9)."""
    c = conv([head(0.5), booster("carry", 600.0, 0.5, wrap_deg=120)],
             takeup={"type": "gravity", "position": "return", "at_m": 900, "mass_kg": "auto"})
    res = solve_steady(c, model="din", params=DIN)
    loop, T = res.loop, res.tension_n
    for e in loop.drive_elements:
        p = loop.pulley_at(e)
        assert T[e - 1] <= p.euler * T[e] * (1 + 1e-9)
    assert res.summary["slip_margin"] >= 1.0 - 1e-9


def test_strand_cuts_put_an_element_end_at_each_point():
    """Boosters and a take-up between element ends cut the strands there; both strands are
    cut at every point (their elements mirror), the element count grows by the pieces."""
    c = conv([head(0.6), booster("carry", 333.0, 0.4)],
             takeup={"type": "gravity", "position": "return", "at_m": 777, "mass_kg": 6000})
    loop = build_loop(c, 1.0, n_elements=20)
    carry = np.flatnonzero(loop.strand == CARRY)
    ret = np.flatnonzero(loop.strand == RETURN)
    for x in (333.0, 777.0):
        assert np.any(np.isclose(loop.x_m[carry], x))
        assert np.any(np.isclose(loop.x_m[ret], x))
    assert loop.dx_m[carry].sum() == pytest.approx(L, rel=1e-12)
    assert loop.dx_m[ret].sum() == pytest.approx(L, rel=1e-12)
    assert np.allclose(np.sort(loop.dx_m[carry]), np.sort(loop.dx_m[ret]))
    # the booster's pulley sits between the carry elements ending and starting at 333 m
    b = loop.drive_elements[1]
    assert loop.x_m[b - 1] + loop.dx_m[b - 1] == pytest.approx(333.0)
    assert loop.x_m[b + 1] == pytest.approx(333.0)
    # heights stay continuous across the pulleys
    assert loop.z_m[b] == pytest.approx(loop.z_end_m[b - 1]) == pytest.approx(loop.z_m[b + 1])


def test_without_boosters_the_loop_is_unchanged_bit_for_bit():
    """x_m of the carry is s_m without pulleys along the carry, and a conveyor without
    strand points meshes as before (same element ends, same masses)."""
    c = conv([head(1.0)])
    loop = build_loop(c, 1.0, n_elements=40)
    carry = loop.strand == CARRY
    np.testing.assert_array_equal(loop.x_m[carry], loop.s_m[carry])
    assert loop.n == 42 and loop.nc == 20


def test_feed_points_and_skirts_on_a_route_with_a_vertical_curve():
    """A feed at 700 m (beyond a concave curve at 500 m, R 400 m) on a curved route: the
    carry is cut there, the material line load steps there, and the skirts count only the
    material fed upstream of each element (ISO 5048 F_gL with the whole flow here)."""
    prof = [{"length_m": 500, "lift_m": 0, "curve_radius_m": 400.0},
            {"length_m": 500, "lift_m": 50.0}]
    c = conv([head(1.0)], profile=prof,
             material={"capacity_t_h": 720, "density_t_m3": 1.0,
                       "feed": [{"at_m": 0, "share": 0.5},
                                {"at_m": 700, "share": 0.5, "skirt_length_m": 8,
                                 "skirt_width_m": 0.6}]})
    res = solve_steady(c, model="din", params=DIN)
    loop = res.loop
    carry = np.flatnonzero(loop.strand == CARRY)
    x = loop.x_m[carry]
    assert np.any(np.isclose(x, 700.0))
    mL = loop.mL_kg_m[carry]
    assert np.allclose(mL[x < 700 - 1e-9], 0.5 * ML) and np.allclose(mL[x >= 700 - 1e-9], ML)
    hand = 0.6 * 0.2**2 * 1000 * G * 8 / (4.0**2 * 0.6**2)
    assert res.summary["te_components_kn"]["accessories"] * 1e3 == pytest.approx(hand,
                                                                                rel=1e-9)
    (curve,) = loop.curves
    assert np.all(loop.strand[curve.carry] == CARRY) and np.all(loop.strand[curve.ret] == RETURN)
    # the curve's return elements lie over the same stretch of route as its carry elements
    mid_c = loop.x_m[curve.carry] + 0.5 * loop.dx_m[curve.carry]
    mid_r = loop.x_m[curve.ret] - 0.5 * loop.dx_m[curve.ret]
    np.testing.assert_allclose(np.sort(mid_c), np.sort(mid_r), atol=1e-9)


def test_a_booster_beyond_a_curve_keeps_the_curve_elements_on_their_arc():
    prof = [{"length_m": 500, "lift_m": 0, "curve_radius_m": 400.0},
            {"length_m": 500, "lift_m": 50.0}]
    c = conv([head(0.5), booster("carry", 800.0, 0.5)], profile=prof,
             takeup={"type": "gravity", "position": "return", "at_m": 900, "mass_kg": 6000})
    loop = build_loop(c, 1.0, n_elements=40)
    (curve,) = loop.curves
    for els in (curve.carry, curve.ret):
        assert np.all((loop.strand[els] == CARRY) | (loop.strand[els] == RETURN))
    mid_c = loop.x_m[curve.carry] + 0.5 * loop.dx_m[curve.carry]
    assert np.all((mid_c > curve.start_m) & (mid_c < curve.end_m))
    mid_r = loop.x_m[curve.ret] - 0.5 * loop.dx_m[curve.ret]
    assert np.all((mid_r > curve.start_m) & (mid_r < curve.end_m))
    assert len(curve.ret) == len(curve.carry)


@pytest.mark.parametrize("drives, takeup, field", [
    ([head(0.5), {**booster("carry", 500, 0.5), "at_m": None}], None, "at_m"),
    ([{**head(1.0), "at_m": 100}], None, "at_m"),
    ([head(0.5), booster("carry", 1000, 0.5)], None, r"drives.1\.at_m"),
    ([head(0.5), booster("return", 0, 0.5)], None, r"drives.1\.at_m"),
    ([head(1.0)], {"type": "gravity", "position": "return", "mass_kg": 6000}, "at_m"),
    ([head(1.0)], {"type": "gravity", "position": "return", "at_m": 1200, "mass_kg": 6000},
     r"takeup\.at_m"),
    ([head(1.0)], {"type": "gravity", "position": "tail", "at_m": 100, "mass_kg": 6000},
     "at_m"),
])
def test_booster_and_takeup_positions_are_checked_naming_the_field(drives, takeup, field):
    with pytest.raises(InputError, match=field):
        conv(drives, takeup)


def test_a_point_on_a_vertical_curves_arc_is_refused_naming_it():
    prof = [{"length_m": 500, "lift_m": 0, "curve_radius_m": 400.0},
            {"length_m": 500, "lift_m": 50.0}]
    # the arc runs 500 -+ 400 x 0.05 / 2 = 490 to 510 m
    with pytest.raises(InputError, match=r"drives.1\.at_m: 505 m lies on vertical curve 1"):
        conv([head(0.5), booster("carry", 505.0, 0.5)], profile=prof)
    with pytest.raises(InputError, match=r"material\.feed.1\.at_m: 495 m lies on vertical"):
        conv([head(1.0)], profile=prof,
             material={"capacity_t_h": 720, "density_t_m3": 1.0,
                       "feed": [{"at_m": 0, "share": 0.5}, {"at_m": 495, "share": 0.5}]})


def test_messages_name_a_booster_by_where_it_sits():
    c = conv([head(0.5), booster("carry", 500.0, 0.5, rated_power_kw=1.0)])
    res = solve_steady(c, model="din", params=DIN)
    assert "drive 2 (carry at 500 m)" in res.summary["message"]
