"""A measured load written as a per cent of the design load (a plant log's 50 for half load)
is refused naming the row's load and the fraction it stands for, not only the range; a load
that is no number says so, not that NaN lies outside the range."""

from __future__ import annotations

import math

import pytest

from beltstudy.engine import load_conveyor
from beltstudy.engine.calibration import Measurement, calibrate
from beltstudy.engine.conveyor import LOAD_MAX, section_loads
from beltstudy.engine.errors import InputError
from tests.conftest import CONVEYORS


@pytest.fixture(scope="module")
def conv():
    return load_conveyor(CONVEYORS / "overland-4km.yaml")


def test_a_load_in_per_cent_is_refused_with_its_fraction(conv):
    rows = [Measurement(0.5, 10.0, {"power_kw": 900.0}), Measurement(30, 12.0, {"power_kw": 800.0})]
    with pytest.raises(InputError) as err:
        calibrate(conv, rows, "din", ["f_carry"])
    assert err.value.field == "measured.1.load"
    # 30 % of the design load is the fraction 30 / 100 = 0.3
    assert "not a per cent" in err.value.reason and "is 0.3)" in err.value.reason


def test_a_per_cent_in_a_load_per_section_is_named_too(conv):
    n = len(conv.profile)
    with pytest.raises(InputError) as err:
        section_loads([100.0] * n, conv)
    assert "not a per cent" in err.value.reason and "is 1)" in err.value.reason


def test_a_surge_past_the_largest_fraction_is_not_called_a_per_cent(conv):
    # 1.5 is past 1.3 but 1.5 % (0.015) is no plausible reading of it: the range alone
    with pytest.raises(InputError) as err:
        section_loads(1.5, conv)
    assert "per cent" not in err.value.reason
    assert f"outside 0..{LOAD_MAX:g}" in err.value.reason
    # past 100 x the largest fraction is no per cent of the design load either
    with pytest.raises(InputError) as err:
        section_loads(500.0, conv)
    assert "per cent" not in err.value.reason


def test_a_load_that_is_no_number_says_so(conv):
    with pytest.raises(InputError) as err:
        section_loads(math.nan, conv)
    assert err.value.reason.startswith("not a number")
