"""The slow, obvious numpy implementation of the kernel's equations (STYLE: a reference path
beside the numba kernel, tested against it).

Same model (:class:`~beltstudy.engine.dynamics.model.System`) and same scheme as
:mod:`beltstudy.engine.dynamics.kernel`, written for reading rather than speed, and sharing with it only
the scalar laws (:mod:`beltstudy.engine.dynamics.laws`, :mod:`beltstudy.engine.dynamics.profiles`):

* the resistance law with exact ``np.power``, every step (``resistance_rtol = 0``) or, as the
  kernel, expanded between exact evaluations (:mod:`beltstudy.engine.dynamics.linlaw`, the same windows
  and expansion points; :class:`ExpandedLaw`);
* the free elements and the springs as whole-array numpy operations;
* every implicit block (a pulley with the springs on both its sides, the elements at their
  far ends, the pulley shafts and the take-up carriage) as a dense matrix assembled from the
  momentum balances and solved with ``np.linalg.solve``, inside a plain loop over its active
  set: resistance zones, brakes and holdbacks holding or sliding, shafts sticking to the belt
  or slipping on it (capstan friction), torque limits, the carriage at an end stop; the speed
  loop's output ``U`` found by superposition of two solves.

The decision rules (thresholds, the order of the checks) are the kernel's, so both take the
same branches. Use it on small models and short times: a step costs milliseconds.
"""

from __future__ import annotations

import math
from types import SimpleNamespace

import numpy as np

from beltstudy.engine.dynamics import codes as C
from beltstudy.engine.dynamics.laws import brake_fraction, coupling_torque, motor_force
from beltstudy.engine.dynamics.linlaw import (
    BIG,
    PREDICT,
    element_windows,
    expansion,
    law_windows,
    x_cap,
)
from beltstudy.engine.dynamics.model import System, chord_strain
from beltstudy.engine.dynamics.passes import NEWTON_CURVE, NEWTON_MORE
from beltstudy.engine.dynamics.profiles import FORCE, TORQUE, start_reference, stop_reference

__all__ = ["ReferenceResult", "ExpandedLaw", "run_reference"]

#: Most passes over a block's active set in one step (as in the kernel).
ACTIVE_SET_PASSES = 24


class ReferenceResult(dict):
    """Final state and run quantities of :func:`run_reference`, SI units.

    Keys: ``v`` [m/s], ``te``, ``ts``, ``td``, ``tension`` [N] (elastic, strain, relaxing arm and total tension
    per spring), ``x_takeup`` [m], ``u_takeup`` [m/s], ``integrator`` [N], ``shaft_speed``
    [m/s], ``shaft_slip`` [-1, 0, 1], ``drive_force`` [N], ``t_max``, ``t_min`` [N]
    (per-spring envelopes of the whole cycle), ``steps``, ``t_end`` [s], ``status`` (0 ok,
    1 diverged, 2 the belt ran away), ``div_where`` (of a diverged run: -1 the belt, s >= 0
    shaft s, -2 - k drive k's motor), ``w_drive`` [J], ``start_ach``, ``stop_ach`` [s] (-1 not reached),
    ``slip_s`` [s] and ``slip_m`` [m] per drive (time slipping, belt length slipped),
    ``shaft_slip_s`` [s] and ``shaft_slip_m`` [m] the same per shaft,
    ``slack_s`` [s] (time with a slack span), ``t_trip`` and ``hold_set`` [s], ``law_evals``
    (exact evaluations of an element's law after the first, with the expanded law).
    """


# --------------------------------------------------------------------------------------
# laws of the belt


def _law(sys: System, v: np.ndarray, T: np.ndarray) -> np.ndarray:
    """Resistance magnitude per element before regularisation [N].

    ``R0_j = sum_k coef[k, j] |v_j|^pv[k] phi_j^ps[k]``, with ``phi_j`` the sag ratio over the
    reference from the element's mean tension (its two springs), capped at ``hs_cap``.
    """
    tm = 0.5 * (np.roll(T, 1) + T)
    phi = np.minimum(sys.sag_w_n / sys.hs_ref / np.maximum(tm, 1.0), sys.hs_cap / sys.hs_ref)
    av = np.abs(v)
    total = np.zeros(sys.n)
    for c, p, q in zip(sys.coef, sys.pv, sys.ps, strict=True):
        total += c * np.power(av, p) * np.power(phi, q)
    return total


class ExpandedLaw:
    """The resistance law as the kernel takes it with ``resistance_rtol > 0``
    (:mod:`beltstudy.engine.dynamics.linlaw`): each element's law evaluated exactly (``np.power``) when
    its speed or mean tension has left the window round its expansion point, and its
    second-order expansion about that point otherwise. Call with the state for R0 [N].

    The expansion point is the state moved by ``PREDICT`` of the window towards the side of
    the old window the state is on (where the speed is expanded and the sag ratio follows the
    tension; the old window starts at zero); the expansion and the windows are
    :func:`linlaw.expansion` and :func:`linlaw.element_windows`, as in the kernel's
    :func:`beltstudy.engine.dynamics.passes.law_refresh`.
    """

    def __init__(self, sys: System):
        self.sys = sys
        self.w = law_windows(sys.coef, sys.pv, sys.ps, sys.resistance_rtol)
        self.sw = sys.sag_w_n / sys.hs_ref
        self.hsm = sys.hs_cap / sys.hs_ref
        self.xc = x_cap(self.sw, self.hsm)
        self.du, self.d0, self.dx = element_windows(sys.coef, sys.pv, sys.ps, self.sw, self.hsm,
                                                    sys.v_eps, self.w)
        n = sys.n
        self.poly = np.zeros((6, n))
        self.bounds = np.zeros((4, n))  # u low, u high, T low, T high
        self.started = False
        self.evaluations = 0  # exact evaluations of an element's law after the first

    def __call__(self, v: np.ndarray, T: np.ndarray) -> np.ndarray:
        u = np.abs(v)
        tm = 0.5 * (np.roll(T, 1) + T)
        lo_u, hi_u, lo_t, hi_t = self.bounds
        if not self.started:
            out = np.ones(self.sys.n, dtype=bool)
            self.started = True
        else:
            out = (u < lo_u) | (u > hi_u) | (tm < lo_t) | (tm > hi_t)
            self.evaluations += int(out.sum())
        if out.any():
            self._evaluate(np.flatnonzero(out), u, tm)
        k, gu, guu, gx, gxx, gux = self.poly
        return k + u * (gu + guu * u + gux * tm) + tm * (gx + gxx * tm)

    def _evaluate(self, j, u, tm):
        sys = self.sys
        u, tm = u[j], tm[j]
        du, w0, dx, xc = self.du[j], self.d0[j], self.dx[j], self.xc[j]
        lo_u, hi_u, lo_t, hi_t = self.bounds[:, j]
        # the expansion point
        expand_u = (du < BIG) & (du * u >= w0)
        uc = np.where(expand_u, u + PREDICT * du * u * np.where(u >= 0.5 * (lo_u + hi_u), 1.0,
                                                                -1.0), u)
        uc = np.where(du * uc < w0, u, uc)
        follow_t = (dx < BIG) & (tm >= xc)
        tc = np.where(follow_t, np.maximum(
            tm + PREDICT * dx * tm * np.where(tm >= 0.5 * (lo_t + hi_t), 1.0, -1.0), xc), tm)
        # the exact law's terms there and the sums of the expansion
        phi = np.minimum(self.sw[j] / np.maximum(tc, 1.0), self.hsm[j])
        r, a, aa, b, bb, e = (np.zeros(len(j)) for _ in range(6))
        for c, p, q in zip(sys.coef[:, j], sys.pv, sys.ps, strict=True):
            t = c * np.power(uc, p) * np.power(phi, q)
            r += t
            a += p * t
            aa += p * (p - 1.0) * t
            b += q * t
            bb += q * (q + 1.0) * t
            e += p * q * t
        moving = du * uc >= w0
        uncapped = tc >= xc
        f32 = np.float32  # the kernel stores the expansion and the windows in float32
        self.poly[:, j] = f32(expansion(r, a, aa, b, bb, e, uc, tc, moving, uncapped))
        wu = np.where(moving, du * uc, w0)
        self.bounds[0, j] = f32(np.where(du >= BIG, -BIG, uc - wu))
        self.bounds[1, j] = f32(np.where(du >= BIG, BIG, uc + wu))
        self.bounds[2, j] = f32(np.where((dx >= BIG) | ~uncapped, -BIG,
                                         np.maximum(tc - dx * tc, xc)))
        self.bounds[3, j] = f32(np.where(dx >= BIG, BIG, np.where(uncapped, tc + dx * tc, xc)))


def _tangent(sys: System, te: np.ndarray, j=slice(None)) -> np.ndarray:
    """Ernst tangent modulus ``EB T^3 / (T^3 + a EB)`` of springs j [N], held at the floor
    tension below it."""
    t3 = np.maximum(te, sys.t_floor_n[j]) ** 3
    return sys.stiffness_n * t3 / (t3 + sys.a_ernst[j] * sys.stiffness_n)


def _damper(sys: System) -> tuple[float, float]:
    """The relaxing arm of the standard linear solid: (decay over a step, gain per unit tangent
    stiffness and strain increment), ``d' = e d + g kt de``; (0, 0) without an arm."""
    if sys.damping != "belt" or not sys.stiffness_dyn_n > sys.stiffness_n:
        return 0.0, 0.0
    h = sys.dt_s / sys.relaxation_s
    e = math.exp(-h)
    return e, (sys.stiffness_dyn_n - sys.stiffness_n) / sys.stiffness_n * (1.0 - e) / h


def _newton(sys, te, ts, j=slice(None)):
    """One Newton step of Ernst's chord law ``s(T) = T - a EB / (2 T^2)`` towards the strain
    tension ts from the elastic tension te (held at the floor below it) for springs j: (the
    step's tension, the tangent modulus [N] at its start, whether its estimated error,
    ``1.5 u r^3 |ds| / T`` of the increment with ``u = a EB / T^3``, ``r = 1 / (1 + u)``,
    exceeds ``NEWTON_CURVE``)."""
    tc = np.maximum(te, sys.t_floor_n[j])
    aeb = sys.a_ernst[j] * sys.stiffness_n
    kt = _tangent(sys, te, j)
    r = kt / sys.stiffness_n
    ds = ts - (tc - aeb / (2.0 * tc * tc))
    curve = 1.5 * (aeb / tc**3) * r**3 * np.abs(ds) / tc
    return tc + r * ds, kt, curve > NEWTON_CURVE


def _strain_rest(sys, te, ts, j=slice(None)):
    """Elastic tension of springs j at their strain before the increment (the constant part
    of the Newton step in :func:`_springs`) and their tangent modulus [N]."""
    e, kt, _ = _newton(sys, te, ts, j)
    return e, kt


def _springs(sys, te, ts, td, de, damp):
    """Every spring after the strain increment ``de`` [-]: (elastic, strain, arm, total)
    tension [N].

    Strain tension ``ts = EB eps`` (chord strain) integrates the increment exactly; elastic
    tension is its inverse under Ernst's chord law by a Newton step from the old tension, the
    larger of that and the floor line (the floor modulus below the floor tension, on into
    slack); springs whose step bends more than ``NEWTON_CURVE`` of the increment take
    ``NEWTON_MORE`` further steps. Slack (below the floor line's zero): no arm, no mesh
    viscosity. Arm: ``e d + g kt de``. Mesh viscosity ``alpha Z len / dt x de``. A belt never
    pushes.
    """
    e_damp, g_damp = damp
    eb = sys.stiffness_n
    s1 = ts + eb * de
    tfl = sys.t_floor_n
    sfl = eb * chord_strain(tfl, sys.a_ernst, eb, tfl, sys.k_floor_n)
    fl = tfl + (s1 - sfl) * sys.k_floor_n / eb
    e1, kt, more = _newton(sys, te, s1)
    e1 = np.maximum(e1, fl)
    for _ in range(NEWTON_MORE):
        e1 = np.where(more, np.maximum(_newton(sys, e1, s1)[0], fl), e1)
    taut = fl >= 0.0
    d1 = np.where(taut, e_damp * td + g_damp * kt * de, 0.0)
    visc = np.where(taut, _viscosity(sys) * de, 0.0)
    return e1, s1, d1, np.maximum(e1 + d1 + visc, 0.0)


def _viscosity(sys: System) -> np.ndarray:
    """Mesh viscosity per spring as tension per strain increment over a step [N]."""
    return sys.mesh_viscosity * sys.impedance_ns_m * sys.len_m / sys.dt_s


def _zone(x: float, v_eps: float) -> float:
    """Zone of the regularised resistance at speed x: -1, 0 (linear, ``|x| <= v_eps``) or +1."""
    return 1.0 if x > v_eps else (-1.0 if x < -v_eps else 0.0)


def _free_elements(sys, v, T, R0):
    """New velocity of every element as a free (explicit) one [m/s].

    ``M (v' - v) / dt = T_j - T_{j-1} - G_j - R0_j clip(v' / v_eps, -1, 1)``, the resistance
    implicit (solved in closed form); a negative resistance term is taken explicitly.
    """
    h = sys.dt_s / sys.mass_kg
    rp, rn = np.maximum(R0, 0.0), np.minimum(R0, 0.0)
    vs = v + h * (T - np.roll(T, 1) - sys.gravity_n - rn * np.clip(v / sys.v_eps, -1.0, 1.0))
    e = h * rp
    return np.where(np.abs(vs) <= sys.v_eps + e, vs * (sys.v_eps / (sys.v_eps + e)),
                    vs - np.copysign(e, vs))


def _coulomb(p, dd, fb, hb):
    """Velocity of a mass under ``dd v = p - fb sign(v)`` (a brake holding when ``|p| <= fb``),
    never below zero with a holdback."""
    if fb > 0.0:
        v = 0.0 if abs(p) <= fb else (p - math.copysign(fb, p)) / dd
    else:
        v = p / dd
    return 0.0 if hb and v < 0.0 else v


# --------------------------------------------------------------------------------------
# phase: brakes and drive laws


def _brake_forces(sys, brk, sh, t, t_stopcmd, stopping, stopped, t_stopped):
    """Command, release and force of every brake, summed per shaft into ``sh.fb`` [N].

    A brake stop commands every brake at the stop command; a holding brake is commanded when
    the belt has stopped and stays set, others are released then. Returns the time the last
    holding brake is fully set, or -1 while one is not (or there is none).
    """
    sh.fb[:] = 0.0
    latest, pending = -1.0, False
    for b in range(len(sys.brake_shaft)):
        hold = sys.brake_hold[b] == 1
        ct, cf, nc = brk.curve[b]
        if stopping and brk.t_cmd[b] < 0.0 and not brk.released[b]:
            if sys.stop_mode == C.BRAKE:
                brk.t_cmd[b] = t_stopcmd
            elif hold and stopped:
                brk.t_cmd[b] = t_stopped
        if not hold and stopped and brk.t_cmd[b] >= 0.0:
            brk.released[b] = True
        if brk.t_cmd[b] >= 0.0 and not brk.released[b]:
            tau = t - brk.t_cmd[b] - sys.brake_delay_s[b]
            sh.fb[sys.brake_shaft[b]] += sys.brake_force_n[b] * brake_fraction(
                tau, sys.brake_ramp_s[b], ct, cf, nc)
        if hold:
            if brk.t_cmd[b] < 0.0:
                pending = True
            else:
                full = ct[nc - 1] if nc > 0 else sys.brake_ramp_s[b]
                latest = max(latest, brk.t_cmd[b] + sys.brake_delay_s[b] + full)
    if not sys.brake_hold.any() or pending or t < latest:
        return -1.0
    return latest


def _drive_laws(sys, dr, sh, phase, t, t_trip, stopping, first_off):
    """Each drive's force law for the step, in ``dr.mode``: 0 a force ``f0 + f1 v`` linear in
    its shaft speed (held at rest: zero; dol: the motor curve, through the fluid coupling with
    the motor's own inertia eliminated; power off: the force at the trip decaying over the
    trip time; open-loop start), 1 its share of the speed loop's output, 2 the shaft speed
    imposed (moving support). ``first_off``: the first step with the power off."""
    dt, v_d = sys.dt_s, sys.v_design
    for k in range(len(sys.drive_share)):
        dr.sat[k] = False
        dr.lim[k] = sys.drive_limit_n[k]
        dr.lin[k] = None
        vs = sh.vs[sys.drive_shaft[k]]
        fac = 1.0
        if phase == C.OFF:
            if first_off:
                dr.f_trip[k] = dr.force[k]
            ts = sys.drive_trip_s[k]
            fac = 0.0 if ts <= 0.0 else max(0.0, 1.0 - (t - t_trip) / ts)
        dr.mode[k], dr.f0[k], dr.f1[k] = 0, 0.0, 0.0
        if phase == C.HOLD:
            continue
        if sys.drive_control[k] == C.DOL:
            rated = sys.drive_rated_n[k]
            cx, cy, cn = dr.curve[k]
            if sys.drive_coupling[k] == C.COUPLING_NONE:
                f, df = motor_force(cx, cy, cn, rated, v_d, vs)
                f1 = min(df * fac, 0.0)
                dr.f0[k], dr.f1[k] = f * fac - f1 * vs, f1
                continue
            # motor (mass mm, force a0 + a1 vm) -> coupling (c0 + cm vm + cs vs) -> shaft:
            # the motor's new speed eliminated, vm' = (p - cs vs') / den
            vm = dr.vm[k]
            fm, dfm = motor_force(cx, cy, cn, rated, v_d, vm)
            a1 = min(dfm * fac, 0.0)
            a0 = fm * fac - a1 * vm
            fill = 1.0
            if sys.drive_coupling[k] == C.COUPLING_FILL:
                fill = min(max((t - sys.pre_rest_s) / sys.drive_fill_s[k], 0.0), 1.0)
            tc, dtm, dts = coupling_torque(rated, v_d, vm, vs, fill)
            cm, cs = max(dtm, 0.0), min(dts, 0.0)
            c0 = tc - cm * vm - cs * vs
            mm = max(sys.drive_motor_mass_kg[k], 1.0) / dt
            den = mm - a1 + cm
            p = mm * vm + a0 - c0
            dr.f0[k], dr.f1[k] = c0 + cm * p / den, cs * (mm - a1) / den
            dr.lin[k] = (p, den, cs)
        elif phase == C.OFF:
            dr.f0[k] = dr.f_trip[k] * fac
        elif sys.formulation == C.SUPPORT:
            dr.mode[k] = 2
        elif sys.start_control == FORCE and not stopping:
            dr.f0[k] = sys.drive_share[k] * sys.force_start_n
        else:
            dr.mode[k] = 1


# --------------------------------------------------------------------------------------
# implicit blocks


def _share_force(sys, dr, k, U):
    """Drive k's share of the speed loop's output within its force limit [N] (a drive found
    beyond it is saturated for the rest of the step)."""
    f = sys.drive_share[k] * U
    if abs(f) > dr.lim[k]:
        dr.sat[k] = True
        dr.f0[k] = math.copysign(dr.lim[k], f)
        return dr.f0[k]
    return f


def _saturate_master(sys, dr, U):
    """The speed loop's output ``U`` within the master drive's limit (``share x U``)."""
    k = sys.master
    if abs(sys.drive_share[k] * U) > dr.lim[k]:
        dr.sat[k] = True
        dr.f0[k] = math.copysign(dr.lim[k], sys.drive_share[k] * U)
        return dr.f0[k] / sys.drive_share[k]
    return U


def _shaft_drive_force(sys, dr, k, U):
    """Force of drive k on its shaft with the loop output U (mode 0 without its speed part)."""
    if dr.mode[k] == 1:
        return dr.f0[k] if dr.sat[k] else sys.drive_share[k] * U
    return dr.f0[k]


def _block_step(sys, blk, ctx, st, sh, dr, R0, U, u_known):
    """Velocities of one implicit block at the end of the step.

    Unknowns: the block's element velocities (and the carriage's speed). Each element row is
    its momentum balance over the step, ``M (x - v) / dt = T_right - T_left - R - G + F``, with
    the block's springs at the new step, ``T = A + B (x_{k+1} - x_k (+ x_car))`` (their tangent
    stiffness, arm and viscosity), the outer springs at the step start, the resistance in its
    zone (linear below ``v_eps``), a sticking shaft's mass and forces (drive, sliding brake)
    added to its element, a slipping shaft's sliding force ``ck T_slack`` added to the slack
    side. Rows held at a speed (the element holding the belt at rest, an imposed shaft speed,
    a brake or holdback holding) are identities. The active set is updated from the solution
    until consistent. Updates ``st.v``, the shafts, the drives; returns ``(U, U known,
    carriage speed, carriage speed at an end stop or -1, holding force or nan, drive work)``.
    """
    n, dt, v_eps, e_damp, g_damp = sys.n, sys.dt_s, sys.v_eps, *ctx.damp
    nodes = np.asarray(blk)
    m = len(nodes)
    car = sys.takeup_gravity and sys.i_takeup in blk
    mu = m + 1 if car else m
    # linearised block springs (spring nodes[k] joins nodes[k] and nodes[k + 1])
    sj = nodes[:-1]
    taut = st.te[sj] >= 0.0
    er, kt = _strain_rest(sys, st.te[sj], st.ts[sj], sj)
    sA = np.where(taut, er + e_damp * st.td[sj], 0.0)
    sB = np.where(taut, (kt * (1.0 + g_damp) + ctx.visc[sj])
                  * dt / sys.len_m[sj], 0.0)
    cj = sys.carriage_coupling[sj] if car else np.zeros(m - 1)
    t_in, t_out = st.tt[(nodes[0] - 1) % n], st.tt[nodes[-1]]
    vo = st.v[nodes].copy()
    mass = sys.mass_kg[nodes]
    rpos = np.maximum(R0[nodes], 0.0)
    fexp = -np.minimum(R0[nodes], 0.0) * np.clip(vo / v_eps, -1.0, 1.0) - sys.gravity_n[nodes]
    zone = np.array([_zone(x, v_eps) for x in vo])
    shaft = ctx.node_shaft[nodes]
    fixed = nodes == ctx.hold_node
    fixv = np.zeros(m)
    stuck = np.zeros(m, dtype=bool)
    bforce, c_lo, c_hi = np.zeros(m), np.zeros(m), np.zeros(m)
    bdir = np.where(vo >= 0.0, 1.0, -1.0)
    vsn = np.zeros(m)
    km = -1

    def brake_row(k, v_was):
        """A brake and/or holdback on element k's sticking shaft: the reaction range of a stick,
        tried when the element moves slower than v_eps (or backwards onto a holdback)."""
        s = shaft[k]
        fb, hb = sh.fb[s], sys.shaft_holdback[s] == 1
        bforce[k], c_lo[k], c_hi[k] = fb, -fb, (1e300 if hb else fb)
        stuck[k] = (fb > 0.0 or hb) and (abs(v_was) <= v_eps or (hb and v_was < 0.0))

    for k in range(m):
        s = shaft[k]
        if s >= 0:
            if sh.slip[s] == 0.0:
                brake_row(k, vo[k])
            if sys.shaft_drive[s] == sys.master:
                km = k

    def side_tensions(x, k):
        """Tensions of the springs left and right of block element k at the solution [N]."""
        tl = t_in if k == 0 else sA[k - 1] + sB[k - 1] * (x[k] - x[k - 1] + cj[k - 1] * x[-1])
        tr = t_out if k == m - 1 else sA[k] + sB[k] * (x[k + 1] - x[k] + cj[k] * x[-1])
        return tl, tr

    def belt_force(x, k, tl, tr):
        """Force the pulley passes to belt element k: its momentum balance's remainder [N]."""
        rk = rpos[k] * (x[k] / v_eps if zone[k] == 0.0 else zone[k])
        return mass[k] / dt * (x[k] - vo[k]) - (tr - tl) + rk - fexp[k]

    car_fixed, car_v, car_hit = False, 0.0, -1.0
    for _ in range(ACTIVE_SET_PASSES):
        # ---- the speed loop's output: known, from a held or slipping master, or unknown
        two = False
        if km >= 0 and not u_known and dr.mode[sys.master] == 1 and not dr.sat[sys.master]:
            s = shaft[km]
            if sh.slip[s] != 0.0:
                # the slipping master's shaft predicted with the slack side at the step start
                sl = sh.slip[s]
                ts = st.tt[nodes[km]] if sl > 0.0 else st.tt[(nodes[km] - 1) % n]
                ms, share = sys.shaft_mass_kg[s] / dt, sys.drive_share[sys.master]
                ck = sys.shaft_euler_kinetic[s] - 1.0
                vp = (ms * sh.vs[s] + share * ctx.f0u - sl * ck * ts) / (ms - share * ctx.f1u)
                U = _saturate_master(sys, dr, ctx.f0u + ctx.f1u * vp)
            elif fixed[km] or stuck[km]:
                U = _saturate_master(sys, dr, ctx.f0u + ctx.f1u * fixv[km])
            else:
                two = True
        # ---- momentum balances: A x = b + U bu
        A = np.zeros((mu, mu))
        b = np.zeros(mu)
        bu = np.zeros(mu)
        ml, mr = np.ones(m), np.ones(m)
        for k in range(m):
            A[k, k] += mass[k] / dt
            b[k] += mass[k] / dt * vo[k] + fexp[k]
            s = shaft[k]
            if s >= 0 and sh.slip[s] != 0.0:
                # the sliding force ck T_slack on the side the slip unloads
                ck = sys.shaft_euler_kinetic[s] - 1.0
                if sh.slip[s] > 0.0:
                    mr[k] += ck
                else:
                    ml[k] += ck
            elif s >= 0:
                ms = sys.shaft_mass_kg[s] / dt
                A[k, k] += ms
                b[k] += ms * sh.vs[s]
                d = sys.shaft_drive[s]
                if d >= 0 and dr.mode[d] == 2:
                    if not fixed[k]:
                        fixed[k], fixv[k] = True, ctx.v_ref
                elif d >= 0 and dr.mode[d] == 1:
                    if dr.sat[d]:
                        b[k] += dr.f0[d]
                    elif two:
                        bu[k] += sys.drive_share[d]
                    else:
                        b[k] += _share_force(sys, dr, d, U)
                elif d >= 0:
                    A[k, k] -= dr.f1[d]
                    b[k] += dr.f0[d]
            if zone[k] == 0.0:
                A[k, k] += rpos[k] / v_eps
            else:
                b[k] -= zone[k] * rpos[k]
            if bforce[k] > 0.0 and not stuck[k]:
                b[k] -= bdir[k] * bforce[k]
        b[0] -= ml[0] * t_in
        b[m - 1] += mr[m - 1] * t_out
        for i in range(m - 1):
            # spring i pulls element i forward, element i + 1 back, the carriage back
            for row, f in ((i, mr[i]), (i + 1, -ml[i + 1]), (m, -1.0 if cj[i] else 0.0)):
                if f != 0.0:
                    A[row, i] += f * sB[i]
                    A[row, i + 1] -= f * sB[i]
                    if car:
                        A[row, m] -= f * sB[i] * cj[i]
                    b[row] += f * sA[i]
        if car:
            A[m, m] += sys.takeup_inertia_kg / dt
            b[m] += sys.takeup_inertia_kg / dt * ctx.u_tu + sys.takeup_weight_n
        # rows held at a speed
        Ah, bh, buh = A.copy(), b.copy(), bu.copy()
        for k in np.flatnonzero(fixed | stuck):
            Ah[k] = 0.0
            Ah[k, k] = 1.0
            bh[k] = fixv[k] if fixed[k] else 0.0
            buh[k] = 0.0
        if car and car_fixed:
            Ah[m] = 0.0
            Ah[m, m] = 1.0
            bh[m], buh[m] = car_v, 0.0
        if two:
            # U = f0u + f1u x_master with x = x0 + U xu: two solves
            x0, xu = np.linalg.solve(Ah, np.column_stack([bh, buh])).T
            U = _saturate_master(sys, dr, (ctx.f0u + ctx.f1u * x0[km])
                                 / (1.0 - ctx.f1u * xu[km]))
            x = x0 + U * xu
        else:
            x = np.linalg.solve(Ah, bh)

        # ---- consistency of the active set with the solution
        again = False
        if car and not car_fixed:
            x_try = ctx.x_tu + dt * x[m]
            if x_try > sys.takeup_hi_m or x_try < sys.takeup_lo_m:
                car_fixed, again = True, True
                car_v = ((sys.takeup_hi_m if x_try > sys.takeup_hi_m else sys.takeup_lo_m)
                         - ctx.x_tu) / dt
                car_hit = abs(x[m])
        for k in range(m):
            s = shaft[k]
            d = sys.shaft_drive[s] if s >= 0 else -1
            if d >= 0 and d != sys.master and dr.mode[d] == 1 and not dr.sat[d]:
                f = sys.drive_share[d] * U
                if abs(f) > dr.lim[d]:
                    dr.sat[d], dr.f0[d], again = True, math.copysign(dr.lim[d], f), True
            if fixed[k]:
                zone[k] = _zone(fixv[k], v_eps)
            else:
                if stuck[k]:
                    # the reaction the brake or holdback must give to hold the element
                    react = A[k] @ x - b[k] - (U * bu[k] if two else 0.0)
                    if not c_lo[k] <= react <= c_hi[k]:
                        stuck[k], again = False, True
                        bdir[k] = -1.0 if react > c_hi[k] else 1.0
                elif c_hi[k] > 1e299 and x[k] < 0.0:
                    stuck[k], again = True, True  # the holdback engages
                elif bforce[k] > 0.0 and x[k] * bdir[k] < 0.0:
                    stuck[k], again = True, True  # the brake stops the element
                z = 0.0 if stuck[k] else _zone(x[k], v_eps)
                if z != zone[k]:
                    zone[k], again = z, True
            if s < 0:
                continue
            tl, tr = side_tensions(x, k)
            sl = sh.slip[s]
            if sl == 0.0:
                if nodes[k] == ctx.hold_node or sys.shaft_euler[s] < 1.0:
                    continue  # holding the belt at rest, or slip switched off (verification)
                # capstan: what the pulley passes within T_slack (e^(mu theta) - 1)
                ft = belt_force(x, k, tl, tr)
                cap = (sys.shaft_euler[s] - 1.0) * max(min(tl, tr), 0.0)
                if abs(ft) > cap * (1.0 + 1e-9) + 1e-9:
                    sh.slip[s] = 1.0 if ft > 0.0 else -1.0
                    stuck[k], bforce[k], c_lo[k], c_hi[k] = False, 0.0, 0.0, 0.0
                    fixed[k] = False  # an imposed speed now holds the shaft, not the belt
                    again = True
            else:
                vsn[k] = _shaft_speed(sys, ctx, sh, dr, s, U, sl * max(tr if sl > 0 else tl, 0))
                if sl * (vsn[k] - x[k]) <= 0.0:
                    sh.slip[s] = 0.0  # the speeds crossed: the shaft sticks again
                    brake_row(k, vo[k])
                    again = True
        if not again:
            break

    # ---- write back: velocities, shafts, drive forces and work
    st.v[nodes] = x[:m]
    hold_f = math.nan
    w_drive = 0.0
    for k in np.flatnonzero(shaft >= 0):
        s = shaft[k]
        tl, tr = side_tensions(x, k)
        vs_old, sl = sh.vs[s], sh.slip[s]
        if sl == 0.0:
            vs_new, ft = x[k], belt_force(x, k, tl, tr)
        else:
            vs_new = vsn[k]
            ft = sl * (sys.shaft_euler_kinetic[s] - 1.0) * max(tr if sl > 0.0 else tl, 0.0)
        if nodes[k] == ctx.hold_node:
            hold_f = ft
        sh.vs[s] = vs_new
        d = sys.shaft_drive[s]
        if d < 0:
            continue
        inertia = sys.shaft_mass_kg[s] / dt * (vs_new - vs_old)
        if dr.mode[d] == 2:
            f = ft + inertia
        elif dr.mode[d] == 1:
            f = _shaft_drive_force(sys, dr, d, U)
            if sl != 0.0 and d != sys.master:
                # a follower in its speed window gives what holds its shaft there
                f = min(f, inertia + ft) if f > 0.0 else max(f, inertia + ft)
        else:
            f = dr.f0[d] + dr.f1[d] * vs_new
        if dr.lin[d] is not None:
            p, den, cs = dr.lin[d]
            dr.vm[d] = (p - cs * vs_new) / den
        dr.force[d], dr.ft[d] = f, ft
        w_drive += f * 0.5 * (vs_old + vs_new) * dt
    u_new = x[m] if car else ctx.u_tu
    return U, u_known or km >= 0, u_new, car_hit, hold_f, w_drive


def _shaft_speed(sys, ctx, sh, dr, s, U, f_slide):
    """New speed of slipping shaft s [m/s]: its inertia under its drive and brake less the
    sliding force ``ck T_slack`` (``f_slide = slip x T_slack``); an imposed speed holds it at
    the reference, a torque follower stays within its speed window."""
    ms = sys.shaft_mass_kg[s] / sys.dt_s
    f = -(sys.shaft_euler_kinetic[s] - 1.0) * f_slide
    dd = ms
    d = sys.shaft_drive[s]
    if d >= 0:
        if dr.mode[d] == 2:
            return ctx.v_ref
        f += _shaft_drive_force(sys, dr, d, U)
        if dr.mode[d] == 0:
            dd -= dr.f1[d]
    v = _coulomb(ms * sh.vs[s] + f, dd, sh.fb[s], sys.shaft_holdback[s] == 1)
    if d >= 0 and dr.mode[d] == 1 and d != sys.master:
        v = min(max(v, ctx.v_ref - ctx.window), ctx.v_ref + ctx.window)
    return v


# --------------------------------------------------------------------------------------
# the cycle


def _curve(points) -> tuple[np.ndarray, np.ndarray, int]:
    """A list of (x, y) points as the scalar laws take it: x array, y array, point count."""
    pts = np.array(list(points) or [(0.0, 0.0)], dtype=np.float64)
    return pts[:, 0].copy(), pts[:, 1].copy(), len(points)


def run_reference(sys: System, t_end_s: float | None = None) -> ReferenceResult:
    """Integrate the whole cycle (rest, start, run, stop, rest) with numpy.

    Parameters
    ----------
    sys : System
        The model (:func:`beltstudy.engine.dynamics.model.build_system`); not changed.
    t_end_s : float, optional
        End the run at this time [s] instead of after the stop.

    Returns
    -------
    ReferenceResult
        The final state and the run quantities (see :class:`ReferenceResult`).
    """
    n, dt, v_d = sys.n, sys.dt_s, sys.v_design
    t_pre, t_start = sys.pre_rest_s, sys.start_s
    t_stopcmd = t_pre + t_start + sys.run_s
    vfd = sys.drive_control[0] == C.VFD
    support = sys.formulation == C.SUPPORT
    nd, ns = len(sys.drive_share), len(sys.shaft_node)
    f_res = sys.te_n - float(sys.gravity_n.sum())
    damp, visc = _damper(sys), _viscosity(sys)
    law = ExpandedLaw(sys) if law_windows(sys.coef, sys.pv, sys.ps,
                                          sys.resistance_rtol) is not None else None
    free = np.ones(n, dtype=bool)
    for blk in sys.blocks:
        free[blk] = False
    m_node = int(sys.drive_node[sys.master])
    blocks = sorted(sys.blocks, key=lambda b: 0 if m_node in b else 1)  # master's first
    node_shaft = np.full(n, -1)
    node_shaft[sys.shaft_node] = np.arange(ns)

    te = np.maximum(sys.tension_rest_n, 0.0)
    ts = sys.stiffness_n * chord_strain(te, sys.a_ernst, sys.stiffness_n, sys.t_floor_n,
                                        sys.k_floor_n)
    st = SimpleNamespace(v=np.zeros(n), te=te.copy(), ts=ts, td=np.zeros(n), tt=te.copy())
    sh = SimpleNamespace(vs=np.zeros(ns), slip=np.zeros(ns), fb=np.zeros(ns))
    dr = SimpleNamespace(mode=[0] * nd, f0=np.zeros(nd), f1=np.zeros(nd), sat=[False] * nd,
                         lim=np.zeros(nd), lin=[None] * nd, vm=np.zeros(nd),
                         force=np.zeros(nd), ft=np.zeros(nd), f_trip=np.zeros(nd),
                         curve=[_curve(c) for c in sys.drive_curves])
    brk = SimpleNamespace(t_cmd=np.full(len(sys.brake_shaft), -1.0),
                          released=np.zeros(len(sys.brake_shaft), dtype=bool),
                          curve=[_curve(c) for c in sys.brake_curves])
    x_tu, u_tu, integ, hold_f = 0.0, 0.0, 0.0, sys.hold_force_n
    t_max, t_min = st.tt.copy(), st.tt.copy()
    slip_s, slip_m = np.zeros(nd), np.zeros(nd)
    shaft_slip_s, shaft_slip_m = np.zeros(ns), np.zeros(ns)
    w_drive, slack_s = 0.0, 0.0
    start_ach = stop_ach = t_stopped = t_trip = hold_set = -1.0
    stopped = pi_started = was_off = False
    status, div_where = C.OK, 0
    v_fail = C.V_FAIL_FACTOR * v_d
    t_limit = t_stopcmd + sys.stop_max_s + sys.post_rest_s
    if t_end_s:
        t_limit = min(t_limit, float(t_end_s))
    max_steps = int(t_limit / dt) + 2
    step, t_new = 0, 0.0
    while step < max_steps:
        step += 1
        t_new = step * dt
        # ---- phase: reference, what the drives do, brakes, drive laws, speed loop
        started, stopping = t_new > t_pre, t_new > t_stopcmd
        a_ref = 0.0
        if not stopping:
            v_ref, a_ref = start_reference(sys.start_control, t_new - t_pre, t_start, v_d)
        elif sys.stop_mode == C.CONTROLLED:
            v_ref, a_ref = stop_reference(t_new - t_stopcmd, sys.stop_s, v_d)
        else:
            v_ref = 0.0
        if stopping and t_trip < 0.0:
            if sys.stop_mode != C.CONTROLLED:
                t_trip = t_stopcmd  # coast and brake stops: the power is cut
            elif hold_set >= 0.0:
                t_trip = hold_set  # a controlled stop: off once the holding brakes are set
        phase = C.HOLD if not started else (C.OFF if 0.0 <= t_trip < t_new else C.RUN)
        hold_set = _brake_forces(sys, brk, sh, t_new, t_stopcmd, stopping, stopped, t_stopped)
        _drive_laws(sys, dr, sh, phase, t_new, t_trip, stopping, phase == C.OFF and not was_off)
        was_off = phase == C.OFF
        pi = phase == C.RUN and vfd and not support and (sys.start_control != FORCE
                                                          or stopping)
        if pi and not pi_started:
            integ, pi_started = hold_f, True
        if sys.start_control == TORQUE and not stopping and phase == C.RUN:
            ramp = min(max((t_new - t_pre) / t_start, 0.0), 1.0)
            dr.lim[:] = sys.drive_limit_n * ramp + sys.drive_share * abs(hold_f) * (1.0 - ramp)
        # speed loop output U = f0u + f1u v_master: rigid-body feedforward, integrator, gain
        f_ff = sys.total_mass_kg * a_ref + f_res * min(max(v_ref / sys.v_ff_m_s, 0.0), 1.0)
        ctx = SimpleNamespace(damp=damp, visc=visc, node_shaft=node_shaft, v_ref=v_ref,
                              window=C.SPEED_WINDOW * v_d, f0u=f_ff + integ + sys.kp * v_ref,
                              f1u=-sys.kp, hold_node=sys.hold_node if phase == C.HOLD else -1,
                              x_tu=x_tu, u_tu=u_tu)

        # ---- free elements, then the blocks
        R0 = law(st.v, st.tt) if law is not None else _law(sys, st.v, st.tt)
        v_free = _free_elements(sys, st.v, st.tt, R0)
        st.v[free] = v_free[free]
        U, u_known, u_new = 0.0, not pi, u_tu
        for blk in blocks:
            U, u_known, u_b, hit, hf, w = _block_step(sys, blk, ctx, st, sh, dr, R0, U,
                                                      u_known)
            if sys.takeup_gravity and sys.i_takeup in blk:
                u_new = u_b
            if not math.isnan(hf):
                hold_f = hf
            w_drive += w
        if pi:
            e_v = v_ref - sh.vs[sys.drive_shaft[sys.master]]
            if not dr.sat[sys.master] or e_v * dr.f0[sys.master] < 0.0:
                integ += dt * sys.ki * e_v  # not further into the torque limit
        if sys.takeup_gravity:
            u_tu = u_new
            x_tu = min(max(x_tu + dt * u_tu, sys.takeup_lo_m), sys.takeup_hi_m)

        # ---- springs from the new velocities (the carriage lengthens its two springs)
        de = (np.roll(st.v, -1) - st.v + sys.carriage_coupling * u_tu) * dt / sys.len_m
        st.te, st.ts, st.td, st.tt = _springs(sys, st.te, st.ts, st.td, de, damp)

        # ---- observe
        t_max, t_min = np.fmax(t_max, st.tt), np.fmin(t_min, st.tt)
        if not np.isfinite(st.v).all() or np.abs(st.v).max() > v_fail:
            status, div_where = C.DIVERGED, -1
            break
        bad_shaft = ~(np.abs(sh.vs) <= v_fail)  # also NaN
        bad_motor = ~(np.abs(dr.vm) <= v_fail)
        if bad_shaft.any() or bad_motor.any():
            status = C.DIVERGED
            div_where = (-2 - int(np.flatnonzero(bad_motor)[-1]) if bad_motor.any()
                         else int(np.flatnonzero(bad_shaft)[-1]))
            break
        v_mean = float(sys.belt_mass_kg @ st.v) / float(sys.belt_mass_kg.sum())
        if abs(v_mean) > C.RUNAWAY_FACTOR * v_d:
            status = C.RUNAWAY  # the belt could not be held: a physical result
            break
        if started:
            slipping = sh.slip != 0.0
            shaft_slip_s += np.where(slipping, dt, 0.0)
            shaft_slip_m += np.where(slipping, np.abs(sh.vs - st.v[sys.shaft_node]) * dt, 0.0)
            for k in range(nd):
                s = sys.drive_shaft[k]
                if sh.slip[s] != 0.0:
                    slip_s[k] += dt
                    slip_m[k] += abs(sh.vs[s] - st.v[sys.shaft_node[s]]) * dt
            if start_ach < 0.0 and v_mean >= 0.99 * v_d:
                start_ach = t_new - t_pre
            if st.tt.min() <= 0.0:
                slack_s += dt
        if stopping and stop_ach < 0.0 and v_mean < 0.01 * v_d:
            stop_ach = t_new - t_stopcmd
        if stopping and not stopped and v_mean < 0.01 * v_d and (
                sys.stop_mode != C.CONTROLLED or t_new >= t_stopcmd + sys.stop_s):
            stopped, t_stopped = True, t_new
            t_limit = min(t_limit, t_new + sys.post_rest_s)
        if t_new >= t_limit:
            break
    return ReferenceResult(
        v=st.v, te=st.te, ts=st.ts, td=st.td, tension=st.tt, x_takeup=x_tu, u_takeup=u_tu,
        integrator=integ, shaft_speed=sh.vs, shaft_slip=sh.slip, drive_force=dr.force,
        t_max=t_max, t_min=t_min, steps=step, t_end=t_new, status=status, w_drive=w_drive,
        start_ach=start_ach, stop_ach=stop_ach, slip_s=slip_s, slip_m=slip_m,
        shaft_slip_s=shaft_slip_s, shaft_slip_m=shaft_slip_m, slack_s=slack_s, t_trip=t_trip,
        hold_set=hold_set, law_evals=law.evaluations if law is not None else 0,
        div_where=div_where)
