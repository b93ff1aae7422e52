"""A skirt width whose square underflows makes ISO 5048's skirt friction infinite
(F_gL = mu_2 I_V^2 rho g l_b / (v^2 b_1^2)): the file is refused naming the field, where every
tension was inf and the pulley checks raised StopIteration (a traceback from beltstudy static,
a 500 from POST /studies). A narrow but finite width is still solved, by hand."""

from __future__ import annotations

import pytest

from beltstudy.engine.conveyor import parse_conveyor
from beltstudy.engine.errors import InputError
from beltstudy.engine.statics import solve_steady
from tests.conftest import hand_conveyor_dict


def _fed(width_m: float) -> dict:
    return hand_conveyor_dict(material={
        "capacity_t_h": 720, "density_t_m3": 1.0,
        "feed": [{"at_m": 0, "share": 1.0, "skirt_length_m": 5.0, "skirt_width_m": width_m}]})


@pytest.mark.parametrize("width", [1e-200, 1e-160])
def test_a_skirt_width_that_makes_the_friction_infinite_is_refused(width):
    with pytest.raises(InputError, match=r"material\.feed\.0\.skirt_width_m: .* makes their "
                       r"friction infinite .*two thirds of the belt width, 0\.667 m"):
        parse_conveyor(_fed(width))


def test_a_narrow_skirt_is_solved_by_iso_5048():
    """b_1 0.05 m, 5 m of skirts, m'_L 50 kg/m, rho 1000 kg/m3, mu_2 0.6:
    F_gL = 0.6 x 9.81 x 5 x 50^2 / (1000 x 0.05^2) = 29.43 kN more Te than without skirts."""
    narrow = solve_steady(parse_conveyor(_fed(0.05)), model="din").summary["te_kn"]
    plain = hand_conveyor_dict()
    bare = solve_steady(parse_conveyor(plain), model="din").summary["te_kn"]
    assert narrow - bare == pytest.approx(0.6 * 9.81 * 5 * 50 ** 2 / (1000 * 0.05 ** 2) / 1e3,
                                          rel=2e-3)
