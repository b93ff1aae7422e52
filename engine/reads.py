"""What a run reads of its scenario: the fields that can change its result.

A run does not read every scenario field. A steady-only run (dynamics off) reads
:data:`STEADY_FIELDS` (``load``, ``temperature_c``, ``elements``); a run that coasts to a stop
does not read ``stop.time_s`` (the belt stops on its own). Two runs whose scenarios differ only
in fields neither reads give the same result, so a caller that keys runs by their inputs (the
study service's run ids) keys them on :func:`scenario_as_read` and merges such runs.

Auto-sized brakes read the stop time only of a run that stops on them
(:func:`brake_sizing_stop_time`); any other run installs the holding size
(:mod:`beltstudy.engine.design`).
"""

from __future__ import annotations

from collections.abc import Mapping

from beltstudy.engine.conveyor import Scenario

__all__ = ["STEADY_FIELDS", "unread_fields", "scenario_as_read", "brake_sizing_stop_time"]

#: Scenario fields a steady-only run reads; it reads no other.
STEADY_FIELDS = ("load", "temperature_c", "elements")


def _defaults() -> dict:
    """The default scenario as a mapping (JSON types, field aliases)."""
    return Scenario().model_dump(mode="json", by_alias=True)


def unread_fields(scenario: Mapping, *, dynamics: bool) -> tuple[str, ...]:
    """The scenario fields a run does not read, as dotted names.

    Parameters
    ----------
    scenario : Mapping
        The scenario as a mapping (``Scenario.model_dump(mode="json", by_alias=True)``).
    dynamics : bool
        Whether the run simulates the transient (False: steady state only).

    Returns
    -------
    tuple of str
        Every field but :data:`STEADY_FIELDS` for a steady-only run; ``stop.time_s`` for a
        run that coasts to a stop; nothing otherwise.
    """
    if not dynamics:
        return tuple(k for k in _defaults() if k not in STEADY_FIELDS)
    if (scenario.get("stop") or {}).get("mode") == "coast":
        return ("stop.time_s",)
    return ()


def scenario_as_read(scenario: dict, *, dynamics: bool) -> dict:
    """The scenario as a run reads it: every field it does not read set to its default.

    Two scenarios that give the same answer here give the same run. ``scenario`` is a mapping
    as :func:`unread_fields` takes it; it is returned itself when every field the run does not
    read already has its default, and never changed in place.
    """
    unread = unread_fields(scenario, dynamics=dynamics)
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
