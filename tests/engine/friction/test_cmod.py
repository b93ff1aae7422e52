"""Modified CEMA (``cmod``) against hand calculations.

Tolerances: 1e-6 relative for the hand calculations (its parts are taken at the final tensions
of a fixed point solved to 1e-6).
"""

from __future__ import annotations

import numpy as np
import pytest
from numpy.testing import assert_allclose

from beltstudy.engine.conveyor import InputError, load_conveyor
from beltstudy.engine.friction import get_model
from beltstudy.engine.law import HS_MAX, HS_REF
from beltstudy.engine.loop import CARRY
from beltstudy.engine.statics import solve_steady
from tests.conftest import CONVEYORS
from tests.engine.friction.conftest import COS, MG, ML, SC, G, L, V


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
    ("cmod", {"ky_sag_share": 2}, "ky_sag_share"),
    ("cmod", {"ky_sag_ref_pct": 0}, "ky_sag_ref_pct"),
])
def test_bad_parameters(model, over, needle):
    with pytest.raises(InputError, match=needle):
        get_model(model).params(over)
