"""A study writes its design's auto sizes into the conveyor each run gets, and its row says
what set them (``brake_governed_by`` from the design). The run's message must say the same:
a probe study of a 600 m decline (brake force 49.05 kN, set by holding) gave rows reading
brake_governed_by 'holding' whose message said the missed brake stop (15.8 s against 10 s)
was 'sized by it as a rigid body' and asked for a 6.31 s stop.time_s, where ``beltstudy
simulate`` of the same run says 'set by holding'."""

from __future__ import annotations

from beltstudy.engine import __version__
from beltstudy.service.dask.tasks import run_spec, run_specs
from beltstudy.service.grid.expand import RunSpec
from tests.conftest import incline300_dict

# incline300's auto head brake asked for a 2 s stop holds the loaded belt instead:
# 1.2 x 27.78 kg/m x 9.81 x 15 m = 4.905 kN; its pulley grips less in the stop, so the stop
# takes over 3 s (tests/engine/test_missed_brake_stop.py)
CONVEYOR = incline300_dict(brakes=[{"position": "head", "force_kn": 4.905, "delay_s": 0.5}],
                           takeup={"type": "gravity", "position": "tail", "mass_kg": 1363.7})


def _spec(run_id: str, stop_s: float) -> RunSpec:
    return RunSpec(run_id=run_id, axes={}, conveyor=CONVEYOR,
                   scenario={"elements": 60, "run_s": 20,
                             "stop": {"mode": "brake", "time_s": stop_s}},
                   model="din", params={}, dynamics=True, engine_version=__version__,
                   design={"brake_governed_by": "holding"})


def _said_holding(row: dict) -> None:
    assert row["status"] == "warning", row["message"]
    assert row["brake_governed_by"] == "holding"
    assert "brake stop missed its stop.time_s" in row["message"], row["message"]
    assert "(set by holding:" in row["message"]
    assert "sized by it as a rigid body" not in row["message"]


def test_a_run_alone_says_the_designs_reason_for_its_brake():
    row, _ = run_spec(_spec("a" * 16, 2.0))
    _said_holding(row)


def test_runs_sharing_a_start_say_the_designs_reason_for_their_brake():
    rows = [row for row, _ in run_specs([_spec("b" * 16, 2.0), _spec("c" * 16, 1.5)])]
    for row in rows:
        _said_holding(row)
