"""Restart safety: SIGKILL the service (and its workers) mid-study, start it again on the same
data directory; the study completes with exactly one row per run, equal to an uninterrupted run.
"""

from __future__ import annotations

import json

import pandas as pd
import pytest

from beltstudy.service.dask.jobs import study_schema
from beltstudy.service.dask.tasks import run_batch
from beltstudy.service.door.studyfile import resolve_study
from beltstudy.service.store.columns import rows_to_table

pytestmark = pytest.mark.slow


def _uninterrupted(study) -> pd.DataFrame:
    """The same runs one after another in this process (no Dask, no store)."""
    out = run_batch(study.id, study.runs)
    return rows_to_table(out["rows"], study_schema(study)).to_pandas(), out["timeseries"]


def test_sigkill_mid_study_then_restart_resumes_without_duplicates(
    live_service, make_study, tmp_path
):
    data_dir = tmp_path / "data"

    def body_with(n_temps: int) -> dict:
        body = make_study(
            name="restart",
            dynamics=True,
            grid={
                # models whose laws read every temperature (DIN's reads none: its runs
                # across temperatures are one kernel run, and would end the study at once)
                "friction_model": ["nonlin", "visco"],
                "temperature_c": [round(-40.0 + 80.0 * i / (n_temps - 1), 6)
                                  for i in range(n_temps)],
            },
        )
        body["scenario"] = {**body["scenario"], "elements": 200, "run_s": 30}
        return body

    # size the study from this machine's measured run time: about 4 s of work for each of the
    # two workers, so the kill (at the first stored rows, about a second in) lands mid-study
    probe = resolve_study(body_with(2))
    specs = probe.runs[:2]
    run_batch(probe.id, specs[:1])  # compiled and warm
    per_run_s = max(run_batch(probe.id, specs)["seconds"] / 2, 1e-3)
    n_temps = min(max(int(4.0 * 2 / per_run_s / 2), 20), 400)
    body = body_with(n_temps)

    svc = live_service(data_dir)
    sub, _ = svc.client.submit(body)
    total = sub["total"]
    assert total == 2 * n_temps
    st = svc.wait(sub["id"], until=lambda s: s["done"] >= 1)
    assert st["done"] < total // 2, f"the study is half over before the kill: {st}"
    svc.kill()

    doc = json.loads((data_dir / "studies" / sub["id"] / "study.json").read_text())
    assert doc["state"] == "running"
    done_before = len(pd.read_parquet(data_dir / "studies" / sub["id"] / "runs"))
    assert 0 < done_before < total

    svc = live_service(data_dir)
    st = svc.wait(sub["id"])
    assert st["state"] == "done" and st["done"] == total and st["failed"] == 0
    svc.stop()

    root = data_dir / "studies" / sub["id"]
    runs = pd.read_parquet(root / "runs")
    assert len(runs) == total and runs["run_id"].is_unique
    assert not [p for p in root.rglob(".*")], "temporary files left behind"

    study = resolve_study(body)
    assert study.id == sub["id"]
    ref, ref_ts = _uninterrupted(study)
    cols = [c for c in ref.columns if c != "elapsed_s"]
    got = runs[cols].sort_values("run_id").reset_index(drop=True)
    want = ref[cols].sort_values("run_id").reset_index(drop=True)
    pd.testing.assert_frame_equal(got, want, check_exact=False, rtol=1e-12, atol=0)

    ts = pd.read_parquet(root / "timeseries")
    assert len(ts) == ref_ts.num_rows
    assert (
        ts.groupby("run_id")
        .size()
        .sort_index()
        .equals(ref_ts.to_pandas().groupby("run_id").size().sort_index())
    )
