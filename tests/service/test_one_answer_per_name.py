"""One name, one answer, whichever parameter names it.

``te_components_kn`` is the JSON object a row's ``te_<part>_kn`` columns are folded into:
``columns=`` said so and listed the parts, while ``filter=``, ``sort=`` and compare's
``metrics=`` answered "did you mean 'te_main_return_kn'?", a part picked by spelling. Each
now says what ``columns=`` says, with its own fix. ``GET /health?x=1`` answered 200 while
every API route refuses a query parameter it does not take (422 naming it): health does too.
"""

from __future__ import annotations

import pytest
from fastapi.testclient import TestClient

from beltstudy.service.api.app import create_app

FOLDED = "te_components_kn is the JSON object the te_<part>_kn columns are folded into; "


@pytest.fixture
def done(data_dir, finished_study, make_study, make_settings):
    sid = finished_study(data_dir, make_study(
        grid={"friction_model": ["cema", "din"], "temperature_c": [0, 20]}))
    return sid, TestClient(create_app(make_settings(data_dir)))


@pytest.mark.parametrize(("path", "params", "fix"), [
    ("runs", {"columns": "te_components_kn"}, "columns: " + FOLDED + "name those ("),
    ("runs", {"filter": "te_components_kn=1"}, "filter: " + FOLDED + "filter on one of those ("),
    ("runs", {"columns": "run_id", "filter": "te_components_kn=1"},
     "filter: " + FOLDED + "filter on one of those ("),
    ("runs", {"sort": "te_components_kn"}, "sort: " + FOLDED + "sort by one of those ("),
    ("runs", {"sort": "-te_components_kn"}, "sort: " + FOLDED + "sort by one of those ("),
    ("compare", {"baseline": "cema", "candidate": "din", "metrics": "te_components_kn"},
     "metrics: " + FOLDED + "compare those ("),
])
def test_te_components_kn_is_said_as_the_folded_object_everywhere(done, path, params, fix):
    sid, client = done
    r = client.get(f"/studies/{sid}/{path}", params=params)
    assert r.status_code == 422, r.text
    message = r.json()["message"]
    assert message.startswith(fix), message
    assert "did you mean" not in message, message
    assert "te_main_carry_kn, te_main_return_kn, te_lift_kn" in message, message


def test_the_parts_it_names_are_taken_where_it_was_refused(done):
    sid, client = done
    assert client.get(f"/studies/{sid}/runs", params={"sort": "-te_lift_kn"}).status_code == 200
    r = client.get(f"/studies/{sid}/runs", params={"filter": "te_lift_kn=0"})
    assert r.status_code == 200 and r.json()["total"] == 0
    r = client.get(f"/studies/{sid}/compare", params={"baseline": "cema", "candidate": "din",
                                                      "metrics": "te_lift_kn"})
    assert r.status_code == 200, r.text


def test_health_refuses_a_query_parameter_it_does_not_take(data_dir, make_settings):
    client = TestClient(create_app(make_settings(data_dir)))
    r = client.get("/health", params={"x": "1"})
    assert r.status_code == 422, r.text
    assert r.json()["message"] == "query.x: unknown parameter; this route takes: none"
    # as every API route says it
    assert client.get("/models", params={"x": "1"}).json() == r.json()
    assert client.get("/health").status_code == 200
