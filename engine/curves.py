"""Vertical curves: lift-off at concave curves, edge strain at convex ones (docs/routes.md,
part (c); SPEC 7.1 and 7.4).

The loop puts elements on each curve (:class:`beltstudy.engine.loop.Curve`, the element's
slope the arc's at its middle); these checks read the tensions there.

Concave curve (a valley, the grade increasing). The belt's tension T bends round the curve and
presses it outwards (upwards) with T / R per metre; its weight presses it onto the idlers with
m' g cos(a) per metre. It leaves its idlers where

    T > R m' g cos(a)                                   (lift-off)

(CEMA, *Belt Conveyors for Bulk Materials*, 7th ed., ch. 9 "Concave vertical curves", the
radius r = T / (w_b cos a) that keeps the empty belt on its idlers; DIN 22101:2011 names the
same balance for concave curves; both *unverified* against the printed text). m' is the belt's
own mass m'_G: with material on it (m'_G + m'_L) the limit is higher, so the empty belt, and
the empty return strand that runs through the same valley, lift first. The check uses the
empty belt on both strands at the tensions of the load case run, running and at start-up:
CEMA 7th ed. takes a concave curve's radius from the belt tension at the curve during
starting, DIN 22101 the most unfavourable operating case, so the steady check also walks the
start-up tensions (the drives at ``STARTUP_FACTOR`` x their running force, the walk of the
start-up slip check: :func:`beltstudy.engine.statics.startup_tensions`) and names the radius
``R x T_start / T_lift`` that keeps the belt down at start, a rigid-body estimate beside the
transient run's ``liftoff_*``.

Convex curve (a crest, the grade decreasing). The trough's wings lie above the belt's centre
line, so on a curve of radius R a fibre at height z above it runs on radius R + z and is
stretched by z / R more than the centre. With the mean strain eps = T / (E B) fixed by the
tension, the centre carries eps - z_mean / R and the edges (height h) eps + (h - z_mean) / R
(z_mean the height of the trough's cross-section averaged over the belt width). The smallest
radius keeps the edge within the admissible strain and the centre in tension:

    R_min = max((h - z_mean) / (eps_adm - eps), z_mean / eps)

with eps_adm = (rating / S_min) / (E B), the admissible running tension's strain (DIN 22101's
edge-strain treatment of transitions and convex curves, CEMA 7th ed. ch. 9 "Convex vertical
curves": edge tension and centre tension limits; CEMA lets the edge go somewhat above the
rated tension: this limit is the stricter; *unverified* against the printed texts). The
trough's cross-section is :func:`beltstudy.engine.capacity.trough_segments` over the whole
belt width. On a convex curve every idler set carries T S / R more (the belt's tension
pressing round the curve); on a concave one that much less.
"""

from __future__ import annotations

import math

import numpy as np

from beltstudy.engine import checks
from beltstudy.engine.capacity import middle_roll_length_m, trough_segments
from beltstudy.engine.loop import CARRY, RETURN, Curve, G, Loop
from beltstudy.engine.wording import gnum

__all__ = ["liftoff_tension_n", "liftoff_limits_n", "convex_radius_min_m",
           "convex_idler_warnings", "steady_checks", "transient_liftoff"]


def liftoff_tension_n(radius_m: float, mass_kg_m: float, angle_rad: float) -> float:
    """Tension at which a belt leaves its idlers on a concave curve, R m' g cos(a) [N].

    Parameters
    ----------
    radius_m : float
        Curve radius R [m].
    mass_kg_m : float
        Mass per metre resting on the idlers m' [kg/m] (the belt's own, m'_G, for the empty
        belt, which lifts first).
    angle_rad : float
        Slope angle a at the point [rad].
    """
    return radius_m * mass_kg_m * G * math.cos(angle_rad)


def liftoff_limits_n(loop: Loop, curve: Curve) -> tuple[np.ndarray, np.ndarray]:
    """The points of the curve's arc on both strands (carry then return), as the springs
    (element ends, ``T[j]`` at the end of element j) that sit on them, and each point's
    lift-off tension for the empty belt, R m'_G g cos(a) at that point's slope [N].

    The points are the arc's two ends and every junction of its elements: on each strand the
    spring just before the strand's first arc element (where the belt enters the arc) and the
    end of every arc element. Each is judged by its own tension against the cosine of the
    arc's slope there, ``a = a_in + (x - x_start) / R`` (``x`` along the route): the tension at
    an element's end against the slope at its middle (half an element's turn, up to 0.5 deg,
    away) let a belt lift by up to ``R m'_G g (cos(a - step / 2) - cos a)`` at the arc's steep
    end unseen, and the point where each strand enters the arc was not judged at all (on the
    return, and on a carry running down into the valley, that is the steeper end).
    """
    sign = 1.0 if curve.delta_rad > 0.0 else -1.0
    # arc length from the arc's tail-side end to each carry element's ends: the slope there
    along = np.concatenate(([0.0], np.cumsum(loop.dx_m[curve.carry])))
    ang = curve.angle_in_rad + sign * along / curve.radius_m
    carry, ret = curve.carry, curve.ret  # ret in carry order: ret[i] runs over carry[i]
    # carry: the spring before its first arc element (the tail-side end), then each end;
    # return (head -> tail): the spring before ret[-1] (the head-side end), then each
    # element's end, the tail-side end of the stretch it runs over
    el = np.concatenate(([carry[0] - 1], carry, [ret[-1] - 1], ret))
    el = np.where(el < 0, el + loop.n, el)  # the carry's first element: the tail's end
    a = np.concatenate((ang, [ang[-1]], ang[:-1]))
    m_g = np.concatenate((loop.mG_kg_m[carry[:1]], loop.mG_kg_m[carry],
                          loop.mG_kg_m[ret[-1:]], loop.mG_kg_m[ret]))
    return el, curve.radius_m * m_g * G * np.cos(a)


def _trough_heights(width_m: float, rolls: int, trough_deg: float, roll_length_m: float
                    ) -> tuple[float, float]:
    """Edge height h and width-mean height z_mean of a troughed belt's cross-section above its
    centre line [m]."""
    z = area = 0.0
    for length, angle in trough_segments(width_m, rolls, trough_deg, roll_length_m):
        rise = length * math.sin(angle)
        area += length * (z + 0.5 * rise)  # the segment's height integrated along the belt
        z += rise
    return z, area / (0.5 * width_m)


def convex_radius_min_m(tension_n: float, stiffness_n: float, admissible_n: float,
                        width_m: float, rolls: int, trough_deg: float,
                        roll_length_m: float | None = None) -> float | None:
    """Smallest radius of a convex curve for the troughed belt's edge and centre strains [m].

    Parameters
    ----------
    tension_n : float
        Belt tension at the curve T [N].
    stiffness_n : float
        Axial stiffness E B [N].
    admissible_n : float
        Admissible running tension, rating / S_min [N]: the edge strain's limit is its strain.
    width_m, rolls, trough_deg, roll_length_m
        Belt width B [m], rolls of the carry set, trough angle [deg], middle-roll length [m]
        (default by width, :func:`beltstudy.engine.capacity.middle_roll_length_m`).

    Returns
    -------
    float or None
        ``max((h - z_mean) / (eps_adm - eps), z_mean / eps)``; ``inf`` when the tension is at
        or above the admissible one or not positive (no radius is enough); None for a flat
        belt (no trough: the edges follow the centre).
    """
    roll = middle_roll_length_m(width_m, rolls) if roll_length_m is None else roll_length_m
    h, z_mean = _trough_heights(width_m, rolls, trough_deg, roll)
    if h <= 0.0:
        return None
    eps, eps_adm = tension_n / stiffness_n, admissible_n / stiffness_n
    if eps <= 0.0 or eps >= eps_adm:
        return math.inf
    return max((h - z_mean) / (eps_adm - eps), z_mean / eps)


def convex_idler_warnings(conv, loop: Loop, curve: Curve, tension_n: float) -> list[str]:
    """The carry idler sets on a convex curve against their CEMA class: rating and L10.

    On a convex curve each carry set carries, beside the weight of belt and load
    ``g (m'_G + m'_L) S``, the belt's tension pressing round the curve, ``T S / R`` (CEMA,
    *Belt Conveyors for Bulk Materials*, 7th ed., ch. 5 idler selection and ch. 9 convex
    curves: the radial load from the belt tension is added to the idler load; DIN 22101:2011
    the same balance; *unverified* against the printed texts). The set's load is judged
    against the class's rating and its middle roll (the straight run's share of the set's
    load, :func:`beltstudy.engine.checks.middle_roll_share`, kept for the curve's part too: an
    upper estimate) against the L10 basis, as ``idler_load_carry_n`` and ``idler_l10_h`` are
    on the straight run (:mod:`beltstudy.engine.checks`).

    Returns
    -------
    list of str
        One warning when a limit is passed, naming the curve, the set's load (weight and curve part)
        and the pitch or radius that meets it; empty without a ``cema_class``.
    """
    ic = conv.idlers.carry
    rating = checks._idler_ratings().get(ic.cema_class) if ic.cema_class else None
    if rating is None:
        return []
    pitch = conv.idler_spacing_m("carry")
    m_load = max(loop.design_load_kg_m, loop.load_max_kg_m)
    f_weight = checks.idler_load_set_n(loop.belt.mass_kg_m, m_load, pitch)
    f_curve = tension_n * pitch / curve.radius_m
    f_set = f_weight + f_curve
    share = checks.middle_roll_share(ic.rolls, ic.trough_deg)
    where = (f"curve {curve.k} (convex, R {curve.radius_m:g} m at {curve.at_m:.0f} m): each "
             f"carry idler set carries {f_set:.0f} N ({f_weight:.0f} N of belt and design load "
             f"over {pitch:g} m and {f_curve:.0f} N of the tension {tension_n / 1e3:.1f} kN "
             f"pressing round the curve, T S / R)")
    parts = []
    if f_set > rating["carry_rating_n"]:
        # the set load is proportional to the pitch; the curve part alone to 1 / R
        room = rating["carry_rating_n"] - f_weight
        radius = (f", or a radius of at least {math.ceil(curve.radius_m * f_curve / room):.0f} m"
                  if room > 0.0 else "")
        # the pitch is rounded down to the cm: rounded to the nearest it could name one a
        # little above the rating's (1.5 x 4003 / 4323 = 1.389 m printed 1.39 m, 4006 N)
        closer = checks.pitch_within_m(pitch, rating["carry_rating_n"], f_set)
        parts.append(f"above the CEMA {ic.cema_class} rating {rating['carry_rating_n']:.0f} N: a "
                     f"heavier class, a closer pitch of the sets on the curve (at most "
                     f"{closer:.2f} m at this tension; idlers.carry.spacing_m is the whole "
                     f"carry's pitch, whose added idlers raise the tension a little: rerun "
                     f"to confirm){radius}")
    l10 = checks.bearing_l10_h(rating["bearing_c_n"], share * f_set / 2.0, loop.speed_m_s,
                               ic.roll_diameter_m)
    if l10 < rating["l10_min_h"]:
        parts.append(f"its middle roll's bearing life L10 {l10:.0f} h (ISO 281, "
                     f"{share * f_set:.0f} N on two bearings) is below the CEMA "
                     f"{ic.cema_class} basis {rating['l10_min_h']:.0f} h: a heavier class, "
                     "larger rolls, a closer pitch there or a larger radius")
    return [f"{where}, " + "; and ".join(parts)] if parts else []


def _kn_range(lo_n: float, hi_n: float) -> str:
    """``12.3`` or ``12.3 to 14.5`` [kN] as one figure reads."""
    lo, hi = f"{lo_n / 1e3:.1f}", f"{hi_n / 1e3:.1f}"
    return hi if lo == hi else f"{lo} to {hi}"


def _start_liftoff(c: Curve, loop: Loop, el: np.ndarray, lim: np.ndarray, T: np.ndarray,
                   T_start: np.ndarray | None, lifts_running: bool) -> tuple[dict, list[str]]:
    """A concave curve's lift-off at start-up: ``curve{k}_*_start`` fields and a warning.

    CEMA (*Belt Conveyors for Bulk Materials*, 7th ed., ch. 9, concave curves) takes the
    curve's radius from the belt tension at the curve during starting, and DIN 22101:2011
    checks the most unfavourable operating case, which on a concave curve is usually the
    start (*unverified* against the printed texts). The start-up tensions are the steady
    solution's own start-up walk (:func:`beltstudy.engine.statics.startup_tensions`: the
    drives give ``STARTUP_FACTOR`` = 1.5 x their running force, the excess accelerating
    every moving mass, the take-up holding its running mean tension; the walk the take-up's
    ``slip_start`` sizing and ``slip_margin_start`` use), a rigid-body estimate: the
    transient run's ``liftoff_*`` is the start's own figure. The belt lifts at start-up where
    ``T_start > R m'_G g cos(a)`` on either strand; the radius that keeps it down is
    ``R max(T_start / T_lift)`` over the curve's elements, ``max T_start / (m'_G g cos a)``.

    Returns
    -------
    dict, list of str
        ``curve{k}_tension_start_kn`` (highest start-up tension on the curve, either strand),
        ``curve{k}_liftoff_start`` and ``curve{k}_radius_min_start_m`` (all null without
        start-up tensions); one warning when the start lifts the belt and running does not
        (where running lifts, its own warning names the start's radius too).
    """
    k = c.k
    if T_start is None:
        return {f"curve{k}_tension_start_kn": None, f"curve{k}_liftoff_start": None,
                f"curve{k}_radius_min_start_m": None}, []
    ts = T_start[el]
    over = ts - lim
    j = int(np.argmax(over))
    lifts = bool(over[j] > 0.0)
    r_need = float(np.max(ts * c.radius_m / lim))  # T_start / (m'_G g cos a)
    out = {f"curve{k}_tension_start_kn": float(ts.max()) / 1e3,
           f"curve{k}_liftoff_start": lifts, f"curve{k}_radius_min_start_m": r_need}
    if not lifts or lifts_running:
        return out, []
    strand = "carry" if loop.strand[el[j]] == CARRY else "return"
    return out, [
        f"curve {k} (concave, R {c.radius_m:g} m at {c.at_m:.0f} m): at start-up the empty "
        f"belt lifts off its {strand} idlers, start-up tension {ts[j] / 1e3:.1f} kN (the "
        f"drives at the start-up factor of the slip check, a rigid-body estimate) above the "
        f"lift-off tension {lim[j] / 1e3:.1f} kN (R m'_G g cos a), though running stays "
        f"down ({T[el[j]] / 1e3:.1f} kN there); a radius of at least {math.ceil(r_need):.0f} m "
        "(R x T_start / T_lift) keeps it on them at start (a larger radius lengthens the "
        "curve and moves the tensions a little: rerun to confirm), or a gentler start "
        "lowers the start-up tension (simulate gives the transient figure, liftoff_*)"]


def _rest_liftoff(c: Curve, loop: Loop, el: np.ndarray, lim: np.ndarray,
                  T_rest: np.ndarray | None, lifts_running: bool) -> tuple[dict, list[str]]:
    """A concave curve where the belt held at rest lifts off its idlers (``T_rest > R m'_G g
    cos a``): ``curve{k}_*_rest`` fields and a warning ([] where it does not lift, or where
    running lifts it: that warning names the radius at rest too). At rest no resistance holds
    the tension down: the take-up's tension and the weight of the belt above it (a 6 km
    overland's empty belt held 210.4 kN at its 600 m curve, 10 m above its tail take-up,
    against 202.6 kN of lift-off tension, and only the transient run said so, as lift-off in
    the start). The radius that keeps it down at rest is ``R max(T_rest / T_lift)``; no start
    or stop time changes it.

    Returns
    -------
    dict, list of str
        ``curve{k}_tension_rest_kn`` (highest at-rest tension on the curve, either strand),
        ``curve{k}_liftoff_rest`` and ``curve{k}_radius_min_rest_m`` (all null without
        at-rest tensions); one warning when the belt at rest lifts and running does not.
    """
    k = c.k
    if T_rest is None:
        return {f"curve{k}_tension_rest_kn": None, f"curve{k}_liftoff_rest": None,
                f"curve{k}_radius_min_rest_m": None}, []
    tr = T_rest[el]
    over = tr - lim
    j = int(np.argmax(over))
    lifts = bool(over[j] > 0.0)
    r_need = float(np.max(tr * c.radius_m / lim))
    out = {f"curve{k}_tension_rest_kn": float(tr.max()) / 1e3,
           f"curve{k}_liftoff_rest": lifts, f"curve{k}_radius_min_rest_m": r_need}
    if not lifts or lifts_running:
        return out, []
    strand = "carry" if loop.strand[el[j]] == CARRY else "return"
    return out, [
        f"curve {c.k} (concave, R {c.radius_m:g} m at {c.at_m:.0f} m): held at rest the empty "
        f"belt lifts off its {strand} idlers, at-rest tension {tr[j] / 1e3:.1f} kN (the "
        "take-up's and the belt's weight, no running resistance: an estimate the transient "
        f"run's lift-off at rest replaces) above the lift-off tension {lim[j] / 1e3:.1f} kN "
        f"(R m'_G g cos a); a radius of at least {math.ceil(r_need):.0f} m (R x T_rest / "
        "T_lift; rerun to confirm) or less tension there at rest (a lighter take-up, where "
        "its slip checks allow) keeps it on them; no start or stop time changes it"]


def _convex_words(k: int, c: Curve, belt, ic, sf_min: float, t_low: float, t_high: float,
                  r_min: float) -> str:
    """The warning of a convex curve below its radius (:func:`convex_radius_min_m`): which
    strain sets the radius, the edge's at the arc's highest tension or the centre's at its
    lowest, the radius rounded up (a radius rounded to the nearest metre can fall short of it)
    and the other levers of that strain."""
    where = (f"curve {k} (convex, R {c.radius_m:g} m at {c.at_m:.0f} m): the troughed belt's "
             f"tension on the arc {_kn_range(t_low, t_high)} kN")
    if not math.isfinite(r_min):
        return (f"{where}: {t_high / 1e3:.1f} kN is at or above the admissible "
                f"{belt.rating_n / sf_min / 1e3:.1f} kN (rating / S_min), so no radius keeps the "
                "edge strain within it: a stronger belt or less tension there")
    roll = (middle_roll_length_m(belt.width_m, ic.rolls) if ic.roll_length_m is None
            else ic.roll_length_m)
    h, z_mean = _trough_heights(belt.width_m, ic.rolls, ic.trough_deg, roll)
    # the centre's radius as convex_radius_min_m writes it, z_mean / eps, judged to a relative
    # 1e-9: z_mean EB / T can come out an ulp below the same radius written z_mean / (T / EB),
    # and a curve set by its centre was told its edges pass the admissible strain, and less
    # tension, which slackens the centre further (0.0551 m / (25.7 kN / 72 000 kN) = 154.4 m)
    r_centre = z_mean / (t_low / belt.stiffness_n)
    if r_centre >= r_min * (1.0 - 1e-9):
        why = (f"at {t_low / 1e3:.1f} kN its centre line, stretched z_mean / R less than the "
               f"mean strain T / EB (z_mean {z_mean * 1e3:.0f} mm), goes slack")
        other = "more tension there (a heavier take-up) or a shallower trough"
    else:
        why = (f"at {t_high / 1e3:.1f} kN its edges, stretched (h - z_mean) / R more than the "
               f"mean strain T / EB (h - z_mean {(h - z_mean) * 1e3:.0f} mm), pass the "
               f"admissible strain, that of rating / S_min = {belt.rating_n / sf_min / 1e3:.1f} "
               "kN")
        other = "a stronger belt, less tension there or a shallower trough"
    return (f"{where}: {why}: a radius of at least {math.ceil(r_min):.0f} m (at these "
            f"tensions, which a larger radius moves a little: rerun to confirm) or {other}")


def _convex_radius_over(belt, ic, sf_min: float, t_high_n: float, t_low_n: float
                        ) -> float | None:
    """A convex arc's least radius over its tensions (:func:`convex_radius_min_m`): the edge
    term at the highest, the centre's at the lowest; None where no radius keeps the edges
    within the admissible strain (or the belt is flat)."""
    radii = [convex_radius_min_m(t, belt.stiffness_n, belt.rating_n / sf_min, belt.width_m,
                                 ic.rolls, ic.trough_deg, ic.roll_length_m)
             for t in (t_high_n, t_low_n)]
    return None if radii[0] is None else max(radii)


def _carry_points(loop: Loop, curve: Curve) -> np.ndarray:
    """The springs on the curve's carry arc: the one where the belt enters it (before its
    first arc element) and the end of each arc element (``T[j]`` at the end of element j).
    The entry is where a regenerating decline's carry is tightest on the arc, and a rise's
    slackest: judged by the arc elements' ends alone, a 400 m convex curve on a loaded
    decline was told 435 m where its entry tension (206.4 kN) needs 435.8 m."""
    pts = np.concatenate(([curve.carry[0] - 1], curve.carry))
    return np.where(pts < 0, pts + loop.n, pts)


def steady_checks(conv, loop: Loop, T: np.ndarray, sf_min: float,
                  T_start: np.ndarray | None = None,
                  T_rest: np.ndarray | None = None) -> tuple[dict, list[str]]:
    """Per curve k: ``curve{k}_*`` fields and warnings (concave: lift-off running and at
    start-up; convex: radius).

    Parameters
    ----------
    conv : Conveyor
    loop : Loop
    T : ndarray
        Steady boundary tensions, ``T[j]`` at the end of element j [N]; a concave curve is
        judged at the points of its arc, each by the tension there (:func:`liftoff_limits_n`).
    sf_min : float
        Minimum running belt safety factor [-] (the convex edge limit, rating / S_min).
    T_start : ndarray, optional
        Start-up boundary tensions [N] (:func:`beltstudy.engine.statics.startup_tensions`):
        a concave curve's lift-off at start-up (:func:`_start_liftoff`); None leaves its
        fields null.
    T_rest : ndarray, optional
        Tensions held at rest [N] (:func:`beltstudy.engine.statics.rest_tensions`): a
        concave curve where the stopped belt lifts is warned of (:func:`_rest_liftoff`).
    """
    out: dict = {}
    warnings: list[str] = []
    belt = loop.belt
    ic = conv.idlers.carry
    for c in loop.curves:
        k = c.k
        el, lim = liftoff_limits_n(loop, c)
        carry_pts = _carry_points(loop, c)
        t_carry = float(T[carry_pts].max())
        out[f"curve{k}_kind"] = c.kind
        out[f"curve{k}_at_m"] = c.at_m
        # the tension the verdict is judged at: the carry's on a convex curve (its edge strain
        # and idler load), either strand's on a concave one (the empty return runs through
        # the same valley and lifts first where it is the tighter, e.g. a regenerating decline)
        out[f"curve{k}_tension_kn"] = (float(T[el].max()) if c.concave else t_carry) / 1e3
        out[f"curve{k}_idler_load_extra_n"] = (t_carry * conv.idler_spacing_m("carry")
                                                / c.radius_m)
        if c.concave:
            over = T[el] - lim
            j = int(np.argmax(over))
            lifts = bool(over[j] > 0.0)
            r_need = float(np.max(T[el] * c.radius_m / lim))  # T / (m'_G g cos a)
            out[f"curve{k}_liftoff_tension_kn"] = float(lim.min()) / 1e3
            out[f"curve{k}_liftoff"] = lifts
            out[f"curve{k}_radius_min_m"] = r_need
            started, start_words = _start_liftoff(c, loop, el, lim, T, T_start, lifts)
            out.update(started)
            warnings += start_words
            rested, rest_words = _rest_liftoff(c, loop, el, lim, T_rest, lifts)
            out.update(rested)
            warnings += rest_words
            if lifts:
                strand = "carry" if loop.strand[el[j]] == CARRY else "return"
                r_start = started[f"curve{k}_radius_min_start_m"]
                at_start = (f", and at start-up ({started[f'curve{k}_tension_start_kn']:.1f} "
                            f"kN there) at least {math.ceil(r_start):.0f} m"
                            if r_start is not None and r_start > r_need else "")
                # held at rest the tension can be higher still (no resistance holds it down):
                # a 5 km route told 455 m for its start lifted at rest on 455 m, and 469 m held
                r_rest = rested[f"curve{k}_radius_min_rest_m"]
                at_rest = (f", and held at rest ({rested[f'curve{k}_tension_rest_kn']:.1f} kN "
                           f"there, an estimate) at least {math.ceil(r_rest):.0f} m"
                           if r_rest is not None and r_rest > max(r_need, r_start or 0.0)
                           else "")
                warnings.append(
                    f"curve {k} (concave, R {c.radius_m:g} m at {c.at_m:.0f} m): the empty belt "
                    f"lifts off its {strand} idlers, steady tension {T[el[j]] / 1e3:.1f} kN "
                    f"above the lift-off tension {lim[j] / 1e3:.1f} kN (R m'_G g cos a); a "
                    f"radius of at least {math.ceil(r_need):.0f} m keeps it on them at these "
                    f"tensions{at_start}{at_rest} (a larger radius lengthens the curve and moves "
                    "them a little: rerun to confirm)")
        else:
            out[f"curve{k}_liftoff_tension_kn"] = None
            out[f"curve{k}_liftoff"] = False
            out[f"curve{k}_tension_start_kn"] = None
            out[f"curve{k}_liftoff_start"] = False
            out[f"curve{k}_radius_min_start_m"] = None
            out[f"curve{k}_tension_rest_kn"] = None
            out[f"curve{k}_liftoff_rest"] = False
            out[f"curve{k}_radius_min_rest_m"] = None
            warnings += convex_idler_warnings(conv, loop, c, t_carry)
            # the edge strain is largest at the arc's highest tension, the centre's relief
            # at its lowest: the radius meets both
            t_low = float(T[carry_pts].min())
            r_min = _convex_radius_over(belt, ic, sf_min, t_carry, t_low)
            out[f"curve{k}_radius_min_m"] = r_min if r_min is None or math.isfinite(r_min) \
                else None
            if r_min is not None and c.radius_m < r_min:
                warnings.append(_convex_words(k, c, belt, ic, sf_min, t_low, t_carry, r_min))
    return out, warnings


def transient_liftoff(loop: Loop, segs, t_start_end_s: float, t_stop_cmd_s: float,
                      start_time_s: float, steady_n: np.ndarray,
                      softer_start: str | None = None,
                      softer_stop: str = "a softer stop (stop time, brake force)",
                      survey: list[dict] | tuple = (), t_start_cmd_s: float = 0.0,
                      t_rested_s: float | None = None) -> tuple[dict, list[str]]:
    """Lift-off at concave curves during the cycle: ``liftoff_*`` fields and one warning per
    phase in which the belt leaves its idlers.

    Parameters
    ----------
    loop : Loop
        The loop the transient ran on (its springs are the loop's element ends).
    segs : list
        The kernel's envelope segments ``(t0, t1, t_max, t_max_t, t_min, t_min_t)``
        (``TransientResult.raw["segments"]``): per spring the highest tension of every time
        step within the segment and its time.
    t_start_end_s, t_stop_cmd_s : float
        End of the start (the rest before it and the start reference) and the stop command
        [s]: a peak up to the first is in the start, up to the second in steady running,
        later in the stop.
    start_time_s : float
        The scenario's start time [s] (the remedy's rigid-body estimate).
    steady_n : ndarray
        Steady running tensions per spring [N].
    softer_start : str, optional
        What softens a start that does not read ``start.time_s`` (dol drives: their
        couplings), offered instead of a longer start; None: the start follows its time.
    softer_stop : str, optional
        What softens this run's stop (by its stop mode:
        :func:`beltstudy.engine.dynamics.simulate.stop_levers`).
    survey : list of dict, optional
        The concave grade changes given as survey points (no ``curve_radius_m``), each with
        its springs and their lift-off tensions (:func:`survey_liftoff_limits_n`): judged as
        the curves are, neighbouring ones as one bend.
    t_start_cmd_s : float, optional
        The start command [s]: ``liftoff_over_start_kn`` is of the segments from it to the
        stop command (SPEC 6.4's start phase; the kernel cuts a segment there), the rest
        before it counting in the whole cycle's figure only.
    t_rested_s : float, optional
        When the belt came to rest in its stop [s] (None: it did not). A peak before the start
        command or after this is the belt at rest: said as lift-off at rest, whose levers are
        the radius and the tension at rest, not the start or the stop (a 6 km overland's
        empty belt lifted at its concave curve at t = 0.1 s, 22.7 kN over, and was told a
        start of 266 s, then 616 s, avoids it).

    Returns
    -------
    dict, list of str
        ``liftoff_max_kn_over``: the largest T - R m'_G g cos(a) over the springs on the
        concave curves' arcs (:func:`liftoff_limits_n`) and the concave survey grade
        changes' springs (both strands) and the cycle [kN],
        negative when the belt stays on its idlers (the margin left), null without either;
        ``liftoff_over_start_kn`` / ``liftoff_over_stop_kn`` the same from the start command
        to the stop command and after it (null for a phase no envelope covers);
        ``liftoff_at_m`` / ``liftoff_time_s``
        where (loop position of the spring, as ``t_max_dyn_at_m``) and when, null when it
        never lifts. Exact: the envelopes hold every step's tension and the limit is fixed
        per element, so max(T - T_lift) = max(T) - T_lift element by element.

    Notes
    -----
    Per phase, each element's peak in each segment is put in the phase its time falls in (a
    segment spans the start and running; a lower excess of an element in one phase behind
    its higher one in another is not seen, so a phase may be under-reported, never the
    whole cycle's maximum); steady running is also judged at the steady tensions, which a
    start's higher peak in the same segment cannot hide. The remedy for a start: the start's
    extra tension at the curve over the steady one scales with the acceleration (rigid body,
    ~ 1 / start time), so a start time of ``start_time_s x (T_peak - T_steady) / (T_lift -
    T_steady)`` keeps the belt down when the steady tension is below the limit; a softer stop
    for a stop likewise. The radius named is ``R max(T / T_lift)`` over the curve's elements,
    in the phase and in steady running alike (the limit grows with R). Where running lifts the
    belt at its steady tension, neither a start nor a stop alone avoids it: the radius, or
    less tension there.
    """
    concave = [c for c in loop.curves if c.concave]
    none = {"liftoff_max_kn_over": None, "liftoff_at_m": None, "liftoff_time_s": None,
            "liftoff_over_start_kn": None, "liftoff_over_stop_kn": None}
    bends = _survey_bends(survey)
    if not (concave or bends) or not segs:
        return none, []
    els, lims, ks = [], [], []
    for c in concave:
        el, lim = liftoff_limits_n(loop, c)
        els.append(el)
        lims.append(lim)
        ks += [c.k] * len(el)
    for b in bends:  # after the curves, keyed below zero (curves are 1, 2, ...)
        els.append(b["el"])
        lims.append(b["lim"])
        ks += [b["k"]] * len(b["el"])
    el, lim, ks = np.concatenate(els), np.concatenate(lims), np.asarray(ks)
    radius = np.concatenate([np.full(len(e), np.nan) for e in els[:len(concave)]]
                            + [b["r"] for b in bends]) if bends else None
    hi_all = np.array([s[2] for s in segs])
    hi_t_all = np.array([s[3] for s in segs])
    hi, hi_t = hi_all[:, el], hi_t_all[:, el]
    over = np.where(np.isfinite(hi), hi - lim, -np.inf)
    kseg, j = np.unravel_index(int(np.argmax(over)), over.shape)
    worst = float(over[kseg, j])
    s_end = loop.s_end_m
    out = dict(none, liftoff_max_kn_over=worst / 1e3)
    # per phase, split at the stop command as the segments are (exact): the largest excess of
    # one phase may lie under the other's on one mesh and pass it on a finer one
    before = hi_t <= t_stop_cmd_s
    # the start phase from the start command (SPEC 6.4): the segments that begin there
    started = np.array([s[0] >= t_start_cmd_s for s in segs])[:, None]
    for key, mask in (("liftoff_over_start_kn", before & started),
                      ("liftoff_over_stop_kn", ~before)):
        part = over[mask & np.isfinite(over)]
        out[key] = float(part.max()) / 1e3 if part.size else None
    if worst > 0.0:
        out["liftoff_at_m"] = float(s_end[el[j]])
        out["liftoff_time_s"] = float(hi_t[kseg, j])
    phase = np.where(hi_t <= t_start_end_s, 0, np.where(hi_t <= t_stop_cmd_s, 1, 2))
    # the belt at rest: before the start command, and once it rested in its stop
    at_rest = hi_t < t_start_cmd_s - 1e-9
    if t_rested_s is not None and t_rested_s >= 0.0:
        at_rest |= hi_t >= t_rested_s
    # a later peak no higher than the rest's before the start command is that rest state (the
    # start's segment holds it from its first step: a peak at t = 2.0 s, the start command,
    # before the start's front reached the curve)
    pre = np.array([s[0] < t_start_cmd_s - 1e-9 for s in segs])  # the kernel cuts there
    if pre.any() and t_start_cmd_s > 0.0:
        rest_hi = np.where(np.isfinite(hi[pre]), hi[pre], -np.inf).max(axis=0)
        at_rest |= np.isfinite(hi) & (hi <= rest_hi + 1e-4 * np.abs(lim))
    phase = np.where(at_rest, 3, phase)
    steady_over = steady_n[el] - lim  # what running lifts at its steady tension
    # every spring's phase alike (the radius told is judged over the arc it gives, which a
    # larger radius reaches beyond this arc's springs: _liftoff_radius)
    phase_all = np.where(hi_t_all <= t_start_end_s, 0,
                         np.where(hi_t_all <= t_stop_cmd_s, 1, 2))
    rest_all = hi_t_all < t_start_cmd_s - 1e-9
    if t_rested_s is not None and t_rested_s >= 0.0:
        rest_all |= hi_t_all >= t_rested_s
    if pre.any() and t_start_cmd_s > 0.0:
        rest_hi_all = np.where(np.isfinite(hi_all[pre]), hi_all[pre], -np.inf).max(axis=0)
        rest_all |= np.isfinite(hi_all) & (hi_all <= rest_hi_all + 1e-4 * np.abs(hi_all))
    phase_all = np.where(rest_all, 3, phase_all)
    warnings = []
    curves = {c.k: c for c in concave}
    curves.update({b["k"]: b for b in bends})
    for p, name in enumerate(("the start", "steady running", "the stop", "rest")):
        masked = np.where(phase == p, over, -np.inf)
        kseg, j = np.unravel_index(int(np.argmax(masked)), masked.shape)
        at_steady = p == 1 and steady_over.max() > max(masked[kseg, j], 0.0)
        if at_steady:  # a segment's peak that fell in the start hides running's own
            j = int(np.argmax(steady_over))
        elif not masked[kseg, j] > 0.0:
            continue
        c = curves[int(ks[j])]
        k_c = int(ks[j])
        on_c = ks == k_c
        e = int(el[j])
        t_lim = float(lim[j])
        t_peak = float(steady_n[e]) if at_steady else float(hi[kseg, j])
        strand = "carry" if loop.strand[e] == CARRY else "return"
        # the radius that keeps the whole curve down in this phase and while running (the
        # limit grows with R: R max T / T_lift over the curve's elements; a survey bend's
        # points have their own radii, R T / T_lift = T / (m'_G g cos a) each)
        scale = 1.0 if k_c > 0 else radius[on_c]
        ratio = float((scale * steady_n[el][on_c] / lim[on_c]).max())
        if not at_steady:
            ratio = max(ratio, float((scale * np.where(phase == p, hi, -np.inf)[:, on_c]
                                      / lim[on_c]).max()))
        peaks = steady_n if at_steady else np.maximum(
            steady_n, np.where(phase_all == p, hi_all, -np.inf).max(axis=0))
        r_told = _liftoff_radius(loop, c, k_c, peaks,
                                 c.radius_m * ratio if k_c > 0 else ratio)
        if k_c > 0:
            fixes = [f"a curve radius of at least {math.ceil(r_told):.0f} m (at "
                     "this run's tensions over the arc it gives, which a larger radius moves a "
                     "little: rerun to confirm)"]
        else:
            fixes = [f"a vertical curve of at least {math.ceil(r_told):.0f} m there "
                     "(curve_radius_m on the section before the grade change, or survey "
                     "points on that radius; at this run's tensions over the arc it gives, "
                     "which a larger radius moves a little: rerun to confirm)"]
        runs_over = bool((steady_over[on_c] > 0.0).any())  # running lifts there as it is
        t_run = float(steady_n[e])
        if p == 0 and not runs_over and softer_start is not None:
            fixes.insert(0, softer_start)
        elif p == 0 and not runs_over and t_run < t_lim:
            # every element of the curve that lifts in the start needs its own: the one with
            # the least room below its limit in running may not be the one lifted most
            peak = np.where(phase == p, hi, -np.inf)[:, on_c].max(axis=0)
            run_c, lim_c = steady_n[el][on_c], lim[on_c]
            lifts = peak > lim_c
            need = (peak[lifts] - run_c[lifts]) / (lim_c[lifts] - run_c[lifts])
            i_need = int(np.argmax(need))
            t_need = start_time_s * float(need[i_need])
            room = float(lim_c[lifts][i_need] - run_c[lifts][i_need])
            fixes.insert(0, f"a start of about {t_need:.0f} s (start.time_s; rigid-body "
                            f"estimate: running leaves {gnum(room / 1e3)} kN below the lift-off "
                            f"tension {gnum(lim_c[lifts][i_need] / 1e3)} kN there, "
                            f"{gnum(100.0 * room / lim_c[lifts][i_need], 3)} %)")
        elif p == 2 and not runs_over:
            fixes.insert(0, softer_stop)
        elif p == 3:
            # held at rest no start or stop acts: the radius or the tension at rest
            fixes.append("less tension there at rest (a lighter take-up, where its slip "
                         "checks allow; no start or stop time changes the tension at rest)")
        elif runs_over:
            fixes.append("less tension there in running (a lighter take-up, the curve nearer "
                         "the slack side)")
        when = ("at its steady running tension" if at_steady
                else f"at t = {hi_t[kseg, j]:.1f} s")
        where = (f"curve {c.k} (concave, R {c.radius_m:g} m" if k_c > 0 else
                 _survey_where(c, float(radius[j])))
        warnings.append(
            f"lift-off {'at' if p == 3 else 'in'} {name}: the empty belt leaves its "
            f"{strand} idlers at {where}, "
            f"at {s_end[e]:.0f} m round the loop) {when}, "
            f"{(t_peak - t_lim) / 1e3:.1f} kN over its lift-off "
            f"tension {t_lim / 1e3:.1f} kN (R m'_G g cos a, the belt's own weight: a stretch "
            "carrying material holds more); " + " or ".join(fixes) + " avoids it")
    return out, warnings


def _liftoff_radius(loop: Loop, c, k: int, peaks_n: np.ndarray, radius_m: float) -> float:
    """The radius a concave curve (``k`` > 0, a :class:`Curve`) or survey bend (``k`` < 0,
    :func:`_survey_bends`) needs to keep the empty belt down at the peak tensions ``peaks_n``
    [N] (per spring, a phase's with running's), judged over the arc that radius gives: from
    ``radius_m``, the radius the present arc's own points need, to the fixed point of ``R =
    max T / (m'_G g cos a)`` over the span ``R |delta|`` about the curve's junction, on either
    strand (:func:`_radius_over_own_arc`; ``cos a`` of the steeper grade, the tension at the
    span's ends read along the strand). A larger radius reaches further up a loaded grade: a
    coast stop's 538 m curve was told 710 m from its own arc's peaks, and lifted at 710 m,
    0.7 kN over, on the same mesh."""
    if k > 0:
        turn, at_m = c.delta_rad, c.at_m
        cos_a = min(math.cos(c.angle_in_rad), math.cos(c.angle_in_rad + c.delta_rad))
        m_g = float(loop.mG_kg_m[c.carry[0]])
    else:
        turn = sum(jn["turn"] for jn in c["changes"])
        at_m = 0.5 * (c["changes"][0]["at_m"] + c["changes"][-1]["at_m"])
        cos_a = min(jn["cos"] for jn in c["changes"])
        m_g = float(loop.mG_kg_m[int(c["el"][0])])
    w = m_g * G * cos_a

    def need(lo_m: float, hi_m: float) -> float:
        return max(hi for _s, hi, _lo in _span_tensions(loop, peaks_n, lo_m, hi_m)) / w

    return _radius_over_own_arc(need, radius_m, turn, at_m)


# ------------------------------------------------- grade changes without a vertical curve
__all__ += ["survey_radius_m", "junction_checks"]


def survey_radius_m(length_in_m: float, length_out_m: float, turn_rad: float) -> float:
    """Radius of the circle through a grade change's three survey points [m].

    A route given by survey points (short sections, no ``curve_radius_m``) describes its
    vertical curves by the points themselves: the circle through a point and its two
    neighbours, ``R = |AC| / (2 sin |delta|)`` with ``|AC|^2 = l_1^2 + l_2^2 + 2 l_1 l_2
    cos(delta)`` (the circumradius of the triangle whose angle at the middle point is
    ``pi - |delta|``). Points spaced ``l`` on a curve of radius R give back R exactly
    (``l = 2 R sin(delta / 2)``); an isolated kink between long sections reads as the gentle
    curve those sections leave room for.

    Parameters
    ----------
    length_in_m, length_out_m : float
        The two sections' lengths along the belt, l_1 and l_2 [m].
    turn_rad : float
        The change of grade angle delta [rad] (either sign); 0 gives ``inf``.
    """
    s = math.sin(abs(turn_rad))
    if s <= 0.0:
        return math.inf
    chord = math.sqrt(length_in_m ** 2 + length_out_m ** 2
                      + 2.0 * length_in_m * length_out_m * math.cos(turn_rad))
    return chord / (2.0 * s)


def _strand_points(loop: Loop, T: np.ndarray):
    """Per strand with idler elements: (name, route position [m], tension [N]) of each idler
    element's two ends (``T[j - 1]`` at its start, ``T[j]`` at its end)."""
    x0 = loop.x_m if loop.x_m is not None else loop.s_m
    for code, name, sign in ((CARRY, "carry", 1.0), (RETURN, "return", -1.0)):
        j = np.flatnonzero(loop.strand == code)
        if j.size:
            yield (name, np.concatenate((x0[j], x0[j] + sign * loop.dx_m[j])),
                   np.concatenate((T[j - 1], T[j])))


def _node_tensions(loop: Loop, T: np.ndarray, x_m: float) -> list[tuple[str, float]]:
    """(strand, tension [N]) at the idler element ends nearest route position x_m, per strand
    (the sections meet at an element end; a pulley there has idler elements either side)."""
    out = []
    for name, pos, ten in _strand_points(loop, T):
        gap = np.abs(pos - x_m)
        near = gap <= gap.min() + 1e-6 * max(1.0, loop.length_m)
        out.append((name, float(ten[near].max())))
    return out


def _span_tensions(loop: Loop, T: np.ndarray, lo_m: float, hi_m: float
                   ) -> list[tuple[str, float, float]]:
    """(strand, highest, lowest tension [N]) between route positions lo_m and hi_m, per
    strand: at the idler element ends within, the ends nearest the span's middle always among
    them (:func:`_node_tensions` where the span is a point), and at the span's two ends,
    interpolated along the strand (the tension is linear along an element)."""
    tol = 1e-6 * max(1.0, loop.length_m)
    mid = 0.5 * (lo_m + hi_m)
    out = []
    for name, pos, ten in _strand_points(loop, T):
        gap = np.abs(pos - mid)
        inside = (gap <= gap.min() + tol) | ((pos >= lo_m - tol) & (pos <= hi_m + tol))
        order = np.argsort(pos, kind="stable")
        ends = [float(np.interp(x, pos[order], ten[order])) for x in (lo_m, hi_m)
                if pos.min() <= x <= pos.max()]
        found = np.concatenate((ten[inside], ends))
        out.append((name, float(found.max()), float(found.min())))
    return out


def _radius_over_own_arc(need, radius_m: float, turn_rad: float, at_m: float) -> float:
    """The radius a vertical curve at a grade change at ``at_m`` needs, judged over the arc it
    gives itself: ``need(lo_m, hi_m)`` is the radius the tensions between two route positions
    need [m]; the arc of radius R is about ``R |turn|`` long about the change, so a larger
    radius reaches tensions further along (on a loaded incline, higher towards the head).
    Solved from the radius ``radius_m`` the change's own point needs, by fixed point, up to
    0.01 % (the radius grows at each round; at most 50 rounds)."""
    r = radius_m
    for _ in range(50):
        half = 0.5 * r * abs(turn_rad)
        r_next = need(at_m - half, at_m + half)
        if not math.isfinite(r_next) or r_next <= r * (1.0 + 1e-4):
            return max(r, r_next) if math.isfinite(r_next) else r_next
        r = r_next
    return r


def _junctions(conv) -> list[dict]:
    """Each grade change without ``curve_radius_m``: section, where, turn and survey radius.

    Sections on one grade (no turn, no curve between them) are one straight run: the survey
    circle goes through the ends of the straight runs either side (:func:`survey_radius_m`),
    so a straight written as one section or as many points is read alike. A curve whose arc
    is shorter than an idler pitch is such a change (:meth:`Conveyor.judged_profile`)."""
    prof = conv.judged_profile()
    angles = [math.asin(p.lift_m / p.length_m) for p in prof]
    runs: list[list[float]] = [[0.0, 0.0]]  # per straight run: [length, end position]
    breaks = []  # (section i, turn) at each end of a run that is a grade change without curve
    for i, p in enumerate(prof):
        runs[-1][0] += p.length_m
        runs[-1][1] += p.length_m
        if i == len(prof) - 1:
            break
        turn = angles[i + 1] - angles[i]
        if p.curve_radius_m is None and abs(turn) < 1e-12:
            continue
        breaks.append((i, turn if p.curve_radius_m is None else None))
        runs.append([0.0, runs[-1][1]])
    out = []
    for r, (i, turn) in enumerate(breaks):
        if turn is None:
            continue
        out.append({"i": i, "run": r, "at_m": runs[r][1], "turn": turn,
                    "cos": min(math.cos(angles[i]), math.cos(angles[i + 1])),
                    "radius_m": survey_radius_m(runs[r][0], runs[r + 1][0], turn)})
    return out


def _judge_junction(conv, loop: Loop, jn: dict, T: np.ndarray, T_start, sf_min: float
                    ) -> dict | None:
    """A grade change judged as its survey circle: None when it passes, else the figures."""
    belt, ic = loop.belt, conv.idlers.carry
    if jn["turn"] > 0.0:  # concave: the empty belt lifts first, on either strand
        w = float(loop.mG_kg_m[0]) * G * jn["cos"]
        nodes = _node_tensions(loop, T, jn["at_m"])
        starts = [] if T_start is None else _node_tensions(loop, T_start, jn["at_m"])
        strand, t_run = max(nodes, key=lambda n: n[1])
        t_start = max((t for _s, t in starts), default=0.0)
        need = max(t_run, t_start) / w
        if need <= jn["radius_m"]:
            return None

        return {**jn, "kind": "concave", "strand": strand, "t_n": t_run, "t_start_n": t_start,
                "limit_n": jn["radius_m"] * w, "need_m": need, "need_run_m": t_run / w,
                "at_start": t_run <= jn["radius_m"] * w}
    t_carry = max(t for s, t in _node_tensions(loop, T, jn["at_m"]) if s == "carry")
    need = convex_radius_min_m(t_carry, belt.stiffness_n, belt.rating_n / sf_min,
                               belt.width_m, ic.rolls, ic.trough_deg, ic.roll_length_m)
    if need is None or need <= jn["radius_m"]:
        return None
    return {**jn, "kind": "convex", "strand": "carry", "t_n": t_carry, "need_m": need}


def _bend_advice(conv, loop: Loop, bend: list[dict], worst: dict, T: np.ndarray, T_start,
                 sf_min: float) -> dict:
    """The radius a vertical curve replacing a bend of survey points needs (``need_m``, and
    for a concave bend ``need_run_m`` at the running tensions alone), judged over the arc it
    gives itself (:func:`_radius_over_own_arc`): the bend's whole turn (its grade changes of
    one kind in a row) about its middle, from the radius its worst point needs. A curve of
    that radius, or survey points on it, reaches further up a loaded grade than the points
    did: a 3 km route's five points on R 250 m were told 530 m from the tension at the worst
    point, and a curve of 530 m lifted at start-up (144.0 kN against 142.0 kN)."""
    turn = sum(jn["turn"] for jn in bend)
    at_m = 0.5 * (bend[0]["at_m"] + bend[-1]["at_m"])
    if worst["kind"] == "concave":
        w = float(loop.mG_kg_m[0]) * G * min(jn["cos"] for jn in bend)

        def run_need(lo_m, hi_m):
            return max(hi for _s, hi, _lo in _span_tensions(loop, T, lo_m, hi_m)) / w

        def all_need(lo_m, hi_m):
            spans = [] if T_start is None else _span_tensions(loop, T_start, lo_m, hi_m)
            return max([run_need(lo_m, hi_m)] + [hi / w for _s, hi, _lo in spans])

        return {"need_m": _radius_over_own_arc(all_need, worst["need_m"], turn, at_m),
                "need_run_m": _radius_over_own_arc(run_need, worst["need_run_m"], turn, at_m)}
    belt, ic = loop.belt, conv.idlers.carry

    def carry_need(lo_m, hi_m):
        ((_s, hi, lo),) = [n for n in _span_tensions(loop, T, lo_m, hi_m) if n[0] == "carry"]
        r_min = _convex_radius_over(belt, ic, sf_min, hi, lo)
        return math.inf if r_min is None else r_min

    return {"need_m": _radius_over_own_arc(carry_need, worst["need_m"], turn, at_m)}


def _junction_words(group: list[dict]) -> str:
    """One warning for a run of neighbouring grade changes of one kind that fail."""
    worst = max(group, key=lambda g: g["need_m"] / g["radius_m"])
    first, last = group[0], group[-1]
    where = (f"at {first['at_m']:.0f} m (profile[{first['i']}] to profile[{first['i'] + 1}]"
             if len(group) == 1 else
             f"from {first['at_m']:.0f} to {last['at_m']:.0f} m ({len(group)} of them, "
             f"profile[{first['i']}] to profile[{last['i'] + 1}]; the tightest at "
             f"{worst['at_m']:.0f} m")
    head = (f"grade change without a vertical curve {where}, {worst['kind']}, the grade "
            f"turning by {gnum(math.degrees(abs(worst['turn'])), 3)} deg): read as the circle through "
            f"the survey points there, radius {worst['radius_m']:.0f} m, ")
    need = ("a lower tension there (no radius keeps the edge within it)"
            if not math.isfinite(worst["need_m"]) else
            f"the route there needs a vertical curve of at least {math.ceil(worst['need_m']):.0f}"
            " m (give it as curve_radius_m on the section before the grade change, or "
            "survey points on that radius)")
    if worst["kind"] == "convex":
        return (head + f"the troughed belt's edge strain or centre tension is out of bounds at "
                f"{worst['t_n'] / 1e3:.1f} kN: " + need)
    if worst["at_start"]:
        return (head + f"at start-up the empty belt lifts off its idlers, start-up tension "
                f"{worst['t_start_n'] / 1e3:.1f} kN (a rigid-body estimate) above the lift-off "
                f"tension {worst['limit_n'] / 1e3:.1f} kN (R m'_G g cos a), though running stays "
                f"down ({worst['t_n'] / 1e3:.1f} kN); " + need + ", or a gentler start")
    start = (f" ({math.ceil(worst['need_run_m']):.0f} m at the running tensions, the rest "
             f"for the start-up tension {worst['t_start_n'] / 1e3:.1f} kN)"
             if worst["need_m"] > worst["need_run_m"] else "")
    return (head + f"the empty belt lifts off its {worst['strand']} idlers, steady tension "
            f"{worst['t_n'] / 1e3:.1f} kN above the lift-off tension "
            f"{worst['limit_n'] / 1e3:.1f} kN (R m'_G g cos a); " + need + start)


def junction_checks(conv, loop: Loop, T: np.ndarray, sf_min: float,
                    T_start: np.ndarray | None = None) -> list[str]:
    """Grade changes between profile sections that give no ``curve_radius_m``.

    Such a change is read as the circle through its survey points (:func:`survey_radius_m`),
    so a route written as survey points along a curve gets the verdicts of the same route
    with ``curve_radius_m``: a concave change is judged for lift-off of the empty belt on
    either strand, running and at start-up (``T > R m'_G g cos a``, ``cos a`` of the steeper
    grade), a convex one for the troughed belt's edge strain (:func:`convex_radius_min_m`),
    at the tension where the sections meet. The tension walk keeps the sections' straight
    grades (no elements on an arc), and there are no result columns: a warning names the
    change (where, which sections, its turn and survey radius), the tension against its
    limit and the radius the route needs there. Neighbouring changes of one kind that fail
    are one warning, naming the tightest.

    Returns
    -------
    list of str
        The warnings, in route order.
    """
    junctions = _junctions(conv)
    fails = [f for jn in junctions
             if (f := _judge_junction(conv, loop, jn, T, T_start, sf_min)) is not None]
    groups: list[list[dict]] = []
    for f in fails:
        if (groups and groups[-1][-1]["run"] == f["run"] - 1
                and groups[-1][-1]["kind"] == f["kind"]):
            groups[-1].append(f)
        else:
            groups.append([f])
    # the bends: grade changes of one kind in a row (a curve given as survey points)
    bends: list[list[dict]] = []
    for jn in junctions:
        if (bends and bends[-1][-1]["run"] == jn["run"] - 1
                and (bends[-1][-1]["turn"] > 0.0) == (jn["turn"] > 0.0)):
            bends[-1].append(jn)
        else:
            bends.append([jn])
    out = []
    for g in groups:
        worst = max(g, key=lambda f: f["need_m"] / f["radius_m"])
        (bend,) = [b for b in bends if any(jn["run"] == worst["run"] for jn in b)]
        if math.isfinite(worst["need_m"]):
            worst.update(_bend_advice(conv, loop, bend, worst, T, T_start, sf_min))
        out.append(_junction_words(g))
    return out


# ------------------------------------------------- survey grade changes in the transient
__all__ += ["survey_liftoff_limits_n"]


def _junction_springs(loop: Loop, x_m: float) -> np.ndarray:
    """The springs at route position x_m on both strands (carry then return): the end of
    each idler element that ends there and the one before each that starts there (one
    spring where idler elements meet, both sides of a pulley standing there)."""
    x0 = loop.x_m if loop.x_m is not None else loop.s_m
    tol = 1e-6 * max(1.0, loop.length_m)
    out: list[int] = []
    for code, sign in ((CARRY, 1.0), (RETURN, -1.0)):
        j = np.flatnonzero(loop.strand == code)
        ends = j[np.abs(x0[j] + sign * loop.dx_m[j] - x_m) <= tol]
        starts = j[np.abs(x0[j] - x_m) <= tol] - 1
        out += sorted(set(ends.tolist()) | set(starts.tolist()))
    return np.asarray(out, dtype=np.int64)


def survey_liftoff_limits_n(conv, loop: Loop) -> list[dict]:
    """The concave grade changes given as survey points (no ``curve_radius_m``), for the
    transient lift-off check (:func:`transient_liftoff`).

    Each is read as the circle through its survey points (:func:`survey_radius_m`, as the
    steady :func:`junction_checks` reads it); the belt bends where the sections meet, so its
    springs there, on both strands, get the empty belt's lift-off tension
    ``R m'_G g cos a`` (``a`` the steeper grade). A valley written as survey points along an
    arc has a spring at every point, as the arc given with ``curve_radius_m`` has elements
    along it; the springs between points (a section cut into several elements) lie on a
    straight chord and get none. A straight, in one section or many, has no grade change.
    A change whose lift-off tension at every spring is above the belt's breaking force
    (``rating_kn_m`` x width) is left out: no tension the belt can carry lifts it there (a
    kink between long straight sections reads as a circle of tens of kilometres, with a
    lift-off tension of tens of meganewtons, which would only fill the output).

    Returns
    -------
    list of dict
        Per concave change in route order: ``i`` (profile[i] to profile[i + 1]), ``run``
        (its straight run's number: neighbours are one apart), ``at_m``, ``turn``,
        ``radius_m``, ``el`` (springs) and ``lim`` (their lift-off tensions [N]).
    """
    out = []
    for jn in _junctions(conv):
        if jn["turn"] <= 0.0:
            continue
        el = _junction_springs(loop, jn["at_m"])
        if el.size == 0:
            continue
        lim = jn["radius_m"] * loop.mG_kg_m[el] * G * jn["cos"]
        if loop.belt.rating_n > 0.0 and bool(np.all(lim > loop.belt.rating_n)):
            continue
        out.append({**jn, "el": el, "lim": lim})
    return out


def _survey_bends(survey) -> list[dict]:
    """Neighbouring concave survey changes as one bend (the tightest named), keyed -1, -2,
    ... in route order: springs, lift-off tensions and each spring's survey radius."""
    groups: list[list[dict]] = []
    for jn in survey:
        if groups and groups[-1][-1]["run"] == jn["run"] - 1:
            groups[-1].append(jn)
        else:
            groups.append([jn])
    return [{"k": -(n + 1), "changes": g,
             "el": np.concatenate([jn["el"] for jn in g]),
             "lim": np.concatenate([jn["lim"] for jn in g]),
             "r": np.concatenate([np.full(len(jn["el"]), jn["radius_m"]) for jn in g])}
            for n, g in enumerate(groups)]


def _survey_where(bend: dict, radius_m: float) -> str:
    """Where a survey bend is, for a lift-off warning (the text before ', at ... round the
    loop)')."""
    g = bend["changes"]
    first, last = g[0], g[-1]
    span = (f"at {first['at_m']:.0f} m (profile[{first['i']}] to profile[{first['i'] + 1}]"
            if len(g) == 1 else
            f"from {first['at_m']:.0f} to {last['at_m']:.0f} m ({len(g)} of them, "
            f"profile[{first['i']}] to profile[{last['i'] + 1}]")
    return (f"the grade change without a vertical curve {span}, concave, read as the circle "
            f"through the survey points there, radius {radius_m:.0f} m")
