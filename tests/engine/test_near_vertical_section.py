"""A section a few centimetres short of vertical: the curve check's test that a section's
straight rest keeps its lift turned the grade by a further degree past 90 deg, where the sine
falls again, found the section's own lift outside its bounds and asked for a curve fix on a
route with no curve (a TypeError from beltstudy static, a 500 from POST /studies)."""

from __future__ import annotations

import math

import pytest

from beltstudy.engine.conveyor import parse_conveyor
from tests.conftest import hand_conveyor_dict


@pytest.mark.parametrize("lift_m", [199.995, -199.995, 199.9, -199.9])
def test_a_section_just_short_of_vertical_is_read(lift_m):
    d = hand_conveyor_dict()
    d["profile"] = [{"length_m": 200.0, "lift_m": lift_m}]
    d["holdback"] = lift_m > 0.0
    conv = parse_conveyor(d)  # was TypeError in _curve_fit_fix
    sec = conv.profile[0]
    # the route keeps its lift: 89.6 deg (or 88.2 deg) off the level, as given
    assert sec.lift_m == lift_m
    assert math.degrees(math.asin(abs(sec.lift_m) / sec.length_m)) > 88.0
