"""The words of a take-up carriage that reached its rest end stop (engine/dynamics/simulate.py,
``_endstop_words``): each remedy once, joined by one comma."""
from __future__ import annotations

from beltstudy.engine.conveyor import Scenario, parse_conveyor
from beltstudy.engine.run import run_one


def _incline() -> dict:
    """A 400 m incline rising 20 m (EP630/4, 600 t/h at 3 m/s) with a 2 400 kg take-up on 0.6 m
    of travel: the loaded coast stop draws the carriage to its rest end."""
    return {
        "name": "incline-400m", "speed_m_s": 3.0,
        "belt": {"type": "EP630/4", "width_m": 1.0},
        "material": {"capacity_t_h": 600, "density_t_m3": 1.2},
        "profile": [{"length_m": 200, "lift_m": 8}, {"length_m": 200, "lift_m": 12}],
        "idlers": {"carry": {"spacing_m": 1.2, "trough_deg": 30},
                   "return": {"spacing_m": 3.0, "rolls": 1}},
        "drives": [{"position": "head", "wrap_deg": 200, "friction": 0.35,
                    "pulley_diameter_m": 0.63, "inertia_kg_m2": 30, "rated_power_kw": 60}],
        "takeup": {"type": "gravity", "position": "tail", "mass_kg": 2400, "travel_m": 0.6},
    }


def test_the_rest_end_remedies_are_joined_by_one_comma():
    """The warning read '... or a heavier take-up, which resists the pull drawing it in,, or a
    gentler stop, which swings the carriage less ...' (two commas): now one."""
    scn = Scenario(start={"control": "s-curve", "time_s": 15}, run_s=3,
                   stop={"mode": "coast", "time_s": 3}, elements=80, temperature_c=20)
    r = run_one(parse_conveyor(_incline()), scn, model="din")
    msg = r.summary["message"]
    assert "take-up carriage reached the rest end" in msg, msg
    assert ",," not in msg
    assert "which resists the pull drawing it in, or a gentler stop" in msg
