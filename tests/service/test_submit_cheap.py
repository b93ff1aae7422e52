"""Cheap refusals first: a resend of a stored study answers without expanding it again, and
expansions run at most ``max_expansions`` at once (then 503 with Retry-After).

In-process (TestClient without the lifespan); the studies are stored as done, so no job and
no Dask cluster starts. Timing is in ``benchmarks/bench_submit.py``; these tests count.
"""

from __future__ import annotations

import json
import time

import pyarrow as pa
from fastapi.testclient import TestClient

from beltstudy.service.api.app import create_app
from beltstudy.service.door.studyfile import resolve_study
from beltstudy.service.store.parquet import Store
from beltstudy.service.studies import StudyService

from .conftest import ROOT


def _store_done(data_dir, data: dict) -> str:
    """Store ``data`` as a finished study: its document and a runs part of each run's id and
    status only (a done study whose rows are missing is run again when submitted)."""
    study = resolve_study(data, studies_dir=ROOT / "studies", max_runs=20_000)
    store = Store(data_dir)
    store.create(study.id, {**StudyService._new_doc(study), "state": "done"})
    ids = [r.run_id for r in study.runs]
    store.write_part(study.id, "runs", "all", pa.table({"run_id": ids,
                                                         "status": ["ok"] * len(ids)}))
    return study.id


def test_resending_a_stored_20000_run_study_does_not_expand_it(data_dir, make_settings,
                                                                make_study, make_conveyor):
    # 20 000 temperatures from -60 to 80 C: the largest study the service takes (sizes
    # given, so no design basis is solved: the test counts expansions, the benchmark times)
    conveyor = make_conveyor(takeup={"mass_kg": 1500})
    conveyor["drives"] = [{**conveyor["drives"][0], "rated_power_kw": 30}]
    data = make_study("big", conveyor=conveyor,
                      grid={"temperature_c": {"start": -60, "stop": 79.993, "step": 0.007}})
    sid = _store_done(data_dir, data)
    service = StudyService(make_settings(data_dir, max_runs=20_000))
    client = TestClient(create_app(service=service, settings=service.settings),
                        raise_server_exceptions=False)
    body = json.dumps(data)
    first = client.post("/studies", content=body, headers={"content-type": "application/json"})
    assert first.status_code == 200 and first.json()["id"] == sid
    assert first.json()["total"] == 20_000
    assert service.expansions == 1  # a body not seen before: expanded, found stored
    for _ in range(3):
        r = client.post("/studies", content=body,
                        headers={"content-type": "application/json"})
        assert r.status_code == 200 and r.json()["id"] == sid
    assert service.expansions == 1  # resends: answered from the body's hash, not expanded
    # the same study as YAML is the same body once parsed: known too
    import yaml

    r = client.post("/studies", content=yaml.safe_dump(data),
                    headers={"content-type": "application/yaml"})
    assert r.status_code == 200 and r.json()["id"] == sid
    assert service.expansions == 1
    # another service process on the same store knows the body too (the index is on disk)
    other = StudyService(make_settings(data_dir, max_runs=20_000))
    status, created = other.submit(json.loads(body))
    assert (status["id"], created, other.expansions) == (sid, False, 0)


def test_a_deleted_study_is_expanded_again(data_dir, make_settings, make_study):
    data = make_study("again")
    sid = _store_done(data_dir, data)
    service = StudyService(make_settings(data_dir))
    assert service.submit(data)[0]["id"] == sid and service.expansions == 1
    assert service.submit(data)[0]["id"] == sid and service.expansions == 1
    Store(data_dir).delete(sid)
    service._closing = True  # a study admitted now is stored but not started (no Dask here)
    status, created = service.submit(data)
    assert created and status["id"] == sid and service.expansions == 2


def test_expansions_beyond_the_bound_get_503_with_retry_after(data_dir, make_settings,
                                                              make_study):
    service = StudyService(make_settings(data_dir, max_expansions=1, expansion_wait_s=0.2))
    client = TestClient(create_app(service=service, settings=service.settings),
                        raise_server_exceptions=False)
    assert service._slots.acquire(timeout=1)  # one expansion running: the bound is reached
    try:
        t0 = time.monotonic()
        r = client.post("/studies", content=json.dumps(make_study("wait")),
                        headers={"content-type": "application/json"})
        waited = time.monotonic() - t0
    finally:
        service._slots.release()
    assert r.status_code == 503 and r.headers["retry-after"] == "1"
    assert "expanding 1 study already (BELTSTUDY_MAX_EXPANSIONS)" in r.json()["message"]
    assert waited >= 0.2 and service.expansions == 0
    assert not (data_dir / "studies").exists() or not any((data_dir / "studies").iterdir())
    assert service._slots.acquire(timeout=0)  # released again: the slot is free
    service._slots.release()
