"""Answers that never mislead: a study that exists is never a 404 while it runs, a body in
another media type is a 415, empty or unknown query values are a 422 naming the parameter,
HEAD answers wherever GET does.

In-process (TestClient without the lifespan): no Dask cluster starts, so a stored study in
the state ``queued`` stays as it is, with no runs yet, as a study that has just begun.
"""

from __future__ import annotations

import json

import pytest
from fastapi.testclient import TestClient

from beltstudy.service.api.app import create_app
from beltstudy.service.door.studyfile import resolve_study
from beltstudy.service.store.parquet import Store
from beltstudy.service.studies import StudyService

from .conftest import ROOT


@pytest.fixture
def client(data_dir, make_settings):
    return TestClient(create_app(make_settings(data_dir)), raise_server_exceptions=False)


@pytest.fixture
def running(data_dir, make_study):
    """A stored study, queued with no finished run (as mid-study, before the first part)."""
    study = resolve_study(make_study("mid"), studies_dir=ROOT / "studies")
    doc = StudyService._new_doc(study)
    Store(data_dir).create(study.id, {**doc, "state": "running"})
    return study


def _written(data_dir) -> list[str]:
    root = data_dir / "studies"
    return sorted(p.name for p in root.iterdir()) if root.exists() else []


def test_every_route_of_a_running_study_answers_with_its_state(client, running):
    sid, run_id = running.id, running.runs[0].run_id
    paths = [
        f"/studies/{sid}",
        f"/studies/{sid}/runs",
        f"/studies/{sid}/runs?format=csv",
        f"/studies/{sid}/runs?format=parquet",
        f"/studies/{sid}/accuracy",
        f"/studies/{sid}/compare?baseline=din&candidate=cema",
        f"/studies/{sid}/runs/{run_id}/profile",
        f"/studies/{sid}/plots/ratio?format=svg",
        f"/studies/{sid}/plots/power-temperature?format=svg",
        f"/studies/{sid}/report",
        f"/ui/data/studies/{sid}",
    ]
    for path in paths:
        r = client.get(path)
        assert r.status_code == 200, (path, r.status_code, r.text[:200])
    cmp = client.get(f"/studies/{sid}/compare", params={"baseline": "din",
                                                        "candidate": "cema"}).json()
    assert cmp["state"] == "running" and cmp["pairs"] == []
    assert (cmp["done"], cmp["total"], cmp["same_in_all_pairs"]) == (0, 6, {})
    # a steady-only study's default is power alone, before any run has finished too (it was
    # the stop-phase figures as well, which such a study never writes)
    assert cmp["metrics"] == ["power_kw"]
    # a run of the study not finished yet: 409 with the state, never 404
    # (the steady profile above is the run's steady solve, answered before the run ends; the
    # transient figure of this steady study says it has none)
    for path in (f"/studies/{sid}/runs/{run_id}", f"/studies/{sid}/runs/{run_id}/surface"):
        r = client.get(path)
        assert r.status_code == 409, (path, r.status_code)
        assert "not finished yet (the study is running: 0 of 6 runs done)" in r.text
    r = client.get(f"/studies/{sid}/runs/{run_id}")
    assert r.status_code == 409 and r.json()["error"] == "conflict"
    # an id the study does not have is still not found
    assert client.get(f"/studies/{sid}/runs/ffffffffffffffff").status_code == 404


def test_a_dynamic_run_not_finished_has_no_transient_figure_yet(client, data_dir, make_study):
    """The transient figure of a dynamic run still to come is a 409 with the study's state,
    as its row and surface are, not a figure saying the run has no transient."""
    study = resolve_study(make_study("mid-dyn", dynamics=True), studies_dir=ROOT / "studies")
    Store(data_dir).create(study.id, {**StudyService._new_doc(study), "state": "running"})
    r = client.get(f"/studies/{study.id}/runs/{study.runs[0].run_id}/plots/transient")
    assert r.status_code == 409 and "not finished yet (the study is running" in r.text


def test_compare_names_a_model_the_study_does_not_run_even_mid_study(client, running):
    r = client.get(f"/studies/{running.id}/compare", params={"baseline": "din",
                                                             "candidate": "nonlin"})
    assert r.status_code == 422
    # given explicitly: not said to be the default (test_compare_asked_names)
    assert r.json()["message"] == "candidate: model 'nonlin' is not in this study; it has: " \
        "din, cema: give candidate=NAME from those"
    # with nothing given (the defaults cema and nonlin) the answer says which is the default
    r = client.get(f"/studies/{running.id}/compare")
    assert r.status_code == 422
    assert r.json()["message"].startswith("candidate: model 'nonlin' (the default) is not in")
    r = client.get(f"/studies/{running.id}/compare", params={"baseline": "cmod",
                                                             "candidate": "din"})
    assert r.json()["message"] == "baseline: model 'cmod' is not in this study; it has: " \
        "din, cema: give baseline=NAME from those"


@pytest.mark.parametrize("media", ["text/plain", "application/x-www-form-urlencoded",
                                   "multipart/form-data; boundary=x", None])
def test_a_body_in_another_media_type_is_415(client, data_dir, make_study, media):
    headers = {"content-type": media} if media else {}
    r = client.post("/studies", content=json.dumps(make_study()), headers=headers)
    assert r.status_code == 415, r.text
    body = r.json()
    assert body["error"] == "unsupported_media_type"
    assert "application/json" in body["message"] and "application/yaml" in body["message"]
    assert _written(data_dir) == []


@pytest.mark.parametrize("route", ["/studies", "/calibrations"])
def test_a_compressed_or_non_utf8_body_is_415_naming_the_header(client, data_dir, make_study,
                                                                route):
    """A gzip body (Content-Encoding: gzip) and a UTF-16 one declared as such were a 422
    'body: not UTF-8 text' naming neither header; each is a 415 naming it and the fix."""
    import gzip

    text = json.dumps(make_study())
    r = client.post(route, content=gzip.compress(text.encode()),
                    headers={"content-type": "application/json", "content-encoding": "gzip"})
    assert r.status_code == 415, r.text
    assert r.json()["message"].startswith("Content-Encoding: 'gzip' is not read here; send")
    assert "uncompressed" in r.json()["message"]
    r = client.post(route, content=text.encode("utf-16"),
                    headers={"content-type": "application/json; charset=UTF-16"})
    assert r.status_code == 415, r.text
    assert r.json()["message"].startswith("Content-Type: charset 'utf-16' is not read here")
    assert _written(data_dir) == []
    for fine in ("application/json; charset=utf-8", 'application/json; charset="UTF-8"'):
        # an invalid body: the answer is its 422, past the door
        r = client.post(route, content='{"name": "x"}', headers={"content-type": fine,
                                                                 "content-encoding": "identity"})
        assert r.status_code == 422, r.text


@pytest.mark.parametrize("media", ["application/json; charset=utf-8", "application/yaml",
                                   "text/yaml", "application/x-yaml"])
def test_json_and_yaml_media_types_pass_the_door(client, media):
    # an invalid study: the answer is the study's 422, not a 415
    text = "name: x\n" if "yaml" in media else '{"name": "x"}'
    r = client.post("/studies", content=text, headers={"content-type": media})
    assert r.status_code == 422, r.text


def test_empty_and_unknown_query_values_are_422_naming_the_parameter(client, running):
    sid = running.id
    cases = [
        (f"/studies/{sid}/plots/ratio", {"baseline": ""}, "query.baseline: empty"),
        (f"/studies/{sid}/plots/ratio", {"candidate": " "}, "query.candidate: empty"),
        (f"/studies/{sid}/compare", {"baseline": ""}, "query.baseline: empty"),
        (f"/studies/{sid}/compare", {"metrics": ""}, "query.metrics: empty"),
        (f"/studies/{sid}/runs", {"friction_model": ""}, "query.friction_model: empty"),
        (f"/studies/{sid}/runs", {"colour": "red"}, "query.colour: unknown parameter"),
        (f"/studies/{sid}/plots/ratio", {"baseline": "nope"}, "baseline: unknown model"),
        (f"/studies/{sid}/plots/ratio", {"candidate": "visco"},
         "candidate: model 'visco' is not in this study"),
        ("/models", {"x": "1"}, "query.x: unknown parameter; this route takes: none"),
    ]
    for path, params, message in cases:
        r = client.get(path, params=params)
        assert r.status_code == 422, (path, params, r.text)
        assert r.json()["message"].startswith(message), (path, params, r.json())


def test_head_answers_where_get_does(client, running):
    for path in ("/health", "/models", "/studies", f"/studies/{running.id}",
                 f"/studies/{running.id}/runs?format=csv", "/"):
        get = client.get(path)
        head = client.head(path)
        assert head.status_code == get.status_code == 200, path
        assert head.content == b""
        assert head.headers["content-type"] == get.headers["content-type"]
        assert head.headers["content-length"] == str(len(get.content)), path
    assert client.head("/studies/0123456789abcdef").status_code == 404
    r = client.put("/health")
    assert r.status_code == 405 and r.headers["allow"] == "GET, HEAD"



@pytest.mark.parametrize("query", ["limit=1&limit=2", "format=parquet&format=csv",
                                   "baseline=din&baseline=cema&candidate=cema"])
def test_a_query_parameter_given_twice_is_a_422_naming_it(client, running, query):
    """The last value won silently before; a list the route reads whole (filter) may repeat."""
    key = query.split("=")[0]
    for path in ("runs", "compare"):
        r = client.get(f"/studies/{running.id}/{path}?{query}")
        assert r.status_code == 422
        assert r.json() == {"error": "invalid",
                            "message": f"query: '{key}' given twice; give each parameter once"}
    r = client.get(f"/studies/{running.id}/runs?filter=load=full&filter=friction_model=din")
    assert r.status_code != 422 or "given twice" not in r.text
