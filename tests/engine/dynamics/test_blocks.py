"""The implicit blocks round the pulleys (engine/dynamics/blocks.py): their band solve against
a dense solve."""

from __future__ import annotations

import numpy as np
from numpy.testing import assert_allclose

from beltstudy.engine.dynamics.blocks import solve_arrow


def test_block_solve_matches_a_dense_solve():
    """The blocks' band solve (tridiagonal element rows plus the take-up carriage's row and
    column) against numpy's dense solve, on random systems of the form the kernel builds:
    masses / dt on the diagonal plus springs B g g^T, g = e_(k+1) - e_k (+ e_carriage), some
    rows imposed (identity), the carriage free or at its end stop."""
    rng = np.random.default_rng(7)
    for _ in range(300):
        m = int(rng.integers(1, 7))
        car = bool(rng.integers(0, 2))
        mu = m + 1 if car else m
        A = np.diag(rng.uniform(1e3, 1e6, mu))
        for k in range(m - 1):
            g = np.zeros(mu)
            g[k + 1], g[k] = 1.0, -1.0
            if car and rng.integers(0, 2):
                g[m] = 1.0
            A += rng.uniform(0.0, 1e8) * np.outer(g, g)
        b = rng.normal(size=mu) * 1e5
        fixed = rng.uniform(size=m) < 0.25
        car_free = car and rng.uniform() >= 0.3  # a carriage at its end stop is imposed
        Aw, bw = A.copy(), b.copy()
        for k in np.flatnonzero(fixed):
            Aw[k] = 0.0
            Aw[k, k] = 1.0
        if car and not car_free:
            Aw[m] = 0.0
            Aw[m, m] = 1.0
        want = np.linalg.solve(Aw, bw)
        d = np.diag(Aw).copy()
        lo = np.array([Aw[k, k - 1] if k > 0 else 0.0 for k in range(m)] + [0.0])
        up = np.array([Aw[k, k + 1] if k + 1 < m else 0.0 for k in range(m)] + [0.0])
        cl = np.array([Aw[k, m] if car else 0.0 for k in range(m)] + [0.0])
        rw = np.array([Aw[m, k] if car else 0.0 for k in range(m)] + [0.0])
        x = bw.copy()
        assert solve_arrow(d, lo, up, cl, rw, x, m, car, car_free)
        assert_allclose(x, want, rtol=1e-9, atol=1e-12 * np.abs(want).max())
