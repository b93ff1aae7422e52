"""Non-Lin (Harrison 2008, Eq. 1) term by term against hand calculations, its scaling laws,
its one seal-drag temperature law and the flexure cap at the sag limit.

Tolerances: hand calculations 1e-9 relative (the same arithmetic in another order).
"""

from __future__ import annotations

import dataclasses
import math

import numpy as np
import pytest
from numpy.testing import assert_allclose

from beltstudy.engine.conveyor import InputError, load_conveyor, parse_conveyor
from beltstudy.engine.friction import get_model
from beltstudy.engine.friction import nonlin as nl
from beltstudy.engine.law import HS_MAX, HS_REF
from beltstudy.engine.loop import CARRY, RETURN, build_loop
from beltstudy.engine.statics import solve_steady
from tests.conftest import CONVEYORS
from tests.engine.friction.conftest import (
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


def test_every_term_by_hand(conv):
    T = 20.0
    res = solve_steady(conv, model="nonlin", temperature_c=T, n_elements=100)
    assert res.status != "failed" and res.iterations > 1
    c = res.summary["te_components_kn"]
    assert set(c) == {"lift", "feed", "secondary", "accessories", "idler_rotation",
                      "indentation", "belt_flexure", "material_flexure"}
    p = nl.NonlinParams()
    assert p.kta is None  # Kta = CEMA Kt(20 C) = 1.0

    # R, bearing part: g Kta mu_b (d_b / D) (m'_G + m'_L) cos(a) L per strand
    bearing = G * 1.0 * 0.0015 * (0.045 / D) * ((MG + ML) * COS * L + MG * COS * L)
    # R, seal drag: A_i (v / 2)^0.3 e^{-0.017 (T - 0)} / S L, the file's drag per set
    # (5.0 N carry, 3.0 N return)
    speed = (V / 2.0) ** 0.3
    temp = math.exp(-0.017 * T)
    drag = (5.0 / SC + 3.0 / SR) * speed * temp * L
    assert_allclose(c["idler_rotation"] * 1e3, bearing + drag, rtol=RTOL)

    # BI: per roll kappa tan(delta) F^{4/3} h^{1/3} / (b^{1/3} E'^{1/3} D^{2/3}), f = v / 0.03
    tan, e = rubber_by_hand(T, V / 0.03)
    w_b, w_m = G * MG * COS * SC, G * ML * COS * SC  # carry set: belt and material [N]
    centre = w_b / 3 + 0.65 * w_m
    wing = w_b / 3 + 0.175 * w_m
    k = 1.16 * tan * HC ** (1 / 3) / (e ** (1 / 3) * D ** (2 / 3))
    per_set_carry = k * (centre ** (4 / 3) + 2 * wing ** (4 / 3)) / (1 / 3) ** (1 / 3)
    per_set_return = k * (G * MG * COS * SR) ** (4 / 3) / 1.0 ** (1 / 3)
    bi = (per_set_carry / SC + per_set_return / SR) * L
    assert_allclose(c["indentation"] * 1e3, bi, rtol=RTOL)
    assert_allclose(res.law.info["tan_delta"], tan, rtol=RTOL)

    # BF and MF at the solved local sag h/S = g (m'_G + m'_L) cos S / (8 T_mean)
    loop = res.loop
    tm = res.tension_mean_n
    carry, ret = loop.strand == CARRY, loop.strand == RETURN
    hs = np.where(carry, G * (MG + ML) * COS * SC / 8, G * MG * COS * SR / 8) / tm
    phi = np.minimum(hs, HS_MAX) / HS_REF
    bf_c = G * 0.0035 * (MG + ML) * COS * loop.dx_m[carry] * phi[carry] ** 1.5
    bf_r = G * 0.0035 * MG * COS * loop.dx_m[ret] * phi[ret] ** 1.5
    assert_allclose(c["belt_flexure"] * 1e3, bf_c.sum() + bf_r.sum(), rtol=RTOL)
    # MF = (p + q v) (1.66 S_c / S_r)^s (m'_L / 100) phi g dx, carry only
    mf = G * (0.4 + 0.08 * V) * (1.66 * SC / SR) ** 1.5 * (ML / 100.0) * phi[carry]
    assert_allclose(c["material_flexure"] * 1e3, (mf * loop.dx_m[carry]).sum(), rtol=RTOL)

    # V: material lift m'_L g H; feed I_m (v - v0) = 50 x 4 x 4; pulleys 200 + 150 lbf (CEMA T_p)
    assert_allclose(c["lift"] * 1e3, ML * G * H, rtol=RTOL)
    assert_allclose(c["feed"] * 1e3, ML * V * V, rtol=RTOL)
    assert_allclose(c["secondary"] * 1e3, 350 * 4.4482216, rtol=RTOL)
    assert_allclose(c["accessories"] * 1e3, 1500.0, rtol=RTOL)
    # parts at the final tensions, Te at the last iterate: equal to the fixed-point tolerance
    assert_allclose(sum(c.values()), res.summary["te_kn"], rtol=1e-6)
    assert_allclose(res.summary["power_kw"], res.summary["te_kn"] * V, rtol=1e-12)


def test_kta_is_cema_kt_below_zero(conv):
    loop = build_loop(conv, 1.0, n_elements=50)
    fm = get_model("nonlin")
    law = fm.build(loop, conv, -30.0, fm.params())
    # Kt(-30 C) between -34 C (1.55) and -29 C (1.45): 1.55 - 0.10 x 4/5 = 1.47
    assert_allclose(law.info["kta"], 1.47, rtol=1e-12)
    law1 = fm.build(loop, conv, -30.0, fm.params({"kta": 1.0}))
    ratio = law.parts(V, np.full(loop.n, 50e3))["belt_flexure"].sum() / law1.parts(
        V, np.full(loop.n, 50e3))["belt_flexure"].sum()
    assert_allclose(ratio, 1.47, rtol=1e-12)


# ---------------------------------------------------------------------------------------------
# Scaling laws


def _indentation_n_m(d: dict, temperature_c: float = 20.0) -> float:
    """Carry indentation per metre of belt at the design speed [N/m]."""
    conv = parse_conveyor(d)
    loop = build_loop(conv, 1.0, n_elements=20)
    law = get_model("nonlin").build(loop, conv, temperature_c, nl.NonlinParams())
    bi = law.parts(V, np.full(loop.n, 1e5))["indentation"]
    carry = loop.strand == CARRY
    return bi[carry].sum() / loop.dx_m[carry].sum()


def _one_roll(d: dict, **carry) -> dict:
    d["idlers"] = dict(d["idlers"])
    d["idlers"]["carry"] = dict(d["idlers"]["carry"], rolls=1, trough_deg=0, **carry)
    return d


def test_indentation_per_idler_grows_with_load_to_four_thirds():
    # per roll, directly: F^{4/3}
    loads = np.array([[1000.0, 0, 0, 0, 0], [2000.0, 0, 0, 0, 0]])
    per = nl.indentation_per_set(loads, np.array([1.0, 1.0]), np.array([D, D]), HC, 0.2, 5e6,
                                 1.16)
    assert_allclose(per[1] / per[0], 2 ** (4 / 3), rtol=1e-12)
    # through the model: one-roll carry sets, m'_G + m'_L from 70 to 140 kg/m (m'_L 50 -> 120)
    base = _indentation_n_m(_one_roll(nl_dict()))
    heavy = _indentation_n_m(_one_roll(nl_dict(material={"capacity_t_h": 1728,
                                                         "density_t_m3": 1.0})))
    assert_allclose(heavy / base, 2 ** (4 / 3), rtol=1e-9)


def test_indentation_falls_with_idler_diameter():
    values = [_indentation_n_m(_one_roll(nl_dict(), roll_diameter_m=dd))
              for dd in (0.102, 0.133, 0.159, 0.194)]
    assert np.all(np.diff(values) < 0)
    assert_allclose(values[2] / values[1], (0.133 / 0.159) ** (2 / 3), rtol=1e-9)


def test_indentation_per_metre_scales_with_spacing_to_one_third():
    # the per-roll 4/3 law divided by the spacing: S^{4/3} / S = S^{1/3}
    a = _indentation_n_m(_one_roll(nl_dict(), spacing_m=1.0))
    b = _indentation_n_m(_one_roll(nl_dict(), spacing_m=2.0))
    assert_allclose(b / a, 2 ** (1 / 3), rtol=1e-9)


def test_indentation_grows_with_cover_and_falls_with_compound():
    d = nl_dict()  # 10 mm cover, carcass lighter by 5 x 1.15 kg/m2: the same m'_G = 20 kg/m
    d["belt"] = dict(d["belt"], bottom_cover_mm=10, carcass_mass_kg_m2=14.25 - 5.75)
    assert_allclose(_indentation_n_m(d) / _indentation_n_m(nl_dict()), 2 ** (1 / 3), rtol=1e-9)
    d = nl_dict()
    d["belt"] = dict(d["belt"], compound="lrr")
    assert _indentation_n_m(d) < 0.7 * _indentation_n_m(nl_dict())
    # colder cover, more indentation
    assert _indentation_n_m(nl_dict(), -20.0) > 1.5 * _indentation_n_m(nl_dict(), 20.0)


def test_belt_and_material_flexure_fall_as_tension_rises(conv):
    loop = build_loop(conv, 1.0, n_elements=50)
    law = get_model("nonlin").build(loop, conv, 20.0, nl.NonlinParams())
    tensions = [10e3, 20e3, 40e3, 80e3]
    bf = [law.parts(V, np.full(loop.n, t))["belt_flexure"].sum() for t in tensions]
    mf = [law.parts(V, np.full(loop.n, t))["material_flexure"].sum() for t in tensions]
    assert np.all(np.diff(bf) < 0) and np.all(np.diff(mf) < 0)
    assert_allclose(bf[1] / bf[0], 2 ** -1.5, rtol=1e-12)  # n = 3/2
    assert_allclose(mf[1] / mf[0], 2 ** -1.0, rtol=1e-12)  # linear in sag
    # the other parts do not depend on tension
    for name in ("idler_rotation", "indentation", "feed", "secondary", "accessories"):
        a = law.parts(V, np.full(loop.n, 10e3))[name]
        b = law.parts(V, np.full(loop.n, 80e3))[name]
        assert_allclose(a, b, rtol=0, atol=0)
    # a slack span: the sag is capped at 10 %, the resistance stays finite
    slack = law.parts(V, np.full(loop.n, 1.0))["belt_flexure"].sum()
    assert np.isfinite(slack) and slack > bf[0]


def test_idler_drag_rises_as_temperature_falls(conv):
    loop = build_loop(conv, 1.0, n_elements=50)
    fm = get_model("nonlin")

    def rotation(t, **p):
        law = fm.build(loop, conv, t, fm.params(p))
        return law.parts(V, np.full(loop.n, 50e3))["idler_rotation"].sum()

    temps = np.arange(-40.0, 40.01, 10.0)
    values = [rotation(t) for t in temps]
    assert np.all(np.diff(values) < 0)
    # with Kta held at 1 the drag doubles between +20 and -20 C: e^{0.017 x 40} = 1.97
    bearing = rotation(20.0, kta=1.0, drag_per_set_n=0.0)
    ratio = (rotation(-20.0, kta=1.0) - bearing) / (rotation(20.0, kta=1.0) - bearing)
    assert_allclose(ratio, math.exp(0.017 * 40), rtol=1e-12)


def test_seal_drag_factor_scales_the_seal_drag_alone(conv):
    """models.nonlin.seal_drag_factor (SPEC 7.2's sampled axis) multiplies the seal drag A_z
    and nothing else: the idler rotation less its bearing part scales with it exactly, every
    other part stays."""
    loop = build_loop(conv, 1.0, n_elements=50)
    fm = get_model("nonlin")
    tm = np.full(loop.n, 50e3)

    def parts(**p):
        return fm.build(loop, conv, -10.0, fm.params(p)).parts(V, tm)

    bearing = parts(drag_per_set_n=0.0)["idler_rotation"].sum()
    one, two = parts(), parts(seal_drag_factor=2.3)
    assert_allclose(two["idler_rotation"].sum() - bearing,
                    2.3 * (one["idler_rotation"].sum() - bearing), rtol=1e-12)
    assert one["idler_rotation"].sum() - bearing > 0.0
    for name in ("indentation", "belt_flexure", "material_flexure"):
        assert_allclose(two[name], one[name], rtol=0, atol=0)
    with pytest.raises(InputError, match="seal_drag_factor"):
        fm.params({"seal_drag_factor": -1.0}).check()


def test_speed_exponents_of_the_law(conv):
    loop = build_loop(conv, 1.0, n_elements=50)
    law = get_model("nonlin").build(loop, conv, 20.0, nl.NonlinParams())
    pv = {(n, float(pv_), float(ps)) for n, pv_, ps in zip(law.names, law.pv, law.ps,
                                                              strict=True)}
    assert ("idler_rotation", 0.3, 0.0) in pv and ("idler_rotation", 0.0, 0.0) in pv
    assert ("belt_flexure", 0.0, 1.5) in pv
    assert ("material_flexure", 0.0, 1.0) in pv and ("material_flexure", 1.0, 1.0) in pv
    e = law.info["indentation_speed_exp"]
    assert 0.0 < e < 0.5 and ("indentation", e, 0.0) in pv
    # e is the local slope of tan(delta) E'^(-1/3) against frequency at f = v / l_c
    f = V / 0.03
    t1, e1 = rubber_by_hand(20.0, f / 1.1)
    t2, e2 = rubber_by_hand(20.0, f * 1.1)
    assert_allclose(e, math.log((t2 / e2 ** (1 / 3)) / (t1 / e1 ** (1 / 3))) / math.log(1.21),
                    rtol=1e-9)
    # the seal drag alone (no bearing part) scales as v^0.3, material flexure as p + q v
    law = get_model("nonlin").build(loop, conv, 20.0, nl.NonlinParams(mu_b=0.0))
    tm = np.full(loop.n, 50e3)
    slow = law.parts(V / 2, tm)
    fast = law.parts(V, tm)
    assert_allclose(slow["idler_rotation"].sum() / fast["idler_rotation"].sum(), 0.5 ** 0.3,
                    rtol=1e-12)
    assert_allclose(slow["material_flexure"].sum() / fast["material_flexure"].sum(),
                    (0.4 + 0.08 * V / 2) / (0.4 + 0.08 * V), rtol=1e-12)
    assert_allclose(slow["indentation"].sum() / fast["indentation"].sum(), 0.5 ** e,
                    rtol=1e-12)


def test_drag_source_precedence():
    # file drag given (hand conveyor): used as is, per set
    conv = parse_conveyor(nl_dict())
    loop = build_loop(conv, 1.0, n_elements=20)
    drag = nl.idler_drag_n(loop, conv, None, 1.0)
    assert set(drag[loop.strand == CARRY]) == {5.0} and set(drag[loop.strand == RETURN]) == {3.0}
    # no file drag: drag_per_roll_n x rolls (3 carry, 1 return)
    d = nl_dict()
    d["idlers"] = {k: {kk: vv for kk, vv in v.items() if kk != "seal_drag_n"}
                   for k, v in d["idlers"].items()}
    conv = parse_conveyor(d)
    loop = build_loop(conv, 1.0, n_elements=20)
    drag = nl.idler_drag_n(loop, conv, None, 1.0)
    assert set(drag[loop.strand == CARRY]) == {3.0} and set(drag[loop.strand == RETURN]) == {1.0}
    # an explicit drag per set overrides both
    drag = nl.idler_drag_n(loop, conv, 2.5, 1.0)
    assert set(drag[loop.is_idler]) == {2.5} and drag[~loop.is_idler].sum() == 0.0


def test_parameters_documented_and_in_paper_ranges():
    p = nl.NonlinParams()
    assert 0.003 < p.m_star < 0.008 and p.bf_sag_exp == 1.5
    assert 0.2 < p.p_mf < 3 and 0.02 < p.q_mf < 0.6 and 1 < p.s_mf < 3
    assert 0.3 <= p.drag_speed_exp <= 0.5 and p.drag_temp_coef == pytest.approx(0.017)
    assert p.mu_b == pytest.approx(0.0015)
    for f in dataclasses.fields(nl.NonlinParams):
        assert len(f.metadata.get("doc", "")) > 20, f.name


@pytest.mark.parametrize("over, needle", [
    ({"m_stat": 0.005}, "did you mean 'm_star'"),
    ({"m_star": -1}, "m_star: must be >= 0"),
    ({"contact_length_m": 0}, "contact_length_m: must be > 0"),
    ({"centre_share": 1.5}, "centre_share"),
    ({"kta": -0.1}, "kta: must be >= 0"),
])
def test_bad_parameters(over, needle):
    with pytest.raises(InputError, match=needle):
        get_model("nonlin").params(over)


def test_empty_belt_reports_every_part(conv):
    res = solve_steady(conv, model="nonlin", load="empty", n_elements=50)
    c = res.summary["te_components_kn"]
    assert set(c) == {"lift", "feed", "secondary", "accessories", "idler_rotation",
                      "indentation", "belt_flexure", "material_flexure"}
    assert c["material_flexure"] == 0.0 and c["lift"] == 0.0 and c["feed"] == 0.0
    assert c["indentation"] > 0 and c["belt_flexure"] > 0


# ---------------------------------------------------------------------------------------------
# One seal-drag temperature law, the flexure cap


def test_nonlin_seal_drag_has_one_temperature_law():
    """The seal drag follows the paper's e^{-c T} alone: from 0 C to -30 C it grows by
    e^{0.017 x 30} = 1.665, not by CEMA's Kt on top (1.665 x 1.47)."""
    conv = load_conveyor(CONVEYORS / "slope-5pct.yaml")
    loop = build_loop(conv, 1.0, n_elements=40)
    fm = get_model("nonlin")

    def seal(temp):
        law = fm.build(loop, conv, temp, fm.params())
        k = [i for i, name in enumerate(law.names) if name == "idler_rotation"
             and law.pv[i] != 0.0]
        return float(law.coef[k].sum())

    assert seal(-30.0) / seal(0.0) == pytest.approx(math.exp(0.017 * 30.0), rel=1e-9)


def test_sag_dependent_resistance_is_capped_at_the_strands_sag_limit():
    """A slack span keeps the resistance the law gives at its strand's admissible sag (the
    conveyor's sag_limit_pct): belt flexure at zero tension equals it at the limit."""
    conv = load_conveyor(CONVEYORS / "slope-5pct.yaml")
    loop = build_loop(conv, 1.0, n_elements=40)
    law = get_model("nonlin").build(loop, conv, 20.0, get_model("nonlin").params())
    carry = loop.strand == 0
    t_at_limit = loop.sag_w_n / (conv.sag_limit_pct.carry / 100.0)
    slack = law.parts(4.5, np.full(loop.n, 1.0))["belt_flexure"][carry]
    at_limit = law.parts(4.5, t_at_limit)["belt_flexure"][carry]
    np.testing.assert_allclose(slack, at_limit, rtol=1e-12)
    # by hand: (1.5 % / 1 %)^1.5 times the reference-sag value
    ref = law.parts(4.5, loop.sag_w_n / 0.01)["belt_flexure"][carry]
    np.testing.assert_allclose(slack, ref * 1.5**1.5, rtol=1e-12)
