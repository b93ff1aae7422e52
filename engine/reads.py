"""What a run reads of its scenario: the fields that can change its result.

A run does not read every scenario field. A steady-only run (dynamics off) reads
:data:`STEADY_FIELDS` (``load``, ``temperature_c``, ``elements``); a run that coasts to a stop
does not read ``stop.time_s`` (the belt stops on its own), nor does a brake stop whose brakes
all have their force given (the stop time sizes nothing; the brakes stop the belt). Two runs whose scenarios differ only
in fields neither reads give the same result, so a caller that keys runs by their inputs (the
study service's run ids) keys them on :func:`scenario_as_read` and merges such runs.

Auto-sized brakes read the stop time only of a run that stops on them
(:func:`brake_sizing_stop_time`); any other run installs the holding size
(:mod:`beltstudy.engine.design`).

Of the conveyor, a run does not read the law of a brake that never acts
(:func:`unread_brakes`, :func:`conveyor_as_read`): in a steady-only run the statics place a
brake (its pulley holds the belt at rest) but never use its force, delay, ramp or force curve;
in a transient run that does not stop on its brakes (``stop.mode`` coast or controlled) a brake
without ``hold`` is never applied. A brake with ``hold`` is set once the belt has stopped, in
every stop mode, and carries the gravity pull with its force from then on: its law is read.
"""

from __future__ import annotations

from collections.abc import Mapping

from beltstudy.engine.conveyor import Scenario

__all__ = [
    "STEADY_FIELDS",
    "unread_fields",
    "scenario_as_read",
    "brake_sizing_stop_time",
    "BRAKE_LAW_FIELDS",
    "UNREAD",
    "unread_brakes",
    "conveyor_as_read",
]

#: The fields of a brake's law (what it does once applied): unread when it never acts.
BRAKE_LAW_FIELDS = ("force_kn", "delay_s", "ramp_s", "force_curve")
#: What :func:`conveyor_as_read` writes in place of a field a run does not read.
UNREAD = "unread"

#: Scenario fields a steady-only run reads; it reads no other.
STEADY_FIELDS = ("load", "temperature_c", "elements")


def _defaults() -> dict:
    """The default scenario as a mapping (JSON types, field aliases)."""
    return Scenario().model_dump(mode="json", by_alias=True)


def unread_fields(scenario: Mapping, *, dynamics: bool,
                  brakes_given: bool = False) -> tuple[str, ...]:
    """The scenario fields a run does not read, as dotted names.

    Parameters
    ----------
    scenario : Mapping
        The scenario as a mapping (``Scenario.model_dump(mode="json", by_alias=True)``).
    dynamics : bool
        Whether the run simulates the transient (False: steady state only).
    brakes_given : bool
        Every brake of the run's conveyor has its ``force_kn`` given (none ``auto``): a brake
        stop then sizes nothing by its stop time, and the brakes stop the belt as they will.

    Returns
    -------
    tuple of str
        Every field but :data:`STEADY_FIELDS` for a steady-only run; ``stop.time_s`` for a
        run that coasts to a stop, or that stops on brakes whose forces are all given;
        nothing otherwise.
    """
    if not dynamics:
        return tuple(k for k in _defaults() if k not in STEADY_FIELDS)
    mode = (scenario.get("stop") or {}).get("mode")
    if mode == "coast" or (mode == "brake" and brakes_given):
        return ("stop.time_s",)
    return ()


def scenario_as_read(scenario: dict, *, dynamics: bool, brakes_given: bool = False) -> dict:
    """The scenario as a run reads it: every field it does not read set to its default.

    Two scenarios that give the same answer here give the same run. ``scenario`` and
    ``brakes_given`` are as :func:`unread_fields` takes them; the scenario is returned itself
    when every field the run does not read already has its default, and never changed in
    place.
    """
    unread = unread_fields(scenario, dynamics=dynamics, brakes_given=brakes_given)
    if not unread:
        return scenario
    defaults = _defaults()
    out = scenario
    for name in unread:
        path = name.split(".")
        default = _get(defaults, path)
        if _get(out, path) != default:
            out = _with(out, path, default)
    return out


def _get(data: Mapping, path: list[str]):
    for key in path:
        data = (data or {}).get(key)
    return data


def _with(data: Mapping, path: list[str], value) -> dict:
    """A copy of ``data`` with ``value`` at ``path`` (the mappings along it copied)."""
    head, *rest = path
    return {**data, head: _with(data.get(head) or {}, rest, value) if rest else value}


def brake_sizing_stop_time(scenario: Mapping, *, dynamics: bool) -> float | None:
    """The stop time [s] a run's auto-sized brakes are sized for: the scenario's
    ``stop.time_s`` for a run that stops on its brakes (dynamics on, ``stop.mode: brake``),
    None for any other run (it installs the holding size)."""
    stop = scenario.get("stop") or {}
    if dynamics and stop.get("mode") == "brake":
        return float(stop["time_s"])
    return None


def unread_brakes(conveyor: Mapping, scenario: Mapping, *, dynamics: bool) -> tuple[int, ...]:
    """Indices of the brakes (file order) whose law (:data:`BRAKE_LAW_FIELDS`) a run never
    reads: every brake of a steady-only run; in a transient run that does not stop on its
    brakes, every brake without ``hold``.

    Parameters
    ----------
    conveyor, scenario : Mapping
        The run's conveyor and scenario as dumped mappings (JSON types, field aliases).
    dynamics : bool
        Whether the run simulates the transient.
    """
    brakes = conveyor.get("brakes") or []
    if not dynamics:
        return tuple(range(len(brakes)))
    if (scenario.get("stop") or {}).get("mode") == "brake":
        return ()
    return tuple(i for i, b in enumerate(brakes) if b.get("hold", True) is False)


def conveyor_as_read(conveyor: Mapping, scenario: Mapping, *, dynamics: bool) -> Mapping:
    """The conveyor as a run reads it: the law of every brake it never reads
    (:func:`unread_brakes`) written as :data:`UNREAD`. Two runs whose conveyors give the same
    answer here (and whose scenarios give the same :func:`scenario_as_read`) give the same
    result. ``conveyor`` itself is returned when the run reads all of it (so a key made of it
    is the key it always was), and never changed in place. A key, not a conveyor to run: the
    marker is no valid value."""
    unread = unread_brakes(conveyor, scenario, dynamics=dynamics)
    if not unread:
        return conveyor
    brakes = [
        {**b, **{k: UNREAD for k in BRAKE_LAW_FIELDS}} if i in unread else b
        for i, b in enumerate(conveyor["brakes"])
    ]
    return {**conveyor, "brakes": brakes}
