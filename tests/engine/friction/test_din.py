"""DIN 22101 against hand calculations, term by term (tolerance 0.1 %)."""

from __future__ import annotations

import pytest
from numpy.testing import assert_allclose

from beltstudy.engine.friction import din as din_mod
from beltstudy.engine.statics import solve_steady
from tests.engine.friction.conftest import COS, LBF, MG, ML, MRC, MRR, G, H, L, V

RTOL = 1e-3  # 0.1 %


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
