"""A study writes its design's auto brake into every run as a number; at a case outside the
design's list the brake can be short of holding that case's loaded belt, and the run said
'holding brakes of at least X kN in all (force_kn: auto sizes them 1.2 x the pull, Y kN)',
though the brake is auto already: sized over the design's cases, it covers this one when the
case is in the design's list. The words now say so where the caller gives the design's
brake_governed_by."""
from __future__ import annotations

import pytest

from beltstudy.engine.conveyor import Scenario, parse_conveyor
from beltstudy.engine.run import run_one
from tests.conftest import incline300_dict

G = 9.81
# the 300 m, 15 m lift incline with a 1 kN brake, as a design sized at another case wrote it
CONV = incline300_dict(brakes=[{"position": "head", "force_kn": 1.0, "delay_s": 0.5}])


@pytest.mark.parametrize("dynamics", [False, True])
def test_a_design_brake_short_at_another_case_names_the_design_list(dynamics):
    scn = Scenario(elements=60, run_s=20)
    pull_kn = G * 200 / (3.6 * 2.0) * 15 / 1e3  # g m'_L H: the belt's own weight cancels
    alone = run_one(parse_conveyor(CONV), scn, model="din", dynamics=dynamics).summary
    assert f"(force_kn: auto sizes them 1.2 x the pull, {1.2 * pull_kn:.4g} kN)" \
        in alone["message"]
    held = run_one(parse_conveyor(CONV), scn, model="din", dynamics=dynamics,
                   governed={"brake_governed_by": "holding @ empty"}).summary
    msg = held["message"]
    assert "holding brakes cannot hold the loaded belt at rest" in msg
    assert "force_kn: auto sizes them" not in msg
    assert ("(the study's auto brakes are sized over its design cases, brake_governed_by "
            "holding @ empty, and this run's case is not one of them: with its load, model "
            "and temperature in the study's design: list they are sized for it too, 1.2 x its "
            f"pull, {1.2 * pull_kn:.4g} kN)") in msg, msg
    # a given brake stays given: the file's own force is the lever
    given = run_one(parse_conveyor(CONV), scn, model="din", dynamics=dynamics,
                    governed={"brake_governed_by": "given"}).summary
    assert "force_kn: auto sizes them" in given["message"]
