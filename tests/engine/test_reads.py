"""What a run reads of its scenario (engine/reads.py)."""

from __future__ import annotations

import copy

from beltstudy.engine.conveyor import Scenario, parse_scenario
from beltstudy.engine.reads import (
    STEADY_FIELDS,
    brake_sizing_stop_time,
    scenario_as_read,
    unread_fields,
)

DEFAULT = Scenario().model_dump(mode="json", by_alias=True)


def _scenario(**fields) -> dict:
    return parse_scenario(fields).model_dump(mode="json", by_alias=True)


def test_a_steady_run_reads_only_the_load_the_temperature_and_the_mesh():
    scn = _scenario(load=0.5, temperature_c=-10, elements=50, run_s=99,
                    stop={"mode": "brake", "time_s": 12}, record_dt_s=0.5)
    assert set(unread_fields(scn, dynamics=False)) == set(DEFAULT) - set(STEADY_FIELDS)
    assert scenario_as_read(scn, dynamics=False) == {
        **DEFAULT, "load": 0.5, "temperature_c": -10.0, "elements": 50}


def test_two_steady_runs_that_differ_only_in_what_they_do_not_read_are_one():
    a = _scenario(load="empty", run_s=5, start={"time_s": 20})
    b = _scenario(load="empty", run_s=50, stop={"mode": "coast", "time_s": 90})
    assert scenario_as_read(a, dynamics=False) == scenario_as_read(b, dynamics=False)
    assert scenario_as_read(a, dynamics=True) != scenario_as_read(b, dynamics=True)


def test_a_coast_stop_does_not_read_its_stop_time():
    scn = _scenario(stop={"mode": "coast", "time_s": 45}, run_s=10)
    before = copy.deepcopy(scn)
    assert unread_fields(scn, dynamics=True) == ("stop.time_s",)
    read = scenario_as_read(scn, dynamics=True)
    assert read == {**scn, "stop": {"mode": "coast", "time_s": DEFAULT["stop"]["time_s"]}}
    assert scn == before  # never changed in place


def test_a_run_that_reads_everything_gets_its_scenario_back():
    for stop in ({"mode": "brake", "time_s": 12}, {"mode": "controlled", "time_s": 40},
                 {"mode": "coast"}):
        scn = _scenario(stop=stop)
        if stop["mode"] != "coast":
            assert unread_fields(scn, dynamics=True) == ()
        assert scenario_as_read(scn, dynamics=True) is scn


def test_brakes_are_sized_for_the_stop_time_only_of_a_brake_stop():
    brake = _scenario(stop={"mode": "brake", "time_s": 12})
    assert brake_sizing_stop_time(brake, dynamics=True) == 12.0
    assert brake_sizing_stop_time(brake, dynamics=False) is None
    for mode in ("coast", "controlled"):
        scn = _scenario(stop={"mode": mode, "time_s": 12})
        assert brake_sizing_stop_time(scn, dynamics=True) is None
