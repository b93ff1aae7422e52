"""Auto sizes and what set them (engine/design.py), by hand."""

from __future__ import annotations

import math
import re

import numpy as np
import pytest
from numpy.testing import assert_allclose

from beltstudy.engine.conveyor import Scenario, load_conveyor, parse_conveyor
from beltstudy.engine.design import (
    RATED_POWER_FACTOR,
    auto_sizes,
    brake_force_auto,
    brake_stop_time,
    moving_mass_kg,
)
from beltstudy.engine.dynamics import build_system
from beltstudy.engine.loop import G, rotating_parts
from beltstudy.engine.run import run_one
from beltstudy.engine.statics import solve_steady
from tests.conftest import CONVEYORS, hand_conveyor_dict
from tests.engine.conftest import decline_2500_dict, hand_conv, steep_incline


def _euler(wrap_deg=200, mu=0.35):
    return math.exp(mu * math.radians(wrap_deg))


def test_rated_power_by_hand():
    """1.25 x share x Te x v / eta (the motor power, eta 0.95 by default) for a lifting
    conveyor without a given rated power."""
    conv = parse_conveyor(hand_conveyor_dict())
    scn = Scenario()
    sizes = auto_sizes(conv, scn, model="din")
    st = solve_steady(conv, model="din")
    assert sizes["drive_rated_power_kw"] == pytest.approx(
        [RATED_POWER_FACTOR * 1.0 * st.te_n * 4.0 / 0.95 / 1e3], rel=1e-9)
    assert sizes["drive_rated_power_governed_by"] == ["peripheral_force"]
    assert sizes["takeup_governed_by"] == "slip_start"
    assert sizes["takeup_mass_kg"] == pytest.approx(st.summary["takeup_mass_kg"], rel=1e-12)


def test_brake_sized_by_the_stop_time_or_held_by_the_holding_floor():
    """Rigid body: M v_1 = Te t_b + F_b (t_b - r / 2), t_b = t_stop - t_delay, v_1 = v - Te
    t_delay / M, r the ramp (1 s by default); at least 1.2 x the net pull of the loaded belt.
    A coast run uses no stop time: holding size. The 60 t take-up lets the head pulley pass
    the 3 s stop's force (test_auto_brake_held_within_its_pulleys_grip covers the grip)."""
    d = hand_conveyor_dict(brakes=[{"position": "head", "force_kn": "auto", "delay_s": 0.5}],
                           takeup={"type": "gravity", "position": "tail", "mass_kg": 60000})
    conv = parse_conveyor(d)
    st = solve_steady(conv, model="din")
    m = moving_mass_kg(conv, st)
    v1 = 4.0 - st.te_n * 0.5 / m
    pull = G * 50.0 * 50.0  # m'_L g H: the loaded lift
    short = auto_sizes(conv, Scenario(stop={"mode": "brake", "time_s": 3.0}), model="din")
    f_stop = (m * v1 - st.te_n * 2.5) / (2.5 - 0.5 * 1.0)
    assert f_stop > 1.2 * pull
    assert short["brake_force_kn"] == pytest.approx([f_stop / 1e3], rel=1e-9)
    assert short["brake_governed_by"] == ["stop_time"]
    long = auto_sizes(conv, Scenario(stop={"mode": "brake", "time_s": 60.0}), model="din")
    assert long["brake_force_kn"] == pytest.approx([1.2 * pull / 1e3], rel=1e-9)
    assert long["brake_governed_by"] == ["holding"]
    coast = auto_sizes(conv, Scenario(stop={"mode": "coast", "time_s": 3.0}), model="din")
    assert coast["brake_force_kn"] == long["brake_force_kn"]


@pytest.mark.parametrize("stop_s, delay_s, ramp_s", [
    (1.2, 0.5, 1.0),   # the belt stops on the ramp (t_b 0.7 s < r 1 s)
    (3.0, 1.0, 4.0),   # on a long ramp (t_b 2 s < r 4 s)
    (10.0, 0.5, 1.0),  # past the ramp (t_b 9.5 s > r 1 s)
    (1.5, 0.5, 1.0),   # the ramp ends at the stop (t_b = r)
])
def test_auto_brake_force_meets_the_stop_time_on_its_ramp_or_past_it(stop_s, delay_s, ramp_s):
    """The brake's impulse is the integral of its delay-then-ramp force history, F(t) = 0 to
    the delay, F_b (t - d) / r over the ramp r, then F_b. Rigid body, M 100 t at v 4 m/s,
    Te 20 kN: v_1 = v - Te d / M; the brake's impulse over t_b = t_stop - d is M v_1 - Te t_b,
    which is F_b t_b^2 / (2 r) when the belt stops on the ramp (t_b < r), F_b (t_b - r / 2)
    past it. For 1.2 s, 0.5 s, 1 s: v_1 = 3.9 m/s, M v_1 - Te t_b = 390 000 - 14 000 =
    376 000 N s, F_b = 376 000 x 2 x 1 / 0.7^2 = 1 534 694 N (t_b - r/2 = 0.2 s would give
    1 074 286 N, 30 % short, a 1.33 s stop). The stop time of that force (brake_stop_time) is
    the asked one, and a forward-Euler integration of the force history stops the belt then."""
    m, v, te = 100_000.0, 4.0, 20_000.0
    v1 = v - te * delay_s / m
    t_b = stop_s - delay_s
    impulse = m * v1 - te * t_b
    hand = (impulse * 2.0 * ramp_s / t_b**2 if t_b < ramp_s
            else impulse / (t_b - 0.5 * ramp_s))
    force = brake_force_auto(m, v, te, stop_s, delay_s, ramp_s)
    assert force == pytest.approx(hand, rel=1e-12)
    if (stop_s, delay_s, ramp_s) == (1.2, 0.5, 1.0):
        assert force == pytest.approx(1_534_694, abs=1.0)
    assert brake_stop_time(m, v, te, force, delay_s, ramp_s) == pytest.approx(stop_s, rel=1e-9)
    dt, t, u = 1e-4, 0.0, v
    while u > 0.0:
        f = 0.0 if t < delay_s else force * min((t - delay_s) / ramp_s, 1.0)
        u -= (te + f) / m * dt
        t += dt
    assert t == pytest.approx(stop_s, abs=2e-3)


def test_brake_stop_time_of_a_force_short_of_the_ramp_or_none():
    """A force too small to stop on the ramp stops past it: t_b = (M v_1 + F_b r / 2) /
    (Te + F_b) (100 t, 4 m/s, Te 20 kN, d 0.5 s, r 1 s, F_b 20 kN: v_1 = 3.9, t_b =
    (390 000 + 10 000) / 40 000 = 10 s); without a brake the belt coasts, t_b = M v_1 / Te
    = 19.5 s; a brake below a downhill pull never stops it."""
    assert brake_stop_time(1e5, 4.0, 2e4, 2e4, 0.5, 1.0) == pytest.approx(10.5, rel=1e-12)
    assert brake_stop_time(1e5, 4.0, 2e4, 0.0, 0.5, 1.0) == pytest.approx(20.0, rel=1e-12)
    assert brake_stop_time(1e5, 4.0, -2e4, 1e4, 0.5, 1.0) == math.inf
    assert brake_force_auto(1e5, 4.0, 2e4, 0.5, 0.5, 1.0) == math.inf  # no time after the delay


@pytest.mark.parametrize("name", ["downhill-regen.yaml", "fabric-1km.yaml"])
def test_auto_sizes_are_what_the_transient_model_uses(name):
    """The design module and the transient model agree on the rated force and brake force
    (the study service substitutes the design module's numbers)."""
    data = load_conveyor(CONVEYORS / name).model_dump(by_alias=True)
    for drive in data["drives"]:
        drive["rated_power_kw"] = None
    data["brakes"] = [{"position": "head", "force_kn": "auto", "delay_s": 0.5}]
    conv = parse_conveyor(data)
    scn = Scenario(elements=60, stop={"mode": "brake", "time_s": 15.0})
    st = solve_steady(conv, model="din", n_elements=60)
    sizes = auto_sizes(conv, scn, model="din", steady=st)
    sys = build_system(conv, scn, st)
    assert_allclose(sys.model.control.m_tot, moving_mass_kg(conv, st), rtol=1e-12)
    assert_allclose(np.sum(sys.model.drives.rated) * conv.speed_m_s / 1e3,
                    sum(sizes["drive_rated_power_kw"]), rtol=1e-6)
    assert_allclose(sys.model.brakes.force / 1e3, sizes["brake_force_kn"], rtol=1e-9)


def test_auto_brake_force_set_by_holding_is_said():
    conv = hand_conv(brakes=[{"position": "head", "force_kn": "auto", "delay_s": 0.5}])
    r = run_one(conv, Scenario(start={"time_s": 20}, run_s=5, elements=60,
                               stop={"mode": "brake", "time_s": 30}), model="din")
    msg = r.summary["message"]
    assert "set by holding" in msg and "stop then takes about" in msg


def test_auto_brake_on_a_level_belt_that_coasts_within_the_stop_time():
    """A level loop (no net pull, its sum over the elements rounding noise) whose rigid-body
    coast, M v / Te by hand, is shorter than the 40 s brake stop asked for: the auto brake
    needs no force, and the message says why (no noise-sized holding force)."""
    conv = hand_conv(profile=[{"length_m": 1000, "lift_m": 0}],
                     brakes=[{"position": "head", "force_kn": "auto", "delay_s": 0.5}])
    st = solve_steady(conv, model="din", n_elements=60)
    sysm = build_system(conv, Scenario(start={"time_s": 20}, run_s=5, elements=60,
                                       stop={"mode": "brake", "time_s": 40}), st)
    assert sysm.model.control.m_tot * 4.0 / st.te_n < 40.0
    assert sysm.model.brakes.force.tolist() == [0.0]
    note = "; ".join(sysm.notes)
    assert "auto brake force 0 kN: the belt coasts to rest within the stop time 40 s" in note
    assert "e-1" not in note


def _note_stop_time(note: str) -> float:
    return float(re.search(r"brake stop then takes about ([0-9.]+) s", note).group(1))


def test_auto_brake_held_within_its_pulleys_grip():
    """A 3 s stop on the 10 % incline needs more than the head pulley passes. By hand (PHYSICS
    5.1, capstan): rigid-body deceleration d = (Te + F) / M; the slack side is the head's
    incoming carry, walked from the tail take-up: T_in = T_run_in - d m_carry (the steady
    walk less the inertia of the carry and half the tail pulley with its shell); doubled fall for the
    fronts, T_slack = T_run_in - 2 (T_run_in - T_in); the pulley passes F - m_p d, m_p its
    shaft's reduced mass: F - m_p d = (e^(mu theta) - 1) T_slack at the sized force (1 %)."""
    conv = steep_incline()
    st = solve_steady(conv, model="din")
    sizes = auto_sizes(conv, Scenario(stop={"mode": "brake", "time_s": 3.0}), model="din")
    assert sizes["brake_governed_by"] == ["grip"]
    f = sizes["brake_force_kn"][0] * 1e3
    loop = st.loop
    parts = rotating_parts(conv, loop)
    m_total = moving_mass_kg(conv, st)
    d = (st.te_n + f) / m_total
    head = loop.i_head
    tail = loop.i_takeup  # the tail pulley, its shell turning with the belt
    m_carry = float(loop.mass_kg[:head].sum()) + 0.5 * (float(loop.mass_kg[tail])
                                                       + parts.plain_mass[tail])
    t_run = float(st.tension_n[head - 1])
    t_in = t_run - d * m_carry
    t_slack = t_run - 2.0 * (t_run - t_in)
    m_p = parts.shaft_mass[head]
    assert f - m_p * d == pytest.approx((_euler() - 1.0) * t_slack, rel=0.01)
    # the stop time it makes, and what would meet 3 s
    note = sizes["brake_note"]
    t_b = (m_total * (4.0 - st.te_n * 0.5 / m_total) + 0.5 * f * 0.5) / (st.te_n + f)
    assert _note_stop_time(note) == pytest.approx(0.5 + t_b, rel=0.01)
    assert "not by the stop time 3 s" in note and "take-up of" in note
    heavier = re.search(r"take-up of ([0-9,]+) kg", note).group(1).replace(",", "")
    big = steep_incline(takeup={"type": "gravity", "position": "tail",
                                "mass_kg": float(heavier) * 1.01})
    again = auto_sizes(big, Scenario(stop={"mode": "brake", "time_s": 3.0}), model="din")
    assert again["brake_governed_by"] == ["stop_time"]


def test_auto_brake_within_its_grip_is_set_by_the_stop_time():
    """A 3.5 s stop on the same incline is within the head pulley's grip: the rigid-body
    force of the stop time, above the holding floor (1.2 x 50 kg/m x g x 150 m)."""
    conv = steep_incline()
    st = solve_steady(conv, model="din")
    sizes = auto_sizes(conv, Scenario(stop={"mode": "brake", "time_s": 3.5}), model="din")
    m = moving_mass_kg(conv, st)
    v1 = 4.0 - st.te_n * 0.5 / m
    f_stop = (m * v1 - st.te_n * 3.0) / (3.0 - 0.5 * 0.5)
    assert f_stop > 1.2 * 50.0 * G * 150.0
    assert sizes["brake_governed_by"] == ["stop_time"]
    assert sizes["brake_force_kn"] == pytest.approx([f_stop / 1e3], rel=1e-9)


def test_a_holding_force_beyond_the_grip_is_said():
    """On the 12 t take-up the head pulley passes about 11 kN in the stop, below the holding
    floor (1.2 x 50 kg/m x g x 150 m = 88.3 kN): holding sets the brake, and the note says the
    pulley slides in the stop and what would avoid it (an incline: a holdback)."""
    conv = steep_incline(takeup={"type": "gravity", "position": "tail", "mass_kg": 12000})
    sizes = auto_sizes(conv, Scenario(stop={"mode": "brake", "time_s": 3.0}), model="din")
    assert sizes["brake_governed_by"] == ["holding"]
    assert sizes["brake_force_kn"] == pytest.approx([1.2 * 50.0 * G * 150.0 / 1e3], rel=1e-9)
    note = sizes["brake_note"]
    assert "beyond the grip of drive 1's pulley (head) in the stop" in note
    assert "a holdback to hold the belt at rest" in note
    assert sizes["brake_grip_kn"] < 0.5 * sizes["brake_force_kn"][0]


def test_a_given_brake_beyond_its_grip_is_told_the_force_its_pulley_passes():
    """A given 88 kN head brake on the 12 t take-up: the head pulley passes far less in the
    stop. The run's slip warning said only 'less brake force'; the note now names the pulley,
    the given force and the largest it passes, which meets the capstan limit by hand at that
    force (as an auto brake's grip: F - m_p d = (e^(mu theta) - 1) T_slack, 1 %), and within
    the grip a given brake has no note."""
    conv = steep_incline(brake_force=88.0,
                         takeup={"type": "gravity", "position": "tail", "mass_kg": 12000})
    scn = Scenario(stop={"mode": "brake", "time_s": 3.0})
    sizes = auto_sizes(conv, scn, model="din")
    note = sizes["brake_note"]
    assert sizes["brake_governed_by"] == ["given"] and sizes["brake_force_kn"] == [88.0]
    m = re.search(r"drive 1's pulley \(head\) passes at most ([0-9.]+) kN of brake force in "
                  r"the stop against the 88 kN set \(brakes.0.force_kn\)", note)
    assert m, note
    assert "a force within it, a heavier take-up or a brake on another pulley" in note
    f = float(m.group(1)) * 1e3
    st = solve_steady(conv, model="din")
    loop = st.loop
    parts = rotating_parts(conv, loop)
    d = (st.te_n + f) / moving_mass_kg(conv, st)
    head, tail = loop.i_head, loop.i_takeup
    m_carry = float(loop.mass_kg[:head].sum()) + 0.5 * (float(loop.mass_kg[tail])
                                                       + parts.plain_mass[tail])
    t_run = float(st.tension_n[head - 1])
    t_slack = t_run - 2.0 * (t_run - (t_run - d * m_carry))
    assert f - parts.shaft_mass[head] * d == pytest.approx((_euler() - 1.0) * t_slack,
                                                           rel=0.01)
    within = steep_incline(brake_force=0.9 * f / 1e3,
                           takeup={"type": "gravity", "position": "tail", "mass_kg": 12000})
    assert auto_sizes(within, scn, model="din")["brake_note"] == ""
    # a coast stop does not use the brake: nothing to say
    assert auto_sizes(conv, Scenario(stop={"mode": "coast"}), model="din")["brake_note"] == ""


def test_a_holding_note_does_not_offer_the_holdback_a_conveyor_has():
    """The same incline with holdback: true: the note says the holdback already holds it and
    offers a given brake force within the grip instead of a holdback."""
    conv = steep_incline(takeup={"type": "gravity", "position": "tail", "mass_kg": 12000},
                         holdback=True)
    note = auto_sizes(conv, Scenario(stop={"mode": "brake", "time_s": 3.0}),
                      model="din")["brake_note"]
    assert "a holdback to hold" not in note
    assert "its holdback (holdback: true) already holds the belt at rest" in note
    assert "brakes[].force_kn" in note


def test_two_auto_brakes_share_within_each_pulleys_grip():
    """A head and a tail auto brake: each passes what its own pulley allows beside the other
    (the capstan room of each >= 0), and together the asked force of a stop within both."""
    from beltstudy.engine.stopgrip import StopWalk, grip_limits

    conv = steep_incline(brakes=[{"position": "head", "force_kn": "auto", "delay_s": 0.5,
                                  "ramp_s": 0.5},
                                 {"position": "tail", "force_kn": "auto", "delay_s": 0.5,
                                  "ramp_s": 0.5}])
    st = solve_steady(conv, model="din")
    walk = StopWalk.of(conv, st)
    nodes = [st.loop.i_head, st.loop.i_tail]
    forces, capped = grip_limits(walk, nodes, {}, 400e3)  # far beyond both
    assert capped
    acting = dict(zip(nodes, forces, strict=True))
    for node in nodes:
        assert walk.room_n(node, acting) == pytest.approx(0.0, abs=1e-3 * max(forces))
    sizes = auto_sizes(conv, Scenario(stop={"mode": "brake", "time_s": 3.0}), model="din")
    assert sizes["brake_governed_by"] == ["stop_time", "stop_time"]
    assert sum(sizes["brake_force_kn"]) < sizes["brake_grip_kn"]


def test_a_shaft_brake_behind_a_drive_acts_through_its_pulley():
    """A brake on the head drive's shaft (``drive: 1``) passes through the same pulley as a
    head brake (the head drive's pulley is the first head pulley): the same grip, the same
    force, named by that pulley."""
    scn = Scenario(stop={"mode": "brake", "time_s": 3.0})
    head = auto_sizes(steep_incline(), scn, model="din")
    shaft = auto_sizes(steep_incline(brakes=[{"drive": 1, "force_kn": "auto", "delay_s": 0.5,
                                              "ramp_s": 0.5}]), scn, model="din")
    assert shaft["brake_force_kn"] == pytest.approx(head["brake_force_kn"], rel=1e-12)
    assert shaft["brake_governed_by"] == ["grip"]
    assert "drive 1's pulley (head)" in shaft["brake_note"]


def _decline_two_auto_brakes():
    """A 2.5 km steel-cord decline falling 120 m (ST1600, 2000 t/h at 4 m/s, net pull m'_L g H
    = 138.9 x 9.81 x 120 = 163.5 kN), auto gravity take-up at the tail, an auto brake on the
    head drive's pulley and one on the tail pulley."""
    return parse_conveyor(decline_2500_dict(
        name="decline-two-brakes",
        brakes=[{"position": "head", "force_kn": "auto", "delay_s": 1.0},
                {"position": "tail", "force_kn": "auto", "delay_s": 1.0}]))


def test_auto_holding_brakes_are_shared_by_their_pulleys_grip():
    """Holding sets the two auto brakes at 1.2 x 163.5 = 196.2 kN. Shared equally, 98.1 kN
    each, the head pulley's brake is beyond what that pulley passes in the stop (74.45 kN
    with the tail's share set) while the tail pulley has room: both together pass 287.7 kN.
    An auto size is sized within its pulley's grip (issue 26, brakes within their grip), so
    the holding force is now shared by grip: the head brake at most its pulley's grip, the tail
    the rest, the total still 196.2 kN, and no pulley beyond its grip. With a 40 t take-up
    the two together pass 131.9 kN, less than the holding force: the equal share stays, and the
    note quotes the short head pulley's own grip against the force set on it (not the braked
    pulleys' total, which may exceed the whole). (Engine 0.6.25 counts no brake's rise against
    another's fall, so the 30 t take-up this test had leaves the head pulley no grip at all.)"""
    conv = _decline_two_auto_brakes()
    scn = Scenario(stop={"mode": "brake", "time_s": 30.0})
    sizes = auto_sizes(conv, scn, model="din")
    hold = 1.2 * 2000 / 3.6 / 4.0 * G * 120.0 / 1e3
    assert sizes["brake_governed_by"] == ["holding", "holding"]
    head, tail = sizes["brake_force_kn"]
    assert head + tail == pytest.approx(hold, rel=1e-6)
    assert head < hold / 2 < tail
    assert sizes["brake_grip_kn"] > hold
    note = sizes["brake_note"]
    assert "shared by the braked pulleys' grip in the stop" in note
    assert "beyond the grip" not in note  # each pulley within its grip (1e-6)

    light = conv.model_copy(update={"takeup": conv.takeup.model_copy(update={"mass_kg": 40000})})
    sizes = auto_sizes(light, scn, model="din")
    assert sizes["brake_force_kn"] == pytest.approx([hold / 2, hold / 2], rel=1e-3)
    assert sizes["brake_grip_kn"] < hold
    note = sizes["brake_note"]
    m = re.search(r"beyond the grip of drive 1's pulley \(head\) \(it passes at most ([0-9.]+) "
                  r"kN against the ([0-9.]+) kN set on it\) in the stop \(with ", note)
    assert m, note
    assert float(m.group(2)) == pytest.approx(hold / 2, rel=1e-3)
    assert float(m.group(1)) < float(m.group(2))  # the claim 'beyond' holds for the figure
    assert f"{sizes['brake_grip_kn']:.4g} kN" not in note  # not the total's grip
    # a 20 t take-up: the head pulley passes no brake force at all; said as what it is, not
    # as 'it passes at most 0 kN'
    lighter = conv.model_copy(update={"takeup": conv.takeup.model_copy(update={"mass_kg":
                                                                            20000})})
    note = auto_sizes(lighter, scn, model="din")["brake_note"]
    assert ("drive 1's pulley (head) (unbraked, its slack side already falls so far that it "
            f"passes no brake force against the {hold / 2:.4g} kN set on it)") in note
    assert "at most 0 kN" not in note


def test_a_given_takeup_is_reported_as_given_not_through_its_tension():
    """A study writes its design's take-up into each run's conveyor (3748.2 kg) and its row's
    takeup_mass_kg must be that conveyor's: the summary said 2 (3748.2 G / 2) / G =
    3748.1999999999994 kg, and a user who wrote the row's figure back into the conveyor got
    other transient figures (last bits, up to 7e-11 relative in the error bars). A fixed
    take-up's pretension_kn is reported as given the same way (10.0071 kN x 1e3 / 1e3 is not
    10.0071)."""
    assert 2.0 * (3748.2 * G / 2.0) / G != 3748.2  # the round trip this guards against
    assert 10.0071 * 1e3 / 1e3 != 10.0071
    data = hand_conveyor_dict()
    data["takeup"] = {**data["takeup"], "type": "gravity", "mass_kg": 3748.2}
    data["takeup"].pop("pretension_kn", None)
    conv = parse_conveyor(data)
    s = run_one(conv, Scenario(), model="din", dynamics=False).summary
    assert s["takeup_mass_kg"] == 3748.2
    assert auto_sizes(conv, Scenario(), model="din")["takeup_mass_kg"] == 3748.2

    data["takeup"] = {k: v for k, v in data["takeup"].items() if k != "mass_kg"}
    data["takeup"].update(type="fixed", pretension_kn=10.0071)
    conv = parse_conveyor(data)
    s = run_one(conv, Scenario(), model="din", dynamics=False).summary
    assert s["takeup_pretension_kn"] == 10.0071
    assert s["takeup_mass_kg"] is None
