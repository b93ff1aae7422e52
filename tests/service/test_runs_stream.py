"""A JSON page of many runs is written out a block of rows at a time: built whole (and checked
against the response model) the 19 764 rows of a large study took about 1 GB of the server's
memory for one 199 MB answer. The streamed document is the same as the whole one."""

from __future__ import annotations

import json

import pytest
from fastapi.testclient import TestClient

from beltstudy.service.api import studies as routes
from beltstudy.service.api.app import create_app


@pytest.mark.parametrize("query", ["", "?columns=run_id,power_kw,te_kn", "?offset=1&limit=4",
                                   "?sort=-power_kw&status=ok"])
def test_a_streamed_page_is_the_same_document_as_a_whole_one(
    data_dir, make_study, make_settings, finished_study, monkeypatch, query
):
    sid = finished_study(data_dir, make_study())
    client = TestClient(create_app(make_settings(data_dir)))
    whole = client.get(f"/studies/{sid}/runs{query}")
    assert whole.status_code == 200
    monkeypatch.setattr(routes, "STREAM_ROWS", 1)
    monkeypatch.setattr(routes, "STREAM_BLOCK", 2)  # blocks of 2 rows: 3 blocks for 6 rows
    streamed = client.get(f"/studies/{sid}/runs{query}")
    assert streamed.status_code == 200
    assert streamed.headers["content-type"] == "application/json"
    body = json.loads(streamed.content)
    assert body == whole.json() and len(body["runs"]) > 1
    assert list(body) == ["study_id", "state", "done", "study_runs", "total", "offset", "limit",
                          "runs"]
