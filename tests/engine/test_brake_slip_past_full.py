"""A drive pulley whose brake's full force is beyond its grip slips in a brake stop whatever the
brake's ramp: the slip warning must not offer a longer ramp (brakes[].ramp_s) as its cure."""
from __future__ import annotations

import re

import pytest

from beltstudy.engine.conveyor import Scenario, parse_conveyor
from beltstudy.engine.dynamics import DynamicsOptions, build_system, simulate
from beltstudy.engine.statics import solve_steady

G = 9.81


def _decline(ramp_s: float) -> dict:
    """A 1.2 km regenerating decline (100 m drop, ST1250, 1 200 t/h at 3.5 m/s) with one auto
    brake on its head drive: the brake is set by holding the loaded belt at rest."""
    return {
        "name": "regen-decline-brake-on-drive", "speed_m_s": 3.5,
        "belt": {"type": "ST1250", "width_m": 1.0},
        "material": {"capacity_t_h": 1200, "density_t_m3": 1.6},
        "profile": [{"length_m": 800, "lift_m": -80}, {"length_m": 400, "lift_m": -20}],
        "idlers": {"carry": {"spacing_m": 1.2, "roll_diameter_m": 0.133, "rolls": 3,
                             "trough_deg": 35, "cema_class": "D"},
                   "return": {"spacing_m": 3.0, "roll_diameter_m": 0.133, "rolls": 1,
                              "cema_class": "C"}},
        "drives": [{"position": "head", "wrap_deg": 210, "friction": 0.35, "share": 1.0,
                    "pulley_diameter_m": 1.0, "inertia_kg_m2": 300, "rated_power_kw": 250,
                    "torque_limit": 1.5}],
        "takeup": {"type": "gravity", "position": "tail", "mass_kg": "auto", "travel_m": 4},
        "brakes": [{"position": "head", "force_kn": "auto", "delay_s": 0.5, "ramp_s": ramp_s}],
        "holdback": True,
        "accessories": {"head_kn": 1.0, "tail_kn": 0.5},
    }


def _run(ramp_s: float):
    conv = parse_conveyor(_decline(ramp_s))
    scn = Scenario(start={"control": "s-curve", "time_s": 30}, run_s=10,
                   stop={"mode": "brake", "time_s": 20}, elements=60)
    st = solve_steady(conv, model="din", load=scn.load, n_elements=60)
    sys_ = build_system(conv, scn, st, DynamicsOptions())
    return sys_, simulate(sys_, steady_summary=st.summary, conveyor=conv)


def test_a_slip_past_the_brakes_full_force_is_not_offered_a_longer_ramp():
    # the holding force by hand: 1.2 x the loaded lift m'_L g H, m'_L = 1200 / (3.6 x 3.5)
    hold_kn = 1.2 * 1200 / (3.6 * 3.5) * G * 100.0 / 1e3
    assert hold_kn == pytest.approx(112.11, abs=0.01)
    sys_, res = _run(1.0)
    assert float(sys_.model.brakes.force.sum()) / 1e3 == pytest.approx(hold_kn, rel=1e-9)
    msg = res.message
    slip = [p for p in msg.split("; drive") if "slipped on its pulley during the stop" in p]
    assert slip, msg
    words = slip[0]
    m = re.search(r"from t = ([\d.]+) to ([\d.]+) s", words)
    t_full = sys_.stop_command_s + 0.5 + 1.0  # the command, the delay and the 1 s ramp
    assert float(m.group(2)) > t_full + 1.0  # slid long after the full force
    assert "brakes[].ramp_s) would not" in words
    assert "a longer brake ramp" not in words
    assert f"reached full force (t = {t_full:.1f} s)" in words
    assert "part of the brake force on a brake on another pulley" in words
    # the auto brake is at its holding size: less force on it would not hold the belt at rest
    assert (f"(not less force on this one: its {hold_kn:.4g} kN is what holds the loaded belt "
            "at rest, 1.2 x its net gravity pull)") in words
    assert "or less brake force on this one" not in words
    # the ramp indeed does not cure it: five times longer, the belt slides as long or longer
    _, res5 = _run(5.0)
    assert res5.summary["drive1_slip_s"] >= 0.9 * res.summary["drive1_slip_s"] > 5.0


def test_a_given_brake_above_its_holding_size_is_offered_less_force_down_to_it():
    """A given 150 kN brake where 1.2 x the net gravity pull is 112.11 kN: less force on it is
    offered down to the holding size, rounded up (113 kN), not below."""
    d = _decline(1.0)
    d["brakes"] = [{**d["brakes"][0], "force_kn": 150}]
    conv = parse_conveyor(d)
    scn = Scenario(start={"control": "s-curve", "time_s": 30}, run_s=10,
                   stop={"mode": "brake", "time_s": 20}, elements=60)
    st = solve_steady(conv, model="din", load=scn.load, n_elements=60)
    sys_ = build_system(conv, scn, st, DynamicsOptions())
    msg = simulate(sys_, steady_summary=st.summary, conveyor=conv).message
    assert ("or less brake force on this one (now 150 kN; a given force_kn of at least 113 kN, "
            "which with the others holds the loaded belt at rest, 1.2 x its net gravity pull)"
            ) in msg, msg


def test_an_empty_belts_pull_that_cancels_round_the_loop_is_no_force_to_hold():
    """An empty 400 m incline's brake-stop slip read 'a given force_kn of at least 5.12e-17 kN,
    which ... holds the loaded belt at rest': the belt's own weight pulls as much down the
    return as up the carry, and the sum of the elements' gravity is rounding noise. A pull
    below 1 mN is none: the words give no holding figure."""
    from types import SimpleNamespace

    import numpy as np

    from beltstudy.engine.dynamics import codes as C
    from beltstudy.engine.dynamics.simulate import _brake_past_full

    g = np.array([5.12e-17 * 1e3 / 1.2, 0.0, 0.0, 0.0])  # the sum the incline's terms left
    sys_ = SimpleNamespace(
        stop_command_s=90.0,
        model=SimpleNamespace(
            cycle=SimpleNamespace(stop_mode=C.BRAKE),
            brakes=SimpleNamespace(shaft=np.array([0]), delay=np.array([0.5]),
                                   ramp=np.array([1.0]), curve_n=np.array([0]),
                                   curve_t=np.zeros((1, 1)), force=np.array([40e3])),
            shafts=SimpleNamespace(drive=np.array([0]), hb=np.array([0])),
            nodes=SimpleNamespace(gravity=g),
            takeup=SimpleNamespace(gravity=True)))
    levers, why = _brake_past_full(sys_, 0, 100.0)
    assert "less brake force on this one (now 40 kN; a given force_kn)" in levers, levers
    assert "at least" not in levers and not re.search(r"\de-\d", levers)
    assert "reached full force (t = 91.5 s)" in why
