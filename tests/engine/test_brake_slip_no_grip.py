"""A drive that slides in a brake stop after its brakes reached full force was offered 'less
brake force on this one (now 20 kN; a given force_kn of at least 9.81 kN, which with the
others holds the loaded belt at rest)' beside the design note that its pulley passes no brake
force at all in the stop (the undamped bound): a 100 m belt lifting 15 m on a 6 kN fixed
take-up. With 9.81 kN, the holding force, the run still slides, so that lever was wrong. The
slip's words now offer less force only where the holding force fits within the pulley's
grip (simulate.py _brake_past_full, System.brake_grip)."""
from __future__ import annotations

import numpy as np

from beltstudy.engine.checks import HOLD_MARGIN
from beltstudy.engine.conveyor import Scenario
from beltstudy.engine.dynamics import DynamicsOptions, build_system
from beltstudy.engine.dynamics.simulate import _brake_past_full
from beltstudy.engine.run import run_one
from beltstudy.engine.statics import solve_steady, up3
from tests.engine.test_brake_grip_words import FIXED_LOW, _conv


# the 100 m, 15 m lift belt of the grip note's tests, its 6 kN fixed take-up at the tail
def _lift(brake_kn: float):
    return _conv(FIXED_LOW, brake_kn)


BRAKE = Scenario(elements=80, stop={"mode": "brake", "time_s": 1.0})
PAST_FULL = "the belt still slid after the brakes on this pulley reached full force"


def _slid(brake_kn: float) -> str:
    return run_one(_lift(brake_kn), BRAKE, model="din").summary["message"]


def test_no_less_force_where_the_pulley_passes_none():
    msg = _slid(20.0)
    assert "passes no brake force in the stop" in msg, msg  # the design note's bound
    assert PAST_FULL in msg, msg
    assert "or less brake force on this one" not in msg, msg
    assert ("not less force on this one: by the stop's undamped bound its pulley passes no "
            "brake force at all") in msg, msg
    # the lever left out would not have worked: at the holding force the belt still slides
    conv = _lift(20.0)
    steady = solve_steady(conv, model="din", n_elements=80)
    pull_kn = float(np.sum(build_system(conv, BRAKE, steady, DynamicsOptions())
                           .model.nodes.gravity)) / 1e3
    hold_kn = up3(HOLD_MARGIN * pull_kn)
    assert 9.0 < hold_kn < 11.0  # 1.2 x g x 400 / (3.6 x 2) kg/m x 15 m = 9.81 kN, by hand
    assert "slipped on its pulley during the stop" in _slid(hold_kn)


def test_less_force_offered_only_down_to_what_the_grip_passes():
    conv = _lift(20.0)
    steady = solve_steady(conv, model="din", n_elements=80)
    system = build_system(conv, BRAKE, steady, DynamicsOptions())
    floor_kn = HOLD_MARGIN * float(np.sum(system.model.nodes.gravity)) / 1e3
    t_late = system.stop_command_s + 60.0
    system.brake_grip = lambda node: 0.5 * floor_kn * 1e3  # a grip below the holding force
    levers, _why = _brake_past_full(system, 0, t_late)
    assert "or less brake force" not in levers, levers
    assert (f"passes at most {0.5 * floor_kn:.3g} kN, below the {up3(floor_kn):g} kN that "
            "with the others holds the loaded belt at rest") in levers, levers
    system.brake_grip = lambda node: 1.5 * floor_kn * 1e3  # room above it: less is a lever
    levers, _why = _brake_past_full(system, 0, t_late)
    assert f"a given force_kn of at least {up3(floor_kn):g} kN" in levers, levers
    system.brake_grip = None  # not known: offered as before
    levers, _why = _brake_past_full(system, 0, t_late)
    assert f"a given force_kn of at least {up3(floor_kn):g} kN" in levers, levers


def test_a_brake_that_holds_with_the_others_says_their_sum_is_the_holding_force():
    """A 1.8 km decline's head and tail brakes of 122.6 kN each, together 1.2 x its net gravity
    pull of 204.4 kN, were told 'its 122.6 kN is what holds the loaded belt at rest, 1.2 x its
    net gravity pull': that is their sum, not this brake's own force. Two brakes here, head and
    tail, each half the holding size: the head's words name both forces."""
    conv = _lift(20.0)
    steady = solve_steady(conv, model="din", n_elements=80)
    pull_kn = float(np.sum(build_system(conv, BRAKE, steady, DynamicsOptions())
                           .model.nodes.gravity)) / 1e3
    half = up3(HOLD_MARGIN * pull_kn) / 2.0
    two = conv.model_copy(update={"brakes": [
        conv.brakes[0].model_copy(update={"force_kn": half}),
        conv.brakes[0].model_copy(update={"position": "tail", "force_kn": half})]})
    steady = solve_steady(two, model="din", n_elements=80)
    system = build_system(two, BRAKE, steady, DynamicsOptions())
    system.brake_grip = None
    levers, _why = _brake_past_full(system, 0, system.stop_command_s + 60.0)
    assert (f"(not less force on this one: its {half:.4g} kN with the others' {half:.4g} kN "
            f"is what holds the loaded belt at rest, {HOLD_MARGIN:g} x its net gravity pull)"
            ) in levers, levers
