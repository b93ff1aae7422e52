"""Calibration (SPEC 7.3) on data a plant gives: a reading that stands apart from the others,
two readings of one steady state that disagree, and as many readings as fitted names. Each is
a warning naming the rows, not an ``ok`` fit that the bad reading has quietly moved."""

from __future__ import annotations

import numpy as np
import pytest

from beltstudy.engine import load_conveyor, solve_steady
from beltstudy.engine.calibration import Measurement, calibrate
from tests.conftest import CONVEYORS

TRUTH = 0.0237
STATES = [(load, temp) for load in (0.2, 0.4, 0.6, 0.8, 1.0) for temp in (-10.0, 20.0)]


@pytest.fixture(scope="module")
def plant():
    """overland-4km's power made by DIN at f_carry = 0.0237 at ten steady states, with 1 %
    seeded noise (a class-1 meter)."""
    conv = load_conveyor(CONVEYORS / "overland-4km.yaml")
    rng = np.random.default_rng(4)
    rows = []
    for load, temp in STATES:
        p = solve_steady(conv, model="din", params={"f_carry": TRUTH}, temperature_c=temp,
                         load=load).summary["power_kw"]
        rows.append(Measurement(load, temp, {"power_kw": p * (1 + 0.01 * rng.standard_normal())}))
    return conv, rows


def test_consistent_readings_fit_ok(plant):
    conv, rows = plant
    cal = calibrate(conv, rows, "din", ["f_carry"])
    assert cal.status == "ok", cal.message
    assert abs(cal.fit["f_carry"]["value"] - TRUTH) < 2.3 * cal.fit["f_carry"]["se"]


def test_an_outlier_is_named_by_its_row_and_how_far_it_stands(plant):
    """One reading 12 % high among ten good to 1 %: the rms residual (3.3 %) stays under the
    5 % misfit, so it was an ``ok`` fit with f_carry pulled 1.6 % up; the externally studentized
    residual (9.4 against the Bonferroni limit 5.0 for ten readings at 1 %) names it."""
    conv, rows = plant
    bad = list(rows)
    m = bad[6]
    bad[6] = Measurement(m.load, m.temperature_c, {"power_kw": 1.12 * m.values["power_kw"]})
    cal = calibrate(conv, bad, "din", ["f_carry"])
    assert cal.rms_relative < 0.05  # the premise: the misfit alone would not say it
    assert cal.status == "warning"
    assert "row 6 (load 0.8, -10 C): measured power_kw" in cal.message
    assert "above the fit" in cal.message and "outlier" in cal.message
    assert sum("row 6" in n for n in cal.notes) == 1
    assert not any(f"row {i} " in cal.message for i in range(10) if i != 6)


def test_two_readings_of_one_state_that_disagree_are_named(plant):
    """A second reading of row 2's state 20 % below it: no f_carry meets both; the message names
    the two rows and their spread instead of only a misfit."""
    conv, rows = plant
    m = rows[2]
    again = Measurement(m.load, m.temperature_c, {"power_kw": 0.8 * m.values["power_kw"]})
    cal = calibrate(conv, [*rows, again], "din", ["f_carry"])
    assert cal.status == "warning"
    assert "rows 2 and 10 read one steady state (load 0.4, -10 C)" in cal.message
    assert "differ by 22.2 %" in cal.message  # (1 - 0.8) / 0.9


def test_as_many_readings_as_names_is_a_warning_not_ok(plant):
    """Two readings, two names: met exactly whatever their errors, with no standard errors;
    status was ``ok``."""
    conv, rows = plant
    cal = calibrate(conv, [rows[0], rows[9]], "din", ["f_carry", "f_return"])
    assert cal.dof == 0 and cal.not_identifiable == []
    assert all(f["se"] is None for f in cal.fit.values())
    assert cal.status == "warning"
    assert "nothing is left to check the fit against" in cal.message


def test_copies_of_one_reading_are_one_state_not_three_degrees_of_freedom(plant):
    """One row pasted three times, one name: the three values are one steady state, which
    f_carry meets whatever the model (the fitted power equals the reading, residuals 0); the
    fit counted 2 degrees of freedom and answered ``ok`` with a standard error of 0 (a 95 %
    interval of zero width). It is a warning naming the state and its rows."""
    conv, rows = plant
    cal = calibrate(conv, [rows[0]] * 3, "din", ["f_carry"])
    assert max(abs(r["relative"]) for r in cal.residuals) < 1e-8  # one state, met exactly
    assert cal.status == "warning"
    assert "read only as many steady states as fitted names" in cal.message
    assert "load 0.2, -10 C power_kw (rows 0, 1, 2)" in cal.message


def test_repeats_of_two_states_for_two_names_are_a_warning(plant):
    """Two states read twice each, two names: four values, two degrees of freedom, but the two
    states fix the two names whatever the model; a third state gives the fit something to
    miss and is ``ok``."""
    conv, rows = plant
    cal = calibrate(conv, [rows[0], rows[9], rows[0], rows[9]], "din", ["f_carry", "f_return"])
    assert cal.dof == 2 and cal.status == "warning"
    assert "(rows 0, 2)" in cal.message and "(rows 1, 3)" in cal.message
    one = calibrate(conv, [rows[0], rows[9], rows[0]], "din", ["f_carry"])
    assert "steady states as fitted names" not in one.message


def test_power_and_te_of_one_state_are_one_state(plant):
    """A row that gives both the power and the peripheral force of one steady state (P = Te v,
    the two agree) is two values but one state and one reading: one name meets it whatever the
    model, so the fit is a warning, not ``ok``, with no degree of freedom (the pair counts
    once: tests/engine/test_calibrate_power_and_te.py)."""
    conv, rows = plant
    row = rows[0]
    v = conv.speed_m_s
    both = type(row)(load=row.load, temperature_c=row.temperature_c,
                     values={"power_kw": row.values["power_kw"],
                             "te_kn": row.values["power_kw"] / v})
    cal = calibrate(conv, [both], "din", ["f_carry"])
    assert cal.dof == 0 and cal.status == "warning"
    assert "power_kw and te_kn (row 0)" in cal.message


@pytest.mark.parametrize(("column", "scale", "unit", "own"), [
    ("power_kw", 1e-3, "MW", "kW"),
    ("te_kn", 1e-3, "MN", "kN"),
])
def test_readings_a_prefix_step_off_are_said_to_be_in_that_unit(plant, column, scale, unit,
                                                                 own):
    """Plant power logged in MW and put in the kW column (2.8 for 2 800 kW) read as a misfit
    of 85 000 % with 'check the values'. The model at its textbook start (DIN f 0.020 against
    the plant's 0.0237) computes 1000 x each reading within the friction's share, so the
    readings are said to be in MW."""
    conv, rows = plant
    v = conv.speed_m_s
    moved = [Measurement(m.load, m.temperature_c, {column: scale * (
        m.values["power_kw"] if column == "power_kw" else m.values["power_kw"] / v)})
        for m in rows]
    cal = calibrate(conv, moved, "din", ["f_carry"])
    assert cal.status == "warning"
    assert f"the readings look written in {unit}; give them in {own}" in cal.message
    assert any(f"look written in {unit}" in n for n in cal.notes)
    times = float(cal.message.split("computes about ")[1].split(" x")[0])
    # 1000 x the reading, times the textbook start's share of the plant's power (f 0.020
    # against 0.0237 on a belt whose lift takes part of the power): 0.7-1 x
    assert 700 <= times <= 1000
    good = calibrate(conv, rows, "din", ["f_carry"])
    assert not any("look written" in n for n in [good.message, *good.notes])
