"""A rated power written in W for kW (``rated_power_kw: 15000`` for a 15 kW motor) passed
silently with a utilisation of 0.0003, and the transient ran a 15 MW motor. A given rated power
WATTS_RATIO (500) or more times what an auto size would install now gets a note naming the
field and the kW it would be; a motor a few times its need does not."""
from __future__ import annotations

import pytest

from beltstudy.engine.conveyor import parse_conveyor
from beltstudy.engine.drives import RATED_POWER_FACTOR, WATTS_RATIO
from beltstudy.engine.statics import solve_steady
from tests.conftest import short30_dict


def _steady(rated_kw: float):
    d = short30_dict()
    d["drives"] = [{**d["drives"][0], "rated_power_kw": rated_kw}]
    return solve_steady(parse_conveyor(d), model="din")


def test_a_power_written_in_watts_is_named():
    res = _steady(15000.0)
    # the auto size by hand: 1.25 x Te x v / eta on a level belt (Te above the running
    # resistance by the accessories only; eta 0.95), a few kW, so 15 000 is thousands of times
    # it
    te_kn = float(res.summary["te_kn"])
    auto_kw = RATED_POWER_FACTOR * te_kn * 2.0 / 0.95
    assert 2.0 < auto_kw < 10.0
    ratio = 15000.0 / auto_kw
    assert ratio > WATTS_RATIO
    assert res.status == "ok", res.message  # a note, not a warning
    assert (f"note: drives.0.rated_power_kw 15,000 kW is {ratio:,.0f} x the "
            in res.message), res.message
    assert "if it was written in W, it is 15 kW" in res.message


@pytest.mark.parametrize("rated_kw", [15.0, 300.0])
def test_a_motor_a_few_times_its_need_is_not_taken_for_watts(rated_kw):
    assert "rated_power_kw is in kW" not in _steady(rated_kw).message


def test_a_power_written_in_megawatts_is_named_and_printed_as_given():
    # slope-5pct-like by hand is not needed: the same short belt, its motor written as
    # 0.005 (5 kW in MW); the auto size is a few kW, so 0.005 is under 1/500 of it
    res = _steady(0.005)
    te_kn = float(res.summary["te_kn"])
    auto_kw = RATED_POWER_FACTOR * te_kn * 2.0 / 0.95
    assert auto_kw / 0.005 > WATTS_RATIO
    assert (f"note: drives.0.rated_power_kw 0.005 kW is 1/{auto_kw / 0.005:,.0f} of the "
            in res.message), res.message
    assert "if it was written in MW, it is 5 kW" in res.message
    # the warning prints the rating as given (1.25 read 'rated 1.2 kW')
    res = _steady(1.25e-3)
    assert "rated 0.00125 kW" in res.message, res.message
