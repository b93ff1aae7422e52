"""A take-up set where the running belt is much tighter than at the slackest point of the
return is named, with the lighter take-up there: a gravity take-up sets the tension where it
hangs (its weight m g on two strands, T = m g / 2), and the loop's running tensions follow
from it, so the same tensions need about 2 T / g at the slackest point."""
from __future__ import annotations

import copy
import re
from pathlib import Path

import pytest

from beltstudy.engine.conveyor import load_conveyor, parse_conveyor
from beltstudy.engine.statics import solve_steady

G = 9.81
ROOT = Path(__file__).resolve().parents[2]

DECLINE_TAIL_DRIVE = {  # 500 m, -40 m, regenerating through a tail drive; take-up at the tail
    "name": "decline-tail-drive", "speed_m_s": 2.0,
    "belt": {"type": "EP630/4", "width_m": 0.8, "top_cover_mm": 5, "bottom_cover_mm": 2},
    "material": {"capacity_t_h": 200, "density_t_m3": 1.2},
    "profile": [{"length_m": 500, "lift_m": -40}],
    "idlers": {"carry": {"spacing_m": 1.2, "roll_diameter_m": 0.127, "rolls": 3,
                         "trough_deg": 35, "cema_class": "C"},
               "return": {"spacing_m": 3.0, "roll_diameter_m": 0.127, "rolls": 1,
                          "cema_class": "C"}},
    "drives": [{"position": "tail", "wrap_deg": 200, "friction": 0.35, "share": 1.0,
                "pulley_diameter_m": 0.5, "inertia_kg_m2": 30, "rated_power_kw": 75,
                "torque_limit": 1.5}],
    "takeup": {"type": "gravity", "position": "tail", "mass_kg": "auto"},
    "accessories": {"head_kn": 0.0, "tail_kn": 0.0},
}


def test_a_take_up_far_tighter_than_the_slackest_return_is_named_with_the_lighter_one():
    res = solve_steady(parse_conveyor(DECLINE_TAIL_DRIVE), model="din", n_elements=100)
    m = re.search(r"note: the take-up holds ([\d.]+) kN where it sits, ([\d.]+) x the slackest "
                  r"running tension of the return \(([\d.]+) kN ([\d]+) m from the tail on the "
                  r"return\): a take-up there \(takeup.position: return, at_m: (\d+)\) holds "
                  r"about the same running tensions with a counterweight of about (\d+) kg "
                  r"\(2 T / g there, now (\d+) kg\)", res.message)
    assert m, res.message
    t_tu, ratio, t_low = float(m.group(1)), float(m.group(2)), float(m.group(3))
    # the take-up's tension is its weight on two strands
    assert t_tu == pytest.approx(res.takeup_mass_kg * G / 2 / 1e3, rel=5e-3)  # 3 figures
    assert ratio == pytest.approx(t_tu / t_low, abs=0.06) and ratio >= 1.5
    assert float(m.group(6)) == pytest.approx(2 * t_low * 1e3 / G, rel=5e-3)  # t_low: 3 figures
    # moved there and sized by the engine with every check, the counterweight is near the
    # estimate (the take-up's own pulleys add their resistance) and far below the tail's
    moved = copy.deepcopy(DECLINE_TAIL_DRIVE)
    moved["takeup"] = {"type": "gravity", "position": "return", "at_m": int(m.group(5)),
                       "mass_kg": "auto"}
    there = solve_steady(parse_conveyor(moved), model="din", n_elements=100)
    assert there.takeup_mass_kg == pytest.approx(float(m.group(6)), rel=0.10)
    assert there.takeup_mass_kg < 0.6 * res.takeup_mass_kg
    assert "note: the take-up holds" not in there.message


@pytest.mark.parametrize("name", ["slope-5pct", "overland-4km", "downhill-regen"])
def test_a_take_up_near_the_slackest_return_gets_no_note(name):
    conv = load_conveyor(ROOT / "studies" / "conveyors" / f"{name}.yaml")
    res = solve_steady(conv, model="din", n_elements=100)
    assert "note: the take-up holds" not in res.message


def test_a_take_up_named_at_the_tail_end_of_the_return_is_placed_at_the_tail():
    """A 1 km incline with a return booster at 300 m and its take-up on the return at 800 m:
    the slackest return tension is where the return reaches the tail. The note read
    'takeup.position: return, at_m: 0', which the file refuses (a take-up at an end is
    position: head or tail); it names the tail, and the named place parses."""
    d = {
        "name": "boost1", "speed_m_s": 4.0,
        "belt": {"width_m": 1.0, "rating_kn_m": 1000, "modulus_kn_m": 60000,
                 "carcass_mass_kg_m2": 20.0, "top_cover_mm": 0, "bottom_cover_mm": 0},
        "material": {"capacity_t_h": 720, "density_t_m3": 1.0},
        "profile": [{"length_m": 1000, "lift_m": 50}],
        "idlers": {"carry": {"spacing_m": 1.25, "roll_diameter_m": 0.133, "rolls": 3,
                             "trough_deg": 35, "rotating_mass_kg": 12.5, "seal_drag_n": 5.0},
                   "return": {"spacing_m": 2.5, "roll_diameter_m": 0.133, "rolls": 1,
                              "rotating_mass_kg": 7.5, "seal_drag_n": 3.0}},
        "drives": [{"position": "head", "wrap_deg": 200, "friction": 0.35, "share": 0.7,
                    "pulley_diameter_m": 1.0},
                   {"position": "return", "at_m": 300, "wrap_deg": 200, "friction": 0.35,
                    "share": 0.3, "pulley_diameter_m": 1.0}],
        "takeup": {"type": "gravity", "position": "return", "at_m": 800, "mass_kg": 6000},
        "accessories": {"head_kn": 1.0, "tail_kn": 0.5},
    }
    res = solve_steady(parse_conveyor(d), model="din", n_elements=100)
    m = re.search(r"a take-up there \((takeup\.position: [^)]*)\) holds", res.message)
    assert m and m.group(1) == "takeup.position: tail", res.message
    moved = copy.deepcopy(d)
    moved["takeup"] = {"type": "gravity", "position": "tail", "mass_kg": "auto"}
    there = solve_steady(parse_conveyor(moved), model="din", n_elements=100)
    assert "note: the take-up holds" not in there.message
