"""The belt loop cut into elements (PHYSICS section 1, docs/ARCHITECTURE.md).

Order in the direction of travel: carry elements tail -> head, the head pulley element, a
take-up pulley element when the take-up sits at the head, return elements head -> tail, and
the tail pulley element last. Boundary tension ``T[j]`` is the tension at the end of element
``j``. Build once per conveyor and load case; every later step reads these arrays.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from engine import catalog
from engine.conveyor import Conveyor, section_loads

__all__ = ["G", "Loop", "build_loop", "CARRY", "RETURN", "HEAD", "TAIL", "TAKEUP"]

#: Gravitational acceleration [m/s2].
G = 9.81

CARRY, RETURN, HEAD, TAIL, TAKEUP = 0, 1, 2, 3, 4

#: Diameter used for a non-drive pulley when the file does not give one [m] (estimate).
DEFAULT_PULLEY_DIAMETER_M = 0.8


@dataclass(frozen=True, eq=False)
class Loop:
    """Per-element arrays of the belt loop. Units are in the field names."""

    n: int
    nc: int
    i_head: int
    i_tail: int
    i_takeup: int
    strand: np.ndarray
    dx_m: np.ndarray
    s_m: np.ndarray
    z_m: np.ndarray
    z_end_m: np.ndarray
    sin_a: np.ndarray
    cos_a: np.ndarray
    spacing_m: np.ndarray
    roll_diameter_m: np.ndarray
    rolls: np.ndarray
    trough_deg: np.ndarray
    mG_kg_m: np.ndarray
    mL_kg_m: np.ndarray
    mR_kg_m: np.ndarray
    seal_drag_n: np.ndarray
    length_m: float
    lift_m: float
    load_fraction: float  # carry-length-weighted mean of section_load
    speed_m_s: float
    belt: catalog.ResolvedBelt
    design_load_kg_m: float
    section_load: tuple[float, ...] = ()  # load fraction per carry profile section

    @property
    def load_max_kg_m(self) -> float:
        """Largest material mass per metre on the carry strand [kg/m] (the loaded sections)."""
        carry = self.strand == CARRY
        return float(self.mL_kg_m[carry].max()) if carry.any() else 0.0

    @property
    def mass_kg(self) -> np.ndarray:
        """Moving mass of each element (m'_G + m'_L + m'_R) dx [kg]."""
        return (self.mG_kg_m + self.mL_kg_m + self.mR_kg_m) * self.dx_m

    @property
    def sag_w_n(self) -> np.ndarray:
        """g (m'_G + m'_L) cos(a) S / 8 [N]; the sag ratio h/S is sag_w_n / T (0 on pulleys)."""
        s = np.where(np.isfinite(self.spacing_m), self.spacing_m, 0.0)
        return G * (self.mG_kg_m + self.mL_kg_m) * self.cos_a * s / 8.0

    @property
    def gravity_n(self) -> np.ndarray:
        """Gravity component along the belt (m'_G + m'_L) g dx sin(a) [N] per element."""
        return (self.mG_kg_m + self.mL_kg_m) * G * self.dx_m * self.sin_a

    @property
    def is_idler(self) -> np.ndarray:
        return (self.strand == CARRY) | (self.strand == RETURN)

    @property
    def s_mid_m(self) -> np.ndarray:
        return self.s_m + 0.5 * self.dx_m

    @property
    def s_end_m(self) -> np.ndarray:
        return self.s_m + self.dx_m

    @property
    def total_length_m(self) -> float:
        return float(self.dx_m.sum())

    def where(self, s_m: float) -> tuple[str, float]:
        """Strand and distance from the tail along the conveyor of a loop position [m].

        ``s_m`` is measured round the loop from the tail, carry first. Returns ``("carry",
        x)``, ``("return", x)`` with x the distance from the tail of the point the belt passes
        over, or ``("head", L)`` / ``("tail", 0)`` / ``("takeup", L)`` on a pulley.
        """
        j = int(np.clip(np.searchsorted(self.s_end_m, s_m, side="left"), 0, self.n - 1))
        code = int(self.strand[j])
        if code == CARRY:
            return "carry", float(min(max(s_m, 0.0), self.length_m))
        if code == RETURN:
            start = float(self.s_m[self.strand == RETURN].min())
            return "return", float(min(max(self.length_m - (s_m - start), 0.0), self.length_m))
        return {HEAD: "head", TAIL: "tail", TAKEUP: "takeup"}[code], (
            0.0 if code == TAIL else self.length_m)


def _split(n: int, lengths: list[float]) -> list[int]:
    """Split n elements over sections proportionally to length, at least one each."""
    total = sum(lengths)
    raw = [n * L / total for L in lengths]
    counts = [max(1, int(math.floor(r))) for r in raw]
    # hand out the remainder to the sections with the largest fractional parts
    while sum(counts) < n:
        i = max(range(len(raw)), key=lambda k: raw[k] - counts[k])
        counts[i] += 1
    while sum(counts) > n and max(counts) > 1:
        i = max(range(len(raw)), key=lambda k: counts[k] - raw[k])
        if counts[i] > 1:
            counts[i] -= 1
    return counts


def _pulley_diameter(conv: Conveyor, position: str) -> float:
    ds = [d.pulley_diameter_m for d in conv.drives if d.position == position]
    return max(ds) if ds else DEFAULT_PULLEY_DIAMETER_M


def build_loop(
    conv: Conveyor,
    load_fraction: float | str | list = 1.0,
    n_elements: int | None = None,
    target_dx_m: float | None = None,
) -> Loop:
    """Cut the conveyor into elements.

    Parameters
    ----------
    conv : Conveyor
    load_fraction : float, str or list
        Material load as a fraction of the design load (1 full, 0 empty, up to 1.3 a surge),
        or a load case of SPEC 6.2 (``full``, ``empty``, ``inclines``, ``declines``, one
        fraction per carry profile section): see :func:`engine.conveyor.section_loads`. Each
        carry element gets its section's material mass.
    n_elements : int, optional
        Number of belt (idler) elements round the loop, split evenly between the strands;
        pulley elements come on top. Default 200, or from ``target_dx_m``.
    target_dx_m : float, optional
        Target element length [m] instead of a count.
    """
    L = conv.length_m
    if n_elements is None:
        n_elements = 200 if target_dx_m is None else max(2, int(round(2 * L / target_dx_m)))
    n_elements = max(int(n_elements), 2 * len(conv.profile), 2)
    n_strand = n_elements // 2
    lengths = [p.length_m for p in conv.profile]
    counts = _split(n_strand, lengths)

    belt = catalog.resolve_belt(conv.belt)
    mG = belt.mass_kg_m
    design_mL = conv.material.capacity_t_h / (3.6 * conv.speed_m_s)
    loads = section_loads(load_fraction, conv)
    w = belt.width_m
    carry_mass, carry_drag = catalog.idler_set_values(conv.idlers.carry, w)
    ret_mass, ret_drag = catalog.idler_set_values(conv.idlers.return_, w)
    ic, ir = conv.idlers.carry, conv.idlers.return_

    cols: dict[str, list] = {k: [] for k in (
        "strand", "dx", "z", "sin", "cos", "S", "D", "rolls", "trough", "mL", "mR", "drag")}

    def add(strand, dx, z, sin, cos, S, D, rolls, trough, mL_, mR, drag):
        for k, v in zip(cols, (strand, dx, z, sin, cos, S, D, rolls, trough, mL_, mR, drag),
                        strict=True):
            cols[k].append(v)

    # carry strand, tail -> head
    z = 0.0
    for sec, k, frac in zip(conv.profile, counts, loads, strict=True):
        dx = sec.length_m / k
        sin = sec.lift_m / sec.length_m
        cos = math.sqrt(1.0 - sin * sin)
        for _ in range(k):
            add(CARRY, dx, z, sin, cos, ic.spacing_m, ic.roll_diameter_m, ic.rolls,
                ic.trough_deg, design_mL * frac, carry_mass / ic.spacing_m, carry_drag)
            z += dx * sin
    z_head = z
    nc = len(cols["dx"])
    d_head = _pulley_diameter(conv, "head")
    add(HEAD, math.pi * d_head / 2, z_head, 0.0, 1.0, math.inf, 0.0, 0, 0.0, 0.0, 0.0, 0.0)
    i_head = nc
    if conv.takeup.position == "head":
        add(TAKEUP, math.pi * DEFAULT_PULLEY_DIAMETER_M / 2, z_head, 0.0, 1.0, math.inf, 0.0, 0,
            0.0, 0.0, 0.0, 0.0)
        i_takeup = nc + 1
    else:
        i_takeup = -1
    # return strand, head -> tail: the profile backwards, slope negated
    z = z_head
    for sec, k in zip(reversed(conv.profile), reversed(counts), strict=True):
        dx = sec.length_m / k
        sin = -sec.lift_m / sec.length_m
        cos = math.sqrt(1.0 - sin * sin)
        for _ in range(k):
            add(RETURN, dx, z, sin, cos, ir.spacing_m, ir.roll_diameter_m, ir.rolls,
                ir.trough_deg, 0.0, ret_mass / ir.spacing_m, ret_drag)
            z += dx * sin
    d_tail = _pulley_diameter(conv, "tail")
    add(TAIL, math.pi * d_tail / 2, 0.0, 0.0, 1.0, math.inf, 0.0, 0, 0.0, 0.0, 0.0, 0.0)
    n = len(cols["dx"])
    i_tail = n - 1
    if i_takeup < 0:
        i_takeup = i_tail

    arr = {k: np.asarray(v, dtype=np.float64) for k, v in cols.items()}
    dx_arr = arr["dx"]
    s = np.concatenate(([0.0], np.cumsum(dx_arr)[:-1]))
    z_arr = arr["z"]
    z_end = z_arr + dx_arr * arr["sin"]
    z_end[-1] = 0.0
    return Loop(
        n=n,
        nc=nc,
        i_head=i_head,
        i_tail=i_tail,
        i_takeup=i_takeup,
        strand=np.asarray(cols["strand"], dtype=np.int8),
        dx_m=dx_arr,
        s_m=s,
        z_m=z_arr,
        z_end_m=z_end,
        sin_a=arr["sin"],
        cos_a=arr["cos"],
        spacing_m=arr["S"],
        roll_diameter_m=arr["D"],
        rolls=arr["rolls"],
        trough_deg=arr["trough"],
        mG_kg_m=np.full(n, mG),
        mL_kg_m=arr["mL"],
        mR_kg_m=arr["mR"],
        seal_drag_n=arr["drag"],
        length_m=L,
        lift_m=conv.lift_m,
        load_fraction=float(sum(f * p.length_m for f, p in zip(loads, conv.profile,
                                                                strict=True)) / L),
        speed_m_s=float(conv.speed_m_s),
        belt=belt,
        design_load_kg_m=design_mL,
        section_load=loads,
    )
