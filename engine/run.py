"""One run: the unit of work the service fans out (steady solve, then the transient cycle).

``run_one`` is a pure function of its inputs: the conveyor, the scenario, the friction model
name and its parameters. It never raises for physics problems: a run that cannot be solved
returns ``status='failed'`` with the reason in ``message``. Invalid inputs raise
:class:`~beltstudy.engine.conveyor.InputError` before the transient is computed: scenario fields first
(negative times, a stop mode the conveyor cannot do), then, once the loop is cut, a fixed
step above the stability limit.
"""

from __future__ import annotations

import functools
import math
import re
import time
from collections.abc import Callable
from dataclasses import dataclass, replace

import numpy as np
import pandas as pd

from beltstudy.engine import beltselect, catalog
from beltstudy.engine.beltselect import resolve_auto_belt, run_cases, run_message
from beltstudy.engine.checks import design_holding_words, transient_checks
from beltstudy.engine.conveyor import Conveyor, Drive, Scenario, section_loads
from beltstudy.engine.curves import survey_liftoff_limits_n, transient_liftoff
from beltstudy.engine.design import auto_sizes, summary_fields
from beltstudy.engine.dynamics import DynamicsOptions, TransientResult, build_system, simulate
from beltstudy.engine.dynamics.model import check_scenario
from beltstudy.engine.dynamics.simulate import (
    _or,
    heavier_takeup,
    slip_levers,
    slip_words,
    span_sag_pct,
    start_levers,
    stop_levers,
)
from beltstudy.engine.loop import G
from beltstudy.engine.reads import unread_brakes
from beltstudy.engine.remedy import REL_TOL, SAG_WARNING, reads_start_time, slipped_in_stop
from beltstudy.engine.results import check_summary
from beltstudy.engine.sizing import installed_at_full_load
from beltstudy.engine.statics import (
    SAFETY_FACTOR_MIN,
    TRANSIENT_SAFETY_RATIO,
    SteadyResult,
    solve_steady,
)
from beltstudy.engine.stopgrip import brake_grip_n, kn_figure
from beltstudy.engine.wording import gnum

__all__ = ["RunResult", "run_one", "run_group", "check_scenario", "TRANSIENT_SAFETY_RATIO",
           "transient_safety_min"]

#: A table of :class:`RunResult` not given to its constructor: derived from the results.
_DERIVED = object()


class RunResult:
    """Result of one run.

    The tables are built on first access from the steady and transient results (a caller
    that needs only the summary, or stores the arrays, never builds them); a table given to
    the constructor is kept as it is.

    Attributes
    ----------
    summary : dict
        The fields of :mod:`beltstudy.engine.results` (every key is one of them): SPEC section 4 fields (steady, and transient when dynamics ran), the design fields of
        SPEC 6.4 (``takeup_mass_kg``, ``takeup_pretension_kn``, ``brake_force_kn``,
        ``rated_power_kw`` and their ``*_governed_by``, :mod:`beltstudy.engine.design`), ``fill_pct``,
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

    #: The error bars (:class:`beltstudy.engine.accuracy.Accuracy`) of a run checked with
    #: ``run_one(..., check=True)``.
    accuracy = None

    def __init__(self, summary: dict, timeseries=_DERIVED, profile=_DERIVED, surface=_DERIVED,
                 steady: SteadyResult | None = None, transient: TransientResult | None = None):
        self.summary = summary
        self.steady = steady
        self.transient = transient
        self._timeseries = timeseries
        self._profile = profile
        self._surface = surface

    def __repr__(self) -> str:
        return (f"RunResult(status={self.summary.get('status')!r}, "
                f"dynamics={self.transient is not None})")

    @property
    def timeseries(self) -> pd.DataFrame | None:
        if self._timeseries is _DERIVED:
            self._timeseries = None if self.transient is None else self.transient.timeseries
        return self._timeseries

    @timeseries.setter
    def timeseries(self, value: pd.DataFrame | None) -> None:
        self._timeseries = value

    @property
    def surface(self) -> pd.DataFrame | None:
        if self._surface is _DERIVED:
            self._surface = None if self.transient is None else self.transient.surface
        return self._surface

    @surface.setter
    def surface(self, value: pd.DataFrame | None) -> None:
        self._surface = value

    @property
    def profile(self) -> pd.DataFrame | None:
        if self._profile is _DERIVED:
            profile = None if self.steady is None else self.steady.profile()
            if profile is not None and self.transient is not None:
                t_max, t_min = self.transient.envelope_kn()
                profile["t_max_dyn_kn"] = t_max
                profile["t_min_dyn_kn"] = t_min
            self._profile = profile
        return self._profile

    @profile.setter
    def profile(self, value: pd.DataFrame | None) -> None:
        self._profile = value

    def timeseries_arrays(self) -> dict[str, np.ndarray] | None:
        """The time-series columns as arrays (no DataFrame is built unless one was given)."""
        if self._timeseries is _DERIVED:
            return None if self.transient is None else dict(self.transient.series)
        if self._timeseries is None:
            return None
        return {c: self._timeseries[c].to_numpy() for c in self._timeseries.columns}

    def profile_arrays(self) -> dict[str, np.ndarray] | None:
        """The steady profile's columns ``s_m``, ``strand``, ``elevation_m``, ``tension_kn``,
        ``sag_pct`` as arrays (None without a steady solution; no DataFrame is built)."""
        return None if self.steady is None else self.steady.profile_arrays()

    def surface_arrays(self) -> dict[str, np.ndarray] | None:
        """The surface columns ``t_s``, ``s_m``, ``tension_kn``, ``velocity_m_s`` as arrays."""
        if self._surface is _DERIVED:
            return None if self.transient is None else self.transient.surface_arrays()
        if self._surface is None:
            return None
        return {c: self._surface[c].to_numpy() for c in self._surface.columns}


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
    remedy: bool = False,
    check: bool = False,
    say: Callable[[str], None] | None = None,
    auto_brakes: bool | None = None,
    governed: dict[str, str] | None = None,
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
    remedy : bool
        When a drive slips in the start, find the take-up and the start time that avoid it
        by rerunning the start (:mod:`beltstudy.engine.remedy`: about a dozen reruns each); the
        ``slip_free_*`` fields and a sentence in the message; when a drive slips in the stop,
        the take-up and (a controlled stop) the ``stop.time_s`` that avoid it, by rerunning the
        whole cycle (a sentence in the message only); when the cycle sags past a limit, the
        take-up that keeps it within, by rerunning the whole cycle (a sentence in the message
        only). Off by default (studies).
    check : bool
        Error bars of the deciding figures by rerunning the cycle on a mesh half and twice as
        fine (:func:`beltstudy.engine.accuracy.error_bars`: the ``<figure>_err`` and
        ``<figure>_converged`` fields, ``RunResult.accuracy``, the marginal verdicts in the
        message). Off by default (a study checks a sample of its runs).
    say : callable, optional
        Called with one line before a long step a person waits for (the slip remedy's
        reruns), for a command line to print; studies pass nothing.
    auto_brakes : bool, optional
        Whether a brake of the run is auto although ``conveyor`` has its force written in (a
        study writes its design's sizes in): the advice on a fast brake stop then offers
        ``stop.time_s``. None: a brake of ``conveyor`` with ``force_kn: auto``.
    governed : dict, optional
        What set the sizes a caller wrote into ``conveyor`` (a study's design: its
        ``takeup_governed_by``, ``rated_power_governed_by``, ``brake_governed_by``), which the
        run then says in place of ``given``: a brake stop that missed the ``stop.time_s`` of a
        brake the design set for holding says so, as the run with ``force_kn: auto`` does,
        instead of calling it sized by the stop time.

    Raises
    ------
    InputError
        Impossible scenario, named by its field.
    """
    t0 = time.perf_counter()
    opts = options or DynamicsOptions()
    prep = _prepare(conveyor, scenario, model, params, dynamics, opts, governed=governed)
    if prep.done is not None:
        prep.done.summary["elapsed_s"] = time.perf_counter() - t0
        return prep.done
    system = build_system(prep.conveyor, scenario, prep.steady, opts)
    _unsaid(system, prep.steady)
    system.auto_brakes = _auto_brakes(conveyor, auto_brakes)
    system.brakes_timed = _brakes_timed(prep, system.auto_brakes)
    system.brakes_gripped = _brakes_gripped(prep)
    system.motor_cases = _motor_cases(prep, scenario, model, params)
    system.brake_grip = _brake_grip(prep, system, scenario)
    tr = simulate(system, steady_summary=prep.steady.summary, conveyor=prep.conveyor,
                  safety_factor_min=transient_safety_min(prep.conveyor,
                                                         prep.steady.loop.belt.kind))
    result = _complete(prep, scenario, system, tr, model, params, opts, remedy, check, t0, say)
    if conveyor.belt.type == catalog.AUTO:
        result = _transient_belt(conveyor, scenario, result, t0, say, model=model,
                                 params=params, options=opts, remedy=remedy, check=check,
                                 auto_brakes=auto_brakes, governed=governed)
    return result


def _transient_belt(conveyor: Conveyor, scenario: Scenario, result: RunResult, t0: float,
                    say: Callable[[str], None] | None = None, **run) -> RunResult:
    """``belt.type: auto`` past the transient (SPEC 7.1: the lightest catalogue belt that
    passes the steady and transient safety factors): where the steady choice's run falls
    below the transient minimum (``safety_factor_dyn``; its stress waves are the transient
    run's to see, :mod:`beltstudy.engine.beltselect`), the heavier catalogue belts of its kind
    are run in turn, from the first whose rating meets the minimum at this run's peak, to the
    first that passes; the run is of that belt, its words say why. A 500 m incline on a dol
    drive picked ST1000 by its steady checks and ran at a transient safety factor of 2.93
    against 4.47, its note calling ST1000 the lightest belt that passes. None passing, the
    steady choice's run is kept and its warning says so."""
    s = result.summary
    sf, chosen = s.get("safety_factor_dyn"), s.get("belt_type_used")
    kind = (catalog.resolve_belt(beltselect.with_belt(conveyor, chosen).belt).kind
            if chosen else None)
    need = transient_safety_min(conveyor, kind) if kind else None
    if sf is None or need is None or sf >= need * (1.0 - beltselect.RTOL):
        return result
    cands = beltselect.candidates(conveyor)
    ids = [c[0] for c in cands]
    if chosen not in ids:
        return result
    now_kn = cands[ids.index(chosen)][2]
    # the run's peak at least scales with the belt's rating: a heavier belt raises it
    heavier = [c for c in cands[ids.index(chosen) + 1:] if c[2] >= now_kn * need / sf]
    tried = []
    for belt_id, mass, rating in heavier:
        if say is not None:
            say(f"belt.type auto: {chosen} runs at a transient safety factor of {gnum(sf, 3)} "
                f"against {gnum(need, 3)}: rerunning the cycle with {belt_id}")
        trial = run_one(beltselect.with_belt(conveyor, belt_id), scenario,
                        **{**run, "remedy": False, "check": False})
        sf_t = trial.summary.get("safety_factor_dyn")
        tried.append(f"{belt_id} {gnum(sf_t, 3)}" if sf_t is not None else belt_id)
        if sf_t is None or sf_t < need * (1.0 - beltselect.RTOL):
            continue
        final = (trial if not (run["remedy"] or run["check"]) else
                 run_one(beltselect.with_belt(conveyor, belt_id), scenario, say=say, **run))
        f = final.summary
        note = (f"note: belt.type auto ({conveyor.belt.kind}): {chosen}, the lightest "
                f"catalogue belt that passes the steady checks, ran at a transient safety "
                f"factor of {gnum(sf, 3)} against the minimum {gnum(need, 3)}; {belt_id} ({gnum(mass, 3)} "
                f"kg/m, {gnum(rating)} kN), the lightest heavier one whose run passes it "
                f"({'; '.join(tried)}), is the belt of this run")
        f["message"] = "; ".join(m for m in (f.get("message"), note) if m)
        f["elapsed_s"] = time.perf_counter() - t0
        return final
    said = (f"; belt.type auto ({conveyor.belt.kind}): no heavier catalogue belt of this kind "
            f"passes the transient minimum {gnum(need, 3)} either"
            + (f" (rerun with {', '.join(tried)})" if tried else "")
            + ": a wider belt (belt.width_m) or a softer start and stop would avoid it")
    s["message"] = (s.get("message") or "") + said
    return result


def _unsaid(system, steady) -> None:
    """Leave out of the transient's warnings those of its rest state that the steady check
    said already, word for word (the pulley holding the stopped belt beyond its grip, which
    both judge on a gravity take-up's at-rest tensions): the run's message said it twice."""
    system.warnings = [w for w in system.warnings if w not in steady.warnings]


def _brake_grip(prep: _Prepared, system, scenario: Scenario) -> functools.partial | None:
    """The largest brake force [N] a braked pulley passes in the run's brake stop, by its
    element (:func:`beltstudy.engine.stopgrip.brake_grip_n` with the run's brakes, auto sizes
    in), for the stop slip's words; None without a brake stop."""
    brakes = system.model.brakes
    if brakes is None or not len(brakes.force) or scenario.stop.mode != "brake":
        return None
    return functools.partial(brake_grip_n, prep.conveyor, prep.steady,
                             tuple(int(n) for n in brakes.node),
                             tuple(float(f) for f in brakes.force))


def _motor_cases(prep: _Prepared, scenario: Scenario, model: str, params
                 ) -> tuple[tuple[float, float], ...]:
    """The load cases the engine sizes a motor at, each as (Te, running resistance) [N]: the
    run's own and, for a run below the full load somewhere, the full load's, as
    :func:`beltstudy.engine.sizing.installed_at_full_load` installs an auto motor (each case
    by :func:`beltstudy.engine.drives.motor_size_kw`, the largest kept). An empty 30 m belt's
    |Te| is 1.77 kN and its full load's 2.04 kN: judged on the empty case alone, a given motor
    was called 3.4 x the engine's size (4 kW) instead of 2.9 x (5 kW). Te keeps its sign, so a
    regenerating full load is sized through the efficiency as the auto motor is (|Te| v eta,
    not |Te| v / eta: 11 % apart at 0.95)."""
    own = ((float(prep.steady.te_n), float(np.sum(prep.steady.resistance_n))),)
    # read only of dol drives (oversized_motor_words): no second solve for vfd-only belts
    if (all(d.control != "dol" for d in prep.conveyor.drives)
            or all(f == 1.0 for f in section_loads(scenario.load, prep.conveyor))):
        return own
    n = None if scenario.elements == "auto" else int(scenario.elements)
    full = solve_steady(prep.conveyor, model=model, params=params,
                        temperature_c=scenario.temperature_c, load="full", n_elements=n)
    if full.status == "failed":
        return own
    return (*own, (float(full.te_n), float(np.sum(full.resistance_n))))


def said_up(t: float | None) -> float | None:
    """A remedy's time [s] as it is said: rounded up (to the second from 10 s, to a tenth
    below), since the figure is the least found and rounded down it could slip."""
    return None if t is None else (math.ceil(t) if t >= 10.0 else math.ceil(10.0 * t) / 10.0)


def brakes_timed(governed_by: str | None) -> bool | None:
    """Whether a longer ``stop.time_s`` changes the run's auto brakes, from what set their
    size (``brake_governed_by``: ``stop_time``, ``grip``, ``holding`` or ``given`` per brake,
    joined by ``+``, each possibly ``@ <design case>``): True where one is set by the stop
    time or by its pulley's grip against the stop time's need, False where every one is set
    by holding or given; None when the run says nothing of it (no brake)."""
    if not governed_by:
        return None
    return any(w in str(governed_by) for w in ("stop_time", "grip"))


def _brakes_gripped(prep: _Prepared) -> bool | None:
    """Whether an auto brake of the run is held to its pulley's grip below the stop time's
    need at the run's own case (``brake_governed_by`` names ``grip`` without ``@`` another
    design case: a run below full load carries the full load's brake, whose grip and stop
    time are that case's, not this run's); None when the run says nothing of it."""
    governed = prep.summary.get("brake_governed_by")
    if not governed:
        return None
    return any(part.strip() == "grip" for part in str(governed).split("+"))


def _brakes_timed(prep: _Prepared, auto: bool) -> bool | None:
    """:func:`brakes_timed` of the run's sizes; None (not known) where the caller says a brake
    is auto (``auto``, a study's design written in) but the run saw only given forces: what
    set the design's brake is then not the run's to say."""
    governed = prep.summary.get("brake_governed_by")
    timed = brakes_timed(governed)
    if auto and timed is False and "holding" not in str(governed):
        return None
    return timed


def _auto_brakes(conveyor: Conveyor, given: bool | None) -> bool:
    """Whether a brake of the run is auto: ``given`` when the caller knows (a study writes its
    design's sizes into the conveyor it runs), else a brake of ``conveyor`` (the run's own, before
    a run below full load gets the full-load sizes written in) with ``force_kn: auto``."""
    if given is not None:
        return bool(given)
    return any(b.force_kn == "auto" for b in conveyor.brakes)


def run_group(
    conveyor: Conveyor | list[Conveyor],
    scenarios: list[Scenario],
    *,
    model: str,
    params: dict | None = None,
    options: DynamicsOptions | None = None,
    remedy: bool = False,
    check: bool | list[bool] = False,
    auto_brakes: list[bool | None] | None = None,
    governed: list[dict[str, str] | None] | None = None,
) -> list[RunResult]:
    """:func:`run_one` of each scenario of one conveyor, model and parameters, the runs that
    agree on everything the transient engine reads up to the stop command sharing one
    simulated rest, start and run (:mod:`beltstudy.engine.dynamics.shared`: the engine, not the
    caller, decides which do, from the built models), and the runs that agree on what it reads
    after the stop command too (runs that differ only in what their law does not read, such as
    DIN's temperature) sharing one kernel run. Each result equals its :func:`run_one` bit for
    bit but ``elapsed_s`` (the shared stretch counts in full for each run).

    ``conveyor`` may be one per scenario (runs whose brakes differ only in their force, delay,
    ramp, curve or hold still share a start when their models allow it). ``check`` may be one
    flag per scenario (the error bars rerun each checked run's cycle on its own, as
    :func:`run_one` does); ``auto_brakes`` and ``governed`` one per scenario, as :func:`run_one`
    takes them.
    Raises as :func:`run_one` for the first scenario that cannot run; a caller that wants a
    bad scenario to fail alone runs it with :func:`run_one`."""
    from beltstudy.engine.dynamics.shared import group_by_start, simulate_group

    checks = check if isinstance(check, list) else [check] * len(scenarios)
    convs = conveyor if isinstance(conveyor, list) else [conveyor] * len(scenarios)
    opts = options or DynamicsOptions()
    t0 = [time.perf_counter() for _ in scenarios]
    results: list[RunResult | None] = [None] * len(scenarios)
    preps, systems, todo, solved = {}, [], [], {}
    for i, scn in enumerate(scenarios):
        t0[i] = time.perf_counter()
        prep = _prepare(convs[i], scn, model, params, True, opts, solved,
                        governed=None if governed is None else governed[i])
        if prep.done is not None:
            prep.done.summary["elapsed_s"] = time.perf_counter() - t0[i]
            results[i] = prep.done
            continue
        preps[i] = prep
        systems.append(build_system(prep.conveyor, scn, prep.steady, opts))
        _unsaid(systems[-1], prep.steady)
        systems[-1].auto_brakes = _auto_brakes(
            convs[i], None if auto_brakes is None else auto_brakes[i])
        systems[-1].motor_cases = _motor_cases(prep, scn, model, params)
        systems[-1].brakes_timed = _brakes_timed(prep, systems[-1].auto_brakes)
        systems[-1].brakes_gripped = _brakes_gripped(prep)
        systems[-1].brake_grip = _brake_grip(prep, systems[-1], scn)
        todo.append(i)
    for group in group_by_start(systems):
        members = [preps[todo[g]] for g in group]
        trs = simulate_group([systems[g] for g in group],
                             steady_summary=[p.steady.summary for p in members],
                             conveyor=[p.conveyor for p in members],
                             safety_factor_min=[transient_safety_min(
                                 p.conveyor, p.steady.loop.belt.kind) for p in members],
                             grouped=True)
        for g, tr in zip(group, trs, strict=True):
            i = todo[g]
            results[i] = _complete(preps[i], scenarios[i], systems[g], tr, model, params, opts,
                                   remedy, checks[i], t0[i])
    return results  # type: ignore[return-value]


@dataclass
class _Prepared:
    """A run up to its transient: the conveyor it runs (an auto belt resolved), the belt
    choice's words, the steady solution and the summary so far; ``done`` holds the finished
    result of a run without a transient (steady only, or a failed steady state)."""

    conveyor: Conveyor
    belt_choice: object
    steady: object
    summary: dict
    done: RunResult | None = None


def _prepare(conveyor, scenario, model, params, dynamics, opts, solved=None, governed=None
             ) -> _Prepared:
    """The steady part of :func:`run_one`: the scenario checked, the auto belt chosen, the
    steady solve and the sizes this run used. ``solved``: a dict that keeps the belt choice
    and steady solution of each operating case (the conveyor object, temperature, load and
    mesh) for the next scenarios of :func:`run_group` (runs that differ in their stop alone
    solve their design once; neither is changed by what uses it). ``governed``: what set the
    sizes the caller wrote in (:func:`run_one`), put in place of the run's own ``given``."""
    if dynamics:
        check_scenario(scenario, conveyor, opts)
    n = None if scenario.elements == "auto" else int(scenario.elements)
    # a run below the full load installs its auto brakes for its own stop (below)
    key = (id(conveyor), float(scenario.temperature_c), repr(scenario.load), n,
           repr(scenario.stop) if any(b.force_kn == "auto" for b in conveyor.brakes) else "")
    if solved is None or key not in solved:
        # belt.type: auto is chosen once, here, at the run's case; the rest runs on that belt
        conveyor, belt_choice = resolve_auto_belt(conveyor, run_cases(
            conveyor, model, params, scenario.temperature_c, scenario.load, n))
        # auto motors and brakes installed for the full load too (a run below it)
        conveyor, installed = installed_at_full_load(conveyor, scenario, model=model,
                                                     params=params)
        steady = solve_steady(
            conveyor,
            model=model,
            params=params,
            temperature_c=scenario.temperature_c,
            load=scenario.load,
            settle=True,
            n_elements=n,
        )
        if solved is not None:  # the caller holds every conveyor meanwhile: ids stay theirs
            solved[key] = (conveyor, belt_choice, steady, installed)
    else:
        conveyor, belt_choice, steady, installed = solved[key]
    summary = dict(steady.summary)
    # the sizes this run used (take-up, rated power, brakes) and what set each auto one
    summary.update(summary_fields(_as_applied(
        auto_sizes(conveyor, scenario, model=model, params=params, steady=steady),
        conveyor, scenario, dynamics)))
    summary.update(installed)
    # a study's design: the run sees its sizes as given numbers, the caller knows what set them
    summary.update({k: v for k, v in (governed or {}).items() if k.endswith("_governed_by")
                    and not (k == "brake_governed_by" and summary.get("brake_force_kn") is None)})
    held_by = (governed or {}).get("brake_governed_by")
    if held_by and "force_kn: auto sizes them" in steady.message:
        # a holding brake short at a case outside the design: its fix is the design's list
        steady = replace(steady, message=design_holding_words(steady.message, held_by),
                         warnings=[design_holding_words(w, held_by) for w in steady.warnings])
        summary["message"] = design_holding_words(summary.get("message") or "", held_by)
    prep = _Prepared(conveyor, belt_choice, steady, summary)
    if not dynamics and steady.status != "failed" and scenario.start != Scenario().start:
        # the study's start, not the default one, in a steady-only run's start-time note
        summary["message"] = _start_note_for(steady, conveyor, scenario,
                                             summary.get("message") or "")
    if not dynamics or steady.status == "failed":
        run_message(summary, belt_choice)
        check_summary(summary)
        prep.done = RunResult(summary=summary, steady=steady)
    return prep


def _as_applied(sizes: dict, conveyor: Conveyor, scenario: Scenario, dynamics: bool) -> dict:
    """The sizes a transient run used: without the brakes it never applies (a coast or
    controlled stop's brakes without ``hold``, :func:`~beltstudy.engine.reads.unread_brakes`),
    whose law the run does not read, so that runs of a study that differ only in it are one
    run (``conveyor_as_read``). Their force in the row was the first merged grid point's: one
    run of two studies read 150 kN in one and 80 kN in the other. ``brake_force_kn`` is then
    the total of the brakes applied, null where none is. A steady-only run keeps every
    brake's size: the design's holding brake, which the statics place."""
    if not dynamics or not conveyor.brakes:
        return sizes
    unread = set(unread_brakes({"brakes": [{"hold": b.hold} for b in conveyor.brakes]},
                               {"stop": {"mode": scenario.stop.mode}}, dynamics=True))
    if not unread:
        return sizes
    keep = [i for i in range(len(conveyor.brakes)) if i not in unread]
    return {**sizes, "brake_force_kn": [sizes["brake_force_kn"][i] for i in keep],
            "brake_governed_by": [sizes["brake_governed_by"][i] for i in keep]}


def _start_note_for(steady, conveyor, scenario, message: str | None = None) -> str:
    """The steady run's message (``message``, default ``steady.message``) with its start-time
    note (:func:`beltstudy.engine.statics.start_time_note`, which judges the transient's
    default start) said of the run's own start instead: added where only the run's start is
    beyond the start-up checks, left out where only the default one is. A steady-only run of a
    study whose scenario gives a 45 s start was told of "the default 60 s s-curve"."""
    from beltstudy.engine.statics import start_time_note

    text = steady.message if message is None else message
    default = start_time_note(conveyor, steady.loop, steady.te_n)
    own = start_time_note(conveyor, steady.loop, steady.te_n, scenario.start)
    if not default:
        return "; ".join(m for m in (text, own) if m)
    if own:
        return text.replace(default, own)
    for cut in ("; " + default, default + "; ", default):
        if cut in text:
            return text.replace(cut, "", 1)
    return text


def _complete(prep: _Prepared, scenario, system, tr, model, params, opts, remedy, check,
              t0, say=None) -> RunResult:
    """The rest of :func:`run_one` after the transient: its fields, the transient checks,
    lift-off at concave curves, the slip remedy (``say`` told before its reruns), the status
    and message, the error bars."""
    conveyor, steady, summary = prep.conveyor, prep.steady, prep.summary
    summary.update(tr.summary)
    summary.update({k: (v if math.isfinite(v) else None) for k, v in transient_checks(
        steady.loop, np.array([seg[2] for seg in tr.raw["segments"]])).items()})
    messages = [m for m in (_start_note_for(steady, conveyor, scenario), tr.message) if m]
    # lift-off at concave curves and concave survey grade changes in the cycle
    # (engine/curves.py; null fields without either)
    cyc = system.model.cycle
    softer = None if reads_start_time(conveyor) else " or ".join(start_levers(system))
    first = np.asarray(tr.raw.get("drive_slip_first_s", ()), dtype=float)
    if softer is None and np.any((first >= cyc.t_pre) & (first <= cyc.t_pre + cyc.t_start)):
        # a drive pulley that slips in the start holds the start's force at its grip, not at
        # what start.time_s asks: a 3 km route told "a start of about 51 s" lifted by +3.1,
        # -0.15, -0.8, +1.0 kN at 51, 53, 55 and 58 s, its slip capping the peak
        softer = ("a start whose drives do not slip (the slip warning's remedy: while a "
                  "drive pulley slips its grip, not start.time_s, sets the start's peak, so "
                  "rerun the lift-off check after it)")
    # the start ends when the belt first reached 99 % of design speed, where that is after
    # the start reference (the slip and run words read the same, System.t_start_end_s)
    reached = tr.summary.get("start_time_s")
    lifted, lift_warnings = transient_liftoff(
        steady.loop, tr.raw["segments"],
        cyc.t_pre + max(cyc.t_start, reached if reached is not None else 0.0),
        system.stop_command_s,
        max(cyc.t_start, tr.summary.get("start_time_s") or 0.0), system.steady_tension_n,
        softer,
        " or ".join(stop_levers(system)), survey_liftoff_limits_n(conveyor, steady.loop),
        t_start_cmd_s=cyc.t_pre,
        t_rested_s=float(tr.raw["t_stopped"]) if tr.raw.get("stopped") else None)
    summary.update(lifted)
    if lift_warnings:
        messages.append("; ".join(lift_warnings))
        tr.warnings.extend(lift_warnings)
        tr.status = "warning" if tr.status == "ok" else tr.status
    late = _late_brakes(conveyor, scenario, summary.get("stop_time_s"))
    late += missed_controlled_stop(scenario, summary.get("stop_time_s"))
    late += missed_brake_stop(scenario, summary.get("stop_time_s"),
                              summary.get("brake_governed_by"), system.auto_brakes)
    if late:
        messages.append("; ".join(late))
        tr.warnings.extend(late)
        tr.status = "warning" if tr.status == "ok" else tr.status
    if remedy and tr.status != "failed" and any(
            (summary.get(f"drive{i + 1}_slip_s") or 0.0) > 0.0
            for i in range(len(conveyor.drives))):
        # a slip in the stop alone is not searched for the start: the first rerun says so,
        # and ``say`` is told only once the start is known to slip; a slip that reached the
        # stop is searched on its own after it (the whole cycle rerun), from the start's
        # take-up where the start slipped too
        tops: dict[str, str] = {}
        found = _slip_remedy(conveyor, scenario, model, params, opts, summary, say,
                             finer=_finer_mesh(scenario, summary, system, opts) if check
                             else None,
                             sf_min=conveyor.safety_factor_min
                             or SAFETY_FACTOR_MIN.get(steady.loop.belt.kind, 6.7), tops=tops,
                             had=steady.warnings)
        if found:
            messages.append(found)
            _unfound_levers(conveyor, system, tr, messages, summary, tops.get("start"))
        if slipped_in_stop(tr):
            stop_found = _stop_slip_remedy(
                conveyor, scenario, model, params, opts, summary, say,
                sf_min=conveyor.safety_factor_min
                or SAFETY_FACTOR_MIN.get(steady.loop.belt.kind, 6.7),
                finer=_finer_mesh(scenario, summary, system, opts) if check else None,
                had=steady.warnings)
            if stop_found is not None:
                messages.append(stop_found[0])
                _unfound_stop_levers(conveyor, system, tr, messages, stop_found[1],
                                     stop_found[2])
    if remedy and tr.status != "failed" and scenario.stop.mode == "brake":
        messages.extend(_brake_slide_remedies(conveyor, scenario, model, params, opts, summary,
                                              system, tr, say))
    if remedy and tr.status != "failed" and any(w.startswith(SAG_WARNING) for w in tr.warnings):
        messages.append(_sag_remedy(
            conveyor, scenario, model, params, opts, summary, say,
            finer=_finer_mesh(scenario, summary, system, opts) if check else None,
            sf_min=conveyor.safety_factor_min
            or SAFETY_FACTOR_MIN.get(steady.loop.belt.kind, 6.7), had=steady.warnings))
    if remedy and tr.status != "failed" and scenario.stop.mode == "coast":
        _controlled_stop_time(prep, scenario, system, tr, messages, model, params, opts, say)
    # after the remedy's rewrite, which reads the levers' own words
    _fill_estimates(conveyor, system, tr, messages, summary)
    if "failed" in (steady.status, tr.status):
        status = "failed"
    elif steady.status == "warning" or tr.status == "warning":
        status = "warning"
    else:
        status = "ok"
    summary["status"] = status
    summary["message"] = "; ".join(messages)
    run_message(summary, prep.belt_choice)
    result = RunResult(summary=summary, steady=steady, transient=tr)
    if check and status != "failed":
        result.accuracy = _error_bars(conveyor, scenario, result, model, params, opts)
    summary["elapsed_s"] = time.perf_counter() - t0
    check_summary(summary)
    return result


#: The coast's high-stress words' controlled stop, the least time a belt that follows its
#: s-curve needs (``_fast_stop_words`` in :mod:`beltstudy.engine.dynamics.simulate`).
_LEAST_CONTROLLED = re.compile(
    r"with stop\.time_s at least (\d+(?:\.\d+)?) s \(enough for a belt that follows its "
    r"s-curve, .*?names the time to ask\)")
#: Reruns of the controlled stop that :func:`_controlled_stop_time` makes at most.
CONTROLLED_RERUNS = 4


def _controlled_stop_time(prep: _Prepared, scenario: Scenario, system, tr,
                          messages: list[str], model, params, opts, say=None) -> None:
    """A coast stop faster than 5 wave loop times, on vfd drives, is offered a controlled stop
    of at least the time a belt that follows its s-curve needs, at rest from 0.884 of the
    curve. A long or soft belt's mean speed rests sooner (a 350 m fabric incline at 0.80, a
    3.6 km overland at 0.86 of the curve): four of five belts asked that least time still
    stopped under 5 loops (8.77 s for 9.59 s on the 350 m belt). The cycle is rerun with the
    controlled stop on the run's mesh, the time scaled by what each rerun gave (5 loops over
    its stop time, as the controlled stop's own words scale it), up to
    :data:`CONTROLLED_RERUNS` times, and the words give the time that met 5 loops with the
    stop it gave; they stay as they are where none did."""
    from beltstudy.engine.dynamics.simulate import _up_s, ramp_rest_fraction

    need = 5.0 * float(system.wave_loop_time_s)
    if any(d.control != "vfd" for d in prep.conveyor.drives) or not need > 0.0:
        return
    found = next(((k, m) for k, w in enumerate(tr.warnings)
                  if (m := _LEAST_CONTROLLED.search(w))), None)
    if found is None:
        return
    k, m = found
    asked = float(m.group(1))
    if say is not None:
        say("the coast stop is a high-stress stop: rerunning the cycle with the controlled "
            "stop it is offered, to confirm its time")
    tried = []
    for _ in range(CONTROLLED_RERUNS):
        scn = scenario.model_copy(update={"stop": scenario.stop.model_copy(
            update={"mode": "controlled", "time_s": asked})})
        rerun = simulate(build_system(prep.conveyor, scn, prep.steady, opts))
        got = rerun.summary.get("stop_time_s")
        if rerun.status == "failed" or got is None or not got > 0.0:
            return
        tried.append((asked, float(got)))
        if got >= need:
            break
        asked = float(_up_s(max(need * asked / float(got), asked * (1.0 + 1e-6))))
    else:
        return
    reruns = ", ".join(f"{a:g} s {'stopped it ' if i == 0 else ''}in {gnum(g, 4)} s"
                       for i, (a, g) in enumerate(tried))
    words = (f"with stop.time_s of {tried[-1][0]:g} s (this cycle rerun with the controlled "
             f"stop: {reruns}, at least 5 wave loop times, {gnum(need, 4)} s, where a belt "
             f"that follows its s-curve would rest from {ramp_rest_fraction():.3f} of it and a "
             "long or soft one's mean speed rests sooner)")
    w = tr.warnings[k]
    tr.warnings[k] = w[:m.start()] + words + w[m.end():]
    messages[:] = [x.replace(w, tr.warnings[k]) for x in messages]


def _fill_estimates(conveyor: Conveyor, system, tr, messages: list[str], summary: dict
                    ) -> None:
    """A dol drive through a fluid coupling that slipped in the start gets the fill time that
    keeps its start force within its pulley's grip. Through a fill-controlled coupling it was
    offered "a slower coupling fill (a longer coupling_fill_s)" with no amount; through a
    constant-fill one, "a fill-controlled coupling", whose default 20 s fill still slipped a
    600 m incline for 4.7 s (an 85 s fill held). The force of a stalled fill-controlled
    coupling rises with the fill, ``STALL F_rated t / t_fill``; a rigid belt starts to move
    once it passes the running force ``F_run`` (the drive's share of Te) and, for the force
    to stay within the pulley's grip ``F_grip`` (the largest force the pulley passed to the
    belt in the start, where it slipped), must be up to speed before it reaches it: the
    impulse ``(F_grip - F_run)^2 t_fill / (2 STALL F_rated)`` is at least the drive's share of
    ``M v``, so ``t_fill >= 2 m v STALL F_rated / (F_grip - F_run)^2``. The warning names it
    as a rigid-body estimate to confirm by a rerun (the 500 m incline of the tests: slip with
    20, 40, 56 and 80 s; the 101 s estimated holds)."""
    from beltstudy.engine.dynamics.laws import STALL

    te = summary.get("te_kn")
    if te is None:
        return
    drives = system.model.drives
    cyc = system.model.cycle
    t = np.asarray(tr.series["t_s"])
    start = (t >= cyc.t_pre) & (t <= system.stop_command_s)
    default_fill = Drive.model_fields["coupling_fill_s"].default
    for i, d in enumerate(conveyor.drives):
        if (d.control != "dol" or d.coupling not in ("fluid", "fluid_fill_controlled")
                or not (summary.get(f"drive{i + 1}_slip_s") or 0.0) > 0.0 or not start.any()):
            continue
        share = float(drives.share[i])
        f_run = share * float(te) * 1e3
        f_grip = float(np.max(np.asarray(tr.series[f"f_belt{i + 1}_kn"])[start])) * 1e3
        rated = float(drives.rated[i])
        if f_grip > f_run:
            need = math.ceil(2.0 * share * system.model.control.m_tot * system.v_design * STALL
                             * rated / (f_grip - f_run) ** 2)
            est = (f"about {need:.0f} s keeps the start force within the pulley's "
                   f"grip ({gnum(f_grip / 1e3)} kN passed where it slipped, {gnum(f_run / 1e3)} kN "
                   "running): a rigid-body estimate, rerun to confirm")
        else:
            est = (f"no fill keeps the start force within the pulley's grip: it slipped at "
                   f"{gnum(f_grip / 1e3)} kN, not above the running force {gnum(f_run / 1e3)} kN")
        if d.coupling == "fluid_fill_controlled":
            lever = "a slower coupling fill (a longer coupling_fill_s)"
            words = (f"a slower coupling fill (drives.{i}.coupling_fill_s, now "
                     f"{d.coupling_fill_s:g} s; {est})")
        else:
            # the grip this run's constant-fill start slipped at: a slower start loads the
            # slack side less (the 500 m incline of the tests: 54 s from its constant-fill
            # start, which slipped 3.1 s; rerun, that start's own estimate, 116 s, held), so
            # the figure is a floor, and the rerun's words name the next
            lever = "a fill-controlled coupling (coupling: fluid_fill_controlled)"
            floor = (f"at least {est}; the rerun's own words name a slower fill where it still "
                     "slips" if f_grip > f_run else est)
            words = (f"a fill-controlled coupling (drives.{i}.coupling: fluid_fill_controlled; "
                     f"its fill, drives.{i}.coupling_fill_s, {default_fill:g} s if not given: "
                     f"{floor})")
        name = f"drive {i + 1} ({d.where}) slipped on its pulley "
        for k, w in enumerate(tr.warnings):
            if w.startswith(name) and lever in w:
                tr.warnings[k] = w.replace(lever, words, 1)
                messages[:] = [m.replace(w, tr.warnings[k]) for m in messages]


def _unfound_levers(conveyor: Conveyor, system, tr, messages: list[str], summary: dict,
                    not_time: str | None = None) -> None:
    """After the slip remedy: the slip warnings of a start no longer offer a lever the remedy
    searched and did not find within its limit (a heavier take-up, for a vfd start a longer
    start), which the remedy's own sentence contradicted ("a heavier take-up ... would avoid
    it", then "avoided by no take-up up to 4 x this one"); they say what the reruns found
    instead. ``tr.warnings`` and the transient's message in ``messages`` are rewritten."""
    gravity = conveyor.takeup.type == "gravity"
    tu = summary.get("slip_free_takeup_mass_kg" if gravity else "slip_free_takeup_kn")
    _drop_unfound(system, tr, messages, "start", gravity, tu is not None,
                  reads_start_time(conveyor), summary.get("slip_free_start_time_s") is not None,
                  not_time)


def _unfound_stop_levers(conveyor: Conveyor, system, tr, messages: list[str], rem,
                         timed: bool) -> None:
    """:func:`_unfound_levers` for a slip that reached the stop, after the stop's search
    (``rem``, a :class:`~beltstudy.engine.remedy.SlipRemedy`; ``timed``: a controlled stop,
    whose ``stop.time_s`` was searched)."""
    gravity = conveyor.takeup.type == "gravity"
    tu = rem.takeup_mass_kg if gravity else rem.takeup_tension_kn
    _drop_unfound(system, tr, messages, "stop", gravity, tu is not None, timed,
                  rem.stop_time_s is not None,
                  _time_top_words("stop", rem.time_top_s, float(system.model.cycle.t_stop)))


def _time_top_words(phase: str, top_s: float | None, t0: float) -> str:
    """How far a start (stop) time search went, in words: ``N x this one`` where it went to
    :data:`~beltstudy.engine.remedy.START_MAX` (``STOP_MAX``) x the run's time ``t0``, else
    the time it reached [s] (the rigid body's floor, :func:`beltstudy.engine.remedy.
    time_top_s`)."""
    from beltstudy.engine.remedy import START_MAX, STOP_MAX

    what, most = ("start", START_MAX) if phase == "start" else ("stop.time_s", STOP_MAX)
    if top_s is None or top_s <= most * t0 * (1.0 + 1e-9):
        return f"no {what} up to {most:g} x this one"
    return f"no {what} up to {gnum(top_s, 3)} s"


def _drop_unfound(system, tr, messages: list[str], phase: str, gravity: bool, tu_found: bool,
                  time_searched: bool, time_found: bool, not_time: str | None = None) -> None:
    """The rewrite of :func:`_unfound_levers` (``phase`` ``start``) and
    :func:`_unfound_stop_levers` (``stop``): in the slip warnings of that phase, a lever the
    reruns searched and did not find is replaced by what they found."""
    from beltstudy.engine.remedy import START_MAX, STOP_MAX, TAKEUP_MAX

    if tu_found and (time_found or not time_searched):
        return
    noun = "take-up" if gravity else "pretension"
    lever_tu = heavier_takeup(system, "more slack-side tension")
    if phase == "start":
        lever_t, not_t, short_t = ("a longer start (start.time_s)",
                                   not_time or f"no start up to {START_MAX:g} x this one",
                                   "a longer start")
        spans = (("start", "start"), ("start", "running"), ("start", "stop"),
                 ("start", "stop", True))
        rerun = "rerunning the start"
    else:
        lever_t, not_t, short_t = ("a longer stop (stop.time_s)",
                                   not_time or f"no stop.time_s up to {STOP_MAX:g} x this one",
                                   "a longer stop")
        spans = (("stop", "stop"), ("running", "stop"), ("start", "stop"),
                 ("running", "stop", True), ("start", "stop", True))
        rerun = "rerunning the cycle"
    for span in spans:  # (first phase, last phase[, unbroken])
        when, fix = slip_words(*span[:2], system, *span[2:])
        parts = slip_levers(*span[:2], system, *span[2:])
        gone, nots, short = [], [], []
        if not tu_found:
            gone.append(lever_tu)
            nots.append(f"no {noun} up to {TAKEUP_MAX:g} x this one")
            short.append("a heavier take-up" if gravity else "a higher pretension")
        if time_searched and not time_found:
            gone.append(lever_t)
            nots.append(not_t)
            short.append(short_t)
        kept = [p for p in parts if p not in gone]
        found = f"{rerun} found {' and '.join(nots)} that avoids it"
        # 'did not as far as searched': the reruns stop at TAKEUP_MAX (START_MAX, STOP_MAX)
        # x the run's own; a take-up 7 x a tail-driven decline's did avoid what 4 x did not
        new = (f"{_or(kept)} would avoid it; {' or '.join(short)} did not as far as searched: "
               f"{found}" if kept else found)
        old = f"{fix} would avoid it"
        for k, w in enumerate(tr.warnings):
            if when in w and w.endswith(old):
                tr.warnings[k] = w[: -len(old)] + new
                messages[:] = [m.replace(w, tr.warnings[k]) for m in messages]


def _late_brakes(conveyor: Conveyor, scenario: Scenario, stop_time_s: float | None
                 ) -> list[str]:
    """In a brake stop, one sentence per brake whose delay (from the stop command, SPEC 6.1)
    is not shorter than the stop the run achieved (``stop_time_s`` [s]): the belt was at rest
    before that brake came on, so it took no part in the stop (it only holds the belt at rest);
    a delay of hundreds of seconds is most likely milliseconds."""
    if scenario.stop.mode != "brake" or stop_time_s is None or not math.isfinite(stop_time_s):
        return []
    out = []
    for i, b in enumerate(conveyor.brakes):
        if b.delay_s < stop_time_s:
            continue
        ms = f"; {b.delay_s / 1000:g} s if {b.delay_s:g} is ms" if b.delay_s >= 50.0 else ""
        out.append(
            f"brake {i + 1} never acted in the stop: its delay (brakes.{i}.delay_s "
            f"{b.delay_s:g} s from the stop command) is not shorter than the stop itself "
            f"({gnum(stop_time_s, 3)} s to rest), so it only holds the belt at rest: a shorter "
            f"delay_s (a brake comes on in about a second{ms}), or stop.mode: coast for the "
            "stop this was")
    return out


#: A brake stop longer than this multiple of the ``stop.time_s`` asked of its auto brakes
#: is said to have missed it: the rigid-body sizing (:func:`beltstudy.engine.design.
#: brake_force_auto`) is held to 10 % of the simulated stop where it names an achievable
#: time (issue 26's acceptance of the grip-governed brake), so a longer stop is not the
#: sizing's own error but the belt's (a sliding pulley, the elastic belt's swing).
MISSED_STOP_RATIO = 1.1


def _missed_asked(scenario: Scenario, mode: str, stop_time_s: float | None) -> float | None:
    """The ``stop.time_s`` [s] a ``mode`` stop missed: the stop (``stop_time_s``, command to
    rest) took longer than ``MISSED_STOP_RATIO`` x it; None when it did not, or the run is
    not such a stop or did not come to rest."""
    if (scenario.stop.mode != mode or stop_time_s is None
            or not math.isfinite(stop_time_s)):
        return None
    asked = float(scenario.stop.time_s)
    return asked if asked > 0.0 and stop_time_s > MISSED_STOP_RATIO * asked else None


def missed_brake_stop(scenario: Scenario, stop_time_s: float | None,
                      governed_by: str | None, auto: bool) -> list[str]:
    """In a brake stop of auto brakes (``auto``), the sentence saying the stop
    (``stop_time_s`` [s], command to rest) took longer than ``MISSED_STOP_RATIO`` x the
    ``stop.time_s`` asked of them, with what set them (``governed_by``, as
    ``brake_governed_by``) and what would bring the stop nearer the asked time; [] otherwise
    (a given brake is not sized by the stop time, so a stop time asked of it is not a target)."""
    asked = _missed_asked(scenario, "brake", stop_time_s) if auto else None
    if asked is None:
        return []
    said = (f"brake stop missed its stop.time_s: {gnum(stop_time_s, 3)} s from the stop command to "
            f"rest against the {asked:g} s asked of the auto brakes "
            f"({stop_time_s / asked:.2f} x)")
    gov = str(governed_by or "")
    if "grip" in gov:
        return [said + f" (set by {gov}: the note on the brake force names the stop time "
                "its pulleys' grip allows and what would meet the asked one)"]
    if "holding" in gov:
        return [said + f" (set by {gov}: the note on the brake force says why the stop time "
                "did not set it and what would let its pulleys pass the force)"]
    return [said + " (sized by it as a rigid body): the run's slip and end-stop warnings, "
            "where it has them, say what held it back; else the elastic belt's swing did, "
            f"and an auto brake asked for about {gnum(asked * asked / stop_time_s, 3)} s (the "
            "rigid-body force goes about as 1 / t; rerun to check) or a given "
            "brakes[].force_kn would stop it nearer the time asked"]


def missed_controlled_stop(scenario: Scenario, stop_time_s: float | None) -> list[str]:
    """In a controlled stop, the sentence saying the belt (``stop_time_s`` [s], command to
    rest) took longer than ``MISSED_STOP_RATIO`` x the ``stop.time_s`` its drives were asked
    to stop it in; [] otherwise. A belt that follows the drives' s-curve is at rest (1 % of
    design speed) from 0.884 of it, so a stop past the time asked did not follow it: a drive
    slipped, met its torque limit or rating, or the belt swung about its curve (a 600 m
    regenerating decline asked for 10 s slipped its head pulley for 13.2 s and took 15.6 s,
    and only the slip was said)."""
    asked = _missed_asked(scenario, "controlled", stop_time_s)
    if asked is None:
        return []
    return [f"controlled stop missed its stop.time_s: {gnum(stop_time_s, 3)} s from the stop "
            f"command to rest against the {asked:g} s asked of the drives "
            f"({stop_time_s / asked:.2f} x): the belt did not follow the drives' stop curve; "
            "the run's slip, torque-limit and overload warnings, where it has them, say what "
            "held it back and what would avoid it"]


def _error_bars(conveyor, scenario, result, model, params, opts):
    """The error bars of a run (:func:`beltstudy.engine.accuracy.error_bars`, reruns on a
    coarser and a finer mesh) written into its summary and message."""
    from beltstudy.engine.accuracy import error_bars

    o = _mesh_step_options(scenario, result.transient.system, opts)

    def rerun(scn: Scenario) -> dict:
        # a fixed step keeps its fraction of each mesh's limit (``o``); an automatic run's
        # finer mesh given a step (the step refined with the mesh where the automatic one
        # did not follow it, ``accuracy._step_with_the_mesh``) runs at that step
        if scn.dt_s != "auto" and scenario.dt_s != "auto":
            scn = scn.model_copy(update={"dt_s": "auto"})
        return run_one(conveyor, scn, model=model, params=params, options=o).summary

    acc = error_bars(scenario, result.summary, rerun, rtol=opts.resistance_rtol,
                     sag_limit_pct=_sag_limit(conveyor, result.transient),
                     safety_factor_min=transient_safety_min(conveyor,
                                                            result.steady.loop.belt.kind))
    acc.apply(result.summary)
    words = _radius_within_bar(result.steady.loop, result.summary,
                               acc.figures.get("liftoff_max_kn_over"))
    if words:
        result.summary["message"] = "; ".join(
            m for m in (result.summary.get("message"), words) if m)
    return acc


def _radius_within_bar(loop, summary: dict, fe) -> str:
    """The radius of a concave curve that lifts the belt in the transient, covering the lift-off
    excess's error bar (``fe``, :func:`beltstudy.engine.accuracy.error_bars`), in words ("" where
    the belt does not lift, the bar adds nothing, or the peak is at a survey grade change).
    The warning's radius ``R (T_lift + over) / T_lift`` is of the run's own mesh: a 3 km
    route's coast stop lifted 13.4 +- 35 kN (converged estimate +25 kN) and was told 642 m,
    at which the default mesh passed by 0.07 kN and twice the elements lifted 5.5 kN. The
    radius here takes the larger of the bar's top and the converged estimate."""
    from beltstudy.engine.curves import liftoff_limits_n

    over, at = summary.get("liftoff_max_kn_over"), summary.get("liftoff_at_m")
    if fe is None or over is None or at is None or not over > 0.0:
        return ""
    tops = [over + fe.err if math.isfinite(fe.err) else over]
    if fe.converged is not None and math.isfinite(fe.converged):
        tops.append(fe.converged)
    top = max(tops)
    if not top > over:
        return ""
    for c in (c for c in loop.curves if c.concave):
        el, lim = liftoff_limits_n(loop, c)
        here = np.flatnonzero(np.abs(loop.s_end_m[el] - at) < 1e-6)
        if not here.size:
            continue
        t_lift = float(lim[here].min()) / 1e3
        r_bar = math.ceil(c.radius_m * (t_lift + top) / t_lift)
        r_run = math.ceil(c.radius_m * (t_lift + over) / t_lift)
        if r_bar <= r_run:
            return ""
        return (f"within its error bar (liftoff_max_kn_over {gnum(over, 3)} +- {gnum(fe.err, 3)} kN"
                + (f", converged estimate {gnum(fe.converged, 3)} kN" if len(tops) > 1 else "")
                + f"), curve {c.k} needs a radius of at least {r_bar} m to keep the belt on "
                f"its idlers on a finer mesh too (the excess on this run's own mesh asks {r_run} m "
                "there)")
    return ""


def _sag_limit(conveyor: Conveyor, tr: TransientResult) -> float:
    """The sag limit [%] of the strand where the transient sag is largest (the sag at each
    span's low end from the lowest tension of the cycle, as ``sag_max_dyn_pct``)."""
    sag, _ = span_sag_pct(tr.system, tr.envelope_kn()[1] * 1e3)
    strand = int(tr.system.strand[int(np.argmax(sag))])
    lim = conveyor.sag_limit_pct
    return float(lim.return_ if strand == 1 else lim.carry)


def _finer_mesh(scenario: Scenario, summary: dict, system, opts: DynamicsOptions
                ) -> tuple[Scenario, DynamicsOptions]:
    """The scenario and options of the finer mesh a checked run's error bars use
    (:func:`beltstudy.engine.accuracy.error_bars`: ``RATIO`` x the elements the run used, the
    automatic step following the mesh, a fixed one kept at its fraction of the stability
    limit as :func:`_error_bars` keeps it)."""
    from beltstudy.engine.accuracy import RATIO

    o = _mesh_step_options(scenario, system, opts)
    scn = scenario.model_copy(update={"elements": RATIO * int(summary["elements_used"])})
    if scenario.dt_s != "auto":
        scn = scn.model_copy(update={"dt_s": "auto"})
    return scn, o


def _mesh_step_options(scenario: Scenario, system, opts: DynamicsOptions) -> DynamicsOptions:
    """The options of the reruns on other meshes (the error bars, :func:`_finer_mesh`): the
    step keeps the run's fraction of each mesh's stability limit (its Courant number), so a
    finer mesh also takes a finer step, as the bars promise (a mesh 4 x as fine and a quarter
    of the step, :mod:`beltstudy.engine.accuracy`).

    A fixed ``scenario.dt_s`` keeps its fraction: scaled by the asked counts it could land
    above the limit of a mesh the loop's cut made an element or two finer, and that mesh was
    lost. So does an automatic step shortened below ``dt_safety`` of the limit by the fastest
    dol drive train (:func:`beltstudy.engine.dynamics.model.drive_train_time_s`): with
    ``dt_safety`` unchanged every mesh took that same step, and the bars held no step error
    (a 1 km 14 deg EP1600/4 incline on a dol drive with a fluid coupling: the drive's peak
    force 314.7 kN on 102, 202 and 406 elements at 2.08 ms, +- 0.31 kN, and 302.4 kN at
    half the step). A coarser mesh's longer step is shortened to the train's again."""
    dt, lim = float(system.dt_s), float(system.dt_limit_s)
    if scenario.dt_s != "auto" or dt < opts.dt_safety * lim * (1.0 - 1e-9):
        return replace(opts, dt_safety=dt / lim)
    return opts


def _takeup_safety_words(summary: dict, tu_fig: float | None, gravity: bool,
                         sf_min: float | None, width_m: float | None = None) -> str:
    """The clause a slip-free take-up (``tu_fig``: a mass [kg] for a gravity take-up, a
    tension per strand [kN] for a fixed one) gains when it puts the steady belt safety factor
    below ``sf_min`` ("" otherwise). A heavier take-up lifts the tension at the take-up by
    ``(m - m_run) g / 2`` on each strand (the pretension's rise for a fixed one) and the walk
    carries that rise round the loop, so the largest tension rises by it (exactly for a
    tension-independent model, about for a sag-dependent one): ``S = rating / (T_max + dT)``.
    The remedy searched the start's slip only; its take-up could break the running check
    unsaid (a 400 m 16 deg EP1250/5 incline: 4,939 kg for 3,729 kg, T_max 119.8 -> 125.7 kN,
    S 10.44 -> 9.94 against 10). With the belt's width ``width_m`` [m] the clause names the
    rating per metre of width that keeps the minimum with that take-up, ``S_min (T_max + dT) / B``
    (as the steady check's own advice).

    The take-up is found to :data:`~beltstudy.engine.remedy.REL_TOL` of itself (the least
    slip-free figure lies between ``tu_fig (1 - REL_TOL)`` and ``tu_fig``): where the lighter
    end keeps ``sf_min``, the verdict lies within the search's error of the limit and the
    clause says it is marginal (a 250 m dol incline on EP630/4: 4,972 kg on 202 elements,
    S 9.99 against 10, and 4,937 kg, S 10.02, on 406: the verdict flipped with the mesh)."""
    t_max, rating = summary.get("t_max_kn"), summary.get("belt_rating_kn")
    base = summary.get("takeup_mass_kg") if gravity else summary.get("takeup_tension_kn")
    if None in (tu_fig, t_max, rating, base, sf_min) or tu_fig <= base:
        return ""

    def rise(tu: float) -> float:
        return (tu - base) * G / 2.0 / 1e3 if gravity else tu - base

    rise_kn = rise(tu_fig)
    sf = float(rating) / (float(t_max) + rise_kn)
    if sf >= sf_min:
        return ""
    both = ""
    if width_m:
        need = math.ceil(sf_min * (float(t_max) + rise_kn) / float(width_m))
        both = (f"; with it, a belt rated at least {need} kN/m at this width "
                f"({gnum(float(rating) / float(width_m))} kN/m now) keeps the minimum")
    marginal = ""
    lighter = max(float(base), tu_fig * (1.0 - REL_TOL))
    sf_light = float(rating) / (float(t_max) + rise(lighter))
    if sf_light >= sf_min:
        noun, amount = (("take-up", f"{lighter:,.0f} kg") if gravity
                        else ("pretension", f"{gnum(lighter)} kN"))
        marginal = (f" (marginal: the {noun} is found to {100 * REL_TOL:g} %, and "
                    f"{100 * REL_TOL:g} % less, {amount}, keeps {sf_light:.2f}: the verdict "
                    "may flip with the mesh or the step)")
    return (f" lifts the largest running tension by {gnum(rise_kn, 3)} kN, to "
            f"{gnum(float(t_max) + rise_kn)} kN: the belt safety factor falls to about {sf:.2f}, "
            f"below the minimum {sf_min:.2f}{marginal}{both}")


def _takeup_transient_words(conveyor, scenario, model, params, opts, summary: dict,
                            tu_fig: float, gravity: bool) -> str:
    """The clause a slip-free take-up (``tu_fig``: a mass [kg] for a gravity take-up, a
    tension per strand [kN] for a fixed one) gains when, rerun, its start puts the belt
    safety factor during the transient below its minimum (:func:`transient_safety_min`); ""
    otherwise. The remedy searched the start's slip only: a 600 m, +100 m incline on two dol
    drives was told "avoided by a take-up of 22,092 kg", whose start then peaked at 469.4 kN,
    a transient factor of 4.09 against 4.47, unsaid. The running factor's rise
    (:func:`_takeup_safety_words`) does not tell it: the same rise on the start's peak gave
    4.52. One rerun of the start with the take-up, on the run's mesh."""
    rating = summary.get("belt_rating_kn")
    if not rating:
        return ""
    need = transient_safety_min(conveyor, catalog.resolve_belt(conveyor.belt).kind)
    field = "mass_kg" if gravity else "pretension_kn"
    trial = conveyor.model_copy(update={"takeup": conveyor.takeup.model_copy(
        update={field: float(tu_fig)})})
    n = None if scenario.elements == "auto" else int(scenario.elements)
    steady = solve_steady(trial, model=model, params=params,
                          temperature_c=scenario.temperature_c, load=scenario.load,
                          n_elements=n)
    if steady.status == "failed":
        return ""
    system = build_system(trial, scenario, steady, opts)
    t_max = simulate(system, t_end_s=system.stop_command_s).summary.get("t_max_dyn_kn")
    if not t_max or float(rating) / float(t_max) >= need:
        return ""
    return (f" lifts the start's highest tension to {gnum(float(t_max))} kN (a rerun of the "
            f"start with it): the belt safety factor during the transient falls to about "
            f"{float(rating) / float(t_max):.2f}, below its minimum {need:.2f}")


def _warning_kind(words: str) -> str:
    """A steady warning with its figures taken out: two warnings of one kind (the same check at
    the same place) give the same."""
    return re.sub(r"-?\d[\d.,]*", "#", words.split(": ")[0])


def _takeup_steady_words(conveyor, scenario, model, params, tu_fig: float | None,
                         gravity: bool, had: list[str]) -> str:
    """The steady checks a remedy's take-up (``tu_fig``: a mass [kg] for a gravity take-up, a
    tension per strand [kN] for a fixed one) breaks that the run's did not (``had``: the
    run's own steady warnings), as a clause (""; none). The safety factor's is said by
    :func:`_takeup_safety_words`. A 2.2 km route's sag remedy, a 21,388 kg take-up, named the
    safety factor it lowered and not its horizontal curve, where the belt then ran to the
    inside (175.0 kN at the curve's end, above the 141.4 kN its loaded weight holds there).
    One steady solve, at the take-up."""
    if tu_fig is None:
        return ""
    field = "mass_kg" if gravity else "pretension_kn"
    trial = conveyor.model_copy(update={"takeup": conveyor.takeup.model_copy(
        update={field: float(tu_fig)})})
    n = None if scenario.elements == "auto" else int(scenario.elements)
    st = solve_steady(trial, model=model, params=params, temperature_c=scenario.temperature_c,
                      load=scenario.load, n_elements=n)
    if st.status == "failed":
        return ""
    kinds = {_warning_kind(w) for w in had}
    new = [w.split("; ")[0] for w in st.warnings
           if _warning_kind(w) not in kinds and not w.startswith("belt safety factor")]
    if not new:
        return ""
    amount = f"{tu_fig:,.0f} kg" if gravity else f"{gnum(tu_fig)} kN"
    noun = "take-up" if gravity else "pretension"
    return (f"; with the {noun} of {amount} the steady state also warns: "
            + "; ".join(new))


def _slip_remedy(conveyor, scenario, model, params, opts, summary, say=None,
                 finer: tuple[Scenario, DynamicsOptions] | None = None,
                 sf_min: float | None = None, tops: dict | None = None,
                 had: list[str] = ()) -> str:
    """Search what avoids a start's slip (:func:`beltstudy.engine.remedy.slip_remedy`), put the figures
    into ``summary`` and return the sentence for the message ("" when the start did not
    slip); ``tops``, when given, gets under ``start`` how far the start time search went, in
    words (:func:`_time_top_words`). With ``finer`` (the scenario and options of a checked run's finer mesh,
    :func:`_finer_mesh`) each figure is tried there too (:func:`beltstudy.engine.remedy.
    confirm_finer`): where the start still slips with it, the figure found on the finer mesh
    is the one given (the larger), and the message names both."""
    from beltstudy.engine.remedy import GROW, TAKEUP_MAX, confirm_finer, slip_remedy

    gravity = conveyor.takeup.type == "gravity"
    rem = slip_remedy(conveyor, scenario, model=model, params=params, options=opts,
                      elements=scenario.elements,
                      takeup_mass_kg=summary.get("takeup_mass_kg") if gravity else None,
                      takeup_tension_kn=None if gravity else summary.get("takeup_tension_kn"),
                      say=say)
    if rem is None:
        return ""
    # the start time as it is said, which the finer mesh tries: rounded up (26.4 s found was
    # said '26 s', and a start of 26 s still slipped 1.7 s)
    rem = replace(rem, start_time_s=said_up(rem.start_time_s))
    run_tu = rem.takeup_mass_kg if gravity else rem.takeup_tension_kn
    tu_fig, st_fig = run_tu, rem.start_time_s
    fine = None
    if finer is not None and (run_tu is not None or rem.start_time_s is not None):
        fine_scn, fine_opts = finer
        fine = confirm_finer(conveyor, fine_scn, rem, model=model, params=params,
                             options=fine_opts, elements=int(fine_scn.elements),
                             takeup_base=summary.get("takeup_mass_kg") if gravity
                             else summary.get("takeup_tension_kn"))
        tu_fig, st_fig = fine.takeup, fine.start_time_s
    summary["slip_free_takeup_mass_kg"] = tu_fig if gravity else None
    summary["slip_free_takeup_kn"] = None if gravity else tu_fig
    st_fig = said_up(st_fig)
    summary["slip_free_start_time_s"] = st_fig
    unit, noun = ("kg", "take-up") if gravity else ("kN", "pretension")
    article = "a take-up of" if gravity else "a pretension of"

    def amount(x):
        return f"{x:,.0f} {unit}"

    tu = (f"{article} {amount(tu_fig)}" if tu_fig is not None
          else f"no {noun} up to {TAKEUP_MAX:g} x this one")
    safety = _takeup_safety_words(summary, tu_fig, gravity, sf_min,
                                  conveyor.belt.width_m)
    if not safety and tu_fig is not None:
        safety = _takeup_transient_words(conveyor, scenario, model, params, opts, summary,
                                         tu_fig, gravity)
    if safety:
        safety = f"; the {noun} of {amount(tu_fig)}{safety}"
    safety += _takeup_steady_words(conveyor, scenario, model, params, tu_fig, gravity,
                                   had)
    not_time = _time_top_words("start", rem.time_top_s, float(scenario.start.time_s))
    if tops is not None:
        tops["start"] = not_time
    st = f"a start of {st_fig:g} s" if st_fig is not None else not_time
    how = (f"found by rerunning the start {rem.reruns} times on the same mesh, to 2 %; steps "
           f"of x {GROW:g}")
    if fine is not None:
        how += _finer_words(
            fine, int(summary["elements_used"]),
            f"{article} {amount(run_tu)}" if run_tu is not None else "",
            f"a start of {rem.start_time_s:g} s" if rem.start_time_s is not None else "",
            "reruns", "the figure grows as the mesh sharpens the start's front, so the finer "
            "mesh's is given (a margin above it is safer)")
    searched = [(tu_fig, tu)]
    if reads_start_time(conveyor):
        searched.append((st_fig, st))
    else:  # dol drives: the coupling softens their start
        how += ("; a dol start does not read start.time_s: its coupling sets how fast the "
                "torque comes on")
    return remedy_sentence(searched, how) + safety


def _finer_words(fine, n_run: int, takeup_words: str, time_words: str, rerun: str,
                 why: str) -> str:
    """The clause a checked run's remedy adds for the finer mesh (``fine``, a
    :class:`~beltstudy.engine.remedy.FinerCheck`; ``n_run`` the run's elements): the figures
    tried there (their words, "" for one not tried) that slipped again, with ``why`` the finer
    mesh's figure is given, or that each held; ``rerun`` names what the finer search reran."""
    moved = ([takeup_words] if fine.takeup_moved else []) + (
        [time_words] if fine.start_moved else [])
    if moved:
        return (f"; {' and '.join(moved)}, enough on this mesh ({n_run} elements), still "
                f"slipped on one twice as fine ({fine.elements} elements, {fine.reruns} more "
                f"{rerun}): {why}")
    each = "each holds" if takeup_words and time_words else "it holds"
    return f"; {each} on a mesh twice as fine too ({fine.elements} elements)"


def _stop_slip_remedy(conveyor, scenario, model, params, opts, summary, say=None,
                      sf_min: float | None = None,
                      finer: tuple[Scenario, DynamicsOptions] | None = None,
                      had: list[str] = ()):
    """Search what avoids a slip that reached the stop (:func:`beltstudy.engine.remedy.
    slip_remedy` with ``phase="stop"``: the whole cycle rerun on the run's mesh, the take-up
    and, for a controlled stop, ``stop.time_s``) and return ``(sentence, remedy, timed)``
    (None when the rerun found no slip in the stop). Where the start slipped too, the
    start's take-up figure (``slip_free_*`` in ``summary``) is tried first: where it avoids the
    stop's slip too, it is named once for both; else the stop's figure is grown from it and
    is the one that avoids both. The stop's figures are not written into ``summary`` (its
    ``slip_free_*`` fields are the start's). With ``finer`` (a checked run's finer mesh,
    :func:`_finer_mesh`) each figure is tried there too, the whole cycle rerun
    (:func:`beltstudy.engine.remedy.confirm_finer`), as the start's are: where the stop still
    slips, the finer mesh's figure is given and the message names both."""
    from beltstudy.engine.remedy import (
        GROW,
        TAKEUP_MAX,
        confirm_finer,
        reads_stop_time,
        slip_remedy,
    )

    gravity = conveyor.takeup.type == "gravity"
    start_tu = summary.get("slip_free_takeup_mass_kg" if gravity else "slip_free_takeup_kn")
    rem = slip_remedy(conveyor, scenario, model=model, params=params, options=opts,
                      elements=scenario.elements,
                      takeup_mass_kg=summary.get("takeup_mass_kg") if gravity else None,
                      takeup_tension_kn=None if gravity else summary.get("takeup_tension_kn"),
                      say=say, phase="stop", takeup_try=start_tu)
    if rem is None:
        return None
    timed = reads_stop_time(scenario)

    up = said_up
    # the stop time as it is said, which the finer mesh tries
    rem = replace(rem, stop_time_s=up(rem.stop_time_s))
    run_tu = rem.takeup_mass_kg if gravity else rem.takeup_tension_kn
    tu_fig, st_fig = run_tu, rem.stop_time_s
    fine = None
    if finer is not None and (run_tu is not None or st_fig is not None):
        fine_scn, fine_opts = finer
        if say is not None:
            say(f"trying the stop's figures on a mesh twice as fine ({int(fine_scn.elements)} "
                "elements, a whole cycle each)")
        fine = confirm_finer(conveyor, fine_scn, rem, model=model, params=params,
                             options=fine_opts, elements=int(fine_scn.elements),
                             takeup_base=summary.get("takeup_mass_kg") if gravity
                             else summary.get("takeup_tension_kn"))
        tu_fig, st_fig = fine.takeup, fine.start_time_s
    unit, noun = ("kg", "take-up") if gravity else ("kN", "pretension")
    article = "a take-up of" if gravity else "a pretension of"

    def amount(x):
        return f"{x:,.0f} {unit}"

    if tu_fig is None:
        tu = f"no {noun} up to {TAKEUP_MAX:g} x this one"
    elif rem.takeup_shared and not (fine is not None and fine.takeup_moved):
        tu = f"the {noun} of {amount(tu_fig)} found for the start"
    elif start_tu is not None and tu_fig > start_tu:
        tu = (f"{article} {amount(tu_fig)} (which avoids the start's slip too; the start's "
              f"{amount(start_tu)} still slips in the stop)")
    else:
        tu = f"{article} {amount(tu_fig)}"
    safety = ("" if rem.takeup_shared and not (fine is not None and fine.takeup_moved) else
              _takeup_safety_words(summary, tu_fig, gravity, sf_min,
                                   conveyor.belt.width_m))
    if safety:
        safety = f"; the {noun} of {amount(tu_fig)}{safety}"
    if not (rem.takeup_shared and not (fine is not None and fine.takeup_moved)):
        safety += _takeup_steady_words(conveyor, scenario, model, params, tu_fig, gravity,
                                       had)
    st_up = up(st_fig)
    st = (f"a stop.time_s of {st_up:g} s" if st_up is not None
          else _time_top_words("stop", rem.time_top_s, float(scenario.stop.time_s)))
    how = (f"found by rerunning the cycle {rem.reruns} times on the same mesh, to 2 %; steps "
           f"of x {GROW:g}")
    if fine is not None:
        how += _finer_words(
            fine, int(summary["elements_used"]),
            f"{article} {amount(run_tu)}" if run_tu is not None else "",
            f"a stop.time_s of {up(rem.stop_time_s):g} s" if rem.stop_time_s is not None
            else "", "cycles", "the finer mesh's figure is given (a margin above it is safer)")
    searched = [(tu_fig, tu)]
    if timed:
        searched.append((st_up, st))
    else:
        how += ("; a coast stop has no stop.time_s to lengthen" if scenario.stop.mode == "coast"
                else "; the brake stop's own levers (its brakes' force and ramp, an auto "
                "brake's stop.time_s) were not searched")
    return remedy_sentence(searched, how, phase="stop") + safety, rem, timed


def _brake_slide_remedies(conveyor, scenario, model, params, opts, summary, system, tr,
                          say=None) -> list[str]:
    """For each braked pulley without a drive that slid in the brake stop (not once the belt
    rested: no stop force changes what holds it then), the brake force with which it holds
    (:func:`beltstudy.engine.remedy.brake_force_remedy`, the whole cycle rerun on the run's
    mesh), in words. The slide's warning says "a smaller brake force would avoid it"; an auto
    brake held to its pulley's grip is sized by the quasi-static walk of the stop
    (:mod:`beltstudy.engine.stopgrip`), which a stop's end can pass (docs/dynamics.md,
    *Brakes within their grip*)."""
    from beltstudy.engine.remedy import brake_force_remedy

    rested = float(tr.raw["t_stopped"]) if tr.raw.get("stopped") else math.inf
    t_cmd = system.stop_command_s
    forces = [float(f) for f in system.model.brakes.force]
    gravity = conveyor.takeup.type == "gravity"
    said = []
    for slid in tr.raw.get("brake_pulley_slip", ()):
        if slid["last_s"] < t_cmd or slid["first_s"] >= rested:
            continue
        ids = [int(b) for b in slid["brakes"]]
        where = conveyor.brakes[ids[0]].where
        fields = ", ".join(f"brakes.{b}.force_kn" for b in ids)
        now = sum(forces[b] for b in ids)
        if say is not None:
            say(f"searching the brake force that keeps the {where} pulley from sliding in the "
                "stop (a whole cycle per rerun)")
        force, stop_s, reruns = brake_force_remedy(
            conveyor, scenario, model=model, params=params, options=opts,
            elements=scenario.elements, forces_n=forces, brakes=ids,
            takeup_mass_kg=summary.get("takeup_mass_kg") if gravity else None,
            takeup_tension_kn=None if gravity else summary.get("takeup_tension_kn"))
        how = f"found by rerunning the cycle {reruns} times on the same mesh, to 2 %"
        share = " in all, in their proportions" if len(ids) > 1 else ""
        if force is None:
            said.append(f"no {where} brake force down to 1/20 of its {gnum(now / 1e3)} kN keeps "
                        f"its pulley from sliding in the stop ({how}): more tension on that "
                        "pulley (take-up position or mass) would")
            continue
        then = (f"; the stop then takes {gnum(stop_s, 3)} s" if stop_s is not None else "")
        said.append(f"a {where} brake force of {kn_figure(force, up=False)} kN{share} ({fields}; now "
                    f"{gnum(now / 1e3)} kN) keeps its pulley from sliding in the stop ({how})"
                    f"{then}")
    return said


def _sag_remedy(conveyor, scenario, model, params, opts, summary, say=None,
                finer: tuple[Scenario, DynamicsOptions] | None = None,
                sf_min: float | None = None, had: list[str] = ()) -> str:
    """Search the take-up that keeps the cycle's transient sag within its limits
    (:func:`beltstudy.engine.remedy.sag_remedy`: the whole cycle rerun) and return the
    sentence for the message. The sag warning's "at least" take-up counts the whole change
    reaching the sagging span, which a stop's wave need not pass (a 400 m plant belt's brake
    stop: 2 911 kg asked, 2.66 % sag with it against 1.5 %): the sentence names the one the
    reruns found. With ``finer`` (a checked run's finer mesh, :func:`_finer_mesh`) the figure
    is tried there too, and the finer mesh's is given where the run's still sags there."""
    from beltstudy.engine.remedy import GROW, TAKEUP_MAX, sag_remedy

    gravity = conveyor.takeup.type == "gravity"
    base = summary.get("takeup_mass_kg") if gravity else summary.get("takeup_tension_kn")
    rem = sag_remedy(conveyor, scenario, model=model, params=params, options=opts,
                     elements=scenario.elements, takeup=base, finer=finer, say=say)
    unit, noun = ("kg", "take-up") if gravity else ("kN", "pretension")
    if rem is None:
        return ""

    def amount(x):
        return f"{x:,.0f} {unit}" if gravity else f"{gnum(x)} {unit}"

    how = (f"found by rerunning the whole cycle {rem.reruns} times, to 2 %; steps of "
           f"x {GROW:g}")
    if rem.finer_elements is not None and rem.takeup is not None:
        if rem.takeup != rem.run_takeup:
            how += (f"; {amount(rem.run_takeup)}, enough on this mesh "
                    f"({int(summary['elements_used'])} elements), still sagged past the limit "
                    f"on one twice as fine ({rem.finer_elements} elements): the finer mesh's "
                    "is given (a margin above it is safer)")
        else:
            how += f"; it holds on a mesh twice as fine too ({rem.finer_elements} elements)"
    if rem.takeup is None:
        return (f"transient sag not avoided by a heavier {noun}: none up to {TAKEUP_MAX:g} x "
                f"this one keeps the sag within its limits ({how})")
    safety = _takeup_safety_words(summary, rem.takeup, gravity, sf_min, conveyor.belt.width_m)
    if safety:
        safety = f"; the {noun} of {amount(rem.takeup)}{safety}"
    safety += _takeup_steady_words(conveyor, scenario, model, params, rem.takeup, gravity,
                                   had)
    return (f"transient sag within its limits with a {noun} of {amount(rem.takeup)} (the "
            f"sag warning's least {noun} counts the whole change reaching the sagging span; "
            f"{how}){safety}")


def remedy_sentence(searched: list[tuple[float | None, str]], how: str,
                    phase: str = "start") -> str:
    """The slip remedy's finding in words: ``searched`` holds per lever the figure its reruns
    found (None: none up to the search's end) and its words (``a take-up of 39,995 kg``, ``no
    start up to 6 x this one``); ``how`` how they were found. The levers found avoid the slip;
    the rest are said apart, not as an "avoided by no ..." that reads as a finding. ``phase``:
    the slip's, ``start`` or ``stop``."""
    found = [words for fig, words in searched if fig is not None]
    nots = [words for fig, words in searched if fig is None]
    if not found:  # what the reruns tried, none of which avoided the slip
        return f"slip in the {phase} not avoided: {' and '.join(nots)} avoids it ({how})"
    each = "each alone, " if len(found) > 1 else ""
    said = f"slip in the {phase} avoided by {' or by '.join(found)} ({each}{how})"
    return said + "".join(f"; {n} avoids it" for n in nots)
