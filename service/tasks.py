"""Worker-side functions: run a batch of runs through ``engine.run.run_one``; warm a worker.

These run inside Dask workers (and in the benchmark's plain loop). A run that raises becomes
a row with ``status=failed`` and the message; the batch itself never raises for a bad run.
Results travel back as plain rows and Arrow tables.
"""

from __future__ import annotations

import os
import time
from typing import Any

import pyarrow as pa
from distributed import WorkerPlugin

from service.schema import (
    SURFACE_COLUMNS,
    TIMESERIES_COLUMNS,
    failed_row,
    flatten_summary,
    surface_schema,
    timeseries_schema,
)

__all__ = [
    "run_batch",
    "run_spec",
    "warm_up",
    "lower_priority",
    "LowerPriority",
    "TINY_CONVEYOR",
    "TINY_SCENARIO",
]

#: A 60 m conveyor with a handful of elements: compiles every code path in well under a second
#: once numba's cache is warm.
TINY_CONVEYOR: dict[str, Any] = {
    "name": "warm-up",
    "speed_m_s": 2.0,
    "belt": {"type": "EP630/4", "width_m": 0.8},
    "material": {"capacity_t_h": 200, "density_t_m3": 1.0},
    "profile": [{"length_m": 60, "lift_m": 3}],
    "idlers": {
        "carry": {"spacing_m": 1.2, "trough_deg": 30},
        "return": {"spacing_m": 3.0, "rolls": 1},
    },
    "drives": [{"position": "head", "pulley_diameter_m": 0.6, "inertia_kg_m2": 20}],
}
TINY_SCENARIO: dict[str, Any] = {
    "elements": 12,
    "start": {"time_s": 2.0},
    "run_s": 1.0,
    "stop": {"mode": "coast", "time_s": 2.0},
    "record_dt_s": 0.5,
}

_MAX_MESSAGE = 1000


def _message(exc: BaseException) -> str:
    text = str(exc).strip().splitlines()
    first = text[0] if text else ""
    msg = f"{type(exc).__name__}: {first}" if first else type(exc).__name__
    return msg[:_MAX_MESSAGE]


def _frame_table(df, run_id: str, columns: tuple[str, ...], schema: pa.Schema) -> pa.Table | None:
    if df is None or len(df) == 0:
        return None
    data = {"run_id": [run_id] * len(df)}
    for col in columns:
        dtype = schema.field(col).type.to_pandas_dtype()
        data[col] = df[col].to_numpy(dtype=dtype) if col in df else [None] * len(df)
    return pa.Table.from_pydict(data, schema=schema)


def run_spec(spec: dict, study_id: str = "") -> tuple[dict, Any]:
    """One run: (row, result or None). ``spec`` is a :class:`~service.study.RunSpec` as a dict."""
    import engine
    from engine.conveyor import parse_conveyor, parse_scenario

    row: dict[str, Any] = {
        "study_id": study_id,
        "run_id": spec["run_id"],
        **spec["axes"],
        "friction_model": spec["model"],
        "engine_version": engine.__version__,
    }
    t0 = time.perf_counter()
    try:
        if engine.__version__ != spec["engine_version"]:
            raise RuntimeError(
                f"this worker runs engine {engine.__version__}, the study needs "
                f"{spec['engine_version']}"
            )
        from engine.run import run_one

        conveyor = parse_conveyor(spec["conveyor"])
        scenario = parse_scenario(spec["scenario"])
        result = run_one(
            conveyor,
            scenario,
            model=spec["model"],
            params=spec["params"] or None,
            dynamics=spec["dynamics"],
        )
    except Exception as exc:  # a run that raises is data, not an aborted study
        row.update(failed_row(_message(exc), time.perf_counter() - t0))
        return row, None
    row.update(flatten_summary(result.summary))
    # what set each size the study held for this run's conveyor design (service.basis): the
    # run itself only sees the numbers
    row.update(spec.get("design") or {})
    if row["elapsed_s"] is None:
        row["elapsed_s"] = time.perf_counter() - t0
    return row, result


def run_batch(
    study_id: str, specs: list[dict], surface: bool = True, sink: dict | None = None
) -> dict:
    """Run ``specs`` one after another; return rows and the time-series tables.

    With ``sink`` (``{"dir", "token", "key"}``) and the study directory visible here (a
    LocalCluster, or workers sharing the data volume), the time-series tables are written
    straight to ``<dir>/<table>/part-<key>.parquet`` instead of being sent back; the runs
    rows always go back to the service, which writes them last (the commit).

    Returns ``{"rows": [...], "timeseries": Table | None, "surface": Table | None,
    "seconds": float, "pid": int}``.
    """
    t0 = time.perf_counter()
    rows, series, surfaces = [], [], []
    ts_schema, sf_schema = timeseries_schema(), surface_schema()
    for spec in specs:
        row, result = run_spec(spec, study_id)
        rows.append(row)
        if result is None:
            continue
        try:
            table = _frame_table(result.timeseries, spec["run_id"], TIMESERIES_COLUMNS, ts_schema)
            if table is not None:
                series.append(table)
            if surface:
                table = _frame_table(
                    getattr(result, "surface", None), spec["run_id"], SURFACE_COLUMNS, sf_schema
                )
                if table is not None:
                    surfaces.append(table)
        except Exception as exc:  # a malformed result is reported on the run's row
            row.update(failed_row(f"time series: {_message(exc)}", row.get("elapsed_s")))
    out = {
        "rows": rows,
        "timeseries": pa.concat_tables(series) if series else None,
        "surface": pa.concat_tables(surfaces) if surfaces else None,
        "seconds": time.perf_counter() - t0,
        "pid": os.getpid(),
    }
    if sink is not None:
        from service.store import write_part_to

        for table in ("surface", "timeseries"):
            data = out[table]
            if data is not None and write_part_to(
                sink["dir"], sink["token"], table, sink["key"], data
            ):
                out[table] = None
    return out


def warm_up() -> dict:
    """Import the engine and run the tiny conveyor once per model, dynamics on (numba compile).

    Returns the process id, the models warmed and the seconds it took.
    """
    t0 = time.perf_counter()
    from engine.friction import MODELS

    models = list(MODELS)
    errors = []
    for i, name in enumerate(models):
        spec = {
            "run_id": f"warm-up-{name}",
            "axes": {},
            "conveyor": TINY_CONVEYOR,
            "scenario": TINY_SCENARIO,
            "model": name,
            "params": {},
            "dynamics": i == 0,
            "engine_version": __import__("engine").__version__,
        }
        row, _ = run_spec(spec)
        if row["status"] == "failed":
            errors.append(f"{name}: {row['message']}")
    return {
        "pid": os.getpid(),
        "models": models,
        "seconds": time.perf_counter() - t0,
        "errors": errors,
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
