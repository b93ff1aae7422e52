"""DIN 22101 and CEMA against hand calculations, term by term (tolerance 0.1 %)."""

from __future__ import annotations

import math

import numpy as np
import pytest
from numpy.testing import assert_allclose

from beltstudy.engine.friction import cema as cema_mod
from beltstudy.engine.friction import din as din_mod
from beltstudy.engine.statics import solve_steady

G = 9.81
RTOL = 1e-3  # 0.1 %

# The hand conveyor (tests/conftest.py): L = 1000 m, H = 50 m, v = 4 m/s
L, H, V = 1000.0, 50.0, 4.0
SIN = H / L
COS = math.sqrt(1 - SIN**2)  # 0.998749
MG, ML, MRC, MRR = 20.0, 50.0, 10.0, 3.0  # kg/m
LBF = 4.4482216


def test_din_terms_by_hand(hand_conveyor):
    res = solve_steady(hand_conveyor, model="din",
                       params={"f_carry": 0.020, "f_return": 0.015}, n_elements=100)
    c = res.summary["te_components_kn"]
    # F_H carry = f g L [m'_R + (m'_G + m'_L) cos] = 0.020 * 9.81 * 1000 * (10 + 70 * 0.998749)
    fh_carry = 0.020 * G * L * (MRC + (MG + ML) * COS)  # = 15 678.6 N
    # F_H return = 0.015 * 9.81 * 1000 * (3 + 20 * 0.998749)
    fh_return = 0.015 * G * L * (MRR + MG * COS)  # = 3 380.9 N
    # C(1000 m) = 1.09 (DIN table); secondary = (C - 1) (F_H carry + F_H return)
    secondary = 0.09 * (fh_carry + fh_return)
    lift = ML * G * H  # material lift = 50 * 9.81 * 50 = 24 525 N
    accessories = 1500.0  # head 1.0 kN + tail 0.5 kN
    assert_allclose(c["main_carry"] * 1e3, fh_carry, rtol=RTOL)
    assert_allclose(c["main_return"] * 1e3, fh_return, rtol=RTOL)
    assert_allclose(c["secondary"] * 1e3, secondary, rtol=RTOL)
    assert_allclose(c["lift"] * 1e3, lift, rtol=RTOL)
    assert c["feed"] == 0.0  # inside C for L >= 80 m
    te = fh_carry + fh_return + secondary + lift + accessories
    assert_allclose(res.summary["te_kn"] * 1e3, te, rtol=RTOL)
    assert_allclose(res.summary["power_kw"] * 1e3, te * V, rtol=RTOL)
    assert_allclose(sum(c.values()), res.summary["te_kn"], rtol=1e-9)


def test_din_c_table_and_override(hand_conveyor):
    assert din_mod.c_factor(1000) == pytest.approx(1.09)
    assert din_mod.c_factor(90) == pytest.approx((1.92 + 1.78) / 2)
    assert din_mod.c_factor(20000) == pytest.approx(1.03)
    res = solve_steady(hand_conveyor, model="din", params={"c": 1.5, "f_carry": 0.0,
                                                           "f_return": 0.0})
    comps = res.summary["te_components_kn"]
    # zero friction factors (verification runs): only lift and accessories remain
    assert comps["main_carry"] == 0.0 and comps["secondary"] == 0.0
    assert_allclose(res.summary["te_kn"] * 1e3, ML * G * H + 1500.0, rtol=RTOL)


def test_din_temperature_independent(hand_conveyor):
    a = solve_steady(hand_conveyor, model="din", temperature_c=-40).summary["te_kn"]
    b = solve_steady(hand_conveyor, model="din", temperature_c=40).summary["te_kn"]
    assert a == b


def test_din_short_conveyor_explicit_secondary(hand_dict):
    from beltstudy.engine.conveyor import parse_conveyor

    hand_dict["profile"] = [{"length_m": 60, "lift_m": 3}]
    conv = parse_conveyor(hand_dict)
    res = solve_steady(conv, model="din")
    c = res.summary["te_components_kn"]
    # feed I_m (v - v0) = m'_L v * v = 50 * 4 * 4 = 800 N
    assert_allclose(c["feed"] * 1e3, 800.0, rtol=RTOL)
    # pulley allowances: head drive 200 lbf, tail take-up (slack side) 150 lbf
    assert_allclose(c["secondary"] * 1e3, (200 + 150) * LBF, rtol=RTOL)


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
