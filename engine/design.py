"""The auto sizes of a conveyor at one operating case: take-up, rated power, brakes.

:func:`auto_sizes` is the one place that says what an ``auto`` field of the conveyor file
becomes, and which constraint set it. A study calls it once per design case and holds the
largest values for all runs of a conveyor design (``service.study``); ``run_one`` calls it on
the run's own steady solution to report the sizes it used.

* **Take-up** (gravity ``mass_kg: auto``, fixed ``pretension_kn: auto``): the steady solve's
  sizing (:mod:`engine.statics`): the smallest take-up meeting slip at start-up and running
  and the sag limits running and, unless ``takeup.sag_at_rest`` is off, held at rest.
  Governing constraint: ``slip_start``, ``slip_running``, ``sag_running``, ``sag_at_rest``.
* **Rated power** (``rated_power_kw`` omitted): ``RATED_POWER_FACTOR`` x the drive's share of
  the larger of the steady peripheral force |Te| and the running resistance (a regenerating
  decline's motors must still overcome the resistance of the empty belt's start). Governing:
  ``peripheral_force`` or ``running_resistance``.
* **Brakes** (``force_kn: auto``): the total brake force for a rigid-body stop in the
  scenario's stop time after the brake delay, at least ``1.2`` x the net downhill pull of the
  loaded belt (:func:`engine.dynamics.model.brake_force_auto`), less the fixed brakes, shared
  evenly by the auto brakes. Its sizing input is the stop time: a run that stops on its brakes
  (``stop.mode: brake``) sizes them for its stop time (``stop_time``, or ``holding`` where the
  holding floor is larger); any other run uses no stop time and installs the holding size
  (``holding``).
"""

from __future__ import annotations

import math

import numpy as np

from engine.conveyor import Conveyor, Scenario
from engine.dynamics.model import brake_force_auto, pulley_reduced_mass_kg
from engine.loop import G
from engine.statics import SteadyResult, solve_steady

__all__ = ["auto_sizes", "summary_fields", "RATED_POWER_FACTOR", "moving_mass_kg", "GIVEN"]

#: Installed drive power as a multiple of the steady power at the drive [-] (the engine's
#: default of ``drives[].rated_power_kw``: steady power x 1.25, SPEC section 1).
RATED_POWER_FACTOR = 1.25
#: ``*_governed_by`` of a size given in the conveyor file.
GIVEN = "given"


def moving_mass_kg(conv: Conveyor, steady: SteadyResult) -> float:
    """All moving mass reduced to the belt line [kg], as the transient model builds it.

    Belt, material and idler rolls ``(m'_G + m'_L + m'_R) dx`` round the loop, each drive's
    inertia ``J (2 / D)^2`` and, for pulleys without a drive, the pulley estimate
    :func:`engine.dynamics.model.pulley_reduced_mass_kg`.
    """
    loop = steady.loop
    mass = float(loop.mass_kg.sum())
    drive_nodes = set()
    for d in conv.drives:
        drive_nodes.add(loop.i_head if d.position == "head" else loop.i_tail)
        mass += d.inertia_kg_m2 * (2.0 / d.pulley_diameter_m) ** 2
    for node in sorted({loop.i_head, loop.i_tail, loop.i_takeup} - drive_nodes):
        diam = 2.0 * float(loop.dx_m[node]) / math.pi  # pulley elements are half a round
        mass += pulley_reduced_mass_kg(diam, loop.belt.width_m)
    return mass


def _rated(conv: Conveyor, steady: SteadyResult) -> tuple[list[float], list[str]]:
    te = float(steady.te_n)
    r_sum = float(np.sum(steady.resistance_n))
    basis, why = (abs(te), "peripheral_force") if abs(te) >= r_sum else (
        r_sum, "running_resistance")
    v = float(conv.speed_m_s)
    kw, gov = [], []
    for d in conv.drives:
        if d.rated_power_kw is not None:
            kw.append(float(d.rated_power_kw))
            gov.append(GIVEN)
        else:
            kw.append(RATED_POWER_FACTOR * d.share * basis * v / 1e3)
            gov.append(why)
    return kw, gov


def _brakes(conv: Conveyor, scenario: Scenario, steady: SteadyResult
            ) -> tuple[list[float], list[str]]:
    if not conv.brakes:
        return [], []
    auto = [b for b in conv.brakes if b.force_kn == "auto"]
    each, why = 0.0, GIVEN
    if auto:
        fixed_n = sum(b.force_kn * 1e3 for b in conv.brakes if b.force_kn != "auto")
        delay = max(b.delay_s for b in auto)
        mass = moving_mass_kg(conv, steady)
        gravity = float(steady.loop.gravity_n.sum())
        hold_n = brake_force_auto(mass, float(conv.speed_m_s), float(steady.te_n), gravity,
                                  math.inf, delay)
        total_n, why = hold_n, "holding"
        if scenario.stop.mode == "brake":
            total_n = brake_force_auto(mass, float(conv.speed_m_s), float(steady.te_n), gravity,
                                       float(scenario.stop.time_s), delay)
            why = "stop_time" if total_n > hold_n else "holding"
        each = max(total_n - fixed_n, 0.0) / len(auto)
    kn = [each / 1e3 if b.force_kn == "auto" else float(b.force_kn) for b in conv.brakes]
    gov = [why if b.force_kn == "auto" else GIVEN for b in conv.brakes]
    return kn, gov


def auto_sizes(conveyor: Conveyor, scenario: Scenario, *, model: str,
               params: dict | object | None = None, steady: SteadyResult | None = None) -> dict:
    """The take-up, rated power and brake forces of ``conveyor`` at one operating case.

    Parameters
    ----------
    conveyor : Conveyor
    scenario : Scenario
        The case: ``load``, ``temperature_c``, ``elements`` (mesh of the steady solve) and, for
        auto brakes, ``stop.mode`` and ``stop.time_s``.
    model : str
        Friction model name.
    params : dict or parameter dataclass, optional
        Friction model parameter overrides.
    steady : SteadyResult, optional
        The steady solution of this case when the caller has it (no second solve).

    Returns
    -------
    dict
        ``takeup_mass_kg`` (gravity, else None) [kg], ``takeup_pretension_kn`` (tension per
        strand at the take-up) [kN], ``takeup_governed_by``; ``drive_rated_power_kw`` and
        ``drive_rated_power_governed_by`` (lists, one per drive, file order) [kW];
        ``brake_force_kn`` and ``brake_governed_by`` (lists, one per brake) [kN]; ``status``
        of the steady solve (a failed solve sizes nothing reliable).
    """
    if steady is None:
        n = None if scenario.elements == "auto" else int(scenario.elements)
        steady = solve_steady(conveyor, model=model, params=params,
                              temperature_c=scenario.temperature_c, load=scenario.load,
                              n_elements=n)
    tu = conveyor.takeup
    rated, rated_gov = _rated(conveyor, steady)
    brakes, brakes_gov = _brakes(conveyor, scenario, steady)
    return {
        "takeup_mass_kg": (float(2.0 * steady.takeup_tension_n / G)
                           if tu.type == "gravity" else None),
        "takeup_pretension_kn": float(steady.takeup_tension_n) / 1e3,
        "takeup_governed_by": steady.takeup_governed_by,
        "drive_rated_power_kw": rated,
        "drive_rated_power_governed_by": rated_gov,
        "brake_force_kn": brakes,
        "brake_governed_by": brakes_gov,
        "status": steady.status,
    }


def summary_fields(sizes: dict) -> dict:
    """The design columns of a run summary (SPEC 6.4) from :func:`auto_sizes`' answer.

    ``rated_power_kw`` and ``brake_force_kn`` are totals over the drives and brakes (None
    without brakes); ``*_governed_by`` name the constraint (several distinct ones joined by
    ``+``).
    """
    def join(names: list[str]) -> str | None:
        return "+".join(dict.fromkeys(names)) or None

    return {
        "takeup_mass_kg": sizes["takeup_mass_kg"],
        "takeup_pretension_kn": sizes["takeup_pretension_kn"],
        "takeup_governed_by": sizes["takeup_governed_by"],
        "rated_power_kw": float(sum(sizes["drive_rated_power_kw"])),
        "rated_power_governed_by": join(sizes["drive_rated_power_governed_by"]),
        "drive_rated_power_kw": list(sizes["drive_rated_power_kw"]),
        "brake_force_kn": (float(sum(sizes["brake_force_kn"])) if sizes["brake_force_kn"]
                           else None),
        "brake_governed_by": join(sizes["brake_governed_by"]),
    }
