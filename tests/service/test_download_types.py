"""A Parquet download of a study's runs keeps the stored column types: a yes/no column
(``curve{k}_liftoff``, ``hcurve{k}_ok``, ``pulley{j}_diameter_min_ok``) that no run of the
study fills is still boolean, text is ``string``, as in ``runs/part-*.parquet``, so downloads
of two studies read and concatenate as one table.

In-process (TestClient without the lifespan), on a study run in this process.
"""

from __future__ import annotations

import io

import pyarrow.parquet as pq
from fastapi.testclient import TestClient

from beltstudy.service.api.app import create_app


def test_a_runs_download_has_the_stored_schema(data_dir, make_settings, make_study,
                                               finished_study):
    sid = finished_study(data_dir, make_study("types"))
    stored = pq.read_schema(next((data_dir / "studies" / sid / "runs").glob("part-*.parquet")))
    # the tiny conveyor has no vertical curve: its curve verdicts are empty in every row
    assert stored.field("curve1_liftoff").type == "bool"
    client = TestClient(create_app(make_settings(data_dir)), raise_server_exceptions=False)
    for query in ("format=parquet", "format=parquet&sort=-power_kw&status=ok",
                  "format=parquet&columns=run_id,curve1_liftoff,hcurve1_ok,power_kw"):
        r = client.get(f"/studies/{sid}/runs?{query}")
        assert r.status_code == 200, (query, r.text[:200])
        got = pq.read_table(io.BytesIO(r.content)).schema
        wrong = [(f.name, str(f.type), str(stored.field(f.name).type)) for f in got
                 if f.type != stored.field(f.name).type]
        assert not wrong, (query, wrong[:8])


def test_beltstudy_results_from_the_local_store_has_the_stored_schema(
    monkeypatch, data_dir, make_study, finished_study, tmp_path
):
    """``beltstudy results ID -o runs.parquet`` with no service answering reads the store and
    writes the same types as the stored parts."""
    from beltstudy.service.cli import main, study
    from beltstudy.service.cli.demo import free_port

    monkeypatch.delenv("BELTSTUDY_URL", raising=False)
    monkeypatch.setattr(study, "DEFAULT_URL", f"http://127.0.0.1:{free_port()}")
    monkeypatch.setenv("BELTSTUDY_DATA_DIR", str(data_dir))
    sid = finished_study(data_dir, make_study("types-cli"))
    stored = pq.read_schema(next((data_dir / "studies" / sid / "runs").glob("part-*.parquet")))
    out = tmp_path / "runs.parquet"
    assert main(["results", sid, "-o", str(out)]) == 0
    got = pq.read_schema(out)
    wrong = [(f.name, str(f.type), str(stored.field(f.name).type)) for f in got
             if f.type != stored.field(f.name).type]
    assert not wrong, wrong[:8]
