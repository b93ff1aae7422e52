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


#: A 900 m regenerating decline (-50 m) with a head drive, a booster on the return (at 250 m,
#: off the horizontal curve from 300 to 700 m: a drive pulley needs a straight run), the
#: take-up along the return and auto brakes at the head and the tail: the holding force, 1.2 x
#: the net gravity pull 25.89 kN = 31.07 kN, is beyond the head pulley's grip as an even share,
#: so the engine gives the head its grip (15.385 kN) and the tail the rest (15.680 kN), both
#: ``holding``. Its take-up is given at 6 710.93 kg, the auto size (``sag_at_rest``) before
#: the auto take-up let the braked head pulley hold the whole pull at rest (7 331.7 kg,
#: ``slip_breakaway``), at which the even share is within the head's grip.
DECLINE = {
    "name": "decline-two-brakes", "speed_m_s": 3.0,
    "belt": {"type": "EP630/4", "width_m": 1.0},
    "material": {"capacity_t_h": 600, "density_t_m3": 1.4, "feed": [
        {"at_m": 0, "share": 0.5, "skirt_length_m": 4},
        {"at_m": 250, "share": 0.5, "skirt_length_m": 3}]},
    "profile": [{"length_m": 300, "lift_m": -6, "curve_radius_m": 500},
                {"length_m": 400, "lift_m": -40, "horizontal_radius_m": 900,
                 "superelevation_deg": 4, "curve_radius_m": 700},
                {"length_m": 200, "lift_m": -4}],
    "idlers": {"carry": {"spacing_m": 1.2, "roll_diameter_m": 0.127, "rolls": 3,
                         "trough_deg": 35, "cema_class": "C"},
               "return": {"spacing_m": 3.0, "roll_diameter_m": 0.127, "rolls": 1,
                          "cema_class": "C"}},
    "drives": [{"position": "head", "wrap_deg": 210, "friction": 0.35, "share": 0.6,
                "pulley_diameter_m": 0.8, "inertia_kg_m2": 150, "torque_limit": 1.5},
               {"position": "return", "at_m": 250, "wrap_deg": 190, "friction": 0.35,
                "share": 0.4, "pulley_diameter_m": 0.8, "inertia_kg_m2": 100,
                "torque_limit": 1.5}],
    "takeup": {"type": "gravity", "position": "return", "at_m": 850,
               "mass_kg": 6710.932853668639, "travel_m": 10},
    "brakes": [{"position": "head", "force_kn": "auto", "delay_s": 0.5, "ramp_s": 1.5},
               {"position": "tail", "force_kn": "auto", "delay_s": 0.5}],
    "accessories": {"head_kn": 0.5, "tail_kn": 0.5},
}


def test_a_holding_share_at_its_pulleys_grip_is_written_in_within_the_grip():
    """The even share of a holding force beyond one pulley's grip is shared by the grip, both
    brakes still ``holding``: the head's share at its grip, 15.38514 kN, was rounded up like a
    least need to 15.3852 kN, and the study's run (not beltstudy simulate) said 'passes at
    most 15.39 kN of brake force in the stop against the 15.39 kN set ... a take-up of 6,711
    kg (6,710.94 kg written in) would let it pass that force'. It is now rounded down, what
    that takes off going to the other brake, so the two still hold the belt."""
    from beltstudy.service.grid.basis import apply_sizes

    conv = parse_conveyor(DECLINE)
    case = DesignCase(model="din", temperature_c=20.0, load="full")
    scn = {"load": "full", "temperature_c": 20, "stop": {"mode": "brake", "time_s": 15}}
    steady = solve_steady(conv, model="din", temperature_c=20.0, load="full")
    own = auto_sizes(conv, Scenario.model_validate(scn), model="din", steady=steady)
    head, tail = own["brake_force_kn"]
    assert own["brake_governed_by"] == ["holding", "holding"]
    assert "shared by the braked pulleys' grip" in own["brake_note"]
    assert head < tail  # the head at its grip, the tail the rest
    entry = size_design(conv, [case], stop_times=[15.0])["brakes"]["stop_time_s"]["15"]
    assert head * (1 - 1e-5) <= entry["force_kn"][0] <= head
    assert sum(entry["force_kn"]) >= head + tail
    run_conv, _ = apply_sizes(conv.model_dump(mode="json", by_alias=True),
                              size_design(conv, [case], stop_times=[15.0]), scn, True)
    given = parse_conveyor(run_conv)
    steady = solve_steady(given, model="din", temperature_c=20.0, load="full")
    assert auto_sizes(given, Scenario.model_validate(scn), model="din",
                      steady=steady)["brake_note"] == ""
