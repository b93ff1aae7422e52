"""Fixtures of the service tests: tiny conveyors and studies, and a finished study without Dask."""

from __future__ import annotations

import time
from pathlib import Path

import pytest

from beltstudy.service.dask.jobs import study_schema
from beltstudy.service.dask.tasks import run_batch
from beltstudy.service.door.studyfile import resolve_study
from beltstudy.service.examples import TINY_CONVEYOR, TINY_SCENARIO
from beltstudy.service.settings import Settings
from beltstudy.service.store.columns import rows_to_table
from beltstudy.service.store.parquet import PART_TABLES, Store

ROOT = Path(__file__).resolve().parents[2]


def tiny_conveyor(**over) -> dict:
    """A 60 m conveyor (the warm-up conveyor): a steady run takes about a millisecond."""
    return {**TINY_CONVEYOR, **over}


def tiny_study(name: str = "tiny", **over) -> dict:
    """2 models x 3 temperatures, steady only: six runs."""
    study = {
        "name": name,
        "conveyor": tiny_conveyor(),
        "scenario": dict(TINY_SCENARIO),
        "grid": {"friction_model": ["din", "cema"], "temperature_c": [-20, 0, 20]},
        "dynamics": False,
    }
    study.update(over)
    return study


def settings_for(data_dir: Path, **over) -> Settings:
    return Settings(
        data_dir=data_dir, warm_start=False, studies_dir=ROOT / "studies", workers=2, **over
    )


def store_finished(data_dir: Path, data: dict) -> str:
    """Resolve ``data``, run it in this process and store it as a done study; return the id."""
    study = resolve_study(data, studies_dir=ROOT / "studies")
    store = Store(data_dir)
    now = time.time()
    store.create(
        study.id,
        {
            "id": study.id,
            "name": study.name,
            "state": "done",
            "total": study.total,
            "done": study.total,
            "failed": 0,
            "elapsed_s": 0.1,
            "message": "",
            "created_at": now,
            "updated_at": now,
            "started_at": now,
            "finished_at": now,
            "engine_version": study.engine_version,
            "study": study.to_json(),
        },
    )
    out = run_batch(study.id, study.runs, study.surface)
    for table in PART_TABLES:  # before the runs part, as the service does
        if out[table] is not None:
            store.write_part(study.id, table, "all", out[table])
    store.write_part(study.id, "runs", "all", rows_to_table(out["rows"], study_schema(study)))
    return study.id


@pytest.fixture
def data_dir(tmp_path) -> Path:
    return tmp_path / "data"


@pytest.fixture
def make_study():
    """Factory: ``make_study(name="tiny", **over)`` -> a six-run steady study mapping."""
    return tiny_study


@pytest.fixture
def make_conveyor():
    return tiny_conveyor


@pytest.fixture
def make_settings():
    """Factory: ``make_settings(data_dir, **over)`` -> Settings without a warm start."""
    return settings_for


@pytest.fixture
def finished_study():
    """Factory: ``finished_study(data_dir, data)`` -> id of a done study run in-process."""
    return store_finished


# ------------------------------------------------------------------ live servers (slow tests)
#: Tries at a free port before a live service's start fails (:class:`LiveService`).
PORT_ATTEMPTS = 3


def _port_taken(log_path: Path, start: int) -> bool:
    """Whether the server's log, from byte ``start``, says its port was already in use."""
    with open(log_path, "rb") as f:
        f.seek(start)
        return b"is already in use" in f.read()


class LiveService:
    """``beltstudy serve`` in a child process on a free loopback port."""

    def __init__(self, data_dir: Path, log_path: Path, **env: str):
        from beltstudy.service.cli.client import ServiceClient
        from beltstudy.service.cli.demo import free_port, start_server, wait_ready

        self.data_dir = data_dir
        self.env = {
            "BELTSTUDY_DATA_DIR": str(data_dir),
            "BELTSTUDY_STUDIES_DIR": str(ROOT / "studies"),
            "BELTSTUDY_WORKERS": "2",
            "BELTSTUDY_TOKEN": "",
            "BELTSTUDY_SCHEDULER": "",
            **env,
        }
        # a free port can be taken between free_port() and the server's bind (another
        # service's Dask workers bind ports of their own): the server then exits at once
        # saying so, and is started again on another port
        for attempt in range(PORT_ATTEMPTS):
            self.port = free_port()
            self.url = f"http://127.0.0.1:{self.port}"
            self.log = open(log_path, "ab")  # noqa: SIM115 - closed in stop()
            start = self.log.tell()
            self.proc = start_server(self.port, env=self.env, log=self.log)
            self.client = ServiceClient(self.url, self.env["BELTSTUDY_TOKEN"], timeout=60)
            try:
                self.health = wait_ready(self.client, self.proc, timeout_s=240)
                return
            except Exception:
                self.stop()
                if attempt + 1 < PORT_ATTEMPTS and _port_taken(log_path, start):
                    continue
                raise

    def worker_pids(self) -> list[int]:
        """Dask worker processes of the service's LocalCluster."""
        from beltstudy.service.cli.demo import worker_pids

        return worker_pids(self.proc)

    def wait(self, study_id: str, timeout_s: float = 240.0, until=None) -> dict:
        """Poll until the study ends (or ``until(status)`` holds)."""
        t0 = time.monotonic()
        while time.monotonic() - t0 < timeout_s:
            st = self.client.status(study_id)
            if until is not None and until(st):
                return st
            if st["state"] not in ("queued", "running"):
                return st
            time.sleep(0.1 if until else 0.3)
        raise AssertionError(f"study {study_id} did not finish in {timeout_s} s: {st}")

    def kill(self) -> None:
        """SIGKILL the service and every process it started (its process group)."""
        import os
        import signal

        os.killpg(self.proc.pid, signal.SIGKILL)
        self.proc.wait(30)
        self._close()

    def stop(self) -> None:
        from beltstudy.service.cli.demo import stop_server

        stop_server(self.proc)
        self._close()

    def _close(self) -> None:
        self.client.close()
        self.log.close()


@pytest.fixture
def live_service(tmp_path):
    """Factory: ``live_service(data_dir, **env)``; every service started is stopped at the end."""
    started: list[LiveService] = []

    def start(data_dir: Path | None = None, **env: str) -> LiveService:
        svc = LiveService(
            data_dir or tmp_path / "data", tmp_path / f"service{len(started)}.log", **env
        )
        started.append(svc)
        return svc

    yield start
    for svc in started:
        if svc.proc.poll() is None:
            svc.stop()


@pytest.fixture
def env(monkeypatch, data_dir):
    """For the command line: no service listens at the default address; the store is in a
    temporary directory (``data_dir``), run in process with two workers."""
    from beltstudy.service.cli import study
    from beltstudy.service.cli.demo import free_port

    monkeypatch.delenv("BELTSTUDY_URL", raising=False)
    monkeypatch.setattr(study, "DEFAULT_URL", f"http://127.0.0.1:{free_port()}")
    monkeypatch.setenv("BELTSTUDY_DATA_DIR", str(data_dir))
    monkeypatch.setenv("BELTSTUDY_WORKERS", "2")
    return data_dir
