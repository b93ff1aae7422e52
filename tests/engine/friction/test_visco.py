"""ViscoAH (``visco``) and modified CEMA (``cmod``) against hand calculations.

Tolerances: 1e-9 relative for the hand calculations (cmod: 1e-6, its parts are taken at the
final tensions of a fixed point solved to 1e-6).
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from numpy.testing import assert_allclose

from beltstudy.engine.conveyor import InputError, load_conveyor, parse_conveyor
from beltstudy.engine.friction import cema as cema_mod
from beltstudy.engine.friction import get_model
from beltstudy.engine.law import HS_MAX, HS_REF
from beltstudy.engine.loop import CARRY
from beltstudy.engine.statics import solve_steady
from tests.conftest import CONVEYORS
from tests.engine.friction.test_nonlin import (
    COS,
    HC,
    MG,
    ML,
    SC,
    SR,
    D,
    G,
    H,
    L,
    V,
    nl_dict,
    rubber_by_hand,
)

RTOL = 1e-9


@pytest.fixture
def conv():
    return parse_conveyor(nl_dict())


def test_visco_terms_by_hand(conv):
    T = 20.0
    res = solve_steady(conv, model="visco", temperature_c=T, n_elements=100)
    assert res.iterations == 1 and not res.law.tension_dependent
    c = res.summary["te_components_kn"]
    assert set(c) == {"lift", "feed", "secondary", "accessories", "idler_rotation",
                      "indentation", "belt_flexure", "material_flexure"}
    # idler rotation: bearing part as nonlin + the file's drag per set, no speed factor
    bearing = G * 0.0015 * (0.045 / D) * ((MG + ML) * COS * L + MG * COS * L)
    drag = (5.0 / SC + 3.0 / SR) * math.exp(-0.017 * T) * L
    assert_allclose(c["idler_rotation"] * 1e3, bearing + drag, rtol=RTOL)
    # indentation: the nonlin per-roll law with tan(delta), E' at the fixed 10 Hz
    tan, e = rubber_by_hand(T, 10.0)
    w_b, w_m = G * MG * COS * SC, G * ML * COS * SC
    k = 1.16 * tan * HC ** (1 / 3) / (e ** (1 / 3) * D ** (2 / 3))
    carry = k * ((w_b / 3 + 0.65 * w_m) ** (4 / 3) + 2 * (w_b / 3 + 0.175 * w_m) ** (4 / 3)) \
        / (1 / 3) ** (1 / 3)
    ret = k * (G * MG * COS * SR) ** (4 / 3)
    assert_allclose(c["indentation"] * 1e3, (carry / SC + ret / SR) * L, rtol=RTOL)
    # flexure allowances at the design sag = sag limits of the file: carry 3 %, return 5 %
    bf = G * 0.0035 * COS * L * ((MG + ML) * 3.0 ** 1.5 + MG * 5.0 ** 1.5)
    assert_allclose(c["belt_flexure"] * 1e3, bf, rtol=RTOL)
    mf = G * (0.4 + 0.08 * V) * (1.66 * SC / SR) ** 1.5 * (ML / 100) * 3.0 * L
    assert_allclose(c["material_flexure"] * 1e3, mf, rtol=RTOL)
    assert_allclose(c["lift"] * 1e3, ML * G * H, rtol=RTOL)
    assert_allclose(sum(c.values()), res.summary["te_kn"], rtol=1e-12)


def test_visco_design_sag_and_drag_overrides(conv):
    a = solve_steady(conv, model="visco", n_elements=50).summary["te_components_kn"]
    b = solve_steady(conv, model="visco", n_elements=50,
                     params={"sag_carry_pct": 6.0, "sag_return_pct": 10.0,
                             "drag_per_set_n": 0.0}).summary["te_components_kn"]
    assert_allclose(b["belt_flexure"] / a["belt_flexure"], 2 ** 1.5, rtol=RTOL)
    assert_allclose(b["material_flexure"] / a["material_flexure"], 2.0, rtol=RTOL)
    bearing = G * 0.0015 * (0.045 / D) * ((MG + ML) * COS * L + MG * COS * L) / 1e3
    assert_allclose(b["idler_rotation"], bearing, rtol=RTOL)


def test_visco_rises_as_temperature_falls():
    conv = load_conveyor(CONVEYORS / "slope-5pct.yaml")
    p = [solve_steady(conv, model="visco", temperature_c=t).summary["power_kw"]
         for t in (40, 20, 0, -20, -40)]
    assert np.all(np.diff(p) > 0)


def test_cmod_terms_by_hand(conv):
    res = solve_steady(conv, model="cmod", temperature_c=20.0, n_elements=100)
    assert res.law.tension_dependent and res.iterations > 1 and res.status != "failed"
    c = res.summary["te_components_kn"]
    assert {"main_carry", "main_return"} <= set(c)
    # classic CEMA Ky (fit), L = 1000 m >= 914.4 m: 0.016 (70 / 100)^0.15 (1.25 / 1.2)^0.3
    ky = max(0.016, 0.016 * (70 / 100) ** 0.15 * (1.25 / 1.2) ** 0.3)
    kx = 0.00068 * (MG + ML) + 5.0 / (G * SC)  # file drag 5 N per carry set
    loop = res.loop
    carry = loop.strand == CARRY
    hs = G * (MG + ML) * COS * SC / 8 / res.tension_mean_n[carry]
    ky_j = ky * (0.5 + 0.5 * np.minimum(hs, HS_MAX) / 0.02)
    main_carry = (G * (1.0 * (kx + ky_j * MG) + ky_j * ML) * loop.dx_m[carry]).sum()
    assert_allclose(c["main_carry"] * 1e3, main_carry, rtol=1e-9)
    # return: g Kt 0.015 m'_G L (CEMA, no cos), Kt(20 C) = 1
    assert_allclose(c["main_return"] * 1e3, G * 1.0 * 0.015 * MG * L, rtol=1e-9)


def test_cmod_reduces_to_cema_without_sag_share(conv):
    for t in (20.0, -30.0):
        a = solve_steady(conv, model="cema", temperature_c=t, n_elements=80)
        b = solve_steady(conv, model="cmod", temperature_c=t, n_elements=80,
                         params={"ky_sag_share": 0.0})
        assert_allclose(b.summary["te_kn"], a.summary["te_kn"], rtol=1e-12)
    # at the reference sag Ky_j = Ky; at half of it the sag part halves
    b = solve_steady(conv, model="cmod", n_elements=80)
    loop, law = b.loop, b.law
    tension_ref = loop.sag_w_n / 0.02  # h/S = 2 % everywhere
    cm = get_model("cmod").build(loop, conv, 20.0, get_model("cmod").params({"ky_sag_share": 0}))
    assert_allclose(law.parts(V, tension_ref)["main_carry"], cm.parts(V, tension_ref)["main_carry"],
                    rtol=1e-12)
    assert HS_REF == 0.01


def test_cmod_below_cema_on_the_well_tensioned_slope():
    conv = load_conveyor(CONVEYORS / "slope-5pct.yaml")
    cema = solve_steady(conv, model="cema").summary["power_kw"]
    res = solve_steady(conv, model="cmod")
    assert res.summary["sag_max_pct"] < 2.0
    assert res.summary["power_kw"] < cema


@pytest.mark.parametrize("model, over, needle", [
    ("visco", {"frequency_hz": 0}, "frequency_hz: must be > 0"),
    ("visco", {"sag_carry_pct": -1}, "sag_carry_pct: must be > 0"),
    ("visco", {"freq": 10}, "did you mean 'frequency_hz'"),
    ("cmod", {"ky_sag_share": 2}, "ky_sag_share"),
    ("cmod", {"ky_sag_ref_pct": 0}, "ky_sag_ref_pct"),
])
def test_bad_parameters(model, over, needle):
    with pytest.raises(InputError, match=needle):
        get_model(model).params(over)


def test_cema_kt_shared():
    # cmod and nonlin use the cema module's Kt table
    assert cema_mod.kt_factor(20.0) == 1.0
    assert_allclose(cema_mod.kt_factor(-30.0), 1.47, rtol=1e-12)
