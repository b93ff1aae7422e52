"""The command line's output files stay out of the store (``BELTSTUDY_DATA_DIR``).

``results -o``, ``report -o``, ``static --profile/--plot``, ``simulate --timeseries/--plot``
and ``sweep-temperature -o DIR`` took any path: ``results ID -o data/studies/ID/study.json``
replaced the study's document with its runs (the study lost, GET /studies a 500), a file
written into ``studies/ID/runs/`` doubled what ``pd.read_parquet(".../runs")`` reads, and a
sweep's CSV there made it raise. Such a path is refused in one line, exit status 2, before
any work, and nothing in the store changes. An empty ``BELTSTUDY_DATA_DIR`` (what ``export
BELTSTUDY_DATA_DIR=$UNSET`` gives) is the default ``./data``, not the current folder.
"""

from __future__ import annotations

from pathlib import Path

import pandas as pd
import pytest

from beltstudy.engine.textfile import shown_path
from beltstudy.service.cli import main
from beltstudy.service.settings import Settings
from tests.conftest import ROOT

CONVEYOR = str(ROOT / "studies" / "conveyors" / "slope-5pct.yaml")


def _files(folder: Path) -> dict[Path, bytes]:
    return {p: p.read_bytes() for p in folder.rglob("*") if p.is_file()}


@pytest.mark.parametrize("argv", [
    ["results", "{sid}", "-o", "{study}/study.json"],
    ["results", "{sid}", "-o", "{study}/runs/x.parquet"],
    ["results", "{sid}", "-o", "{link}/runs/x.csv"],  # through a symbolic link
    ["report", "{sid}", "-o", "{data}/studies/report.html"],
    ["static", CONVEYOR, "--profile", "{study}/profile/mine.parquet"],
    ["static", CONVEYOR, "--plot", "{study}/x.png"],
    ["simulate", CONVEYOR, "--timeseries", "{study}/timeseries/mine.parquet"],
    ["simulate", CONVEYOR, "--plot", "{data}/bodies/x.png"],
    ["sweep-temperature", CONVEYOR, "--from", "0", "--to", "10", "-o", "{study}/runs"],
    ["sweep-temperature", CONVEYOR, "--from", "0", "--to", "10", "-o", "{study}/new"],
])
def test_an_output_inside_the_data_folder_is_refused_and_the_store_unchanged(
        env, capsys, finished_study, make_study, tmp_path, argv):
    sid = finished_study(env, make_study())
    study = env / "studies" / sid
    (tmp_path / "link").symlink_to(study)
    fill = {"sid": sid, "study": str(study), "data": str(env), "link": str(tmp_path / "link")}
    argv = [a.format(**fill) for a in argv]
    option = argv[-2]
    before = _files(env)
    rows = len(pd.read_parquet(study / "runs"))
    assert main(argv) == 2
    err = capsys.readouterr().err
    said = "--out" if option == "-o" and argv[0] == "sweep-temperature" else option
    # a path over 120 characters is shortened in the message (a test folder of a
    # pytest-xdist worker, popen-gw1/..., is longer)
    assert err.startswith(f"error: {said} {shown_path(argv[-1])}: inside the data folder "
                          f"{shown_path(env.resolve())} (beltstudy's store); write the file"), err
    assert err.rstrip().endswith("elsewhere") and err.count("\n") == 1
    assert _files(env) == before  # not a byte changed, no file added
    assert sorted(p.name for p in study.iterdir()) == sorted(
        ["study.json", "runs", "timeseries", "surface", "profile", "accuracy"])
    assert len(pd.read_parquet(study / "runs")) == rows
    assert main(["status", sid]) == 0  # the study reads as before


def test_an_output_beside_the_data_folder_is_written(env, capsys, finished_study, make_study,
                                                    tmp_path):
    """Only the store's part of the data folder is kept out (its studies, bodies and lock): a
    file next to the folder (a name that starts the same) is written as before, and so is one
    in the folder's root, beside the store (a script or a log kept there), which no reader of
    the store reads."""
    sid = finished_study(env, make_study())
    beside = tmp_path / (env.name + "-exports")
    beside.mkdir()
    assert main(["results", sid, "-o", str(beside / "runs.csv")]) == 0
    assert len(pd.read_csv(beside / "runs.csv")) == 6
    before = _files(env / "studies")
    assert main(["report", sid, "-o", str(env / "report.html")]) == 0
    assert (env / "report.html").read_text().startswith("<!doctype html>")
    assert _files(env / "studies") == before
    assert main(["status", sid]) == 0


@pytest.mark.parametrize("value", ["", "  "])
def test_an_empty_data_dir_setting_is_the_default_not_the_current_folder(
        env, capsys, finished_study, make_study, monkeypatch, tmp_path, value):
    """``BELTSTUDY_DATA_DIR=`` was read as ``Path("")``: the current folder became the store,
    and ``beltstudy run`` in a project folder wrote ``studies/<id>/``, ``bodies/`` and the lock
    among the user's own files. Empty is not set, as for BELTSTUDY_SCHEDULER and
    BELTSTUDY_TOKEN: the store is ``./data``."""
    assert Settings(data_dir=value).data_dir == Path("data")
    sid = finished_study(tmp_path / "data", make_study())  # the default store, ./data
    monkeypatch.chdir(tmp_path)
    monkeypatch.setenv("BELTSTUDY_DATA_DIR", value)
    assert main(["status"]) == 0
    assert sid in capsys.readouterr().out  # read from ./data
    # ./data is the folder kept out of outputs; the current folder is not the store
    assert main(["results", sid, "-o", "runs.csv"]) == 0
    assert len(pd.read_csv(tmp_path / "runs.csv")) == 6
    capsys.readouterr()
    assert main(["results", sid, "-o", f"data/studies/{sid}/study.json"]) == 2
    assert capsys.readouterr().err.startswith(
        f"error: -o data/studies/{sid}/study.json: inside the data folder "
        f"{(tmp_path / 'data').resolve()} (beltstudy's store)")
    assert not (tmp_path / "studies").exists() and not (tmp_path / ".beltstudy.lock").exists()
