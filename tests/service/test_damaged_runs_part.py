"""A runs part file damaged on disk (cut short, or overwritten with other bytes: the service
writes each part whole under a temporary name and renames it, so only something else does
this): every request that read the study's runs answered a bare 500 ("internal error").

Now the JSON runs page serves the rows of the readable parts and names the damaged file
(``unreadable_parts``, ``message``), a run of a readable part still opens, and whatever
cannot be whole without it (a CSV or Parquet download, the comparison, the uncertainty, the
accuracy table, the report, a figure, a run of the damaged part) is a 500 ``damaged`` naming
the study, the file and the way out. No request changes a stored byte.
"""

from __future__ import annotations

import json

import pyarrow.parquet as pq
import pytest
from fastapi.testclient import TestClient

from beltstudy.service.api.app import create_app
from beltstudy.service.cli import main
from beltstudy.service.cli.demo import free_port
from beltstudy.service.store.parquet import Store

DAMAGES = {
    "truncated": lambda data: data[: len(data) // 2],
    "garbage": lambda data: b"this is not a parquet file\n" * 40,
}


def _split_and_damage(data_dir, sid: str, how: str):
    """The study's one runs part as two (rows 0-2 in ``a``, 3-5 in ``b``), then ``b``
    damaged as ``how`` says; returns (run ids of a, run ids of b, path of b, every stored
    file's bytes)."""
    store = Store(data_dir)
    (whole,) = store.parts(sid, "runs")
    table = pq.read_table(whole)
    store.write_part(sid, "runs", "a", table.slice(0, 3))
    bad = store.write_part(sid, "runs", "b", table.slice(3))
    whole.unlink()
    bad.write_bytes(DAMAGES[how](bad.read_bytes()))
    ids = table.column("run_id").to_pylist()
    stored = {p: p.read_bytes() for p in (data_dir / "studies" / sid).rglob("*") if p.is_file()}
    return ids[:3], ids[3:], bad, stored


def _names_the_damage(answer, sid: str, bad) -> None:
    assert answer.status_code == 500, answer.text
    body = answer.json()
    assert body["error"] == "damaged", body
    said = body["message"]
    assert said.startswith(f"study '{sid}': 1 runs part file cannot be read: {bad} (")
    assert f"move it out of {bad.parent}" in said and f"DELETE /studies/{sid}" in said
    assert "restore the file from a backup" in said


@pytest.mark.parametrize("how", sorted(DAMAGES))
def test_a_damaged_runs_part_is_named_and_the_rest_is_served(
    data_dir, make_study, make_settings, finished_study, how
):
    sid = finished_study(data_dir, make_study("damaged-part"))
    good, lost, bad, stored = _split_and_damage(data_dir, sid, how)
    client = TestClient(create_app(make_settings(data_dir)), raise_server_exceptions=False)

    page = client.get(f"/studies/{sid}/runs")
    assert page.status_code == 200, page.text
    doc = page.json()
    assert sorted(r["run_id"] for r in doc["runs"]) == sorted(good) and doc["total"] == 3
    (part,) = doc["unreadable_parts"]
    assert part["file"] == str(bad) and part["reason"]
    assert doc["message"].startswith(f"study '{sid}': 1 runs part file cannot be read: {bad}")
    assert doc["message"].endswith("the runs listed are those of the other parts")
    # the same with columns, a sort and a filter (read column by column)
    page = client.get(f"/studies/{sid}/runs", params={"columns": "run_id,power_kw",
                                                       "sort": "-power_kw",
                                                       "filter": "friction_model=din"})
    assert page.status_code == 200, page.text
    assert {r["run_id"] for r in page.json()["runs"]} <= set(good)
    assert page.json()["unreadable_parts"][0]["file"] == str(bad)
    # a run of the readable part opens; one of the damaged part names it
    assert client.get(f"/studies/{sid}/runs/{good[0]}").status_code == 200
    _names_the_damage(client.get(f"/studies/{sid}/runs/{lost[0]}"), sid, bad)
    # what cannot be whole without the part: named, never a bare 500
    for url, params in [
        (f"/studies/{sid}/runs", {"format": "csv"}),
        (f"/studies/{sid}/runs", {"format": "parquet"}),
        (f"/studies/{sid}/compare", {"baseline": "din", "candidate": "cema",
                                     "metrics": "power_kw"}),
        (f"/studies/{sid}/uncertainty", {}),
        (f"/studies/{sid}/accuracy", {}),
        (f"/studies/{sid}/report", {}),
        (f"/studies/{sid}/plots/power-temperature", {}),
    ]:
        _names_the_damage(client.get(url, params=params), sid, bad)
    # the study itself, the list and the study page's data still answer
    assert client.get(f"/studies/{sid}").json()["state"] == "done"
    assert [s["id"] for s in client.get("/studies").json()["studies"]] == [sid]
    assert "run_id" in client.get(f"/ui/data/studies/{sid}").json()["columns"]
    assert client.get("/health").status_code == 200
    # nothing stored was changed or removed
    now = {p: p.read_bytes() for p in (data_dir / "studies" / sid).rglob("*") if p.is_file()}
    assert now == stored


def test_results_command_writes_the_readable_runs_and_says_which_part_is_not(
    monkeypatch, data_dir, make_study, finished_study, tmp_path, capsys
):
    """``beltstudy results`` on the local store: the JSON document the service answers (the
    readable parts' runs, the damaged part named, a note on stderr); a CSV is refused
    naming the file, and none is written."""
    from beltstudy.service.cli import study

    monkeypatch.delenv("BELTSTUDY_URL", raising=False)
    monkeypatch.setattr(study, "DEFAULT_URL", f"http://127.0.0.1:{free_port()}")  # none there
    monkeypatch.setenv("BELTSTUDY_DATA_DIR", str(data_dir))
    sid = finished_study(data_dir, make_study("damaged-part"))
    good, _, bad, _ = _split_and_damage(data_dir, sid, "truncated")

    out = tmp_path / "runs.json"
    assert main(["results", sid, "-o", str(out)]) == 0
    err = capsys.readouterr().err
    assert f"runs part files of study {sid} cannot be read" in err
    doc = json.loads(out.read_bytes())
    assert sorted(r["run_id"] for r in doc["runs"]) == sorted(good)
    assert doc["unreadable_parts"][0]["file"] == str(bad)

    csv = tmp_path / "runs.csv"
    assert main(["results", sid, "-o", str(csv)]) == 2
    err = capsys.readouterr().err
    assert err.startswith(f"error: study '{sid}': 1 runs part file cannot be read: {bad}")
    assert not csv.exists()
