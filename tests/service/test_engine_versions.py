"""Workers on another engine version than the service's: their runs fail naming the fix, and
``/health`` names them (it said ``ready`` without a word while every run failed)."""

from __future__ import annotations

from beltstudy import engine
from beltstudy.service.dask.executor import Executor
from beltstudy.service.dask.tasks import TINY_CONVEYOR, TINY_SCENARIO, RunSpec, run_spec


def test_a_run_on_another_engine_fails_naming_the_fix():
    spec = RunSpec(run_id="r", axes={}, conveyor=TINY_CONVEYOR, scenario=TINY_SCENARIO,
                   model="din", params={}, dynamics=False, engine_version="0.0.1")
    row, _ = run_spec(spec)
    assert row["status"] == "failed"
    msg = row["message"]
    assert f"this worker runs engine {engine.__version__}, the study needs 0.0.1" in msg
    assert "install the service's beltstudy on every worker" in msg and "DELETE" in msg


def test_health_names_workers_warmed_on_another_engine():
    ex = Executor.__new__(Executor)
    ex.warm = {"tcp://a:1": {"engine_version": engine.__version__, "errors": []}}
    assert ex._other_engines() == ""
    ex.warm["tcp://b:2"] = {"engine_version": "0.0.1", "errors": ["din: ..."]}
    words = ex._other_engines()
    assert "0.0.1 (tcp://b:2)" in words and "tcp://a:1" not in words
    assert f"this service's {engine.__version__}" in words
