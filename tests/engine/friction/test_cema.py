"""CEMA against hand calculations, term by term (tolerance 0.1 %)."""

from __future__ import annotations

import numpy as np
import pytest
from numpy.testing import assert_allclose

from beltstudy.engine.friction import cema as cema_mod
from beltstudy.engine.statics import solve_steady
from tests.engine.friction.conftest import LBF, MG, ML, G, H, L, V

RTOL = 1e-3  # 0.1 %


@pytest.mark.parametrize("temperature_c, kt", [(20.0, 1.00), (-18.0, 1.27), (-40.0, 1.65),
                                                (-29.0, 1.45)])
def test_cema_terms_by_hand(hand_conveyor, temperature_c, kt):
    ky = 0.020
    res = solve_steady(hand_conveyor, model="cema", params={"ky": ky},
                       temperature_c=temperature_c, n_elements=100)
    c = res.summary["te_components_kn"]
    # Kx = 0.00068 (m'_G + m'_L) + A_i / (g S) = 0.00068 * 70 + 5 / (9.81 * 1.25) = 0.45535 kg/m
    kx = 0.00068 * (MG + ML) + 5.0 / (G * 1.25)
    assert kx == pytest.approx(0.45535, rel=1e-4)
    # carry: g L [Kt (Kx + Ky m'_G) + Ky m'_L]
    carry = G * L * (kt * (kx + ky * MG) + ky * ML)
    # return: g L Kt 0.015 m'_G
    ret = G * L * kt * 0.015 * MG
    feed = ML * V * V  # T_am = I_m (v - v0), I_m = m'_L v = 200 kg/s -> 800 N
    pulleys = (200 + 150) * LBF  # head drive pulley (tight) + tail take-up pulley (slack side)
    lift = ML * G * H
    assert_allclose(c["main_carry"] * 1e3, carry, rtol=RTOL)
    assert_allclose(c["main_return"] * 1e3, ret, rtol=RTOL)
    assert_allclose(c["feed"] * 1e3, feed, rtol=RTOL)
    assert_allclose(c["secondary"] * 1e3, pulleys, rtol=RTOL)
    assert_allclose(c["lift"] * 1e3, lift, rtol=RTOL)
    te = carry + ret + feed + pulleys + lift + 1500.0
    assert_allclose(res.summary["te_kn"] * 1e3, te, rtol=RTOL)


def test_cema_kt_and_ky_fit():
    assert cema_mod.kt_factor(25) == 1.0
    assert cema_mod.kt_factor(-60) == pytest.approx(1.65)
    # Ky fit: 0.035 at 250 ft and below, floor 0.016 from 3000 ft, rises with mass and spacing
    assert cema_mod.ky_length(50.0) == pytest.approx(0.035)
    assert cema_mod.ky_length(5000.0) == pytest.approx(0.016)
    assert cema_mod.ky_length(300.0) < cema_mod.ky_length(100.0)
    ky = cema_mod.ky_fit(500.0, np.array([50.0, 150.0, 150.0]), np.array([1.2, 1.2, 1.8]))
    assert ky[0] < ky[1] < ky[2]
    assert cema_mod.ky_fit(10000.0, np.array([10.0]), np.array([0.5]))[0] == 0.016


def test_cema_ai_override_changes_kx_only(hand_conveyor):
    a = solve_steady(hand_conveyor, model="cema", params={"ky": 0.02, "ai_n": 5.0})
    b = solve_steady(hand_conveyor, model="cema", params={"ky": 0.02, "ai_n": 15.0})
    diff = (b.summary["te_components_kn"]["main_carry"]
            - a.summary["te_components_kn"]["main_carry"]) * 1e3
    # 10 N more drag per set, one set every 1.25 m over 1000 m: 800 sets * 10 N = 8000 N
    assert_allclose(diff, 8000.0, rtol=RTOL)


def test_cema_kt_shared():
    # cmod and nonlin use the cema module's Kt table
    assert cema_mod.kt_factor(20.0) == 1.0
    assert_allclose(cema_mod.kt_factor(-30.0), 1.47, rtol=1e-12)
