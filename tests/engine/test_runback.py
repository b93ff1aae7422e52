"""A loaded incline that can run back when stopped, with nothing to hold it, gets a note.

The engine computed the holdback torque such a belt needs (CEMA's backstop rule, pull less half
the running resistance) but said nothing when the file had no holdback: the 31 m published
revert conveyor (benchmarks/conveyors/helix-revert-31m.yaml: lift pull 2.14 kN, resistances at
rest 2.13 kN) crept back after a coast stop, still running back at 0.04 m/s five seconds later,
with status ok and not a word. A note, not a warning: the steady run is not where the belt runs
back, and the status of the steady figures stays theirs.
"""

from __future__ import annotations

import pytest

from beltstudy.engine.conveyor import parse_conveyor
from beltstudy.engine.loop import G
from beltstudy.engine.statics import solve_steady
from tests.conftest import hand_conveyor_dict


def _solve(**over):
    d = hand_conveyor_dict()
    d.update(over)
    return solve_steady(parse_conveyor(d), model="din")


def test_an_incline_without_holdback_notes_the_pull_and_the_holdback_it_needs():
    """The hand conveyor lifts 50 kg/m by 50 m: a pull of 50 x 9.81 x 50 = 24.5 kN back,
    against half its running resistance; the warning names both and the holdback torque."""
    res = _solve()
    s = res.summary
    assert 50 * G * 50 == pytest.approx(24525, rel=1e-4)
    assert s["holdback_torque_knm"] > 0
    assert "note: the loaded belt can run back when it stops" in s["message"]
    assert "its lift pulls 24.5 kN back" in s["message"]
    assert f"at least {s['holdback_torque_knm']:.3g} kNm (holdback: true)" in s["message"]
    assert not any("run back" in w for w in res.warnings)  # a note


@pytest.mark.parametrize("over", [
    {"holdback": True},
    {"brakes": [{"position": "head", "force_kn": 40.0, "delay_s": 0.5}]},  # hold: true default
    {"profile": [{"length_m": 1000, "lift_m": 0}]},
    {"profile": [{"length_m": 1000, "lift_m": -20}]},
])
def test_no_run_back_note_where_something_holds_or_nothing_pulls(over):
    assert "run back" not in _solve(**over).summary["message"]


def test_a_brake_that_does_not_hold_at_rest_does_not_hold_the_belt():
    res = _solve(brakes=[{"position": "head", "force_kn": 40.0, "delay_s": 0.5,
                          "hold": False}])
    assert "can run back when it stops" in res.summary["message"]
