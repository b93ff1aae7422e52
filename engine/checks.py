"""Design checks of a steady solution: DIN 22101, ISO 5048, CEMA and ISO 281 (docs/checks.md).

Pure functions in SI, one per check, and :func:`steady_checks` / :func:`transient_checks`
that apply them to a run's loop and tensions and return the summary fields of
:data:`beltstudy.engine.results.CHECKS` and :data:`~beltstudy.engine.results.CHECKS_TRANSIENT`
with the warnings:

* the minimum pulley diameter by DIN 22101 (groups A, B, C; reduced with the belt's
  utilisation at the pulley): ``pulley{j}_diameter_min_m``, ``pulley{j}_diameter_min_ok``;
* the minimum transition lengths at the head and tail (CEMA 7th ed. Table 7.29):
  ``transition_head_m``, ``transition_tail_m``;
* the pulley resultant (shaft) force, the vector sum of the two belt tensions:
  ``pulley{j}_resultant_kn`` and, from the transient tension envelope,
  ``pulley{j}_resultant_dyn_kn``;
* the carry idler load per set and per roll (DIN 22101 / ISO 5048) against the CEMA class
  rating, and the roll bearings' L10 life (ISO 281): ``idler_load_carry_n``,
  ``idler_load_roll_n``, ``idler_l10_h``;
* the holdback torque at the head pulley (CEMA's rule: the lift less half the friction):
  ``holdback_torque_knm``.

Pulley ``j`` is the pulley's 1-based number in loop order (:attr:`Loop.pulleys`): the head
pulleys first (the head drives in file order, or one plain head pulley), a head take-up
pulley, then at the tail a take-up pulley before the tail drives, the tail drives in file
order, or one plain tail pulley (the take-up pulley of a tail take-up). ``pulley{j}_name``
says which it is.

The catalogue data (``engine/data/pulleys.csv``, ``carcass.csv``, ``transitions.csv``,
``idler_ratings.csv``) name their sources in their headers; values not checked against the
primary source are marked unverified there.
"""

from __future__ import annotations

import bisect
import math
import re
from dataclasses import dataclass
from functools import cache

import numpy as np

from beltstudy.engine.catalog import _rows
from beltstudy.engine.drives import apart
from beltstudy.engine.loop import G, Loop, Pulley
from beltstudy.engine.wording import gnum

__all__ = [
    "LUMP_MAX_KN_M",
    "lump_notes",
    "holding_warning",
    "HOLD_MARGIN",
    "C_TR",
    "BAND_RTOL",
    "GROUP_A_TENSION_SHARE",
    "SNUB_WRAP_DEG",
    "MIDDLE_ROLL_SHARE",
    "BEARING_LIFE_EXPONENT",
    "HOLDBACK_FRICTION_SHARE",
    "runback_note",
    "input_notes",
    "PulleyCheck",
    "pulley_group",
    "pulley_diameter_min_m",
    "transition_length_m",
    "pulley_resultant_n",
    "idler_load_set_n",
    "middle_roll_share",
    "pitch_within_m",
    "bearing_l10_h",
    "idler_ratings",
    "holdback_torque_nm",
    "pulley_name",
    "steady_checks",
    "transient_checks",
]

#: DIN 22101's factor C_Tr of the carcass material [-]: D_A = C_Tr x d_Gk. Steel cord 145,
#: polyester warp (EP) 108. The manufacturer's reprint of the DIN table (engine/data/pulleys.csv
#: [DIN-TAB]) prints 145 for steel and 106 for polyester; 108 is the value usually quoted
#: from DIN 22101 (unverified: the standard was not at hand).
C_TR = {"steel": 145.0, "fabric": 108.0}
#: A plain pulley whose highest tension is at least this share of the way from the loop's
#: lowest to its highest steady tension is in the "range of high belt tension" (group A),
#: below it group B [-]. DIN 22101 names the ranges without a number: this line is the
#: project's reading (unverified).
GROUP_A_TENSION_SHARE = 0.5
#: A pulley with less wrap than this is a snub pulley, group C [deg] (DIN 22101).
SNUB_WRAP_DEG = 30.0
#: Share of a three-roll troughing set's load carried by its middle roll, by trough angle
#: [deg -> -]: the "participation factor" of the most loaded roll as idler makers' handbooks
#: tabulate it (Rulmeca's 20 deg 0.60, 30 deg 0.65, 35 deg 0.67, 45 deg 0.72), interpolated,
#: held at the end values outside 20-45 deg. Quoted from memory of the handbook, not read
#: here: unverified.
MIDDLE_ROLL_SHARE = ((20.0, 0.60), (30.0, 0.65), (35.0, 0.67), (45.0, 0.72))
#: ISO 281 life exponent of ball bearings [-].
BEARING_LIFE_EXPONENT = 3.0
#: Share of the running friction counted against the run-back pull when sizing a holdback
#: [-]: CEMA's rule as Belt Analyst documents it ("the force required to lift the load
#: vertically minus one-half the force required to move the belt and load horizontally",
#: support.overlandconveyor.com, Backstops). DIN 22101's reduced friction for the holding case
#: was not checked (unverified).
HOLDBACK_FRICTION_SHARE = 0.5

#: Minimum holding force of an auto-sized brake as a multiple of the net gravity pull of the
#: loaded belt [-] (a holding margin, an estimate; :mod:`beltstudy.engine.design` sizes with
#: it, :func:`holding_warning` names it).
HOLD_MARGIN = 1.2
#: Utilisation bands of the DIN pulley table (upper bounds, columns of pulleys.csv).
_DIN_BANDS = ((0.3, "30"), (0.6, "60"), (math.inf, "100"))
#: Relative tolerance of a band edge (DIN's 30 % and 60 %, CEMA's 60 % and 90 %): a
#: utilisation at an edge up to float noise is at it. A tension of exactly 90 % of an ST1000
#: belt's rated tension (1 m, 1000 kN / 6.7) reads 0.9000000000000001 as T x S_min / rating,
#: which put its transition in CEMA's "over 90 %" row (6.8 B at 35 deg against 5.2 B).
BAND_RTOL = 1e-9


@cache
def _pulley_table() -> list[dict[str, float]]:
    return [{k: float(v) for k, v in r.items()} for r in _rows("pulleys.csv")]


@cache
def _carcass_mm() -> dict[str, float]:
    return {r["id"]: float(r["carcass_mm"]) for r in _rows("carcass.csv")}


@cache
def _transitions() -> dict[tuple[str, str], list[tuple[float, float]]]:
    out: dict[tuple[str, str], list[tuple[float, float]]] = {}
    for r in _rows("transitions.csv"):
        for kind in ("fabric", "steel"):
            out.setdefault((kind, r["band"]), []).append((float(r["trough_deg"]),
                                                          float(r[kind])))
    return {k: sorted(v) for k, v in out.items()}


@cache
def _idler_ratings() -> dict[str, dict[str, float]]:
    return {r["cema_class"]: {k: float(r[k]) for k in ("carry_rating_n", "return_rating_n",
                                                       "bearing_c_n", "l10_min_h")}
            for r in _rows("idler_ratings.csv")}


def idler_ratings() -> dict[str, dict[str, float]]:
    """The idler catalogue by CEMA class (``engine/data/idler_ratings.csv``, its header names
    the sources): ``carry_rating_n`` and ``return_rating_n``, the load rating of a set [N];
    ``bearing_c_n``, the roll bearing's dynamic rating [N]; ``l10_min_h``, the L10 life [h]
    the rating holds at (CEMA 502). A copy: the caller may change it."""
    return {k: dict(v) for k, v in _idler_ratings().items()}


# ------------------------------------------------------------------ pulley diameters
def pulley_group(wrap_deg: float, drive: bool, tension_n: float, t_low_n: float,
                 t_high_n: float) -> str:
    """DIN 22101 pulley group of a pulley: ``A``, ``B`` or ``C``.

    Parameters
    ----------
    wrap_deg : float
        Wrap of the belt round the pulley [deg].
    drive : bool
        A drive pulley.
    tension_n : float
        Highest steady belt tension at the pulley [N].
    t_low_n, t_high_n : float
        Lowest and highest steady tension round the loop [N].

    Notes
    -----
    C: wrap < 30 deg (snub); A: drive pulleys, and pulleys whose tension is in the upper
    range, ``T >= T_low + GROUP_A_TENSION_SHARE (T_high - T_low)``; B: the others (tail,
    take-up and bend pulleys at low tension).

    References
    ----------
    DIN 22101:2011, pulley diameters (groups A, B, C).
    """
    if wrap_deg < SNUB_WRAP_DEG and not drive:
        return "C"
    if drive or tension_n >= t_low_n + GROUP_A_TENSION_SHARE * (t_high_n - t_low_n):
        return "A"
    return "B"


def pulley_diameter_min_m(kind: str, carcass_m: float, group: str, utilisation: float
                          ) -> float:
    """Minimum pulley diameter by DIN 22101 [m].

    Parameters
    ----------
    kind : str
        ``steel`` (steel cord) or ``fabric`` (polyester warp).
    carcass_m : float
        d_Gk: cord diameter (steel cord) or carcass thickness without covers (fabric) [m].
    group : str
        Pulley group ``A``, ``B`` or ``C`` (:func:`pulley_group`).
    utilisation : float
        Belt tension at the pulley over the admissible steady tension (belt rating / minimum
        safety factor) [-].

    Returns
    -------
    float
        The minimum diameter without lagging [m].

    Notes
    -----
    ``D_A = C_Tr d_Gk`` (C_Tr: :data:`C_TR`), rounded up to the next diameter of the DIN
    table; the table gives the group's minimum in the utilisation band: over 60 % to 100 %,
    over 30 % to 60 % (one step down), up to 30 % (two steps down for group A). Above the
    table's 2000 mm the group A value is D_A itself and the others keep the ratio of the
    table's last row.

    References
    ----------
    DIN 22101:2011, minimum pulley diameters; table in engine/data/pulleys.csv [DIN-TAB].
    """
    d_a_mm = C_TR[kind] * carcass_m * 1e3
    band = next(b for top, b in _DIN_BANDS if utilisation <= top * (1.0 + BAND_RTOL))
    col = f"{group.lower()}_{band}"
    table = _pulley_table()
    sizes = [r["d_a_mm"] for r in table]
    k = bisect.bisect_left(sizes, d_a_mm - 1e-9)
    if k < len(table):
        return table[k][col] / 1e3
    last = table[-1]
    return d_a_mm * last[col] / last["d_a_mm"] / 1e3


# ------------------------------------------------------------------ transitions
def transition_length_m(kind: str, trough_deg: float, width_m: float, utilisation: float
                        ) -> float:
    """Minimum transition length from a terminal pulley to the first fully troughed idler [m].

    Parameters
    ----------
    kind : str
        ``steel`` (steel cord) or ``fabric``.
    trough_deg : float
        Trough angle of the carry idlers [deg].
    width_m : float
        Belt width B [m].
    utilisation : float
        Belt tension at the pulley over the belt's rated (working) tension, the rating over
        the minimum safety factor [-].

    Notes
    -----
    ``L = k(trough, band, kind) B``, full-trough transition, k from CEMA's table in the bands
    over 90 %, 60 % to 90 % and under 60 % of the rated tension, linear in the trough angle
    between the table's 20, 35 and 45 deg, from 0 at a flat belt to the 20 deg value, and
    beyond 45 deg continued with the 35-45 deg slope (outside the table).

    References
    ----------
    CEMA, Belt Conveyors for Bulk Materials, 7th ed., Table 7.29 (engine/data/transitions.csv).
    """
    band = ("high" if utilisation > 0.9 * (1.0 + BAND_RTOL) else
            ("mid" if utilisation >= 0.6 * (1.0 - BAND_RTOL) else "low"))
    pts = [(0.0, 0.0)] + _transitions()[(kind, band)]
    ang = [a for a, _ in pts]
    fac = [f for _, f in pts]
    if trough_deg <= ang[-1]:
        k = float(np.interp(trough_deg, ang, fac))
    else:
        k = fac[-1] + (fac[-1] - fac[-2]) / (ang[-1] - ang[-2]) * (trough_deg - ang[-1])
    return k * width_m


# ------------------------------------------------------------------ pulley resultant
def pulley_resultant_n(t_in_n, t_out_n, wrap_deg: float):
    """Resultant (shaft) force of the belt on a pulley [N].

    Parameters
    ----------
    t_in_n, t_out_n : float or ndarray
        Belt tension running on and off the pulley [N].
    wrap_deg : float
        Wrap angle [deg].

    Notes
    -----
    The two tensions pull along the tangents, at ``180 - wrap`` to each other:
    ``R = sqrt(T_in^2 + T_out^2 - 2 T_in T_out cos(wrap))``; ``T_in + T_out`` at 180 deg.
    The pulley's own weight is not included.

    References
    ----------
    DIN 22101:2011 (forces on pulleys); the law of cosines.
    """
    c = math.cos(math.radians(wrap_deg))
    return np.sqrt(np.maximum(t_in_n * t_in_n + t_out_n * t_out_n - 2.0 * t_in_n * t_out_n * c,
                              0.0))


# ------------------------------------------------------------------ idlers
def idler_load_set_n(belt_kg_m: float, load_kg_m: float, spacing_m: float) -> float:
    """Static load on one carry idler set [N].

    Parameters
    ----------
    belt_kg_m, load_kg_m : float
        Belt mass m'_G and material mass m'_L per metre [kg/m].
    spacing_m : float
        Idler set pitch S [m].

    Notes
    -----
    ``F = g (m'_G + m'_L) S``; no impact, misalignment or uneven-height load (CEMA's IML
    needs the idler's height deviation, which the conveyor file does not give).

    References
    ----------
    DIN 22101:2011 and ISO 5048:1989, idler loads.
    """
    return G * (belt_kg_m + load_kg_m) * spacing_m


def pitch_within_m(pitch_m: float, rating_n: float, load_n: float) -> float:
    """The idler pitch [m] at which a set loaded ``load_n`` at ``pitch_m`` (a load in
    proportion to the pitch) is within ``rating_n``, rounded down to the centimetre the
    warnings print: rounded to the nearest, ``pitch x rating / load`` could print a pitch
    a little above it (1.389 m as 1.39 m), whose load is still above the rating."""
    return math.floor(100.0 * pitch_m * rating_n / load_n * (1.0 + 1e-12)) / 100.0


def middle_roll_share(rolls: int, trough_deg: float) -> float:
    """Share of an idler set's load carried by its most loaded roll [-].

    One roll: 1; two rolls (a V set): 1/2; three or more: the middle roll's share by trough
    angle (:data:`MIDDLE_ROLL_SHARE`, the three-roll values; a five-roll garland's middle
    roll carries less, so this is an upper estimate there).
    """
    if rolls <= 1:
        return 1.0
    if rolls == 2:
        return 0.5
    ang = [a for a, _ in MIDDLE_ROLL_SHARE]
    return float(np.interp(trough_deg, ang, [s for _, s in MIDDLE_ROLL_SHARE]))


def bearing_l10_h(c_n: float, p_n: float, speed_m_s: float, roll_diameter_m: float) -> float:
    """Basic rating life L10 of an idler roll bearing [h].

    Parameters
    ----------
    c_n : float
        Basic dynamic load rating C of the bearing [N].
    p_n : float
        Equivalent dynamic load P on the bearing (a roll's load shared by its two bearings)
        [N].
    speed_m_s : float
        Belt speed [m/s].
    roll_diameter_m : float
        Roll diameter [m].

    Notes
    -----
    ``L10 = (C / P)^3 10^6 / (60 n)`` hours, ``n = 60 v / (pi D)`` rpm (ball bearings,
    exponent 3).

    References
    ----------
    ISO 281:2007, basic rating life.
    """
    if p_n <= 0.0:
        return math.inf
    n_rpm = 60.0 * speed_m_s / (math.pi * roll_diameter_m)
    return (c_n / p_n) ** BEARING_LIFE_EXPONENT * 1e6 / (60.0 * n_rpm)


# ------------------------------------------------------------------ holdback
def holdback_torque_nm(pull_n: float, friction_n: float, diameter_m: float) -> float:
    """Torque a holdback at a pulley must hold against the loaded belt running back [N m].

    Parameters
    ----------
    pull_n : float
        Net downhill pull of the loaded belt at rest, sum of the gravity components round the
        loop (the material's lift; the belt's own weight cancels) [N]; positive pulls the belt
        back.
    friction_n : float
        Running resistance of the belt and load (main and secondary resistances and
        accessories; not the feed) [N].
    diameter_m : float
        Diameter of the pulley carrying the holdback [m].

    Notes
    -----
    ``M = max(pull - HOLDBACK_FRICTION_SHARE x friction, 0) D / 2``: 0 when the belt cannot
    run back. No service factor: the holdback maker applies its own.

    References
    ----------
    CEMA, Belt Conveyors for Bulk Materials (backstops), as Belt Analyst documents it
    (support.overlandconveyor.com, "Backstops").
    """
    return max(pull_n - HOLDBACK_FRICTION_SHARE * friction_n, 0.0) * diameter_m / 2.0


# ------------------------------------------------------------------ applied to a run
def pulley_name(conv, p: Pulley) -> str:
    """How a message names a pulley: ``drive 2 (head)``, ``head``, ``take-up (tail)``."""
    if p.drive >= 0:
        return f"drive {p.drive + 1} ({p.where})"
    return f"take-up ({p.where})" if p.takeup else p.position


@dataclass(frozen=True)
class PulleyCheck:
    """One pulley's steady check: number, name, a drive pulley or not, group, diameter and
    minimum [m], highest tension [N], utilisation [-], resultant [N]."""

    j: int
    name: str
    drive: bool
    group: str
    diameter_m: float
    diameter_min_m: float | None
    tension_n: float
    utilisation: float
    resultant_n: float


def _band_pct(utilisation: float) -> str:
    """A utilisation [-] as the percent a pulley warning prints [%]: whole percent, with more
    decimals where a value just over a DIN band edge (30 %, 60 %) would print as the edge
    (60.04 % as '60 %', whose band is the one below, the minimum a step smaller)."""
    pct = 100.0 * utilisation
    edge = max((100.0 * top for top, _ in _DIN_BANDS
                if 100.0 * top * (1.0 + BAND_RTOL) < pct), default=0.0)
    return apart(pct, edge, 0, rtol=0.0)[0]


def _pulleys(conv, loop: Loop, T: np.ndarray, sf_min: float) -> list[PulleyCheck]:
    belt = loop.belt
    admissible = belt.rating_n / sf_min
    carcass = _carcass_mm().get(belt.id)
    t_low, t_high = float(T.min()), float(T.max())
    out = []
    for j, p in enumerate(loop.pulleys, start=1):
        t_in, t_out = float(T[p.element - 1]), float(T[p.element])
        t = max(t_in, t_out)
        group = pulley_group(p.wrap_deg, p.drive >= 0, t, t_low, t_high)
        u = t / admissible
        d_min = (pulley_diameter_min_m(belt.kind, carcass * 1e-3, group, u)
                 if carcass is not None and belt.kind in C_TR else None)
        name = pulley_name(conv, p)
        out.append(PulleyCheck(j, f"{name}, group {group}", p.drive >= 0, group, p.diameter_m,
                               d_min, t, u,
                               float(pulley_resultant_n(t_in, t_out, p.wrap_deg))))
    return out


def _idlers(conv, loop: Loop) -> tuple[dict, list[str]]:
    ic = conv.idlers.carry
    belt = loop.belt
    m_load = max(loop.design_load_kg_m, loop.load_max_kg_m)
    pitch = conv.idler_spacing_m("carry")
    f_set = idler_load_set_n(belt.mass_kg_m, m_load, pitch)
    f_roll = middle_roll_share(ic.rolls, ic.trough_deg) * f_set
    out = {"idler_load_carry_n": f_set, "idler_load_roll_n": f_roll, "idler_l10_h": None}
    warnings = []
    rating = _idler_ratings().get(ic.cema_class) if ic.cema_class else None
    if rating is None:
        return out, warnings
    l10 = bearing_l10_h(rating["bearing_c_n"], f_roll / 2.0, loop.speed_m_s, ic.roll_diameter_m)
    out["idler_l10_h"] = l10
    if f_set > rating["carry_rating_n"]:
        warnings.append(
            f"carry idler load {f_set:.0f} N per set (belt and design load over "
            f"{pitch:g} m) exceeds the CEMA {ic.cema_class} rating "
            f"{rating['carry_rating_n']:.0f} N: a heavier class or a closer pitch "
            f"({pitch_within_m(pitch, rating['carry_rating_n'], f_set):.2f} m)")
    if l10 < rating["l10_min_h"]:
        # L10 goes as 1 / P^3 and the roll's load P as the pitch: the pitch whose life is the
        # basis, rounded down to the centimetre printed (pitch_within_m)
        closer = pitch_within_m(pitch, (l10 / rating["l10_min_h"]) ** (1.0 / BEARING_LIFE_EXPONENT),
                                1.0)
        warnings.append(
            f"carry idler bearing life L10 {l10:.0f} h (middle roll {f_roll:.0f} N, two "
            f"bearings, ISO 281) is below the CEMA {ic.cema_class} basis "
            f"{rating['l10_min_h']:.0f} h: a heavier class, larger rolls or a closer pitch "
            f"({closer:.2f} m)")
    return out, warnings


def steady_checks(conv, loop: Loop, T: np.ndarray, sf_min: float, friction_n: float
                  ) -> tuple[dict, list[str]]:
    """The steady design-check fields and their warnings.

    Parameters
    ----------
    conv : Conveyor
    loop : Loop
    T : ndarray
        Steady boundary tensions, ``T[j]`` at the end of element j [N].
    sf_min : float
        Minimum belt safety factor in steady running [-]: the admissible tension is the
        rating over it.
    friction_n : float
        Running resistance without the feed [N] (:func:`holdback_torque_nm`).

    Returns
    -------
    dict, list of str
        Fields of :data:`beltstudy.engine.results.CHECKS`; warnings naming the pulley or
        idler, how much and what would avoid it.
    """
    belt = loop.belt
    out: dict = {}
    warnings: list[str] = []
    for pc in _pulleys(conv, loop, T, sf_min):
        # a plain or take-up pulley's diameter is the loop's estimate (engine/loop.py), not
        # a given: its minimum is reported, not judged
        ok = None if pc.diameter_min_m is None or not pc.drive else bool(
            pc.diameter_m >= pc.diameter_min_m - 1e-9)
        out[f"pulley{pc.j}_name"] = pc.name
        out[f"pulley{pc.j}_diameter_min_m"] = pc.diameter_min_m
        out[f"pulley{pc.j}_diameter_min_ok"] = ok
        out[f"pulley{pc.j}_resultant_kn"] = pc.resultant_n / 1e3
        if ok is False:
            warnings.append(
                f"pulley {pc.j} ({pc.name}) diameter {pc.diameter_m:g} m is below the DIN "
                f"22101 minimum {pc.diameter_min_m:g} m for {belt.id} at "
                f"{_band_pct(pc.utilisation)} % of the admissible tension: a pulley of at least "
                f"{pc.diameter_min_m:g} m")
    ic = conv.idlers.carry
    sf = sf_min
    t_head = float(T[loop.i_head - 1])  # the carry arriving at the head
    t_tail = float(T[loop.i_tail])  # the carry leaving the tail
    for where, t in (("head", t_head), ("tail", t_tail)):
        out[f"transition_{where}_m"] = (
            transition_length_m(belt.kind, ic.trough_deg, belt.width_m, t * sf / belt.rating_n)
            if belt.kind in ("steel", "fabric") else None)
    idl, w = _idlers(conv, loop)
    out.update(idl)
    warnings += w
    hb = loop.pulley_at(loop.i_head)
    out["holdback_torque_knm"] = holdback_torque_nm(
        float(loop.gravity_n.sum()), friction_n, hb.diameter_m) / 1e3
    return out, warnings


def runback_note(conv, loop: Loop, friction_n: float) -> str:
    """The note of a loaded incline that can run back when stopped (a holdback torque above 0,
    :func:`holdback_torque_nm`) with nothing to hold it at rest (``holdback: false`` and no
    brake with ``hold``): the pull, the resistance CEMA's backstop rule credits and the
    holdback that avoids it; "" otherwise. A note, not a warning: the steady run is not
    where the belt runs back (the transient's stop is)."""
    if conv.holdback or any(b.hold for b in conv.brakes):
        return ""
    pull = float(loop.gravity_n.sum())
    torque = holdback_torque_nm(pull, friction_n, loop.pulley_at(loop.i_head).diameter_m)
    if torque <= 0.0:
        return ""
    return (f"note: the loaded belt can run back when it stops: its lift pulls {gnum(pull / 1e3, 3)} kN "
            f"back against {gnum(HOLDBACK_FRICTION_SHARE * friction_n / 1e3, 3)} kN (half its "
            "running resistance without the feed, CEMA's backstop rule) and nothing holds it "
            "(holdback: false, no brake with hold: true): a holdback on the head pulley of at "
            f"least {gnum(torque / 1e3, 3)} kNm (holdback: true) or a holding brake would avoid it")


def holding_warning(conv, loop: Loop, friction_n: float) -> str:
    """The warning of holding brakes (``hold: true``) whose given forces cannot hold the loaded
    belt at rest: its net gravity pull (forward on a decline; back on an incline without a
    holdback) less the resistance CEMA's backstop rule credits (half the running resistance
    without the feed, :data:`HOLDBACK_FRICTION_SHARE`) is more than their forces' sum; a brake
    holds at most its force. "" when an auto brake holds (it is sized to
    :data:`HOLD_MARGIN` x the pull), a holdback holds an incline, no
    brake holds, or they hold."""
    holding = [(i, b) for i, b in enumerate(conv.brakes) if b.hold]
    if not holding or any(b.force_kn == "auto" for _, b in holding):
        return ""
    pull = float(loop.gravity_n.sum())
    if pull > 0.0 and conv.holdback:
        return ""
    credit = HOLDBACK_FRICTION_SHARE * max(friction_n, 0.0)
    need = abs(pull) - credit
    given = sum(float(b.force_kn) for _, b in holding) * 1e3
    if need <= 0.0 or given >= need:
        return ""
    way = "forward (downhill)" if pull < 0.0 else "back"
    names = ", ".join(f"brakes.{i} {float(b.force_kn):g} kN" for i, b in holding)
    return (f"the holding brakes cannot hold the loaded belt at rest: {names} give "
            f"{gnum(given / 1e3)} kN in all against its net gravity pull {gnum(abs(pull) / 1e3)} kN "
            f"less {gnum(credit / 1e3, 3)} kN (half its running resistance without the feed, CEMA's "
            f"backstop rule), {gnum(need / 1e3)} kN, so it would creep {way} once stopped; "
            f"holding brakes of at least {math.ceil(need / 1e2) / 10:g} kN in all (force_kn: "
            f"auto sizes them {HOLD_MARGIN:g} x the pull, {gnum(HOLD_MARGIN * abs(pull) / 1e3)} kN)"
            + (" or a holdback (holdback: true)" if pull > 0.0 else "") + " would avoid it")


#: The auto size :func:`holding_warning` offers ("(force_kn: auto sizes them 1.2 x the pull,
#: 50.45 kN)"), which :func:`design_holding_words` rewords for a study's design.
_AUTO_HOLD = re.compile(r"\(force_kn: auto sizes them ([0-9.]+) x the pull, ([0-9.e+-]+) kN\)")


def design_holding_words(text: str, governed_by: str | None) -> str:
    """:func:`holding_warning`'s words in ``text`` said of a study's design: its brakes are
    auto already, sized over the design's cases (``governed_by``, the design's
    ``brake_governed_by``), so 'force_kn: auto sizes them' is no fix; a case outside the
    design's list (the warning fires only there: within it the auto size holds) is, added to
    the list. ``text`` unchanged without a design's brake (None, ``given``) or the words."""
    if not governed_by or governed_by == "given" or not text:
        return text
    return _AUTO_HOLD.sub(
        lambda m: (f"(the study's auto brakes are sized over its design cases, "
                   f"brake_governed_by {governed_by}, and this run's case is not one of them: "
                   f"with its load, model and temperature in the study's design: list they are "
                   f"sized for it too, {m.group(1)} x its pull, {m.group(2)} kN)"), text)


def _loading_speeds(conv) -> list[tuple[str, float]]:
    """``(field, v0)`` of each feed point's along-belt loading speed [m/s], one entry per field
    (a feed point without its own speed reads ``material.loading_speed_m_s``)."""
    if not conv.material.feed:
        return [("material.loading_speed_m_s", float(conv.material.loading_speed_m_s))]
    out: dict[str, float] = {}
    for i, f in enumerate(conv.material.feed):
        if f.loading_speed_m_s is None:
            out["material.loading_speed_m_s"] = float(conv.material.loading_speed_m_s)
        else:
            out[f"material.feed.{i}.loading_speed_m_s"] = float(f.loading_speed_m_s)
    return list(out.items())


#: The largest accessory lump (``accessories.head_kn``, ``tail_kn``) per metre of belt width
#: read as kN [kN/m]; above it a lump is taken for newtons written for kN. ISO 5048 gives a
#: belt scraper A p mu_3 of at most about 0.6 kN per metre of width (A 0.01 m2 a metre,
#: p up to 1e5 N/m2, mu_3 0.6) and a plough 1.5 kN a metre: 50 kN/m is some 80 scrapers,
#: while a 2 kN lump written in newtons on a 1.2 m belt is 1 667 kN/m.
LUMP_MAX_KN_M = 50.0


def lump_notes(conv, width_m: float) -> list[str]:
    """Notes of accessory lumps above :data:`LUMP_MAX_KN_M` per metre of belt width
    ``width_m``: ``head_kn: 2000`` for a 2 kN scraper passed as a 2 MN resistance."""
    notes = []
    for name in ("head_kn", "tail_kn"):
        v = float(getattr(conv.accessories, name))
        if v > LUMP_MAX_KN_M * width_m:
            notes.append(f"note: accessories.{name} {v:g} kN is {v / width_m:,.0f} kN per "
                         f"metre of belt width, above the {LUMP_MAX_KN_M:g} kN/m of some 80 "
                         "belt scrapers (ISO 5048: about 0.6 kN/m each); accessories are in "
                         f"kN: if it was written in N, it is {v / 1e3:g} kN")
    return notes


#: A drive train efficiency below which a note says it is no conveyor gear unit's [-]: the
#: least efficient gear units in use, worm gears, run from about 0.5 up (a self-locking worm
#: is below 0.5); helical and bevel-helical units are 0.94-0.98.
EFFICIENCY_LOW = 0.5


def input_notes(conv, loop: Loop, feed_n: float, c_factor: float | None = None) -> list[str]:
    """Notes on inputs the run reads beyond its tables or in an unusual sense (SPEC: a value
    the engine takes in place of one it has not got is said): an idler roll diameter between
    two catalogue rows (:func:`beltstudy.engine.catalog.idler_note`), a loading speed above
    the belt speed or against the travel, a belt width outside the DIN 22107 roll table and a
    trough angle outside the CEMA transition and middle-roll tables, a vertical curve whose
    arc is shorter than an idler pitch, judged as the bend one idler set makes or as the
    grade change without it (:func:`_short_curve_notes`). ``feed_n`` is the feed
    part of Te [N]; ``c_factor`` DIN's C where the run's law used it (the feed is inside C
    and the loading speed is not read)."""
    from beltstudy.engine import catalog
    from beltstudy.engine.capacity import _roll_table

    notes = []
    width = loop.belt.width_m
    for strand in ("carry", "return_"):
        name = strand.rstrip("_")
        n = catalog.idler_note(getattr(conv.idlers, strand), width, f"idlers.{name}")
        if n:
            notes.append(n)
    for i, d in enumerate(conv.drives):
        if d.efficiency < EFFICIENCY_LOW:
            # below any gear unit a conveyor drive uses: a typo reads as a huge auto motor
            # (0.1 sized a 13,327 kW motor for a 1.2 MW belt, said as ok)
            notes.append(f"note: drives.{i}.efficiency {d.efficiency:g} is below a conveyor "
                         "drive train's (0.85-0.97: helical or bevel-helical gear units and a "
                         f"coupling; docs/drives.md), so the motor takes {gnum(1.0 / d.efficiency, 3)} "
                         "x its pulley's power" + (
                             " (and the auto rated power grows by as much)"
                             if d.rated_power_kw is None else ""))
    v = loop.speed_m_s
    loaded = loop.design_load_kg_m > 0.0
    for field, v0 in _loading_speeds(conv) if loaded else []:
        if c_factor is not None and v0 != 0.0:
            notes.append(f"note: {field} {v0:g} m/s is not read: DIN 22101's secondary "
                         f"resistance factor C = {gnum(c_factor, 3)} holds the feed as a usual "
                         "loading at rest (the models that sum the feed, cema, cmod, nonlin "
                         "and visco, read it; din does below 80 m without models.din.c)")
        elif v0 > v:
            notes.append(f"note: {field} {v0:g} m/s is above the belt speed {v:g} m/s: the "
                         "material fed pushes the belt (DIN 22101 F_bA = I_m (v - v0) below "
                         f"0: the feed part of Te is {gnum(feed_n / 1e3, 3)} kN)")
        elif v0 < 0.0:
            skirts = any(f.skirt_length_m > 0.0 for f in conv.material.feed or [])
            notes.append(f"note: {field} {v0:g} m/s is against the belt's travel: the belt "
                         "stops the material, then accelerates it (F_bA = I_m (v - v0), the "
                         f"feed part of Te {gnum(feed_n / 1e3, 3)} kN)" + (
                             ", and the skirts' friction while it accelerates (ISO 5048 F_f, "
                             "for 0 <= v0 < v, summed by din below 80 m) is that from rest, "
                             "a lower bound" if skirts else ""))
    ic = conv.idlers.carry
    widths, _ = _roll_table()
    if ic.rolls == 3 and ic.roll_length_m is None and not widths[0] <= width <= widths[-1]:
        end = widths[0] if width < widths[0] else widths[-1]
        notes.append(f"note: belt.width_m {width:g} m is outside DIN 22107's roll table "
                     f"({widths[0]:g} to {widths[-1]:g} m, engine/data/trough.csv): the middle "
                     f"roll of the {end:g} m belt is used for the capacity check "
                     "(idlers.carry.roll_length_m gives the set's own)")
    lo, hi = MIDDLE_ROLL_SHARE[0][0], MIDDLE_ROLL_SHARE[-1][0]
    words = []
    top = max(a for (_, k), pts in _transitions().items() for a, _ in pts)
    if loop.belt.kind in ("steel", "fabric") and ic.trough_deg > top:
        words.append(f"the transition lengths continue CEMA Table 7.29's 35 to {top:g} deg "
                     "slope past its last row")
    if ic.rolls >= 3 and not lo <= ic.trough_deg <= hi:
        share = middle_roll_share(ic.rolls, ic.trough_deg)
        words.append(f"the middle roll's share of the set's load is that of "
                     f"{lo if ic.trough_deg < lo else hi:g} deg ({share:.2f}, the table runs "
                     f"{lo:g} to {hi:g} deg)")
    if words:
        notes.append(f"note: idlers.carry.trough_deg {ic.trough_deg:g} deg is outside the "
                     f"tables: {' and '.join(words)}")
    notes += _unread_drive_fields(conv)
    notes += _unread_brake_fields(conv)
    notes += _short_curve_notes(conv)
    return notes


def _unread_brake_fields(conv) -> list[str]:
    """``ramp_s`` given beside a ``force_curve``, as a note: the brake follows its curve (the
    transient model and the auto size alike) and never reads the ramp. Given means other than
    its default, as for the drives (:func:`_unread_drive_fields`)."""
    if not conv.brakes:
        return []
    default = type(conv.brakes[0]).model_fields["ramp_s"].default
    return [f"note: brakes.{i}.ramp_s {b.ramp_s:g} s is not read: brake {i + 1} follows its "
            f"force_curve (the fraction of its force against the time since applied), which "
            f"sets how its force builds: give the build-up in force_curve, or leave force_curve "
            f"out to ramp over ramp_s"
            for i, b in enumerate(conv.brakes)
            if b.force_curve and b.ramp_s != default]


def _short_curve_notes(conv) -> list[str]:
    """A note per vertical curve whose arc is shorter than an idler pitch
    (:meth:`beltstudy.engine.conveyor.Conveyor.short_curves`): the run judges it as a curve
    of ``S / |delta|``, whose arc spans one pitch, where that fits its sections
    (:meth:`beltstudy.engine.conveyor.Conveyor.judged_profile`), else as the grade change
    without a curve. The note names the field, the turn, the arc, the pitch and the
    radius whose arc spans a pitch, ``S / |delta|`` rounded up to the metre, where that is a
    radius the field takes (up to 1e6 m) and its half arcs fit the two sections beside their
    other curves; otherwise that the turn is too small for any curve."""
    from beltstudy.engine.conveyor import CURVE_RADIUS_MAX_M, curve_arc_m

    prof, judged = conv.profile, conv.judged_profile()
    pitch = conv.curve_pitch_m()
    notes = []
    for i, turn, arc in conv.short_curves():
        sec, nxt = prof[i], prof[i + 1]
        grades = (f"profile.{i} lifts {sec.lift_m:.10g} m over {sec.length_m:g} m, "
                  f"profile.{i + 1} {nxt.lift_m:.10g} m over {nxt.length_m:g} m")
        r_span = math.ceil(pitch / turn - 1e-9)
        room = min(sec.length_m - (0.5 * curve_arc_m(judged, i - 1) if i else 0.0),
                   nxt.length_m - 0.5 * curve_arc_m(judged, i + 1))
        head = (f"note: profile.{i}.curve_radius_m {sec.curve_radius_m:g} m: the grades turn "
                f"by {gnum(math.degrees(turn), 3)} deg ({grades}), so its arc is {gnum(arc, 3)} m, "
                f"shorter than the idler pitch {pitch:g} m: at most one idler set stands on it "
                "and the belt bends there as at a kink, not round R, so ")
        radius = judged[i].curve_radius_m
        if radius is not None:
            # judged as the tightest bend the sets give (Conveyor.short_curve_radius_m)
            notes.append(
                head + f"it is judged as a curve of S / |delta| = {gnum(radius)} m, whose arc "
                "spans one pitch (the turn taken on one idler set: its resultant T |delta| "
                "against the belt's weight over a pitch, as that radius judges it); a radius "
                f"of at least {r_span:.0f} m is a curve of its own")
            continue
        if r_span > CURVE_RADIUS_MAX_M:
            fix = (f"the turn is too small for any curve: no radius up to "
                   f"{CURVE_RADIUS_MAX_M:.0f} m spans a pitch (S / |delta| = "
                   f"{gnum(pitch / turn, 3)} m; if the grades should differ, check lift_m)")
        elif 0.5 * r_span * turn > room:
            fix = (f"the turn is too small for any curve on these sections: one whose arc "
                   f"spans a pitch, R >= {r_span:.0f} m (S / |delta|), does not fit them")
        else:
            fix = f"a radius of at least {r_span:.0f} m (S / |delta|) makes the arc span a pitch"
        notes.append(head + "it is judged as a grade change without a curve (the circle "
                     f"through its survey points); {fix}")
    return notes


def _unread_drive_fields(conv) -> list[str]:
    """Drive fields given in the file that this drive's control or coupling does not read, as
    notes: ``coupling_fill_s`` is the fill time of a fill-controlled fluid coupling only,
    ``motor_inertia_kg_m2`` splits the shaft's inertia at a fluid coupling only (without one
    the motor turns with the pulley and ``inertia_kg_m2`` holds it all), and ``torque_limit``
    caps a vfd drive's force only (a dol motor gives its curve's torque, through its coupling
    if it has one: docs/dynamics.md, *Drives*), and ``motor_curve`` is a dol motor's torque
    only (a vfd drive's speed loop sets its force up to ``torque_limit``; SPEC 6.1's drive
    block shows the curve beside ``control: vfd``, so it is taken, checked and said).

    A field counts as given when it differs from its default, not by Pydantic's
    ``model_fields_set``: a study's runs and a non-full-load run's sized conveyor are
    validated again from the whole dumped conveyor, which marks every field set."""
    notes = []
    fields = type(conv.drives[0]).model_fields if conv.drives else {}
    fill_default = fields["coupling_fill_s"].default if conv.drives else None
    limit_default = fields["torque_limit"].default if conv.drives else None
    for i, d in enumerate(conv.drives):
        if d.coupling_fill_s != fill_default and d.coupling != "fluid_fill_controlled":
            notes.append(f"note: drives.{i}.coupling_fill_s {d.coupling_fill_s:g} s is not "
                         f"read: only a fill-controlled fluid coupling fills over a time (coupling: "
                         f"fluid_fill_controlled, control: dol), and drive {i + 1}'s coupling is "
                         f"{d.coupling}")
        if d.motor_inertia_kg_m2 is not None and d.coupling == "none":
            notes.append(f"note: drives.{i}.motor_inertia_kg_m2 {d.motor_inertia_kg_m2:g} kg m2 "
                         f"is not read: it splits the shaft's inertia at a fluid coupling "
                         f"(coupling: fluid or fluid_fill_controlled, control: dol), and without "
                         f"one the motor turns with the pulley and inertia_kg_m2 "
                         f"({d.inertia_kg_m2:g} kg m2) holds it all")
        if d.torque_limit != limit_default and d.control == "dol":
            through = " through its fluid coupling" if d.coupling != "none" else ""
            notes.append(f"note: drives.{i}.torque_limit {d.torque_limit:g} is not read: it "
                         f"caps a vfd drive's force (control: vfd), and drive {i + 1} is a "
                         f"motor on the line (control: dol), whose force is its motor_curve's "
                         f"torque{through}")
        if d.motor_curve is not None and d.control == "vfd":
            notes.append(f"note: drives.{i}.motor_curve is not read: it is the torque of a "
                         f"motor on the line (control: dol), and drive {i + 1} is a vfd drive, "
                         f"whose speed loop sets its force up to torque_limit "
                         f"({d.torque_limit:g} x its rated torque), and control: dol runs the "
                         f"motor on its curve")
    return notes


def transient_checks(loop: Loop, t_max_n: np.ndarray) -> dict:
    """Transient design-check fields: ``pulley{j}_resultant_dyn_kn`` from the tension
    envelopes of the cycle.

    Parameters
    ----------
    loop : Loop
        The loop the transient ran on (its springs are the loop's element ends).
    t_max_n : ndarray
        Highest tension of each spring, every time step [N]: over the whole cycle (one row),
        or one row per envelope segment of the kernel (cut at the start command, when the
        belt first goes slack and at the stop command, ``TransientResult.raw["segments"]``).

    Notes
    -----
    ``R_dyn = max over segments k of R(max_k T_in, max_k T_out)`` (:func:`pulley_resultant_n`):
    within a segment the two maxima need not fall at the same time, so this is an upper bound
    on the largest resultant (exact when both peak together, as they nearly do at a plain
    pulley, whose two tensions differ only by its own drag and inertia). Per segment it is
    tighter than over the whole cycle: a drive pulley's tight side peaks in the start, its
    slack side often in the stop.
    """
    env = np.atleast_2d(np.asarray(t_max_n, dtype=float))
    out = {}
    for j, p in enumerate(loop.pulleys, start=1):
        r = pulley_resultant_n(env[:, p.element - 1], env[:, p.element], p.wrap_deg)
        out[f"pulley{j}_resultant_dyn_kn"] = (float(np.nanmax(r)) / 1e3 if np.isfinite(r).any()
                                              else math.nan)
    return out
