"""A brake whose delay outlasts the stop takes no part in it (SPEC 6.1: the brakes come on
``delay_s`` after the stop command). fabric-1km with a 20 kN head brake at delay_s 500 (0.5 s
written as milliseconds) stopped in 5.9 s as it coasts, f_brake_kn 0: the message spoke of
the brake's force beyond its pulley's grip and offered less force, never that the brake had
not acted."""

from __future__ import annotations

from beltstudy.engine.conveyor import Scenario, parse_conveyor
from beltstudy.engine.run import run_one
from tests.conftest import hand_conveyor_dict

G = 9.81


def _level(delay_s: float):
    """The hand conveyor laid level: 1 km, 4 m/s, a 20 kN head brake."""
    return parse_conveyor(hand_conveyor_dict(
        profile=[{"length_m": 1000, "lift_m": 0}],
        brakes=[{"position": "head", "force_kn": 20, "delay_s": delay_s, "ramp_s": 0.5}]))


def test_a_brake_that_comes_on_after_the_belt_is_at_rest_is_named():
    """Hand bound of the coast: moving mass 1000 m x (2 x 20 belt + 50 load + 10 + 3 idlers)
    = 103 t, 110 t with pulleys and drive; DIN's main resistance alone 0.020 x 1000 m x g x
    103 kg/m = 20.2 kN; so the belt is at rest within 110 t x 4 m/s / 20.2 kN = 21.8 s. A
    brake delayed 60 s never acts in the stop, and the warning names its field."""
    bound_s = 110e3 * 4.0 / (0.020 * 1000 * G * 103)
    scn = Scenario.model_validate({"stop": {"mode": "brake", "time_s": 10.0}, "elements": 40})
    res = run_one(_level(60.0), scn, model="din")
    s = res.summary
    assert s["stop_time_s"] < bound_s < 60.0
    assert s["status"] == "warning"
    assert "brake 1 never acted in the stop: its delay (brakes.0.delay_s 60 s" in s["message"]
    assert "0.06 s if 60 is ms" in s["message"]
    on_time = run_one(_level(0.5), scn, model="din").summary
    assert (on_time["f_brake_kn"] or 0.0) > 0.0
    assert "never acted" not in on_time["message"]
