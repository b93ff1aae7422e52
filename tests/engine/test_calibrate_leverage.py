"""A reading that carries the fit is named. Residuals are relative to each reading, so a
small reading (a belt near zero power) weighs most: on downhill-regen near its balance load
one reading at -36.9 kW beside readings of 230 to 660 kW held 0.75 of a one-name fit, and a
meter's error of 1 % of full scale there moved the fitted value beyond its interval, unsaid.
The leverage is checked against a hand computation: DIN's power is linear in f_carry, so each
reading's relative sensitivity is d r / d ln f = (P(f) - P(0)) / |P|, and with one fitted
name h_k = J_k^2 / sum J^2 (Belsley, Kuh & Welsch 1980, 2.1)."""
from __future__ import annotations

import re

import numpy as np
import pytest

from beltstudy.engine import load_conveyor, solve_steady
from beltstudy.engine.calibration import Measurement, calibrate
from tests.conftest import CONVEYORS

F = 0.018


def _power(conv, load, f):
    return solve_steady(conv, model="din", params={"f_carry": f}, temperature_c=10.0,
                        load=load).summary["power_kw"]


def test_a_reading_near_zero_power_is_named_with_its_leverage():
    conv = load_conveyor(CONVEYORS / "downhill-regen.yaml")
    loads = (0.0, 0.3, 0.6, 1.0)
    rows = [Measurement(load, 10.0, {"power_kw": _power(conv, load, F)}) for load in loads]
    # a meter error of 1 % of full scale (6.6 kW) on each reading, the same sign
    rows = [Measurement(m.load, m.temperature_c, {"power_kw": m.values["power_kw"] + 6.6})
            for m in rows]
    cal = calibrate(conv, rows, "din", ["f_carry"])
    y = np.array([m.values["power_kw"] for m in rows])
    slope = np.array([_power(conv, load, F) - _power(conv, load, 0.0) for load in loads])
    jac = slope / np.abs(y)
    h = jac ** 2 / np.sum(jac ** 2)
    k = int(np.argmax(h))
    assert loads[k] == 0.3 and h[k] > 0.5  # the balance load's small reading
    named = [n for n in cal.notes if "carries a leverage" in n]
    assert len(named) == 1 and named[0].startswith(f"row {k} (load 0.3, 10 C)")
    shown = float(re.search(r"leverage of ([0-9.]+)", named[0]).group(1))
    assert shown == pytest.approx(h[k], abs=0.006)  # printed to two decimals
    assert "add readings at other loads" in named[0]


def test_readings_of_like_size_name_none():
    """overland-4km's power at five loads (all driving, 0.2 to 1.0 of full): no reading
    carries the fit."""
    conv = load_conveyor(CONVEYORS / "overland-4km.yaml")
    rows = [Measurement(load, 10.0, {"power_kw": _power(conv, load, 0.0237)})
            for load in (0.2, 0.4, 0.6, 0.8, 1.0)]
    cal = calibrate(conv, rows, "din", ["f_carry"])
    assert not [n for n in cal.notes if "carries a leverage" in n]
