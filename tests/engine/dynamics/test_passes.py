"""The vectorised passes over the free elements and springs (engine/dynamics/passes.py): the
resistance pass against the reference's law for every exponent code, and the spring law through
the floor into slack and back, by hand."""

from __future__ import annotations

import numpy as np
import pytest
from numpy.testing import assert_allclose

from beltstudy.engine.conveyor import Scenario, load_conveyor
from beltstudy.engine.dynamics import build_system
from beltstudy.engine.dynamics.model import exponent_codes, with_law
from beltstudy.engine.dynamics.passes import resistance, spring
from beltstudy.engine.dynamics.records import Springs
from beltstudy.engine.dynamics.reference import _law
from beltstudy.engine.dynamics.simulate import fresh_run
from beltstudy.engine.statics import solve_steady
from tests.conftest import CONVEYORS


def _spring(e0, s0, de, tfl, sfl, kfl_eb, a_eb, eb):
    """The kernel's update of one spring (:func:`passes.spring`) from elastic tension e0 and
    strain tension s0 after the strain increment de: no arm, no viscosity, no carriage."""
    def one(x):
        return np.array([float(x)])

    none = np.zeros((0, 2), dtype=np.int64)
    sp = Springs(len_m=one(1.0), a_ernst=one(a_eb / eb), t_floor=one(tfl),
                 k_floor=one(kfl_eb * eb), viscosity=one(0.0), car_ind=one(0.0),
                 eps_run=one(0.0), eb=float(eb), eb_dyn=float(eb), dl=one(1.0), a_eb=one(a_eb),
                 s_floor=one(sfl), kfl_eb=one(kfl_eb), kvs=one(0.0), e_damp=0.0, g_damp=0.0,
                 seg_node=none, seg_spring=none)
    return spring(sp, 0, e0, s0, 0.0, de, 0.0)


def test_resistance_every_exponent_code_matches_the_reference_law():
    """The kernel's resistance pass (one specialised loop per speed/sag exponent pair, the
    vectorised log/exp, sparse terms) against the reference's np.power law, for every
    exponent code including ones no shipped model uses, at rest (v = 0) and running."""
    conv = load_conveyor(CONVEYORS / "overland-16km.yaml")
    st = solve_steady(conv, model="nonlin", n_elements=60)
    sys = build_system(conv, Scenario(), st)
    n = sys.n
    rng = np.random.default_rng(1)
    exps = [0.0, 0.5, 1.0, 1.5, 2.0, 0.3, 0.039, 1.7]
    pv, ps, coef = [], [], []
    for p in (0.0, 1.0, 0.3, 2.0, 0.5, 1.7):
        for q in exps:
            pv.append(p)
            ps.append(q)
            coef.append(rng.uniform(0.5, 2.0, n))
    coef = np.array(coef)
    coef[-1, :] = 0.0
    coef[-1, [3, 17]] = 5.0  # a sparse term
    pv, ps = np.array(pv), np.array(ps)
    kr = fresh_run(with_law(sys, coef, pv, ps))
    law, nodes, wk = kr.model.law, kr.model.nodes, kr.work
    assert law.any_ps
    assert law.t_sparse[-1] == 1 and law.t_sparse[:-1].sum() == 0
    assert set(exponent_codes(pv)) | set(exponent_codes(ps)) == {0, 1, 2, 3, 4, 5}
    for v in (np.zeros(n), rng.normal(0.0, 3.0, n)):
        tt = np.maximum(rng.normal(5e4, 3e4, n), 0.0)
        resistance(law, nodes, kr.state._replace(v=v, tt=tt), wk)
        ref = _law(law, nodes, v, tt)
        assert_allclose(wk.r0, ref, rtol=1e-13, atol=1e-12 * np.abs(ref).max())


def _chord_s(t, eb, a_eb, tfl, kfl):
    """Strain tension EB eps of Ernst's chord law by hand, linear at kfl below the floor."""
    sf = tfl - a_eb / (2.0 * tfl**2)
    return t - a_eb / (2.0 * t**2) if t >= tfl else sf - (tfl - t) * eb / kfl


def test_unloading_past_the_floor_stores_the_geometric_slack():
    """A strain increment that takes a spring from running tension to below the floor in one
    step ends on the floor line: by hand, the chord strain 0.1 below the floor's gives
    ``tfl - 0.1 kfl`` (kfl = EB tfl^3 / (tfl^3 + a EB)), slack, and the belt does not push.
    A small increment above the floor lands on the chord law itself (the tension whose chord
    strain is the new strain, solved by bisection, 1e-9)."""
    eb, a_eb, tfl = 3.456e8, 1.97e14, 3.3e3
    kfl = eb * tfl**3 / (tfl**3 + a_eb)
    sf = _chord_s(tfl, eb, a_eb, tfl, kfl)
    e0 = 2.0e5
    s0 = _chord_s(e0, eb, a_eb, tfl, kfl)
    de = (sf - s0) / eb - 0.1
    e1, s1, d1, t1 = _spring(e0, s0, de, tfl, sf, kfl / eb, a_eb, eb)
    assert s1 == pytest.approx(s0 + eb * de, rel=1e-12)
    assert e1 == pytest.approx(tfl - 0.1 * kfl, rel=1e-9)
    assert e1 < 0.0 and t1 == 0.0 and d1 == 0.0  # slack: the belt does not push
    e1, s1, _, _ = _spring(e0, s0, -1e-4, tfl, sf, kfl / eb, a_eb, eb)
    lo, hi = tfl, e0
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if _chord_s(mid, eb, a_eb, tfl, kfl) < s1 else (lo, mid)
    assert e1 == pytest.approx(0.5 * (lo + hi), rel=1e-9)


def test_a_strain_cycle_through_slack_returns_the_tension_it_started_from():
    """The elastic tension is a function of the strain (Ernst's chord law, the floor line,
    slack): a cycle of increments from running tension down through the floor into slack and
    back to the starting strain, in uneven steps, returns the starting tension (1e-9), and the
    elastic work round the cycle, sum of T de, is zero to the order of the steps (a tension
    that lagged the strain would leave work behind)."""
    eb, a_eb, tfl = 3.456e8, 1.97e14, 3.3e3
    kfl = eb * tfl**3 / (tfl**3 + a_eb)
    sf = _chord_s(tfl, eb, a_eb, tfl, kfl)
    e0 = 2.0e5
    s0 = _chord_s(e0, eb, a_eb, tfl, kfl)
    rng = np.random.default_rng(7)
    down = -rng.uniform(0.5, 1.5, 400)
    down *= ((sf - s0) / eb - 2e-3) / down.sum()  # to 2e-3 of strain below the floor
    steps = np.concatenate([down, -down[::-1][rng.permutation(400)]])
    e, s, work, work_scale = e0, s0, 0.0, 0.0
    for de in steps:
        e1, s, _, _ = _spring(e, s, de, tfl, sf, kfl / eb, a_eb, eb)
        work += 0.5 * (max(e, 0.0) + max(e1, 0.0)) * de
        work_scale += 0.5 * (max(e, 0.0) + max(e1, 0.0)) * abs(de)
        e = e1
    assert s == pytest.approx(s0, rel=1e-12)
    assert e == pytest.approx(e0, rel=1e-9)
    assert abs(work) < 1e-3 * work_scale
