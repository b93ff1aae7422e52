"""A grip-held auto brake told a brake on another pulley: the figure makes up the whole.

A 3 km, -150 m regenerating decline's tail brake is held to its pulley's grip (372.9 kN)
below what the stop time asks. A brake on the head drive's shaft changes the tail pulley's
stop tensions, and the auto brake is sized again beside it. The note offered the head brake
the shortfall beside the grip size (103.3 kN for an 8 s stop); given, the tail brake fell to
328.5 kN, the stop missed again and the note asked for 44.47 kN more. The figure is now the
least that makes up the whole with the auto brake sized again beside it, rounded up, and
where the pulley cannot pass that, the note says so with both figures.
"""
from __future__ import annotations

import re

import pytest

from beltstudy.engine.conveyor import Scenario, parse_conveyor
from beltstudy.engine.run import run_one
from tests.engine.integration.test_brake_grip_fronts import DECLINE


def _run(stop_s: float, brakes=None):
    conv = parse_conveyor({**DECLINE, "brakes": brakes or DECLINE["brakes"]})
    scn = Scenario(start={"control": "s-curve", "time_s": 60},
                   stop={"mode": "brake", "time_s": stop_s})
    return run_one(conv, scn, model="din").summary


def test_the_brake_offered_on_another_pulley_meets_the_stop_when_given():
    s = _run(9.5)
    assert s["brake_governed_by"] == "grip"
    msg = s["message"]
    need = float(re.search(r"not by the stop time 9.5 s \(which needs ([\d.]+) kN\)", msg)[1])
    said = re.search(r"a brake on drive 1's shaft \(head\) of ([\d.]+) kN beside these \(its "
                     r"pulley passes up to ([\d.]+) kN; the auto brakes then ([\d.]+) kN, "
                     r"sized again within their grip beside it\)", msg)
    assert said, msg
    head, passes, auto = (float(x) for x in said.groups())
    assert head <= passes
    assert head + auto == pytest.approx(need, rel=1e-3)
    assert head > need - s["brake_force_kn"]  # more than the shortfall beside the grip size
    # followed: the auto brake is sized by the stop time beside it, and the whole is met
    after = _run(9.5, [*DECLINE["brakes"], {"drive": 1, "force_kn": head,
                                               "delay_s": 0.5, "ramp_s": 1.0}])
    assert after["brake_governed_by"] == "stop_time+given", after["brake_governed_by"]
    # the whole the stop time asks (the note prints it to 4 figures)
    assert after["brake_force_kn"] == pytest.approx(need, abs=0.05)
    assert after["brake_force_kn"] - head == pytest.approx(auto, rel=1e-3)


def test_a_pulley_that_cannot_pass_the_whole_is_named_with_both_figures():
    s = _run(8.0)
    msg = s["message"]
    said = re.search(r"not by a brake on another pulley alone: a brake on drive 1's shaft "
                     r"\(head\) would need ([\d.]+) kN beside the auto brakes, then [\d.]+ kN "
                     r"sized again within their grip beside it, and its pulley passes at most "
                     r"([\d.]+) kN",
                     msg)
    assert said, msg
    need, passes = float(said[1]), float(said[2])
    assert need > passes
    assert "beside these (its pulley passes" not in msg


FIXED = {
    "name": "c4-fixed", "speed_m_s": 2.5, "belt": {"type": "EP800/4", "width_m": 0.8},
    "material": {"capacity_t_h": 400, "density_t_m3": 1.5, "loading_speed_m_s": 0.0},
    "profile": [{"length_m": 250, "lift_m": -6}],
    "idlers": {"carry": {"spacing_m": 1.2, "roll_diameter_m": 0.102, "rolls": 3,
                         "trough_deg": 30, "cema_class": "B"},
               "return": {"spacing_m": 3.0, "roll_diameter_m": 0.102, "rolls": 1,
                          "cema_class": "B"}},
    "drives": [{"position": "head", "wrap_deg": 190, "friction": 0.30, "share": 1.0,
                "pulley_diameter_m": 0.63, "inertia_kg_m2": 40, "rated_power_kw": 75,
                "torque_limit": 1.5}],
    "takeup": {"type": "fixed", "position": "tail", "pretension_kn": "auto"},
    "brakes": [{"position": "tail", "force_kn": "auto", "delay_s": 0.2}],
    "holdback": False}


def test_a_fixed_take_ups_pretension_is_named_by_its_field():
    """A 250 m fabric decline on a screw take-up, its tail brake held to its grip in a 4 s
    stop: the note's pretension names the field that sets it, as a gravity take-up's mass
    does (takeup.mass_kg)."""
    scn = Scenario(start={"time_s": 20}, run_s=5, stop={"mode": "brake", "time_s": 4.0})
    s = run_one(parse_conveyor(FIXED), scn, model="din").summary
    assert s["brake_governed_by"] == "grip", s["brake_governed_by"]
    assert re.search(r"a take-up pretension of [\d.]+ kN \(takeup\.pretension_kn\)",
                     s["message"]), s["message"]


GIVEN_HEAD = {
    "name": "c5-decline2", "speed_m_s": 4.0,
    "belt": {"type": "ST2500", "width_m": 1.2, "compound": "standard"},
    "material": {"capacity_t_h": 2200, "density_t_m3": 1.7, "loading_speed_m_s": 0.0},
    "profile": [{"length_m": 1000, "lift_m": -40}, {"length_m": 1000, "lift_m": -110}],
    "idlers": DECLINE["idlers"],
    "drives": [{"position": "head", "wrap_deg": 210, "friction": 0.35, "share": 1.0,
                "pulley_diameter_m": 1.25, "inertia_kg_m2": 1500, "rated_power_kw": 900,
                "torque_limit": 1.5}],
    "takeup": {"type": "gravity", "position": "tail", "mass_kg": "auto", "travel_m": 12},
    "brakes": [{"position": "head", "force_kn": 60, "delay_s": 0.5},
               {"position": "tail", "force_kn": "auto", "delay_s": 0.5}],
    "holdback": False,
    "accessories": {"head_kn": 2.0, "tail_kn": 1.0}}


def test_a_brake_offered_on_a_pulley_counts_the_brake_already_given_there():
    """A 2 km decline with a given 60 kN head brake and an auto tail brake held to its grip:
    a brake on the head drive's shaft acts through the same pulley as the given one. It was
    offered 86.03 kN there (146 kN through a pulley that passes 103.2 kN), which slid 3.5 s
    when followed; the pulley's grip is now weighed against both."""
    scn = Scenario(start={"control": "s-curve", "time_s": 60},
                   stop={"mode": "brake", "time_s": 10.0})
    msg = run_one(parse_conveyor(GIVEN_HEAD), scn, model="din").summary["message"]
    assert "drive 1's shaft (head) of" not in msg, msg
    said = re.search(r"a brake on drive 1's shaft \(head\) would need ([\d.]+) kN beside the "
                     r"auto brakes, then [\d.]+ kN sized again within their grip beside it, and "
                     r"its pulley passes at most ([\d.]+) kN in all \(60 kN is given there "
                     r"already\)", msg)
    assert said, msg
    assert float(said[1]) + 60.0 > float(said[2])
