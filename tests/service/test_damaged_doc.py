"""A study whose stored ``study.json`` was damaged outside the service (edited or truncated
by hand: the service writes it atomically): its requests answered a bare 500, DELETE could
not remove it and GET /studies left it out (first without a word, then with a line in the
log only: the study vanished from the list while its results were still on disk). They now
name the file and the way out, GET /studies lists it with state ``damaged`` and that
message, DELETE removes it, and nothing of it nor of the other studies is changed otherwise."""

from __future__ import annotations

import logging

from fastapi.testclient import TestClient

from beltstudy.service.api.app import create_app
from beltstudy.service.cli import main


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
        listed = {s["id"]: s for s in client.get("/studies").json()["studies"]}
    assert set(listed) == {keep, sid}
    assert listed[sid]["state"] == "damaged" and listed[sid]["message"] == said
    assert listed[keep]["state"] == "done"
    assert any("cannot be read" in rec.getMessage() for rec in caplog.records)
    r = client.delete(f"/studies/{sid}")
    assert r.status_code == 200 and r.json()["was"] == "damaged"
    assert not (data_dir / "studies" / sid).exists()
    assert client.get(f"/studies/{sid}").status_code == 404
    # the other study is as it was: its runs still read back
    assert client.get(f"/studies/{keep}").json()["state"] == "done"
    assert len(client.get(f"/studies/{keep}/runs").json()["runs"]) == 6


def test_a_damaged_study_is_listed_and_nothing_of_it_is_changed(
    data_dir, make_study, make_settings, finished_study, capsys, monkeypatch
):
    """GET /studies lists a study whose study.json was cut short, with state ``damaged``,
    the name its readable start still gives, and the message naming the file and the way
    out; GET /studies/{id} is the 500 naming it (its files are there: never a 404). A
    service that starts on the folder, lists it and answers for it changes none of its
    files; ``beltstudy status`` prints it with the message."""
    from beltstudy.service.cli import study
    from beltstudy.service.cli.demo import free_port

    older = finished_study(data_dir, make_study("older"))
    sid = finished_study(data_dir, make_study("cut-short", grid={"friction_model": ["din"],
                                                                   "temperature_c": [5]}))
    doc = data_dir / "studies" / sid / "study.json"
    text = doc.read_text()
    doc.write_text(text[: text.index('"engine_version"')], encoding="utf-8")  # cut short
    stored = {p: p.read_bytes() for p in (data_dir / "studies").rglob("*") if p.is_file()}

    with TestClient(create_app(make_settings(data_dir))) as client:  # the service starts
        studies = client.get("/studies").json()["studies"]
        assert [s["id"] for s in studies] == [older, sid]  # oldest first, as created
        entry = studies[1]
        assert entry["state"] == "damaged" and entry["name"] == "cut-short"
        assert entry["message"].startswith(f"study '{sid}': its stored document {doc} cannot "
                                           "be read (")
        assert f"DELETE /studies/{sid}" in entry["message"]
        assert entry["status_url"] == f"/studies/{sid}"
        r = client.get(f"/studies/{sid}")
        assert r.status_code == 500 and r.json()["error"] == "damaged"
        assert r.json()["message"] == entry["message"]
        assert client.get(f"/studies/{older}").json()["state"] == "done"
    now = {p: p.read_bytes() for p in (data_dir / "studies").rglob("*") if p.is_file()}
    assert now == stored  # not a byte of either study changed, no file removed

    monkeypatch.delenv("BELTSTUDY_URL", raising=False)
    monkeypatch.setattr(study, "DEFAULT_URL", f"http://127.0.0.1:{free_port()}")  # none there
    monkeypatch.setenv("BELTSTUDY_DATA_DIR", str(data_dir))
    capsys.readouterr()
    assert main(["status"]) == 0
    out = capsys.readouterr().out
    assert f"{sid}  cut-short" in out and "damaged" in out
    assert f"its stored document {doc} cannot be read" in out
