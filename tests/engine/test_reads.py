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


def test_a_brake_stop_reads_its_stop_time_only_to_size_an_auto_brake():
    """The stop time of a brake stop sizes auto brakes and nothing else: with every brake's
    force given it is unread (a 600 m conveyor's brake stop at 10 and 20 s gave identical
    summaries); with an auto brake it is read."""
    scn = _scenario(stop={"mode": "brake", "time_s": 12})
    assert unread_fields(scn, dynamics=True) == ()
    assert unread_fields(scn, dynamics=True, brakes_given=True) == ("stop.time_s",)
    assert scenario_as_read(scn, dynamics=True, brakes_given=True)["stop"] == {
        "mode": "brake", "time_s": DEFAULT["stop"]["time_s"]}
    ctl = _scenario(stop={"mode": "controlled", "time_s": 12})
    assert unread_fields(ctl, dynamics=True, brakes_given=True) == ()


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


# --------------------------------------------------------------------------------------------
# the conveyor as a run reads it: the law of a brake that never acts


def _brake_conveyor(hold: bool) -> dict:
    return {"name": "c", "brakes": [
        {"position": "head", "force_kn": 120.0, "delay_s": 0.5, "ramp_s": 1.0,
         "force_curve": None, "hold": hold}]}


def test_a_brake_that_never_acts_is_not_read():
    from beltstudy.engine.reads import UNREAD, conveyor_as_read, unread_brakes

    coast, brake = {"stop": {"mode": "coast"}}, {"stop": {"mode": "brake"}}
    controlled = {"stop": {"mode": "controlled"}}
    free, held = _brake_conveyor(False), _brake_conveyor(True)
    # transient: a brake without hold acts only in a brake stop; one with hold is set once
    # the belt has stopped in every mode (it then carries the gravity pull: read)
    assert unread_brakes(free, coast, dynamics=True) == (0,)
    assert unread_brakes(free, controlled, dynamics=True) == (0,)
    assert unread_brakes(free, brake, dynamics=True) == ()
    assert unread_brakes(held, coast, dynamics=True) == ()
    # steady: the statics place the brake, never use its law
    assert unread_brakes(held, brake, dynamics=False) == (0,)
    read = conveyor_as_read(free, coast, dynamics=True)
    assert read["brakes"][0] == {"position": "head", "force_kn": UNREAD, "delay_s": UNREAD,
                                 "ramp_s": UNREAD, "force_curve": UNREAD, "hold": False}
    assert free["brakes"][0]["force_kn"] == 120.0  # not changed in place
    # read in full: the conveyor itself (a key made of it is the key it always was)
    assert conveyor_as_read(held, coast, dynamics=True) is held
    assert conveyor_as_read(free, brake, dynamics=True) is free
