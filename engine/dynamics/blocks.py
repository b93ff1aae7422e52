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

from numba import njit, uintp

from beltstudy.engine.dynamics.fastmath import OPTS
from beltstudy.engine.dynamics.passes import spring as _spring_impl
from beltstudy.engine.dynamics.passes import spring_rest as _spring_rest

__all__ = ["block_step", "solve_arrow", "solve_arrow2", "solve_dense", "coulomb"]


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
    return _arrow(d, lo, up, cl, rw, x, x, m, car, car_free, False)


@njit(inline="always", **OPTS)
def solve_arrow2(d, lo, up, cl, rw, x, x2, m, car, car_free):
    """:func:`solve_arrow` for two right-hand sides at once (``x`` and ``x2``, each replaced by
    its solution): the elimination of the matrix is done once and applied to both, each
    right-hand side taking the operations :func:`solve_arrow` gives it, with the same pivots
    and factors (the matrix's operations do not depend on the right-hand side): the same bits
    as two calls on copies of the band. Returns False if a pivot is not positive."""
    return _arrow(d, lo, up, cl, rw, x, x2, m, car, car_free, True)


@njit(inline="always", **OPTS)
def _arrow(d, lo, up, cl, rw, x, x2, m, car, car_free, two):
    """The elimination of :func:`solve_arrow` on ``x`` and, when ``two`` (a constant at each
    call, so the compiler keeps only the work asked for), on ``x2`` too."""
    # eliminate from both ends towards the middle row (halves the chain of dependent
    # divisions); the carriage row collects from each side separately
    mid = m // 2
    dml = 0.0
    xml = 0.0
    xml2 = 0.0
    for k in range(mid):  # unknown k out of row k + 1 (and the carriage row)
        piv = d[k]
        if not piv > 0.0:
            return False
        ip = 1.0 / piv
        d[k] = ip  # the back substitution multiplies by the pivot's reciprocal
        f = lo[k + 1] * ip
        d[k + 1] -= f * up[k]
        x[k + 1] -= f * x[k]
        if two:
            x2[k + 1] -= f * x2[k]
        if car:
            cl[k + 1] -= f * cl[k]
        if car_free:
            g = rw[k] * ip
            rw[k + 1] -= g * up[k]
            dml -= g * cl[k]
            xml -= g * x[k]
            if two:
                xml2 -= g * x2[k]
    dmr = 0.0
    xmr = 0.0
    xmr2 = 0.0
    for k in range(m - 1, mid, -1):  # unknown k out of row k - 1 (and the carriage row)
        piv = d[k]
        if not piv > 0.0:
            return False
        ip = 1.0 / piv
        d[k] = ip
        f = up[k - 1] * ip
        d[k - 1] -= f * lo[k]
        x[k - 1] -= f * x[k]
        if two:
            x2[k - 1] -= f * x2[k]
        if car:
            cl[k - 1] -= f * cl[k]
        if car_free:
            g = rw[k] * ip
            rw[k - 1] -= g * lo[k]
            dmr -= g * cl[k]
            xmr -= g * x[k]
            if two:
                xmr2 -= g * x2[k]
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
        if two:
            # the same divisor computed again after the store (the compiler may not fold two
            # divisions by one value into a reciprocal and two products, which rounds
            # otherwise)
            dm2 = (d[m] + (dml + dmr)) - g * cl[mid]
            x2[m] = ((x2[m] + (xml2 + xmr2)) - g * x2[mid]) / dm2
    s = x[mid]
    if car:
        s -= cl[mid] * x[m]
    x[mid] = s * ip
    if two:
        s2 = x2[mid]
        if car:
            s2 -= cl[mid] * x2[m]
        x2[mid] = s2 * ip
    for k in range(mid - 1, -1, -1):
        s = x[k] - up[k] * x[k + 1]
        if car:
            s -= cl[k] * x[m]
        x[k] = s * d[k]
        if two:
            s2 = x2[k] - up[k] * x2[k + 1]
            if car:
                s2 -= cl[k] * x2[m]
            x2[k] = s2 * d[k]
    for k in range(mid + 1, m):
        s = x[k] - lo[k] * x[k - 1]
        if car:
            s -= cl[k] * x[m]
        x[k] = s * d[k]
        if two:
            s2 = x2[k] - lo[k] * x2[k - 1]
            if car:
                s2 -= cl[k] * x2[m]
            x2[k] = s2 * d[k]
    return True


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
    if two:
        # one elimination for both right-hand sides (the band's operations are the same)
        ok = solve_arrow2(wk.wd, wk.wl, wk.wu, wk.wc, wk.wr, wk.sol, wk.sol2, m, car,
                          car and not car_fixed)
    else:
        ok = solve_arrow(wk.wd, wk.wl, wk.wu, wk.wc, wk.wr, wk.sol, m, car,
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
        jl = uintp(blocks.nodes[p0 + k - 1])
        dv = x[k] - x[k - 1]
        if car:
            dv += sp.car_ind[jl] * x[m]
        tl = wk.bA[k - 1] + wk.bB[k - 1] * dv
    else:
        tl = tt[uintp(blocks.left[p0])]
    j = uintp(blocks.nodes[p0 + k])
    if k < m - 1:
        dv = x[k + 1] - x[k]
        if car:
            dv += sp.car_ind[j] * x[m]
        tr = wk.bA[k] + wk.bB[k] * dv
    else:
        tr = tt[j]
    return tl, tr


@njit(inline="always", **OPTS)
def _belt_force(wk, blocks, x, p0, k, inv_veps, tl, tr, zone):
    """Force the pulley passes to the belt element ``k`` at the solution: what its momentum
    balance needs besides the belt's own forces [N], with the resistance in the ``zone`` the
    solution was found in."""
    xk = x[k]
    rk = wk.rpos[k] * (xk * inv_veps if zone == 0.0 else zone)
    return blocks.mdt[p0 + k] * (xk - wk.v_old[k]) - (tr - tl) + rk - wk.fexp[k]


@njit(inline="always", **OPTS)
def _shaft_push(model, s, U, sl, ft):
    """Momentum over dt plus the forces on a slipping shaft but its brake [N]."""
    shafts = model.shafts
    drives = model.drives
    p = shafts.mass[s] / model.cycle.dt * shafts.vs[s] - ft
    dk = shafts.drive[s]
    if dk >= 0:
        md = drives.mode[dk]
        if md == 1:
            p += drives.f0[dk] if drives.sat[dk] == 1 else drives.share[dk] * U
            p += drives.win_f[dk]  # a follower's window (0 for any other drive)
        elif md == 0:
            p += drives.f0[dk] + drives.f1[dk] * shafts.vs[s]
    return p


@njit(inline="always", **OPTS)
def _shaft_speed(model, s, U, v_ref, sl, ts):
    """New speed of a slipping shaft: its inertia under its drive and brake forces less the
    sliding force ``sl (e^(mu_k theta) - 1) ts`` it gives the belt. A torque-following drive
    keeps its shaft within the speed window (``Control.window``) of the speed reference (its
    speed-window control) through its own torque: the force that takes the shaft into the
    window in this step where the drive's force stays within its limit (``Drives.lim``),
    else the limit, which takes it there over the steps that follow."""
    shafts = model.shafts
    drives = model.drives
    ms = shafts.mass[s] / model.cycle.dt
    f = -sl * shafts.ck[s] * ts
    dd = ms
    dk = shafts.drive[s]
    follower = False
    fd = 0.0
    if dk >= 0:
        md = drives.mode[dk]
        if md == 2:
            return v_ref
        if md == 1:
            fd = drives.f0[dk] if drives.sat[dk] == 1 else drives.share[dk] * U
            f += fd
            follower = dk != model.control.master
        else:
            f += drives.f0[dk]
            dd -= drives.f1[dk]
    p = ms * shafts.vs[s] + f
    fb = shafts.fb[s]
    hb = shafts.hb[s] == 1
    v = coulomb(p, dd, fb, hb)
    if follower:
        window = model.control.window
        vw = min(max(v, v_ref - window), v_ref + window)
        extra = 0.0
        if vw != v:
            lim = drives.lim[dk]
            need = ms * (vw - v)
            if need > lim - fd:
                extra = lim - fd
                v = coulomb(p + extra, dd, fb, hb)
            elif need < -lim - fd:
                extra = -(lim + fd)
                v = coulomb(p + extra, dd, fb, hb)
            else:
                extra = need
                v = vw
        drives.win_f[dk] = extra
    return v


@njit(inline="always", **OPTS)
def _block_setup(model, st, wk, p0, m, hold_node):
    """The block's rows before the active set: each implicit spring's tension at the step's
    start and its stiffness over the step (``bA``, ``bB``), each element's old speed, its
    resistance (the positive part implicit, ``rpos``; the negative part and gravity explicit,
    ``fexp``), its resistance zone, shaft, the held element, and the brakes of shafts that
    stick. Returns the row of the master drive's shaft (-1 none)."""
    blocks = model.blocks
    shafts = model.shafts
    sp = model.springs
    v_eps = model.cycle.v_eps
    inv_veps = 1.0 / v_eps
    master = model.control.master
    r0 = wk.r0
    km = -1
    for k in range(m):
        jn = blocks.nodes[p0 + k]
        j = uintp(jn)  # an element: unsigned, no negative-index wraparound
        if k < m - 1:
            e0 = st.te[j]
            if e0 < 0.0:
                wk.bA[k] = 0.0
                wk.bB[k] = 0.0
            else:
                er, r = _spring_rest(e0, st.ts[j], sp.t_floor[j], sp.a_eb[j])
                wk.bA[k] = er + sp.e_damp * st.td[j]
                wk.bB[k] = (sp.eb * r * (1.0 + sp.g_damp) + sp.kvs[j]) * sp.dl[j]
        vo = st.v[j]
        wk.v_old[k] = vo
        r = r0[j]
        wk.rpos[k] = max(r, 0.0)
        wk.fexp[k] = -min(r, 0.0) * min(max(vo * inv_veps, -1.0), 1.0) - model.nodes.gravity[j]
        wk.fz[k] = 1.0 if vo > v_eps else (-1.0 if vo < -v_eps else 0.0)
        s = blocks.node_shaft[j]
        wk.shk[k] = s
        wk.fixed[k] = 1.0 if jn == hold_node else 0.0
        wk.fixv[k] = 0.0
        wk.stuck[k] = 0.0
        wk.bforce[k] = 0.0
        wk.c_lo[k] = 0.0
        wk.c_hi[k] = 0.0
        wk.bdir[k] = 1.0 if vo >= 0.0 else -1.0
        wk.vsn[k] = 0.0
        wk.crossed[k] = 0.0
        if s >= 0:
            if shafts.slip[s] == 0.0:
                _row_brake(wk, k, shafts.fb[s], shafts.hb[s] == 1, vo, v_eps)
            if shafts.drive[s] == master:
                km = k
    return km


@njit(inline="always", **OPTS)
def _master_output(model, wk, rs, km, U, have_u):
    """The speed loop's output U for this pass when the master's row gives it directly (a
    held or stuck master at its imposed speed), within the master's limit. Returns (U, two):
    ``two`` when U must come by superposition of two solves (the master's new shaft speed
    depends on the block's unknowns: a free row, or a slipping shaft, whose speed follows
    from the sliding force at the new tensions, :func:`_master_speed`)."""
    drives = model.drives
    master = model.control.master
    if km >= 0 and not have_u and drives.mode[master] == 1 and drives.sat[master] == 0:
        if model.shafts.slip[wk.shk[km]] == 0.0 and (wk.fixed[km] == 1.0
                                                      or wk.stuck[km] == 1.0):
            U = _saturate_master(drives, master, rs.f0u + rs.f1u * wk.fixv[km])
            return U, False
        return U, True
    return U, False


@njit(inline="always", **OPTS)
def _slack_side(wk, sp, blocks, tt, x, p0, k, m, car, sl):
    """The tension of the side a slip of direction ``sl`` unloads at block element ``k`` (the
    outgoing spring when ``sl > 0``, the incoming one when ``sl < 0``) as its constant part
    and its part linear in the solution ``x`` [N] (:func:`_side_tensions`' springs)."""
    if sl > 0.0:
        j = uintp(blocks.nodes[p0 + k])
        if k < m - 1:
            dv = x[k + 1] - x[k]
            if car:
                dv += sp.car_ind[j] * x[m]
            return wk.bA[k], wk.bB[k] * dv
        return tt[j], 0.0
    if k > 0:
        jl = uintp(blocks.nodes[p0 + k - 1])
        dv = x[k] - x[k - 1]
        if car:
            dv += sp.car_ind[jl] * x[m]
        return wk.bA[k - 1], wk.bB[k - 1] * dv
    return tt[uintp(blocks.left[p0])], 0.0


@njit(inline="always", **OPTS)
def _master_speed(model, st, wk, p0, km, m, car):
    """The master's new shaft speed as ``g0 + gu U`` from the two solves (``sol``, the
    response ``sol2`` to U): the belt's speed at its row while it sticks; while it slips, its
    own momentum balance over the step under its share of U less the sliding force ``ck T_s``
    at the new tensions, the same balance :func:`_shaft_speed` takes (implicit: the force and
    the shaft's speed at the step's end, consistent with the belt's)."""
    shafts = model.shafts
    s = wk.shk[km]
    sl = shafts.slip[s]
    if sl == 0.0 or abs(wk.crossed[km]) == 2.0:
        return wk.sol[km], wk.sol2[km]  # at the belt's speed
    c0, l0 = _slack_side(wk, model.springs, model.blocks, st.tt, wk.sol, p0, km, m, car, sl)
    _c, lu = _slack_side(wk, model.springs, model.blocks, st.tt, wk.sol2, p0, km, m, car, sl)
    ms = shafts.mass[s] / model.cycle.dt
    ck = shafts.ck[s]
    g0 = shafts.vs[s] - sl * ck * (c0 + l0) / ms
    gu = (model.drives.share[model.control.master] - sl * ck * lu) / ms
    return g0, gu


@njit(inline="always", **OPTS)
def _shaft_row(model, wk, rs, k, s, d, r, U, two):
    """A block row's shaft: its slip factors on the two sides (``ml``, ``mr``), and while it
    sticks its mass and drive force added to the row. Returns (d, r, ml, mr, coefficient of
    U)."""
    shafts = model.shafts
    drives = model.drives
    ml = 1.0
    mr = 1.0
    uc = 0.0
    sl = shafts.slip[s]
    if sl > 0.0:
        mr = 1.0 + shafts.ck[s]
    elif sl < 0.0:
        ml = 1.0 + shafts.ck[s]
    else:
        msd = shafts.mass[s] / model.cycle.dt
        d += msd
        r += msd * shafts.vs[s]
        dk = shafts.drive[s]
        if dk >= 0:
            md = drives.mode[dk]
            if md == 2:
                if wk.fixed[k] == 0.0:
                    wk.fixed[k] = 1.0
                    wk.fixv[k] = rs.v_ref
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
    return d, r, ml, mr, uc


@njit(inline="always", **OPTS)
def _block_rows(model, st, wk, rs, p0, m, car, U, two):
    """Assemble the block's band (``dg``, ``lo``, ``up``, ``cl``, ``rhs``) and the working
    copy the solve takes, with held and stuck rows replaced by their imposed speeds."""
    blocks = model.blocks
    sp = model.springs
    tt = st.tt
    inv_veps = 1.0 / model.cycle.v_eps
    for k in range(m):
        j = uintp(blocks.nodes[p0 + k])
        s = wk.shk[k]
        d = blocks.mdt[p0 + k]
        r = d * wk.v_old[k] + wk.fexp[k]
        ml = 1.0
        mr = 1.0
        uc = 0.0
        if s >= 0:
            d, r, ml, mr, uc = _shaft_row(model, wk, rs, k, s, d, r, U, two)
        if wk.fz[k] == 0.0:
            d += wk.rpos[k] * inv_veps
        else:
            r -= wk.fz[k] * wk.rpos[k]
        if wk.bforce[k] > 0.0 and wk.stuck[k] == 0.0:
            r -= wk.bdir[k] * wk.bforce[k]
        c_k = 0.0
        if k == 0:
            r -= ml * tt[uintp(blocks.left[p0])]
            wk.lo[k] = 0.0
        else:
            b_ = ml * wk.bB[k - 1]
            d += b_
            wk.lo[k] = -b_
            r -= ml * wk.bA[k - 1]
            if car:
                c_k += b_ * sp.car_ind[uintp(blocks.nodes[p0 + k - 1])]
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


@njit(inline="always", **OPTS)
def _carriage_row(model, wk, rs, p0, m, car_fixed, car_v):
    """The gravity take-up carriage's row: its inertia and weight, and the springs beside
    its pulley (or its imposed speed at an end stop)."""
    tu = model.takeup
    dt = model.cycle.dt
    d = tu.mass / dt
    r = tu.mass / dt * rs.u_tu + tu.weight
    for k in range(m - 1):
        if model.springs.car_ind[uintp(model.blocks.nodes[p0 + k])] != 0.0:
            wk.rw[k + 1] += wk.bB[k]
            wk.rw[k] -= wk.bB[k]
            d += wk.bB[k]
            r -= wk.bA[k]
    wk.dg[m] = d
    wk.rhs[m] = r
    wk.wd[m] = 1.0 if car_fixed else d
    wk.crhs[m] = car_v if car_fixed else r
    wk.cuc[m] = 0.0


@njit(inline="always", **OPTS)
def _block_solution(model, st, wk, rs, p0, m, car, car_fixed, two, km, U):
    """Solve the block's band for its speeds (``wk.sol``); with ``two`` also the response to
    U and U from the master's new shaft speed (:func:`_master_speed`), within its limit.
    Returns U."""
    mu = m + 1 if car else m
    for k in range(m):
        wk.wr[k] = wk.rw[k]
    for k in range(mu):
        wk.sol[k] = wk.crhs[k]
        wk.sol2[k] = wk.cuc[k]
    _solve(wk, m, car, car_fixed, two)
    if two:
        g0, gu = _master_speed(model, st, wk, p0, km, m, car)
        U = (rs.f0u + rs.f1u * g0) / (1.0 - rs.f1u * gu)
        U = _saturate_master(model.drives, model.control.master, U)
        for k in range(mu):
            wk.sol[k] += U * wk.sol2[k]
    return U


@njit(inline="always", **OPTS)
def _row_consistent(model, wk, k, m, car, U):
    """The active set of row ``k`` against the solution: a follower at its force limit, a
    stuck element whose reaction left its range, a holdback or brake that now holds, the
    resistance zone. Returns whether anything changed."""
    shafts = model.shafts
    drives = model.drives
    v_eps = model.cycle.v_eps
    x = wk.sol
    again = False
    s = wk.shk[k]
    if s >= 0 and shafts.drive[s] >= 0:
        dk = shafts.drive[s]
        if drives.mode[dk] == 1 and drives.sat[dk] == 0 and dk != model.control.master:
            f = drives.share[dk] * U
            if abs(f) > drives.lim[dk]:
                drives.sat[dk] = 1
                drives.f0[dk] = math.copysign(drives.lim[dk], f)
                again = True
    if wk.fixed[k] == 1.0:
        z = 1.0 if wk.fixv[k] > v_eps else (-1.0 if wk.fixv[k] < -v_eps else 0.0)
        if z != wk.fz[k]:
            wk.fz[k] = z
        return again
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
    if wk.stuck[k] == 1.0 or z * wk.fz[k] < 0.0:
        # a resistance that would turn round within the step goes through its linear band
        # (the speed at which it balances; from one side to the other the two zones give
        # each other's speeds and alternate to the last pass)
        z = 0.0
    if z != wk.fz[k]:
        wk.fz[k] = z
        again = True
    return again


@njit(inline="always", **OPTS)
def _shaft_consistent(model, st, wk, rs, p0, k, m, car, U, zone):
    """Row ``k``'s shaft against the solution: a sticking shaft that would pass more than its
    capstan grip starts to slip; a slipping one whose speed crosses the belt's sticks again
    (the exact outcome of the step, as in time stepping of friction at the velocity level,
    Moreau 1988: the relative speed at the step's end is zero, or has the sign of the sliding
    force). A shaft that sticks again this way and would then need more than its grip in the
    direction it slipped slides on at the belt's speed to the step's end, with the sliding
    force: without it the pair of states alternates to the last pass of the active set.
    ``zone``: the resistance zone the solution was found in (the row's check before this one
    may have moved it: a braked element turning round within the step goes to the linear
    band, where ``rpos x / v_eps`` at the solution's 0.1 m/s read 1.3 MN, and a braked tail
    pulley was said to slip, then chattered at +-100 m/s). Returns whether anything
    changed."""
    shafts = model.shafts
    blocks = model.blocks
    hold_node = rs.hold
    x = wk.sol
    s = wk.shk[k]
    j = blocks.nodes[p0 + k]  # compared with the held element only
    tl, tr = _side_tensions(wk, model.springs, blocks, st.tt, x, p0, k, m, car)
    sl = shafts.slip[s]
    if sl == 0.0:
        if j == hold_node or shafts.cs[s] < 0.0:
            return False  # held at rest, or slip switched off (verification)
        ft = _belt_force(wk, blocks, x, p0, k, 1.0 / model.cycle.v_eps, tl, tr, zone)
        cap = shafts.cs[s] * max(min(tl, tr), 0.0)
        if abs(ft) > cap * (1.0 + 1e-9) + 1e-9:
            shafts.slip[s] = 1.0 if ft > 0.0 else -1.0
            if wk.crossed[k] == shafts.slip[s]:
                # it slipped this way, its speed crossed the belt's within the step, and
                # sticking needs more than its grip the same way: the step ends sliding at
                # the belt's speed (no relative speed, the sliding force)
                wk.crossed[k] = 2.0 * shafts.slip[s]
            wk.stuck[k] = 0.0
            wk.bforce[k] = 0.0
            wk.c_lo[k] = 0.0
            wk.c_hi[k] = 0.0
            if wk.fixed[k] == 1.0 and j != hold_node:
                wk.fixed[k] = 0.0  # an imposed speed now holds the shaft, not the belt
            return True
        return False
    if abs(wk.crossed[k]) == 2.0:
        wk.vsn[k] = x[k]
        if shafts.drive[s] >= 0:
            model.drives.win_f[shafts.drive[s]] = 0.0  # sliding on at the belt's speed
        return False
    ts = max(tr if sl > 0.0 else tl, 0.0)
    vsn = _shaft_speed(model, s, U, rs.v_ref, sl, ts)
    wk.vsn[k] = vsn
    if sl * (vsn - x[k]) <= 0.0:
        wk.crossed[k] = sl
        shafts.slip[s] = 0.0
        _row_brake(wk, k, shafts.fb[s], shafts.hb[s] == 1, wk.v_old[k], model.cycle.v_eps)
        return True
    return False


@njit(inline="always", **OPTS)
def _drive_output(model, rs, s, ft, vs_old, vsn, U):
    """A drive's force at the rim after the step [N] (mode 2: what moved its shaft; mode 1:
    its share of U, a slipping follower's with what its speed window adds; mode 0: its linear
    law), the force at the step's start (``f_start``), and its motor's speed behind a
    coupling."""
    shafts = model.shafts
    drives = model.drives
    dt = model.cycle.dt
    dk = shafts.drive[s]
    md = drives.mode[dk]
    sl = shafts.slip[s]
    if md == 2:
        f = ft + shafts.mass[s] / dt * (vsn - vs_old)
    elif md == 1:
        f = drives.f0[dk] if drives.sat[dk] == 1 else drives.share[dk] * U
        if sl != 0.0 and dk != model.control.master:
            # a slipping follower's speed window adds the force that takes its shaft there,
            # within its limit (:func:`_shaft_speed`)
            f += drives.win_f[dk]
    else:
        f = drives.f0[dk] + drives.f1[dk] * vsn
    # the force at the step's start: the step's law at the shaft's speed before it (a share
    # of the loop's output at the master's speed before it); a slipping follower's window
    # and an imposed speed have no law, their force is the step's
    fs = f
    if md == 0:
        fs = drives.f0[dk] + drives.f1[dk] * vs_old
    elif md == 1 and (sl == 0.0 or dk == model.control.master):
        fs = drives.share[dk] * rs.u0
        if abs(fs) > drives.lim[dk]:
            fs = math.copysign(drives.lim[dk], fs)
    drives.f_start[dk] = fs
    if drives.coupling[dk] != 0 and drives.lin_d[dk] > 0.0:
        drives.vm[dk] = (drives.lin_p[dk] - drives.lin_cs[dk] * vsn) / drives.lin_d[dk]
    drives.force[dk] = f
    return f


@njit(inline="always", **OPTS)
def _write_back(model, st, wk, rs, p0, m, car, U):
    """The solution into the belt, the shafts and the drives. Returns (holding force or nan,
    brake force, sum w v, sum of drive forces, drive power, drive work) of the block; adds the
    holdback's force to ``rs.f_hb``."""
    blocks = model.blocks
    shafts = model.shafts
    drives = model.drives
    dt = model.cycle.dt
    inv_veps = 1.0 / model.cycle.v_eps
    x = wk.sol
    hold_f = math.nan
    f_brake = 0.0
    vsum = 0.0
    f_tot = 0.0
    p_tot = 0.0
    w_drv = 0.0
    for k in range(m):
        jn = blocks.nodes[p0 + k]
        j = uintp(jn)
        xk = x[k]
        st.v[j] = xk
        vsum += model.nodes.w_mean[j] * xk
        if wk.stuck[k] == 1.0 and wk.c_hi[k] > 1e299:
            # a holdback holding: the brake on its shaft gives up to its force, the holdback
            # the rest of the reaction (it engages only past the brake, docs/dynamics.md)
            c_r = _reaction(wk, x, k, m, car) - wk.ucoef[k] * U
            f_brake += min(abs(c_r), wk.bforce[k])
            rs.f_hb += max(c_r - wk.bforce[k], 0.0)
        elif wk.bforce[k] > 0.0:
            f_brake += abs(_reaction(wk, x, k, m, car) - wk.ucoef[k] * U) if wk.stuck[k] == 1.0 \
                else wk.bforce[k]
        s = wk.shk[k]
        if s < 0:
            continue
        tl, tr = _side_tensions(wk, model.springs, blocks, st.tt, x, p0, k, m, car)
        vs_old = shafts.vs[s]
        sl = shafts.slip[s]
        if sl == 0.0:
            vsn = xk
            ft = _belt_force(wk, blocks, x, p0, k, inv_veps, tl, tr, wk.fz[k])
            shafts.fb_out[s] = 0.0
        else:
            vsn = wk.vsn[k]
            ft = sl * shafts.ck[s] * max(tr if sl > 0.0 else tl, 0.0)
            fb = shafts.fb[s]
            if fb > 0.0:
                f_brake += fb if vsn != 0.0 else min(fb, abs(_shaft_push(
                    model, s, U, sl, ft)))
            if shafts.hb[s] == 1 and vsn == 0.0:
                # a slipping shaft the holdback holds at rest: what the brake does not
                rs.f_hb += max(-_shaft_push(model, s, U, sl, ft) - fb, 0.0)
        if jn == rs.hold:
            hold_f = ft
        shafts.vs[s] = vsn
        dk = shafts.drive[s]
        if dk < 0:
            continue
        f = _drive_output(model, rs, s, ft, vs_old, vsn, U)
        drives.ft[dk] = ft
        f_tot += f
        p_tot += f * vsn
        w_drv += f * 0.5 * (vs_old + vsn) * dt
    return hold_f, f_brake, vsum, f_tot, p_tot, w_drv


@njit(inline="always", **OPTS)
def _block_springs(model, st, p0, m, car, u_new):
    """The block's implicit springs from the new velocities (and the carriage's speed)."""
    blocks = model.blocks
    sp = model.springs
    for k in range(m - 1):
        s_ = uintp(blocks.nodes[p0 + k])
        s1 = uintp(blocks.nodes[p0 + k + 1])
        cdt = sp.car_ind[s_] * u_new * sp.dl[s_] if car else 0.0
        e1, ts1, d1, t1 = _spring_impl(sp, s_, st.te[s_], st.ts[s_], st.td[s_],
                                       st.v[s1] - st.v[s_], cdt)
        st.te[s_] = e1
        st.ts[s_] = ts1
        st.td[s_] = d1
        st.tt[s_] = t1


@njit(inline="always", **OPTS)
def block_step(bk, model, st, wk, rs):
    """Advance the velocities of block ``bk`` by one step (see the module docstring).

    Reads the step's phase from the run record ``rs`` (the held element ``hold``, the speed
    reference ``v_ref``, the speed loop's law ``f0u + f1u v``) with the loop's output ``U`` and
    whether it is known (``rs.U``, ``rs.u_known``, updated), and the carriage's position and
    speed. Updates ``st.v``, the shafts' speeds and slip states, the drives' forces (``force``
    at the rim, ``ft`` passed to the belt), motor speeds and saturation, and the block's
    implicit springs. Returns ``(carriage speed, carriage speed at an end stop or -1, holding
    force or nan, brake force, sum w v, sum of drive forces, drive power, drive work)``.
    """
    blocks = model.blocks
    p0 = blocks.ptr[bk]
    m = blocks.ptr[bk + 1] - p0
    car = model.takeup.gravity and blocks.car[bk] == 1
    tu = model.takeup
    km = _block_setup(model, st, wk, p0, m, rs.hold)
    U = rs.U
    have_u = rs.u_known
    if km >= 0 and not have_u:
        # the loop's output at the step's start (the master's block comes first), within the
        # master's limit as the step's own output is (_saturate_master): a follower's force
        # at the step's start is its share of that
        u0 = rs.f0u + rs.f1u * model.shafts.vs[wk.shk[km]]
        master = model.control.master
        lim_u = model.drives.lim[master] / model.drives.share[master]
        rs.u0 = min(max(u0, -lim_u), lim_u)
    car_fixed = False
    car_v = 0.0
    car_hit = -1.0
    for _it in range(24):
        U, two = _master_output(model, wk, rs, km, U, have_u)
        _block_rows(model, st, wk, rs, p0, m, car, U, two)
        if car:
            _carriage_row(model, wk, rs, p0, m, car_fixed, car_v)
        U = _block_solution(model, st, wk, rs, p0, m, car, car_fixed, two, km, U)
        x = wk.sol
        # ------------------------------------------------ consistency
        again = False
        if car and not car_fixed:
            x_try = rs.x_tu + model.cycle.dt * x[m]
            if x_try > tu.hi or x_try < tu.lo:
                car_fixed = True
                car_v = ((tu.hi if x_try > tu.hi else tu.lo) - rs.x_tu) / model.cycle.dt
                car_hit = abs(x[m])
                again = True
        for k in range(m):
            zone = wk.fz[k]  # the zone of this solution, before its row's check moves it
            if _row_consistent(model, wk, k, m, car, U):
                again = True
            if wk.shk[k] >= 0 and _shaft_consistent(model, st, wk, rs, p0, k, m, car, U,
                                                    zone):
                again = True
        if not again:
            break
    u_new = wk.sol[m] if car else rs.u_tu
    hold_f, f_brake, vsum, f_tot, p_tot, w_drv = _write_back(model, st, wk, rs, p0, m, car, U)
    _block_springs(model, st, p0, m, car, u_new)
    rs.U = U
    rs.u_known = have_u or km >= 0
    return u_new, car_hit, hold_f, f_brake, vsum, f_tot, p_tot, w_drv
