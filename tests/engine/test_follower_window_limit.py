"""A torque follower's speed window acts through its motor's torque, within its limit.

A light tail follower behind a 200 kg take-up slips in the start (its pulley grips under
1 kN) and spins its shaft up during the hand-over; the speed loop's window then brings the
shaft back towards the reference. The window set the shaft's speed in one step whatever that
took: 505 kN of drive force for one step (0.95 ms) on a drive whose torque limit is 15.6 kN,
which the run reported as its largest force and its overload. A motor passes at most its
torque limit (``torque_limit`` x rated force, rated force = rated power / design speed), so
it brings the shaft back over the steps that follow.
"""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pytest

from beltstudy.engine import load_conveyor, parse_conveyor
from beltstudy.engine.conveyor import Scenario, load_mapping
from beltstudy.engine.dynamics.model import DynamicsOptions
from beltstudy.engine.run import run_one
from tests.conftest import CONVEYORS

SPEED = 3.0
LIMIT = 1.5


def _conveyor() -> dict:
    drive = dict(wrap_deg=200, friction=0.35, pulley_diameter_m=0.8, torque_limit=LIMIT)
    return dict(
        name="short-multi", speed_m_s=SPEED, belt={"type": "ST1000", "width_m": 1.0},
        material={"capacity_t_h": 800, "density_t_m3": 1.0},
        profile=[{"length_m": 200, "lift_m": 10}, {"length_m": 200, "lift_m": 30}],
        idlers={"carry": {"spacing_m": 1.5, "roll_diameter_m": 0.152, "rolls": 3,
                          "trough_deg": 35, "cema_class": "C"},
                "return": {"spacing_m": 3.0, "roll_diameter_m": 0.152, "rolls": 1,
                           "cema_class": "C"}},
        drives=[dict(drive, position="head", share=0.5, inertia_kg_m2=200),
                dict(drive, position="head", share=0.3, inertia_kg_m2=200),
                dict(drive, position="tail", share=0.2, inertia_kg_m2=100)],
        takeup={"type": "gravity", "position": "tail", "mass_kg": 200, "travel_m": 5},
        holdback=False)


@pytest.mark.parametrize("options", [{}, {"dt_s": 0.0004}, {"elements": 400}],
                         ids=["defaults", "finer-step", "finer-mesh"])
def test_a_follower_never_passes_more_than_its_torque_limit(options):
    scn = dict(start={"control": "s-curve", "time_s": 8}, run_s=4, stop={"mode": "coast"})
    scn.update(options)
    r = run_one(parse_conveyor(_conveyor()), Scenario(**scn), model="din",
                options=DynamicsOptions())
    s = r.summary
    # the tail follower slips (the case the window acts in)
    assert s["drive3_slip_s"] > 0.0
    for i in (1, 2, 3):
        rated_kn = s[f"drive{i}_rated_power_kw"] / SPEED
        limit_kn = LIMIT * rated_kn
        assert s[f"drive{i}_force_max_kn"] <= limit_kn * (1.0 + 1e-9), (i, limit_kn)
    # the peak of all drives together is within the sum of their limits
    total = sum(LIMIT * s[f"drive{i}_rated_power_kw"] / SPEED for i in (1, 2, 3))
    assert s["drive_force_max_kn"] <= total * (1.0 + 1e-9)


@pytest.mark.parametrize("elements", ["auto", 400])
def test_a_slipping_followers_shaft_obeys_newton_with_the_force_reported(elements):
    """overland-16km's tail follower slips for half a minute in its start. A slipping shaft
    of mass m (its inertia at the belt line) moves by m dv / dt = F_drive - F_belt over each
    step (no brake acts in the start). Its window pushed the shaft up to v_ref - window with a
    force the run never reported: at 40 s the motor gave 443 kN (its limit 450 kN) while its
    pulley passed 602 kN to the belt, 160 kN from nowhere. The window's force is now within
    the limit and in the drive's reported force, so the balance holds every step."""
    conv = load_conveyor(CONVEYORS / "overland-16km.yaml")
    r = run_one(conv, Scenario(stop={"mode": "coast"}, record_dt_s=2e-3, elements=elements),
                model="din")
    model = r.transient.system.model
    dt = model.cycle.dt
    ts = r.timeseries
    assert np.allclose(np.diff(ts["t_s"].to_numpy()), dt)  # one record a step
    k_tail = 1  # drive 2, at the tail
    m = model.shafts.mass[model.drives.shaft[k_tail]]
    lim = model.drives.lim0[k_tail]
    v = ts["v_drive2_m_s"].to_numpy()
    f_drive = ts["f_drive2_kn"].to_numpy() * 1e3
    f_belt = ts["f_belt2_kn"].to_numpy() * 1e3
    slipping = np.abs(v - ts["v_tail_m_s"].to_numpy()) > 1e-6
    k = np.flatnonzero(slipping[1:] & slipping[:-1]) + 1
    assert len(k) > 100  # it slips for many steps
    residual = m * (v[k] - v[k - 1]) / dt - (f_drive[k] - f_belt[k])
    assert np.abs(residual).max() <= 1e-6 * lim
    assert np.abs(f_drive).max() <= lim * (1.0 + 1e-9)


def _pair(rated_2_kw: float) -> dict:
    drive = dict(position="head", wrap_deg=220, friction=0.4, pulley_diameter_m=0.8,
                 torque_limit=LIMIT, share=0.5, inertia_kg_m2=50)
    return dict(
        name="pair", speed_m_s=SPEED, belt={"type": "ST1000", "width_m": 1.0},
        material={"capacity_t_h": 800, "density_t_m3": 1.0},
        profile=[{"length_m": 400, "lift_m": 30}],
        idlers={"carry": {"spacing_m": 1.5, "roll_diameter_m": 0.152, "rolls": 3,
                          "trough_deg": 35},
                "return": {"spacing_m": 3.0, "roll_diameter_m": 0.152, "rolls": 1}},
        drives=[dict(drive, rated_power_kw=150.0), dict(drive, rated_power_kw=rated_2_kw)],
        takeup={"type": "gravity", "position": "tail", "mass_kg": 6000, "travel_m": 5})


def test_time_at_the_torque_limit_is_the_force_there_not_a_rounding():
    """Two head drives rated in proportion to their shares: in a 3 s start the master sits at
    its limit (75 kN) for 1.1 s while the slipping follower's speed window holds its force at
    36-75 kN. Its time 'at its torque limit' was counted from the saturation of its share
    (share x U > limit, strictly): 0.1 s at the rating as given, 1.1 s with the rating
    1e-12 lower, as a study's rounded size tips it. It is now the time its force is at
    the limit, the same either way."""
    words = []
    for rated in (150.0, 150.0 * (1.0 - 1e-12), 150.0 * (1.0 + 1e-12)):
        r = run_one(parse_conveyor(_pair(rated)),
                    Scenario(start={"control": "s-curve", "time_s": 3}, run_s=3,
                             stop={"mode": "coast"}), model="din")
        message = r.summary["message"]
        said = [p for p in message.split("; ") if p.startswith("drive 2 (head) was above")]
        assert said, message
        words.append(said[0].split("(first at")[0])
    assert words[0] == words[1] == words[2]
    assert "at its torque limit (75 kN) for 0.1 s" in words[0]


_CASES = json.loads((Path(__file__).parent / "data" / "drive_limit_cases.json").read_text())


def _case(name: str):
    case = _CASES[name]
    return run_one(parse_conveyor(case["conveyor"]), Scenario(**case["scenario"]), model="din")


def test_the_start_hand_over_keeps_each_drive_within_its_limit():
    """A 640 m loaded decline on three drives (head 0.262, tail 0.372, a carry booster 0.366;
    torque limits 1.29, 1.87, 1.33) behind a light take-up: the hold passes 103 kN to the
    drives over the start's hand-over, each its share. Drive 1 was given 26.87 kN against its
    limit 24.71 kN (1.29 x 19.15 kN), drive 3 37.54 against 35.58 kN, and the run said drive
    1 was '40 % over its rating' on a drive that cannot pass 29 %."""
    r = _case("handover_decline")
    s = r.summary
    lim0 = r.transient.system.model.drives.lim0
    for i, limit in enumerate(lim0, start=1):
        assert s[f"drive{i}_force_max_kn"] * 1e3 <= limit * (1.0 + 1e-9), i
        series = np.abs(r.timeseries[f"f_drive{i}_kn"].to_numpy()) * 1e3
        assert series.max() <= limit * (1.0 + 1e-9), i


def test_a_followers_largest_force_is_one_it_gave():
    """Four drives, the master (a return booster, share 0.292) at its limit for 35 s of the
    start: the loop's output is held at the master's limit over its share, so a follower
    gives its share of that. Its largest force was read from the loop's output at the step's
    start before that limit (share x u0, capped only by its own limit): drive 2 (share 0.282)
    reported 31.29 kN, its own limit, where it never gave more than 20.92 kN = 0.282 / 0.292 x
    21.66 kN, and the words called it 81 % over its rating."""
    r = _case("master_at_limit")
    s = r.summary
    drives = r.transient.system.model.drives
    master = r.transient.system.model.control.master
    cap_u = drives.lim0[master] / drives.share[master]
    for i in range(len(drives.share)):
        if i == master:
            continue
        assert s[f"drive{i + 1}_force_max_kn"] * 1e3 <= drives.share[i] * cap_u * (1.0 + 1e-9)
        series = np.abs(r.timeseries[f"f_drive{i + 1}_kn"].to_numpy()) * 1e3
        assert s[f"drive{i + 1}_force_max_kn"] * 1e3 == pytest.approx(series.max(), rel=1e-9)


def test_a_dol_motor_is_never_said_to_be_at_a_torque_limit():
    """A dol motor's force is its curve (164.8 kN at breakaway on fabric-1km, 2.1 x its
    rating); its torque_limit is not read. Counting the time at the limit from the force (not
    from a vfd share's saturation) must leave dol drives out: fabric-1km's dol start was said
    to be 'at its torque limit (119 kN) for 0.021 s'."""
    data = load_mapping(CONVEYORS / "fabric-1km.yaml")
    data["drives"][0]["control"] = "dol"
    r = run_one(parse_conveyor(data), Scenario(stop={"mode": "coast"}), model="din")
    s = r.summary
    assert s["drive1_force_max_kn"] * 1e3 > r.transient.system.model.drives.lim0[0]
    assert "at its torque limit" not in s["message"]
    assert "held at its torque limit" not in s["message"]
