"""A belt safety factor below 1 was said only as 'below the minimum 6.70': a largest tension
above the belt's breaking strength is now said as what it is (statics and the transient,
tests/engine/dynamics/test_simulate.py)."""
from __future__ import annotations

import pytest

from beltstudy.engine.conveyor import parse_conveyor
from beltstudy.engine.statics import solve_steady
from tests.conftest import hand_conveyor_dict


def _steady(rating_kn_m: float):
    d = hand_conveyor_dict()
    d["belt"] = {**d["belt"], "rating_kn_m": rating_kn_m}
    return solve_steady(parse_conveyor(d), model="din")


def test_a_running_tension_past_the_breaking_strength_is_said():
    res = _steady(60.0)  # a 60 kN belt (1 m wide) on the 1 km, 50 m lift hand conveyor
    t_max_kn = float(res.summary["t_max_kn"])
    sf = 60.0 / t_max_kn  # S = k_N B / T_max
    assert sf < 1.0
    assert res.summary["safety_factor"] == pytest.approx(sf, rel=1e-9)
    assert (f"belt safety factor {sf:.2f} is below the minimum" in res.message), res.message
    assert ("below 1, the largest running tension is above the belt's breaking strength: the "
            "belt would break") in res.message


def test_a_factor_below_the_minimum_but_above_one_is_not_called_breaking():
    res = _steady(400.0)
    assert 1.0 < float(res.summary["safety_factor"]) < 6.7, res.summary["safety_factor"]
    assert "below the minimum" in res.message
    assert "breaking strength" not in res.message
