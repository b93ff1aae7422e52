"""A start that never reached 99 % of design speed named no lever. For vfd drives the words
now weigh the drives' force limit against Te: a limit not above Te never gets there (larger
motors or a higher torque_limit); else the rigid body's time still needed at the limit, and a
run_s that gives it, which, followed, reaches design speed."""
from __future__ import annotations

import re

from beltstudy.engine.conveyor import Scenario, parse_conveyor
from beltstudy.engine.run import run_one
from tests.conftest import short30_dict

NEVER = "never reached 99 % of design speed"


def _run(torque_limit: float, run_s: float):
    d = short30_dict()
    d["drives"] = [{**d["drives"][0], "torque_limit": torque_limit}]
    scn = Scenario(elements=40, run_s=run_s, start={"control": "linear", "time_s": 2.0})
    return run_one(parse_conveyor(d), scn, model="din").summary


def test_a_force_limit_below_te_never_gets_there():
    s = _run(0.1, 5.0)  # 0.1 x 15 kW / 2 m/s = 0.75 kN, below Te
    assert s["te_kn"] > 0.75
    assert NEVER in s["message"], s["message"]
    assert "is not above the running resistance Te" in s["message"]
    assert "no start reaches design speed" in s["message"]


def test_the_run_s_named_at_the_force_limit_gets_there():
    s = _run(0.3, 3.0)  # 2.25 kN of force against Te of about 1.9 kN: a slow climb
    lim_kn = 0.3 * 15.0 / 2.0
    assert s["te_kn"] < lim_kn
    said = re.search(r"a run_s of at least ([\d.]+) s", s["message"])
    assert NEVER in s["message"] and said, s["message"]
    followed = _run(0.3, float(said.group(1)))
    assert NEVER not in followed["message"], followed["message"]
