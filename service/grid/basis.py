"""The design basis of a study: every ``auto`` size computed once per conveyor design, then held.

A study compares one installed design, so an ``auto`` field of the conveyor file (take-up
``mass_kg`` or ``pretension_kn``, a drive's ``rated_power_kw``, a brake's ``force_kn``) must not
be sized again in every run. A *conveyor design* is one combination of the study's conveyor
axes (one resolved conveyor). Its sizes come from the engine's
:func:`beltstudy.engine.size_over_cases` at its *design cases*, the largest requirement kept
(this module says which cases a study's ``design:`` names, and writes the sizes into each run's
conveyor):

* default: every friction model (with its parameters) and temperature the study runs on that
  design, at full load;
* ``design: {friction_model, temperature_c, load}`` pins what it names (the rest is still the
  largest over the study's values). Each may be a list (SPEC 7.2): the design cases are then
  every combination of the listed loads, models and temperatures (the design envelope), and
  each size is the largest over them. A run's ``*_governed_by`` names the constraint and the
  case that set its size, by what varies among the design's cases
  (``brake: stop_time @ declines``: :func:`beltstudy.engine.governed_at`).

A list of loads is told from one load per profile section (also a list, SPEC 6.2) by its
entries: a list holding a named load case (``full``, ``empty``, ``inclines``, ``declines``) or
a per-section list is a list of load cases; a list of numbers only is one load per section.

A brake's sizing input is its stop time: for each stop time of the design's brake-stop runs
the brake force is the largest over the same cases (models, temperatures) and held over them
and over the load cases; a run that does not stop on its brakes (coast, controlled, or steady
only) installs the holding size, the part of the sizing that needs no stop time.

``belt.type: auto`` is a design value too: the lightest catalogue belt that passes at every
design case, chosen first (:func:`design_belt`), the other sizes then sized on it.

The numbers are written into each run's conveyor (rounded up to six significant digits, so a
size never falls short by rounding), so a run id reflects the design it ran.
"""

from __future__ import annotations

import math
from typing import Any

from pydantic import BaseModel, ConfigDict, Field

from beltstudy.engine import (
    BELT_AUTO,
    GIVEN,
    BrakeSizes,
    Conveyor,
    DesignCase,
    InputError,
    SizingError,
    brake_sizing_stop_time,
    design_cases,
    get_model,
    governed_at,
    parse_scenario,
    section_loads,
    select_belt,
    size_over_cases,
    with_belt,
)
from beltstudy.engine.conveyor import (
    FORCE_MAX_KN,
    POWER_MAX_KW,
    PRETENSION_MAX_KN,
    TAKEUP_MASS_MAX_KG,
)
from beltstudy.service.errors import Invalid

__all__ = ["DesignIn", "has_auto", "size_design", "apply_sizes", "round_up", "round_down",
           "SIG_DIGITS", "design_loads", "design_models", "design_temperatures", "check_design_loads",
           "check_design_once"]

#: Significant digits of a size written into a run's conveyor (rounded up).
SIG_DIGITS = 6


class DesignIn(BaseModel):
    """The ``design`` field of a study: where the auto sizes are computed (SPEC 6.3)."""

    model_config = ConfigDict(extra="forbid")

    friction_model: str | list[str] | None = Field(
        None, description="friction model of the design cases, or a list of them")
    temperature_c: float | list[float] | None = Field(
        None, description="temperature of the design cases [C], or a list of them")
    load: Any = Field(None, description="load case of the design cases (default full), or a "
                      "list of load cases: full, empty, inclines, declines, a fraction, one "
                      "fraction per profile section")


def round_up(x: float, digits: int = SIG_DIGITS) -> float:
    """``x`` rounded up to ``digits`` significant digits (0 and negatives unchanged)."""
    if not (x > 0.0) or not math.isfinite(x):
        return float(x)
    q = 10.0 ** (math.floor(math.log10(x)) - (digits - 1))
    value = float(f"{math.ceil(x / q - 1e-9) * q:.{digits}g}")
    return value if value >= x * (1.0 - 1e-12) else float(f"{value + q:.{digits}g}")


def round_down(x: float, digits: int = SIG_DIGITS) -> float:
    """``x`` rounded down to ``digits`` significant digits (0 and negatives unchanged): a size
    that is a ceiling (a brake held at its pulley's grip) must not rise past it by rounding."""
    if not (x > 0.0) or not math.isfinite(x):
        return float(x)
    q = 10.0 ** (math.floor(math.log10(x)) - (digits - 1))
    value = float(f"{math.floor(x / q + 1e-9) * q:.{digits}g}")
    return value if value <= x * (1.0 + 1e-12) else float(f"{value - q:.{digits}g}")


def has_auto(conv: dict) -> bool:
    """Whether a (dumped) conveyor has any auto size."""
    tu = conv["takeup"]
    return (
        (tu["type"] == "gravity" and tu["mass_kg"] == "auto")
        or (tu["type"] == "fixed" and tu["pretension_kn"] == "auto")
        or any(d.get("rated_power_kw") is None for d in conv["drives"])
        or any(b.get("force_kn") == "auto" for b in conv.get("brakes") or [])
        or conv["belt"].get("type") == BELT_AUTO
    )


def _field(design: DesignIn | dict | None, name: str) -> Any:
    if design is None:
        return None
    return design.get(name) if isinstance(design, dict) else getattr(design, name)


def _entries(value: Any, name: str) -> list[tuple[str, Any]]:
    """``(field path, value)`` of each entry of a design field that may be a list."""
    if isinstance(value, list):
        if not value:
            raise Invalid(f"design.{name}: an empty list; give at least one value or leave "
                          f"{name} out")
        return [(f"design.{name}[{i}]", v) for i, v in enumerate(value)]
    return [(f"design.{name}", value)]


def _at(msg: str, name: str, where: str) -> str:
    """A scenario field's message (``load: ...; load.0: ...``, one part per problem) with each
    part's field path ``name`` put at ``where`` in the study (``design.load``,
    ``design.load.0``)."""
    parts = msg.split("; ")
    if not parts[0].startswith(name):
        return f"{where}: {msg}"
    return "; ".join(where + p[len(name):] if p.startswith((name + ":", name + ".")) else p
                     for p in parts)


def _is_case_list(load: Any) -> bool:
    """A list of load cases (it holds a named case or a per-section list), not one load per
    profile section (numbers only)."""
    return isinstance(load, list) and any(isinstance(x, str | list) for x in load)


def design_loads(design: DesignIn | dict | None) -> list[tuple[str, Any]]:
    """The design's load cases as ``(field path, load)``, each checked as a scenario load
    (default ``[("design.load", "full")]``); a bad entry is refused naming its place
    (``design.load[1]``)."""
    load = _field(design, "load")
    if load is None:
        return [("design.load", "full")]
    entries = _entries(load, "load") if _is_case_list(load) or load == [] else [
        ("design.load", load)]
    out = []
    for where, value in entries:
        try:
            out.append((where, parse_scenario({"load": value}).load))
        except InputError as exc:
            raise Invalid(_at(str(exc), "load", where)) from None
    return out


def design_models(design: DesignIn | dict | None) -> list[str] | None:
    """The design's friction models, canonical (None: the study's own)."""
    value = _field(design, "friction_model")
    if value is None:
        return None
    out = []
    for where, name in _entries(value, "friction_model"):
        try:
            out.append(get_model(name).name)
        except InputError as exc:
            raise Invalid(f"{where}: {exc.reason}") from None
    return list(dict.fromkeys(out))


def design_temperatures(design: DesignIn | dict | None) -> list[float] | None:
    """The design's temperatures [C], each checked as a scenario's (None: the study's own)."""
    value = _field(design, "temperature_c")
    if value is None:
        return None
    out = []
    for where, t in _entries(value, "temperature_c"):
        try:
            out.append(float(parse_scenario({"temperature_c": t}).temperature_c))
        except InputError as exc:
            raise Invalid(_at(str(exc), "temperature_c", where)) from None
    return list(dict.fromkeys(out))


#: Load cases by name that are one fraction of the design load everywhere.
_LOAD_FRACTIONS = {"full": 1.0, "empty": 0.0}


def check_design_once(design: DesignIn | dict | None) -> None:
    """Refuse a design list that names one case twice (as a grid axis lists each value
    once): a model by an alias, a temperature as -20 and -20.0, a load as full and 1.0. Each
    entry is checked first (:func:`design_loads`, :func:`design_models`,
    :func:`design_temperatures`); called at the door only, so a stored study is read as it
    was accepted."""
    def canon(name: str, value: Any) -> Any:
        if name == "friction_model":
            return get_model(value).name
        if name == "temperature_c":
            return float(value) + 0.0  # -0.0 is 0.0
        load = parse_scenario({"load": value}).load
        return _LOAD_FRACTIONS.get(load, load) if isinstance(load, str) else load

    for name in ("load", "friction_model", "temperature_c"):
        value = _field(design, name)
        if not isinstance(value, list) or (name == "load" and not _is_case_list(value)):
            continue
        seen: dict[str, int] = {}
        for j, entry in enumerate(value):
            key = repr(canon(name, entry))
            i = seen.setdefault(key, j)
            if i == j:
                continue
            first = value[i]
            named = "" if repr(first) == repr(entry) else f" ({first!r})"
            alias = (" (aliases count as the same)" if name == "friction_model" and named
                     else "")
            raise Invalid(f"design.{name}[{j}]: {entry!r} is design.{name}[{i}]{named} again"
                          f"{alias}; give each design case once")


def check_design_loads(conv: Conveyor, design: DesignIn | dict | None, where: str = "") -> None:
    """Refuse a design load that does not fit the conveyor's profile, naming its place."""
    for path, load in design_loads(design):
        try:
            section_loads(load, conv)
        except InputError as exc:
            hint = ("; a list of numbers is one load per profile section: a list of load "
                    "cases names at least one (full, empty, inclines, declines)"
                    if path == "design.load" and isinstance(load, list) else "")
            tail = f" (conveyor design {where})" if where else ""
            raise Invalid(f"{path}: {exc.reason}{hint}{tail}") from None


def size_design(conv: Conveyor, cases: list[DesignCase], stop_times: list[float],
                where: str = "") -> dict:
    """The auto sizes of one conveyor design: the largest over ``cases``, each at its own load
    (:func:`beltstudy.engine.size_over_cases`), rounded up as a run's conveyor holds them.

    Returns a JSON-able mapping: ``takeup`` (``{value, unit, field, governed_by, case, at}``)
    or None, ``drives`` (one entry per drive, None where the file gives the rated power),
    ``brakes`` (``{"holding": {...}, "stop_time_s": {"<t>": {...}}}`` with ``force_kn`` per
    brake, ``governed_by``, ``case`` and ``at``) or None, ``failed_cases``. ``case`` is the
    full case (load, model, temperature), ``at`` the case by what varies among ``cases``
    ("" for one case).
    """
    conv, belt = design_belt(conv, cases)
    try:
        sized = size_over_cases(conv, cases, stop_times=stop_times, design=where)
    except SizingError as exc:  # named as the study's design case
        raise Invalid(f"design.{exc.field}: {exc.reason}" if exc.field
                      else f"design: {exc.reason}") from None
    out: dict[str, Any] = {"takeup": None, "drives": [None] * len(sized.drives),
                           "brakes": None, "failed_cases": list(sized.failed_cases),
                           "belt": belt}
    if sized.takeup is not None:
        gravity = conv.takeup.type == "gravity"
        out["takeup"] = {"field": "mass_kg" if gravity else "pretension_kn",
                         "value": round_up(sized.takeup.value), "unit": "kg" if gravity else "kN",
                         "governed_by": sized.takeup.governed_by,
                         "case": sized.takeup.case.label(), "at": sized.takeup.at}
    for i, drive in enumerate(sized.drives):
        if drive is not None:
            out["drives"][i] = {"rated_power_kw": round_up(drive.value),
                                "governed_by": drive.governed_by, "case": drive.case.label(),
                                "at": drive.at}
    if sized.brakes_holding is not None:
        out["brakes"] = {"holding": _brake_entry(sized.brakes_holding),
                         "stop_time_s": {f"{t:g}": _brake_entry(b)
                                         for t, b in sized.brakes_by_stop.items()}}
    return out


def design_belt(conv: Conveyor, cases: list[DesignCase]) -> tuple[Conveyor, dict | None]:
    """The conveyor on its design belt and the choice as JSON (None for a given belt):
    ``belt.type: auto`` is a design value, the lightest catalogue belt that passes at every
    design case, each at its own load (and at full load,
    :func:`beltstudy.engine.design_cases`), chosen once here and held for all the design's
    runs; the take-up, motors and brakes are sized on it."""
    if conv.belt.type != BELT_AUTO:
        return conv, None
    choice = select_belt(conv, design_cases(conv, cases, "full"))
    c, lighter = choice.chosen, choice.lighter
    return with_belt(conv, choice.belt_id), {
        "type": choice.belt_id, "kind": choice.kind, "passed": choice.passed,
        "mass_kg_m": c.mass_kg_m, "safety_factor": c.safety_factor,
        "safety_factor_start": c.safety_factor_start, "case": c.case,
        "next_lighter": None if lighter is None else {
            "type": lighter.id, "mass_kg_m": lighter.mass_kg_m,
            "safety_factor": lighter.safety_factor,
            "safety_factor_start": lighter.safety_factor_start},
        "note": choice.note() or choice.warning()}


def _brake_entry(brakes: BrakeSizes) -> dict:
    # a force held at its pulley's grip is the most the pulley passes: rounded down, as every
    # other size (a least need) is rounded up; rounded up, the grip size at its own case was
    # beyond the grip (59.3205 kN set against 59.32052 kN passed) and its run said so
    forces, why = list(brakes.force_kn), list(brakes.governed_by)
    held = [k for k, w in enumerate(why) if w == "holding"]
    # a holding force shared by the pulleys' grip (engine.design: an even share is beyond one
    # pulley's grip): the brakes below the even share sit at their grip, rounded down too,
    # what that takes off going to the others (rounded up) so the brakes still hold the belt
    at_grip: set[int] = set()
    if len(held) > 1:
        even = sum(forces[k] for k in held) / len(held)
        at_grip = {k for k in held if forces[k] < even * (1.0 - 1e-9)}
    others = [k for k in held if k not in at_grip]
    if at_grip and others:
        taken = sum(forces[k] - round_down(forces[k]) for k in at_grip)
        for k in others:
            forces[k] += taken / len(others)
    return {"force_kn": [max(round_down(f) if w == "grip" or k in at_grip else round_up(f),
                             1e-3)
                         for k, (f, w) in enumerate(zip(forces, why, strict=True))],
            "governed_by": list(brakes.governed_by), "case": brakes.case.label(),
            "at": brakes.at}


def apply_sizes(conv: dict, sizes: dict | None, scenario: dict, dynamics: bool
                ) -> tuple[dict, dict]:
    """A run's conveyor with the design's sizes written in, and its ``*_governed_by`` fields.

    ``conv`` is the run's (dumped) conveyor with its auto fields; ``scenario`` the run's
    scenario: a brake-stop run of a dynamic study gets the brake sized for its stop time, any
    other run the holding size.
    """
    if not sizes:
        return conv, {}
    # copies of the parts sizes are written into; the rest is shared with ``conv`` (read only)
    out = {**conv, "belt": dict(conv["belt"]), "takeup": dict(conv["takeup"]),
           "drives": [dict(d) for d in conv["drives"]],
           "brakes": [dict(b) for b in conv.get("brakes") or []]}
    governed: dict[str, str] = {}
    if sizes.get("belt") is not None and out["belt"].get("type") == BELT_AUTO:
        out["belt"]["type"] = sizes["belt"]["type"]
    tu = sizes.get("takeup")
    # a sampled study's take-up may be drawn: only an auto field gets the design's size; a
    # size beyond what a file may give (no counterweight or screw holds it) stays auto, so
    # the run sizes its own and says what sets it and what would avoid it
    if tu is not None and out["takeup"][tu["field"]] == "auto" and tu["value"] <= (
            TAKEUP_MASS_MAX_KG if tu["field"] == "mass_kg" else PRETENSION_MAX_KN):
        out["takeup"][tu["field"]] = tu["value"]
        governed["takeup_governed_by"] = governed_at(tu["governed_by"], tu.get("at", ""))
    why, kept = [], False
    for drive, size in zip(out["drives"], sizes.get("drives") or [], strict=False):
        # a size beyond what a file may give stays auto, as the take-up's does: the run sizes
        # its own and says what sets it (and its own *_governed_by then names it)
        if size is not None and drive.get("rated_power_kw") is None:
            if size["rated_power_kw"] > POWER_MAX_KW:
                kept = True
                continue
            drive["rated_power_kw"] = size["rated_power_kw"]
            why.append(governed_at(size["governed_by"], size.get("at", "")))
        else:
            why.append(GIVEN)
    if any(w != GIVEN for w in why) and not kept:
        governed["rated_power_governed_by"] = "+".join(dict.fromkeys(why))
    brakes = sizes.get("brakes")
    if brakes is not None:
        entry = brakes["holding"]
        stop_s = brake_sizing_stop_time(scenario, dynamics=dynamics)
        if stop_s is not None:
            entry = brakes["stop_time_s"].get(f"{stop_s:g}", entry)
        why, kept = [], False
        for brake, force, reason in zip(out["brakes"], entry["force_kn"], entry["governed_by"],
                                        strict=True):
            if brake["force_kn"] == "auto" and force > FORCE_MAX_KN:
                kept = True  # stays auto, as a motor beyond its bound does
            elif brake["force_kn"] == "auto":
                brake["force_kn"] = force
                why.append(governed_at(reason, entry.get("at", "")))
            else:
                why.append(GIVEN)
        if not kept:
            governed["brake_governed_by"] = "+".join(dict.fromkeys(why))
    return out, governed
