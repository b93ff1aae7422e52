"""An accessory lump written in newtons (accessories.head_kn: 2000 for a 2 kN scraper on a
1.2 m belt) passed as a 2 MN resistance, said only through its effects (a drive 8 x short,
a safety factor below 1). It now gets a note naming the field and the kN it would be: above
LUMP_MAX_KN_M (50 kN) a metre of belt width, some 80 ISO 5048 scrapers (A p mu_3: 0.01 m2 a
metre x 1e5 N/m2 x 0.6 = 0.6 kN/m each)."""
from __future__ import annotations

import pytest

from beltstudy.engine.checks import LUMP_MAX_KN_M
from beltstudy.engine.conveyor import parse_conveyor
from beltstudy.engine.statics import solve_steady
from tests.conftest import hand_conveyor_dict


def _message(head_kn: float) -> str:
    d = hand_conveyor_dict(accessories={"head_kn": head_kn, "tail_kn": 0.5})
    return solve_steady(parse_conveyor(d), model="din").message


def test_the_iso_scraper_bound():
    assert 0.01 * 1e5 * 0.6 / 1e3 == pytest.approx(0.6)  # kN a metre of width, one scraper
    assert LUMP_MAX_KN_M / 0.6 == pytest.approx(83.3, abs=0.1)


def test_a_lump_in_newtons_is_named():
    msg = _message(2000.0)  # the hand conveyor's belt is 1 m wide
    assert ("note: accessories.head_kn 2000 kN is 2,000 kN per metre of belt width, above the "
            "50 kN/m") in msg, msg
    assert "if it was written in N, it is 2 kN" in msg


@pytest.mark.parametrize("head_kn", [2.0, 40.0])
def test_a_lump_of_scrapers_is_not_taken_for_newtons(head_kn):
    assert "accessories are in kN" not in _message(head_kn)
