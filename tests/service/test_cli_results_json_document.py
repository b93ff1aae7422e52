"""``beltstudy results ID -o runs.json`` writes the document ``GET /studies/{id}/runs``
answers, whether a service answers or the command reads the local store.

It wrote ``{"runs": [...]}`` (indented) from the local store and the service's
``{"study_id", "total", "offset", "limit", "runs"}`` through a service: on a 6-run study
98 425 bytes against 87 533, and a script reading ``doc["total"]`` worked with a service only.
"""

from __future__ import annotations

import json

from fastapi.testclient import TestClient

from beltstudy.service.api.app import create_app
from beltstudy.service.cli import main
from beltstudy.service.cli.demo import free_port


def test_local_results_json_is_the_rest_document(
    monkeypatch, data_dir, finished_study, make_study, make_settings, tmp_path, capsys
):
    from beltstudy.service.cli import study

    monkeypatch.delenv("BELTSTUDY_URL", raising=False)
    monkeypatch.setattr(study, "DEFAULT_URL", f"http://127.0.0.1:{free_port()}")  # none there
    monkeypatch.setenv("BELTSTUDY_DATA_DIR", str(data_dir))
    sid = finished_study(data_dir, make_study())

    out = tmp_path / "runs.json"
    assert main(["results", sid, "-o", str(out)]) == 0
    capsys.readouterr()
    rest = TestClient(create_app(make_settings(data_dir))).get(f"/studies/{sid}/runs")
    assert rest.status_code == 200

    doc = json.loads(out.read_bytes())
    assert list(doc) == ["study_id", "state", "done", "study_runs", "total", "offset", "limit",
                         "runs"]
    assert doc["state"] == "done" and doc["done"] == doc["study_runs"] == 6
    assert doc["study_id"] == sid and doc["total"] == 6 and doc["offset"] == 0
    assert doc["limit"] is None and len(doc["runs"]) == 6
    assert "te_components_kn" in doc["runs"][0]
    assert doc == rest.json()
    assert out.read_bytes() == rest.content  # the same bytes as the service writes
