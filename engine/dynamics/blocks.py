"""The implicit blocks round the pulleys: each pulley element with the springs on both its
sides and the belt elements at their far ends (and the gravity take-up carriage when its pulley
is in the block), solved together every step.

Short, stiff springs round light pulleys would otherwise set the step. A block's springs are
taken at the new step (linearised with the tangent stiffness the spring update uses) and its
velocities come from one small solve: tridiagonal plus the carriage's row and column,
eliminated from both ends without fill-in (a dense pivoting solve as fallback). Piecewise
parts are resolved by an active set, the solve repeated until consistent:

* the resistance's zone (linear below ``v_eps``, constant above);
* brakes and holdbacks holding an element at rest or sliding;
* **pulley slip** (capstan friction, PHYSICS 5.1): every drive pulley (and braked or
  holdback pulley) has a shaft. While the shaft sticks to the belt it adds its mass and its
  forces (drive, brake, holdback) to the pulley element, and the force it passes to the belt
  must stay within ``T_slack (e^(mu theta) - 1)`` with the new tensions; beyond it the pulley
  slips. A slipping shaft follows its own inertia under its drive and brake forces less the
  sliding force ``T_s (e^(mu_k theta) - 1)``, which the belt receives, ``T_s`` being the side
  the sliding friction unloads (the outgoing side when the shaft runs faster than the belt,
  the incoming side when slower; implicit, so the slack-side spring's coefficients in the
  pulley's row grow by ``e^(mu_k theta) - 1``); it sticks again when the speeds cross;
* the drives: a force linear in the shaft speed ``f0 + f1 v`` (motor curves and couplings,
  linearised; power off), a share of the speed loop's output ``U`` (torque following: every
  vfd drive gives ``share x U``, ``U = f0u + f1u v_master``, solved with the master's shaft
  speed by superposition of two solves), or an imposed shaft speed (moving support); the
  torque limits;
* the carriage's end stops.
"""

from __future__ import annotations

import math

from numba import njit

from beltstudy.engine.dynamics.fastmath import OPTS
from beltstudy.engine.dynamics.passes import spring as _spring_impl
from beltstudy.engine.dynamics.passes import spring_rest as _spring_rest

__all__ = ["block_step", "solve_arrow", "solve_dense", "coulomb"]


@njit(**OPTS)
def solve_dense(A, b, m):
    """Solve A[:m, :m] x = b[:m] in place (Gaussian elimination, partial pivoting); x in b."""
    for k in range(m):
        p = k
        big = abs(A[k, k])
        for i in range(k + 1, m):
            if abs(A[i, k]) > big:
                big = abs(A[i, k])
                p = i
        if p != k:
            for c in range(m):
                tmp = A[k, c]
                A[k, c] = A[p, c]
                A[p, c] = tmp
            tmp = b[k]
            b[k] = b[p]
            b[p] = tmp
        piv = A[k, k]
        for i in range(k + 1, m):
            f = A[i, k] / piv
            if f != 0.0:
                for c in range(k, m):
                    A[i, c] -= f * A[k, c]
                b[i] -= f * b[k]
    for k in range(m - 1, -1, -1):
        s = b[k]
        for c in range(k + 1, m):
            s -= A[k, c] * b[c]
        b[k] = s / A[k, k]


@njit(inline="always", **OPTS)
def solve_arrow(d, lo, up, cl, rw, x, m, car, car_free):
    """Solve a block's system in place (x holds the right-hand side, then the solution).

    The block matrix is tridiagonal over the ``m`` element rows (``lo[k] = A[k, k-1]``,
    ``d[k] = A[k, k]``, ``up[k] = A[k, k+1]``) with, when ``car``, the carriage column
    ``cl[k] = A[k, m]`` and row ``rw[k] = A[m, k]``, ``d[m] = A[m, m]``; ``car_free`` False
    means the carriage row is the identity (``x[m]`` already holds its imposed speed).
    Eliminating the element unknowns from both ends of the chain inwards, then the
    carriage, makes no fill-in. No pivoting: the free rows are symmetric
    positive definite (mass, controller gain and resistance slope on the diagonal plus each
    implicit spring's ``B g g^T`` with ``g = e_{k+1} - e_k (+ e_m)``, B >= 0), and an
    identity row of an imposed or stuck unknown only moves its value to the right-hand
    side, leaving a principal submatrix: every pivot is positive. Returns False if one is
    not (nothing then is reliable in x, use :func:`solve_dense`).
    """
    # eliminate from both ends towards the middle row (halves the chain of dependent
    # divisions); the carriage row collects from each side separately
    mid = m // 2
    dml = 0.0
    xml = 0.0
    for k in range(mid):  # unknown k out of row k + 1 (and the carriage row)
        piv = d[k]
        if not piv > 0.0:
            return False
        ip = 1.0 / piv
        d[k] = ip  # the back substitution multiplies by the pivot's reciprocal
        f = lo[k + 1] * ip
        d[k + 1] -= f * up[k]
        x[k + 1] -= f * x[k]
        if car:
            cl[k + 1] -= f * cl[k]
        if car_free:
            g = rw[k] * ip
            rw[k + 1] -= g * up[k]
            dml -= g * cl[k]
            xml -= g * x[k]
    dmr = 0.0
    xmr = 0.0
    for k in range(m - 1, mid, -1):  # unknown k out of row k - 1 (and the carriage row)
        piv = d[k]
        if not piv > 0.0:
            return False
        ip = 1.0 / piv
        d[k] = ip
        f = up[k - 1] * ip
        d[k - 1] -= f * lo[k]
        x[k - 1] -= f * x[k]
        if car:
            cl[k - 1] -= f * cl[k]
        if car_free:
            g = rw[k] * ip
            rw[k - 1] -= g * lo[k]
            dmr -= g * cl[k]
            xmr -= g * x[k]
    piv = d[mid]
    if not piv > 0.0:
        return False
    ip = 1.0 / piv
    d[mid] = ip
    if car_free:
        g = rw[mid] * ip
        dm = (d[m] + (dml + dmr)) - g * cl[mid]
        if not dm > 0.0:
            return False
        x[m] = ((x[m] + (xml + xmr)) - g * x[mid]) / dm
    s = x[mid]
    if car:
        s -= cl[mid] * x[m]
    x[mid] = s * ip
    for k in range(mid - 1, -1, -1):
        s = x[k] - up[k] * x[k + 1]
        if car:
            s -= cl[k] * x[m]
        x[k] = s * d[k]
    for k in range(mid + 1, m):
        s = x[k] - lo[k] * x[k - 1]
        if car:
            s -= cl[k] * x[m]
        x[k] = s * d[k]
    return True


@njit(inline="always", **OPTS)
def _offdiag(lo, up, cl, x, k, m, car):
    """Sum of A[k, c] x[c] over c != k for an element row of a block's band."""
    s = 0.0
    if k > 0:
        s += lo[k] * x[k - 1]
    if k + 1 < m:
        s += up[k] * x[k + 1]
    if car:
        s += cl[k] * x[m]
    return s



@njit(inline="always", **OPTS)
def coulomb(p, dd, fb, hb):
    """Velocity of a mass under ``dd v = p - fb sign(v)`` (a Coulomb brake of force ``fb``,
    holding when ``|p| <= fb``) and, with a holdback ``hb``, never below zero. ``dd > 0``."""
    if fb > 0.0:
        if abs(p) <= fb:
            v = 0.0
        else:
            v = (p - math.copysign(fb, p)) / dd
    else:
        v = p / dd
    if hb and v < 0.0:
        v = 0.0
    return v


@njit(inline="always", **OPTS)
def _solve(wk, m, car, car_fixed, two):
    """Solve the working band (wd, wl, wu, wc, wr) for ``sol`` (and ``sol2`` when ``two``),
    band elimination first, the dense pivoting solve when a pivot is not positive. The
    right-hand sides are ``crhs`` and ``cuc`` (already copied into ``sol`` and ``sol2``)."""
    mu = m + 1 if car else m
    # keep the band: the elimination overwrites the diagonal and the carriage parts
    for k in range(mu):
        wk.kd[k] = wk.wd[k]
        wk.kc[k] = wk.wc[k]
        wk.kr[k] = wk.wr[k]
    ok = solve_arrow(wk.wd, wk.wl, wk.wu, wk.wc, wk.wr, wk.sol, m, car, car and not car_fixed)
    if ok and two:
        for k in range(mu):
            wk.wd[k] = wk.kd[k]
            wk.wc[k] = wk.kc[k]
            wk.wr[k] = wk.kr[k]
        ok = solve_arrow(wk.wd, wk.wl, wk.wu, wk.wc, wk.wr, wk.sol2, m, car,
                         car and not car_fixed)
    if ok:
        return
    for rhs_no in range(2 if two else 1):
        A = wk.Ac
        for r in range(mu):
            for c in range(mu):
                A[r, c] = 0.0
        for k in range(m):
            A[k, k] = wk.kd[k]
            if k > 0:
                A[k, k - 1] = wk.wl[k]
            if k + 1 < m:
                A[k, k + 1] = wk.wu[k]
            if car:
                A[k, m] = wk.kc[k]
                if not car_fixed:
                    A[m, k] = wk.kr[k]
        if car:
            A[m, m] = wk.kd[m]
        b = wk.sol if rhs_no == 0 else wk.sol2
        for k in range(mu):
            b[k] = wk.crhs[k] if rhs_no == 0 else wk.cuc[k]
        solve_dense(A, b, mu)


@njit(inline="always", **OPTS)
def _row_brake(wk, k, fb, hb, vo, v_eps):
    """A brake of force ``fb`` and/or a holdback acting on block row ``k`` (its shaft sticks to
    the belt): the stick's reaction range; the element is tried held at rest when it moves
    slower than ``v_eps`` (the implicit Coulomb law: held if the reaction it needs is within
    the brake's force, else sliding)."""
    wk.bforce[k] = fb
    wk.c_lo[k] = -fb
    wk.c_hi[k] = 1e300 if hb else fb
    can = fb > 0.0 or hb
    wk.stuck[k] = 1.0 if (can and (abs(vo) <= v_eps or (hb and vo < 0.0))) else 0.0


@njit(inline="always", **OPTS)
def _reaction(wk, x, k, m, car):
    """Residual of row ``k`` at the solution: the reaction a stuck element's brake or holdback
    gives."""
    s = wk.dg[k] * x[k] - wk.rhs[k]
    if k > 0:
        s += wk.lo[k] * x[k - 1]
    if k + 1 < m:
        s += wk.up[k] * x[k + 1]
    if car:
        s += wk.cl[k] * x[m]
    return s


@njit(inline="always", **OPTS)
def _saturate_master(drives, master, U):
    """The speed loop's output within the master drive's force limit (``share x U``)."""
    f = drives.share[master] * U
    if abs(f) > drives.lim[master]:
        drives.sat[master] = 1
        drives.f0[master] = math.copysign(drives.lim[master], f)
        return drives.f0[master] / drives.share[master]
    return U


@njit(inline="always", **OPTS)
def _share_force(drives, dk, U):
    """A torque-following drive's force ``share x U`` within its own force limit."""
    f = drives.share[dk] * U
    if abs(f) > drives.lim[dk]:
        drives.sat[dk] = 1
        drives.f0[dk] = math.copysign(drives.lim[dk], f)
        return drives.f0[dk]
    return f


@njit(inline="always", **OPTS)
def _side_tensions(wk, sp, blocks, tt, x, p0, k, m, car):
    """Tensions of the springs on both sides of block element ``k`` at the solution [N]."""
    if k > 0:
        jl = blocks.nodes[p0 + k - 1]
        dv = x[k] - x[k - 1]
        if car:
            dv += sp.car_ind[jl] * x[m]
        tl = wk.bA[k - 1] + wk.bB[k - 1] * dv
    else:
        tl = tt[blocks.left[p0]]
    j = blocks.nodes[p0 + k]
    if k < m - 1:
        dv = x[k + 1] - x[k]
        if car:
            dv += sp.car_ind[j] * x[m]
        tr = wk.bA[k] + wk.bB[k] * dv
    else:
        tr = tt[j]
    return tl, tr


@njit(inline="always", **OPTS)
def _belt_force(wk, blocks, x, p0, k, inv_veps, tl, tr):
    """Force the pulley passes to the belt element ``k`` at the solution: what its momentum
    balance needs besides the belt's own forces [N]."""
    xk = x[k]
    rk = wk.rpos[k] * (xk * inv_veps if wk.fz[k] == 0.0 else wk.fz[k])
    return blocks.mdt[p0 + k] * (xk - wk.v_old[k]) - (tr - tl) + rk - wk.fexp[k]


@njit(inline="always", **OPTS)
def _shaft_push(shafts, drives, s, master, U, dt, sl, ft):
    """Momentum over dt plus the forces on a slipping shaft but its brake [N]."""
    p = shafts.mass[s] / dt * shafts.vs[s] - ft
    dk = shafts.drive[s]
    if dk >= 0:
        md = drives.mode[dk]
        if md == 1:
            p += drives.f0[dk] if drives.sat[dk] == 1 else drives.share[dk] * U
        elif md == 0:
            p += drives.f0[dk] + drives.f1[dk] * shafts.vs[s]
    return p


@njit(inline="always", **OPTS)
def _shaft_speed(shafts, drives, s, master, U, v_ref, window, dt, sl, ts):
    """New speed of a slipping shaft: its inertia under its drive and brake forces less the
    sliding force ``sl (e^(mu_k theta) - 1) ts`` it gives the belt. A torque-following drive
    keeps its shaft within ``window`` of the speed reference (its speed-window control)."""
    ms = shafts.mass[s] / dt
    f = -sl * shafts.ck[s] * ts
    dd = ms
    dk = shafts.drive[s]
    follower = False
    if dk >= 0:
        md = drives.mode[dk]
        if md == 2:
            return v_ref
        if md == 1:
            f += drives.f0[dk] if drives.sat[dk] == 1 else drives.share[dk] * U
            follower = dk != master
        else:
            f += drives.f0[dk]
            dd -= drives.f1[dk]
    v = coulomb(ms * shafts.vs[s] + f, dd, shafts.fb[s], shafts.hb[s] == 1)
    if follower:
        v = min(max(v, v_ref - window), v_ref + window)
    return v


@njit(inline="always", **OPTS)
def block_step(bk, blocks, shafts, drives, sp, nodes, st, wk, dt, v_eps, eb, e_damp, g_damp,
               hold_node, v_ref, window, f0u, f1u, u_in, u_known, master, tu_gravity, x_tu,
               u_tu, tu_lo, tu_hi, tu_w, tu_m):
    """Advance the velocities of block ``bk`` by one step (see the module docstring).

    Updates ``st.v``, the shafts' speeds and slip states, the drives' forces (``force`` at the
    rim, ``ft`` passed to the belt), motor speeds and saturation, and the block's implicit
    springs. Returns ``(U, U known, carriage speed, carriage speed at an end stop or -1,
    holding force or nan, brake force, sum w v, sum of drive forces, drive power, drive
    work)``.
    """
    p0 = blocks.ptr[bk]
    m = blocks.ptr[bk + 1] - p0
    car = tu_gravity and blocks.car[bk] == 1
    v = st.v
    te = st.te
    tsn = st.ts
    td = st.td
    tt = st.tt
    r0 = wk.r0
    inv_veps = 1.0 / v_eps
    km = -1
    for k in range(m):
        j = blocks.nodes[p0 + k]
        if k < m - 1:
            e0 = te[j]
            if e0 < 0.0:
                wk.bA[k] = 0.0
                wk.bB[k] = 0.0
            else:
                er, r = _spring_rest(e0, tsn[j], sp.t_floor[j], sp.a_eb[j])
                wk.bA[k] = er + e_damp * td[j]
                wk.bB[k] = (eb * r * (1.0 + g_damp) + sp.kvs[j]) * sp.dl[j]
        vo = v[j]
        wk.v_old[k] = vo
        r = r0[j]
        wk.rpos[k] = max(r, 0.0)
        wk.fexp[k] = -min(r, 0.0) * min(max(vo * inv_veps, -1.0), 1.0) - nodes.gravity[j]
        wk.fz[k] = 1.0 if vo > v_eps else (-1.0 if vo < -v_eps else 0.0)
        s = blocks.node_shaft[j]
        wk.shk[k] = s
        wk.fixed[k] = 1.0 if j == hold_node else 0.0
        wk.fixv[k] = 0.0
        wk.stuck[k] = 0.0
        wk.bforce[k] = 0.0
        wk.c_lo[k] = 0.0
        wk.c_hi[k] = 0.0
        wk.bdir[k] = 1.0 if vo >= 0.0 else -1.0
        wk.vsn[k] = 0.0
        if s >= 0:
            if shafts.slip[s] == 0.0:
                _row_brake(wk, k, shafts.fb[s], shafts.hb[s] == 1, vo, v_eps)
            if shafts.drive[s] == master:
                km = k
    U = u_in
    have_u = u_known
    car_fixed = False
    car_v = 0.0
    car_hit = -1.0
    two = False
    mu = m + 1 if car else m
    for _it in range(24):
        # ------------------------------------------------ the speed loop's output U
        two = False
        if km >= 0 and not have_u and drives.mode[master] == 1 and drives.sat[master] == 0:
            s_m = wk.shk[km]
            if shafts.slip[s_m] != 0.0:
                # a slipping master: its shaft predicted with the tension at the step start
                jm = blocks.nodes[p0 + km]
                sl = shafts.slip[s_m]
                ts = tt[jm] if sl > 0.0 else tt[blocks.left[p0 + km]]
                ms = shafts.mass[s_m] / dt
                sh = drives.share[master]
                vp = (ms * shafts.vs[s_m] + sh * f0u - sl * shafts.ck[s_m] * ts) / (ms - sh * f1u)
                U = f0u + f1u * vp
            elif wk.fixed[km] == 1.0 or wk.stuck[km] == 1.0:
                U = f0u + f1u * wk.fixv[km]
            else:
                two = True
            if not two:
                U = _saturate_master(drives, master, U)
        # ------------------------------------------------ rows
        for k in range(m):
            j = blocks.nodes[p0 + k]
            s = wk.shk[k]
            d = blocks.mdt[p0 + k]
            r = d * wk.v_old[k] + wk.fexp[k]
            ml = 1.0
            mr = 1.0
            uc = 0.0
            if s >= 0:
                sl = shafts.slip[s]
                if sl > 0.0:
                    mr = 1.0 + shafts.ck[s]
                elif sl < 0.0:
                    ml = 1.0 + shafts.ck[s]
                else:
                    msd = shafts.mass[s] / dt
                    d += msd
                    r += msd * shafts.vs[s]
                    dk = shafts.drive[s]
                    if dk >= 0:
                        md = drives.mode[dk]
                        if md == 2:
                            if wk.fixed[k] == 0.0:
                                wk.fixed[k] = 1.0
                                wk.fixv[k] = v_ref
                        elif md == 1:
                            if drives.sat[dk] == 1:
                                r += drives.f0[dk]
                            elif two:
                                uc = drives.share[dk]
                            else:
                                r += _share_force(drives, dk, U)
                        else:
                            d -= drives.f1[dk]
                            r += drives.f0[dk]
            if wk.fz[k] == 0.0:
                d += wk.rpos[k] * inv_veps
            else:
                r -= wk.fz[k] * wk.rpos[k]
            if wk.bforce[k] > 0.0 and wk.stuck[k] == 0.0:
                r -= wk.bdir[k] * wk.bforce[k]
            c_k = 0.0
            if k == 0:
                r -= ml * tt[blocks.left[p0]]
                wk.lo[k] = 0.0
            else:
                b_ = ml * wk.bB[k - 1]
                d += b_
                wk.lo[k] = -b_
                r -= ml * wk.bA[k - 1]
                if car:
                    c_k += b_ * sp.car_ind[blocks.nodes[p0 + k - 1]]
            if k == m - 1:
                r += mr * tt[j]
                wk.up[k] = 0.0
            else:
                b_ = mr * wk.bB[k]
                d += b_
                wk.up[k] = -b_
                r += mr * wk.bA[k]
                if car:
                    c_k -= b_ * sp.car_ind[j]
            wk.dg[k] = d
            wk.rhs[k] = r
            wk.cl[k] = c_k
            wk.ucoef[k] = uc
            wk.rw[k] = 0.0
            if wk.fixed[k] == 1.0 or wk.stuck[k] == 1.0:
                wk.wd[k] = 1.0
                wk.wl[k] = 0.0
                wk.wu[k] = 0.0
                wk.wc[k] = 0.0
                wk.crhs[k] = wk.fixv[k] if wk.fixed[k] == 1.0 else 0.0
                wk.cuc[k] = 0.0
            else:
                wk.wd[k] = d
                wk.wl[k] = wk.lo[k]
                wk.wu[k] = wk.up[k]
                wk.wc[k] = c_k
                wk.crhs[k] = r
                wk.cuc[k] = uc
        if car:
            d = tu_m / dt
            r = tu_m / dt * u_tu + tu_w
            for k in range(m - 1):
                if sp.car_ind[blocks.nodes[p0 + k]] != 0.0:
                    wk.rw[k + 1] += wk.bB[k]
                    wk.rw[k] -= wk.bB[k]
                    d += wk.bB[k]
                    r -= wk.bA[k]
            wk.dg[m] = d
            wk.rhs[m] = r
            wk.wd[m] = 1.0 if car_fixed else d
            wk.crhs[m] = car_v if car_fixed else r
            wk.cuc[m] = 0.0
        for k in range(m):
            wk.wr[k] = wk.rw[k]
        for k in range(mu):
            wk.sol[k] = wk.crhs[k]
            wk.sol2[k] = wk.cuc[k]
        _solve(wk, m, car, car_fixed, two)
        if two:
            den = 1.0 - f1u * wk.sol2[km]
            U = (f0u + f1u * wk.sol[km]) / den
            U = _saturate_master(drives, master, U)
            for k in range(mu):
                wk.sol[k] += U * wk.sol2[k]
        x = wk.sol
        # ------------------------------------------------ consistency
        again = False
        if car and not car_fixed:
            x_try = x_tu + dt * x[m]
            if x_try > tu_hi or x_try < tu_lo:
                car_fixed = True
                car_v = ((tu_hi if x_try > tu_hi else tu_lo) - x_tu) / dt
                car_hit = abs(x[m])
                again = True
        for k in range(m):
            s = wk.shk[k]
            if s >= 0 and shafts.drive[s] >= 0:
                dk = shafts.drive[s]
                if drives.mode[dk] == 1 and drives.sat[dk] == 0 and dk != master:
                    f = drives.share[dk] * U
                    if abs(f) > drives.lim[dk]:
                        drives.sat[dk] = 1
                        drives.f0[dk] = math.copysign(drives.lim[dk], f)
                        again = True
            if wk.fixed[k] == 1.0:
                z = 1.0 if wk.fixv[k] > v_eps else (-1.0 if wk.fixv[k] < -v_eps else 0.0)
                if z != wk.fz[k]:
                    wk.fz[k] = z
            else:
                xk = x[k]
                if wk.stuck[k] == 1.0:
                    # a follower's share of U is not in rhs when U comes by superposition
                    c_r = _reaction(wk, x, k, m, car) - wk.ucoef[k] * U
                    if c_r > wk.c_hi[k] or c_r < wk.c_lo[k]:
                        wk.stuck[k] = 0.0
                        wk.bdir[k] = -1.0 if c_r > wk.c_hi[k] else 1.0
                        again = True
                else:
                    if wk.c_hi[k] > 1e299 and xk < 0.0:
                        wk.stuck[k] = 1.0  # holdback engages
                        again = True
                    elif wk.bforce[k] > 0.0 and xk * wk.bdir[k] < 0.0:
                        wk.stuck[k] = 1.0  # the brake stops the element
                        again = True
                z = 1.0 if xk > v_eps else (-1.0 if xk < -v_eps else 0.0)
                if wk.stuck[k] == 1.0:
                    z = 0.0
                if z != wk.fz[k]:
                    wk.fz[k] = z
                    again = True
            if s < 0:
                continue
            j = blocks.nodes[p0 + k]
            tl, tr = _side_tensions(wk, sp, blocks, tt, x, p0, k, m, car)
            sl = shafts.slip[s]
            if sl == 0.0:
                if j == hold_node:
                    continue
                if shafts.cs[s] < 0.0:
                    continue  # slip switched off (verification)
                ft = _belt_force(wk, blocks, x, p0, k, inv_veps, tl, tr)
                cap = shafts.cs[s] * max(min(tl, tr), 0.0)
                if abs(ft) > cap * (1.0 + 1e-9) + 1e-9:
                    shafts.slip[s] = 1.0 if ft > 0.0 else -1.0
                    wk.stuck[k] = 0.0
                    wk.bforce[k] = 0.0
                    wk.c_lo[k] = 0.0
                    wk.c_hi[k] = 0.0
                    if wk.fixed[k] == 1.0 and j != hold_node:
                        wk.fixed[k] = 0.0  # an imposed speed now holds the shaft, not the belt
                    again = True
            else:
                ts = max(tr if sl > 0.0 else tl, 0.0)
                vsn = _shaft_speed(shafts, drives, s, master, U, v_ref, window, dt, sl, ts)
                wk.vsn[k] = vsn
                if sl * (vsn - x[k]) <= 0.0:
                    shafts.slip[s] = 0.0
                    _row_brake(wk, k, shafts.fb[s], shafts.hb[s] == 1, wk.v_old[k], v_eps)
                    again = True
        if not again:
            break
    # ---------------------------------------------------- write back
    x = wk.sol
    u_new = x[m] if car else u_tu
    hold_f = math.nan
    f_brake = 0.0
    vsum = 0.0
    f_tot = 0.0
    p_tot = 0.0
    w_drv = 0.0
    for k in range(m):
        j = blocks.nodes[p0 + k]
        xk = x[k]
        v[j] = xk
        vsum += nodes.w_mean[j] * xk
        if wk.bforce[k] > 0.0:
            f_brake += abs(_reaction(wk, x, k, m, car) - wk.ucoef[k] * U) if wk.stuck[k] == 1.0 \
                else wk.bforce[k]
        s = wk.shk[k]
        if s < 0:
            continue
        tl, tr = _side_tensions(wk, sp, blocks, tt, x, p0, k, m, car)
        vs_old = shafts.vs[s]
        sl = shafts.slip[s]
        if sl == 0.0:
            vsn = xk
            ft = _belt_force(wk, blocks, x, p0, k, inv_veps, tl, tr)
            shafts.fb_out[s] = 0.0
        else:
            vsn = wk.vsn[k]
            ft = sl * shafts.ck[s] * max(tr if sl > 0.0 else tl, 0.0)
            fb = shafts.fb[s]
            if fb > 0.0:
                f_brake += fb if vsn != 0.0 else min(fb, abs(_shaft_push(
                    shafts, drives, s, master, U, dt, sl, ft)))
        if j == hold_node:
            hold_f = ft
        shafts.vs[s] = vsn
        dk = shafts.drive[s]
        if dk < 0:
            continue
        md = drives.mode[dk]
        if md == 2:
            f = ft + shafts.mass[s] / dt * (vsn - vs_old)
        elif md == 1:
            f = drives.f0[dk] if drives.sat[dk] == 1 else drives.share[dk] * U
            if sl != 0.0 and dk != master:
                # a follower in its speed window gives what holds its shaft there
                f = min(f, shafts.mass[s] / dt * (vsn - vs_old) + ft) if f > 0.0 else \
                    max(f, shafts.mass[s] / dt * (vsn - vs_old) + ft)
        else:
            f = drives.f0[dk] + drives.f1[dk] * vsn
        if drives.coupling[dk] != 0 and drives.lin_d[dk] > 0.0:
            drives.vm[dk] = (drives.lin_p[dk] - drives.lin_cs[dk] * vsn) / drives.lin_d[dk]
        drives.force[dk] = f
        drives.ft[dk] = ft
        f_tot += f
        p_tot += f * vsn
        w_drv += f * 0.5 * (vs_old + vsn) * dt
    # implicit springs of the block
    for k in range(m - 1):
        s_ = blocks.nodes[p0 + k]
        s1 = blocks.nodes[p0 + k + 1]
        cdt = sp.car_ind[s_] * u_new * sp.dl[s_] if car else 0.0
        e1, ts1, d1, t1 = _spring_impl(te[s_], tsn[s_], td[s_], v[s1] - v[s_], sp.dl[s_], cdt,
                                       sp.t_floor[s_], sp.s_floor[s_], sp.kfl_eb[s_],
                                       sp.a_eb[s_], eb, e_damp, g_damp, sp.kvs[s_])
        te[s_] = e1
        tsn[s_] = ts1
        td[s_] = d1
        tt[s_] = t1
    known = have_u or km >= 0
    return U, known, u_new, car_hit, hold_f, f_brake, vsum, f_tot, p_tot, w_drv
