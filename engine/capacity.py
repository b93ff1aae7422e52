"""Capacity check: the material cross-section a troughed belt carries (ISO 5048, DIN 22101).

``fill_pct`` is the design volume flow over the volume flow the belt's cross-section carries at
the design speed, in percent; above 100 % the design load does not fit on the belt.

Notes
-----
Usable width (the loaded part of the belt, an unloaded edge on each side), ISO 5048 clause 6 /
DIN 22101 section 5::

    b = 0.9 B - 0.05 m      for B <= 2 m
    b = B - 0.25 m          for B > 2 m

The cross-section is the trough part below the line joining the loaded edges, ``S2``, plus the
surcharge heaped above it, ``S1``, a parabola meeting the edges at the surcharge angle theta.
For a three-roll set with middle roll length ``l`` and trough angle lambda (ISO 5048)::

    S1 = [l + (b - l) cos(lambda)]^2 tan(theta) / 6
    S2 = [l + (b - l) cos(lambda) / 2] [(b - l) sin(lambda) / 2]

A flat belt (one roll) is ``l >= b`` or lambda = 0: ``S1 = b^2 tan(theta) / 6``, ``S2 = 0``; a
V trough (two rolls) is ``l = 0``. Both are the same polygon computed here: the half-section
from the belt centre as straight segments (length, angle), ``S2`` the area between the
segments and the edge line, ``S1 = w^2 tan(theta) / 6`` over the edge-to-edge width ``w``.
Four- and five-roll (garland) sets are not in ISO 5048: they are taken as equal rolls of
``roll_length_m`` (default B / rolls, an estimate) whose angles rise in equal steps to the
trough angle, the outer rolls taking the rest of the usable width.

On an incline the surcharge part carries less (ISO 5048)::

    k = 1 - (S1 / S) (1 - k1),   k1 = sqrt((cos^2(delta) - cos^2(theta)) / (1 - cos^2(theta)))

taken at the steepest carry section (k1 = 0 where delta >= theta). The capacity is then
``Q_V = 3600 S v k`` [m3/h].

References
----------
ISO 5048:1989 Continuous mechanical handling equipment - Belt conveyors with carrying idlers -
Calculation of operating power and tensile forces, clause 6 (capacity and cross-section).
DIN 22101:2002-08 Continuous conveyors - Belt conveyors for loose bulk materials, section 5.
DIN 22107 / ISO 1537 roll lengths of troughed idler sets (``engine/data/trough.csv``).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from functools import cache

import numpy as np

from beltstudy.engine.conveyor import FILL_MAX_PCT, Conveyor, register_check
from beltstudy.engine.drives import down3, up3
from beltstudy.engine.errors import InputError
from beltstudy.engine.wording import gnum

__all__ = [
    "check_fill",
    "incline_warning",
    "usable_width_m",
    "middle_roll_length_m",
    "trough_segments",
    "cross_section_m2",
    "slope_factor",
    "Capacity",
    "capacity",
    "fill_pct",
]


def usable_width_m(belt_width_m: float, edge_distance_m: float | None = None) -> float:
    """Loaded width b of a belt of width B [m] (ISO 5048, DIN 22101).

    ``b = 0.9 B - 0.05`` up to ``B = 2 m``, ``B - 0.25`` above; with an edge distance e given,
    ``b = B - 2 e`` (never below 0).
    """
    if edge_distance_m is not None:
        return max(belt_width_m - 2.0 * edge_distance_m, 0.0)
    if belt_width_m <= 2.0:
        return max(0.9 * belt_width_m - 0.05, 0.0)
    return belt_width_m - 0.25


@cache
def _roll_table() -> tuple[np.ndarray, np.ndarray]:
    from beltstudy.engine.catalog import _rows

    rows = _rows("trough.csv")
    return (np.array([float(r["belt_width_m"]) for r in rows]),
            np.array([float(r["roll_length_m"]) for r in rows]))


def middle_roll_length_m(belt_width_m: float, rolls: int = 3) -> float:
    """Default roll length of a carrying set [m].

    Three rolls: DIN 22107 by belt width (``engine/data/trough.csv``, interpolated, held at the
    table's ends). Four or five rolls: ``B / rolls`` (an estimate). One or two rolls have no
    middle roll (0).
    """
    if rolls <= 2:
        return 0.0
    if rolls >= 4:
        return belt_width_m / rolls
    widths, lengths = _roll_table()
    return float(np.interp(belt_width_m, widths, lengths))


def trough_segments(b_m: float, rolls: int, trough_deg: float, roll_length_m: float
                    ) -> list[tuple[float, float]]:
    """Half the loaded belt from its centre as straight segments ``(length [m], angle [rad])``.

    One roll: flat. Two: one wing at the trough angle. Three: half the middle roll flat, then a
    wing at the trough angle taking the rest of ``b / 2``. Four and five: rolls of
    ``roll_length_m`` at angles rising in equal steps to the trough angle, the outer roll taking
    the rest of ``b / 2``.
    """
    lam = math.radians(trough_deg)
    half = 0.5 * b_m
    if rolls <= 1 or trough_deg == 0.0:
        return [(half, 0.0)]
    if rolls == 2:
        return [(half, lam)]
    if rolls % 2 == 1:  # a horizontal middle roll, then (rolls - 1) / 2 rolls per side
        steps = (rolls - 1) // 2
        first = min(0.5 * roll_length_m, half)
        segs = [(first, 0.0)]
    else:  # two middle rolls meeting at the centre
        steps = rolls // 2
        segs = []
    used = sum(s[0] for s in segs)
    for i in range(1, steps + 1):
        angle = lam * i / steps
        length = half - used if i == steps else min(roll_length_m, half - used)
        segs.append((max(length, 0.0), angle))
        used += segs[-1][0]
    return segs


def cross_section_m2(b_m: float, rolls: int, trough_deg: float, roll_length_m: float,
                     surcharge_deg: float) -> tuple[float, float]:
    """Surcharge part S1 and trough part S2 of the material cross-section [m2].

    Parameters
    ----------
    b_m : float
        Usable (loaded) width b [m].
    rolls : int
        Rolls per carrying set.
    trough_deg : float
        Trough angle lambda [deg].
    roll_length_m : float
        Middle roll length l [m] (three rolls), roll length (four, five).
    surcharge_deg : float
        Surcharge angle theta [deg].
    """
    x = y = 0.0
    s2_half = 0.0
    pts = [(0.0, 0.0)]
    for length, angle in trough_segments(b_m, rolls, trough_deg, roll_length_m):
        x += length * math.cos(angle)
        y += length * math.sin(angle)
        pts.append((x, y))
    top = pts[-1][1]
    for (x0, y0), (x1, y1) in zip(pts[:-1], pts[1:], strict=True):
        s2_half += (x1 - x0) * (top - 0.5 * (y0 + y1))
    width = 2.0 * pts[-1][0]
    s1 = width * width * math.tan(math.radians(surcharge_deg)) / 6.0
    return s1, 2.0 * s2_half


def slope_factor(s1_m2: float, s2_m2: float, slope_deg: float, surcharge_deg: float) -> float:
    """ISO 5048 reduction k of the cross-section on a slope delta [-] (1 on the level)."""
    s = s1_m2 + s2_m2
    if s <= 0.0 or s1_m2 <= 0.0:
        return 1.0
    # k1 = sqrt((cos^2 delta - cos^2 theta) / (1 - cos^2 theta)), written with sines
    # (cos^2 delta - cos^2 theta = sin^2 theta - sin^2 delta): below about 6e-7 deg of
    # surcharge cos^2 theta rounds to 1 and the cosine form divides by zero
    sd = abs(math.sin(math.radians(slope_deg)))
    st = math.sin(math.radians(surcharge_deg))
    k1 = math.sqrt(1.0 - (sd / st) ** 2) if sd < st else 0.0
    return 1.0 - (s1_m2 / s) * (1.0 - k1)


@dataclass(frozen=True)
class Capacity:
    """The capacity check of a conveyor. Units in the names."""

    usable_width_m: float
    roll_length_m: float
    s1_m2: float
    s2_m2: float
    slope_deg: float
    slope_factor: float
    volume_flow_m3_h: float  # design volume flow, capacity / density
    capacity_m3_h: float  # what the cross-section carries at the design speed
    fill_pct: float


def capacity(conv: Conveyor) -> Capacity:
    """Cross-section, capacity and ``fill_pct`` of a conveyor at its design speed."""
    from beltstudy.engine.catalog import resolve_belt

    belt = resolve_belt(conv.belt)
    ic = conv.idlers.carry
    mat = conv.material
    b = usable_width_m(belt.width_m, mat.edge_distance_m)
    roll = ic.roll_length_m if ic.roll_length_m is not None else middle_roll_length_m(
        belt.width_m, ic.rolls)
    s1, s2 = cross_section_m2(b, ic.rolls, ic.trough_deg, roll, mat.surcharge_deg)
    slope = max(math.degrees(math.asin(abs(p.lift_m) / p.length_m)) for p in conv.profile)
    k = slope_factor(s1, s2, slope, mat.surcharge_deg)
    q_design = mat.capacity_t_h / mat.density_t_m3
    q_belt = 3600.0 * (s1 + s2) * conv.speed_m_s * k
    if q_design <= 0.0:
        fill = 0.0
    else:
        fill = 100.0 * q_design / q_belt if q_belt > 0.0 else math.inf
    return Capacity(usable_width_m=b, roll_length_m=roll, s1_m2=s1, s2_m2=s2, slope_deg=slope,
                    slope_factor=k, volume_flow_m3_h=q_design, capacity_m3_h=q_belt,
                    fill_pct=fill)


def fill_pct(conv: Conveyor) -> float:
    """Design volume flow over the belt's cross-section capacity at design speed [%]."""
    return capacity(conv).fill_pct


def fill_levers(conv: Conveyor, fill: float, limit_pct: float) -> str:
    """What brings a cross-section filled to ``fill`` [%] down to ``limit_pct`` [%], in words:
    a capacity of at most ..., a speed of at least ... (the fill falls as 1 / speed, the
    area being the belt's, ISO 5048) or a wider belt. A speed beyond speed_m_s's own bound
    is no lever (a 0.1 m belt, a width typed in the wrong unit, was told 'a speed of at least
    1210 m/s', which is then refused)."""
    speed = up3(conv.speed_m_s * fill / limit_pct)
    top = type(conv).model_fields["speed_m_s"].metadata
    v_max = min((float(m.le) for m in top if getattr(m, "le", None) is not None),
                default=math.inf)
    cap = f"a capacity of at most {down3(conv.material.capacity_t_h * limit_pct / fill):g} t/h"
    if speed <= v_max:
        return (f"{cap} (material.capacity_t_h), a speed of at least {speed:g} m/s (speed_m_s; "
                "the fill falls as 1 / speed) or a wider or deeper-troughed belt")
    return (f"{cap} (material.capacity_t_h) or a wider belt (belt.width_m, now "
            f"{conv.belt.width_m:g} m); no speed within speed_m_s's bound of {v_max:g} m/s "
            f"would do (it would take {speed:g} m/s)")


def check_fill(conv: Conveyor, prefix: str = "") -> None:
    """Refuse a capacity that fills the belt's cross-section more than
    :data:`~beltstudy.engine.conveyor.FILL_MAX_PCT` at the design speed (ISO 5048 geometry,
    :func:`fill_pct`); registered with :func:`~beltstudy.engine.conveyor.register_check`."""
    if conv.belt.type == "auto":  # the belt is chosen later; capacity_t_h's own bound holds
        return
    edge = conv.material.edge_distance_m
    if edge is not None and usable_width_m(conv.belt.width_m, edge) <= 0.0:
        raise InputError(
            f"{prefix}material.edge_distance_m: {edge:g} m on each side leaves no width of the "
            f"{conv.belt.width_m:g} m belt to carry material; give less than half the belt width "
            "(leave it out for ISO 5048 / DIN 22101's 0.05 B + 0.025 m up to B = 2 m)")
    fill = fill_pct(conv)
    if fill > FILL_MAX_PCT:
        levers = fill_levers(conv, fill, FILL_MAX_PCT)
        raise InputError(
            f"{prefix}material.capacity_t_h: {conv.material.capacity_t_h:g} t/h fills the "
            f"belt's cross-section to {gnum(fill, 3)} % at {conv.speed_m_s:g} m/s; at most "
            f"{FILL_MAX_PCT:g} % (beyond that the material heaps far above the belt's edges, "
            f"no belt carries it): {levers}")


register_check(check_fill)


def check_middle_roll(conv: Conveyor, prefix: str = "") -> None:
    """A troughed carry set's flat middle roll (three or five rolls) shorter than the belt;
    registered with :func:`~beltstudy.engine.conveyor.register_check`.

    Geometry: a belt no wider than the middle roll lies flat on it and never reaches the wing
    rolls, so the set troughs nothing: the trough angle, the middle roll's share of the load
    and the ISO 5048 cross-section would all be read for a trough that is not there.
    """
    ic = conv.idlers.carry
    width = conv.belt.width_m
    if ic.rolls in (3, 5) and ic.trough_deg > 0.0 and ic.roll_length_m is not None \
            and ic.roll_length_m >= width:
        usual = middle_roll_length_m(width, ic.rolls)
        raise InputError(
            f"{prefix}idlers.carry.roll_length_m: a middle roll of {ic.roll_length_m:g} m is "
            f"not shorter than the {width:g} m belt (belt.width_m): the belt lies flat on it "
            f"and never reaches the wing rolls, so the set troughs nothing at trough_deg "
            f"{ic.trough_deg:g}; give the set's middle roll (leave it out for "
            f"{gnum(usual, 3)} m, DIN 22107 for this width), or a wider belt, or rolls: 1 with "
            "trough_deg: 0 for a flat belt")


register_check(check_middle_roll)


def incline_warning(conv: Conveyor, loop) -> str:
    """A warning for each loaded carry section steeper than the material rides ("" if none).

    The material's surcharge angle theta is the slope its surface takes on the moving belt
    (CEMA, Belt Conveyors for Bulk Materials, Table 4-1), and ISO 5048's slope factor ends
    there: ``k1 = sqrt((cos^2(delta) - cos^2(theta)) / (1 - cos^2(theta)))`` is 0 at
    ``delta = theta`` (no surcharge is carried) and has no value beyond it. A section steeper
    than theta that carries material in the run's load case (``loop.mL_kg_m`` on its carry
    elements) has no ISO 5048 capacity and the material can slide back down it (forward down a
    decline), while the run carries it as if it stayed. The fix named is the section length
    at which the same lift is at the surcharge angle, ``|lift| / sin(theta)``.
    """
    from beltstudy.engine.loop import CARRY

    theta = conv.material.surcharge_deg
    sin_t = math.sin(math.radians(theta))
    carry = (loop.strand == CARRY) & (loop.mL_kg_m > 0.0)
    if loop.x_m is None or not carry.any():
        return ""
    x = np.asarray(loop.x_m)
    steep = []
    x0 = 0.0
    for i, p in enumerate(conv.profile):
        x1 = x0 + p.length_m
        delta = math.degrees(math.asin(min(abs(p.lift_m) / p.length_m, 1.0)))
        # float noise: a section written at exactly the surcharge angle is at the edge, inside
        loaded = bool((carry & (x >= x0) & (x < x1)).any())
        if loaded and delta > theta * (1.0 + 1e-9):
            need = abs(p.lift_m) / sin_t if sin_t > 0.0 else math.inf
            fix = (f"at least {math.ceil(need):.0f} m for that lift" if math.isfinite(need)
                   else "a level section")
            steep.append(f"profile.{i} {'climbs' if p.lift_m > 0 else 'falls'} {delta:.1f} deg "
                         f"({gnum(p.lift_m)} m over {gnum(p.length_m)} m, {x0:.0f} to {x1:.0f} m from "
                         f"the tail; length_m {fix})")
        x0 = x1
    if not steep:
        return ""
    return (f"loaded section steeper than the material rides: {'; '.join(steep)}: beyond the "
            f"material's surcharge angle, material.surcharge_deg {theta:g} deg, ISO 5048's "
            "slope factor carries no surcharge and has no value: the material can slide "
            "back down the belt, which this run carries as if it stayed; a flatter route (the "
            "length above), a material.surcharge_deg as steep if the material stands so on "
            "the moving belt (CEMA Table 4-1, at most 30 deg), or a cleated or pocket belt "
            "(not modelled) would avoid it")
