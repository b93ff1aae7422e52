"""A grip-held auto brake told a brake on another pulley: the figure makes up the whole.

A 3 km, -150 m regenerating decline's tail brake is held to its pulley's grip (372.9 kN)
below what the stop time asks. A brake on the head drive's shaft changes the tail pulley's
stop tensions, and the auto brake is sized again beside it. The note offered the head brake
the shortfall beside the grip size (103.3 kN for an 8 s stop); given, the tail brake fell to
328.5 kN, the stop missed again and the note asked for 44.47 kN more. The figure is now the
least that makes up the whole with the auto brake sized again beside it, rounded up, and
where the pulley cannot pass that, the note says so with both figures.
"""
from __future__ import annotations

import re

import pytest

from beltstudy.engine.conveyor import Scenario, parse_conveyor
from beltstudy.engine.run import run_one
from tests.engine.integration.test_brake_grip_fronts import DECLINE


def _run(stop_s: float, brakes=None):
    conv = parse_conveyor({**DECLINE, "brakes": brakes or DECLINE["brakes"]})
    scn = Scenario(start={"control": "s-curve", "time_s": 60},
                   stop={"mode": "brake", "time_s": stop_s})
    return run_one(conv, scn, model="din").summary


def test_the_brake_offered_on_another_pulley_meets_the_stop_when_given():
    s = _run(9.0)
    assert s["brake_governed_by"] == "grip"
    msg = s["message"]
    need = float(re.search(r"not by the stop time 9 s \(which needs ([\d.]+) kN\)", msg)[1])
    said = re.search(r"a brake on drive 1's shaft \(head\) of ([\d.]+) kN beside these \(its "
                     r"pulley passes up to ([\d.]+) kN; the auto brakes then ([\d.]+) kN, "
                     r"sized again within their grip beside it\)", msg)
    assert said, msg
    head, passes, auto = (float(x) for x in said.groups())
    assert head <= passes
    assert head + auto == pytest.approx(need, rel=1e-3)
    assert head > need - s["brake_force_kn"]  # more than the shortfall beside the grip size
    # followed: the auto brake is sized by the stop time beside it, and the whole is met
    after = _run(9.0, [*DECLINE["brakes"], {"drive": 1, "force_kn": head,
                                               "delay_s": 0.5, "ramp_s": 1.0}])
    assert after["brake_governed_by"] == "stop_time+given", after["brake_governed_by"]
    # the whole the stop time asks (the note prints it to 4 figures)
    assert after["brake_force_kn"] == pytest.approx(need, abs=0.05)
    assert after["brake_force_kn"] - head == pytest.approx(auto, rel=1e-3)


def test_a_pulley_that_cannot_pass_the_whole_is_named_with_both_figures():
    s = _run(8.0)
    msg = s["message"]
    said = re.search(r"not by a brake on another pulley alone: a brake on drive 1's shaft "
                     r"\(head\) would need ([\d.]+) kN beside the auto brakes, sized again "
                     r"within their grip beside it, and its pulley passes at most ([\d.]+) kN",
                     msg)
    assert said, msg
    need, passes = float(said[1]), float(said[2])
    assert need > passes
    assert "beside these (its pulley passes" not in msg
