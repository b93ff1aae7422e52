"""A profile section shorter than the rounding of where it ends along the route (1e-17 m after
1000 m: 1000 + 1e-17 == 1000 in floating point) on a conveyor with feed points: the section
was cut into one piece of 0 m and the split of its elements divided by zero (a
ZeroDivisionError traceback from beltstudy static, a 500 from POST /studies)."""

from __future__ import annotations

import math

import pytest

from beltstudy.engine.conveyor import parse_conveyor
from beltstudy.engine.loop import G
from beltstudy.engine.statics import solve_steady
from tests.conftest import hand_conveyor_dict

DIN_C1 = {"f_carry": 0.020, "f_return": 0.020, "c": 1.0}


@pytest.mark.parametrize("tiny_m", [1e-17, 1e-160, 1e-300])
def test_a_vanishing_flat_section_adds_nothing_to_the_hand_resistances(tiny_m):
    d = hand_conveyor_dict(profile=[{"length_m": 1000, "lift_m": 50},
                                    {"length_m": tiny_m, "lift_m": 0}],
                           accessories={"head_kn": 0.0, "tail_kn": 0.0})
    d["material"] = {**d["material"], "feed": [{"at_m": 0, "share": 0.6},
                                              {"at_m": 500, "share": 0.4}]}
    res = solve_steady(parse_conveyor(d), model="din", params=DIN_C1)
    # by hand over the 1000 m rising 50 m (cos a = sqrt(1 - 0.05^2)), f 0.020,
    # m'_G 20, m'_R 10 carry, 3 return [kg/m], m'_L 0.6 x 50 = 30 on the first 500 m and 50
    # after the second feed: F_H = f g L [m'_R + (m'_G + m'_L) cos a] per strand and piece,
    # lift g m'_L H (25 m on each half)
    cos_a = math.sqrt(1.0 - 0.05 ** 2)
    carry = 0.020 * G * 500 * ((10 + 50 * cos_a) + (10 + 70 * cos_a))  # 13.719 kN
    ret = 0.020 * G * 1000 * (3 + 20 * cos_a)  # 4.508 kN
    lift = G * (30 * 25 + 50 * 25)  # 19.620 kN
    parts = res.summary["te_components_kn"]
    assert parts["main_carry"] * 1e3 == pytest.approx(carry, rel=1e-9)
    assert parts["main_return"] * 1e3 == pytest.approx(ret, rel=1e-9)
    assert parts["lift"] * 1e3 == pytest.approx(lift, rel=1e-9)
    assert (carry, ret, lift) == pytest.approx((13719.3, 4507.7, 19620.0), abs=0.1)
