"""Horizontal curves as a statics check (SPEC 7.1, 7.4; docs/routes.md).

A profile section with ``horizontal_radius_m`` R is a horizontal curve of the carry strand,
its idler sets tilted by ``superelevation_deg`` beta (raised on the inside of the curve).
The belt's tension T pulls it towards the inside of the curve with T / R per metre; the
weight of the belt and its load on the troughed, tilted sets pushes it back towards the
outside. The belt drifts sideways until the two balance; this check asks whether it finds
that balance before an edge leaves its wing roll:

* too much tension and the belt runs to the inside: ``T <= T_max = R q(+d)``;
* too little tension and the loaded belt runs down the tilt to the outside:
  ``T >= T_min = R q(-d)``;

with ``q(d)`` the weight's restoring force per metre with the belt drifted by ``d`` to the
inside (the conventional method of Grimmer and Kessler, as a secondary source writes it out:
see :func:`restoring_force_n_m`) and ``d`` the drift at which the belt's edge reaches the
end of a wing roll (``l_W - b_W``). Lateral friction between belt and rolls and forward-
tilted (training) idlers are left out: the limits are on the safe side of them.

Evaluated in the run's own state: the belt with the load the run has on the curve's section
and the steady tension of that same run along the curve (the weight that holds the belt and
the tension that pulls it come from one state). Every load case is checked by running it: an
empty run (``load: empty``, or ``design``/grid load cases in a study) has a lighter belt and
lower tensions, and is where published curve designs find the belt runs to the inside first.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from beltstudy.engine.capacity import middle_roll_length_m, trough_segments
from beltstudy.engine.conveyor import HCURVE_TURN_MAX_DEG
from beltstudy.engine.loop import CARRY, G
from beltstudy.engine.wording import gnum

__all__ = ["restoring_force_n_m", "drift_limit_m", "tension_limits_n", "garland_limits_n",
           "HCurve",
           "hcurves", "hcurve_checks"]


def restoring_force_n_m(mass_kg_m: float, width_m: float, middle_m: float, trough_deg: float,
                        superelevation_deg: float, drift_m: float = 0.0,
                        cos_incline: float = 1.0) -> float:
    """Restoring force of the weight towards the outside of a horizontal curve [N/m].

    Parameters
    ----------
    mass_kg_m : float
        Belt plus load per metre m'_G + m'_L [kg/m].
    width_m : float
        Belt width B [m].
    middle_m : float
        Belt width on the middle roll b_M [m] (the middle roll's length, at most B; B for a
        flat set, 0 for a V set).
    trough_deg, superelevation_deg : float
        Trough angle lambda and superelevation (tilt) beta [deg].
    drift_m : float
        Sideways drift of the belt towards the inside of the curve d [m] (negative: outwards).
    cos_incline : float
        cos(alpha) of the section's slope [-].

    Returns
    -------
    float
        q [N/m]; positive pushes the belt towards the outside.

    Notes
    -----
    With the belt's width on the wing rolls ``b_W = (B - b_M) / 2``, on the inside wing
    ``b_i = b_W + d`` and on the outside wing ``b_o = b_W - d``::

        q = (m'_G + m'_L) g cos(alpha) [ b_i / B sin(lambda + beta) cos(lambda)
                                         + b_M / B sin(beta)
                                         - b_o / B sin(lambda - beta) cos(lambda) ]

    The weight is shared between the rolls by the belt's width on each.

    References
    ----------
    Grimmer, K.-J., Kessler, F.: Kurvengängige Gurtförderer (Teil I), conventional method,
    1987 (the inside, middle and outside weight components and their sum), as written out
    in the open-source library eytelwein (``horizontal_curves``). *Unverified* against the
    primary text; the balance T l / R against the weight force per idler pitch l is also
    the one Helix delta-T describes for its horizontal curves.
    """
    lam, beta = math.radians(trough_deg), math.radians(superelevation_deg)
    b_w = 0.5 * (width_m - middle_m)
    b_i, b_o = b_w + drift_m, b_w - drift_m
    k = (b_i * math.sin(lam + beta) * math.cos(lam) + middle_m * math.sin(beta)
         - b_o * math.sin(lam - beta) * math.cos(lam)) / width_m
    return mass_kg_m * G * cos_incline * k


def drift_limit_m(width_m: float, middle_m: float, wing_roll_m: float) -> float:
    """Sideways drift at which the belt's edge reaches the end of a wing roll [m]:
    ``l_W - b_W`` with ``b_W = (B - b_M) / 2`` (0 when the belt already overhangs)."""
    return max(wing_roll_m - 0.5 * (width_m - middle_m), 0.0)


def tension_limits_n(mass_kg_m: float, radius_m: float, width_m: float, middle_m: float,
                     wing_roll_m: float, trough_deg: float, superelevation_deg: float,
                     cos_incline: float = 1.0) -> tuple[float, float]:
    """Lowest and highest belt tension that keep the belt in a horizontal curve [N].

    ``T_min = max(R q(-d), 0)`` (below it the belt runs out of the curve),
    ``T_max = max(R q(+d), 0)`` (above it the belt runs into the curve), ``d`` the drift
    limit (:func:`drift_limit_m`), ``q`` :func:`restoring_force_n_m`.
    """
    d = drift_limit_m(width_m, middle_m, wing_roll_m)
    args = (mass_kg_m, width_m, middle_m, trough_deg, superelevation_deg)
    t_min = radius_m * restoring_force_n_m(*args, drift_m=-d, cos_incline=cos_incline)
    t_max = radius_m * restoring_force_n_m(*args, drift_m=d, cos_incline=cos_incline)
    return max(t_min, 0.0), max(t_max, 0.0)


def garland_limits_n(mass_kg_m: float, radius_m: float, width_m: float,
                     segments: list[tuple[float, float]], drift_m: float,
                     superelevation_deg: float, cos_incline: float = 1.0
                     ) -> tuple[float, float]:
    """Lowest and highest tension that keep the belt in a horizontal curve on a set of two,
    four or five rolls [N], :func:`tension_limits_n` with the belt's half width on each roll.

    ``segments`` is half the belt from its centre as ``(width on the roll [m], roll angle
    [rad])`` (:func:`beltstudy.engine.capacity.trough_segments` at the full belt width B),
    ``drift_m`` the room d the outer roll leaves beyond the belt's edge. Each roll takes the
    weight of the belt's width on it, as in :func:`restoring_force_n_m`: on the inside of the
    curve ``b sin(theta + beta) cos(theta)``, on the outside ``- b sin(theta - beta)
    cos(theta)`` (a flat roll, theta 0, gives ``b sin(beta)`` on each side, the middle roll's
    term); drifted by d to the inside, the inside outer roll carries ``b + d`` and the outside
    edge moves in by d, off the outside outer roll and, where d is more than the belt's width
    on it, off the rolls inside it. Three rolls is :func:`tension_limits_n` exactly."""
    beta = math.radians(superelevation_deg)

    def side(d: float) -> list[float]:
        """The belt's width on each roll of one side, drifted ``d`` outwards on it (the
        outer roll takes the drift; drifted inwards the edge leaves the outer roll and then
        the ones inside it: 4 rolls of 0.45 m under a 1 m belt, 0.4 m in, leave 0.1 m on
        the 17.5 deg roll and none on the 35 deg one)."""
        widths = [b for b, _ in segments]
        if d >= 0.0:
            widths[-1] += d
            return widths
        left = -d
        for j in range(len(widths) - 1, -1, -1):
            cut = min(widths[j], left)
            widths[j] -= cut
            left -= cut
        return widths

    def q(d: float) -> float:
        inside, outside = side(d), side(-d)
        k = 0.0
        for (_b, th), b_i, b_o in zip(segments, inside, outside, strict=True):
            k += (b_i * math.sin(th + beta) - b_o * math.sin(th - beta)) * math.cos(th)
        return mass_kg_m * G * cos_incline * k / width_m

    return max(radius_m * q(-drift_m), 0.0), max(radius_m * q(drift_m), 0.0)


def _garland(ic, width: float) -> tuple[list[tuple[float, float]], float, bool]:
    """Half a two-, four- or five-roll set's belt as roll segments, the drift room [m] and
    whether the roll length is the default (the rolls spanning the belt exactly: B / rolls for
    four or five, B / 2 for two)."""
    given = ic.roll_length_m is not None
    roll = float(ic.roll_length_m) if given else (
        0.5 * width if ic.rolls == 2 else middle_roll_length_m(width, ic.rolls))
    segs = trough_segments(width, ic.rolls, ic.trough_deg, roll)
    # the rolls of one side reach out (rolls - 1) / 2 roll lengths past the middle roll's half
    # (odd), rolls / 2 from the centre (even); the outer segment is the belt's width there
    reach = roll * (0.5 + (ic.rolls - 1) // 2) if ic.rolls % 2 else roll * (ic.rolls // 2)
    return segs, max(reach - 0.5 * width, 0.0), not given


def _no_room(ic, garland) -> str:
    """Words for a set whose rolls are taken to span the belt exactly (no roll length given),
    leaving no room to drift (d = 0): the band is then a single tension. "" otherwise."""
    if garland is None or not garland[2] or garland[1] > 0.0:
        return ""
    default = "B / 2" if ic.rolls == 2 else f"B / {ic.rolls}"
    return (f"; idlers.carry.roll_length_m is not given, so the {ic.rolls} rolls are taken to "
            f"span the belt exactly ({default} each), leaving it no room to drift: the "
            "rolls' own length (idlers.carry.roll_length_m) gives the band its width")


@dataclass(frozen=True)
class HCurve:
    """One horizontal curve: ``number`` (1-based, profile order), ``section`` (0-based
    profile index), where it starts and ends from the tail [m], its radius [m] and tilt
    [deg]."""

    number: int
    section: int
    start_m: float
    end_m: float
    radius_m: float
    superelevation_deg: float


def hcurves(conv) -> list[HCurve]:
    """The conveyor's horizontal curves in profile order."""
    out, s = [], 0.0
    for i, sec in enumerate(conv.profile):
        if sec.horizontal_radius_m is not None:
            out.append(HCurve(len(out) + 1, i, s, s + sec.length_m,
                              float(sec.horizontal_radius_m), float(sec.superelevation_deg)))
        s += sec.length_m
    return out


def _load_case(m_load: float, m_full: float) -> str:
    """The belt's load in words: ``m_load`` the material on it, ``m_full`` the run's load
    where it is all on [kg/m]."""
    m = float(m_load)
    return "empty" if m == 0.0 else "loaded" if m == m_full else (
        f"partly loaded ({gnum(m, 3)} kg/m of material)")


def hcurve_checks(conv, loop, T: np.ndarray) -> tuple[dict, list[str]]:
    """``hcurve{k}_*`` fields and warnings of a steady solution (empty with no curves).

    ``T`` is the steady tension at the element ends [N]; a curve's tensions are those at
    the ends of its carry elements and at its start.
    """
    curves = hcurves(conv)
    if not curves:
        return {}, []
    ic = conv.idlers.carry
    belt = loop.belt
    width = belt.width_m
    if ic.rolls <= 1:
        middle = width
    elif ic.rolls == 2:
        # a V set has no middle roll (b_M = 0): roll_length_m is the middle roll's length
        # (the capacity and convex checks read it only for three rolls or more)
        middle = 0.0
    else:
        roll = ic.roll_length_m or middle_roll_length_m(width, ic.rolls)
        middle = min(roll, width)
    wing = middle if ic.rolls >= 3 else 0.5 * width
    # two, four and five rolls: the belt's width on each roll (a V set has no middle roll, a
    # garland two rolls a side); three rolls and flat sets as before
    garland = _garland(ic, width) if ic.rolls in (2, 4, 5) else None
    carry = np.flatnonzero(loop.strand == CARRY)
    s_mid = loop.x_m[carry] + 0.5 * loop.dx_m[carry]
    out, warnings = {}, []
    for c in curves:
        idx = carry[(s_mid >= c.start_m) & (s_mid <= c.end_m)]
        before = idx[0] - 1 if idx[0] > 0 else loop.n - 1  # the tension entering the curve
        t_run = np.concatenate((T[idx], [T[before]]))
        sec = conv.profile[c.section]
        cos_a = math.sqrt(1.0 - (sec.lift_m / sec.length_m) ** 2)
        # each element against the limits of its own load (a feed point within the curve
        # changes it); the tension entering the curve goes with the first element's load
        m_el = np.concatenate((loop.mL_kg_m[idx], loop.mL_kg_m[idx[:1]]))
        m_full = float(loop.mL_kg_m[carry].max())  # the run's load where it is all on
        cache: dict[float, tuple[float, float]] = {}
        for m in np.unique(m_el):
            cache[float(m)] = (tension_limits_n(belt.mass_kg_m + float(m), c.radius_m, width,
                                                middle, wing, ic.trough_deg,
                                                c.superelevation_deg, cos_a)
                               if garland is None else
                               garland_limits_n(belt.mass_kg_m + float(m), c.radius_m, width,
                                                garland[0], garland[1],
                                                c.superelevation_deg, cos_a))
        lo = np.array([cache[float(m)][0] for m in m_el])
        hi = np.array([cache[float(m)][1] for m in m_el])
        # where each tension acts: an element's end, or the curve's start for the entry
        x_at = np.concatenate((loop.x_m[idx] + loop.dx_m[idx], [c.start_m]))
        t_lo, t_hi = float(lo.max()), float(hi.min())
        run_lo, run_hi = float(t_run.min()), float(t_run.max())
        k = c.number
        j_in, j_out = int(np.argmax(t_run - hi)), int(np.argmax(lo - t_run))
        inside, outside = t_run[j_in] > hi[j_in], t_run[j_out] < lo[j_out]
        out.update({f"hcurve{k}_tension_min_kn": t_lo / 1e3,
                    f"hcurve{k}_tension_max_kn": t_hi / 1e3,
                    f"hcurve{k}_t_low_kn": run_lo / 1e3,
                    f"hcurve{k}_t_high_kn": run_hi / 1e3,
                    f"hcurve{k}_ok": bool(not inside and not outside)})
        where = (f"horizontal curve {k} (profile.{c.section}, {c.start_m:g} to "
                 f"{c.end_m:g} m from the tail, R {c.radius_m:g} m, superelevation "
                 f"{c.superelevation_deg:g} deg)")
        # both limits are R q(+-d): proportional to the radius at this tension and tilt, so
        # the radii that hold the belt run from r_in (below it the belt runs to the inside)
        # to r_out (above it, out of the curve); the file takes no radius under r_turn (a
        # section of more than a full turn). A radius is named only where that range is open.
        r_in = (c.radius_m * float(np.max(t_run / hi)) if (hi > 0.0).all() else math.inf)
        held = lo > 0.0
        r_out = (c.radius_m * float(np.min(t_run[held] / lo[held])) if held.any()
                 else math.inf)
        r_turn = sec.length_m / math.radians(HCURVE_TURN_MAX_DEG)
        r_lo = max(r_in, math.ceil(r_turn)) if math.isinf(r_in) else max(
            math.ceil(r_in), math.ceil(r_turn))
        r_hi = math.floor(r_out) if math.isfinite(r_out) else math.inf
        none_holds = (
            "no radius holds it at this superelevation: the weight on these sets gives no "
            "restoring force against the tension" if math.isinf(r_in) else
            f"no radius holds it at this superelevation and these tensions (at least "
            f"{math.ceil(r_in):.0f} m against running in, at most {r_hi:.0f} m against "
            "running out: the tension changes along the curve by more than the band R q(-d) "
            "to R q(+d) allows)") + _no_room(ic, garland)
        holds = math.isfinite(r_lo) and r_lo <= r_hi
        if inside:
            radius = (f"a radius of at least {r_lo:.0f} m (at this superelevation and these "
                      "tensions" + (f"; above {r_hi:.0f} m the belt runs out of the curve)"
                                    if math.isfinite(r_out) else ")")
                      if holds else none_holds)
            warnings.append(
                f"{where}: the belt runs to the inside of the curve: tension "
                f"{t_run[j_in] / 1e3:.1f} kN at {x_at[j_in]:.0f} m from the tail, above the "
                f"{hi[j_in] / 1e3:.1f} kN the weight of the {_load_case(m_el[j_in], m_full)} "
                f"belt holds there; {radius}, more superelevation, a deeper trough or "
                "less tension there (a take-up with less tension, the curve nearer the slack "
                "side)")
        if outside and t_run[j_out] <= 0.0:
            # a slack belt: no radius holds it (the tension's pull to the inside, T / R, is
            # gone) and no tilt does (the least tension it needs there is itself 0 or more):
            # a 6.5 km decline's curve was told "a tighter radius (at most inf m ...)", another
            # "at most -821 m"
            warnings.append(
                f"{where}: the {_load_case(m_el[j_out], m_full)} belt runs out of the curve: "
                f"tension {t_run[j_out] / 1e3:.1f} kN at {x_at[j_out]:.0f} m from the tail, "
                f"below the {lo[j_out] / 1e3:.1f} kN it needs there; the belt is slack there, "
                "and no radius or superelevation holds a belt without tension in a curve: "
                "more take-up tension would avoid it")
        elif outside:
            if holds:
                radius = (f"a tighter radius (at most {r_hi:.0f} m at this superelevation "
                          "and these tensions: the tension's pull to the inside, T / R, grows "
                          "as the radius shrinks" + (
                              f"; below {r_lo:.0f} m the belt runs to the inside)"
                              if math.isfinite(r_in) and r_lo == math.ceil(r_in) else
                              f"; not below {r_lo:.0f} m, a full turn of the section)"))
            elif math.isfinite(r_in) and math.ceil(r_in) <= r_hi:
                radius = (f"a tighter radius is no help: the {r_hi:.0f} m that holds it would "
                          f"turn the section's {sec.length_m:g} m more than a full turn "
                          f"(at least {r_turn:.1f} m)")
            else:
                radius = none_holds
            sep = ", or " if holds else "; "
            warnings.append(
                f"{where}: the {_load_case(m_el[j_out], m_full)} belt runs out of the curve: "
                f"tension {t_run[j_out] / 1e3:.1f} kN at {x_at[j_out]:.0f} m from the tail, "
                f"below the {lo[j_out] / 1e3:.1f} kN it needs there; less superelevation, "
                f"more take-up tension{sep}{radius}")
    return out, warnings
