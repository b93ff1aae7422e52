"""Worker-side functions: run a batch of runs through ``beltstudy.engine.run.run_one``; warm a worker.

These run inside Dask workers (and in the benchmark's plain loop). A batch is a list of
:class:`~beltstudy.service.grid.expand.RunSpec` records as the grid made them, sent to the
worker as they are (pickled once with the task, in a :class:`Specs`); a run's conveyor and
scenario mappings become the engine's models here, where the engine runs them. A run that
raises becomes a row with ``status=failed`` and the message; the batch itself never raises
for a bad run. Results travel back as plain rows and Arrow tables.
"""

from __future__ import annotations

import dataclasses
import json
import os
import time
from typing import Any

import numpy as np
import pyarrow as pa
from distributed import WorkerPlugin

from beltstudy import engine
from beltstudy.engine import GIVEN, MODELS, parse_conveyor, parse_scenario
from beltstudy.engine.friction import get_model
from beltstudy.service.examples import TINY_CONVEYOR, TINY_SCENARIO
from beltstudy.service.grid.expand import RunSpec
from beltstudy.service.store.columns import (
    ACCURACY_COLUMNS,
    PROFILE_COLUMNS,
    SURFACE_COLUMNS,
    TIMESERIES_COLUMNS,
    accuracy_schema,
    failed_row,
    flatten_summary,
    profile_schema,
    surface_schema,
    timeseries_schema,
)
from beltstudy.service.store.parquet import PART_TABLES, write_part_to

__all__ = [
    "run_batch",
    "run_specs",
    "start_candidate",
    "Specs",
    "arrays_table",
    "timeseries_table",
    "surface_table",
    "recompute_surface",
    "profile_table",
    "accuracy_table",
    "run_spec",
    "warm_up",
    "lower_priority",
    "LowerPriority",
]

_MAX_MESSAGE = 1000


def _message(exc: BaseException) -> str:
    """A failed run's ``message``: an input problem in its own words (it names the field:
    ``scenario.dt_s: 5 s is above ...``); anything else with its exception's name, which
    says it is a fault of the program rather than of the inputs."""
    text = str(exc).strip().splitlines()
    first = text[0] if text else ""
    if isinstance(exc, engine.InputError) and first:
        return first[:_MAX_MESSAGE]
    msg = f"{type(exc).__name__}: {first}" if first else type(exc).__name__
    return msg[:_MAX_MESSAGE]


def _layout(schema: pa.Schema, columns: tuple[str, ...]) -> list[tuple[str, pa.DataType, Any]]:
    return [(c, schema.field(c).type, schema.field(c).type.to_pandas_dtype()) for c in columns]


def arrays_table(
    run_id: str, arrays: dict | None, columns: tuple[str, ...], schema: pa.Schema
) -> pa.Table | None:
    """One run's columns (name -> 1-D array) as a table of ``schema``: ``run_id`` first, then
    ``columns`` cast to their types (a column the run does not have is null). None when the
    run has no rows. No DataFrame is built on the way."""
    return _arrays_table(run_id, arrays, _layout(schema, columns), schema)


def _arrays_table(run_id: str, arrays: dict | None, layout, schema: pa.Schema):
    if not arrays:
        return None
    n = len(next(iter(arrays.values())))
    if n == 0:
        return None
    data = [pa.repeat(run_id, n)]
    for col, typ, dtype in layout:
        values = arrays.get(col)
        if values is None:
            data.append(pa.nulls(n, typ))
        else:
            data.append(pa.array(np.ascontiguousarray(values, dtype=dtype), type=typ))
    return pa.Table.from_arrays(data, schema=schema)


_TS_SCHEMA = timeseries_schema()
_TS_LAYOUT = _layout(_TS_SCHEMA, TIMESERIES_COLUMNS)
_SF_SCHEMA = surface_schema()
_SF_LAYOUT = _layout(_SF_SCHEMA, SURFACE_COLUMNS)
_PF_SCHEMA = profile_schema()
_PF_LAYOUT = _layout(_PF_SCHEMA, PROFILE_COLUMNS)


def timeseries_table(run_id: str, result) -> pa.Table | None:
    """The stored time series (SPEC section 5 key points) of a run's result."""
    return _arrays_table(run_id, result.timeseries_arrays(), _TS_LAYOUT, _TS_SCHEMA)


def profile_table(run_id: str, result) -> pa.Table | None:
    """The steady profile of a run's result (the table the run page draws)."""
    return _arrays_table(run_id, result.profile_arrays(), _PF_LAYOUT, _PF_SCHEMA)


def surface_table(run_id: str, result) -> pa.Table | None:
    """The surface table (float32) of a run's result: the same whether a worker stores it or
    the service recomputes it for a run whose study did not store surfaces."""
    return _arrays_table(run_id, result.surface_arrays(), _SF_LAYOUT, _SF_SCHEMA)


def recompute_surface(spec: RunSpec, study_id: str) -> pa.Table | None:
    """One run's surface recomputed (its stored inputs, no error bars): a task for a worker,
    whose engine is compiled, so the service's own process stays free to answer."""
    _, result = run_spec(dataclasses.replace(spec, check=False), study_id)
    return surface_table(spec.run_id, result) if result is not None else None


_AC_SCHEMA = accuracy_schema()


def accuracy_table(run_id: str, result) -> pa.Table | None:
    """The error bars of a checked run (one row; None for a run without them)."""
    if getattr(result, "accuracy", None) is None:
        return None
    fields = result.accuracy.fields()
    data = {"run_id": [run_id]}
    for c in ACCURACY_COLUMNS:
        v = fields.get(c)
        data[c] = [v if v is None or isinstance(v, str) else float(v)]
    return pa.Table.from_pydict(data, schema=_AC_SCHEMA)


def run_spec(spec: RunSpec, study_id: str = "") -> tuple[dict, Any]:
    """One run: (row, result or None)."""

    row = _row_head(spec, study_id)
    t0 = time.perf_counter()
    try:
        if engine.__version__ != spec.engine_version:
            raise RuntimeError(
                f"this worker runs engine {engine.__version__}, the study needs "
                f"{spec.engine_version}: install the service's beltstudy on every worker "
                "(the same version; `pip install` of the same checkout or image) and restart "
                "them, then DELETE /studies/<id> and POST the study again (a resubmitted "
                "study with failed runs is not rerun)"
            )
        # deferred: the transient engine (numba) loads on the worker's first run, not
        # in the API process that imports this module for its table builders
        from beltstudy.engine.run import run_one

        conveyor, scenario = parse_conveyor(spec.conveyor), parse_scenario(spec.scenario)
        result = _run(run_one, conveyor, scenario, spec)
    except Exception as exc:  # a run that raises is data, not an aborted study
        row.update(failed_row(_message(exc), time.perf_counter() - t0))
        return row, None
    return _row_done(row, spec, result, t0), result


def _row_head(spec: RunSpec, study_id: str) -> dict[str, Any]:
    """A run's row before its figures: ids, axis values, model, engine version."""
    return {"study_id": study_id, "run_id": spec.run_id, **spec.axes,
            "friction_model": spec.model, "engine_version": engine.__version__}


def _row_done(row: dict, spec: RunSpec, result, t0: float) -> dict:
    """A run's row with its figures and what set each size of its design."""
    row.update(flatten_summary(result.summary))
    # what set each size the study held for this run's conveyor design (beltstudy.service.grid.basis):
    # the run sees the numbers, and these words from the design (its message says them too)
    row.update(spec.design)
    if row["elapsed_s"] is None:
        row["elapsed_s"] = time.perf_counter() - t0
    return row


#: A brake's conveyor fields the transient engine reads only after the stop command
#: (``STOP_ONLY`` in engine/dynamics/shared.py): runs whose conveyors differ only in them may
#: share a start.
BRAKE_STOP_FIELDS = ("force_kn", "delay_s", "ramp_s", "force_curve", "hold")


def start_candidate(spec: RunSpec, memo: dict | None = None) -> tuple:
    """Runs that may share one simulated start: one conveyor but its brakes' forces, delays,
    ramps, curves and hold, one model, parameters and scenario but its stop, and temperatures
    that the model's law reads alike (DIN reads none, CEMA its Kt). The engine decides
    which of them do (:func:`beltstudy.engine.run.run_group`, from the models it builds). A
    steady-only run or one in the accuracy sample (its error bars rerun it) stands alone.
    ``memo`` (id of a conveyor mapping -> its key) saves work over runs sharing a mapping."""
    if not spec.dynamics or spec.check:
        return ("alone", spec.run_id)
    conv = spec.conveyor
    shape = memo.get(id(conv)) if memo is not None else None
    if shape is None:
        brakes = [{k: v for k, v in b.items() if k not in BRAKE_STOP_FIELDS}
                  for b in conv.get("brakes") or []]
        shape = json.dumps({**conv, "brakes": brakes}, sort_keys=True, default=str)
        if memo is not None:
            memo[id(conv)] = shape
    params = json.dumps(spec.params, sort_keys=True, default=str)
    scn = {k: v for k, v in spec.scenario.items() if k != "stop"}
    if "temperature_c" in scn:
        scn["temperature_c"] = _temperature_as_read(spec.model, params, spec.params,
                                                    scn["temperature_c"], memo)
    return (shape, json.dumps(scn, sort_keys=True, default=str), spec.model, params,
            spec.engine_version)


def _temperature_as_read(model: str, key: str, params: dict | None, temperature_c, memo):
    """What ``model``'s law reads of ``temperature_c``
    (:meth:`~beltstudy.engine.friction.base.FrictionModel.temperature_as_read`: nothing for
    DIN, Kt for CEMA), so that runs whose laws read their temperatures alike go to one task;
    the temperature itself when the model or its parameters do not resolve (the run then
    fails on its own)."""
    memo_key = ("temperature", model, key, temperature_c)
    if memo is not None and memo_key in memo:
        return memo[memo_key]
    try:
        fm = get_model(model)
        read = fm.temperature_as_read(fm.params(params), float(temperature_c))
    except Exception:
        read = temperature_c
    if memo is not None:
        memo[memo_key] = read
    return read


def run_specs(specs: list[RunSpec], study_id: str = "") -> list[tuple[dict, Any]]:
    """:func:`run_spec` of each spec, the runs that differ only in their stop sharing one
    simulated start (:func:`beltstudy.engine.run.run_group`); results and rows as run alone.
    A group whose shared run raises runs again one run at a time (a bad run fails alone)."""
    groups: dict[tuple, list[int]] = {}
    memo: dict = {}
    for i, spec in enumerate(specs):
        groups.setdefault(start_candidate(spec, memo), []).append(i)
    out: list[tuple[dict, Any] | None] = [None] * len(specs)
    for idx in groups.values():
        if len(idx) > 1:
            shared = _run_shared([specs[i] for i in idx], study_id)
            if shared is not None:
                for i, pair in zip(idx, shared, strict=True):
                    out[i] = pair
                continue
        for i in idx:
            out[i] = run_spec(specs[i], study_id)
    return out  # type: ignore[return-value]


def _run_shared(specs: list[RunSpec], study_id: str) -> list[tuple[dict, Any]] | None:
    """The rows and results of runs that may share a start, or None when one of them cannot
    run (the caller then runs each alone, so the bad one fails with its own message)."""
    from beltstudy.engine.run import run_group

    t0 = time.perf_counter()
    try:
        if any(engine.__version__ != s.engine_version for s in specs):
            return None
        parsed: dict[int, object] = {}  # runs sharing a conveyor mapping share its model
        for s in specs:
            if id(s.conveyor) not in parsed:
                parsed[id(s.conveyor)] = parse_conveyor(s.conveyor)
        conveyors = [parsed[id(s.conveyor)] for s in specs]
        scenarios = [parse_scenario(s.scenario) for s in specs]
        results = run_group(conveyors, scenarios, model=specs[0].model,
                            params=specs[0].params or None,
                            auto_brakes=[_auto_brakes(s) for s in specs],
                            governed=[s.design for s in specs])
    except Exception:
        return None
    return [(_row_done(_row_head(spec, study_id), spec, result, t0), result)
            for spec, result in zip(specs, results, strict=True)]


def _auto_brakes(spec: RunSpec) -> bool | None:
    """Whether the study's design sized a brake of this run (its ``brake_governed_by`` names
    a reason other than ``given``): the conveyor the worker runs has the size written in, so
    the engine is told; None (the engine reads the conveyor) where the design sized none."""
    why = spec.design.get("brake_governed_by")
    if not why:
        return None
    return any(part.split(" @")[0].strip() != GIVEN for part in why.split("+"))


def _run(run_one, conveyor, scenario, spec: RunSpec):
    """``run_one`` of a spec, with error bars for a run of the accuracy sample; a check that
    raises leaves the run without them, with a note in its message."""
    kw = {"model": spec.model, "params": spec.params or None, "dynamics": spec.dynamics,
          "auto_brakes": _auto_brakes(spec), "governed": spec.design}
    if not (spec.check and spec.dynamics):
        return run_one(conveyor, scenario, **kw)
    try:
        return run_one(conveyor, scenario, check=True, **kw)
    except Exception as exc:  # the run stands; only its error bars are missing
        result = run_one(conveyor, scenario, **kw)
        s = result.summary
        s["message"] = "; ".join(m for m in (s.get("message"),
                                             f"note: no error bars: {_message(exc)}") if m)
        return result


class Specs:
    """The runs of one task. Dask walks every list and dict among a task's arguments looking
    for futures; wrapped, a batch of runs with their nested conveyors is passed as it is
    (pickled once: runs that share a conveyor mapping share it in the pickle too)."""

    __slots__ = ("items",)

    def __init__(self, items: list[RunSpec]):
        self.items = items

    def __len__(self) -> int:
        return len(self.items)


def run_batch(
    study_id: str, specs: list[RunSpec] | Specs, surface: bool = False, sink: dict | None = None
) -> dict:
    """Run ``specs`` one after another; return rows, the time series and steady profiles.

    ``surface``: also return (or write) each dynamic run's tension/velocity surface; without
    it the surface is never built (it is recomputed from the run's inputs when asked for).
    With ``sink`` (``{"dir", "token", "key"}``) and the study directory visible here (a
    LocalCluster, or workers sharing the data volume), the time-series tables are written
    straight to ``<dir>/<table>/part-<key>.parquet`` (one part per table and task) instead of
    being sent back; the runs rows always go back to the service, which writes them last (the
    commit).

    Returns ``{"rows": [...], "timeseries": Table | None, "profile": Table | None,
    "surface": Table | None, "accuracy": Table | None (the error bars of the runs in the
    study's accuracy sample),
    "seconds": float, "pid": int, "split": {"run_s", "tables_s", "write_s", "cpu_s"}}``: the
    split is the task's wall time in running the runs, in building the Arrow tables and in
    writing parts, and the CPU time of the whole task.
    """
    t0 = time.perf_counter()
    cpu0 = time.thread_time()
    if isinstance(specs, Specs):
        specs = specs.items
    rows, series, profiles, surfaces, accuracy = [], [], [], [], []
    t_run = t_tables = t_write = 0.0
    t1 = time.perf_counter()
    pairs = run_specs(specs, study_id)
    t_run = time.perf_counter() - t1
    for spec, (row, result) in zip(specs, pairs, strict=True):
        t2 = time.perf_counter()
        rows.append(row)
        if result is None:
            continue
        builders = [(timeseries_table, series), (profile_table, profiles),
                    (accuracy_table, accuracy)] + ([(surface_table, surfaces)] if surface else [])
        try:
            for build, tables in builders:
                table = build(spec.run_id, result)
                if table is not None:
                    tables.append(table)
        except Exception as exc:  # a malformed result is reported on the run's row
            row.update(failed_row(f"time series: {_message(exc)}", row.get("elapsed_s")))
        t_tables += time.perf_counter() - t2
    t2 = time.perf_counter()
    out = {
        "rows": rows,
        "timeseries": pa.concat_tables(series) if series else None,
        "profile": pa.concat_tables(profiles) if profiles else None,
        "surface": pa.concat_tables(surfaces) if surfaces else None,
        "accuracy": pa.concat_tables(accuracy) if accuracy else None,
        "pid": os.getpid(),
    }
    t_tables += time.perf_counter() - t2
    if sink is not None:
        t2 = time.perf_counter()
        for table in PART_TABLES:
            data = out[table]
            if data is not None and write_part_to(
                sink["dir"], sink["token"], table, sink["key"], data
            ):
                out[table] = None
        t_write = time.perf_counter() - t2
    out["seconds"] = time.perf_counter() - t0
    out["split"] = {"run_s": t_run, "tables_s": t_tables, "write_s": t_write,
                    "cpu_s": time.thread_time() - cpu0}
    return out


def warm_up() -> dict:
    """Import the engine and run the tiny conveyor once per model, dynamics on (numba compile).

    Returns the process id, the models warmed, the seconds it took, the errors, and whether
    this process compiled the kernel (``compiled``) instead of loading it from numba's cache.
    """
    t0 = time.perf_counter()

    models = list(MODELS)
    errors = []
    for i, name in enumerate(models):
        spec = RunSpec(run_id=f"warm-up-{name}", axes={}, conveyor=TINY_CONVEYOR,
                       scenario=TINY_SCENARIO, model=name, params={}, dynamics=i == 0,
                       engine_version=engine.__version__)
        row, _ = run_spec(spec)
        if row["status"] == "failed":
            errors.append(f"{name}: {row['message']}")
    from beltstudy.engine.warmth import kernel_dispatchers

    return {
        "pid": os.getpid(),
        "engine_version": engine.__version__,
        "models": models,
        "seconds": time.perf_counter() - t0,
        "errors": errors,
        # compiled here rather than loaded from numba's cache: this process's kernel gives
        # other last bits than the cached one every later process loads (issue 31)
        "compiled": any(d.stats.cache_misses for d in kernel_dispatchers()),
    }


def lower_priority(niceness: int) -> int:
    """Run this worker process at ``niceness`` (absolute, so calling it twice is harmless);
    returns the niceness in force. The LocalCluster's workers share the machine with the API:
    at a lower priority they leave it the CPU it needs to answer at once."""
    try:
        os.setpriority(os.PRIO_PROCESS, 0, niceness)
        return os.getpriority(os.PRIO_PROCESS, 0)
    except (AttributeError, OSError):  # not on this platform, or not allowed
        return 0


class LowerPriority(WorkerPlugin):
    """A worker plugin: every worker, restarted ones too, at :func:`lower_priority`."""

    name = "beltstudy-lower-priority"

    def __init__(self, niceness: int):
        self.niceness = niceness

    def setup(self, worker) -> None:
        lower_priority(self.niceness)
