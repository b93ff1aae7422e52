"""takeup_endstop_gap_m of a carriage that starts at an end of its travel. The travel is laid
out from the rest position (x = 0); where the running stretch needs all of it, the rest
position is the rest end's stop. A 300 kg take-up on the report-failures decline (empty,
slack in the steady state) moved 0.01 m of its travel from that end, hit nothing, and read
gap 0, so the report listed it as 'reached a take-up end stop'."""
from __future__ import annotations

import pytest
import yaml

from beltstudy.engine.conveyor import Scenario, parse_conveyor
from beltstudy.engine.run import run_one
from tests.conftest import ROOT


def test_resting_at_the_end_the_travel_starts_from_is_no_reach():
    doc = yaml.safe_load((ROOT / "studies" / "report-failures.yaml").read_text())
    conv = doc["conveyor"]
    conv["takeup"] = {**conv["takeup"], "mass_kg": 300, "travel_m": 0.5}
    s = run_one(parse_conveyor(conv), Scenario(start={"time_s": 10}, run_s=2, elements=24,
                                               record_dt_s=0.5, load="empty"),
                model="cema").summary
    assert "end stop" not in s["message"] and s["takeup_endstop_speed_m_s"] == 0.0
    # from the rest end (x = 0) the clearance is to the running end: the travel less how far
    # the carriage ran
    assert s["takeup_travel_m"] < 0.5
    assert s["takeup_endstop_gap_m"] == pytest.approx(0.5 - s["takeup_travel_m"], abs=1e-9)
