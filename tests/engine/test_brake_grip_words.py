"""The words of a brake beyond its pulley's grip in a brake stop, and of the take-up lever.

A short incline whose head pulley, on a low screw take-up, passes nothing in the stop: its
slack side (the carry strand into the head) falls with the coast deceleration, and with that
fall doubled for the stop's fronts it is already at zero before any brake acts. The note said
'passes at most 0 kN ... against the 5 kN given', and 'given' also for a force the design
sized (an auto brake written in). A fixed take-up has no counterweight: 'a heavier take-up'
was offered for it.
"""

from __future__ import annotations

import math
import re
from types import SimpleNamespace

import numpy as np

from beltstudy.engine.conveyor import Conveyor, Scenario
from beltstudy.engine.design import auto_sizes
from beltstudy.engine.statics import solve_steady

BRAKE_STOP = Scenario.model_validate({"stop": {"mode": "brake", "time_s": 1.0},
                                      "elements": 40})


def _conv(takeup: dict, brake_kn, lift_m: float = 15.0, **over) -> Conveyor:
    d = {
        "name": "short-incline", "speed_m_s": 2.0,
        "belt": {"type": "EP630/4", "width_m": 0.8, "compound": "standard"},
        "material": {"capacity_t_h": 400, "density_t_m3": 1.6, "loading_speed_m_s": 0.0},
        "profile": [{"length_m": 100, "lift_m": lift_m}],
        "idlers": {"carry": {"spacing_m": 1.2, "roll_diameter_m": 0.133, "rolls": 3,
                             "trough_deg": 35, "cema_class": "C"},
                   "return": {"spacing_m": 3.0, "roll_diameter_m": 0.133, "rolls": 1,
                              "cema_class": "C"}},
        "drives": [{"position": "head", "wrap_deg": 200, "friction": 0.35, "share": 1.0,
                    "pulley_diameter_m": 0.63, "inertia_kg_m2": 20}],
        "takeup": takeup,
        "brakes": [{"position": "head", "force_kn": brake_kn, "delay_s": 0.2, "ramp_s": 0.3}],
        "holdback": False, "sag_limit_pct": {"carry": 1.5, "return": 3.0},
    }
    d.update(over)
    return Conveyor.model_validate(d)


def _note(conv: Conveyor) -> str:
    st = solve_steady(conv, model="din", n_elements=40)
    return auto_sizes(conv, BRAKE_STOP, model="din", steady=st)["brake_note"]


FIXED_LOW = {"type": "fixed", "position": "tail", "pretension_kn": 6.0}


def test_a_pulley_that_passes_nothing_is_said_so_with_the_take_up_that_holds():
    note = _note(_conv(FIXED_LOW, 5.0))
    assert "passes no brake force in the stop" in note, note
    assert "slides on it at any brake force" in note
    assert "passes at most 0 kN" not in note and "kN given" not in note
    # its slack side at or below zero unbraked: a grip of 0 against its own shell's need
    assert float(re.search(r"already falls to (-?[\d.]+) kN", note).group(1)) <= 0.0
    assert "a grip of 0 kN against the" in note
    # no 'a force within it' (there is none) and no counterweight for a screw take-up
    assert "a force within it" not in note and "heavier take-up" not in note
    assert "a higher take-up pretension (takeup.pretension_kn)" in note
    # the pretension named is the capstan's: 1 % above it the pulley passes the 5 kN
    need = float(re.search(r"a take-up pretension of ([\d.]+) kN", note).group(1))
    assert need > 6.0
    assert _note(_conv({**FIXED_LOW, "pretension_kn": 1.01 * need}, 5.0)) == ""
    assert "beyond the grip" in _note(_conv({**FIXED_LOW, "pretension_kn": 0.97 * need}, 5.0))


def test_a_force_beyond_the_grip_is_not_called_given_and_names_its_field():
    """A force in the file is the file's or an auto size written in (the design's, or a run
    below full load sized at full load too): the note names the field and leaves which to
    brake_governed_by."""
    gravity = {"type": "gravity", "position": "tail", "mass_kg": "auto", "travel_m": 2}
    note = _note(_conv(gravity, 30.0, lift_m=-15.0,
                       brakes=[{"position": "tail", "force_kn": 30.0, "delay_s": 0.2,
                                "ramp_s": 0.3}]))
    grip = float(re.search(r"passes at most ([\d.]+) kN", note).group(1))
    assert 0.0 < grip < 30.0, note
    assert "against the 30 kN set (brakes.0.force_kn)" in note
    assert "given (brakes" not in note and "as brake_governed_by says" in note
    assert "a force within it, a heavier take-up" in note  # a counterweight here


def test_a_holding_brake_beyond_the_grip_on_a_screw_take_up_names_its_pretension():
    note = _note(_conv({"type": "fixed", "position": "tail", "pretension_kn": "auto"}, "auto",
                       lift_m=-15.0))
    assert "beyond the grip" in note, note
    assert "heavier take-up" not in note
    said = re.search(r"a higher take-up pretension \(takeup\.pretension_kn, ([\d.]+) kN by that "
                     r"bound\)", note)
    assert said, note
    # the pretension named, followed, lets the pulley pass the holding force in the stop
    after = _note(_conv({"type": "fixed", "position": "tail",
                         "pretension_kn": float(said.group(1))}, "auto", lift_m=-15.0))
    assert "beyond the grip" not in after, after


def test_a_rest_state_beyond_the_grip_names_the_lever_of_its_take_up():
    """Euler-Eytelwein at rest (model._rest_grip): the slack-side tension that holds, and a
    heavier take-up only where there is a counterweight."""
    from beltstudy.engine.dynamics.model import _rest_grip

    pulley = SimpleNamespace(element=3, friction=0.35, wrap_deg=220.0, where="head")
    loop = SimpleNamespace(pulleys=[pulley])
    slack = 20e3
    held = 1.1 * slack * math.expm1(0.35 * math.radians(220.0))
    T = np.array([0.0, 0.0, slack + held, slack, 0.0])
    fixed = SimpleNamespace(takeup=SimpleNamespace(type="fixed"))
    gravity = SimpleNamespace(takeup=SimpleNamespace(type="gravity"))
    w_fixed = _rest_grip(loop, 3, T, fixed)[0]
    w_gravity = _rest_grip(loop, 3, T, gravity)[0]
    assert f"slack-side tension of {1.1 * slack / 1e3:.4g} kN (a higher take-up pretension " \
        "(takeup.pretension_kn))" in w_fixed, w_fixed
    assert "heavier" not in w_fixed
    assert "(a heavier take-up)" in w_gravity
