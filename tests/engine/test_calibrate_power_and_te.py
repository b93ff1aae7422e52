"""Calibration (SPEC 7.3): a row that gives both ``power_kw`` and ``te_kn`` is one reading of its
steady state (P = Te v), counted once in the degrees of freedom and the standard errors."""

from __future__ import annotations

import math

import numpy as np
import pytest

from beltstudy.engine import load_conveyor, solve_steady
from beltstudy.engine.calibration import calibrate, measurements_from_rows
from tests.conftest import CONVEYORS

STATES = [(0.2, 18.0), (0.35, 12.0), (0.5, 6.0), (0.65, 15.0), (0.8, 22.0), (0.95, 2.0),
          (1.0, 9.0)]
TRUTH = 0.025


@pytest.fixture(scope="module")
def plant():
    """slope-5pct (18 t counterweight), its power made by DIN at f_carry = 0.025 at seven
    states with 3 % seeded noise, and the model's power at f_carry 0.02 and 0.03 (DIN's power
    is linear in f_carry: two solves give it exactly)."""
    conv = load_conveyor(CONVEYORS / "slope-5pct.yaml")
    conv = conv.model_copy(update={"takeup": conv.takeup.model_copy(
        update={"mass_kg": 18000.0})})

    def power(f):
        return np.array([solve_steady(conv, model="din", params={"f_carry": f},
                                      temperature_c=t, load=ld).summary["power_kw"]
                         for ld, t in STATES])

    rng = np.random.default_rng(21)
    y = power(TRUTH) * (1 + 0.03 * rng.standard_normal(len(STATES)))
    return conv, y, power(0.02), power(0.03)


def _hand_fit(y, p2, p3):
    """The weighted least squares of one linear name by hand: r_i(f) = (P_i(f) - y_i) / |y_i|
    with P_i(f) = P_i(0.02) + J_i |y_i| (f - 0.02), J_i = (P_i(0.03) - P_i(0.02)) / 0.01 / |y_i|;
    f = 0.02 - sum J r(0.02) / sum J^2, se = sqrt(SSR / (n - 1) / sum J^2)."""
    jac = (p3 - p2) / 0.01 / np.abs(y)
    r0 = (p2 - y) / np.abs(y)
    f = 0.02 - float(jac @ r0) / float(jac @ jac)
    r = r0 + jac * (f - 0.02)
    return f, math.sqrt(float(r @ r) / (len(y) - 1) / float(jac @ jac))


def test_a_rows_power_and_te_count_once_in_the_standard_error(plant):
    """Seven rows giving power and te_kn = P / 4.5 (the drive's force read as its power over
    the speed): the fit counted 14 residuals, 13 degrees of freedom, and its standard error was
    sqrt(6 / 13) = 0.68 of the power-only fit's (5.93e-4 against 8.73e-4): its 95 % intervals
    covered the truth in 81 % of such fits. Each row now counts once: 6 degrees of freedom and
    the power-only fit's standard error, which the hand computation gives."""
    conv, y, p2, p3 = plant
    f_hand, se_hand = _hand_fit(y, p2, p3)
    v = conv.speed_m_s
    power = calibrate(conv, measurements_from_rows([
        {"load": ld, "temperature_c": t, "power_kw": p}
        for (ld, t), p in zip(STATES, y, strict=True)]), "din", ["f_carry"])
    both = calibrate(conv, measurements_from_rows([
        {"load": ld, "temperature_c": t, "power_kw": p, "te_kn": p / v}
        for (ld, t), p in zip(STATES, y, strict=True)]), "din", ["f_carry"])
    for cal in (power, both):
        assert cal.dof == 6
        assert cal.fit["f_carry"]["value"] == pytest.approx(f_hand, rel=1e-6)
        assert cal.fit["f_carry"]["se"] == pytest.approx(se_hand, rel=1e-4)
    assert len(both.residuals) == 14  # every measured value is still shown
    assert both.status == power.status == "ok"


def test_a_rows_power_and_te_that_differ_meet_the_fit_as_their_mean(plant):
    """Power and a Te 4 % above P / v on each row (within the 10 % two readings may differ):
    the row's one residual is the mean of the two relative residuals, r = (r_P + r_T) / 2,
    with the mean of their sensitivities; by hand as above on that mean, 6 degrees of
    freedom."""
    conv, y, p2, p3 = plant
    v = conv.speed_m_s
    te = 1.04 * y / v
    jac = ((p3 - p2) / 0.01 / np.abs(y) + (p3 - p2) / v / 0.01 / np.abs(te)) / 2
    r0 = ((p2 - y) / np.abs(y) + (p2 / v - te) / np.abs(te)) / 2
    f = 0.02 - float(jac @ r0) / float(jac @ jac)
    r = r0 + jac * (f - 0.02)
    se = math.sqrt(float(r @ r) / 6 / float(jac @ jac))
    cal = calibrate(conv, measurements_from_rows([
        {"load": ld, "temperature_c": t, "power_kw": p, "te_kn": q}
        for (ld, t), p, q in zip(STATES, y, te, strict=True)]), "din", ["f_carry"])
    assert cal.dof == 6
    assert cal.fit["f_carry"]["value"] == pytest.approx(f, rel=1e-6)
    assert cal.fit["f_carry"]["se"] == pytest.approx(se, rel=1e-4)
