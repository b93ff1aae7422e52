"""The main job (``make run``): the service end to end on the embedded defaults.

Starts ``beltstudy serve`` on a free loopback port (LocalCluster, data in ``./data``), submits
``studies/paper-comparison.yaml`` over HTTP, shows progress, prints the CEMA vs Non-Lin
comparison of drive power and transient peak tension and where the Parquet files are, and
stops the service.
"""

from __future__ import annotations

import os
import signal
import socket
import subprocess
import sys
import time
from pathlib import Path

from beltstudy.engine.warmth import COMPILE_LINE
from beltstudy.service.cli.client import ServiceClient
from beltstudy.service.cli.console import ProgressBar, format_compare, format_duration
from beltstudy.service.dask.executor import WARMING
from beltstudy.service.door.studyfile import study_body
from beltstudy.service.errors import Unavailable
from beltstudy.service.settings import load_settings
from beltstudy.service.store.parquet import Store

__all__ = ["run_demo", "free_port", "start_server", "stop_server", "wait_ready", "worker_pids"]

METRICS = ["power_kw", "t_max_stop_kn", "t_min_stop_kn"]
#: The friction models compared: the paper's Non-Lin against CEMA.
BASELINE, CANDIDATE = "cema", "nonlin"


def free_port() -> int:
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


def start_server(port: int, env: dict | None = None, log=None) -> subprocess.Popen:
    """``beltstudy serve`` in a child process (its own process group)."""
    cmd = [sys.executable, "-m", "beltstudy.service.cli", "serve", "--host", "127.0.0.1", "--port", str(port)]
    return subprocess.Popen(
        cmd,
        env={**os.environ, **(env or {})},
        stdout=log or subprocess.DEVNULL,
        stderr=log or subprocess.DEVNULL,
        start_new_session=True,
    )


#: A service that has not answered ``/health`` for this long is stuck [s] (it answers within
#: seconds whatever the load: the route runs on its event loop, Dask starts in a thread).
STUCK_S = 120.0


def wait_ready(client, proc: subprocess.Popen | None = None, timeout_s: float | None = None,
               say=None) -> dict:
    """Poll ``/health`` until the Dask executor is ready (workers started and warmed).

    No fixed limit: it follows the service's progress (``say(line)`` once per stage: starting
    the workers, compiling the transient engine) as long as the service answers. It gives up
    when the service exits, when Dask reports an error, when ``/health`` has not answered for
    :data:`STUCK_S`, or after ``timeout_s`` when one is given."""

    t0 = last_answer = time.monotonic()
    stage = None
    while timeout_s is None or time.monotonic() - t0 < timeout_s:
        if proc is not None and proc.poll() is not None:
            raise Unavailable(f"the service exited with status {proc.returncode}")
        try:
            health = client.health()
        except Unavailable:
            health = None  # not listening yet
        now = time.monotonic()
        if health is None:
            if now - last_answer > STUCK_S:
                raise Unavailable(f"the service has not answered /health for {STUCK_S:.0f} s")
        else:
            last_answer = now
            state = health["executor"]["state"]
            if state == "ready":
                return health
            if state == "error":
                raise Unavailable(f"Dask: {health['executor']['error']}")
            if state != stage and say is not None:
                stage = state
                if state == WARMING:
                    say(f"{COMPILE_LINE} ...")
                elif state == "starting":
                    say("starting the Dask workers ...")
        time.sleep(0.5)
    raise Unavailable(f"the service was not ready after {timeout_s:.0f} s")


def stop_server(proc: subprocess.Popen, timeout_s: float = 30.0) -> None:
    """SIGTERM (graceful: studies stay resumable), then SIGKILL of the group if needed."""
    if proc.poll() is not None:
        return
    proc.send_signal(signal.SIGTERM)
    try:
        proc.wait(timeout_s)
    except subprocess.TimeoutExpired:
        os.killpg(proc.pid, signal.SIGKILL)
        proc.wait(10)


def run_demo(study_path: str = "studies/paper-comparison.yaml", port: int = 0) -> int:
    settings = load_settings()
    port = port or free_port()
    body = study_body(study_path)
    data_dir = Path(settings.data_dir).resolve()
    log_path = data_dir / "beltstudy.service.log"
    data_dir.mkdir(parents=True, exist_ok=True)
    print(
        f"starting the service on http://127.0.0.1:{port} (LocalCluster, data in {data_dir}, "
        f"log {log_path})"
    )
    with open(log_path, "ab") as log:
        proc = start_server(port, log=log)
    t0 = time.monotonic()
    try:
        with ServiceClient(f"http://127.0.0.1:{port}", settings.token) as client:
            health = wait_ready(client, proc, say=lambda line: print(line, flush=True))
            n = health["executor"]["workers"]
            print(
                f"{n} Dask worker{'' if n == 1 else 's'} ready and warmed in "
                f"{time.monotonic() - t0:.1f} s"
            )
            st, created = client.submit(body)
            print(
                f"{'submitted' if created else 'already in the store'}: {st['name']} "
                f"{st['id']} ({st['total']} runs)"
            )
            bar = ProgressBar(every_s=3.0)
            while True:
                st = client.status(st["id"])
                bar(st)
                if st["state"] not in ("queued", "running"):
                    break
                time.sleep(1.0)
            print(
                f"{st['state']}: {st['done']} runs, {st['failed']} failed, compute time "
                f"{format_duration(st['elapsed_s'])}"
            )
            result = client.compare(st["id"], BASELINE, CANDIDATE, METRICS)
            print()
            print(format_compare(result))
    finally:
        stop_server(proc)
    runs = Store(data_dir).study_dir(st["id"])
    print()
    print(f"Parquet files: {runs}/runs (summary rows), {runs}/timeseries (key points; a run's "
          "surface is recomputed when asked for unless the study says surface: true)")
    print(f'read them with: pandas.read_parquet("{runs}/runs")')
    return 0 if st["state"] == "done" else 1


def worker_pids(proc: subprocess.Popen) -> list[int]:
    """The Dask worker processes of a service started by :func:`start_server` (its
    LocalCluster's spawned children)."""
    import psutil

    out = []
    for child in psutil.Process(proc.pid).children(recursive=True):
        try:
            cmd = " ".join(child.cmdline())
        except psutil.Error:
            continue
        if "spawn_main" in cmd or "forkserver" in cmd:
            out.append(child.pid)
    return out
