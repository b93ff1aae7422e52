"""Reading results: JSON-safe rows, filters, and the friction-model comparison.

Pure functions of DataFrames read from the store; the API and the CLI share them.
"""

from __future__ import annotations

import difflib
import io
import json
import math
from typing import Any

import numpy as np
import pandas as pd
import pyarrow as pa
import pyarrow.parquet as pq

from beltstudy.engine import InputError, canonical_name, get_model
from beltstudy.service.errors import Invalid, damaged_parts_message
from beltstudy.service.store.columns import TE_PART_COLUMNS, components_from_row

__all__ = [
    "row_to_json",
    "rows_to_json",
    "columns_to_json",
    "records_to_json",
    "apply_filters",
    "filter_columns",
    "column_list",
    "no_column",
    "folded_components",
    "sort_key",
    "sort_rows",
    "compare",
    "model_pair",
    "to_csv",
    "to_parquet",
    "accuracy_columns",
    "unreadable_fields",
    "DEFAULT_METRICS",
]

#: power, and the peak and lowest tension of the stop (the phase a stop-time axis changes)
DEFAULT_METRICS = ("power_kw", "t_max_stop_kn", "t_min_stop_kn")


def _clean(value: Any) -> Any:
    if value is None:
        return None
    if isinstance(value, np.generic):
        value = value.item()
    if isinstance(value, float) and not math.isfinite(value):
        return None
    if value is pd.NA or value is pd.NaT:
        return None
    return value


def row_to_json(row: dict) -> dict:
    """A flat runs row as REST/CLI output: ``te_<part>_kn`` folded into ``te_components_kn``."""
    out = {k: _clean(v) for k, v in row.items() if k not in TE_PART_COLUMNS}
    out["te_components_kn"] = {k: _clean(v) for k, v in components_from_row(row).items()}
    return out


def rows_to_json(df: pd.DataFrame) -> list[dict]:
    return [row_to_json(r) for r in df.to_dict(orient="records")]


def records_to_json(df: pd.DataFrame) -> list[dict]:
    """A DataFrame as a list of ``{column: value}`` with NaN as null (no folding)."""
    return [{k: _clean(v) for k, v in r.items()} for r in df.to_dict(orient="records")]


def columns_to_json(df: pd.DataFrame) -> dict[str, list]:
    """A DataFrame as ``{column: [values]}`` with NaN as null."""
    return {c: [_clean(v) for v in df[c].tolist()] for c in df.columns}


def unreadable_fields(study_id: str, bad: list[tuple[Any, str]]) -> dict:
    """What a runs page read from the readable parts says of the parts it could not read:
    ``unreadable_parts`` (``{file, reason}`` each) and ``message`` (the files, that the rows
    listed are the other parts', and the way out); nothing for a sound study (its page is
    as it always was)."""
    if not bad:
        return {}
    return {
        "unreadable_parts": [{"file": str(path), "reason": why} for path, why in bad],
        "message": damaged_parts_message(study_id, "runs", bad) + "; the runs listed are "
                   "those of the other parts",
    }


def axis_hint(filters: list[str], axes: dict[str, str]) -> dict:
    """A ``message`` for a runs page no row matched where a filter names a study axis by its
    name and the axis is stored under another column (the stop-time axis ``stop_time_s`` is
    the column ``stop_time_target_s``; ``stop_time_s`` is the stop time each run achieved):
    ``{}`` otherwise. ``axes``: ``{axis name: column}`` of the study's status."""
    said = []
    for item in filters:
        name, eq, value = item.partition("=")
        column = axes.get(name)
        if eq and column and column != name:
            said.append(f"filter {item} matched no row: the study's axis {name} is the column "
                        f"{column} (filter={column}={value}); the column {name} holds each "
                        "run's own figure")
    return {"message": "; ".join(said)} if said else {}


class _NoMatch(Exception):
    """A filter value no row of that column can equal (text for a number column)."""


def _boolean(series: pd.Series) -> bool:
    """A yes/no column: boolean, or one whose values but its nulls are all booleans (a failed
    run's null makes ``pulley1_diameter_min_ok`` an object column of True and None, where
    ``filter=pulley1_diameter_min_ok=true``, the value as the JSON rows show it, matched
    nothing: it was compared as text with 'True')."""
    if pd.api.types.is_bool_dtype(series):
        return True
    values = series.dropna()
    return (series.dtype == object and len(values) > 0
            and all(isinstance(v, bool | np.bool_) for v in values))


def _coerce(series: pd.Series, text: str) -> Any:
    if _boolean(series):
        if text.lower() not in ("true", "false"):
            raise _NoMatch
        return text.lower() == "true"
    if pd.api.types.is_numeric_dtype(series):
        try:
            value = float(text)
        except ValueError:
            raise _NoMatch from None
        if not math.isfinite(value):
            raise _NoMatch
        return value
    return text


def model_name(text: str, field: str) -> str:
    """The canonical name of a friction model given by name or alias (``iso5048`` is
    ``din``, as in study files); :class:`Invalid` naming ``field`` and the valid names."""

    try:
        return get_model(text).name
    except InputError as exc:
        raise Invalid(f"{field}: {exc.reason}") from None


#: The breakdown of ``te_kn`` as REST and CLI rows hold it: a JSON object, stored as the
#: ``te_<part>_kn`` columns (no column of its own to name, filter, sort or compare).
FOLDED_COMPONENTS = "te_components_kn"
#: What to do instead of naming :data:`FOLDED_COMPONENTS`, by the parameter that named it.
_PARTS_FIX = {"columns": "name those ({parts}) or leave columns= out for whole rows",
              "filter": "filter on one of those ({parts})",
              "sort": "sort by one of those ({parts})",
              "metrics": "compare those ({parts})"}


def folded_components(field: str, columns: list[str]) -> Invalid:
    """The 422 for ``te_components_kn`` named in ``field`` (``columns``, ``filter``,
    ``sort``, ``metrics``): what it is, and the study's part columns to name instead."""
    parts = ", ".join(c for c in columns if c in TE_PART_COLUMNS)
    fix = _PARTS_FIX.get(field, _PARTS_FIX["filter"]).format(parts=parts)
    return Invalid(f"{field}: {FOLDED_COMPONENTS} is the JSON object the te_<part>_kn columns "
                   f"are folded into; {fix}")


def no_column(field: str, column: str, columns: list[str]) -> Invalid:
    """The 422 for a column the study does not have: names ``field``, the closest column
    and every column (``te_components_kn``: :func:`folded_components`)."""
    if column == FOLDED_COMPONENTS:
        return folded_components(field, columns)
    close = difflib.get_close_matches(column, columns, n=1)
    hint = f" (did you mean '{close[0]}'?)" if close else ""
    return Invalid(f"{field}: this study has no column '{column}'{hint}; columns: "
                   f"{', '.join(columns)}")


def filter_columns(filters: list[str]) -> list[str]:
    """The columns ``column=value`` filters name (malformed ones are left to
    :func:`apply_filters`, which names them)."""
    return [item.partition("=")[0] for item in filters if "=" in item]


def column_list(text: str, columns: list[str], field: str = "columns") -> list[str]:
    """``a,b,c`` as a list of columns of the study, in the order given; :class:`Invalid`
    naming ``field`` for an empty name, a name given twice or a column the study lacks."""
    names = [n.strip() for n in text.split(",")]
    seen: set[str] = set()
    for name in names:
        if not name:
            raise Invalid(f"{field}: an empty name in '{text}'; give column names separated "
                          "by commas (a,b,c)")
        if name in seen:
            raise Invalid(f"{field}: '{name}' is named twice; give each column once")
        if name not in columns:
            raise no_column(field, name, columns)
        seen.add(name)
    return names


def sort_key(text: str, columns: list[str], field: str = "sort") -> tuple[str, bool]:
    """``column`` (ascending) or ``-column`` (descending) as ``(column, descending)``;
    :class:`Invalid` naming ``field`` for a column the study lacks, or for several keys
    (``te_kn,power_kw``: one column is taken)."""
    if "," in text:
        first = text.split(",")[0].strip().lstrip("-") or "te_kn"
        raise Invalid(f"{field}: one column ('{first}' or '-{first}'); several keys are not "
                      f"supported ('{text}'): sort in pandas")
    descending = text.startswith("-")
    column = text[1:] if descending else text
    if column not in columns:
        raise no_column(field, column, columns)
    return column, descending


def sort_rows(df: pd.DataFrame, column: str, descending: bool = False) -> pd.DataFrame:
    """Rows ordered by ``column``: numbers as numbers, text as text, missing values last in
    either direction, ties in their stored order (stable, so pages do not overlap)."""
    series = df[column]
    if pd.api.types.is_numeric_dtype(series) or pd.api.types.is_bool_dtype(series):
        order = series.reset_index(drop=True).sort_values(
            ascending=not descending, kind="mergesort", na_position="last").index
        return df.iloc[order.to_numpy()]
    # text, or a mixed axis stored as text (``load: [full, 0.5]``, ``takeup.mass_kg: [auto,
    # 500, 3000]`` as '500.0', '3000.0'): its numbers as numbers before its words (as text
    # '3000.0' came before '500.0'), the order reversed for descending, missing values last
    text = series.map(lambda v: None if v is None or v is pd.NA
                      or (isinstance(v, float) and math.isnan(v)) else str(v))
    text = text.reset_index(drop=True).astype(object)
    number = pd.to_numeric(text, errors="coerce")
    number = number.where(np.isfinite(number.astype(float)))
    keys = pd.DataFrame({"missing": text.isna(), "word": number.isna() & text.notna(),
                         "number": number, "text": text.where(number.isna())})
    up = not descending
    order = keys.sort_values(["missing", "word", "number", "text"],
                             ascending=[True, up, up, up], kind="mergesort",
                             na_position="last").index
    return df.iloc[order.to_numpy()]


def _text_matches(series: pd.Series, text: str) -> np.ndarray:
    """Rows of a text column equal to ``text``; in a mixed axis stored as text (``auto``,
    '3000.0') a number matches by value, so ``3000`` (as the study page's filter offers the
    grid's value) finds '3000.0'."""
    as_text = series.map(lambda v: None if v is None or v is pd.NA else str(v))
    exact = (as_text == text).fillna(False).to_numpy(bool)
    if text.lstrip().startswith(("[", "{")):
        # a list or mapping axis value, stored as JSON ('[0.5, 1.0]'): matched by what it
        # holds, so '[0.5,1]' finds it (numbers by value, as above)
        try:
            wanted = json.loads(text)
        except ValueError:
            return exact
        return exact | np.fromiter((_json_equal(_json_or_none(v), wanted) for v in as_text),
                                   bool, len(as_text))
    try:
        value = float(text)
    except ValueError:
        return exact
    if not math.isfinite(value):
        return exact
    numbers = pd.to_numeric(as_text, errors="coerce").to_numpy(float)
    close = np.isclose(numbers, value, rtol=1e-9, atol=1e-12) & np.isfinite(numbers)
    return exact | close


def _json_or_none(text: str | None) -> Any:
    """A stored JSON axis value, or None for a missing or non-JSON one."""
    if text is None:
        return None
    try:
        return json.loads(text)
    except ValueError:
        return None


def _json_equal(a: Any, b: Any) -> bool:
    """Two JSON values alike: numbers by value (relative 1e-9), lists item by item, mappings
    key by key, anything else equal."""
    num = (int, float)
    if isinstance(a, num) and isinstance(b, num) and not isinstance(a, bool) \
            and not isinstance(b, bool):
        return math.isclose(a, b, rel_tol=1e-9, abs_tol=1e-12)
    if isinstance(a, list) and isinstance(b, list):
        return len(a) == len(b) and all(_json_equal(x, y) for x, y in zip(a, b, strict=True))
    if isinstance(a, dict) and isinstance(b, dict):
        return a.keys() == b.keys() and all(_json_equal(a[k], b[k]) for k in a)
    return a is not None and type(a) is type(b) and a == b


def apply_filters(df: pd.DataFrame, filters: list[str]) -> pd.DataFrame:
    """Keep rows where every ``column=value`` holds (numbers compared as numbers; a value
    that no row of the column can have, like text for a number, keeps no row).
    A column the study does not have is :class:`Invalid` (422) naming ``filter`` and listing
    the columns."""
    for item in filters:
        column, sep, text = item.partition("=")
        if not sep or not column:
            raise Invalid(f"filter: '{item}' is not column=value")
        if not text.strip():
            raise Invalid(f"filter: '{item}' has an empty value; give column=value (a value "
                          "no row has keeps no row)")
        if column not in df.columns:
            raise no_column("filter", column, [str(c) for c in df.columns])
        if column == "friction_model":  # its aliases too; an unknown name keeps no row
            text = canonical_name(text)
        try:
            value = _coerce(df[column], text)
        except _NoMatch:
            df = df.iloc[0:0]
            continue
        if isinstance(value, float):
            df = df[np.isclose(df[column].astype(float), value, rtol=1e-9, atol=1e-12)]
        elif isinstance(value, str):
            df = df[_text_matches(df[column], value)]
        else:  # a yes/no value: a null equals neither
            df = df[df[column] == value]
    return df


def to_csv(df: pd.DataFrame) -> str:
    return df.to_csv(index=False)


def to_parquet(df: pd.DataFrame, schema: pa.Schema | None = None) -> bytes:
    """``df`` as Parquet; ``schema``: the stored table's, so each column keeps its stored
    type (a yes/no column with no value in any row stays boolean, not Arrow's null type)."""
    table = pa.Table.from_pandas(df, preserve_index=False)
    if schema is not None:
        fields = [schema.field(n) if n in schema.names else table.schema.field(n)
                  for n in table.column_names]
        table = pa.Table.from_pandas(df, schema=pa.schema(fields), preserve_index=False)
    buf = io.BytesIO()
    pq.write_table(table, buf)
    return buf.getvalue()


#: Relative size below which a metric's value counts as zero in :func:`compare`: float64
#: round-off of sums of terms of the metric's own size (about 1e-16 each) stays far below it.
ZERO_REL = 1e-9


def _stats(values: pd.Series) -> dict:
    v = values.dropna()
    if not len(v):
        return {"n": 0, "mean": None, "min": None, "max": None}
    return {
        "n": int(len(v)),
        "mean": _clean(float(v.mean())),
        "min": _clean(float(v.min())),
        "max": _clean(float(v.max())),
    }


#: Valid metrics named in the refusal of an unknown one; the rest are counted.
SHOWN_METRICS = 20


#: The models a comparison pairs when none are named (``GET /studies/{id}/compare``,
#: ``beltstudy compare``): CEMA against the paper's Non-Lin.
PAIR_DEFAULTS = {"baseline": "cema", "candidate": "nonlin"}


def model_pair(baseline: str, candidate: str) -> tuple[str, str]:
    """The baseline and candidate friction models by their canonical names; the same model
    twice (or by an alias) is :class:`Invalid` naming ``candidate``: a ratio needs two."""
    baseline = model_name(baseline, "baseline")
    candidate = model_name(candidate, "candidate")
    if baseline == candidate:
        raise Invalid(f"candidate: '{candidate}' is the baseline too; compare two different "
                      "models")
    return baseline, candidate


def _shown_metrics(valid: list[str]) -> str:
    """The first :data:`SHOWN_METRICS` of ``valid`` (a study's number columns run to
    hundreds, 6 200 characters), and how many more."""
    return ", ".join(valid[:SHOWN_METRICS]) + (
        f", and {len(valid) - SHOWN_METRICS} more (the study's number columns)"
        if len(valid) > SHOWN_METRICS else "")


def _check_metrics(runs: pd.DataFrame, axes: list[str], metrics: list[str]) -> list[str]:
    """The study's number columns that are no axis (the valid metrics); :class:`Invalid`
    naming ``metrics`` for a name given twice, an axis, a column that is no number and a name
    the study lacks (the folded ``te_components_kn`` said as ``columns=`` says it)."""
    valid = [c for c in runs.columns if pd.api.types.is_float_dtype(runs[c]) and c not in axes]
    for i, m in enumerate(metrics):
        if m in metrics[:i]:
            raise Invalid(f"metrics: '{m}' is listed twice; give each metric once")
        if m in axes:
            raise Invalid(
                f"metrics: '{m}' is an axis of this study, not a result; valid: "
                + ", ".join(valid)
            )
        if m in runs.columns and m not in valid:
            raise Invalid(
                f"metrics: '{m}' is not a number in this study's rows (a ratio needs one); "
                "valid: " + ", ".join(valid)
            )
        if m == FOLDED_COMPONENTS and m not in valid:
            raise folded_components("metrics", valid)
        if m not in valid:
            close = difflib.get_close_matches(m, valid, n=1)
            hint = f" (did you mean '{close[0]}'?)" if close else ""
            raise Invalid(f"metrics: unknown metric '{m}'{hint}; valid: {_shown_metrics(valid)}")
    return valid


def _metrics_with_values(runs: pd.DataFrame, metrics: list[str], defaulted: bool,
                         valid: list[str], settled: bool = True) -> list[str]:
    """The metrics to compare: the defaults keep those some run of the study has a value of
    (a steady-only study has no stop-phase figures: power alone, not two columns of nulls);
    a metric asked by name that no run of the study has a value of (a transient figure of a
    steady study, another model's part) is :class:`Invalid` naming it and those that have
    values. A study whose rows so far are all of failed runs (which write few figures)
    refuses nothing yet."""
    if not len(runs) or not settled:  # a running study's later runs may have it
        return metrics
    if defaulted:
        return [m for m in metrics if runs[m].notna().any()] or metrics[:1]
    if "status" in runs.columns and not (runs["status"] != "failed").any():
        return metrics
    for m in metrics:
        if not runs[m].notna().any():
            having = [c for c in valid if runs[c].notna().any()]
            raise Invalid(f"metrics: '{m}' has no values in this study: none of its runs has "
                          "one (a figure of another friction model, of transient runs in a "
                          "study with dynamics: false, or one no run reached, as stop_time_s "
                          "where no run stopped); metrics with values: "
                          + _shown_metrics(having))
    return metrics


def _named_pair(baseline: str | None, candidate: str | None, models: list[str]
                ) -> tuple[str, str]:
    """The pair compared (:func:`model_pair`), a model left out (None) being its default of
    :data:`PAIR_DEFAULTS`; one the study does not run is :class:`Invalid` naming the
    parameter, and "(the default)" only when it was left out."""
    given = {"baseline": baseline, "candidate": candidate}
    pair = model_pair(baseline or PAIR_DEFAULTS["baseline"],
                      candidate or PAIR_DEFAULTS["candidate"])
    for label, name in zip(("baseline", "candidate"), pair, strict=True):
        if models and name not in models:
            default = " (the default)" if given[label] is None else ""
            raise Invalid(
                f"{label}: model '{name}'{default} is not in this study; it has: "
                f"{', '.join(models)}: give {label}=NAME from those"
            )
    return pair


def compare(
    runs: pd.DataFrame,
    axes: list[str],
    baseline: str | None,
    candidate: str | None,
    metrics: list[str],
    study_id: str = "",
    models: list[str] | None = None,
    settled: bool = True,
) -> dict:
    """Pairs of runs that differ only in the friction model, with candidate / baseline ratios.

    Returns ``{"study_id", "baseline", "candidate", "metrics", "pairs": [...],
    "failed_pairs", "summary": {metric: {"overall": stats, "by_axis": {axis: {value:
    stats}}}}, "same_in_all_pairs": {axis: value}, "ratio"}``; stats are n, mean, min and max
    of the ratio. A ratio is a magnitude, ``|candidate| / |baseline|``; ``<metric>_sign`` says
    ``opposite`` where the two values have opposite signs (``overall.opposite_sign`` counts
    them) and ``zero`` where either is zero (within :data:`ZERO_REL` of the metric's largest
    magnitude in the pairs, so round-off of a zero gives no ratio); where either value is
    missing (a column one of the two models does not write) ratio and sign are null. Only the axes whose values differ between the pairs are listed per pair and per
    axis; the others are in ``same_in_all_pairs``. A pair with a failed run has no ratio
    (``failed_pairs`` counts them). ``baseline`` / ``candidate``: None for one left out (its
    default, :data:`PAIR_DEFAULTS`). ``models``: the study's friction models (a model
    not among them is :class:`Invalid` naming the parameter); default: those in ``runs``.
    A metric asked by name that no run has a value of is :class:`Invalid`
    (:func:`_metrics_with_values`) once the study is ``settled`` (not queued or running: a
    running study's later runs may have one).
    """
    defaulted = not metrics or list(metrics) == list(DEFAULT_METRICS)
    metrics = list(metrics) or list(DEFAULT_METRICS)
    valid = _check_metrics(runs, axes, metrics)
    metrics = _metrics_with_values(runs, metrics, defaulted, valid, settled)
    if models is None:
        models = sorted(set(runs["friction_model"].dropna())) if len(runs) else []
    baseline, candidate = _named_pair(baseline, candidate, models)
    others = [a for a in axes if a != "friction_model"]
    keep = ["run_id", "status", *metrics]
    base = runs[runs["friction_model"] == baseline][others + keep]
    cand = runs[runs["friction_model"] == candidate][others + keep]
    if others:
        # an axis one model's runs do not read (another model's parameter: null there, which
        # stands for any value) pairs each of its runs with the other model's at every value
        keys = [a for a in others if base[a].notna().any() and cand[a].notna().any()]
        merged = base.merge(cand, how="inner" if keys else "cross", on=keys or None,
                            suffixes=("_baseline", "_candidate"))
        for a in others:
            if a not in keys:
                merged[a] = merged.pop(f"{a}_baseline").combine_first(
                    merged.pop(f"{a}_candidate"))
    else:
        # one run per model: the pair is those two rows (their labels in ``runs`` differ)
        merged = base.reset_index(drop=True).add_suffix("_baseline").join(
            cand.reset_index(drop=True).add_suffix("_candidate"), how="inner")
    if others and len(merged):
        merged = merged.sort_values(others, kind="stable").reset_index(drop=True)
    # only the parameters that differ between the pairs: an axis the two models' runs do not
    # read (another model's parameter) or that has one value among them is no difference
    same = {a: _clean(merged[a].iloc[0]) for a in others
            if len(merged) and merged[a].nunique(dropna=False) <= 1}
    merged = merged.drop(columns=list(same))
    others = [a for a in others if a not in same]
    pairs = []
    summary: dict[str, dict] = {}
    usable = (merged["status_baseline"] != "failed") & (merged["status_candidate"] != "failed")
    for m in metrics:
        b = merged[f"{m}_baseline"].astype(float)
        c = merged[f"{m}_candidate"].astype(float)
        # a value within ZERO_REL of the metric's largest magnitude in the pairs is a zero
        # written with round-off (a baseline of -4e-14 kN gave a ratio of 1e14 and swamped
        # the mean): no ratio over it, and no sign
        scale = np.nanmax(np.abs(np.concatenate([b[usable], c[usable]])), initial=0.0)
        # a missing value (a column one model does not write, such as Non-Lin's
        # te_idler_rotation_kn under CEMA) stays missing: no ratio and no sign, never a zero
        b = b.mask(np.abs(b) <= ZERO_REL * scale, 0.0)
        c = c.mask(np.abs(c) <= ZERO_REL * scale, 0.0)
        known = usable & b.notna() & c.notna()
        with np.errstate(divide="ignore", invalid="ignore"):
            # a magnitude: |candidate| / |baseline|; where the two have opposite signs (a
            # drive that regenerates under one model and drives under the other, a tension
            # below zero) the sign column says so instead of a negative ratio
            merged[f"{m}_ratio"] = np.where(known & (b != 0), np.abs(c) / np.abs(b), np.nan)
            opposite = known & (np.sign(b) * np.sign(c) < 0)
            zero = known & ((b == 0) | (c == 0))
        merged[f"{m}_sign"] = np.where(opposite, "opposite", np.where(
            zero, "zero", np.where(known, "same", None)))
        summary[m] = {
            "overall": {**_stats(merged[f"{m}_ratio"]), "opposite_sign": int(opposite.sum())},
            "by_axis": {
                a: {
                    str(_clean(value)): _stats(group[f"{m}_ratio"])
                    for value, group in merged.groupby(a, sort=True)
                }
                for a in others
            },
        }
    for rec in merged.to_dict(orient="records"):
        pairs.append({k: _clean(v) for k, v in rec.items()})
    return {
        "study_id": study_id,
        "baseline": baseline,
        "candidate": candidate,
        "metrics": metrics,
        "pairs": pairs,
        "failed_pairs": int((~usable).sum()),
        "summary": summary,
        "same_in_all_pairs": same,
        "ratio": "magnitude |candidate| / |baseline|; <metric>_sign is 'opposite' where the "
                 "two values have opposite signs and 'zero' (no ratio over a zero baseline) "
                 "where either is zero; ratio and sign are null where either is missing",
    }


def accuracy_columns(runs: pd.DataFrame, accuracy: pd.DataFrame) -> pd.DataFrame:
    """The error of each result column over a study's accuracy sample: one row per column
    with a bar (``column``, ``unit``, ``runs`` sampled, the median ``value`` of the column on
    those runs, the median and largest ``err``, and the largest ``err`` over its value
    ``err_rel_max_pct`` [%]), in the order of the results."""
    from beltstudy.engine import results as R

    out = []
    if not len(accuracy):
        return pd.DataFrame(columns=["column", "unit", "runs", "value_median", "err_median",
                                     "err_max", "err_rel_max_pct"])
    values = runs.set_index("run_id") if len(runs) else None
    for col in accuracy.columns:
        if not col.endswith("_err"):
            continue
        errs = accuracy[["run_id", col]].dropna()
        if not len(errs):
            continue
        name = col[:-4]
        if values is not None and name in values.columns:
            vals = values[name].reindex(errs["run_id"]).to_numpy(dtype=float)
        else:
            vals = np.full(len(errs), np.nan)
        err = errs[col].to_numpy(dtype=float)
        with np.errstate(divide="ignore", invalid="ignore"):
            rel = np.where(np.abs(vals) > 0, 100.0 * err / np.abs(vals), np.nan)
        out.append({
            "column": name,
            "unit": R.field(col).unit,
            "runs": int(len(errs)),
            "value_median": float(np.nanmedian(vals)) if np.isfinite(vals).any() else None,
            "err_median": float(np.median(err)),
            "err_max": float(np.max(err)),
            "err_rel_max_pct": float(np.nanmax(rel)) if np.isfinite(rel).any() else None,
        })
    return pd.DataFrame(out, columns=["column", "unit", "runs", "value_median", "err_median",
                                      "err_max", "err_rel_max_pct"])
