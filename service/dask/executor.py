"""The Dask side: one client per service, to a LocalCluster or to an existing scheduler.

With ``BELTSTUDY_SCHEDULER`` empty the service starts a :class:`distributed.LocalCluster` of
worker processes, one thread each (``BELTSTUDY_WORKERS``, default one per core); with
``tcp://host:port`` it connects to that scheduler. Once connected every worker runs
:func:`beltstudy.service.dask.tasks.warm_up` (imports, numba compile) before any study is timed.

Connecting happens in one background thread that retries until it succeeds or the executor
is closed; nobody else ever waits on it while holding a lock. Callers wait for the client
with a timeout (:meth:`Executor.client`), and :meth:`Executor.close` waits on Dask at most
``BELTSTUDY_DASK_TIMEOUT_S`` per step, so a scheduler that is gone never holds up a request
or a shutdown.
"""

from __future__ import annotations

import logging
import re
import threading
import time
import uuid
from urllib.parse import urlsplit, urlunsplit

import dask
from distributed import Client, LocalCluster

from beltstudy import engine
from beltstudy.service.dask.tasks import LowerPriority, warm_up
from beltstudy.service.errors import Unavailable
from beltstudy.service.settings import Settings

__all__ = ["Executor"]

log = logging.getLogger("beltstudy.executor")

#: How long to wait for workers to appear and warm up [s].
WARM_TIMEOUT_S = 600.0
#: How long to wait for a first worker to join an external scheduler before that counts as a
#: failure to start (reported in ``error``, then retried) [s]: a study waiting on Dask fails
#: once it has failed for ``jobs.NO_WORKER_FAIL_S``.
JOIN_TIMEOUT_S = 10.0
#: The executor's ``state`` while its workers run their warm-up (the engine compiles there).
WARMING = "warming"
#: Pause between two attempts to reach Dask [s].
RETRY_S = 5.0
#: Dask settings of the LocalCluster (inherited by its worker processes): no statistical
#: profiler sampling every worker each 10 ms, no GIL monitor, a slower event-loop tick, the
#: system monitor (CPU, memory and network of each process, for the dashboard) every 2 s
#: without host-wide disk counters, and the memory monitors (spilling, pausing, the nanny's
#: restart at 95 %) every 0.5 s instead of 0.1 s: a run's memory is a few MB.
#: An idle cluster then costs a few % of a core instead of ~15 %: on 2 cores that matters.
LOCAL_DASK_CONFIG = {
    "distributed.worker.profile.enabled": False,
    "distributed.admin.system-monitor.gil.enabled": False,
    "distributed.admin.tick.interval": "200ms",
    "distributed.admin.system-monitor.interval": "2s",
    "distributed.admin.system-monitor.disk": False,
    "distributed.worker.memory.monitor-interval": "500ms",
}
#: Dask settings of this process, for either kind of cluster: its batched comms (the client's
#: and an in-process scheduler's) keep no log of their last 1000 messages (a debugging aid):
#: those hold the tasks sent, so the runs of a finished study, with their conveyors.
PROCESS_DASK_CONFIG = {"distributed.admin.low-level-log-length": 0}
#: CPU niceness of the LocalCluster's worker processes: below the API, which shares the cores.
LOCAL_WORKER_NICE = 10
#: Client states in which futures still make progress (``connecting``: reconnecting).
LIVE_CLIENT_STATES = ("running", "connecting")


def _close_quietly(client, cluster, timeout_s: float) -> None:
    """Close a client and a cluster, waiting at most ``timeout_s`` on each."""
    for obj in (client, cluster):
        if obj is None:
            continue
        try:
            obj.close(timeout=timeout_s)
        except Exception:  # a half-started cluster or a scheduler that is gone: nothing to keep
            pass


def _dashboard_link(link: str, host: str) -> str:
    """The dashboard's address on ``host``, where it listens: Dask's link names the
    scheduler's address (loopback) whatever host the dashboard binds to. A wildcard host
    keeps Dask's link, which reaches it."""
    if host in ("", "0.0.0.0", "::", "[::]"):
        return link
    parts = urlsplit(link)
    name = f"[{host.strip('[]')}]" if ":" in host else host
    netloc = f"{name}:{parts.port}" if parts.port is not None else name
    return urlunsplit(parts._replace(netloc=netloc))


class Executor:
    """Lazily connected Dask client shared by every study of a service."""

    def __init__(self, settings: Settings):
        self.settings = settings
        self.state = "idle"  # idle | starting | warming | ready | error | closed
        self.error = ""
        #: When Dask first failed to start since it was last ready (monotonic) [s], or None;
        #: also set when a ready client is found reconnecting to a lost scheduler
        self.failing_since: float | None = None
        #: When the ready client was first found reconnecting to its lost scheduler
        #: (monotonic) [s], or None: cleared when it reconnects or a new client is ready
        self._lost_at: float | None = None
        self.warm: dict[str, dict] = {}
        self.dashboard: str | None = None
        self._client = None
        self._cluster = None
        self._lock = threading.Lock()  # guards the fields; never held while talking to Dask
        self._ready = threading.Event()
        self._closed = threading.Event()
        self._thread: threading.Thread | None = None

    # ---------------------------------------------------------------- lifecycle
    def start_background(self) -> None:
        """Connect and warm up in a thread (the API answers meanwhile); no-op if under way."""
        with self._lock:
            if self._closed.is_set() or (self._thread is not None and self._thread.is_alive()):
                return
            self._thread = threading.Thread(
                target=self._connect_loop, name="beltstudy-executor", daemon=True
            )
            self._thread.start()

    def _connect_loop(self) -> None:
        where = self.settings.scheduler or "a LocalCluster"
        last_error = ""
        while not self._closed.is_set():
            if self.failing_since is None:  # a retry keeps saying the failure ("error"), not
                self.state = "starting"  # "starting" every other 5 s
            try:
                client, cluster = self._connect()
            except Exception as exc:
                last_error = self._failed(exc, where, last_error)
                self._closed.wait(RETRY_S)
                continue
            with self._lock:
                closed = self._closed.is_set()
                if not closed:
                    self._client, self._cluster = client, cluster
            if closed:  # closed while connecting: close what was made here
                _close_quietly(client, cluster, self.settings.dask_timeout_s)
                return
            # the workers compile the transient engine (first run only); a worker joined, so
            # an earlier failure to start is over (its words would send the operator to start
            # workers that are compiling, and fail a waiting study 12 s after it)
            with self._lock:
                self.state, self.error, self.failing_since = WARMING, "", None
                self._lost_at = None
            try:
                self._warm_up(client)
            except Exception as exc:
                last_error = self._failed(exc, where, last_error)
                self._drop()
                self._closed.wait(RETRY_S)
                continue
            with self._lock:
                if self._closed.is_set():
                    return
                self.state, self.error = "ready", self._other_engines()
                self.failing_since = None
                self._ready.set()
            return

    def _other_engines(self) -> str:
        """The workers warmed on another engine version than this service's, in words ("" for
        none): every run sent to one fails, and ``/health`` said ``ready`` without a word."""
        other = sorted({f"{w.get('engine_version')} ({a})" for a, w in self.warm.items()
                        if w.get("engine_version") not in (None, engine.__version__)})
        if not other:
            return ""
        log.warning("workers on another engine version: %s", ", ".join(other))
        return (f"workers on another engine than this service's {engine.__version__}: "
                f"{', '.join(other)}; install the service's beltstudy on them and restart them "
                "(their runs fail until then)")

    def _start_fix(self) -> str:
        """How to bring an external scheduler and its workers back, in words."""
        address = self.settings.scheduler
        port = re.search(r":(\d+)/?$", address)
        scheduler = (f"'dask scheduler --port {port[1]}' on its host" if port
                     else "'dask scheduler' on its host")
        return f"start it ({scheduler}) and its workers ('dask worker {address}')"

    def unreachable(self, why: str) -> str:
        """Why the external scheduler cannot be used (``why``) and the fix, naming it: what a
        study waiting for it and ``/health`` say (Dask's own ``OSError: Timed out trying to
        connect to ...`` named neither what to do nor that it was the scheduler)."""
        return (f"cannot reach the Dask scheduler {self.settings.scheduler} ({why}): "
                f"{self._start_fix()}")

    def _failed(self, exc: Exception, where: str, last_error: str) -> str:
        error = exc.message if isinstance(exc, Unavailable) else f"{type(exc).__name__}: {exc}"
        if self.settings.scheduler and not isinstance(exc, Unavailable):
            error = self.unreachable(error)  # no scheduler there (Unavailable: no worker)
        if not self._closed.is_set():
            self.state, self.error = "error", error
            if self.failing_since is None:
                self.failing_since = time.monotonic()
            if error != last_error:  # once per distinct failure, not every retry
                log.warning("cannot start Dask on %s: %s (retrying every %.0f s)",
                            where, error, RETRY_S)
        return error

    def _connect(self):
        timeout = f"{self.settings.dask_timeout_s}s"
        dask.config.set(PROCESS_DASK_CONFIG)
        if self.settings.scheduler:
            client = Client(self.settings.scheduler, timeout=timeout, set_as_default=False)
            try:
                client.wait_for_workers(1, timeout=JOIN_TIMEOUT_S)
            except Exception as exc:
                _close_quietly(client, None, self.settings.dask_timeout_s)
                raise Unavailable(
                    f"no Dask worker joined the scheduler {self.settings.scheduler} within "
                    f"{JOIN_TIMEOUT_S:g} s ({type(exc).__name__}); start workers with "
                    f"'dask worker {self.settings.scheduler}'") from None
            return client, None

        dask.config.set(LOCAL_DASK_CONFIG)
        dashboard = (
            f"{self.settings.host}:{self.settings.dashboard_port}"
            if self.settings.dashboard
            else None
        )
        cluster = LocalCluster(
            n_workers=self.settings.n_local_workers,
            threads_per_worker=1,
            processes=True,
            host="127.0.0.1",
            dashboard_address=dashboard,
            # without the dashboard the scheduler still serves /health and metrics over
            # HTTP: on loopback, on a free port
            scheduler_kwargs=None if dashboard else {"dashboard_address": "127.0.0.1:0"},
            silence_logs=logging.ERROR,
        )
        try:
            client = Client(cluster, set_as_default=False, timeout=timeout)
        except Exception:
            _close_quietly(None, cluster, self.settings.dask_timeout_s)
            raise
        if dashboard is not None:
            self.dashboard = _dashboard_link(cluster.dashboard_link, self.settings.host)
            log.info("Dask dashboard at %s (no token: keep it on a trusted network)",
                     self.dashboard)
        return client, cluster

    def _warm_up(self, client) -> None:
        if not self.settings.scheduler:  # our own workers, on the API's cores
            client.register_plugin(LowerPriority(LOCAL_WORKER_NICE))
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
            if self._closed.is_set():
                return
            try:
                self.warm[addr] = fut.result(timeout=WARM_TIMEOUT_S)
            except Exception as exc:  # a worker that cannot warm up still gets work
                self.warm[addr] = {"errors": [f"{type(exc).__name__}: {exc}"]}
        log.info("warmed %d worker%s in %.1f s", len(futures), "" if len(futures) == 1 else "s",
                 time.monotonic() - t0)
        compiled = [a for a, w in self.warm.items() if a in futures and w.get("compiled")]
        if compiled and not self.settings.scheduler and not self._closed.is_set():
            # A process that compiled the kernel computes other last bits (about 1e-12) than
            # one that loads it from numba's cache: so that a run gives the same stored figures
            # whichever worker runs it, the workers that compiled start again and load it
            log.info("restarting %d workers that compiled the kernel, to load it from the "
                     "cache", len(compiled))
            try:
                client.restart_workers(compiled, timeout=WARM_TIMEOUT_S)
                addrs = list(client.scheduler_info(n_workers=-1)["workers"])
                again = [client.submit(warm_up, key=f"beltstudy-warm-up-{nonce}-again-{i}",
                                       workers=[a], allow_other_workers=False, pure=False)
                         for i, a in enumerate(addrs)]
                self.warm = {a: f.result(timeout=WARM_TIMEOUT_S)
                             for a, f in zip(addrs, again, strict=True)}
            except Exception as exc:  # the workers go on with the kernel they compiled
                log.warning("could not restart the workers that compiled the kernel (%s: %s); "
                            "their runs may differ from other processes' in the last bits",
                            type(exc).__name__, exc)

    def _drop(self) -> None:
        """Forget a client that is no longer usable (closing it in the background)."""
        with self._lock:
            client, cluster = self._client, self._cluster
            self._client = self._cluster = None
            self._ready.clear()
        if client is not None or cluster is not None:
            threading.Thread(
                target=_close_quietly,
                args=(client, cluster, self.settings.dask_timeout_s),
                name="beltstudy-executor-close",
                daemon=True,
            ).start()

    # ---------------------------------------------------------------- use
    def _lost_words(self) -> str:
        """What ``error`` says while the scheduler is lost and the client reconnects."""
        if not self.settings.scheduler:
            return "lost the Dask scheduler of the service's LocalCluster; reconnecting"
        return (f"lost the Dask scheduler {self.settings.scheduler}: {self._start_fix()} "
                "(the service reconnects when it is back)")

    def _note_client(self, client) -> str:
        """The ready ``client``'s status, noted in ``state`` and ``error``: a client
        reconnecting to its lost scheduler is a failure of Dask from when it was first seen
        (``failing_since``: a study that has not started fails after ``NO_WORKER_FAIL_S`` of
        it, as when the service cannot reach the scheduler at its start), and that note is
        cleared when it is connected again."""
        status = client.status
        with self._lock:
            if self._client is not client or self._closed.is_set():
                return status
            if status == "connecting" and self._lost_at is None:
                log.warning("lost the Dask scheduler %s; reconnecting",
                            self.settings.scheduler or "of the LocalCluster")
                self._lost_at = time.monotonic()
                self.state, self.error = "error", self._lost_words()
                if self.failing_since is None:
                    self.failing_since = self._lost_at
            elif status == "running" and self._lost_at is not None:
                log.info("reconnected to the Dask scheduler")
                self._lost_at = self.failing_since = None
                self.state, self.error = "ready", ""
        return status

    def _live_client(self, connected: bool = False):
        """The ready client, or None; a client that closed itself (its scheduler was gone
        longer than the connect timeout) is dropped and a new connection started.
        ``connected``: not a client reconnecting to a lost scheduler either (a study that has
        not started waits for a scheduler that is there)."""
        if not self._ready.is_set():
            return None
        client = self._client
        if client is not None:
            status = self._note_client(client)
            if status == "running" or (status in LIVE_CLIENT_STATES and not connected):
                return client
            if status in LIVE_CLIENT_STATES:  # reconnecting: not for a study to start on
                return None
        if self._closed.is_set():
            return None
        log.warning("lost the Dask scheduler; reconnecting")
        with self._lock:
            self.state, self.error = "error", self._lost_words()
            if self.failing_since is None:  # the loss is a failure from when it was seen
                self.failing_since = self._lost_at or time.monotonic()
            self._lost_at = None
        self._drop()
        self.start_background()
        return None

    def client(self, timeout: float | None = None, halt: threading.Event | None = None,
               connected: bool = False):
        """The connected, warmed client; starts connecting on first use.

        Waits at most ``timeout`` seconds (None: until ready), and returns None as soon as
        ``halt`` is set. Raises :class:`Unavailable` when closed or out of time.
        ``connected``: a client reconnecting to its lost scheduler is waited for too (what a
        study that has not started asks: one that has keeps its tasks through a reconnect).
        """
        deadline = None if timeout is None else time.monotonic() + timeout
        while True:
            client = self._live_client(connected)
            if client is not None:
                return client
            if self._closed.is_set():
                raise Unavailable("the service is shutting down")
            self.start_background()
            if halt is not None and halt.is_set():
                return None
            left = None if deadline is None else deadline - time.monotonic()
            if left is not None and left <= 0:
                where = self.settings.scheduler or "a LocalCluster"
                detail = self.error or ("its workers are compiling the transient engine "
                                        "(first run only)" if self.state == WARMING
                                        else f"connecting to the scheduler {where}"
                                        if self.settings.scheduler else "still starting")
                raise Unavailable(f"Dask on {where} is not ready: {detail}")
            self._ready.wait(0.1 if left is None else min(0.1, left))

    def workers_connected(self) -> int | None:
        """Workers connected to the scheduler now, from the client's cached scheduler
        information (refreshed by the client every few seconds; never a call to the
        scheduler); None while no client is ready or before the client has that information.
        0 is a real answer: an external cluster whose workers are all gone (killed, or ended
        with a scheduler that came back within the client's reconnect time)."""
        if not self._ready.is_set():
            return None
        info = getattr(self._client, "_scheduler_identity", None) or {}
        n = info.get("n_workers")
        if n is None and "workers" in info:
            n = len(info["workers"] or {})
        return None if n is None else int(n)

    def n_workers(self) -> int:
        """Workers to plan for (at least 1): :meth:`workers_connected`, else 1."""
        return max(1, self.workers_connected() or 0)

    def no_workers(self) -> str:
        """Why nothing runs when the client is ready but no worker is connected ("" when one
        is, or when that is not known): an external scheduler's workers do not come back on
        their own (a LocalCluster's nannies restart theirs)."""
        if not self.settings.scheduler or self.workers_connected() != 0:
            return ""
        address = self.settings.scheduler
        return (f"no Dask worker is connected to the scheduler {address}; start workers with "
                f"'dask worker {address}'")

    def info(self) -> dict:
        client = self._client
        if client is not None and self._ready.is_set():
            self._note_client(client)  # a scheduler lost while nothing asked for the client
        return {
            "state": self.state,
            "error": self.error or self.no_workers(),
            "scheduler": self.settings.scheduler or "local",
            "workers": self.workers_connected() or 0,
            "dashboard": self.dashboard,
        }

    def close(self) -> None:
        """Stop connecting; close the client and the cluster, at most ``dask_timeout_s`` each."""
        with self._lock:
            self._closed.set()
            self.state = "closed"
            self._ready.clear()
            client, cluster = self._client, self._cluster
            self._client = self._cluster = None
        _close_quietly(client, cluster, self.settings.dask_timeout_s)
