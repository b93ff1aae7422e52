"""The kernel's fast scalar maths (engine/dynamics/fastmath.py): vectorised log and exp
against numpy."""

from __future__ import annotations

import numpy as np
from numba import njit
from numpy.testing import assert_allclose

from beltstudy.engine.dynamics.fastmath import OPTS, _exp, _ln

#: The kernel's options, not cached: these loops exist for this test alone (a cached function
#: the engine never runs would count as not compiled, engine/warmth.py).
_OPTS = {**OPTS, "cache": False}


@njit(**_OPTS)
def vlog(x, out):
    """``out = ln(x)`` for x >= 0 with the kernel's :func:`_ln`."""
    for j in range(x.shape[0]):
        out[j] = _ln(x[j])


@njit(**_OPTS)
def vexp(y, out):
    """``out = exp(y)`` for y in [-700, 700] with the kernel's :func:`_exp`."""
    for j in range(y.shape[0]):
        out[j] = _exp(y[j])


def test_vectorised_log_and_exp():
    x = np.concatenate([[1e-300, 1e-12, 1.0, 2.0], np.exp(np.linspace(-20, 20, 997))])
    out = np.empty_like(x)
    vlog(x, out)
    err = np.abs(out - np.log(x)) / np.maximum(1.0, np.abs(np.log(x)))
    assert err.max() < 2e-15
    y = np.linspace(-700, 700, 1001)
    vexp(y, out[:1001])
    assert_allclose(out[:1001], np.exp(y), rtol=5e-15)
    for p in (0.3, 0.039, 1.7):  # the powers the friction laws use
        z = np.exp(np.linspace(-5, 3, 500))
        lz, pz = np.empty(500), np.empty(500)
        vlog(z, lz)
        vexp(p * lz, pz)
        assert_allclose(pz, z**p, rtol=1e-14)
