"""A remedy's start time is said rounded up: it is the least the search found, and rounded
to the nearest second it can fall below it. fabric-1km on a 4 105 kg take-up with a 5 s
start slips; the search found a start of 26.4 s, said '26 s', and a start of 26 s still
slipped 1.7 s (0.011 m of belt)."""
from __future__ import annotations

import math
import re

from beltstudy.engine import load_conveyor
from beltstudy.engine.conveyor import Scenario
from beltstudy.engine.run import run_one, said_up
from tests.conftest import CONVEYORS


def test_said_up_never_rounds_below():
    for t in (0.31, 9.99, 10.0, 26.397, 125.0001):
        assert said_up(t) >= t
    assert said_up(26.397) == 27 and said_up(9.91) == 10.0 and said_up(3.21) == 3.3


def test_the_start_the_remedy_says_avoids_the_slip():
    conv = load_conveyor(CONVEYORS / "fabric-1km.yaml")
    conv = conv.model_copy(update={"takeup": conv.takeup.model_copy(update={"mass_kg": 4105})})
    scn = Scenario(start={"time_s": 5}, elements=80)
    s = run_one(conv, scn, model="din", remedy=True).summary
    assert s["drive1_slip_s"] > 0.0
    t = s["slip_free_start_time_s"]
    said = re.search(r"or by a start of ([\d.]+) s", s["message"])
    assert said and float(said.group(1)) == t and t == math.ceil(t)
    again = run_one(conv, scn.model_copy(update={"start": scn.start.model_copy(
        update={"time_s": t})}), model="din").summary
    assert again["drive1_slip_s"] == 0.0, again["message"]
