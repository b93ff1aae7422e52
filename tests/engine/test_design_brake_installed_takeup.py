"""A design's brake-stop size is held within the grip its pulley has on the installed take-up.

Over a study's design cases the brake of a stop time is the largest need held within the
least grip over the cases (docs/dynamics.md): a force every case's pulley passes. The grip
grows with the braked pulley's slack-side tension, and every run has the take-up the design
installs, the largest over the cases. The grips were taken at each case's own auto take-up:
on a 500 m route (+5 m, then -8 m, tail drive and brake, fixed head take-up) over full,
inclines, declines and empty loads, DIN and CEMA, -20 and 25 C, the installed pretension is
31.0 kN (slip at start-up, loaded inclines, CEMA, -20 C), but the 4 s brake stop was held at
10.76 kN, the grip of the empty DIN case on its own 16.6 kN pretension, where on 31.0 kN
that pulley passes 21.06 kN and the least over the cases is 17.53 kN (empty, CEMA, -20 C);
the stop needs 29.59 kN at full load under DIN.
"""

from __future__ import annotations

import itertools

from beltstudy.engine import DesignCase, size_over_cases
from beltstudy.engine.conveyor import Conveyor, Scenario
from beltstudy.engine.design import auto_sizes
from beltstudy.engine.statics import solve_steady

ROUTE = {
    "name": "level-500-fixed", "speed_m_s": 3.0,
    "belt": {"type": "ST1000", "width_m": 0.8},
    "material": {"capacity_t_h": 500, "density_t_m3": 1.0},
    "profile": [{"length_m": 250, "lift_m": 5}, {"length_m": 250, "lift_m": -8}],
    "idlers": {"carry": {"spacing_m": 1.2, "roll_diameter_m": 0.108, "rolls": 3,
                         "trough_deg": 30},
               "return": {"spacing_m": 3.0, "roll_diameter_m": 0.108, "rolls": 1}},
    "drives": [{"position": "tail", "wrap_deg": 200, "friction": 0.3, "share": 1.0,
                "pulley_diameter_m": 0.63, "inertia_kg_m2": 40, "torque_limit": 1.5}],
    "takeup": {"type": "fixed", "position": "head", "pretension_kn": "auto"},
    "brakes": [{"position": "tail", "force_kn": "auto", "delay_s": 0.2}],
}
LOADS, MODELS, TEMPS = ("full", "inclines", "declines", "empty"), ("din", "cema"), (-20.0, 25.0)


def _grip_kn(conv: Conveyor, model: str, temp: float, load: str) -> float:
    steady = solve_steady(conv, model=model, temperature_c=temp, load=load)
    scn = Scenario.model_validate({"load": load, "temperature_c": temp,
                                   "stop": {"mode": "brake", "time_s": 4.0}})
    return auto_sizes(conv, scn, model=model, steady=steady)["brake_grip_kn"]


def test_the_brake_stop_size_is_the_least_grip_on_the_installed_take_up():
    conv = Conveyor.model_validate(ROUTE)
    cases = [DesignCase(model=m, temperature_c=t, load=ld)
             for ld, m, t in itertools.product(LOADS, MODELS, TEMPS)]
    sized = size_over_cases(conv, cases, stop_times=[4.0])
    pretension = sized.takeup.value
    assert 30.0 < pretension < 32.0
    brake = sized.brakes_by_stop[4.0]
    assert brake.governed_by == ("grip",)
    installed = Conveyor.model_validate(
        {**ROUTE, "takeup": {**ROUTE["takeup"], "pretension_kn": pretension}})
    grips = {(m, t, ld): _grip_kn(installed, m, t, ld)
             for ld, m, t in itertools.product(LOADS, MODELS, TEMPS)}
    least = min(grips.values())
    # a force every case's pulley passes on the installed take-up, and no less than that
    assert brake.force_kn[0] <= least * (1 + 1e-9)
    assert brake.force_kn[0] >= least * (1 - 1e-6)
    assert min(grips, key=grips.get) == ("cema", -20.0, "empty")
    assert brake.at == "empty, cema, -20 C"
    # well above the 10.76 kN of the empty DIN case on its own 16.6 kN pretension
    assert brake.force_kn[0] > 17.0
