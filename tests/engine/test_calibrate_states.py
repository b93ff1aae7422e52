"""What makes two measured rows one steady state (SPEC 7.3): the state the model computes,
not the row as written. ``full``, ``1.0`` and ``"1.0,1.0"`` are one load, ``empty`` and ``0``
another; a model without a temperature term (DIN) computes every temperature alike. The
checks that count states (the outlier test's degrees of freedom, the one-state warning, the
copy note, two readings of one state that disagree) read it so."""

from __future__ import annotations

import pytest

from beltstudy.engine import load_conveyor, solve_steady
from beltstudy.engine.calibration import Measurement, calibrate
from tests.conftest import CONVEYORS


@pytest.fixture(scope="module")
def conv():
    return load_conveyor(CONVEYORS / "slope-5pct.yaml")


def _power(conv, load, temp=10.0, f_carry=0.0237):
    return solve_steady(conv, model="din", params={"f_carry": f_carry}, load=load,
                        temperature_c=temp).summary["power_kw"]


def test_full_and_one_are_one_state_pasted_twice(conv):
    """``full`` and ``1.0`` at 10 C with one reading, and a third row 1.85 % off the fit: two
    states for one name. Written ``1.0`` twice it is ``ok`` with a copy note; written ``full``
    and ``1.0`` it named the good third row an outlier with an externally studentized residual
    of 7.5e5 (the two copies left nothing for it to stand apart from but each other)."""
    p1, p05 = _power(conv, 1.0), _power(conv, 0.5, 15.0)
    assert _power(conv, "full") == p1
    same = [Measurement(1.0, 10.0, {"power_kw": p1}), Measurement(1.0, 10.0, {"power_kw": p1}),
            Measurement(0.5, 15.0, {"power_kw": 0.98 * p05})]
    spelled = [Measurement("full", 10.0, {"power_kw": p1}), *same[1:]]
    a, b = (calibrate(conv, rows, "din", ["f_carry"]) for rows in (same, spelled))
    assert a.status == b.status == "ok", (a.message, b.message)
    assert "outlier" not in b.message
    assert any("row 1 repeats row 0 exactly" in n for n in b.notes), b.notes
    # empty and 0 alike
    p0 = _power(conv, 0.0)
    rows = [Measurement("empty", 12.0, {"power_kw": p0}), Measurement(0.0, 12.0, {"power_kw": p0}),
            Measurement(0.5, 15.0, {"power_kw": 0.98 * p05})]
    c = calibrate(conv, rows, "din", ["f_carry"])
    assert "outlier" not in c.message and c.status == "ok", c.message


def test_three_spellings_of_one_load_are_one_state(conv):
    """``full``, ``1.0`` and ``[1.0, 1.0]`` (one per section of this two-... conveyor's
    sections) at one temperature: one state, met by f_carry whatever the model, so a warning
    naming the state, as ``1.0`` three times is; they read ``ok``."""
    n = len(conv.profile)
    p1 = _power(conv, 1.0)
    rows = [Measurement("full", 10.0, {"power_kw": p1}),
            Measurement(1.0, 10.0, {"power_kw": 1.008 * p1}),
            Measurement([1.0] * n, 10.0, {"power_kw": 0.994 * p1})]
    cal = calibrate(conv, rows, "din", ["f_carry"])
    assert cal.status == "warning", cal.message
    assert "read only as many steady states as fitted names" in cal.message
    assert "(rows 0, 1, 2)" in cal.message


def test_full_and_one_that_disagree_are_named_as_one_state(conv):
    """``full`` and ``1.0`` at 10 C 23 % apart: two readings of one state that no f_carry
    meets both, named as such (written ``1.0`` twice it was; written ``full`` and ``1.0``
    only the general misfit was said)."""
    p1, p05, p07 = _power(conv, 1.0), _power(conv, 0.5, 15.0), _power(conv, 0.7, 5.0)
    rows = [Measurement("full", 10.0, {"power_kw": p1}),
            Measurement(1.0, 10.0, {"power_kw": 0.77 * p1}),
            Measurement(0.5, 15.0, {"power_kw": p05}), Measurement(0.7, 5.0, {"power_kw": p07})]
    cal = calibrate(conv, rows, "din", ["f_carry"])
    assert cal.status == "warning"
    assert "rows 0 and 1 (lines 2 and 3) read one steady state" in cal.message \
        or "rows 0 and 1 read one steady state" in cal.message, cal.message
    assert f"differ by {100 * 0.23 / ((1 + 0.77) / 2):.3g} %" in cal.message


def test_din_at_several_temperatures_is_one_state(conv):
    """One load at -10 to 30 C fitted with DIN's f_carry: DIN has no temperature term, so the
    five readings are one state the fit meets whatever the model, as they are at one
    temperature, where it warned; at five temperatures it said ``ok`` (4 degrees of freedom).
    The warning says the model reads no temperature and asks for another load, not another
    temperature. A model with a temperature term (nonlin) reads them as five states."""
    p = _power(conv, 0.5)
    temps = (-10.0, 0.0, 10.0, 20.0, 30.0)
    scatter = (1.0, 1.008, 0.99, 1.004, 0.996)
    rows = [Measurement(0.5, t, {"power_kw": k * p}) for t, k in zip(temps, scatter, strict=True)]
    cal = calibrate(conv, rows, "din", ["f_carry"])
    assert cal.status == "warning", cal.message
    assert "load 0.5 at -10 to 30 C (the model has no temperature term: one state)" \
        in cal.message
    assert "another load or speed: din has no temperature term" in cal.message
    one = calibrate(conv, [Measurement(0.5, 10.0, r.values) for r in rows], "din", ["f_carry"])
    assert one.status == "warning"
    nl = calibrate(conv, rows, "nonlin", ["drag_per_roll_n"])
    assert "steady states as fitted names" not in nl.message
