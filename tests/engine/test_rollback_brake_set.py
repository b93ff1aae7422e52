"""A belt that swings back after a brake stop with its brakes already at full force is not told
that a brake which sets sooner would hold it: that note is for a holding brake that sets after
the belt has stopped (``simulate.rollback_notes``).

A 600 m level belt at 3 m/s on a 12.7 t gravity take-up, auto head brake (0.5 s delay, 1 s
ramp) for a 6 s brake stop: the brake is at full force about 1.5 s after the stop command and
the belt stops some 4.8 s later; the take-up carriage then swings back with the belt's
stretch. The note said 'a holding brake that sets sooner (a shorter delay_s or ramp_s) holds
its pulley sooner'; set sooner (0.1 s, 0.2 s) the belt swung back further."""
from __future__ import annotations

import re

from beltstudy.engine.conveyor import Scenario, parse_conveyor
from beltstudy.engine.dynamics import DynamicsOptions
from beltstudy.engine.run import run_one

FLAT = {
    "name": "flat-600", "speed_m_s": 3.0,
    "belt": {"type": "EP630/4", "width_m": 1.0, "compound": "standard"},
    "material": {"capacity_t_h": 800, "density_t_m3": 1.6, "loading_speed_m_s": 0.0},
    "profile": [{"length_m": 600, "lift_m": 0}],
    "idlers": {"carry": {"spacing_m": 1.2, "roll_diameter_m": 0.127, "rolls": 3,
                         "trough_deg": 35, "cema_class": "C"},
               "return": {"spacing_m": 3.0, "roll_diameter_m": 0.127, "rolls": 1,
                          "cema_class": "C"}},
    "drives": [{"position": "head", "wrap_deg": 210, "friction": 0.35, "share": 1.0,
                "pulley_diameter_m": 0.8, "inertia_kg_m2": 80, "rated_power_kw": 160,
                "torque_limit": 1.5}],
    "takeup": {"type": "gravity", "position": "tail", "mass_kg": 12755, "travel_m": 6},
    "brakes": [{"position": "head", "force_kn": "auto", "delay_s": 0.5, "ramp_s": 1.0}],
    "holdback": False,
    "accessories": {"head_kn": 0.5, "tail_kn": 0.3},
}
SCN = Scenario(elements=60, run_s=5.0, start={"time_s": 20.0},
               stop={"mode": "brake", "time_s": 6.0})
SWUNG = (r"the belt swung back after it stopped: its mean speed was below -[\d.]+ m/s from "
         r"t = ([\d.]+) to [\d.]+ s, at most ([\d.]+) m/s backwards \(t = [\d.]+ s\), about "
         r"([\d.]+) m of belt, with its brakes at full force \(([\d.]+) kN together\) since "
         r"t = ([\d.]+) s")


def _run(brake: dict) -> tuple[dict, re.Match]:
    s = run_one(parse_conveyor({**FLAT, "brakes": [brake]}), SCN, model="din").summary
    said = re.search(SWUNG, s["message"])
    assert said, s["message"]
    return s, said


def test_a_swing_back_with_the_brakes_set_is_not_offered_a_sooner_brake():
    s, said = _run(FLAT["brakes"][0])
    t_cmd = DynamicsOptions().pre_rest_s + 20.0 + 5.0  # the rest, the start, the run [s]
    # the brake set at the command + delay + ramp, before the swing began
    assert float(said.group(5)) <= float(said.group(1))
    assert float(said.group(5)) >= t_cmd + 0.5 + 1.0 - 0.1
    assert abs(float(said.group(4)) - s["brake_force_kn"]) <= 0.01 * s["brake_force_kn"]
    assert "sets sooner (a shorter delay_s or ramp_s) holds" not in s["message"]
    assert "neither a holdback nor a brake that sets sooner would avoid it" in s["message"]
    assert "take-up carriage swinging back" in s["message"]
    # set sooner, at the same force, the belt swings back about as far: not a lever
    _, sooner = _run({**FLAT["brakes"][0], "force_kn": s["brake_force_kn"], "delay_s": 0.1,
                      "ramp_s": 0.2})
    assert float(sooner.group(3)) >= 0.9 * float(said.group(3)), (sooner.group(0),
                                                                   said.group(0))
