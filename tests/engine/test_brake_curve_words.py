"""The stop's brake advice reads a brake's force curve, not the ``ramp_s`` it does not read.

A given 30 kN head brake on the curve [[0, 0.5], [3, 1]] (half its force at once, full at
3 s) stops an 800 m incline in 5.06 s, under 5 wave loop times (6.06 s). The advice named
the largest force that lasts the 6.06 s "with the brakes' 0.5 s delay and 1 s ramp", a ramp
the brake does not have (10.98 kN); it now takes the curve (11.5 kN) and says so.
"""

from __future__ import annotations

import re

import pytest

from beltstudy.engine.conveyor import Scenario, parse_conveyor
from beltstudy.engine.dynamics import build_system, simulate
from beltstudy.engine.statics import solve_steady

CONV = {
    "name": "curve-brake-incline", "speed_m_s": 3.0,
    "belt": {"type": "ST1600", "width_m": 1.0},
    "material": {"capacity_t_h": 1000, "density_t_m3": 1.6},
    "profile": [{"length_m": 400, "lift_m": 40}, {"length_m": 400, "lift_m": -10}],
    "idlers": {"carry": {"spacing_m": 1.5, "roll_diameter_m": 0.133, "rolls": 3,
                         "trough_deg": 35, "rotating_mass_kg": 18.0},
               "return": {"spacing_m": 3.0, "roll_diameter_m": 0.133, "rolls": 1,
                          "rotating_mass_kg": 10.0}},
    "drives": [{"position": "head", "wrap_deg": 210, "friction": 0.35, "share": 1.0,
                "pulley_diameter_m": 1.0, "inertia_kg_m2": 400, "rated_power_kw": 400,
                "torque_limit": 1.5}],
    "takeup": {"type": "gravity", "position": "tail", "mass_kg": 8000},
    "brakes": [{"position": "head", "force_kn": 30, "delay_s": 0.5,
                "force_curve": [[0, 0.5], [3, 1.0]]}],
}


def _curve_integral(t: float) -> float:
    """The curve's fraction integrated from application to t [s]: 0.5 rising to 1 over 3 s,
    then 1."""
    if t <= 3.0:
        return 0.5 * t + t * t / 12.0
    return 2.25 + (t - 3.0)


def test_the_brake_advice_reads_the_force_curve():
    conv = parse_conveyor(CONV)
    st = solve_steady(conv, model="din", n_elements=60)
    sysm = build_system(conv, Scenario(elements=60, stop={"mode": "brake"}), st)
    r = simulate(sysm, conveyor=conv)
    said = re.search(r"at most about ([\d.]+) kN in all, now 30 kN \(rigid body, ([\d.]+) t "
                     r"from 3 m/s against Te ([\d.]+) kN with the brakes' 0\.5 s delay and "
                     r"their force curve \(full at 3 s\), a stop of ([\d.]+) s", r.message)
    assert said, r.message
    f_said, m_t, te_kn, need_s = (float(g) for g in said.groups())
    # by hand: coast 0.5 s at Te / M, then the brake's impulse F x integral(curve) over the
    # rest, to zero speed, moved out by the rest criterion's last stretch (1 % of the speed
    # at the deceleration the force gives), iterated as the words do
    m, te, v = m_t * 1e3, te_kn * 1e3, 3.0
    v1 = v - te * 0.5 / m
    force = 0.0
    t_stop = need_s
    for _ in range(4):
        t_b = t_stop - 0.5
        force = (m * v1 - te * t_b) / _curve_integral(t_b)
        t_stop = need_s + 0.01 * v * m / (te + force)
    assert f_said == pytest.approx(force / 1e3, rel=6e-3)
    assert "s ramp, a stop" not in r.message
