"""The Parquet store: one directory per study under ``<data_dir>/studies``.

::

    <data_dir>/studies/<study_id>/study.json              resolved study, state, counts, times
    <data_dir>/studies/<study_id>/runs/part-<key>.parquet        SPEC section 4 rows
    <data_dir>/studies/<study_id>/timeseries/part-<key>.parquet  SPEC section 5 key points
    <data_dir>/studies/<study_id>/profile/part-<key>.parquet     steady tension along the loop
    <data_dir>/studies/<study_id>/surface/part-<key>.parquet     SPEC section 5 long table
                                                                 (studies with surface: true)
    <data_dir>/studies/<study_id>/accuracy/part-<key>.parquet    error bars of the sampled
                                                                 runs (accuracy: {sample})

Every file is written under a temporary name starting with ``.`` (which Arrow's dataset
reader skips) and then renamed, so readers never see half a file. A batch writes its
``surface``, ``timeseries`` and ``profile`` parts first and its ``runs`` part last, under one
part key:
a run counts as done exactly when its ``runs`` row exists, and :meth:`Store.clean` removes
the time-series parts of a batch whose ``runs`` part never landed.
``pd.read_parquet("<data_dir>/studies/<id>/runs")`` reads the runs table.
"""

from __future__ import annotations

import json
import logging
import os
import re
import shutil
import threading
import time
import uuid
from pathlib import Path
from typing import Any

import pandas as pd
import pyarrow as pa
import pyarrow.parquet as pq

from beltstudy.service.errors import (
    Damaged,
    DamagedParts,
    NotFound,
    bad_study_id,
    shown_id,
)
from beltstudy.service.store.columns import (
    accuracy_schema,
    profile_schema,
    runs_schema_for_axes,
    surface_schema,
    timeseries_schema,
)

log = logging.getLogger(__name__)

__all__ = ["Store", "STATES", "TABLES", "PART_TABLES", "write_part_to"]

STATES = ("queued", "running", "done", "failed", "cancelled")
#: The keys every study's document has (:meth:`Store.read` refuses a ``study.json`` without
#: them as damaged): what the list and a study's status read.
DOC_KEYS = ("id", "name", "state", "total", "study")
TABLES = ("runs", "timeseries", "surface", "profile", "accuracy")
#: The tables a batch writes before its ``runs`` part (which commits them).
PART_TABLES = ("surface", "timeseries", "profile", "accuracy")
_ID_RE = re.compile(r"^[0-9a-f]{16}$")


def is_study_id(text: object) -> bool:
    """Whether ``text`` has a study id's form (16 lower-case hexadecimal digits)."""
    return isinstance(text, str) and bool(_ID_RE.match(text))


#: Studies whose runs table :meth:`Store.read_runs` keeps for reuse.
RUNS_CACHE_STUDIES = 4


#: Tags this process's temporary files (``.<name>.<tag>-<random>.tmp``): one that does not
#: carry it was left by a process killed mid-write (a live write lasts milliseconds), and
#: :meth:`Store.clean` / :meth:`Store.sweep` remove it. A tag, not the pid: a restarted
#: service (pid 1 in a container) may be given its predecessor's pid.
PROCESS_TAG = uuid.uuid4().hex[:8]


def tmp_path(path: Path) -> Path:
    """A temporary name beside ``path`` for an atomic write by this process."""
    return path.with_name(f".{path.name}.{PROCESS_TAG}-{uuid.uuid4().hex[:8]}.tmp")


def _left_by_dead_process(p: Path) -> bool:
    return (p.name.startswith(".") and p.name.endswith(".tmp")
            and f".{PROCESS_TAG}-" not in p.name and p.is_file())


def _write_atomic(path: Path, write) -> None:
    tmp = tmp_path(path)
    try:
        write(tmp)
        os.replace(tmp, path)
    finally:
        if tmp.exists():
            tmp.unlink()


def _write_parquet(path: Path, data: pa.Table) -> None:
    # dictionary-encode the text columns only: floats rarely repeat, and encoding them costs
    # several times the compression
    text = [f.name for f in data.schema if pa.types.is_string(f.type)]
    _write_atomic(path, lambda p: pq.write_table(data, p, compression="zstd", use_dictionary=text))


def write_part_to(study_dir: str | Path, token: str, table: str, key: str, data: pa.Table) -> bool:
    """Write a part straight into a study directory if this process sees it (shared disk).

    Used by workers: ``token`` must match the study's ``store_token`` (so a worker on another
    machine with a look-alike path never writes there). Returns False when it cannot.
    """
    directory = Path(study_dir)
    try:
        doc = json.loads((directory / "study.json").read_text(encoding="utf-8"))
    except (OSError, ValueError):
        return False
    if not token or doc.get("store_token") != token:
        return False
    target = directory / table
    if not target.is_dir():
        return False
    _write_parquet(target / f"part-{key}.parquet", data)
    return True


def damaged_parts(parts: list[Path], columns=None) -> list[tuple[Path, str]]:
    """The part files among ``parts`` that Arrow cannot read (``columns`` of them), each
    with why: a file cut short or overwritten on disk (this store writes whole files)."""
    bad = []
    for part in parts:
        try:
            with pq.ParquetFile(part) as f:
                f.read(columns=columns)
        except FileNotFoundError:
            raise
        except (pa.ArrowException, OSError) as exc:
            bad.append((part, str(exc).strip() or type(exc).__name__))
    return bad


def damaged_entry(study_id: str, path: Path, message: str) -> dict:
    """A study whose ``study.json`` cannot be read, as the list shows it: its id, state
    ``damaged``, ``message`` (the file and the way out), and what the document's readable
    start still says of its ``name`` and ``created_at`` (else "" and the file's time). The
    file is only read."""
    try:
        text = path.read_text(encoding="utf-8", errors="replace")
        created: float | None = path.stat().st_mtime
    except OSError:
        text, created = "", None
    name = ""
    # top-level keys, as :meth:`Store.create` writes them (indent 1): one line each
    found = re.search(r'^ "name": ("(?:[^"\\]|\\.)*"),?$', text, re.M)
    if found:
        try:
            name = str(json.loads(found.group(1)))
        except ValueError:
            pass
    found = re.search(r'^ "created_at": ([0-9.eE+-]+),?$', text, re.M)
    if found:
        try:
            created = float(found.group(1))
        except ValueError:
            pass
    return {"id": study_id, "name": name, "state": "damaged", "message": message,
            "created_at": created}


#: Age after which a half-created study directory is a leftover [s] (creating one takes
#: milliseconds; a killed process leaves it behind).
LEFTOVER_TMP_S = 600.0

#: What a study id the store does not hold is told with: where the stored ones are listed.
LISTED = "; GET /studies and beltstudy status list the stored studies"


class Store:
    """Files of every study under one data directory. Thread-safe for distinct studies."""

    def __init__(self, data_dir: str | Path):
        self.data_dir = Path(data_dir)
        self.root = self.data_dir / "studies"
        self._runs_cache: dict[str, tuple[tuple, pa.Table]] = {}
        #: columns of a study's runs table read on their own (a page, a figure), kept while
        #: its parts do not change: {study: (parts key, {column: (field, values)})}
        self._columns_cache: dict[str, tuple[tuple, dict[str, tuple]]] = {}
        self._runs_reading: dict[str, threading.Lock] = {}
        self._runs_lock = threading.Lock()

    # ---------------------------------------------------------------- paths and ids
    def study_dir(self, study_id: str) -> Path:
        if not is_study_id(study_id):
            raise NotFound(bad_study_id(study_id))
        return self.root / study_id

    def table_dir(self, study_id: str, table: str) -> Path:
        return self.study_dir(study_id) / table

    def exists(self, study_id: str) -> bool:
        try:
            return (self.study_dir(study_id) / "study.json").is_file()
        except NotFound:
            return False

    # ---------------------------------------------------------------- study.json
    def create(self, study_id: str, doc: dict) -> None:
        """Create a study directory with its ``study.json`` (the directory appears complete)."""
        final = self.study_dir(study_id)
        self.root.mkdir(parents=True, exist_ok=True)
        if final.exists() and not (final / "study.json").exists():
            shutil.rmtree(final, ignore_errors=True)  # leftovers of a deleted study
        tmp = self.root / f".{study_id}.{uuid.uuid4().hex[:8]}.tmp"
        tmp.mkdir()
        try:
            for table in TABLES:
                (tmp / table).mkdir()
            (tmp / "study.json").write_text(json.dumps(doc, indent=1), encoding="utf-8")
            os.replace(tmp, final)
        finally:
            if tmp.exists():
                shutil.rmtree(tmp, ignore_errors=True)

    def read(self, study_id: str) -> dict:
        """The study's ``study.json``; :class:`NotFound` for an unknown id, :class:`Damaged`
        (a 500 naming the file and the way out) for one that is not a study's document (edited
        or truncated by hand, or overwritten: this store writes it atomically): not a JSON
        object, an object without the keys every document has (:data:`DOC_KEYS`), or the
        document of another study (its ``id`` not its folder's). A runs download written over
        it (``{"study_id": ..., "runs": [...]}``) passed as a document, and every reader then
        failed on ``doc["id"]``: ``GET /studies`` a 500 for all studies, the CLI a traceback."""
        path = self.study_dir(study_id) / "study.json"
        try:
            doc = json.loads(path.read_text(encoding="utf-8"))
        except FileNotFoundError:
            raise NotFound(f"study '{shown_id(study_id)}' not found{LISTED}") from None
        except (json.JSONDecodeError, UnicodeDecodeError) as exc:
            raise Damaged(study_id, path, str(exc)) from None
        if not isinstance(doc, dict):
            raise Damaged(study_id, path, f"it holds a JSON {type(doc).__name__}, not an object")
        missing = [k for k in DOC_KEYS if k not in doc]
        if missing:
            raise Damaged(study_id, path, "it is a JSON object but not a study's document: "
                          f"it has no {', '.join(missing)} (a study's document has "
                          f"{', '.join(DOC_KEYS)})")
        if doc["id"] != study_id:
            raise Damaged(study_id, path, f"it is the document of study {str(doc['id'])[:40]!r}, "
                          "not of this folder's")
        if not isinstance(doc["study"], dict):
            raise Damaged(study_id, path, "its study is not a JSON object")
        return doc

    def update(self, study_id: str, **fields: Any) -> dict:
        """Merge ``fields`` into ``study.json`` (atomic replace); return the new document."""
        doc = self.read(study_id)
        doc.update(fields)
        doc["updated_at"] = time.time()
        path = self.study_dir(study_id) / "study.json"
        _write_atomic(path, lambda p: p.write_text(json.dumps(doc, indent=1), encoding="utf-8"))
        return doc

    def list_studies(self, damaged: bool = False) -> list[dict]:
        """``study.json`` of every study, oldest first. A study whose ``study.json`` cannot
        be read is logged, and with ``damaged`` listed as :func:`damaged_entry` says (state
        ``damaged``); nothing of it is changed."""
        out = []
        if not self.root.is_dir():
            return out
        for child in self.root.iterdir():
            if child.name.startswith(".") or not _ID_RE.match(child.name):
                continue
            try:
                out.append(self.read(child.name))
            except NotFound:
                continue
            except Damaged as exc:  # said, not dropped in silence
                log.warning("%s", exc.message)
                if damaged:
                    out.append(damaged_entry(child.name, child / "study.json", exc.message))
        return sorted(out, key=lambda d: (d.get("created_at") or 0, d.get("id", "")))

    def delete(self, study_id: str) -> None:
        """Remove a study's directory (renamed away first so it vanishes at once)."""
        path = self.study_dir(study_id)
        if not path.exists():
            raise NotFound(f"study '{shown_id(study_id)}' not found{LISTED}")
        trash = self.root / f".{study_id}.{uuid.uuid4().hex[:8]}.deleted"
        os.replace(path, trash)
        shutil.rmtree(trash, ignore_errors=True)

    def sweep(self, tmp_age_s: float = LEFTOVER_TMP_S) -> int:
        """Remove what a killed process left at the top of the store: the directories of
        deleted studies (``.<id>.<tag>.deleted``: moved away, the deletion decided) and
        studies half created (``.<id>.<tag>.tmp``) older than ``tmp_age_s`` (a live one
        lasts milliseconds), and the temporary files of body records (``bodies/``) a killed
        process left. None is listed nor read; they only hold disk. Returns how many were
        removed."""
        removed = 0
        if not self.root.is_dir():
            return removed
        now = time.time()
        for child in self.root.iterdir():
            name = child.name
            if not (name.startswith(".") and child.is_dir()):
                continue
            try:
                stale = name.endswith(".deleted") or (
                    name.endswith(".tmp") and now - child.stat().st_mtime > tmp_age_s)
            except FileNotFoundError:
                continue
            if stale:
                shutil.rmtree(child, ignore_errors=True)
                removed += not child.exists()
        bodies = self.data_dir / "bodies"
        if bodies.is_dir():
            for p in bodies.iterdir():
                if _left_by_dead_process(p):
                    p.unlink(missing_ok=True)
                    removed += 1
        return removed

    # ---------------------------------------------------------------- parts
    def write_part(self, study_id: str, table: str, key: str, data: pa.Table) -> Path:
        """Write one part file ``<table>/part-<key>.parquet`` (temporary name, then rename)."""
        directory = self.table_dir(study_id, table)
        directory.mkdir(parents=True, exist_ok=True)
        path = directory / f"part-{key}.parquet"
        _write_parquet(path, data)
        return path

    def parts(self, study_id: str, table: str) -> list[Path]:
        directory = self.table_dir(study_id, table)
        if not directory.is_dir():
            return []
        return sorted(p for p in directory.glob("part-*.parquet"))

    def clean(self, study_id: str) -> int:
        """Remove temporary files (in the tables, and a ``study.json`` write a killed process
        cut short), and time-series parts holding runs without a runs row.

        Time-series parts are written before the runs rows that commit them (by the service
        or, on a shared disk, by the workers); a part whose runs never got their rows is
        removed, and those runs are run again.
        """
        removed = 0
        for p in self.study_dir(study_id).iterdir():  # a study.json write cut short
            if _left_by_dead_process(p):
                p.unlink(missing_ok=True)
                removed += 1
        done = set(self.done_runs(study_id)["run_id"])
        for table in TABLES:
            directory = self.table_dir(study_id, table)
            if not directory.is_dir():
                continue
            for p in directory.iterdir():
                orphan = False
                if table != "runs" and p.name.startswith("part-"):
                    ids = pq.read_table(p, columns=["run_id"]).column("run_id").unique()
                    orphan = not set(ids.to_pylist()) <= done
                if p.name.startswith(".") or orphan:
                    p.unlink(missing_ok=True)
                    removed += 1
        return removed

    # ---------------------------------------------------------------- reading
    def _empty(self, study_id: str, table: str) -> pa.Table:
        if table == "runs":
            return runs_schema_for_axes(self.read(study_id)["study"]["axes"]).empty_table()
        schemas = {"timeseries": timeseries_schema, "surface": surface_schema,
                   "profile": profile_schema, "accuracy": accuracy_schema}
        return schemas[table]().empty_table()

    def _vanishing(self, study_id: str, read):
        """``read()``, which reads part files of the study: a file that vanishes meanwhile (the
        study deleted: its directory is moved away at once; a part :meth:`clean` removed) is
        :class:`NotFound` when the study is gone, else read again from the files there are
        now. Never a bare ``FileNotFoundError`` (a 500) for a study deleted while it is read."""
        for attempt in range(3):
            try:
                return read()
            except FileNotFoundError:
                if not self.exists(study_id):
                    raise NotFound(f"study '{shown_id(study_id)}' not found{LISTED}") from None
                if attempt == 2:
                    raise

    def _read_parts(self, study_id: str, table: str, parts: list[Path], columns=None,
                    filters=None) -> tuple[pa.Table, list[tuple[Path, str]]]:
        """The rows of ``parts`` that Arrow reads, and the parts it cannot (``(path, why)``:
        truncated or overwritten on disk). All parts are read at once; only when that fails
        is each tried on its own, to name the damaged ones and read the others."""
        try:
            return pq.ParquetDataset(parts, filters=filters).read(columns=columns), []
        except FileNotFoundError:
            raise  # the study or a part removed meanwhile: :meth:`_vanishing` says which
        except (pa.ArrowException, OSError) as exc:
            bad = damaged_parts(parts, columns)
            if not bad:  # not a damaged file (parts that disagree): as it was
                raise exc from None
        good = [p for p in parts if p not in {path for path, _ in bad}]
        if not good:
            empty = self._empty(study_id, table)
            return (empty.select(columns) if columns else empty), bad
        return pq.ParquetDataset(good, filters=filters).read(columns=columns), bad

    def _read_table(self, study_id: str, table: str, columns=None, filters=None) -> pd.DataFrame:
        """A table of the study; :class:`DamagedParts` (a 500 naming the files and the way
        out) when a part file cannot be read."""
        def read() -> pd.DataFrame:
            parts = self.parts(study_id, table)
            if not parts:
                empty = self._empty(study_id, table)
                return (empty.select(columns) if columns else empty).to_pandas()
            data, bad = self._read_parts(study_id, table, parts, columns, filters)
            if bad:
                raise DamagedParts(study_id, table, bad)
            return data.to_pandas()

        return self._vanishing(study_id, read)

    def read_runs(self, study_id: str, columns: list[str] | None = None) -> pd.DataFrame:
        """The runs table of a study (one row per finished run). The table read last for the
        same part files is reused (a few studies are kept): status pages and downloads read
        it far more often than a running study adds a part. ``columns``: only those, taken
        from that kept table while it is current (a page of a few columns of a large study
        costs milliseconds, not the conversion of every column), else read from the parts.
        A part file that cannot be read is :class:`DamagedParts` (a 500 naming it and the
        way out); :meth:`read_runs_readable` reads the others."""
        df, bad = self.read_runs_readable(study_id, columns)
        if bad:
            raise DamagedParts(study_id, "runs", bad)
        return df

    def read_runs_readable(self, study_id: str, columns: list[str] | None = None
                           ) -> tuple[pd.DataFrame, list[tuple[Path, str]]]:
        """The rows of the study's runs parts that can be read (as :meth:`read_runs`), and
        the parts that cannot (``(path, why)``; empty for a sound study)."""
        self.read(study_id)
        if columns is not None:
            return self._vanishing(study_id, lambda: self._read_runs_columns(study_id, columns))
        return self._vanishing(study_id, lambda: self._read_runs(study_id))

    def runs_columns(self, study_id: str) -> list[str]:
        """The names of the columns of a study's runs table (its schema; no rows read)."""
        return [n for n in self.runs_schema(study_id).names
                if not n.startswith("__index_level_")]

    def runs_schema(self, study_id: str) -> pa.Schema:
        """The schema of a study's runs table, as its part files store it (no rows read)."""
        self.read(study_id)

        def read() -> pa.Schema:
            for part in self.parts(study_id, "runs"):  # the first that can be read
                try:
                    return pq.read_schema(part)
                except FileNotFoundError:
                    raise
                except (pa.ArrowException, OSError):
                    continue  # damaged: named by whatever reads its rows
            return self._empty(study_id, "runs").schema

        return self._vanishing(study_id, read)

    @staticmethod
    def _parts_key(parts: list[Path]) -> tuple:
        return tuple((p.name, st.st_mtime_ns, st.st_size) for p in parts for st in [p.stat()])

    def _read_runs_columns(self, study_id: str, columns: list[str]
                           ) -> tuple[pd.DataFrame, list[tuple[Path, str]]]:
        """``columns`` of the runs table: from the whole table kept, else from the columns
        kept for the same parts, reading from the parts only those not kept yet (a study
        with a damaged part: from its readable parts, nothing kept)."""
        parts = self.parts(study_id, "runs")
        if not parts:
            return self._read_table(study_id, "runs", columns), []
        key = self._parts_key(parts)
        with self._runs_lock:
            hit = self._runs_cache.get(study_id)
            kept = self._columns_cache.get(study_id)
        if hit is not None and hit[0] == key:
            return hit[1].select(columns).to_pandas(), hit[2]
        have = dict(kept[1]) if kept is not None and kept[0] == key else {}
        missing = [c for c in columns if c not in have]
        if missing:
            table, bad = self._read_parts(study_id, "runs", parts, missing)
            if bad:  # rows of the readable parts only: read whole, never mixed with kept ones
                table, bad = self._read_parts(study_id, "runs", parts, columns)
                return table.to_pandas(), bad
            have.update({c: (table.schema.field(c), table.column(c)) for c in missing})
            with self._runs_lock:
                self._columns_cache.pop(study_id, None)
                self._columns_cache[study_id] = (key, have)
                while len(self._columns_cache) > RUNS_CACHE_STUDIES:
                    self._columns_cache.pop(next(iter(self._columns_cache)))
        schema = pa.schema([have[c][0] for c in columns])
        return (pa.Table.from_arrays([have[c][1] for c in columns], schema=schema).to_pandas(),
                [])

    def _read_runs(self, study_id: str) -> tuple[pd.DataFrame, list[tuple[Path, str]]]:
        parts = self.parts(study_id, "runs")
        if not parts:
            return self._read_table(study_id, "runs"), []
        key = self._parts_key(parts)
        with self._runs_lock:
            reading = self._runs_reading.setdefault(study_id, threading.Lock())
        with reading:  # one reader per study: the others wait for its table
            with self._runs_lock:
                hit = self._runs_cache.get(study_id)
            if hit is not None and hit[0] == key:
                return hit[1].to_pandas(), hit[2]
            table, bad = self._read_parts(study_id, "runs", parts)
            with self._runs_lock:
                self._runs_cache.pop(study_id, None)
                self._runs_cache[study_id] = (key, table, bad)
                while len(self._runs_cache) > RUNS_CACHE_STUDIES:
                    gone = next(iter(self._runs_cache))
                    self._runs_cache.pop(gone)
                    self._runs_reading.pop(gone, None)
        return table.to_pandas(), bad

    def done_runs(self, study_id: str) -> pd.DataFrame:
        """``run_id`` and ``status`` of the finished runs."""
        return self._read_table(study_id, "runs", ["run_id", "status"])

    def read_timeseries(self, study_id: str, run_id: str | None = None) -> pd.DataFrame:
        """Key-point time series (SPEC section 5), of one run or of all."""
        self.read(study_id)
        filters = [("run_id", "=", run_id)] if run_id else None
        return self._read_table(study_id, "timeseries", filters=filters)

    def read_profile(self, study_id: str, run_id: str | None = None) -> pd.DataFrame:
        """Steady tension along the loop (``run_id`` + ``PROFILE_COLUMNS``), of one run or of
        all; empty for runs stored before profiles were."""
        self.read(study_id)
        filters = [("run_id", "=", run_id)] if run_id else None
        return self._read_table(study_id, "profile", filters=filters)

    def read_accuracy(self, study_id: str, run_id: str | None = None) -> pd.DataFrame:
        """The error bars of the study's sampled runs (``run_id`` + the ``<figure>_err`` and
        ``<figure>_converged`` columns; empty without ``accuracy:``)."""
        self.read(study_id)
        filters = [("run_id", "=", run_id)] if run_id else None
        return self._read_table(study_id, "accuracy", filters=filters)

    def read_surface(self, study_id: str, run_id: str | None = None) -> pd.DataFrame:
        """Tension and velocity at every element (long table), of one run or of all."""
        self.read(study_id)
        filters = [("run_id", "=", run_id)] if run_id else None
        return self._read_table(study_id, "surface", filters=filters)
