"""Calibration rows measured off the design speed (SPEC 7.3 ``speed_m_s``): the fill of the
belt's cross-section a row makes is its own load's at its own speed, not the design
capacity's. A plant slows a speed-controlled belt when it carries little, so a light load at a
low speed is an ordinary steady state; a row whose flow overfills the belt is named."""

from __future__ import annotations

import pytest

from beltstudy.engine import load_conveyor, solve_steady
from beltstudy.engine.calibration import Measurement, calibrate
from beltstudy.engine.capacity import fill_pct
from beltstudy.engine.errors import InputError
from tests.conftest import CONVEYORS

TRUTH = 0.025


@pytest.fixture(scope="module")
def conv():
    # slope-5pct: 2000 t/h at 4.5 m/s fills its cross-section to about 47 %
    return load_conveyor(CONVEYORS / "slope-5pct.yaml")


def _row(conv, load, temp, speed=None):
    at = conv if speed is None else conv.model_copy(update={"speed_m_s": speed})
    p = solve_steady(at, model="din", params={"f_carry": TRUTH}, temperature_c=temp,
                     load=load).summary["power_kw"]
    return Measurement(load, temp, {"power_kw": p}, speed)


def test_a_light_load_at_a_low_speed_is_fitted_not_refused(conv):
    # at 0.6 m/s the design 2000 t/h would fill the cross-section to 47 % x 4.5 / 0.6 = 352 %,
    # past the 300 % no belt carries, but the row carries 0.1 of it: 35 %
    design = fill_pct(conv)
    assert 0.1 * design * 4.5 / 0.6 < 100.0 < 300.0 < design * 4.5 / 0.6
    rows = [_row(conv, 0.1, 10.0, 0.6), _row(conv, 0.5, 10.0), _row(conv, 0.8, 5.0),
            _row(conv, 1.0, 15.0)]
    cal = calibrate(conv, rows, "din", ["f_carry"])
    assert cal.status == "ok", cal.message
    assert cal.fit["f_carry"]["value"] == pytest.approx(TRUTH, rel=1e-4)
    assert not any("spills" in n for n in cal.notes)


def test_a_row_whose_flow_overfills_the_belt_is_noted_with_its_fill(conv):
    # full load at 1.8 m/s: the fill grows as 1 / speed, 47 % x 4.5 / 1.8 = 117 %
    rows = [_row(conv, 1.0, 10.0, 1.8), _row(conv, 0.5, 10.0), _row(conv, 0.8, 5.0)]
    cal = calibrate(conv, rows, "din", ["f_carry"])
    want = fill_pct(conv) * 4.5 / 1.8
    (note,) = [n for n in cal.notes if "spills" in n]
    assert note.startswith("row 0 (load 1 at 1.8 m/s)")
    assert f"{want:.3g} %" in note


def test_a_row_past_what_any_belt_carries_is_refused_by_its_speed(conv):
    # 1.3 x the design load at 0.6 m/s: 1.3 x 352 % = 457 %, past 300 %
    rows = [_row(conv, 0.5, 10.0), Measurement(1.3, 10.0, {"power_kw": 900.0}, 0.6)]
    with pytest.raises(InputError) as err:
        calibrate(conv, rows, "din", ["f_carry"])
    assert err.value.field == "measured.1.speed_m_s"
    assert f"{1.3 * fill_pct(conv) * 4.5 / 0.6:.3g} %" in err.value.reason
