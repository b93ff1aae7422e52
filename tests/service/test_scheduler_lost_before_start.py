"""A study submitted while the external Dask scheduler is unreachable, after the service had
reached it, fails within 30 s of its submission as the README says of a study that has not
started ("no Dask worker could start in 12 s: ..."), naming the scheduler and how to start it;
a service started while the scheduler is down says the same.

Before the fix such a study was ``running`` (``started_at`` set), 0 runs done, for as long as
one watched, with Dask's ``OSError: Timed out trying to connect to tcp://...`` as its message
and no fix: it had been handed the client while the client was still reconnecting to the lost
scheduler, and a study that has started waits for its scheduler without limit.

Real processes: ``dask scheduler`` on a free port and one ``dask worker`` (no nanny); the
service's :class:`~beltstudy.service.studies.StudyService` runs in this process.
"""

from __future__ import annotations

import os
import signal
import subprocess
import sys
import time

import pytest

pytestmark = pytest.mark.slow

DASK = os.path.join(os.path.dirname(sys.executable), "dask")
#: The README's bound: a study that has not started fails within 30 s of its submission.
FAIL_WITHIN_S = 30.0


def _until(what, check, timeout_s: float):
    t0 = time.monotonic()
    while time.monotonic() - t0 < timeout_s:
        value = check()
        if value:
            return value
        time.sleep(0.1)
    raise AssertionError(f"{what} not seen in {timeout_s} s")


def _stop(procs: list[subprocess.Popen]) -> None:
    for p in reversed(procs):
        if p.poll() is None:
            p.kill()
    for p in procs:
        p.wait(20)


def _fails_naming_the_scheduler(service, study: dict, address: str, port: int) -> dict:
    """Submit ``study``; follow it until it fails (at most FAIL_WITHIN_S); it never shows
    ``running`` nor a start time on the way, and its message names the scheduler and the fix."""
    t0 = time.monotonic()
    sub, created = service.submit(study)
    assert created
    seen = []
    while time.monotonic() - t0 < FAIL_WITHIN_S:
        st = service.status(sub["id"])
        seen.append((st["state"], st["message"]))
        if st["state"] not in ("queued", "running"):
            break
        time.sleep(0.2)
    assert st["state"] == "failed", (time.monotonic() - t0, seen[-3:])
    assert {state for state, _ in seen} <= {"queued", "failed"}, seen
    assert st["done"] == 0 and st["started_at"] is None, st
    assert st["message"].startswith("no Dask worker could start in 12 s: "), st["message"]
    for words in (f"the Dask scheduler {address}",
                  f"start it ('dask scheduler --port {port}' on its host)",
                  f"'dask worker {address}'",
                  "submit the study again once Dask works"):
        assert words in st["message"], st["message"]
    # while it waited, it said what for (the scheduler), and the fix once it was known
    waiting = [m for s, m in seen if m.startswith("waiting for Dask: ")]
    assert waiting and all(address in m for m in waiting), waiting
    assert f"dask scheduler --port {port}" in waiting[-1], waiting
    return st


def test_a_study_submitted_after_the_scheduler_is_lost_fails_in_time(
        data_dir, make_settings, make_study, tmp_path):
    from beltstudy.service.cli.demo import free_port
    from beltstudy.service.studies import StudyService

    port = free_port()
    address = f"tcp://127.0.0.1:{port}"
    log = open(tmp_path / "dask.log", "ab")  # noqa: SIM115
    procs = [subprocess.Popen(
        [DASK, "scheduler", "--host", "127.0.0.1", "--port", str(port), "--no-dashboard"],
        stdout=log, stderr=log)]
    service = None
    try:
        procs.append(subprocess.Popen(
            [DASK, "worker", address, "--nthreads", "1", "--no-nanny", "--no-dashboard",
             "--host", "127.0.0.1"], stdout=log, stderr=log))
        service = StudyService(make_settings(data_dir, scheduler=address))
        service.start()
        service.executor.start_background()
        _until("the executor ready on the scheduler",
               lambda: service.executor.state == "ready", timeout_s=120)

        procs[0].send_signal(signal.SIGKILL)  # the scheduler is gone (its worker ends too)
        procs[0].wait(10)
        _fails_naming_the_scheduler(service, make_study("after-the-loss"), address, port)
        health = service.executor.info()
        assert health["state"] == "error" and address in health["error"], health
        assert f"dask scheduler --port {port}" in health["error"], health

        # a service started while the scheduler is down says the same of a new study
        service.close()
        service = StudyService(make_settings(data_dir, scheduler=address))
        service.start()
        _fails_naming_the_scheduler(service, make_study("after-a-restart"), address, port)
    finally:
        if service is not None:
            service.close()
        _stop(procs)
        log.close()


def test_a_reconnecting_client_is_no_dask_to_start_on_and_its_note_clears(tmp_path,
                                                                          monkeypatch):
    """The executor's side without processes: a ready client found reconnecting to its lost
    scheduler is a failure from then (``failing_since``, ``/health`` says it with the fix); a
    study that has not started is not handed it (``connected=True``), one that has is (its
    tasks survive a reconnect); once connected again the note is gone."""
    from types import SimpleNamespace

    from beltstudy.service.dask.executor import Executor
    from beltstudy.service.errors import Unavailable
    from beltstudy.service.settings import Settings

    address = "tcp://127.0.0.1:8711"
    exe = Executor(Settings(data_dir=tmp_path, warm_start=False, scheduler=address))
    monkeypatch.setattr(exe, "start_background", lambda: None)  # no real connection
    fake = SimpleNamespace(status="running")
    exe._client, exe.state = fake, "ready"
    exe._ready.set()
    assert exe.client(timeout=0.05, connected=True) is fake
    fake.status = "connecting"
    with pytest.raises(Unavailable) as err:
        exe.client(timeout=0.05, connected=True)
    fix = ("start it ('dask scheduler --port 8711' on its host) and its workers "
           f"('dask worker {address}')")
    assert str(err.value) == (f"Dask on {address} is not ready: lost the Dask scheduler "
                              f"{address}: {fix} (the service reconnects when it is back)")
    assert exe.failing_since is not None
    assert exe.client(timeout=0.05) is fake  # a started study keeps its client
    assert exe.info()["state"] == "error" and fix in exe.info()["error"]
    fake.status = "running"  # back within the client's reconnect time
    assert exe.info()["state"] == "ready" and exe.info()["error"] == ""
    assert exe.failing_since is None
    fake.status = "closed"  # gone for good: dropped, still a failure with the fix
    with pytest.raises(Unavailable, match=r"lost the Dask scheduler .*dask scheduler --port"):
        exe.client(timeout=0.05, connected=True)
    assert exe.failing_since is not None and exe._client is None
