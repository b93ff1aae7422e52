"""A surcharge angle close to zero: ISO 5048's slope factor k1 = sqrt((cos^2 delta -
cos^2 theta) / (1 - cos^2 theta)) divided by zero once cos^2 theta rounds to 1 (below about
6e-7 deg), a ZeroDivisionError (a traceback from beltstudy static, a 500 from POST /studies)."""

from __future__ import annotations

import math

import pytest

from beltstudy.engine.capacity import capacity, slope_factor
from beltstudy.engine.conveyor import parse_conveyor
from tests.conftest import hand_conveyor_dict


@pytest.mark.parametrize("theta_deg", [5e-7, 1e-12, 1e-300])
def test_a_slope_steeper_than_a_near_zero_surcharge_heaps_nothing(theta_deg):
    # delta 2.86 deg (5 %) > theta: k1 = 0, k = 1 - s1 / (s1 + s2) = 1 - 0.05 / 0.16
    assert slope_factor(0.05, 0.11, 2.86, theta_deg) == pytest.approx(0.6875, rel=1e-12)
    # on the level k1 = 1 at any surcharge: k = 1
    assert slope_factor(0.05, 0.11, 0.0, theta_deg) == 1.0


def test_the_sine_form_is_iso_5048s_cosine_form():
    # delta 10 deg, theta 20 deg: k1 = sqrt((0.96985 - 0.88302) / 0.11698) = 0.8616
    k1 = math.sqrt((math.cos(math.radians(10)) ** 2 - math.cos(math.radians(20)) ** 2)
                   / math.sin(math.radians(20)) ** 2)
    assert k1 == pytest.approx(0.8616, rel=1e-3)
    assert slope_factor(0.05, 0.11, 10, 20) == pytest.approx(1 - 0.05 / 0.16 * (1 - k1),
                                                             rel=1e-12)


def test_a_conveyor_with_a_near_zero_surcharge_is_read_and_filled_as_flat():
    # 1.0 m belt on 3 rolls at 35 deg, 5 % up; usable width 0.9 x 1.0 - 0.05 = 0.85 m,
    # middle roll 0.38 m (DIN 22107), wings 0.235 m: s2 = (0.38 + 0.235 cos 35) x 0.235 x
    # sin 35 = 0.07717 m2; s1 ~ 0 (no heap); 720 m3/h over 3600 x 0.07717 x 4 m/s = 64.8 %
    d = hand_conveyor_dict()
    d["material"] = {**d["material"], "surcharge_deg": 5e-7}
    cap = capacity(parse_conveyor(d))  # was ZeroDivisionError in check_fill
    assert cap.roll_length_m == pytest.approx(0.38)
    assert cap.s2_m2 == pytest.approx(0.07717, rel=1e-3)
    assert cap.s1_m2 < 1e-8
    assert cap.fill_pct == pytest.approx(64.8, rel=2e-3)
