"""The design basis of a study: every ``auto`` size computed once per conveyor design, then held.

A study compares one installed design, so an ``auto`` field of the conveyor file (take-up
``mass_kg`` or ``pretension_kn``, a drive's ``rated_power_kw``, a brake's ``force_kn``) must not
be sized again in every run. A *conveyor design* is one combination of the study's conveyor
axes (one resolved conveyor). Its sizes come from :func:`beltstudy.engine.design.auto_sizes` at its
*design cases*, the largest requirement kept:

* default: every friction model (with its parameters) and temperature the study runs on that
  design, at full load;
* ``design: {friction_model, temperature_c, load}`` pins what it names (the rest is still the
  largest over the study's values).

A brake's sizing input is its stop time: for each stop time of the design's brake-stop runs
the brake force is the largest over the same cases (models, temperatures) and held over them
and over the load cases; a run that does not stop on its brakes (coast, controlled, or steady
only) installs the holding size, the part of the sizing that needs no stop time.

The numbers are written into each run's conveyor (rounded up to six significant digits, so a
size never falls short by rounding), so a run id reflects the design it ran.
"""

from __future__ import annotations

import copy
import dataclasses
import math
from dataclasses import dataclass
from typing import Any

from pydantic import BaseModel, ConfigDict, Field

from beltstudy.engine.conveyor import Conveyor, InputError, Scenario, parse_scenario, section_loads
from beltstudy.engine.design import auto_sizes
from beltstudy.engine.friction import get_model
from beltstudy.engine.statics import solve_steady
from beltstudy.service.errors import Invalid

__all__ = ["DesignIn", "Case", "has_auto", "size_design", "apply_sizes", "round_up",
           "SIG_DIGITS"]

#: Significant digits of a size written into a run's conveyor (rounded up).
SIG_DIGITS = 6


class DesignIn(BaseModel):
    """The ``design`` field of a study: where the auto sizes are computed (SPEC 6.3)."""

    model_config = ConfigDict(extra="forbid")

    friction_model: str | None = Field(None, description="friction model of the design case")
    temperature_c: float | None = Field(None, description="temperature of the design case [C]")
    load: Any = Field(None, description="load case of the design case (default full)")


@dataclass(frozen=True)
class Case:
    """One design case: a friction model with its parameter overrides and a scenario."""

    model: str
    params: tuple[tuple[str, float | None], ...]
    temperature_c: float
    elements: Any

    def label(self) -> str:
        defaults = dataclasses.asdict(get_model(self.model).params())
        changed = [f"{k}={v:g}" for k, v in self.params
                   if v is not None and defaults.get(k) != v]
        model = self.model + (f" ({', '.join(changed)})" if changed else "")
        return f"{model}, {self.temperature_c:g} C"


def round_up(x: float, digits: int = SIG_DIGITS) -> float:
    """``x`` rounded up to ``digits`` significant digits (0 and negatives unchanged)."""
    if not (x > 0.0) or not math.isfinite(x):
        return float(x)
    q = 10.0 ** (math.floor(math.log10(x)) - (digits - 1))
    value = float(f"{math.ceil(x / q - 1e-9) * q:.{digits}g}")
    return value if value >= x * (1.0 - 1e-12) else float(f"{value + q:.{digits}g}")


def has_auto(conv: dict) -> bool:
    """Whether a (dumped) conveyor has any auto size."""
    tu = conv["takeup"]
    return (
        (tu["type"] == "gravity" and tu["mass_kg"] == "auto")
        or (tu["type"] == "fixed" and tu["pretension_kn"] == "auto")
        or any(d.get("rated_power_kw") is None for d in conv["drives"])
        or any(b.get("force_kn") == "auto" for b in conv.get("brakes") or [])
    )


def design_scenario(design: DesignIn | None, base: dict) -> Scenario:
    """The design load checked as a scenario field (names ``design.load``)."""
    load = "full" if design is None or design.load is None else design.load
    try:
        return parse_scenario({**base, "load": load}, prefix="design.")
    except InputError as exc:
        raise Invalid(str(exc)) from None


def _largest(items: list[tuple[float, str, Case]]) -> tuple[float, str, Case]:
    best = items[0]
    for item in items[1:]:
        if item[0] > best[0]:
            best = item
    return best


def size_design(conv: Conveyor, cases: list[Case], load, stop_times: list[float],
                where: str = "") -> dict:
    """The auto sizes of one conveyor design: the largest over ``cases`` at ``load``.

    Returns a JSON-able mapping: ``takeup`` (``{value, unit, field, governed_by, case}``) or
    None, ``drives`` (one entry per drive, None where the file gives the rated power),
    ``brakes`` (``{"holding": {...}, "stop_time_s": {"<t>": {...}}}`` with ``force_kn`` per
    brake, ``governed_by`` and ``case``) or None.
    """

    data = conv.model_dump(mode="json", by_alias=True)
    tu = data["takeup"]
    tu_auto = (tu["type"] == "gravity" and tu["mass_kg"] == "auto") or (
        tu["type"] == "fixed" and tu["pretension_kn"] == "auto")
    drive_auto = [d["rated_power_kw"] is None for d in data["drives"]]
    brake_auto = any(b["force_kn"] == "auto" for b in data.get("brakes") or [])
    try:
        section_loads(load, conv)
    except InputError as exc:
        raise Invalid(f"design.load: {exc.reason}"
                      + (f" (conveyor design {where})" if where else "")) from None

    takeups, rated, holding = [], [[] for _ in drive_auto], []
    by_stop: dict[float, list] = {t: [] for t in stop_times}
    failures = []
    for case in cases:
        scn = Scenario(load=load, temperature_c=case.temperature_c, elements=case.elements)
        n = None if case.elements == "auto" else int(case.elements)
        params = dict(case.params)
        steady = solve_steady(conv, model=case.model, params=params,
                              temperature_c=case.temperature_c, load=load, n_elements=n)
        if steady.status == "failed":
            failures.append(f"{case.label()}: {steady.message}")
            continue
        sizes = auto_sizes(conv, scn, model=case.model, params=params, steady=steady)
        if tu_auto:
            value = (sizes["takeup_mass_kg"] if tu["type"] == "gravity"
                     else sizes["takeup_pretension_kn"])
            takeups.append((value, sizes["takeup_governed_by"], case))
        for i, auto in enumerate(drive_auto):
            if auto:
                rated[i].append((sizes["drive_rated_power_kw"][i],
                                 sizes["drive_rated_power_governed_by"][i], case))
        if brake_auto:
            holding.append((sum(sizes["brake_force_kn"]), sizes, case))
            for t in stop_times:
                braked = auto_sizes(conv, scn.model_copy(update={
                    "stop": scn.stop.model_copy(update={"mode": "brake", "time_s": t})}),
                    model=case.model, params=params, steady=steady)
                by_stop[t].append((sum(braked["brake_force_kn"]), braked, case))
    if len(failures) == len(cases):
        where_text = f" of conveyor design {where}" if where else ""
        raise Invalid(f"design: the steady solve failed at every design case{where_text}, so "
                      f"nothing can be sized: {failures[0]}")

    where_text = f" (conveyor design {where})" if where else ""
    for name, items in (("takeup", takeups), *((f"drives.{i}.rated_power_kw", r)
                                              for i, r in enumerate(rated)),
                        ("brakes", holding), *(("brakes", v) for v in by_stop.values())):
        for value, _why, case in items:
            if not math.isfinite(value):
                raise Invalid(f"design: the auto size of {name} is not finite at "
                              f"{case.label()}{where_text}; check sag_limit_pct, the drives' "
                              "friction and wrap")
    out: dict[str, Any] = {"takeup": None, "drives": [None] * len(drive_auto), "brakes": None,
                           "failed_cases": failures}
    if tu_auto:
        value, why, case = _largest(takeups)
        gravity = tu["type"] == "gravity"
        out["takeup"] = {"field": "mass_kg" if gravity else "pretension_kn",
                         "value": round_up(value), "unit": "kg" if gravity else "kN",
                         "governed_by": why, "case": case.label()}
    for i, items in enumerate(rated):
        if items:
            value, why, case = _largest(items)
            out["drives"][i] = {"rated_power_kw": round_up(value), "governed_by": why,
                                "case": case.label()}
    if brake_auto:
        def brake_entry(items):
            _total, sizes, case = _largest(items)
            return {"force_kn": [max(round_up(f), 1e-3) for f in sizes["brake_force_kn"]],
                    "governed_by": [g for g in sizes["brake_governed_by"]],
                    "case": case.label()}

        out["brakes"] = {"holding": brake_entry(holding),
                         "stop_time_s": {f"{t:g}": brake_entry(items)
                                         for t, items in by_stop.items()}}
    return out


def apply_sizes(conv: dict, sizes: dict | None, scenario: dict, dynamics: bool
                ) -> tuple[dict, dict]:
    """A run's conveyor with the design's sizes written in, and its ``*_governed_by`` fields.

    ``conv`` is the run's (dumped) conveyor with its auto fields; ``scenario`` the run's
    scenario: a brake-stop run of a dynamic study gets the brake sized for its stop time, any
    other run the holding size.
    """
    if not sizes:
        return conv, {}
    out = copy.deepcopy(conv)
    governed: dict[str, str] = {}
    tu = sizes.get("takeup")
    if tu is not None:
        out["takeup"][tu["field"]] = tu["value"]
        governed["takeup_governed_by"] = tu["governed_by"]
    why = []
    for drive, size in zip(out["drives"], sizes.get("drives") or [], strict=False):
        if size is not None and drive.get("rated_power_kw") is None:
            drive["rated_power_kw"] = size["rated_power_kw"]
            why.append(size["governed_by"])
        else:
            why.append("given")
    if any(w != "given" for w in why):
        governed["rated_power_governed_by"] = "+".join(dict.fromkeys(why))
    brakes = sizes.get("brakes")
    if brakes is not None:
        entry = brakes["holding"]
        stop = scenario.get("stop") or {}
        if dynamics and stop.get("mode") == "brake":
            entry = brakes["stop_time_s"].get(f"{float(stop.get('time_s')):g}", entry)
        why = []
        for brake, force, reason in zip(out["brakes"], entry["force_kn"], entry["governed_by"],
                                        strict=True):
            if brake["force_kn"] == "auto":
                brake["force_kn"] = force
                why.append(reason)
            else:
                why.append("given")
        governed["brake_governed_by"] = "+".join(dict.fromkeys(why))
    return out, governed
