"""Calibration: a friction model's parameters fitted to measured steady power (SPEC 7.3).

Each measurement is one steady running state of the plant: its load (a load case as in a
scenario), ambient temperature, optionally its belt speed, and the measured drive power
``power_kw`` or peripheral force ``te_kn`` (optionally the tight-side tension
``t_tight_kn``). :func:`calibrate` solves the steady state of every measurement
(:func:`beltstudy.engine.statics.solve_steady`) and fits the named parameters by least
squares (``scipy.optimize.least_squares``, trust-region reflective, parameters >= 0).

Notes
-----
Residuals are relative, r_i = (y_model,i - y_meas,i) / |y_meas,i|: weighted least squares
with a measurement error proportional to the reading (a meter's accuracy is a share of its
reading), which also lets power and tension rows share one fit. A row that gives both
``power_kw`` and ``te_kn`` gives one reading of its state, not two: P = Te v at the drive
pulleys, and a plant's Te is most often its power over the speed, so their errors are one
error; the fit takes the mean of the two relative residuals as the row's one residual
(:func:`_observations`). Counted as two, a row read both ways halved s^2 / n and gave standard
errors sqrt 2 too small (95 % intervals covering 81 % of fits); for two independent meters the
mean is conservative (its error is 1 / sqrt 2 of one meter's). With J the Jacobian of the
readings' residuals r at the solution (central differences), n readings and p fitted
parameters, the standard errors are the square roots of the diagonal of

    Cov = s^2 (J^T J)^-1,   s^2 = SSR / (n - p)

(the linearised covariance of a nonlinear least-squares estimate; Seber & Wild 2003, section
2.1). A name ends at its lower bound when the data would take it below (:func:`_at_bound`:
the Gauss-Newton step from the fit leaves the bound's side), whatever its start.
Identifiability: the columns of J (relative sensitivities d r / d ln x, each scaled to unit
length) must be independent. Their singular values decide it: a named parameter whose
column adds a singular value below ``RCOND`` times the largest to those named before it cannot
be told apart from them by these data (the parameters only act together, e.g. as a product
as ``mu_b`` and ``bearing_diameter_m`` in Non-Lin's bearing term, or it does not act at all).
It is not fitted: it is held at its start value and named in ``not_identifiable`` together
with the parameters it only acts with (the null vector of the Jacobian).

References
----------
Seber, G.A.F., Wild, C.J.: Nonlinear Regression. Wiley 2003, sections 2.1, 3.4.
Bates, D.M., Watts, D.G.: Nonlinear Regression Analysis and Its Applications. Wiley 1988.
Nocedal, J., Wright, S.J.: Numerical Optimization, 2nd ed. Springer 2006, section 12.3.
"""

from __future__ import annotations

import dataclasses
import difflib
import math
import re
from collections.abc import Sequence
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from beltstudy.engine.conveyor import LOAD_MAX, Conveyor, parse_conveyor, section_loads
from beltstudy.engine.errors import InputError
from beltstudy.engine.friction import get_model
from beltstudy.engine.statics import solve_steady
from beltstudy.engine.wording import gnum

__all__ = ["Measurement", "Calibration", "calibrate", "measurements_from_rows", "RCOND",
           "MEASURED", "time_column_hint"]

#: Relative singular value below which a Jacobian column is taken as dependent on the others
#: (columns scaled to unit length; 1e-4: the fitted pair's estimates would correlate beyond
#: 1 - 5e-9, far beyond anything 1 % data can resolve).
RCOND = 1e-4
#: Why a fitted name whose Jacobian column is zero is held: it moves no modelled value (Non-Lin's
#: drag_per_roll_n where the conveyor file gives the idlers' seal_drag_n; material flexure on
#: rows all at load empty), so no other name stands in for it.
_INERT = ("none of the modelled values of these rows: the model does not read it here (a field "
          "of the conveyor file may set what it stands for) or it acts only in states these "
          "rows do not have (another load, speed or temperature)")
#: Relative step of the central differences of the Jacobian.
DIFF_STEP = 1e-4
#: Measured column -> the steady summary field the model gives for it.
MEASURED = {"power_kw": "power_kw", "te_kn": "te_kn", "t_tight_kn": "t1_kn"}
#: Names that set several parameters of a model to one value: DIN 22101's single
#: fictitious friction factor f for both strands (the table's f; f_carry and f_return split it).
TIED = {"din": {"f": ("f_carry", "f_return")}}
#: Start values of parameters whose default is computed (None), read from the law's info.
_INFO_START = {"c": "c_factor", "ky": "ky_mean", "kt": "kt", "kta": "kta"}


@dataclass(frozen=True)
class Measurement:
    """One measured steady state: load case, ambient [C], speed [m/s] (None: the file's) and
    the measured values by column (``power_kw`` [kW], ``te_kn`` [kN], ``t_tight_kn`` [kN])."""

    load: float | str | list[float]
    temperature_c: float
    values: dict[str, float]
    speed_m_s: float | None = None
    #: the steady state the model computes for the row (:func:`_with_states`): the load per
    #: section, the temperature where the model reads one (None where it has no temperature
    #: term) and the speed; None: not resolved (the row as written is its state)
    state: tuple | None = None


@dataclass
class Calibration:
    """The fit: values and standard errors of the fitted parameters, residuals, the names the
    data cannot identify, and the ``models:`` block for a study."""

    model: str
    fit: dict[str, dict[str, float | None]]
    residuals: list[dict[str, Any]]
    not_identifiable: list[str]
    held: dict[str, float]
    models: dict[str, dict[str, float]]
    rms_relative: float
    dof: int
    singular_values: list[float]
    status: str
    message: str
    notes: list[str] = field(default_factory=list)

    def to_json(self) -> dict:
        return dataclasses.asdict(self)


def _number(value: Any, what: str) -> float | None:
    if value is None or (isinstance(value, str) and not value.strip()):
        return None
    try:
        out = float(value)
    except (TypeError, ValueError):
        raise InputError(f"expected a number, got {value!r}", field=what) from None
    if isinstance(value, float) and math.isnan(value):
        return None
    if not math.isfinite(out):
        raise InputError(f"expected a finite number, got {value!r}", field=what)
    return out


def _load(value: Any, what: str) -> float | str | list[float]:
    if isinstance(value, str):
        text = value.strip()
        if text in ("full", "empty", "inclines", "declines"):
            return text
        try:
            values = [float(v) for v in text.split(",")]
        except ValueError:
            raise InputError(f"a load case: full, empty, inclines, declines, a fraction or "
                             f"one fraction per carry section; got {value!r}", field=what) from None
        if (re.fullmatch(r"[+-]?\d+,\d+", text)
                and not all(0.0 <= v <= LOAD_MAX for v in values)):
            # '0,7' is a list of one fraction per section, [0, 7], or 0.7 with a decimal comma:
            # read as the list, 7 was told 'a fraction, not a per cent (0.07)', a tenth of it
            raise InputError(
                f"{value!r} is one fraction per carry section ({', '.join(f'{v:g}' for v in values)}"
                f"), {next(v for v in values if not 0.0 <= v <= LOAD_MAX):g} outside "
                f"0..{LOAD_MAX:g}; if it is "
                f"{text.replace(',', '.')} written with a decimal comma, write "
                f"{text.replace(',', '.')}", field=what)
        return values[0] if len(values) == 1 else values
    if value is None:
        raise InputError("missing: give the load case of the measurement", field=what)
    if isinstance(value, list | tuple):  # one fraction per carry section, as in a scenario
        if not value:
            raise InputError("an empty list: give one load fraction per carry section, tail "
                             "to head, or one load case (full, empty, a fraction)", field=what)
        values = [_number(v, f"{what}.{k}") for k, v in enumerate(value)]
        if any(v is None for v in values):
            k = values.index(None)
            raise InputError("missing: give one load fraction per carry section, tail to head",
                             field=f"{what}.{k}")
        return values
    return _number(value, what)


#: Column names of a logged time series (a time or date column): calibration takes steady
#: states, one row each, not the log they were read from (:func:`time_column_hint`).
_TIME_COLUMN = re.compile(r"(t|time|timestamp|date|datetime|date_?time|clock|elapsed|hour|"
                          r"minute|second)(_(s|ms|min|h|hr|utc|local))?", re.IGNORECASE)


def time_column_hint(name: str) -> str:
    """What to do with a column ``name`` that holds a time or date (``time_s``, ``timestamp``):
    calibration fits steady states, one row each, not a time series; ``""`` for another
    name."""
    if not _TIME_COLUMN.fullmatch(name.strip()):
        return ""
    return (f"calibration takes steady states, one row each, not a time series: give each "
            f"steady stretch of the log as one row (its mean load, temperature and power) "
            f"and drop '{name}'")


def measurements_from_rows(rows: Sequence[dict[str, Any]]) -> list[Measurement]:
    """Measurements from table rows (CSV columns ``load``, ``temperature_c``, ``power_kw`` or
    ``te_kn``, optional ``speed_m_s`` and ``t_tight_kn``); a bad cell is named by its row
    (``measured.2.power_kw``, rows from 0)."""
    if not rows:
        raise InputError("no measurements: give one row per measured steady state",
                         field="measured")
    out = []
    known = {"load", "temperature_c", "speed_m_s", *MEASURED}
    for i, row in enumerate(rows):
        where = f"measured.{i}"
        unknown = [k for k in row if k not in known]
        if unknown:
            timed = time_column_hint(str(unknown[0]))
            if timed:
                raise InputError(f"unknown column '{unknown[0]}': {timed}", field=where)
            close = difflib.get_close_matches(unknown[0], sorted(known), n=1)
            hint = f" (did you mean '{close[0]}'?)" if close else ""
            raise InputError(f"unknown column '{unknown[0]}'{hint}; columns: "
                             f"{', '.join(sorted(known))}", field=where)
        temp = _number(row.get("temperature_c"), f"{where}.temperature_c")
        if temp is None:
            raise InputError("missing: give the ambient temperature of the measurement [C]",
                             field=f"{where}.temperature_c")
        values = {}
        for col in MEASURED:
            val = _number(row.get(col), f"{where}.{col}")
            if val is not None:
                # power and Te are negative where the drives regenerate (the runs' own sign);
                # a tension is positive; none is 0 (residuals are relative to it)
                if val == 0 or (col == "t_tight_kn" and val < 0):
                    raise InputError(_zero_reading(col, val), field=f"{where}.{col}")
                values[col] = val
        if "power_kw" not in values and "te_kn" not in values:
            raise InputError("give the measured power_kw or te_kn", field=where)
        speed = _number(row.get("speed_m_s"), f"{where}.speed_m_s")
        out.append(Measurement(_load(row.get("load"), f"{where}.load"), temp, values, speed))
    return out


def _zero_reading(col: str, val: float) -> str:
    """Why a measured ``col`` of ``val`` (0, or a negative tension) is refused, and the fix."""
    if col == "t_tight_kn":
        return (f"a measured t_tight_kn must be > 0 [kN] (got {val:g}): a belt's tight-side "
                "tension pulls; give the tension at the main drive in kN, or leave the cell "
                "empty")
    what, unit = (("power at the drive pulleys", "kW") if col == "power_kw"
                  else ("peripheral force at the drive pulleys", "kN"))
    return (f"a measured {col} must not be 0 (got {val:g}): each residual is relative to its "
            f"reading, and 0 gives it no scale; give the steady state's {what} [{unit}] "
            "(positive where the drives motor, negative where they regenerate, not 0), or leave "
            f"out a row read at balance (near 0 {unit})")


#: Largest measured speed over the design speed [-]: drives run up to their overspeed trip,
#: 1.1 x (plant overspeed switches, docs/dynamics.md); 1.5 x is beyond any plant and catches
#: a speed in ft/s (3.28 x) or km/h (3.6 x).
SPEED_OVER_DESIGN = 1.5


def _check_rows(conv: Conveyor, rows: Sequence[Measurement]) -> list[str]:
    """Each row's speed and load fit the conveyor (a speed within its bounds, one load
    fraction per carry section, the flow they make within what the belt's cross-section
    holds), named by its row: ``measured.2.speed_m_s: ...``. Returns a note for each row whose
    flow overfills the cross-section (:func:`_row_fill`) but not past what any belt carries."""
    notes = []
    for i, m in enumerate(rows):
        at = conv
        if m.speed_m_s is not None and m.speed_m_s != conv.speed_m_s:
            at = _at_speed(conv, m.speed_m_s, f"measured.{i}.")
        if m.speed_m_s is not None and m.speed_m_s > SPEED_OVER_DESIGN * conv.speed_m_s:
            raise InputError(
                f"{m.speed_m_s:g} m/s is {gnum(m.speed_m_s / conv.speed_m_s, 3)} x the conveyor's "
                f"design speed {conv.speed_m_s:g} m/s, beyond the {SPEED_OVER_DESIGN:g} x no plant "
                "runs a belt at: give the speed in m/s (1 ft/s = 0.3048 "
                "m/s, 1 km/h = 1/3.6 m/s), or the conveyor's own speed_m_s",
                field=f"measured.{i}.speed_m_s")
        try:
            loads = section_loads(m.load, conv)
        except InputError as exc:
            raise InputError(exc.reason, field=f"measured.{i}.load") from None
        notes += _row_fill(at, m, i, max(loads))
        _check_magnitudes(conv, m, i)
    return notes


def _at_speed(conv: Conveyor, speed_m_s: float, prefix: str) -> Conveyor:
    """The conveyor at a measured speed, validated as a file's but for the fill of its design
    capacity at that speed: a plant slows a belt when it carries less (a speed-controlled
    drive at a light load), so the fill at that speed is the row's load's
    (:func:`_row_fill`), not the design capacity's (the file's fill passed at its speed)."""
    from pydantic import ValidationError

    from beltstudy.engine import catalog
    from beltstudy.engine.capacity import check_fill
    from beltstudy.engine.conveyor import WHOLE_CHECKS, format_validation_error, strict_validate

    data = {**conv.model_dump(mode="json", by_alias=True), "speed_m_s": speed_m_s}
    try:
        out = strict_validate(Conveyor, data)
    except ValidationError as exc:
        raise InputError(format_validation_error(exc, Conveyor, prefix)) from None
    catalog.check_conveyor(out, prefix)
    for check in WHOLE_CHECKS:
        if check is not check_fill:
            check(out, prefix)
    return out


def _row_fill(at: Conveyor, m: Measurement, i: int, load: float) -> list[str]:
    """The fill of the belt's cross-section by a row's flow (its largest section load x the
    design capacity, at its speed; ISO 5048 geometry): past what any belt carries
    (:data:`~beltstudy.engine.conveyor.FILL_MAX_PCT`) it is refused naming the row, past 100 %
    it is a note (the material spills: the belt did not carry that load at that speed)."""
    from beltstudy.engine.capacity import fill_pct
    from beltstudy.engine.conveyor import FILL_MAX_PCT

    if at.belt.type == "auto" or at.material.capacity_t_h <= 0.0 or load <= 0.0:
        return []
    fill = load * fill_pct(at)
    where = f"load {m.load if isinstance(m.load, str) else _load_text(m.load)} at {at.speed_m_s:g} m/s"
    if fill > FILL_MAX_PCT:
        raise InputError(
            f"{where} fills the belt's cross-section to {gnum(fill, 3)} % (ISO 5048), beyond the "
            f"{FILL_MAX_PCT:g} % no belt carries: check the row's load (a fraction of the "
            f"design {at.material.capacity_t_h:g} t/h) and speed [m/s]",
            field=f"measured.{i}.{'speed_m_s' if m.speed_m_s is not None else 'load'}")
    if fill > 100.0:
        return [f"row {i} ({where}) fills the belt's cross-section to {gnum(fill, 3)} % (ISO 5048): "
                "the material spills past the belt's edges, so the belt did not carry that load "
                "at that speed; check the row's load (a fraction of the design "
                f"{at.material.capacity_t_h:g} t/h) and speed"]
    return []


def _load_text(load: float | list[float]) -> str:
    return ",".join(f"{x:g}" for x in load) if isinstance(load, list) else f"{load:g}"


#: Largest disagreement of a row's measured power and peripheral force [-], |P / (Te v) - 1|:
#: the drive pulleys' power is Te v exactly in a steady state, and two readings each good to
#: :data:`MISFIT_PCT` (5 %) at most disagree by at most about twice that.
POWER_FORCE_MISMATCH = 2.0 * 5.0 / 100.0


def _breaking_force_kn(conv: Conveyor) -> tuple[float, str] | None:
    """The belt's breaking force rating x width [kN] and the belt it is of, or None when the
    belt is still to be picked (``type: auto``)."""
    from beltstudy.engine import catalog

    if conv.belt.type == catalog.AUTO:
        return None
    b = catalog.resolve_belt(conv.belt)
    name = conv.belt.type or "the file's belt"
    return b.rating_n / 1e3, f"{name}, {b.rating_kn_m:g} kN/m x {b.width_m:g} m"


def _check_magnitudes(conv: Conveyor, m: Measurement, i: int) -> None:
    """A row's measured force, tension and power within what the belt can carry (its breaking
    force; at the row's speed for a power), and its power and force, when both are given,
    agreeing as P = Te v: a value in N or W for kN or kW (1000 x) or a mistyped row is named
    by its field, not fitted into a friction factor of nothing real."""
    v = m.speed_m_s if m.speed_m_s is not None else conv.speed_m_s
    vals = m.values
    broke = _breaking_force_kn(conv)
    if broke is not None:
        fb, belt = broke
        for col in ("te_kn", "t_tight_kn"):
            if col in vals and abs(vals[col]) > fb:
                raise InputError(
                    f"{vals[col]:g} kN is more than the belt's breaking force {gnum(fb)} kN "
                    f"({belt}): no belt carries it; give the force in kN (1 kN = 1000 N), "
                    "or the plant's belt in the conveyor file", field=f"measured.{i}.{col}")
        if "power_kw" in vals and abs(vals["power_kw"]) / v > fb:
            p = vals["power_kw"]
            raise InputError(
                f"{p:g} kW at {v:g} m/s needs a peripheral force of {gnum(abs(p) / v)} kN, more "
                f"than the belt's breaking force {gnum(fb)} kN ({belt}): no belt carries it; "
                "give the power at the drive pulleys in kW (1 kW = 1000 W, 1 MW = 1000 kW)",
                field=f"measured.{i}.power_kw")
    if "power_kw" in vals and "te_kn" in vals:
        p, te = vals["power_kw"], vals["te_kn"]
        if abs(p / (te * v) - 1.0) > POWER_FORCE_MISMATCH:
            raise InputError(
                f"{p:g} kW and te_kn {te:g} kN disagree: at {v:g} m/s the peripheral force "
                f"{te:g} kN is {gnum(te * v)} kW at the drive pulleys (P = Te v), "
                f"{100.0 * (p / (te * v) - 1.0):+.3g} % off, more than the "
                f"{100.0 * POWER_FORCE_MISMATCH:g} % two plant readings differ by: check the "
                "row (the same steady state, power at the pulleys not at the motors), or give "
                "one of them", field=f"measured.{i}.power_kw")


def _conveyor_at(conv: Conveyor, speed_m_s: float | None, cache: dict) -> Conveyor:
    """The conveyor running at a measured speed (validated like a file's)."""
    if speed_m_s is None or speed_m_s == conv.speed_m_s:
        return conv
    if speed_m_s not in cache:
        cache[speed_m_s] = _at_speed(conv, speed_m_s, "measured.speed_m_s: ")
    return cache[speed_m_s]


def _takeup_held(conv: Conveyor, fm, rows: Sequence[Measurement], params: dict
                 ) -> tuple[Conveyor, str]:
    """The plant's take-up held for every row: an ``auto`` counterweight (or fixed take-up's
    pretension) sized once, as a study's design basis sizes it (the largest requirement at
    full load over the rows' temperatures), with the start parameters. Sized per row, it
    would follow each row's temperature and the trial parameters, which one counterweight
    does not. Returns the conveyor and a note ("" when the file gives the size)."""
    tu = conv.takeup
    field, key, unit = (("mass_kg", "takeup_mass_kg", "kg") if tu.type == "gravity"
                        else ("pretension_kn", "takeup_pretension_kn", "kN"))
    if getattr(tu, field) != "auto":
        return conv, ""
    p = fm.params(params)
    temps = sorted({m.temperature_c for m in rows})
    size = max(float(solve_steady(conv, model=fm.name, params=p, temperature_c=t,
                                  load="full").summary[key]) for t in temps)
    data = conv.model_dump(mode="json", by_alias=True)
    data["takeup"][field] = size
    held = parse_conveyor(data)
    return held, (f"takeup.{field} auto: held at {size:.6g} {unit} for every row (sized once, "
                  f"at full load over the rows' temperatures {', '.join(f'{t:g}' for t in temps)} "
                  f"C with the start values, as a study's design basis sizes it); give the "
                  f"plant's as takeup.{field}")


def _upper(model, name: str) -> float:
    """The largest value a fit gives parameter ``name``: its declared largest value
    (:meth:`FrictionModel.largest`), else 1 where the model's own check stops it there (a
    share: ``centre_share``, ``ky_sag_share``), else no bound."""
    hi = model.largest(name)
    if hi is not None:
        return float(hi)
    return 1.0 if model.accepts(name, 1.0) and not model.accepts(name, 1.0 + 1e-9) else math.inf


def _lower(model, name: str) -> float:
    """The smallest value a fit gives parameter ``name``: 0, or the model's own lower limit
    where its check refuses 0 (DIN's C >= 1), found by bisection on :meth:`accepts`."""
    if model.accepts(name, 0.0):
        return 0.0
    hi = 1.0
    for _ in range(64):
        if model.accepts(name, hi):
            break
        hi *= 2.0
    else:
        return 0.0
    lo = 0.0
    for _ in range(80):
        mid = 0.5 * (lo + hi)
        lo, hi = (lo, mid) if model.accepts(name, mid) else (mid, hi)
    return hi


def _check_names(model, fit: Sequence[str], fixed: dict) -> list[str]:
    valid = [f.name for f in dataclasses.fields(model.params_class)]
    valid += list(TIED.get(model.name, {}))
    names = []
    for name in fit:
        if name not in valid:
            close = difflib.get_close_matches(name, valid, n=1, cutoff=0.5)
            hint = f" (did you mean '{close[0]}'?)" if close else ""
            raise InputError(f"'{name}' is not a parameter of model {model.name}{hint}; "
                             f"valid: {', '.join(valid)}", field="fit")
        if name in names:
            raise InputError(f"'{name}' is named twice", field="fit")
        _check_overlap(model.name, name, names, fixed)
        names.append(name)
    if not names:
        raise InputError(f"name at least one parameter to fit; valid: {', '.join(valid)}",
                         field="fit")
    return names


def _sets_text(model: str, name: str) -> str:
    """What fitting a :data:`TIED` ``name`` sets, in words: ``'f' sets f_carry and f_return to
    one value``."""
    return f"'{name}' sets {' and '.join(_sets(model, name))} to one value"


def _check_overlap(model: str, name: str, names: Sequence[str], fixed: dict) -> None:
    """A fitted ``name`` that sets a parameter held in ``fixed`` or set by a name fitted
    before it (DIN's ``f`` sets ``f_carry`` and ``f_return``) is refused naming both and which
    to fit instead."""
    sets = _sets(model, name)
    clash = [q for q in sets if q in fixed]
    if clash:
        held = (f"{' and '.join(clash)} {'is' if len(clash) == 1 else 'are'} held at "
                f"{' and '.join(f'{fixed[q]:g}' for q in clash)} (--param, or the request's "
                "params)")
        if sets == (name,):
            raise InputError(f"'{name}' is both fitted and fixed: {held}; fit it or hold it, "
                             "not both", field="fit")
        rest = [q for q in sets if q not in clash]
        instead = (f"fit {' and '.join(rest)} instead, with {' and '.join(clash)} held, or "
                   if rest else "")
        raise InputError(f"'{name}' is both fitted and fixed: it sets {' and '.join(sets)} to "
                         f"one value, and {held}: {instead}stop holding "
                         f"{' and '.join(clash)} to fit '{name}'", field="fit")
    for other in names:
        both = [q for q in sets if q in _sets(model, other)]
        if both:
            tied = [t for t in (other, name) if _sets(model, t) != (t,)]
            why = f" ({'; '.join(_sets_text(model, t) for t in tied)})" if tied else ""
            raise InputError(f"'{name}' sets a parameter another fitted name sets: "
                             f"{' and '.join(both)}, which '{other}' sets too{why}; fit one of "
                             "them, not both", field="fit")


def _sets(model: str, name: str) -> tuple[str, ...]:
    """The parameters a fitted name sets (itself, or those :data:`TIED` names)."""
    return TIED.get(model, {}).get(name, (name,))


def _expanded(model: str, values: dict[str, float]) -> dict[str, float]:
    return {p: v for name, v in values.items() for p in _sets(model, name)}


def _starts(model, conv, rows, names, fixed, starts, lowest=None) -> np.ndarray:
    """Start values: given, else the model's default, else the law's computed value."""
    base = model.params(fixed)
    info = None
    out = []
    for name in names:
        value = starts.get(name, getattr(base, _sets(model.name, name)[0]))
        if value is None:
            if info is None:
                m = rows[0]
                info = solve_steady(conv, model=model.name, params=base,
                                    temperature_c=m.temperature_c, load=m.load).law.info
            value = info.get(_INFO_START.get(name, name))
        if value is None:
            raise InputError(f"'{name}' has no default to start from; give one as "
                             f"{name}=VALUE", field="fit")
        low = (lowest or {}).get(name, 0.0)
        if value < low:
            where = ("the bound 0 the fit keeps every parameter above (docs/uncertainty.md)"
                     if low == 0 else f"the smallest value model {model.name} takes ({low:g})")
            hold = (f", or hold it there as a fixed parameter (--param {name}={value:g}, the "
                    "request's params)" if model.accepts(name, value) else "")
            raise InputError(f"'{name}' starts at {value:g}, below {where}: start it at "
                             f"{low:g} or above ({name}=START){hold}", field="fit")
        if name in starts:
            _check_start(model, name, value)
        out.append(float(value))
    return np.array(out)


def _check_start(model, name: str, value: float) -> None:
    """A given start (``NAME=START``) the model's own check refuses is named as the fit item
    the user wrote (``fit: 'f_carry=5': ...``), not as a study's ``models.<model>.`` field."""
    for q in _sets(model.name, name):
        try:
            model.params({q: value})
        except InputError as exc:
            reason = exc.reason.removeprefix(f"models.{model.name}.{q}: ")
            raise InputError(f"'{name}={value:g}': the start of {q} is out of the model's "
                             f"range: {reason}; start it within that range ({name}=START), or "
                             "drop =START to start at the model's default",
                             field="fit") from None


def calibrate(conv: Conveyor, measured: Sequence[Measurement], model: str,
              fit: Sequence[str], *, fixed: dict[str, float] | None = None,
              starts: dict[str, float] | None = None) -> Calibration:
    """Fit the parameters ``fit`` of friction model ``model`` to the measurements.

    Parameters
    ----------
    conv : Conveyor
        The plant's conveyor.
    measured : sequence of Measurement
        One per measured steady state.
    model : str
        Friction model name.
    fit : sequence of str
        Parameters to fit (names of the model's parameter dataclass, or a name of
        :data:`TIED`: ``f`` of din sets f_carry and f_return to one value).
    fixed : dict, optional
        Other parameters held at given values.
    starts : dict, optional
        Start values of fitted parameters (default: the model's defaults).

    Returns
    -------
    Calibration
    """
    from scipy.optimize import least_squares

    try:
        fm = get_model(model)
    except InputError as exc:  # the calibration's field is its model (--model, "model")
        raise InputError(exc.reason, field="model") from None
    fixed = dict(fixed or {})
    fm.params(fixed)
    names = _check_names(fm, fit, fixed)
    rows = list(measured)
    overfilled = _check_rows(conv, rows)
    rows = _with_states(conv, fm, rows)
    # each name's smallest value: 0, or the model's own limit above it (DIN's C >= 1)
    lowest = {n: max(_lower(fm, q) for q in _sets(fm.name, n)) for n in names}
    x0 = _starts(fm, conv, rows, names, fixed, dict(starts or {}), lowest)
    conv, held_takeup = _takeup_held(conv, fm, rows, {**fixed, **_expanded(
        fm.name, dict(zip(names, map(float, x0), strict=True)))})
    cols = [(i, col) for i, m in enumerate(rows) for col in m.values]
    y = np.array([rows[i].values[col] for i, col in cols])
    obs = _observations(cols)
    combine = _combiner(obs, len(cols))
    speeds: dict = {}

    # each name's largest value (friction.base.param, else the model's own limit: 1 for a
    # share): the fit's bound, and where the differences of its Jacobian are taken at it,
    # the value they reach past it
    largest = {n: min(_upper(fm, q) for q in _sets(fm.name, n)) for n in names}
    own_limit = [n for n in names
                 if all(fm.largest(q) is None for q in _sets(fm.name, n)) and
                 np.isfinite(largest[n])]

    def model_values(x: np.ndarray, which: Sequence[str]) -> np.ndarray:
        p = fm.params({**fixed, **_expanded(fm.name, {
            n: min(max(float(v), lowest[n]), largest[n]) for n, v in zip(which, x, strict=True)})})
        out = {}
        for i, m in enumerate(rows):
            res = solve_steady(_conveyor_at(conv, m.speed_m_s, speeds), model=fm.name,
                               params=p, temperature_c=m.temperature_c, load=m.load)
            out[i] = res.summary
        return np.array([out[i][MEASURED[col]] for i, col in cols], dtype=float)

    def residual(x, which):
        return (model_values(x, which) - y) / np.abs(y)

    def fit_residual(x, which):  # one per reading: a row's power and Te are one (_observations)
        return combine(residual(x, which))

    free, held, groups = _identifiable(lambda x: fit_residual(x, names), x0, names,
                                       [lowest[n] for n in names])
    x_free = np.array([x0[names.index(n)] for n in free])
    held_values = {n: float(x0[names.index(n)]) for n in held}
    # a held name whose default the law computes (CEMA's kt from each row's temperature, ky,
    # ai_n from the catalogue) is left to the law, as it would be unnamed: its start is the
    # value at the first row, and pinned there it would stand for every row's temperature
    # (and, in the models block, for every run of a study)
    base = fm.params(fixed)
    computed = {n for n in held if n not in (starts or {})
                and getattr(base, _sets(fm.name, n)[0]) is None}
    fixed.update(_expanded(fm.name, {n: v for n, v in held_values.items()
                                     if n not in computed}))
    # a fitted name whose default the law computes for each row (CEMA's kt from its
    # temperature) is one value for every row once fitted: exact CEMA data at -20, 0 and
    # 20 C fitted kt 1.089 at a 3.6 % misfit, status ok, where the law gives 1.30 and 1.0
    spread = len({m.temperature_c for m in measured}) > 1
    law_notes = []
    for n in free:
        if spread and n not in (starts or {}) and getattr(base, _sets(fm.name, n)[0]) is None:
            law_notes.append(
                f"{n} is computed by model {fm.name} for each row where it is not given (from "
                "the row's temperature, load or the catalogue); fitted, it is one value for "
                "rows at several temperatures, and the models block pins it for every run "
                "of a study: fit it on rows at one temperature, or leave it to the law and "
                "fit a factor on it or another name")
    upper = [largest[n] for n in free]
    lower = [lowest[n] for n in free]
    sol = least_squares(fit_residual, x_free, args=(free,), bounds=(lower, upper),
                        x_scale="jac", diff_step=DIFF_STEP, xtol=1e-12, ftol=1e-12)
    r = residual(sol.x, free)
    r_fit = combine(r)
    jac = _jacobian(lambda x: fit_residual(x, free), sol.x, lower)
    n, p = len(r), len(free)
    dof = len(obs) - p
    notes = [(f"{', '.join(g)}: only act together on these data; " if len(g) > 1 else
              f"{g[0]}: changes {_INERT}; ") + "; ".join(
        f"{x} held at the value model {fm.name} computes for each row, its default "
        f"({gnum(held_values[x])} at row 0)" if x in computed else f"{x} held at the start value"
        for x in g if x in held) for g in groups]
    if held_takeup:
        notes.append(held_takeup)
    notes += overfilled + law_notes
    se = _standard_errors(r_fit, jac, dof)
    if dof <= 0:
        notes.append(_no_dof(n, len(obs), p))
    at_bound = _at_bound(free, sol.x, lower, jac, r_fit)
    at_upper = [n for n, v, hi in zip(free, sol.x, upper, strict=True)
                if np.isfinite(hi) and v >= hi * (1.0 - 1e-6)]
    notes += _value_notes(fm.name, free, sol.x, se, at_bound, lowest)
    values = model_values(sol.x, free)
    t95 = _t95(dof)
    # a name ended at either bound has no interval (docs/uncertainty.md), and an interval
    # stays within the name's own range (a seal_drag_factor stopped at its largest value
    # 100 read '0 to 1566')
    fitted = {name: {"value": float(v), "se": s, "start": float(x0[names.index(name)]),
                     "ci95": (None if s is None or name in at_bound or name in at_upper
                              else [max(float(v - t95 * s), lowest[name]),
                                    min(float(v + t95 * s), float(hi))])}
              for name, v, s, hi in zip(free, sol.x, se, upper, strict=True)}
    fitted.update({name: {"value": v, "se": None, "start": v, "ci95": None}
                   for name, v in held_values.items()})
    residuals = [{"row": i, "measured": col, "value": float(y[k]), "model": float(values[k]),
                  "residual": float(values[k] - y[k]), "relative": float(r[k])}
                 for k, (i, col) in enumerate(cols)]
    block = {**{k: float(v) for k, v in fixed.items()},
             **_expanded(fm.name, {name: float(f"{v:.6g}")
                                   for name, v in zip(free, sol.x, strict=True)})}
    sv = np.linalg.svd(_unit_columns(jac), compute_uv=False) if p else np.array([])
    slips = _sign_slips(rows, cols, y, values)
    x_start = x0[[names.index(n) for n in free]]
    unit = _unit_slip(cols, y, model_values(x_start, free) if p else values, ", ".join(
        f"{n} {gnum(v)}" for n, v in zip(free, x_start, strict=True)) or "as given")
    if unit:
        notes.append(unit)
    first = [ks[0] for ks in obs]  # each reading's first value (a row's power before its Te)
    # the deletion identity of the outlier test holds where the fit's gradient is zero: in
    # the names left free, not in one stopped at a bound (it read 'unbounded' for readings
    # 1.3 % off with 1 % noise); a name at a bound is held there for the test
    inside = [k for k, name in enumerate(free) if name not in at_bound and name not in at_upper]
    suspect = (slips or _contradictions(rows, cols, y)
               or _outliers(rows, [cols[k] for k in first], y[first], values[first], r_fit,
                            jac[:, inside] if jac.size else jac, dof,
                            len({_state_key(m) for m in rows})))
    notes += _collinear_note(free, jac)
    notes += suspect + _copies(rows) + _leverage_notes(
        rows, [cols[k] for k in first], y[first], jac, dof)
    # a row's power and Te left as many readings as names: those states are met, not checked
    few = _few_states(rows, cols, p) if dof > 0 or len(obs) < n else ""
    # a name at its bound in a fit that meets the data without it is not determined by them
    # where other fitted names took its part (the verdict says 'these data do not determine
    # c'): named with the held ones (SPEC 7.3, 'the names that cannot be identified'); DIN's
    # f_carry and c fitted together ended with c at its bound 1 and an empty list
    undetermined = (at_bound if sol.success and not slips and not at_upper
                    and len(free) > len(at_bound)
                    and 100.0 * math.sqrt(float(r @ r) / n) <= MISFIT_PCT else [])
    return Calibration(
        model=fm.name, fit=fitted, residuals=residuals,
        not_identifiable=sorted({x for g in groups for x in g} | set(undetermined),
                                key=names.index),
        held=held_values, models={fm.name: block},
        rms_relative=float(math.sqrt(float(r @ r) / n)), dof=dof,
        singular_values=[float(s) for s in sv],
        notes=notes, **_verdict(
            sol, at_bound, r, fm.name, at_upper, {n: largest[n] for n in own_limit},
            lowest=lowest, held=_Held(groups, held_values, computed),
            doubts=_Doubts(suspect, slips, few, bool(p) and dof == 0, unit)))


#: Condition index of the fit's scaled sensitivities beyond which two names are said to be
#: hardly told apart by the data: 30, where Belsley, Kuh and Welsch (*Regression
#: Diagnostics*, 1980, ch. 3) find strong dependencies between columns.
COLLINEAR_INDEX = 30.0


def _collinear_note(free: Sequence[str], jac: np.ndarray) -> list[str]:
    """A note when the data hardly tell the fitted names apart: the condition index (largest
    over smallest singular value of the unit-scaled sensitivities) beyond
    :data:`COLLINEAR_INDEX`, naming the two names the weakest direction mixes most. Rows at
    19 and 20 C only, fitting seal_drag_factor and drag_temp_coef (index 79), ran the factor
    to its largest value with the advice to check the data."""
    if len(free) < 2 or not jac.size:
        return []
    _, sv, vt = np.linalg.svd(_unit_columns(jac), full_matrices=False)
    if sv[-1] <= 0.0 or sv[0] / sv[-1] <= COLLINEAR_INDEX:
        return []
    a, b = (free[k] for k in np.argsort(-np.abs(vt[-1]))[:2])
    return [f"these data hardly tell {a} from {b}: the condition index of the fit's "
            f"scaled sensitivities is {gnum(sv[0] / sv[-1], 3)}, beyond {COLLINEAR_INDEX:g} (Belsley, "
            "Kuh and Welsch 1980: columns that strong a dependency joins), so a change of one "
            "is nearly made up by the other and their values and errors are loose together; "
            "readings over a wider range of what sets them (temperature, load, speed) "
            "separate them, or hold one (--param NAME=VALUE)"]


def _observations(cols: Sequence[tuple[int, str]]) -> list[list[int]]:
    """The measured values grouped into readings (indices into ``cols``): a row's
    ``power_kw`` and ``te_kn`` are one reading of its steady state (P = Te v at the drive
    pulleys; a plant's Te is most often its power over the speed), every other value its
    own. The fit takes the mean of a reading's relative residuals as its one residual
    (:func:`_combiner`) and counts the degrees of freedom by readings."""
    out: list[list[int]] = []
    drive: dict[int, list[int]] = {}
    for k, (i, col) in enumerate(cols):
        if col in ("power_kw", "te_kn"):
            if i not in drive:
                drive[i] = []
                out.append(drive[i])
            drive[i].append(k)
        else:
            out.append([k])
    return out


def _combiner(obs: Sequence[Sequence[int]], n: int):
    """The map from the ``n`` relative residuals of the measured values to one per reading
    (:func:`_observations`): the mean of a reading's values; the residuals themselves where
    every reading is one value."""
    if all(len(ks) == 1 for ks in obs):
        return lambda r: r
    a = np.zeros((len(obs), n))
    for o, ks in enumerate(obs):
        a[o, ks] = 1.0 / len(ks)
    return lambda r: a @ r


def _standard_errors(r: np.ndarray, jac: np.ndarray, dof: int) -> list[float | None]:
    """The square roots of the diagonal of Cov = s^2 (J^T J)^-1, s^2 = SSR / dof, of the
    readings' relative residuals ``r`` [-] (one per reading) and their Jacobian; None each
    without degrees of freedom."""
    if dof <= 0:
        return [None] * jac.shape[1]
    cov = float(r @ r) / dof * np.linalg.pinv(jac.T @ jac)
    return [float(math.sqrt(max(cov[k, k], 0.0))) for k in range(jac.shape[1])]


def _no_dof(n: int, readings: int, p: int) -> str:
    """The note of a fit without degrees of freedom: ``n`` measured values, ``readings``
    readings (a row's power and Te one), ``p`` fitted names."""
    what = (f"{n} residuals" if n == readings else f"{_values(n)} ({readings} reading"
            f"{'' if readings == 1 else 's'}: a row's power_kw and te_kn are one)")
    return f"{what} for {p} parameters: no degrees of freedom left, no standard errors"


#: Ranges of published values that a model's own parameter check quotes ([-]; DIN 22101's
#: fictitious friction factor f, 0.010 to about 0.04: ``engine/friction/din.py``): a fitted
#: value outside is noted (:func:`_value_notes`).
PUBLISHED = {"din": {name: (0.010, 0.04, "DIN 22101: 0.010 to about 0.04")
                    for name in ("f_carry", "f_return", "f")}}


def _value_notes(model: str, free: Sequence[str], x: np.ndarray, se: Sequence[float | None],
                 at_bound: Sequence[str], lowest: dict[str, float]) -> list[str]:
    """A note per fitted value at its bound, poorly determined (its standard error above the
    value) or outside the published range its model's check quotes (:data:`PUBLISHED`)."""
    notes = []
    for name, v, s in zip(free, x, se, strict=True):
        if name in at_bound:
            notes.append(f"{name} ended at its bound {lowest[name]:g}: the data would take it "
                         "below; its standard error is not that of a free estimate")
            continue
        if s is not None and s > abs(v):
            notes.append(f"{name} is poorly determined by these data: its standard error "
                         f"({gnum(s, 3)}) exceeds its value ({gnum(v, 3)})")
        lo, hi, src = PUBLISHED.get(model, {}).get(name, (-math.inf, math.inf, ""))
        if not lo <= v <= hi:
            notes.append(
                f"{name} {gnum(v)} lies {'above' if v > hi else 'below'} the published range "
                f"({src}; model {model}'s own check quotes it): a conveyor file whose "
                "length or lift is not the plant's (a plant "
                f"{'longer or higher' if v > hi else 'shorter or lower'} than the file) asks "
                "for such a value to make up the difference; check the file's profile "
                "(length_m, lift_m), capacity and speed against the plant's before using it")
    return notes


def _t95(dof: int) -> float:
    """Student's t quantile of a two-sided 95 % interval with ``dof`` degrees of freedom
    (the residual variance is estimated from the same data, so 1.96 undercovers: 2.45 at 6,
    2.23 at 10 degrees of freedom); nan without any."""
    if dof < 1:
        return math.nan
    from scipy.stats import t as student

    return float(student.ppf(0.975, dof))


#: Rms relative residual [%] above which a fit misses its data: a plant's logged drive power
#: is good to a few per cent (meter class 1 to 2, plus the steady-state reading of a belt whose
#: load varies), so a larger misfit points at the data or the conveyor file, not the noise.
MISFIT_PCT = 5.0
#: Chance [-] that a fit of consistent data names a row as an outlier: each row's externally
#: studentized residual is judged against Student's t at the Bonferroni level
#: OUTLIER_ALPHA / (2 n) with n - p - 1 degrees of freedom (Cook & Weisberg 1982, 2.2.2;
#: Belsley, Kuh & Welsch 1980, 2.1): 1 fit in 100 of consistent data names one (a warning
#: is rare where nothing is wrong).
OUTLIER_ALPHA = 0.01
#: Leverage [-] of one reading above which it is named as carrying the fit: Huber's bound
#: (Robust Statistics, 1981, 7.2: h above 0.5 is to be avoided, the reading then outweighs
#: the rest), and above twice the mean leverage 2 p / n (Belsley, Kuh & Welsch 1980, 2.1).
LEVERAGE_HIGH = 0.5
#: Smallest relative residual [%] named as an outlier however far it stands from the rest: a
#: plant meter of class 1 reads within 1 % (the class of :data:`MISFIT_PCT`'s note).
OUTLIER_MIN_PCT = 1.0
#: Largest difference [-] of two readings of one steady state (the same load, temperature and
#: speed), relative to their mean: each good to :data:`MISFIT_PCT` at most, they differ by at
#: most twice that.
REPLICATE_SPREAD = 2.0 * MISFIT_PCT / 100.0


def _state_key(m: Measurement) -> tuple:
    """What makes two rows readings of one steady state: equal load, temperature and speed,
    as the model computes them (``m.state``, :func:`_with_states`), else as written."""
    return m.state if m.state is not None else (repr(m.load), m.temperature_c, m.speed_m_s)


def _reading_key(m: Measurement) -> tuple:
    """What makes two rows readings of one state of the plant: :func:`_state_key` with the
    temperature as written, whether or not the model reads it (a plant at -10 and 20 C runs
    two states, which DIN computes alike: their readings may differ without either being
    wrong)."""
    key = _state_key(m)
    return (key[0], float(m.temperature_c), *key[2:]) if m.state is not None else key


def _with_states(conv: Conveyor, fm, rows: Sequence[Measurement]) -> list[Measurement]:
    """The rows with the steady state the model computes for each (``Measurement.state``):
    the load as one fraction per section (``full``, ``1.0`` and ``"1.0,1.0"`` are one load,
    :func:`~beltstudy.engine.conveyor.section_loads`), the temperature only where the model
    has a temperature term (DIN's figures at 10 and 30 C are one state) and the speed (the
    file's where a row gives none). Rows of one state are repeats: a file with ``full`` and
    ``1.0`` at 10 C named its third row an outlier (a residual of 7.5e5), where ``1.0`` twice
    noted the copy; a DIN fit of one load at five temperatures said ``ok`` where the same
    readings at one temperature said the data check the model against nothing."""
    temp = bool(getattr(fm, "temperature_term", True))
    return [dataclasses.replace(m, state=(
        tuple(float(v) for v in section_loads(m.load, conv)),
        float(m.temperature_c) if temp else None,
        float(m.speed_m_s if m.speed_m_s is not None else conv.speed_m_s))) for m in rows]


def _state_text(m: Measurement, group: Sequence[Measurement] = ()) -> str:
    """A measured steady state in words: ``load 0.5, 5 C`` (and the speed when given); of a
    ``group`` of rows of one state read at several temperatures by a model without a
    temperature term, ``load 0.5 at -10 to 30 C (the model reads no temperature)``."""
    load = m.load if not isinstance(m.load, list) else ",".join(f"{v:g}" for v in m.load)
    load = f"{load:g}" if isinstance(load, float) else load
    speed = f", {m.speed_m_s:g} m/s" if m.speed_m_s is not None else ""
    temps = sorted({float(g.temperature_c) for g in group})
    if m.state is not None and m.state[1] is None and len(temps) > 1:
        return (f"load {load} at {temps[0]:g} to {temps[-1]:g} C (the model has no "
                f"temperature term: one state){speed}")
    return f"load {load}, {m.temperature_c:g} C{speed}"


def _few_states(rows: Sequence[Measurement], cols: Sequence[tuple[int, str]], p: int) -> str:
    """The steady states the measured values read, in words, when they are no more than the
    ``p`` fitted names (``""`` otherwise): repeated readings of one state (equal load,
    temperature and speed, in any column: power and Te of one state are one reading,
    P = Te v) tell the meter's scatter, not the model, so that many states are
    met whatever the model, as :func:`_verdict`'s ``exact`` is, with degrees of freedom that
    count only the repeats."""
    states: dict[tuple, dict[int, list[str]]] = {}
    for i, col in cols:
        states.setdefault(_state_key(rows[i]), {}).setdefault(i, []).append(col)
    if not p or len(states) > p:
        return ""
    return "; ".join(
        f"{_state_text(rows[next(iter(ix))], [rows[i] for i in ix])} "
        f"{' and '.join(dict.fromkeys(c for cs in ix.values() for c in cs))} "
        f"(row{'s' if len(ix) > 1 else ''} {', '.join(map(str, ix))})"
        for ix in states.values())


def _sign_slips(rows: Sequence[Measurement], cols: Sequence[tuple[int, str]], y: np.ndarray,
                values: np.ndarray) -> list[str]:
    """Measured power or Te of the other sign than the fit's for its state, the fit at least
    :data:`MISFIT_PCT` of the reading away from zero (so not a belt near balance, where
    either sign is honest): power and Te are negative only where the drives regenerate, so
    such a reading is most likely a meter or a column the other way round; one sentence per
    such value."""
    out = []
    for k, (i, col) in enumerate(cols):
        if col not in ("power_kw", "te_kn") or y[k] * values[k] >= 0.0:
            continue
        if abs(values[k]) < MISFIT_PCT / 100.0 * abs(y[k]):
            continue
        runs = "regenerates" if values[k] < 0 else "motors"
        out.append(f"row {i} ({_state_text(rows[i])}): measured {col} {gnum(y[k])} has the "
                   f"other sign than the fit's {gnum(values[k])} (the belt {runs} in that state "
                   "by the model; power and Te are negative only where the drives "
                   "regenerate): check the row's sign (a meter or a column the other way "
                   "round) and fit again")
    return out


#: A reading taken as written in the unit a prefix step (1000 x) away from the column's when
#: the model at its textbook start values computes within half a decade of 1000 x (or of
#: 1 / 1000 x) the readings (the median over them): a plant's friction factors lie within 3 x
#: of the textbook's (DIN 22101's f 0.010-0.030 about its 0.020; CEMA's Kx, Ky alike), far from
#: 1000 x.
PREFIX_STEP = 1000.0
#: Units a prefix step (1000 x) above and below each measured column's (:func:`_unit_slip`).
_PREFIX_UNITS = {"power_kw": ("MW", "W", "kW"), "te_kn": ("MN", "N", "kN")}


def _unit_slip(cols: Sequence[tuple[int, str]], y: np.ndarray, start: np.ndarray,
               names: str) -> str:
    """A sentence when the readings look written in another unit than their column's (MW or
    W in ``power_kw``, MN or N in ``te_kn``): the model at its start values ``start`` (the
    fitted ``names``' textbook values) computes about :data:`PREFIX_STEP` x (or 1 /
    :data:`PREFIX_STEP` x) each reading; ``""`` otherwise."""
    ratios = [m / v for (_, col), v, m in zip(cols, y, start, strict=True)
              if col in _PREFIX_UNITS and v * m > 0.0]
    if not ratios or 2 * len(ratios) < len(cols):
        return ""
    ratio = float(np.median(ratios))
    half_decade = math.sqrt(10.0)
    units = {_PREFIX_UNITS[col] for _, col in cols if col in _PREFIX_UNITS}
    if len(units) != 1:
        return ""
    above, below, own = units.pop()
    if PREFIX_STEP / half_decade <= ratio <= PREFIX_STEP * half_decade:
        unit, times = above, f"{ratio:.0f} x"
    elif PREFIX_STEP / half_decade <= 1.0 / ratio <= PREFIX_STEP * half_decade:
        unit, times = below, f"1 / {1.0 / ratio:.0f} of"
    else:
        return ""
    return (f"At its textbook values ({names}) the model computes about {times} each "
            f"reading: the readings look written in {unit}; give them in {own} (1 "
            f"{above} = 1000 {own} = 1 000 000 {below}) and fit again.")


def _copies(rows: Sequence[Measurement]) -> list[str]:
    """Rows that repeat an earlier one exactly (state and every measured value): a reading
    pasted twice counts as a second one and narrows the interval; one note per copy."""
    seen: dict[tuple, int] = {}
    out = []
    for i, m in enumerate(rows):
        key = (_reading_key(m), tuple(sorted(m.values.items())))
        if key in seen:
            out.append(f"row {i} repeats row {seen[key]} exactly ({_state_text(m)}, every "
                       "measured value equal): a copy counts as a second reading and "
                       "narrows the interval; remove it if it was pasted twice (a true "
                       "repeat of a steady state rarely reads every digit alike)")
        else:
            seen[key] = i
    return out


def _contradictions(rows: Sequence[Measurement], cols: Sequence[tuple[int, str]],
                    y: np.ndarray) -> list[str]:
    """Readings of one steady state (rows of equal load, temperature and speed) whose
    measured values of a column differ by more than :data:`REPLICATE_SPREAD` of their mean:
    no parameter value meets both; one sentence per such group."""
    groups: dict[tuple, list[int]] = {}
    for k, (i, col) in enumerate(cols):
        groups.setdefault((_reading_key(rows[i]), col), []).append(k)
    out = []
    for (_, col), ks in groups.items():
        if len(ks) < 2:
            continue
        vals = y[ks]
        lo, hi = int(ks[int(np.argmin(vals))]), int(ks[int(np.argmax(vals))])
        spread = (y[hi] - y[lo]) / abs(float(np.mean(vals)))
        if spread > REPLICATE_SPREAD:
            i_lo, i_hi = sorted((cols[lo][0], cols[hi][0]))
            out.append(
                f"rows {i_lo} and {i_hi} read one steady state ({_state_text(rows[i_lo])}) "
                f"but their {col} differ by {gnum(100 * spread, 3)} % ({gnum(y[lo])} and {gnum(y[hi])}), "
                f"more than the {100 * REPLICATE_SPREAD:g} % two readings each good to "
                f"{MISFIT_PCT:g} % can: at least one is not that state (its load, temperature, "
                "speed or units); no parameter value meets both")
    return out


def _outliers(rows: Sequence[Measurement], cols: Sequence[tuple[int, str]], y: np.ndarray,
              values: np.ndarray, r: np.ndarray, jac: np.ndarray, dof: int,
              states: int) -> list[str]:
    """The measured values that stand apart from the fit of the others: the externally
    studentized residual t_k = r_k / (s_(k) sqrt(1 - h_k)), with h_k the leverage (the hat
    matrix J (J^T J)^-1 J^T of the relative residuals) and s_(k) the residual scale without
    value k, beyond Student's t at the Bonferroni level (:data:`OUTLIER_ALPHA`) and beyond
    :data:`OUTLIER_MIN_PCT`. One value per reading (a row's power and Te are one,
    :func:`_observations`: ``r`` and ``jac`` are the readings'). One sentence per such value;
    none when fewer than two degrees of freedom are left, counted by the distinct steady
    ``states`` the readings are of (the others cannot judge it: a state read twice, a row
    pasted twice, leaves the other state's reading nothing to stand apart from but the copies,
    which agree exactly, a residual scale s_(k) of 0), or a value alone sets a parameter
    (leverage 1)."""
    from scipy.stats import t as student

    n = len(r)
    if dof < 2 or states - jac.shape[1] < 2:
        return []
    h = _leverages(jac) if jac.size else np.zeros(n)
    ssr = float(r @ r)
    limit = float(student.ppf(1.0 - OUTLIER_ALPHA / (2 * n), dof - 1))
    out = []
    for k, (i, col) in enumerate(cols):
        if h[k] > 1.0 - 1e-6 or abs(r[k]) * 100 <= OUTLIER_MIN_PCT:
            continue
        rest = (ssr - r[k] ** 2 / (1.0 - h[k])) / (dof - 1)
        tk = abs(r[k]) / math.sqrt(rest * (1.0 - h[k])) if rest > 0 else math.inf
        if tk <= limit:
            continue
        side = "above" if y[k] > values[k] else "below"
        shown = f"{gnum(tk, 3)}" if math.isfinite(tk) else "unbounded"
        out.append(
            f"row {i} ({_state_text(rows[i])}): measured {col} {gnum(y[k])} lies "
            f"{gnum(100 * abs(y[k] - values[k]) / abs(values[k]), 3)} % {side} the fit "
            f"({gnum(values[k])}; externally studentized residual {shown}, "
            f"where {n} readings as consistent as the rest pass {gnum(limit, 3)} only 1 time in "
            f"{1 / OUTLIER_ALPHA:.0f}): an outlier, and it pulls the fitted values; check the "
            "row (a steady state? its load, temperature, speed and units) and fit again "
            "without it if it is wrong")
    return out


def _leverages(jac: np.ndarray) -> np.ndarray:
    """Each reading's leverage h_k [-]: the diagonal of the hat matrix J (J^T J)^+ J^T of
    the readings' relative residuals, clipped to [0, 1] (float noise); they sum to the rank
    of J (Belsley, Kuh & Welsch 1980, 2.1)."""
    return np.clip(np.diag(jac @ np.linalg.pinv(jac.T @ jac) @ jac.T), 0.0, 1.0)


def _leverage_notes(rows: Sequence[Measurement], cols: Sequence[tuple[int, str]],
                    y: np.ndarray, jac: np.ndarray, dof: int) -> list[str]:
    """The readings that carry most of the fit: leverage h_k (the diagonal of the hat matrix
    J (J^T J)^-1 J^T of the readings' relative residuals; the h_k sum to the p fitted names)
    above :data:`LEVERAGE_HIGH` and above twice its mean 2 p / n (Belsley, Kuh & Welsch 1980,
    section 2.1). With residuals relative to each reading, a small reading (a belt near
    zero power, regenerating or nearly balanced) weighs most: a meter's error of a share of
    its full scale there moves the fitted values most, and their intervals do not show it.
    None when no degree of freedom is left (every reading then sets the fit alike)."""
    n, p = jac.shape if jac.ndim == 2 else (len(y), 0)
    if dof < 1 or not p:
        return []
    h = _leverages(jac)
    big = float(np.max(np.abs(y)))
    out = []
    for k, (i, col) in enumerate(cols):
        if h[k] <= max(LEVERAGE_HIGH, 2.0 * p / n):
            continue
        out.append(
            f"row {i} ({_state_text(rows[i])}): its {col} {gnum(y[k])} carries a leverage of "
            f"{h[k]:.2f} (the {n} readings' leverages sum to {p}, one per fitted name); the "
            "residuals are relative to each reading, so a small one (the largest reading is "
            f"{gnum(big)} in size) weighs most "
            "and a meter error of a share of its full scale there moves the fitted values "
            "most, beyond their standard errors: check that reading, add readings at other "
            "loads or temperatures, or fit again without it to see how far the values move")
    return out


def _at_bound(free: Sequence[str], x: np.ndarray, lower: Sequence[float], jac: np.ndarray,
              r: np.ndarray) -> list[str]:
    """The fitted names held at their lower bound (0, or the model's own limit such as DIN's
    C >= 1: ``lower``) by the bound, not by the data: those the data would take below it.

    From the fit ``x`` the Gauss-Newton step d = -(J^T J)^+ J^T r (``jac`` and ``r`` the
    readings' Jacobian and relative residuals there) reaches the least squares of the
    linearised model without bounds; a name with x + d below its bound ends at the bound
    (its gradient points out of the box: the Karush-Kuhn-Tucker condition of a bound
    constraint; Nocedal & Wright 2006, section 12.3, Theorem 12.1). A fit that converged
    inside its bounds has J^T r = 0, d = 0. The verdict depends on the data only: the
    trust-region reflective method keeps its iterates strictly inside the bounds and ends a
    distance from the bound that depends on where it started (Non-Lin's m_star 3.7e-7 from
    0.0035, 2.8e-7 from 0.007, d = -5.8e-5 from both, its standard error 0.012), which a
    share of the start (the former test, 1e-4 x start) turned into two verdicts."""
    if not len(free):
        return []
    step = -np.linalg.pinv(jac.T @ jac) @ (jac.T @ r)
    return [name for name, v, d, lo in zip(free, x, step, lower, strict=True) if v + d < lo]


def _values(n: int) -> str:
    """``n`` measured value(s), in words."""
    return f"{n} measured value{'' if n == 1 else 's'}"


@dataclass(frozen=True)
class _Held:
    """The names a fit held (:func:`_verdict`): ``groups`` that only act together on the data,
    the held ``values`` and those of them left to the law's own value (``computed``)."""

    groups: Sequence[Sequence[str]] = ()
    values: dict[str, float] | None = None
    computed: Sequence[str] = ()


@dataclass(frozen=True)
class _Doubts:
    """What speaks against the readings (:func:`_verdict`): sentences naming values the
    others contradict (``suspect``), readings of the other sign (``slips``), too few states
    (``few``), and a fit met exactly with nothing to check it (``exact``)."""

    suspect: Sequence[str] = ()
    slips: Sequence[str] = ()
    few: str = ""
    exact: bool = False
    unit: str = ""


def _verdict(sol, at_bound: list[str], r: np.ndarray, model: str,
             at_upper: Sequence[str] = (), own_limit: dict[str, float] | None = None,
             lowest: dict[str, float] | None = None, held: _Held | None = None,
             doubts: _Doubts | None = None) -> dict[str, str]:
    """``status`` and ``message`` of the fit in this project's words (never SciPy's text):
    ``failed`` when it stopped without converging, ``warning`` when a fitted parameter ended
    at its bound (the data ask for a value the model does not allow: the rest of the misfit
    stays in the residuals: at 0, or at its largest value, far beyond any published one) or
    when it converged but misses the measurements by more than :data:`MISFIT_PCT`, ``ok``
    otherwise; a converged fit that held names it was asked to fit (``held``: its ``groups``
    that only act together on these data, held at ``values``) is a ``warning`` too: the values it
    gives assume the held ones. ``own_limit``: the names whose largest value is the model's
    own limit (a share's 1), not a declared one far beyond any published value. ``doubts``
    about the readings (:class:`_Doubts`): ``suspect``:
    sentences naming measured values the others contradict (readings of one state that
    disagree, :func:`_contradictions`; outliers, :func:`_outliers`): a ``warning`` that names
    them before a misfit's general advice. ``exact``: as many measured values as fitted
    names, met exactly: nothing checks the fit and it has no standard errors, a
    ``warning``. ``lowest``: each name's smallest value (0 unless the model's own check sets
    another, DIN's C >= 1), named where a fit ends there. ``computed``: the held names left
    to the value the law computes for each row (their default), not held at a number.
    ``slips``: the sentences of :func:`_sign_slips` (readings of the other sign than the
    fit's): they lead the message even where a name ended at a bound, since a reading of the
    wrong sign is what drives a friction factor to 0. ``few``: the steady states read, in words, when the measured values repeat
    no more states than there are fitted names (:func:`_few_states`): met whatever the model
    as ``exact`` is, the repeats' scatter alone setting the standard errors, a ``warning``
    (with ``exact`` too: a row's power and Te, one reading, left no degrees of freedom)."""
    held = held or _Held()
    doubts = doubts or _Doubts()
    groups, computed = held.groups, held.computed
    suspect, exact, few, slips = doubts.suspect, doubts.exact, doubts.few, doubts.slips
    held = held.values
    rms = 100 * math.sqrt(float(r @ r) / len(r))
    rms_text = f"{gnum(rms, 3)}" if rms < 1000 else f"{rms:.0f}"
    check = ("Check the measured values (power at the drive pulleys [kW] or peripheral force "
             "[kN], negative only where the drives regenerate; each row's load and temperature) "
             "and the conveyor file "
             "(lift, capacity, speed, take-up), or fit other parameters of the model")
    if doubts.unit:
        # readings a prefix step off (MW in a kW column): the likeliest cause, said first
        check = f"{doubts.unit} {check}"
    kept = "; ".join(f"{n} at the value model {model} computes for each row, its default"
                     if n in computed else f"{n} at {gnum(v)}" for n, v in (held or {}).items())
    together = "; ".join(" and ".join(g) for g in groups if len(g) > 1)
    inert = [g[0] for g in groups if len(g) == 1]
    cannot = "; ".join(([f"these data cannot tell {together} apart"] if together else []) + (
        [f"{' and '.join(inert)} {'changes' if len(inert) == 1 else 'change'} {_INERT}"]
        if inert else []))
    if groups:
        # a held name's value is the fit's assumption: a misfit or a bound may be its doing,
        # not the data's
        check = (f"{cannot[0].upper()}{cannot[1:]}, so {kept.replace('; ', ', ')} "
                 "is held and the fitted values assume it: fit the held name in place of the "
                 "other, or hold it at a value from the literature (--param, or the request's "
                 f"params). {check}")
    if not sol.success:
        return {"status": "failed", "message": (
            f"the fit stopped after {sol.nfev} evaluations without converging (rms relative "
            f"residual {rms_text} %): start it nearer the answer (NAME=START) or fit fewer "
            "names")}
    if slips:
        ended = at_bound or at_upper
        bound = (f"; {', '.join(ended)} ended at {'a' if len(ended) == 1 else 'their'} bound "
                 "trying to meet them" if ended else "")
        return {"status": "warning", "message": (
            f"{len(slips)} of {len(r)} measured values have the other sign than the fit's "
            f"(rms relative residual {rms_text} %{bound}): {'; '.join(slips)}")}
    if at_upper:
        own = own_limit or {}
        names = ", ".join(at_upper)
        verb = "ends" if len(at_upper) == 1 else "end"
        if not any(n in own for n in at_upper):
            where = ", far beyond any published value"
        elif len(at_upper) == 1:
            where = f" ({own[at_upper[0]]:g}, its own limit)"
        else:
            where = " (" + "; ".join(f"{n}: {own[n]:g}, its own limit" if n in own else
                                     f"{n}: far beyond any published value"
                                     for n in at_upper) + ")"
        return {"status": "warning", "message": (
            f"{names} {verb} at the largest value model {model} takes{where} (the "
            f"data would take it higher), and the fit misses the measurements by {rms_text} % "
            f"(rms relative residual). {check}")}
    if at_bound:
        names = ", ".join(at_bound)
        verb, it = ("ends", "it") if len(at_bound) == 1 else ("end", "them")
        bounds = {(lowest or {}).get(n, 0.0) for n in at_bound}
        bound = (f"the bound {bounds.pop():g}" if len(bounds) == 1 else "their bounds (" +
                 "; ".join(f"{n}: {(lowest or {}).get(n, 0.0):g}" for n in at_bound) + ")")
        head = (f"{names} {verb} at {bound} (the data would take {it} below, which model "
                f"{model} does not allow)")
        if rms > MISFIT_PCT:
            return {"status": "warning", "message": (
                f"{head} and the fit still misses the measurements by {rms_text} % (rms "
                f"relative residual). {check}")}
        if len(sol.x) == len(at_bound):
            # nothing else was fitted to take its part: the data ask for a value past the
            # bound, which a meter reading a few per cent off also asks (DIN's C made at 1 and
            # read 2 % low), not for no value
            return {"status": "warning", "message": (
                f"{head}; at the bound the fit meets the measurements to {rms_text} % (rms "
                f"relative residual): they ask for {it} past what model {model} allows, as a "
                f"meter reading a few per cent off would. {check}")}
        return {"status": "warning", "message": (
            f"{head}; the fit matches the measurements to {rms_text} % (rms relative residual) "
            f"without {it}: these data do not determine {names}. Hold {it} at a value from "
            "the literature (--param, or the request's params) and fit the others")}
    if suspect:
        return {"status": "warning", "message": (
            f"converged (rms relative residual {rms_text} % over {_values(len(r))}), "
            f"but some readings disagree with the others: {'; '.join(suspect)}")}
    if rms > MISFIT_PCT:
        return {"status": "warning", "message": (
            f"converged, but the fit misses the measurements by {rms_text} % (rms relative "
            f"residual over {_values(len(r))}; a plant's logged power is good to a few "
            f"per cent, {MISFIT_PCT:g} % at most). {check}")}
    if groups:
        at = "" if set(held or {}) <= set(computed) else " at the start"
        return {"status": "warning", "message": (
            f"converged (rms relative residual {rms_text} % over {_values(len(r))}), "
            f"but {cannot}: held{at} ({kept})" + (
                ", and the fitted values assume it. Hold the held names at values from the "
                "literature (--param, or the request's params) and fit the others, or, where "
                "the model lets them act apart, measure at other loads, speeds or temperatures"
                if together else ". Fit a parameter these rows move, or measure in the states "
                "where it acts"))}
    if few:
        errors = ("no degrees of freedom are left (a row's power_kw and te_kn are one "
                  "reading): no standard errors" if exact else
                  "the standard errors tell only how the repeated readings agree, not how the "
                  "model fits the plant (copies of one row agree exactly, a standard error of 0)")
        return {"status": "warning", "message": (
            f"converged, but the {len(r)} measured values read only as many steady states as "
            f"fitted names ({few}): those states are met whatever the model, and {errors}. "
            f"Measure at least one more steady state ({_another_state(model)}), or fit "
            "fewer names")}
    if exact:
        return {"status": "warning", "message": (
            f"converged, but {_values(len(r))} for as many fitted names "
            f"{'is' if len(r) == 1 else 'are'} met exactly whatever their errors: nothing is left to check the fit against and it "
            "has no standard errors. Measure at least one more steady state "
            f"({_another_state(model)}), or fit fewer names")}
    return {"status": "ok", "message": f"converged: rms relative residual {rms_text} % over "
            f"{_values(len(r))}"}


def _another_state(model: str) -> str:
    """What makes another steady state for ``model``: another load or temperature, or another
    load only where the model has no temperature term (DIN computes 10 and 30 C alike)."""
    try:
        temp = get_model(model).temperature_term
    except InputError:
        temp = True
    return ("another load or temperature" if temp else
            f"another load or speed: {model} has no temperature term")


def _jacobian(fun, x: np.ndarray, lower: Sequence[float] | None = None) -> np.ndarray:
    """Central-difference Jacobian of ``fun`` at ``x`` (relative step :data:`DIFF_STEP`),
    one-sided where a step below would pass a parameter's ``lower`` bound (default 0)."""
    if not len(x):  # nothing fitted (every name held): a Jacobian of no columns
        return np.zeros((len(fun(x)), 0))
    cols = []
    for k in range(len(x)):
        h = DIFF_STEP * max(abs(x[k]), 1e-6)
        lo, hi = x.copy(), x.copy()
        lo[k] = max(x[k] - h, 0.0 if lower is None else lower[k])
        hi[k] = x[k] + h
        cols.append((fun(hi) - fun(lo)) / (hi[k] - lo[k]))
    return np.column_stack(cols)


def _unit_columns(jac: np.ndarray) -> np.ndarray:
    norms = np.linalg.norm(jac, axis=0)
    return jac / np.where(norms > 0, norms, 1.0)


def _identifiable(fun, x0: np.ndarray, names: list[str], lower: Sequence[float] | None = None
                  ) -> tuple[list[str], list[str], list[list[str]]]:
    """The names the data identify (in the order named), those held, and each held name's
    group: the named parameters it only acts together with (the Jacobian's null vector)."""
    jac = _unit_columns(_jacobian(fun, x0, lower) * np.where(x0 != 0, x0, 1.0))
    free: list[int] = []
    held: list[str] = []
    groups: list[list[str]] = []
    for k, name in enumerate(names):
        trial = jac[:, [*free, k]]
        if not np.any(trial[:, -1]):
            held.append(name)
            groups.append([name])
            continue
        # fewer residuals than names: the last one named cannot be told apart (its null
        # vector exists; the full decomposition gives it)
        _, s, vt = np.linalg.svd(trial, full_matrices=True)
        if trial.shape[1] <= trial.shape[0] and s[-1] >= RCOND * s[0]:
            free.append(k)
            continue
        null = np.abs(vt[-1])
        held.append(name)
        groups.append([names[j] for j, w in zip([*free, k], null, strict=True)
                       if w > 0.1 * null.max()])
    return [names[k] for k in free], held, groups
