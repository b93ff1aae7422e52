"""The vectorised passes of one step over the free belt (explicit) elements and springs.

Each pass is one loop over contiguous elements or springs, written so LLVM vectorises it
(unsigned indices, no branches in the body but selects, reductions through ``_fmin`` /
``_fmax``): the resistance law term by term, the velocity update of free elements, the spring
update, the envelopes and extremes. The implicit blocks round the pulleys are in
:mod:`engine.dynamics.blocks`.
"""

from __future__ import annotations

import math

from numba import njit, uintp

from engine.dynamics.fastmath import (
    OPTS,
    OPTS_RED,
    _exp,
    _fmax,
    _fmin,
    _ln0,
    _mul_strict,
    _power,
    _speed,
)

__all__ = ["resistance", "node_pass", "spring", "spring_pass", "observe", "extremes",
           "slack_zones"]


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


@njit(**OPTS)
def resistance(r0, v, tt, coef, pvc, pvv, psc, psv, sw_ref, hsm_ref, any_ps, phi,
               lnv, lnphi, t_sparse, t_ptr, t_idx):
    """Resistance magnitude ``R0_j = sum_k coef[k, j] |v_j|^pv[k] phi_j^ps[k]`` into r0 [N].

    One vectorised pass per term, compiled for its exponents: speed exponents 0 and 1 need
    no power, others ``exp(p ln|v|)``; sag exponents 0, 0.5, 1, 1.5 and 2 use sqrt and
    products, others ``exp(q ln phi)``. The logarithms are computed once per step; the
    constant term initialises r0. ``phi`` is the sag ratio over the reference from the
    element's mean tension, ``phi_j = min(sw_ref_j / T, hsm_ref_j)`` with the sag weight and
    the element's sag cap both over the reference sag; ``phi``, ``lnv`` and ``lnphi`` are
    scratch arrays.
    """
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


@njit(inline="always", **OPTS)
def _friction(vs, e, v_eps):
    """Solve ``v = vs - e clip(v / v_eps, -1, 1)`` for v exactly (e >= 0: e = dt R0 / M)."""
    a1 = vs * v_eps / (v_eps + e)
    a2 = vs - math.copysign(e, vs)
    return a1 if abs(vs) <= v_eps + e else a2


# --------------------------------------------------------------------------------------
# vectorised passes


@njit(**OPTS)
def node_pass(a, b, v, tt, hm, grav, r0, v_eps, w):
    """Explicit velocity update of free elements a..b-1 (b <= n - 1, a >= 1); returns
    ``sum w_j v_j`` over them. ``hm = dt / M``."""
    s = 0.0
    for jj in range(a, b):
        # unsigned indices: numba then drops the negative-index wraparound and LLVM vectorises
        j = uintp(jj)
        jm = uintp(jj - 1)
        h = hm[j]
        r = r0[j]
        rp = max(r, 0.0)
        rn = min(r, 0.0)
        vj = v[j]
        vs = vj + h * (tt[j] - tt[jm] - grav[j] - rn * min(max(vj / v_eps, -1.0), 1.0))
        # _friction, with its division computed from old values only (off the path from
        # the old state to the new velocity)
        e = h * rp
        den = v_eps + e
        a1 = _mul_strict(vs, v_eps / den)
        a2 = vs - math.copysign(e, vs)
        vn = a1 if abs(vs) <= den else a2
        v[j] = vn
        s += w[j] * vn
    return s


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

    Strain tension ``s = EB eps`` (eps the chord strain, :func:`engine.dynamics.model.
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
    len / dt``): a Kelvin-Voigt term acting on the modes the mesh cannot resolve."""
    s1 = s0 + eb * de
    fl = tfl + (s1 - sfl) * kfl_eb
    e1, r, more = _newton(e0, s1, tfl, aeb)
    e1 = max(e1, fl)
    taut = fl >= 0.0
    d1 = e_damp * d0 + g_damp * (eb * r) * de if taut else 0.0
    kv = kvs * de if taut else 0.0
    return e1, s1, d1, max(e1 + d1 + kv, 0.0), more


@njit(inline="always", **OPTS)
def fl_taut(s1, tfl, sfl, kfl_eb):
    """Whether a spring at strain tension s1 is taut (above the floor line's zero)."""
    return tfl + (s1 - sfl) * kfl_eb >= 0.0


@njit(inline="always", **OPTS)
def spring_refine(e1, s1, tfl, sfl, kfl_eb, aeb):
    """:data:`NEWTON_MORE` further Newton steps of the chord law at the strain tension s1."""
    fl = tfl + (s1 - sfl) * kfl_eb
    for _ in range(NEWTON_MORE):
        e1 = max(_newton(e1, s1, tfl, aeb)[0], fl)
    return e1


@njit(inline="always", **OPTS)
def spring(e0, s0, d0, dv, dlj, cdt, tfl, sfl, kfl_eb, aeb, eb, e_damp, g_damp, kvs):
    """One spring after the strain increment ``de = dv * dl + cdt`` (dl = dt / len, cdt =
    carriage term): :func:`spring_first`, refined where it needs it. Returns (elastic,
    strain, arm, total)."""
    de = dv * dlj + cdt
    e1, s1, d1, t1, more = spring_first(e0, s0, d0, de, tfl, sfl, kfl_eb, aeb, eb, e_damp,
                                        g_damp, kvs)
    if more:
        e1 = spring_refine(e1, s1, tfl, sfl, kfl_eb, aeb)
        kv = kvs * de if fl_taut(s1, tfl, sfl, kfl_eb) else 0.0
        t1 = max(e1 + d1 + kv, 0.0)
    return e1, s1, d1, t1


@njit(inline="always", **OPTS)
def spring_rest(e0, s0, tfl, aeb):
    """The elastic tension a spring holds at its strain before the step's increment (the
    constant part of :func:`spring`'s Newton step) and its tangent modulus over EB; (e0 up to
    rounding when the state is consistent)."""
    e, r, _ = _newton(e0, s0, tfl, aeb)
    return e, r


@njit(**OPTS)
def spring_pass(a, b, v, te, ts, td, tt, dl, t_floor, s_floor, kfl_eb, a_eb, eb, e_damp,
                g_damp, kvs, more):
    """Update springs a..b-1 (b <= n - 1) from the new velocities: the first Newton step of
    every spring in one vectorised loop (``more`` [0/1] marks the springs whose step bends too
    much), then the marked ones refined (:func:`spring_refine`) in a second loop, only when
    there are any."""
    cnt = 0
    for jj in range(a, b):
        j = uintp(jj)
        de = (v[uintp(jj + 1)] - v[j]) * dl[j]
        e1, s1, d1, t1, m = spring_first(te[j], ts[j], td[j], de, t_floor[j], s_floor[j],
                                         kfl_eb[j], a_eb[j], eb, e_damp, g_damp, kvs[j])
        te[j] = e1
        ts[j] = s1
        td[j] = d1
        tt[j] = t1
        more[j] = 1.0 if m else 0.0
        cnt += 1 if m else 0
    if cnt > 0:
        for jj in range(a, b):
            j = uintp(jj)
            if more[j] != 0.0:
                e1 = te[j]
                s1 = ts[j]
                e2 = spring_refine(e1, s1, t_floor[j], s_floor[j], kfl_eb[j], a_eb[j])
                de = (v[uintp(jj + 1)] - v[j]) * dl[j]
                taut = fl_taut(s1, t_floor[j], s_floor[j], kfl_eb[j])
                te[j] = e2
                tt[j] = max(e2 + td[j] + (kvs[j] * de if taut else 0.0), 0.0)


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
