"""Issue 28 (a): input as catalogues print it (``belt.mass_kg_m``, idler sets by ``count``,
rotating mass per roll) and horizontal curves as a statics check (``hcurve{k}_*``).

Hand numbers: the hand conveyor of tests/conftest.py (1 km rising 50 m, m'_G 20 kg/m,
m'_L 50 kg/m, carry sets 12.5 kg at 1.25 m, return 7.5 kg at 2.5 m, B = 1 m).
"""

from __future__ import annotations

import math

import numpy as np
import pytest
import yaml

from beltstudy.engine.conveyor import InputError, parse_conveyor
from beltstudy.engine.hcurves import restoring_force_n_m, tension_limits_n
from beltstudy.engine.loop import CARRY, RETURN, build_loop
from beltstudy.engine.statics import solve_steady
from tests.conftest import CONVEYORS, hand_conveyor_dict

G = 9.81
#: DIN model with C = 1 and f = 0.02 on both strands: the main resistance alone depends on
#: the belt's mass (tests/engine/conftest.py).
DIN = {"f_carry": 0.02, "f_return": 0.02, "c": 1.0}


def _belt(**over) -> dict:
    b = {"width_m": 1.0, "rating_kn_m": 1000, "modulus_kn_m": 60000, "top_cover_mm": 0,
         "bottom_cover_mm": 0}
    b.update(over)
    return b


def _idlers(carry: dict | None = None, ret: dict | None = None) -> dict:
    c = {"spacing_m": 1.25, "roll_diameter_m": 0.133, "rolls": 3, "trough_deg": 35,
         "rotating_mass_kg": 12.5, "seal_drag_n": 5.0}
    r = {"spacing_m": 2.5, "roll_diameter_m": 0.133, "rolls": 1, "rotating_mass_kg": 7.5,
         "seal_drag_n": 3.0}
    c.update(carry or {})
    r.update(ret or {})
    return {"carry": {k: v for k, v in c.items() if v is not None},
            "return": {k: v for k, v in r.items() if v is not None}}


# ------------------------------------------------------------------------ belt.mass_kg_m
def test_belt_mass_per_metre_is_the_loops_belt_mass():
    conv = parse_conveyor(hand_conveyor_dict(belt=_belt(mass_kg_m=38.5)))
    loop = build_loop(conv, "full")
    # m'_G is the printed mass on every element, pulleys included (it moves with the belt)
    np.testing.assert_allclose(loop.mG_kg_m, 38.5, rtol=0, atol=0)
    assert solve_steady(conv, model="din", params=DIN).summary["belt_mass_kg_m"] == 38.5


def test_belt_mass_per_metre_moves_te_by_the_main_resistance_of_both_strands():
    """DIN 22101 (C = 1): F_H = f L g [m'_Ro + m'_Ru + (2 m'_G + m'_L) cos(delta)], so two
    belts differing by dm in m'_G differ in Te by 2 f L g cos(delta) dm (the belt's own lift
    cancels round the loop). L = 1000 m, H = 50 m, f = 0.02, dm = 38.5 - 20 kg/m."""
    light = solve_steady(parse_conveyor(hand_conveyor_dict(belt=_belt(mass_kg_m=20.0))),
                         model="din", params=DIN)
    heavy = solve_steady(parse_conveyor(hand_conveyor_dict(belt=_belt(mass_kg_m=38.5))),
                         model="din", params=DIN)
    cos_d = math.sqrt(1.0 - (50.0 / 1000.0) ** 2)
    hand = 2 * 0.02 * 1000.0 * G * cos_d * (38.5 - 20.0)
    assert heavy.te_n - light.te_n == pytest.approx(hand, rel=1e-9)


def test_belt_mass_per_metre_on_a_catalogue_belt_keeps_its_covers():
    """SPEC 7.1's example: ST1600 at 1.2 m printed at 38.5 kg/m. m'_G is 38.5; the covers
    (the catalogue's) stay for the rubber model, and the carcass the thickness estimate reads
    is m'_G / B - covers x 1.15 kg/m2/mm (engine/catalog.py)."""
    from beltstudy.engine.catalog import COVER_MASS_KG_M2_PER_MM, belt, resolve_belt

    conv = parse_conveyor(hand_conveyor_dict(
        belt={"type": "ST1600", "width_m": 1.2, "mass_kg_m": 38.5}))
    b = resolve_belt(conv.belt)
    row = belt("ST1600")
    assert b.mass_kg_m == 38.5
    assert (b.top_cover_mm, b.bottom_cover_mm) == (row.top_cover_mm, row.bottom_cover_mm)
    covers = (row.top_cover_mm + row.bottom_cover_mm) * COVER_MASS_KG_M2_PER_MM
    assert b.carcass_mass_kg_m2 == pytest.approx(38.5 / 1.2 - covers, rel=1e-12)


@pytest.mark.parametrize("belt, words", [
    (_belt(mass_kg_m=30.0, carcass_mass_kg_m2=20.0), "not both"),
    (_belt(mass_kg_m=0.0), "belt.mass_kg_m"),
    (_belt(mass_kg_m=-3.0), "belt.mass_kg_m"),
    ({"type": "auto", "kind": "steel_cord", "width_m": 1.2, "mass_kg_m": 30.0}, "mass_kg_m"),
    (_belt(mass_kg_m=5.0, top_cover_mm=8, bottom_cover_mm=6), "covers alone"),
])
def test_belt_mass_per_metre_errors_name_the_field(belt, words):
    with pytest.raises(InputError, match=words):
        conv = parse_conveyor(hand_conveyor_dict(belt=belt))
        build_loop(conv)  # the covers-versus-mass check needs the resolved belt


# ------------------------------------------------------------------ idler sets by count
def test_idler_count_gives_the_pitch_length_over_count():
    """S = L / count along the carry, the same length on the return: 640 carry sets and 320
    return sets over 1000 m are 1.5625 m and 3.125 m; m'_R = set mass / S = 12.5 / 1.5625 =
    8 kg/m and 7.5 / 3.125 = 2.4 kg/m."""
    conv = parse_conveyor(hand_conveyor_dict(idlers=_idlers(
        {"spacing_m": None, "count": 640}, {"spacing_m": None, "count": 320})))
    loop = build_loop(conv)
    carry, ret = loop.strand == CARRY, loop.strand == RETURN
    np.testing.assert_allclose(loop.spacing_m[carry], 1000.0 / 640, rtol=1e-15)
    np.testing.assert_allclose(loop.spacing_m[ret], 1000.0 / 320, rtol=1e-15)
    np.testing.assert_allclose(loop.mR_kg_m[carry], 8.0, rtol=1e-12)
    np.testing.assert_allclose(loop.mR_kg_m[ret], 2.4, rtol=1e-12)


def test_idler_count_and_the_same_spacing_give_the_same_te():
    """800 sets over 1000 m are the hand conveyor's 1.25 m pitch (400 return sets its 2.5 m)."""
    by_spacing = solve_steady(parse_conveyor(hand_conveyor_dict()), model="din", params=DIN)
    by_count = solve_steady(parse_conveyor(hand_conveyor_dict(idlers=_idlers(
        {"spacing_m": None, "count": 800}, {"spacing_m": None, "count": 400}))),
        model="din", params=DIN)
    assert by_count.te_n == by_spacing.te_n


def test_rotating_mass_per_roll_times_rolls():
    """Three carry rolls of 4 kg: 12 kg per set, m'_R = 12 / 1.25 = 9.6 kg/m; one return roll
    of 6 kg at 2.5 m: 2.4 kg/m."""
    conv = parse_conveyor(hand_conveyor_dict(idlers=_idlers(
        {"rotating_mass_kg": None, "rotating_mass_per_roll_kg": 4.0},
        {"rotating_mass_kg": None, "rotating_mass_per_roll_kg": 6.0})))
    loop = build_loop(conv)
    np.testing.assert_allclose(loop.mR_kg_m[loop.strand == CARRY], 9.6, rtol=1e-12)
    np.testing.assert_allclose(loop.mR_kg_m[loop.strand == RETURN], 2.4, rtol=1e-12)


@pytest.mark.parametrize("carry, words", [
    ({"count": 800}, "idlers.carry: give the idler pitch spacing_m .* not both"),
    ({"spacing_m": None}, "idlers.carry: give the idler pitch spacing_m .* one of them"),
    ({"spacing_m": None, "count": 20}, "idlers.carry.count: 20 sets over 1000 m is a pitch "
     "of 50 m"),
    ({"spacing_m": None, "count": 0}, "idlers.carry.count"),
    ({"rotating_mass_per_roll_kg": 4.0}, "idlers.carry: give the rotating mass per set"),
    ({"rotating_mass_per_roll_kg": -1.0, "rotating_mass_kg": None},
     "idlers.carry.rotating_mass_per_roll_kg"),
])
def test_idler_errors_name_the_field(carry, words):
    with pytest.raises(InputError, match=words):
        parse_conveyor(hand_conveyor_dict(idlers=_idlers(carry)))


# ------------------------------------------------------------------- horizontal curves
#: A horizontal curve on the hand conveyor: 35 deg trough, DIN 22107's 380 mm rolls at
#: B = 1 m (given, so the test does not lean on the table), the curve over the whole route.
ROLL = 0.38


def _curved(radius: float, tilt: float, **over):
    d = hand_conveyor_dict(
        profile=[{"length_m": 1000, "lift_m": 50, "horizontal_radius_m": radius,
                  "superelevation_deg": tilt}],
        idlers=_idlers({"roll_length_m": ROLL}), **over)
    return parse_conveyor(d)


def _hand_k(b_i: float, b_m: float, b_o: float, lam: float, beta: float, width: float
            ) -> float:
    """Grimmer & Kessler's conventional weight components, over B (engine/hcurves.py)."""
    lam, beta = math.radians(lam), math.radians(beta)
    return (b_i * math.sin(lam + beta) * math.cos(lam) + b_m * math.sin(beta)
            - b_o * math.sin(lam - beta) * math.cos(lam)) / width


def test_flat_belt_balance_is_the_banked_plane():
    """No trough: q = m g cos(alpha) sin(beta), the weight's component down the tilted roll;
    with 70 kg/m, beta = 4 deg, level: 70 x 9.81 x sin 4 deg = 47.90 N/m."""
    q = restoring_force_n_m(70.0, 1.0, 1.0, 0.0, 4.0, drift_m=0.0)
    assert q == pytest.approx(70 * G * math.sin(math.radians(4.0)), rel=1e-12)
    assert q == pytest.approx(47.90, abs=0.01)


def test_horizontal_curve_limits_by_hand():
    """R = 1500 m, trough 35 deg, superelevation 8 deg, B = 1 m on 0.38 m rolls: the belt
    has b_W = (1 - 0.38) / 2 = 0.31 m on each wing and may drift d = 0.38 - 0.31 = 0.07 m
    before its edge leaves a wing roll.

    T_max (running in), belt drifted 0.07 m inwards (b_i 0.38, b_o 0.24), empty belt 20 kg/m:
      k = 0.38 sin 43 cos 35 + 0.38 sin 8 - 0.24 sin 27 cos 35 = 0.17592
      T_max = R m'_G g cos(alpha) k = 1500 x 20 x 9.81 x 0.99875 x 0.17592 = 51.71 kN
    T_min (running out), drifted 0.07 m outwards (b_i 0.24, b_o 0.38), loaded 70 kg/m:
      k = 0.24 sin 43 cos 35 + 0.38 sin 8 - 0.38 sin 27 cos 35 = 0.04565
      T_min = 1500 x 70 x 9.81 x 0.99875 x 0.04565 = 46.96 kN
    """
    cos_a = math.sqrt(1 - 0.05 ** 2)
    k_in = _hand_k(0.38, 0.38, 0.24, 35, 8, 1.0)
    k_out = _hand_k(0.24, 0.38, 0.38, 35, 8, 1.0)
    assert k_in == pytest.approx(0.17592, abs=1e-5)
    assert k_out == pytest.approx(0.04565, abs=1e-5)
    t_min_empty, t_max_empty = tension_limits_n(20.0, 1500, 1.0, ROLL, ROLL, 35, 8, cos_a)
    t_min_full, t_max_full = tension_limits_n(70.0, 1500, 1.0, ROLL, ROLL, 35, 8, cos_a)
    assert t_max_empty == pytest.approx(1500 * 20 * G * cos_a * k_in, rel=1e-12)
    assert t_max_empty / 1e3 == pytest.approx(51.71, abs=0.01)
    assert t_min_full == pytest.approx(1500 * 70 * G * cos_a * k_out, rel=1e-12)
    assert t_min_full / 1e3 == pytest.approx(46.96, abs=0.01)
    # the loaded belt's upper limit is higher, the empty belt's lower limit lower
    assert t_max_full > t_max_empty and t_min_empty < t_min_full


def test_the_run_reports_the_curve_limits_of_its_own_load():
    """The steady summary's limits are those of the belt as the run loads it (70 kg/m: the
    hand T_min above, and T_max = R 70 g cos(alpha) k_in), the verdict compares them with the
    same run's tensions; an empty run gets the empty belt's limits (the hand T_max above)."""
    cos_a = math.sqrt(1 - 0.05 ** 2)
    t_max_loaded = 1500 * 70 * G * cos_a * _hand_k(0.38, 0.38, 0.24, 35, 8, 1.0) / 1e3
    res = solve_steady(_curved(1500, 8), model="din", params=DIN)
    s = res.summary
    assert s["hcurve1_tension_min_kn"] == pytest.approx(46.96, abs=0.01)
    assert s["hcurve1_tension_max_kn"] == pytest.approx(t_max_loaded, rel=1e-9)
    empty = solve_steady(_curved(1500, 8), model="din", params=DIN, load="empty").summary
    assert empty["hcurve1_tension_max_kn"] == pytest.approx(51.71, abs=0.01)
    carry = res.loop.strand == CARRY
    t_run = np.concatenate((res.tension_n[carry], [res.tension_n[-1]]))
    assert s["hcurve1_t_low_kn"] == pytest.approx(t_run.min() / 1e3, rel=1e-12)
    assert s["hcurve1_t_high_kn"] == pytest.approx(t_run.max() / 1e3, rel=1e-12)
    inside = s["hcurve1_t_high_kn"] > t_max_loaded
    outside = s["hcurve1_t_low_kn"] < 46.96
    assert s["hcurve1_ok"] is (not inside and not outside)
    assert inside or outside  # the hand conveyor's tensions (tens of kN) straddle the band
    curve_warnings = [w for w in res.warnings if w.startswith("horizontal curve 1")]
    assert curve_warnings and all("profile.0, 0 to 1000 m from the tail" in w
                                  for w in curve_warnings)
    if inside:
        assert any("runs to the inside" in w and "larger radius" in w for w in curve_warnings)
    if outside:
        assert any("runs out of the curve" in w and "loaded" in w for w in curve_warnings)


def test_a_feed_within_the_curve_gives_the_upper_limit_of_the_least_loaded_belt():
    """Feeds of 10 % at the tail and 90 % at 500 m of the 1 000 m curve: the first half carries
    5 kg/m of material (25 kg/m with the belt), the second 50 (70 kg/m). The belt's weight holds
    it against running in least where it is lightest, so T_max is the 25 kg/m belt's,
    R 25 g cos(alpha) k_in = 1500 x 25 x 9.81 x 0.99875 x 0.17592 = 64.64 kN, and T_min the
    70 kg/m belt's (46.96 kN, as above); the verdict holds the tensions to both."""
    cos_a = math.sqrt(1 - 0.05 ** 2)
    material = {"capacity_t_h": 720, "density_t_m3": 1.0,
                "feed": [{"at_m": 0, "share": 0.1}, {"at_m": 500, "share": 0.9}]}
    res = solve_steady(_curved(1500, 8, material=material), model="din", params=DIN)
    s = res.summary
    t_max = 1500 * 25 * G * cos_a * _hand_k(0.38, 0.38, 0.24, 35, 8, 1.0) / 1e3
    assert t_max == pytest.approx(64.64, abs=0.01)
    assert s["hcurve1_tension_max_kn"] == pytest.approx(t_max, rel=1e-9)
    assert s["hcurve1_tension_min_kn"] == pytest.approx(46.96, abs=0.01)
    # each element against its own load's limits (the profile's tensions, by hand)
    carry = np.flatnonzero(res.loop.strand == CARRY)
    x_end = res.loop.x_m[carry] + res.loop.dx_m[carry]
    t_el = res.tension_n[carry] / 1e3
    light = x_end <= 500 + 1e-9
    t_max_full = 1500 * 70 * G * cos_a * _hand_k(0.38, 0.38, 0.24, 35, 8, 1.0) / 1e3
    runs_in = (t_el[light] > t_max).any() or (t_el[~light] > t_max_full).any()
    assert not s["hcurve1_ok"] if runs_in else True
    if runs_in and (t_el[light] > t_max).any():
        assert any("partly loaded (5 kg/m of material) belt holds there" in w
                   for w in res.warnings)


def test_a_wide_untilted_curve_keeps_the_belt():
    """R = 20 km, no superelevation: T_min = 0 (the belt cannot run out: k < 0 drifted out)
    and T_max = R (m'_G + m'_L) g cos(alpha) (0.38 - 0.24) sin 35 cos 35 = 902 kN (the
    loaded belt, 70 kg/m), above the hand conveyor's tensions: no warning."""
    cos_a = math.sqrt(1 - 0.05 ** 2)
    hand = 20000 * 70 * G * cos_a * (0.38 - 0.24) * math.sin(math.radians(35)) * math.cos(
        math.radians(35)) / 1e3
    res = solve_steady(_curved(20000, 0), model="din", params=DIN)
    s = res.summary
    assert s["hcurve1_tension_min_kn"] == 0.0
    assert s["hcurve1_tension_max_kn"] == pytest.approx(hand, rel=1e-9)
    assert s["hcurve1_ok"] is True
    assert not [w for w in res.warnings if "horizontal curve" in w]


def test_no_curve_no_hcurve_fields(hand_conveyor):
    s = solve_steady(hand_conveyor, model="din", params=DIN).summary
    assert not [k for k in s if k.startswith("hcurve")]


def test_curves_are_numbered_in_profile_order():
    d = hand_conveyor_dict(profile=[
        {"length_m": 300, "lift_m": 0, "horizontal_radius_m": 20000},
        {"length_m": 400, "lift_m": 50},
        {"length_m": 300, "lift_m": 0, "horizontal_radius_m": 30000,
         "superelevation_deg": 2}])
    s = solve_steady(parse_conveyor(d), model="din", params=DIN).summary
    assert {k for k in s if k.startswith("hcurve")} == {
        f"hcurve{k}_{f}" for k in (1, 2)
        for f in ("tension_min_kn", "tension_max_kn", "t_low_kn", "t_high_kn", "ok")}
    # the second curve's radius is the larger: its upper limit too (trough and belt alike)
    assert s["hcurve2_tension_max_kn"] > s["hcurve1_tension_max_kn"]


@pytest.mark.parametrize("section, words", [
    ({"length_m": 1000, "lift_m": 50, "superelevation_deg": 3}, "give horizontal_radius_m"),
    ({"length_m": 1000, "lift_m": 50, "horizontal_radius_m": 5}, "horizontal_radius_m"),
    ({"length_m": 1000, "lift_m": 50, "horizontal_radius_m": 500, "superelevation_deg": 30},
     "superelevation_deg"),
])
def test_horizontal_curve_errors_name_the_field(section, words):
    with pytest.raises(InputError, match=words):
        parse_conveyor(hand_conveyor_dict(profile=[section]))


def test_a_curve_of_more_than_a_full_turn_is_refused():
    """A constant-radius arc turns L / R: 500 m at R 10 m is 50 rad = 2 864.8 deg, a route
    that comes back over itself (more than 2 pi R = 62.8 m of arc); the error names the
    field, the turn, the bound and the radius that makes one turn (500 / 2 pi = 79.577 m),
    rounded up to a tenth of a metre so that the file takes it: 1500 m at the 238.7 m that
    rounding to the nearest gave (1500 / 2 pi = 238.732 m) turns 360.05 deg, and was refused
    as turning "360 deg" with the same advice. Just under a full turn (R 80 m: 358.1 deg) is
    taken."""
    curl = {"length_m": 500, "lift_m": 0, "horizontal_radius_m": 10}
    with pytest.raises(InputError, match=r"profile\.0: horizontal_radius_m \(10 m\).*turns "
                       r"the belt 2865 deg.*full turn \(360 deg\).*at least 79\.6 m"):
        parse_conveyor(hand_conveyor_dict(profile=[curl]))
    near = {"length_m": 1500, "lift_m": 0, "horizontal_radius_m": 238.7}
    with pytest.raises(InputError, match=r"turns the belt 360\.05 deg.*at least 238\.8 m"):
        parse_conveyor(hand_conveyor_dict(profile=[near]))
    parse_conveyor(hand_conveyor_dict(profile=[{**near, "horizontal_radius_m": 238.8}]))
    assert math.degrees(500 / 80) < 360.0
    conv = parse_conveyor(hand_conveyor_dict(profile=[{**curl, "horizontal_radius_m": 80}]))
    assert conv.profile[0].horizontal_radius_m == 80


def test_at_most_max_hcurves_curves():
    from beltstudy.engine.results import MAX_HCURVES

    profile = [{"length_m": 100, "lift_m": 0, "horizontal_radius_m": 5000}
               for _ in range(MAX_HCURVES + 1)]
    with pytest.raises(InputError, match=f"at most {MAX_HCURVES}"):
        parse_conveyor(hand_conveyor_dict(profile=profile))


def test_a_horizontal_curve_warning_names_the_radius_that_holds_the_belt():
    """Both limits are R q(+-d) (Grimmer and Kessler), proportional to the radius at a given
    tilt: the belt runs out of the curve where T < T_min = R q(-d), so a *tighter* radius
    (more pull T / R to the inside) holds it, at most R min(T / T_min); it runs to the inside
    where T > T_max = R q(+d), so a larger radius holds it, at least R max(T / T_max). The
    low-tension warning used to advise a larger radius, which raises T_min. Hand conveyor
    (70 kg/m loaded, T_min 46.96 kN at R 1500 m, tilt 8 deg; empty at R 600 m, T_max 20.68
    kN): the named radius removes the warning on a rerun; the tilt is kept, and the tensions
    do not depend on the radius."""
    res = solve_steady(_curved(1500, 8), model="din", params=DIN)
    s = res.summary
    (out,) = [w for w in res.warnings if "runs out of the curve" in w]
    assert "a larger radius" not in out
    r_max = float(out.split("a tighter radius (at most ")[1].split(" m")[0])
    # by hand: every element of the loaded curve has T_min 46.96 kN; the lowest tension rules
    assert r_max == pytest.approx(1500 * s["hcurve1_t_low_kn"] / 46.96, abs=1.0)
    tighter = solve_steady(_curved(r_max, 8), model="din", params=DIN)
    assert not any("runs out of the curve" in w for w in tighter.warnings)
    empty = solve_steady(_curved(600, 8), model="din", params=DIN, load="empty")
    (inside,) = [w for w in empty.warnings if "runs to the inside" in w]
    assert "a radius of at least" in inside
    r_min = float(inside.split("a radius of at least ")[1].split(" m")[0])
    # by hand: the empty belt's T_max 51.71 kN at R 1500 m is 20.684 kN at R 600 m, the
    # highest tension rules
    assert r_min == pytest.approx(1500 * empty.summary["hcurve1_t_high_kn"] / 51.71, abs=2.0)
    larger = solve_steady(_curved(r_min, 8), model="din", params=DIN, load="empty")
    assert not any("runs to the inside" in w for w in larger.warnings)


def test_a_belt_mass_below_its_covers_is_named_with_the_files_path():
    """fabric-1km's EP800/4 with mass_kg_m 0.5 (covers 5 + 2 mm x 1.15 kg/m2/mm x 1 m = 8.05
    kg/m alone) was refused as 'belt.mass_kg_m: ...' without the file the command read, and a
    study's inline conveyor without 'conveyor.': the check ran once the belt was resolved, past
    the door. It runs at the door now, under the prefix every other field of the file has."""
    d = yaml.safe_load((CONVEYORS / "fabric-1km.yaml").read_text())
    d["belt"]["mass_kg_m"] = 0.5
    with pytest.raises(InputError) as ei:
        parse_conveyor(d, prefix="conveyor.")
    assert str(ei.value).startswith("conveyor.belt.mass_kg_m: 0.5 kg/m is no more than the "
                                    "covers alone weigh")
    assert "= 8.0 kg/m" in str(ei.value)


def test_a_v_set_has_no_middle_roll_whatever_roll_length_m_says():
    """Two rolls (a V set, trough 20 deg), R 1500 m, superelevation 5 deg, loaded belt
    70 kg/m on the 5 % grade: no middle roll, b_M = 0, each wing carries b_W = B / 2 = 0.5 m
    and the belt cannot drift (d = 0), so T_min = T_max = R q(0):
      k = 0.5 sin 25 cos 20 - 0.5 sin 15 cos 20 = 0.07696
      T = 1500 x 70 x 9.81 x 0.99875 x 0.07696 = 79.17 kN.
    (``roll_length_m`` not given: the rolls are taken to span the belt. It is each V roll's
    length, not a middle roll's: with 0.6 m it was read as a 0.6 m middle roll, leaving
    -0.1 m of belt on the outer wing and a band of 0 to 283 kN; with 0.6 m V rolls the band
    is tests/engine/test_hcurve_garland.py's.)"""
    cos_a = math.sqrt(1 - 0.05 ** 2)
    k = _hand_k(0.5, 0.0, 0.5, 20, 5, 1.0)
    assert k == pytest.approx(0.07696, abs=1e-5)
    hand = 1500 * 70 * G * cos_a * k / 1e3
    assert hand == pytest.approx(79.17, abs=0.01)
    for roll in (None,):
        d = hand_conveyor_dict(
            profile=[{"length_m": 1000, "lift_m": 50, "horizontal_radius_m": 1500,
                      "superelevation_deg": 5}],
            idlers=_idlers({"rolls": 2, "trough_deg": 20, "roll_length_m": roll}))
        s = solve_steady(parse_conveyor(d), model="din", params=DIN).summary
        assert s["hcurve1_tension_min_kn"] == pytest.approx(hand, rel=1e-9)
        assert s["hcurve1_tension_max_kn"] == pytest.approx(hand, rel=1e-9)


def _level_curve(radius: float, tilt: float) -> object:
    """A level 2 000 m carry that is all one horizontal curve, a 4 000 kg take-up at the tail:
    the carry starts at 19.62 + 0.5 / 2 = 19.87 kN (the take-up's m g / 2, tail_kn across the
    tail pulley) and, with DIN f 0.02, C 1, rises by 0.02 x 9.81 x (20 + 50 + 10) x 2000 =
    31.392 kN to 51.262 kN at the head."""
    return parse_conveyor(hand_conveyor_dict(
        profile=[{"length_m": 2000, "lift_m": 0, "horizontal_radius_m": radius,
                  "superelevation_deg": tilt}],
        idlers=_idlers({"roll_length_m": ROLL}),
        takeup={"type": "gravity", "position": "tail", "mass_kg": 4000}))


def _band_per_m(tilt: float) -> tuple[float, float]:
    """q(-d) and q(+d) of the loaded level belt, 70 kg/m, by hand [kN/m of radius]."""
    return (70 * G * _hand_k(0.24, ROLL, 0.38, 35, tilt, 1.0) / 1e3,
            70 * G * _hand_k(0.38, ROLL, 0.24, 35, tilt, 1.0) / 1e3)


def test_a_tighter_radius_is_named_only_where_it_holds_the_belt_both_ways():
    """Tilt 10 deg: q(-d) 50.44 and q(+d) 139.41 N/m. The belt runs out of the curve at
    19.87 kN (T_min at R 2000 m is 100.9 kN): a tighter radius holds it up to 19.87 / 0.05044
    = 393.9 m, but below 51.262 / 0.13941 = 367.7 m the head end runs to the inside. The
    warning names both (at most 393 m, below 368 m) and a rerun at either keeps the belt."""
    q_out, q_in = _band_per_m(10)
    assert (q_out, q_in) == (pytest.approx(0.05044, abs=1e-5), pytest.approx(0.13941, abs=1e-5))
    res = solve_steady(_level_curve(2000, 10), model="din", params=DIN)
    s = res.summary
    assert (s["hcurve1_t_low_kn"], s["hcurve1_t_high_kn"]) == (
        pytest.approx(19.87, abs=1e-9), pytest.approx(51.262, abs=1e-9))
    (out,) = [w for w in res.warnings if "runs out of the curve" in w]
    assert math.floor(19.87 / q_out) == 393 and math.ceil(51.262 / q_in) == 368
    assert "a tighter radius (at most 393 m" in out
    assert "below 368 m the belt runs to the inside" in out
    for radius in (393, 368):
        again = solve_steady(_level_curve(radius, 10), model="din", params=DIN).summary
        assert again["hcurve1_ok"] is True
    for radius in (394, 367):
        assert solve_steady(_level_curve(radius, 10), model="din", params=DIN
                            ).summary["hcurve1_ok"] is False


def test_no_radius_is_named_where_none_holds_the_belt():
    """Tilt 16 deg: q(-d) 107.25, q(+d) 194.09 N/m, a band of 1.81 : 1 against the curve's
    tensions 19.87 to 51.262 kN (2.58 : 1). Against running out the radius must be at most
    19.87 / 0.10725 = 185.3 m, against running in at least 51.262 / 0.19409 = 264.1 m: no
    radius holds both, and the warning says so instead of naming 185 m (which ran the head
    end to the inside, and which the file refuses besides: 2000 m at 185 m turns 619 deg).
    With f 0.01 (19.87 to 35.566 kN) 185 m would hold it both ways (35.566 / 0.19409 =
    183.2 m) but is more than a full turn (at least 2000 / 2 pi = 318.3 m): said so."""
    q_out, q_in = _band_per_m(16)
    assert (q_out, q_in) == (pytest.approx(0.10725, abs=1e-5), pytest.approx(0.19409, abs=1e-5))
    res = solve_steady(_level_curve(2000, 16), model="din", params=DIN)
    (out,) = [w for w in res.warnings if "runs out of the curve" in w]
    assert math.ceil(51.262 / q_in) == 265 and math.floor(19.87 / q_out) == 185
    assert "a tighter radius" not in out
    assert ("no radius holds it at this superelevation and these tensions (at least 265 m "
            "against running in, at most 185 m against running out" in out)
    soft = solve_steady(_level_curve(2000, 16), model="din", params={**DIN, "f_carry": 0.01})
    assert soft.summary["hcurve1_t_high_kn"] == pytest.approx(35.566, abs=1e-9)
    assert 35.566 / q_in < 185 < 2000 / (2 * math.pi)
    (out,) = [w for w in soft.warnings if "runs out of the curve" in w]
    assert ("a tighter radius is no help: the 185 m that holds it would turn the section's "
            "2000 m more than a full turn (at least 318.3 m)") in out
