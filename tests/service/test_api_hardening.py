"""Requests that used to end in a 500: each is now a 4xx naming the field, nothing written;
an unexpected exception is a logged 500 without its text; every error is {error, message}.

In-process (TestClient without the lifespan): no Dask cluster starts.
"""

from __future__ import annotations

import json
import logging
import re

import pytest
import yaml
from fastapi.testclient import TestClient

from beltstudy.service.api.app import create_app


@pytest.fixture
def api(data_dir, make_settings):
    def build(**over):
        return TestClient(create_app(make_settings(data_dir, **over)),
                          raise_server_exceptions=False)

    return build


def _written(data_dir) -> list[str]:
    root = data_dir / "studies"
    return sorted(p.name for p in root.iterdir()) if root.exists() else []


def _study_json(make_study, **over) -> str:
    return json.dumps({**make_study(), **over})


def _study_yaml(make_study, **over) -> str:
    return yaml.safe_dump({**make_study(), **over})


def _json_with(make_study, key: str, raw: str) -> str:
    """A study as JSON text with ``"key": raw`` spliced in (NaN, Infinity, huge integers)."""
    text = json.dumps({**make_study(), key: "__RAW__"})
    return text.replace('"__RAW__"', raw)


BODIES = [
    (
        "NaN in a grid list",
        lambda ms: _json_with(ms, "grid", '{"temperature_c": [0, NaN]}'),
        "json",
        422,
        r"^grid\.temperature_c\.1: NaN is not a number",
    ),
    (
        "Infinity in a model parameter",
        lambda ms: _json_with(ms, "models", '{"din": {"f_carry": Infinity}}'),
        "json",
        422,
        r"^models\.din\.f_carry: infinity is not a finite number",
    ),
    (
        ".nan in a YAML grid list",
        lambda ms: _study_yaml(ms).replace("- -20", "- .nan"),
        "yaml",
        422,
        r"^grid\.temperature_c\.0: NaN is not a number",
    ),
    (
        "a range to .inf",
        lambda ms: _study_yaml(ms, grid={"temperature_c": {"start": 0, "stop": "X", "step": 1}})
        .replace("X", ".inf").replace("'.inf'", ".inf"),
        "yaml",
        422,
        r"^grid\.temperature_c\.stop: infinity is not a finite number",
    ),
    (
        "a range beyond float range",
        lambda ms: _study_json(
            ms, grid={"temperature_c": {"start": -1e308, "stop": 1e308, "step": 1e-300}}
        ),
        "json",
        413,
        r"^grid\.temperature_c: the range has more than 10\^15 \(from -1e\+308 to 1e\+308 in "
        r"steps of 1e-300\) values; the study limit is 20000 runs",
    ),
    (
        "an integer of 5000 digits",
        lambda ms: _json_with(ms, "grid", '{"temperature_c": [' + "1" * 5000 + "]}"),
        "json",
        422,
        r"^grid\.temperature_c\.0: a number with 5000 digits is out of range",
    ),
    (
        "an integer of 5000 digits in YAML",
        lambda ms: _study_yaml(ms, grid={"temperature_c": ["X"]}).replace("X", "1" * 5000)
        .replace("'", ""),
        "yaml",
        422,
        r"^grid\.temperature_c\.0: a number with 5000 digits is out of range",
    ),
    (
        "a NUL byte in the conveyor path",
        lambda ms: _study_json(ms, conveyor="conveyors/slope-5pct.yaml\x00"),
        "json",
        422,
        r"^conveyor: path .* contains control characters",
    ),
    (
        "deeply nested JSON",
        lambda ms: _json_with(ms, "grid", '{"temperature_c": ' + "[" * 50_000 + "]" * 50_000
                              + "}"),
        "json",
        422,
        r"nested deeper than 32 levels",
    ),
    (
        "deeply nested YAML",
        lambda ms: _study_yaml(ms) + "description: " + "[" * 50_000 + "]" * 50_000 + "\n",
        "yaml",
        422,
        r"^body: nested deeper than 32 levels at line \d+, column \d+",
    ),
    (
        "a duplicate YAML key",
        lambda ms: _study_yaml(ms) + "dynamics: true\n",
        "yaml",
        422,
        r"^body: key 'dynamics' appears twice \(lines \d+ and \d+\)",
    ),
    (
        "a duplicate JSON key",
        lambda ms: _study_json(ms)[:-1] + ', "dynamics": true}',
        "json",
        422,
        r"^body: key 'dynamics' appears twice",
    ),
]


@pytest.mark.parametrize(("case", "body", "kind", "status", "message"), BODIES,
                         ids=[b[0] for b in BODIES])
def test_bodies_that_were_server_errors_are_4xx_naming_the_field(
    api, data_dir, make_study, case, body, kind, status, message
):
    client = api()
    ctype = "application/yaml" if kind == "yaml" else "application/json"
    r = client.post("/studies", content=body(make_study).encode(),
                    headers={"Content-Type": ctype})
    assert r.status_code == status, r.text
    out = r.json()
    assert set(out) == {"error", "message"}
    assert re.search(message, out["message"]), out["message"]
    assert _written(data_dir) == []
    assert client.get("/health").status_code == 200  # the connection and the service carry on


def test_compare_metrics_twice_or_an_axis_are_4xx(api, data_dir, finished_study, make_study):
    client = api()
    sid = finished_study(data_dir, make_study())
    base = {"baseline": "din", "candidate": "cema"}
    r = client.get(f"/studies/{sid}/compare", params={**base, "metrics": "power_kw,power_kw"})
    assert r.status_code == 422 and r.json()["message"].startswith(
        "metrics: 'power_kw' is listed twice"), r.text
    r = client.get(f"/studies/{sid}/compare", params={**base, "metrics": "temperature_c"})
    assert r.status_code == 422 and r.json()["message"].startswith(
        "metrics: 'temperature_c' is an axis of this study"), r.text
    ok = client.get(f"/studies/{sid}/compare", params={**base, "metrics": "power_kw,te_kn"})
    assert ok.status_code == 200 and ok.json()["metrics"] == ["power_kw", "te_kn"]


def test_an_unexpected_exception_is_a_generic_logged_500(api, caplog):
    client = api()

    @client.app.get("/boom")
    def boom():
        raise RuntimeError("secret internal detail")

    with caplog.at_level(logging.ERROR, logger="beltstudy.api"):
        r = client.get("/boom")
    assert r.status_code == 500
    body = r.json()
    assert body["error"] == "internal" and "secret" not in r.text
    ref = re.search(r"reference ([0-9a-f]{12})", body["message"]).group(1)
    logged = [rec for rec in caplog.records if ref in rec.getMessage()]
    assert logged and "secret internal detail" in str(logged[0].exc_info[1])
    assert client.get("/health").status_code == 200


def test_unknown_routes_and_methods_are_json_with_allow(api):
    client = api()
    r = client.get("/nowhere")
    assert r.status_code == 404 and r.json() == {
        "error": "not_found", "message": "no route GET /nowhere"}
    r = client.request("OPTIONS", "/studies")
    assert r.status_code == 405 and r.json()["error"] == "method_not_allowed"
    assert set(r.headers["allow"].split(", ")) >= {"GET", "POST"}
    r = client.put("/studies/0123456789abcdef")
    assert r.status_code == 405
    assert set(r.headers["allow"].split(", ")) >= {"GET", "DELETE"}


def test_api_description_needs_the_token_like_every_route_but_health(api):
    client = api(token="s3cret")
    for path in ("/openapi.json", "/docs"):
        r = client.get(path)
        assert r.status_code == 401 and r.json()["error"] == "unauthorized", path
    auth = {"Authorization": "Bearer s3cret"}
    assert client.get("/openapi.json", headers=auth).json()["info"]["title"] == "beltstudy"
    assert "/studies/{study_id}/runs" in client.get("/docs", headers=auth).text
    assert client.get("/health").status_code == 200


def test_the_api_page_loads_nothing_from_another_origin(api):
    """/docs (the pages' *API* link) was FastAPI's Swagger UI, whose script and style come
    from cdn.jsdelivr.net: without internet access it was a blank page. It is now the
    routes, their parameters and body types from /openapi.json on one page with no script."""
    client = api()
    r = client.get("/docs")
    assert r.status_code == 200 and r.headers["content-type"].startswith("text/html")
    text = r.text
    assert "http://" not in text and "https://" not in text and "<script" not in text
    assert "default-src 'none'" in r.headers["content-security-policy"]
    spec = client.get("/openapi.json").json()
    for path, ops in spec["paths"].items():
        for method in ops:
            assert f'{method.upper()}</span>{path}</h2>' in text, (method, path)
    assert '<code>application/yaml</code>' in text and 'href="/openapi.json"' in text


def test_the_body_is_held_to_its_published_schema(api, data_dir, make_study):
    client = api()
    for change, where in [
        ({"dynamics": "true"}, "dynamics"),
        ({"scenario": {"elements": "12"}}, "scenario.elements"),
        ({"grid": {"temperature_c": ["20"]}}, "grid.temperature_c"),
        ({"models": {"din": {"f_carry": "0.01"}}}, "models.din.f_carry"),
    ]:
        r = client.post("/studies", json={**make_study(), **change})
        assert r.status_code == 422, (change, r.text)
        assert where in r.json()["message"], (change, r.json()["message"])
    assert _written(data_dir) == []


def test_the_published_schema_says_what_is_accepted(api):
    from beltstudy.service.door.openapi import NOT_IN_SCHEMA, metric_names

    schema = api().get("/openapi.json").json()
    comps = schema["components"]["schemas"]
    body = comps["StudyDoc"]
    conveyor = body["properties"]["conveyor"]["anyOf"][0]
    assert "conveyors/slope-5pct.yaml" in conveyor["enum"]
    # a calibration names its conveyor file as a study does: the same enum of the files
    calibration = comps["CalibrationIn"]["properties"]["conveyor"]["anyOf"][0]
    assert calibration["enum"] == conveyor["enum"]
    assert "ST2000" in comps["Belt"]["properties"]["type"]["anyOf"][0]["enum"]
    grid = body["properties"]["grid"]
    assert {"temperature_c", "takeup.mass_kg", "scenario.run_s"} <= set(grid["properties"])
    assert grid["properties"]["temperature_c"]["anyOf"][0]["items"]["maximum"] == 80
    din = body["properties"]["models"]["properties"]["din"]["properties"]
    assert din["c"]["anyOf"][0]["minimum"] == 1.0 and din["f_carry"]["minimum"] == 0.0
    assert all(rule in body["description"] for rule in NOT_IN_SCHEMA)
    params = {p["name"]: p for p in
              schema["paths"]["/studies/{study_id}/compare"]["get"]["parameters"]}
    metrics = params["metrics"]
    assert metrics["explode"] is False and metrics["schema"]["uniqueItems"] is True
    assert set(metrics["schema"]["items"]["enum"]) == set(metric_names())
    assert params["study_id"]["schema"]["pattern"] == "^[0-9a-f]{16}$"
