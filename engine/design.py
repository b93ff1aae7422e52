"""The auto sizes of a conveyor at one operating case: take-up, rated power, brakes.

:func:`auto_sizes` is the one place that says what an ``auto`` field of the conveyor file
becomes, and which constraint set it. :func:`beltstudy.engine.sizing.size_over_cases` calls it
once per design case and keeps the largest values (a study holds them for all runs of a
conveyor design); ``run_one`` calls it on the run's own steady solution to report the sizes it
used.

* **Take-up** (gravity ``mass_kg: auto``, fixed ``pretension_kn: auto``): the steady solve's
  sizing (:mod:`beltstudy.engine.statics`): the smallest take-up meeting slip at start-up
  (the start-up force and, gravity take-ups, breakaway: the drives taking the net gravity pull
  at standstill, a regenerating belt's start) and running, and the sag limits running and,
  unless ``takeup.sag_at_rest`` is off, held at rest. Governing constraint: ``slip_start``,
  ``slip_breakaway``, ``slip_running``, ``sag_running``, ``sag_at_rest``.
* **Rated power** (``rated_power_kw`` omitted): ``RATED_POWER_FACTOR`` x the motor power
  (through the drive train's ``efficiency``: ``F v / eta`` driving, ``|F v| eta``
  regenerating) of the drive's share of the larger of the steady peripheral force |Te| and the
  running resistance (a regenerating decline's motors must still overcome the resistance of
  the empty belt's start). Governing:
  ``peripheral_force`` or ``running_resistance``.
* **Brakes** (``force_kn: auto``): the total brake force for a rigid-body stop in the
  scenario's stop time after the brake delay and over its ramp (:func:`brake_force_auto`), at
  least ``HOLD_MARGIN`` x the net downhill pull of the loaded belt, less the fixed brakes,
  shared evenly by the auto brakes (within their pulleys' grip in a brake stop, where an even
  share is beyond one pulley's grip and the others have room). Its sizing input is the stop
  time: a run that stops on its brakes (``stop.mode: brake``) sizes them for its stop time
  (``stop_time``, or ``holding`` where the holding floor is larger); any other run uses no
  stop time and installs the holding size (``holding``).

The rotating parts (:func:`rotating_parts`) and these rules are the ones the transient model
builds with (:func:`beltstudy.engine.dynamics.model.build_system`), so a size reported here is the size
a run used.
"""

from __future__ import annotations

import math

import numpy as np

from beltstudy.engine.checks import HOLD_MARGIN
from beltstudy.engine.conveyor import FORCE_MAX_KN, Conveyor, Scenario
from beltstudy.engine.drives import GIVEN, RATED_POWER_FACTOR, rated_power_kw
from beltstudy.engine.loop import (
    MOTOR_INERTIA_SHARE,
    G,
    RotatingParts,
    pulley_reduced_mass_kg,
    rotating_parts,
)
from beltstudy.engine.statics import SteadyResult, lever_words, solve_steady
from beltstudy.engine.stopgrip import (
    StopWalk,
    _bisect_up,
    grip_limits,
    grip_remedies,
    pulley_name,
    takeup_at_least,
)
from beltstudy.engine.wording import gnum

__all__ = ["auto_sizes", "summary_fields", "RATED_POWER_FACTOR", "HOLD_MARGIN",
           "MOTOR_INERTIA_SHARE", "moving_mass_kg", "rotating_parts", "RotatingParts",
           "pulley_reduced_mass_kg", "rated_power_kw", "brake_forces", "brake_force_auto",
           "brake_stop_time", "brake_profile", "brake_grip_kn", "brake_kn_within_grip", "GIVEN",
           "takeup_lever"]



def moving_mass_kg(conv: Conveyor, steady: SteadyResult) -> float:
    """All moving mass reduced to the belt line [kg], as the transient model builds it: belt,
    material and idler rolls ``(m'_G + m'_L + m'_R) dx`` round the loop and the rotating
    parts (:func:`rotating_parts`)."""
    loop = steady.loop
    return float(loop.mass_kg.sum()) + rotating_parts(conv, loop).total_kg


def brake_force_auto(total_mass_kg: float, v_d: float, te_n: float, stop_s: float,
                     delay_s: float, ramp_s: float = 0.0,
                     curve: tuple[tuple[float, float], ...] | None = None) -> float:
    """Total brake force for a rigid-body stop in ``stop_s`` [N] (no holding minimum).

    The belt coasts for ``delay_s`` decelerating at ``Te / M`` (accelerating when Te < 0, a
    regenerative belt), then the brake force builds linearly from zero over ``ramp_s`` = r to
    ``F_b`` and holds (:mod:`beltstudy.engine.dynamics.brakes`). Over the braking time
    ``t_b = t_stop - t_delay`` the momentum after the delay, ``M v_1`` with
    ``v_1 = v - Te t_delay / M``, equals the resistance's impulse ``Te t_b`` plus the brake's,
    the integral of its force history:

    * ``t_b >= r`` (the ramp ends before the stop): ``M v_1 = Te t_b + F_b (t_b - r / 2)``;
    * ``t_b < r`` (the belt stops on the ramp, the force there ``F_b t / r``):
      ``M v_1 = Te t_b + F_b t_b^2 / (2 r)``.

    Parameters
    ----------
    total_mass_kg : float
        All moving mass reduced to the belt line [kg].
    v_d : float
        Design speed [m/s].
    te_n : float
        Steady peripheral force (resistance + gravity) [N].
    stop_s, delay_s, ramp_s : float
        Target stop time, brake delay and ramp [s].
    curve : tuple of (float, float), optional
        The brakes' force history instead of the ramp (:func:`brake_profile`): fraction of
        ``F_b`` against the time since application [s, -]; the brake's impulse is then
        ``F_b`` times its integral over ``t_b``.

    Returns
    -------
    float
        ``F_b`` [N]: 0 when the belt coasts to rest in time on its own, inf when the stop time
        is not longer than the delay (no force stops it; run inputs refuse that,
        :func:`beltstudy.engine.dynamics.model.build_system`).
    """
    if not math.isfinite(stop_s):
        return 0.0
    v1 = v_d - te_n * delay_s / total_mass_kg
    if v1 <= 0.0:
        return 0.0
    t_b = stop_s - delay_s
    if t_b <= 0.0:
        return math.inf
    need = total_mass_kg * v1 - te_n * t_b  # the impulse the brake must give [N s]
    impulse_per_n = brake_impulse_per_n(t_b, ramp_s, curve)
    if impulse_per_n <= 0.0:
        return math.inf if need > 0.0 else 0.0
    return max(need / impulse_per_n, 0.0)


def brake_impulse_per_n(t_b: float, ramp_s: float = 0.0,
                        curve: tuple[tuple[float, float], ...] | None = None) -> float:
    """The impulse of a brake of 1 N over ``t_b`` [s] from its application [N s / N]: the
    integral of its force history, ``t_b - r / 2`` past a ramp of ``ramp_s`` = r,
    ``t_b^2 / (2 r)`` on it, or the integral of ``curve`` (:func:`brake_profile`)."""
    if t_b <= 0.0:
        return 0.0
    if curve is not None:
        return _profile_integral(curve, t_b)
    if t_b >= ramp_s:
        return t_b - 0.5 * ramp_s
    return t_b * t_b / (2.0 * ramp_s)


def brake_stop_time(total_mass_kg: float, v_d: float, te_n: float, force_n: float,
                    delay_s: float, ramp_s: float = 0.0,
                    curve: tuple[tuple[float, float], ...] | None = None) -> float:
    """Rigid-body stop time with a brake force ``force_n`` [s] (the inverse of
    :func:`brake_force_auto`, the stop on the ramp or past it; inf if the belt does not stop;
    with ``curve``, the first zero of the momentum under that force history, segment by
    segment).

    On the ramp the speed is ``v_1 - Te t / M - F_b t^2 / (2 r M)``, whose one positive root is
    the stop when it is at most r; past it ``t_b = (M v_1 + F_b r / 2) / (Te + F_b)``."""
    v1 = v_d - te_n * delay_s / total_mass_kg
    if v1 <= 0.0:
        return delay_s
    if curve is not None:
        return delay_s + _profile_stop(curve, total_mass_kg * v1, te_n, max(force_n, 0.0))
    if te_n + force_n <= 0.0:
        return math.inf
    if force_n > 0.0 and ramp_s > 0.0:
        a = force_n / (2.0 * ramp_s)  # F_b t^2 / (2 r) = M v_1 - Te t on the ramp
        t_ramp = (-te_n + math.sqrt(te_n * te_n + 4.0 * a * total_mass_kg * v1)) / (2.0 * a)
        if t_ramp <= ramp_s:
            return delay_s + t_ramp
    t_b = (total_mass_kg * v1 + 0.5 * max(force_n, 0.0) * ramp_s) / (te_n + force_n)
    return delay_s + t_b


def _points(brake) -> list[tuple[float, float]]:
    """A brake's force fraction against the time since application as points (a jump is two
    points at one time): its ``force_curve`` (zero before the first point, linear between,
    the last value held) or its ramp from zero to full over ``ramp_s``."""
    if brake.force_curve:
        pts = [(float(t), float(f)) for t, f in brake.force_curve]
        return ([(0.0, 0.0), (pts[0][0], 0.0)] if pts[0][0] > 0.0 else []) + pts
    r = float(brake.ramp_s)
    return [(0.0, 0.0), (r, 1.0)] if r > 0.0 else [(0.0, 1.0)]


def _at(pts: list[tuple[float, float]], t: float, left: bool) -> float:
    """The fraction of ``pts`` at ``t`` (``left``: just before t, else just after)."""
    ts = [p[0] for p in pts]
    i = (np.searchsorted(ts, t, side="left") - 1 if left
         else np.searchsorted(ts, t, side="right") - 1)
    if i < 0:
        return 0.0 if left or t < ts[0] else pts[0][1]
    if i >= len(pts) - 1:
        return pts[-1][1]
    (t0, f0), (t1, f1) = pts[i], pts[i + 1]
    return f0 + (f1 - f0) * (t - t0) / (t1 - t0) if t1 > t0 else f1


def brake_profile(brakes) -> tuple[tuple[float, float], ...] | None:
    """The force history the auto ``brakes`` share (even shares: the mean of their
    fractions against the time since application) where one of them has a ``force_curve``;
    None where all ramp (the rigid-body sizes then take the longest ``ramp_s``, as before).

    A brake with a force curve does not read ``ramp_s`` (the dynamics follow the curve): a
    size taken over its ``ramp_s`` stopped a brake whose curve builds over 8 s (``[[0, 0],
    [8, 1]]``) as if it built over the default 1 s, 58.4 kN asked for a 12 s stop of a
    526 t overland where the curve needs 85.7 kN."""
    if not any(b.force_curve for b in brakes):
        return None
    each = [_points(b) for b in brakes]
    times = sorted({p[0] for pts in each for p in pts})
    out: list[tuple[float, float]] = []
    for t in times:
        before = sum(_at(p, t, True) for p in each) / len(each)
        after = sum(_at(p, t, False) for p in each) / len(each)
        if out and before != after:
            out.append((t, before))
        out.append((t, after))
    return tuple(out)


def _segments(curve):
    """(start, length, fraction at start, slope) of each piece of a profile, the last one
    held without end (length inf)."""
    pts = list(curve)
    for (t0, f0), (t1, f1) in zip(pts, pts[1:], strict=False):
        if t1 > t0:
            yield t0, t1 - t0, f0, (f1 - f0) / (t1 - t0)
    yield pts[-1][0], math.inf, pts[-1][1], 0.0


def _profile_integral(curve, t: float) -> float:
    """Integral of the profile's fraction from application to ``t`` [s]."""
    total = 0.0
    for a, length, f0, k in _segments(curve):
        if t <= a:
            break
        tau = min(t - a, length)
        total += f0 * tau + 0.5 * k * tau * tau
    return total


def _profile_stop(curve, momentum: float, te_n: float, force_n: float) -> float:
    """Time from application [s] at which ``momentum - Te t - F_b * integral of the
    fraction`` first reaches zero (inf if never): exact on each linear piece."""
    g = momentum
    for a, length, f0, k in _segments(curve):
        qa, qb = 0.5 * force_n * k, te_n + force_n * f0  # g - qb tau - qa tau^2 = 0
        roots = []
        if qa == 0.0:
            if qb > 0.0:
                roots = [g / qb]
        else:
            disc = qb * qb + 4.0 * qa * g
            if disc >= 0.0:
                sq = math.sqrt(disc)
                roots = [(-qb + sq) / (2.0 * qa), (-qb - sq) / (2.0 * qa)]
        hits = [r for r in roots if 0.0 <= r <= length]
        if hits:
            return a + min(hits)
        if not math.isfinite(length):
            return math.inf
        g -= qb * length + qa * length * length
    return math.inf


def brake_forces(conv: Conveyor, scenario: Scenario, total_mass_kg: float, te_n: float,
                 gravity_sum_n: float, steady: SteadyResult | None = None
                 ) -> tuple[list[float], list[str], str]:
    """Force of each brake [kN], what set it, and a note when holding or the grip set an auto
    force.

    Auto brakes share ``max(stop force, holding force) - fixed brakes`` evenly (in a brake
    stop within their pulleys' grip where an even share is beyond one's and the others have
    room, :func:`_hold_shared_by_grip`, :func:`_within_grip`): the stop
    force of :func:`brake_force_auto` for a run that stops on its brakes (none otherwise),
    the holding force ``HOLD_MARGIN`` x the net gravity pull ``gravity_sum_n`` [N]. With the
    ``steady`` solution, a stop force is held within what each braked pulley can pass in the
    stop (:mod:`beltstudy.engine.stopgrip`): where that is below the stop force, the brakes
    are ``grip``-governed and the note gives the stop time they make and what would meet the
    asked one.
    """
    if not conv.brakes:
        return [], [], ""
    auto = [b for b in conv.brakes if b.force_kn == "auto"]
    each, why, note, asked = [0.0] * len(auto), GIVEN, "", 0.0
    if auto:
        fixed_n = sum(b.force_kn * 1e3 for b in conv.brakes if b.force_kn != "auto")
        delay = max(b.delay_s for b in auto)
        ramp = max(b.ramp_s for b in auto)
        curve = brake_profile(auto)
        v = float(conv.speed_m_s)
        # a level loop's pull is zero; summed over its elements it is rounding noise
        pull_n = abs(gravity_sum_n) if abs(gravity_sum_n) > 1e-9 * G * total_mass_kg else 0.0
        hold_n = HOLD_MARGIN * pull_n
        stop_n = 0.0
        if scenario.stop.mode == "brake":
            stop_n = brake_force_auto(total_mass_kg, v, te_n, float(scenario.stop.time_s),
                                      delay, ramp, curve)
        if stop_n >= hold_n:
            total_n, why = stop_n, "stop_time"
            each = [max(total_n - fixed_n, 0.0) / len(auto)] * len(auto)
            asked = sum(each)
            if scenario.stop.mode == "brake" and total_n <= 0.0:
                note = (f"auto brake force 0 kN: the belt coasts to rest within the stop time "
                        f"{scenario.stop.time_s:g} s on its own resistances and nothing pulls it "
                        "once stopped; a shorter stop time or a given force_kn sizes a brake")
            elif steady is not None and total_n > fixed_n:
                each, why, note = _within_grip(conv, scenario, steady, each, hold_n,
                                               (total_mass_kg, v, te_n, delay, ramp, curve))
        else:
            total_n, why = hold_n, "holding"
            each = [max(total_n - fixed_n, 0.0) / len(auto)] * len(auto)
            asked = sum(each)
            if scenario.stop.mode == "brake":
                t_gives = brake_stop_time(total_mass_kg, v, te_n, hold_n, delay, ramp, curve)
                shared = False
                if steady is not None:
                    each, shared = _hold_shared_by_grip(conv, steady, each)
                note = (f"auto brake force {gnum(hold_n / 1e3)} kN is set by holding the loaded "
                        f"belt at rest ({HOLD_MARGIN:g} x the net gravity pull "
                        f"{gnum(pull_n / 1e3)} kN), not by the stop time "
                        f"{scenario.stop.time_s:g} s ("
                        + (f"which needs {gnum(stop_n / 1e3)} kN" if stop_n > 0.0 else
                           "which needs none: the belt coasts to rest within it on its own "
                           "resistances")
                        + ")"
                        + (", shared by the braked pulleys' grip in the stop (an equal share "
                           "is beyond one pulley's grip, the others have room)" if shared
                           else "")
                        + f": the rigid-body brake stop then takes about {gnum(t_gives, 3)} s")
                if steady is not None:
                    said, passed_n = _holding_grip(conv, steady, each)
                    note += said
                    if said and passed_n > 0.0:
                        # the force the pulleys pass lies between that bound and the holding
                        # force, so the stop between their two rigid-body times (a 1.2 km
                        # decline was told 14.8 s alone, and took 23.8 s as its pulley slid)
                        t_grip = brake_stop_time(total_mass_kg, v, te_n, passed_n, delay,
                                                 ramp, curve)
                        note += (f"; held to that bound ({gnum(passed_n / 1e3)} kN; the "
                                 "sliding pulley passes more) the rigid-body brake stop takes "
                                 f"about {gnum(t_grip, 3)} s, so as the pulley slides the stop "
                                 f"lies between about {gnum(t_gives, 3)} and "
                                 f"{gnum(t_grip, 3)} s" if math.isfinite(t_grip) else
                                 f"; held to that bound ({gnum(passed_n / 1e3)} kN; the sliding "
                                 "pulley passes more) the rigid belt would not stop at all, so "
                                 "the rigid-body time above is no figure for this stop: "
                                 "read the run's own stop time (stop_time_s)")
    if scenario.stop.mode == "brake" and steady is not None:
        given = _given_grip(conv, steady, each, asked)
        note = f"{note}; {given}" if note and given else note or given
    shares = iter(each)
    kn = [next(shares) / 1e3 if b.force_kn == "auto" else float(b.force_kn)
          for b in conv.brakes]
    gov = [why if b.force_kn == "auto" else GIVEN for b in conv.brakes]
    beyond = [f"brakes.{i}.force_kn {f:,.0f} kN" for i, (b, f) in enumerate(
        zip(conv.brakes, kn, strict=True)) if b.force_kn == "auto" and f > FORCE_MAX_KN]
    if beyond:
        # as the take-up's and the motors' auto sizes beyond a file's bound are said
        note = (f"{note}; " if note else "") + (
            f"the auto brake force ({', '.join(beyond)}) is beyond the breaking force of any "
            f"catalogue belt (a file may give at most {FORCE_MAX_KN:,.0f} kN): no belt "
            "passes it, so the brakes must share it over more pulleys, or the route be split "
            "into flights")
    return kn, gov, note


def _brake_nodes(conv: Conveyor, loop) -> tuple[list[int], dict]:
    """The pulley element of each auto brake, and the fixed brakes' forces by element [N]."""
    nodes, fixed = [], {}
    for b in conv.brakes:
        node = loop.brake_element(b)
        if b.force_kn == "auto":
            nodes.append(node)
        else:
            fixed[node] = fixed.get(node, 0.0) + float(b.force_kn) * 1e3
    return nodes, fixed


def _rigid_stop_words(t_s: float, at: str, caveat: str) -> str:
    """'; <at> the rigid-body brake stop takes about T s (<caveat>)', or that the rigid belt
    does not stop on it (:func:`brake_stop_time` infinite)."""
    if not math.isfinite(t_s):
        return f"; {at} the rigid belt does not stop at all"
    return f"; {at} the rigid-body brake stop takes about {gnum(t_s, 3)} s ({caveat})"


def _within_grip(conv: Conveyor, scenario: Scenario, steady: SteadyResult, each: list[float],
                 hold_n: float, rigid: tuple) -> tuple[list[float], str, str]:
    """The auto brakes' forces [N] within their pulleys' grip in the stop
    (:func:`beltstudy.engine.stopgrip.grip_limits`), ``grip`` or ``stop_time``, and the note
    when the grip held them below the stop time's need (``rigid``: mass, speed, Te, delay,
    ramp and force profile of :func:`brake_stop_time`)."""
    walk = StopWalk.of(conv, steady)
    nodes, fixed = _brake_nodes(conv, steady.loop)
    wanted = sum(each)
    forces, capped = grip_limits(walk, nodes, fixed, wanted)
    if not capped or sum(forces) >= wanted * (1.0 - 1e-6):
        return each, "stop_time", ""
    total = sum(forces) + sum(fixed.values())
    m, v, te, delay, ramp, curve = rigid
    if total < hold_n:  # the holding floor stays; the pulley may slide in the stop
        forces = [f + (hold_n - total) / len(forces) for f in forces]
        where = ", ".join(dict.fromkeys(pulley_name(conv, steady.loop, n) for n in nodes))
        # the stop time asks more than holding, the grip passes less than either: the
        # holding floor sets the force, which is said as that chain, not as a stop force
        # smaller than the holding one
        return forces, "holding", (
            f"auto brake force {gnum(hold_n / 1e3)} kN is set by holding the loaded belt at rest "
            f"({HOLD_MARGIN:g} x the net gravity pull), not by the stop time "
            f"{scenario.stop.time_s:g} s: that needs "
            f"{gnum((wanted + sum(fixed.values())) / 1e3)} kN, beyond the grip of {where} in "
            f"the stop ({gnum(total / 1e3)} kN with the fall of its slack side doubled, the "
            "undamped bound), and held to that grip it would fall below the holding force; "
            f"the holding force {gnum(hold_n / 1e3)} kN is beyond the grip too, so the pulley "
            "may slide (the run's slip check says)"
            + _rigid_stop_words(brake_stop_time(m, v, te, hold_n, delay, ramp, curve),
                                "at the holding force", "longer as the pulley slides")
            + ": " + _hold_fix(conv, steady, takeup=_takeup_words(conv, walk, lambda w: sum(
                grip_limits(w, nodes, fixed, wanted)[0]) + sum(fixed.values())
                >= hold_n * (1.0 - 1e-9))))
    t_gives = brake_stop_time(m, v, te, total, delay, ramp, curve)
    asked = float(scenario.stop.time_s)
    where = ", ".join(dict.fromkeys(pulley_name(conv, steady.loop, n) for n in nodes))
    note = (f"auto brake force {gnum(total / 1e3)} kN is set by the grip of {where} in the "
            f"stop (the capstan limit at the slack-side tension of the stop, its fall "
            f"doubled for the stop's fronts), not by the stop time {asked:g} s (which needs "
            f"{gnum((wanted + sum(fixed.values())) / 1e3)} kN): "
            + (f"the rigid-body brake stop then takes about {gnum(t_gives, 3)} s"
               if math.isfinite(t_gives) else "the belt does not stop on it")
            + f"; the stop time {asked:g} s would be met by "
            + grip_remedies(conv, steady, walk, nodes, fixed, each, forces))
    return forces, "grip", note


def brake_grip_kn(conv: Conveyor, steady: SteadyResult) -> float | None:
    """The largest total brake force [kN] (fixed brakes included) the braked pulleys pass in
    a brake stop at this case, the auto brakes sharing it as :func:`brake_forces` does
    (None without auto brakes)."""
    if not any(b.force_kn == "auto" for b in conv.brakes):
        return None
    walk = StopWalk.of(conv, steady)
    nodes, fixed = _brake_nodes(conv, steady.loop)
    forces, _capped = grip_limits(walk, nodes, fixed, 1e12)  # beyond any pulley's grip
    return (sum(forces) + sum(fixed.values())) / 1e3


def brake_kn_within_grip(conv: Conveyor, steady: SteadyResult, total_kn: float
                         ) -> list[float]:
    """Each brake's force [kN] (file order) when the auto brakes share ``total_kn`` less the
    fixed ones within their pulleys' grip at this case (:func:`brake_grip_kn` at most)."""
    walk = StopWalk.of(conv, steady)
    nodes, fixed = _brake_nodes(conv, steady.loop)
    wanted = max(total_kn * 1e3 - sum(fixed.values()), 0.0)
    forces, _capped = grip_limits(walk, nodes, fixed, wanted)
    shares = iter(forces)
    return [next(shares) / 1e3 if b.force_kn == "auto" else float(b.force_kn)
            for b in conv.brakes]


def _given_room_n(walk: StopWalk, node: int, given: dict, nodes: list[int],
                  auto_wanted: float) -> float:
    """:meth:`~beltstudy.engine.stopgrip.StopWalk.room_n` of a given brake's pulley with the
    auto brakes on ``nodes`` sized again on this walk (:func:`grip_limits`, sharing
    ``auto_wanted`` [N]), as they would be on a conveyor with the walk's take-up."""
    acting = dict(given)
    if nodes and auto_wanted > 0.0:
        forces, _capped = grip_limits(walk, nodes, given, auto_wanted)
        for n, f in zip(nodes, forces, strict=True):
            acting[n] = acting.get(n, 0.0) + f
    return walk.room_n(node, acting)


def _given_grip(conv: Conveyor, steady: SteadyResult, auto_n: list[float] | None = None,
                auto_wanted: float = 0.0) -> str:
    """The note of brake forces beyond their pulleys' grip in a brake stop ("" when within):
    per pulley with a given brake, the largest force it passes with the other brakes as set
    (the auto brakes at their sizes ``auto_n`` [N], file order of the auto brakes: an auto
    brake is sized within its own pulley's grip, but a given one beside it is not; the
    take-up advised sizes them again, sharing ``auto_wanted`` [N], what the stop or holding
    asks of them, as the design does on a conveyor with that take-up)
    (:meth:`~beltstudy.engine.stopgrip.StopWalk.grip_n`, the same undamped bound as an auto
    brake's) and the take-up that would let it pass its force, so the run's slip warning
    comes with the force that avoids it. The force is the file's ``force_kn``: given there,
    or an auto size the design (or a run below full load, sized at full load too) wrote in,
    which ``brake_governed_by`` names. A pulley that passes nothing is said as what it is:
    unbraked, the stop's fall of its slack side already leaves too little tension to slow its
    own shell, so the belt slides on it at any brake force."""
    nodes, given = _brake_nodes(conv, steady.loop)
    if not given:
        return ""
    walk = StopWalk.of(conv, steady)
    fixed = dict(given)
    for node, force in zip(nodes, auto_n or [0.0] * len(nodes), strict=True):
        fixed[node] = fixed.get(node, 0.0) + force
    parts, slides_any = [], False
    for node in given:
        force = fixed[node]
        if walk.room_n(node, fixed) >= 0.0:
            continue
        grip = walk.grip_n(node, fixed)
        field = " + ".join(f"brakes.{k}.force_kn" for k, b in enumerate(conv.brakes)
                           if steady.loop.brake_element(b) == node)
        name = pulley_name(conv, steady.loop, node)
        if grip <= 0.0:
            low, f = walk.slack_n(node, {**fixed, node: 0.0})
            euler = steady.loop.pulley_at(node).euler
            said = (f"{name} passes no brake force in the stop: unbraked, its slack side "
                    f"already falls to {gnum(low / 1e3, 3)} kN (its fall doubled), a grip of "
                    f"{gnum(max(low, 0.0) * (euler - 1.0) / 1e3, 3)} kN against the "
                    f"{gnum(abs(f) / 1e3, 3)} kN that slows its own shell and shaft, so by that bound "
                    f"the belt slides on it at any brake force, the {gnum(force / 1e3)} kN set "
                    f"({field}) too")
        else:
            said = (f"{name} passes at most {gnum(grip / 1e3)} kN of brake force in the stop "
                    f"against the {gnum(force / 1e3)} kN set ({field})")
        need = _bisect_up(lambda t, n=node: _given_room_n(walk.at_takeup(t), n, given, nodes,
                                                           auto_wanted) >= 0.0,
                          walk.takeup_n, 100.0 * walk.takeup_n + 1e6)
        if need is not None:
            said += (f" (a take-up of {takeup_at_least(need, G)}, takeup.mass_kg,"
                     if conv.takeup.type == "gravity" else
                     f" (a take-up pretension of {takeup_at_least(need)}, "
                     "takeup.pretension_kn,")
            said += " would let it pass that force)"
        parts.append(said)
        slides_any = slides_any or grip <= 0.0
    if not parts:
        return ""
    within = "" if slides_any else "a force within it, "
    return ("brake force beyond the grip in the stop (the capstan limit at the "
            "slack-side tension of the stop, its fall doubled for the stop's fronts, the "
            "undamped bound; the force is given in the file or an auto size written in, as "
            "brake_governed_by says): " + "; ".join(parts) + "; the pulley may slide (the "
            f"run's slip check says): {within}{takeup_lever(conv)} or a brake on another "
            "pulley would avoid it")


def _hold_shared_by_grip(conv: Conveyor, steady: SteadyResult, each: list[float]
                         ) -> tuple[list[float], bool]:
    """The auto brakes' holding forces [N] shared within their pulleys' grip in the stop
    (:func:`beltstudy.engine.stopgrip.grip_limits`, as a stop-time size is) where an equal
    share ``each`` is beyond one pulley's grip and the others together pass the whole; else
    ``each``. Returns the forces and whether the grip shared them."""
    walk = StopWalk.of(conv, steady)
    nodes, fixed = _brake_nodes(conv, steady.loop)
    wanted = sum(each)
    if len(set(nodes)) < 2 or wanted <= 0.0:
        return each, False
    forces, capped = grip_limits(walk, nodes, fixed, wanted)
    if capped and sum(forces) >= wanted * (1.0 - 1e-6):
        return forces, True
    return each, False


def _holding_grip(conv: Conveyor, steady: SteadyResult, each: list[float]
                  ) -> tuple[str, float]:
    """The clause a holding-set note gains when the holding force is beyond the braked
    pulleys' grip in the stop ("" when within), and the brake force the braked pulleys pass
    then [N]: each pulley's set force held to its grip, the fixed brakes' as set."""
    walk = StopWalk.of(conv, steady)
    nodes, fixed = _brake_nodes(conv, steady.loop)
    acting = dict(fixed)
    for node, f in zip(nodes, each, strict=True):
        acting[node] = acting.get(node, 0.0) + f
    # each pulley's own grip against the force set on it (the other brakes as set), not the
    # braked pulleys' total, which may exceed the whole holding force; beyond it by more
    # than the grip sharing leaves (it converges to 1e-9 of the whole)
    grips = {n: walk.grip_n(n, acting) for n in dict.fromkeys(nodes)}
    short = [n for n, grip in grips.items() if acting[n] > grip * (1.0 + 1e-6) + 1e-3]
    if not short:
        return "", 0.0
    passed = sum(min(f, max(grips[n], 0.0)) if n in grips else f for n, f in acting.items())
    parts = []
    for n in short:
        grip = grips[n]
        passes = (f"it passes at most {gnum(grip / 1e3)} kN" if grip > 0.0 else
                  "unbraked, its slack side already falls so far that it passes no brake "
                  "force")
        parts.append(f"{pulley_name(conv, steady.loop, n)} ({passes} against the "
                     f"{gnum(acting[n] / 1e3)} kN set on it)")
    said = (f"; this force is beyond the grip of {' and of '.join(parts)} in the stop (with "
            "the fall of the slack side doubled, the undamped bound), which may slide (the "
            "run's slip check says): ")
    # the take-up with which every braked pulley passes an even share of the holding force
    # (the design shares it evenly where that fits), the holding force itself not moving
    even = dict(fixed)
    for node in nodes:
        even[node] = even.get(node, 0.0) + sum(each) / len(each)
    takeup = _takeup_words(conv, walk, lambda w: all(w.room_n(n, even) >= 0.0 for n in nodes))
    return said + _hold_fix(conv, steady, any(grips[n] <= 0.0 for n in short), takeup), passed


def _takeup_words(conv: Conveyor, walk: StopWalk, passes) -> str:
    """The least take-up with which ``passes(walk at that take-up)`` holds, in the words of
    the take-up lever's brackets: a counterweight in kg (``takeup.mass_kg``), or a
    pretension; "" when none up to 100 x today's does (bisection, rounded up)."""
    need = _bisect_up(lambda t: passes(walk.at_takeup(t)), walk.takeup_n,
                      100.0 * walk.takeup_n + 1e6, rel=1e-7)
    if need is None:
        return ""
    if conv.takeup.type == "gravity":
        return f"{takeup_at_least(need, G)}, takeup.mass_kg, by that bound"
    return f"{takeup_at_least(need)} by that bound"


def takeup_lever(conv: Conveyor, why: str = "") -> str:
    """The take-up lever in words: ``a heavier take-up`` for a gravity take-up, ``a higher
    take-up pretension (takeup.pretension_kn)`` for a fixed (screw or winch) one, which has no
    counterweight to make heavier (the words of
    :func:`beltstudy.engine.dynamics.simulate.heavier_takeup`); ``why`` goes in the
    brackets."""
    return lever_words(conv.takeup.type == "gravity", why)


def _hold_fix(conv: Conveyor, steady: SteadyResult, none_passes: bool = False,
              takeup: str = "") -> str:
    """What lets a holding-sized brake's pulley keep its grip in the stop, in words: on an
    incline a holdback holds the belt at rest instead (where it has one, the brake need not
    hold it: a given force within the grip, not offered where a pulley passes no brake force,
    ``none_passes``); on a decline only more tension or another braked pulley do. ``takeup``:
    the take-up figure (:func:`_takeup_words`) the lever names."""
    more = takeup_lever(conv, takeup)
    if float(steady.loop.gravity_n.sum()) > 0.0:
        if conv.holdback and none_passes:
            return (f"{more} or the brake on another pulley (its holdback, holdback: true, "
                    "already holds the belt at rest) would avoid it")
        if conv.holdback:
            return ("its holdback (holdback: true) already holds the belt at rest, so a given "
                    f"brake force (brakes[].force_kn) within the grip, {more} or a "
                    "brake on another pulley would avoid it")
        return (f"a holdback to hold the belt at rest with a smaller given brake, {more} or "
                "a brake on another pulley would avoid it")
    return f"{more} or part of the force on a brake on another pulley would avoid it"


def auto_sizes(conveyor: Conveyor, scenario: Scenario, *, model: str,
               params: dict | object | None = None, steady: SteadyResult | None = None) -> dict:
    """The take-up, rated power and brake forces of ``conveyor`` at one operating case.

    Parameters
    ----------
    conveyor : Conveyor
    scenario : Scenario
        The case: ``load``, ``temperature_c``, ``elements`` (mesh of the steady solve) and, for
        auto brakes, ``stop.mode`` and ``stop.time_s``.
    model : str
        Friction model name.
    params : dict or parameter dataclass, optional
        Friction model parameter overrides.
    steady : SteadyResult, optional
        The steady solution of this case when the caller has it (no second solve).

    Returns
    -------
    dict
        ``takeup_mass_kg`` (gravity, else None) [kg], ``takeup_pretension_kn`` (tension per
        strand at the take-up) [kN], ``takeup_governed_by``; ``drive_rated_power_kw`` and
        ``drive_rated_power_governed_by`` (lists, one per drive, file order) [kW];
        ``brake_force_kn`` and ``brake_governed_by`` (lists, one per brake) [kN],
        ``brake_note`` (why an auto brake is not the stop time's size, "" otherwise),
        ``brake_grip_kn`` (a brake stop: the most the braked pulleys pass, None otherwise)
        [kN]; ``status`` of the steady solve (a failed solve sizes nothing reliable).
    """
    if steady is None:
        n = None if scenario.elements == "auto" else int(scenario.elements)
        steady = solve_steady(conveyor, model=model, params=params,
                              temperature_c=scenario.temperature_c, load=scenario.load,
                              n_elements=n)
    tu = conveyor.takeup
    rated, rated_gov = rated_power_kw(conveyor, float(steady.te_n),
                                      float(np.sum(steady.resistance_n)))
    brakes, brakes_gov, brake_note = brake_forces(conveyor, scenario,
                                                  moving_mass_kg(conveyor, steady),
                                                  float(steady.te_n),
                                                  float(steady.loop.gravity_n.sum()), steady)
    # a given take-up as given (the steady solve keeps its mass), not as its round trip
    # through the tension: 2 (3748.2 G / 2) / G is 3748.1999999999994, and a row that says so
    # is not the conveyor the run used
    given_kn = (float(tu.pretension_kn)
                if tu.type != "gravity" and tu.pretension_kn != "auto" else None)
    return {
        "takeup_mass_kg": steady.takeup_mass_kg if tu.type == "gravity" else None,
        "takeup_pretension_kn": (given_kn if given_kn is not None
                                 else float(steady.takeup_tension_n) / 1e3),
        "takeup_governed_by": steady.takeup_governed_by,
        "drive_rated_power_kw": rated,
        "drive_rated_power_governed_by": rated_gov,
        "brake_force_kn": brakes,
        "brake_governed_by": brakes_gov,
        "brake_note": brake_note,
        "brake_grip_kn": (brake_grip_kn(conveyor, steady) if scenario.stop.mode == "brake"
                          else None),
        "status": steady.status,
    }


def summary_fields(sizes: dict) -> dict:
    """The design columns of a run summary (SPEC 6.4) from :func:`auto_sizes`' answer.

    ``rated_power_kw`` and ``brake_force_kn`` are totals over the drives and brakes (None
    without brakes), ``drive{i}_rated_power_kw`` each drive's; ``*_governed_by`` name the
    constraint (several distinct ones joined by ``+``). Fields: :mod:`beltstudy.engine.results`.
    """
    def join(names: list[str]) -> str | None:
        return "+".join(dict.fromkeys(names)) or None

    return {
        "takeup_mass_kg": sizes["takeup_mass_kg"],
        "takeup_pretension_kn": sizes["takeup_pretension_kn"],
        "takeup_governed_by": sizes["takeup_governed_by"],
        "rated_power_kw": float(sum(sizes["drive_rated_power_kw"])),
        "rated_power_governed_by": join(sizes["drive_rated_power_governed_by"]),
        **{f"drive{i}_rated_power_kw": kw
           for i, kw in enumerate(sizes["drive_rated_power_kw"], start=1)},
        "brake_force_kn": (float(sum(sizes["brake_force_kn"])) if sizes["brake_force_kn"]
                           else None),
        "brake_governed_by": join(sizes["brake_governed_by"]),
    }
