"""What a stop's words offer where the lever they name cannot act.

* An auto brake held to its pulley's grip (``brake_governed_by`` grip): a 1.5 km, -120 m loaded
  decline asked an 8 s brake stop; the grip held the head brake at 157.1 kN, the stop took
  11.9 s, under 5 wave loop times (13 s), and the words offered "a stop.time_s of 8.8 s or
  more". Followed, the brake stayed at 157.1 kN, the stop at 11.89 s, and the words then asked
  for 9.6 s. No stop time below the grip force's own rigid-body stop (about 11.7 s) changes the
  brake. The words now name a stop time past it, scaled as this run's stop scaled from its
  rigid-body one, and say the asked 8 s is itself shorter than 5 wave loop times.
* A drive pulley slipping through steady running into the stop (its steady margin under 1)
  was offered "a longer start", which no start changes; it is offered its pulley's grip and
  its share of the drive force.
"""
from __future__ import annotations

import re

import pytest

from beltstudy.engine.conveyor import Scenario, parse_conveyor
from beltstudy.engine.run import run_one

DECLINE = {
    "name": "decline1500", "speed_m_s": 3.0, "belt": {"type": "ST1250", "width_m": 1.0},
    "material": {"capacity_t_h": 1200, "density_t_m3": 1.6, "loading_speed_m_s": 0.0},
    "profile": [{"length_m": 1500, "lift_m": -120}],
    "idlers": {"carry": {"spacing_m": 1.2, "roll_diameter_m": 0.152, "rolls": 3,
                         "trough_deg": 35, "cema_class": "D"},
               "return": {"spacing_m": 3.0, "roll_diameter_m": 0.152, "rolls": 1,
                          "cema_class": "C"}},
    "drives": [{"position": "head", "wrap_deg": 210, "friction": 0.35, "share": 1.0,
                "pulley_diameter_m": 1.0, "inertia_kg_m2": 300, "rated_power_kw": 400,
                "torque_limit": 1.5}],
    "takeup": {"type": "gravity", "position": "tail", "mass_kg": 88982, "travel_m": 6},
    "brakes": [{"position": "head", "force_kn": "auto", "delay_s": 0.5}],
    "holdback": False}


def _brake_stop(stop_s: float, **route):
    conv = {**DECLINE, **route}
    scn = Scenario(elements=60, start={"time_s": 30}, run_s=10,
                   stop={"mode": "brake", "time_s": stop_s})
    return run_one(parse_conveyor(conv), scn, model="din").summary


#: The same belt level on a 20 t take-up: the grip holds the head brake at 24.7 kN, far
#: above its holding force (0: a level belt has no pull)
LEVEL = {"profile": [{"length_m": 1500, "lift_m": 0}],
         "takeup": {**DECLINE["takeup"], "mass_kg": 20000}}


def test_a_grip_held_brake_is_told_a_stop_time_that_changes_it():
    s = _brake_stop(3.0, **LEVEL)
    assert s["brake_governed_by"].startswith("grip"), s["brake_governed_by"]
    msg = s["message"]
    need = 5.0 * s["wave_loop_time_s"]
    assert s["stop_time_s"] < need  # the premise: a high-stress stop
    assert "(the stop.time_s asked, 3 s, is itself shorter than that)" in msg, msg
    said = re.search(r"or a stop\.time_s of ([\d.]+) s or more \(the auto brake is held to "
                     r"its pulley's grip, whose rigid-body stop takes ([\d.]+) s: a "
                     r"stop\.time_s below that leaves it as it is\)", msg)
    assert said, msg
    asked, t_grip = float(said.group(1)), float(said.group(2))
    assert asked > t_grip
    # the rigid-body stop at the grip force, as the design note gives it
    note = re.search(r"the rigid-body brake stop then takes about ([\d.]+) s", msg)
    assert note and float(note.group(1)) == pytest.approx(t_grip, rel=0.01)
    # a time below it leaves the brake and the stop as they are
    below = _brake_stop(0.5 * (3.0 + t_grip), **LEVEL)
    assert below["brake_force_kn"] == pytest.approx(s["brake_force_kn"], rel=1e-9)
    assert below["stop_time_s"] == pytest.approx(s["stop_time_s"], abs=1e-6)
    # followed: the auto brake is sized by that time, below the grip, and the stop lasts
    # 5 wave loop times: no high-stress stop
    after = _brake_stop(asked, **LEVEL)
    assert after["brake_force_kn"] < s["brake_force_kn"]
    assert after["brake_governed_by"].startswith("stop_time")
    assert after["stop_time_s"] >= need and "high-stress" not in after["message"]


def test_no_stop_time_is_offered_where_the_holding_force_keeps_the_brake():
    """The 1.5 km, -120 m decline: the grip holds the brake at 157.1 kN, and the holding force
    (1.2 x the 130.8 kN pull) is 157.0 kN, so no auto brake is softer: 8.8 s, and even 13 s,
    leave the stop at 11.9 s. The words offered 8.8 s, then 9.6 s; they now say no stop
    time would, with the force curve that does."""
    s = _brake_stop(8.0)
    assert s["brake_governed_by"].startswith("grip"), s["brake_governed_by"]
    msg = s["message"]
    assert "(the stop.time_s asked, 8 s, is itself shorter than that)" in msg, msg
    assert "no stop.time_s would: the auto brake is held to its pulley's grip" in msg, msg
    assert "no auto brake falls below the holding force 157 kN" in msg
    assert "or a stop.time_s of" not in msg
    later = _brake_stop(13.0)
    assert later["stop_time_s"] < 5.0 * later["wave_loop_time_s"]
    assert "brakes[].force_curve" in msg  # the lever that works (13.6 s when followed)


BOOSTED = {
    "name": "c4-boosters", "speed_m_s": 4.0, "belt": {"type": "ST1250", "width_m": 1.0},
    "material": {"capacity_t_h": 1200, "density_t_m3": 1.4},
    "profile": [{"length_m": 1000, "lift_m": 20}, {"length_m": 1000, "lift_m": 40}],
    "idlers": {"carry": {"spacing_m": 1.5, "roll_diameter_m": 0.152, "rolls": 3,
                         "trough_deg": 35, "cema_class": "D"},
               "return": {"spacing_m": 3.0, "roll_diameter_m": 0.152, "rolls": 1,
                          "cema_class": "C"}},
    "drives": [{"position": "head", "wrap_deg": 210, "friction": 0.35, "share": 0.5,
                "pulley_diameter_m": 1.0, "inertia_kg_m2": 400},
               {"position": "carry", "at_m": 800, "wrap_deg": 90, "friction": 0.35,
                "share": 0.3, "pulley_diameter_m": 1.0, "inertia_kg_m2": 300},
               {"position": "return", "at_m": 1200, "wrap_deg": 200, "friction": 0.35,
                "share": 0.2, "pulley_diameter_m": 1.0, "inertia_kg_m2": 200}],
    "takeup": {"type": "gravity", "position": "return", "at_m": 1900, "mass_kg": 9000,
               "travel_m": 10},
    "holdback": True}


def test_a_pulley_slipping_through_steady_running_is_offered_its_grip_not_a_longer_start():
    """A carry booster of 90 deg wrap on a 9 t take-up: its steady slip margin is
    e^(0.35 pi / 2) / (T1 / T2) = 1.733 / 2.459 = 0.70 by hand (the statics say so), so it
    slips from its start to the stop command and on. It was offered 'a heavier take-up or a
    longer start', and no start changes a steady slip."""
    conv = parse_conveyor(BOOSTED)
    s = run_one(conv, Scenario(elements=60, start={"time_s": 60}, run_s=60),
                model="din").summary
    assert s["drive2_slip_margin"] < 1.0  # the premise, statics
    msg = s["message"]
    said = re.search(r"drive 2 \(carry at 800 m\) slipped on its pulley from the start into "
                     r"the stop: [^;]*; ([^;]*) would avoid it", msg)
    assert said, msg
    fix = said.group(1)
    assert "longer start" not in fix
    assert ("more grip on that pulley (a lagged pulley, drives[].friction, or a snub pulley, "
            "drives[].wrap_deg) or a smaller share of the drive force on it "
            "(drives[].share)") in fix


def test_more_wrap_is_offered_for_a_drive_pulley_only():
    """A plain pulley has no wrap field (it is taken as 180 deg): a grip-held brake on the
    tail pulley of a 3 km, -150 m decline (take-up at the head, an 8 s brake stop) was
    offered "a wrap of 222 deg on the tail pulley (now 180)", which no file can give."""
    conv = {**DECLINE, "speed_m_s": 4.5, "belt": {"type": "ST2000", "width_m": 1.2},
            "material": {"capacity_t_h": 2000, "density_t_m3": 1.5, "loading_speed_m_s": 0},
            "profile": [{"length_m": 1500, "lift_m": -60}, {"length_m": 1500, "lift_m": -90}],
            "drives": [{"position": "head", "wrap_deg": 210, "friction": 0.35, "share": 1.0,
                        "pulley_diameter_m": 1.25, "inertia_kg_m2": 1200,
                        "torque_limit": 1.5}],
            "takeup": {"type": "gravity", "position": "head", "mass_kg": "auto",
                       "travel_m": 15},
            "brakes": [{"position": "tail", "force_kn": "auto", "delay_s": 0.5,
                        "ramp_s": 1.0}]}
    scn = Scenario(elements=60, start={"time_s": 30}, run_s=10,
                   stop={"mode": "brake", "time_s": 8})
    s = run_one(parse_conveyor(conv), scn, model="din").summary
    assert s["brake_governed_by"].startswith("grip"), s["brake_governed_by"]
    said = re.search(r"would be met by ([^;]*(?:; or [^;]*)*)", s["message"]).group(1)
    assert "(takeup.mass_kg)" in said  # the premise: the remedies are said
    assert "wrap" not in said, said
