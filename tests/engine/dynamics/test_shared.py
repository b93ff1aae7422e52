"""One start, many stops (engine/dynamics/shared.py, issue 29 item 1): runs that differ only in
their stop share one simulated rest, start and run, and each result equals its own separate run
bit for bit: every summary figure (but the wall time), every time-series column, the surface and
the envelopes."""

from __future__ import annotations

import math

import numpy as np
import pytest

from beltstudy.engine.conveyor import Scenario
from beltstudy.engine.dynamics import build_system
from beltstudy.engine.dynamics.shared import group_by_start, simulate_group, start_key
from beltstudy.engine.run import run_group, run_one
from beltstudy.engine.statics import solve_steady
from tests.engine.conftest import hand_conv, hand_drive, steep_incline

TIMING = {"elapsed_s", "wall_s", "kernel_s"}


def assert_same(a, b):
    """Two run results equal bit for bit (NaN equal to NaN), but their timing."""
    sa, sb = a.summary, b.summary
    assert set(sa) == set(sb)
    for k in sa:
        if k in TIMING:
            continue
        va, vb = sa[k], sb[k]
        if isinstance(va, float) and isinstance(vb, float) and math.isnan(va):
            assert math.isnan(vb), k
        else:
            assert va == vb, (k, va, vb)
    if a.transient is None:
        assert b.transient is None
        return
    ta, tb = a.transient.series, b.transient.series
    assert list(ta) == list(tb)
    for k in ta:
        np.testing.assert_array_equal(ta[k], tb[k], err_msg=k)
    for x, y in zip(a.transient.surface_arrays().values(), b.transient.surface_arrays().values(),
                    strict=True):
        np.testing.assert_array_equal(x, y)
    for x, y in zip(a.transient.envelope_kn(), b.transient.envelope_kn(), strict=True):
        np.testing.assert_array_equal(x, y)


STOPS = [{"mode": "coast"}, {"mode": "brake", "time_s": 3}, {"mode": "brake", "time_s": 8},
         {"mode": "controlled", "time_s": 20}]


def test_a_shared_start_gives_each_stop_its_own_runs_results():
    """The 10 % incline with a head brake on a 20 t take-up, whose drive slips in a 6 s start:
    coast, two braked stops (the slip goes on into them) and a controlled stop share one
    start, and each equals its separate run."""
    conv = steep_incline(takeup={"type": "gravity", "position": "tail", "mass_kg": 20000})
    scns = [Scenario(start={"time_s": 6}, run_s=10, stop=s) for s in STOPS]
    grouped = run_group(conv, scns, model="din")
    alone = [run_one(conv, s, model="din") for s in scns]
    assert all(r.summary["drive1_slip_s"] > 0 for r in alone)  # slip in the start
    assert "into the stop" in alone[1].summary["message"]
    assert len({r.summary["stop_time_s"] for r in alone}) >= 3  # coast, brake, controlled differ
    for g, a in zip(grouped, alone, strict=True):
        assert_same(g, a)


def test_runs_that_differ_before_the_stop_are_not_grouped():
    """A start time, a load or a take-up differ before the stop command: their runs get
    separate start keys, and simulate_group refuses to share them."""
    conv = hand_conv(drives=[hand_drive()], brakes=[{"position": "head", "delay_s": 0.2}])
    st = solve_steady(conv, model="din", n_elements=40)
    base = Scenario(start={"time_s": 10}, run_s=5, elements=40)
    systems = [build_system(conv, base, st),
               build_system(conv, Scenario(start={"time_s": 10}, run_s=5, elements=40,
                                           stop={"mode": "brake", "time_s": 5}), st),
               build_system(conv, Scenario(start={"time_s": 12}, run_s=5, elements=40), st)]
    keys = [start_key(s) for s in systems]
    assert keys[0] == keys[1] != keys[2]
    assert group_by_start(systems) == [[0, 1], [2]]
    with pytest.raises(ValueError, match="differ before the stop command"):
        simulate_group(systems)


def test_a_runaway_before_the_stop_ends_every_run_of_the_group_alike():
    """A decline the drive cannot hold runs away before the stop command: the shared stretch
    ends the run, and each stop of the group reports the same runaway as its own run."""
    conv = hand_conv(profile=[{"length_m": 1000, "lift_m": -150}],
                     drives=[hand_drive(torque_limit=0.3, rated_power_kw=20)],
                     takeup={"type": "gravity", "position": "tail", "mass_kg": 20000})
    scns = [Scenario(start={"time_s": 10}, run_s=30, elements=40, stop=s)
            for s in ({"mode": "coast"}, {"mode": "controlled", "time_s": 10})]
    grouped = run_group(conv, scns, model="din")
    alone = [run_one(conv, s, model="din") for s in scns]
    assert "runs away" in alone[0].summary["message"] or "ran away" in alone[0].summary["message"]
    for g, a in zip(grouped, alone, strict=True):
        assert_same(g, a)


def _arrays(record, name=""):
    """Every array of a record tree by its dotted name."""
    if hasattr(record, "_fields"):
        out = {}
        for f in record._fields:
            out.update(_arrays(getattr(record, f), f"{name}.{f}"))
        return out
    return {name: record.copy()} if isinstance(record, np.ndarray) else {}


@pytest.mark.parametrize("model,stop", [("din", {"mode": "brake", "time_s": 3}),
                                        ("nonlin", {"mode": "coast"}),
                                        ("cema", {"mode": "controlled", "time_s": 8})])
def test_the_kernel_only_reads_the_records_a_branch_shares(model, stop):
    """A branch of a shared start copies only the records with *state* arrays (STATEFUL) and
    shares the rest with its siblings: a whole cycle (slip in the start, a brake, a vfd speed
    loop, a gravity take-up) leaves every array of the shared records as it was."""
    from beltstudy.engine.dynamics.shared import STATEFUL
    from beltstudy.engine.dynamics.simulate import fresh_run

    conv = steep_incline(takeup={"type": "gravity", "position": "tail", "mass_kg": 20000})
    scn = Scenario(start={"time_s": 6}, run_s=10, stop=stop, elements=60)
    sysm = build_system(conv, scn, solve_steady(conv, model=model, n_elements=60))
    kr = fresh_run(sysm)
    shared = {rec: _arrays(getattr(kr.model, rec)) for rec in kr.model._fields
              if rec not in STATEFUL}
    assert sum(len(a) for a in shared.values()) > 20
    kr.call()
    assert kr.run["steps"] > 1000
    for rec, arrays in shared.items():
        now = _arrays(getattr(kr.model, rec))
        for name, before in arrays.items():
            np.testing.assert_array_equal(now[name], before, err_msg=f"{rec}{name}")


@pytest.mark.parametrize("model,temperatures,kernel_runs", [
    ("din", (-20.0, 20.0, 35.0), 1 + 2),     # no temperature term: one start, two stops
    ("cema", (5.0, 30.0), 1 + 2),            # Kt is 1 at and above 0 C (CEMA's curve)
    ("cema", (-20.0, 30.0), 2 * (1 + 2)),    # Kt 1.31 against 1: two laws, two starts
])
def test_runs_whose_law_reads_their_temperatures_alike_are_simulated_once(
        monkeypatch, model, temperatures, kernel_runs):
    """Runs of one model whose law reads their temperatures alike build the same model: the
    group simulates each of their stops once (the kernel calls are counted: a shared start is
    one call up to the stop command and one per distinct stop), and each run's result still
    equals its own separate run bit for bit, its own words included (DIN's note that its
    figures are those of 20 C appears at -20 and 35 C alone)."""
    from beltstudy.engine.dynamics.simulate import KernelRun

    conv = steep_incline(takeup={"type": "gravity", "position": "tail", "mass_kg": 20000})
    scns = [Scenario(start={"time_s": 6}, run_s=10, temperature_c=t, elements=60, stop=s)
            for t in temperatures
            for s in ({"mode": "coast"}, {"mode": "controlled", "time_s": 8})]
    alone = [run_one(conv, s, model=model) for s in scns]
    calls = []
    real = KernelRun.call
    monkeypatch.setattr(KernelRun, "call", lambda self, *a: calls.append(1) or real(self, *a))
    grouped = run_group(conv, scns, model=model)
    assert len(calls) == kernel_runs
    for g, a in zip(grouped, alone, strict=True):
        assert_same(g, a)
    if model == "din":
        notes = ["has no temperature term" in r.summary["message"] for r in grouped]
        assert notes == [True, True, False, False, True, True]
