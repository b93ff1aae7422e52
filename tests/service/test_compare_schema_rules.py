"""``GET /studies/{id}/compare``: the published schema states the rules its handler enforces,
so the requests a generator calls valid are accepted.

Schemathesis (positive mode, fuzzing and coverage, seed 5, a study of din, cema and nonlin)
had 387 of 525 schema-valid compare requests refused: 34 ``metrics=`` (the array had no
``minItems``; the handler refuses an empty value) and 353 ``baseline=din&candidate=din`` (both
enums began with ``din``). ``metrics`` now has ``minItems: 1``; the baseline and candidate enums
begin with their defaults (cema, nonlin); that the two differ, a rule across parameters, is
said in the candidate's description and held by ``schemathesis_hooks.filter_model_pair``.
``filter=`` keeps the route's ``maxItems`` (500; the patched schema had dropped it).
"""

from __future__ import annotations

from fastapi.testclient import TestClient

from beltstudy.service.api.app import create_app
from tests.service import schemathesis_hooks


def _params(client, path: str) -> dict:
    spec = client.get("/openapi.json").json()
    return {p["name"]: p for p in spec["paths"][path]["get"]["parameters"]}


def test_compare_schema_states_what_the_handler_refuses(
    data_dir, finished_study, make_study, make_settings
):
    sid = finished_study(data_dir, make_study(
        grid={"friction_model": ["cema", "nonlin"], "temperature_c": [0, 20]}))
    client = TestClient(create_app(make_settings(data_dir)))
    params = _params(client, "/studies/{study_id}/compare")

    metrics = params["metrics"]["schema"]
    assert metrics["minItems"] == 1 and metrics["uniqueItems"] is True
    # what minItems stands for: an empty list is refused, naming the parameter and the fix
    r = client.get(f"/studies/{sid}/compare", params={"metrics": ""})
    assert r.status_code == 422
    assert r.json()["message"] == ("query.metrics: empty; give a value or leave the "
                                   "parameter out")

    # each enum begins with its default, and the first values are a valid pair
    base, cand = params["baseline"]["schema"], params["candidate"]["schema"]
    assert base["enum"][0] == base["default"] == "cema"
    assert cand["enum"][0] == cand["default"] == "nonlin"
    assert sorted(base["enum"]) == sorted(cand["enum"])
    assert "another model than the baseline" in cand["description"]
    r = client.get(f"/studies/{sid}/compare",
                   params={"baseline": base["enum"][0], "candidate": cand["enum"][0]})
    assert r.status_code == 200, r.text
    # the rule across the two (an alias is its model) stays the handler's, with its words
    r = client.get(f"/studies/{sid}/compare", params={"baseline": "cema", "candidate": "cema"})
    assert r.status_code == 422
    assert r.json()["message"] == ("candidate: 'cema' is the baseline too; compare two "
                                   "different models")

    flt = _params(client, "/studies/{study_id}/runs")["filter"]["schema"]
    assert flt["maxItems"] == 500 and flt["items"]["pattern"] == "^[^=]+="
    r = client.get(f"/studies/{sid}/runs", params={"filter": ["te_kn=1"] * 501})
    assert r.status_code == 422 and "filter" in r.json()["message"]


def test_the_hooks_skip_a_comparison_of_one_model():
    ok = schemathesis_hooks._pair_ok
    path = "/studies/{study_id}/compare"
    assert not ok(path, {"baseline": "din", "candidate": "din"})
    assert not ok(path, {"baseline": "din22101", "candidate": "iso5048"})  # both din
    assert not ok(path, {"candidate": "cema"})  # the baseline's default is cema
    assert not ok(path, {"baseline": "non-lin"})  # the candidate's default is nonlin
    assert ok(path, {})
    assert ok(path, {"baseline": "din", "candidate": "visco"})
    assert ok(path, {"baseline": 3, "candidate": 3})  # a negative case: left to the handler
    assert ok("/studies/{study_id}/runs", {"baseline": "din", "candidate": "din"})


def test_an_empty_metric_name_is_said_as_one(data_dir, finished_study, make_study, make_settings):
    """``metrics=power_kw,`` answered "metrics: unknown metric ''; valid: te_kn, ..." (a
    blank among hundreds of names); it says the empty name, as columns= and --metrics do."""
    sid = finished_study(data_dir, make_study(
        grid={"friction_model": ["cema", "nonlin"], "temperature_c": [0, 20]}))
    client = TestClient(create_app(make_settings(data_dir)))
    for given in ("power_kw,", ",", "power_kw,,te_kn"):
        r = client.get(f"/studies/{sid}/compare", params={"metrics": given})
        assert r.status_code == 422, given
        assert r.json()["message"] == (
            f"metrics: an empty name in '{given}'; give result columns comma-separated "
            "(metrics=power_kw,t_max_stop_kn), or leave the parameter out for the defaults")
