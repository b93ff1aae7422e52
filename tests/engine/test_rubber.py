"""Cover rubber: WLF shift, loss peak and storage modulus against hand calculations and the
PHYSICS section 3 ranges."""

from __future__ import annotations

import math

import numpy as np
import pytest
from numpy.testing import assert_allclose

from beltstudy.engine import catalog, rubber
from beltstudy.engine.conveyor import InputError

COMPOUNDS = ("standard", "lrr", "cold", "fire-resistant")


def test_every_catalogue_compound_has_viscoelastic_parameters():
    assert set(catalog.compounds()) == set(COMPOUNDS)
    for cid in COMPOUNDS:
        c = rubber.compound(cid)
        assert c.wlf_c1 > 0 and c.wlf_c2 > 0 and c.loss_width_dec > 0
        assert 0 < c.tan_delta_floor < 0.2 and 0 < c.loss_peak < 1.5
        assert 1.0 <= c.e_rubbery_mpa <= 20.0
        # glassy / rubbery modulus ratio of a filled rubber: tens to a few thousand
        assert 30 < c.glassy_ratio < 5000


def test_unknown_compound_lists_valid_ids():
    with pytest.raises(InputError, match="valid: standard, lrr"):
        rubber.compound("standart")


def test_wlf_shift_by_hand():
    # standard: T_g = -50 C, C1 = 17.44, C2 = 51.6 K
    assert float(rubber.shift_log10(-50.0, "standard")) == 0.0
    # 20 C: dT = 70 K: -17.44 * 70 / (51.6 + 70) = -10.0395
    assert_allclose(rubber.shift_log10(20.0, "standard"), -17.44 * 70 / 121.6, rtol=1e-12)
    # lrr: T_g = -70 C; at -30 C dT = 40 K
    assert_allclose(rubber.shift_log10(-30.0, "lrr"), -17.44 * 40 / 91.6, rtol=1e-12)
    # far below T_g - C2 the shift is held at dT = -C2 / 2 (finite, glassy)
    held = -17.44 * (-25.8) / (51.6 - 25.8)
    assert_allclose(rubber.shift_log10(-150.0, "standard"), held, rtol=1e-12)
    assert np.isfinite(rubber.tan_delta(-150.0, 100.0, "standard"))


def test_loss_and_modulus_by_hand():
    # standard at 20 C, 100 Hz: x = log10(100) + log10 a_T - log10 f_peak
    x = 2.0 - 17.44 * 70 / 121.6 - (-0.25)  # = -7.7895 decades
    u = x / 1.75
    tan = 0.105 + 0.85 / math.cosh(u)
    gd = 2 * math.atan(math.tanh(u / 2))
    e = 5.0e6 * math.exp((2 / math.pi) * math.log(10) * 0.85 * 1.75 * (gd + math.pi / 2))
    t_calc, e_calc = rubber.loss_and_modulus(20.0, 100.0, "standard")
    assert_allclose(t_calc, tan, rtol=1e-12)
    assert_allclose(e_calc, e, rtol=1e-12)
    assert_allclose(rubber.tan_delta(20.0, 100.0, "standard"), tan, rtol=1e-12)
    assert_allclose(rubber.storage_modulus(20.0, 100.0, "standard"), e, rtol=1e-12)
    # the contact frequency f = v / l_c
    assert_allclose(rubber.contact_frequency(4.5, 0.03), 150.0)


def test_modulus_limits_and_kramers_kronig():
    c = rubber.compound("standard")
    # far below the peak E' -> E_r, far above -> E_r x glassy ratio
    assert_allclose(rubber.storage_modulus(80.0, 1e-6, c), c.e_rubbery_mpa * 1e6, rtol=1e-3)
    assert_allclose(rubber.storage_modulus(-70.0, 1e9, c),
                    c.e_rubbery_mpa * 1e6 * c.glassy_ratio, rtol=2e-3)
    # approximate Kramers-Kronig: d ln E' / d ln f = (2 / pi) (tan(delta) - floor)
    for t in (-45.0, -30.0, 0.0, 20.0):
        f = 100.0
        h = 1e-4
        d = (math.log(rubber.storage_modulus(t, f * math.exp(h), c))
             - math.log(rubber.storage_modulus(t, f * math.exp(-h), c))) / (2 * h)
        relax = float(rubber.tan_delta(t, f, c)) - c.tan_delta_floor
        assert_allclose(d, 2 / math.pi * relax, rtol=1e-5)


def test_standard_cover_in_physics_ranges():
    t20 = float(rubber.tan_delta(20.0, 100.0, "standard"))
    t_30 = float(rubber.tan_delta(-30.0, 100.0, "standard"))
    assert 0.12 <= t20 <= 0.20
    assert t_30 >= 3.0 * t20  # rising several-fold toward -30 C
    # the loss peak at 100 Hz lies 5-20 K above T_g = -50 C
    temps = np.arange(-60.0, 40.01, 0.5)
    t_peak = temps[np.argmax(rubber.tan_delta(temps, 100.0, "standard"))]
    assert -45.0 <= t_peak <= -30.0


def test_lrr_lower_than_standard():
    t_std = float(rubber.tan_delta(20.0, 100.0, "standard"))
    t_lrr = float(rubber.tan_delta(20.0, 100.0, "lrr"))
    assert 0.30 <= 1 - t_lrr / t_std <= 0.50  # 30-50 % lower at 20 C (PHYSICS section 3)
    # and its indentation factor tan(delta) E'^(-1/3) is lower at every temperature
    temps = np.arange(-40.0, 40.01, 1.0)
    for f in (50.0, 150.0):
        k_std = rubber.tan_delta(temps, f, "standard") / np.cbrt(
            rubber.storage_modulus(temps, f, "standard"))
        k_lrr = rubber.tan_delta(temps, f, "lrr") / np.cbrt(
            rubber.storage_modulus(temps, f, "lrr"))
        assert np.all(k_lrr < k_std)


def test_time_temperature_superposition():
    # above the loss peak temperature, cooling and raising the frequency both raise tan(delta)
    temps = np.arange(-20.0, 40.01, 5.0)
    for cid in COMPOUNDS:
        t = rubber.tan_delta(temps, 100.0, cid)
        assert np.all(np.diff(t) < 0), cid
        assert np.all(rubber.tan_delta(20.0, 1000.0, cid) > rubber.tan_delta(20.0, 10.0, cid))
        # E' stiffens as it cools
        e = rubber.storage_modulus(temps, 100.0, cid)
        assert np.all(np.diff(e) < 0), cid
    # a shift of the temperature equals a shift of log frequency by log10 a_T
    c = rubber.compound("standard")
    shift = float(rubber.shift_log10(0.0, c) - rubber.shift_log10(20.0, c))
    assert_allclose(rubber.tan_delta(0.0, 100.0, c),
                    rubber.tan_delta(20.0, 100.0 * 10**shift, c), rtol=1e-10)
