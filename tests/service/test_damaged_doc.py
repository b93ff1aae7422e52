"""A study whose stored ``study.json`` was damaged outside the service (edited or truncated
by hand: the service writes it atomically): its requests answered a bare 500, DELETE could
not remove it and GET /studies left it out (first without a word, then with a line in the
log only: the study vanished from the list while its results were still on disk). They now
name the file and the way out, GET /studies lists it with state ``damaged`` and that
message, DELETE removes it, and nothing of it nor of the other studies is changed otherwise."""

from __future__ import annotations

import json
import logging

import pytest
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


def _runs_download(sid: str) -> str:
    """What ``beltstudy results ID -o data/studies/ID/study.json`` wrote over the document
    (a JSON object, valid, but no study's)."""
    return json.dumps({"study_id": sid, "total": 1, "offset": 0, "limit": None, "runs": []})


@pytest.mark.parametrize("written", [
    '{"foo": 1}',
    "RUNS",  # the runs download the CLI's -o wrote there (_runs_download)
    "OTHER",  # the document of another study, copied into this folder
    '{"id": "SID", "name": "x", "state": "done", "total": 1, "study": {}}',  # keys, no contents
])
def test_a_json_object_that_is_no_study_document_is_damaged_not_a_500_for_all(
    data_dir, make_study, make_settings, finished_study, written
):
    """A ``study.json`` that is valid JSON but not a study's document (``{"foo": 1}``, or the
    runs that ``results -o`` wrote over it) passed as a document: GET /studies was a 500 for
    every study (``KeyError: 'id'`` in the list), GET /studies/{id} a bare "internal error",
    DELETE answered ``was: ""``. It is now damaged as an unreadable one is."""
    keep = finished_study(data_dir, make_study("kept"))
    sid = finished_study(data_dir, make_study("overwritten", grid={"friction_model": ["din"],
                                                                     "temperature_c": [5]}))
    doc = data_dir / "studies" / sid / "study.json"
    text = {"RUNS": _runs_download(sid),
            "OTHER": (data_dir / "studies" / keep / "study.json").read_text()}.get(written,
                                                                               written)
    doc.write_text(text.replace("SID", sid), encoding="utf-8")
    with TestClient(create_app(make_settings(data_dir))) as client:
        r = client.get("/studies")
        assert r.status_code == 200, r.text
        listed = {s["id"]: s for s in r.json()["studies"]}
        assert set(listed) == {keep, sid} and listed[keep]["state"] == "done"
        said = listed[sid]["message"]
        assert listed[sid]["state"] == "damaged", listed[sid]
        assert said.startswith(f"study '{sid}': its stored document {doc} cannot be read ("), said
        assert f"delete the study (DELETE /studies/{sid}" in said
        r = client.get(f"/studies/{sid}")
        assert r.status_code == 500 and r.json()["error"] == "damaged"
        assert r.json()["message"] == said
        r = client.delete(f"/studies/{sid}")
        assert r.status_code == 200 and r.json()["was"] == "damaged"
        assert not (data_dir / "studies" / sid).exists()
        assert len(client.get(f"/studies/{keep}/runs").json()["runs"]) == 6


def test_the_cli_reads_a_store_with_a_non_study_document_without_a_traceback(
    data_dir, make_study, finished_study, capsys, monkeypatch, tmp_path
):
    """Without a service, ``status``, ``status ID`` and ``results ID`` printed a Python
    traceback (KeyError: 'id', KeyError: 'study') for a ``study.json`` holding ``{"foo": 1}``."""
    from beltstudy.service.cli import study
    from beltstudy.service.cli.demo import free_port

    keep = finished_study(data_dir, make_study("kept"))
    sid = "0123456789abcdef"
    (data_dir / "studies" / sid).mkdir(parents=True)
    doc = data_dir / "studies" / sid / "study.json"
    doc.write_text('{"foo": 1}', encoding="utf-8")
    monkeypatch.delenv("BELTSTUDY_URL", raising=False)
    monkeypatch.setattr(study, "DEFAULT_URL", f"http://127.0.0.1:{free_port()}")  # none there
    monkeypatch.setenv("BELTSTUDY_DATA_DIR", str(data_dir))
    capsys.readouterr()
    assert main(["status"]) == 0
    out = capsys.readouterr().out
    assert f"{keep}  kept" in out and f"{sid}" in out and "damaged" in out
    assert f"its stored document {doc} cannot be read (it is a JSON object but not a " \
        "study's document: it has no id, name, state, total, study" in out
    for argv in (["status", sid], ["results", sid, "-o", str(tmp_path / "x.csv")]):
        assert main(argv) == 2
        err = capsys.readouterr().err
        assert err.startswith(f"error: study '{sid}': its stored document {doc} cannot be "
                              "read ("), err
        assert err.count("\n") == 1 and "Traceback" not in err
    assert not (tmp_path / "x.csv").exists()
