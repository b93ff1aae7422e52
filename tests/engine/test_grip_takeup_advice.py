"""The take-up a brake-grip note advises is rounded up, so following it clears the note.

An 800 m decline (-10 m over 300 m, then -50 m over 500 m) driven at the tail, its gravity
take-up at the head just after the head pulley and a 58.86 kN head brake (1.2 x the loaded
belt's net pull, 1.2 x 49.05 kN, the holding size of ``force_kn: auto``): under CEMA at
-20 C, full load, the head pulley passes the brake force in the stop from a counterweight
of 30 045.3 kg. The note advised 'a take-up of 30,045 kg' (rounded to the nearest); at
30 045 kg the pulley was 3 N short and the note repeated the same 30,045 kg.
"""

from __future__ import annotations

import re

from beltstudy.engine.conveyor import Conveyor, Scenario
from beltstudy.engine.design import auto_sizes
from beltstudy.engine.statics import solve_steady
from beltstudy.engine.stopgrip import takeup_at_least

BRAKE_STOP = Scenario.model_validate({"stop": {"mode": "brake", "time_s": 6.0}})


def _decline(mass_kg: float) -> Conveyor:
    return Conveyor.model_validate({
        "name": "decline-800", "speed_m_s": 3.0,
        "belt": {"type": "ST1250", "width_m": 1.0},
        "material": {"capacity_t_h": 900, "density_t_m3": 1.6},
        "profile": [{"length_m": 300, "lift_m": -10}, {"length_m": 500, "lift_m": -50}],
        "idlers": {"carry": {"spacing_m": 1.2, "roll_diameter_m": 0.133, "rolls": 3,
                             "trough_deg": 35},
                   "return": {"spacing_m": 3.0, "roll_diameter_m": 0.133, "rolls": 1}},
        "drives": [{"position": "tail", "wrap_deg": 200, "friction": 0.35, "share": 1.0,
                    "pulley_diameter_m": 0.8, "inertia_kg_m2": 250, "torque_limit": 1.5}],
        "takeup": {"type": "gravity", "position": "head", "mass_kg": mass_kg, "travel_m": 6},
        "brakes": [{"position": "head", "force_kn": 58.86, "delay_s": 0.3, "hold": True}],
    })


def _note(conv: Conveyor) -> str:
    st = solve_steady(conv, model="cema", temperature_c=-20.0, load="full")
    return auto_sizes(conv, BRAKE_STOP, model="cema", steady=st)["brake_note"]


def test_the_advised_take_up_clears_the_grip_note():
    note = _note(_decline(12060.3))
    assert "beyond the grip in the stop" in note, note
    advised = int(re.search(r"a take-up of ([\d,]+) kg", note).group(1).replace(",", ""))
    assert 30_040 < advised < 30_050
    # the advice followed: the pulley passes the force, no note
    assert _note(_decline(advised)) == ""
    # a kilogram less is short again (the advice is the least whole kilogram)
    assert "beyond the grip in the stop" in _note(_decline(advised - 1))


def test_take_up_figures_are_rounded_up():
    # 2 T / g by hand: 2 x 147 372.2 N / 9.81 = 30 045.3 kg -> 30,046 kg, not 30,045
    assert takeup_at_least(147_372.2, 9.81) == "30,046 kg"
    # a whole kilogram stays (2 x 49 050 N / 9.81 = 10 000 kg)
    assert takeup_at_least(49_050.0, 9.81) == "10,000 kg"
    # a pretension at four significant figures, upward: 147.3722 kN -> 147.4 kN
    assert takeup_at_least(147_372.2) == "147.4 kN"
    assert takeup_at_least(147_300.0) == "147.3 kN"
    assert takeup_at_least(9_000.01) == "9.001 kN"


def _two_brakes(mass_kg) -> Conveyor:
    """A 2 km, -150 m decline: head drive, tail take-up, a given 60 kN head brake beside an
    auto tail brake."""
    return Conveyor.model_validate({
        "name": "decline-2k", "speed_m_s": 4.0,
        "belt": {"type": "ST2500", "width_m": 1.2},
        "material": {"capacity_t_h": 2200, "density_t_m3": 1.7},
        "profile": [{"length_m": 1000, "lift_m": -40}, {"length_m": 1000, "lift_m": -110}],
        "idlers": {"carry": {"spacing_m": 1.2, "roll_diameter_m": 0.152, "rolls": 3,
                             "trough_deg": 35},
                   "return": {"spacing_m": 3.0, "roll_diameter_m": 0.152, "rolls": 1}},
        "drives": [{"position": "head", "wrap_deg": 210, "friction": 0.35, "share": 1.0,
                    "pulley_diameter_m": 1.25, "inertia_kg_m2": 1500, "torque_limit": 1.5}],
        "takeup": {"type": "gravity", "position": "tail", "mass_kg": mass_kg, "travel_m": 12},
        "brakes": [{"position": "head", "force_kn": 60, "delay_s": 0.5},
                   {"position": "tail", "force_kn": "auto", "delay_s": 0.5}],
    })


def test_a_given_brake_beside_an_auto_one_is_checked_against_its_grip():
    # the auto tail brake is sized within the tail pulley's grip; the given 60 kN head brake
    # acts through drive 1's pulley, whose slack side (the return leaving the head) falls in
    # the stop: the note says it is beyond that pulley's grip, as it does with no auto brake
    scenario = Scenario.model_validate({"stop": {"mode": "brake", "time_s": 9.0}})
    conv = _two_brakes("auto")
    st = solve_steady(conv, model="din", temperature_c=20.0, load="full")
    sizes = auto_sizes(conv, scenario, model="din", steady=st)
    note = sizes["brake_note"]
    assert sizes["brake_governed_by"][0] == "given"
    assert "drive 1's pulley (head) passes at most" in note, note
    assert "against the 60 kN set (brakes.0.force_kn)" in note, note
    # the take-up advised is found with the auto brake sized again beside it (a heavier
    # take-up lets the tail brake grow toward the stop's need, which lowers the head's slack
    # side too); followed, the head pulley passes its 60 kN and the note is gone
    said = re.search(r"beyond the grip in the stop.*a take-up of ([\d,]+) kg, takeup\.mass_kg",
                     note)
    advised = int(said.group(1).replace(",", ""))
    conv = _two_brakes(advised)
    st = solve_steady(conv, model="din", temperature_c=20.0, load="full")
    after = auto_sizes(conv, scenario, model="din", steady=st)
    assert after["brake_force_kn"][1] > sizes["brake_force_kn"][1]  # the auto brake grew
    assert "beyond the grip in the stop" not in after["brake_note"], after["brake_note"]
