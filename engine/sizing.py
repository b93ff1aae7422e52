"""The auto sizes of one conveyor design over a list of design cases: the largest of each.

An installed conveyor has one take-up, one motor per drive and one set of brakes, however many
operating cases it meets. :func:`size_over_cases` solves the steady state at every
:class:`DesignCase` (load case, friction model with its parameters, temperature, mesh), sizes
each ``auto`` field there with :func:`beltstudy.engine.design.auto_sizes`, and keeps the
largest requirement of each size with what set it (``governed_by``) and at which case: the
design envelope (SPEC 7.2). ``at`` names that case by what varies among the cases (the load,
the model, the temperature: ``declines``, ``declines, -20 C``), "" when only one case is
sized, and :func:`governed_at` joins the two as a run's ``*_governed_by`` states them
(``stop_time @ declines``).

Brakes: their sizing input is the stop time (:mod:`beltstudy.engine.design`). The holding size
(no stop time) is the largest over the cases; for each stop time of ``stop_times`` the size
for a brake stop in that time is the largest over the same cases, held within what the braked
pulleys pass in the stop at every case (``grip`` at the case of the least,
:mod:`beltstudy.engine.stopgrip`).

A case whose steady solve fails is skipped and named in ``failed_cases``; when every case
fails, or a size is not finite, nothing can be sized and :class:`SizingError` says why.
"""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Sequence
from dataclasses import dataclass
from typing import Any

from beltstudy.engine.conveyor import Conveyor, Scenario, section_loads
from beltstudy.engine.design import GIVEN, auto_sizes, brake_kn_within_grip
from beltstudy.engine.errors import InputError
from beltstudy.engine.friction import get_model
from beltstudy.engine.statics import solve_steady

__all__ = ["DesignCase", "Largest", "BrakeSizes", "DesignSizes", "SizingError",
           "size_over_cases", "load_label", "governed_at"]


class SizingError(InputError):
    """A design that cannot be sized over its cases: its load does not fit the profile
    (``field="load"``), the steady solve failed at every case, or a size is not finite."""


def load_label(load: Any) -> str:
    """A load case in words: ``full``, ``declines``, ``load 0.8``, ``load [1, 0.5]``."""
    if isinstance(load, str):
        return load
    if isinstance(load, list | tuple):
        return "load [" + ", ".join(f"{float(x):g}" for x in load) + "]"
    return f"load {float(load):g}"


def governed_at(governed_by: str, at: str) -> str:
    """A size's ``*_governed_by`` with its case: ``stop_time @ declines`` (SPEC 7.2); the
    constraint alone when ``at`` is "" (one design case) or the size is given."""
    return f"{governed_by} @ {at}" if at and governed_by != GIVEN else governed_by


@dataclass(frozen=True)
class DesignCase:
    """One design case: a friction model with its parameter overrides, a temperature, the
    mesh of the steady solve and a load case (SPEC 6.2; a per-section list is held as a
    tuple so the case can be a key)."""

    model: str
    params: tuple[tuple[str, float | None], ...] = ()  # (name, value) overrides, sorted
    temperature_c: float = 20.0  # [C]
    elements: Any = "auto"  # element count, or "auto"
    load: Any = "full"  # full | empty | inclines | declines | a fraction | per-section tuple
    #: name the model in ``at`` even where every case has it: a study whose ``design:`` pins
    #: the model sizes its runs of other models by it (not part of the case's identity)
    name_model: bool = dataclasses.field(default=False, compare=False)

    def __post_init__(self) -> None:
        if isinstance(self.load, list):
            object.__setattr__(self, "load", tuple(self.load))

    @property
    def load_case(self) -> Any:
        """The load as a scenario takes it (a per-section load as a list)."""
        return list(self.load) if isinstance(self.load, tuple) else self.load

    def _model_label(self) -> str:
        defaults = dataclasses.asdict(get_model(self.model).params())
        changed = [f"{k}={v:g}" for k, v in self.params
                   if v is not None and defaults.get(k) != v]
        return self.model + (f" ({', '.join(changed)})" if changed else "")

    def label(self) -> str:
        """``load, model (changed parameters), T C``: the case as messages and reports name
        it (``declines, din, -20 C``)."""
        return f"{load_label(self.load)}, {self._model_label()}, {self.temperature_c:g} C"

    def at(self, cases: Sequence[DesignCase], tied: Sequence[DesignCase] = ()) -> str:
        """This case named by what varies among ``cases`` (load, model with its parameters,
        temperature, in that order), "" when nothing varies (one case). ``tied``: the cases
        that need as much as this one; what varies among them is not named (a holding brake
        needs the same at every temperature: ``holding @ declines``, not ``@ declines, -20
        C``). The model is named wherever ``name_model`` is set (a model the study's
        ``design:`` pins, which its runs of other models are sized by)."""
        group = [self, *tied]
        parts = []
        for key, name, always in (
                (lambda c: c.load, load_label(self.load), False),
                (lambda c: (c.model, c.params), self._model_label(), self.name_model),
                (lambda c: c.temperature_c, f"{self.temperature_c:g} C", False)):
            if (always or len({key(c) for c in cases}) > 1) and len({key(c) for c in group}) == 1:
                parts.append(name)
        return ", ".join(parts)


@dataclass(frozen=True)
class Largest:
    """The largest requirement of one size over the cases, what set it and at which case."""

    value: float
    governed_by: str
    case: DesignCase
    at: str = ""  # the case by what varies among the design's cases (DesignCase.at)


@dataclass(frozen=True)
class BrakeSizes:
    """The brake forces [kN] (one per brake, file order) of the case that needs the largest
    total, with what set each and that case."""

    force_kn: tuple[float, ...]
    governed_by: tuple[str, ...]
    case: DesignCase
    at: str = ""  # the case by what varies among the design's cases (DesignCase.at)


@dataclass(frozen=True)
class DesignSizes:
    """The auto sizes of one conveyor design (None where the conveyor file gives the size).

    ``takeup``: ``mass_kg`` of a gravity take-up [kg] or ``pretension_kn`` of a fixed one
    [kN]; ``drives``: ``rated_power_kw`` per drive [kW]; ``brakes_holding``: the holding size;
    ``brakes_by_stop``: per stop time [s], the size for a brake stop in that time;
    ``failed_cases``: ``label: message`` of every case whose steady solve failed.
    """

    takeup: Largest | None
    drives: tuple[Largest | None, ...]
    brakes_holding: BrakeSizes | None
    brakes_by_stop: dict[float, BrakeSizes]
    failed_cases: tuple[str, ...]


@dataclass
class _Needs:
    """What each case needs, gathered before the largest is kept."""

    takeup: list = dataclasses.field(default_factory=list)
    rated: list = dataclasses.field(default_factory=list)
    holding: list = dataclasses.field(default_factory=list)
    by_stop: dict = dataclasses.field(default_factory=dict)
    failures: list = dataclasses.field(default_factory=list)
    steady: dict = dataclasses.field(default_factory=dict)  # id(case) -> its steady solution
    installed: Conveyor | None = None  # the conveyor on the installed take-up (brake stops)


def _auto_fields(conveyor: Conveyor) -> tuple[bool, list[bool], bool]:
    """Which sizes are ``auto``: the take-up, each drive's rated power, any brake."""
    data = conveyor.model_dump(mode="json", by_alias=True)
    tu = data["takeup"]
    tu_auto = (tu["type"] == "gravity" and tu["mass_kg"] == "auto") or (
        tu["type"] == "fixed" and tu["pretension_kn"] == "auto")
    drive_auto = [d["rated_power_kw"] is None for d in data["drives"]]
    brake_auto = any(b["force_kn"] == "auto" for b in data.get("brakes") or [])
    return tu_auto, drive_auto, brake_auto


def _gather(conveyor: Conveyor, cases: Sequence[DesignCase],
            stop_times: Sequence[float], auto: tuple[bool, list[bool], bool]) -> _Needs:
    """Solve and size every case; each requirement with what set it and the case."""
    tu_auto, drive_auto, brake_auto = auto
    gravity = conveyor.takeup.type == "gravity"
    needs = _Needs(rated=[[] for _ in drive_auto], by_stop={t: [] for t in stop_times})
    for case in cases:
        load = case.load_case
        scn = Scenario(load=load, temperature_c=case.temperature_c, elements=case.elements)
        n = None if case.elements == "auto" else int(case.elements)
        params = dict(case.params)
        steady = solve_steady(conveyor, model=case.model, params=params,
                              temperature_c=case.temperature_c, load=load, n_elements=n)
        if steady.status == "failed":
            needs.failures.append(f"{case.label()}: {steady.message}")
            continue
        needs.steady[id(case)] = steady
        sizes = auto_sizes(conveyor, scn, model=case.model, params=params, steady=steady)
        if tu_auto:
            value = sizes["takeup_mass_kg"] if gravity else sizes["takeup_pretension_kn"]
            needs.takeup.append((value, sizes["takeup_governed_by"], case))
        for i, auto in enumerate(drive_auto):
            if auto:
                needs.rated[i].append((sizes["drive_rated_power_kw"][i],
                                       sizes["drive_rated_power_governed_by"][i], case))
        if brake_auto:
            needs.holding.append((sum(sizes["brake_force_kn"]), sizes, case))
            for t in stop_times:
                braked = auto_sizes(conveyor, scn.model_copy(update={
                    "stop": scn.stop.model_copy(update={"mode": "brake", "time_s": t})}),
                    model=case.model, params=params, steady=steady)
                needs.by_stop[t].append((sum(braked["brake_force_kn"]), braked, case))
    return needs


def _check_finite(needs: _Needs, design: str) -> None:
    where = f" (conveyor design {design})" if design else ""
    for name, items in (("takeup", needs.takeup),
                        *((f"drives.{i}.rated_power_kw", r) for i, r in enumerate(needs.rated)),
                        ("brakes", needs.holding), *(("brakes", v) for v in needs.by_stop.values())):
        for value, _why, case in items:
            if not math.isfinite(value):
                raise SizingError(f"the auto size of {name} is not finite at {case.label()}"
                                  f"{where}; check sag_limit_pct, the drives' friction and wrap")


def _largest(items: list[tuple[float, Any, DesignCase]]) -> tuple[float, Any, DesignCase]:
    """The item of the largest value (the first of equals)."""
    best = items[0]
    for item in items[1:]:
        if item[0] > best[0]:
            best = item
    return best


def _brakes(items: list, conveyor: Conveyor | None = None, steady: dict | None = None
            ) -> BrakeSizes:
    """The largest need over the cases, held within the braked pulleys' grip at every case of
    a brake stop: a total above the least grip (``brake_grip_kn``) is that grip, shared at
    its case (``grip`` at that case), unless holding needs more at some case (then that
    holding size, whose note says its pulley slides in the stop)."""
    total, sizes, case = _largest(items)
    grips = [(s["brake_grip_kn"], c) for _t, s, c in items if s.get("brake_grip_kn") is not None]
    holding = [it for it in items if "holding" in it[1]["brake_governed_by"]]
    if conveyor is not None and grips:
        grip, at = min(grips, key=lambda g: g[0])
        if holding and _largest(holding)[0] >= grip:  # the holding floor stays
            _t, sizes, case = _largest(holding)
        elif total > grip * (1.0 + 1e-9):
            kn = brake_kn_within_grip(conveyor, steady[id(at)], grip)
            gov = [GIVEN if b.force_kn != "auto" else "grip" for b in conveyor.brakes]
            return BrakeSizes(tuple(kn), tuple(gov), at)
    return BrakeSizes(tuple(sizes["brake_force_kn"]), tuple(sizes["brake_governed_by"]), case)


def _brakes_on_installed_takeup(conveyor: Conveyor, cases: Sequence[DesignCase],
                                stop_times: Sequence[float], drive_auto: list[bool],
                                needs: _Needs) -> None:
    """Each case's brake-stop sizes again on the take-up the design installs (the largest
    over the cases), in place of each case's own auto take-up: a braked pulley's grip grows
    with its slack-side tension, and the installed take-up is the one every run has. Sized
    at each case's own take-up, a 500 m route's 4 s brake stop was held at the grip of its
    empty DIN case with a 16.6 kN pretension, 10.76 kN, where the installed 31.0 kN
    pretension lets that pulley pass 21.06 kN and every case's pass at least 17.53 kN. A
    take-up beyond what a file may give keeps the per-case sizes."""
    value = _largest(needs.takeup)[0]
    data = conveyor.model_dump(mode="python", by_alias=True)
    data["takeup"]["mass_kg" if conveyor.takeup.type == "gravity" else "pretension_kn"] = value
    try:
        installed = type(conveyor).model_validate(data)
    except (ValueError, InputError):
        return
    again = _gather(installed, cases, stop_times, (False, [False] * len(drive_auto), True))
    if again.failures:
        return
    needs.by_stop = again.by_stop
    needs.steady = again.steady
    needs.installed = installed


def size_over_cases(conveyor: Conveyor, cases: Sequence[DesignCase], *, load: Any = None,
                    stop_times: Sequence[float] = (), design: str = "") -> DesignSizes:
    """The auto sizes of one conveyor design: the largest of each over ``cases``.

    Parameters
    ----------
    conveyor : Conveyor
        The design, with its ``auto`` fields.
    cases : sequence of DesignCase
        The design cases (at least one), each at its own load case: the envelope over loads,
        models and temperatures.
    load : load case, optional
        When given, every case at this load instead of its own (SPEC 6.2: a fraction,
        ``full``, ``empty``, ...).
    stop_times : sequence of float
        The stop times [s] the brakes are sized for, besides the holding size.
    design : str
        Names the conveyor design in messages (``conveyor design <design>``).

    Returns
    -------
    DesignSizes
        Unrounded sizes: take-up [kg or kN], rated power per drive [kW], brake forces [kN],
        each with the constraint that set it, its case and (``at``) that case named by what
        varies among ``cases``.

    Raises
    ------
    SizingError
        A case's load does not fit the conveyor's profile (``field="load"``), the steady
        solve failed at every case, or a size is not finite.
    """
    if load is not None:
        cases = [dataclasses.replace(c, load=load) for c in cases]
    cases = list(dict.fromkeys(cases))
    for case in cases:
        try:
            section_loads(case.load_case, conveyor)
        except InputError as exc:
            raise SizingError(exc.reason + (f" (conveyor design {design})" if design else ""),
                              field="load") from None
    auto = _auto_fields(conveyor)
    needs = _gather(conveyor, cases, stop_times, auto)
    if len(needs.failures) == len(cases):
        where = f" of conveyor design {design}" if design else ""
        raise SizingError(f"the steady solve failed at every design case{where}, so nothing "
                          f"can be sized: {needs.failures[0]}")
    _check_finite(needs, design)
    tu_auto, drive_auto, brake_auto = auto
    if tu_auto and brake_auto and stop_times and needs.takeup:
        _brakes_on_installed_takeup(conveyor, cases, stop_times, drive_auto, needs)

    def tied(items, value: float) -> list[DesignCase]:
        return [c for v, _why, c in items if math.isclose(v, value, rel_tol=1e-9)]

    def largest(items) -> Largest:
        value, why, case = _largest(items)
        return Largest(value, why, case, case.at(cases, tied(items, value)))

    def brakes(sized: BrakeSizes, items) -> BrakeSizes:
        same = [c for c in tied(items, sum(sized.force_kn)) if c != sized.case]
        return dataclasses.replace(sized, at=sized.case.at(cases, same))

    return DesignSizes(
        takeup=largest(needs.takeup) if tu_auto else None,
        drives=tuple(largest(items) if items else None for items in needs.rated),
        brakes_holding=brakes(_brakes(needs.holding), needs.holding) if brake_auto else None,
        brakes_by_stop={t: brakes(_brakes(items, needs.installed or conveyor, needs.steady),
                                  items)
                        for t, items in needs.by_stop.items()}
        if brake_auto else {},
        failed_cases=tuple(needs.failures),
    )


__all__ += ["installed_at_full_load"]


def installed_at_full_load(conveyor: Conveyor, scenario: Scenario, *, model: str,
                           params: dict | object | None = None) -> tuple[Conveyor, dict]:
    """A single run's conveyor with its auto motors and brakes installed for the full design
    load too: a run below the full load somewhere (``empty``, a fraction, ``inclines``) gets
    each ``auto`` rated power and brake force sized over its own load case and the full load
    (:func:`size_over_cases`, the largest kept), written into the conveyor as given sizes, as
    the belt (:func:`beltstudy.engine.beltselect.run_cases`) and the counterweight
    (:mod:`beltstudy.engine.statics`) are installed once. A brake-stop run's brakes are
    sized for its stop time, any other run's for holding.

    Returns the conveyor (``conveyor`` itself when nothing changes: a full-load run, or no
    auto motor or brake) and the ``rated_power_governed_by`` / ``brake_governed_by`` fields
    of what it installed (``stop_time @ full``)."""
    if all(f == 1.0 for f in section_loads(scenario.load, conveyor)):
        return conveyor, {}
    _tu, drive_auto, brake_auto = _auto_fields(conveyor)
    if not (any(drive_auto) or brake_auto):
        return conveyor, {}
    if dataclasses.is_dataclass(params):
        params = dataclasses.asdict(params)
    pairs = tuple(sorted((params or {}).items()))
    case = DesignCase(model, pairs, float(scenario.temperature_c), scenario.elements,
                      scenario.load)
    full = dataclasses.replace(case, load="full")
    braked = scenario.stop.mode == "brake"
    stop_s = float(scenario.stop.time_s) if braked else None
    sizes = size_over_cases(conveyor, [case, full],
                            stop_times=(stop_s,) if stop_s is not None else ())
    data = conveyor.model_dump(mode="python", by_alias=True)
    governed: dict[str, str] = {}
    why = []
    for d, size, auto in zip(data["drives"], sizes.drives, drive_auto, strict=True):
        if auto and size is not None:
            d["rated_power_kw"] = float(size.value)
            why.append(governed_at(size.governed_by, size.at))
        else:
            why.append(GIVEN)
    if any(drive_auto):
        governed["rated_power_governed_by"] = "+".join(dict.fromkeys(why))
    if brake_auto:
        sized = sizes.brakes_by_stop[stop_s] if braked else sizes.brakes_holding
        why = []
        for b, force, reason in zip(data["brakes"], sized.force_kn, sized.governed_by,
                                    strict=True):
            if b["force_kn"] == "auto":
                # a 0 kN size (a level belt that coasts to rest in time) stays auto: the
                # largest of the two cases, it is 0 at this case too, and a given force is > 0
                if force > 0.0:
                    b["force_kn"] = float(force)
                why.append(governed_at(reason, sized.at))
            else:
                why.append(GIVEN)
        governed["brake_governed_by"] = "+".join(dict.fromkeys(why))
    return type(conveyor).model_validate(data), governed
