"""Steady advice that names a value no file may hold, or no curve can have (engine/statics.py
``_grip_levers``, engine/hcurves.py): a 6.5 km decline with a counterweight far too light
(2.4 t) slips its drives and goes slack in a horizontal curve."""
from __future__ import annotations

import math
import re

from beltstudy.engine.conveyor import parse_conveyor
from beltstudy.engine.statics import solve_steady

#: 6.5 km, -328 m, ST3150 x 2.2 m, 12 500 t/h at 5.48 m/s, two horizontal curves; a head and
#: a tail vfd drive, and a 2.4 t gravity take-up at the tail.
DECLINE = {
    "name": "decline-light-takeup", "speed_m_s": 5.48,
    "belt": {"type": "ST3150", "width_m": 2.2, "compound": "lrr"},
    "material": {"capacity_t_h": 12500.0, "density_t_m3": 2.3, "loading_speed_m_s": 0.0},
    "profile": [
        {"length_m": 2561.5, "lift_m": -117.13, "horizontal_radius_m": 941.0,
         "superelevation_deg": 2.5},
        {"length_m": 3972.8, "lift_m": -210.78, "horizontal_radius_m": 800.0,
         "superelevation_deg": 2.6}],
    "idlers": {"carry": {"spacing_m": 1.1, "roll_diameter_m": 0.127, "rolls": 3,
                         "trough_deg": 45, "cema_class": "E"},
               "return": {"spacing_m": 3.27, "roll_diameter_m": 0.152, "rolls": 1,
                          "cema_class": "C"}},
    "drives": [
        {"position": "head", "wrap_deg": 180, "friction": 0.27, "share": 0.591,
         "pulley_diameter_m": 1.6, "inertia_kg_m2": 155.0, "torque_limit": 1.85,
         "control": "vfd"},
        {"position": "tail", "wrap_deg": 240, "friction": 0.39, "share": 0.409,
         "pulley_diameter_m": 1.6, "inertia_kg_m2": 501.0, "torque_limit": 1.55,
         "control": "vfd"}],
    "takeup": {"type": "gravity", "position": "tail", "mass_kg": 2400.0},
    "holdback": False,
    "accessories": {"head_kn": 0.1, "tail_kn": 1.1},
}


def test_a_slack_belt_in_a_curve_is_told_the_take_up_not_a_radius():
    """Where the tension in a horizontal curve is at or below zero, its pull to the inside
    (T / R) is gone: no radius holds the belt, and the words gave "a tighter radius (at most
    inf m ...)" (or "at most -821 m"). They now say the belt is slack there and name the
    take-up."""
    res = solve_steady(parse_conveyor(DECLINE), model="cmod", temperature_c=25.6)
    curve = [w for w in res.warnings if w.startswith("horizontal curve") and "runs out" in w]
    assert curve, res.message
    for w in curve:
        tension = float(re.search(r"tension (-?[\d.]+) kN", w).group(1))
        if tension <= 0.0:
            assert "the belt is slack there" in w and "more take-up tension" in w, w
            assert "inf m" not in w and not re.search(r"-\d+ m", w), w
    assert any("the belt is slack there" in w for w in curve), curve


def test_grip_levers_name_only_values_a_file_may_hold_and_the_share_that_passes():
    """The slipping drives' levers on their own pulley: a friction above 1 or a wrap of 360
    deg or more is no value a file may give (a slope was told "friction at least 1.08",
    "wrap_deg at least 644 deg"): said out of reach instead. The smaller share is the one
    the pulley passes at the same slack side, share (e^(mu theta) - 1) / (T1 / T2 - 1), below
    the drive's present share (the words gave the present share)."""
    conv = parse_conveyor(DECLINE)
    res = solve_steady(conv, model="cmod", temperature_c=25.6)
    slips = [w for w in res.warnings if w.startswith("slip at drive")]
    assert slips, res.message
    for w in slips:
        for mu in re.findall(r"friction at least ([\d.]+)", w):
            assert float(mu) <= 1.0, w
        for wrap in re.findall(r"wrap_deg at least ([\d.]+) deg", w):
            assert float(wrap) < 360.0, w
        for k, most, now in re.findall(r"drives\.(\d)\.share at most ([\d.]+), now ([\d.]+)", w):
            d = conv.drives[int(k)]
            assert float(now) == d.share and float(most) < d.share, w
            # the levers are for the least margin of the phases said
            margin = min(float(m) for m in re.findall(r"slip margin ([\d.]+) < 1", w))
            e = math.exp(d.friction * math.radians(d.wrap_deg))
            ratio = e / margin
            # the margin is printed to two figures: the share to within that rounding
            hand = d.share * (e - 1) / (ratio - 1)
            assert abs(float(most) - hand) <= 0.01 + 0.05 * hand, (w, hand)


def test_round_off_at_a_held_pulley_is_no_force_it_fails_to_hold():
    """A 316 m incline whose 594 kg take-up leaves the belt slack at rest (loaded declines,
    none here, so the belt is empty): its at-rest words said the tail pulley "passes
    1.819e-15 kN, beyond its grip of 0 kN ... a slack-side tension of 8.405e-16 kN would hold
    it", round-off against a grip clamped to 0. Round-off beside the tensions is no force."""
    d = {
        "name": "slack-at-rest", "speed_m_s": 3.15,
        "belt": {"type": "ST2500", "width_m": 0.8, "compound": "lrr"},
        "material": {"capacity_t_h": 835.0, "density_t_m3": 1.73, "loading_speed_m_s": 0.0},
        "profile": [{"length_m": 316.0, "lift_m": 43.77, "horizontal_radius_m": 3950.0}],
        "idlers": {"carry": {"spacing_m": 1.28, "roll_diameter_m": 0.127, "rolls": 3,
                             "trough_deg": 45, "cema_class": "C"},
                   "return": {"spacing_m": 4.06, "roll_diameter_m": 0.152, "rolls": 2,
                              "trough_deg": 10, "cema_class": "C"}},
        "drives": [
            {"position": "head", "wrap_deg": 240, "friction": 0.27, "share": 0.415,
             "pulley_diameter_m": 0.63, "inertia_kg_m2": 202.0, "torque_limit": 1.86,
             "control": "vfd"},
            {"position": "tail", "wrap_deg": 200, "friction": 0.33, "share": 0.333,
             "pulley_diameter_m": 0.63, "inertia_kg_m2": 2350.0, "torque_limit": 1.21,
             "control": "vfd"},
            {"position": "head", "wrap_deg": 210, "friction": 0.31, "share": 0.252,
             "pulley_diameter_m": 0.63, "inertia_kg_m2": 5000.0, "torque_limit": 1.74,
             "control": "vfd", "rated_power_kw": 219.0, "trip_s": 0.09}],
        "takeup": {"type": "gravity", "position": "return", "at_m": 153.6, "mass_kg": 594.0,
                   "carriage_mass_kg": 267.0},
        "brakes": [{"force_kn": "auto", "delay_s": 1.72, "position": "tail"}],
        "holdback": True,
        "accessories": {"head_kn": 1.4, "tail_kn": 0.5},
    }
    res = solve_steady(parse_conveyor(d), model="nonlin", temperature_c=-7.7, load="declines")
    assert "holding the belt passes" not in res.message, res.message
    assert "e-15" not in res.message and "e-16" not in res.message
