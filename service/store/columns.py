"""Arrow schemas of the stored tables (SPEC sections 4 and 5) and row flattening.

The runs schema is fixed per study: the inputs (``study_id``, ``run_id``, one column per
grid axis, ``friction_model``, ``engine_version``), then every result of
:mod:`beltstudy.engine.results` in its order: the ``te_<part>_kn`` columns of every part any model
reports (null where a model has no such part; ``te_other_kn`` sums parts outside the SPEC
list) and the per-drive columns for drives 1 to ``MAX_DRIVES``.
"""

from __future__ import annotations

import json
import math
from typing import Any

import pyarrow as pa

from beltstudy.engine import MAX_DRIVES
from beltstudy.engine import results as R

__all__ = [
    "MAX_DRIVES",
    "PHASE_COLUMNS",
    "STEADY_COLUMNS",
    "DESIGN_COLUMNS",
    "DESIGN_TEXT_COLUMNS",
    "TRANSIENT_COLUMNS",
    "TE_PARTS",
    "TE_PART_COLUMNS",
    "RESULT_COLUMNS",
    "CHECK_COLUMNS",
    "BOOKKEEPING_COLUMNS",
    "TIMESERIES_COLUMNS",
    "SURFACE_COLUMNS",
    "PROFILE_COLUMNS",
    "profile_schema",
    "accuracy_schema",
    "ACCURACY_COLUMNS",
    "runs_schema",
    "runs_schema_for_axes",
    "axis_type",
    "flatten_summary",
    "failed_row",
    "rows_to_table",
    "timeseries_schema",
    "surface_schema",
    "components_from_row",
]

#: Every result column is derived from :mod:`beltstudy.engine.results` (name, unit, meaning): a field
#: defined there is a column here, and nothing else is.
STEADY_COLUMNS = R.columns((R.STEADY, R.STEADY_DRIVE))
#: SPEC 6.4 per phase: start (start command to stop command) and stop (stop command on).
PHASE_COLUMNS = R.columns((R.PHASE,))
TRANSIENT_COLUMNS = R.columns((R.TRANSIENT, R.PHASE, R.SLACK, R.TRANSIENT_DRIVE))
TE_PARTS = R.TE_PARTS
TE_PART_COLUMNS = R.columns((R.TE_COMPONENTS,))
#: SPEC 6.4 design and capacity columns: the sizes the run used (totals over drives and
#: brakes, and per drive) and the capacity check.
DESIGN_COLUMNS = R.columns((R.DESIGN, R.DESIGN_DRIVE))
#: What set each auto size, and the pulleys' names (text).
DESIGN_TEXT_COLUMNS = R.columns((R.DESIGN_BASIS,)) + tuple(
    c for c in R.columns((R.CHECKS,)) if R.field(c).text) + tuple(
    c for c in R.columns((R.CURVES,)) if R.field(c).text)
#: SPEC 7.4 per drive: the motor power needed against the rating (steady), the time above
#: the rated force and the RMS force (transient).
DRIVE_POWER_COLUMNS = R.columns((R.DRIVE_POWER, R.DRIVE_LOAD))
#: Design checks (docs/checks.md): numbers, the per-pulley names (text) and verdicts (bool).
CHECK_COLUMNS = tuple(c for c in R.columns((R.CHECKS, R.CHECKS_TRANSIENT))
                      if not R.field(c).text)
#: Vertical curves (docs/routes.md, part (c)): numbers and verdicts (bool); curve{k}_kind is
#: text, with the design text columns.
CURVE_COLUMNS = tuple(c for c in R.columns((R.CURVES, R.CURVES_TRANSIENT))
                      if not R.field(c).text)
#: Horizontal curves (docs/routes.md): per curve 1 to MAX_HCURVES.
HCURVE_COLUMNS = R.columns((R.HCURVES,))
RESULT_COLUMNS = (STEADY_COLUMNS + DESIGN_COLUMNS + TE_PART_COLUMNS + TRANSIENT_COLUMNS
                  + DRIVE_POWER_COLUMNS + CHECK_COLUMNS + CURVE_COLUMNS + HCURVE_COLUMNS)
BOOKKEEPING_COLUMNS = R.columns((R.BOOKKEEPING,))
INPUT_COLUMNS = ("study_id", "run_id", "friction_model", "engine_version")

TIMESERIES_COLUMNS = (
    "t_s", "v_drive_m_s", "v_tail_m_s", "f_drive_kn", "t_head_in_kn", "t_head_out_kn",
    "t_tail_kn", "t_takeup_kn", "x_takeup_m", "t_min_kn", "t_max_kn", "v_mean_m_s",
    "v_ref_m_s", "f_brake_kn", "p_drive_kw", "v_abs_max_m_s", "slack_m", "f_holdback_kn",
) + tuple(f"{q}{i}_{u}" for i in range(1, MAX_DRIVES + 1)
          for q, u in (("f_drive", "kn"), ("v_drive", "m_s"), ("f_belt", "kn"),
                       ("v_motor", "m_s"))
          )  # fmt: skip
SURFACE_COLUMNS = ("t_s", "s_m", "tension_kn", "velocity_m_s")
#: The steady tension along the loop at element ends (``RunResult.profile``).
PROFILE_COLUMNS = ("s_m", "strand", "elevation_m", "tension_kn", "sag_pct")


def axis_type(values: list[Any]) -> pa.DataType:
    """Arrow type of an axis column: int64, float64, bool or string (JSON for mixed values)."""
    if values and all(isinstance(v, bool) for v in values):
        return pa.bool_()
    if values and all(isinstance(v, int) and not isinstance(v, bool) for v in values):
        return pa.int64()
    if values and all(isinstance(v, int | float) and not isinstance(v, bool) for v in values):
        return pa.float64()
    return pa.string()


def axis_value(value: Any, typ: pa.DataType) -> Any:
    """An axis value as stored in its column."""
    if pa.types.is_string(typ):
        return value if isinstance(value, str) else json.dumps(value, sort_keys=True)
    if pa.types.is_floating(typ):
        return float(value)
    return value


def runs_schema(axis_columns: list[tuple[str, pa.DataType]]) -> pa.Schema:
    """The runs table schema of a study with these axis columns."""
    fields = [pa.field("study_id", pa.string()), pa.field("run_id", pa.string())]
    names = {"study_id", "run_id"}
    for name, typ in axis_columns:
        fields.append(pa.field(name, typ))
        names.add(name)
    for name in ("friction_model", "engine_version"):
        if name not in names:
            fields.append(pa.field(name, pa.string()))
    fields += [pa.field(c, pa.bool_() if R.field(c).flag else pa.float64())
               for c in RESULT_COLUMNS]
    fields += [pa.field(c, pa.string() if R.field(c).text else pa.float64())
               for c in DESIGN_TEXT_COLUMNS + BOOKKEEPING_COLUMNS]
    return pa.schema(fields)


def runs_schema_for_axes(axes: list[dict]) -> pa.Schema:
    """The runs schema from the ``axes`` list of a stored study (``column`` and ``values``)."""
    return runs_schema([(a["column"], axis_type(list(a["values"]))) for a in axes])


def timeseries_schema() -> pa.Schema:
    return pa.schema(
        [pa.field("run_id", pa.string())] + [pa.field(c, pa.float64()) for c in TIMESERIES_COLUMNS]
    )


#: The accuracy table (a study's ``accuracy: {sample: ...}``): per sampled run, the error
#: bars of :data:`beltstudy.engine.results.ACCURACY` (``<figure>_err``, ``<figure>_converged``,
#: per-drive ones for drives 1 to MAX_DRIVES, the meshes and methods).
ACCURACY_COLUMNS = R.columns((R.ACCURACY,))


def accuracy_schema() -> pa.Schema:
    """The accuracy table: ``run_id``, then :data:`ACCURACY_COLUMNS` (text or float64)."""
    return pa.schema(
        [pa.field("run_id", pa.string())]
        + [pa.field(c, pa.string() if R.field(c).text else pa.float64())
           for c in ACCURACY_COLUMNS]
    )


def profile_schema() -> pa.Schema:
    """The steady profile table: one row per element end, ``strand`` as text."""
    return pa.schema(
        [pa.field("run_id", pa.string())]
        + [pa.field(c, pa.string() if c == "strand" else pa.float64()) for c in PROFILE_COLUMNS]
    )


def surface_schema() -> pa.Schema:
    """The surface table: float32 values (plots need no more; a quarter of the bytes)."""
    return pa.schema(
        [pa.field("run_id", pa.string())] + [pa.field(c, pa.float32()) for c in SURFACE_COLUMNS]
    )


def _number(value: Any) -> float | None:
    try:
        x = float(value)
    except (TypeError, ValueError):
        return None
    return x if math.isfinite(x) else None


def flatten_summary(summary: dict) -> dict:
    """SPEC section 4 result fields of a ``RunResult.summary`` as flat row values.

    ``te_components_kn`` becomes ``te_<part>_kn`` columns; parts outside :data:`TE_PARTS`
    are summed into ``te_other_kn`` so the parts still add up to ``te_kn``.
    """
    row: dict[str, Any] = {c: _number(summary.get(c))
                           for c in STEADY_COLUMNS + DESIGN_COLUMNS + TRANSIENT_COLUMNS
                           + DRIVE_POWER_COLUMNS}
    for c in CHECK_COLUMNS + CURVE_COLUMNS + HCURVE_COLUMNS:
        value = summary.get(c)
        row[c] = (None if value is None else bool(value)) if R.field(c).flag else _number(value)
    for c in DESIGN_TEXT_COLUMNS:
        row[c] = str(summary[c]) if summary.get(c) is not None else None
    parts = summary.get("te_components_kn") or {}
    other = None
    for part, value in parts.items():
        col = f"te_{part}_kn"
        if col in TE_PART_COLUMNS and part != "other":
            row[col] = _number(value)
        else:
            other = (other or 0.0) + (_number(value) or 0.0)
    for col in TE_PART_COLUMNS:
        row.setdefault(col, None)
    row["te_other_kn"] = other
    row["status"] = str(summary.get("status") or "ok")
    row["message"] = str(summary.get("message") or "")
    row["elapsed_s"] = _number(summary.get("elapsed_s"))
    return row


def failed_row(message: str, elapsed_s: float | None = None) -> dict:
    """Result values of a run that raised: every result null, status failed."""
    row: dict[str, Any] = dict.fromkeys(RESULT_COLUMNS + DESIGN_TEXT_COLUMNS)
    row.update(status="failed", message=message, elapsed_s=elapsed_s)
    return row


def rows_to_table(rows: list[dict], schema: pa.Schema) -> pa.Table:
    """Rows (dicts) to a table of exactly ``schema`` (missing keys null, extra keys dropped;
    a non-text value in a text column, such as a load given per section, as its JSON)."""
    columns = {f.name: [r.get(f.name) for r in rows] for f in schema}
    for f in schema:
        if pa.types.is_string(f.type):
            columns[f.name] = [v if v is None or isinstance(v, str) else axis_value(v, f.type)
                               for v in columns[f.name]]
    return pa.Table.from_pydict(columns, schema=schema)


def components_from_row(row: dict) -> dict[str, float]:
    """``te_components_kn`` rebuilt from a flat row (parts that are not null)."""
    out = {}
    for part, col in zip(TE_PARTS, TE_PART_COLUMNS, strict=True):
        value = row.get(col)
        if value is not None and not (isinstance(value, float) and math.isnan(value)):
            out[part] = value
    return out
