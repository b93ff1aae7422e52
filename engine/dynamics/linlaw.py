"""The resistance law between exact evaluations: each element's law expanded about an
expansion point and used while the element's speed and tension stay within windows round it,
sized for a stated accuracy.

The law ``R0_j = sum_k c_kj u_j^p_k phi_j^q_k`` (``u = |v|`` [m/s], ``phi_j`` the sag ratio
over the reference from the element's mean tension ``T_j`` [N], ``beltstudy.engine.law``) costs a
logarithm, an exponential per fractional exponent, a division and a square root per element
and step, more than the rest of the step. Speed and tension change slowly compared with the
step (set by the wave criterion over one element), so the kernel evaluates the law exactly
only for the elements whose state has left the window round their expansion point (``u_c``,
``T_c``), and otherwise uses the law's second-order expansion about that point:

    ``R0 = R_c + G_u du + H_uu du^2 + G_T dT + H_TT dT^2 + H_uT du dT``
    (``du = u - u_c``, ``dT = T - T_c``)

``G_u = sum_k p_k t_k / u_c``, ``H_uu = sum_k p_k (p_k - 1) t_k / (2 u_c^2)``, ``G_T = -sum_k
q_k t_k / T_c``, ``H_TT = sum_k q_k (q_k + 1) t_k / (2 T_c^2)``, ``H_uT = -sum_k p_k q_k t_k /
(u_c T_c)`` (``t_k`` the exact terms at the expansion point, ``phi = sw / T``), kept as a
polynomial in u and T [N] (:func:`expansion`; six float32 numbers per element, their rounding
included in the bounds below). The windows, per element:

* speed: ``|u - u_c| <= du u_c`` where that is wider than the creep window ``d0 v_eps``;
  below (creep, ``u_c < d0 v_eps / du``, where the law acts as ``R0 v / v_eps``, the
  regularised stand-in for sticking) the speed dependence is held (``G_u = H_uu = H_uT =
  0``) within ``|u - u_c| <= d0 v_eps``;
* tension: ``|T - T_c| <= dx T_c``, and on the same side of ``X_cap``, the tension below which
  the sag ratio is held at its cap (below it ``G_T = H_TT = H_uT = 0``: the law does not
  change with T).

An element with no speed-dependent (sag-dependent) term has no speed (tension) window. When an
element leaves its window, the law is evaluated exactly at its new expansion point: its state
moved by ``PREDICT`` (half) of the window the way it was moving (towards the side of the old
window it is on). The state is inside the new window, farther from the edge it is heading
for, so a steady acceleration crosses a window in one and a half times as many steps.

The window sizes follow from the law's exponents and the tolerance ``rtol``
(``DynamicsOptions.resistance_rtol``, 1e-3 by default) by the Taylor remainder of each term,
``(1 + x)^p (1 + y)^-q`` less ``1 + p x + p (p - 1) x^2 / 2 - q y + q (q + 1) y^2 / 2 - p q x
y``, over ``|x| <= du``, ``|y| <= dx`` (:func:`law_windows`). The stated accuracy, at every
step and every element:

* outside the creep window the resistance used is within ``rtol`` of the exact law at the
  current state: ``|R0 - R0_exact| <= rtol sum_k |t_k|`` (``rtol R0_exact`` when every term
  is positive, as in every friction model), and so is the force ``R0 min(u / v_eps, 1)``;
* in the creep window the regularised force is within ``rtol`` of the law's value at
  ``v_eps`` (at the same tension).

For Non-Lin (``rtol`` 1e-3): ``du`` = 0.23, ``dx`` = 0.052, ``d0`` = 6.3e-4.

``rtol = 0`` evaluates the exact law every step; so does a law whose element-wide terms need no
power, logarithm or square root (speed exponents 0 and 1, sag exponents 0, 1 and 2: DIN, CEMA,
VISCO, C-MOD with its linear sag term), which costs no more than the expansion. The sign and
the regularisation below ``v_eps`` are applied exactly every step
(:func:`beltstudy.engine.dynamics.passes.node_pass`).

The kernel (:func:`beltstudy.engine.dynamics.passes.law_refresh`, :func:`~beltstudy.engine.dynamics.passes.
observe_lin`) and the numpy reference (:class:`beltstudy.engine.dynamics.reference.ExpandedLaw`) apply
the same windows, expansion points and expansion, so they agree to rounding; the exact law is
``resistance_rtol = 0``.
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import lru_cache

import numpy as np

__all__ = ["LawWindows", "law_windows", "element_windows", "sparse_terms", "x_cap",
           "expansion", "remainder_bound", "creep_bound", "BIG", "DU_MAX", "K_LIN", "N_POW",
           "PREDICT", "F32"]

#: The window size (and bound) of a quantity the law does not depend on: never crossed (finite:
#: the kernel's reductions are compiled without infinities, and float32 holds it).
BIG = 1e38
#: Unit roundoff of float32, in which the expansion's coefficients and the windows' edges are
#: stored: the bounds include it.
F32 = 2.0**-24
#: Most terms (merged by exponents) of a law the kernel expands: the kernel's element-wise
#: evaluation is unrolled over them (:func:`beltstudy.engine.dynamics.passes.law_refresh`).
K_LIN = 8
#: Most speed exponents other than 0 and 1, and most sag exponents other than 0, 0.5, 1, 1.5
#: and 2, of a law the kernel expands (each an exponential there).
N_POW = 3
#: Where the expansion point goes when an element's law is evaluated again: its state moved
#: by this fraction of the window towards the side of the old window the state left by, the
#: way it has been moving (the state stays inside the new window, farther from the edge it is
#: moving to). 0: the expansion point is the state.
PREDICT = 0.5
#: Largest relative speed window.
DU_MAX = 0.5
#: Bisection steps of the window sizes (the sizes found are within 2^-18 of their range of
#: the largest that meet the tolerance).
BISECTIONS = 18


@dataclass(frozen=True)
class LawWindows:
    """Window sizes of the expanded law and the accuracy they give.

    ``du``, ``dx``: relative speed and tension windows [-] (BIG: no term depends on it);
    ``d0``: creep window as a fraction of ``v_eps`` [-] (BIG: no speed dependence); ``bound``:
    largest relative remainder outside the creep window [-]; ``creep``: largest error of the
    regularised force in the creep window, relative to the law's value at ``v_eps`` [-]. Both
    are at most ``rtol``.
    """

    du: float
    dx: float
    d0: float
    bound: float
    creep: float
    rtol: float


def sparse_terms(coef: np.ndarray) -> np.ndarray:
    """Terms acting on a few elements only (feed, pulleys, accessories): bool per term. The
    kernel evaluates them on those elements only."""
    n = coef.shape[1]
    return np.array([np.count_nonzero(c) <= max(8, n // 16) for c in coef], dtype=bool)


def x_cap(sw_ref: np.ndarray, hsm_ref: np.ndarray) -> np.ndarray:
    """The mean tension below which the sag ratio is held at its cap, per element [N]:
    ``phi = min(sw_ref / max(T, 1), hsm_ref)`` is ``sw_ref / T`` above ``X_cap = max(1,
    sw_ref / hsm_ref)`` and constant below (1 where the element has no sag)."""
    ok = (sw_ref > 0.0) & (hsm_ref > 0.0)
    return np.where(ok, np.maximum(1.0, sw_ref / np.where(ok, hsm_ref, 1.0)), 1.0)


def expansion(r, a, aa, b, bb, e, u, t, moving, uncapped):
    """The expansion about ``(u, t)`` as a polynomial ``k + gu u + guu u^2 + gx T + gxx T^2 +
    gux u T`` (numpy arrays; the kernel's :func:`passes.law_refresh` computes the same, element
    by element). ``r = sum t_k``, ``a = sum p t_k``, ``aa = sum p (p - 1) t_k``, ``b = sum q
    t_k``, ``bb = sum q (q + 1) t_k``, ``e = sum p q t_k``; ``moving``: the speed is expanded
    (else held), ``uncapped``: the sag ratio follows the tension (else held). Returns ``(k,
    gu, guu, gx, gxx, gux)``."""
    iu = np.where(moving, 1.0 / np.where(moving, u, 1.0), 0.0)
    it = np.where(uncapped, 1.0 / np.where(uncapped, t, 1.0), 0.0)
    g_u = a * iu
    h_uu = 0.5 * aa * iu * iu
    g_t = -b * it
    h_tt = 0.5 * bb * it * it
    h_ut = -e * iu * it
    k = r - g_u * u + h_uu * u * u - g_t * t + h_tt * t * t + h_ut * u * t
    return (k, g_u - 2.0 * h_uu * u - h_ut * t, h_uu, g_t - 2.0 * h_tt * t - h_ut * u, h_tt,
            h_ut)


def _grid(d: float, k: int = 65) -> np.ndarray:
    return np.linspace(-d, d, k) if 0.0 < d < BIG else np.zeros(1)


def _storage(p, q, su, sv):
    """The polynomial's monomials' sizes, ``sum_i |c_i| U^a_i V^b_i`` at ``U = u / u_c = su``,
    ``V = T / T_c = sv``, for one term in units of its value at the expansion point: each
    coefficient is stored in float32, so the expansion is off by at most F32 times this."""
    a = 0.5 * p * (p - 1.0)
    b = 0.5 * q * (q + 1.0)
    return (abs(1.0 - p + a + q + b - p * q) + abs(p - 2.0 * a + p * q) * su + abs(a) * su * su
            + abs(-q - 2.0 * b + p * q) * sv + abs(b) * sv * sv + abs(p * q) * su * sv)


def remainder_bound(pairs, du: float, dx: float) -> float:
    """Largest relative error of the expansion over the windows: the maximum over the terms
    ``(p, q)`` and ``|x| <= du``, ``|y| <= dx`` of ``(|f - taylor| + F32 storage) / f``, ``f =
    (1 + x)^p (1 + y)^-q``, ``taylor = 1 + p x + p (p - 1) x^2 / 2 - q y + q (q + 1) y^2 / 2 -
    p q x y``, storage the float32 rounding of the stored polynomial and of the window's edges
    (:func:`_storage`) [-] (on a 65 x 65 grid with the box's edges; the remainder is smooth
    and largest at the corners)."""
    x = _grid(du * (1.0 + 2.0 * F32))[:, None]
    y = _grid(dx * (1.0 + 2.0 * F32))[None, :]
    worst = 0.0
    for p, q in pairs:
        f = (1.0 + x) ** p * (1.0 + y) ** (-q)
        taylor = (1.0 + p * x + 0.5 * p * (p - 1.0) * x * x - q * y + 0.5 * q * (q + 1.0) * y * y
                  - p * q * x * y)
        err = np.abs(f - taylor) + F32 * _storage(p, q, 1.0 + x, 1.0 + y)
        worst = max(worst, float(np.max(err / f)))
    return worst


def _tension_remainder(pairs, dx: float) -> float:
    y = _grid(dx * (1.0 + 2.0 * F32))
    return max(float(np.max(np.abs((1.0 + y) ** (-q) - 1.0 + q * y - 0.5 * q * (q + 1.0) * y * y)
                            + F32 * _storage(0.0, q, 1.0, 1.0 + y)))
               for _, q in pairs)


def creep_bound(pairs, d0: float, dx: float) -> float:
    """Largest error of the regularised force ``R0 min(u / v_eps, 1)`` in the creep window,
    the speed dependence held within ``|u - u_c| <= d0 v_eps`` and the tension expanded
    within ``dx``, relative to the term's value at ``v_eps`` [-]: over ``a = u_c / v_eps`` in
    [0, 1] and the window's ends, ``|u^p - a^p| min(u, 1) (1 - dx)^-q`` plus the tension
    remainder."""
    a = np.unique(np.concatenate([np.linspace(0.0, 1.0, 1001), np.geomspace(1e-12, 1.0, 200)]))
    worst = 0.0
    for p, q in pairs:
        if p == 0.0:
            continue
        hi = a + d0
        lo = np.maximum(a - d0, 0.0)
        e = np.maximum(np.abs(hi**p - a**p) * np.minimum(hi, 1.0),
                       np.abs(lo**p - a**p) * np.minimum(lo, 1.0))
        worst = max(worst, float(e.max()) * (1.0 - min(dx, 0.5)) ** (-q))
    return worst + _tension_remainder(pairs, min(dx, 0.5))


def _largest(ok, hi: float) -> float:
    """The largest s in (0, hi] with ok(s) (ok holds below some size), by bisection."""
    if ok(hi):
        return hi
    lo = 0.0
    for _ in range(BISECTIONS):
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if ok(mid) else (lo, mid)
    return lo


#: Share of the tolerance the speed window takes on its own; the tension window takes the rest
#: (speed moves most elements most often, so its window is the one to keep wide).
SPEED_SHARE = 0.9


@lru_cache(maxsize=64)
def _windows(pairs: tuple, rtol: float) -> LawWindows:
    speed = any(p != 0.0 for p, _ in pairs)
    sag = any(q != 0.0 for _, q in pairs)
    # the speed window first, on most of the tolerance; then the widest tension window within
    # the rest, which with a speed dependence keeps half the tolerance for the creep window
    du = d0 = dx = BIG
    if speed:
        du = _largest(lambda s: remainder_bound(pairs, s, 0.0) <= SPEED_SHARE * rtol, DU_MAX)
    duf = du if du < BIG else 0.0
    if sag:
        share = 0.5 if speed else 1.0
        dx = _largest(lambda s: remainder_bound(pairs, duf, s) <= rtol
                      and _tension_remainder(pairs, s) <= share * rtol, 0.5)
    dxf = dx if dx < BIG else 0.0
    if speed:
        d0 = _largest(lambda s: creep_bound(pairs, s, dxf) <= rtol, 1.0)
    bound = remainder_bound(pairs, duf, dxf)
    creep = creep_bound(pairs, d0, dxf) if speed else bound
    return LawWindows(du=du, dx=dx, d0=d0, bound=bound, creep=creep, rtol=rtol)


def law_windows(coef: np.ndarray, pv: np.ndarray, ps: np.ndarray,
                rtol: float) -> LawWindows | None:
    """Windows of the expanded law for tolerance ``rtol``, or None when the law is evaluated
    exactly every step: ``rtol <= 0``, a constant law, one whose element-wide terms need no
    power, logarithm or square root (speed exponents 0 and 1, sag exponents 0, 1 and 2: the
    exact law costs no more than the expansion), or one beyond the kernel's element-wise
    evaluation (more than K_LIN terms, more than N_POW other exponents)."""
    if rtol <= 0.0 or len(pv) > K_LIN:
        return None
    if (len({float(p) for p in pv} - {0.0, 1.0}) > N_POW
            or len({float(q) for q in ps} - {0.0, 0.5, 1.0, 1.5, 2.0}) > N_POW):
        return None
    sparse = sparse_terms(coef)
    if all(sparse[k] or (pv[k] in (0.0, 1.0) and ps[k] in (0.0, 1.0, 2.0))
           for k in range(len(pv))):
        return None
    pairs = tuple(sorted({(float(p), float(q)) for p, q, c in zip(pv, ps, coef, strict=True)
                          if np.any(c != 0.0)}))
    return _windows(pairs, float(rtol))


def element_windows(coef, pv, ps, sw_ref, hsm_ref, v_eps, w: LawWindows):
    """Per-element window sizes: relative speed window, creep window [m/s] and relative tension
    window; BIG where no term of the element depends on speed (sag)."""
    nz = coef != 0.0
    dep_u = np.any(nz & (pv[:, None] != 0.0), axis=0)
    dep_x = np.any(nz & (ps[:, None] != 0.0), axis=0) & (sw_ref > 0.0) & (hsm_ref > 0.0)
    du = np.where(dep_u, min(w.du, BIG), BIG)
    d0 = np.where(dep_u, min(w.d0 * v_eps, BIG), BIG)
    dx = np.where(dep_x, min(w.dx, BIG), BIG)
    return du, d0, dx
