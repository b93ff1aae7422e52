"""What a braked pulley can pass in a brake stop (PHYSICS 5.1, capstan).

A brake acts on a pulley shaft, so the belt receives the brake force only through the pulley's
friction: ``|T_out - T_in| <= T_slack (e^(mu theta) - 1)``, ``T_slack`` the lower of the
pulley's two tensions *during the stop*. A brake holds the belt back, so its pulley's slack
side is the incoming one (on a head pulley the carry strand at the head), and that tension
falls as the brake decelerates the belt.

The tensions of the stop are walked like statics' running ones (:mod:`beltstudy.engine.statics`),
with the belt as a rigid body decelerating at ``d = (Te + sum F_b) / M`` (the deceleration
the auto force is sized for, :func:`beltstudy.engine.design.brake_force_auto`): each element
adds its running resistance and gravity component and loses its inertia force ``m_j d``
(``m_j`` with the idler rolls and the plain pulleys' shells), each shaft (drive pulley, braked
pulley) takes ``f_k = F_k - m_k d`` from the belt (its brake force less what decelerates its
own rotating parts, motor included), and the walk starts at the take-up, whose carriage holds
the mean of its two strands at the running value (a gravity take-up's weight; a fixed
take-up's pretension, held here as well: the loop-length change of a stop is not walked). The
walk from the take-up to a braked pulley's incoming side crosses the strands between them, so
the position of the take-up and of the brake set the slack side: a head brake with a tail
take-up loses the whole carry strand's inertia force, ``T_in = T_tu + sum (R + G) - d sum m``.

The stop's fronts (the drives' trip, the brake's application) are suddenly applied loads: the
slack side is taken at the running tension less :data:`FRONT_FACTOR` x its quasi-static fall,
the falls of the stop's loads (the trip, each brake) counted one by one and a load's rise
not set against them (:meth:`StopWalk.slack_n`), and the largest force a pulley passes, ``f = T_slack (e^(mu theta) - 1)``, is found by bisection on
the brake force (the slack side falls as the force grows).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace

import numpy as np

from beltstudy.engine.drives import down3, up3
from beltstudy.engine.loop import G, Loop, rotating_parts
from beltstudy.engine.wording import gnum

__all__ = ["BRAKE_GRIP_MARGIN", "FRONT_FACTOR", "StopWalk", "brake_grip_n", "grip_limits",
           "grip_remedies", "kn_figure", "pulley_name", "takeup_at_least"]

#: Dynamic factor on the fall of a braked pulley's slack-side tension [-]. The walk above is
#: quasi-static; the stop's fronts (the drives' trip, the brake) are suddenly applied loads,
#: and the response of an undamped elastic system to a suddenly applied load reaches twice its
#: static change (the dynamic load factor of a step, Biggs, *Introduction to Structural
#: Dynamics*, 1964, ch. 2; Clough and Penzien, *Dynamics of Structures*, ch. 4). The slack side
#: is therefore taken at ``T_run - 2 (T_run - T_stop)``: the margin kept is the whole
#: overshoot an undamped belt could make (the belt's damping keeps the real dip above it).
FRONT_FACTOR = 2.0
#: Extra margin on the capstan limit itself [-]: none, the friction is the file's static one
#: and the front factor above is the margin.
BRAKE_GRIP_MARGIN = 1.0


@dataclass(frozen=True, eq=False)
class StopWalk:
    """The tensions of a rigid-body brake stop as linear functions of the brake forces.

    Attributes
    ----------
    loop : Loop
    base : ndarray
        Running resistance plus gravity component per element [N].
    inertia : ndarray
        Mass per element decelerating with the belt (belt, material, idler rolls, plain
        pulley shells) [kg].
    shaft : dict
        Element -> reduced mass of each shaft (drive pulleys with their motors, braked
        pulleys) [kg].
    takeup_n : float
        Mean tension of the take-up's two strands [N].
    running : ndarray
        Steady running boundary tensions [N], the level the stop's fronts start from.
    """

    loop: Loop
    base: np.ndarray
    inertia: np.ndarray
    shaft: dict
    takeup_n: float
    running: np.ndarray

    @classmethod
    def of(cls, conv, steady) -> StopWalk:
        """The walk of a conveyor's brake stop from its steady solution."""
        loop = steady.loop
        parts = rotating_parts(conv, loop)
        inertia = loop.mass_kg.copy()
        for node, m in parts.plain_mass.items():
            inertia[node] += m
        shaft = dict(parts.shaft_mass)
        for node, i in parts.shaft_drive.items():
            shaft[node] += parts.motor_mass[i]
        base = np.asarray(steady.resistance_n, dtype=float) + loop.gravity_n
        return cls(loop, base, inertia, shaft, float(steady.takeup_tension_n),
                   np.asarray(steady.tension_n, dtype=float))

    def at_takeup(self, takeup_n: float) -> StopWalk:
        """The same walk with the take-up at ``takeup_n`` [N]: a take-up's tension adds to
        every running tension of the loop alike (the shift :meth:`slack_n` applies)."""
        return replace(self, takeup_n=float(takeup_n),
                       running=self.running + (float(takeup_n) - self.takeup_n))

    @property
    def mass_kg(self) -> float:
        """All moving mass at the belt line [kg]."""
        return float(self.inertia.sum()) + float(sum(self.shaft.values()))

    @property
    def te_n(self) -> float:
        """Resistances plus gravity, the force that decelerates the belt unbraked [N]."""
        return float(self.base.sum())

    def decel(self, forces: dict) -> float:
        """Rigid-body deceleration with the brake forces ``{element: N}`` [m/s2]."""
        return (self.te_n + sum(forces.values())) / self.mass_kg

    def tensions(self, forces: dict, takeup_n: float | None = None) -> np.ndarray:
        """Boundary tensions of the stop (``T[j]`` at the end of element ``j``) [N], with the
        brake forces ``{element: N}`` at full force and the take-up at ``takeup_n``."""
        loop = self.loop
        d = self.decel(forces)
        inc = self.base - self.inertia * d
        for node in set(self.shaft) | set(forces):
            inc[node] += forces.get(node, 0.0) - self.shaft.get(node, 0.0) * d
        n = loop.n
        k = loop.i_takeup
        order = (k + np.arange(n)) % n  # from the take-up element round to the one entering it
        out = np.empty(n)
        out[order] = np.cumsum(inc[order])  # T[j] - T[k-1]; the walk closes: out[k-1] = 0
        # the carriage holds the mean of the take-up's two strands: T[k-1] + T[k] = 2 T_tu
        t_tu = self.takeup_n if takeup_n is None else takeup_n
        return out - out[k - 1] + t_tu - 0.5 * inc[k]

    def pulley(self, node: int, forces: dict, takeup_n: float | None = None
               ) -> tuple[float, float, float]:
        """``(T_in, T_out, f)`` at a pulley element [N]: its two tensions and the force the
        belt passes to it against the motion (``T_out - T_in``)."""
        t = self.tensions(forces, takeup_n)
        t_in, t_out = float(t[node - 1]), float(t[node])
        return t_in, t_out, t_out - t_in

    def slack_n(self, node: int, forces: dict, takeup_n: float | None = None,
                front: float = FRONT_FACTOR) -> tuple[float, float]:
        """``(T_slack, f)`` at a pulley [N]: the lower of its two tensions in the stop, each the
        running one less ``front`` (:data:`FRONT_FACTOR`) x the falls the stop's loads bring
        it, and the force it passes against the motion.

        The walk is linear in the stop's loads (the drives' trip, each brake), and each is a
        suddenly applied load whose undamped response swings between 0 and ``front`` x its
        static change. A load's fall therefore counts doubled and a load's rise counts for
        nothing: at the moment another load's fall peaks, a rise's own swing may be back at
        0. Netting the rise against the fall is the unsafe side of the same bound. On a 3 km
        regenerating decline with a head drive and a tail brake, the trip raises the tail's
        slack side by 8.8 kN while the brake lowers it by 74.2 kN; the net fall doubled left
        the slack side at 197.6 kN, where the simulated stop dipped to 193 kN as the brake
        came on and the pulley slid. Counting a rise once its front has arrived (a rule tried
        before this one) let a 2.2 km decline's tail brake grow from 576.5 to 638.2 kN as its
        delay passed the trip's arrival, and that brake slid 2.2-2.8 m."""
        shift = 0.0 if takeup_n is None else takeup_n - self.takeup_n
        r_in = float(self.running[node - 1]) + shift
        r_out = float(self.running[node]) + shift
        b_in, b_out, _ = self.pulley(node, {}, takeup_n)  # the drives' trip alone
        fall_in = max(r_in - b_in, 0.0)
        fall_out = max(r_out - b_out, 0.0)
        for where, force in forces.items():
            if force == 0.0:
                continue
            o_in, o_out, _ = self.pulley(node, {where: force}, takeup_n)
            fall_in += max(b_in - o_in, 0.0)
            fall_out += max(b_out - o_out, 0.0)
        f = self.pulley(node, forces, takeup_n)[2]
        return min(r_in - front * fall_in, r_out - front * fall_out), f

    def room_n(self, node: int, forces: dict, *, euler: float | None = None,
               takeup_n: float | None = None, margin: float = BRAKE_GRIP_MARGIN) -> float:
        """What the pulley at ``node`` could pass beyond what it passes with ``forces`` [N]:
        ``T_slack (e^(mu theta) - 1) / margin - |f|`` (negative: it slides)."""
        e = self.loop.pulley_at(node).euler if euler is None else euler
        low, f = self.slack_n(node, forces, takeup_n)
        return max(low, 0.0) * (e - 1.0) / margin - abs(f)

    def grip_n(self, node: int, forces: dict, margin: float = BRAKE_GRIP_MARGIN) -> float:
        """The largest brake force at ``node`` [N] its pulley passes in the stop
        (:meth:`room_n` >= 0), the other brakes at ``forces`` (``node``'s entry replaced):
        bisection, the room falls as the force grows; 0 when even no brake force fits."""
        others = {n: f for n, f in forces.items() if n != node}

        def room(force: float) -> float:
            return self.room_n(node, {**others, node: force}, margin=margin)

        if room(0.0) < 0.0:
            return 0.0
        hi = max(self.te_n, 1e3)
        while room(hi) >= 0.0:
            hi *= 2.0
            if hi > 1e12:
                return math.inf
        lo = 0.0
        for _ in range(60):
            mid = 0.5 * (lo + hi)
            lo, hi = (mid, hi) if room(mid) >= 0.0 else (lo, mid)
        return lo


def brake_grip_n(conv, steady, nodes: tuple, forces: tuple, node: int) -> float:
    """The largest brake force [N] the pulley at ``node`` passes in a brake stop
    (:meth:`StopWalk.grip_n`, the undamped bound), the run's brakes at elements ``nodes`` with
    their full forces ``forces`` [N] (auto sizes in) as the others; 0 when it passes none.
    The run's stop-slip words read it (``System.brake_grip``) so that they do not offer less
    force on a pulley that would still slide at the force that holds the loaded belt."""
    fixed: dict = {}
    for n, f in zip(nodes, forces, strict=True):
        fixed[int(n)] = fixed.get(int(n), 0.0) + float(f)
    return StopWalk.of(conv, steady).grip_n(int(node), fixed)


def grip_limits(walk: StopWalk, nodes: list[int], fixed: dict, wanted: float,
                margin: float = BRAKE_GRIP_MARGIN) -> tuple[list[float], bool]:
    """Forces [N] of auto brakes on ``nodes`` sharing ``wanted`` [N] evenly, each within its
    pulley's grip beside the others and the fixed brakes ``fixed`` ``{element: N}``: a brake
    held at its grip hands the rest to the others (water-filling ``f_i = min(cap_i, L)``,
    ``sum f = wanted``, the caps recomputed with the others' forces until they settle).
    Returns the forces and whether the grip held any of them below the even share."""
    n = len(nodes)
    force = [wanted / n] * n
    caps = [math.inf] * n
    # to 1e-9 of the whole: a cap falls as the other brakes' forces rise (each brake's fall
    # at the other's slack side), so the shares approach their fixed point from above, and
    # to 1e-6 a head brake stood 0.06 N past its own grip (its check's tolerance 0.024 N)
    for _ in range(200):
        for i, node in enumerate(nodes):
            acting = dict(fixed)
            for j, other in enumerate(nodes):
                if j != i:
                    acting[other] = acting.get(other, 0.0) + force[j]
            caps[i] = max(walk.grip_n(node, acting, margin) - acting.get(node, 0.0), 0.0)
        new = _water_fill(caps, wanted)
        moved = max(abs(a - b) for a, b in zip(new, force, strict=True))
        force = new
        if moved <= 1e-9 * max(wanted, 1.0):
            break
    return force, any(f < wanted / n * (1.0 - 1e-9) for f in force)


def _water_fill(caps: list[float], wanted: float) -> list[float]:
    """``min(cap_i, L)`` with the level L that sums to ``wanted`` (every cap when they sum to
    less)."""
    finite = [c for c in caps if math.isfinite(c)]
    if len(finite) == len(caps) and sum(finite) <= wanted:
        return list(caps)
    lo, hi = 0.0, wanted
    for _ in range(100):
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if sum(min(c, mid) for c in caps) < wanted else (lo, mid)
    return [min(c, hi) for c in caps]


def takeup_at_least(tension_n: float, g: float | None = None) -> str:
    """The least take-up a grip note advises, rounded up so the advice passes: with ``g`` a
    counterweight holding ``tension_n`` [N] on each strand, ``2 T / g`` in whole kilograms
    (``30,046 kg``), else a pretension in kN at four significant figures (``147.4 kN``).
    Rounded to the nearest, a decline's head brake needing 30 045.3 kg was advised
    '30,045 kg', which left its pulley 3 N short and repeated the same advice."""
    if g is not None:
        return f"{math.ceil(2.0 * tension_n / g * (1.0 - 1e-12)):,} kg"
    kn = tension_n / 1e3
    if not (kn > 0.0) or not math.isfinite(kn):
        return f"{gnum(kn)} kN"
    step = 10.0 ** (math.floor(math.log10(kn)) - 3)
    return f"{float(f'{gnum(math.ceil(kn / step * (1.0 - 1e-12)) * step)}'):g} kN"


def pulley_name(conv, loop: Loop, node: int) -> str:
    """A pulley in words: ``drive N's pulley (head)``, ``the head pulley``, ``the tail
    pulley``."""
    p = loop.pulley_at(node)
    if p.drive >= 0:
        return f"drive {p.drive + 1}'s pulley ({p.where})"
    return f"the {p.where} pulley"


def kn_figure(force_n: float, *, up: bool) -> str:
    """A force [N] in kN to 4 significant figures, rounded ``up`` (a brake force that must make
    up a whole: rounded down it could fall short by the rounding) or down (a force found to
    hold its pulley: a smaller one holds too, a larger one might not);
    :func:`beltstudy.engine.drives.up3` and ``down3`` at 4 figures."""
    kn = force_n / 1e3
    if kn <= 0.0:
        return "0"
    return f"{gnum((up3 if up else down3)(kn, 4))}"


def _bisect_up(ok, lo: float, hi: float, rel: float = 0.0) -> float | None:
    """The least x in [lo, hi] with ``ok(x)`` (monotone), None when ``ok(hi)`` fails; to
    ``rel`` of x where given (else 60 halvings)."""
    if not ok(hi):
        return None
    for _ in range(60):
        if hi - lo <= rel * hi:
            break
        mid = 0.5 * (lo + hi)
        lo, hi = (lo, mid) if ok(mid) else (mid, hi)
    return hi


def grip_remedies(conv, steady, walk: StopWalk, nodes: list[int], fixed: dict,
                  asked: list[float], sized: list[float]) -> str:
    """What would let the brakes pass the forces ``asked`` [N] (one per auto brake on
    ``nodes``; ``sized``: the grip-limited ones), in words: a brake on another pulley, a
    heavier take-up (its mass or pretension), more wrap on the braked pulleys (drive pulleys
    only: a plain pulley has no wrap field)."""
    loop = walk.loop
    acting = dict(fixed)
    for node, f in zip(nodes, asked, strict=True):
        acting[node] = acting.get(node, 0.0) + f
    out = []
    # another pulley beside the auto brakes: a brake there changes their pulleys' stop
    # tensions, so they are sized again beside it (grip_limits, the auto share being what
    # the stop asks less the new brake): its force is the least that makes up the whole
    # with them. A 3 km decline's tail brake (372.9 kN at its grip, 476.3 kN asked) was told
    # 103.3 kN on the head drive's shaft; given, the tail brake fell to 328.5 kN, the stop
    # missed again and the note asked for 44.47 kN more.
    wanted = sum(asked)
    short = wanted - sum(sized)
    best: tuple | str | None = None

    def beside(node: int, x: float) -> tuple[dict, float]:
        """The brakes acting with ``x`` [N] at ``node`` and the auto ones sized again
        beside it, and the auto brakes' sum [N]."""
        given = {**fixed, node: fixed.get(node, 0.0) + x}
        forces, _capped = grip_limits(walk, nodes, given, max(wanted - x, 0.0))
        held = dict(given)
        for n, f in zip(nodes, forces, strict=True):
            held[n] = held.get(n, 0.0) + f
        return held, sum(forces)

    for node in dict.fromkeys([loop.i_head, *loop.drive_elements, loop.i_tail]):
        if node in nodes:
            continue
        p = loop.pulley_at(node)
        name = (f"a brake on drive {p.drive + 1}'s shaft ({p.where})" if p.drive >= 0
                else f"a brake on the {p.where} pulley")
        x = _bisect_up(lambda x, node=node: x + beside(node, x)[1] >= wanted * (1.0 - 1e-9),
                       short, wanted, rel=1e-5)
        x = wanted if x is None else x
        held, auto = beside(node, x)
        # what the pulley passes in all, a given brake already acting through it included
        # (a 60 kN head brake beside 86.03 kN offered on the head drive's shaft: 146 kN
        # through a pulley that passes 103.2 kN, which slid 3.5 s when followed)
        extra = walk.grip_n(node, held)
        there = fixed.get(node, 0.0)
        given = (f" in all ({gnum(there / 1e3)} kN is given there already)" if there > 0.0
                 else "")
        if extra >= x + there:
            out.append(f"{name} of {kn_figure(x, up=True)} kN beside these (its pulley passes up "
                       f"to {gnum(extra / 1e3)} kN{given}; the auto brakes then "
                       f"{gnum(auto / 1e3)} kN, sized again within their grip beside it)")
            break
        if best is None or extra - x - there > best[1] - best[2] - best[3]:
            best = (name, extra, x, there, given, auto)
    else:
        # the auto brakes' own figure beside it, so the reader tells the share from the whole
        # (a decline's tail brake "would need 652 kN beside the auto brakes", 652 kN being
        # the whole stop force, the auto brakes then 0 kN)
        best = best and (f" (not by a brake on another pulley alone: {best[0]} would need "
                         + (f"{gnum(best[2] / 1e3)} kN beside the auto brakes, then "
                            f"{gnum(best[5] / 1e3)} kN sized again within their grip beside it"
                            if best[5] > 0.0 else
                            f"the whole {gnum(best[2] / 1e3)} kN itself, the auto brakes then "
                            "none")
                         + f", and its pulley passes at most {gnum(best[1] / 1e3)} kN{best[4]})")
    # a heavier take-up: every tension rises with it
    t0 = walk.takeup_n
    t_need = _bisect_up(lambda t: all(walk.room_n(n, acting, takeup_n=t) >= 0.0
                                      for n in dict.fromkeys(nodes)), t0, 100.0 * t0 + 1e6)
    if t_need is not None:
        if conv.takeup.type == "gravity":
            out.append(f"a take-up of {takeup_at_least(t_need, G)} (takeup.mass_kg)")
        else:
            out.append(f"a take-up pretension of {takeup_at_least(t_need)} (takeup.pretension_kn)")
    # more wrap on each braked pulley: a drive pulley's (drives[i].wrap_deg); a plain pulley
    # has no wrap field (it is taken as 180 deg), so no wrap is offered where one is braked
    wraps = []
    for node in dict.fromkeys(nodes):
        p = loop.pulley_at(node)
        low, f = walk.slack_n(node, acting)
        if low <= 0.0 or p.drive < 0:
            wraps = []
            break
        e = 1.0 + abs(f) * BRAKE_GRIP_MARGIN / low
        if math.degrees(math.log(e) / p.friction) >= 359.5:
            # no pulley wraps a full turn (a file refuses it): a decline was offered 377 deg
            wraps = []
            break
        wraps.append(f"{math.degrees(math.log(e) / p.friction):.0f} deg on "
                     f"{pulley_name(conv, loop, node)} (drives.{p.drive}.wrap_deg, now "
                     f"{p.wrap_deg:g})")
    if wraps:
        out.append("a wrap of " + ", ".join(wraps))
    said = "; or ".join(out) if out else "none of a heavier take-up or more wrap"
    return said + (best if isinstance(best, str) else "")
