"""ViscoAH (``visco``) against hand calculations.

Tolerances: 1e-9 relative for the hand calculations.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from numpy.testing import assert_allclose

from beltstudy.engine.conveyor import InputError, load_conveyor
from beltstudy.engine.friction import get_model
from beltstudy.engine.statics import solve_steady
from tests.conftest import CONVEYORS
from tests.engine.friction.conftest import COS, HC, MG, ML, SC, SR, D, G, H, L, V, rubber_by_hand

RTOL = 1e-9


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


@pytest.mark.parametrize("model, over, needle", [
    ("visco", {"frequency_hz": 0}, "frequency_hz: must be > 0"),
    ("visco", {"sag_carry_pct": -1}, "sag_carry_pct: must be > 0"),
    ("visco", {"freq": 10}, "did you mean 'frequency_hz'"),
])
def test_bad_parameters(model, over, needle):
    with pytest.raises(InputError, match=needle):
        get_model(model).params(over)
