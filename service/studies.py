"""The study service: submit, list, status, results, compare, delete; resume on start.

Routes and the CLI call these methods; they raise :mod:`beltstudy.service.errors` for the caller's
mistakes. One :class:`StudyService` owns the store, the Dask executor and a thread per
running study.

Every way a study gets started (a new submission, a repeated one, a resume on start) goes
through :meth:`StudyService._admit`, which decides and starts under one lock: however many
requests carry the same study at once, it is stored once and runs in one job. A job removes
itself when its thread ends, so a finished study holds no memory here. Deleting and closing
never wait on Dask longer than ``BELTSTUDY_DASK_TIMEOUT_S``.
"""

from __future__ import annotations

import dataclasses
import logging
import os
import threading
import time
from collections import OrderedDict
from concurrent.futures import CancelledError
from pathlib import Path
from typing import Any

import pandas as pd
import pyarrow as pa
from distributed import KilledWorker

from beltstudy import engine
from beltstudy.service.dask.executor import Executor
from beltstudy.service.dask.jobs import NO_WORKER_PREFIX, StudyJob
from beltstudy.service.dask.tasks import (
    profile_table,
    recompute_surface,
    run_spec,
    surface_table,
)
from beltstudy.service.door.studyfile import conveyor_from_path, resolve_study
from beltstudy.service.errors import (
    Conflict,
    Damaged,
    DamagedParts,
    Invalid,
    NotFound,
    ServiceError,
    Unavailable,
    shown_id,
    unknown_run,
)
from beltstudy.service.grid.expand import (
    DEFAULT_MODEL,
    ResolvedStudy,
    RunSpec,
    stable_hash,
    study_from_json,
)
from beltstudy.service.settings import Settings, check_data_dir
from beltstudy.service.store import query
from beltstudy.service.store.claim import DataDirClaim
from beltstudy.service.store.columns import profile_schema, surface_schema
from beltstudy.service.store.parquet import Store, tmp_path

__all__ = ["StudyService", "ACTIVE_STATES", "RESOLVED_CACHE", "SURFACE_CACHE", "study_models",
           "belt_choices", "damaged_status"]

log = logging.getLogger("beltstudy.service")

ACTIVE_STATES = ("queued", "running")
#: Expanded studies kept for run pages and surfaces (a study id is a hash of its content).
RESOLVED_CACHE = 8
#: Recomputed surfaces kept (a run id is a hash of the run's inputs: the surface is the same
#: every time).
SURFACE_CACHE = 4
#: How long a recomputed surface waits for a ready Dask worker before the service computes it
#: itself [s] (a worker has the engine compiled; a cold service process would compile it).
SURFACE_WORKER_WAIT_S = 5.0


def _waits_for_workers(doc: dict) -> bool:
    """Whether a stored study failed only because no Dask worker could start."""
    return doc.get("state") == "failed" and str(doc.get("message", "")).startswith(
        NO_WORKER_PREFIX)


def study_models(doc: dict) -> list[str]:
    """The friction models a stored study runs (its ``friction_model`` axis, or its one
    model)."""
    study = doc.get("study") or {}
    for axis in study.get("axes", []):
        if axis.get("column") == "friction_model":
            return [str(v) for v in axis["values"]]
    return [str(study.get("model") or DEFAULT_MODEL)]


def belt_choices(study: dict) -> list[dict] | None:
    """The belts ``belt.type: auto`` chose for a stored study, as its ``study.json`` holds
    them (:func:`beltstudy.service.grid.basis.design_belt`: type, kind, ``passed`` (False: no
    catalogue belt passes, the heaviest is used and ``note`` is that warning), mass, safety
    factors, the deciding case, ``next_lighter``, ``note``), one per conveyor design that
    chose one, with the design's conveyor ``axes`` ({} for one design); None when the
    conveyor gives its belt."""
    out = [{"axes": d.get("axes") or {}, **d["sizes"]["belt"]}
           for d in study.get("designs") or [] if (d.get("sizes") or {}).get("belt")]
    return out or None


def damaged_status(entry: dict) -> dict:
    """The status of a study whose ``study.json`` cannot be read (a list entry of
    :meth:`Store.list_studies`): state ``damaged``, ``message`` naming the file and the way
    out; the counts it cannot tell are 0, its runs are on disk as they were."""
    return {
        "id": entry["id"], "name": entry.get("name") or "", "state": "damaged",
        "total": 0, "done": 0, "failed": 0, "elapsed_s": 0.0, "eta_s": None,
        "message": entry.get("message", ""), "created_at": entry.get("created_at"),
        "started_at": None, "finished_at": None, "dynamics": False, "grid_points": None,
        "merged": 0, "merged_axes": [], "axes": {}, "engine_version": None,
        "belt_choices": None,
    }


class StudyService:
    """Everything the API and the CLI do with studies."""

    def __init__(self, settings: Settings, executor: Executor | None = None, *,
                 read_only: bool = False):
        self.settings = settings
        # a data folder that is a file or not writable: refused here, when the service or a
        # command starts, not by every POST /studies after /health said ok (``read_only``: a
        # command that only reads the store, which may be an archive it cannot write)
        self.store = Store(check_data_dir(settings.data_dir, write=not read_only))
        # the one process that runs this folder's studies (taken when one starts to run)
        self.claim = None if read_only else DataDirClaim(settings.data_dir)
        self.executor = executor or Executor(settings)
        self._jobs: dict[str, StudyJob] = {}  # studies with a job thread not yet ended
        self._deleting: set[str] = set()
        self._closing = False
        self._lock = threading.Lock()
        self.started_at = time.time()
        self._resolved: OrderedDict[str, ResolvedStudy] = OrderedDict()
        self._surfaces: OrderedDict[str, pa.Table | None] = OrderedDict()
        self._cache_lock = threading.Lock()
        self._slots = threading.BoundedSemaphore(settings.max_expansions)
        self._inflight: dict[str, threading.Event] = {}  # body hash -> its expansion's end
        self.expansions = 0  # studies expanded by submit (a resend of a stored one is not)

    # ---------------------------------------------------------------- lifecycle
    def start(self) -> None:
        """Resume unfinished studies; start (and warm) Dask when configured to."""
        with self._lock:
            self._closing = False
        self._take_claim()
        swept = self.store.sweep()
        if swept:
            log.info("removed %d leftover folders of deleted or half-created studies", swept)
        resumed = 0
        for doc in self.store.list_studies():
            if doc.get("state") in ACTIVE_STATES:
                try:
                    self._admit(self._load(doc))
                    resumed += 1
                except Exception as exc:  # a study that cannot be rebuilt is marked failed
                    log.warning("cannot resume study %s: %s", doc.get("id"), exc)
                    self.store.update(doc["id"], state="failed", message=f"cannot resume: {exc}")
        if resumed:
            log.info("resuming %d unfinished studies", resumed)
        if self.settings.warm_start or resumed:
            self.executor.start_background()

    def close(self) -> None:
        """Stop the study threads (studies stay resumable) and the Dask client; waits at most
        ``dask_timeout_s`` for the threads, then for the client and the cluster."""
        with self._lock:
            self._closing = True
            jobs = list(self._jobs.values())
        for job in jobs:
            job.stop()
        deadline = time.monotonic() + self.settings.dask_timeout_s
        for job in jobs:
            job.join(timeout=max(0.0, deadline - time.monotonic()))
        left = [job.study.id for job in jobs if job.is_alive()]
        if left:
            log.warning("study threads still busy at shutdown: %s", ", ".join(left))
        self.executor.close()
        if self.claim is not None:
            self.claim.drop()

    def _load(self, doc: dict) -> ResolvedStudy:
        if doc.get("engine_version") != engine.__version__:
            raise Invalid(
                f"study was made with engine {doc.get('engine_version')}, this is "
                f"{engine.__version__}; submit it again"
            )
        return study_from_json(doc["study"], doc["id"])

    def _take_claim(self) -> None:
        """Hold the data folder for this process (:class:`DataDirClaim`; a read-only service
        holds nothing)."""
        if self.claim is not None:
            self.claim.take()

    def _admit(self, study: ResolvedStudy) -> bool:
        """Store ``study`` unless it is stored, and run it unless it is finished or running:
        the one way a study starts, decided and done under the lock. Returns whether it was
        new to the store."""
        self._take_claim()
        with self._lock:
            if study.id in self._deleting:
                raise Conflict(
                    f"study '{study.id}' is being deleted; submit it again when that is done"
                )
            created = not self.store.exists(study.id)
            doc = None
            if created:
                self.store.create(study.id, self._new_doc(study))
                active = True
            else:
                doc = self.store.read(study.id)
                active = doc.get("state") in ACTIVE_STATES
                lost = self._rows_lost(study.id, doc)
                if lost and not self._closing:
                    # a done study whose rows were moved out of its folder (a damaged part,
                    # docs say so): submitted again, it runs the runs it no longer has
                    doc = self.store.update(
                        study.id, state="queued", finished_at=None,
                        message=f"{lost} of its {doc['total']} runs' rows are no longer "
                                "stored (a part file moved out of the study's folder): "
                                "running them again")
                    active = True
                elif _waits_for_workers(doc) and not self._closing:
                    # failed for want of Dask workers: submitted again, it goes on
                    doc = self.store.update(study.id, state="queued", message="",
                                            finished_at=None)
                    active = True
            if active and study.id not in self._jobs and not self._closing:
                # a study interrupted earlier (`beltstudy run` stopped) carries on; during a
                # shutdown it stays queued in the store and starts with the service
                job = StudyJob(study, self.store, self.executor, self.settings, self._job_ended,
                               doc=doc)
                self._jobs[study.id] = job
                job.start()
        return created

    def _rows_lost(self, study_id: str, doc: dict) -> int:
        """How many runs a done study no longer has rows for (0 otherwise, and while a part
        file cannot be read: its 500 says what to do first)."""
        if doc.get("state") != "done":
            return 0
        try:
            have = self.store.done_runs(study_id)
        except ServiceError:
            return 0
        return max(int(doc.get("total") or 0) - len(have), 0)

    def _job_ended(self, job: StudyJob) -> None:
        """Called by a job's thread as it ends: forget it (and its resolved runs)."""
        with self._lock:
            if self._jobs.get(job.study.id) is job:
                del self._jobs[job.study.id]

    @staticmethod
    def _new_doc(study: ResolvedStudy) -> dict:
        now = time.time()
        return {
            "id": study.id,
            "name": study.name,
            "state": "queued",
            "total": study.total,
            "done": 0,
            "failed": 0,
            "elapsed_s": 0.0,
            "message": "",
            "created_at": now,
            "updated_at": now,
            "started_at": None,
            "finished_at": None,
            "engine_version": study.engine_version,
            "study": study.to_json(),
        }

    # ---------------------------------------------------------------- submit
    def submit(
        self, data: Any, *, base_dir: Path | None = None, confine: bool = True,
        strict: bool = False,
    ) -> tuple[dict, bool]:
        """Validate and store a study, start it; return (status, created).

        ``confine`` keeps conveyor paths inside the studies directory (HTTP bodies);
        ``base_dir`` resolves them for a local study file; ``strict`` is kept for callers (every
        study is held to its JSON types). An identical study already in the store is returned
        as it is (``created`` False).

        Cheap refusals first: the body (with the conveyor file it names) is hashed before
        anything is expanded, and a body seen before whose study is stored answers at once,
        without expanding it again (:meth:`_known_body`). Expansions run at most
        ``max_expansions`` at once; a request that finds no free slot within
        ``expansion_wait_s`` is :class:`Unavailable` (503) with ``Retry-After``; the same body
        sent again while it is being expanded waits for that expansion instead of repeating it.
        """
        key = self._body_key(data, base_dir, confine)
        known = self._known_body(key)
        if known is not None:
            return known, False
        owner, event = self._claim(key)
        try:
            if not owner:  # the same body is being expanded by another request: its answer
                event.wait(self.settings.expansion_wait_s)
                known = self._known_body(key)
                if known is not None:
                    return known, False
            study = self._expand_bounded(data, base_dir, confine)
            created = self._admit(study)
            self._remember_body(key, study.id)
        finally:
            if owner:
                with self._lock:
                    self._inflight.pop(key, None)
                event.set()
        return self.status(study.id), created

    def _expand_bounded(self, data: Any, base_dir: Path | None, confine: bool
                        ) -> ResolvedStudy:
        """:func:`resolve_study` within the bound on expansions running at once."""
        if not self._slots.acquire(timeout=self.settings.expansion_wait_s):
            retry = max(1, round(self.settings.expansion_wait_s))
            raise Unavailable(
                f"the service is expanding {self.settings.max_expansions} "
                f"{'study' if self.settings.max_expansions == 1 else 'studies'} already "
                f"(BELTSTUDY_MAX_EXPANSIONS) and none finished within "
                f"{self.settings.expansion_wait_s:g} s; send the study again in {retry} s",
                headers={"Retry-After": str(retry)},
            )
        try:
            with self._lock:
                self.expansions += 1
            return resolve_study(
                data,
                base_dir=base_dir,
                studies_dir=self.settings.studies_dir if confine else None,
                max_runs=self.settings.max_runs,
                strict=True,
            )
        finally:
            self._slots.release()

    def _claim(self, key: str | None) -> tuple[bool, threading.Event]:
        """(whether this request expands ``key``, the event set when its expansion ends)."""
        if key is None:
            return True, threading.Event()
        with self._lock:
            event = self._inflight.get(key)
            if event is not None:
                return False, event
            event = self._inflight[key] = threading.Event()
            return True, event

    def _body_key(self, data: Any, base_dir: Path | None, confine: bool) -> str | None:
        """A hash of what decides a submitted study before it is expanded: the body as given,
        the conveyor file it names (read, a few kB), the engine version and the run limit.
        None for a body that cannot be hashed (it is refused by the full check)."""
        if not isinstance(data, dict):
            return None
        ref = data.get("conveyor")
        conveyor_file = None
        try:
            if isinstance(ref, str):
                conveyor_file, _ = conveyor_from_path(
                    ref, base_dir, self.settings.studies_dir if confine else None)
            return stable_hash({"body": data, "conveyor_file": conveyor_file,
                                "engine_version": engine.__version__,
                                "max_runs": self.settings.max_runs})
        except (ServiceError, TypeError, ValueError, RecursionError):
            return None

    def _body_path(self, key: str) -> Path:
        return Path(self.settings.data_dir) / "bodies" / key

    def _known_body(self, key: str | None) -> dict | None:
        """The status of the stored study a body with hash ``key`` made, when it is stored, not
        being deleted and not waiting to be resumed by this process; ``None`` otherwise, and
        the body goes the full way, through :meth:`_admit` (a study being deleted is a 409
        there; one deleted meanwhile is stored anew)."""
        if key is None:
            return None
        try:
            study_id = self._body_path(key).read_text(encoding="utf-8").strip()
        except OSError:
            return None
        if study_id in self._deleting or not self.store.exists(study_id):
            return None
        try:
            doc = self.store.read(study_id)
            if study_id not in self._jobs and (doc.get("state") in ACTIVE_STATES
                                               or _waits_for_workers(doc)
                                               or self._rows_lost(study_id, doc)):
                return None
            return self.status(study_id)
        except NotFound:  # deleted since it was looked for
            return None

    def _remember_body(self, key: str | None, study_id: str) -> None:
        if key is None:
            return
        path = self._body_path(key)
        path.parent.mkdir(parents=True, exist_ok=True)
        tmp = tmp_path(path)
        tmp.write_text(study_id, encoding="utf-8")
        os.replace(tmp, path)

    # ---------------------------------------------------------------- reading
    def status(self, study_id: str) -> dict:
        """State and progress of a study (live while it runs). A document with the keys of
        one (:meth:`Store.read`) but not their contents (``"study": {}``, edited by hand) is
        :class:`Damaged` as an unreadable one is, so :meth:`list` lists it as damaged rather
        than failing for every study."""
        doc = self.store.read(study_id)
        try:
            return self._status(study_id, doc)
        except (KeyError, TypeError, AttributeError) as exc:
            what = (f"no {exc.args[0]!r} where a study's document has one"
                    if isinstance(exc, KeyError) else f"a value of the wrong type ({exc})")
            raise Damaged(study_id, self.store.study_dir(study_id) / "study.json",
                          f"it is not a study's document: {what}") from None

    def _status(self, study_id: str, doc: dict) -> dict:
        job = self._jobs.get(study_id)
        out = {
            "id": doc["id"],
            "name": doc["name"],
            "state": doc["state"],
            "total": doc["total"],
            "done": doc.get("done", 0),
            "failed": doc.get("failed", 0),
            "elapsed_s": doc.get("elapsed_s", 0.0),
            "eta_s": 0.0 if doc["state"] == "done" else None,
            "message": doc.get("message", ""),
            "created_at": doc.get("created_at"),
            "started_at": doc.get("started_at"),
            "finished_at": doc.get("finished_at"),
            "dynamics": doc["study"]["dynamics"],
            "grid_points": doc["study"].get("grid_points", doc["total"]),
            "merged": doc["study"].get("merged", 0),
            "merged_axes": doc["study"].get("merged_axes", []),
            "axes": {a["name"]: a["column"] for a in doc["study"]["axes"]},
            "engine_version": doc.get("engine_version"),
            "belt_choices": belt_choices(doc["study"]),
        }
        if job is not None and job.is_alive():
            out.update(
                state=job.state,
                done=job.done,
                failed=job.failed,
                elapsed_s=round(job.elapsed_s(), 3),
                eta_s=job.eta_s(),
            )
        if out["eta_s"] is not None:  # to 0.1 s; only no runs left reads 0 (as a done study)
            out["eta_s"] = max(round(out["eta_s"], 1), 0.1) if out["eta_s"] > 0 else 0.0
        return out

    def running_count(self) -> int:
        with self._lock:
            return sum(1 for j in self._jobs.values() if j.is_alive())

    def job_count(self) -> int:
        """Jobs held in memory (a job leaves when its thread ends)."""
        with self._lock:
            return len(self._jobs)

    def list(self) -> list[dict]:
        """Every stored study's status; one deleted while the list is made is left out (the
        list itself is never a 404)."""
        out = []
        for doc in self.store.list_studies(damaged=True):
            if doc.get("state") == "damaged":  # its study.json unreadable: listed, untouched
                out.append(damaged_status(doc))
                continue
            try:
                out.append(self.status(doc["id"]))
            except NotFound:
                continue
            except Damaged as exc:  # damaged since it was listed
                out.append(damaged_status({"id": doc["id"], "name": doc.get("name", ""),
                                           "created_at": doc.get("created_at"),
                                           "message": exc.message}))
        return out

    def study_doc(self, study_id: str) -> dict:
        return self.store.read(study_id)

    def runs(self, study_id: str) -> pd.DataFrame:
        return self.store.read_runs(study_id)

    def accuracy(self, study_id: str) -> tuple[pd.DataFrame, pd.DataFrame]:
        """The study's accuracy table (error bars of its sampled runs) and the error of each
        column over them (:func:`beltstudy.service.store.query.accuracy_columns`)."""
        acc = self.store.read_accuracy(study_id)
        return acc, query.accuracy_columns(self.store.read_runs(study_id), acc)

    def uncertainty(self, study_id: str) -> dict:
        """What a sampled study's runs say: distributions, exceedance probabilities and the
        sensitivity ranking (:func:`beltstudy.service.uncertainty.summarise`)."""
        from beltstudy.service.uncertainty import summarise

        doc = self.store.read(study_id)
        return {"study_id": study_id, **summarise(doc.get("study") or {},
                                                  self.store.read_runs(study_id))}

    def run_detail(self, study_id: str, run_id: str) -> dict:
        """Summary row and time series of one run."""
        runs, bad = self.store.read_runs_readable(study_id)
        match = runs[runs["run_id"] == run_id] if len(runs) else runs
        if not len(match):
            self._no_row(study_id, run_id, bad)
        row = query.row_to_json(match.iloc[0].to_dict())
        ts = self.store.read_timeseries(study_id, run_id)
        # a sampled run's error bars (accuracy: {sample: ...}): the run page shows them
        acc = self.store.read_accuracy(study_id, run_id)
        bars = None
        if len(acc):
            bars = {k: v for k, v in query.row_to_json(acc.iloc[0].to_dict()).items()
                    if k != "run_id" and v is not None}
        return {
            "study_id": study_id,
            "run_id": run_id,
            "summary": row,
            "timeseries": query.columns_to_json(ts.drop(columns=["run_id"])) if len(ts) else None,
            "accuracy": bars,
        }

    def resolved(self, study_id: str) -> ResolvedStudy:
        """The study of ``study_id`` expanded into its runs again (cached: a study id is a hash
        of its content); :class:`NotFound` for a study this engine cannot expand."""
        doc = self.store.read(study_id)
        with self._cache_lock:
            study = self._resolved.get(study_id)
            if study is not None:
                self._resolved.move_to_end(study_id)
                return study
        try:
            study = study_from_json(doc["study"], study_id)
        except Exception as exc:  # made by another engine version, or damaged
            raise NotFound(f"study '{shown_id(study_id)}' cannot be expanded here: {exc}") from None
        with self._cache_lock:
            self._resolved[study_id] = study
            while len(self._resolved) > RESOLVED_CACHE:
                self._resolved.popitem(last=False)
        return study

    def run_spec(self, study_id: str, run_id: str) -> RunSpec:
        """The resolved inputs of one run (conveyor with the design basis, scenario, model,
        parameters), as the workers ran it."""
        spec = next((r for r in self.resolved(study_id).runs if r.run_id == run_id), None)
        if spec is None:
            raise NotFound(unknown_run(study_id, run_id))
        return spec

    def run_profile(self, study_id: str, run_id: str) -> tuple[pd.DataFrame, str]:
        """The steady tension along the loop of one run (``run_id`` + ``PROFILE_COLUMNS``) and
        where it came from: ``stored`` by the worker that ran it, or ``recomputed`` (the
        steady solve only) for a run stored before profiles were. Empty for a run that
        raised."""

        spec = self.run_spec(study_id, run_id)
        stored = self.store.read_profile(study_id, run_id)
        if len(stored):
            return stored, "stored"
        _, result = run_spec(dataclasses.replace(spec, dynamics=False, check=False), study_id)
        table = profile_table(run_id, result) if result is not None else None
        return (table if table is not None else profile_schema().empty_table()).to_pandas(), \
            "recomputed"

    def run_surface(self, study_id: str, run_id: str) -> tuple[pd.DataFrame, str]:
        """Tension and velocity at every sampled spring and time of one finished run
        (``run_id, t_s, s_m, tension_kn, velocity_m_s``), and where it came from: ``stored``
        (a study with ``surface: true``) or ``recomputed`` from the run's stored inputs (runs
        are deterministic: the same table the worker would have stored). Empty for a run
        without a transient (steady only, or a run that raised)."""

        doc = self.store.read(study_id)
        self.require_row(study_id, run_id)
        study = doc.get("study") or {}
        if not study.get("dynamics", True):
            return surface_schema().empty_table().to_pandas(), "recomputed"
        if study.get("surface", True):
            stored = self.store.read_surface(study_id, run_id)
            if len(stored):
                return stored, "stored"
        return self._recomputed_surface(study_id, run_id).to_pandas(), "recomputed"

    def no_surface_reason(self, study_id: str, run_id: str) -> str:
        """Why a finished run has no surface rows: a steady-only study, a study made on another
        engine version (its surface is recomputed from the run's inputs, which only the
        engine that made it reproduces: the run page of a 0.6.14 study under 0.6.15 said 'the
        run has no transient' for runs that had one), or a run without a transient (failed,
        with its own message)."""
        doc = self.store.read(study_id)
        study = doc.get("study") or {}
        if not study.get("dynamics", True):
            return ("the study runs without dynamics (dynamics: false): a steady run has no "
                    "transient, so no surface; submit it with dynamics: true for one")
        made = study.get("engine_version") or doc.get("engine_version")
        if made and made != engine.__version__:
            return (f"the study was run on engine {made} and this service runs engine "
                    f"{engine.__version__}: a surface not stored with the run is recomputed "
                    "from its inputs, which only the engine that ran it reproduces; submit the "
                    f"study again for its runs and surfaces on engine {engine.__version__} "
                    "(surface: true stores them with the runs)")
        row, _ = self.store.read_runs_readable(study_id, columns=["run_id", "status", "message"])
        row = row[row["run_id"] == run_id]
        if len(row) and row["status"].iloc[0] == "failed":
            return f"the run failed, so it has no transient: {row['message'].iloc[0]}"
        return "the run has no transient"

    def _recomputed_surface(self, study_id: str, run_id: str) -> pa.Table:
        with self._cache_lock:
            if run_id in self._surfaces:
                self._surfaces.move_to_end(run_id)
                table = self._surfaces[run_id]
                return table if table is not None else surface_schema().empty_table()
        spec = self.run_spec(study_id, run_id)
        table = self._surface_on_worker(spec, study_id)
        with self._cache_lock:
            self._surfaces[run_id] = table
            while len(self._surfaces) > SURFACE_CACHE:
                self._surfaces.popitem(last=False)
        return table if table is not None else surface_schema().empty_table()

    def _surface_on_worker(self, spec: RunSpec, study_id: str) -> pa.Table | None:
        """The run recomputed for its surface (no error bars again) on a Dask worker, whose
        engine is compiled, so this process keeps answering; here when Dask is not started or
        no worker is ready within :data:`SURFACE_WORKER_WAIT_S` (the same table: runs are
        deterministic)."""
        try:
            if self.executor.state in ("idle", "closed"):
                raise Unavailable("Dask is not started")  # not started for a surface alone
            client = self.executor.client(timeout=SURFACE_WORKER_WAIT_S)
            future = client.submit(recompute_surface, spec, study_id, pure=False,
                                   priority=10)
            table = future.result()
            log.info("surface of %s recomputed on a Dask worker", spec.run_id)
            return table
        except (Unavailable, CancelledError, KilledWorker) as exc:
            log.info("surface of %s recomputed in the service: %s", spec.run_id,
                     str(exc) or type(exc).__name__)
        _, result = run_spec(dataclasses.replace(spec, check=False), study_id)
        return surface_table(spec.run_id, result) if result is not None else None

    def compare(self, study_id: str, baseline: str | None, candidate: str | None,
                metrics: list[str]) -> dict:
        """Pairs of runs that differ only in the friction model (:func:`query.compare`) with
        the study's state: a running study answers with the pairs finished so far.
        ``baseline`` / ``candidate``: None for one left to its default."""
        doc = self.store.read(study_id)
        axes = [a["column"] for a in doc["study"]["axes"]]
        status = self.status(study_id)
        if ((not metrics or list(metrics) == list(query.DEFAULT_METRICS))
                and not doc["study"].get("dynamics", True)):
            # a steady-only study's default is power alone, whether or not a run has finished
            # (with none yet, the stop-phase defaults were kept, which it never writes)
            metrics = [query.DEFAULT_METRICS[0]]
        out = query.compare(
            self.store.read_runs(study_id), axes, baseline, candidate, metrics, study_id,
            models=study_models(doc), settled=status["state"] not in ACTIVE_STATES,
        )
        return {**out, "state": status["state"], "done": status["done"],
                "total": status["total"]}

    def require_row(self, study_id: str, run_id: str) -> None:
        """Raise as :meth:`_no_row` unless the run has its stored row (it finished)."""
        runs, bad = self.store.read_runs_readable(study_id, columns=["run_id"])
        if not len(runs) or not (runs["run_id"] == run_id).any():
            self._no_row(study_id, run_id, bad)

    def _no_row(self, study_id: str, run_id: str, bad: list | tuple = ()) -> None:
        """Raise for a run without a stored row: 409 with the study's state for a run of the
        study that has not finished (never 404 for what exists), 404 for an unknown run,
        :class:`DamagedParts` (500 naming the files) for a run of the study while ``bad``
        runs parts cannot be read (its row may be in one)."""
        if not any(r.run_id == run_id for r in self.resolved(study_id).runs):
            raise NotFound(unknown_run(study_id, run_id))
        if bad:
            raise DamagedParts(study_id, "runs", list(bad))
        st = self.status(study_id)
        if st["state"] in ACTIVE_STATES:
            raise Conflict(
                f"run '{run_id}' of study '{study_id}' is not finished yet (the study is "
                f"{st['state']}: {st['done']} of {st['total']} runs done); ask again later"
            )
        raise Conflict(
            f"run '{run_id}' of study '{study_id}' has no result: the study is {st['state']}"
            + (f" ({st['message']})" if st.get("message") else "")
        )

    # ---------------------------------------------------------------- delete
    def delete(self, study_id: str) -> dict:
        """Cancel a study's tasks and delete its files; waits at most ``dask_timeout_s`` for
        its job to leave (the job never waits on Dask: its tasks are released, not awaited).
        The answer's ``state`` is ``deleted``; ``cancelled`` says whether it was still queued
        or running (its tasks cancelled), ``was`` the state it had. A study another request is
        deleting is a :class:`Conflict` (409) until that request has finished, also once its
        files are already gone; :class:`NotFound` (404) only for a study no request holds."""
        with self._lock:
            # checked before the store is read: the first DELETE moves the files away before
            # it has finished (it may still be waiting for the study's job)
            if study_id in self._deleting:
                raise Conflict(f"study '{study_id}' is already being deleted")
            self._deleting.add(study_id)
        job = None
        try:
            try:  # the state the list shows (a document with a study's keys, not its
                # contents, is listed damaged: said so here too, not its stored state)
                was = self.status(study_id)["state"]
            except Damaged:  # its document is unreadable: the rest of it goes all the same
                was = "damaged"
            with self._lock:
                job = self._jobs.pop(study_id, None)
            if job is not None:
                job.cancel()
                job.join(timeout=self.settings.dask_timeout_s)
                if job.is_alive():
                    log.warning("study %s: its job is still busy; deleting its files", study_id)
            self.store.delete(study_id)
        finally:
            with self._lock:
                self._deleting.discard(study_id)
        return {"id": study_id, "state": "deleted", "deleted": True,
                "cancelled": job is not None or was in ACTIVE_STATES, "was": was}

    # ---------------------------------------------------------------- waiting
    def wait(
        self, study_id: str, *, poll_s: float = 0.5, timeout_s: float | None = None, progress=None
    ) -> dict:
        """Block until the study leaves queued/running; ``progress(status)`` on every poll."""
        t0 = time.monotonic()
        while True:
            st = self.status(study_id)
            if progress is not None:
                progress(st)
            if st["state"] not in ACTIVE_STATES:
                return st
            if timeout_s is not None and time.monotonic() - t0 > timeout_s:
                return st
            time.sleep(poll_s)
