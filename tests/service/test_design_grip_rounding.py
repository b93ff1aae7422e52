"""A design brake held at its pulley's grip is written into the runs rounded down, not up.

Every auto size of a design is written into its runs rounded to six significant digits, up,
so that a least need never falls short by rounding. A brake held at its pulley's grip
(``brake_governed_by: grip``) is a most, not a least: rounded up, a 1.2 km undulating route's
head brake (cema, -20 C, loaded inclines, 3 s brake stop, 32 101 kg take-up) was written in
as 59.3205 kN against the 59.32052 kN its pulley passes, and the run at that very case said
'passes at most 59.32 kN of brake force in the stop against the 59.32 kN set ... a take-up of
32,102 kg ... would let it pass that force'.
"""

from __future__ import annotations

from beltstudy.engine import DesignCase
from beltstudy.engine.conveyor import Scenario, parse_conveyor
from beltstudy.engine.design import auto_sizes
from beltstudy.engine.statics import solve_steady
from beltstudy.service.grid.basis import round_down, size_design

ROUTE = {
    "name": "undul-1200", "speed_m_s": 3.5,
    "belt": {"type": "ST1600", "width_m": 1.0},
    "material": {"capacity_t_h": 1200, "density_t_m3": 1.0},
    "profile": [{"length_m": 400, "lift_m": 30}, {"length_m": 500, "lift_m": -45},
                {"length_m": 300, "lift_m": 20}],
    "idlers": {"carry": {"spacing_m": 1.2, "roll_diameter_m": 0.133, "rolls": 3,
                         "trough_deg": 35},
               "return": {"spacing_m": 3.0, "roll_diameter_m": 0.133, "rolls": 1}},
    "drives": [{"position": "head", "wrap_deg": 200, "friction": 0.35, "share": 1.0,
                "pulley_diameter_m": 0.8, "inertia_kg_m2": 300, "torque_limit": 1.5,
                "rated_power_kw": 370}],
    "takeup": {"type": "gravity", "position": "tail", "mass_kg": 32101, "travel_m": 6},
    "brakes": [{"position": "head", "force_kn": "auto", "delay_s": 0.3}],
}
CASE = DesignCase(model="cema", temperature_c=-20.0, load="inclines")
STOP = Scenario.model_validate({"load": "inclines", "temperature_c": -20.0,
                                "stop": {"mode": "brake", "time_s": 3.0}})


def test_round_down_by_hand():
    assert round_down(59.320523) == 59.3205
    assert round_down(59.3205) == 59.3205
    assert round_down(12_345_678.9) == 12_345_600.0
    assert round_down(0.000123456789) == 0.000123456
    assert round_down(0.0) == 0.0


def test_a_grip_held_design_brake_is_within_the_grip_at_its_own_case():
    conv = parse_conveyor(ROUTE)
    sizes = size_design(conv, [CASE], stop_times=[3.0])
    entry = sizes["brakes"]["stop_time_s"]["3"]
    assert entry["governed_by"] == ["grip"]
    steady = solve_steady(conv, model="cema", temperature_c=-20.0, load="inclines")
    grip_kn = auto_sizes(conv, STOP, model="cema", steady=steady)["brake_grip_kn"]
    # the 3 s stop asks more than the pulley passes (it took 4.09 s at the grip size) and
    # the holding floor, 1.2 x 1200 t/h / (3.6 x 3.5 m/s) x 9.81 x 50 m = 56.06 kN, is below it
    assert 56.06 < grip_kn < 62.0
    force = entry["force_kn"][0]
    assert grip_kn * (1 - 1e-5) <= force <= grip_kn
    # written into the run: the brake note finds it within the grip
    given = parse_conveyor({**ROUTE, "brakes": [{**ROUTE["brakes"][0], "force_kn": force}]})
    steady = solve_steady(given, model="cema", temperature_c=-20.0, load="inclines")
    assert auto_sizes(given, STOP, model="cema", steady=steady)["brake_note"] == ""
