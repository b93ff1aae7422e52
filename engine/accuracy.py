"""Error bars of a transient run's deciding figures, by systematic mesh refinement.

The practice of code verification (Roache 1994, "Perspective: a method for uniform reporting
of grid refinement studies", J. Fluids Eng. 116; ASME V&V 20-2009, section 2-4; Celik et al.
2008, "Procedure for estimation and reporting of uncertainty due to discretization in CFD
applications", J. Fluids Eng. 130, 078001): the run is repeated on a coarser and a finer mesh
(ratio :data:`RATIO`, ``n/2, n, 2n`` elements with ``n`` the run's own), the automatic step
following the mesh so the Courant number stays (a fixed ``dt_s`` keeps its fraction of the
stability limit on every mesh, :func:`beltstudy.engine.run.run_one`). For
each deciding figure ``f`` (``f3, f2, f1`` on the coarse, the run's and the fine mesh):

- ``e32 = f3 - f2`` and ``e21 = f2 - f1`` of one sign: the observed order
  ``p = ln(e32 / e21) / ln r`` (Celik's fixed point for unequal ratios) and the Richardson
  estimate ``f1 + (f1 - f2) / (r^p - 1)`` (``<figure>_converged``). The bar of the run's
  figure ``f2`` is the grid convergence index of the coarser of the two meshes,
  ``Fs |f2 - f1| r^p / (r^p - 1)``: with ``p`` within :data:`P_CLOSE` of the scheme's formal
  order :data:`P_FORMAL` (the asymptotic range) ``Fs = 1.25`` and the observed ``p`` (method
  ``richardson``); otherwise ``Fs = 3`` with ``p`` bounded to [:data:`P_MIN`,
  :data:`P_FORMAL`] (method ``gci3``; Oberkampf & Roy 2010, section 8.6.3: an observed
  order above the formal one is not credited, and an extreme behind a front converges as
  ``sqrt(dx)``, PHYSICS 5.2), and with an order above the formal one at least
  :data:`FS_RANGE` x the range of the three values (Eca & Hoekstra 2014); with an observed
  order of zero or below (the differences grow as the mesh is refined) the bar stands, with
  ``p`` at :data:`P_MIN`, but no converged estimate is given (method ``growing``). With two meshes only (one failed, or too coarse), ``p`` is
  assumed (:data:`P_ASSUMED`) and ``Fs = 3`` (method ``gci2``).
- differences of opposite signs (or a zero difference next to a non-zero one): the figure
  is not in the asymptotic range; the bar is the spread, ``Fs = 3`` x the largest distance
  of the other meshes' values from ``f2`` (method ``spread``), with no converged estimate.
- all three equal: method ``unchanged``.
- a run whose drive pulley slipped or whose belt went slack (at an automatic step) is also run
  on its own mesh at half its step: where three times its move is wider than the mesh bar,
  that is the bar (method ``step``, :func:`step_bar`), and a start time that moves with the
  step is said as a marginal verdict (the meshes keep the Courant number, which can itself
  set such an event's time).

No bar is below what the run resolves of the figure (:func:`resolution`: the step for a
time, the resistance law's relative accuracy for the rest).

The bar is of the figure the run reports, at the run's own mesh, in its unit
(``<figure>_err``); it is meant to contain the value a mesh 4 x as fine (and a quarter of the
step) gives, which ``benchmarks/check_error_bars.py`` checks on the example conveyors.

A verdict whose figure lies within its bar of the limit (slack, sag, slip margin, transient
safety factor, lift-off at a concave curve) is *marginal* (PHYSICS 5.2): :func:`marginal_verdicts` says so, with the
figure, the limit and the error, in the run's message. A run is checked with
``beltstudy.engine.run.run_one(..., check=True)``.
"""

from __future__ import annotations

import math
import re
from dataclasses import dataclass, field, replace

from beltstudy.engine.conveyor import InputError, Scenario
from beltstudy.engine.dynamics import DynamicsOptions
from beltstudy.engine.results import DECIDING
from beltstudy.engine.wording import gnum

__all__ = [
    "RATIO", "FS_THREE", "FS_TWO", "FS_SPREAD", "FS_RANGE", "P_FORMAL", "P_CLOSE", "P_MIN",
    "P_ASSUMED",
    "NON_NEGATIVE", "DECIDING", "FigureError", "Accuracy", "deciding_figures", "figure_error",
    "resolution", "bars", "error_bars", "marginal_verdicts", "step_bar",
]

#: Refinement ratio of the meshes (Roache: 2 is usual; at least 1.3).
RATIO = 2
#: Safety factors of the grid convergence index (Roache 1994): three meshes with an observed
#: order in the asymptotic range; two meshes, or an assumed order.
FS_THREE = 1.25
FS_TWO = 3.0
#: Safety factor on the spread of a figure outside the asymptotic range: its order is not
#: established, which is Roache's case for Fs = 3.
FS_SPREAD = 3.0
#: The formal order of the transient scheme: semi-implicit Euler is first order in time
#: with the explicit Kelvin-Voigt damping and the speed-dependent resistances (second order
#: only on the undamped chain), and the step follows the mesh.
P_FORMAL = 1.0
#: An observed order within this fraction of the formal one is in the asymptotic range
#: (Oberkampf & Roy 2010, Verification and Validation in Scientific Computing, 8.6.3).
P_CLOSE = 0.1
#: The lowest order used: an extreme read behind a smeared front converges as sqrt(dx)
#: (PHYSICS 5.2).
P_MIN = 0.5
#: The order assumed where it is not observed: the slowest of PHYSICS 5.2.
P_ASSUMED = 0.5
#: Safety factor on the data range of three meshes whose observed order is above the formal
#: one (Eca & Hoekstra 2014, "A procedure for the estimation of the numerical uncertainty of
#: CFD calculations based on grid refinement studies", J. Comput. Phys. 262, 104-130,
#: section 4: for p above the formal order the uncertainty is at least 1.25 x the largest
#: difference between the solutions): such an order says the finer pair agrees by chance,
#: and a bar from their difference alone is too narrow.
FS_RANGE = 1.25
#: Fewest elements of a mesh the refinement uses (the transient model's own floor is 8).
ELEMENTS_MIN = 8

_DRIVE = re.compile(r"^drive(\d+)_(.+)$")


def deciding_figures(summary: dict) -> list[str]:
    """The deciding figures ``summary`` holds as finite numbers, in :data:`DECIDING` order."""
    names = []
    for pattern in DECIDING:
        if "{i}" in pattern:
            tail = pattern.split("_", 1)[1]
            keys = sorted((k for k in summary if (m := _DRIVE.match(k)) and m.group(2) == tail),
                          key=lambda k: int(_DRIVE.match(k).group(1)))
        else:
            keys = [pattern]
        names += [k for k in keys if _finite(summary.get(k))]
    return names


def _finite(x) -> bool:
    return isinstance(x, int | float) and not isinstance(x, bool) and math.isfinite(x)


@dataclass(frozen=True)
class FigureError:
    """The error bar of one figure.

    name : the figure (a result name)
    value : the figure at the run's own mesh
    err : the bar, same unit: the value at a finer mesh is expected in value +- err
    converged : the Richardson estimate (None where not extrapolated)
    method : ``richardson`` (three meshes, observed order near the formal one, Fs 1.25),
        ``gci3`` (three meshes, order bounded, Fs 3), ``gci2`` (two meshes, assumed order,
        Fs 3), ``spread`` (not in the asymptotic range), ``step`` (the run's own mesh at half
        its step set the bar: :func:`step_bar`), ``unchanged`` or ``none``
    order : the observed order p (None where not observed)
    values : the figure on each mesh, coarse to fine (None where a mesh gave none)
    half_step : the figure on the run's mesh at half its step (None where not run)
    """

    name: str
    value: float
    err: float
    converged: float | None
    method: str
    order: float | None
    values: tuple
    half_step: float | None = None


def _order(e32: float, e21: float, r21: float, r32: float) -> float:
    """Observed order from differences of one sign, meshes in ratios r21 (fine / run) and
    r32 (run / coarse) (Celik et al. 2008, Eq. 3, fixed point; exact for r21 == r32)."""
    ratio = e32 / e21
    p = math.log(ratio) / math.log(r21)
    if abs(r21 - r32) < 1e-9:
        return p
    for _ in range(50):
        p = min(p, 50.0)  # far outside any range used; keeps r^p finite
        q = math.log((r21 ** p - 1.0) / (r32 ** p - 1.0)) if p > 1e-9 else 0.0
        p_new = (math.log(ratio) + q) / math.log(r21)
        if abs(p_new - p) < 1e-10:
            return p_new
        p = p_new
    return p


#: Deciding figures that cannot be negative: belt tensions (the model's tension floor is 0 kN,
#: a slack span), the take-up's travel, end-stop speed and clearance, the stop time, the belt
#: gathered by slack, slip margins, the safety factor and the sag. A drive's force and power
#: (regenerating), the stopping distance (run-back) and a lift-off excess may be below 0.
NON_NEGATIVE = re.compile(r"^(t_(max|min)_\w+_kn|takeup_travel\w*_m|takeup_endstop_speed_m_s|"
                          r"takeup_endstop_gap_m|stop_time_s|slack_max_m|slip_margin_min\w*|"
                          r"safety_factor_dyn|sag_max_dyn_pct)$")


def figure_error(name: str, values: tuple, elements: tuple[int, int, int],
                 floor: float = 0.0) -> FigureError | None:
    """The bar of one figure from its ``values`` on three meshes of ``elements`` (coarse, the
    run's, fine; a value may be None where that mesh gave none), at least ``floor`` (the
    run's resolution of that figure, :func:`resolution`). None when the run's own value is
    missing.

    An extrapolation below 0 of a figure that cannot be negative (:data:`NON_NEGATIVE`: a
    lowest tension of 47.9 kN on 10 elements and 18.2 kN on 22 extrapolates, at the assumed
    order 0.5, to -43.2 kN) is no estimate of it: the meshes are not where the extrapolation
    holds, and no converged estimate is given; the bar stands."""
    fe = _figure_error(name, values, elements)
    if fe is None:
        return None
    conv = fe.converged
    if conv is not None and conv < 0.0 and NON_NEGATIVE.match(name):
        conv = None
    if fe.err < floor or conv is not fe.converged:
        fe = FigureError(fe.name, fe.value, max(fe.err, float(floor)), conv, fe.method,
                         fe.order, fe.values)
    return fe


def resolution(name: str, summary: dict, rtol: float) -> float:
    """What a run resolves of a figure, the floor of its bar: a time is read at a step
    (``dt_used_s``); any other figure carries the relative accuracy ``rtol`` of the
    resistance law between its exact evaluations (``DynamicsOptions.resistance_rtol``). A
    lift-off margin (``liftoff_*``, T - T_lift) carries that of the tension T at the curve,
    not of the margin, which is near 0 where the verdict is close: ``rtol`` x the cycle's
    highest tension ``t_max_dyn_kn`` (T is at most that)."""
    value = summary.get(name)
    if not _finite(value):
        return 0.0
    if name.endswith("_time_s") or name == "stop_time_s":
        return float(summary.get("dt_used_s") or 0.0)
    if name.startswith("liftoff_") and _finite(summary.get("t_max_dyn_kn")):
        return rtol * max(abs(float(value)), abs(float(summary["t_max_dyn_kn"])))
    return rtol * abs(float(value))


#: A cycle's figure and its phases' (the cycle's is the lowest or highest of theirs).
CYCLE_PHASES = (
    ("t_min_dyn_kn", ("t_min_start_kn", "t_min_stop_kn"), min),
    ("t_max_dyn_kn", ("t_max_start_kn", "t_max_stop_kn"), max),
    ("slip_margin_min_dyn", ("slip_margin_min_start_dyn", "slip_margin_min_stop_dyn"), min),
    ("liftoff_max_kn_over", ("liftoff_over_start_kn", "liftoff_over_stop_kn"), max),
)


def step_bar(fe: FigureError, half: float | None) -> FigureError:
    """``fe`` with the step's error where it is the larger: ``half`` the figure on the run's
    own mesh at half its step. The explicit scheme is first order in the step at a fixed
    mesh, so the run's value is off by about ``f(dt) - f(dt / 2)`` (Richardson, p = 1) and
    the converged estimate is ``2 f(dt / 2) - f(dt)``; two runs, so Fs 3 (:data:`FS_TWO`,
    Roache). The mesh bars refine the step with the mesh (the Courant number stays) and
    cannot see an error set by the Courant number itself: a 100 m incline whose tail drive
    slipped against a slack fixed take-up read a start of 14.18 s at the automatic step,
    12.17, 10.54, 10.14 and 10.16 s at a half, a quarter, an eighth and a sixteenth of it,
    and 10.57 s on twice the elements at a quarter."""
    if not _finite(half) or not math.isfinite(fe.err):
        return fe
    d = fe.value - float(half)
    err = FS_TWO * abs(d)
    if err <= fe.err:
        return replace(fe, half_step=float(half))
    conv = float(half) - d
    if conv < 0.0 and NON_NEGATIVE.match(fe.name):
        conv = None  # (as figure_error: no estimate of a figure that cannot be negative)
    return replace(fe, err=err, converged=conv, method="step", order=None,
                   half_step=float(half))


def bars(runs: list, elements: tuple, rtol: float, half: dict | None = None) -> dict:
    """The bar of every deciding figure of the run ``runs[1]`` from its summaries on three
    meshes (coarse, the run's, fine; None for a mesh that gave none) of ``elements``.

    A cycle's extreme is the lower (higher) of its phases': where the phase that holds it
    changes between meshes, its three values come from different phases and miss how the
    other phase's converges (a 1.6 km decline's slip margin: 1.31, the rest's, on 103 and 205
    elements, 1.26 on 409, while the stop's fell 1.51, 1.44, 1.26 and on to 0.96 on 3 279).
    The cycle's bar therefore also covers each phase's range, ``min(v_p - e_p)`` to
    ``min(v_p + e_p)`` (``max`` for a highest figure), where it is wider. ``half``: the
    run's summary on its own mesh at half its step, where it was run (:func:`step_bar`)."""
    out = {}
    for name in deciding_figures(runs[1]):
        vals = tuple(None if s is None else s.get(name) for s in runs)
        fe = figure_error(name, vals, elements, resolution(name, runs[1], rtol))
        if fe is not None and half is not None:
            fe = step_bar(fe, half.get(name))
        if fe is not None:
            out[name] = fe
    for cycle, phases, pick in CYCLE_PHASES:
        fe = out.get(cycle)
        own = [out[p] for p in phases if p in out and math.isfinite(out[p].err)]
        if fe is None or not own or not math.isfinite(fe.err):
            continue
        lo = pick(p.value - p.err for p in own)
        hi = pick(p.value + p.err for p in own)
        err = max(fe.err, fe.value - lo, hi - fe.value)
        if err > fe.err:
            out[cycle] = replace(fe, err=err)
    return out


def _figure_error(name: str, values: tuple, elements: tuple[int, int, int]
                  ) -> FigureError | None:
    f3, f2, f1 = values
    n3, n2, n1 = elements
    if not _finite(f2):
        return None
    have3, have1 = _finite(f3), _finite(f1)
    tiny = 1e-12 * max(1.0, abs(f2))

    def gci2(fa: float, fb: float, r: float) -> FigureError:
        """Two meshes, assumed order, Fs 3: ``fa`` the coarser, ``fb`` the finer value."""
        rp = r ** P_ASSUMED - 1.0
        conv = fb + (fb - fa) / rp
        return FigureError(name, f2, FS_TWO * abs(f2 - conv), conv, "gci2", None, values)

    if have3 and have1:
        e32, e21 = f3 - f2, f2 - f1
        if abs(e32) <= tiny and abs(e21) <= tiny:
            return FigureError(name, f2, 0.0, f2, "unchanged", None, values)
        if abs(e32) <= tiny or abs(e21) <= tiny or (e32 > 0) != (e21 > 0):
            spread = max(abs(e32), abs(e21))
            return FigureError(name, f2, FS_SPREAD * spread, None, "spread", None, values)
        r21, r32 = n1 / n2, n2 / n3
        p = _order(e32, e21, r21, r32)
        if abs(p - P_FORMAL) <= P_CLOSE * P_FORMAL:
            fs, p_used, method = FS_THREE, p, "richardson"
        elif p <= 0.0:  # the differences grow with refinement: no order, no converged value
            fs, p_used, method = FS_TWO, P_MIN, "growing"
        else:  # not shown to be asymptotic: Fs 3, the order bounded (Oberkampf & Roy 2010)
            fs, p_used, method = FS_TWO, min(max(P_MIN, p), P_FORMAL), "gci3"
        conv = f1 + (f1 - f2) / (r21 ** p_used - 1.0)
        err = fs * abs(f2 - conv)
        if p > P_FORMAL * (1.0 + P_CLOSE):
            # an order above the formal one: the finer pair may agree by chance (a lowest
            # tension of 37.77, 36.818 and 36.808 kN on 106, 204 and 412 elements, p 6.9,
            # gave +- 0.06 kN; 820 elements read 36.39 kN): at least 1.25 x the data range
            err = max(err, FS_RANGE * (max(f3, f2, f1) - min(f3, f2, f1)))
        # differences that grow with refinement (p <= 0) converge to no value that three
        # meshes show: the bar stands (with the order bounded), no estimate is given
        return FigureError(name, f2, err, conv if p > 0.0 else None, method, p, values)
    if have1:
        if abs(f2 - f1) <= tiny:
            return FigureError(name, f2, 0.0, f2, "unchanged", None, values)
        return gci2(f2, f1, n1 / n2)
    if have3:
        if abs(f3 - f2) <= tiny:
            return FigureError(name, f2, 0.0, f2, "unchanged", None, values)
        return gci2(f3, f2, n2 / n3)
    return FigureError(name, f2, math.nan, None, "none", None, values)


@dataclass
class Accuracy:
    """The error bars of a run.

    elements : the meshes, coarse to fine (the run's in the middle; None for one not run)
    figures : the bar of each deciding figure, by name
    marginal : the marginal verdicts in words (``marginal: ...``)
    notes : meshes that could not be run, and why
    """

    elements: tuple
    figures: dict = field(default_factory=dict)
    marginal: list = field(default_factory=list)
    notes: list = field(default_factory=list)

    def fields(self) -> dict:
        """``<figure>_err`` and ``<figure>_converged`` of every figure, ``accuracy_elements``
        and ``accuracy_methods`` (the result fields of :data:`beltstudy.engine.results.ACCURACY`)."""
        out: dict = {"accuracy_elements": "/".join("-" if n is None else str(n)
                                                   for n in self.elements),
                     "accuracy_methods": self.methods()}
        for name, fe in self.figures.items():
            out[f"{name}_err"] = None if math.isnan(fe.err) else fe.err
            out[f"{name}_converged"] = fe.converged
        return out

    def apply(self, summary: dict) -> dict:
        """Write the bars into a run's ``summary``: the :meth:`fields`, the marginal verdicts
        and the meshes that could not be run appended to its message (a run ``ok`` with a
        marginal verdict becomes ``warning``). Returns ``summary``."""
        summary.update(self.fields())
        notes = [f"note: error bars from two meshes, {n}" for n in self.notes]
        if self.marginal or notes:
            summary["message"] = "; ".join(
                m for m in (summary.get("message"), *self.marginal, *notes) if m)
        if self.marginal and summary.get("status") == "ok":
            summary["status"] = "warning"
        return summary

    def methods(self) -> str:
        """Each figure's method, grouped: ``richardson: a (p 0.8), b (p 1.1); spread: c``;
        the observed order, with the bounded one the bar used where ``gci3`` bounds it
        (``gci3: d (p 4.2 observed, 1 used)``)."""
        groups: dict[str, list[str]] = {}
        for name, fe in self.figures.items():
            words = name if fe.order is None else f"{name} (p {fe.order:.2g})"
            if fe.method == "step":
                words = f"{name} ({gnum(fe.half_step, 4)} at half the step)"
            if fe.method == "gci3":
                used = min(max(P_MIN, fe.order), P_FORMAL)
                if f"{used:.2g}" != f"{fe.order:.2g}":
                    words = f"{name} (p {fe.order:.2g} observed, {used:.2g} used)"
            groups.setdefault(fe.method, []).append(words)
        return "; ".join(f"{m}: {', '.join(v)}" for m, v in groups.items())


def _mesh_scenario(scenario: Scenario, n_run: int, n: int) -> Scenario:
    """The scenario on ``n`` elements; a fixed step scaled with the mesh (same Courant
    number), the automatic one following it by itself."""
    update: dict = {"elements": int(n)}
    if scenario.dt_s != "auto":
        update["dt_s"] = float(scenario.dt_s) * n_run / n
    return scenario.model_copy(update=update)


#: The finer mesh's automatic step follows the mesh when it is at most this fraction of the
#: run's (halving the elements halves it, 0.48 to 0.51 on every example conveyor); above it
#: something the mesh does not refine sets the step (a curve's arc elements, cut by the turn,
#: not the mesh; a dol drive train), and the finer run is given the step refined with the
#: mesh instead.
STEP_FOLLOWS = 0.6


def _step_with_the_mesh(scenario: Scenario, summary: dict, fine: dict, m: int,
                        rerun) -> dict:
    """The finer mesh's run with the step refined with the mesh (PHYSICS 5.2: the Courant
    number stays): ``fine`` itself where its automatic step followed the mesh (at most
    :data:`STEP_FOLLOWS` of the run's), else a rerun at the run's step x ``n / n_fine``.
    Without it the bar of a route whose step a curve's arc sets held no step error: an
    820 m incline's stop slip margin read 1.029 +- 0.032, 'converged estimate 1.04, which
    passes', where halving and quartering the step gave 1.004 and 0.991, a slip."""
    dt, dt_fine = summary.get("dt_used_s"), fine.get("dt_used_s")
    n, n_fine = summary.get("elements_used"), fine.get("elements_used")
    if (scenario.dt_s != "auto" or not dt or not dt_fine or not n or not n_fine
            or float(dt_fine) <= STEP_FOLLOWS * float(dt)):
        return fine
    want = float(dt) * int(n) / int(n_fine)
    try:
        return rerun(scenario.model_copy(update={"elements": int(m), "dt_s": want}))
    except InputError:
        return fine  # (a step the run refuses: the automatic one's bar, as before)


def error_bars(scenario: Scenario, summary: dict, rerun, *,
               rtol: float = DynamicsOptions.resistance_rtol,
               sag_limit_pct: float | None = None,
               safety_factor_min: float | None = None) -> Accuracy:
    """The error bars of the run of ``scenario`` whose summary is ``summary``: reruns on
    ``n / RATIO`` and ``n x RATIO`` elements, ``n`` the run's ``elements_used``.

    Parameters
    ----------
    scenario : Scenario
        The run's scenario (its ``elements`` and a fixed ``dt_s`` are changed per mesh).
    summary : dict
        The run's summary.
    rerun : callable
        ``rerun(scenario) -> summary`` of the same conveyor, model and options
        (:func:`beltstudy.engine.run.run_one`); it may raise ``InputError`` (that mesh is
        left out).
    rtol : float
        The resistance law's relative accuracy (``DynamicsOptions.resistance_rtol``), the
        floor of a bar (:func:`resolution`) [-].
    sag_limit_pct, safety_factor_min : float, optional
        The limits of the marginal verdicts: the sag limit of the strand where the run's sag
        is largest [%], the transient safety factor limit
        (:func:`beltstudy.engine.run.transient_safety_min`) [-].
    """
    n = int(summary["elements_used"])
    meshes = (max(ELEMENTS_MIN, n // RATIO), n, n * RATIO)
    runs: list[dict | None] = []
    fine_dt = None  # the finest mesh's step where it was given, not automatic
    acc = Accuracy(elements=meshes)
    for k, m in enumerate(meshes):
        if k == 0 and m >= n:
            runs.append(None)
            acc.notes.append(f"no mesh coarser than {n} elements (the fewest is {ELEMENTS_MIN})")
            continue
        if k == 1:
            runs.append(summary)
            continue
        try:
            other = rerun(_mesh_scenario(scenario, n, m))
        except InputError as exc:
            runs.append(None)
            acc.notes.append(f"{m} elements not run: {exc}")
            continue
        if k == 2 and other.get("status") != "failed":
            stepped = _step_with_the_mesh(scenario, summary, other, m, rerun)
            if stepped is not other:  # run at a given step: the advice names one too
                fine_dt = stepped.get("dt_used_s")
            other = stepped
        if other.get("status") == "failed":
            runs.append(None)
            acc.notes.append(f"{m} elements failed: {other.get('message')}")
            continue
        runs.append(other)
    # the mesh a run used (the loop's cut may add an element or two to the asked count)
    used = tuple(int(s["elements_used"]) if s is not None and s.get("elements_used") else m
                 for s, m in zip(runs, meshes, strict=True))
    if runs[0] is not None and used[0] >= used[1]:
        # the coarse mesh asked came out no coarser than this run's own: the fewest belt
        # elements, with one element per pulley on top
        runs[0] = None
        acc.notes.append(f"no mesh coarser than {n} elements ({meshes[0]} asked gave "
                         f"{used[0]} with the pulleys; the fewest is {ELEMENTS_MIN} belt elements)")
    used = tuple(None if s is None else u for s, u in zip(runs, used, strict=True))
    acc.elements = used
    half = _half_step(scenario, summary, rerun, acc)
    acc.figures = bars(runs, used, rtol, half)
    acc.marginal = marginal_verdicts(summary, acc.figures, sag_limit_pct=sag_limit_pct,
                                     safety_factor_min=safety_factor_min, finest=used[-1],
                                     finest_dt_s=fine_dt if runs[-1] is not None else None)
    if half is not None:
        acc.marginal += _start_with_the_step(summary, half)
    return acc


#: A drive pulley that slips or a belt gone slack: events a force crossing a grip or a
#: tension crossing zero decides, whose time the step moves at a fixed mesh.
_STEP_EVENTS = re.compile(r"^drive\d+_slip_s$")


def _step_events(summary: dict) -> bool:
    """The run had a drive pulley slip or the belt go slack (:data:`_STEP_EVENTS`)."""
    if _finite(summary.get("slack_max_m")) and summary["slack_max_m"] > 0.0:
        return True
    return any(_STEP_EVENTS.match(k) and _finite(v) and v > 0.0 for k, v in summary.items())


def _half_step(scenario: Scenario, summary: dict, rerun, acc: Accuracy) -> dict | None:
    """The run on its own mesh at half its automatic step, where a drive pulley slipped or
    the belt went slack in it (:func:`_step_events`; None otherwise, or for a step the file
    gives). The meshes refine the step with the mesh and keep the Courant number, which is
    what sets such an event's time (:func:`step_bar`)."""
    dt = summary.get("dt_used_s")
    if scenario.dt_s != "auto" or not _finite(dt) or not _step_events(summary):
        return None
    try:
        half = rerun(scenario.model_copy(update={"dt_s": 0.5 * float(dt)}))
    except InputError as exc:
        acc.notes.append(f"half the step not run: {exc}")
        return None
    if half.get("status") == "failed":
        acc.notes.append(f"half the step failed: {half.get('message')}")
        return None
    return half


def _start_with_the_step(summary: dict, half: dict) -> list[str]:
    """The start time against the run's at half the step, in words where they differ by more
    than 1 % (or one reached design speed and the other did not): the start time has no bar
    of its own, and an event the step moves can move it by seconds."""
    a, b = summary.get("start_time_s"), half.get("start_time_s")
    dt = float(summary.get("dt_used_s") or 0.0)
    step = f"the run's step ({gnum(dt, 3)} s)"
    why = ("a drive pulley slipping or the belt going slack in it, whose times the step "
           "moves; a smaller scenario.dt_s settles it")
    if a is None and b is None:
        return []
    if a is None or b is None:
        at, never = ("half the step", step) if a is None else (step, "half the step")
        t = b if a is None else a
        return [f"marginal: start_time_s: the belt reached 99 % of design speed at {at} "
                f"({gnum(t, 4)} s) and not at {never}: {why}"]
    if abs(a - b) <= max(0.01 * abs(a), 2.0 * dt):
        return []
    return [f"marginal: start_time_s {gnum(a, 4)} s at {step}, {gnum(b, 4)} s at half of it "
            f"(about {gnum(2.0 * b - a, 4)} s converged, the step's first order): {why}"]


def _held_on_a_mesh(fe: FigureError | None) -> bool:
    """Whether a slip margin's check held on one of its meshes (above 1 there: no pulley
    reached its grip), the slip of the run's own mesh then a verdict the mesh flips."""
    return fe is not None and any(v is not None and math.isfinite(v) and v > 1.0
                                  for v in (fe.values or ()))


def _marginal(fe: FigureError | None, limit: float, unit: str, higher_passes: bool,
              finest: int | None = None, finest_dt_s: float | None = None) -> str | None:
    """The words of a verdict within ``fe``'s bar of ``limit``, else None. ``higher_passes``:
    a value above the limit passes the check (a lowest tension above 0 kN), else one below it
    (a sag under its limit); ``finest`` the elements of the finest mesh run. The words give
    the finest mesh's value, the Richardson estimate's side of the limit where there is one,
    and the finer mesh that narrows the bar (the bar shrinks with the mesh at the observed
    order); ``finest_dt_s`` the finest mesh's step where it was given (the automatic one did
    not follow the mesh): the finer mesh named then comes with its own step, as an automatic
    one would not refine it."""
    if fe is None or not math.isfinite(fe.err) or fe.err <= 0.0:
        return None
    if fe.method == "unchanged":
        # the same on every mesh: its bar is only the run's resolution (the floor), and no
        # mesh moves the verdict (a belt held at rest on a take-up sized to the grip limit)
        return None
    if abs(fe.value - limit) > fe.err:
        return None
    u = f" {unit}" if unit else ""
    if fe.method == "step":
        return _marginal_step(fe, limit, u, higher_passes)
    vals = [v for v in (fe.values or ()) if v is not None and math.isfinite(v)]
    side = fe.value - limit
    dist = [abs(v - limit) for v in vals]
    if (len(vals) == 3 and side != 0.0 and all((v - limit) * side > 0.0 for v in vals)
            and dist[0] <= dist[1] < dist[2]):
        # every mesh run gives the same verdict, each finer one further from the limit:
        # refining moves away from a flip (a wide spread bar alone, as a sag of 50.8 %
        # +- 133 % against 1.5 % that is 63.7 % on the finer mesh, is no flip)
        return None
    said = ["the verdict may flip with the mesh"]
    fine = fe.values[-1] if fe.values else None
    if fine is not None and finest:
        said.append(f"{_beside(fine, limit)}{u} on {finest} elements")
    conv = fe.converged
    if conv is not None and math.isfinite(conv):
        side = ("at the limit" if conv == limit else
                "which passes" if (conv > limit) == higher_passes else "which fails")
        said.append(f"converged estimate {_beside(conv, limit)}{u}, {side}")
    if finest and finest_dt_s:
        said.append(f"a finer mesh and step (scenario.elements {2 * finest}, scenario.dt_s "
                    f"{gnum(finest_dt_s / 2, 3)}) narrow the bar")
    elif finest:
        said.append(f"a finer mesh (scenario.elements {2 * finest}) narrows the bar")
    return (f"marginal: {fe.name} {_beside(fe.value, limit)} against limit {limit:g} +- "
            f"{gnum(fe.err, 3)}{u} "
            f"({'; '.join(said)})")


def _marginal_step(fe: FigureError, limit: float, u: str, higher_passes: bool) -> str | None:
    """:func:`_marginal` of a bar the half step set (method ``step``): None where half the
    step gives the same verdict further from the limit (refining moves away from a flip)."""
    side, h = fe.value - limit, fe.half_step
    if side != 0.0 and (h - limit) * side > 0.0 and abs(h - limit) > abs(side):
        return None
    said = ["the verdict may flip with the step", f"{_beside(h, limit)}{u} at half the step"]
    conv = fe.converged
    if conv is not None and math.isfinite(conv):
        where = ("at the limit" if conv == limit else
                 "which passes" if (conv > limit) == higher_passes else "which fails")
        said.append(f"converged estimate {_beside(conv, limit)}{u}, {where}")
    said.append("a smaller step (scenario.dt_s) narrows the bar")
    return (f"marginal: {fe.name} {_beside(fe.value, limit)} against limit {limit:g} +- "
            f"{gnum(fe.err, 3)}{u} ({'; '.join(said)})")


def _beside(value: float, limit: float) -> str:
    """``value`` beside the ``limit`` it is judged against [any unit]: four significant
    figures, more (up to ten) where four print it as the limit though it differs (a slip
    margin of 1.00003 against 1 read "1 against limit 1", and its converged estimate 0.99996
    "1, which fails")."""
    for digits in range(4, 11):
        text = gnum(value, digits)
        if (text != f"{limit:.{digits}g}"
                or abs(value - limit) <= 1e-9 * max(abs(value), abs(limit))):
            return text
    return text


def marginal_verdicts(summary: dict, figures: dict, *, sag_limit_pct: float | None = None,
                      safety_factor_min: float | None = None, finest: int | None = None,
                      finest_dt_s: float | None = None) -> list[str]:
    """The verdicts whose figure lies within its error bar of the limit (PHYSICS 5.2), of the
    figures that move with the mesh (one the same on every mesh, method ``unchanged``, has
    only the run's resolution for a bar and no mesh flips its verdict: an auto take-up sized
    to a slip margin of exactly 1 with the belt held at rest):

    - slack: a belt that went slack by less than the error of ``slack_max_m`` (limit 0 m),
      or one that did not by less than the error of its lowest tension ``t_min_dyn_kn``
      (limit 0 kN); where it went slack in one phase only, also the other phase's lowest
      tension (``t_min_start_kn`` or ``t_min_stop_kn``, limit 0 kN): a span there that
      did not go slack is judged by its sag, a verdict that turns into slack on the mesh
      where that tension reaches 0 kN;
    - sag: ``sag_max_dyn_pct`` against ``sag_limit_pct``, the limit of the strand where the
      sag is largest;
    - slip: ``slip_margin_min_dyn`` against 1, when no drive slipped (a slip is reported
      by itself), or when one did and a mesh of the check held (its margin above 1);
    - safety factor: ``safety_factor_dyn`` against ``safety_factor_min``;
    - a high-stress stop: ``stop_time_s`` against 5 wave loop times (``wave_loop_time_s``;
      Harrison after Funke 1973), of a belt that reached design speed (``start_time_s``);
    - take-up end stop: a carriage that reached one by an impact speed
      ``takeup_endstop_speed_m_s`` within its error of 0 m/s, or one that did not by a
      clearance ``takeup_endstop_gap_m`` within its error of 0 m;
    - lift-off: ``liftoff_max_kn_over`` (the most the tension at a concave curve or survey
      grade change exceeded its lift-off tension, > 0 the belt lifted) against 0 kN, where
      the run has one (:func:`beltstudy.engine.curves.transient_liftoff`); and each phase's,
      ``liftoff_over_start_kn`` and ``liftoff_over_stop_kn``, on its own bar: a phase's
      excess under the other's on the run's mesh may pass it on a finer one, which the
      cycle's figure on three meshes does not show. A phase holding the cycle's value is
      said only when the cycle's line has not said it: its bar, from that phase's own three
      meshes, can reach 0 where the cycle's (whose three values may come from different
      phases) does not.

    Each verdict says what would settle it (:func:`_marginal`): the finest mesh's value
    (``finest`` its elements), the side of the limit its converged estimate lies on, and the
    finer mesh that narrows the bar.
    """
    slack = (summary.get("slack_max_m") or 0.0) > 0.0
    # (figure, limit, unit, a value above the limit passes)
    checks = [("slack_max_m", 0.0, "m", False) if slack else ("t_min_dyn_kn", 0.0, "kN", True)]
    if slack:
        # a phase that did not go slack (its lowest tension above 0 kN) while the other did:
        # the cycle's slack verdict says nothing of it, and its lowest tension within its bar
        # of 0 kN may go slack on a finer mesh (a 1 km 14 deg incline on a dol drive, slack
        # in the stop: the return near the tail fell to 0.087 kN +- 0.52 kN in the start on
        # 202 elements, a sag of 100 % past its 3 % limit, and to 0 kN on 406, where a slack
        # span's sag has no value and the start's verdict was gone)
        checks += [(name, 0.0, "kN", True) for name in ("t_min_start_kn", "t_min_stop_kn")
                   if _finite(summary.get(name)) and summary[name] > 0.0]
    if sag_limit_pct is not None:
        checks.append(("sag_max_dyn_pct", float(sag_limit_pct), "%", False))
    slipped = any((v or 0.0) > 0.0 for k, v in summary.items()
                  if k.startswith("drive") and k.endswith("_slip_s"))
    if not slipped or _held_on_a_mesh(figures.get("slip_margin_min_dyn")):
        # a slip that happened is its own verdict, the margin then at its floor, unless a
        # mesh of the check held (a margin above 1 there): a 350 m 16 deg incline slipped
        # 5.7e-5 m at 0.9953 +- 0.0717 on 203 elements and held at 1.003 on 103
        checks.append(("slip_margin_min_dyn", 1.0, "", True))
    if safety_factor_min is not None:
        checks.append(("safety_factor_dyn", float(safety_factor_min), "", True))
    wave = summary.get("wave_loop_time_s")
    if (_finite(summary.get("stop_time_s")) and _finite(wave) and wave > 0.0
            and summary.get("start_time_s") is not None):
        # the 5-wave-loop rule (a high-stress stop below it; judged of a belt that reached
        # design speed): a 2.5 km belt's controlled stop rested in 18.7215 +- 0.0067 s
        # against 5 x 3.74418 s = 18.7209 s, 'ok', and in 18.7203 s on twice the elements,
        # a high-stress stop, unnamed
        checks.append(("stop_time_s", 5.0 * float(wave), "s", True))
    checks.append(("takeup_endstop_speed_m_s", 0.0, "m/s", False)
                  if (summary.get("takeup_endstop_speed_m_s") or 0.0) > 0.0
                  else ("takeup_endstop_gap_m", 0.0, "m", True))
    said = [_marginal(figures.get(name), limit, unit, up, finest, finest_dt_s)
            for name, limit, unit, up in checks]
    # lift-off (no bar without a concave curve): the cycle's, then a phase's other peak
    cycle = figures.get("liftoff_max_kn_over")
    cycle_said = _marginal(cycle, 0.0, "kN", False, finest, finest_dt_s)
    said.append(cycle_said)
    for name in ("liftoff_over_start_kn", "liftoff_over_stop_kn"):
        fe = figures.get(name)
        if fe is not None and not (cycle_said and fe.value == cycle.value):
            said.append(_marginal(fe, 0.0, "kN", False, finest, finest_dt_s))
    return [words for words in said if words]
