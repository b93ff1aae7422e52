"""Arrow schemas of the stored tables (SPEC sections 4 and 5) and row flattening.

The runs schema is fixed per study: the inputs (``study_id``, ``run_id``, one column per
grid axis, ``friction_model``, ``engine_version``), every SPEC section 4 result column, the
``te_<part>_kn`` columns of every part any model reports (null where a model has no such
part; ``te_other_kn`` sums parts outside the SPEC list), and the bookkeeping columns.
"""

from __future__ import annotations

import json
import math
from typing import Any

import pyarrow as pa

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
    "BOOKKEEPING_COLUMNS",
    "TIMESERIES_COLUMNS",
    "SURFACE_COLUMNS",
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

#: Most drives a conveyor may have: the per-drive columns ``drive{i}_*`` run from 1 to it
#: (null where a conveyor has fewer drives).
MAX_DRIVES = 6
STEADY_DRIVE_FIELDS = ("t_tight_kn", "t_slack_kn", "slip_margin")
TRANSIENT_DRIVE_FIELDS = ("force_max_kn", "power_max_kw", "slip_margin_min", "slip_s", "slip_m")
STEADY_COLUMNS = (
    "te_kn", "power_kw", "t1_kn", "t2_kn", "t_max_kn", "t_max_at_m", "t_min_kn", "t_min_at_m",
    "sag_max_pct", "takeup_mass_kg", "takeup_tension_kn", "slip_margin", "slip_margin_start",
    "safety_factor", "belt_mass_kg_m", "load_mass_kg_m", "idler_mass_carry_kg_m",
    "idler_mass_return_kg_m", "belt_modulus_kn", "belt_modulus_dyn_kn", "belt_rating_kn",
    "wave_speed_carry_m_s", "wave_speed_return_m_s",
) + tuple(f"drive{i}_{f}" for i in range(1, MAX_DRIVES + 1)
          for f in STEADY_DRIVE_FIELDS)  # fmt: skip
#: SPEC 6.4 per phase: start (start command to stop command) and stop (stop command on).
PHASE_COLUMNS = tuple(f"t_{m}_{p}_{k}" for p in ("start", "stop") for m in ("max", "min")
                      for k in ("kn", "at_m", "time_s"))
TRANSIENT_COLUMNS = (
    "t_max_dyn_kn", "t_max_dyn_at_m", "t_max_dyn_time_s", "t_min_dyn_kn", "t_min_dyn_at_m",
    "t_min_dyn_time_s", "dyn_factor", "drive_force_max_kn", "drive_power_max_kw",
    "velocity_max_m_s", "velocity_min_m_s", "takeup_travel_m", "start_time_s", "stop_time_s",
    "wave_loop_time_s", "stop_wave_ratio", "sag_max_dyn_pct", "slip_margin_min_dyn",
    "safety_factor_dyn",
) + PHASE_COLUMNS + (
    "t_max_pre_slack_kn", "t_max_post_slack_kn", "t_max_post_slack_at_m",
    "t_max_post_slack_time_s", "slack_max_m", "slack_at_m", "slack_time_s", "slack_duration_s",
    "takeup_endstop_speed_m_s",
) + tuple(f"drive{i}_{f}" for i in range(1, MAX_DRIVES + 1)
          for f in TRANSIENT_DRIVE_FIELDS)  # fmt: skip
#: Parts of ``te_components_kn``: the six every model reports, then nonlin's finer split.
TE_PARTS = (
    "main_carry", "main_return", "lift", "feed", "secondary", "accessories",
    "idler_rotation", "indentation", "belt_flexure", "material_flexure", "other",
)  # fmt: skip
TE_PART_COLUMNS = tuple(f"te_{p}_kn" for p in TE_PARTS)
#: SPEC 6.4 design and capacity columns: the sizes the run used (totals over drives and
#: brakes) and the capacity check.
DESIGN_COLUMNS = ("takeup_pretension_kn", "rated_power_kw", "brake_force_kn", "fill_pct")
#: What set each auto size (text): take-up ``slip_start`` | ``slip_running`` | ``sag_running``
#: | ``sag_at_rest``; rated power ``peripheral_force`` | ``running_resistance``; brakes
#: ``stop_time`` | ``holding``; ``given`` when the file gives the size.
DESIGN_TEXT_COLUMNS = ("takeup_governed_by", "rated_power_governed_by", "brake_governed_by")
RESULT_COLUMNS = STEADY_COLUMNS + DESIGN_COLUMNS + TE_PART_COLUMNS + TRANSIENT_COLUMNS
BOOKKEEPING_COLUMNS = ("status", "message", "elapsed_s")
INPUT_COLUMNS = ("study_id", "run_id", "friction_model", "engine_version")

TIMESERIES_COLUMNS = (
    "t_s", "v_drive_m_s", "v_tail_m_s", "f_drive_kn", "t_head_in_kn", "t_head_out_kn",
    "t_tail_kn", "t_takeup_kn", "x_takeup_m", "t_min_kn", "t_max_kn", "v_mean_m_s",
    "v_ref_m_s", "f_brake_kn", "p_drive_kw", "v_abs_max_m_s", "slack_m",
) + tuple(f"{q}{i}_{u}" for i in range(1, MAX_DRIVES + 1)
          for q, u in (("f_drive", "kn"), ("v_drive", "m_s"), ("f_belt", "kn"))
          )  # fmt: skip
SURFACE_COLUMNS = ("t_s", "s_m", "tension_kn", "velocity_m_s")


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
    fields += [pa.field(c, pa.float64()) for c in RESULT_COLUMNS]
    fields += [pa.field(c, pa.string()) for c in DESIGN_TEXT_COLUMNS]
    fields += [
        pa.field("status", pa.string()),
        pa.field("message", pa.string()),
        pa.field("elapsed_s", pa.float64()),
    ]
    return pa.schema(fields)


def runs_schema_for_axes(axes: list[dict]) -> pa.Schema:
    """The runs schema from the ``axes`` list of a stored study (``column`` and ``values``)."""
    return runs_schema([(a["column"], axis_type(list(a["values"]))) for a in axes])


def timeseries_schema() -> pa.Schema:
    return pa.schema(
        [pa.field("run_id", pa.string())] + [pa.field(c, pa.float64()) for c in TIMESERIES_COLUMNS]
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
                           for c in STEADY_COLUMNS + DESIGN_COLUMNS + TRANSIENT_COLUMNS}
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
