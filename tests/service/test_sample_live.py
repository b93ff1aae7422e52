"""A sampled study through the real service (uvicorn, LocalCluster of two workers): every
sample point a run, a killed worker losing and duplicating none, and the uncertainty answer
and report section from the stored runs."""

from __future__ import annotations

import os
import signal

import pandas as pd
import pytest

from beltstudy.service.door.studyfile import resolve_study

pytestmark = pytest.mark.slow


def test_sampled_study_survives_a_killed_worker(live_service, make_study):
    svc = live_service()
    # 64 = 16 (2 + 2): Saltelli's design over two inputs, dynamic runs of the 60 m conveyor
    study = make_study(
        name="sampled-kill", dynamics=True, grid={"friction_model": ["din"]},
        sample={"n": 64, "method": "sobol", "seed": 3, "axes": {
            "temperature_c": {"dist": "uniform", "low": -25, "high": 35},
            "models.din.f_carry": {"dist": "lognormal", "median": 0.02, "sigma": 0.25}}})
    study["scenario"] = {**study["scenario"], "elements": 400, "run_s": 30}  # ~0.4 s a run
    expected = {r.run_id for r in resolve_study(study).runs}
    assert len(expected) == 64
    sub, created = svc.client.submit(study)
    assert created and sub["total"] == 64
    st = svc.wait(sub["id"], until=lambda st: st["done"] >= 4)
    assert st["done"] <= 40, "the study is nearly over before the kill; make it longer"
    pids = svc.worker_pids()
    assert len(pids) == 2, pids
    os.kill(pids[0], signal.SIGKILL)
    st = svc.wait(sub["id"], timeout_s=400)
    assert st["state"] == "done" and st["done"] == st["total"] == 64
    runs = pd.read_parquet(svc.data_dir / "studies" / sub["id"] / "runs")
    assert len(runs) == 64 and runs["run_id"].is_unique
    assert set(runs["run_id"]) == expected  # none lost, none extra
    assert (runs["status"] != "failed").all(), runs.loc[runs["status"] == "failed", "message"]
    # the re-submission is the same study: nothing runs again
    again, created = svc.client.submit(study)
    assert not created and again["id"] == sub["id"]

    out = svc.client.uncertainty(sub["id"])
    (cell,) = out["cells"]
    assert cell["runs"] == 64 and cell["points_missing"] == 0
    assert {"t_max_start_kn", "t_max_stop_kn", "stop_time_s", "power_kw"} <= set(cell["figures"])
    sens = cell["sensitivity"]["power_kw"]
    assert sens["method"].startswith("sobol")
    # din has no temperature term: the steady power follows f_carry alone
    assert sens["ranking"][0] == "models.din.f_carry"
    assert {e["limit"] for e in cell["exceedance"]} == {"safety", "slip", "sag", "slack",
                                                       "overload"}
    page = svc.client.report(sub["id"])
    assert "Uncertainty of the sampled inputs" in page and 'alt="ranking"' in page
