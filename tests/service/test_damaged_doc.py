"""A study whose stored ``study.json`` was damaged outside the service (edited or truncated
by hand: the service writes it atomically): its requests answered a bare 500, DELETE could
not remove it and GET /studies left it out without a word. They now name the file and the
way out, DELETE removes it, and the other studies are untouched."""

from __future__ import annotations

import logging

from fastapi.testclient import TestClient

from beltstudy.service.api.app import create_app


def test_a_damaged_study_document_is_named_and_can_be_deleted(
    data_dir, make_study, make_settings, finished_study, caplog
):
    keep = finished_study(data_dir, make_study("kept"))
    sid = finished_study(data_dir, make_study("damaged", grid={"friction_model": ["din"],
                                                                 "temperature_c": [5]}))
    doc = data_dir / "studies" / sid / "study.json"
    doc.write_text(doc.read_text()[:40], encoding="utf-8")  # cut short by hand
    client = TestClient(create_app(make_settings(data_dir)))
    r = client.get(f"/studies/{sid}")
    assert r.status_code == 500
    said = r.json()["message"]
    assert said.startswith(f"study '{sid}': its stored document ") and "study.json cannot be " \
        "read (" in said and f"delete the study (DELETE /studies/{sid}" in said
    with caplog.at_level(logging.WARNING):
        listed = [s["id"] for s in client.get("/studies").json()["studies"]]
    assert listed == [keep]
    assert any("cannot be read" in rec.getMessage() for rec in caplog.records)
    r = client.delete(f"/studies/{sid}")
    assert r.status_code == 200 and r.json()["was"] == "damaged"
    assert not (data_dir / "studies" / sid).exists()
    assert client.get(f"/studies/{sid}").status_code == 404
    # the other study is as it was: its runs still read back
    assert client.get(f"/studies/{keep}").json()["state"] == "done"
    assert len(client.get(f"/studies/{keep}/runs").json()["runs"]) == 6
