"""One study executing on Dask: batching, streaming results into the store, progress.

A :class:`StudyJob` runs in its own thread. It skips the runs the store already has (so a
restarted service resumes where it stopped), cuts the rest into batches of about
``task_seconds`` of work (the first wave is one run per task, to measure), submits them
with explicit keys, keeps about two tasks per worker in flight, and streams them back with
``as_completed(..., with_results=True, raise_errors=False)``. A task that errors (a worker
lost too often) becomes failed rows; the study goes on.

The thread never blocks on the scheduler: it waits for the client with a timeout, polls for
finished tasks, and leaves as soon as the study is cancelled or the service stops (tasks in
flight are released, not waited for). When the client is lost, the tasks in flight go back
into the queue and the job waits for Dask again.
"""

from __future__ import annotations

import hashlib
import logging
import math
import threading
import time
import uuid
from collections import deque

import pyarrow as pa
from distributed import KilledWorker, as_completed

from beltstudy import engine
from beltstudy.service.dask.executor import LIVE_CLIENT_STATES
from beltstudy.service.dask.tasks import Specs, run_batch, start_candidate
from beltstudy.service.errors import Unavailable
from beltstudy.service.grid.expand import ResolvedStudy, RunSpec
from beltstudy.service.store.columns import (
    axis_value,
    failed_row,
    rows_to_table,
    runs_schema_for_axes,
)
from beltstudy.service.store.parquet import PART_TABLES, Store

__all__ = ["StudyJob", "study_schema", "batch_size", "RunRate", "NoWorkers",
           "NO_WORKER_PREFIX"]

log = logging.getLogger("beltstudy.jobs")


class NoWorkers(Unavailable):
    """Dask could not start any worker for the study's whole wait: the study fails."""

#: Tasks kept in flight per worker.
IN_FLIGHT_PER_WORKER = 2
#: Largest batch [runs].
MAX_BATCH = 1000
#: Smallest work per task once the run time is known [s]: a task costs a few ms beyond its
#: runs (the scheduler's round trip, which the tasks in flight hide, and a part file); the last
#: tasks of a study are cut down to it so no worker idles long while another finishes.
MIN_TASK_S = 0.05
#: Runs per task in the first wave, before any run time is measured.
FIRST_BATCH_STEADY = 8
FIRST_BATCH_DYNAMIC = 1
#: How often study.json is rewritten while running [s].
SAVE_EVERY_S = 1.0
#: Finished batches are written together: at least this often [s] or this many runs. Runs
#: not yet written when the service dies are simply run again.
FLUSH_S = 1.0
FLUSH_RUNS = 1000
#: How often a running job looks for finished tasks and for a stop [s].
POLL_S = 0.02
#: How long a job waits for Dask before noting it in ``message`` and waiting again [s].
WAIT_FOR_DASK_S = 5.0
#: How often a running job asks the executor whether any worker is connected [s] (the
#: client's cached scheduler information: no call to the scheduler).
WORKERS_CHECK_S = 1.0
#: A study fails when Dask has kept failing to start (no cluster, no scheduler, no worker
#: joining: ``Executor.failing_since``) for this long [s]; with the connect and join
#: timeouts a study with no worker able to start fails within 30 s. A cluster that is
#: starting or compiling is waited for without limit.
NO_WORKER_FAIL_S = 12.0
#: How the message of a study failed for want of Dask workers starts (such a study starts
#: again when it is submitted again).
NO_WORKER_PREFIX = "no Dask worker could start in"


def _part_key(batch: list[RunSpec]) -> str:
    """Part file key of a set of runs (the same runs always give the same key)."""
    return hashlib.sha256("".join(r.run_id for r in batch).encode()).hexdigest()[:16]


def adjacent_starts(runs: list[RunSpec]) -> list[RunSpec]:
    """``runs`` with those that may share a start (:func:`start_candidate`) side by side, in
    the order their first run came (a stable regrouping: a study's other order is kept)."""
    groups: dict[tuple, list[RunSpec]] = {}
    memo: dict = {}
    for r in runs:
        groups.setdefault(start_candidate(r, memo), []).append(r)
    return [r for g in groups.values() for r in g]


def batch_size(
    per_run_s: float | None, pending: int, cap: int, task_seconds: float, dynamics: bool
) -> int:
    """Runs in the next task: about ``task_seconds`` of work, smaller near the end so every
    worker stays busy, but never under ``MIN_TASK_S`` of work.
    Before any run time is measured (``per_run_s`` None): a first wave of small tasks."""
    if per_run_s is None:
        return FIRST_BATCH_DYNAMIC if dynamics else FIRST_BATCH_STEADY
    per_run_s = max(per_run_s, 1e-6)
    size = int(task_seconds / per_run_s)
    fair = math.ceil(pending / max(cap, 1))
    floor = math.ceil(MIN_TASK_S / per_run_s)
    return max(1, min(size, max(fair, floor), MAX_BATCH))


class RunRate:
    """The run rate measured from finished tasks, for the time left.

    Until a task finishes nothing is known (no ETA: start-up, warm-up and numba compiling are
    not runs). From the first finished task on, the rate is the runs finished since then over
    the time since then, once that window is at least two tasks long; before that, the
    measured compute time per run spread over the workers.
    """

    def __init__(self, clock=time.monotonic):
        self.clock = clock
        self.first_t: float | None = None
        self.first_runs = 0
        self.runs = 0
        self.tasks = 0
        self.seconds = 0.0

    def finished(self, runs: int, seconds: float) -> None:
        """A task with ``runs`` runs finished after ``seconds`` of compute."""
        if self.first_t is None:
            self.first_t = self.clock()
            self.first_runs = runs
        self.runs += runs
        self.tasks += 1
        self.seconds += seconds

    def eta_s(self, remaining: int, workers: int) -> float | None:
        """Seconds left for ``remaining`` runs on ``workers`` workers (None: not known yet)."""
        if remaining <= 0:
            return 0.0
        if self.first_t is None or self.runs == 0:
            return None
        since = self.runs - self.first_runs
        span = self.clock() - self.first_t
        if since > 0 and span > 0 and span >= 2.0 * self.seconds / self.tasks:
            rate = since / span
        else:
            rate = max(workers, 1) * self.runs / max(self.seconds, 1e-9)
        return remaining / rate


def study_schema(study: ResolvedStudy) -> pa.Schema:
    """The runs schema of a study (axis column types from the axis values)."""
    return runs_schema_for_axes([a.to_json() for a in study.axes])


class StudyJob:
    """Executes the missing runs of one study; progress readable from other threads."""

    def __init__(self, study: ResolvedStudy, store: Store, executor, settings, on_exit=None,
                 doc: dict | None = None):
        """``doc``: the study's stored status when it was stored before (a resumed study), so
        its progress reads what the store last said (not 0 runs done) until :meth:`_execute`
        has counted its stored runs."""
        doc = doc or {}
        self.study = study
        self._on_exit = on_exit  # called with the job when its thread ends
        self.store = store
        self.executor = executor
        self.settings = settings
        self.state = "queued"
        self.done = int(doc.get("done") or 0)
        self.failed = int(doc.get("failed") or 0)
        self.session_done = 0
        self.session_start: float | None = None
        self.elapsed_before = float(doc.get("elapsed_s") or 0.0)
        self._cancel = threading.Event()
        self._stop = threading.Event()
        self._lock = threading.Lock()
        self._inflight: dict = {}
        self._ac = None
        self._buffer: list[tuple[list[RunSpec], dict]] = []
        self._buffered = 0
        self.rate = RunRate()
        #: where the workers' time went in this session (sums over finished tasks [s])
        self.worker_s: dict[str, float] = {}
        self._last_flush = time.monotonic()
        self._per_run_s: float | None = None
        self._waited = False  # the study's message says it waits for Dask
        self._workers_checked = 0.0  # when _note_workers last looked (monotonic) [s]
        self._thread = threading.Thread(
            target=self._main, name=f"beltstudy-study-{study.id}", daemon=True
        )
        self.schema = study_schema(study)
        self._types = {f.name: f.type for f in self.schema}

    # ---------------------------------------------------------------- control
    def start(self) -> None:
        self._thread.start()

    def is_alive(self) -> bool:
        return self._thread.is_alive()

    def join(self, timeout: float | None = None) -> None:
        self._thread.join(timeout)

    def cancel(self) -> None:
        """Stop for good (the caller deletes the study); returns at once, never waits on Dask:
        the job thread releases its tasks in flight on its way out."""
        self._cancel.set()
        self.stop()

    def stop(self) -> None:
        """Stop for a service shutdown: the study stays ``running`` and resumes next start.
        Returns at once; the thread leaves within about ``POLL_S``."""
        self._stop.set()  # also wakes a job waiting for Dask
        ac = self._ac
        if ac is not None:
            ac.clear()  # wakes the job if it waits on finished tasks

    def _release_inflight(self) -> list[list[RunSpec]]:
        """Forget the tasks in flight (the scheduler drops them; non-blocking); their runs."""
        with self._lock:
            inflight, self._inflight = self._inflight, {}
        for fut in inflight:
            try:
                fut.release()
            except Exception:  # client already closed: nothing left to release
                pass
        return list(inflight.values())

    @property
    def halted(self) -> bool:
        return self._cancel.is_set() or self._stop.is_set()

    # ---------------------------------------------------------------- progress
    def elapsed_s(self) -> float:
        run = time.monotonic() - self.session_start if self.session_start else 0.0
        return self.elapsed_before + run

    def eta_s(self) -> float | None:
        """Time left from the measured run rate (:class:`RunRate`); None until a task of this
        session has finished, and again from a lost Dask client until a task finishes on
        the next one."""
        remaining = self.study.total - self.done - self._buffered
        if remaining > 0 and self._no_workers():
            return None  # nothing runs until a worker joins: no time left to tell
        try:
            workers = self.executor.n_workers()
        except Exception:  # the cluster is gone: the measured rate alone
            workers = 1
        return self.rate.eta_s(remaining, workers)

    def _save(self, **extra) -> None:
        if self._cancel.is_set():
            return
        self.store.update(
            self.study.id,
            state=self.state,
            done=self.done,
            failed=self.failed,
            elapsed_s=round(self.elapsed_s(), 3),
            worker_s={k: round(v, 4) for k, v in self.worker_s.items()},
            **extra,
        )

    # ---------------------------------------------------------------- main loop
    def _main(self) -> None:
        try:
            self._execute()
        except NoWorkers as exc:  # said in the study's message, not an unexpected error
            log.warning("study %s failed: %s", self.study.id, exc.message)
            if not self._cancel.is_set():
                self.state = "failed"
                self._save(message=exc.message, finished_at=time.time())
        except Exception as exc:  # an unexpected error ends this study, not the service
            log.exception("study %s failed", self.study.id)
            if not self._cancel.is_set():
                self.state = "failed"
                self._save(message=f"{type(exc).__name__}: {exc}", finished_at=time.time())
        finally:
            self._release_inflight()
            self._buffer, self._ac = [], None
            if self._on_exit is not None:
                self._on_exit(self)

    def _new_session(self) -> dict:
        """A new store token: workers still finishing tasks of an earlier session (an external
        cluster outlives a killed service, a lost client) can no longer write into this study;
        then the parts such tasks left without their runs part are removed."""
        sid = self.study.id
        doc = self.store.update(sid, store_token=uuid.uuid4().hex)
        self._sink = {
            "dir": str(self.store.study_dir(sid).resolve()),
            "token": doc["store_token"],
        }
        self.store.clean(sid)
        return doc

    def _execute(self) -> None:
        sid = self.study.id
        doc = self.store.read(sid)
        self.elapsed_before = float(doc.get("elapsed_s") or 0.0)
        doc = self._new_session()
        have = self.store.done_runs(sid)
        done_ids = set(have["run_id"]) if len(have) else set()
        self.done = len(done_ids)
        self.failed = int((have["status"] == "failed").sum()) if len(have) else 0
        todo = deque(adjacent_starts([r for r in self.study.runs if r.run_id not in done_ids]))
        del have, done_ids
        lost = False
        while todo and not self.halted:
            client = self._wait_for_client()
            if client is None:
                return
            if lost:
                self._new_session()
            if self.state != "running":
                self.state = "running"
                self.session_start = time.monotonic()
                self._save(started_at=doc.get("started_at") or time.time(), message="")
            elif self._waited:  # back on Dask after losing it: no longer waiting
                self._save(message="")
            self._waited = False
            lost = self._stream(client, todo)
            if lost:  # nothing runs until Dask is back: no time left until it is measured
                self.rate = RunRate()  # again (not a rate averaged over the outage)
        if self.halted:
            if self.session_start is not None:  # a stop wrote what finished: say so (a
                self._save()  # cancel saves nothing)
            return
        self.state = "done"
        self._save(finished_at=time.time(), message=self._final_message())

    def _final_message(self) -> str:
        if self.failed:
            return f"{self.failed} of {self.study.total} runs failed"
        return ""

    def _wait_for_client(self):
        """The executor's client, or None once the job is halted (never blocks longer).

        While Dask starts or its workers compile, the study waits and says so; when Dask has
        failed to start for :data:`NO_WORKER_FAIL_S` (its ``error`` state throughout), the
        study fails naming why (:class:`NoWorkers`)."""
        while not self.halted:
            t0 = time.monotonic()
            try:
                if self.session_start is None:  # not on a client reconnecting to a lost
                    return self.executor.client(  # scheduler: that is no Dask to start on
                        timeout=WAIT_FOR_DASK_S, halt=self._stop, connected=True)
                return self.executor.client(timeout=WAIT_FOR_DASK_S, halt=self._stop)
            except Unavailable as exc:
                if self.halted:
                    break
                since = getattr(self.executor, "failing_since", None)
                # a study that has not started here fails; one that lost its scheduler
                # mid-study waits for it to come back (its message says so)
                if (self.session_start is None and since is not None
                        and time.monotonic() - since >= NO_WORKER_FAIL_S):
                    raise NoWorkers(
                        f"{NO_WORKER_PREFIX} {NO_WORKER_FAIL_S:g} s: "
                        f"{self.executor.error or exc}; its finished runs are kept: submit "
                        "the study again once Dask works and it goes on") from None
                self._save(message=f"waiting for Dask: {exc}")
                self._waited = True
                self._stop.wait(max(0.0, WAIT_FOR_DASK_S - (time.monotonic() - t0)))
        return None

    def _stream(self, client, todo: deque[RunSpec]) -> bool:
        """Run ``todo`` on ``client`` until it is empty, the job is halted, or the client is
        lost (then the batches in flight go back into ``todo`` and this returns True)."""

        sid = self.study.id
        nonce = uuid.uuid4().hex[:8]
        seq = 0
        per_run_s: float | None = self._per_run_s
        ac = as_completed([], with_results=True, raise_errors=False, loop=client.loop)
        self._ac = ac
        last_save = time.monotonic()

        memo: dict = {}  # conveyor mapping -> its start key (start_candidate)

        def top_up() -> None:
            nonlocal seq
            cap = max(2, IN_FLIGHT_PER_WORKER * self.executor.n_workers())
            while todo and len(self._inflight) < cap and not self.halted:
                size = batch_size(
                    per_run_s, len(todo), cap, self.settings.task_seconds, self.study.dynamics
                )
                batch = [todo.popleft() for _ in range(min(size, len(todo)))]
                # runs that may share a start go to one task whole (beltstudy.engine.run.run_group)
                while todo and (start_candidate(todo[0], memo)
                                == start_candidate(batch[-1], memo)):
                    batch.append(todo.popleft())
                key = f"beltstudy-{sid}-{nonce}-{seq:06d}"
                seq += 1
                sink = {**self._sink, "key": _part_key(batch)}
                try:
                    fut = client.submit(
                        run_batch, sid, Specs(batch), self.study.surface, sink, key=key,
                        pure=False,
                    )
                except Exception:
                    if client.status in LIVE_CLIENT_STATES:
                        raise
                    todo.extendleft(reversed(batch))  # the client is gone: the caller sees it
                    return
                with self._lock:
                    self._inflight[fut] = batch
                ac.add(fut)

        lost = False
        top_up()
        while self._inflight and not self.halted:
            self._note_workers()
            if not ac.has_ready():
                if client.status not in LIVE_CLIENT_STATES:
                    lost = True
                    break
                self._stop.wait(POLL_S)
                continue
            for fut, result in ac.next_batch(block=False):
                with self._lock:
                    batch = self._inflight.pop(fut, None)
                if self.halted or batch is None:
                    continue
                if fut.status == "finished":
                    n = len(batch)
                    self.rate.finished(n, float(result["seconds"]))
                    self._account(n, result)
                    self._add(batch, result)
                    sample = result["seconds"] / n
                    per_run_s = sample if per_run_s is None else 0.7 * per_run_s + 0.3 * sample
                elif fut.status == "cancelled":
                    todo.extendleft(reversed(batch))  # cancelled by the scheduler: run again
                else:
                    exc = result[1] if isinstance(result, tuple) else result
                    message = task_failed_words(exc)
                    self._add(batch, {"rows": [self._failed(r, message) for r in batch]})
                fut.release()
            top_up()
            if time.monotonic() - last_save > SAVE_EVERY_S:
                self._save()
                last_save = time.monotonic()
        self._per_run_s = per_run_s
        self._ac = None
        lost = lost or (not self.halted and client.status not in LIVE_CLIENT_STATES)
        if lost:
            log.warning("study %s: lost the Dask client; its tasks in flight will run again", sid)
            for batch in self._release_inflight():
                todo.extendleft(reversed(batch))
        if not self._cancel.is_set():
            self._flush()  # also on a shutdown: what finished is kept
        return lost

    def _no_workers(self) -> str:
        """Why no task can run now ("" when a worker is connected or it is not known)."""
        no_workers = getattr(self.executor, "no_workers", None)
        try:
            return no_workers() if no_workers is not None else ""
        except Exception:  # the client is going away: the stream loop sees that itself
            return ""

    def _note_workers(self) -> None:
        """Say in the study's message that it waits for a worker while the scheduler has none
        (an external cluster whose workers were killed, or ended with a scheduler restarted
        within the client's reconnect time: the client is connected, the tasks wait), and
        clear it once one has joined. At most every ``WORKERS_CHECK_S``."""
        now = time.monotonic()
        if now - self._workers_checked < WORKERS_CHECK_S:
            return
        self._workers_checked = now
        why = self._no_workers()
        if why and not self._waited:
            self._save(message=f"waiting for Dask: {why}")
            self._waited = True
        elif not why and self._waited:
            self._save(message="")
            self._waited = False

    def _account(self, runs: int, result: dict) -> None:
        """Add a finished task's time to ``worker_s``: runs, tasks, task wall time and its
        split (running the runs, building tables, writing parts, CPU)."""
        acc = self.worker_s
        acc["runs"] = acc.get("runs", 0) + runs
        acc["tasks"] = acc.get("tasks", 0) + 1
        acc["task_s"] = acc.get("task_s", 0.0) + float(result.get("seconds") or 0.0)
        for key, value in (result.get("split") or {}).items():
            acc[key] = acc.get(key, 0.0) + float(value)

    def _add(self, batch: list[RunSpec], result: dict) -> None:
        """Buffer a finished batch; write the buffer every ``FLUSH_S`` or ``FLUSH_RUNS``."""
        self._buffer.append((batch, result))
        self._buffered += len(batch)
        if self._buffered >= FLUSH_RUNS or time.monotonic() - self._last_flush >= FLUSH_S:
            self._flush()

    def _flush(self) -> None:
        if not self._buffer:
            return
        runs = [r for batch, _ in self._buffer for r in batch]
        merged: dict = {"rows": [row for _, res in self._buffer for row in res["rows"]]}
        for table in PART_TABLES:
            parts = [res[table] for _, res in self._buffer if res.get(table) is not None]
            merged[table] = pa.concat_tables(parts) if parts else None
        self._buffer, self._buffered = [], 0
        self._last_flush = time.monotonic()
        self._commit(runs, merged)

    def _failed(self, spec: RunSpec, message: str) -> dict:
        row = {
            "study_id": self.study.id,
            "run_id": spec.run_id,
            **spec.axes,
            "friction_model": spec.model,
            "engine_version": engine.__version__,
        }
        row.update(failed_row(message))
        return row

    def _commit(self, batch: list[RunSpec], result: dict) -> None:
        """Write finished runs: time series first, the runs part last (the commit point)."""
        if self._cancel.is_set():
            return
        key = _part_key(batch)
        sid = self.study.id
        for table in PART_TABLES:
            data = result.get(table)
            if data is not None and data.num_rows:
                self.store.write_part(sid, table, key, data)
        rows = result["rows"]
        for row in rows:
            for col, value in list(row.items()):
                typ = self._types.get(col)
                if typ is not None and col in self.study.columns and value is not None:
                    row[col] = axis_value(value, typ)
        self.store.write_part(sid, "runs", key, rows_to_table(rows, self.schema))
        self.done += len(rows)
        self.failed += sum(1 for r in rows if r.get("status") == "failed")
        self.session_done += len(rows)


def task_failed_words(exc: BaseException) -> str:
    """A failed row's message for a task that raised ``exc`` (at most 1 000 characters).

    A task whose workers died under it (Dask's ``KilledWorker``, after its allowed failures)
    said only Dask's own text ('Attempted to run task ... on 4 different workers ...
    Inspecting worker logs ...'): it is said in the study's terms, with its likely causes
    and the way to run it again (a failed row is a finished run: a resubmission finds the
    study done)."""
    if isinstance(exc, KilledWorker):
        return ("task failed: the Dask worker running it died each time it was tried "
                "(KilledWorker: killed from outside, or out of memory); the run itself was "
                "not judged: if it is memory, a coarser mesh (scenario.elements) or fewer "
                "time-series records (scenario.record_dt_s) lighten it; to run it again, "
                "DELETE the study and submit it again")[:1000]
    return f"task failed: {type(exc).__name__}: {exc}"[:1000]
