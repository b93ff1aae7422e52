"""``beltstudy submit|run|status|results|compare`` (service/cli/study.py, service/cli/console.py)."""

from __future__ import annotations

import json

import pandas as pd
import pyarrow.parquet as pq
import pytest
import yaml

from beltstudy.service.cli import main
from beltstudy.service.cli.console import ProgressBar, format_compare
from beltstudy.service.cli.demo import free_port
from beltstudy.service.store.parquet import Store


def test_status_results_compare_read_the_local_store_without_a_service(
    env, capsys, finished_study, make_study, tmp_path
):
    sid = finished_study(env, make_study())
    assert main(["status"]) == 0
    out = capsys.readouterr().out
    assert sid in out and "done" in out and "6/6" in out
    assert main(["status", sid]) == 0
    assert main(["results", sid, "-o", str(tmp_path / "r.parquet")]) == 0
    assert len(pd.read_parquet(tmp_path / "r.parquet")) == 6
    assert main(["results", sid, "-o", str(tmp_path / "r.csv")]) == 0
    assert len(pd.read_csv(tmp_path / "r.csv")) == 6
    assert main(["results", sid, "-o", str(tmp_path / "r.json")]) == 0
    rows = json.loads((tmp_path / "r.json").read_text())["runs"]
    assert len(rows) == 6 and "te_components_kn" in rows[0]
    capsys.readouterr()
    assert (
        main(["compare", sid, "--baseline", "din", "--candidate", "cema", "--metrics", "power_kw"])
        == 0
    )
    out = capsys.readouterr().out
    assert "cema / din" in out and "power_kw: ratio mean" in out and "by temperature_c" in out
    # a wrong metric or model is said with the option, and hundreds of valid columns are
    # not listed whole (6 200 characters: 'metrics: unknown metric ...; valid: ...')
    assert main(["compare", sid, "--metrics", "foo"]) != 0
    err = capsys.readouterr().err
    assert "--metrics: unknown metric 'foo'; valid: " in err and "more (the study's number" in err
    assert len(err) < 1500, len(err)
    assert main(["compare", sid, "--baseline", "dinx", "--candidate", "cema"]) != 0
    assert "--baseline: unknown model 'dinx'" in capsys.readouterr().err


def test_an_offline_status_says_a_running_study_is_not_running_now(
    env, capsys, finished_study, make_study
):
    """Without a service, status reads the local store, where a study stopped mid-run is
    still 'running': it printed that state alone, as if it ran. It says no service runs it and
    that a service started on the data dir resumes it."""
    sid = finished_study(env, make_study())
    assert main(["status"]) == 0
    assert "not running now" not in capsys.readouterr().out  # a finished study: no note
    Store(env).update(sid, state="running")
    assert main(["status", sid]) == 0
    out = capsys.readouterr().out
    assert "running" in out and ("no service answers: the queued or running studies above are "
                                 "not running now; a service started on this data dir resumes "
                                 "them") in out
    assert main(["status"]) == 0
    assert "not running now" in capsys.readouterr().out


def test_user_mistakes_print_one_line_and_exit_2(env, capsys, tmp_path, make_study):
    assert main(["status", "0123456789abcdef"]) == 2
    assert capsys.readouterr().err.strip() == ("error: study '0123456789abcdef' not found; GET "
                                               "/studies and beltstudy status list the stored "
                                               "studies")
    assert main(["results", "0123456789abcdef", "-o", str(tmp_path / "x.xlsx")]) == 2
    assert "use a .parquet, .csv or .json" in capsys.readouterr().err
    path = tmp_path / "bad.yaml"
    path.write_text(yaml.safe_dump(make_study(grid={"temprature_c": [0]})))
    assert main(["run", str(path)]) == 2
    err = capsys.readouterr().err
    assert len(err.strip().splitlines()) == 1 and "did you mean 'temperature_c'" in err
    assert main(["submit", str(path)]) == 2  # no service: one line naming the address
    err = capsys.readouterr().err
    assert "cannot reach the service at http://127.0.0.1:" in err
    assert not (env / "studies").exists() or not list((env / "studies").iterdir())


def test_progress_in_a_log_prints_a_line_when_it_moves_and_else_once_a_minute(monkeypatch):
    """Off a terminal (a log, CI, make run piped) the first compile held the study at 0 runs
    for minutes and the bar printed the same line every 5 s. Now: a line when the runs done,
    the failures, the state or the message moved (at most every 5 s), else one a minute."""
    import io

    from beltstudy.service.cli import console

    clock = {"t": 1000.0}
    monkeypatch.setattr(console.time, "monotonic", lambda: clock["t"])
    out = io.StringIO()
    bar = ProgressBar(stream=out)
    waiting = {"total": 85, "done": 0, "failed": 0, "eta_s": None, "state": "queued",
               "message": "compiling the transient engine (first run only)"}
    for _ in range(60):  # five minutes of polls every 5 s, nothing moving
        bar(waiting)
        clock["t"] += 5.0
    assert len(out.getvalue().splitlines()) == 5  # at 0 s and each minute after
    bar({**waiting, "state": "running", "done": 3})  # moved: said at once (5 s since the last)
    clock["t"] += 1.0
    bar({**waiting, "state": "running", "done": 9})  # moved, but within 5 s: not yet
    clock["t"] += 5.0
    bar({**waiting, "state": "running", "done": 12})
    bar({**waiting, "state": "done", "done": 85})  # the end is always said
    lines = out.getvalue().splitlines()
    assert [ln.split("]")[1].split(" runs")[0].strip() for ln in lines[5:]] == [
        "3/85", "12/85", "85/85"]


def test_progress_bar_and_compare_table():
    bar = ProgressBar(stream=None)
    line = bar.render({"total": 40, "done": 10, "failed": 1, "eta_s": 95, "state": "running"})
    assert line.startswith("[" + "#" * 8 + "." * 22 + "] 10/40 runs  1 failed  01:35 left")
    table = format_compare(
        {
            "baseline": "cema",
            "candidate": "nonlin",
            "metrics": ["power_kw"],
            "summary": {
                "power_kw": {
                    "overall": {"n": 1, "mean": 0.8, "min": 0.8, "max": 0.8},
                    "by_axis": {"load": {"full": {"n": 1, "mean": 0.8}}},
                }
            },
            "pairs": [
                {
                    "load": "full",
                    "run_id_baseline": "a",
                    "status_baseline": "ok",
                    "power_kw_baseline": 100.0,
                    "run_id_candidate": "b",
                    "status_candidate": "ok",
                    "power_kw_candidate": 80.0,
                    "power_kw_ratio": 0.8,
                }
            ],
        }
    )
    assert "power_kw: ratio mean 0.800" in table
    assert table.splitlines()[-1].split() == ["full", "100.0", "80.0", "0.800"]


@pytest.mark.slow
def test_run_uses_the_executor_and_store_in_process(env, capsys, tmp_path, make_study):
    conveyor = tmp_path / "conveyors" / "tiny.yaml"
    conveyor.parent.mkdir()
    study = make_study(name="cli-run")
    conveyor.write_text(yaml.safe_dump(study.pop("conveyor")))
    path = tmp_path / "study.yaml"
    path.write_text(yaml.safe_dump({**study, "conveyor": "conveyors/tiny.yaml"}))
    assert main(["run", str(path)]) == 0
    out = capsys.readouterr().out
    assert "done" in out and "6/6" in out
    (sid,) = [p.name for p in (env / "studies").iterdir()]
    assert len(pd.read_parquet(env / "studies" / sid / "runs")) == 6
    assert main(["run", str(path)]) == 0  # already done: nothing is run again
    assert "existing study" in capsys.readouterr().err
    # a part file moved out of the study's folder (what a damaged part's message offers):
    # the same study submitted again runs the runs it no longer has, and only those
    runs = env / "studies" / sid / "runs"
    (part,) = list(runs.glob("*.parquet"))
    table = pq.read_table(part)
    kept = pq.read_table(part).slice(0, 2)
    part.unlink()
    kept_path = Store(env).write_part(sid, "runs", "kept", kept)
    assert main(["run", str(path)]) == 0
    again = pd.read_parquet(runs)
    assert sorted(again["run_id"]) == sorted(table.column("run_id").to_pylist())
    assert len(again) == 6 and again["run_id"].is_unique
    assert kept_path.exists()  # the rows it had are kept, not run again
    assert pq.read_table(kept_path).equals(kept)


def test_an_output_in_a_missing_folder_is_one_line_before_any_work(env, capsys, tmp_path):
    missing = tmp_path / "no" / "such"
    for command, name in (("results", "r.csv"), ("report", "rep.html")):
        out = missing / name
        assert main([command, "0123456789abcdef", "-o", str(out)]) == 2
        err = capsys.readouterr().err
        # checked before the study is looked for: the folder, not "study not found"
        assert err == f"error: cannot write {out}: the folder {missing} does not exist\n"


def test_an_address_given_that_does_not_answer_is_an_error_not_the_local_store(
        env, capsys, monkeypatch, finished_study, make_study):
    """BELTSTUDY_URL is read as --url is: a silent fall-back to ./data would show another
    store's studies (or none) as if they were the service's."""
    finished_study(env, make_study())
    url = f"http://127.0.0.1:{free_port()}"
    monkeypatch.setenv("BELTSTUDY_URL", url)
    assert main(["status"]) == 2
    err = capsys.readouterr().err
    assert err.startswith(f"error: cannot reach the service at {url} ")
    assert "'beltstudy serve'" in err and "BELTSTUDY_URL" in err
    assert main(["status", "--url", url]) == 2
    assert f"cannot reach the service at {url} " in capsys.readouterr().err


@pytest.mark.parametrize(("variable", "value", "argv", "message"), [
    ("BELTSTUDY_MAX_RUNS", "abc", ["status"],
     "error: BELTSTUDY_MAX_RUNS: must be an integer (got 'abc')"),
    ("BELTSTUDY_WARM_START", "maybe", ["serve"],
     "error: BELTSTUDY_WARM_START: must be true or false (got 'maybe')"),
    ("BELTSTUDY_WORKERS", "0", ["status"],
     "error: BELTSTUDY_WORKERS: must be greater than or equal to 1 (got '0')"),
    # a scheduler address Dask cannot use: the service started and retried for ever
    # ('unknown address scheme', 'Timed out trying to connect to tcp://127.0.0.1:99999')
    ("BELTSTUDY_SCHEDULER", "http://127.0.0.1:8786", ["status"],
     "error: BELTSTUDY_SCHEDULER: must be a Dask scheduler address such as "
     "tcp://127.0.0.1:8786: 'http' is not a Dask scheme (tcp, tls, ucx, ws, wss, inproc) "
     "(got 'http://127.0.0.1:8786')"),
    ("BELTSTUDY_SCHEDULER", "tcp://127.0.0.1:99999", ["status"],
     "error: BELTSTUDY_SCHEDULER: must be a Dask scheduler address such as "
     "tcp://127.0.0.1:8786: a port is 1 to 65535 (got 'tcp://127.0.0.1:99999')"),
    ("BELTSTUDY_SCHEDULER", "tcp://:8786", ["status"],
     "error: BELTSTUDY_SCHEDULER: must be a Dask scheduler address such as "
     "tcp://127.0.0.1:8786: no host (got 'tcp://:8786')"),
    # a host without a port: the service started and retried it every 5 s ('missing port
    # number in address'), the studies failing 30 s later
    ("BELTSTUDY_SCHEDULER", "notaurl", ["serve"],
     "error: BELTSTUDY_SCHEDULER: must be a Dask scheduler address such as "
     "tcp://127.0.0.1:8786: no port (host:port; a Dask scheduler listens on 8786 unless told "
     "otherwise) (got 'notaurl')"),
    # a token with a space: HTTP strips it from the header, so no client could ever send it
    # (every route 401 for ever); its value stays out of the log
    ("BELTSTUDY_TOKEN", "s3cret ", ["serve"],
     "error: BELTSTUDY_TOKEN: a token is printable ASCII (letters, digits and punctuation), "
     "without spaces, line breaks or other characters: no client could send it in an "
     "Authorization header (check for a trailing space) (got 7 characters, not shown)"),
])
def test_a_bad_setting_in_the_environment_is_one_line_and_exit_2(
        env, capsys, monkeypatch, variable, value, argv, message):
    monkeypatch.setenv(variable, value)
    assert main(argv) == 2
    assert capsys.readouterr().err == message + "\n"


@pytest.mark.parametrize(("argv", "message"), [
    (["serve", "--port", "99999"], "argument --port: a port is 1 to 65535 (got 99999)"),
    (["serve", "--port", "-1"], "argument --port: a port is 1 to 65535 (got -1)"),
    (["serve", "--port", "0"], "argument --port: a port is 1 to 65535 (got 0)"),
    (["demo", "--port", "70000"], "argument --port: a port is 0 to 65535 (got 70000)"),
    (["demo", "--port", "http"], "argument --port: expected a port number, got 'http'"),
])
def test_a_port_out_of_range_is_refused_before_anything_starts(capsys, monkeypatch, argv,
                                                                message):
    from beltstudy.service.cli import study

    def never(*_a, **_k):
        raise AssertionError("started")

    monkeypatch.setattr(study, "cmd_serve", never)
    monkeypatch.setattr(study, "run_demo", never)
    with pytest.raises(SystemExit) as exc:
        main(argv)
    assert exc.value.code == 2
    err = capsys.readouterr().err
    assert err.startswith("usage: beltstudy ") and err.strip().endswith(message)


@pytest.mark.parametrize("command", ["submit", "run", "status", "results", "report", "compare",
                                     "uncertainty", "serve", "demo"])
def test_every_study_command_help_has_a_description(capsys, command):
    """``beltstudy COMMAND --help`` says what the command does under its usage."""
    from beltstudy.service.cli import build_parser

    sub = next(a for a in build_parser()._actions if a.dest == "command")
    assert sub.choices[command].description, command
    with pytest.raises(SystemExit):
        main([command, "--help"])
    out = capsys.readouterr().out
    assert sub.choices[command].description.split()[0] in out.split("\n\n")[1]


def test_compare_help_names_its_defaults(capsys):
    with pytest.raises(SystemExit):
        main(["compare", "--help"])
    out = " ".join(capsys.readouterr().out.split())
    assert "baseline friction model (default: cema)" in out
    assert "candidate friction model (default: nonlin)" in out


@pytest.mark.parametrize(("content", "message"), [
    (b"", "empty; expected a mapping of keys at the top level"),
    (b"\xff\xfe", "empty; expected a mapping of keys at the top level"),  # UTF-16 BOM alone
    (b"name: caf\xe9\n", "not UTF-8 text (byte 0xe9 at line 1, column 10): save it as UTF-8"),
    (b"- 1\n", "expected a mapping of keys at the top level"),
])
def test_a_conveyor_file_that_is_not_a_mapping_says_why(env, capsys, tmp_path, make_study,
                                                         content, message):
    (tmp_path / "conv.yaml").write_bytes(content)
    path = tmp_path / "study.yaml"
    path.write_text(yaml.safe_dump(make_study(conveyor="conv.yaml")))
    assert main(["run", str(path)]) == 2
    assert capsys.readouterr().err == f"error: conveyor: conv.yaml: {message}\n"


def test_a_data_dir_that_is_a_file_stops_serve_before_it_listens(env, capsys, monkeypatch,
                                                                  tmp_path, make_study):
    # serve started, /health said ok, then every POST /studies was a 500 (NotADirectoryError)
    import os
    import subprocess
    import sys

    store = tmp_path / "store"
    store.write_text("not a folder\n")
    for data_dir, what in ((store, "is a file"), (store / "sub", f"is under {store}, a file")):
        said = (f"error: BELTSTUDY_DATA_DIR: {data_dir} {what}, not a folder; give a folder "
                "for the store (it is created if missing)\n")
        env_vars = {**os.environ, "BELTSTUDY_DATA_DIR": str(data_dir),
                    "BELTSTUDY_WARM_START": "false"}
        # a service that started would serve until the timeout ends the test
        proc = subprocess.run(
            [sys.executable, "-m", "beltstudy.service.cli", "serve", "--port", str(free_port())],
            env=env_vars, capture_output=True, text=True, timeout=120)
        assert (proc.returncode, proc.stderr) == (2, said)
        monkeypatch.setenv("BELTSTUDY_DATA_DIR", str(data_dir))
        path = tmp_path / "study.yaml"
        path.write_text(yaml.safe_dump(make_study()))
        for argv in (["run", str(path)], ["status"]):  # the local store: the same line
            assert main(argv) == 2
            assert capsys.readouterr().err == said
    assert store.read_text() == "not a folder\n"


def test_a_store_that_is_only_read_need_not_be_writable(tmp_path, monkeypatch):
    """serve and run refuse a data folder they may not write in; a local read (status,
    results, report, compare of an archived store) takes it. os.access is asked for the
    permission (root may write anywhere, so the answer is set here)."""
    import os

    from beltstudy.service.errors import Invalid
    from beltstudy.service.settings import check_data_dir

    store = tmp_path / "archive"
    store.mkdir()
    monkeypatch.setattr(os, "access", lambda path, mode: not mode & os.W_OK)
    with pytest.raises(Invalid, match=r"DATA_DIR: .*archive: no permission to write in"):
        check_data_dir(store)
    assert check_data_dir(store, write=False) == store
    (tmp_path / "afile").write_text("x")
    with pytest.raises(Invalid, match=r"is a file, not a folder"):
        check_data_dir(tmp_path / "afile", write=False)


def test_compare_of_a_running_study_says_it_is_running():
    """A running study's comparison said 'no pairs: the study has no runs of both models
    with equal other axes' (as if it never would) and printed empty 'by <axis>' lines."""
    result = {
        "baseline": "cema", "candidate": "nonlin", "metrics": ["power_kw"],
        "summary": {"power_kw": {"overall": {"n": 0, "mean": None, "min": None, "max": None},
                                 "by_axis": {"load": {}}}},
        "pairs": [], "state": "running", "done": 12, "total": 40,
    }
    text = format_compare(result)
    assert "study running: 12 of 40 runs done; the ratios are of the pairs finished so far" \
        in text
    assert "no pairs yet" in text and "has no runs of both models" not in text
    assert "by load" not in text
    done = format_compare(dict(result, state="done", done=40))
    assert "study" not in done.splitlines()[1] and "no pairs: the study has no runs" in done


def test_results_and_report_of_an_unfinished_study_say_so(env, capsys, finished_study,
                                                          make_study, tmp_path):
    """`results` and `report` of a study still running wrote the rows finished so far with
    exit 0 and no word that the study was not done."""
    sid = finished_study(env, make_study())
    doc_path = env / "studies" / sid / "study.json"
    doc = json.loads(doc_path.read_text(encoding="utf-8"))
    doc.update(state="running", done=2, finished_at=None)
    doc_path.write_text(json.dumps(doc), encoding="utf-8")
    assert main(["status", sid]) == 0
    assert "running" in capsys.readouterr().out  # the local store reads the state it keeps
    for argv in (["results", sid, "-o", str(tmp_path / "runs.csv")],
                 ["report", sid, "-o", str(tmp_path / "report.html")]):
        assert main(argv) == 0
        err = capsys.readouterr().err
        assert err.startswith(f"note: study {sid} is running (2 of 6 runs done): "), err
        assert err.count("\n") == 1
    finished = finished_study(env, make_study(name="other"))
    assert main(["results", finished, "-o", str(tmp_path / "all.csv")]) == 0
    assert capsys.readouterr().err == ""


@pytest.mark.parametrize("typed", ["../health", "..", "../catalog/belts", "abc?x=1", "abc#f"])
def test_a_study_id_as_typed_reaches_only_the_study_routes(typed):
    """`beltstudy status ../health` sent GET /health (the id joined into the path unescaped and
    the dot segment resolved away) and printed a KeyError traceback reading the health answer
    as a study; `status abc?x=1` sent a query. The id is one percent-encoded path segment: the
    service answers it as an unknown study."""
    from urllib.parse import quote

    import httpx

    from beltstudy.service.cli.client import ServiceClient
    from beltstudy.service.errors import ServiceError

    seen = []

    def answer(request: httpx.Request) -> httpx.Response:
        seen.append(request.url.raw_path.decode().split("?")[0])  # the path, not the query
        if request.url.path == "/health":
            return httpx.Response(200, json={"status": "ok"})
        return httpx.Response(404, json={"error": "not_found", "message": "study not found"})

    client = ServiceClient("http://127.0.0.1:9")
    client._http = httpx.Client(base_url=client.url, transport=httpx.MockTransport(answer))
    for call in (client.status, client.uncertainty, client.report, client.delete,
                 lambda i: client.compare(i, "cema", "din", []), client.runs):
        with pytest.raises(ServiceError, match=r"study not found \(HTTP 404\)"):
            call(typed)
    assert len(seen) == 6 and all(p.startswith("/studies/") for p in seen), seen
    assert {p.split("/")[2] for p in seen} == {
        quote(typed, safe="") if typed != ".." else "%2E%2E"}


def test_submit_wait_of_a_failed_study_prints_why(monkeypatch, capsys):
    """`beltstudy submit STUDY --wait` against a service whose Dask scheduler is gone ended
    on 'bd32af557a4b12b7  power-vs-temperature  failed  0/85 ...' and exit 1, without the
    study's message ('no Dask worker could start in 12 s: ...; submit the study again once
    Dask works'), which `beltstudy status ID` prints. The message now follows the line."""
    from pathlib import Path

    from beltstudy.service.cli import study

    why = ("no Dask worker could start in 12 s: OSError: Timed out trying to connect to "
           "tcp://127.0.0.1:8799 after 5 s; its finished runs are kept: submit the study "
           "again once Dask works and it goes on")
    failed = {"id": "bd32af557a4b12b7", "name": "power-vs-temperature", "state": "failed",
              "total": 85, "done": 0, "failed": 0, "elapsed_s": 0.0, "eta_s": None,
              "message": why, "status_url": "/studies/bd32af557a4b12b7"}

    class Client:
        url = "http://127.0.0.1:8000"

        def __enter__(self):
            return self

        def __exit__(self, *exc):
            return False

        def submit(self, body):
            return dict(failed, state="queued", message=""), True

        def status(self, sid):
            return failed

    monkeypatch.setattr(study, "_client", lambda args: Client())
    root = Path(__file__).resolve().parents[2]
    code = main(["submit", str(root / "studies" / "power-vs-temperature.yaml"), "--wait"])
    out = capsys.readouterr().out.splitlines()
    assert code == 1
    assert out[-2].startswith("bd32af557a4b12b7  power-vs-temperature") and "failed" in out[-2]
    assert out[-1] == f"  {why}"


def test_the_progress_line_of_a_running_study_waiting_for_dask_says_so():
    """A 512-run study whose scheduler was killed at 168 runs showed '168/512 runs  0 failed
    00:41 left  (running)' for 25 s, the time left growing, while the study's message said
    'waiting for Dask: ... lost the Dask scheduler; reconnecting': the bar showed a message
    only while queued. It shows it while running too."""
    why = ("waiting for Dask: Dask on tcp://127.0.0.1:8786 is not ready: lost the Dask "
           "scheduler; reconnecting")
    line = ProgressBar().render({"state": "running", "total": 512, "done": 168, "failed": 0,
                                 "eta_s": 41.0, "message": why})
    assert line.endswith("(running)  " + why)
    quiet = ProgressBar().render({"state": "running", "total": 512, "done": 168, "failed": 0,
                                  "eta_s": 41.0, "message": ""})
    assert quiet.endswith("(running)")


def test_status_and_compare_print_the_service_s_documents_as_json(
    env, capsys, finished_study, make_study
):
    """status and compare had no --json (uncertainty and simulate had): a script had to
    parse the tables. With --json they print the documents REST answers, here from the local
    store: GET /studies/{id} (state, done of total), GET /studies ({"studies": [...]}) and
    GET /studies/{id}/compare (its pairs, each a ratio of the two models' power)."""
    sid = finished_study(env, make_study())
    capsys.readouterr()
    assert main(["status", sid, "--json"]) == 0
    st = json.loads(capsys.readouterr().out)
    assert st["id"] == sid and st["state"] == "done" and st["done"] == st["total"] == 6
    assert main(["status", "--json"]) == 0
    assert [s["id"] for s in json.loads(capsys.readouterr().out)["studies"]] == [sid]
    assert main(["compare", sid, "--baseline", "din", "--candidate", "cema", "--metrics",
                 "power_kw", "--json"]) == 0
    doc = json.loads(capsys.readouterr().out)
    assert doc["baseline"] == "din" and doc["candidate"] == "cema" and doc["pairs"]
    for p in doc["pairs"]:
        assert p["power_kw_ratio"] == pytest.approx(
            abs(p["power_kw_candidate"]) / abs(p["power_kw_baseline"]), rel=1e-12)
