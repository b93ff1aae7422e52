"""A braked pulley's slack side in a brake stop: the stop's loads one at a time.

A 3 km, -150 m regenerating decline (head drive and take-up, a tail brake held to its pulley's
grip in an 8 s stop). The drives' trip raises the tail's slack side (the return arriving at the
tail: with the regenerating drive gone the belt is no longer held back), and the brake lowers
it. Setting that rise against the brake's fall sized the brake at 393.1 kN with the slack
side at 197.6 kN, where the simulated stop dipped to 193 kN as the brake came on and the tail
pulley slid. A rise now counts for nothing against a fall (PHYSICS 5.1; the walk in
``beltstudy.engine.stopgrip``).
"""
from __future__ import annotations

import re

import numpy as np
import pytest

from beltstudy.engine.conveyor import Scenario, parse_conveyor
from beltstudy.engine.design import brake_grip_kn
from beltstudy.engine.dynamics import DynamicsOptions, build_system, simulate
from beltstudy.engine.dynamics.model import with_probes
from beltstudy.engine.statics import solve_steady
from beltstudy.engine.stopgrip import FRONT_FACTOR, StopWalk

DECLINE = {
    "name": "decline3k", "speed_m_s": 4.5,
    "belt": {"type": "ST2000", "width_m": 1.2, "compound": "standard"},
    "material": {"capacity_t_h": 2000, "density_t_m3": 1.5, "loading_speed_m_s": 0.0},
    "profile": [{"length_m": 1500, "lift_m": -60}, {"length_m": 1500, "lift_m": -90}],
    "idlers": {"carry": {"spacing_m": 1.2, "roll_diameter_m": 0.152, "rolls": 3,
                         "trough_deg": 35, "cema_class": "D"},
               "return": {"spacing_m": 3.0, "roll_diameter_m": 0.152, "rolls": 1,
                          "cema_class": "C"}},
    "drives": [{"position": "head", "wrap_deg": 210, "friction": 0.35, "share": 1.0,
                "pulley_diameter_m": 1.25, "inertia_kg_m2": 1200, "torque_limit": 1.5,
                "speed_loop_rad_s": 1}],
    "takeup": {"type": "gravity", "position": "head", "mass_kg": 51245, "travel_m": 15},
    "brakes": [{"position": "tail", "force_kn": "auto", "delay_s": 0.5, "ramp_s": 1.0}],
    "holdback": False,
    "accessories": {"head_kn": 1.5, "tail_kn": 0.5}}


def _walk(delay_s: float = 0.5):
    conv = parse_conveyor({**DECLINE, "brakes": [{**DECLINE["brakes"][0], "delay_s": delay_s}]})
    steady = solve_steady(conv, model="din", settle=True)
    return conv, steady, StopWalk.of(conv, steady)


def test_a_rise_is_never_set_against_a_fall():
    """The trip's rise at the tail's slack side against the brake's fall: a step's undamped
    response swings between 0 and twice its static change, so at the fall's peak the rise may
    be back at 0. Whenever the brake acts (0.5 s, before the trip's front has come down the
    return, or 3 s, after it), the slack side is the running tension less twice the brake's
    own fall."""
    _conv, steady, walk = _walk()
    loop = steady.loop
    tail = loop.i_tail
    force = 300e3
    r_in = walk.running[tail - 1]
    trip_in = walk.pulley(tail, {})[0]
    braked_in = walk.pulley(tail, {tail: force})[0]
    assert trip_in > r_in  # the premise: the trip raises the tail's slack side
    # by hand: the brake's fall alone, doubled
    expected = r_in - FRONT_FACTOR * (trip_in - braked_in)
    for delay in (0.5, 3.0):
        _c, _s, w = _walk(delay_s=delay)
        low, _f = w.slack_n(tail, {tail: force})
        assert low == pytest.approx(expected, rel=1e-9)
    # the net fall doubled, as engines before 0.6.25 took it, is higher: the unsafe side
    assert braked_in - (FRONT_FACTOR - 1.0) * (r_in - braked_in) > expected


def test_the_grip_sized_brake_holds_its_pulley_through_the_stops_fronts():
    conv = parse_conveyor(DECLINE)
    steady = solve_steady(conv, model="din", settle=True)
    grip_kn = brake_grip_kn(conv, steady)
    sized = parse_conveyor({**DECLINE, "brakes": [{**DECLINE["brakes"][0],
                                                   "force_kn": grip_kn}]})
    steady = solve_steady(sized, model="din", settle=True)
    walk = StopWalk.of(sized, steady)
    tail = steady.loop.i_tail
    bound, _f = walk.slack_n(tail, {tail: grip_kn * 1e3})
    scn = Scenario(start={"control": "s-curve", "time_s": 60}, run_s=30,
                   stop={"mode": "brake", "time_s": 8}, record_dt_s=0.01)
    sys = with_probes(build_system(sized, scn, steady, DynamicsOptions()), [tail - 1])
    res = simulate(sys, steady_summary=steady.summary, conveyor=sized)
    t = res.traces["t_s"].to_numpy()
    slack = res.traces.iloc[:, 1].to_numpy() * 1e3
    brake = res.timeseries["f_brake_kn"].to_numpy()
    on = np.flatnonzero(brake > 0.0)
    t_on = float(res.timeseries["t_s"].to_numpy()[on[0]])
    # one wave loop from the brake's first force: its front and the trip's, and their
    # reflections once round
    window = (t >= t_on) & (t <= t_on + float(sys.wave_loop_time_s))
    lowest = float(slack[window].min())
    assert lowest >= bound, (lowest, bound)
    # and the pulley passes the brake there: the capstan limit at the lowest slack side
    euler = steady.loop.pulley_at(tail).euler
    assert lowest * (euler - 1.0) >= grip_kn * 1e3


def test_a_sliding_brake_pulley_is_told_the_brake_force_that_holds_it_and_it_does():
    """The walk has no end of the stop: on this decline the 372.9 kN grip size still slides
    0.32 s as the belt comes to rest (docs/dynamics.md, *Brakes within their grip*). The
    run's remedy reruns the cycle for the force that holds, and that force, given, holds."""
    from beltstudy.engine.run import run_one

    scn = Scenario(start={"control": "s-curve", "time_s": 60},
                   stop={"mode": "brake", "time_s": 8})
    res = run_one(parse_conveyor(DECLINE), scn, model="din", remedy=True)
    msg = res.summary["message"]
    assert "the tail brake's pulley slipped" in msg, msg
    said = re.search(r"a tail brake force of ([\d.]+) kN \(brakes\.0\.force_kn; now ([\d.]+) "
                     r"kN\) keeps its pulley from sliding in the stop \(found by rerunning the "
                     r"cycle (\d+) times", msg)
    assert said, msg
    force, now = float(said.group(1)), float(said.group(2))
    assert now == pytest.approx(res.summary["brake_force_kn"], rel=1e-3)
    assert force < now
    given = {**DECLINE, "brakes": [{**DECLINE["brakes"][0], "force_kn": force}],
             "takeup": {**DECLINE["takeup"], "mass_kg": res.summary["takeup_mass_kg"]}}
    after = run_one(parse_conveyor(given), scn, model="din")
    assert "brake's pulley slipped" not in after.summary["message"], after.summary["message"]
    t_cmd = after.transient.system.stop_command_s
    assert not [s for s in after.transient.raw["brake_pulley_slip"] if s["last_s"] >= t_cmd]
