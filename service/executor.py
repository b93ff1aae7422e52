"""The Dask side: one client per service, to a LocalCluster or to an existing scheduler.

With ``BELTSTUDY_SCHEDULER`` empty the service starts a :class:`distributed.LocalCluster` of
worker processes, one thread each (``BELTSTUDY_WORKERS``, default one per core); with
``tcp://host:port`` it connects to that scheduler. Once connected every worker runs
:func:`service.tasks.warm_up` (imports, numba compile) before any study is timed.
"""

from __future__ import annotations

import logging
import threading
import time
import uuid

from service.errors import Unavailable
from service.settings import Settings

__all__ = ["Executor"]

log = logging.getLogger("beltstudy.executor")

#: How long to wait for workers to appear and warm up [s].
WARM_TIMEOUT_S = 600.0
#: Dask settings of the LocalCluster (inherited by its worker processes): no statistical
#: profiler sampling every worker each 10 ms, no GIL monitor, a slower event-loop tick.
#: An idle cluster then costs a few % of a core instead of ~15 %: on 2 cores that matters.
LOCAL_DASK_CONFIG = {
    "distributed.worker.profile.enabled": False,
    "distributed.admin.system-monitor.gil.enabled": False,
    "distributed.admin.tick.interval": "200ms",
}


class Executor:
    """Lazily connected Dask client shared by every study of a service."""

    def __init__(self, settings: Settings):
        self.settings = settings
        self.state = "idle"  # idle | starting | ready | error | closed
        self.error = ""
        self.warm: dict[str, dict] = {}
        self._client = None
        self._cluster = None
        self._lock = threading.Lock()
        self._ready = threading.Event()
        self._workers_cache = (0.0, 1)

    # ---------------------------------------------------------------- lifecycle
    def start_background(self) -> None:
        """Connect and warm up in a thread (the API answers meanwhile)."""
        threading.Thread(target=self._start_quietly, name="beltstudy-executor", daemon=True).start()

    def _start_quietly(self) -> None:
        try:
            self.client()
        except Unavailable as exc:
            log.warning("%s", exc)

    def client(self):
        """The connected, warmed client; connects on first use. Raises :class:`Unavailable`."""
        if self._ready.is_set():
            return self._client
        with self._lock:
            if self._ready.is_set():
                return self._client
            if self.state == "closed":
                raise Unavailable("the service is shutting down")
            self.state = "starting"
            try:
                self._connect()
                self._warm_up()
            except Exception as exc:
                self.state, self.error = "error", f"{type(exc).__name__}: {exc}"
                self._close_quietly()
                where = self.settings.scheduler or "a LocalCluster"
                raise Unavailable(f"cannot start Dask on {where}: {self.error}") from exc
            self.state, self.error = "ready", ""
            self._ready.set()
            return self._client

    def _connect(self) -> None:
        from distributed import Client, LocalCluster

        if self.settings.scheduler:
            self._client = Client(self.settings.scheduler, timeout="30s", set_as_default=False)
            self._client.wait_for_workers(1, timeout=WARM_TIMEOUT_S)
        else:
            import dask

            dask.config.set(LOCAL_DASK_CONFIG)
            self._cluster = LocalCluster(
                n_workers=self.settings.n_local_workers,
                threads_per_worker=1,
                processes=True,
                dashboard_address=":0",
                silence_logs=logging.ERROR,
            )
            self._client = Client(self._cluster, set_as_default=False)

    def _warm_up(self) -> None:
        from service.tasks import warm_up

        client = self._client
        workers = list(client.scheduler_info(n_workers=-1)["workers"])
        nonce = uuid.uuid4().hex[:8]
        futures = {
            addr: client.submit(
                warm_up,
                key=f"beltstudy-warm-up-{nonce}-{i}",
                workers=[addr],
                allow_other_workers=False,
                pure=False,
            )
            for i, addr in enumerate(workers)
        }
        t0 = time.monotonic()
        for addr, fut in futures.items():
            try:
                self.warm[addr] = fut.result(timeout=WARM_TIMEOUT_S)
            except Exception as exc:  # a worker that cannot warm up still gets work
                self.warm[addr] = {"errors": [f"{type(exc).__name__}: {exc}"]}
        log.info("warmed %d workers in %.1f s", len(futures), time.monotonic() - t0)

    def n_workers(self) -> int:
        """Workers connected now (cached for two seconds)."""
        stamp, n = self._workers_cache
        if time.monotonic() - stamp > 2.0 and self._client is not None:
            try:
                n = max(1, len(self._client.scheduler_info(n_workers=-1)["workers"]))
            except Exception:  # scheduler briefly unreachable: keep the last count
                pass
            self._workers_cache = (time.monotonic(), n)
        return n

    def info(self) -> dict:
        return {
            "state": self.state,
            "error": self.error,
            "scheduler": self.settings.scheduler or "local",
            "workers": self.n_workers() if self._ready.is_set() else 0,
        }

    def _close_quietly(self) -> None:
        for obj in (self._client, self._cluster):
            if obj is None:
                continue
            try:
                obj.close()
            except Exception:  # closing a half-started cluster may fail: nothing to keep
                pass
        self._client = self._cluster = None

    def close(self) -> None:
        with self._lock:
            self.state = "closed"
            self._ready.clear()
            self._close_quietly()
