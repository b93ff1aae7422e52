"""Run tables straight from the engine's arrays, and the surface stored only on request.

In-process: runs go through ``beltstudy.service.dask.tasks.run_batch`` (the workers' code) and are stored
as the service stores them; the API is a TestClient without the lifespan (no Dask). The same
with a real uvicorn server and LocalCluster is in ``test_service_live.py``.
"""

from __future__ import annotations

import io

import numpy as np
import pandas as pd
import pyarrow as pa
import pytest
from fastapi.testclient import TestClient

from beltstudy.engine.conveyor import parse_conveyor, parse_scenario
from beltstudy.engine.run import run_one
from beltstudy.service.api.app import create_app
from beltstudy.service.dask.tasks import surface_table, timeseries_table
from beltstudy.service.door.studyfile import resolve_study
from beltstudy.service.examples import TINY_CONVEYOR, TINY_SCENARIO
from beltstudy.service.store.columns import MAX_DRIVES, SURFACE_COLUMNS, TIMESERIES_COLUMNS
from beltstudy.service.store.parquet import Store
from beltstudy.service.studies import StudyService


def _dynamic(make_study, name: str, **over) -> dict:
    """Four dynamic runs of the 60 m conveyor (two models x two temperatures)."""
    study = make_study(name=name, dynamics=True,
                       grid={"friction_model": ["din", "cema"], "temperature_c": [-10, 20]})
    study.update(over)
    return study


def test_worker_tables_hold_the_values_of_the_run_result():
    result = run_one(parse_conveyor(TINY_CONVEYOR), parse_scenario(TINY_SCENARIO), model="din")
    ts = timeseries_table("r1", result)
    sf = surface_table("r1", result)
    frame = result.timeseries  # built from the same arrays on first access
    assert ts.num_rows == len(frame) > 10
    assert ts.column("run_id").to_pylist() == ["r1"] * len(frame)
    for col in TIMESERIES_COLUMNS:
        if col in frame:
            np.testing.assert_array_equal(ts.column(col).to_numpy(), frame[col].to_numpy())
        else:  # a drive the conveyor does not have
            assert ts.column(col).null_count == ts.num_rows
    assert "f_drive1_kn" in frame and "f_drive2_kn" not in frame and MAX_DRIVES >= 2
    surface = result.surface
    assert sf.num_rows == len(surface) > 100
    assert sf.schema.field("tension_kn").type == pa.float32()
    for col in SURFACE_COLUMNS:
        np.testing.assert_array_equal(sf.column(col).to_numpy(),
                                      surface[col].to_numpy().astype(np.float32))
    # the surface is time-major: every sampled spring at each sampled time
    n_t = surface["t_s"].nunique()
    assert len(surface) == n_t * surface["s_m"].nunique()
    # the lazily built tables are the engine's: the profile carries the transient envelope
    assert (result.profile["t_max_dyn_kn"] >= result.profile["tension_kn"] - 1e-9).all()
    steady = run_one(parse_conveyor(TINY_CONVEYOR), parse_scenario(TINY_SCENARIO), model="din",
                     dynamics=False)
    assert timeseries_table("r2", steady) is None and surface_table("r2", steady) is None


def test_surface_option_is_false_by_default_and_changes_the_study_not_its_runs(make_study):
    plain = resolve_study(_dynamic(make_study, "s"))
    kept = resolve_study(_dynamic(make_study, "s", surface=True))
    assert plain.surface is False and kept.surface is True
    assert plain.to_json()["surface"] is False and kept.to_json()["surface"] is True
    assert plain.id != kept.id  # two studies ...
    assert [r.run_id for r in plain.runs] == [r.run_id for r in kept.runs]  # ... same runs


def test_a_steady_study_asking_for_surfaces_is_refused(make_study):
    """``surface: true`` with ``dynamics: false`` was accepted and stored nothing (a steady run
    has no transient), a second study id for the same runs; it is refused as ``accuracy`` is
    there, naming the field and the way out."""
    from beltstudy.service.errors import Invalid

    with pytest.raises(Invalid, match=r"^surface: the tension and velocity surface is that of "
                                      r"the transient runs; this study has dynamics: false.*"
                                      r"set dynamics: true or remove surface"):
        resolve_study(make_study("steady-surface", dynamics=False, surface=True))
    assert resolve_study(make_study("steady", dynamics=False, surface=False)).surface is False


def test_a_study_stores_surfaces_only_when_asked_and_recomputes_the_same(
    data_dir, make_study, make_settings, finished_study
):
    plain = finished_study(data_dir, _dynamic(make_study, "surface-off"))
    kept = finished_study(data_dir, _dynamic(make_study, "surface-on", surface=True))
    store = Store(data_dir)
    assert store.parts(plain, "surface") == []
    assert store.parts(plain, "timeseries") and store.parts(kept, "surface")
    stored_all = store.read_surface(kept)
    run_ids = sorted(store.read_runs(plain)["run_id"])
    assert run_ids == sorted(store.read_runs(kept)["run_id"]) == sorted(set(stored_all["run_id"]))

    service = StudyService(make_settings(data_dir))
    for run_id in run_ids:
        stored, source = service.run_surface(kept, run_id)
        assert source == "stored" and len(stored) > 100
        again, source = service.run_surface(plain, run_id)
        assert source == "recomputed"
        pd.testing.assert_frame_equal(again.reset_index(drop=True),
                                      stored.reset_index(drop=True), check_exact=True)

    client = TestClient(create_app(make_settings(data_dir)))
    run_id = run_ids[0]
    r = client.get(f"/studies/{plain}/runs/{run_id}/surface")
    assert r.headers["x-beltstudy-surface"] == "recomputed"  # JSON too, as the formats
    body = r.json()
    stored = stored_all[stored_all["run_id"] == run_id].reset_index(drop=True)
    assert body["source"] == "recomputed" and body["rows"] == len(stored)
    assert list(body["surface"]) == list(SURFACE_COLUMNS)
    np.testing.assert_array_equal(np.array(body["surface"]["tension_kn"], dtype=np.float32),
                                  stored["tension_kn"].to_numpy())
    r = client.get(f"/studies/{plain}/runs/{run_id}/surface", params={"format": "parquet"})
    assert r.status_code == 200 and r.headers["x-beltstudy-surface"] == "recomputed"
    pd.testing.assert_frame_equal(pd.read_parquet(io.BytesIO(r.content)), stored)
    r = client.get(f"/studies/{kept}/runs/{run_id}/surface", params={"format": "csv"})
    assert r.headers["x-beltstudy-surface"] == "stored"
    assert len(pd.read_csv(io.StringIO(r.text))) == len(stored)
    # the run page's figure draws the recomputed surface
    r = client.get(f"/studies/{plain}/runs/{run_id}/plots/transient")
    assert r.status_code == 200 and r.content.startswith(b"\x89PNG")
    assert store.parts(plain, "surface") == []  # nothing was written on the way


@pytest.mark.parametrize("path", ["ffffffffffffffff", "not-a-run"])
def test_surface_of_an_unknown_run_is_404(data_dir, make_study, make_settings, finished_study,
                                          path):
    sid = finished_study(data_dir, _dynamic(make_study, "surface-404"))
    client = TestClient(create_app(make_settings(data_dir)))
    r = client.get(f"/studies/{sid}/runs/{path}/surface")
    assert r.status_code == 404 and f"run '{path}'" in r.json()["message"]
    r = client.get(f"/studies/0123456789abcdef/runs/{path}/surface")
    assert r.status_code == 404


def test_a_steady_study_has_no_surface(data_dir, make_study, make_settings, finished_study):
    sid = finished_study(data_dir, make_study("steady-surface"))
    client = TestClient(create_app(make_settings(data_dir)))
    run_id = client.get(f"/studies/{sid}/runs").json()["runs"][0]["run_id"]
    body = client.get(f"/studies/{sid}/runs/{run_id}/surface").json()
    assert body["rows"] == 0 and body["surface"] is None
    # it said only "source: recomputed, rows 0": it says why
    assert body["reason"].startswith("the study runs without dynamics (dynamics: false): a "
                                     "steady run has no transient, so no surface")


def test_a_study_of_another_engine_says_why_its_surface_is_not_recomputed(
    data_dir, make_study, make_settings, finished_study, monkeypatch
):
    """The run page of a study made on the engine before (0.6.14, the service on 0.6.15) said
    'the run has no transient' for runs that had one: the recompute is refused on another
    engine version. It now says so, and what gets the figure. The upgrade is the service's
    engine version moved on after the study finished."""
    from beltstudy import engine

    sid = finished_study(data_dir, _dynamic(make_study, "surface-old-engine"))
    made = Store(data_dir).read(sid)["engine_version"]
    monkeypatch.setattr(engine, "__version__", made + ".1")
    client = TestClient(create_app(make_settings(data_dir)))
    run_id = client.get(f"/studies/{sid}/runs").json()["runs"][0]["run_id"]
    body = client.get(f"/studies/{sid}/runs/{run_id}/surface").json()
    assert body.get("rows") == 0, body
    assert body["reason"].startswith(
        f"the study was run on engine {made} and this service runs engine {made}.1"
    ), body["reason"]
    assert "has no transient" not in body["reason"]
