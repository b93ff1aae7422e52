"""Honest waits: a study submitted to a service whose Dask cannot start fails within 30 s
naming why; the CLI's wait follows the service's progress and says what it waits for; a
command knows before a run whether the transient engine will compile.
"""

from __future__ import annotations

import os
import subprocess
import sys
import time

import pytest

from beltstudy.engine.warmth import COMPILE_LINE, kernel_cold
from beltstudy.service.cli.client import ServiceClient
from beltstudy.service.cli.console import ProgressBar
from beltstudy.service.cli.demo import free_port, start_server, stop_server, wait_ready
from beltstudy.service.errors import Unavailable

from .conftest import ROOT


@pytest.mark.slow
def test_a_study_with_no_worker_able_to_start_fails_within_30_s_naming_why(tmp_path,
                                                                           make_study):
    port, nowhere = free_port(), free_port()  # nothing listens on ``nowhere``
    scheduler = f"tcp://127.0.0.1:{nowhere}"
    env = {"BELTSTUDY_DATA_DIR": str(tmp_path / "data"),
           "BELTSTUDY_STUDIES_DIR": str(ROOT / "studies"), "BELTSTUDY_TOKEN": "",
           "BELTSTUDY_SCHEDULER": scheduler, "BELTSTUDY_WARM_START": "false"}
    with open(tmp_path / "service.log", "ab") as log:
        proc = start_server(port, env=env, log=log)
    client = ServiceClient(f"http://127.0.0.1:{port}", timeout=30)
    try:
        t0 = time.monotonic()
        while True:  # /health answers within seconds of the start
            try:
                client.health()
                break
            except Unavailable:
                assert time.monotonic() - t0 < 60, "the service never answered /health"
                time.sleep(0.2)
        st, created = client.submit(make_study("no-workers"))
        assert created
        t_submit = time.monotonic()
        while st["state"] in ("queued", "running"):
            assert time.monotonic() - t_submit < 30, f"still {st['state']} after 30 s: {st}"
            time.sleep(0.5)
            st = client.status(st["id"])
        waited = time.monotonic() - t_submit
        assert st["state"] == "failed", st
        assert st["message"].startswith("no Dask worker could start in 12 s: "), st["message"]
        assert "submit the study again once Dask works" in st["message"]
        assert str(nowhere) in st["message"] or "connect" in st["message"].lower()
        assert st["done"] == 0 and waited < 30
        # submitted again (Dask still down): it is queued again, not answered as failed
        again, created = client.submit(make_study("no-workers"))
        assert not created and again["id"] == st["id"] and again["state"] == "queued"
        # the CLI's wait gives up on Dask's error at once, naming it, after saying what it
        # waited for
        lines: list[str] = []
        with pytest.raises(Unavailable, match=r"^Dask: "):
            wait_ready(client, proc, say=lines.append)
    finally:
        client.close()
        stop_server(proc)


def test_the_progress_line_says_what_a_queued_study_waits_for():
    bar = ProgressBar()
    st = {"total": 4, "done": 0, "failed": 0, "eta_s": None, "state": "queued",
          "message": "waiting for Dask: Dask on a LocalCluster is not ready: its workers are "
                     "compiling the transient engine (first run only)"}
    assert bar.render(st).endswith(f"(queued)  {COMPILE_LINE}")
    assert bar.render({**st, "message": ""}).endswith("(queued)")
    # a running study's message is cleared when it runs (StudyJob._execute) and set again only
    # while it waits for Dask (a scheduler lost, workers compiling again): then said too
    assert bar.render({**st, "state": "running"}).endswith(f"(running)  {COMPILE_LINE}")
    assert bar.render({**st, "state": "running", "message": ""}).endswith("(running)")


def test_a_command_knows_before_the_run_whether_the_engine_compiles(tmp_path):
    # this checkout's numba cache is warm (the tests' warm-up loaded or wrote it)
    assert kernel_cold() is False
    # with an empty cache directory, the first run would compile
    code = "from beltstudy.engine.warmth import kernel_cold; print(kernel_cold())"
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                         env={**os.environ, "NUMBA_CACHE_DIR": str(tmp_path)}, timeout=300)
    assert out.stdout.strip() == "True", out.stderr


def test_workers_that_joined_after_a_failure_are_said_to_warm_not_to_be_missing(monkeypatch,
                                                                                tmp_path):
    """A worker that joins an external scheduler after a first 'no Dask worker joined' ends
    that failure: while it warms up (the engine compiles: minutes on a fresh clone) the
    executor said the old error, so a study waiting on it said 'no Dask worker joined ...;
    start workers with ...' for 3.5 min with two workers compiling, and a study that had not
    started failed 12 s after the first failure with 'no Dask worker could start in 12 s'."""
    import threading

    from beltstudy.service.dask import executor as ex
    from beltstudy.service.settings import Settings

    monkeypatch.setattr(ex, "RETRY_S", 0.0)
    exe = ex.Executor(Settings(data_dir=tmp_path, warm_start=False,
                               scheduler="tcp://127.0.0.1:1"))
    attempts = iter([Unavailable("no Dask worker joined the scheduler tcp://127.0.0.1:1 "
                                 "within 10 s (WorkerStartTimeoutError); start workers with "
                                 "'dask worker tcp://127.0.0.1:1'"), ("client", None)])

    def connect():
        answer = next(attempts)
        if isinstance(answer, Exception):
            raise answer
        return answer

    warming, release = threading.Event(), threading.Event()

    def warm_up(client):
        warming.set()
        release.wait(10)

    monkeypatch.setattr(exe, "_connect", connect)
    monkeypatch.setattr(exe, "_warm_up", warm_up)
    exe.start_background()
    try:
        assert warming.wait(10)
        assert exe.state == ex.WARMING
        assert exe.error == "" and exe.failing_since is None, (exe.error, exe.failing_since)
        with pytest.raises(Unavailable) as err:
            exe.client(timeout=0.05)
        assert "compiling the transient engine" in str(err.value), str(err.value)
        assert "no Dask worker joined" not in str(err.value)
    finally:
        release.set()
        exe._thread.join(10)
    assert exe.state == "ready" and exe.error == ""
