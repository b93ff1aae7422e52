"""Bad input over HTTP: the right 4xx, a message naming the problem, nothing written.

In-process (TestClient without the lifespan): no Dask cluster is started, since nothing valid
is ever submitted here.
"""

from __future__ import annotations

import json

import pytest
import yaml
from fastapi.testclient import TestClient

from beltstudy.service.api.app import create_app
from beltstudy.service.examples import TINY_CONVEYOR, TINY_SCENARIO


@pytest.fixture
def api(data_dir, make_settings):
    def build(**over):
        return TestClient(create_app(make_settings(data_dir, **over)))

    return build


def _written(data_dir) -> list[str]:
    root = data_dir / "studies"
    return sorted(p.name for p in root.iterdir()) if root.exists() else []


def _post_yaml(client, text: str, **kw):
    return client.post(
        "/studies",
        content=text.encode(),
        headers={"Content-Type": "application/yaml", **kw.pop("headers", {})},
        **kw,
    )


CASES = [
    (
        "malformed YAML",
        "name: x\ngrid: {temperature_c: [1, 2\n",
        422,
        r"body: not valid YAML at line \d+, column \d+",
    ),
    ("wrong type", {"dynamics": "often"}, 422, r'dynamics: "often" is not of type "boolean"'),
    (
        "unknown axis",
        {"grid": {"temprature_c": [0]}},
        422,
        r"unknown axis 'temprature_c'; did you mean 'temperature_c'",
    ),
    ("empty grid", {"grid": {}}, 422, r"grid: empty"),
    ("empty axis", {"grid": {"load": []}}, 422, r"grid.load: empty axis"),
    (
        "oversize grid",
        {"grid": {"temperature_c": {"start": -60, "stop": 80, "step": 0.001}}},
        413,
        r"grid.temperature_c: the range has 140001 values; the study limit is 20000 runs",
    ),
    (
        "oversize product",
        {
            "grid": {
                "temperature_c": {"start": -60, "stop": 79, "step": 1},
                "run_s": {"start": 0, "stop": 199, "step": 1},
            }
        },
        413,
        r"grid: the study has 28000 grid points \(runs before identical ones are merged\); "
        r"the limit is 20000",
    ),
    ("path traversal name", {"name": "../../etc"}, 422, r"name: must start with an ASCII letter"),
    (
        "path traversal conveyor",
        {"conveyor": "../../../etc/passwd"},
        422,
        r"conveyor: path '../../../etc/passwd' must be relative to the studies directory",
    ),
    ("absolute conveyor", {"conveyor": "/etc/passwd"}, 422, r"conveyor: path '/etc/passwd'"),
    (
        "empty conveyor path (it read as a path leaving the studies directory)",
        {"conveyor": ""},
        422,
        r"^conveyor: empty; give the path of a conveyor file \(e\.g\. "
        r"conveyors/slope-5pct\.yaml\) or the conveyor inline$",
    ),
    (
        "missing conveyor file",
        {"conveyor": "conveyors/none.yaml"},
        422,
        r"conveyor: file 'conveyors/none.yaml' not found",
    ),
    (
        "a folder for the conveyor file",
        {"conveyor": "conveyors"},
        422,
        r"^conveyor: 'conveyors' is a folder in the studies directory, not a file",
    ),
    (
        "bad axis value",
        {"grid": {"belt_type": ["ST2000", "ST2001"]}},
        422,
        r"belt_type='ST2001'.*unknown belt type 'ST2001'",
    ),
    (
        "unknown model",
        {"grid": {"friction_model": ["din", "magic"]}},
        422,
        r"grid.friction_model: unknown model 'magic'",
    ),
    (
        "half a surrogate pair",
        '{"name": "a\\ud800"}',
        422,
        r"name: contains U\+D800, half of a UTF-16 surrogate pair",
    ),
    (
        "text for a number inside an inline conveyor",
        {"conveyor": {**TINY_CONVEYOR, "speed_m_s": "4.5"}},
        422,
        r'^conveyor.speed_m_s: "4.5" is not of type "number": write 4.5 without quotes$',
    ),
    (
        "text for a number in a grid axis",
        {"grid": {"temperature_c": ["15", 20]}},
        422,
        r'^grid.temperature_c.0: "15" is not of type "number": write 15 without quotes$',
    ),
    (
        "'nan' as text",
        {"conveyor": {**TINY_CONVEYOR, "speed_m_s": "nan"}},
        422,
        r'^conveyor.speed_m_s: "nan" is not of type "number": write a number, in m/s$',
    ),
    (
        "a run time no transient run can simulate",
        {"dynamics": True, "scenario": {**TINY_SCENARIO, "run_s": 1e308}},
        422,
        r"^scenario.run_s: Input should be less than or equal to 3600 \(got 1e\+308\)$",
    ),
    (
        "a sample spacing of a nanosecond",
        {"dynamics": True, "scenario": {**TINY_SCENARIO, "record_dt_s": 1e-9}},
        422,
        r"scenario.record_dt_s: 1e-09 s over a cycle of .*use a spacing of at least",
    ),
    (
        "a sag limit of nothing",
        {"conveyor": {**TINY_CONVEYOR, "sag_limit_pct": {"carry": 1e-9, "return": 3}}},
        422,
        r"sag_limit_pct.carry",
    ),
    (
        "a friction factor beyond any conveyor",
        {"models": {"din": {"f_carry": 50}}},
        422,
        r"models.din.f_carry",
    ),
    (
        "an inline conveyor that over-fills its belt (a file's check, inline too)",
        {"conveyor": {**TINY_CONVEYOR, "material": {"capacity_t_h": 5000, "density_t_m3": 1.0}}},
        422,
        r"^conveyor\.material\.capacity_t_h: 5000 t/h fills the belt's cross-section to",
    ),
    (
        "stop mode the conveyor cannot do",
        {"dynamics": True, "grid": {"scenario.stop.mode": ["coast", "brake"]}},
        422,
        r"scenario.stop.mode: 'brake' needs brakes.*grid point scenario.stop.mode='brake'",
    ),
]


@pytest.mark.parametrize(("case", "change", "status", "message"), CASES, ids=[c[0] for c in CASES])
def test_bad_studies_get_the_right_status_and_write_nothing(
    api, data_dir, make_study, case, change, status, message
):
    client = api()
    if isinstance(change, str) and change.startswith("{"):
        response = client.post("/studies", content=change.encode(),
                               headers={"Content-Type": "application/json"})
    elif isinstance(change, str):
        response = _post_yaml(client, change)
    else:
        response = client.post("/studies", json={**make_study(), **change})
    assert response.status_code == status, response.text
    body = response.json()
    assert set(body) == {"error", "message"}
    import re

    assert re.search(message, body["message"]), body["message"]
    assert _written(data_dir) == []


def test_yaml_body_is_accepted_and_validated(api, data_dir, make_study):
    text = yaml.safe_dump({**make_study(), "grid": {"tempreture_c": [1]}})
    response = _post_yaml(api(), text)
    assert response.status_code == 422
    assert "did you mean 'temperature_c'" in response.json()["message"]


def test_oversize_body_is_413(api, data_dir, make_study):
    client = api(max_body_bytes=2048)
    study = make_study(description="x" * 1900)
    response = client.post(
        "/studies", content=json.dumps(study).encode(), headers={"Content-Type": "application/json"}
    )
    assert response.status_code == 413
    assert "the limit is 2048 (BELTSTUDY_MAX_BODY_BYTES)" in response.json()["message"]
    # the fix: the conveyor as a path, or the setting (the 413 named neither)
    assert "give the conveyor as a path" in response.json()["message"]
    assert _written(data_dir) == []


@pytest.mark.parametrize("chunked", [False, True])
def test_an_oversize_calibration_is_told_to_send_fewer_measured_rows(api, chunked):
    """A calibration's bytes are its measured rows: it was told the study's fix (the conveyor
    as a path, which it was already, and a shorter description, which it has none of)."""
    row = {"load": "full", "temperature_c": 20.0, "power_kw": 741.9}
    body = json.dumps({"conveyor": "conveyors/slope-5pct.yaml", "model": "din",
                       "fit": ["f_carry"], "measured": [row] * 200}).encode()
    content = iter([body]) if chunked else body  # no Content-Length: counted as it arrives
    response = api(max_body_bytes=2048).post(
        "/calibrations", content=content, headers={"Content-Type": "application/json"})
    assert response.status_code == 413
    said = response.json()["message"]
    assert said.startswith("body: ") and "(BELTSTUDY_MAX_BODY_BYTES); send fewer measured rows " \
        "(a calibration takes at most 200), or averages of repeated readings at the same load " \
        "and temperature, or raise the service's BELTSTUDY_MAX_BODY_BYTES" in said, said
    assert "conveyor" not in said and "description" not in said


def test_not_json_and_empty_bodies(api, data_dir):
    client = api()
    r = client.post("/studies", content=b"{not json", headers={"Content-Type": "application/json"})
    assert r.status_code == 422 and "not valid JSON at line 1" in r.json()["message"]
    r = client.post("/studies", content=b"", headers={"Content-Type": "application/json"})
    assert r.status_code == 422 and "body: empty" in r.json()["message"]
    r = client.post("/studies", json=[1, 2])
    assert r.status_code == 422 and "expected a mapping" in r.json()["message"]
    assert _written(data_dir) == []


def test_token_is_required_everywhere_but_health(api, data_dir, make_study):
    client = api(token="s3cret")
    for method, path in [
        ("GET", "/studies"),
        ("GET", "/models"),
        ("GET", "/catalog/belts"),
        ("GET", "/studies/0123456789abcdef"),
        ("POST", "/studies"),
        ("DELETE", "/studies/0123456789abcdef"),
    ]:
        r = client.request(method, path, json=make_study() if method == "POST" else None)
        assert r.status_code == 401, (method, path)
        assert "bearer token" in r.json()["message"]
        assert r.headers["www-authenticate"] == "Bearer"
    r = client.get("/studies", headers={"Authorization": "Bearer wrong"})
    assert r.status_code == 401
    assert client.get("/health").status_code == 200
    ok = client.get("/studies", headers={"Authorization": "Bearer s3cret"})
    assert ok.status_code == 200 and ok.json() == {"studies": []}
    assert _written(data_dir) == []


def test_unknown_ids_are_404(api, data_dir, finished_study, make_study):
    client = api()
    for path in [
        "/studies/0123456789abcdef",
        "/studies/../../etc/runs",
        "/studies/0123456789abcdef/runs",
        "/studies/0123456789abcdef/compare",
    ]:
        r = client.get(path)
        assert r.status_code == 404, path
    sid = finished_study(data_dir, make_study())
    r = client.get(f"/studies/{sid}/runs/ffffffffffffffff")
    assert r.status_code == 404 and "run 'ffffffffffffffff'" in r.json()["message"]
    assert client.delete("/studies/0123456789abcdef").status_code == 404
    # a long id is not echoed back whole: its start and its length
    long_id = "a" * 5000
    for path in (f"/studies/{long_id}", f"/studies/{sid}/runs/{long_id}"):
        r = client.get(path)
        assert r.status_code == 404 and len(r.text) < 300, r.text[:200]
        assert "'aaaaaaaaaaaaaaaa... (5000 characters)'" in r.json()["message"]


def test_an_id_that_cannot_be_a_study_is_an_unknown_study(api, data_dir, finished_study,
                                                          make_study):
    """``/studies/..%2Fx`` was answered 'no route GET /studies/../x' (the encoded slash split
    the path, so no route took it): now, as 'xyz' and any id no study can have, a 404 naming
    the id, what a study id is and how to list the studies."""
    client = api()
    form = ("a study id is 16 lower-case hexadecimal digits, as POST /studies answers it; "
            "GET /studies (beltstudy status) lists the studies")
    # an upper-case id is 16 hexadecimal digits too, yet no study's: the words say which form
    for path, study_id in [("/studies/0123456789ABCDEF", "0123456789ABCDEF"),
                           ("/studies/..%2Fx", "../x"), ("/studies/a%2Fb/runs", "a/b"),
                           ("/studies/xyz", "xyz"), ("/studies/xyz/runs", "xyz"),
                           ("/studies/%2F..%2F..%2Fhealth", "/../../health")]:
        r = client.get(path)
        assert r.status_code == 404, path
        assert r.json() == {"error": "not_found",
                            "message": f"study '{study_id}' not found: {form}"}, path
    # an id of a study's form keeps its words; a route under a real study that is not one is
    # still no route
    r = client.get("/studies/0123456789abcdef")
    assert r.json()["message"] == ("study '0123456789abcdef' not found; GET /studies and "
                                   "beltstudy status list the stored studies")
    sid = finished_study(data_dir, make_study())
    r = client.get(f"/studies/{sid}/nothing")
    assert r.status_code == 404 and r.json()["message"] == f"no route GET /studies/{sid}/nothing"


def test_an_unknown_run_id_says_what_a_run_id_is_and_where_they_are(api, data_dir,
                                                                    finished_study, make_study):
    """``/studies/{id}/runs/A8D7...`` (upper case) was a plain 'run ... not found' where a study
    id of that form is told what a study id is: now the run's words say what a run id is
    (when it cannot be one) and where the study's run ids are listed, on every run route."""
    client = api()
    sid = finished_study(data_dir, make_study())
    where = f"GET /studies/{sid}/runs?columns=run_id (beltstudy results {sid} -o runs.csv) lists them"
    real = client.get(f"/studies/{sid}/runs", params={"columns": "run_id"}).json()["runs"][0]
    upper = real["run_id"].upper()
    for tail in ("", "/surface", "/profile"):
        r = client.get(f"/studies/{sid}/runs/{upper}{tail}")
        assert r.status_code == 404, tail
        assert r.json()["message"] == (f"run '{upper}' of study '{sid}' not found: a run id is 16 "
                                       f"lower-case hexadecimal digits; {where}"), tail
    r = client.get(f"/studies/{sid}/runs/ffffffffffffffff")
    assert r.status_code == 404
    assert r.json()["message"] == (f"run 'ffffffffffffffff' of study '{sid}' not found; its run "
                                   f"ids: {where}")


def test_query_errors_name_the_parameter(api, data_dir, finished_study, make_study):
    client = api()
    sid = finished_study(data_dir, make_study())
    r = client.get(f"/studies/{sid}/runs", params={"format": "xlsx"})
    assert r.status_code == 422 and r.json()["message"].startswith("query.format:")
    r = client.get(f"/studies/{sid}/runs", params={"filter": "nope"})
    assert r.status_code == 422 and "filter: 'nope' is not column=value" in r.json()["message"]
    # well-formed, but this study has no such column or model: 422 naming the parameter and
    # what the study has (a 404 would read as "no such study")
    r = client.get(f"/studies/{sid}/runs", params={"filter": "nope=1"})
    assert r.status_code == 422 and "this study has no column 'nope'" in r.json()["message"]
    r = client.get(f"/studies/{sid}/compare", params={"baseline": "din", "candidate": "nonlin"})
    # given explicitly: not said to be the default (test_compare_asked_names)
    assert r.status_code == 422 and "candidate: model 'nonlin' is not in this study" in r.text
    # a value no row of a number column can have keeps no row
    r = client.get(f"/studies/{sid}/runs", params={"filter": "power_kw=abc"})
    assert r.status_code == 200 and r.json()["total"] == 0
    # an empty value is refused, as status= and format= are (it kept no row without a word)
    for item in ("load=", "temperature_c= "):
        r = client.get(f"/studies/{sid}/runs", params={"filter": item})
        assert r.status_code == 422, item
        assert r.json()["message"].startswith(f"filter: '{item}' has an empty value")
    # paging is JSON's: a download with limit or offset is refused, not cut silently
    for fmt in ("csv", "parquet"):
        for name in ("limit", "offset"):
            r = client.get(f"/studies/{sid}/runs", params={"format": fmt, name: 2})
            assert r.status_code == 422, (fmt, name)
            assert r.json()["message"].startswith(
                f"query.{name}: paging is JSON only (format=json); a {fmt} download holds "
                "every row")
    page = client.get(f"/studies/{sid}/runs", params={"format": "json", "limit": 2}).json()
    assert len(page["runs"]) == 2 and page["total"] == 6
    # filters are capped (each costs a pass over the rows): 500 are taken, 501 refused
    from beltstudy.service.api.studies import FILTERS_MAX

    r = client.get(f"/studies/{sid}/runs", params={"filter": ["status=ok"] * FILTERS_MAX})
    assert r.status_code == 200, r.text
    r = client.get(f"/studies/{sid}/runs", params={"filter": ["status=ok"] * (FILTERS_MAX + 1)})
    assert r.status_code == 422 and r.json()["message"].startswith("query.filter:"), r.text


def test_a_misspelt_query_parameter_or_choice_names_the_one_meant(api, data_dir,
                                                                  finished_study, make_study):
    """GET /studies/{id}/runs?limt=3 was refused with 'query.limt: unknown parameter; this
    route takes: format, ..., limit, offset' and ?format=jsn with 'Input should be 'json',
    'csv' or 'parquet'', neither naming the one meant; each now does, as a study's door does
    for a misspelt key or word."""
    client = api()
    sid = finished_study(data_dir, make_study())
    r = client.get(f"/studies/{sid}/runs", params={"limt": 3})
    assert r.status_code == 422
    assert r.json()["message"].startswith(
        "query.limt: unknown parameter (did you mean 'limit'?); this route takes: ")
    r = client.get(f"/studies/{sid}/runs", params={"format": "jsn"})
    assert r.status_code == 422
    assert r.json()["message"] == (
        "query.format: Input should be 'json', 'csv' or 'parquet': did you mean 'json'?")
    # a name near none keeps the list alone
    r = client.get(f"/studies/{sid}/runs", params={"zzz": 1})
    assert r.json()["message"].startswith("query.zzz: unknown parameter; this route takes: ")


def test_reading_a_finished_study(api, data_dir, finished_study, make_study):
    import io

    import pandas as pd

    client = api()
    sid = finished_study(data_dir, make_study())
    st = client.get(f"/studies/{sid}").json()
    assert st["state"] == "done" and st["total"] == st["done"] == 6
    assert st["status_url"] == f"/studies/{sid}"
    page = client.get(f"/studies/{sid}/runs", params={"limit": 2, "offset": 1}).json()
    assert page["total"] == 6 and len(page["runs"]) == 2
    assert "te_main_carry_kn" not in page["runs"][0]
    assert set(page["runs"][0]["te_components_kn"]) >= {"main_carry", "lift", "secondary"}
    cema = client.get(f"/studies/{sid}/runs", params={"friction_model": "cema"}).json()
    assert cema["total"] == 3
    csv = client.get(f"/studies/{sid}/runs", params={"format": "csv", "filter": "temperature_c=0"})
    assert csv.headers["content-type"].startswith("text/csv")
    assert len(pd.read_csv(io.StringIO(csv.text))) == 2
    pq = client.get(f"/studies/{sid}/runs", params={"format": "parquet"})
    assert len(pd.read_parquet(io.BytesIO(pq.content))) == 6
    # downloads are named files (no Content-Disposition before: browsers saved "runs")
    assert csv.headers["content-disposition"] == f'attachment; filename="{sid}-runs.csv"'
    assert pq.headers["content-disposition"] == f'attachment; filename="{sid}-runs.parquet"'
    assert "content-disposition" not in client.get(f"/studies/{sid}/runs").headers
    rid = page["runs"][0]["run_id"]
    detail = client.get(f"/studies/{sid}/runs/{rid}").json()
    assert detail["summary"]["run_id"] == rid
    cmp = client.get(
        f"/studies/{sid}/compare",
        params={"baseline": "din", "candidate": "cema", "metrics": "power_kw"},
    ).json()
    assert len(cmp["pairs"]) == 3 and cmp["summary"]["power_kw"]["overall"]["n"] == 3
    assert [s["id"] for s in client.get("/studies").json()["studies"]] == [sid]
    models = client.get("/models").json()["models"]
    assert {"din", "cema"} <= {m["name"] for m in models}
    assert "iso5048" in next(m for m in models if m["name"] == "din")["aliases"]
    belts = client.get("/catalog/belts").json()["belts"]
    assert any(b["id"] == "ST2000" for b in belts)
    # a finished study is deleted, not cancelled (it answered "state": "cancelled")
    assert client.delete(f"/studies/{sid}").json() == {
        "id": sid,
        "state": "deleted",
        "deleted": True,
        "cancelled": False,
        "was": "done",
    }
    assert _written(data_dir) == []


def test_openapi_documents_the_study_body(api):
    schema = api().get("/openapi.json").json()
    body = schema["paths"]["/studies"]["post"]["requestBody"]["content"]
    assert body["application/json"]["schema"] == {"$ref": "#/components/schemas/StudyDoc"}
    assert "application/yaml" in body
    comps = schema["components"]["schemas"]
    assert {"StudyDoc", "Conveyor", "Scenario", "ErrorOut"} <= set(comps)
    assert "grid" in comps["StudyDoc"]["properties"]
    # every scenario field and every sample distribution's parameter says what it is (and its
    # unit): dt_s, elements, formulation, start, stop, stop.mode, start.control and the
    # distributions' low/high/mean/mode had no description
    for name in ("Scenario", "StartSpec", "StopSpec", "Uniform", "Normal", "Lognormal",
                 "Triangular"):
        for field, prop in comps[name]["properties"].items():
            if field != "dist":
                assert prop.get("description"), f"{name}.{field} has no description"
    for field in ("dt_s", "start", "stop"):
        assert "[s]" in comps["Scenario"]["properties"][field]["description"], field


def test_compare_and_queries_take_model_aliases_and_pair_a_models_only_study(
        api, data_dir, finished_study, make_study):
    """A study whose only axis is the friction model has one pair; the aliases study files
    take (iso5048 = din) work in queries too; an unknown model is a 422 naming the field."""
    client = api()
    sid = finished_study(data_dir, make_study(grid={"friction_model": ["din", "cema"]}))
    cmp = client.get(f"/studies/{sid}/compare",
                     params={"baseline": "iso5048", "candidate": "cema", "metrics": "power_kw"})
    assert cmp.status_code == 200, cmp.text
    body = cmp.json()
    assert body["baseline"] == "din" and len(body["pairs"]) == 1
    pair = body["pairs"][0]
    assert pair["power_kw_ratio"] == pytest.approx(
        pair["power_kw_candidate"] / pair["power_kw_baseline"], rel=1e-12)
    runs = client.get(f"/studies/{sid}/runs", params={"friction_model": "din22101"}).json()
    assert runs["total"] == 1 and runs["runs"][0]["friction_model"] == "din"
    runs = client.get(f"/studies/{sid}/runs", params={"filter": "friction_model=iso5048"})
    assert runs.json()["total"] == 1
    r = client.get(f"/studies/{sid}/runs", params={"friction_model": "coulomb"})
    assert r.status_code == 422 and "unknown model 'coulomb'; valid: din" in r.text, r.text
    # a filter value no row has keeps no row, as for any column
    r = client.get(f"/studies/{sid}/runs", params={"filter": "friction_model=coulomb"})
    assert r.status_code == 200 and r.json()["total"] == 0
    # the OpenAPI schema lists the names these parameters take
    spec = client.get("/openapi.json").json()
    params = {p["name"]: p for p in spec["paths"]["/studies/{study_id}/compare"]["get"]
              ["parameters"]}
    assert {"din", "nonlin", "iso5048"} <= set(params["baseline"]["schema"]["enum"])


def test_an_input_error_past_the_door_is_a_422_naming_the_field(api, data_dir, make_study,
                                                                 monkeypatch):
    """The last line of defence: an engine InputError no check turned into Invalid still
    answers 422 with its message (not a 500 hiding it)."""
    from beltstudy.engine import InputError
    from beltstudy.service import studies

    def refuse(*_a, **_k):
        raise InputError("must be positive", field="conveyor.speed_m_s")

    monkeypatch.setattr(studies, "resolve_study", refuse)
    r = api().post("/studies", json=make_study())
    assert r.status_code == 422, r.text
    assert r.json() == {"error": "invalid", "message": "conveyor.speed_m_s: must be positive"}


def test_a_delete_while_another_is_deleting_the_study_is_409_not_404(
        data_dir, make_settings, finished_study, make_study):
    """Two DELETEs of one study at once: the second is a 409 until the first has finished,
    also after the first has already moved the files away (it answered 404 there: the store
    was read before the study was looked for among those being deleted)."""
    from beltstudy.service.studies import StudyService

    sid = finished_study(data_dir, make_study())
    service = StudyService(make_settings(data_dir))
    client = TestClient(create_app(service=service, settings=service.settings),
                        raise_server_exceptions=False)
    # a first DELETE in progress: the study is held as being deleted (while it waits for the
    # study's job, and while it removes the files) ...
    with service._lock:
        service._deleting.add(sid)
    try:
        r = client.delete(f"/studies/{sid}")
        assert r.status_code == 409, r.text
        assert r.json() == {"error": "conflict",
                            "message": f"study '{sid}' is already being deleted"}
        service.store.delete(sid)  # ... and its files are gone already
        r = client.delete(f"/studies/{sid}")
        assert r.status_code == 409, r.text
        assert client.post("/studies", json=make_study()).status_code == 409
    finally:
        with service._lock:
            service._deleting.discard(sid)
    # once it has finished, the study is unknown: 404, and nothing is left held
    assert client.delete(f"/studies/{sid}").status_code == 404
    assert client.delete("/studies/0123456789abcdef").status_code == 404
    assert service._deleting == set()


def test_a_study_deleted_while_its_runs_are_read_is_404_not_500(
        data_dir, make_settings, finished_study, make_study):
    """A read that has listed the study's part files when a DELETE moves them away answers
    404 (the study is gone), not a 500 from the vanished file."""
    import threading
    import time

    from beltstudy.service.studies import StudyService

    sid = finished_study(data_dir, make_study())
    service = StudyService(make_settings(data_dir))
    client = TestClient(create_app(service=service, settings=service.settings),
                        raise_server_exceptions=False)
    store = service.store
    # the runs table's reader lock held: a read lists the part files, then waits here
    with store._runs_lock:
        reading = store._runs_reading.setdefault(sid, threading.Lock())
    answers: list = []
    with reading:
        reader = threading.Thread(
            target=lambda: answers.append(client.get(f"/studies/{sid}/runs")))
        reader.start()
        time.sleep(0.5)  # it has listed the files and waits for the lock
        assert client.delete(f"/studies/{sid}").status_code == 200
    reader.join(30)
    assert answers and answers[0].status_code == 404, answers[0].text
    assert answers[0].json()["error"] == "not_found"
    assert client.get("/studies").json() == {"studies": []}


def test_a_study_sent_again_while_it_is_being_deleted_is_409(
        data_dir, make_settings, finished_study, make_study):
    """A body sent before is answered from its hash; while its study is being deleted that
    answer was a 200 with the study about to vanish (or a 404 once it had): it is the 409 of
    a study being deleted, and once the delete has finished the study is stored anew."""
    from beltstudy.service.studies import StudyService

    data = make_study()
    sid = finished_study(data_dir, data)
    service = StudyService(make_settings(data_dir))
    client = TestClient(create_app(service=service, settings=service.settings),
                        raise_server_exceptions=False)
    first = client.post("/studies", json=data)
    assert first.status_code == 200 and first.json()["id"] == sid  # the body is known now
    with service._lock:
        service._deleting.add(sid)  # a DELETE of it in progress
    try:
        r = client.post("/studies", json=data)
        assert r.status_code == 409, r.text
        assert "is being deleted" in r.json()["message"]
        service.store.delete(sid)  # its files already moved away
        r = client.post("/studies", json=data)
        assert r.status_code == 409, r.text
    finally:
        with service._lock:
            service._deleting.discard(sid)
    service._closing = True  # a study admitted now is stored but not started (no Dask here)
    r = client.post("/studies", json=data)
    assert r.status_code == 202 and r.json()["id"] == sid, r.text
