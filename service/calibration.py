"""Calibration at the service's door (SPEC 7.3): the request checked, the engine's fit run.

Both ``beltstudy calibrate`` and ``POST /calibrations`` come here: a conveyor (a file or an
inline mapping), the measured rows, the model and the names to fit (``NAME`` or
``NAME=START``), optional fixed parameters. The fit itself is
:func:`beltstudy.engine.calibrate` (:mod:`beltstudy.engine.calibration`) (method, standard errors, identifiability: its module
notes); an input problem is an :class:`~beltstudy.service.errors.Invalid` naming the field.
"""

from __future__ import annotations

import re
from pathlib import Path
from typing import Any

from pydantic import BaseModel, ConfigDict, Field, ValidationError

from beltstudy.engine import (
    TEMPERATURE_MAX_C,
    TEMPERATURE_MIN_C,
    Conveyor,
    InputError,
    calibrate,
    catalog,
    get_model,
    measurements_from_rows,
    parse_conveyor,
)
from beltstudy.engine.calibration import time_column_hint
from beltstudy.engine.conveyor import strict_validate
from beltstudy.service.door.messages import describe, with_type_fixes
from beltstudy.service.door.study import ConveyorRef, ModelName
from beltstudy.service.door.studyfile import conveyor_from_path
from beltstudy.service.errors import Invalid, TooLarge, shown_path

__all__ = ["CalibrationIn", "read_calibration", "run_calibration", "check_params", "split_fit", "MAX_ROWS",
           "MAX_FIT", "NO_ROWS", "ROWS_FIX", "too_many_rows", "with_row_fixes"]

#: Measurements and fitted names a request may hold (the fit runs in the request: each
#: measurement is a steady solve per evaluation, about 5 ms on a 2 km conveyor).
MAX_ROWS = 200
MAX_FIT = 12

#: A calibration without measured rows, said alike by the command line (a CSV with a header
#: only) and ``POST /calibrations`` (``"measured": []``), with its fix.
ROWS_FIX = ("give one row per measured steady state (load, temperature_c, and power_kw or "
            "te_kn)")
NO_ROWS = f"no measured rows; {ROWS_FIX}"
#: What a row's required column is, said after ``required field is missing`` (Pydantic's
#: words named the field but not what to give).
_REQUIRED = {"load": "give the load case of the measurement (full, empty or a fraction of "
                     "the design load)",
             "temperature_c": "give the ambient temperature of the measurement [C]"}
_MISSING = re.compile(r"\b(measured\.\d+\.(" + "|".join(_REQUIRED) + r")): required field is "
                      r"missing(?=;|$)")


def too_many_rows(count: int | None = None) -> str:
    """More measured rows than a calibration takes (``count`` of them, where known), with the
    fix: one wording for the command line and ``POST /calibrations`` (HTTP 413, as the README's
    limits)."""
    counted = f" ({count})" if count is not None else ""
    return (f"more than {MAX_ROWS} measured rows{counted}; a calibration takes at most "
            f"{MAX_ROWS} (each costs a steady solve per step of the fit): give fewer steady "
            "states, or averages of repeated readings at the same load and temperature")


def with_row_fixes(message: str) -> str:
    """``message`` with what to give after each measured row's missing required column
    (``measured.1.temperature_c: required field is missing: give the ambient temperature of
    the measurement [C]``), the words the engine's own check of the rows uses."""
    return _MISSING.sub(lambda m: f"{m[1]}: required field is missing: {_REQUIRED[m[2]]}",
                        message)


class MeasuredRow(BaseModel):
    """One measured steady state (a row of the CSV)."""

    model_config = ConfigDict(extra="forbid", allow_inf_nan=False)

    load: str | float | list[float] = Field(..., description="load case as in a scenario")
    temperature_c: float = Field(..., ge=TEMPERATURE_MIN_C, le=TEMPERATURE_MAX_C,
                                 description="ambient temperature [C]")
    power_kw: float | None = Field(None, description="measured power at the drive pulleys [kW] "
                                   "(negative where the drives regenerate; not 0)")
    te_kn: float | None = Field(None, description="measured peripheral force [kN] (negative "
                                "where the drives regenerate; not 0)")
    t_tight_kn: float | None = Field(None, gt=0, description="measured tight-side tension [kN]")
    speed_m_s: float | None = Field(None, gt=0, description="belt speed [m/s] (default: the "
                                    "conveyor's)")


class CalibrationIn(BaseModel):
    """The body of ``POST /calibrations``."""

    model_config = ConfigDict(extra="forbid", allow_inf_nan=False)

    conveyor: ConveyorRef = Field(
        ..., description="a conveyor file under the studies directory, or inline")
    measured: list[MeasuredRow] = Field(
        ..., min_length=1, max_length=MAX_ROWS, description="one row per measured steady "
        "state (at most 200: each costs a steady solve per step of the fit): load, "
        "temperature_c, power_kw or te_kn (optional speed_m_s, t_tight_kn)")
    model: ModelName = Field(..., description="friction model to calibrate (din, cema, nonlin, ...)")
    fit: list[str] = Field(..., min_length=1, max_length=MAX_FIT, description="parameters "
                           "to fit: NAME or "
                           "NAME=START (e.g. f_carry, mu_b=0.002)")
    params: dict[str, float] = Field(default_factory=dict,
                                     description="other parameters held at these values")


def read_calibration(data: Any) -> CalibrationIn:
    """A parsed request body (JSON or YAML) as a :class:`CalibrationIn`; :class:`Invalid`
    naming each problem's field as the study door says it (an unknown key with the nearest
    valid one, an inline conveyor's fields as the engine names them)."""
    if not isinstance(data, dict):
        raise Invalid("body: expected a mapping with conveyor, measured, model, fit")
    measured = data.get("measured")
    if isinstance(measured, list):  # the command line's words, not Pydantic's list lengths
        if len(measured) > MAX_ROWS:
            raise TooLarge(f"measured: {too_many_rows(len(measured))}")
        if not measured:
            raise Invalid(f"measured: {NO_ROWS}")
    _refuse_time_keys(measured)
    try:  # JSON's types exactly, as a study's (``"4.5"`` is no number, ``"yes"`` no boolean)
        return strict_validate(CalibrationIn, data)
    except ValidationError as exc:
        raise Invalid(with_row_fixes(describe(exc, data, model=CalibrationIn,
                                              json_types=True))) from None
    except InputError as exc:
        raise Invalid(f"body: {exc}") from None


def _refuse_time_keys(measured: Any) -> None:
    """A measured row with a time or date key (``time_s``) is refused saying calibration takes
    steady states, one row each, not a time series (the schema's own refusal named the nearest
    field, ``te_kn``)."""
    if not isinstance(measured, list):
        return
    for i, row in enumerate(measured):
        if not isinstance(row, dict):
            continue
        for key in row:
            if key not in MeasuredRow.model_fields and time_column_hint(str(key)):
                raise Invalid(f"measured.{i}.{key}: unknown key '{key}'; "
                              f"{time_column_hint(str(key))}")


def split_fit(items: list[str]) -> tuple[list[str], dict[str, float]]:
    """``NAME`` / ``NAME=START`` items into the names and the start values."""
    names, starts = [], {}
    for item in items:
        name, eq, value = str(item).partition("=")
        name = name.strip()
        names.append(name)
        if eq:
            try:
                starts[name] = float(value)
            except ValueError:
                raise Invalid(f"fit: '{item}': expected NAME or NAME=START with a number") \
                    from None
    return names, starts


def check_params(body: CalibrationIn, field: str = "params.") -> None:
    """The held parameters as the model takes them; a problem names the request's own field
    (``params.f_return``; the CLI passes ``--param `` for its option), not the study's
    ``models.<model>.`` path the engine's check names."""
    try:
        fm = get_model(body.model)
    except InputError as exc:  # the request's field is model, not a study's friction_model
        raise Invalid(f"model: {exc.reason}") from None
    try:
        fm.params(body.params)
    except InputError as exc:
        message = str(exc)
        engine_field = f"models.{fm.name}."
        if message.startswith(engine_field):
            message = field + message[len(engine_field):]
        raise Invalid(message) from None


def run_calibration(body: CalibrationIn, *, base_dir: Path | None = None,
                    studies_dir: Path | None = None, params_field: str = "params.") -> dict:
    """Fit the request; the answer as SPEC 7.3 states it (``fit.<name>.value``, ``.se``,
    ``residuals``, ``not_identifiable``, ``models``). A held parameter's problem names
    ``params_field`` + its name."""
    names, starts = split_fit(body.fit)
    check_params(body, params_field)
    try:
        if isinstance(body.conveyor, Conveyor):
            conv = body.conveyor
            catalog.check_conveyor(conv, "conveyor.")
        else:
            data, _ = conveyor_from_path(body.conveyor, base_dir, studies_dir)
            where = f"conveyor: {shown_path(body.conveyor)}: "
            try:
                conv = parse_conveyor(data, prefix=where)
            except InputError as exc:  # a wrong type with its fix (with_type_fixes)
                raise InputError(with_type_fixes(str(exc), data, Conveyor, where)) from None
        rows = measurements_from_rows([r.model_dump(exclude_none=True) for r in body.measured])
        result = calibrate(conv, rows, body.model, names, fixed=body.params, starts=starts)
    except InputError as exc:
        raise Invalid(str(exc)) from None
    return {"conveyor": conv.name, **result.to_json()}
