"""One run: the unit of work the service fans out (steady solve, then the transient cycle).

``run_one`` is a pure function of its inputs: the conveyor, the scenario, the friction model
name and its parameters. It never raises for physics problems: a run that cannot be solved
returns ``status='failed'`` with the reason in ``message``. Invalid inputs raise
:class:`~engine.conveyor.InputError` before the transient is computed: scenario fields first
(negative times, a stop mode the conveyor cannot do), then, once the loop is cut, a fixed
step above the stability limit.
"""

from __future__ import annotations

import time
from dataclasses import dataclass

import pandas as pd

from engine.conveyor import Conveyor, Scenario
from engine.design import auto_sizes, summary_fields
from engine.dynamics import DynamicsOptions, TransientResult, build_system, simulate
from engine.dynamics.model import check_scenario
from engine.statics import SAFETY_FACTOR_MIN, SteadyResult, solve_steady

__all__ = ["RunResult", "run_one", "check_scenario", "TRANSIENT_SAFETY_RATIO",
           "transient_safety_min"]

#: Minimum belt safety factor during starting and stopping as a fraction of the running
#: minimum [-]. Standards allow a lower factor for short non-steady loads than for steady
#: running; two thirds is this project's estimate (unverified), used only for the warning.
TRANSIENT_SAFETY_RATIO = 2.0 / 3.0


@dataclass
class RunResult:
    """Result of one run.

    Attributes
    ----------
    summary : dict
        SPEC section 4 fields (steady, and transient when dynamics ran), the design fields of
        SPEC 6.4 (``takeup_mass_kg``, ``takeup_pretension_kn``, ``brake_force_kn``,
        ``rated_power_kw`` and their ``*_governed_by``, :mod:`engine.design`), ``fill_pct``,
        ``status``, ``message``, ``elapsed_s`` [s], ``te_components_kn`` as a dict [kN].
    timeseries : DataFrame or None
        SPEC section 5 key points at ``record_dt_s`` (``t_s``, ``v_drive_m_s``,
        ``v_tail_m_s``, ``f_drive_kn``, ``t_head_in_kn``, ``t_head_out_kn``, ``t_tail_kn``,
        ``t_takeup_kn``, ``x_takeup_m``, ``t_min_kn``, ``t_max_kn``, then the extra columns
        ``v_mean_m_s``, ``v_ref_m_s``, ``f_brake_kn``, ``p_drive_kw``).
    profile : DataFrame
        Steady tension along the loop: ``s_m``, ``strand``, ``elevation_m``, ``tension_kn``,
        ``sag_pct``; with dynamics also the transient envelope ``t_max_dyn_kn``,
        ``t_min_dyn_kn``.
    surface : DataFrame or None
        Long table ``t_s``, ``s_m``, ``tension_kn``, ``velocity_m_s``.
    steady : SteadyResult or None
    transient : TransientResult or None
        The transient engine's full output (traces round the loop for plots, envelopes,
        final state).
    """

    summary: dict
    timeseries: pd.DataFrame | None
    profile: pd.DataFrame
    surface: pd.DataFrame | None
    steady: SteadyResult | None = None
    transient: TransientResult | None = None


def transient_safety_min(conveyor: Conveyor, belt_kind: str) -> float:
    """Minimum belt safety factor for the transient warning [-]."""
    running = conveyor.safety_factor_min or SAFETY_FACTOR_MIN.get(belt_kind, 6.7)
    return TRANSIENT_SAFETY_RATIO * running


def run_one(
    conveyor: Conveyor,
    scenario: Scenario,
    *,
    model: str,
    params: dict | None = None,
    dynamics: bool = True,
    options: DynamicsOptions | None = None,
) -> RunResult:
    """Steady solve and, with ``dynamics``, the rest -> start -> run -> stop -> rest cycle.

    Parameters
    ----------
    conveyor : Conveyor
    scenario : Scenario
    model : str
        Friction model name (``din``, ``cema``, ``cmod``, ``visco``, ``nonlin``).
    params : dict, optional
        Friction model parameter overrides.
    dynamics : bool
        Run the transient cycle (default) or the steady state only.
    options : DynamicsOptions, optional
        Transient engine settings (damping, Ernst law, step safety, ...).

    Raises
    ------
    InputError
        Impossible scenario, named by its field.
    """
    t0 = time.perf_counter()
    opts = options or DynamicsOptions()
    if dynamics:
        check_scenario(scenario, conveyor, opts)
    n = None if scenario.elements == "auto" else int(scenario.elements)
    steady = solve_steady(
        conveyor,
        model=model,
        params=params,
        temperature_c=scenario.temperature_c,
        load=scenario.load,
        n_elements=n,
    )
    summary = dict(steady.summary)
    # the sizes this run used (take-up, rated power, brakes) and what set each auto one
    summary.update(summary_fields(auto_sizes(conveyor, scenario, model=model, params=params,
                                             steady=steady)))
    profile = steady.profile()
    if not dynamics or steady.status == "failed":
        summary["elapsed_s"] = time.perf_counter() - t0
        return RunResult(summary=summary, timeseries=None, profile=profile, surface=None,
                         steady=steady)

    system = build_system(conveyor, scenario, steady, opts)
    tr = simulate(system, steady_summary=steady.summary, conveyor=conveyor,
                  safety_factor_min=transient_safety_min(conveyor, steady.loop.belt.kind))
    summary.update(tr.summary)
    messages = [m for m in (steady.message, tr.message) if m]
    if "failed" in (steady.status, tr.status):
        status = "failed"
    elif steady.status == "warning" or tr.status == "warning":
        status = "warning"
    else:
        status = "ok"
    summary["status"] = status
    summary["message"] = "; ".join(messages)
    profile["t_max_dyn_kn"] = tr.envelope["t_max_kn"].to_numpy()
    profile["t_min_dyn_kn"] = tr.envelope["t_min_kn"].to_numpy()
    summary["elapsed_s"] = time.perf_counter() - t0
    return RunResult(summary=summary, timeseries=tr.timeseries, profile=profile,
                     surface=tr.surface, steady=steady, transient=tr)
