"""The belt loop cut into elements (PHYSICS section 1, docs/ARCHITECTURE.md).

Order in the direction of travel: carry elements tail -> head, the head pulleys (every head
drive its own pulley element, in the order of the file, which is the order the belt meets
them; one plain head pulley when the head has no drive), a take-up pulley element when the
take-up sits at the head, return elements head -> tail, then the tail pulleys (a separate
take-up pulley first when the take-up sits at a driven tail, then the tail drives in file
order; one plain tail pulley, which is also the take-up pulley of a tail take-up, when the tail
has no drive). A booster drive along a strand (SPEC 7.1 ``position: carry | return``, ``at_m``)
and a take-up along the return are pulley elements inside their strand, where the belt
passes ``at_m``: the strands are cut there (and at the feed points) so that an element ends
at each (:func:`route_cuts`). Boundary tension ``T[j]`` is the tension at the end of element ``j``. Build
once per conveyor and load case; every later step reads these arrays.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from beltstudy.engine import catalog
from beltstudy.engine.conveyor import (
    CURVE_STEP_DEG,
    Conveyor,
    curve_arc_m,
    place,
    route_points,
    section_loads,
)
from beltstudy.engine.wording import gnum

__all__ = ["G", "Loop", "Pulley", "build_loop", "CARRY", "RETURN", "HEAD", "TAIL", "TAKEUP",
           "BOOSTER", "route_cuts",
           "Curve", "CURVE_STEP_DEG", "RotatingParts", "rotating_parts", "pulley_reduced_mass_kg", "MOTOR_INERTIA_SHARE"]

#: Gravitational acceleration [m/s2].
G = 9.81

CARRY, RETURN, HEAD, TAIL, TAKEUP = 0, 1, 2, 3, 4
#: Strand code of a booster drive's pulley along the carry or the return.
BOOSTER = 5

#: Diameter used for a non-drive pulley when the file does not give one [m] (estimate).
DEFAULT_PULLEY_DIAMETER_M = 0.8


#: Wrap of a plain (non-drive) head or tail pulley [deg] and the belt-pulley friction used when
#: such a pulley carries a brake (a lagged pulley's typical dry value, as the drives' default).
PLAIN_WRAP_DEG = 180.0
PLAIN_FRICTION = 0.35


@dataclass(frozen=True)
class Pulley:
    """A pulley element of the loop.

    Attributes
    ----------
    element : int
        Element index.
    position : str
        ``head``, ``tail``, or ``carry`` / ``return`` (a booster drive, a take-up along the
        return).
    drive : int
        Index of the drive in the conveyor file (0-based), -1 for a plain or take-up pulley.
    diameter_m, wrap_deg, friction, friction_kinetic : float
        Geometry and belt-pulley friction (static, sliding) [m, deg, -].
    takeup : bool
        The take-up pulley (its carriage moves).
    at_m : float or None
        Along a strand: where, from the tail along the conveyor [m].
    """

    element: int
    position: str
    drive: int
    diameter_m: float
    wrap_deg: float
    friction: float
    friction_kinetic: float
    takeup: bool = False
    at_m: float | None = None

    @property
    def where(self) -> str:
        """``head``, ``tail`` or ``carry at 1000 m``, for messages."""
        return place(self.position, self.at_m)

    @property
    def euler(self) -> float:
        """e^(mu theta) with the static friction [-]."""
        return math.exp(self.friction * math.radians(self.wrap_deg))

    @property
    def euler_kinetic(self) -> float:
        """e^(mu_k theta) with the sliding friction [-]."""
        return math.exp(self.friction_kinetic * math.radians(self.wrap_deg))




@dataclass(frozen=True, eq=False)
class Curve:
    """A vertical curve of the route (``profile[section].curve_radius_m``, docs/routes.md).

    Attributes
    ----------
    k : int
        1-based curve number in profile order.
    section : int
        Profile section (0-based) the curve ends; it joins it to section + 1.
    radius_m : float
        Radius R [m].
    angle_in_rad, angle_out_rad : float
        Slope angle of the two grades it joins, tail -> head [rad].
    at_m : float
        The two sections' junction, from the tail along the carry [m].
    start_m, end_m : float
        The arc's ends along the carry [m] (at_m -/+ R |delta| / 2).
    carry, ret : numpy.ndarray
        Element indices on the arc, carry strand and return strand.
    """

    k: int
    section: int
    radius_m: float
    angle_in_rad: float
    angle_out_rad: float
    at_m: float
    start_m: float
    end_m: float
    carry: np.ndarray
    ret: np.ndarray

    @property
    def delta_rad(self) -> float:
        """Change of slope angle, tail -> head [rad]; positive concave (a valley)."""
        return self.angle_out_rad - self.angle_in_rad

    @property
    def concave(self) -> bool:
        """Grade increasing (a valley): the belt's tension pulls it off its idlers."""
        return self.delta_rad > 0.0

    @property
    def kind(self) -> str:
        return "concave" if self.concave else "convex"


@dataclass(frozen=True, eq=False)
class Loop:
    """Per-element arrays of the belt loop. Units are in the field names.

    ``i_head`` is the first head pulley (T1 = ``T[i_head - 1]``), ``i_tail`` the last element
    (the tail pulley the carry strand leaves), ``i_takeup`` the take-up pulley;
    ``pulleys`` lists every pulley element in loop order and ``drive_elements`` the element of
    each drive in file order.
    """

    n: int
    nc: int
    i_head: int
    i_tail: int
    i_takeup: int
    pulleys: tuple
    drive_elements: tuple
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
    sag_limit: np.ndarray
    length_m: float
    lift_m: float
    load_fraction: float  # carry-length-weighted mean of section_load
    speed_m_s: float
    belt: catalog.ResolvedBelt
    design_load_kg_m: float
    section_load: tuple[float, ...] = ()  # load fraction per carry profile section
    curves: tuple = ()  # the vertical curves (Curve), in profile order
    x_m: np.ndarray | None = None  # where each element starts along the route from the tail [m]

    @property
    def load_max_kg_m(self) -> float:
        """Largest material mass per metre on the carry strand [kg/m] (the loaded sections)."""
        carry = self.strand == CARRY
        return float(self.mL_kg_m[carry].max()) if carry.any() else 0.0

    def brake_element(self, brake) -> int:
        """Element of a brake's pulley: a drive's pulley (``drive: N``), the first head pulley
        (the discharge pulley) or the tail pulley the carry strand leaves."""
        if brake.drive is not None:
            return int(self.drive_elements[brake.drive - 1])
        return int(self.i_head if brake.where == "head" else self.i_tail)

    def pulley_at(self, element: int) -> Pulley:
        """The pulley of a pulley element."""
        return next(p for p in self.pulleys if p.element == element)

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
        over, or on a pulley its kind (``head``, ``tail``, ``takeup``, ``booster``) and where
        it sits.
        """
        j = int(np.clip(np.searchsorted(self.s_end_m, s_m, side="left"), 0, self.n - 1))
        code = int(self.strand[j])
        x0 = float(self.x_m[j]) if self.x_m is not None else float(self.s_m[j])
        past = float(s_m) - float(self.s_m[j])
        if code == CARRY:
            return "carry", float(min(max(x0 + past, 0.0), self.length_m))
        if code == RETURN:
            return "return", float(min(max(x0 - past, 0.0), self.length_m))
        return {HEAD: "head", TAIL: "tail", TAKEUP: "takeup", BOOSTER: "booster"}[code], x0


def _split(n: int, lengths: list[float]) -> list[int]:
    """Split n elements over sections proportionally to length, at least one each."""
    total = sum(lengths)
    raw = [n * L / total for L in lengths]
    counts = [max(1, int(math.floor(r))) for r in raw]
    # hand out the remainder to the sections with the largest fractional parts
    while sum(counts) < n:
        i = max(range(len(raw)), key=lambda k: raw[k] - counts[k])
        counts[i] += 1
    # take the surplus back from sections that keep at least one (a short section floored up
    # to one element must not be picked: it would leave the count unchanged for ever)
    while sum(counts) > n and max(counts) > 1:
        i = max((k for k in range(len(raw)) if counts[k] > 1), key=lambda k: counts[k] - raw[k])
        counts[i] -= 1
    return counts


def route_cuts(conv: Conveyor) -> list[float]:
    """Where an element must end along the route, from the tail [m], ascending: the feed
    points, the booster drives and a take-up along the return
    (:func:`beltstudy.engine.conveyor.route_points`); points closer than a micrometre are one."""
    out: list[float] = []
    for at in sorted(at for _, at in route_points(conv)):
        if not out or at - out[-1] > 1e-6:
            out.append(at)
    return out


def section_cuts(conv: Conveyor, start_m: float, length_m: float, k: int
                 ) -> list[tuple[float, int, float]]:
    """A profile section cut at the points of :func:`route_cuts` inside it (feed points,
    booster drives, a take-up along the return).

    Parameters
    ----------
    conv : Conveyor
    start_m, length_m : float
        Where the section starts along the route from the tail, and its length [m].
    k : int
        Elements of the section; each piece between cuts gets at least one, the rest by length
        (as the sections share the strand's elements).

    Returns
    -------
    list of (length [m], elements, share fed upstream [-])
        The pieces tail -> head; the share is the sum of the shares of the feed points at or
        upstream of the piece's start (the material line load is the design load times it;
        1 without ``material.feed``: all fed at the tail).
    """
    feed = sorted(conv.material.feed or [], key=lambda f: f.at_m)
    end = start_m + length_m
    tol = 1e-9 * max(1.0, end)
    cuts = [c for c in route_cuts(conv) if start_m + tol < c < end - tol]
    bounds = [start_m, *cuts, end]
    # uncut, the piece is the section's own length: a section shorter than the rounding of its
    # end along the route (1e-17 m after 60 m) would otherwise be a piece of 0 m
    pieces = ([b - a for a, b in zip(bounds[:-1], bounds[1:], strict=True)] if cuts
              else [length_m])
    counts = _split(max(k, len(pieces)), pieces)
    out = []
    for a, piece, c in zip(bounds[:-1], pieces, counts, strict=True):
        fed = (sum(f.share for f in feed if f.at_m <= a + tol)
               if conv.material.feed is not None else 1.0)
        out.append((piece, c, min(fed, 1.0)))
    return out


def _heights(z: float, dz: float, k: int) -> tuple[list[float], float]:
    """Heights of ``k`` elements from ``z`` rising ``dz`` each (summed one by one), and the
    height after them."""
    out = []
    for _ in range(k):
        out.append(z)
        z += dz
    return out, z


def _strand_pulleys(conv: Conveyor) -> tuple[list, list]:
    """The pulleys along the strands as ``(at_m, 0 drive / 1 take-up, drive index or -1)``:
    the carry's booster drives tail -> head, the return's boosters and a take-up along it
    head -> tail (the take-up after the drives at its position)."""
    on_carry = sorted((float(d.at_m), 0, i) for i, d in enumerate(conv.drives)
                      if d.position == "carry")
    on_return = [(float(d.at_m), 0, i) for i, d in enumerate(conv.drives)
                 if d.position == "return"]
    if conv.takeup.position == "return":
        on_return.append((float(conv.takeup.at_m), 1, -1))
    on_return.sort(key=lambda p: (-p[0], p[1], p[2]))
    return on_carry, on_return


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
        fraction per carry profile section): see :func:`beltstudy.engine.conveyor.section_loads`. Each
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
    design_mL = conv.material.capacity_t_h / (3.6 * conv.speed_m_s)
    loads = section_loads(load_fraction, conv)
    w = belt.width_m
    carry_mass, carry_drag = catalog.idler_set_values(conv.idlers.carry, w)
    ret_mass, ret_drag = catalog.idler_set_values(conv.idlers.return_, w)
    ic, ir = conv.idlers.carry, conv.idlers.return_
    # the pitch: spacing_m, or the conveyor length over the number of sets (count)
    s_c, s_r = conv.idler_spacing_m("carry"), conv.idler_spacing_m("return")

    cols: dict[str, list] = {k: [] for k in (
        "strand", "dx", "z", "sin", "cos", "S", "D", "rolls", "trough", "mL", "mR", "drag")}

    def add(k=None, **values):
        """One element, or ``k`` equal elements at the heights in the list ``z``; a value for
        every column, by name."""
        if k is None:
            for key in cols:
                cols[key].append(values[key])
            return
        for key in cols:
            v = values[key]
            cols[key].extend(v if key == "z" else [v] * k)

    pulleys: list[Pulley] = []

    def add_pulley(code, position, drive, diameter, wrap, mu, mu_k, takeup, z_at, at_m=None):
        pulleys.append(Pulley(len(cols["dx"]), position, drive, diameter, wrap, mu, mu_k,
                              takeup, at_m))
        add(strand=code, dx=math.radians(wrap) * diameter / 2, z=z_at, sin=0.0, cos=1.0,
            S=math.inf, D=0.0, rolls=0, trough=0.0, mL=0.0, mR=0.0, drag=0.0)

    # the pulleys along the strands: booster drives (file order at one position) and a take-up
    # along the return (after the drives at its position)
    tol = 1e-6 * max(1.0, L)
    on_carry, on_return = _strand_pulleys(conv)
    cut_return = bool(on_return)
    cut_carry = bool(route_cuts(conv))

    def along(pending, x, z_at, reached):
        """Add the pending strand pulleys the belt has reached at route position x."""
        while pending and reached(pending[0][0], x):
            at, _, i = pending.pop(0)
            if i >= 0:
                d = conv.drives[i]
                add_pulley(BOOSTER, d.position, i, d.pulley_diameter_m, d.wrap_deg,
                           d.friction, d.mu_kinetic, False, z_at, at)
            else:
                add_pulley(TAKEUP, "return", -1, DEFAULT_PULLEY_DIAMETER_M, PLAIN_WRAP_DEG,
                           PLAIN_FRICTION, PLAIN_FRICTION, True, z_at, at)

    def upto(at, x):
        return at <= x + tol

    def downto(at, x):
        return at >= x - tol

    # carry strand, tail -> head (on vertical curves element by element, _curve_elements)
    z = 0.0
    x = 0.0
    pieces, arcs = _curve_elements(conv, counts)
    carry_el: list[int] = []
    for sec_i, dx, sin, cos, fed in pieces:  # vertical curves
        along(on_carry, x, z, upto)
        carry_el.append(len(cols["dx"]))
        add(strand=CARRY, dx=dx, z=z, sin=sin, cos=cos, S=s_c,
            D=ic.roll_diameter_m, rolls=ic.rolls, trough=ic.trough_deg,
            mL=design_mL * loads[sec_i] * fed, mR=carry_mass / s_c, drag=carry_drag)
        z += dx * sin
        x += dx
    s0 = 0.0
    for sec, k, frac in zip(conv.profile, counts, loads, strict=True):
        if pieces:  # straight sections only below
            break
        dx = sec.length_m / k
        sin = sec.lift_m / sec.length_m
        cos = math.sqrt(1.0 - sin * sin)
        if cut_carry:  # feed points and pulleys along the route: no element straddles one
            x = s0
            for sub_len, sub_k, fed in section_cuts(conv, s0, sec.length_m, k):
                along(on_carry, x, z, upto)
                zs, z = _heights(z, sub_len / sub_k * sin, sub_k)
                add(sub_k, strand=CARRY, dx=sub_len / sub_k, z=zs, sin=sin, cos=cos,
                    S=s_c, D=ic.roll_diameter_m, rolls=ic.rolls,
                    trough=ic.trough_deg, mL=design_mL * frac * fed,
                    mR=carry_mass / s_c, drag=carry_drag)
                x += sub_len
            s0 += sec.length_m
            continue
        zs, z = _heights(z, dx * sin, k)
        add(k, strand=CARRY, dx=dx, z=zs, sin=sin, cos=cos, S=s_c,
            D=ic.roll_diameter_m, rolls=ic.rolls, trough=ic.trough_deg, mL=design_mL * frac,
            mR=carry_mass / s_c, drag=carry_drag)
    along(on_carry, math.inf, z, upto)
    z_head = z
    nc = len(cols["dx"])

    def add_end(position, code, z_at, takeup_here):
        drives = [(i, d) for i, d in enumerate(conv.drives) if d.position == position]
        for i, d in drives:
            add_pulley(code, position, i, d.pulley_diameter_m, d.wrap_deg, d.friction,
                       d.mu_kinetic, False, z_at)
        if not drives:
            add_pulley(code, position, -1, DEFAULT_PULLEY_DIAMETER_M, PLAIN_WRAP_DEG,
                       PLAIN_FRICTION, PLAIN_FRICTION, takeup_here, z_at)

    # head end: the drives in file order (or one plain pulley), then a head take-up pulley
    add_end("head", HEAD, z_head, False)
    i_head = nc
    if conv.takeup.position == "head":
        add_pulley(TAKEUP, "head", -1, DEFAULT_PULLEY_DIAMETER_M, PLAIN_WRAP_DEG,
                   PLAIN_FRICTION, PLAIN_FRICTION, True, z_head)
    # return strand, head -> tail: the profile backwards, slope negated
    z = z_head
    x = L
    ret_el: dict[int, int] = {}
    for j in reversed(range(len(pieces))):
        _, dx, sin, cos, _fed = pieces[j]
        along(on_return, x, z, downto)
        ret_el[j] = len(cols["dx"])
        add(strand=RETURN, dx=dx, z=z, sin=-sin, cos=cos, S=s_r,
            D=ir.roll_diameter_m, rolls=ir.rolls, trough=ir.trough_deg, mL=0.0,
            mR=ret_mass / s_r, drag=ret_drag)
        z -= dx * sin
        x -= dx
    if not pieces:
        s1 = L
        for sec, k in zip(reversed(conv.profile), reversed(counts), strict=True):
            dx = sec.length_m / k
            sin = -sec.lift_m / sec.length_m
            cos = math.sqrt(1.0 - sin * sin)
            s1 -= sec.length_m
            parts = (reversed(section_cuts(conv, s1, sec.length_m, k)) if cut_return
                     else [(sec.length_m, k, 1.0)])
            x = s1 + sec.length_m
            for sub_len, sub_k, _fed in parts:
                along(on_return, x, z, downto)
                zs, z = _heights(z, sub_len / sub_k * sin, sub_k)
                add(sub_k, strand=RETURN, dx=sub_len / sub_k if cut_return else dx, z=zs,
                    sin=sin, cos=cos, S=s_r, D=ir.roll_diameter_m, rolls=ir.rolls,
                    trough=ir.trough_deg, mL=0.0, mR=ret_mass / s_r, drag=ret_drag)
                x -= sub_len
    along(on_return, -math.inf, z, downto)
    i_tail0 = len(cols["dx"])
    # tail end: a take-up pulley before the tail drives, or the plain tail pulley as take-up
    tail_driven = any(d.position == "tail" for d in conv.drives)
    if conv.takeup.position == "tail" and tail_driven:
        add_pulley(TAKEUP, "tail", -1, DEFAULT_PULLEY_DIAMETER_M, PLAIN_WRAP_DEG,
                   PLAIN_FRICTION, PLAIN_FRICTION, True, 0.0)
    add_end("tail", TAIL, 0.0, conv.takeup.position == "tail")
    curves = tuple(Curve(carry=np.asarray([carry_el[j] for j in c["carry_"]], dtype=np.int64),
                         ret=np.asarray([ret_el[j] for j in c["carry_"]], dtype=np.int64),
                         **{k: v for k, v in c.items() if k != "carry_"})
                   for c in arcs)
    return _assemble(conv, belt, cols, pulleys, nc, i_head, i_tail0, loads, design_mL, curves)


def _assemble(conv: Conveyor, belt, cols: dict[str, list], pulleys: list[Pulley], nc: int,
              i_head: int, i_tail0: int, loads: list[float], design_mL: float,
              curves: tuple) -> Loop:
    """The :class:`Loop` from :func:`build_loop`'s element columns and pulleys: ``nc`` carry
    elements (with the carry's pulleys), the head end from ``i_head``, the tail end from
    ``i_tail0``; positions round the loop and along the route, heights, the sag limits."""
    L = conv.length_m
    mG = belt.mass_kg_m
    n = len(cols["dx"])
    i_tail = n - 1
    i_takeup = next(p.element for p in pulleys if p.takeup)
    drive_elements = tuple(next(p.element for p in pulleys if p.drive == i)
                           for i in range(len(conv.drives)))

    arr = {k: np.asarray(v, dtype=np.float64) for k, v in cols.items()}
    dx_arr = arr["dx"]
    s = np.concatenate(([0.0], np.cumsum(dx_arr)[:-1]))
    z_arr = arr["z"]
    z_end = z_arr + dx_arr * arr["sin"]
    z_end[-1] = 0.0
    strand = np.asarray(cols["strand"], dtype=np.int8)
    # along the route: the carry from the tail, the return back from the head, pulleys where
    # they sit (without pulleys along the carry its elements' x is their s, bit for bit)
    idx = np.arange(n)
    x_carry = np.concatenate(([0.0], np.cumsum(np.where(strand == CARRY, dx_arr, 0.0))[:-1]))
    x_ret = L - np.concatenate(([0.0], np.cumsum(np.where(strand == RETURN, dx_arr, 0.0))[:-1]))
    x_arr = np.where(idx < i_head, x_carry, np.where(idx < i_tail0, x_ret, 0.0))
    return Loop(
        n=n,
        nc=nc,
        i_head=i_head,
        i_tail=i_tail,
        i_takeup=i_takeup,
        pulleys=tuple(pulleys),
        drive_elements=drive_elements,
        strand=strand,
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
        sag_limit=np.where(np.asarray(cols["strand"]) == CARRY, conv.sag_limit_pct.carry / 100,
                           np.where(np.asarray(cols["strand"]) == RETURN,
                                    conv.sag_limit_pct.return_ / 100, 1.0)),
        length_m=L,
        lift_m=conv.lift_m,
        load_fraction=float(sum(f * p.length_m for f, p in zip(loads, conv.profile,
                                                                strict=True)) / L),
        speed_m_s=float(conv.speed_m_s),
        belt=belt,
        design_load_kg_m=design_mL,
        section_load=loads,
        curves=curves,
        x_m=x_arr,
    )


def _curve_elements(conv: Conveyor, counts: list[int]) -> tuple[list, list]:
    """The carry elements of a route with vertical curves, tail -> head, and its curves.

    Each section keeps its automatic element size ``length / count``. A curve at the end of
    section i takes half its arc R |delta| from the end of section i and half from the start
    of section i + 1 (no element straddles the junction); each half is cut into elements no
    longer than its section's automatic size and turning at most :data:`CURVE_STEP_DEG` each;
    an element's slope is the arc's at its middle. The straight rest of each section keeps
    its grade, tangent to the arc; the arc rises by a hair less than the two straight halves
    it replaces (R (cos a1 - cos a2) against R |delta| (sin a1 + sin a2) / 2, a difference of
    order R delta^4), and that difference goes half to each section's straight rest, so the
    route keeps its length and its lift. A rest too short to take its half within the larger
    of :data:`CURVE_STEP_DEG` and its curves' own turn off its grade (a curve of nearly the
    largest radius its section holds leaves a rest of centimetres: 0.014 m took -0.021 m of
    lift, a sine of -1.46) turns by that much and leaves the rest of its half out
    (millimetres to centimetres of lift). The junction then lies off the grades' intersection
    by the curve's external distance R (sec(delta / 2) - 1), as on a real curve.

    Returns
    -------
    pieces : list of (section, dx_m, sin, cos, fed)
        One per carry element, ``fed`` the share of the capacity fed at or upstream of its
        start (1 without ``material.feed``); the straight rests are cut at
        :func:`route_cuts`; empty when no section has a curve (the caller then cuts the
        straight sections as before, bit for bit).
    arcs : list of dict
        Per curve the :class:`Curve` fields, with ``carry_`` its carry elements.
    """
    prof = conv.judged_profile()  # a curve shorter than an idler pitch is a grade change
    if all(sec.curve_radius_m is None for sec in prof):
        return [], []
    ang = [math.asin(sec.lift_m / sec.length_m) for sec in prof]
    step = math.radians(CURVE_STEP_DEG)

    def half_arc(length, a0, a1, dx_auto):
        m = max(1, math.ceil(length / dx_auto - 1e-9), math.ceil(abs(a1 - a0) / step - 1e-9))
        da = (a1 - a0) / m
        return [(length / m, math.sin(a), math.cos(a))
                for a in (a0 + (j + 0.5) * da for j in range(m))]

    # each curve's two halves (the out half in section i, the in half in section i + 1) and
    # the lift the straight halves would have had beyond the arc's
    out_half, in_half, excess = {}, {}, {}
    for i, sec in enumerate(prof):
        if sec.curve_radius_m is None:
            continue
        h = 0.5 * curve_arc_m(prof, i)
        mid = 0.5 * (ang[i] + ang[i + 1])
        out_half[i] = half_arc(h, ang[i], mid, sec.length_m / counts[i])
        in_half[i + 1] = half_arc(h, mid, ang[i + 1], prof[i + 1].length_m / counts[i + 1])
        arc = sum(d * s_ for d, s_, _ in out_half[i] + in_half[i + 1])
        excess[i] = h * (math.sin(ang[i]) + math.sin(ang[i + 1])) - arc
    feed = conv.material.feed
    cuts = route_cuts(conv)

    def fed(x: float) -> float:
        """Share of the capacity fed at or upstream of route position x [-]."""
        if feed is None:
            return 1.0
        return min(sum(f.share for f in feed if f.at_m <= x + 1e-9 * max(1.0, x)), 1.0)

    pieces: list = []
    arcs: list = []
    at = 0.0
    for i, (sec, k) in enumerate(zip(prof, counts, strict=True)):
        first, last = in_half.get(i, []), out_half.get(i, [])
        rest = sec.length_m - sum(d for d, _, _ in first + last)
        straight = []
        if rest > 1e-9 * sec.length_m:
            lift = (rest * sec.lift_m / sec.length_m
                    + 0.5 * (excess.get(i - 1, 0.0) + excess.get(i, 0.0)))
            # a rest a sliver long (a curve of nearly the largest radius its section holds)
            # cannot take its share of the excess: it turns off its grade by at most the
            # larger of an arc element's step and its curves' own turn, and what lift is
            # left over (centimetres, on such a sliver) is left out
            turn = max([step] + [abs(ang[j + 1] - ang[j]) for j in (i - 1, i)
                                 if j in excess])
            sin = min(max(lift / rest, math.sin(ang[i] - turn)), math.sin(ang[i] + turn))
            cos = math.sqrt(1.0 - sin * sin)
            # cut at the feed points and pulleys along the route (never on an arc: refused)
            a0 = at + sum(d for d, _, _ in first)
            tol = 1e-9 * max(1.0, a0 + rest)
            inner = [c - a0 for c in cuts if a0 + tol < c < a0 + rest - tol]
            bounds = [0.0, *inner, rest]
            for a, b in zip(bounds[:-1], bounds[1:], strict=True):
                m = max(1, round((b - a) / (sec.length_m / k)))
                straight += [((b - a) / m, sin, cos)] * m
        start = len(pieces)
        x = at
        for d, s_, c_ in first + straight + last:
            pieces.append((i, d, s_, c_, fed(x)))
            x += d
        if first:
            arcs[-1]["carry_"] += list(range(start, start + len(first)))
        at += sec.length_m
        if last:
            h = 0.5 * curve_arc_m(prof, i)
            arcs.append(dict(k=len(arcs) + 1, section=i, radius_m=float(sec.curve_radius_m),
                             angle_in_rad=ang[i], angle_out_rad=ang[i + 1], at_m=at,
                             start_m=at - h, end_m=at + h,
                             carry_=list(range(len(pieces) - len(last), len(pieces)))))
    return pieces, arcs


#: Share of a drive's reduced inertia taken as the motor's when a fluid coupling separates it
#: and ``motor_inertia_kg_m2`` is not given [-]: the motor rotor dominates the reduced inertia
#: through the square of the gear ratio (an estimate; give the motor's data).
MOTOR_INERTIA_SHARE = 2.0 / 3.0
#: Steel density for the pulley estimate [kg/m3].
STEEL_KG_M3 = 7850.0


def pulley_reduced_mass_kg(diameter_m: float, belt_width_m: float) -> float:
    """Estimated reduced mass of a pulley at the belt line [kg].

    A welded drum pulley is modelled as a thin steel shell of diameter D, face B + 0.2 m and
    wall 12 mm + 1 % of D, plus 30 % for the end discs (a thin shell has J (2/D)^2 = m).
    An estimate, not a catalogue value: give ``DynamicsOptions.pulley_mass_kg`` when the
    pulley data are known.

    Parameters
    ----------
    diameter_m : float
        Pulley diameter D [m].
    belt_width_m : float
        Belt width B [m].
    """
    wall = 0.012 + 0.01 * diameter_m
    return 1.3 * STEEL_KG_M3 * math.pi * diameter_m * (belt_width_m + 0.2) * wall


@dataclass(frozen=True)
class RotatingParts:
    """Rotating parts reduced to the belt line [kg]: the mass of each shaft (by pulley
    element: every drive pulley, and the braked and holdback pulleys), the drive of each
    shaft, each drive's motor mass behind a fluid coupling (0 without), and the own mass of
    each plain pulley that turns with the belt."""

    shaft_mass: dict
    shaft_drive: dict
    motor_mass: list
    plain_mass: dict

    @property
    def total_kg(self) -> float:
        return float(sum(self.shaft_mass.values()) + sum(self.motor_mass)
                     + sum(self.plain_mass.values()))


def _drive_given_kg(d) -> tuple[float, float | None]:
    """A drive's given inertia at the belt line on its pulley shaft, ``(J + J_flywheel) (2 /
    D)^2`` less the motor's part behind a fluid coupling [kg], and that motor inertia
    ``J_motor`` [kg m2] (``motor_inertia_kg_m2``, default ``MOTOR_INERTIA_SHARE`` of
    ``inertia_kg_m2``; None without a coupling)."""
    red = (2.0 / d.pulley_diameter_m) ** 2
    total = (d.inertia_kg_m2 + d.flywheel_kg_m2) * red
    if d.coupling == "none":
        return total, None
    j_m = (d.motor_inertia_kg_m2 if d.motor_inertia_kg_m2 is not None
           else MOTOR_INERTIA_SHARE * d.inertia_kg_m2)
    return max(total - j_m * red, 0.0), j_m


def rotating_parts(conv: Conveyor, loop: Loop, pulley_mass_kg: float | None = None
                   ) -> RotatingParts:
    """The rotating parts of a conveyor (:class:`RotatingParts`).

    A drive's shaft carries ``(J + J_flywheel) (2 / D)^2`` (at least the pulley's own shell,
    :func:`pulley_reduced_mass_kg`); with a fluid coupling the motor's part ``J_motor (2 /
    D)^2`` (``motor_inertia_kg_m2``, default ``MOTOR_INERTIA_SHARE`` of ``inertia_kg_m2``) is
    a separate mass behind the coupling. A braked or holdback pulley without a drive is a
    shaft of its own shell; every other plain pulley's shell turns with the belt.
    """
    width = loop.belt.width_m

    def shell(node: int) -> float:
        if pulley_mass_kg is not None:
            return float(pulley_mass_kg)
        return pulley_reduced_mass_kg(loop.pulley_at(node).diameter_m, width)

    shaft_mass, shaft_drive, motor = {}, {}, []
    for i, d in enumerate(conv.drives):
        node = int(loop.drive_elements[i])
        total, j_m = _drive_given_kg(d)
        m_motor = 0.0 if j_m is None else max(j_m * (2.0 / d.pulley_diameter_m) ** 2, 1.0)
        shaft_mass[node] = max(total, pulley_reduced_mass_kg(d.pulley_diameter_m, width))
        shaft_drive[node] = i
        motor.append(m_motor)
    extra = [loop.brake_element(b) for b in conv.brakes]
    if conv.holdback:
        extra.append(loop.i_head)
    for node in extra:
        if node not in shaft_mass:
            shaft_mass[node] = shell(node)
    plain = {p.element: shell(p.element) for p in loop.pulleys if p.element not in shaft_mass}
    return RotatingParts(shaft_mass, shaft_drive, motor, plain)


__all__ += ["shell_floor_notes"]


def shell_floor_notes(conv: Conveyor, loop: Loop) -> list[str]:
    """What :func:`rotating_parts` said nothing of: a drive whose given inertia, reduced to
    the belt line on its pulley shaft (``(J + J_flywheel) (2 / D)^2``, less the motor's part
    behind a fluid coupling; a drive that gives neither field, or both 0, is not told), is below the estimate of its pulley's own shell
    (:func:`pulley_reduced_mass_kg`): the shaft is given the shell's mass instead, since the
    given J cannot hold less than the pulley it turns. One note per such drive, with the given
    and the used reduced masses [kg] and the inertia that would have given the used one."""
    width = loop.belt.width_m
    out = []
    for i, d in enumerate(conv.drives):
        if d.inertia_kg_m2 == 0.0 and d.flywheel_kg_m2 == 0.0:
            # nothing given: the shell is the estimate of the pulley asked for (by value, not
            # model_fields_set: a study's runs are validated from the whole dumped conveyor)
            continue
        red = (2.0 / d.pulley_diameter_m) ** 2
        given, j_m = _drive_given_kg(d)
        motor = ("" if j_m is None else
                 f", less the motor's {gnum(j_m)} kg m2 behind the fluid coupling")
        shell = pulley_reduced_mass_kg(d.pulley_diameter_m, width)
        if given >= shell:
            continue
        out.append(
            f"drive {i + 1}'s given inertia (drives.{i}.inertia_kg_m2 {d.inertia_kg_m2:g} kg m2"
            + (f" + flywheel_kg_m2 {d.flywheel_kg_m2:g}" if d.flywheel_kg_m2 else "")
            + f"{motor}) is {gnum(given)} kg at the belt line (x (2 / D)^2, D "
            f"{d.pulley_diameter_m:g} m), below the estimate of its pulley's own shell, "
            f"{gnum(shell)} kg (a steel drum of D {d.pulley_diameter_m:g} m, face B + 0.2 m, wall "
            "12 mm + 1 % of D, + 30 % for the end discs: pulley_reduced_mass_kg), so the run "
            f"used {gnum(shell)} kg on that shaft ({gnum(shell / red)} kg m2 at the pulley); an "
            "inertia_kg_m2 with the pulley, gearbox and motor in it, from the drive's data, "
            "sets it")
    return out
