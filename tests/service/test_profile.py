"""The steady profile is stored with the run and read back by the run page and the API;
runs stored before profiles were get it recomputed, the same table."""

from __future__ import annotations

import io
import shutil

import numpy as np
import pandas as pd
from fastapi.testclient import TestClient

from beltstudy.engine.conveyor import parse_conveyor, parse_scenario
from beltstudy.engine.run import run_one
from beltstudy.service.api.app import create_app
from beltstudy.service.dask.tasks import profile_table
from beltstudy.service.examples import TINY_CONVEYOR, TINY_SCENARIO
from beltstudy.service.store.columns import PROFILE_COLUMNS
from beltstudy.service.store.parquet import Store
from beltstudy.service.studies import StudyService


def test_profile_table_holds_the_steady_profile_of_the_result():
    result = run_one(parse_conveyor(TINY_CONVEYOR), parse_scenario(TINY_SCENARIO), model="din")
    table = profile_table("r1", result).to_pandas()
    frame = result.steady.profile()
    assert len(table) == len(frame) == result.steady.loop.n
    assert set(table["run_id"]) == {"r1"}
    pd.testing.assert_frame_equal(table[list(PROFILE_COLUMNS)], frame[list(PROFILE_COLUMNS)])
    assert set(table["strand"]) >= {"carry", "return"}


def test_a_study_stores_each_runs_profile_and_the_run_page_reads_it(
    data_dir, make_study, make_settings, finished_study
):
    sid = finished_study(data_dir, make_study(name="profile", dynamics=True))
    store = Store(data_dir)
    assert store.parts(sid, "profile")
    run_ids = sorted(store.read_runs(sid)["run_id"])
    assert sorted(set(store.read_profile(sid)["run_id"])) == run_ids

    service = StudyService(make_settings(data_dir))
    stored = {}
    for run_id in run_ids:
        df, source = service.run_profile(sid, run_id)
        assert source == "stored" and len(df) > 10
        stored[run_id] = df.reset_index(drop=True)

    client = TestClient(create_app(make_settings(data_dir)))
    run_id = run_ids[0]
    r = client.get(f"/studies/{sid}/runs/{run_id}/profile")
    body = r.json()
    assert r.status_code == 200 and body["source"] == "stored"
    assert body["rows"] == len(stored[run_id]) and list(body["profile"]) == list(PROFILE_COLUMNS)
    np.testing.assert_array_equal(body["profile"]["tension_kn"],
                                  stored[run_id]["tension_kn"].to_numpy())
    r = client.get(f"/studies/{sid}/runs/{run_id}/plots/steady-profile")
    assert r.status_code == 200 and r.content.startswith(b"\x89PNG")

    # a study stored before profiles were: recomputed from the run's inputs, the same table
    shutil.rmtree(store.table_dir(sid, "profile"))
    service = StudyService(make_settings(data_dir))
    for run_id in run_ids:
        df, source = service.run_profile(sid, run_id)
        assert source == "recomputed"
        pd.testing.assert_frame_equal(df.reset_index(drop=True), stored[run_id],
                                      check_exact=True)
    client = TestClient(create_app(make_settings(data_dir)))
    r = client.get(f"/studies/{sid}/runs/{run_id}/profile", params={"format": "parquet"})
    assert r.status_code == 200 and r.headers["x-beltstudy-profile"] == "recomputed"
    assert r.headers["content-disposition"] == (
        f'attachment; filename="{sid}-{run_id}-profile.parquet"')
    pd.testing.assert_frame_equal(pd.read_parquet(io.BytesIO(r.content)), stored[run_id])
    r = client.get(f"/studies/{sid}/runs/{run_id}/plots/steady-profile")
    assert r.status_code == 200 and r.content.startswith(b"\x89PNG")
    assert not store.parts(sid, "profile")  # nothing was written on the way


def test_profile_of_an_unknown_run_is_404(data_dir, make_study, make_settings, finished_study):
    sid = finished_study(data_dir, make_study(name="profile-404"))
    client = TestClient(create_app(make_settings(data_dir)))
    r = client.get(f"/studies/{sid}/runs/ffffffffffffffff/profile")
    assert r.status_code == 404 and "run 'ffffffffffffffff'" in r.json()["message"]
