"""The resistance law between exact evaluations (beltstudy.engine.dynamics.linlaw): the windows bound the
expansion's error by the stated tolerance, the kernel's evaluation and expansion are the
reference's, and the expanded law leaves the results of the example cycles within 0.1 % of the
exact law's."""

from __future__ import annotations

import numpy as np
import pytest

from beltstudy.engine.conveyor import InputError, Scenario, load_conveyor
from beltstudy.engine.dynamics import DynamicsOptions, build_system
from beltstudy.engine.dynamics import codes as C
from beltstudy.engine.dynamics.linlaw import (
    BIG,
    PREDICT,
    creep_bound,
    element_windows,
    expansion,
    law_windows,
    remainder_bound,
)
from beltstudy.engine.dynamics.model import with_law
from beltstudy.engine.dynamics.passes import law_refresh
from beltstudy.engine.dynamics.reference import ExpandedLaw
from beltstudy.engine.dynamics.simulate import fresh_run, simulate
from beltstudy.engine.statics import solve_steady
from tests.conftest import CONVEYORS

RTOL = 1e-3
OVERLAND = dict(start={"control": "s-curve", "time_s": 120}, run_s=30,
                stop={"mode": "controlled", "time_s": 60})


def _system(name="overland-16km", model="nonlin", n=60, scenario=None, rtol=RTOL):
    conv = load_conveyor(CONVEYORS / f"{name}.yaml")
    scn = Scenario(**(scenario or {}))
    st = solve_steady(conv, model=model, load=scn.load, n_elements=n)
    return conv, st, build_system(conv, scn, st, DynamicsOptions(resistance_rtol=rtol))


def _terms(coef, pv, ps, u, phi):
    """The exact law's terms (K, m) at speeds u and sag ratios phi."""
    return np.array([c * np.power(u, p) * np.power(phi, q)
                     for c, p, q in zip(coef, pv, ps, strict=True)])


def _sums(t, pv, ps):
    p, q = pv[:, None], ps[:, None]
    return (t.sum(0), (p * t).sum(0), (p * (p - 1) * t).sum(0), (q * t).sum(0),
            (q * (q + 1) * t).sum(0), (p * q * t).sum(0))


def test_windows_meet_the_tolerance_for_non_lin_and_other_exponents():
    """The window sizes put the largest Taylor remainder of every term at or below rtol, and
    the creep window the regularised force's error; a sag-only law has no speed window, a law
    without powers is evaluated exactly."""
    _, _, sys = _system()
    law = sys.model.law
    w = law_windows(law.coef, law.pvv, law.psv, RTOL)
    pairs = sorted(set(zip(law.pvv.tolist(), law.psv.tolist(), strict=True)))
    assert 0.1 < w.du < 0.5 and 0.02 < w.dx < 0.2 and 0.0 < w.d0 < 0.01
    assert remainder_bound(pairs, w.du, w.dx) <= RTOL
    assert creep_bound(pairs, w.d0, w.dx) <= RTOL
    assert w.bound <= RTOL and w.creep <= RTOL
    coef = np.ones((2, 100))
    sag = law_windows(coef, np.array([0.0, 0.0]), np.array([0.0, 1.7]), RTOL)
    assert sag.du == BIG and sag.d0 == BIG and sag.bound <= RTOL
    assert law_windows(coef, np.array([0.0, 1.0]), np.array([0.0, 1.0]), RTOL) is None
    assert law_windows(law.coef, law.pvv, law.psv, 0.0) is None


@pytest.mark.parametrize("pv,ps", [
    (None, None),  # Non-Lin's own law on the 16.8 km example
    ([0.0, 0.3, 1.0, 2.0, 0.039, 0.0, 1.0, 0.3], [0.0, 1.5, 1.0, 0.5, 2.0, 1.7, 2.5, 0.7]),
])
def test_expansion_stays_within_rtol_of_the_exact_law_over_its_windows(pv, ps):
    """Sampled: expansion points over speeds 1e-7..10 m/s and tensions from the sag cap to
    1 MN, states anywhere in their windows (corners included). Above the creep window the
    expanded law is within rtol of the exact law's terms' sum at the state; in the creep window
    the regularised force is within rtol of the law's value at v_eps."""
    _, _, sys = _system()
    rng = np.random.default_rng(7)
    law = sys.model.law
    coef_all, pv_, ps_ = law.coef, law.pvv, law.psv
    if pv is not None:
        pv_, ps_ = np.array(pv), np.array(ps)
        coef_all = rng.uniform(0.5, 2.0, (len(pv), sys.n))
    v_eps = sys.model.cycle.v_eps
    w = law_windows(coef_all, pv_, ps_, RTOL)
    sw = sys.model.nodes.sag_w / law.hs_ref
    hsm = sys.model.nodes.hs_cap / law.hs_ref
    du, d0, dx = element_windows(coef_all, pv_, ps_, sw, hsm, v_eps, w)
    m = 20000
    j = rng.integers(0, sys.n, m)
    j = j[(du[j] < BIG) & (dx[j] < BIG)]
    m = len(j)
    xcap = np.maximum(1.0, sw[j] / hsm[j])
    uc = 10.0 ** rng.uniform(-7, 1, m)
    tc = xcap * 10.0 ** rng.uniform(0, 4, m)
    coef = coef_all[:, j]
    tc_phi = np.minimum(sw[j] / tc, hsm[j])
    moving = du[j] * uc >= d0[j]
    r, a, aa, b, bb, e = _sums(_terms(coef, pv_, ps_, uc, tc_phi), pv_, ps_)
    poly = expansion(r, a, aa, b, bb, e, uc, tc, moving, np.ones(m, dtype=bool))
    corners = rng.integers(0, 2, (2, m)) * 2 - 1
    for x, y in [(rng.uniform(-1, 1, m), rng.uniform(-1, 1, m)), corners]:
        u = np.where(moving, uc * (1 + x * du[j]), np.maximum(uc + x * d0[j], 0.0))
        t = np.maximum(tc * (1 + y * dx[j]), xcap)
        phi = np.minimum(sw[j] / t, hsm[j])
        tk = _terms(coef, pv_, ps_, u, phi)
        k, gu, guu, gx, gxx, gux = poly
        approx = k + u * (gu + guu * u + gux * t) + t * (gx + gxx * t)
        err = np.abs(approx - tk.sum(0))
        scale = np.abs(tk).sum(0)
        assert np.all(err[moving] <= RTOL * scale[moving] * (1 + 1e-9))
        # creep: the force R0 min(u / v_eps, 1), against the law at v_eps (and phi at T)
        creep = ~moving
        at_veps = np.abs(_terms(coef, pv_, ps_, np.full(m, v_eps), phi)).sum(0)
        force_err = err * np.minimum(u / v_eps, 1.0)
        assert np.all(force_err[creep] <= RTOL * at_veps[creep] * (1 + 1e-9))
        assert creep.sum() > 100 and moving.sum() > 1000


def test_kernel_evaluation_and_expansion_are_the_references():
    """law_refresh (the kernel's exact evaluation, expansion point and windows) against the
    reference's ExpandedLaw on random states and old windows, for a law with every kind of
    factor: powers by exp and log, square roots, squares, the sag cap and the creep window."""
    _, _, sys = _system(n=200)
    rng = np.random.default_rng(3)
    pv = np.array([0.0, 0.3, 1.0, 2.0, 0.3, 0.039, 0.0, 1.0])
    ps = np.array([0.0, 1.5, 1.0, 0.5, 2.0, 0.0, 1.7, 0.0])
    coef = rng.uniform(0.5, 2.0, (8, sys.n))
    coef[7] = 0.0
    coef[7, [5, 50]] = 3.0  # a sparse term
    sys = with_law(sys, coef, pv, ps)
    kr = fresh_run(sys)
    assert kr.model.law.mode == C.LAW_LINEAR
    lin = kr.model.lin
    ref = ExpandedLaw(sys)
    n = sys.n
    v = rng.choice([-1.0, 1.0], n) * 10.0 ** rng.uniform(-9, 1, n)
    v[:5] = 0.0
    tt = 10.0 ** rng.uniform(1, 6, n)
    # the first evaluation of every element, then again from random old windows
    ref(v, tt)
    idx = np.zeros(n + 8, dtype=np.int64)
    idx[:n] = np.arange(n)
    r0 = np.zeros(n)
    law_refresh(idx, n, v, tt, lin, r0)
    for _ in range(2):
        poly_k = np.array([lin.k, lin.gu, lin.guu, lin.gx, lin.gxx, lin.gux])
        bounds_k = np.array([lin.ulo, lin.uhi, lin.tlo, lin.thi])
        for row_k, row_r in zip(poly_k, ref.poly, strict=True):
            np.testing.assert_allclose(row_k, row_r, rtol=1e-12,
                                       atol=1e-13 * np.abs(row_r).max())
        np.testing.assert_allclose(bounds_k, ref.bounds, rtol=1e-15, atol=0)
        np.testing.assert_allclose(r0, ref(v, tt), rtol=1e-12)
        v = v * rng.uniform(0.5, 1.5, n)
        tt = tt * rng.uniform(0.5, 1.5, n)
        ref._evaluate(np.arange(n), np.abs(v), 0.5 * (np.roll(tt, 1) + tt))
        law_refresh(idx, n, v, tt, lin, r0)


def test_modes_and_the_tolerance_option():
    """Non-Lin's law is expanded, DIN's constant, CEMA's (constant and feed) exact every step;
    resistance_rtol 0 evaluates Non-Lin's exactly; out-of-range tolerances are refused."""
    for model, mode in (("din", C.LAW_CONST), ("cema", C.LAW_EXACT), ("nonlin", C.LAW_LINEAR)):
        _, _, sys = _system(model=model, n=40)
        assert sys.model.law.mode == mode, model
    _, _, sys = _system(n=40, rtol=0.0)
    assert sys.model.law.mode == C.LAW_EXACT
    conv, st, _ = _system(n=40)
    for bad in (-1e-3, 0.05):
        with pytest.raises(InputError, match="resistance_rtol"):
            build_system(conv, Scenario(), st, DynamicsOptions(resistance_rtol=bad))
    assert 0.0 < PREDICT < 1.0


KEYS = ("t_max_dyn_kn", "t_min_dyn_kn", "drive_force_max_kn", "drive_power_max_kw",
        "start_time_s", "stop_time_s", "takeup_travel_m", "slack_max_m", "t_max_stop_kn",
        "t_min_stop_kn")


@pytest.mark.parametrize("name,n,scenario", [
    ("overland-16km", 1000, OVERLAND),
    ("fabric-1km", 200, dict(stop={"mode": "coast"})),
    ("downhill-regen", 200, {}),
    ("overland-4km", 400, dict(stop={"mode": "brake", "time_s": 10})),
])
def test_expanded_law_results_within_a_tenth_of_a_percent_of_the_exact_law(name, n, scenario):
    """Whole cycles with Non-Lin's law expanded (the default, rtol 1e-3) and evaluated exactly
    every step: peak and lowest tension (whole cycle and stop), peak drive force and power,
    start and stop times, take-up travel, slack and drive work within 0.1 % (the lowest
    tension of the peak tension, the slack of 1 m)."""
    conv, st, exact = _system(name, n=n, scenario=scenario, rtol=0.0)
    expanded = build_system(conv, Scenario(**scenario), st)
    a = simulate(exact, steady_summary=st.summary, conveyor=conv)
    b = simulate(expanded, steady_summary=st.summary, conveyor=conv)
    assert a.status == b.status and a.raw["steps"] == b.raw["steps"]
    assert b.raw["law_evals"] < 0.02 * b.raw["steps"] * expanded.n
    sa, sb = a.summary, b.summary
    t_peak = sa["t_max_dyn_kn"]
    for key in KEYS:
        if sa.get(key) is None:
            assert sb.get(key) is None, key
            continue
        scale = t_peak if key.startswith("t_min") else (1.0 if key == "slack_max_m"
                                                         else abs(sa[key]))
        assert abs(sb[key] - sa[key]) <= 1e-3 * scale, (key, sa[key], sb[key])
    assert b.raw["w_drive"] == pytest.approx(a.raw["w_drive"], rel=1e-3)
