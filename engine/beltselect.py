"""Belt selection: ``belt.type: auto`` picks the lightest catalogue belt that passes.

The candidates are the catalogue belts (``engine/data/belts.csv``) of the file's
``belt.kind`` (``steel_cord`` -> the catalogue's ``steel``, ``fabric`` -> ``fabric``), at the
file's width, covers (each belt's default covers where the file gives none) and compound,
tried from the lightest belt mass per metre ``m'_G = (carcass + covers x 1.15 kg/m2/mm) B``
upward. A belt changes the masses, the tensions and an auto take-up, so each candidate gets
its own steady solve (:func:`beltstudy.engine.statics.solve_steady`) at every case asked
(friction model, parameters, temperature, load, mesh; an auto take-up installed once, the
largest over the cases, :func:`_solve_cases`), and passes when at every case

1. the running safety factor ``S = k_N B / T_max`` (rating x width over the largest steady
   tension) is at least the running minimum ``safety_factor_min`` (the conveyor's, else
   :data:`~beltstudy.engine.statics.SAFETY_FACTOR_MIN` by kind: 6.7 steel cord, 10 fabric,
   typical DIN 22101 values, estimates), and
2. the start-up safety factor ``S_A = k_N B / T_max,A`` is at least the transient minimum,
   :data:`~beltstudy.engine.statics.TRANSIENT_SAFETY_RATIO` x the running one (the minimum the
   transient run's ``safety_factor_dyn`` is warned against, ``run.transient_safety_min``).
   ``T_max,A`` is the largest tension of DIN 22101's start-up state: the drives give the
   start-up factor ``p_A`` = :data:`~beltstudy.engine.statics.STARTUP_FACTOR` (1.5) x the
   steady peripheral force, the excess ``(p_A - 1) |Te|`` accelerating every moving mass, the
   take-up holding its running mean tension (:func:`beltstudy.engine.statics.startup_tensions`,
   the walk the take-up's ``slip_start`` sizing uses). It is a rigid-body estimate: the
   transient run's ``t_max_start_kn`` (wave fronts, the drives' torque limit) is the check, and
   a stop's peak (a braked stop of a decline) is checked only there.

A single run (``run_one``, ``beltstudy static``) picks at its own case and, below the full
load, also at full load (:func:`run_cases`: the belt is installed once); a study picks once
per conveyor design over its design cases (``service/grid/basis.py``) and holds the choice for
all the design's runs. The first candidate that passes is the choice; the one before it (the next lighter) is named
with its safety factors, so the margin of the choice and why a lighter belt fails are in the
run's message (a note). When no candidate passes the heaviest is used, with a warning.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass
from typing import Any

from beltstudy.engine import catalog
from beltstudy.engine.conveyor import Conveyor, section_loads
from beltstudy.engine.drives import apart
from beltstudy.engine.errors import InputError
from beltstudy.engine.statics import (
    SAFETY_FACTOR_MIN,
    TRANSIENT_SAFETY_RATIO,
    auto_width_words,
    solve_steady,
    startup_tensions,
)

__all__ = ["SteadyCase", "Candidate", "BeltChoice", "candidates", "with_belt", "select_belt",
           "resolve_auto_belt", "safety_minima", "run_message", "run_cases", "design_cases"]

#: Relative tolerance of the pass test (a factor equal to its minimum passes).
RTOL = 1e-9


@dataclass(frozen=True)
class SteadyCase:
    """One case a belt must pass: friction model, parameter overrides, temperature [C], load
    (as in a scenario) and the element count of the steady solve (None: automatic)."""

    model: str
    params: Any = None
    temperature_c: float = 20.0
    load: Any = "full"
    n_elements: int | None = None

    def label(self) -> str:
        return f"{self.model}, {self.temperature_c:g} C, load {self.load}"


@dataclass(frozen=True)
class Candidate:
    """One catalogue belt tried: mass [kg/m], breaking force rating x width [kN], the largest
    steady and start-up tensions over the cases [kN], the least safety factors [-] with the
    case of each, and whether it passes (``failed``: why a steady solve failed, else "")."""

    id: str
    mass_kg_m: float
    rating_kn: float
    t_max_kn: float
    t_max_start_kn: float
    safety_factor: float
    safety_factor_start: float
    case: str
    case_start: str
    passes: bool
    failed: str = ""

    def factors(self, sf_min: float, sf_start_min: float) -> str:
        """Both factors against their minima, in words."""
        if self.failed:
            return f"the steady solve failed ({self.failed})"

        def one(sf: float, low: float, what: str, case: str) -> str:
            passes = sf >= low * (1 - RTOL)
            # printed so the pair reads as judged (6.5487 against 6.549 was '6.55 < 6.55')
            a, b = apart(sf, low, rtol=RTOL)
            margin = 100 * (sf / low - 1)
            # a pass within RTOL reads +0 %, a fail below 0 at the decimals that show it
            m = f"{max(margin, 0.0):+.0f}" if passes else apart(margin, 0.0, 0, rtol=0.0)[0]
            return f"{a} {what} {'>=' if passes else '<'} {b} (margin {m} %, {case})"

        return (one(self.safety_factor, sf_min, "running", self.case) + ", "
                + one(self.safety_factor_start, sf_start_min, "at start-up", self.case_start))


@dataclass(frozen=True)
class BeltChoice:
    """The outcome of :func:`select_belt`: the file's kind, the minima [-], every candidate
    tried (lightest first), the choice and the next lighter (None when the choice is the
    lightest), ``passed`` False when no candidate passed (the heaviest is the choice)."""

    kind: str
    safety_factor_min: float
    safety_factor_start_min: float
    tried: tuple[Candidate, ...]
    chosen: Candidate
    lighter: Candidate | None
    passed: bool
    width_m: float = 0.0
    #: the width [m] at which the heaviest candidate passes every case, solved with the
    #: belt's own weight at that width (:func:`_width_needed`); None: not found
    width_needed_m: float | None = None

    @property
    def belt_id(self) -> str:
        return self.chosen.id

    def note(self) -> str:
        """The choice, its margins and why the next lighter fails, in words."""
        c = self.chosen
        head = (f"belt.type auto ({self.kind}): {c.id} ({c.mass_kg_m:.1f} kg/m, "
                f"{c.rating_kn:.0f} kN)")
        if not self.passed:
            return ""
        out = (f"{head}, the lightest catalogue belt that passes: safety factor "
               f"{c.factors(self.safety_factor_min, self.safety_factor_start_min)}")
        if self.lighter is None:
            return out + f"; it is the lightest {self.kind} belt of the catalogue"
        lt = self.lighter
        return (out + f"; the next lighter, {lt.id} ({lt.mass_kg_m:.1f} kg/m), fails: "
                + lt.factors(self.safety_factor_min, self.safety_factor_start_min))

    def warning(self) -> str:
        """The warning when no candidate passes ("" otherwise)."""
        if self.passed:
            return ""
        c = self.chosen
        return (f"belt.type auto ({self.kind}): no catalogue belt passes the safety factors; "
                f"the heaviest, {c.id} ({c.mass_kg_m:.1f} kg/m, {c.rating_kn:.0f} kN), is used "
                f"with safety factor {c.factors(self.safety_factor_min, self.safety_factor_start_min)}"
                + self._remedy())

    def _remedy(self) -> str:
        """What would avoid a failed choice: the width the heaviest belt needs at these
        tensions (the factor is proportional to the width, the tensions held), or lower
        tensions."""
        c = self.chosen
        if c.failed or not self.width_m:
            return "; lower tensions or a stronger belt would avoid it"
        if self.width_needed_m is not None:
            width = (f"{c.id} passes at a width of {self.width_needed_m:.2f} m (belt.width_m, "
                     f"now {self.width_m:g} m; solved again at that width, the belt's own "
                     "weight with it)")
        else:
            width = (f"at these tensions {c.id} would need a width of at least "
                     f"{self.width_estimate_m():.2f} m (not {self.width_m:g} m; more "
                     "with its own weight)")
        return (f"; {width}; lower tensions (drive force shared nearer the load, a tail or "
                "booster drive) would avoid it too")

    def width_estimate_m(self) -> float:
        """The width [m] the heaviest candidate needs at its present tensions, up to the
        centimetre: the factor is proportional to the width, the tensions held (a wider,
        heavier belt needs more, which :attr:`width_needed_m` solves for)."""
        c = self.chosen
        need = self.width_m * max(self.safety_factor_min / c.safety_factor,
                                  self.safety_factor_start_min / c.safety_factor_start)
        return math.ceil(need * 100.0) / 100.0

    def table(self) -> list[dict]:
        """One row per candidate tried: id, mass [kg/m], rating [kN], tensions [kN],
        safety factors [-], pass."""
        return [{"belt": c.id, "mass_kg_m": c.mass_kg_m, "rating_kn": c.rating_kn,
                 "t_max_kn": c.t_max_kn, "t_max_start_kn": c.t_max_start_kn,
                 "safety_factor": c.safety_factor, "safety_factor_start": c.safety_factor_start,
                 "passes": c.passes, "failed": c.failed or None} for c in self.tried]


def safety_minima(conv: Conveyor, kind: str) -> tuple[float, float]:
    """Running and start-up minimum safety factors [-] of a catalogue ``kind`` (``steel``,
    ``fabric``): the conveyor's ``safety_factor_min`` or the kind's default, and
    ``TRANSIENT_SAFETY_RATIO`` x that (as ``run.transient_safety_min``)."""
    running = conv.safety_factor_min or SAFETY_FACTOR_MIN.get(kind, 6.7)
    return float(running), float(TRANSIENT_SAFETY_RATIO * running)


#: Belt fields that override a catalogue row: a candidate is its catalogue row, so they are
#: cleared (``type: auto`` refuses them; a given belt asked for a suggestion drops them).
OVERRIDES = ("rating_kn_m", "modulus_kn_m", "dynamic_modulus_kn_m", "carcass_mass_kg_m2",
             "mass_kg_m")


def with_belt(conv: Conveyor, belt_id: str) -> Conveyor:
    """The conveyor with ``belt.type`` set to a catalogue id, its catalogue values (no
    overrides); width, covers, compound and ``kind`` kept."""
    update = {"type": belt_id, **dict.fromkeys(OVERRIDES)}
    if conv.belt.kind is not None:
        update["kind"] = catalog.FILE_KIND[catalog.belt(belt_id).kind]
    return conv.model_copy(update={"belt": conv.belt.model_copy(update=update)})


def _catalogue_kind(conv: Conveyor) -> str:
    if conv.belt.type == catalog.AUTO:
        return catalog.KIND_OF_FILE[conv.belt.kind]
    if conv.belt.type is None:
        return catalog.resolve_belt(conv.belt).kind
    return catalog.belt(conv.belt.type).kind


def candidates(conv: Conveyor) -> list[tuple[str, float, float]]:
    """``(id, mass [kg/m], rating x width [kN])`` of the catalogue belts of the conveyor's
    kind at its width, covers and compound, lightest first (then the weaker first)."""
    kind = _catalogue_kind(conv)
    out = []
    for row in catalog.belts().values():
        if row.kind != kind:
            continue
        b = catalog.resolve_belt(with_belt(conv, row.id).belt)
        out.append((row.id, b.mass_kg_m, b.rating_n / 1e3))
    return sorted(out, key=lambda r: (r[1], r[2]))


def _solve_cases(trial: Conveyor, cases: Sequence[SteadyCase]) -> list:
    """Steady solutions of ``trial`` at every case, the take-up installed once: an auto take-up
    is sized at each case, then held at the largest of them (as a study's design basis and a
    single run below full load install it, :func:`beltstudy.engine.sizing.size_over_cases`)
    and the cases it was lighter at are solved again with it. Judged with each case's own
    take-up, a pick could fail its study's runs: a fabric belt chosen at safety factor 10.51
    >= 10.5 (CEMA, -20 C) ran at 10.49 on the 6 582 kg take-up the DIN case installed."""
    def solve(conv, case):
        return solve_steady(conv, model=case.model, params=case.params,
                            temperature_c=case.temperature_c, load=case.load,
                            n_elements=case.n_elements)

    results = [solve(trial, case) for case in cases]
    tu = trial.takeup
    auto = tu.mass_kg == "auto" if tu.type == "gravity" else tu.pretension_kn == "auto"
    if not auto or len(cases) < 2 or any(r.status == "failed" for r in results):
        return results
    gravity = tu.type == "gravity"
    sizes = [r.takeup_mass_kg if gravity else r.takeup_tension_n / 1e3 for r in results]
    installed = max(sizes)
    held = trial.model_copy(update={"takeup": tu.model_copy(
        update={"mass_kg" if gravity else "pretension_kn": installed})})
    return [r if size >= installed else solve(held, case)
            for r, size, case in zip(results, sizes, cases, strict=True)]


def _evaluate(conv: Conveyor, belt_id: str, cases: Sequence[SteadyCase],
              minima: tuple[float, float]) -> Candidate:
    """Steady-solve one candidate at every case (its take-up installed once,
    :func:`_solve_cases`); its least safety factors."""
    trial = with_belt(conv, belt_id)
    b = catalog.resolve_belt(trial.belt)
    rating_n = b.rating_n
    worst = (float("inf"), 0.0, "")  # (factor, tension [N], case)
    worst_start = (float("inf"), 0.0, "")
    for case, res in zip(cases, _solve_cases(trial, cases), strict=True):
        if res.status == "failed":
            return Candidate(belt_id, b.mass_kg_m, rating_n / 1e3, float("nan"), float("nan"),
                             float("nan"), float("nan"), case.label(), case.label(), False,
                             failed=f"{case.label()}: {res.message}")
        t_max = float(res.tension_n.max())
        t_start = float(startup_tensions(res).max())
        if rating_n / t_max < worst[0]:
            worst = (rating_n / t_max, t_max, case.label())
        if rating_n / t_start < worst_start[0]:
            worst_start = (rating_n / t_start, t_start, case.label())
    sf_min, sf_start_min = minima
    passes = worst[0] >= sf_min * (1 - RTOL) and worst_start[0] >= sf_start_min * (1 - RTOL)
    return Candidate(belt_id, b.mass_kg_m, rating_n / 1e3, worst[1] / 1e3, worst_start[1] / 1e3,
                     worst[0], worst_start[0], worst[2], worst_start[2], passes)


def select_belt(conv: Conveyor, cases: Sequence[SteadyCase], *, every: bool = False
                ) -> BeltChoice:
    """The lightest catalogue belt of the conveyor's kind that passes at every case.

    Parameters
    ----------
    conv : Conveyor
        ``belt.type: auto`` with ``belt.kind``, or a given belt (its catalogue kind: what
        ``beltstudy static --suggest-belt`` asks of a file with a belt type).
    cases : sequence of SteadyCase
        The cases every safety factor must pass at (at least one).
    every : bool
        Try every candidate (the full table) instead of stopping at the first that passes.

    Returns
    -------
    BeltChoice
    """
    if not cases:
        raise ValueError("select_belt: no case to select the belt at")
    kind = _catalogue_kind(conv)
    minima = safety_minima(conv, kind)
    tried: list[Candidate] = []
    chosen = None
    for belt_id, _mass, _rating in candidates(conv):
        cand = _evaluate(conv, belt_id, cases, minima)
        tried.append(cand)
        if cand.passes and chosen is None:
            chosen = len(tried) - 1
            if not every:
                break
    passed = chosen is not None
    width_needed = None
    if chosen is None:
        chosen = len(tried) - 1
        width_needed = _width_needed(conv, tried[chosen], cases, minima)
    return BeltChoice(catalog.FILE_KIND[kind], minima[0], minima[1], tuple(tried),
                      tried[chosen], tried[chosen - 1] if chosen > 0 else None, passed,
                      float(conv.belt.width_m), width_needed)


#: Most steady re-solves :func:`_width_needed` spends on the width [-].
WIDTH_TRIES = 6


def _width_needed(conv: Conveyor, heaviest: Candidate, cases: Sequence[SteadyCase],
                  minima: tuple[float, float]) -> float | None:
    """The width [m] (up to the centimetre) at which the heaviest candidate passes every case,
    or None. The safety factor is proportional to the width at fixed tensions, but a wider
    belt is heavier and its tensions grow with it: a 6 km, 430 m-lift belt's ST5400 at 1 m
    (factor 4.007 against 6.7) was told 'about 1.67 m' and at 1.67 m reached 6.21. So the
    width is scaled by the shortfall and the cases solved again at it, until it passes."""
    if heaviest.failed or not math.isfinite(heaviest.safety_factor):
        return None
    width, cand = float(conv.belt.width_m), heaviest
    for _ in range(WIDTH_TRIES):
        short = max(minima[0] / cand.safety_factor, minima[1] / cand.safety_factor_start)
        width = math.ceil(width * short * 100.0 - 1e-6) / 100.0
        try:
            wider = conv.model_copy(update={"belt": conv.belt.model_copy(
                update={"width_m": width})})
            cand = _evaluate(wider, heaviest.id, cases, minima)
        except (ValueError, InputError):
            return None
        if cand.failed or not math.isfinite(cand.safety_factor):
            return None
        if cand.passes:
            return width
        width += 0.01 if short <= 1.0 else 0.0
    return None


def run_cases(conv: Conveyor, model: str, params: Any, temperature_c: float, load: Any,
              n_elements: int | None = None) -> list[SteadyCase]:
    """The cases a single run picks its belt at: the run's own and, for a run below the
    full design load somewhere, also the full load (the belt is installed once and carries
    the design load, as an auto take-up's counterweight does)."""
    run = SteadyCase(model, params, float(temperature_c), load, n_elements)
    if all(f == 1.0 for f in section_loads(load, conv)):
        return [run]
    return [run, SteadyCase(model, params, float(temperature_c), "full", n_elements)]


def design_cases(conv: Conveyor, cases: Sequence[Any], load: Any) -> list[SteadyCase]:
    """A study's design cases as :class:`SteadyCase` (each with the full load too, as
    :func:`run_cases`); ``cases`` are :class:`beltstudy.engine.sizing.DesignCase` (model,
    params as pairs, temperature_c, elements; a case's own ``load`` where it has one)."""
    out: list[SteadyCase] = []
    for c in cases:
        n = None if c.elements == "auto" else int(c.elements)
        for case in run_cases(conv, c.model, dict(c.params), c.temperature_c,
                              getattr(c, "load", load), n):
            if case not in out:
                out.append(case)
    return out


def resolve_auto_belt(conv: Conveyor, cases: Sequence[SteadyCase]
                      ) -> tuple[Conveyor, BeltChoice | None]:
    """The conveyor with ``belt.type: auto`` replaced by its choice at ``cases``, and the
    choice; a conveyor with a given belt comes back as it is, with None."""
    if conv.belt.type != catalog.AUTO:
        return conv, None
    choice = select_belt(conv, cases)
    return with_belt(conv, choice.belt_id), choice


def run_message(summary: dict, choice: BeltChoice | None) -> None:
    """Add the choice to a run summary's message: the note, or (no belt passes) the warning,
    which makes an ``ok`` run a ``warning``."""
    if choice is None:
        return
    if choice.passed:
        extra = "note: " + choice.note()
    else:
        extra = choice.warning()
        if summary.get("status") == "ok":
            summary["status"] = "warning"
        c = choice.chosen
        if summary.get("message") and choice.width_m and not c.failed:
            # the safety factor's warning gives the width of the same belt: one figure
            solved = choice.width_needed_m is not None
            summary["message"] = auto_width_words(
                summary["message"], c.id,
                choice.width_needed_m if solved else choice.width_estimate_m(), solved)
    summary["message"] = "; ".join(m for m in (summary.get("message"), extra) if m)
