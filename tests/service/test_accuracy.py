"""A study's accuracy sample (SPEC 7.2 ``accuracy: {sample: 0.05}``): validated at the door,
a seeded sample of the runs, stored as its own table, answered by ``GET
/studies/{id}/accuracy`` and shown in the report as the error of each column.

In-process: runs go through ``run_batch`` (the workers' code) and are stored as the service
stores them; the API is a TestClient without the lifespan (no Dask)."""

from __future__ import annotations

import io
import math

import pandas as pd
import pytest
from fastapi.testclient import TestClient

from beltstudy.service.api.app import create_app
from beltstudy.service.door.studyfile import resolve_study
from beltstudy.service.errors import Invalid
from beltstudy.service.grid.expand import accuracy_sample, study_from_json
from beltstudy.service.store.parquet import Store
from tests.service.conftest import ROOT


def _dynamic(make_study, name: str, **over) -> dict:
    """Four dynamic runs of the 60 m conveyor (two models x two temperatures)."""
    study = make_study(name=name, dynamics=True,
                       grid={"friction_model": ["din", "cema"], "temperature_c": [-10, 20]})
    study.update(over)
    return study


@pytest.mark.parametrize("accuracy,expect", [
    ({"sample": 0}, "accuracy.sample"),
    ({"sample": 1.5}, "accuracy.sample"),
    ({"samples": 0.1}, "accuracy.samples"),
    ({"sample": 0.1, "seed": -1}, "accuracy.seed"),
    (0.05, "accuracy"),
])
def test_a_wrong_accuracy_is_refused_by_name(make_study, accuracy, expect):
    with pytest.raises(Invalid, match=expect.replace(".", r"\.")):
        resolve_study(_dynamic(make_study, "acc-bad", accuracy=accuracy),
                      studies_dir=ROOT / "studies")


def test_a_share_written_alone_is_told_the_block_that_holds_it(make_study):
    """'accuracy: 0.05' said only 'is not of type "object"'."""
    with pytest.raises(Invalid, match=r"^accuracy: 0\.05 is not of type \"object\": write the "
                                      r"share of runs to check as accuracy: \{sample: 0\.05\}"):
        resolve_study(_dynamic(make_study, "acc-bare", accuracy=0.05),
                      studies_dir=ROOT / "studies")


def test_accuracy_needs_the_transient(make_study):
    with pytest.raises(Invalid, match="accuracy: error bars are those of the transient runs"):
        resolve_study(make_study(name="acc-steady", accuracy={"sample": 0.5}),
                      studies_dir=ROOT / "studies")


def test_the_sample_is_seeded_deterministic_and_at_least_one_run():
    ids = [f"{i:016x}" for i in range(200)]
    a = accuracy_sample(ids, 0.05, seed=0)
    assert len(a) == 10 and a == accuracy_sample(list(reversed(ids)), 0.05, seed=0)
    assert accuracy_sample(ids, 0.05, seed=1) != a
    assert len(accuracy_sample(ids[:3], 0.05)) == 1 and accuracy_sample([], 0.5) == set()
    assert accuracy_sample(ids[:3], 1.0) == set(ids[:3])


def test_the_sample_survives_a_restart_and_the_id_changes_with_it(make_study):
    plain = resolve_study(_dynamic(make_study, "acc-id"), studies_dir=ROOT / "studies")
    study = resolve_study(_dynamic(make_study, "acc-id", accuracy={"sample": 0.5, "seed": 3}),
                          studies_dir=ROOT / "studies")
    assert study.id != plain.id and not any(r.check for r in plain.runs)
    checked = sorted(r.run_id for r in study.runs if r.check)
    assert len(checked) == 2
    again = study_from_json(study.to_json(), study.id)
    assert sorted(r.run_id for r in again.runs if r.check) == checked


def test_the_sampled_runs_get_their_error_bars_table_route_and_report(
    data_dir, make_study, make_settings, finished_study
):
    sid = finished_study(data_dir, _dynamic(make_study, "acc-table",
                                            accuracy={"sample": 0.25}))
    store = Store(data_dir)
    acc = store.read_accuracy(sid)
    runs = store.read_runs(sid)
    assert len(acc) == 1 and len(runs) == 4 and acc["run_id"].iloc[0] in set(runs["run_id"])
    # readable with pandas straight from the files
    direct = pd.read_parquet(data_dir / "studies" / sid / "accuracy")
    assert list(direct["run_id"]) == list(acc["run_id"])
    row = acc.iloc[0]
    assert row["accuracy_elements"].count("/") == 2
    for name in ("t_max_dyn_kn", "t_min_dyn_kn", "drive_force_max_kn", "stop_time_s"):
        assert row[f"{name}_err"] >= 0.0, name
    assert math.isnan(row["drive2_force_max_kn_err"])  # one drive
    # a sampled run's message says marginal where a verdict is within its bar; the others'
    # never do (they were not checked)
    unchecked = runs[runs["run_id"] != row["run_id"]]
    assert not unchecked["message"].str.contains("marginal:").any()

    client = TestClient(create_app(make_settings(data_dir)))
    body = client.get(f"/studies/{sid}/accuracy").json()
    assert body["total"] == 1 and body["sample"] == {"sample": 0.25, "seed": 0}
    cols = {c["column"]: c for c in body["columns"]}
    assert cols["t_max_dyn_kn"]["unit"] == "kN" and cols["t_max_dyn_kn"]["runs"] == 1
    assert cols["t_max_dyn_kn"]["err_max"] == pytest.approx(row["t_max_dyn_kn_err"])
    r = client.get(f"/studies/{sid}/accuracy", params={"format": "parquet"})
    assert r.status_code == 200
    assert list(pd.read_parquet(io.BytesIO(r.content))["run_id"]) == list(acc["run_id"])
    report = client.get(f"/studies/{sid}/report").text
    assert "Error of each column" in report and "<code>t_max_dyn_kn</code>" in report


def test_a_study_without_accuracy_has_an_empty_table(data_dir, make_study, make_settings,
                                                      finished_study):
    sid = finished_study(data_dir, _dynamic(make_study, "acc-none"))
    assert len(Store(data_dir).read_accuracy(sid)) == 0
    client = TestClient(create_app(make_settings(data_dir)))
    body = client.get(f"/studies/{sid}/accuracy").json()
    assert body == {"study_id": sid, "state": "done", "sample": None, "total": 0, "columns": [],
                    "runs": []}
    assert "No error bars" in client.get(f"/studies/{sid}/report").text


def test_a_sampled_runs_detail_carries_its_error_bars_for_the_run_page(
    data_dir, make_study, make_settings, finished_study
):
    """The run page (GET /studies/{id}/runs/{run_id}) gave a sampled run's summary row only:
    its error bars, in the study's accuracy table, were not on it. The detail now has
    ``accuracy`` with the run's <figure>_err (the table's value), meshes and methods; a run
    outside the sample has null."""
    sid = finished_study(data_dir, _dynamic(make_study, "acc-detail",
                                            accuracy={"sample": 0.25}))
    store = Store(data_dir)
    acc = store.read_accuracy(sid)
    sampled = acc["run_id"].iloc[0]
    other = next(r for r in store.read_runs(sid)["run_id"] if r != sampled)
    client = TestClient(create_app(make_settings(data_dir)))
    bars = client.get(f"/studies/{sid}/runs/{sampled}").json()["accuracy"]
    assert bars["t_max_dyn_kn_err"] == pytest.approx(acc["t_max_dyn_kn_err"].iloc[0])
    assert bars["accuracy_elements"] == acc["accuracy_elements"].iloc[0]
    assert bars["accuracy_methods"] == acc["accuracy_methods"].iloc[0]
    assert client.get(f"/studies/{sid}/runs/{other}").json()["accuracy"] is None


def test_a_share_in_per_cent_is_told_the_fraction(make_study):
    """'accuracy: {sample: 5}' named the bound only ('less than or equal to 1 (got 5)')."""
    with pytest.raises(Invalid, match=r"accuracy\.sample: .*\(got 5\): a fraction of the runs, "
                                      r"0\.05 if 5 is %"):
        resolve_study(_dynamic(make_study, "acc-pct", accuracy={"sample": 5}),
                      studies_dir=ROOT / "studies")
