"""A controlled stop ramps down from the speed the belt has, not from design speed it never
reached (SPEC 2: 'the drive follows a reverse S-curve from speed to zero').

A level 1.5 km belt on one 400 kW vfd drive at a torque limit of 1.1 (110 kN against a running
force of about 51 kN), started with the torque control over 10 s, was at 1.70 m/s when its
controlled stop was commanded at 17 s. The stop's reference began at the design 4 m/s, the
speed loop held the drive at its limit for 7 s more, and the 'stop' drove the belt up to
3.47 m/s (at 0.24 m/s2, (110 - 50.7) kN / 245.7 t); a 40 s stop reached 105 % of design
speed. A master held at its limit below design speed now has its ramp start from its own
speed, the speed loop's integrator taking the force it gave (bumpless: no jolt)."""
from __future__ import annotations

import numpy as np
import pytest

from beltstudy.engine.conveyor import Scenario, parse_conveyor
from beltstudy.engine.run import run_one

LEVEL_SLOW = {
    "name": "level-slow", "speed_m_s": 4.0,
    "belt": {"type": "ST1250", "width_m": 1.0},
    "material": {"capacity_t_h": 1500, "density_t_m3": 1.6},
    "profile": [{"length_m": 1500, "lift_m": 0}],
    "idlers": {"carry": {"spacing_m": 1.5, "roll_diameter_m": 0.152, "rolls": 3,
                         "trough_deg": 35, "cema_class": "D"},
               "return": {"spacing_m": 3.0, "roll_diameter_m": 0.152, "rolls": 1,
                          "cema_class": "C"}},
    "drives": [{"position": "head", "wrap_deg": 210, "friction": 0.35, "share": 1.0,
                "pulley_diameter_m": 1.0, "inertia_kg_m2": 300, "rated_power_kw": 400,
                "torque_limit": 1.1}],
    "takeup": {"type": "gravity", "position": "tail", "mass_kg": 15000, "travel_m": 10},
}


@pytest.mark.parametrize("stop_s", [20.0, 40.0])
def test_a_controlled_stop_of_a_belt_short_of_speed_does_not_speed_it_up(stop_s):
    conv = parse_conveyor(LEVEL_SLOW)
    scn = Scenario(start={"control": "torque", "time_s": 10}, run_s=5,
                   stop={"mode": "controlled", "time_s": stop_s}, elements=40,
                   record_dt_s=0.05)
    res = run_one(conv, scn, model="din", check=False)
    ts = res.timeseries
    t = np.asarray(ts["t_s"])
    t_cmd = 2.0 + 10.0 + 5.0  # the rest before the start, the start and the run [s]
    before = t <= t_cmd + 1e-9
    v_drive = np.asarray(ts["v_drive_m_s"])
    v_cmd = float(v_drive[before][-1])
    assert 1.5 < v_cmd < 2.5  # short of its 4 m/s design speed at the command
    after = t > t_cmd
    # the ramp starts at the pulley's speed (within the step it is read at) and falls
    v_ref = np.asarray(ts["v_ref_m_s"])[after]
    assert v_ref[0] == pytest.approx(v_cmd, rel=0.02)
    assert np.all(np.diff(v_ref) <= 1e-12)
    # the pulley follows it: never 3 % above its speed at the command (it was 3.4 m/s)
    assert v_drive[after].max() <= 1.03 * v_cmd
    assert res.summary["velocity_max_m_s"] < 0.7 * conv.speed_m_s
    # no jolt at the switch: the drive's force right after the command is the force it gave
    f = np.asarray(ts["f_drive_kn"])
    assert f[after][0] == pytest.approx(f[before][-1], rel=0.05)


def test_a_controlled_stop_behind_a_slipping_pulley_ramps_from_the_belt():
    """The same belt on a 30 m decline, its controlled stop commanded 1 s after a 10 s torque
    start: the head pulley slips at the command (about 3.9 m/s against the belt's 2.5 m/s
    mean). Ramped from design speed, the drive kept pushing at its limit and the stop drove
    the belt's mean speed up to 3.87 m/s (97 % of design speed). The ramp now starts from
    the belt's mean speed, the pulley is pulled back onto its belt and the stop slows it."""
    data = dict(LEVEL_SLOW, name="level-slow-decline",
                profile=[{"length_m": 1500, "lift_m": -30}])
    conv = parse_conveyor(data)
    scn = Scenario(start={"control": "torque", "time_s": 10}, run_s=1,
                   stop={"mode": "controlled", "time_s": 15}, elements=40,
                   record_dt_s=0.05)
    res = run_one(conv, scn, model="din", check=False)
    ts = res.timeseries
    t = np.asarray(ts["t_s"])
    t_cmd = 2.0 + 10.0 + 1.0
    before = t <= t_cmd + 1e-9
    v_mean = np.asarray(ts["v_mean_m_s"])
    v_pulley = np.asarray(ts["v_drive_m_s"])
    v_belt_cmd = float(v_mean[before][-1])
    # the pulley runs well ahead of its belt at the command: it slips
    assert float(v_pulley[before][-1]) > 1.2 * v_belt_cmd
    after = t > t_cmd
    v_ref = np.asarray(ts["v_ref_m_s"])[after]
    assert v_ref[0] <= 1.02 * v_belt_cmd
    assert np.all(np.diff(v_ref) <= 1e-12)
    # the belt's mean speed stays well short of design speed (ramped from it: 97 %); what
    # it gains after the command is the stretch the drive's pull had stored and the slope
    assert v_mean[after].max() < 0.8 * conv.speed_m_s
