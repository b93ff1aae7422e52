"""Runs of a study that differ only in their stop share one simulated start in the worker
(beltstudy.service.dask.tasks.run_specs -> beltstudy.engine.run.run_group), and their rows are
those of the runs run alone; the job keeps such runs side by side and in one task."""

from __future__ import annotations

import math

from beltstudy.service.dask.jobs import adjacent_starts
from beltstudy.service.dask.tasks import run_spec, run_specs, start_candidate
from beltstudy.service.door.studyfile import resolve_study

TIMING = {"elapsed_s"}


def _study(make_study):
    """The 60 m example conveyor, dynamic: DIN and Non-Lin x two temperatures x three stops
    (coast, two controlled stop times)."""
    return resolve_study(make_study(
        name="stops", dynamics=True,
        grid={"friction_model": ["din", "nonlin"], "temperature_c": [-10, 20],
              "scenario.stop.mode": ["coast", "controlled"], "stop_time_s": [5, 10]}))


def test_stops_of_one_start_are_grouped_and_give_the_rows_of_their_own_runs(make_study):
    runs = _study(make_study).runs
    keys = {start_candidate(r) for r in runs}
    # one candidate start for DIN, whose law reads no temperature; one per temperature for
    # Non-Lin
    assert len(keys) == 3
    pairs = run_specs(runs, "sid")
    for spec, (row, _result) in zip(runs, pairs, strict=True):
        alone, _ = run_spec(spec, "sid")
        assert set(row) == set(alone)
        for k, v in row.items():
            if k in TIMING:
                continue
            w = alone[k]
            if isinstance(v, float) and math.isnan(v):
                assert isinstance(w, float) and math.isnan(w), k
            else:
                assert v == w, (spec.run_id, k, v, w)


def test_the_job_keeps_the_runs_of_one_start_side_by_side(make_study):
    runs = _study(make_study).runs
    ordered = adjacent_starts(list(reversed(runs)))
    assert sorted(r.run_id for r in ordered) == sorted(r.run_id for r in runs)
    keys = [start_candidate(r) for r in ordered]
    # each candidate's runs form one unbroken stretch
    changes = sum(1 for a, b in zip(keys, keys[1:], strict=False) if a != b)
    assert changes == len(set(keys)) - 1


def test_brake_stops_of_one_start_share_it_though_their_brakes_are_sized_apart(make_study,
                                                                              make_conveyor):
    """A head brake sized for each brake stop's time (force auto): the runs' conveyors differ
    in the brake's force, which the engine reads only after the stop command, so the coast and
    the two braked stops of a temperature are one candidate start, and each row is its run's
    alone."""
    conv = make_conveyor(brakes=[{"position": "head", "force_kn": "auto", "delay_s": 0.2}])
    runs = resolve_study(make_study(
        name="brakes", dynamics=True, conveyor=conv,
        grid={"temperature_c": [-10, 20], "scenario.stop.mode": ["coast", "brake"],
              "stop_time_s": [2, 4]})).runs
    brake_runs = [r for r in runs if r.scenario["stop"]["mode"] == "brake"]
    forces = {r.conveyor["brakes"][0]["force_kn"] for r in brake_runs}
    assert len(forces) == 2  # sized apart for the two stop times
    assert len({start_candidate(r) for r in runs}) == 1  # DIN's law reads no temperature
    for spec, (row, _result) in zip(runs, run_specs(runs, "sid"), strict=True):
        alone, _ = run_spec(spec, "sid")
        for k, v in row.items():
            if k in TIMING:
                continue
            w = alone[k]
            assert (v == w) or (isinstance(v, float) and math.isnan(v) and math.isnan(w)), \
                (spec.run_id, k, v, w)
