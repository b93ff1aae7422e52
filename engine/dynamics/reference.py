"""The slow, obvious numpy implementation of the kernel's equations (STYLE: a reference path
beside the numba kernel, tested against it).

Same model (the records of :class:`~beltstudy.engine.dynamics.model.System`, ``sys.model``:
:mod:`beltstudy.engine.dynamics.records`) and same scheme as
:mod:`beltstudy.engine.dynamics.kernel`, written for reading rather than speed, and sharing with
it only the scalar laws (:mod:`beltstudy.engine.dynamics.laws`,
:mod:`beltstudy.engine.dynamics.profiles`, the brakes' force law in
:mod:`beltstudy.engine.dynamics.brakes`). It reads the records' physical quantities (lengths,
masses, stiffness, viscosity, Ernst's sag term) and computes from them what the kernel keeps in
per-step forms (``dt / len``, ``dt / mass``, ``a EB``, the arm's decay and gain):

* the resistance law with exact ``np.power``, every step (``Law.rtol = 0``) or, as the
  kernel, expanded between exact evaluations (:mod:`beltstudy.engine.dynamics.linlaw`, the same
  windows and expansion points; :class:`ExpandedLaw`);
* the free elements and the springs as whole-array numpy operations;
* every implicit block (a pulley with the springs on both its sides, the elements at their
  far ends, the pulley shafts and the take-up carriage) as a dense matrix assembled from the
  momentum balances and solved with ``np.linalg.solve``, inside a plain loop over its active
  set: resistance zones, brakes and holdbacks holding or sliding, shafts sticking to the belt
  or slipping on it (capstan friction), torque limits, the carriage at an end stop; the speed
  loop's output ``U`` found by superposition of two solves.

One step is the kernel's sequence of phases, each a function of the same name
(:func:`_phase` with :func:`_brake_forces` and :func:`_drive_laws`, :func:`_resistances`,
:func:`_free_elements`, :func:`_blocks` with :func:`_block_step`, :func:`_spring_step`,
:func:`_observe`, :func:`_switches`), over the belt state, the shafts', drives' and brakes'
state and a run record of the step's scalars (``rs``, the kernel's
:data:`~beltstudy.engine.dynamics.records.RUN`); the kernel's block functions have their
counterparts here (:func:`_block_setup`, :func:`_master_output`, :func:`_block_rows`,
:func:`_block_solution`, :func:`_row_consistent`, :func:`_shaft_consistent`,
:func:`_write_back`). The decision rules (thresholds, the order of the checks) are the
kernel's, so both take the same branches. Use it on small models and short times: a step costs
milliseconds.
"""

from __future__ import annotations

import math
from types import SimpleNamespace

import numpy as np

from beltstudy.engine.dynamics import codes as C
from beltstudy.engine.dynamics.brakes import brake_force, set_at
from beltstudy.engine.dynamics.laws import coupling_torque, motor_force
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
from beltstudy.engine.dynamics.records import Law, Model, Nodes, Springs

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
    ``stop_dist`` [m] (the belt's travel from the stop command until the stop is achieved),
    ``slip_s`` [s] and ``slip_m`` [m] per drive (time slipping, belt length slipped),
    ``shaft_slip_s`` [s] and ``shaft_slip_m`` [m] the same per shaft,
    ``slack_s`` [s] (time with a slack span), ``t_trip`` and ``hold_set`` [s], ``law_evals``
    (exact evaluations of an element's law after the first, with the expanded law),
    ``verr_max`` [m/s] and ``verr_t`` [s] (the master's largest tracking error after the first
    wave loop time of the start, and when), ``vmean_hi`` [m/s] and ``vmean_hi_t`` [s] (the
    highest mean belt speed before the stop command), ``takeup_travel_start`` and
    ``takeup_travel_stop`` [m] (the carriage's range in each phase), ``over_s``, ``over_stop_s``
    and ``lim_s`` [s] per drive (time with |force| above the rated force, the part of it after
    the stop command, time at the torque limit),
    ``f2_int`` [N^2 s] and ``rms_s`` [s] per drive (the force squared integrated from the start
    command until the belt is at rest after the stop, and that time), ``f_brake`` and ``f_hb``
    [N] (the last step's brake and holdback forces), ``fbr_max`` and ``fhb_max`` [N] (their
    largest over the run).
    """


# --------------------------------------------------------------------------------------
# laws of the belt


def _law(law: Law, nodes: Nodes, v: np.ndarray, T: np.ndarray) -> np.ndarray:
    """Resistance magnitude per element before regularisation [N].

    ``R0_j = sum_k coef[k, j] |v_j|^pv[k] phi_j^ps[k]``, with ``phi_j`` the sag ratio over the
    reference from the element's mean tension (its two springs), capped at ``hs_cap``.
    """
    tm = 0.5 * (np.roll(T, 1) + T)
    phi = np.minimum(nodes.sag_w / law.hs_ref / np.maximum(tm, 1.0), nodes.hs_cap / law.hs_ref)
    av = np.abs(v)
    total = np.zeros(len(v))
    for c, p, q in zip(law.coef, law.pvv, law.psv, strict=True):
        total += c * np.power(av, p) * np.power(phi, q)
    return total


class ExpandedLaw:
    """The resistance law as the kernel takes it with ``Law.rtol > 0``
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
        model = sys.model
        law, nodes = model.law, model.nodes
        self.law = law
        self.w = law_windows(law.coef, law.pvv, law.psv, law.rtol)
        self.sw = nodes.sag_w / law.hs_ref
        self.hsm = nodes.hs_cap / law.hs_ref
        self.xc = x_cap(self.sw, self.hsm)
        self.du, self.d0, self.dx = element_windows(law.coef, law.pvv, law.psv, self.sw,
                                                    self.hsm, model.cycle.v_eps, self.w)
        n = nodes.mass.shape[0]
        self.n = n
        self.poly = np.zeros((6, n))
        self.bounds = np.zeros((4, n))  # u low, u high, T low, T high
        self.started = False
        self.evaluations = 0  # exact evaluations of an element's law after the first

    def __call__(self, v: np.ndarray, T: np.ndarray) -> np.ndarray:
        u = np.abs(v)
        tm = 0.5 * (np.roll(T, 1) + T)
        lo_u, hi_u, lo_t, hi_t = self.bounds
        if not self.started:
            out = np.ones(self.n, dtype=bool)
            self.started = True
        else:
            out = (u < lo_u) | (u > hi_u) | (tm < lo_t) | (tm > hi_t)
            self.evaluations += int(out.sum())
        if out.any():
            self._evaluate(np.flatnonzero(out), u, tm)
        k, gu, guu, gx, gxx, gux = self.poly
        return k + u * (gu + guu * u + gux * tm) + tm * (gx + gxx * tm)

    def _evaluate(self, j, u, tm):
        law = self.law
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
        for c, p, q in zip(law.coef[:, j], law.pvv, law.psv, strict=True):
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


def _tangent(sp: Springs, te: np.ndarray, j=slice(None)) -> np.ndarray:
    """Ernst tangent modulus ``EB T^3 / (T^3 + a EB)`` of springs j [N], held at the floor
    tension below it."""
    t3 = np.maximum(te, sp.t_floor[j]) ** 3
    return sp.eb * t3 / (t3 + sp.a_ernst[j] * sp.eb)


def _damper(sys: System) -> tuple[float, float]:
    """The relaxing arm of the standard linear solid: (decay over a step, gain per unit tangent
    stiffness and strain increment), ``d' = e d + g kt de``; (0, 0) without an arm."""
    sp = sys.model.springs
    if sys.damping != "belt" or not sp.eb_dyn > sp.eb:
        return 0.0, 0.0
    h = sys.dt_s / sys.relaxation_s
    e = math.exp(-h)
    return e, (sp.eb_dyn - sp.eb) / sp.eb * (1.0 - e) / h


def _viscosity(model: Model) -> np.ndarray:
    """Mesh viscosity per spring as tension per strain increment over a step [N]:
    ``alpha Z len / dt``."""
    sp = model.springs
    return sp.viscosity * sp.len_m / model.cycle.dt


def _newton(sp: Springs, te, ts, j=slice(None)):
    """One Newton step of Ernst's chord law ``s(T) = T - a EB / (2 T^2)`` towards the strain
    tension ts from the elastic tension te (held at the floor below it) for springs j: (the
    step's tension, the tangent modulus [N] at its start, whether its estimated error,
    ``1.5 u r^3 |ds| / T`` of the increment with ``u = a EB / T^3``, ``r = 1 / (1 + u)``,
    exceeds ``NEWTON_CURVE``)."""
    tc = np.maximum(te, sp.t_floor[j])
    aeb = sp.a_ernst[j] * sp.eb
    kt = _tangent(sp, te, j)
    r = kt / sp.eb
    ds = ts - (tc - aeb / (2.0 * tc * tc))
    curve = 1.5 * (aeb / tc**3) * r**3 * np.abs(ds) / tc
    return tc + r * ds, kt, curve > NEWTON_CURVE


def _strain_rest(sp: Springs, te, ts, j=slice(None)):
    """Elastic tension of springs j at their strain before the increment (the constant part
    of the Newton step in :func:`_springs`) and their tangent modulus [N]."""
    e, kt, _ = _newton(sp, te, ts, j)
    return e, kt


def _springs(sp: Springs, st, de, damp, visc):
    """Every spring of the belt state ``st`` after the strain increment ``de`` [-]: (elastic,
    strain, arm, total) tension [N].

    Strain tension ``ts = EB eps`` (chord strain) integrates the increment exactly; elastic
    tension is its inverse under Ernst's chord law by a Newton step from the old tension, the
    larger of that and the floor line (the floor modulus below the floor tension, on into
    slack); springs whose step bends more than ``NEWTON_CURVE`` of the increment take
    ``NEWTON_MORE`` further steps. Slack (below the floor line's zero): no arm, no mesh
    viscosity. Arm: ``e d + g kt de`` (``damp = (e, g)``). Mesh viscosity ``visc x de``
    (``alpha Z len / dt``). A belt never pushes.
    """
    e_damp, g_damp = damp
    eb = sp.eb
    s1 = st.ts + eb * de
    tfl = sp.t_floor
    sfl = eb * chord_strain(tfl, sp.a_ernst, eb, tfl, sp.k_floor)
    fl = tfl + (s1 - sfl) * sp.k_floor / eb
    e1, kt, more = _newton(sp, st.te, s1)
    e1 = np.maximum(e1, fl)
    for _ in range(NEWTON_MORE):
        e1 = np.where(more, np.maximum(_newton(sp, e1, s1)[0], fl), e1)
    taut = fl >= 0.0
    d1 = np.where(taut, e_damp * st.td + g_damp * kt * de, 0.0)
    vis = np.where(taut, visc * de, 0.0)
    return e1, s1, d1, np.maximum(e1 + d1 + vis, 0.0)


def _zone(x: float, v_eps: float) -> float:
    """Zone of the regularised resistance at speed x: -1, 0 (linear, ``|x| <= v_eps``) or +1."""
    return 1.0 if x > v_eps else (-1.0 if x < -v_eps else 0.0)


def _free_velocities(model: Model, v, T, R0):
    """New velocity of every element as a free (explicit) one [m/s].

    ``M (v' - v) / dt = T_j - T_{j-1} - G_j - R0_j clip(v' / v_eps, -1, 1)``, the resistance
    implicit (solved in closed form); a negative resistance term is taken explicitly.
    """
    nodes, v_eps = model.nodes, model.cycle.v_eps
    h = model.cycle.dt / nodes.mass
    rp, rn = np.maximum(R0, 0.0), np.minimum(R0, 0.0)
    vs = v + h * (T - np.roll(T, 1) - nodes.gravity - rn * np.clip(v / v_eps, -1.0, 1.0))
    e = h * rp
    return np.where(np.abs(vs) <= v_eps + e, vs * (v_eps / (v_eps + e)), vs - np.copysign(e, vs))


def _coulomb(p, dd, fb, hb):
    """Velocity of a mass under ``dd v = p - fb sign(v)`` (a brake holding when ``|p| <= fb``),
    never below zero with a holdback."""
    if fb > 0.0:
        v = 0.0 if abs(p) <= fb else (p - math.copysign(fb, p)) / dd
    else:
        v = p / dd
    return 0.0 if hb and v < 0.0 else v


# --------------------------------------------------------------------------------------
# phase: the speed reference, brakes and drive laws of the step


def _brake_forces(model: Model, rs, sh, brk) -> float:
    """Command, release and force of every brake (its law:
    :func:`beltstudy.engine.dynamics.brakes.brake_force`, with the shaft's speed at the step's
    start), summed per shaft into ``sh.fb`` [N]; ``brk`` is the brakes' record with this run's
    command times and released flags.

    A brake stop commands every brake at the stop command; a holding brake is commanded when
    the belt has stopped and stays set, others are released then. Returns the time the last
    holding brake is fully set, or -1 while one is not (or there is none).
    """
    sh.fb[:] = 0.0
    latest, pending = -1.0, False
    for b in range(len(brk.shaft)):
        hold = brk.hold[b] == 1
        s = brk.shaft[b]
        if rs.stopping and brk.t_cmd[b] < 0.0 and not brk.released[b]:
            if model.cycle.stop_mode == C.BRAKE:
                brk.t_cmd[b] = rs.t_stopcmd
            elif hold and rs.stopped:
                brk.t_cmd[b] = rs.t_stopped
        if not hold and rs.stopped and brk.t_cmd[b] >= 0.0:
            brk.released[b] = 1
        if brk.t_cmd[b] >= 0.0 and not brk.released[b]:
            sh.fb[s] += brake_force(brk, b, rs.t - brk.t_cmd[b] - brk.delay[b], sh.vs[s])
        if hold:
            if brk.t_cmd[b] < 0.0:
                pending = True
            else:
                latest = max(latest, set_at(brk, b))
    if not (brk.hold == 1).any() or pending or rs.t < latest:
        return -1.0
    return latest


def _dol_law(model: Model, dr, k, vs, fac, t):
    """Dol drive k's force law ``f0 + f1 v`` for the step: its motor curve linearised in the
    shaft speed vs, or through its fluid coupling with the motor's own inertia eliminated
    (``dr.lin``: ``(P, D, c_s)`` for the motor's new speed); ``fac`` scales the motor's torque
    (1, or falling after a trip)."""
    drives, v_d = model.drives, model.cycle.v_d
    rated = drives.rated[k]
    cx, cy, cn = drives.curve_x[k], drives.curve_y[k], int(drives.curve_n[k])
    if drives.coupling[k] == C.COUPLING_NONE:
        f, df = motor_force(cx, cy, cn, rated, v_d, vs)
        f1 = min(df * fac, 0.0)
        dr.f0[k], dr.f1[k] = f * fac - f1 * vs, f1
        return
    # motor (mass mm, force a0 + a1 vm) -> coupling (c0 + cm vm + cs vs) -> shaft:
    # the motor's new speed eliminated, vm' = (p - cs vs') / den
    vm = dr.vm[k]
    fm, dfm = motor_force(cx, cy, cn, rated, v_d, vm)
    a1 = min(dfm * fac, 0.0)
    a0 = fm * fac - a1 * vm
    fill = 1.0
    if drives.coupling[k] == C.COUPLING_FILL:
        fill = min(max((t - model.cycle.t_pre) / drives.fill_s[k], 0.0), 1.0)
    tc, dtm, dts = coupling_torque(rated, v_d, vm, vs, fill)
    cm, cs = max(dtm, 0.0), min(dts, 0.0)
    c0 = tc - cm * vm - cs * vs
    mm = max(drives.motor_mass[k], 1.0) / model.cycle.dt
    den = mm - a1 + cm
    p = mm * vm + a0 - c0
    dr.f0[k], dr.f1[k] = c0 + cm * p / den, cs * (mm - a1) / den
    dr.lin[k] = (p, den, cs)


def _drive_laws(model: Model, rs, sh, dr, first_off):
    """Each drive's force law for the step, in ``dr.mode``: 0 a force ``f0 + f1 v`` linear in
    its shaft speed (held at rest: zero; dol: the motor curve, through the fluid coupling with
    the motor's own inertia eliminated, :func:`_dol_law`; power off: the force at the trip
    decaying over the trip time; open-loop start), 1 its share of the speed loop's output, 2
    the shaft speed imposed (moving support). ``first_off``: the first step with the power
    off."""
    drives, cyc = model.drives, model.cycle
    for k in range(len(drives.share)):
        dr.sat[k] = False
        dr.win_f[k] = 0.0
        dr.lim[k] = drives.lim0[k]
        dr.lin[k] = None
        vs = sh.vs[drives.shaft[k]]
        fac = 1.0
        if rs.phase == C.OFF:
            if first_off:
                dr.f_trip[k] = dr.force[k]
            ts = drives.trip_s[k]
            fac = 0.0 if ts <= 0.0 else max(0.0, 1.0 - (rs.t - rs.t_trip) / ts)
        dr.mode[k], dr.f0[k], dr.f1[k] = 0, 0.0, 0.0
        if rs.phase == C.HOLD:
            if rs.started:  # the start's hand-over: the share of the holding force, built
                # over t_hand, within the drive's torque limit
                f = drives.share[k] * rs.hold_f * min((rs.t - cyc.t_pre) / cyc.t_hand, 1.0)
                dr.f0[k] = math.copysign(min(abs(f), dr.lim[k]), f)
            continue
        if drives.control[k] == C.DOL:
            _dol_law(model, dr, k, vs, fac, rs.t)
        elif rs.phase == C.OFF:
            dr.f0[k] = dr.f_trip[k] * fac
        elif cyc.formulation == C.SUPPORT:
            dr.mode[k] = 2
        elif cyc.start_ctrl == FORCE and not rs.stopping:
            dr.f0[k] = drives.share[k] * model.control.f_const
        else:
            dr.mode[k] = 1


def _phase(model: Model, rs, sh, dr, brk):
    """The step's phase into ``rs``: the speed reference (start or controlled stop), the
    drives' trip, what the drives do (hold at rest, run, off), the brakes' forces
    (:func:`_brake_forces`), each drive's law (:func:`_drive_laws`), whether the speed loop
    runs (switched on bumpless from the holding force), a torque start's ramped limits, and
    the speed loop's law ``U = f0u + f1u v_master`` (rigid-body feedforward, integrator,
    proportional gain)."""
    cyc, ctl, drives = model.cycle, model.control, model.drives
    t = rs.t
    rs.started, rs.stopping = t > cyc.t_pre, t > rs.t_stopcmd
    rs.a_ref = 0.0
    if not rs.stopping:
        rs.v_ref, rs.a_ref = start_reference(cyc.start_ctrl, t - cyc.t_pre, cyc.t_start, cyc.v_d)
    elif cyc.stop_mode == C.CONTROLLED:
        if rs.v_stop0 < 0.0:  # from v_d; a master held at its limit below it: its speed;
            rs.v_stop0 = cyc.v_d  # a master whose pulley slips: the belt's mean if lower
            k = drives.shaft[ctl.master]
            vm = sh.vs[k]
            v0 = cyc.v_d
            if rs.pi_started and dr.sat[ctl.master] != 0:
                v0 = min(v0, vm)
            if rs.pi_started and sh.slip[k] != 0:
                v0 = min(v0, vm, rs.v_mean)
            if v0 < cyc.v_d:
                rs.v_stop0 = max(v0, 0.0)
                rs.integ = rs.U - ctl.kp * (rs.v_stop0 - vm)
        rs.v_ref, rs.a_ref = stop_reference(t - rs.t_stopcmd, cyc.t_stop, rs.v_stop0)
    else:
        rs.v_ref = 0.0
    if rs.stopping and rs.t_trip < 0.0:
        if cyc.stop_mode != C.CONTROLLED:
            rs.t_trip = rs.t_stopcmd  # coast and brake stops: the power is cut
        elif rs.hold_set >= 0.0:
            rs.t_trip = rs.hold_set  # a controlled stop: off once the holding brakes are set
    rs.phase = C.HOLD if not rs.started else (
        C.OFF if 0.0 <= rs.t_trip < t else (C.HOLD if t - cyc.t_pre <= cyc.t_hand else C.RUN))
    rs.hold_set = _brake_forces(model, rs, sh, brk)
    _drive_laws(model, rs, sh, dr, rs.phase == C.OFF and not rs.was_off)
    rs.was_off = rs.phase == C.OFF
    rs.pi = rs.phase == C.RUN and ctl.vfd and cyc.formulation != C.SUPPORT and (
        cyc.start_ctrl != FORCE or rs.stopping)
    if rs.pi and not rs.pi_started:
        # bumpless switch-on: the loop's output goes on from the drives' force before it
        u0 = ctl.f_const if cyc.start_ctrl == FORCE else rs.hold_f
        rs.integ = u0 - ctl.kp * (rs.v_ref - sh.vs[drives.shaft[ctl.master]])
        rs.pi_started = True
    if cyc.start_ctrl == TORQUE and not rs.stopping and rs.phase == C.RUN:
        ramp = min(max((t - cyc.t_pre) / cyc.t_start, 0.0), 1.0)
        dr.lim[:] = drives.lim0 * ramp + drives.share * abs(rs.hold_f) * (1.0 - ramp)
    # speed loop output U = f0u + f1u v_master: rigid-body feedforward, integrator, gain
    f_ff = ctl.ff * (ctl.m_tot * rs.a_ref + ctl.f_res * min(max(rs.v_ref / ctl.v_ff, 0.0),
                                                             1.0))
    rs.f0u = f_ff + rs.integ + ctl.kp * rs.v_ref
    rs.f1u = -ctl.kp
    rs.hold = cyc.hold_node if rs.phase == C.HOLD else -1


# --------------------------------------------------------------------------------------
# the passes of one step: resistances, free elements (the blocks below), springs


def _resistances(model: Model, ref, st) -> np.ndarray:
    """The resistance law per element for this step [N]: exactly, or expanded between exact
    evaluations (:class:`ExpandedLaw`)."""
    if ref.law is not None:
        return ref.law(st.v, st.tt)
    return _law(model.law, model.nodes, st.v, st.tt)


def _free_elements(model: Model, ref, st, R0):
    """The free elements' new velocities (:func:`_free_velocities`) into ``st.v``."""
    v_free = _free_velocities(model, st.v, st.tt, R0)
    st.v[ref.free] = v_free[ref.free]


def _spring_step(model: Model, ref, st, rs):
    """Every spring from the new velocities, the blocks' springs with the free ones (the
    carriage lengthens its two springs); the kernel takes them in two parts
    (``blocks._block_springs`` and ``kernel._free_springs``) with the same law."""
    sp = model.springs
    de = (np.roll(st.v, -1) - st.v + sp.car_ind * rs.u_tu) * model.cycle.dt / sp.len_m
    st.te, st.ts, st.td, st.tt = _springs(sp, st, de, ref.damp, ref.visc * _limiter(sp, st.v))


def _limiter(sp: Springs, v) -> np.ndarray:
    """The share of the mesh viscosity each spring keeps: on the free springs (when
    ``sp.limited``) Christensen's monotonised central limiter of the ratios of the
    neighbours' strain increments to the spring's own, ``1 - max(0, min((r_l + r_r) / 2,
    2 r_l, 2 r_r, 1))`` (:func:`beltstudy.engine.dynamics.passes.visc_limiter`), 1 on the
    blocks' springs."""
    keep = np.ones(v.shape[0])
    if not sp.limited:
        return keep
    de = (np.roll(v, -1) - v) * sp.dl
    inv = de / (de * de + 1e-300)
    rl, rr = np.roll(de, 1) * inv, np.roll(de, -1) * inv
    psi = np.maximum(np.minimum(np.minimum(0.5 * (rl + rr), 2.0 * rl),
                                np.minimum(2.0 * rr, 1.0)), 0.0)
    for a, b in sp.seg_spring:
        keep[a:b] = 1.0 - psi[a:b]
    return keep


# --------------------------------------------------------------------------------------
# implicit blocks


def _share_force(model: Model, dr, k, U):
    """Drive k's share of the speed loop's output within its force limit [N] (a drive found
    beyond it is saturated for the rest of the step)."""
    f = model.drives.share[k] * U
    if abs(f) > dr.lim[k]:
        dr.sat[k] = True
        dr.f0[k] = math.copysign(dr.lim[k], f)
        return dr.f0[k]
    return f


def _saturate_master(model: Model, dr, U):
    """The speed loop's output ``U`` within the master drive's limit (``share x U``)."""
    k = model.control.master
    share = model.drives.share[k]
    if abs(share * U) > dr.lim[k]:
        dr.sat[k] = True
        dr.f0[k] = math.copysign(dr.lim[k], share * U)
        return dr.f0[k] / share
    return U


def _shaft_drive_force(model: Model, dr, k, U):
    """Force of drive k on its shaft with the loop output U (mode 0 without its speed part)."""
    if dr.mode[k] == 1:
        return dr.f0[k] if dr.sat[k] else model.drives.share[k] * U
    return dr.f0[k]


def _row_brake(model: Model, bk, sh, k, v_was):
    """A brake and/or holdback on block element k's sticking shaft: the reaction range of a
    stick, tried when the element moves slower than v_eps (or backwards onto a holdback)."""
    s = bk.shaft[k]
    fb, hb = sh.fb[s], model.shafts.hb[s] == 1
    bk.bforce[k], bk.c_lo[k], bk.c_hi[k] = fb, -fb, (1e300 if hb else fb)
    bk.stuck[k] = (fb > 0.0 or hb) and (abs(v_was) <= bk.v_eps or (hb and v_was < 0.0))


def _side_tensions(bk, x, k):
    """Tensions of the springs left and right of block element k at the solution x [N]."""
    sA, sB, cj, m = bk.sA, bk.sB, bk.cj, bk.m
    tl = bk.t_in if k == 0 else sA[k - 1] + sB[k - 1] * (x[k] - x[k - 1] + cj[k - 1] * x[-1])
    tr = bk.t_out if k == m - 1 else sA[k] + sB[k] * (x[k + 1] - x[k] + cj[k] * x[-1])
    return tl, tr


def _belt_force(bk, x, k, tl, tr, zone):
    """Force the pulley passes to belt element k: its momentum balance's remainder [N], with
    the resistance in the ``zone`` the solution was found in."""
    rk = bk.rpos[k] * (x[k] / bk.v_eps if zone == 0.0 else zone)
    return bk.mass[k] / bk.dt * (x[k] - bk.vo[k]) - (tr - tl) + rk - bk.fexp[k]


def _block_setup(model: Model, ref, nodes, st, sh, rs, R0):
    """The block of elements ``nodes`` before its active set: its springs linearised at the
    step's start (``T = sA + sB (x_{k+1} - x_k (+ cj x_car))``, their tangent stiffness, arm
    and viscosity), the outer springs' tensions, each element's old speed, mass, resistance
    (the positive part implicit, ``rpos``; the negative part and gravity explicit, ``fexp``)
    and zone, its shaft, the held element, the brakes of shafts that stick, the master
    drive's row ``km`` (-1 none). Returns the block's working namespace."""
    sp, tu, dt = model.springs, model.takeup, model.cycle.dt
    v_eps = model.cycle.v_eps
    n, e_damp, g_damp = len(st.v), *ref.damp
    nodes = np.asarray(nodes)
    m = len(nodes)
    car = bool(tu.gravity) and tu.node in nodes
    # linearised block springs (spring nodes[k] joins nodes[k] and nodes[k + 1])
    sj = nodes[:-1]
    taut = st.te[sj] >= 0.0
    er, kt = _strain_rest(sp, st.te[sj], st.ts[sj], sj)
    vo = st.v[nodes].copy()
    R = R0[nodes]
    bk = SimpleNamespace(
        nodes=nodes, m=m, car=car, mu=m + 1 if car else m, dt=dt, v_eps=v_eps,
        sA=np.where(taut, er + e_damp * st.td[sj], 0.0),
        sB=np.where(taut, (kt * (1.0 + g_damp) + ref.visc[sj]) * dt / sp.len_m[sj], 0.0),
        cj=sp.car_ind[sj] if car else np.zeros(m - 1),
        t_in=st.tt[(nodes[0] - 1) % n], t_out=st.tt[nodes[-1]], vo=vo,
        mass=model.nodes.mass[nodes], rpos=np.maximum(R, 0.0),
        fexp=-np.minimum(R, 0.0) * np.clip(vo / v_eps, -1.0, 1.0) - model.nodes.gravity[nodes],
        zone=np.array([_zone(x, v_eps) for x in vo]), shaft=ref.node_shaft[nodes],
        fixed=nodes == rs.hold, fixv=np.zeros(m), stuck=np.zeros(m, dtype=bool),
        bforce=np.zeros(m), c_lo=np.zeros(m), c_hi=np.zeros(m),
        bdir=np.where(vo >= 0.0, 1.0, -1.0), vsn=np.zeros(m), crossed=np.zeros(m), km=-1,
        car_fixed=False, car_v=0.0, car_hit=-1.0)
    for k in range(m):
        s = bk.shaft[k]
        if s >= 0:
            if sh.slip[s] == 0.0:
                _row_brake(model, bk, sh, k, vo[k])
            if model.shafts.drive[s] == model.control.master:
                bk.km = k
    return bk


def _master_output(model: Model, bk, st, sh, dr, rs, U):
    """The speed loop's output for this pass: known (from an earlier block), from a held or
    stuck master row, or unknown (``two``: found from the solution by superposition, with the
    master's new shaft speed, :func:`_master_speed`). Returns (U, two)."""
    master, km = model.control.master, bk.km
    if km < 0 or rs.u_known or dr.mode[master] != 1 or dr.sat[master]:
        return U, False
    if sh.slip[bk.shaft[km]] == 0.0 and (bk.fixed[km] or bk.stuck[km]):
        return _saturate_master(model, dr, rs.f0u + rs.f1u * bk.fixv[km]), False
    return U, True


def _master_speed(model: Model, bk, sh, x0, xu):
    """The master's new shaft speed ``g0 + gu U`` from the solution ``x0`` and its response
    ``xu`` to U: the belt's speed at its row while it sticks; while it slips, its momentum
    balance over the step under its share of U less the sliding force ``ck T_s`` at the new
    tensions (as :func:`_shaft_speed`)."""
    km = bk.km
    s = bk.shaft[km]
    sl = sh.slip[s]
    if sl == 0.0 or abs(bk.crossed[km]) == 2.0:
        return x0[km], xu[km]  # at the belt's speed
    side = 1 if sl > 0.0 else 0  # the side the slip unloads (outgoing, incoming)
    t0 = _side_tensions(bk, x0, km)[side]
    tu = _side_tensions(bk, x0 + xu, km)[side] - t0
    ms = model.shafts.mass[s] / bk.dt
    ck = model.shafts.ck[s]
    g0 = sh.vs[s] - sl * ck * t0 / ms
    gu = (model.drives.share[model.control.master] - sl * ck * tu) / ms
    return g0, gu


def _shaft_row(model: Model, bk, sh, dr, rs, k, U, two):
    """Block row k's shaft: a slipping shaft's sliding force ``ck T_slack`` on the side the
    slip unloads (``bk.ml``, ``bk.mr``); a sticking one's mass, its drive's force (an imposed
    speed fixes the row, a follower's share is U's coefficient ``bu`` when ``two``)."""
    shafts = model.shafts
    s = bk.shaft[k]
    if sh.slip[s] != 0.0:
        if sh.slip[s] > 0.0:
            bk.mr[k] += shafts.ck[s]
        else:
            bk.ml[k] += shafts.ck[s]
        return
    ms = shafts.mass[s] / bk.dt
    bk.A[k, k] += ms
    bk.b[k] += ms * sh.vs[s]
    d = shafts.drive[s]
    if d >= 0 and dr.mode[d] == 2:
        if not bk.fixed[k]:
            bk.fixed[k], bk.fixv[k] = True, rs.v_ref
    elif d >= 0 and dr.mode[d] == 1:
        if dr.sat[d]:
            bk.b[k] += dr.f0[d]
        elif two:
            bk.bu[k] += model.drives.share[d]
        else:
            bk.b[k] += _share_force(model, dr, d, U)
    elif d >= 0:
        bk.A[k, k] -= dr.f1[d]
        bk.b[k] += dr.f0[d]


def _block_rows(model: Model, bk, sh, dr, rs, U, two):
    """The block's momentum balances ``A x = b + U bu`` (``bk.A``, ``bk.b``, ``bk.bu``): each
    element's mass over the step, its shaft (:func:`_shaft_row`), its resistance in its zone,
    a sliding brake, the springs (the outer ones at the step start), and the carriage's row
    (its inertia and weight, the springs beside its pulley)."""
    m, mu, dt, v_eps = bk.m, bk.mu, bk.dt, bk.v_eps
    bk.A, bk.b, bk.bu = np.zeros((mu, mu)), np.zeros(mu), np.zeros(mu)
    bk.ml, bk.mr = np.ones(m), np.ones(m)
    A, b = bk.A, bk.b
    for k in range(m):
        A[k, k] += bk.mass[k] / dt
        b[k] += bk.mass[k] / dt * bk.vo[k] + bk.fexp[k]
        if bk.shaft[k] >= 0:
            _shaft_row(model, bk, sh, dr, rs, k, U, two)
        if bk.zone[k] == 0.0:
            A[k, k] += bk.rpos[k] / v_eps
        else:
            b[k] -= bk.zone[k] * bk.rpos[k]
        if bk.bforce[k] > 0.0 and not bk.stuck[k]:
            b[k] -= bk.bdir[k] * bk.bforce[k]
    b[0] -= bk.ml[0] * bk.t_in
    b[m - 1] += bk.mr[m - 1] * bk.t_out
    for i in range(m - 1):
        # spring i pulls element i forward, element i + 1 back, the carriage back
        for row, f in ((i, bk.mr[i]), (i + 1, -bk.ml[i + 1]), (m, -1.0 if bk.cj[i] else 0.0)):
            if f != 0.0:
                A[row, i] += f * bk.sB[i]
                A[row, i + 1] -= f * bk.sB[i]
                if bk.car:
                    A[row, m] -= f * bk.sB[i] * bk.cj[i]
                b[row] += f * bk.sA[i]
    if bk.car:
        tu = model.takeup
        A[m, m] += tu.mass / dt
        b[m] += tu.mass / dt * rs.u_tu + tu.weight


def _block_solution(model: Model, bk, sh, dr, rs, U, two):
    """Solve the block with the rows held at a speed as identities (an imposed or held
    element, a brake or holdback holding, the carriage at an end stop) for its speeds
    (``bk.x``); with ``two`` also its response to U, and U from the master's row (within its
    limit). Returns U."""
    m = bk.m
    Ah, bh, buh = bk.A.copy(), bk.b.copy(), bk.bu.copy()
    for k in np.flatnonzero(bk.fixed | bk.stuck):
        Ah[k] = 0.0
        Ah[k, k] = 1.0
        bh[k] = bk.fixv[k] if bk.fixed[k] else 0.0
        buh[k] = 0.0
    if bk.car and bk.car_fixed:
        Ah[m] = 0.0
        Ah[m, m] = 1.0
        bh[m], buh[m] = bk.car_v, 0.0
    bk.two = two
    if two:
        # U = f0u + f1u x_master with x = x0 + U xu: two solves
        x0, xu = np.linalg.solve(Ah, np.column_stack([bh, buh])).T
        g0, gu = _master_speed(model, bk, sh, x0, xu)
        U = _saturate_master(model, dr, (rs.f0u + rs.f1u * g0) / (1.0 - rs.f1u * gu))
        bk.x = x0 + U * xu
    else:
        bk.x = np.linalg.solve(Ah, bh)
    return U


def _carriage_consistent(model: Model, bk, rs):
    """The carriage against the solution: a position past an end of its travel fixes it at
    the end stop. Returns whether it changed."""
    if not bk.car or bk.car_fixed:
        return False
    tu, m = model.takeup, bk.m
    x_try = rs.x_tu + bk.dt * bk.x[m]
    if x_try > tu.hi or x_try < tu.lo:
        bk.car_fixed = True
        bk.car_v = ((tu.hi if x_try > tu.hi else tu.lo) - rs.x_tu) / bk.dt
        bk.car_hit = abs(bk.x[m])
        return True
    return False


def _row_consistent(model: Model, bk, dr, k, U):
    """Row k's active set against the solution: a follower past its force limit, a stuck
    element whose reaction left its range, a holdback or brake that now holds, the resistance
    zone. Returns whether anything changed."""
    x, v_eps = bk.x, bk.v_eps
    again = False
    s = bk.shaft[k]
    d = model.shafts.drive[s] if s >= 0 else -1
    if d >= 0 and d != model.control.master and dr.mode[d] == 1 and not dr.sat[d]:
        f = model.drives.share[d] * U
        if abs(f) > dr.lim[d]:
            dr.sat[d], dr.f0[d], again = True, math.copysign(dr.lim[d], f), True
    if bk.fixed[k]:
        bk.zone[k] = _zone(bk.fixv[k], v_eps)
        return again
    if bk.stuck[k]:
        # the reaction the brake or holdback must give to hold the element
        react = bk.A[k] @ x - bk.b[k] - (U * bk.bu[k] if bk.two else 0.0)
        if not bk.c_lo[k] <= react <= bk.c_hi[k]:
            bk.stuck[k], again = False, True
            bk.bdir[k] = -1.0 if react > bk.c_hi[k] else 1.0
    elif bk.c_hi[k] > 1e299 and x[k] < 0.0:
        bk.stuck[k], again = True, True  # the holdback engages
    elif bk.bforce[k] > 0.0 and x[k] * bk.bdir[k] < 0.0:
        bk.stuck[k], again = True, True  # the brake stops the element
    z = 0.0 if bk.stuck[k] else _zone(x[k], v_eps)
    if z * bk.zone[k] < 0.0:
        z = 0.0  # turning round within the step: through the linear band
    if z != bk.zone[k]:
        bk.zone[k], again = z, True
    return again


def _shaft_speed(model: Model, sh, dr, rs, s, U, f_slide):
    """New speed of slipping shaft s [m/s]: its inertia under its drive and brake less the
    sliding force ``ck T_slack`` (``f_slide = slip x T_slack``); an imposed speed holds it at
    the reference, a torque follower stays within its speed window through its own torque,
    within its limit ``lim`` (the force that takes it into the window in this step, else the
    limit)."""
    shafts = model.shafts
    ms = shafts.mass[s] / model.cycle.dt
    f = -shafts.ck[s] * f_slide
    dd = ms
    d = shafts.drive[s]
    fd = 0.0
    if d >= 0:
        if dr.mode[d] == 2:
            return rs.v_ref
        fd = _shaft_drive_force(model, dr, d, U)
        f += fd
        if dr.mode[d] == 0:
            dd -= dr.f1[d]
    p = ms * sh.vs[s] + f
    v = _coulomb(p, dd, sh.fb[s], shafts.hb[s] == 1)
    if d >= 0 and dr.mode[d] == 1 and d != model.control.master:
        window = model.control.window
        vw = min(max(v, rs.v_ref - window), rs.v_ref + window)
        extra = 0.0
        if vw != v:
            lim = dr.lim[d]
            need = ms * (vw - v)
            if need > lim - fd:
                extra = lim - fd
                v = _coulomb(p + extra, dd, sh.fb[s], shafts.hb[s] == 1)
            elif need < -lim - fd:
                extra = -(lim + fd)
                v = _coulomb(p + extra, dd, sh.fb[s], shafts.hb[s] == 1)
            else:
                extra = need
                v = vw
        dr.win_f[d] = extra
    return v


def _shaft_consistent(model: Model, bk, sh, dr, rs, k, U, zone):
    """Row k's shaft against the solution: a sticking shaft that would pass more than its
    capstan grip ``T_slack (e^(mu theta) - 1)`` starts to slip; a slipping one whose speed
    crosses the belt's sticks again, and if it then needs more than its grip the way it
    slipped, slides on at the belt's speed (``bk.crossed``). Returns whether anything
    changed."""
    s = bk.shaft[k]
    if s < 0:
        return False
    x = bk.x
    tl, tr = _side_tensions(bk, x, k)
    sl = sh.slip[s]
    if sl == 0.0:
        cs = model.shafts.cs[s]
        if bk.nodes[k] == rs.hold or cs < 0.0:
            return False  # holding the belt at rest, or slip switched off (verification)
        # capstan: what the pulley passes within T_slack (e^(mu theta) - 1)
        ft = _belt_force(bk, x, k, tl, tr, zone)  # the zone the solution was found in
        cap = cs * max(min(tl, tr), 0.0)
        if abs(ft) > cap * (1.0 + 1e-9) + 1e-9:
            sh.slip[s] = 1.0 if ft > 0.0 else -1.0
            if bk.crossed[k] == sh.slip[s]:
                # slipped this way, crossed the belt's speed in this step, and sticking needs
                # more than the grip the same way: slide on at the belt's speed
                bk.crossed[k] = 2.0 * sh.slip[s]
            bk.stuck[k], bk.bforce[k], bk.c_lo[k], bk.c_hi[k] = False, 0.0, 0.0, 0.0
            bk.fixed[k] = False  # an imposed speed now holds the shaft, not the belt
            return True
        return False
    if abs(bk.crossed[k]) == 2.0:
        bk.vsn[k] = x[k]  # sliding on at the belt's speed
        if model.shafts.drive[s] >= 0:
            dr.win_f[model.shafts.drive[s]] = 0.0
        return False
    bk.vsn[k] = _shaft_speed(model, sh, dr, rs, s, U, sl * max(tr if sl > 0 else tl, 0))
    if sl * (bk.vsn[k] - x[k]) <= 0.0:
        bk.crossed[k] = sl
        sh.slip[s] = 0.0  # the speeds crossed: the shaft sticks again
        _row_brake(model, bk, sh, k, bk.vo[k])
        return True
    return False


def _drive_output(model: Model, dr, s, sl, ft, vs_old, vs_new, U):
    """Force at the rim of the drive on shaft s after the step [N] (an imposed speed: what
    moved its shaft; a share of U, a slipping follower's with what its speed window adds; a
    linear law at the new speed), and its motor's speed behind a coupling."""
    shafts = model.shafts
    d = shafts.drive[s]
    inertia = shafts.mass[s] / model.cycle.dt * (vs_new - vs_old)
    if dr.mode[d] == 2:
        f = ft + inertia
    elif dr.mode[d] == 1:
        f = _shaft_drive_force(model, dr, d, U)
        if sl != 0.0 and d != model.control.master:
            # a slipping follower's speed window adds what takes its shaft there (within its
            # limit, :func:`_shaft_speed`)
            f += dr.win_f[d]
    else:
        f = dr.f0[d] + dr.f1[d] * vs_new
    if dr.lin[d] is not None:
        p, den, cs = dr.lin[d]
        dr.vm[d] = (p - cs * vs_new) / den
    return f


def _brake_holdback(model: Model, bk, sh, dr, k, U, ft, vs_new):
    """The brake and holdback forces on block row k's shaft after the solve [N]: a stuck
    row's reaction (a brake alone gives all of it; with a holdback the brake gives up to its
    force, the holdback the rest), a sliding brake's force, and on a slipping shaft the
    brake's and holdback's share of what holds the shaft at rest (its momentum over the step
    and forces but the brake's, ``p``, at its speed before the step)."""
    s = bk.shaft[k]
    fb, hb = bk.bforce[k], model.shafts.hb[s] == 1
    if sh.slip[s] == 0.0:
        if not bk.stuck[k]:
            return fb, 0.0
        react = bk.A[k] @ bk.x - bk.b[k] - (U * bk.bu[k] if bk.two else 0.0)
        if hb:
            return min(abs(react), fb), max(react - fb, 0.0)
        return abs(react), 0.0
    fb = sh.fb[s]
    if vs_new != 0.0:
        return fb, 0.0
    p = model.shafts.mass[s] / bk.dt * sh.vs[s] - ft
    d = model.shafts.drive[s]
    if d >= 0 and dr.mode[d] == 1:
        p += dr.f0[d] if dr.sat[d] else model.drives.share[d] * U
        p += dr.win_f[d]  # a follower's window (0 for any other drive)
    elif d >= 0 and dr.mode[d] == 0:
        p += dr.f0[d] + dr.f1[d] * sh.vs[s]
    return min(fb, abs(p)), (max(-p - fb, 0.0) if hb else 0.0)


def _write_back(model: Model, bk, st, sh, dr, rs, U):
    """The solution into the belt, the shafts and the drives; the brake and holdback forces
    into ``rs.f_brake`` and ``rs.f_hb`` (:func:`_brake_holdback`). Returns (holding force or
    nan, drive work over the step [J])."""
    x = bk.x
    st.v[bk.nodes] = x[:bk.m]
    hold_f = math.nan
    w_drive = 0.0
    for k in np.flatnonzero(bk.shaft >= 0):
        s = bk.shaft[k]
        tl, tr = _side_tensions(bk, x, k)
        vs_old, sl = sh.vs[s], sh.slip[s]
        if sl == 0.0:
            vs_new, ft = x[k], _belt_force(bk, x, k, tl, tr, bk.zone[k])
        else:
            vs_new = bk.vsn[k]
            ft = sl * model.shafts.ck[s] * max(tr if sl > 0.0 else tl, 0.0)
        fbk, fhb = _brake_holdback(model, bk, sh, dr, k, U, ft, vs_new)
        rs.f_brake += fbk
        rs.f_hb += fhb
        if bk.nodes[k] == rs.hold:
            hold_f = ft
        sh.vs[s] = vs_new
        d = model.shafts.drive[s]
        if d < 0:
            continue
        f = _drive_output(model, dr, s, sl, ft, vs_old, vs_new, U)
        dr.force[d], dr.ft[d] = f, ft
        w_drive += f * 0.5 * (vs_old + vs_new) * bk.dt
    return hold_f, w_drive


def _block_step(model: Model, ref, nodes, st, sh, dr, rs, R0):
    """Velocities of one implicit block (elements ``nodes``) at the end of the step.

    Unknowns: the block's element velocities (and the carriage's speed). Each element row is
    its momentum balance over the step, ``M (x - v) / dt = T_right - T_left - R - G + F``, with
    the block's springs at the new step, ``T = A + B (x_{k+1} - x_k (+ x_car))`` (their tangent
    stiffness, arm and viscosity), the outer springs at the step start, the resistance in its
    zone (linear below ``v_eps``), a sticking shaft's mass and forces (drive, sliding brake)
    added to its element, a slipping shaft's sliding force ``ck T_slack`` added to the slack
    side. Rows held at a speed (the element holding the belt at rest, an imposed shaft speed,
    a brake or holdback holding) are identities. The active set is updated from the solution
    until consistent. Updates ``st.v``, the shafts, the drives and the speed loop's output
    (``rs.U``, ``rs.u_known``); returns ``(carriage speed, carriage speed at an end stop or
    -1, holding force or nan, drive work)``.
    """
    bk = _block_setup(model, ref, nodes, st, sh, rs, R0)
    U = rs.U
    for _ in range(ACTIVE_SET_PASSES):
        U, two = _master_output(model, bk, st, sh, dr, rs, U)
        _block_rows(model, bk, sh, dr, rs, U, two)
        U = _block_solution(model, bk, sh, dr, rs, U, two)
        # the active set against the solution
        again = _carriage_consistent(model, bk, rs)
        for k in range(bk.m):
            zone = bk.zone[k]  # the zone of this solution, before its row's check moves it
            if _row_consistent(model, bk, dr, k, U):
                again = True
            if _shaft_consistent(model, bk, sh, dr, rs, k, U, zone):
                again = True
        if not again:
            break
    hold_f, w_drive = _write_back(model, bk, st, sh, dr, rs, U)
    rs.U, rs.u_known = U, rs.u_known or bk.km >= 0
    u_new = bk.x[bk.m] if bk.car else rs.u_tu
    return u_new, bk.car_hit, hold_f, w_drive


def _blocks(model: Model, ref, st, sh, dr, rs, R0):
    """Every implicit block (the master drive's first, so the speed loop's output is known to
    the others), the drives' work; then the speed loop's integrator and the carriage."""
    tu = model.takeup
    rs.U, rs.u_known = 0.0, not rs.pi
    rs.f_brake, rs.f_hb = 0.0, 0.0
    u_new = rs.u_tu
    for nodes in ref.blocks:
        u_b, _hit, hf, w = _block_step(model, ref, nodes, st, sh, dr, rs, R0)
        if tu.gravity and tu.node in nodes:
            u_new = u_b
        if not math.isnan(hf) and not rs.started:
            rs.hold_f = hf
        rs.w_drive += w
    rs.fbr_max, rs.fhb_max = max(rs.fbr_max, rs.f_brake), max(rs.fhb_max, rs.f_hb)
    if rs.pi:
        master = model.control.master
        e_v = rs.v_ref - sh.vs[model.drives.shaft[master]]
        if not dr.sat[master] or e_v * dr.f0[master] < 0.0:
            rs.integ += model.cycle.dt * model.control.ki * e_v  # not further into the limit
        # the master's tracking after the first wave loop time of the start, until the stop
        if not rs.stopping and rs.t - model.cycle.t_pre > model.control.t_track and abs(
                e_v) > rs.verr_max:
            rs.verr_max, rs.verr_t = abs(e_v), rs.t
    if tu.gravity:
        rs.u_tu = u_new
        rs.x_tu = min(max(rs.x_tu + model.cycle.dt * rs.u_tu, tu.lo), tu.hi)
        phase = "stop" if rs.stopping else ("start" if rs.started else None)
        if phase is not None:  # the carriage's range per phase
            lo, hi = rs.x_range[phase]
            rs.x_range[phase] = (min(lo, rs.x_tu), max(hi, rs.x_tu))


# --------------------------------------------------------------------------------------
# observe and the phase switches after a step


def _diverged(model: Model, st, sh, dr, rs) -> bool:
    """Whether the belt, a pulley shaft or a motor behind a coupling left the finite range or
    passed ``v_fail``; sets the status and what diverged (``div_where``)."""
    v_fail = model.cycle.v_fail
    if not np.isfinite(st.v).all() or np.abs(st.v).max() > v_fail:
        rs.status, rs.div_where = C.DIVERGED, -1
        return True
    bad_shaft = ~(np.abs(sh.vs) <= v_fail)  # also NaN
    bad_motor = ~(np.abs(dr.vm) <= v_fail)
    if bad_shaft.any() or bad_motor.any():
        rs.status = C.DIVERGED
        rs.div_where = (-2 - int(np.flatnonzero(bad_motor)[-1]) if bad_motor.any()
                        else int(np.flatnonzero(bad_shaft)[-1]))
        return True
    return False


def _drive_results(model: Model, st, sh, dr, rs, out):
    """Per drive and per shaft after the start command: time and belt length slipped; per
    drive the time above its rated force and at its torque limit, and the force squared
    integrated until the belt is at rest after the stop (the RMS force)."""
    dt, shafts = model.cycle.dt, model.shafts
    fa = np.abs(dr.force)
    out.over_s += np.where(fa > model.drives.rated, dt, 0.0)
    if rs.stopping:
        out.over_stop_s += np.where(fa > model.drives.rated, dt, 0.0)
    out.lim_s += np.where((model.drives.control != C.DOL) & (dr.lim > 0.0)
                          & (np.abs(dr.force) >= dr.lim * (1.0 - 1e-9)), dt, 0.0)
    if not rs.stopped:
        out.f2_int += fa * fa * dt
        out.rms_s += dt
    slipping = sh.slip != 0.0
    out.shaft_slip_s += np.where(slipping, dt, 0.0)
    out.shaft_slip_m += np.where(slipping, np.abs(sh.vs - st.v[shafts.node]) * dt, 0.0)
    for k in range(len(model.drives.share)):
        s = model.drives.shaft[k]
        if sh.slip[s] != 0.0:
            out.slip_s[k] += dt
            out.slip_m[k] += abs(sh.vs[s] - st.v[shafts.node[s]]) * dt


def _observe(model: Model, st, sh, dr, rs, out) -> bool:
    """Envelopes of the new state, divergence (:func:`_diverged`) and runaway, the mean speed
    and, after the start command, the drives' slip (:func:`_drive_results`) and when the start
    was achieved. Returns False when the run ends here (diverged or ran away)."""
    out.t_max, out.t_min = np.fmax(out.t_max, st.tt), np.fmin(out.t_min, st.tt)
    if _diverged(model, st, sh, dr, rs):
        return False
    w = model.nodes.w_mean
    rs.v_mean = float(w @ st.v) / float(w.sum())
    v_d = model.cycle.v_d
    if abs(rs.v_mean) > C.RUNAWAY_FACTOR * v_d:
        rs.status = C.RUNAWAY  # the belt could not be held: a physical result
        return False
    if rs.started:
        _drive_results(model, st, sh, dr, rs, out)
        if rs.start_ach < 0.0 and rs.v_mean >= 0.99 * v_d:
            rs.start_ach = rs.t - model.cycle.t_pre
        if not rs.stopping and rs.v_mean > rs.vmean_hi:
            rs.vmean_hi, rs.vmean_hi_t = rs.v_mean, rs.t
    return True


def _switches(model: Model, st, rs):
    """After the step: the stop achieved, the belt stopped (holding brakes set, the rest
    begins: at 1 % of design speed, and on a controlled stop once its reference has run out;
    the run then ends after the rest), the time with a slack span."""
    cyc, t = model.cycle, rs.t
    if rs.stopping and rs.stop_ach < 0.0:
        rs.stop_dist += rs.v_mean * cyc.dt
    if rs.stopping and rs.stop_ach < 0.0 and rs.v_mean < C.REST_FRACTION * cyc.v_d:
        rs.stop_ach = t - rs.t_stopcmd
    if rs.stopping and not rs.stopped and rs.v_mean < C.REST_FRACTION * cyc.v_d and (
            cyc.stop_mode != C.CONTROLLED or t >= rs.t_stopcmd + cyc.t_stop):
        rs.stopped, rs.t_stopped = True, t
        rs.t_limit = min(t + cyc.post_rest, rs.t_end)  # at rest within the stop window
    if rs.stopped and t >= rs.t_limit and abs(rs.v_mean) > C.REST_FRACTION * cyc.v_d:
        # running back (or on) as a whole is not rest: the rest goes on, up to the stop
        # window's end
        rs.t_limit = min(t + cyc.dt, rs.t_stopcmd + cyc.stop_max, rs.t_end)
    if rs.started and st.tt.min() <= 0.0:
        rs.slack_s += cyc.dt


# --------------------------------------------------------------------------------------
# start and finish; the cycle


def _start(sys: System, t_end_s: float | None):
    """The run's constants (``ref``: the law, the free elements, the blocks with the master
    drive's first, each element's shaft, the arm and the mesh viscosity) and its state from
    rest: the belt (``st``), the shafts (``sh``), the drives (``dr``), the brakes (``brk``),
    the run record (``rs``: the take-up at its rest position, the integrator and the holding
    force, the end of the run) and the results (``out``: envelopes, slip)."""
    model = sys.model
    n, cyc, sp = sys.n, model.cycle, model.springs
    nd, ns, nb = len(model.drives.share), len(model.shafts.node), len(model.brakes.shaft)
    law = model.law
    free = np.ones(n, dtype=bool)
    for blk in sys.blocks:
        free[blk] = False
    m_node = int(model.drives.node[model.control.master])
    node_shaft = np.full(n, -1)
    node_shaft[model.shafts.node] = np.arange(ns)
    ref = SimpleNamespace(
        law=ExpandedLaw(sys) if law_windows(law.coef, law.pvv, law.psv, law.rtol) is not None
        else None, free=free, node_shaft=node_shaft, damp=_damper(sys), visc=_viscosity(model),
        blocks=sorted(sys.blocks, key=lambda b: 0 if m_node in b else 1))  # master's first
    te = np.maximum(sys.tension_rest_n, 0.0)
    ts = sp.eb * chord_strain(te, sp.a_ernst, sp.eb, sp.t_floor, sp.k_floor)
    st = SimpleNamespace(v=np.zeros(n), te=te.copy(), ts=ts, td=np.zeros(n), tt=te.copy())
    sh = SimpleNamespace(vs=np.zeros(ns), slip=np.zeros(ns), fb=np.zeros(ns))
    dr = SimpleNamespace(mode=[0] * nd, f0=np.zeros(nd), f1=np.zeros(nd), sat=[False] * nd,
                         win_f=np.zeros(nd),
                         lim=np.zeros(nd), lin=[None] * nd, vm=np.zeros(nd),
                         force=np.zeros(nd), ft=np.zeros(nd), f_trip=np.zeros(nd))
    brk = model.brakes._replace(t_cmd=np.full(nb, -1.0), released=np.zeros(nb, dtype=np.int64))
    t_stopcmd = cyc.t_pre + cyc.t_start + cyc.t_run
    t_limit = t_stopcmd + cyc.stop_max  # the stop window: a belt not at rest ends there
    t_end = float(t_end_s) if t_end_s else math.inf
    t_limit = min(t_limit, t_end)
    rs = SimpleNamespace(
        step=0, t=0.0, t_stopcmd=t_stopcmd, v_stop0=-1.0, t_limit=t_limit, t_end=t_end,
        status=C.OK,
        div_where=0,
        phase=C.HOLD, started=False, stopping=False, was_off=False, pi=False, pi_started=False,
        hold=-1, v_ref=0.0, a_ref=0.0, f0u=0.0, f1u=0.0, U=0.0, u_known=False,
        x_tu=0.0, u_tu=0.0, integ=0.0, hold_f=sys.hold_force_n, v_mean=0.0, w_drive=0.0,
        start_ach=-1.0, stop_ach=-1.0, stop_dist=0.0, stopped=False, t_stopped=-1.0, t_trip=-1.0,
        hold_set=-1.0, slack_s=0.0, verr_max=0.0, verr_t=-1.0, vmean_hi=0.0, vmean_hi_t=-1.0,
        f_brake=0.0, f_hb=0.0, fbr_max=0.0, fhb_max=0.0,
        x_range={"start": (math.inf, -math.inf), "stop": (math.inf, -math.inf)})
    out = SimpleNamespace(t_max=st.tt.copy(), t_min=st.tt.copy(), slip_s=np.zeros(nd),
                          slip_m=np.zeros(nd), shaft_slip_s=np.zeros(ns),
                          shaft_slip_m=np.zeros(ns), over_s=np.zeros(nd),
                          over_stop_s=np.zeros(nd), lim_s=np.zeros(nd),
                          f2_int=np.zeros(nd), rms_s=np.zeros(nd))
    return ref, st, sh, dr, brk, rs, out


def _finish(ref, st, sh, dr, rs, out) -> ReferenceResult:
    """The final state and the run's quantities."""
    return ReferenceResult(
        v=st.v, te=st.te, ts=st.ts, td=st.td, tension=st.tt, x_takeup=rs.x_tu, u_takeup=rs.u_tu,
        integrator=rs.integ, shaft_speed=sh.vs, shaft_slip=sh.slip, drive_force=dr.force,
        t_max=out.t_max, t_min=out.t_min, steps=rs.step, t_end=rs.t, status=rs.status,
        w_drive=rs.w_drive, start_ach=rs.start_ach, stop_ach=rs.stop_ach, stop_dist=rs.stop_dist,
        slip_s=out.slip_s,
        slip_m=out.slip_m, shaft_slip_s=out.shaft_slip_s, shaft_slip_m=out.shaft_slip_m,
        slack_s=rs.slack_s, t_trip=rs.t_trip, hold_set=rs.hold_set,
        law_evals=ref.law.evaluations if ref.law is not None else 0, div_where=rs.div_where,
        verr_max=rs.verr_max, verr_t=rs.verr_t, vmean_hi=rs.vmean_hi, vmean_hi_t=rs.vmean_hi_t,
        takeup_travel_start=max(rs.x_range["start"][1] - rs.x_range["start"][0], 0.0),
        takeup_travel_stop=max(rs.x_range["stop"][1] - rs.x_range["stop"][0], 0.0),
        over_s=out.over_s, over_stop_s=out.over_stop_s, lim_s=out.lim_s, f2_int=out.f2_int,
        rms_s=out.rms_s,
        f_brake=rs.f_brake, f_hb=rs.f_hb, fbr_max=rs.fbr_max, fhb_max=rs.fhb_max)


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
    model = sys.model
    dt = model.cycle.dt
    ref, st, sh, dr, brk, rs, out = _start(sys, t_end_s)
    max_steps = int(rs.t_limit / dt) + 2
    while rs.step < max_steps:
        rs.step += 1
        rs.t = rs.step * dt
        _phase(model, rs, sh, dr, brk)
        R0 = _resistances(model, ref, st)
        _free_elements(model, ref, st, R0)
        _blocks(model, ref, st, sh, dr, rs, R0)
        _spring_step(model, ref, st, rs)
        if not _observe(model, st, sh, dr, rs, out):
            break
        _switches(model, st, rs)
        if rs.t >= rs.t_limit:
            break
    return _finish(ref, st, sh, dr, rs, out)
