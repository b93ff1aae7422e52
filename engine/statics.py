"""Steady running tensions, take-up sizing and design checks (PHYSICS section 1).

The tension is walked round the loop, ``T[j] = T[j-1] + R_j + G_j - D_j``, with ``R_j`` the
friction model's resistance law at the design speed, ``G_j`` the gravity component and
``D_j`` the drive forces (their shares of Te = sum(R + G)). The walk fixes tensions up to a
constant, which the take-up sets: a gravity take-up carries its counterweight on two strands,
``T_in + T_out = m g``; a fixed take-up holds ``(T_in + T_out) / 2`` at its pretension. With
``mass_kg: auto`` (or ``pretension_kn: auto``) the constant is the smallest that meets

* slip at every drive at start-up (Euler-Eytelwein, T_tight / T_slack <= e^{mu theta}, with the
  drive force times the start-up factor 1.5, the level held by the take-up: a gravity one its
  mean tension, a fixed one the loop length, :func:`start_level`), and running;
* slip at every drive at breakaway: the drives take the loaded belt's
  net gravity pull from the brake at standstill, before any running resistance acts
  (:func:`_breakaway_walk`). This is the start-up of a regenerating belt: there the start-up
  factor's walk asks the drives for less than running (they hold back ``Te + 0.5 |Te|``, half
  the running force, while the belt accelerates), but at standstill they must hold the whole
  net pull, which exceeds the running |Te| by the running resistance, with the at-rest
  tensions, whose slack side (the carry at a head drive) is lower than running;
* the sag limits on both strands, T >= g (m'_G + m'_L) S / (8 (h/S)_adm), running and also
  held at rest (take-up plus gravity, the net pull of the loaded belt taken by the brake or the
  master drive: :func:`rest_walk`; a gravity take-up holds its mean tension at rest, a fixed
  one the loop length, elastic and with the spans' sag in it, :func:`_rest_bound`). The
  held-at-rest rule is this
  project's conservative reading (DIN 22101 checks the minimum tensions in its running and
  starting / stopping states only); it is on by default because a stopped, loaded belt sags
  most where the brake leaves it least tension, and it is switched off per conveyor with
  ``takeup.sag_at_rest: false``.

The constraint that sets an auto take-up is reported as ``takeup_governed_by``: ``slip_start``,
``slip_breakaway``, ``slip_running``, ``sag_running``, ``sag_at_rest`` (or ``positive``, the
belt kept in tension); ``given`` when the take-up is not auto.

Every slip check is Euler-Eytelwein with ``T_tight = max(T_in, T_out)`` and ``T_slack =
min(T_in, T_out)`` at the pulley: a regenerating drive (Te < 0, a loaded decline held back)
has its tight side outgoing, and the check does not depend on the sign of the drive force.

The counterweight is installed once: its auto mass is the larger of what the run's load case
needs and what the full design load needs (same model and temperature), so an empty or part-
load run keeps the full-load counterweight instead of a lighter one of its own.

Tension-dependent laws (nonlin, cmod) make this a fixed point; it is iterated to a relative
change of 1e-6 and the iteration count is reported.
"""

from __future__ import annotations

import math
import re
from dataclasses import dataclass, field

import numpy as np

from beltstudy.engine import catalog, rubber
from beltstudy.engine.capacity import capacity as capacity_check
from beltstudy.engine.capacity import fill_levers, incline_warning
from beltstudy.engine.checks import (
    HOLD_MARGIN,
    holding_warning,
    input_notes,
    lump_notes,
    runback_note,
)
from beltstudy.engine.checks import steady_checks as design_checks
from beltstudy.engine.chord import LEVEL_RTOL, chord_springs, length_level
from beltstudy.engine.conveyor import (
    FORCE_MAX_KN,
    POWER_MAX_KW,
    PRETENSION_MAX_KN,
    SAG_LIMIT_RTOL,
    TAKEUP_MASS_MAX_KG,
    Conveyor,
    curve_arcs,
    section_loads,
)
from beltstudy.engine.curves import junction_checks
from beltstudy.engine.curves import steady_checks as curve_checks
from beltstudy.engine.drives import apart, down3, figures, rated_power_kw, up3, watts_notes
from beltstudy.engine.drives import steady_checks as drive_checks
from beltstudy.engine.errors import InputError
from beltstudy.engine.friction import get_model, temperature_note
from beltstudy.engine.hcurves import hcurve_checks
from beltstudy.engine.law import ResistanceLaw
from beltstudy.engine.loop import (
    BOOSTER,
    CARRY,
    HEAD,
    RETURN,
    TAIL,
    TAKEUP,
    G,
    Loop,
    build_loop,
    rotating_parts,
)
from beltstudy.engine.wording import gnum

__all__ = ["SteadyResult", "solve_steady", "STARTUP_FACTOR", "SAFETY_FACTOR_MIN",
           "TRANSIENT_SAFETY_RATIO", "SPEC_PARTS", "rest_hold_element", "rest_walk",
           "TAKEUP_CONSTRAINTS", "auto_width_words"]

#: Start-up force factor for slip sizing of the take-up [-] (PHYSICS section 1).
STARTUP_FACTOR = 1.5
#: Minimum running safety factor by belt kind [-]: typical DIN 22101 steady-state values
#: (about 6.7 for steel cord, 10 for textile plies); estimates, override per conveyor with
#: ``safety_factor_min``.
SAFETY_FACTOR_MIN = {"steel": 6.7, "fabric": 10.0}
#: Minimum belt safety factor during starting and stopping as a fraction of the running
#: minimum [-]. Standards allow a lower factor for short non-steady loads than for steady
#: running; two thirds is this project's estimate (unverified), used only for the warning.
TRANSIENT_SAFETY_RATIO = 2.0 / 3.0
#: Parts every model reports in ``te_components_kn`` (SPEC section 4).
SPEC_PARTS = ("main_carry", "main_return", "lift", "feed", "secondary", "accessories")
#: Fixed-point tolerance and iteration cap.
TOL = 1e-6
MAX_ITER = 200
#: Smallest relaxation factor of the fixed-point iteration (Aitken / Irons-Tuck).
OMEGA_MIN = 0.05
STRAND_NAMES = {CARRY: "carry", RETURN: "return", HEAD: "head", TAIL: "tail", TAKEUP: "takeup",
                BOOSTER: "booster"}
#: Constraints an auto take-up is sized by (``takeup_governed_by``), in the order of ties.
TAKEUP_CONSTRAINTS = ("slip_start", "slip_breakaway", "slip_running", "sag_running",
                      "sag_at_rest", "positive")


@dataclass
class SteadyResult:
    """Steady running solution. Forces in [N] unless the name says otherwise."""

    conveyor: Conveyor
    loop: Loop
    law: ResistanceLaw
    model: str
    temperature_c: float
    tension_n: np.ndarray  # boundary tensions, T[j] at the end of element j
    resistance_n: np.ndarray  # R_j at design speed
    drive_force_n: np.ndarray  # D_j (driving positive)
    te_n: float
    takeup_mass_kg: float | None
    takeup_tension_n: float  # mean of the two strands at the take-up
    iterations: int
    summary: dict
    warnings: list[str] = field(default_factory=list)
    status: str = "ok"
    message: str = ""
    takeup_governed_by: str = "given"  # the constraint that set an auto take-up
    params_given: bool = False  # the friction model's parameters differ from its defaults
    range_note: str = ""  # the law's note on a temperature beyond its data (FrictionModel)

    @property
    def tension_mean_n(self) -> np.ndarray:
        """Mean tension of each element (T[j-1] + T[j]) / 2 [N]."""
        return 0.5 * (np.roll(self.tension_n, 1) + self.tension_n)

    def profile_arrays(self) -> dict[str, np.ndarray]:
        """Tension along the loop at element ends as arrays: ``s_m``, ``strand`` (text),
        ``elevation_m``, ``tension_kn``, ``sag_pct`` (no DataFrame is built)."""
        loop = self.loop
        low = np.minimum(self.tension_n, np.roll(self.tension_n, 1))
        sag = np.where(loop.is_idler, 100 * loop.sag_w_n / np.maximum(low, 1.0), 0.0)
        names = np.array([STRAND_NAMES.get(k, str(k)) for k in range(max(STRAND_NAMES) + 1)],
                         dtype=object)
        return {
            "s_m": loop.s_end_m,
            "strand": names[loop.strand.astype(np.int64)],
            "elevation_m": loop.z_end_m,
            "tension_kn": self.tension_n / 1e3,
            "sag_pct": sag,
        }

    def profile(self):
        """Tension along the loop at element ends: s_m, strand, elevation_m, tension_kn, sag_pct.

        Returns a pandas DataFrame (pandas is imported here, not at module import, to keep the
        command line quick).
        """
        import pandas as pd

        return pd.DataFrame(self.profile_arrays())


def _drive_elements(conv: Conveyor, loop: Loop) -> list[tuple[int, float, float]]:
    """(element index, share, e^{mu theta}) per drive, in file order: every drive is its own
    pulley element with its own wrap and friction."""
    out = []
    for i, d in enumerate(conv.drives):
        idx = loop.drive_elements[i]
        out.append((idx, d.share, loop.pulley_at(idx).euler))
    return out


def master_drive(conv: Conveyor) -> int:
    """Index of the master drive: the largest share, the first of equals in file order."""
    return max(range(len(conv.drives)), key=lambda i: (conv.drives[i].share, -i))


def rest_hold_element(conv: Conveyor, loop: Loop) -> int:
    """Element that holds the stopped belt: the first brake's pulley, else the master drive's
    (a friction drive alone could not hold a loaded incline or decline, a brake can)."""
    if conv.brakes:
        return loop.brake_element(conv.brakes[0])
    return int(loop.drive_elements[master_drive(conv)])


def _startup_acceleration(conv: Conveyor, loop: Loop, te: float):
    """The start-up check's acceleration: the drives' ``STARTUP_FACTOR`` x |Te| less |Te|
    shared out by every moving mass (belt, load, idler rolls, pulley shells, drive shafts and
    motors: :func:`beltstudy.engine.loop.rotating_parts`). Returns (the rotating parts, each
    element's inertia [kg], the acceleration [m/s2])."""
    parts = rotating_parts(conv, loop)
    inertia = loop.mass_kg.copy()
    for node, m in list(parts.plain_mass.items()) + [
            (node, m) for node, m in parts.shaft_mass.items() if node not in parts.shaft_drive]:
        inertia[node] += m
    extra = (STARTUP_FACTOR - 1.0) * abs(te)
    a = extra / (float(inertia.sum()) + sum(parts.shaft_mass[n] for n in parts.shaft_drive)
                 + sum(parts.motor_mass))
    return parts, inertia, a


def start_time_note(conv: Conveyor, loop: Loop, te: float, start=None) -> str:
    """A note when the start-up checks' force (``STARTUP_FACTOR`` x Te) is less than a start
    asks of a rigid belt: the slip margin at start-up and the auto take-up are sized for that
    force, so a vfd start faster than the one it accelerates the belt at slips with a take-up
    the steady run calls enough. The s-curve (cycloid) start of time T peaks at an
    acceleration of 2 v / T, the linear one runs at v / T; the note names the start times
    whose rigid-body force is within the checks' (waves add to it: the transient run shows
    them). ``start``: the run's start (:class:`~beltstudy.engine.conveyor.StartSpec`); None
    for the steady run, which judges the transient's default start. Only for vfd drives (their
    start time is ``start.time_s``) on a belt that motors (Te > 0), and not for a torque start
    (its force ramps, no reference to follow); "" otherwise."""
    from beltstudy.engine.conveyor import StartSpec

    asked = start if start is not None else StartSpec()
    if (te <= 0.0 or any(d.control != "vfd" for d in conv.drives)
            or asked.control not in ("s-curve", "linear")):
        return ""
    _, _, a = _startup_acceleration(conv, loop, te)
    if not a > 0.0:
        return ""
    v = float(conv.speed_m_s)
    peak = (2.0 if asked.control == "s-curve" else 1.0) * v / float(asked.time_s)
    if peak <= a:
        return ""
    which = "the default" if start is None else "this run's"
    return (f"note: the start-up checks (slip_margin_start, the auto take-up) take the drives at "
            f"{STARTUP_FACTOR:g} x Te, which accelerates this belt at {gnum(a, 3)} m/s2 (the force "
            f"above Te shared out by every moving mass): an s-curve start asks no more of a "
            f"rigid belt from start.time_s {math.ceil(2.0 * v / a):.0f} s (peak acceleration "
            f"2 v / T, a linear one from {math.ceil(v / a):.0f} s), and {which} "
            f"{float(asked.time_s):g} s {asked.control} asks "
            f"{1.0 + (STARTUP_FACTOR - 1.0) * peak / a:.2f} x Te at its peak, more than these "
            "checks allow for (beltstudy simulate shows the start's slip and sizes the take-up "
            "for the start asked)")


def _startup_walk(conv: Conveyor, loop: Loop, dF: np.ndarray, te: float) -> np.ndarray:
    """Tension increments at start-up, walked like the running ones [N].

    The drives give ``STARTUP_FACTOR`` x their running force (of |Te| above the running
    force for a regenerative belt), which accelerates every moving mass at ``a = (f - 1)
    |Te| / M`` (DIN 22101's start-up peripheral force, the acceleration force shared out by
    mass; M with the rotating parts of :func:`beltstudy.engine.loop.rotating_parts`): each element adds
    its inertia force (its own pulley shell included), each drive pulley receives its share of
    the start-up force less what accelerates its own rotating parts, so the walk closes round
    the loop.
    """
    parts, inertia, a = _startup_acceleration(conv, loop, te)
    extra = (STARTUP_FACTOR - 1.0) * abs(te)
    d_start = np.zeros(loop.n)
    for node, i in parts.shaft_drive.items():
        d = conv.drives[i]
        d_start[node] += (d.share * (te + extra)
                          - (parts.shaft_mass[node] + parts.motor_mass[i]) * a)
    return np.cumsum(dF + inertia * a - d_start)


def _breakaway_walk(conv: Conveyor, loop: Loop) -> np.ndarray:
    """Tension increments at breakaway, walked like the running ones [N].

    At standstill no running resistance acts (idler rolling and indentation resistances are
    motion resistances): the drives, taking the belt from the brake at the start, hold the
    net gravity pull ``sum G`` (the loaded lift; the belt's own weight cancels round the
    loop), each its share, as in the at-rest walk (:func:`rest_walk`) with the drives
    holding. On a regenerating belt ``|sum G| = |Te| + sum R`` exceeds the running force.
    The level is held as at start-up (:func:`start_level`): a gravity take-up's mean tension,
    a fixed take-up's loop length (the at-rest level the transient run starts from keeps it
    too). Before, a fixed take-up had no breakaway check: a 2 km, 150 m decline held back by
    its head drive was sized 172 kN for slip running and slid 2.5 m in a 60 s start.
    """
    grav = loop.gravity_n
    pull = float(grav.sum())
    hold = np.zeros(loop.n)
    for i, d in enumerate(conv.drives):
        hold[loop.drive_elements[i]] += d.share * pull
    return np.cumsum(grav - hold)


def _slip_need(w_in: float, w_out: float, e: float) -> float:
    """Smallest constant c with max(T_in, T_out) <= e min(T_in, T_out), T = c + w [N]."""
    return (max(w_in, w_out) - e * min(w_in, w_out)) / (e - 1.0)


def rest_walk(loop: Loop, hold: int, gravity_n: np.ndarray) -> np.ndarray:
    """At-rest tensions relative to the one entering the take-up, ``T[i_takeup - 1] = 0`` [N].

    Held at rest there is no running resistance: walking from the take-up, each element adds
    its gravity component ``G_j`` and the holding element takes the net pull ``sum G`` (the
    loaded lift; the belt's own weight cancels round the loop), so the walk closes.
    """
    n = loop.n
    itu = loop.i_takeup
    order = (itu + np.arange(n - 1)) % n  # every element but itu - 1, in walking order
    inc = gravity_n[order] - np.where(order == hold, float(gravity_n.sum()), 0.0)
    out = np.zeros(n)
    out[order] = np.cumsum(inc)
    return out


def _rest_need(conv: Conveyor, loop: Loop, hs_adm: np.ndarray, fixed: bool
               ) -> np.ndarray | None:
    """The smallest at-rest tensions that keep the belt held at rest within its sag limits
    [N] (None with ``takeup.sag_at_rest`` off): the at-rest walk (:func:`rest_walk`) at the
    least level that meets them, a little above it for a ``fixed`` take-up (by the tolerance
    of the transient model's own level, :data:`~beltstudy.engine.chord.LEVEL_RTOL`, so that
    the rest state it finds from the running tensions meets the limits too).
    :func:`_rest_bound` gives the running level that holds them."""
    if not conv.takeup.sag_at_rest:
        return None
    Wr = rest_walk(loop, rest_hold_element(conv, loop), loop.gravity_n)
    level = _sag_need(loop, Wr, hs_adm)
    if fixed:
        level += LEVEL_RTOL * max(1.0, abs(level))
    return Wr + level


def _rest_bound(loop: Loop, W: np.ndarray, rest: np.ndarray, fixed: bool) -> float:
    """The least constant c [N] of the running tensions ``c + W`` whose take-up holds the
    at-rest tensions ``rest`` (:func:`_rest_need`) or more. A gravity take-up holds the same
    mean tension of its two strands at rest as running (:func:`start_level`). A fixed one
    holds the loop's length: its elastic part (:func:`start_level`, the length-weighted mean
    tension) and, as the transient model's at-rest state takes it, the chord length with the
    spans' sag in it (Ernst, :func:`beltstudy.engine.chord.length_level`); the larger level
    holds both. The sag's part of the length changes from running to rest, which raises the
    rest level on some belts and lowers it on others: sized on the elastic length alone, a
    loaded 110 m decline with a tail drive and its take-up at the tail (13.220 kN) sagged
    1.5005 % at rest against its 1.5 % limit; on its chord length (13.223 kN), 1.5 %."""
    elastic = start_level(loop, rest, fixed) - start_level(loop, W, fixed)
    if not fixed:
        return elastic
    springs = chord_springs(loop)
    return max(elastic, length_level(W, rest, springs[0], springs[1],
                                     float(loop.belt.stiffness_n), springs[2], springs[3]))


def _sag_need(loop: Loop, W: np.ndarray, hs_adm: np.ndarray) -> float:
    """Smallest constant c with every idler element of ``c + W`` at or above its sag minimum.

    The sag of a span is taken at its lowest tension, the lower end of the element (tension
    is linear along an element, so that is its least tension and the bound does not depend
    on the element length): a take-up sized to a sag limit then reports that limit.
    """
    idl = loop.is_idler
    if not idl.any():
        return -np.inf
    tmin_elem = loop.sag_w_n / hs_adm
    lower = np.minimum(W, np.roll(W, 1))
    return float(np.max(np.where(idl, tmin_elem - lower, -np.inf)))


def start_level(loop: Loop, W: np.ndarray, fixed: bool) -> float:
    """The figure of a tension walk ``W`` [N] that the take-up holds from running to start-up.

    A gravity take-up's counterweight holds the mean tension of its two strands,
    ``(W[k - 1] + W[k]) / 2`` at the take-up pulley ``k``, whatever the belt does. A fixed
    (screw or winch) take-up holds its place, so the loop's length: the belt's elastic
    elongation ``sum_j dx_j (W[j - 1] + W[j]) / 2 / EB`` (tension linear along each element,
    EB the same round the loop) stays as running, and the figure held is that length-weighted
    mean tension. Starting, the carry stretches under the drives' extra force and the slack
    side gives up the length: held at the take-up's running tension instead, the start-up
    check of a fixed take-up behind a head drive kept the slack side about 19 kN higher than
    a fixed length leaves it. The belt's sag (Ernst's chord term) is left out of the length:
    at the tensions a start-up check asks for it is a small part of the stretch."""
    if not fixed:
        k = loop.i_takeup
        return float(0.5 * (W[k - 1] + W[k]))
    dx = loop.dx_m
    return float(np.sum(dx * 0.5 * (np.roll(W, 1) + W)) / np.sum(dx))


def _rest_grip_bound(conv: Conveyor | None, loop: Loop, W: np.ndarray, fixed: bool) -> float:
    """The least constant c [N] of the running tensions ``c + W`` whose take-up lets the
    pulley holding the stopped belt (:func:`rest_hold_element`: the first brake's, else the
    master drive's) hold its whole net gravity pull at rest, ``T_tight <= e^(mu theta)
    T_slack`` on the at-rest walk (:func:`rest_walk`, levelled as :func:`_rest_bound`
    levels it); -inf without a conveyor or a pulley there. The breakaway walk shares the
    pull among the drives; at rest one pulley holds it all: a 350 m 16 deg incline on two
    head drives was sized 3 615 kg for start-up slip, where its braked head pulley holding
    112.7 kN at rest needed 4.31 t (the run said the belt would creep over it)."""
    if conv is None:
        return -np.inf
    hold = rest_hold_element(conv, loop)
    pulley = next((p for p in loop.pulleys if p.element == hold), None)
    if pulley is None:
        return -np.inf
    Wr = rest_walk(loop, hold, loop.gravity_n)
    level = _slip_need(float(Wr[hold - 1]), float(Wr[hold]), pulley.euler)
    return _rest_bound(loop, W, Wr + level, fixed)


def _required_offset(loop: Loop, W: np.ndarray, W_start: np.ndarray, drives,
                     hs_adm: np.ndarray, rest_need: np.ndarray | None,
                     W_hold: np.ndarray | None = None, fixed: bool = False,
                     conv: Conveyor | None = None) -> tuple[float, dict]:
    """Smallest constant c (T = c + W) meeting slip at every drive pulley running, at
    start-up (``W_start`` from :func:`_startup_walk`, levelled by :func:`start_level`: a
    ``fixed`` take-up holds the loop length) and at breakaway (``W_hold`` from
    :func:`_breakaway_walk`, and with ``conv`` the pulley holding the belt at rest,
    :func:`_rest_grip_bound`), and sag (running and, with ``rest_need`` from
    :func:`_rest_need`, held at rest)."""
    bounds = {}
    Wprev = np.roll(W, 1)
    Sprev = np.roll(W_start, 1)
    bounds["slip_running"] = float(max(_slip_need(Wprev[idx], W[idx], e)
                                       for idx, _s, e in drives))
    # the start-up walk has its own level: a gravity take-up holds the same mean tension, a
    # fixed one the same loop length (:func:`start_level`)
    shift = start_level(loop, W, fixed) - start_level(loop, W_start, fixed)
    bounds["slip_start"] = float(max(_slip_need(Sprev[idx], W_start[idx], e)
                                     for idx, _s, e in drives) - shift)
    if W_hold is not None:  # levelled as the start-up walk
        hprev = np.roll(W_hold, 1)
        shift_h = start_level(loop, W, fixed) - start_level(loop, W_hold, fixed)
        bounds["slip_breakaway"] = float(max(max(_slip_need(hprev[idx], W_hold[idx], e)
                                                 for idx, _s, e in drives) - shift_h,
                                             _rest_grip_bound(conv, loop, W, fixed)))
    bounds["sag_running"] = _sag_need(loop, W, hs_adm)
    if rest_need is not None:
        bounds["sag_at_rest"] = _rest_bound(loop, W, rest_need, fixed)
    bounds["positive"] = float(np.max(1.0 - W))  # keep every tension above 1 N
    return max(bounds.values()), bounds


def _governing(bounds: dict) -> str:
    """The constraint with the largest need (the first of :data:`TAKEUP_CONSTRAINTS` on a
    tie)."""
    return max(TAKEUP_CONSTRAINTS, key=lambda k: (bounds.get(k, -np.inf),
                                                  -TAKEUP_CONSTRAINTS.index(k)))


def solve_steady(
    conv: Conveyor,
    *,
    model: str = "din",
    params: dict | object | None = None,
    temperature_c: float = 20.0,
    load: float | str = 1.0,
    n_elements: int | None = None,
    target_dx_m: float | None = None,
    settle: bool = False,
) -> SteadyResult:
    """Steady running tensions of a conveyor for one friction model.

    Parameters
    ----------
    conv : Conveyor
    model : str
        Friction model name (registry in :mod:`beltstudy.engine.friction`).
    params : dict or parameter dataclass, optional
        Model parameter overrides.
    temperature_c : float
        Ambient temperature [C].
    load : float or 'full' / 'empty'
        Load case as a fraction of the design load.
    n_elements, target_dx_m : optional
        Element count round the loop or target element length [m].
    settle : bool
        Settle a convex curve's advised radius by solving again at it (:func:`_settle_radii`):
        the run's own steady state (``beltstudy static``, a transient run's), not the solves
        of a search (belt candidates, take-up sizes, calibration fits), which read figures.

    Returns
    -------
    SteadyResult
        With ``summary`` holding the SPEC section 4 steady fields.
    """
    fm = get_model(model)
    p = params if (params is not None and not isinstance(params, dict)) else fm.params(params)
    loads = section_loads(load, conv)
    loop = build_loop(conv, list(loads), n_elements=n_elements, target_dx_m=target_dx_m)
    law = fm.build(loop, conv, float(temperature_c), p)
    v = loop.speed_m_s
    grav = loop.gravity_n
    drives = _drive_elements(conv, loop)
    hs_adm = np.where(loop.strand == CARRY, conv.sag_limit_pct.carry / 100.0,
                      conv.sag_limit_pct.return_ / 100.0)
    tu = conv.takeup
    k = loop.i_takeup
    fixed = tu.type == "fixed"

    rest_need = _rest_need(conv, loop, hs_adm, fixed)
    W_hold = _breakaway_walk(conv, loop)
    # the installed take-up: at least what the full design load needs
    tu_floor_n = -np.inf
    design = None
    auto = (tu.type == "gravity" and tu.mass_kg == "auto") or (
        tu.type == "fixed" and tu.pretension_kn == "auto")
    if auto and any(f != 1.0 for f in loads):
        design = solve_steady(conv, model=model, params=p, temperature_c=temperature_c,
                              load=1.0, n_elements=n_elements, target_dx_m=target_dx_m)
        tu_floor_n = design.takeup_tension_n

    T = None
    iterations = 0
    omega, resid_prev = 1.0, None  # relaxation of the fixed point (tension-dependent laws)
    converged = not law.tension_dependent
    R = law.evaluate(v, None) if not law.tension_dependent else None
    if R is None:
        # first guess: tensions from the tension-independent terms at a nominal 1 % sag
        T = np.full(loop.n, 1.0)
    for iterations in range(1, MAX_ITER + 1):  # noqa: B007
        if law.tension_dependent:
            Tm = 0.5 * (np.roll(T, 1) + T) if iterations > 1 else np.maximum(
                loop.sag_w_n / 0.01, 1.0)
            R = law.evaluate(v, Tm)
        dF = R + grav
        te = float(dF.sum())
        d_force = np.zeros(loop.n)
        for idx, share, _e in drives:
            d_force[idx] += share * te
        W = np.cumsum(dF - d_force)
        W_start = _startup_walk(conv, loop, dF, te)
        w_tu = 0.5 * (W[k - 1] + W[k])
        if tu.type == "gravity" and tu.mass_kg != "auto":
            c = float(tu.mass_kg) * G / 2.0 - w_tu
        elif tu.type == "fixed" and tu.pretension_kn != "auto":
            c = float(tu.pretension_kn) * 1e3 - w_tu
        else:
            c, _ = _required_offset(loop, W, W_start, drives, hs_adm, rest_need, W_hold,
                                    fixed, conv)
            c = max(c, tu_floor_n - w_tu)
        T_new = c + W
        if not law.tension_dependent:
            T = T_new
            break
        if T is not None and iterations > 1:
            resid = T_new - T
            change = float(np.max(np.abs(resid)) / max(np.max(np.abs(T_new)), 1.0))
            if change < TOL:
                T = T_new
                converged = True
                break
            # Aitken (Irons-Tuck) dynamic relaxation: sag-driven resistance feeds back
            # negatively (more tension, less resistance, less take-up tension), which makes
            # the plain iteration oscillate; the factor is fitted from successive residuals.
            if resid_prev is not None:
                dr = resid - resid_prev
                dd = float(dr @ dr)
                if dd > 0.0:
                    omega = float(np.clip(-omega * float(resid_prev @ dr) / dd, OMEGA_MIN, 1.0))
            resid_prev = resid
            T = T + omega * resid
        else:
            T = T_new

    assert T is not None and R is not None
    c_need, bounds = _required_offset(loop, W, W_start, drives, hs_adm, rest_need, W_hold,
                                      fixed, conv)
    takeup_tension = 0.5 * (T[k - 1] + T[k])
    takeup_mass = float(2.0 * takeup_tension / G) if tu.type == "gravity" else None
    if not auto:  # a given take-up is reported as given (not as its round trip through T)
        if tu.type == "gravity":
            takeup_mass = float(tu.mass_kg)
            takeup_tension = takeup_mass * G / 2.0
        else:
            takeup_tension = float(tu.pretension_kn) * 1e3

    result = SteadyResult(
        conveyor=conv, loop=loop, law=law, model=fm.name, temperature_c=float(temperature_c),
        tension_n=T, resistance_n=R, drive_force_n=d_force, te_n=te,
        takeup_mass_kg=takeup_mass, takeup_tension_n=float(takeup_tension),
        iterations=iterations, summary={}, params_given=p != fm.params(None),
        range_note=fm.range_note(p, float(temperature_c)) if fm.range_note else "",
    )
    if auto:
        floor_governs = design is not None and tu_floor_n - w_tu > c_need
        result.takeup_governed_by = (design.takeup_governed_by if floor_governs
                                     else _governing(bounds))
    _summarise(result, drives, hs_adm, bounds, c_need - (T[0] - W[0]), W_start - W,
               None if W_hold is None else W_hold - W)
    pattern = _pattern_note(conv, load, loop)
    if pattern:  # a note, not a warning: the empty belt is a case the run answers
        result.message = "; ".join(m for m in (result.message, pattern) if m)
        result.summary["message"] = result.message
    if not converged:
        result.status = "failed"
        result.message = (
            f"steady solve did not converge in {MAX_ITER} iterations (model {fm.name}); "
            "the tension-dependent resistance may exceed what the take-up can hold: raise "
            "takeup.mass_kg or use mass_kg: auto"
        )
        result.summary["status"] = result.status
        result.summary["message"] = result.message
    bad = [k for k in ("te_kn", "power_kw", "t_max_kn", "t_min_kn", "takeup_mass_kg")
           if isinstance(result.summary.get(k), float) and not math.isfinite(result.summary[k])]
    if bad and result.status != "failed":
        # numbers past float range (a friction factor or a capacity far beyond any
        # conveyor): not a design, and a row of nulls must not read as a warning
        result.status = "failed"
        result.message = (
            f"the steady state is not finite ({', '.join(bad)} overflow): the resistances "
            "or the load are beyond any conveyor; check the model parameters (models.*) and "
            "material.capacity_t_h" + (f"; {result.message}" if result.message else ""))
        result.summary["status"] = result.status
        result.summary["message"] = result.message
    if settle and result.status != "failed":
        case = dict(model=model, params=params, temperature_c=temperature_c, load=load,
                    n_elements=n_elements, target_dx_m=target_dx_m)
        _settle_radii(result, case)
        _settle_concave(result, case)
    return result


def _pattern_note(conv: Conveyor, load, loop: Loop) -> str:
    """A note when a load case that names material puts none on the belt (SPEC 6.2):
    ``inclines`` on a profile without a rising section or ``declines`` without a falling one,
    or a list of fractions whose loaded sections all lie upstream of every feed point
    (``material.feed``): the belt runs empty, which the case's name does not say."""
    if load in ("inclines", "declines"):
        sign = 1.0 if load == "inclines" else -1.0
        if not any(sign * p.lift_m > 0.0 for p in conv.profile):
            what = "rises (lift_m > 0)" if load == "inclines" else "falls (lift_m < 0)"
            return (f"note: load {load}: no profile section {what}, so the belt runs empty "
                    "in this case (the empty case's figures)")
    loaded = [i for i, f in enumerate(loop.section_load) if f > 0.0]
    if conv.material.feed and loaded and loop.load_max_kg_m <= 0.0:
        first = min(f.at_m for f in conv.material.feed)
        names = ", ".join(f"profile.{i}" for i in loaded)
        shown = [float(x) for x in load] if isinstance(load, list | tuple) else load
        return (f"note: load {shown}: the loaded sections ({names}) lie upstream of "
                f"every feed point (the first at {first:g} m, material.feed), so no material "
                "reaches them and the belt runs empty in this case")
    return ""


def _drive_margins(drives, T, Tprev, T_start, Sprev, T_hold):
    """Each drive's slip margin running and at start-up (the lower of start-up and breakaway,
    ``T_hold`` None where it is not checked), its tight and slack tensions as summary fields, and
    whether the breakaway set its start margin: (running, start, fields, breakaway)."""
    slip_margins, start_margins, per_drive, breakaway = [], [], {}, []
    for i, (idx, _s, e) in enumerate(drives, start=1):
        tin, tout = Tprev[idx], T[idx]
        tight, slack = max(tin, tout), min(tin, tout)
        margin = e / (tight / slack) if slack > 0 else 0.0
        slip_margins.append(margin)
        s_tight, s_slack = max(Sprev[idx], T_start[idx]), min(Sprev[idx], T_start[idx])
        start = e / (s_tight / s_slack) if s_slack > 0 else 0.0
        if T_hold is not None:  # breakaway: the drives hold the net pull at standstill
            h_in, h_out = T_hold[idx - 1], T_hold[idx]
            h_slack = min(h_in, h_out)
            hold = e / (max(h_in, h_out) / h_slack) if h_slack > 0 else 0.0
            breakaway.append(hold < start)
            start = min(start, hold)
        else:
            breakaway.append(False)
        start_margins.append(start)
        per_drive[f"drive{i}_t_tight_kn"] = float(tight) / 1e3
        per_drive[f"drive{i}_t_slack_kn"] = float(slack) / 1e3
        per_drive[f"drive{i}_slip_margin"] = float(margin)
    return slip_margins, start_margins, per_drive, breakaway


def _surge_where(conv, section_load) -> str:
    """Where a surge of a per-section load (a list, ``inclines``, ``declines``) sits: the
    profile sections above the design load, by index and distance from the tail ("" when every
    section carries the same load: the whole carry)."""
    loads = tuple(section_load)
    if not loads or min(loads) == max(loads):
        return ""
    ends = np.cumsum([float(sec.length_m) for sec in conv.profile])
    over = [(k, f) for k, f in enumerate(loads) if f > 1.0]
    each = len({f for _, f in over}) > 1  # several surges of their own size: each said
    where = [f"profile.{k} ({(ends[k - 1] if k else 0.0):.6g} to {ends[k]:.6g} m from the tail"
             + (f", {f:g} x" if each else "") + ")" for k, f in over]
    return " on " + ", ".join(where)


def _slip_words(res: SteadyResult, drives, slip_margins, start_margins, breakaway,
                shortfall_n: float) -> list[str]:
    """A warning per drive that slips running or at start-up (or breakaway), each phase with
    its own margin, and the take-up that would avoid it when ``shortfall_n`` > 0."""
    conv, tu = res.conveyor, res.conveyor.takeup
    pull_kn = float(res.loop.gravity_n.sum()) / 1e3
    warnings = []
    for i, ((_idx, _s, e), m_run, m_start, at_hold) in enumerate(
            zip(drives, slip_margins, start_margins, breakaway, strict=True), start=1):
        where = f"drive {i} ({conv.drives[i - 1].where})"
        if m_run < 1.0 - 1e-6 or m_start < 1.0 - 1e-6:
            start = (f"breakaway (the drives hold the net gravity pull {gnum(abs(pull_kn))} kN at "
                     "standstill, no running resistance yet)" if at_hold
                     else f"start-up (force x {STARTUP_FACTOR})")
            # each phase that slips with its own margin: running first, then the start
            cases = [(w, m) for w, m in (("running", m_run), (start, m_start))
                     if m < 1.0 - 1e-6]
            fix = ""
            if shortfall_n > 0 and tu.type == "gravity":
                need = (res.takeup_tension_n + shortfall_n) * 2 / G
                # said as the mass itself: the run's mass may already be an auto one held
                # by a study's design basis, where "use mass_kg: auto" would be no fix
                fix = (f"; take-up mass {figures(res.takeup_mass_kg)} kg is below the "
                       f"{figures(need)} kg needed: a takeup.mass_kg of {math.ceil(need):.0f} kg "
                       "or more")
            elif shortfall_n > 0:
                need_kn = up3((res.takeup_tension_n + shortfall_n) / 1e3)
                fix = (f"; pretension {gnum(res.takeup_tension_n / 1e3, 3)} kN is below the "
                       f"{need_kn:g} kN needed: a takeup.pretension_kn of {need_kn:g} kN or "
                       "more")
            # two decimals, and two figures below 0.1 (not "0.00 < 1")
            said = ", and at ".join(f"{w}: slip margin {m:.2f} < 1" if m >= 0.1 else
                                    f"{w}: slip margin {m:.2g} < 1" for w, m in cases)
            # a margin of 0 is a slack side of no tension: no grip passes a force from it
            least = min(m for _, m in cases)
            grip, aside = _grip_levers(conv, i - 1, e / least) if least > 0.0 else ("", "")
            avoid = (f"{fix}, or{grip}" if fix and grip else fix or (f";{grip}" if grip else ""))
            warnings.append(f"slip at {where} at {said} (e^(mu theta) = {e:.2f}){avoid}"
                            + (" would avoid it" if avoid else "") + aside)
    return warnings


#: Belt-pulley friction of a rubber-lagged pulley, dry, at the top of the range DIN 22101
#: gives (0.35-0.4): a lever asking more is said to be beyond lagging.
LAGGED_FRICTION_MAX = 0.4


def _grip_levers(conv, k: int, ratio: float) -> tuple[str, str]:
    """The levers on the slipping drive's own pulley, beside the take-up: more friction (a
    lagged pulley), more wrap (a snub pulley), each at least what makes ``e^(mu theta)`` the
    tension ratio ``ratio`` it must pass (T1 / T2 of the slipping phase, the same tensions:
    the margin is e^(mu theta) / (T1 / T2)), and, where the conveyor has other drives, a
    smaller share of Te on it. A carry booster of wrap 90 deg slipping at a margin of 0.70
    was offered only a counterweight nearly twice as heavy (9 000 to 17 528 kg), which raises
    the belt's tension everywhere (92 to 134 kN peak).

    A friction beyond 1 or a wrap of 360 deg or more, which no file may give (and no pulley
    has), is said to be out of reach, not offered (a slope's head drive was told "friction at
    least 1.08" and "wrap_deg at least 644 deg"); a friction beyond
    :data:`LAGGED_FRICTION_MAX` is said to be beyond rubber lagging. The smaller share is
    the one whose force the pulley passes at the same slack side, ``share (e^(mu theta) - 1)
    / (T1 / T2 - 1)``: the words gave the drive's present share, which read as the target.
    Returns (the levers, starting with a space; what is out of reach, after a semicolon)."""
    d = conv.drives[k]
    grip = math.exp(d.friction * math.radians(d.wrap_deg))
    log_r = math.log(ratio)
    mu = math.ceil(100.0 * log_r / math.radians(d.wrap_deg)) / 100.0
    wrap = math.ceil(math.degrees(log_r / d.friction)) if d.friction > 0.0 else math.inf
    levers, beyond = [], []
    if mu <= 1.0:
        lagged = (f", beyond the 0.35-{LAGGED_FRICTION_MAX:g} of a rubber-lagged pulley, "
                  "DIN 22101" if mu > LAGGED_FRICTION_MAX else "")
        levers.append(f"more friction (a lagged pulley: drives.{k}.friction at least {mu:g} "
                      f"at this wrap, now {d.friction:g}{lagged})")
    else:
        beyond.append(f"no friction at this wrap (it needs {mu:g}, beyond 1; DIN 22101 gives "
                      f"0.35-{LAGGED_FRICTION_MAX:g} for a lagged pulley)")
    if wrap < 360:
        levers.append(f"more wrap (a snub pulley: drives.{k}.wrap_deg at least {wrap:g} deg "
                      f"at this friction, now {d.wrap_deg:g})")
    elif math.isfinite(wrap):
        beyond.append(f"no wrap of one pulley at this friction (it needs {wrap:g} deg)")
    if len(conv.drives) > 1 and ratio > 1.0:
        most = math.floor(100.0 * d.share * (grip - 1.0) / (ratio - 1.0)) / 100.0
        levers.append(f"a smaller share of Te on it (drives.{k}.share at most {most:g}, now "
                      f"{d.share:g}; the others then take more: rerun to check)")
    said = ""
    if levers:
        on_own = [w for w in levers if not w.startswith("a smaller share")]
        said = (f" on its own pulley {' or '.join(on_own)}" if on_own else "")
        said += (f"{', or ' if on_own else ' '}{levers[-1]}"
                 if levers[-1].startswith("a smaller share") else "")
    aside = f"; {' and '.join(beyond)} passes it" if beyond else ""
    return said, aside


def _brake_beyond_words(conv, loop) -> list[str]:
    """Auto brakes whose holding size (``HOLD_MARGIN`` x the loaded belt's net gravity pull,
    less the given brakes, shared evenly) is beyond what a file may give (``FORCE_MAX_KN``,
    the breaking force of the strongest catalogue belt), in words. A brake stop's size is
    said by the transient run's brake note."""
    auto = [i for i, b in enumerate(conv.brakes) if b.force_kn == "auto"]
    if not auto:
        return []
    fixed = sum(float(b.force_kn) for b in conv.brakes if b.force_kn != "auto") * 1e3
    each = (HOLD_MARGIN * abs(float(loop.gravity_n.sum())) - fixed) / len(auto) / 1e3
    if each <= FORCE_MAX_KN:
        return []
    return [f"the auto brakes' holding size ({HOLD_MARGIN:g} x the loaded belt's net gravity "
            f"pull, {each:,.0f} kN on each of {', '.join(f'brakes.{i}' for i in auto)}) is "
            "beyond the breaking force of any catalogue belt (a file may give at most "
            f"{FORCE_MAX_KN:,.0f} kN): no belt passes it, so the route must be split into "
            "flights or the pull held on more pulleys"]


def _power_beyond_words(conv, rated_kw: list[float]) -> list[str]:
    """An auto rated power beyond what a file may give (``POWER_MAX_KW``, three times the
    largest conveyor drives built), in words with what sets it: the drive's share of the
    power over its drive train's efficiency. A drive train of efficiency 1e-6 sized a 1.3 TW
    motor that `static` reported as ``ok`` and a study's runs failed on."""
    out = []
    for i, (d, kw) in enumerate(zip(conv.drives, rated_kw, strict=True)):
        if d.rated_power_kw is not None or kw <= POWER_MAX_KW:
            continue
        out.append(f"drive {i + 1}'s auto rated power {kw:,.0f} kW is beyond any conveyor "
                   f"motor (a file may give at most {POWER_MAX_KW:,.0f} kW): it is its share "
                   f"{d.share:g} of the running power over its drive train's efficiency "
                   f"(drives.{i}.efficiency {d.efficiency:g}); a drive train's efficiency is "
                   "0.85-0.97 (check drives[].efficiency), else more drives along the belt "
                   "(a booster) share the power")
    return out


def _takeup_beyond_words(res: SteadyResult, drives) -> list[str]:
    """An auto take-up beyond what a file may give: what sets it and what avoids it (no
    warning otherwise)."""
    conv, tu = res.conveyor, res.conveyor.takeup
    beyond = ""
    if tu.type == "gravity" and tu.mass_kg == "auto" and res.takeup_mass_kg > TAKEUP_MASS_MAX_KG:
        beyond = (f"the auto take-up mass {res.takeup_mass_kg / 1e3:,.0f} t is beyond any "
                  f"counterweight (a file may give at most {TAKEUP_MASS_MAX_KG / 1e3:,.0f} t)")
    elif (tu.type == "fixed" and tu.pretension_kn == "auto"
          and res.takeup_tension_n / 1e3 > PRETENSION_MAX_KN):
        beyond = (f"the auto pretension {res.takeup_tension_n / 1e3:,.0f} kN is beyond the "
                  f"breaking force of any catalogue belt ({PRETENSION_MAX_KN:,.0f} kN)")
    if not beyond:
        return []
    gov = res.takeup_governed_by
    if gov.startswith("slip"):
        k = min(range(len(drives)), key=lambda i: drives[i][2])
        d = conv.drives[k]
        fix = (f"drive {k + 1} ({d.where}) grips too little for its share of Te (friction "
               f"{d.friction:g}, wrap {d.wrap_deg:g} deg, e^(mu theta) = "
               f"{gnum(drives[k][2], 3)}): more friction (a lagged pulley), more wrap "
               "(a snub pulley) or a smaller share on it would avoid it")
    else:
        fix = ("closer idlers (idlers.*.spacing_m) or a higher sag limit would lower it")
    return [f"{beyond}, set by {gov}: {fix}"]


def _summarise(res: SteadyResult, drives, hs_adm, bounds, shortfall_n: float,
               start_delta: np.ndarray, hold_delta: np.ndarray | None = None) -> None:
    """Fill ``res.summary`` with the SPEC section 4 and 6.4 steady fields and the warnings.

    ``start_delta`` is the start-up walk less the running one (:func:`_startup_walk`),
    ``hold_delta`` the breakaway walk less the running one (:func:`_breakaway_walk`); both
    are levelled by :func:`start_level` (a gravity take-up's mean tension, a fixed one's loop
    length, as running).
    ``slip_margin_start`` is the lower of the two.
    """
    conv, loop, T = res.conveyor, res.loop, res.tension_n
    belt = loop.belt
    v = loop.speed_m_s
    Tprev = np.roll(T, 1)
    T_start = T + start_delta - start_level(loop, start_delta, conv.takeup.type == "fixed")
    Sprev = np.roll(T_start, 1)
    main_idx = loop.drive_elements[master_drive(conv)]
    t1, t2 = Tprev[main_idx], T[main_idx]
    if res.drive_force_n[main_idx] < 0:  # regenerating: tight side outgoing
        t1, t2 = t2, t1
    T_hold = (None if hold_delta is None else
              T + hold_delta - start_level(loop, hold_delta, conv.takeup.type == "fixed"))
    slip_margins, start_margins, per_drive, breakaway = _drive_margins(
        drives, T, Tprev, T_start, Sprev, T_hold)
    s_end = loop.s_end_m
    imax, imin = int(np.argmax(T)), int(np.argmin(T))
    Tm = res.tension_mean_n
    idl = loop.is_idler
    sag = np.where(idl, loop.sag_w_n / np.maximum(np.minimum(T, Tprev), 1.0), 0.0)
    # a slack span (tension at or below zero) has no sag ratio: w / 1 N read 22 750 % on a
    # decline's slack carry; none, as sag_max_dyn_pct, and at most 100 % (its cap) otherwise
    slack_span = bool((idl & (np.minimum(T, Tprev) <= 0.0)).any())
    sag_max_pct = None if slack_span else float(min(sag.max() * 100, 100.0))
    rating = belt.rating_n
    parts = res.law.parts(v, Tm)
    comps = {name: 0.0 for name in SPEC_PARTS}
    if "idler_rotation" in parts:  # finer models replace main_* by their named parts
        comps.pop("main_carry")
        comps.pop("main_return")
    for name, arr in parts.items():
        comps[name] = comps.get(name, 0.0) + float(arr.sum()) / 1e3
    comps["lift"] = float((loop.mL_kg_m * G * loop.dx_m * loop.sin_a).sum()) / 1e3
    m_carry = belt.mass_kg_m + loop.load_max_kg_m  # the loaded sections of a load pattern
    mR_c = float(loop.mR_kg_m[loop.strand == CARRY][0])
    mR_r = float(loop.mR_kg_m[loop.strand == RETURN][0])
    eb = belt.stiffness_n
    eb_dyn = belt.dynamic_stiffness_n
    res.summary = {
        "te_kn": res.te_n / 1e3,
        "power_kw": res.te_n * v / 1e3,
        "t1_kn": float(t1) / 1e3,
        "t2_kn": float(t2) / 1e3,
        "t_max_kn": float(T[imax]) / 1e3,
        "t_max_at_m": float(s_end[imax]),
        "t_min_kn": float(T[imin]) / 1e3,
        "t_min_at_m": float(s_end[imin]),
        "sag_max_pct": sag_max_pct,
        "takeup_mass_kg": res.takeup_mass_kg,
        "takeup_tension_kn": res.takeup_tension_n / 1e3,
        "takeup_pretension_kn": res.takeup_tension_n / 1e3,
        "takeup_governed_by": res.takeup_governed_by,
        "slip_margin": float(min(slip_margins)),
        "slip_margin_start": float(min(start_margins)),
        "safety_factor": float(rating / T[imax]),
        "belt_mass_kg_m": belt.mass_kg_m,
        "load_mass_kg_m": loop.load_max_kg_m,
        "idler_mass_carry_kg_m": mR_c,
        "idler_mass_return_kg_m": mR_r,
        "belt_modulus_kn": eb / 1e3,
        "belt_modulus_dyn_kn": eb_dyn / 1e3,
        "belt_rating_kn": rating / 1e3,
        "belt_type_used": belt.id,
        "wave_speed_carry_m_s": math.sqrt(eb_dyn / (m_carry + mR_c)),
        "wave_speed_return_m_s": math.sqrt(eb_dyn / (belt.mass_kg_m + mR_r)),
        **per_drive,
        "te_components_kn": comps,
        "steady_iterations": res.iterations,
    }
    warnings: list[str] = []
    # ---- load case and capacity (SPEC 6.2, 6.4)
    surge = max(loop.section_load) if loop.section_load else loop.load_fraction
    cap = capacity_check(conv)
    res.summary["fill_pct"] = cap.fill_pct
    if surge > 1.0 and conv.material.capacity_t_h > 0.0:
        # the surge's volume flow at design speed is the load fraction x the design one: a
        # design load that fills 96 % of the cross-section overflows it at 1.3 (125 %)
        surge_fill = surge * cap.fill_pct
        most = 100.0 / surge_fill * conv.material.capacity_t_h if surge_fill > 0.0 else 0.0
        most = down3(most)  # down at three figures: at most
        spill = (f", beyond its capacity ({figures(cap.capacity_m3_h)} m3/h, ISO 5048): the "
                 f"material heaps past the belt's edges and spills; a design load of at most "
                 f"{gnum(most, 3)} t/h "
                 "(material.capacity_t_h) leaves room for it, or a wider or deeper-troughed belt"
                 if surge_fill > 100.0 else "")
        warnings.append(f"surge: load {surge:g} x the design load (material.capacity_t_h)"
                        f"{_surge_where(conv, loop.section_load)} "
                        f"is above the design capacity; it fills the belt's cross-section to "
                        f"{surge_fill:.0f} % at {v:g} m/s (the design load {cap.fill_pct:.0f} %)"
                        f"{spill}")
    if cap.fill_pct > 100.0:
        warnings.append(
            f"fill_pct {cap.fill_pct:.0f} %: the design volume flow "
            f"({figures(cap.volume_flow_m3_h)} m3/h) exceeds what the belt's cross-section carries "
            f"at {v:g} m/s ({figures(cap.capacity_m3_h)} m3/h, ISO 5048): "
            f"{fill_levers(conv, cap.fill_pct, 100.0)} would avoid it")
    steep = incline_warning(conv, loop)
    if steep:
        warnings.append(steep)
    warnings += _slip_words(res, drives, slip_margins, start_margins, breakaway, shortfall_n)
    warnings += _takeup_beyond_words(res, drives)
    # ---- each drive's motor power against its rating (SPEC 7.4, beltstudy.engine.drives)
    rated_kw, _ = rated_power_kw(conv, res.te_n, float(np.sum(res.resistance_n)))
    warnings += _power_beyond_words(conv, rated_kw)
    fields, short = drive_checks(conv, [share * res.te_n for _i, share, _e in drives], v,
                                  res.te_n, rated_kw)
    res.summary.update(fields)
    warnings += short
    for strand, name in ((CARRY, "carry"), (RETURN, "return")):
        mask = loop.strand == strand
        if mask.any():
            worst = float(sag[mask].max())
            limit = float(hs_adm[mask][0])
            if worst > limit * (1.0 + SAG_LIMIT_RTOL):
                # the span that needs the most added tension, not the largest ratio: every
                # slack span reads w / 1 N, so the first of them tied for the largest ratio
                # and the words sized the take-up for it, not for the slackest span
                lack = np.where(mask & idl, loop.sag_w_n / limit - np.minimum(T, Tprev),
                                -np.inf)
                j = int(np.argmax(lack))
                warnings.append(_sag_words(loop, name, float(sag[j]), limit, j,
                                           float(min(T[j], Tprev[j]))))
    sf_min = conv.safety_factor_min or SAFETY_FACTOR_MIN.get(belt.kind, 6.7)
    sf = res.summary["safety_factor"]
    if sf < sf_min * (1.0 - 1e-9):  # equal to its minimum passes, as belt.type: auto's test
        tu_auto = (conv.takeup.type == "gravity" and conv.takeup.mass_kg == "auto") or (
            conv.takeup.type == "fixed" and conv.takeup.pretension_kn == "auto")
        warnings.append(_safety_words(loop, belt, sf, sf_min, float(T[imax]),
                                      float(s_end[imax]), tu_auto))
    if T.min() <= 1.0 + 1e-9:
        warnings.append("the belt goes slack (tension at or below zero): raise the take-up")
    # ---- design checks: pulleys, transitions, idlers, holdback (beltstudy.engine.checks)
    friction_n = (sum(comps.values()) - comps["lift"] - comps.get("feed", 0.0)) * 1e3
    checked, check_warnings = design_checks(conv, loop, T, sf_min, friction_n)
    res.summary.update(checked)
    warnings += check_warnings
    # held at rest, the pulley holding the stopped belt takes its whole net pull: a given
    # take-up too light for it is said here, not only by the transient run's rest state
    T_rest = rest_tensions(conv, loop, T)
    warnings += rest_grip_words(loop, rest_hold_element(conv, loop), T_rest, conv)
    if loop.curves:  # vertical curves: lift-off running and at start-up (the start-up
        # walk of slip_margin_start, T_start above), convex radius (beltstudy.engine.curves)
        checked, check_warnings = curve_checks(conv, loop, T, sf_min, T_start, T_rest)
        res.summary.update(checked)
        warnings += check_warnings
    # grade changes without curve_radius_m, read as the circle through their survey points
    warnings += junction_checks(conv, loop, T, sf_min, T_start)
    # ---- horizontal curves (beltstudy.engine.hcurves; nothing without curves)
    curved, curve_warnings = hcurve_checks(conv, loop, T)
    res.summary.update(curved)
    warnings += curve_warnings
    held = holding_warning(conv, loop, friction_n)
    if held:
        warnings.append(held)
    warnings += _brake_beyond_words(conv, loop)
    res.warnings = warnings
    res.status = "warning" if warnings else "ok"
    res.message = "; ".join(warnings + _notes(res, friction_n, comps.get("feed", 0.0)))
    res.summary["status"] = res.status
    res.summary["message"] = res.message


def _notes(res: SteadyResult, friction_n: float, feed_kn: float) -> list[str]:
    """The steady run's notes, after its warnings (a note does not make a warning, as the
    transient's notes do not): the law's temperature and glass notes, the run-back, the start
    time, the take-up's place, inputs read beyond the tables or in an unusual sense (idler
    rows, loading speed, ...) and values that look written in other units (W for kW, N for
    kN); ``friction_n`` the running resistance without lift and feed [N], ``feed_kn`` the
    feed part of Te [kN]."""
    conv, loop = res.conveyor, res.loop
    note = temperature_note(get_model(res.model), res.temperature_c, res.params_given)
    glassy = (rubber.glass_note(res.law.info["compound"], res.temperature_c, res.model)
              if "compound" in res.law.info else "")
    given = input_notes(conv, loop, feed_kn * 1e3, res.law.info.get("c_factor"))
    units = (watts_notes(conv, res.te_n, float(np.sum(res.resistance_n)))
             + lump_notes(conv, loop.belt.width_m))
    return [n for n in (note, glassy, res.range_note, runback_note(conv, loop, friction_n),
                        start_time_note(conv, loop, res.te_n), takeup_place_note(res),
                        *given, *units) if n]



# ------------------------------------------------------------ start-up tensions (issue 27)
__all__ += ["startup_tensions", "up3"]


#: A take-up this many times tighter than the slackest point of the return is named in a note
#: with the lighter one there (a design hint, not a verdict: CEMA and DIN 22101 place the
#: take-up where the running belt is slackest, just behind the drive, or at the tail of a head
#: drive whose return falls towards it).
TAKEUP_PLACE_RATIO = 1.5


def takeup_place_note(res: SteadyResult) -> str:
    """A note when the take-up sits where the running belt is much tighter (``TAKEUP_PLACE_RATIO``)
    than at the slackest point of the return: a take-up sets the tension where it is and the
    loop's running tensions follow from it, so about the same running tensions are held by a
    counterweight of ``2 T / g`` (a pretension ``T``) at that point, less the take-up's own
    pulleys' resistance, which moves with it (a 500 m, -40 m decline driven at the tail, its
    take-up at the tail: 2 154 kg; 2 T / g at the head end of the return 884 kg; auto there
    926 kg). The note gives the estimate and the field that sizes it there with every check
    (``mass_kg: auto`` / ``pretension_kn: auto``). "" otherwise."""
    loop, T = res.loop, res.tension_n
    ret = np.flatnonzero(loop.strand == RETURN)
    if not ret.size or res.takeup_tension_n <= 0.0:
        return ""
    j = int(ret[np.argmin(T[ret])])
    t_low, t_tu = float(T[j]), float(res.takeup_tension_n)
    if t_low <= 0.0 or t_tu < TAKEUP_PLACE_RATIO * t_low:
        return ""
    part, x = loop.where(float(loop.s_end_m[j]))
    field = f"takeup.position: {part}" if part in ("head", "tail") else _takeup_at(
        res.conveyor, x)
    gravity = res.conveyor.takeup.type == "gravity"
    size = (f"a counterweight of about {2.0 * t_low / G:.0f} kg (2 T / g there, now "
            f"{res.takeup_mass_kg:.0f} kg), and mass_kg: auto" if gravity else
            f"a pretension of about {gnum(t_low / 1e3, 3)} kN (now {gnum(t_tu / 1e3, 3)} kN), and "
            "pretension_kn: auto")
    return (f"note: the take-up holds {gnum(t_tu / 1e3, 3)} kN where it sits, {t_tu / t_low:.1f} x "
            f"the slackest running tension of the return ({gnum(t_low / 1e3, 3)} kN "
            f"{place_words(loop, float(loop.s_end_m[j]))}): a take-up there ({field}) holds "
            f"about the same running tensions with {size} there sizes it with its own pulleys "
            "and every check")


def _takeup_at(conv: Conveyor, x_m: float) -> str:
    """The take-up fields that place it on the return near ``x_m`` from the tail [m], as the
    conveyor file takes them: an end of the route is ``position: tail`` or ``head`` (the
    slackest return tension at the tail end of the return read 'position: return, at_m: 0',
    which the file refuses), a point on a vertical curve's arc the nearer whole metre off it
    (a take-up on an arc is refused)."""
    for a, b in curve_arcs(conv.judged_profile()):
        if a < x_m < b:
            x_m = math.floor(a) if x_m - a <= b - x_m else math.ceil(b)
    at = round(x_m)
    if at <= 0:
        return "takeup.position: tail"
    if at >= conv.length_m:
        return "takeup.position: head"
    return f"takeup.position: return, at_m: {at:.0f}"


def place_words(loop: Loop, s_m: float) -> str:
    """Words for a loop position [m] (round the loop from the tail, carry first): strand and
    distance from the tail, or the pulley there."""
    part, x = loop.where(s_m)
    if part in ("carry", "return"):
        return f"{x:.0f} m from the tail on the {part}"
    if part in ("head", "tail"):
        return f"at the {part} pulley"
    return f"at the {part} pulley ({x:.0f} m from the tail)"


def _sag_words(loop: Loop, strand: str, sag: float, limit: float, j: int, t_low: float
               ) -> str:
    """The steady sag warning of the span ending at element ``j``: how much, where, the
    tension that keeps it within its limit (the sag ratio goes as 1 / T, DIN 22101) and what
    would avoid it. ``sag`` and ``limit`` are ratios h/S [-], ``t_low`` the span's lower
    tension [N] (at or below zero: the belt is slack there, and its sag is a floor's)."""
    need = float(loop.sag_w_n[j]) / limit
    where = place_words(loop, float(loop.s_end_m[j]))
    if t_low <= 0.0:  # w / max(T, 1 N) is a number, not a sag: the strand lies slack there
        head = (f"the {strand} strand is slack (tension {gnum(t_low / 1e3, 3)} kN {where}): its sag "
                f"there has no bound, far beyond sag_limit_pct.{strand} = {limit * 100:.2f} %")
    else:
        # a sag past its limit by less than the rounding printed as it: '1.50 % exceeds 1.50 %'
        shown, lim = apart(sag * 100, limit * 100, rtol=SAG_LIMIT_RTOL)
        head = (f"sag on the {strand} strand {shown} % exceeds sag_limit_pct.{strand} "
                f"= {lim} % (tension {gnum(t_low / 1e3, 3)} kN {where})")
    return (f"{head}; {up3(need / 1e3):g} kN there keeps "
            f"it within (the sag goes as 1 / T), so the take-up must hold at least "
            f"{up3((need - t_low) / 1e3):g} kN more per strand; that, closer idlers "
            f"(idlers.{strand}.spacing_m) or a higher sag limit would avoid it")


#: The width clause of :func:`_safety_words` ('at these tensions ST5400 needs a width of at
#: least 1.46 m (more with its own weight)'), which :func:`auto_width_words` replaces by the
#: figure of ``belt.type: auto``'s own warning beside it.
_WIDTH_AT_TENSIONS = re.compile(r"at these tensions (\S+) needs a width of at least "
                                r"[0-9.]+ m \(more with its own weight\)")


def auto_width_words(text: str, belt_id: str, width_m: float, solved: bool) -> str:
    """``text`` with :func:`_safety_words`' width for ``belt_id`` (an estimate at the present
    tensions) replaced by the one ``belt.type: auto`` gives beside it
    (:mod:`beltstudy.engine.beltselect`): ``solved``, the width [m] at which the belt passes
    solved again with its own weight at that width, else its estimate over every case it
    picks at (running and start-up). One output gave two figures: 'at these tensions ST5400
    needs a width of at least 1.46 m (more with its own weight)' beside 'ST5400 passes at a
    width of 1.49 m'. Unchanged where the clause names another belt or is absent."""
    if solved:
        said = (f"{belt_id} passes at a width of {width_m:.2f} m (belt.width_m; solved "
                "again at that width, the belt's own weight with it)")
    else:
        said = (f"at these tensions {belt_id} needs a width of at least {width_m:.2f} m (more "
                "with its own weight)")
    return _WIDTH_AT_TENSIONS.sub(lambda m: said if m.group(1) == belt_id else m.group(0),
                                  text)


def _safety_words(loop: Loop, belt, sf: float, sf_min: float, t_max: float, s_m: float,
                  takeup_auto: bool = False) -> str:
    """The steady safety factor warning: how much, where the largest tension is, and the
    belt rating per metre of width that meets the minimum (``rating = S_min T_max / B``);
    a lower largest tension by a lighter take-up only where the take-up is given (an auto
    one, ``takeup_auto``, is already the least its slip and sag limits need)."""
    need_kn_m = sf_min * t_max / belt.width_m / 1e3
    strongest = max((b for b in catalog.belts().values() if b.kind == belt.kind),
                    key=lambda b: b.rating_kn_m, default=None)
    if strongest is None or need_kn_m <= strongest.rating_kn_m:
        # belt.type: auto without belt.kind is refused ('needs belt.kind'): the kind is named
        kind = catalog.FILE_KIND.get(belt.kind)
        pick = ("belt.type: auto" + (f" with belt.kind: {kind}" if kind else "")
                + " picks the lightest catalogue belt that passes")
    else:
        # no catalogue belt of this kind is that strong, so belt.type: auto would not find one;
        # the strongest meets the minimum at these tensions on a belt this much wider
        width = sf_min * t_max / (strongest.rating_kn_m * 1e3)
        pick = (f"stronger than any catalogue {belt.kind} belt: the strongest, "
                f"{strongest.id}, is rated {figures(strongest.rating_kn_m)} kN/m, and "
                f"belt.type: auto finds none that passes; at these tensions {strongest.id} "
                f"needs a width of at least {math.ceil(width * 100.0) / 100.0:.2f} m (more with "
                "its own weight), "
                "or a belt of its own from a maker's sheet (rating_kn_m)")
    lower = ("drives spread along the belt; the auto take-up is already the least the slip "
             "and sag limits need" if takeup_auto else
             "a take-up no heavier than the slip and sag limits need, drives spread along "
             "the belt")
    # below 1 the running tension is past the belt's breaking strength: said as what it is
    broken = ("; below 1, the largest running tension is above the belt's breaking strength: "
              "the belt would break" if sf < 1.0 else "")
    sf_text, min_text = apart(sf, sf_min)  # never '6.55 is below the minimum 6.55'
    return (f"belt safety factor {sf_text} is below the minimum {min_text} (t_max "
            f"{t_max / 1e3:.1f} kN {place_words(loop, s_m)}; belt rating "
            f"{figures(belt.rating_n / 1e3)} kN, {figures(belt.rating_kn_m)} kN/m x "
            f"{belt.width_m:g} m){broken}: a "
            f"belt rated at least {math.ceil(need_kn_m)} kN/m at this width ({pick}), or a "
            f"lower largest tension ({lower}) "
            "would avoid it")


#: The words of a convex curve's radius at the tensions of the run's own arc
#: (:func:`beltstudy.engine.curves._convex_words`), which :func:`_settle_radii` replaces.
_AT_THESE = re.compile(r"curve (\d+) \(convex, .*?a radius of at least (\d+) m \(at these "
                       r"tensions, which a larger radius moves a little: rerun to confirm\)")
#: Solves at most, settling one radius.
SETTLE_MAX = 6
#: The words of a concave curve's radius at the tensions of the run's own arc
#: (:func:`beltstudy.engine.curves.steady_curve_checks`, ``_start_liftoff`` and
#: ``_rest_liftoff``), each with the summary field that names the radius it needs: running, at
#: start-up and held at rest.
_CONCAVE_AT = (
    (re.compile(r"curve (\d+) \(concave, .*?a radius of at least (\d+) m keeps it on them "
                r"at these tensions"), "curve{k}_radius_min_m"),
    (re.compile(r"curve (\d+) \(concave, .*?, and at start-up \([\d.]+ kN there\) at least "
                r"(\d+) m"), "curve{k}_radius_min_start_m"),
    (re.compile(r"curve (\d+) \(concave, .*?a radius of at least (\d+) m \(R x T_start / "
                r"T_lift"), "curve{k}_radius_min_start_m"),
    (re.compile(r"curve (\d+) \(concave, .*?, and held at rest \([\d.]+ kN there, an "
                r"estimate\) at least (\d+) m"), "curve{k}_radius_min_rest_m"),
    (re.compile(r"curve (\d+) \(concave, .*?a radius of at least (\d+) m \(R x T_rest / "
                r"T_lift"), "curve{k}_radius_min_rest_m"),
)


def _settled_radius(res: SteadyResult, case: dict, k: int, r_try: int, key: str
                    ) -> int | None:
    """Curve ``k``'s radius solved again from ``r_try`` [m] until the radius its summary field
    ``key`` names holds at that radius (the least whole metre found so); None where a radius
    does not fit its sections or does not settle within :data:`SETTLE_MAX` solves."""
    curve = next((c for c in res.loop.curves if c.k == k), None)
    if curve is None:
        return None
    for _ in range(SETTLE_MAX):
        data = res.conveyor.model_dump(mode="json", by_alias=True, exclude_none=True)
        data["profile"][curve.section]["curve_radius_m"] = r_try
        try:
            trial = solve_steady(Conveyor.model_validate(data), settle=False, **case)
        except (ValueError, InputError):
            return None
        need = trial.summary.get(key.format(k=k))
        if need is None or not math.isfinite(need):
            return None
        if need <= r_try:
            return r_try
        r_try = math.ceil(need)
    return None


def _settle_concave(res: SteadyResult, case: dict) -> None:
    """A concave curve's advised radius (running, and at start-up) solved again at that radius
    until it holds there, as :func:`_settle_radii` does for a convex one: a 400 m belt's tight
    concave curve near its tail was told 167 m, and lifted at 167 m (176 m needed); a 3 km
    route's 661 m needed 666 m, its start-up 824 m needed 833 m."""
    for pattern, key in _CONCAVE_AT:
        for w in list(res.warnings):
            m = pattern.search(w)
            if m is None:
                continue
            k, r_asked = int(m.group(1)), int(m.group(2))
            settled = _settled_radius(res, case, k, r_asked, key)
            if settled is None or settled == r_asked:
                continue
            old = m.group(0)
            head, _, _ = old.rpartition(f"{r_asked} m")
            new = (f"{head}{settled} m (solved again at that radius: its longer arc moves the "
                   f"tensions, and {r_asked} m at this run's own falls short)"
                   + old[len(head) + len(f"{r_asked} m"):])
            res.warnings = [x.replace(old, new) for x in res.warnings]
            res.message = res.message.replace(old, new)
            res.summary["message"] = res.message


def _settle_radii(res: SteadyResult, case: dict) -> None:
    """A convex curve's advised radius solved again at that radius until it holds there
    (the longer arc moves the tensions on it, and the radius its edges need with them): the
    words name the settled radius instead of the one at the run's own arc. A 6 km overland's
    crest was told 3 738 m, which failed at 3 835 m, which failed at 3 838 m. Each solve is
    this case's (``case``); the words are left as they were where a radius does not fit its
    sections or does not settle within :data:`SETTLE_MAX` solves."""
    for m in list(_AT_THESE.finditer(res.message)):
        settled = _settled_radius(res, case, int(m.group(1)), int(m.group(2)),
                                  "curve{k}_radius_min_m")
        if settled is None or settled == int(m.group(2)):
            continue
        said = (f"a radius of at least {settled} m (solved again at that radius: its longer arc "
                f"moves the tensions, and {m.group(2)} m at this run's own falls short)")
        old = m.group(0)
        new = old.replace(old[old.index("a radius of at least"):], said)
        res.warnings = [w.replace(old, new) for w in res.warnings]
        res.message = res.message.replace(old, new)
        res.summary["message"] = res.message


def lever_words(gravity: bool, why: str = "") -> str:
    """The take-up lever in words (:func:`beltstudy.engine.design.takeup_lever`) of a take-up
    that is ``gravity`` or not: ``a heavier take-up``, or for a fixed (screw or winch) one,
    which has no counterweight, ``a higher take-up pretension (takeup.pretension_kn)``;
    ``why`` goes in the brackets."""
    if not gravity:
        return "a higher take-up pretension (takeup.pretension_kn" + (f", {why})" if why else ")")
    return "a heavier take-up" + (f" ({why})" if why else "")


def rest_grip_words(loop: Loop, hold: int, T_rest: np.ndarray, conv=None) -> list[str]:
    """The pulley holding the belt at rest passes at most ``T_slack (e^(mu theta) - 1)``
    (Euler-Eytelwein, PHYSICS 5.1, static friction): a rest state that asks more of it cannot
    stand (the belt would creep over the held pulley). In words, with the take-up lever of
    ``conv`` (:func:`lever_words`: a fixed take-up has no counterweight to make heavier); []
    where it holds. The steady check says it of a given
    take-up (an auto one is sized to hold, :func:`_rest_grip_bound`), the transient run of its
    own rest state."""
    pulley = next((p for p in loop.pulleys if p.element == hold), None)
    if pulley is None:
        return []
    t_in, t_out = float(T_rest[hold - 1]), float(T_rest[hold])
    slack = max(min(t_in, t_out), 0.0)
    grip = slack * math.expm1(pulley.friction * math.radians(pulley.wrap_deg))
    held = abs(t_out - t_in)
    # a take-up sized to the grip holds (rounding aside); and round-off beside tensions of
    # any size is no force (a belt slack at rest read "passes 1.819e-15 kN, beyond its grip
    # of 0 kN ... a slack-side tension of 8.405e-16 kN would hold it")
    if held <= grip * (1.0 + 1e-9) + 1e-9 * max(abs(t_in), abs(t_out), 1.0):
        return []
    need = held / math.expm1(pulley.friction * math.radians(pulley.wrap_deg))
    more = (lever_words(conv.takeup.type == "gravity") if conv is not None
            else "a heavier take-up")
    return [f"at rest the {pulley.where} pulley holding the belt passes {gnum(held / 1e3)} kN, "
            f"beyond its grip of {gnum(grip / 1e3)} kN (slack side {gnum(slack / 1e3)} kN, mu "
            f"{pulley.friction:g}, wrap {pulley.wrap_deg:g} deg): the belt would creep over it; "
            f"a slack-side tension of {gnum(need / 1e3)} kN ({more}) or a brake or "
            "holdback on another pulley would hold it"]


def rest_tensions(conv: Conveyor, loop: Loop, T: np.ndarray) -> np.ndarray:
    """Tensions held at rest [N], an estimate: the at-rest walk (:func:`rest_walk`: no
    running resistance, the pulley holding the belt, :func:`rest_hold_element`, taking the
    net gravity pull) levelled as the start-up walk is (:func:`start_level`: a gravity
    take-up's mean tension, a fixed one's loop length, elastic only; the transient run's rest
    state takes the chord length with the spans' sag for a fixed take-up)."""
    fixed = conv.takeup.type == "fixed"
    Wr = rest_walk(loop, rest_hold_element(conv, loop), loop.gravity_n)
    return Wr + (start_level(loop, T, fixed) - start_level(loop, Wr, fixed))


def startup_tensions(res: SteadyResult) -> np.ndarray:
    """Tensions at start-up with DIN 22101's start-up peripheral force [N].

    The steady solution's own start-up walk (:func:`_startup_walk`: the drives give
    ``STARTUP_FACTOR`` x Te, the excess accelerating every moving mass), levelled so a
    gravity take-up holds the same mean tension as running and a fixed one the same loop
    length (:func:`start_level`): the tensions the take-up's
    ``slip_start`` sizing and ``slip_margin_start`` use, at the boundaries of the elements
    (and the concave curves' lift-off at start-up, ``curve{k}_liftoff_start``).
    The largest is the start-up peak of a rigid-body start (no wave fronts, no overshoot of
    the torque limit), an estimate the transient run's ``t_max_start_kn`` replaces.
    """
    conv, loop = res.conveyor, res.loop
    dF = res.resistance_n + loop.gravity_n
    W = np.cumsum(dF - res.drive_force_n)
    delta = _startup_walk(conv, loop, dF, res.te_n) - W
    return res.tension_n + delta - start_level(loop, delta, conv.takeup.type == "fixed")
