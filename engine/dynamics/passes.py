"""The vectorised passes of one step over the free belt (explicit) elements and springs.

Each pass is one loop over contiguous elements or springs, written so LLVM vectorises it
(unsigned indices, no branches in the body but selects, reductions through ``_fmin`` /
``_fmax``): the resistance law term by term, the velocity update of free elements, the spring
update, the envelopes and extremes. The implicit blocks round the pulleys are in
:mod:`beltstudy.engine.dynamics.blocks`.
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit, uint64, uintp

from beltstudy.engine.dynamics.fastmath import (
    OPTS,
    OPTS_RED,
    _cttz,
    _exp,
    _fmax,
    _fmin,
    _ln0,
    _mul_strict,
    _power,
    _speed,
)
from beltstudy.engine.dynamics.linlaw import BIG, K_LIN, N_POW, PREDICT

__all__ = ["resistance", "law_flagged", "law_refresh", "node_pass", "spring",
           "spring_segments", "observe", "observe_lin", "extremes", "slack_zones", "law_rows"]


@njit(inline="always", **OPTS)
def _term(r0, c, v, lnv, phi, lnphi, sc, p, qc, q):
    """``r0 += c |v|^p phi^q`` over all elements; ``sc``/``qc`` are literal codes at every
    call, so each call compiles to its own branch-free loop."""
    for jj in range(r0.shape[0]):
        j = uintp(jj)
        r0[j] += c[j] * _speed(v[j], lnv[j], sc, p) * (
            1.0 if qc == 0 else
            (_power(phi[j], qc, q) if qc != 5 else _exp(q * lnphi[j])))


@njit(inline="always", **OPTS)
def _term_sag(r0, c, v, lnv, phi, lnphi, sc, p, qc, q):
    """:func:`_term` with the sag code ``qc`` turned into a literal (``sc`` is one already)."""
    if qc == 0:
        _term(r0, c, v, lnv, phi, lnphi, sc, p, 0, q)
    elif qc == 1:
        _term(r0, c, v, lnv, phi, lnphi, sc, p, 1, q)
    elif qc == 2:
        _term(r0, c, v, lnv, phi, lnphi, sc, p, 2, q)
    elif qc == 3:
        _term(r0, c, v, lnv, phi, lnphi, sc, p, 3, q)
    elif qc == 4:
        _term(r0, c, v, lnv, phi, lnphi, sc, p, 4, q)
    else:
        _term(r0, c, v, lnv, phi, lnphi, sc, p, 5, q)


@njit(inline="always", **OPTS)
def resistance(law, nodes, st, wk):
    """Resistance magnitude ``R0_j = sum_k coef[k, j] |v_j|^pv[k] phi_j^ps[k]`` into
    ``wk.r0`` [N] (:class:`~beltstudy.engine.dynamics.records.Law`) at the state ``st``.

    One vectorised pass per term, compiled for its exponents: speed exponents 0 and 1 need
    no power, others ``exp(p ln|v|)``; sag exponents 0, 0.5, 1, 1.5 and 2 use sqrt and
    products, others ``exp(q ln phi)``. The logarithms are computed once per step; the
    constant term initialises r0. ``phi`` is the sag ratio over the reference from the
    element's mean tension, ``phi_j = min(sw_ref_j / T, hsm_ref_j)`` with the sag weight and
    the element's sag cap both over the reference sag (``nodes``); ``wk.phi``, ``wk.lnv`` and
    ``wk.lnphi`` are scratch arrays.
    """
    _resistance(law, nodes.sw_ref, nodes.hsm_ref, st.v, st.tt, wk.r0, wk.phi, wk.lnv, wk.lnphi)


@njit(**OPTS)
def _resistance(law, sw_ref, hsm_ref, v, tt, r0, phi, lnv, lnphi):
    """:func:`resistance` on the arrays it reads and writes (the kernel's call then passes
    these, not the whole node, state and scratch records)."""
    coef, pvc, pvv, psc, psv = law.coef, law.pvc, law.pvv, law.psc, law.psv
    t_sparse, t_ptr, t_idx = law.t_sparse, law.t_ptr, law.t_idx
    any_ps = law.any_ps
    n = r0.shape[0]
    if any_ps:
        phi[0] = min(sw_ref[0] / max(0.5 * (tt[n - 1] + tt[0]), 1.0), hsm_ref[0])
        for jj in range(1, n):
            j = uintp(jj)
            phi[j] = min(sw_ref[j] / max(0.5 * (tt[uintp(jj - 1)] + tt[j]), 1.0), hsm_ref[j])
    need_lnv = False
    need_lnphi = False
    first = -1
    for k in range(coef.shape[0]):
        if t_sparse[k] == 0:
            need_lnv = need_lnv or (pvc[k] != 0 and pvc[k] != 2)
            need_lnphi = need_lnphi or psc[k] == 5
            if first < 0 and pvc[k] == 0 and psc[k] == 0:
                first = k
    if need_lnv:
        for jj in range(n):
            j = uintp(jj)
            lnv[j] = _ln0(abs(v[j]))
    if need_lnphi:
        for jj in range(n):
            j = uintp(jj)
            lnphi[j] = _ln0(phi[j])
    if first >= 0:
        c = coef[first]
        for jj in range(n):
            j = uintp(jj)
            r0[j] = c[j]
    else:
        for jj in range(n):
            r0[uintp(jj)] = 0.0
    for k in range(coef.shape[0]):
        if k == first:
            continue
        pc = pvc[k]
        sc = 0 if pc == 0 else (2 if pc == 2 else 5)
        qc = psc[k]
        p = pvv[k]
        q = psv[k]
        if t_sparse[k] == 1:
            # a sparse term (a few elements: feed, pulleys, accessories): its elements only
            for i in range(t_ptr[k], t_ptr[k + 1]):
                j = t_idx[i]
                r0[j] += coef[k, j] * _power(abs(v[j]), pc, p) * (
                    _power(phi[j], qc, q) if any_ps else 1.0)
            continue
        c = coef[k]
        # literal speed codes here and literal sag codes in _term_sag: one specialised loop
        # per (speed, sag) pair
        if sc == 0:
            _term_sag(r0, c, v, lnv, phi, lnphi, 0, p, qc, q)
        elif sc == 2:
            _term_sag(r0, c, v, lnv, phi, lnphi, 2, p, qc, q)
        else:
            _term_sag(r0, c, v, lnv, phi, lnphi, 5, p, qc, q)


# --------------------------------------------------------------------------------------
# the law expanded between exact evaluations (beltstudy.engine.dynamics.linlaw)


@njit(**OPTS)
def law_flagged(flag64, idx, count):
    """The indices of the ``count`` flagged elements into idx, word by word (a word of eight
    flags that is not zero is taken apart by its trailing zero count); returns their
    number."""
    m = 0
    zero = uint64(0)
    one = uint64(1)
    for w in range(flag64.shape[0]):
        x = flag64[w]
        while x != zero:
            idx[m] = 8 * w + (_cttz(x) >> 3)
            m += 1
            x &= x - one
        if m >= count:
            break
    return m


#: Elements per chunk of the element-wise evaluation: its scratch rows are CHUNK long, at
#: offsets known when compiling, so LLVM vectorises its loops without alias checks between
#: rows.
CHUNK = 64
#: Rows of the factors of the terms (:func:`law_refresh`): 1, u, the N_POW powers of u, phi,
#: phi^2, sqrt(phi), phi^1.5, the N_POW powers of phi.
F_ONE, F_U, F_UP, F_PHI, F_PHI2, F_SQRT, F_PHI15, F_PHIP = 0, 1, 2, 2 + N_POW, 3 + N_POW, \
    4 + N_POW, 5 + N_POW, 6 + N_POW
N_F = 6 + 2 * N_POW
#: Gathered rows: the expansion point (u, T), the state (u, T), sag weight and cap over the
#: reference sag, xcap, window sizes, then the K_LIN coefficients.
G_U, G_T, G_UN, G_TN, G_SW, G_HSM, G_XC, G_DU, G_D0, G_DX, G_C = range(11)
N_G = 10 + K_LIN
#: Output rows: the polynomial's six coefficients, the four window bounds.
N_O = 10


@njit(**OPTS)
def _refresh_gather(idx, i0, m, v, tt, erow, ulo, uhi, tlo, thi, g):
    """The state, the expansion point, the per-element constants and the coefficients of the
    elements ``idx[i0:i0 + m]`` into the rows of g (``erow``: each element's constants and
    coefficients in one row of 16).

    The expansion point is the state moved by PREDICT of its window towards the side of the
    old window the state is on (the way it has been moving), where the speed is expanded and
    the sag ratio follows the tension; the state stays inside the new window (see
    :mod:`beltstudy.engine.dynamics.linlaw`). Without branches on the data (selects)."""
    n = tt.shape[0]
    big = BIG
    for ii in range(m):
        i = uintp(ii)
        jj = idx[i0 + ii]
        j = uintp(jj)
        jm = uintp(jj - 1 + (n if jj == 0 else 0))
        u = abs(v[j])
        tm = 0.5 * (tt[jm] + tt[j])
        xc = erow[j, 2]
        du = erow[j, 3]
        w0 = erow[j, 4]
        dx = erow[j, 5]
        su = 1.0 if u >= 0.5 * (ulo[j] + uhi[j]) else -1.0
        uc = u + PREDICT * du * u * su
        uc = uc if ((du < big) & (du * u >= w0) & (du * uc >= w0)) else u
        st = 1.0 if tm >= 0.5 * (tlo[j] + thi[j]) else -1.0
        tc = max(tm + PREDICT * dx * tm * st, xc)
        tc = tc if ((dx < big) & (tm >= xc)) else tm
        g[G_U * CHUNK + i] = uc
        g[G_T * CHUNK + i] = tc
        g[G_UN * CHUNK + i] = u
        g[G_TN * CHUNK + i] = tm
        g[G_SW * CHUNK + i] = erow[j, 0]
        g[G_HSM * CHUNK + i] = erow[j, 1]
        g[G_XC * CHUNK + i] = xc
        g[G_DU * CHUNK + i] = du
        g[G_D0 * CHUNK + i] = w0
        g[G_DX * CHUNK + i] = dx
        for k in range(K_LIN):
            g[(G_C + k) * CHUNK + i] = erow[j, 8 + k]


@njit(**OPTS)
def _refresh_factors(m, g, f, upow, qpow, nqp):
    """The factors of the terms over the gathered elements into the rows of f, in one
    vectorised loop: 1, u, ``u^upow[x] = exp(upow[x] ln u)`` (all N_POW, padded exponents
    0), phi, phi^2, sqrt(phi), phi^1.5; then ``phi^qpow[x]`` when a sag exponent takes exp
    and log (row offsets unsigned: no negative-index wraparound)."""
    p0 = upow[0]
    p1 = upow[1]
    p2 = upow[2]
    for ii in range(m):
        i = uintp(ii)
        u = g[G_U * CHUNK + i]
        tm = g[G_T * CHUNK + i]
        phi = min(g[G_SW * CHUNK + i] / max(tm, 1.0), g[G_HSM * CHUNK + i])
        ln = _ln0(u)
        r = math.sqrt(phi)
        f[F_ONE * CHUNK + i] = 1.0
        f[F_U * CHUNK + i] = u
        f[F_UP * CHUNK + i] = _exp(p0 * ln)
        f[(F_UP + 1) * CHUNK + i] = _exp(p1 * ln)
        f[(F_UP + 2) * CHUNK + i] = _exp(p2 * ln)
        f[F_PHI * CHUNK + i] = phi
        f[F_PHI2 * CHUNK + i] = phi * phi
        f[F_SQRT * CHUNK + i] = r
        f[F_PHI15 * CHUNK + i] = phi * r
    if nqp > 0:
        for ii in range(m):
            i = uintp(ii)
            f[F_PHIP * CHUNK + i] = _ln0(f[F_PHI * CHUNK + i])
        for x in range(nqp - 1, -1, -1):
            base = uintp((F_PHIP + x) * CHUNK)
            q = qpow[x]
            for ii in range(m):
                i = uintp(ii)
                f[base + i] = _exp(q * f[F_PHIP * CHUNK + i])


@njit(inline="always", **OPTS)
def _tk(g, f, i, k, bs, bq):
    """Term k of the gathered element i: its coefficient times its speed and sag factors
    (``bs``, ``bq``: the unsigned offsets of their rows)."""
    return g[(G_C + k) * CHUNK + i] * f[bs + i] * f[bq + i]


@njit(**OPTS)
def _refresh_eval(m, rs, rq, wk, g, f, o):
    """The exact law and its expansion over the gathered elements (one vectorised loop): the
    terms ``c u^p phi^q`` from the factor rows (``rs``, ``rq``: each term's rows), the sums
    ``R``, ``sum p t``, ``sum p (p - 1) t``, ``sum q t``, ``sum q (q + 1) t``, ``sum p q t``
    (weights ``wk``, one row of K_LIN each), the polynomial's coefficients and the window's
    bounds into the rows of o."""
    c = CHUNK
    s0, s1, s2, s3 = uintp(rs[0] * c), uintp(rs[1] * c), uintp(rs[2] * c), uintp(rs[3] * c)
    s4, s5, s6, s7 = uintp(rs[4] * c), uintp(rs[5] * c), uintp(rs[6] * c), uintp(rs[7] * c)
    q0, q1, q2, q3 = uintp(rq[0] * c), uintp(rq[1] * c), uintp(rq[2] * c), uintp(rq[3] * c)
    q4, q5, q6, q7 = uintp(rq[4] * c), uintp(rq[5] * c), uintp(rq[6] * c), uintp(rq[7] * c)
    w1 = (wk[1, 0], wk[1, 1], wk[1, 2], wk[1, 3], wk[1, 4], wk[1, 5], wk[1, 6], wk[1, 7])
    w2 = (wk[2, 0], wk[2, 1], wk[2, 2], wk[2, 3], wk[2, 4], wk[2, 5], wk[2, 6], wk[2, 7])
    w3 = (wk[3, 0], wk[3, 1], wk[3, 2], wk[3, 3], wk[3, 4], wk[3, 5], wk[3, 6], wk[3, 7])
    w4 = (wk[4, 0], wk[4, 1], wk[4, 2], wk[4, 3], wk[4, 4], wk[4, 5], wk[4, 6], wk[4, 7])
    w5 = (wk[5, 0], wk[5, 1], wk[5, 2], wk[5, 3], wk[5, 4], wk[5, 5], wk[5, 6], wk[5, 7])
    big = BIG
    for ii in range(m):
        i = uintp(ii)
        t0 = _tk(g, f, i, 0, s0, q0)
        t1 = _tk(g, f, i, 1, s1, q1)
        t2 = _tk(g, f, i, 2, s2, q2)
        t3 = _tk(g, f, i, 3, s3, q3)
        t4 = _tk(g, f, i, 4, s4, q4)
        t5 = _tk(g, f, i, 5, s5, q5)
        t6 = _tk(g, f, i, 6, s6, q6)
        t7 = _tk(g, f, i, 7, s7, q7)
        r = ((t0 + t1) + (t2 + t3)) + ((t4 + t5) + (t6 + t7))
        a = _wsum(w1, t0, t1, t2, t3, t4, t5, t6, t7)
        aa = _wsum(w2, t0, t1, t2, t3, t4, t5, t6, t7)
        b = _wsum(w3, t0, t1, t2, t3, t4, t5, t6, t7)
        bb = _wsum(w4, t0, t1, t2, t3, t4, t5, t6, t7)
        e = _wsum(w5, t0, t1, t2, t3, t4, t5, t6, t7)
        u = g[G_U * CHUNK + i]
        tm = g[G_T * CHUNK + i]
        xc = g[G_XC * CHUNK + i]
        du = g[G_DU * CHUNK + i]
        w0 = g[G_D0 * CHUNK + i]
        dx = g[G_DX * CHUNK + i]
        moving = du * u >= w0
        uncapped = tm >= xc
        iu = 1.0 / u if moving else 0.0
        it = 1.0 / tm if uncapped else 0.0
        g_u = a * iu
        h_uu = 0.5 * aa * iu * iu
        g_t = -b * it
        h_tt = 0.5 * bb * it * it
        h_ut = -e * iu * it
        k0 = r - g_u * u + h_uu * u * u - g_t * tm + h_tt * tm * tm + h_ut * u * tm
        k1 = g_u - 2.0 * h_uu * u - h_ut * tm
        k3 = g_t - 2.0 * h_tt * tm - h_ut * u
        o[i] = k0
        o[CHUNK + i] = k1
        o[2 * CHUNK + i] = h_uu
        o[3 * CHUNK + i] = k3
        o[4 * CHUNK + i] = h_tt
        o[5 * CHUNK + i] = h_ut
        wu = du * u if moving else w0
        o[6 * CHUNK + i] = -big if du >= big else u - wu
        o[7 * CHUNK + i] = big if du >= big else u + wu
        o[8 * CHUNK + i] = -big if (dx >= big or not uncapped) else max(tm - dx * tm, xc)
        o[9 * CHUNK + i] = big if dx >= big else (tm + dx * tm if uncapped else xc)


@njit(inline="always", **OPTS)
def _wsum(w, t0, t1, t2, t3, t4, t5, t6, t7):
    """``sum_k w[k] t_k``."""
    return ((w[0] * t0 + w[1] * t1) + (w[2] * t2 + w[3] * t3)) \
        + ((w[4] * t4 + w[5] * t5) + (w[6] * t6 + w[7] * t7))


@njit(**OPTS)
def _refresh_scatter(idx, i0, m, g, o, lin, r0):
    """The expansion and the windows of the evaluated chunk into the elements' (float32)
    arrays, and r0 from the stored expansion at their state."""
    for ii in range(m):
        i = uintp(ii)
        j = uintp(idx[i0 + ii])
        lin.k[j] = o[i]
        lin.gu[j] = o[CHUNK + i]
        lin.guu[j] = o[2 * CHUNK + i]
        lin.gx[j] = o[3 * CHUNK + i]
        lin.gxx[j] = o[4 * CHUNK + i]
        lin.gux[j] = o[5 * CHUNK + i]
        lin.ulo[j] = o[6 * CHUNK + i]
        lin.uhi[j] = o[7 * CHUNK + i]
        lin.tlo[j] = o[8 * CHUNK + i]
        lin.thi[j] = o[9 * CHUNK + i]
        r0[j] = _lin(g[G_UN * CHUNK + i], g[G_TN * CHUNK + i], lin.k[j], lin.gu[j], lin.guu[j],
                     lin.gx[j], lin.gxx[j], lin.gux[j])


@njit(**OPTS)
def law_refresh(idx, m, v, tt, lin, r0):
    """Evaluate the exact law for the elements ``idx[:m]`` at their new expansion points and
    expand it there (:mod:`beltstudy.engine.dynamics.linlaw`); r0 [N] from the expansion at their state.

    For each element j, with ``u = |v_j|`` [m/s] and ``T`` its mean tension [N]: the expansion
    point is the state moved by PREDICT of its window the way it was moving
    (:func:`_refresh_gather`); there the terms ``t_k = coef[k, j] u^pv[k] phi^ps[k]`` (the law
    of :func:`resistance`; ``lin.erow`` the coefficients by element, padded to K_LIN terms
    with zero ones, each term a product of a speed and a sag factor, ``lin.rs`` / ``lin.rq`` their
    rows, ``lin.upow`` / ``lin.qpow`` the exponents taken by exp and log); the second-order
    expansion (:func:`beltstudy.engine.dynamics.linlaw.expansion`) as the polynomial ``R0 = k + gu u +
    guu u^2 + gx T + gxx T^2 + gux u T`` and the window round the point as bounds on u and T
    (+-BIG where the law does not depend on it), stored in float32. The speed is expanded
    where its relative window ``du u`` is wider than the creep window ``d0``, and held within
    ``d0`` below. A sag ratio at its cap stays there while ``T <= xcap``; an uncapped one
    while ``T >= xcap``, so the expansion is in T on either side.

    In chunks of CHUNK elements (padded to whole vectors with the last one again): gathered
    into contiguous rows, evaluated in vectorised loops, scattered back.
    """
    while m % 4 != 0:
        idx[m] = idx[m - 1]
        m += 1
    nqp = lin.npow[1]
    for i0 in range(0, m, CHUNK):
        mc = min(CHUNK, m - i0)
        _refresh_gather(idx, i0, mc, v, tt, lin.erow, lin.ulo, lin.uhi, lin.tlo, lin.thi,
                        lin.sg)
        _refresh_factors(mc, lin.sg, lin.sf, lin.upow, lin.qpow, nqp)
        _refresh_eval(mc, lin.rs, lin.rq, lin.wk, lin.sg, lin.sf, lin.so)
        _refresh_scatter(idx, i0, mc, lin.sg, lin.so, lin, r0)


@njit(inline="always", **OPTS)
def _lin(u, tm, k, gu, guu, gx, gxx, gux):
    """The expanded law ``k + gu u + guu u^2 + gx T + gxx T^2 + gux u T`` [N]."""
    return k + u * (gu + guu * u + gux * tm) + tm * (gx + gxx * tm)


# --------------------------------------------------------------------------------------
# vectorised passes


@njit(inline="always", **OPTS)
def _node(vj, h, r, dtj, gj, v_eps):
    """New velocity of one free element: ``vs`` from the forces with a negative resistance
    explicit, then :func:`_friction` with its division computed from old values only (off the
    path from the old state to the new velocity)."""
    rp = max(r, 0.0)
    rn = min(r, 0.0)
    vs = vj + h * (dtj - gj - rn * min(max(vj / v_eps, -1.0), 1.0))
    e = h * rp
    den = v_eps + e
    a1 = _mul_strict(vs, v_eps / den)
    a2 = vs - math.copysign(e, vs)
    return a1 if abs(vs) <= den else a2


@njit(**OPTS)
def node_pass(a, b, v, tt, hm, grav, r0, v_eps, w):
    """Explicit velocity update of free elements a..b-1 (b <= n - 1, a >= 1); returns
    ``sum w_j v_j`` over them (:func:`weighted_sum`, in a fixed order). ``hm = dt / M``."""
    for jj in range(a, b):
        # unsigned indices: numba then drops the negative-index wraparound and LLVM vectorises
        j = uintp(jj)
        jm = uintp(jj - 1)
        v[j] = _node(v[j], hm[j], r0[j], tt[j] - tt[jm], grav[j], v_eps)
    return weighted_sum(w, v, a, b)


@njit(**OPTS)
def weighted_sum(w, v, a, b):
    """``sum w_j v_j`` over j = a..b-1 in a fixed order: four running sums over j mod 4, joined
    as ``(s0 + s1) + (s2 + s3)`` (the same bits whatever the memory layout: the kernel is
    compiled without reassociation, :data:`~beltstudy.engine.dynamics.fastmath.FASTMATH`).
    Unsigned indices: no negative-index wraparound in the four chains of additions."""
    s0 = 0.0
    s1 = 0.0
    s2 = 0.0
    s3 = 0.0
    nq = (b - a) // 4 if b > a else 0
    one, two, three = uintp(1), uintp(2), uintp(3)
    for q in range(nq):
        j = uintp(a + 4 * q)
        s0 += w[j] * v[j]
        s1 += w[j + one] * v[j + one]
        s2 += w[j + two] * v[j + two]
        s3 += w[j + three] * v[j + three]
    for jj in range(a + 4 * nq, b):
        j = uintp(jj)
        s0 += w[j] * v[j]
    return (s0 + s1) + (s2 + s3)


#: Curvature bound of one Newton step on Ernst's chord law: a spring whose first step's
#: estimated error exceeds this fraction of its strain increment (``1.5 u r^3 |ds| / T``,
#: the law's second derivative, ``u = a EB / T^3``, ``r = 1 / (1 + u)``) takes
#: :data:`NEWTON_MORE` more steps. A step left a step late to the next step's correction acts
#: as a delayed stiffness that feeds energy into springs near the floor tension, where the law
#: bends hardest (a slack belt being taken up diverged with one step for every spring, and
#: with two on a take-up a little heavier); running springs need one.
NEWTON_CURVE = 1e-3
NEWTON_MORE = 2


@njit(inline="always", **OPTS)
def _newton(e0, s1, tfl, aeb):
    """One Newton step of Ernst's chord law ``s(T) = T - aeb / (2 T^2)`` towards the strain
    tension ``s1`` from the tension ``e0`` (held at the floor ``tfl`` below it). Returns the
    step's tension, the tangent modulus over EB at its start (``r = t^3 / (t^3 + aeb)``) and
    whether its estimated error exceeds :data:`NEWTON_CURVE` of the increment."""
    tc = max(e0, tfl)
    t3 = tc * tc * tc
    sm = t3 + aeb
    q = 1.0 / (t3 * sm)  # the one division: r = t3 / sm, aeb / T^2 = aeb T sm q, 1 / T = T^2 sm q
    r = t3 * t3 * q
    ds = s1 - (tc - 0.5 * aeb * tc * sm * q)
    # estimated error over |ds|: 1.5 u r^3 |ds| / T with u = aeb sm q, 1 / T = tc^2 sm q
    curve = 1.5 * (aeb * sm * q) * (r * r * r) * abs(ds) * (tc * tc * sm * q)
    return tc + r * ds, r, curve > NEWTON_CURVE


@njit(inline="always", **OPTS)
def spring_first(e0, s0, d0, de, tfl, sfl, kfl_eb, aeb, eb, e_damp, g_damp, kvs):
    """One spring after the strain increment ``de`` [-], the chord law by one Newton step.
    Returns (elastic, strain, arm, total tension, whether it needs :func:`spring_refine`).

    Strain tension ``s = EB eps`` (eps the chord strain, :func:`beltstudy.engine.dynamics.model.
    chord_strain`) is the state the motion integrates exactly: ``s1 = s0 + EB de``. The
    elastic tension is its inverse under the static modulus softened by sag (Ernst's chord
    law ``s = T - a EB / (2 T^2)``, held linear at the floor modulus ``kfl = kfl_eb EB`` below
    the floor tension ``tfl``, ``s = sfl`` there, and on into slack below zero tension):
    Newton from the old tension, ``e1 = tc + (kt / EB) (s1 - s(tc))``, the larger of it and
    the floor line (each undershoots the law where the other holds). Its error does not
    accumulate (the next step starts from the exact strain), so the elastic energy is a
    function of the strain and a cycle through low tension or slack gives back what it took;
    ``e0 + kt de`` piles its path error up where the tangent modulus changes fast.

    The spring is slack (no arm, no viscous tension) when its strain is below the floor line's
    zero, ``s1 < sfl - tfl / kfl_eb``: the same whatever the Newton steps.
    Arm: the standard linear solid's relaxing arm (dynamic less static modulus, relaxation by
    its exact exponential: ``e_damp``, ``g_damp``). Mesh viscosity ``kvs de`` (``kvs = alpha Z
    len / dt``): a Kelvin-Voigt term acting on the modes the mesh cannot resolve (``kvs`` is
    the free springs' limited one in :func:`spring_segments`, :func:`visc_limiter`)."""
    s1 = s0 + eb * de
    fl = tfl + (s1 - sfl) * kfl_eb
    e1, r, more = _newton(e0, s1, tfl, aeb)
    e1 = max(e1, fl)
    taut = fl >= 0.0
    d1 = e_damp * d0 + g_damp * (eb * r) * de if taut else 0.0
    kv = kvs * de if taut else 0.0
    return e1, s1, d1, max(e1 + d1 + kv, 0.0), more


@njit(inline="always", **OPTS)
def spring_refine(e1, s1, d1, de, tfl, sfl, kfl_eb, aeb, kvs):
    """:data:`NEWTON_MORE` further Newton steps of the chord law at the strain tension s1, for
    a spring whose first step (:func:`spring_first`) left arm tension d1 after the increment
    de. Returns (elastic, total tension)."""
    fl = tfl + (s1 - sfl) * kfl_eb
    for _ in range(NEWTON_MORE):
        e1 = max(_newton(e1, s1, tfl, aeb)[0], fl)
    kv = kvs * de if fl >= 0.0 else 0.0
    return e1, max(e1 + d1 + kv, 0.0)


@njit(inline="always", **OPTS)
def spring(sp, j, e0, s0, d0, dv, cdt):
    """Spring j (:class:`~beltstudy.engine.dynamics.records.Springs`) from its elastic, strain
    and arm tension ``e0``, ``s0``, ``d0`` after the strain increment ``de = dv * dl + cdt``
    (dl = dt / len, cdt = carriage term): :func:`spring_first`, refined where it needs it.
    Returns (elastic, strain, arm, total)."""
    de = dv * sp.dl[j] + cdt
    e1, s1, d1, t1, more = spring_first(e0, s0, d0, de, sp.t_floor[j], sp.s_floor[j],
                                        sp.kfl_eb[j], sp.a_eb[j], sp.eb, sp.e_damp, sp.g_damp,
                                        sp.kvs[j])
    if more:
        e1, t1 = spring_refine(e1, s1, d1, de, sp.t_floor[j], sp.s_floor[j], sp.kfl_eb[j],
                               sp.a_eb[j], sp.kvs[j])
    return e1, s1, d1, t1


@njit(inline="always", **OPTS)
def spring_rest(e0, s0, tfl, aeb):
    """The elastic tension a spring holds at its strain before the step's increment (the
    constant part of :func:`spring`'s Newton step) and its tangent modulus over EB; (e0 up to
    rounding when the state is consistent)."""
    e, r, _ = _newton(e0, s0, tfl, aeb)
    return e, r


#: Added to the square of a spring's strain increment in :func:`visc_limiter`'s ratios, so a
#: spring at rest (``de = 0``) divides by no zero (its viscous force is zero anyway).
LIMIT_TINY = 1e-300


@njit(inline="always", **OPTS)
def visc_limiter(dem, de, dep):
    """The share ``1 - psi`` of the mesh viscosity a free spring keeps, from its strain
    increment ``de`` and its neighbours' ``dem``, ``dep`` [-].

    The limited artificial viscosity of Lagrangian shock codes (Christensen 1990, "Godunov
    methods on a staggered mesh: an improved artificial viscosity", UCRL-JC-105269; Caramana,
    Shashkov & Whalen 1998, J. Comput. Phys. 144, 70-97, sec. 4): with the ratios of the
    neighbours' strain rates to the spring's own, ``r_l = dem / de`` and ``r_r = dep / de``
    (the strain rates of a step are the increments over dt), the monotonised central limiter
    ``psi = max(0, min((r_l + r_r) / 2, 2 r_l, 2 r_r, 1))`` is 1 where the strain rate varies
    smoothly (the viscosity off: a resolved wave, or a front already spread over a few
    elements, is not diffused further) and 0 at a jump or at an extremum of the strain rate
    (the chain's dispersive ringing behind a front: the full viscosity). The ratios without
    a division by zero: ``de / (de^2 + tiny)``; at ``de = 0`` the viscous force is zero
    anyway."""
    inv = de / (de * de + LIMIT_TINY)
    rl = dem * inv
    rr = dep * inv
    psi = max(min(min(0.5 * (rl + rr), 2.0 * rl), min(2.0 * rr, 1.0)), 0.0)
    return 1.0 - psi


@njit(inline="always", **OPTS)
def _rate_and_viscosity(j, jm, jp, jq, st, sp, limited):
    """Free spring j's strain increment over the step from the new velocities and its mesh
    viscosity per strain increment, limited when ``limited`` (:func:`visc_limiter` on the
    neighbours' increments; indices as :func:`_spring_free`)."""
    v = st.v
    dl = sp.dl
    de = (v[jp] - v[j]) * dl[j]
    kvs = sp.kvs[j]
    if limited:
        kvs *= visc_limiter((v[j] - v[jm]) * dl[jm], de, (v[jq] - v[jp]) * dl[jp])
    return de, kvs


@njit(inline="always", **OPTS)
def _spring_free(j, jm, jp, jq, st, sp, more, limited):
    """Free spring j (between elements j and jp; jm before j, jq after jp) from the new
    velocities into the state; returns whether it needs :func:`spring_refine` (``more[j]``
    marks it)."""
    de, kvs = _rate_and_viscosity(j, jm, jp, jq, st, sp, limited)
    e1, s1, d1, t1, m = spring_first(st.te[j], st.ts[j], st.td[j], de, sp.t_floor[j],
                                     sp.s_floor[j], sp.kfl_eb[j], sp.a_eb[j], sp.eb,
                                     sp.e_damp, sp.g_damp, kvs)
    st.te[j] = e1
    st.ts[j] = s1
    st.td[j] = d1
    st.tt[j] = t1
    more[j] = 1.0 if m else 0.0
    return m


@njit(inline="always", **OPTS)
def _spring_more(j, jm, jp, jq, st, sp, limited):
    """:func:`spring_refine` of free spring j (indices as :func:`_spring_free`)."""
    de, kvs = _rate_and_viscosity(j, jm, jp, jq, st, sp, limited)
    st.te[j], st.tt[j] = spring_refine(st.te[j], st.ts[j], st.td[j], de, sp.t_floor[j],
                                       sp.s_floor[j], sp.kfl_eb[j], sp.a_eb[j], kvs)


@njit(inline="always", **OPTS)
def _spring_range(a, b, st, sp, more):
    """Update springs a..b-1 (b <= n - 2) of the state ``st`` from the new velocities: the
    first Newton step of every spring in one vectorised loop (``more`` [0/1] marks the springs
    whose step bends too much), then the marked ones refined (:func:`spring_refine`) in a
    second loop, only when there are any. The mesh viscosity of a free spring is limited by
    :func:`visc_limiter` when ``sp.limited`` (its neighbours' strain increments from the new
    velocities: every element is updated before the free springs); spring 0's left neighbour
    is spring n - 1 (taken before the loop, which then has no wraparound)."""
    n = st.v.shape[0]
    limited = sp.limited != 0
    cnt = 0
    a1 = a
    if a == 0:
        cnt += 1 if _spring_free(0, n - 1, 1, 2, st, sp, more, limited) else 0
        a1 = 1
    for jj in range(a1, b):
        j = uintp(jj)
        cnt += 1 if _spring_free(j, uintp(jj - 1), uintp(jj + 1), uintp(jj + 2), st, sp, more,
                                 limited) else 0
    if cnt > 0:
        for jj in range(a, b):
            j = uintp(jj)
            if more[j] != 0.0:
                _spring_more(j, uintp(jj - 1 + (n if jj == 0 else 0)), uintp(jj + 1),
                             uintp(jj + 2), st, sp, limited)


@njit(inline="always", **OPTS)
def spring_segments(st, sp, more):
    """:func:`_spring_range` over every free spring segment (``sp.seg_spring``), in order, inlined
    into the caller (the records are not passed as arguments, which costs about as much as a
    few springs)."""
    for k in range(sp.seg_spring.shape[0]):
        _spring_range(sp.seg_spring[k, 0], sp.seg_spring[k, 1], st, sp, more)


@njit(**OPTS_RED)
def observe(tt, v, t_max, t_min):
    """Envelopes of every spring and the extremes of tension and speed, in one pass.

    Returns (min tension, max tension, min speed, max speed). A separate function: the
    reductions may drop NaN semantics here (divergence is checked on the speed sum).
    """
    lo = tt[0]
    hi = tt[0]
    vlo = v[0]
    vhi = v[0]
    for jj in range(tt.shape[0]):
        j = uintp(jj)
        t1 = tt[j]
        vj = v[j]
        t_max[j] = _fmax(t_max[j], t1)
        t_min[j] = _fmin(t_min[j], t1)
        lo = _fmin(lo, t1)
        hi = _fmax(hi, t1)
        vlo = _fmin(vlo, vj)
        vhi = _fmax(vhi, vj)
    return lo, hi, vlo, vhi


@njit(inline="always", **OPTS_RED)
def _next_law(lin, j, vj, ta, tb):
    """Element j's expanded law (:class:`~beltstudy.engine.dynamics.records.Lin`) at its speed
    ``vj`` and the mean of its springs' tensions ``ta``, ``tb``, and whether that state is
    outside its window."""
    u = abs(vj)
    tm = 0.5 * (ta + tb)
    return (_lin(u, tm, lin.k[j], lin.gu[j], lin.guu[j], lin.gx[j], lin.gxx[j], lin.gux[j]),
            (u < lin.ulo[j]) | (u > lin.uhi[j]) | (tm < lin.tlo[j]) | (tm > lin.thi[j]))


@njit(**OPTS_RED)
def observe_lin(st, t_max, t_min, lin, r0):
    """:func:`observe` of the state ``st``, and the law for the next step: the expanded law
    at the state the step ends in, into r0 [N], and the flags (1, ``lin.flag``) of the
    elements whose speed or mean tension is outside the window of the expansion
    (:func:`law_refresh`): their law is evaluated exactly before the next step. Returns (min
    tension, max tension, min speed, max speed, number flagged)."""
    tt, v, flag = st.tt, st.v, lin.flag
    n = tt.shape[0]
    lo = tt[0]
    hi = tt[0]
    vlo = v[0]
    vhi = v[0]
    r, f = _next_law(lin, 0, v[0], tt[n - 1], tt[0])
    r0[0] = r
    flag[0] = f
    cnt = 1 if f else 0
    t_max[0] = _fmax(t_max[0], tt[0])
    t_min[0] = _fmin(t_min[0], tt[0])
    for jj in range(1, n):
        j = uintp(jj)
        jm = uintp(jj - 1)
        t1 = tt[j]
        vj = v[j]
        t_max[j] = _fmax(t_max[j], t1)
        t_min[j] = _fmin(t_min[j], t1)
        lo = _fmin(lo, t1)
        hi = _fmax(hi, t1)
        vlo = _fmin(vlo, vj)
        vhi = _fmax(vhi, vj)
        r, f = _next_law(lin, j, vj, tt[jm], t1)
        r0[j] = r
        flag[j] = f
        cnt += 1 if f else 0
    return lo, hi, vlo, vhi, cnt


@njit(**OPTS_RED)
def extremes(x):
    """(min, max) of an array."""
    lo = x[0]
    hi = x[0]
    for jj in range(1, x.shape[0]):
        j = uintp(jj)
        lo = _fmin(lo, x[j])
        hi = _fmax(hi, x[j])
    return lo, hi


@njit(**OPTS)
def slack_zones(ts, tt, eb, len_m, eps_run):
    """Belt length gathered by the slack spans [m] and the spring that gathered most.

    A span is slack when its tension is zero; the belt length it has gathered is its chord
    shortening since running, ``(eps_run - eps) len`` (``eps = ts / EB``, the strain tension
    ``ts`` of :func:`spring`): the sag it has taken up and the slack
    beyond. Summed over the slack spans this is the belt they have drawn in, the same on any
    mesh: a coarse mesh puts it in one spring, a fine one spreads it over several, and may
    leave a spring in the middle of a slack stretch momentarily taut, so the sum is over every
    slack span, not one run of consecutive ones. Returns (total [m], deepest spring or -1)."""
    total = 0.0
    deep = -1
    worst = 0.0
    inv_eb = 1.0 / eb
    for j in range(ts.shape[0]):
        if tt[j] <= 0.0:
            g = (eps_run[j] - ts[j] * inv_eb) * len_m[j]
            if g > 0.0:
                total += g
                if g > worst:
                    worst = g
                    deep = j
    return total, deep


def law_rows(pv, ps):
    """Each term's speed and sag factor rows for :func:`law_refresh`, the exponents taken by
    exp and log, and the weights of the sums over the terms (padded to K_LIN terms); plain
    Python, for :func:`beltstudy.engine.dynamics.model.build_system`. Returns ``(rs, rq, upow, qpow,
    npow, wk)``."""
    ups = sorted({float(p) for p in pv} - {0.0, 1.0})
    qps = sorted({float(q) for q in ps} - {0.0, 0.5, 1.0, 1.5, 2.0})
    srow = {0.0: F_ONE, 1.0: F_U} | {p: F_UP + x for x, p in enumerate(ups)}
    qrow = {0.0: F_ONE, 1.0: F_PHI, 2.0: F_PHI2, 0.5: F_SQRT, 1.5: F_PHI15} | {
        q: F_PHIP + x for x, q in enumerate(qps)}
    nk = len(pv)
    rs = np.full(K_LIN, F_ONE, dtype=np.int64)
    rq = np.full(K_LIN, F_ONE, dtype=np.int64)
    wk = np.zeros((6, K_LIN))
    for k in range(nk):
        p, q = float(pv[k]), float(ps[k])
        rs[k] = srow[p]
        rq[k] = qrow[q]
        wk[:, k] = (1.0, p, p * (p - 1.0), q, q * (q + 1.0), p * q)
    upow = np.zeros(N_POW)
    qpow = np.zeros(N_POW)
    upow[:len(ups)] = ups
    qpow[:len(qps)] = qps
    npow = np.array([len(ups), len(qps), 1 if any(float(q) in (0.5, 1.5) for q in ps) else 0],
                    dtype=np.int64)
    return rs, rq, upow, qpow, npow, wk
