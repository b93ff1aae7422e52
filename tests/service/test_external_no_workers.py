"""An external Dask cluster whose workers are all gone while the service stays connected to
its scheduler: ``/health`` counts 0 workers and says how to start one, a study submitted
meanwhile says it waits for a worker (no time left), and it finishes once one joins.

Real processes: ``dask scheduler``, ``dask worker`` (no nanny, so SIGKILL ends it for good,
as when its host is lost) and ``beltstudy serve`` pointed at the scheduler. Before the fix
``/health`` said ``workers: 1`` with no error and the study said ``running``, 0 done, no
message, for as long as no worker came (seen with a scheduler killed and restarted within the
client's 5 s reconnect time: the workers ended with the old one).
"""

from __future__ import annotations

import os
import signal
import subprocess
import sys
import time

import pandas as pd
import pytest

pytestmark = pytest.mark.slow

DASK = os.path.join(os.path.dirname(sys.executable), "dask")


def _worker(address: str, log) -> subprocess.Popen:
    return subprocess.Popen(
        [DASK, "worker", address, "--nthreads", "1", "--no-nanny", "--no-dashboard",
         "--host", "127.0.0.1"],
        stdout=log, stderr=log,
    )


def _until(what, check, timeout_s: float = 60.0):
    t0 = time.monotonic()
    while time.monotonic() - t0 < timeout_s:
        value = check()
        if value:
            return value
        time.sleep(0.3)
    raise AssertionError(f"{what} not seen in {timeout_s} s")


def test_no_worker_connected_is_said_and_waited_for(live_service, make_study, tmp_path):
    from beltstudy.service.cli.demo import free_port

    port = free_port()
    address = f"tcp://127.0.0.1:{port}"
    log = open(tmp_path / "dask.log", "ab")  # noqa: SIM115
    procs = [subprocess.Popen(
        [DASK, "scheduler", "--host", "127.0.0.1", "--port", str(port), "--no-dashboard"],
        stdout=log, stderr=log,
    )]
    try:
        time.sleep(1.0)
        procs.append(_worker(address, log))
        svc = live_service(BELTSTUDY_SCHEDULER=address)
        _until("one worker", lambda: svc.client.health()["executor"]["workers"] == 1)

        procs[1].send_signal(signal.SIGKILL)  # the cluster's only worker
        procs[1].wait(10)
        executor = _until("no worker in /health", lambda: (
            (e := svc.client.health()["executor"])["workers"] == 0 and e))
        assert executor["state"] == "ready"
        assert executor["error"] == (f"no Dask worker is connected to the scheduler {address}; "
                                     f"start workers with 'dask worker {address}'")

        study = make_study(name="no-workers", dynamics=True,
                           grid={"friction_model": ["din", "cema"], "temperature_c": [-10, 20]})
        sub, created = svc.client.submit(study)
        assert created
        st = _until("the study's waiting message", lambda: (
            (s := svc.client.status(sub["id"]))["message"].startswith("waiting for Dask") and s),
            timeout_s=30)
        assert st["message"] == f"waiting for Dask: {executor['error']}"
        assert st["state"] in ("queued", "running") and st["done"] == 0 and st["eta_s"] is None

        procs.append(_worker(address, log))  # a worker joins: the study goes on
        st = svc.wait(sub["id"], timeout_s=120)
        assert st["state"] == "done" and st["done"] == st["total"] == 4
        assert st["failed"] == 0 and st["message"] == ""
        runs = pd.read_parquet(svc.data_dir / "studies" / sub["id"] / "runs")
        assert len(runs) == 4 and runs["run_id"].is_unique
        # /health reads the scheduler's workers as it polls it: on a loaded machine its
        # answer can trail the study's end by a poll
        health = _until("the worker in /health", lambda: (
            (e := svc.client.health()["executor"])["workers"] == 1 and e), timeout_s=60)
        assert health["workers"] == 1 and health["error"] == ""
        svc.stop()
    finally:
        for p in reversed(procs):
            if p.poll() is None:
                p.send_signal(signal.SIGTERM)
        for p in procs:
            try:
                p.wait(20)
            except subprocess.TimeoutExpired:
                p.kill()
        log.close()
