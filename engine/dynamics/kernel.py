"""The Euler-X kernel: the whole rest -> start -> run -> stop -> rest cycle in one call.

Semi-implicit (symplectic) Euler on plain float64 arrays (PHYSICS section 5; the seed
paper's Eq. 4 with the order of 4d changed: velocities first, then tensions from the new
velocities; the literal forward Euler of Eq. 4d is unstable on an undamped chain).

One step is a short sequence of named passes:

1. **phase**: the speed reference, what the drives do (hold at rest, run, off after a power
   failure or once the holding brakes have set), the brakes' forces (applied after their
   delay, ramped or along their force curve; holding brakes set once the belt has stopped)
   and each drive's force law for the step (:func:`_drive_laws`);
2. **resistance**: the friction model's law per element, exactly (:func:`passes.resistance`)
   or, for a law with fractional exponents (Non-Lin), its second-order expansion about each
   element's expansion point, which the last observe evaluated at the state; the elements
   whose speed or tension has left the window round that point are evaluated exactly and
   expanded again (:func:`passes.law_refresh`; the windows and the accuracy they give, 0.1 %
   of the law by default: :mod:`beltstudy.engine.dynamics.linlaw`);
3. **free elements**: explicit velocity update with the resistance implicit in closed form
   (:func:`passes.node_pass`);
4. **blocks**: the pulleys with their springs, shafts, drives, brakes and the take-up
   carriage, solved implicitly (:func:`blocks.block_step`), the master drive's block first so
   the speed loop's output is known to the others; then the speed loop's integrator;
5. **free springs**: elastic (Ernst tangent), relaxing arm and mesh viscosity
   (every segment in one call: :func:`passes.spring_segments`);
6. **observe**: envelopes, extremes (with the expanded law also the law at the new state and
   the elements outside their windows, :func:`passes.observe_lin`), divergence, per-drive slip
   and margins, the stop, slack, the envelope segments (cut at the stop command and when the
   belt first goes slack) and the records.

The numpy implementation of the same equations is :mod:`beltstudy.engine.dynamics.reference`.
"""

from __future__ import annotations

import math

from numba import njit, uintp

from beltstudy.engine.dynamics import codes as C
from beltstudy.engine.dynamics.blocks import block_step
from beltstudy.engine.dynamics.brakes import brake_force, set_at
from beltstudy.engine.dynamics.fastmath import OPTS
from beltstudy.engine.dynamics.laws import coupling_torque, motor_force
from beltstudy.engine.dynamics.passes import (
    extremes,
    law_flagged,
    law_refresh,
    node_pass,
    observe,
    observe_lin,
    resistance,
    slack_zones,
    spring_segments,
)
from beltstudy.engine.dynamics.profiles import FORCE, TORQUE, start_reference, stop_reference

__all__ = ["run_cycle"]

# what the drives do in a step
HOLD, RUN, OFF = C.HOLD, C.RUN, C.OFF


# --------------------------------------------------------------------------------------
# phase: the speed reference, brakes and drive laws of the step


@njit(inline="always", **OPTS)
def _dol_law(model, dk, vs, fac, t):
    """A dol drive's force law ``f0 + f1 v`` for the step: its motor curve linearised in the
    shaft speed, or through its coupling (the motor's speed eliminated over the step; the
    linearisation ``P``, ``D``, ``c_s`` kept for the motor's new speed); ``fac`` scales the
    motor's torque (1, or falling after a trip)."""
    drives = model.drives
    v_d = model.cycle.v_d
    rated = drives.rated[dk]
    n = drives.curve_n[dk]
    if drives.coupling[dk] == C.COUPLING_NONE:
        f, df = motor_force(drives.curve_x[dk], drives.curve_y[dk], n, rated, v_d, vs)
        f *= fac
        df *= fac
        f1 = min(df, 0.0)
        drives.f0[dk] = f - f1 * vs
        drives.f1[dk] = f1
        return
    vm = drives.vm[dk]
    fm, dfm = motor_force(drives.curve_x[dk], drives.curve_y[dk], n, rated, v_d, vm)
    fm *= fac
    dfm *= fac
    a1 = min(dfm, 0.0)
    a0 = fm - a1 * vm
    fill = 1.0
    if drives.coupling[dk] == C.COUPLING_FILL:
        fill = min(max((t - model.cycle.t_pre) / drives.fill_s[dk], 0.0), 1.0)
    tc, dtm, dts = coupling_torque(rated, v_d, vm, vs, fill)
    cm = max(dtm, 0.0)
    cs = min(dts, 0.0)
    c0 = tc - cm * vm - cs * vs
    mmd = drives.motor_mass[dk] / model.cycle.dt
    den = mmd - a1 + cm
    p = mmd * vm + a0 - c0
    drives.f0[dk] = c0 + cm * p / den
    drives.f1[dk] = cs * (mmd - a1) / den
    drives.lin_p[dk] = p
    drives.lin_d[dk] = den
    drives.lin_cs[dk] = cs


@njit(inline="always", **OPTS)
def _drive_laws(model, rs, first_off):
    """Each drive's force law for this step (modes of :class:`~beltstudy.engine.dynamics.
    records.Drives`): the speed loop's share (vfd running, relative formulation), an imposed
    shaft speed (vfd running, moving support), the motor curve through its coupling
    linearised in the shaft speed (dol), the open-loop force (verification), or the decaying
    force after a trip."""
    drives = model.drives
    shafts = model.shafts
    phase = rs.phase
    support = model.cycle.formulation == C.SUPPORT
    for dk in range(drives.share.shape[0]):
        drives.sat[dk] = 0
        drives.win_f[dk] = 0.0
        drives.lim[dk] = drives.lim0[dk]
        drives.lin_d[dk] = 0.0
        vs = shafts.vs[drives.shaft[dk]]
        fac = 1.0
        if phase == OFF:
            # power off: the motor's torque falls to zero over its trip time
            if first_off:
                drives.f_trip[dk] = drives.force[dk]
            ts = drives.trip_s[dk]
            fac = 0.0 if ts <= 0.0 else max(0.0, 1.0 - (rs.t - rs.t_trip) / ts)
        if phase == HOLD:
            # at rest: off; in the start's hand-over, the share of the holding force built
            # over t_hand while the hold keeps the belt
            drives.mode[dk] = 0
            f = 0.0 if not rs.started else drives.share[dk] * rs.hold_f * min(
                (rs.t - model.cycle.t_pre) / model.cycle.t_hand, 1.0)
            # within the drive's torque limit, as its share of the loop's output is after
            drives.f0[dk] = math.copysign(min(abs(f), drives.lim[dk]), f)
            drives.f1[dk] = 0.0
            continue
        if drives.control[dk] == C.DOL:
            drives.mode[dk] = 0
            _dol_law(model, dk, vs, fac, rs.t)
        elif phase == OFF:
            drives.mode[dk] = 0
            drives.f0[dk] = drives.f_trip[dk] * fac
            drives.f1[dk] = 0.0
        elif support:
            drives.mode[dk] = 2
        elif model.cycle.start_ctrl == FORCE and not rs.stopping:
            drives.mode[dk] = 0
            drives.f0[dk] = drives.share[dk] * model.control.f_const
            drives.f1[dk] = 0.0
        else:
            drives.mode[dk] = 1


@njit(inline="always", **OPTS)
def _brake_forces(model, rs):
    """Command, release and current force of every brake (its law:
    :func:`beltstudy.engine.dynamics.brakes.brake_force`); the force on each shaft. Returns
    the time the last holding brake is fully set (-1 while one is not)."""
    brakes = model.brakes
    shafts = model.shafts
    t = rs.t
    stopped = rs.stopped
    brake_mode = model.cycle.stop_mode == C.BRAKE
    for s in range(shafts.fb.shape[0]):
        shafts.fb[s] = 0.0
    any_hold = False
    pending = False
    latest = -1.0
    for b in range(brakes.shaft.shape[0]):
        if rs.stopping and brakes.t_cmd[b] < 0.0 and brakes.released[b] == 0:
            if brake_mode:
                brakes.t_cmd[b] = rs.t_stopcmd
            elif brakes.hold[b] == 1 and stopped:
                brakes.t_cmd[b] = rs.t_stopped
        if brakes.hold[b] == 0 and stopped and brakes.t_cmd[b] >= 0.0:
            brakes.released[b] = 1  # a brake without hold is released once the belt stopped
        f = 0.0
        s = brakes.shaft[b]
        if brakes.t_cmd[b] >= 0.0 and brakes.released[b] == 0:
            f = brake_force(brakes, b, t - brakes.t_cmd[b] - brakes.delay[b], shafts.vs[s])
        shafts.fb[s] += f
        if brakes.hold[b] == 1:
            any_hold = True
            if brakes.t_cmd[b] < 0.0:
                pending = True
            else:
                latest = max(latest, set_at(brakes, b))
    if not any_hold or pending or t < latest:
        return -1.0
    return latest


@njit(inline="always", **OPTS)
def _stop_from(model, rs):
    """The speed a controlled stop's ramp starts from, at its command. Design speed, the
    reference the loop followed; a master held at its limit short of it (a torque start, a
    drive at its torque limit) ramps from its own speed, and a master whose pulley slips from
    the belt's mean speed where that is lower (the pulley runs ahead of its belt); the
    integrator takes the force the drive gave (ramp-function generator tracking, bumpless).
    Ramped from design speed, a stop drove a belt at 1.7 m/s up to 3.5 m/s at the limit, and
    a belt at 2.6 m/s behind its slipping pulley up to 3.9 m/s."""
    cyc = model.cycle
    ctl = model.control
    sh = model.drives.shaft[ctl.master]
    rs.v_stop0 = cyc.v_d
    vm = model.shafts.vs[sh]
    if not rs.pi_started:
        return
    v0 = cyc.v_d
    if model.drives.sat[ctl.master] != 0:
        v0 = min(v0, vm)
    if model.shafts.slip[sh] != 0:
        v0 = min(v0, vm, rs.v_mean)
    if v0 < cyc.v_d:
        rs.v_stop0 = max(v0, 0.0)
        rs.integ = rs.U - ctl.kp * (rs.v_stop0 - vm)


@njit(inline="always", **OPTS)
def _phase(model, rs):
    """The step's phase: the speed reference (start or controlled stop), the drives' trip,
    what the drives do (hold at rest, run, off), the brakes' forces (:func:`_brake_forces`),
    each drive's law (:func:`_drive_laws`), whether the speed loop runs (switched on bumpless
    from the holding force), a torque start's ramped limits, and the speed loop's law ``U =
    f0u + f1u v`` (rigid-body feedforward, integrator, proportional gain)."""
    cyc = model.cycle
    ctl = model.control
    drives = model.drives
    t = rs.t
    rs.started = t > cyc.t_pre
    rs.stopping = t > rs.t_stopcmd
    rs.a_ref = 0.0
    if not rs.stopping:
        rs.v_ref, rs.a_ref = start_reference(cyc.start_ctrl, t - cyc.t_pre, cyc.t_start, cyc.v_d)
    elif cyc.stop_mode == C.CONTROLLED:
        if rs.v_stop0 < 0.0:
            _stop_from(model, rs)
        rs.v_ref, rs.a_ref = stop_reference(t - rs.t_stopcmd, cyc.t_stop, rs.v_stop0)
    else:
        rs.v_ref = 0.0
    if rs.stopping and rs.t_trip < 0.0:
        if cyc.stop_mode != C.CONTROLLED:
            rs.t_trip = rs.t_stopcmd
        elif rs.hold_set >= 0.0:
            rs.t_trip = rs.hold_set
    if not rs.started:
        rs.phase = HOLD
    elif rs.t_trip >= 0.0 and t > rs.t_trip:
        rs.phase = OFF
    elif t - cyc.t_pre <= cyc.t_hand:
        rs.phase = HOLD  # the hand-over: the drives build the holding force, the hold keeps
    else:
        rs.phase = RUN
    rs.hold_set = _brake_forces(model, rs)
    _drive_laws(model, rs, rs.phase == OFF and not rs.was_off)
    rs.was_off = rs.phase == OFF
    rs.pi = rs.phase == RUN and ctl.vfd and cyc.formulation != C.SUPPORT and (
        cyc.start_ctrl != FORCE or rs.stopping)
    if rs.pi and not rs.pi_started:
        # bumpless switch-on (Astrom & Hagglund, Advanced PID Control, 2006, *bumpless
        # transfer*): the integrator takes the drives' force before it (the holding force
        # after the hand-over, the open-loop force at a force start's stop command) less the
        # proportional term at the master's speed, so the loop's output goes on from there
        u0 = ctl.f_const if cyc.start_ctrl == FORCE else rs.hold_f
        rs.integ = u0 - ctl.kp * (rs.v_ref - model.shafts.vs[drives.shaft[ctl.master]])
        rs.pi_started = True
    if cyc.start_ctrl == TORQUE and not rs.stopping and rs.phase == RUN:
        ramp = min(max((t - cyc.t_pre) / cyc.t_start, 0.0), 1.0)
        for dk in range(drives.share.shape[0]):
            drives.lim[dk] = drives.lim0[dk] * ramp + drives.share[dk] * abs(rs.hold_f) * (
                1.0 - ramp)
    # rigid-body feedforward: inertia plus the running resistance (Te less the net gravity,
    # which the integrator already holds from rest), regularised like the belt
    f_ff = ctl.ff * (ctl.m_tot * rs.a_ref + ctl.f_res * min(max(rs.v_ref / ctl.v_ff, 0.0),
                                                             1.0))
    rs.f0u = f_ff + rs.integ + ctl.kp * rs.v_ref
    rs.f1u = -ctl.kp
    rs.hold = cyc.hold_node if rs.phase == HOLD else -1


# --------------------------------------------------------------------------------------
# the passes of one step


@njit(inline="always", **OPTS)
def _resistances(model, st, wk, rs):
    """The resistance law per element for this step into ``wk.r0``: exactly, or with the
    expanded law the elements the last observe found outside their windows."""
    law = model.law
    if law.mode == C.LAW_EXACT:
        resistance(law, model.nodes, st, wk)
    elif law.mode == C.LAW_LINEAR and rs.n_out > 0:
        # r0 holds the expanded law at this state (the last observe); the elements outside
        # their windows are evaluated exactly and expanded again
        lin = model.lin
        m = law_flagged(lin.flag64, lin.idx, rs.n_out)
        rs.law_evals += m
        law_refresh(lin.idx, m, st.v, st.tt, lin, wk.r0)


@njit(inline="always", **OPTS)
def _free_elements(model, st, wk, rs):
    """Explicit velocity update of the free elements; ``rs.vsum`` their weighted speed sum."""
    sp = model.springs
    nodes = model.nodes
    vsum = 0.0
    for k in range(sp.seg_node.shape[0]):
        vsum += node_pass(sp.seg_node[k, 0], sp.seg_node[k, 1], st.v, st.tt, nodes.hm,
                          nodes.gravity, wk.r0, model.cycle.v_eps, nodes.w_mean)
    rs.vsum = vsum


@njit(inline="always", **OPTS)
def _blocks(model, st, wk, rs):
    """Every implicit block (the master drive's first, so the speed loop's output is known to
    the others), the step's drive and brake totals, the take-up carriage's end stops; then the
    speed loop's integrator and the carriage's position."""
    tu = model.takeup
    blocks = model.blocks
    rs.f_tot = 0.0
    rs.p_tot = 0.0
    rs.f_brake = 0.0
    rs.f_hb = 0.0
    u_new = rs.u_tu
    rs.U = 0.0
    rs.u_known = not rs.pi
    for bk in range(blocks.ptr.shape[0] - 1):
        u_b, hit, hf, fbk, vs_b, ft_b, pt_b, w_b = block_step(bk, model, st, wk, rs)
        if tu.gravity and blocks.car[bk] == 1:
            u_new = u_b
            if hit >= 0.0:
                rs.endstop += 1
                if rs.endstop_t < 0.0:
                    rs.endstop_t = rs.t
                rs.endstop_speed = max(rs.endstop_speed, hit)
        if not math.isnan(hf) and not rs.started:
            rs.hold_f = hf  # what holds the belt at rest, up to the start command
        rs.f_brake += fbk
        rs.vsum += vs_b
        rs.f_tot += ft_b
        rs.p_tot += pt_b
        rs.w_drive += w_b
    rs.fbr_max = max(rs.fbr_max, rs.f_brake)
    rs.fhb_max = max(rs.fhb_max, rs.f_hb)
    if rs.pi:
        # conditional integration: not further into the torque limit
        drives = model.drives
        master = model.control.master
        e_v = rs.v_ref - model.shafts.vs[drives.shaft[master]]
        if drives.sat[master] == 0 or e_v * drives.f0[master] < 0.0:
            rs.integ += model.cycle.dt * model.control.ki * e_v
        # the master's tracking after the first wave loop time of the start, until the stop
        if not rs.stopping and rs.t - model.cycle.t_pre > model.control.t_track and abs(
                e_v) > rs.verr_max:
            rs.verr_max = abs(e_v)
            rs.verr_t = rs.t
    if tu.gravity:
        rs.u_tu = u_new
        rs.x_tu += model.cycle.dt * rs.u_tu
        rs.x_tu = min(max(rs.x_tu, tu.lo), tu.hi)
        rs.xmin = min(rs.xmin, rs.x_tu)
        rs.xmax = max(rs.xmax, rs.x_tu)
        if rs.stopping:
            rs.xlo_stop = min(rs.xlo_stop, rs.x_tu)
            rs.xhi_stop = max(rs.xhi_stop, rs.x_tu)
        elif rs.started:
            rs.xlo_start = min(rs.xlo_start, rs.x_tu)
            rs.xhi_start = max(rs.xhi_start, rs.x_tu)


@njit(inline="always", **OPTS)
def _free_springs(model, st, wk):
    """The free springs from the new velocities."""
    spring_segments(st, model.springs, wk.more)


# --------------------------------------------------------------------------------------
# observe: envelopes, extremes, divergence, per-drive results


@njit(inline="always", **OPTS)
def _diverged(model, rs):
    """Whether the belt, a pulley shaft or a motor behind a coupling left the finite range or
    passed ``v_fail``; sets the status and what diverged (``div_where``)."""
    v_fail = model.cycle.v_fail
    if not math.isfinite(rs.vsum) or rs.vhi > v_fail or rs.vlo < -v_fail:
        rs.status = C.DIVERGED
        rs.div_where = -1
        return True
    # the shafts (a slipping one leaves the belt) and the motors behind couplings
    shafts = model.shafts
    for s in range(shafts.node.shape[0]):
        if not abs(shafts.vs[s]) <= v_fail:  # also NaN
            rs.status = C.DIVERGED
            rs.div_where = s
    drives = model.drives
    for dk in range(drives.share.shape[0]):
        if not abs(drives.vm[dk]) <= v_fail:
            rs.status = C.DIVERGED
            rs.div_where = -2 - dk
    return rs.status == C.DIVERGED


@njit(inline="always", **OPTS)
def _drive_results(model, st, out, rs):
    """Per drive after the start command: largest force and power, the slip margin with the
    tensions on both sides of its pulley, time and belt length slipped, time above the rated
    force and at the torque limit, the force squared integrated until the belt is at rest; per
    shaft the same slip."""
    shafts = model.shafts
    drives = model.drives
    dt = model.cycle.dt
    tt = st.tt
    n = tt.shape[0]
    t = rs.t
    for dk in range(drives.share.shape[0]):
        d = out.drv[dk]
        s = drives.shaft[dk]
        j = shafts.node[s]
        jm = j - 1 if j > 0 else n - 1
        # the force's extremes over the step are at its ends (it is linear in the shaft's
        # speed, monotone over the step): the start of a step matters after a switch
        f = max(abs(drives.force[dk]), abs(drives.f_start[dk]))
        if f > d.fmax:
            d.fmax = f
            d.fmax_t = t
        pw = abs(drives.force[dk] * shafts.vs[s])
        if pw > d.pmax:
            d.pmax = pw
        # the motor's load: time above the rated force, time at the torque limit, the force
        # squared integrated until the belt is at rest after the stop (the RMS force)
        fa = abs(drives.force[dk])
        if fa > drives.rated[dk]:
            d.over_s += dt
            if rs.stopping:
                d.over_stop_s += dt
        # at its torque limit: a vfd drive's force there (to the last bits: a follower rated
        # in proportion to its share meets its limit when the master does, whichever way a
        # rounded size tips it); a saturated share its speed window holds lower is not; a dol
        # motor has no torque limit (its curve is its force)
        if (drives.control[dk] != C.DOL and drives.lim[dk] > 0.0
                and fa >= drives.lim[dk] * (1.0 - 1e-9)):
            d.lim_s += dt
        if not rs.stopped:
            d.f2_int += fa * fa * dt
            d.rms_s += dt
        # the margin of the force the pulley passes (its capstan law's): e^(mu theta) T_slack
        # over T_slack + |F_belt|, 1 at the grip; the tensions of the springs beside it add
        # the pulley element's own inertia (a breakaway's spike, resolved higher the shorter
        # the step), so a sliding pulley is 1 at most, and 0 with its slack side slack (no
        # grip at all); a sticking pulley slack on both sides has no reading (1e300)
        hi_ = max(tt[j], tt[jm])
        lo_t = min(tt[j], tt[jm])
        if shafts.slip[s] != 0.0:
            mg = (0.0 if lo_t <= 0.0 else
                  min((shafts.cs[s] + 1.0) * lo_t / (lo_t + abs(drives.ft[dk])), 1.0))
        elif hi_ > 0.0:
            lo_ = max(lo_t, 1.0)
            mg = (shafts.cs[s] + 1.0) * lo_ / (lo_ + abs(drives.ft[dk]))
        else:
            mg = 1e300
        if mg < d.slip_min:
            d.slip_min = mg
            d.slip_min_t = t
        if mg < rs.slip_min:
            rs.slip_min = mg
            rs.slip_min_t = t
        if shafts.slip[s] != 0.0:
            d.slip_s += dt
            d.slip_m += abs(shafts.vs[s] - st.v[j]) * dt
            if d.slip_first < 0.0:
                d.slip_first = t
            d.slip_last = t
    for s in range(shafts.node.shape[0]):
        if shafts.slip[s] != 0.0:
            h = out.shs[s]
            h.slip_s += dt
            h.slip_m += abs(shafts.vs[s] - st.v[shafts.node[s]]) * dt
            if h.first < 0.0:
                h.first = t
            h.last = t


@njit(inline="always", **OPTS)
def _observe(model, st, out, wk, rs):
    """Envelopes and extremes of the new state (with the expanded law also the law at the new
    state, :func:`passes.observe_lin`), divergence and runaway, the cycle's extremes and, after
    the start command, the drives' results and when the start was achieved. Returns False
    when the run ends here (diverged or ran away)."""
    rs.v_mean = rs.vsum * rs.inv_w_sum
    if model.law.mode == C.LAW_LINEAR:
        rs.tlo, rs.thi, rs.vlo, rs.vhi, rs.n_out = observe_lin(st, out.t_max, out.t_min,
                                                               model.lin, wk.r0)
    else:
        rs.tlo, rs.thi, rs.vlo, rs.vhi = observe(st.tt, st.v, out.t_max, out.t_min)
    if _diverged(model, rs):
        return False
    if abs(rs.v_mean) > C.RUNAWAY_FACTOR * model.cycle.v_d:
        rs.status = C.RUNAWAY  # a physical result: the belt could not be held
        return False
    t = rs.t
    if rs.vhi > rs.vmax:
        rs.vmax = rs.vhi
        rs.vmax_t = t
    if rs.vlo < rs.vmin:
        rs.vmin = rs.vlo
        rs.vmin_t = t
    if rs.thi > rs.tmax:
        rs.tmax = rs.thi
        rs.tmax_t = t
    if rs.tlo < rs.tmin:
        rs.tmin = rs.tlo
        rs.tmin_t = t
    if rs.started:
        f_start = 0.0
        for dk in range(model.drives.share.shape[0]):
            f_start += model.drives.f_start[dk]
        af = max(abs(rs.f_tot), abs(f_start))
        if af > rs.fmax:
            rs.fmax = af
            rs.fmax_t = t
        if abs(rs.p_tot) > rs.pmax:
            rs.pmax = abs(rs.p_tot)
        _drive_results(model, st, out, rs)
        if rs.start_ach < 0.0 and rs.v_mean >= 0.99 * model.cycle.v_d:
            rs.start_ach = t - model.cycle.t_pre
        if not rs.stopping and rs.v_mean > rs.vmean_hi:
            rs.vmean_hi = rs.v_mean
            rs.vmean_hi_t = t
    return True


# --------------------------------------------------------------------------------------
# the phase switches after a step: stop, slack, envelope segments


@njit(**OPTS)
def _envelope_times(t, t_max, t_min, snap_max, snap_min, t_max_t, t_min_t):
    """Stamp the springs whose envelope grew since the last record with time t."""
    for jj in range(t_max.shape[0]):
        # the envelopes only grow, so the snapshots can be copied unconditionally (selects
        # and plain stores: LLVM vectorises them)
        j = uintp(jj)
        hi = t_max[j]
        lo = t_min[j]
        t_max_t[j] = t if hi > snap_max[j] else t_max_t[j]
        t_min_t[j] = t if lo < snap_min[j] else t_min_t[j]
        snap_max[j] = hi
        snap_min[j] = lo


@njit(**OPTS)
def _archive_segment(seg, t, out):
    """Copy the current envelopes into segment ``seg`` and close it at time t."""
    for j in range(out.t_max.shape[0]):
        out.seg_env[seg, 0, j] = out.t_max[j]
        out.seg_env[seg, 1, j] = out.t_max_t[j]
        out.seg_env[seg, 2, j] = out.t_min[j]
        out.seg_env[seg, 3, j] = out.t_min_t[j]
    out.seg_time[seg, 1] = t


@njit(**OPTS)
def _cut_segment(seg, t, tt, out, wk):
    """Close the envelope segment ``seg`` at time t and start the next from the tensions now."""
    _envelope_times(t, out.t_max, out.t_min, wk.t_max_snap, wk.t_min_snap, out.t_max_t,
                    out.t_min_t)
    _archive_segment(seg, t, out)
    for j in range(tt.shape[0]):
        out.t_max[j] = tt[j]
        out.t_min[j] = tt[j]
        out.t_max_t[j] = t
        out.t_min_t[j] = t
        wk.t_max_snap[j] = tt[j]
        wk.t_min_snap[j] = tt[j]
    if seg + 1 < out.seg_time.shape[0]:
        out.seg_time[seg + 1, 0] = t
    return seg + 1


@njit(inline="always", **OPTS)
def _switches(model, st, out, wk, rs):
    """After the step: the stop achieved, the belt stopped (holding brakes set, the rest
    begins: at 1 % of design speed, and on a controlled stop once its reference has run out;
    a belt running back or on as a whole when the rest would end is not at rest, and the run
    goes on), slack (the belt length gathered by the slack spans, the time with a slack span), and the
    envelope cut at the start command (the rest before it a segment of its own: SPEC 6.4's
    start phase begins there), when the belt first goes slack and at the stop command."""
    cyc = model.cycle
    t = rs.t
    if rs.stopping and rs.stop_ach < 0.0:
        rs.stop_dist += rs.v_mean * cyc.dt  # the belt's travel in the stop [m]
    if rs.stopping and rs.stop_ach < 0.0 and rs.v_mean < C.REST_FRACTION * cyc.v_d:
        rs.stop_ach = t - rs.t_stopcmd
    if rs.stopping and not rs.stopped and rs.v_mean < C.REST_FRACTION * cyc.v_d and (
            cyc.stop_mode != C.CONTROLLED or t >= rs.t_stopcmd + cyc.t_stop):
        rs.stopped = True
        rs.t_stopped = t
        rs.t_end_limit = t + cyc.post_rest  # came to rest within the stop window
        if cyc.t_end > 0.0:
            rs.t_end_limit = min(rs.t_end_limit, cyc.t_end)
    if rs.stopped and t >= rs.t_end_limit and abs(rs.v_mean) > C.REST_FRACTION * cyc.v_d:
        # running back (or on, forwards) as a whole is not rest: the rest goes on, up to the
        # stop window's end (a belt speeding up backwards then ends as a runaway, not 4.2 m/s
        # backwards; a loaded decline whose brake without hold let go at rest, 0.77 m/s
        # forwards and speeding up, ended 'ok')
        lim = min(t + cyc.dt, rs.t_stopcmd + cyc.stop_max)
        rs.t_end_limit = min(lim, cyc.t_end) if cyc.t_end > 0.0 else lim
    nseg = out.seg_time.shape[0]
    # the step before this one, as its own time was computed (steps x dt): t - dt can round
    # past it (a stop command at 62 s on a 1 ms step: t = 62001 x 0.001 = 62.001000000000005,
    # t - dt = 62.00000000000001 > 62), and the cut at the command was then never made
    t_prev = (rs.steps - 1) * cyc.dt
    if rs.started and rs.seg == 0 and t_prev <= cyc.t_pre and nseg > 1:
        rs.seg = _cut_segment(rs.seg, t, st.tt, out, wk)
    if rs.tlo <= 0.0 and rs.started:
        rs.slack_dur += cyc.dt
        sp = model.springs
        total, deep = slack_zones(st.ts, st.tt, sp.eb, sp.len_m, sp.eps_run)
        rs.slack_m = total
        if total > rs.slack_max:
            rs.slack_max = total
            rs.slack_at = deep
            rs.slack_time = t
        if rs.slack_first < 0.0:
            rs.slack_first = t
            if rs.seg + 1 < nseg:
                rs.seg = _cut_segment(rs.seg, t, st.tt, out, wk)
    elif rs.slack_m > 0.0:
        rs.slack_m = 0.0
    if rs.stopping and t_prev <= rs.t_stopcmd and rs.seg + 1 < nseg:
        rs.seg = _cut_segment(rs.seg, t, st.tt, out, wk)


# --------------------------------------------------------------------------------------
# records


@njit(**OPTS)
def _record(pr, shafts, drives, master, i_tu, st, out, rs, vabs):
    """One record of the key points (:data:`~beltstudy.engine.dynamics.records.RECORD`), the
    probe springs (``pr``, :class:`~beltstudy.engine.dynamics.records.Probes`) and the drives
    at ``rs.t``: the master drive's shaft speed, the take-up pulley ``i_tu``'s tension;
    ``vabs`` the largest |speed| [m/s]. (A separate function taking the records it reads: the
    kernel calls it at the start, every record and at the end.)"""
    if rs.nrec >= out.rec.shape[0]:
        return
    tt = st.tt
    v = st.v
    r = out.rec[rs.nrec]
    r.t = rs.t
    r.v_drive = shafts.vs[drives.shaft[master]]
    r.v_tail = v[pr.i_tail]
    r.f_drive = rs.f_tot
    r.t_head_in = tt[pr.s_head_in]
    r.t_head_out = tt[pr.s_head_out]
    r.t_tail = tt[pr.i_tail]
    r.t_takeup = 0.5 * (tt[i_tu - 1] + tt[i_tu])
    r.x_tu = rs.x_tu
    r.t_min = rs.tlo
    r.t_max = rs.thi
    r.v_mean = rs.v_mean
    r.f_brake = rs.f_brake
    r.v_ref = rs.v_ref
    r.p_drive = rs.p_tot
    r.v_abs = vabs
    r.slack_m = rs.slack_m
    r.f_holdback = rs.f_hb
    for k in range(pr.probes.shape[0]):
        out.rec_t[rs.nrec, k] = tt[pr.probes[k]]
        out.rec_v[rs.nrec, k] = v[pr.probes[k]]
    for dk in range(drives.share.shape[0]):
        d = out.rec_d[rs.nrec, dk]
        d.f = drives.force[dk]
        d.v = shafts.vs[drives.shaft[dk]]
        d.ft = drives.ft[dk]
        d.vm = drives.vm[dk] if drives.coupling[dk] != 0 else shafts.vs[drives.shaft[dk]]
    rs.nrec += 1


@njit(inline="always", **OPTS)
def _record_now(model, st, out, rs, vabs):
    """:func:`_record` with the records it reads."""
    _record(model.probes, model.shafts, model.drives, model.control.master, model.takeup.node,
            st, out, rs, vabs)


@njit(**OPTS)
def _record_surface(probes, st, out, rs):
    """One row of the surface: the tension and speed of the surface springs at ``rs.t``."""
    if rs.nsurf >= out.surf_t.shape[0]:
        return
    out.surf_t[rs.nsurf, 0] = rs.t
    idx = probes.surface
    for k in range(idx.shape[0]):
        out.surf_t[rs.nsurf, k + 1] = st.tt[idx[k]]
        out.surf_v[rs.nsurf, k] = st.v[idx[k]]
    rs.nsurf += 1


@njit(inline="always", **OPTS)
def _records(model, st, out, wk, rs):
    """The records and the surface due at this step, with the envelopes' times."""
    dt = model.cycle.dt
    t = rs.t
    if t + 0.5 * dt >= rs.nrec * model.cycle.rec_dt:
        _record_now(model, st, out, rs, max(rs.vhi, -rs.vlo))
        _envelope_times(t, out.t_max, out.t_min, wk.t_max_snap, wk.t_min_snap, out.t_max_t,
                        out.t_min_t)
    if t + 0.5 * dt >= rs.nsurf * model.cycle.surf_dt:
        _record_surface(model.probes, st, out, rs)


# --------------------------------------------------------------------------------------
# start and finish


@njit(inline="always", **OPTS)
def _start(model, st, out, wk, rs):
    """The run's initial values: the law at the initial state, envelopes from the rest
    tensions, empty results, the end of the run, the first record. The take-up, the speed
    loop's integrator and the holding force come set in ``rs`` (at rest)."""
    cyc = model.cycle
    law = model.law
    v = st.v
    tt = st.tt
    n = tt.shape[0]
    w_sum = 0.0
    for j in range(n):
        w_sum += model.nodes.w_mean[j]
    rs.inv_w_sum = 1.0 / w_sum
    if law.mode == C.LAW_CONST:
        for j in range(n):
            wk.r0[j] = law.coef[0, j]
    elif law.mode == C.LAW_LINEAR:
        # the exact law at the initial state, and its expansion about it, for every element
        for j in range(n):
            model.lin.idx[j] = j
        law_refresh(model.lin.idx, n, v, tt, model.lin, wk.r0)
    for j in range(n):
        out.t_max[j] = tt[j]
        out.t_min[j] = tt[j]
        out.t_max_t[j] = 0.0
        out.t_min_t[j] = 0.0
        wk.t_max_snap[j] = tt[j]
        wk.t_min_snap[j] = tt[j]
    for dk in range(out.drv.shape[0]):
        out.drv[dk].slip_min = 1e300
        out.drv[dk].slip_first = -1.0
        out.drv[dk].slip_last = -1.0
    for s in range(model.shafts.node.shape[0]):
        out.shs[s].first = -1.0
        out.shs[s].last = -1.0
    out.seg_time[0, 0] = 0.0
    rs.slip_min = 1e300
    rs.endstop_t = -1.0
    rs.start_ach = -1.0
    rs.stop_ach = -1.0
    rs.stop_dist = 0.0
    rs.t_stopped = -1.0
    rs.t_trip = -1.0
    rs.hold_set = -1.0
    rs.slack_at = -1
    rs.slack_time = -1.0
    rs.slack_first = -1.0
    rs.tmin, rs.tmax = extremes(tt)
    rs.xmin = rs.x_tu
    rs.xmax = rs.x_tu
    rs.xlo_start = 1e300
    rs.xhi_start = -1e300
    rs.xlo_stop = 1e300
    rs.xhi_stop = -1e300
    rs.verr_t = -1.0
    rs.vmean_hi_t = -1.0
    rs.t_stopcmd = cyc.t_pre + cyc.t_start + cyc.t_run
    rs.v_stop0 = -1.0
    rs.t_end_limit = rs.t_stopcmd + cyc.stop_max  # the stop window: not at rest, ends there
    if cyc.t_end > 0.0:
        rs.t_end_limit = min(rs.t_end_limit, cyc.t_end)
    if not model.control.vfd:
        for dk in range(model.drives.vm.shape[0]):
            model.drives.vm[dk] = 0.0
    v_mean = 0.0
    for j in range(n):
        v_mean += model.nodes.w_mean[j] * v[j]
    rs.v_mean = v_mean * rs.inv_w_sum
    rs.tlo = rs.tmin
    rs.thi = rs.tmax
    _record_now(model, st, out, rs, 0.0)
    _record_surface(model.probes, st, out, rs)


@njit(inline="always", **OPTS)
def _finish(model, st, out, wk, rs):
    """After the last step: a last record at the end time, the envelopes' times, the last
    envelope segment archived."""
    t = rs.t
    dt = model.cycle.dt
    if rs.status != C.DIVERGED and rs.nrec > 0 and out.rec[rs.nrec - 1].t < t - 0.5 * dt:
        rs.tlo, rs.thi = extremes(st.tt)
        vlo, vhi = extremes(st.v)
        _record_now(model, st, out, rs, max(vhi, -vlo))
    _envelope_times(t, out.t_max, out.t_min, wk.t_max_snap, wk.t_min_snap, out.t_max_t,
                    out.t_min_t)
    _archive_segment(rs.seg, t, out)


#: What :func:`run_cycle` returns when it paused before ``t_pause`` (not a run status).
PAUSED = -1


@njit(**OPTS)
def run_cycle(model, st, out, wk, t_pause):
    """Integrate the whole cycle (see the module docstring for one step).

    ``model`` (:class:`~beltstudy.engine.dynamics.records.Model`) from
    :func:`beltstudy.engine.dynamics.model.build_system` with fresh state arrays; ``st`` the
    belt at rest, updated in place (it holds the final state on return, as do the shafts' speeds
    and slip and the drives' motor speeds); ``out`` receives the records, the surface, the
    envelope segments, the per-drive and per-shaft results and the run's scalars
    (``out.run[0]``, :data:`~beltstudy.engine.dynamics.records.RUN`); ``wk`` scratch. Returns
    the run's status (:mod:`beltstudy.engine.dynamics.codes`).

    ``t_pause`` >= 0 pauses before the first step whose time is past it and returns
    :data:`PAUSED` (the stop command: every array then holds the state after the last step
    at or before it); called again with the same arrays (``out.run[0].steps`` > 0) the run
    goes on from there, step for step as if it had not paused. ``t_pause`` < 0: no pause.
    """
    rs = out.run[0]
    if rs.steps == 0:
        _start(model, st, out, wk, rs)
    dt = model.cycle.dt
    max_steps = int(rs.t_end_limit / dt) + 2
    while rs.steps < max_steps:
        if t_pause >= 0.0 and (rs.steps + 1) * dt > t_pause:
            return PAUSED
        rs.steps += 1
        rs.t = rs.steps * dt
        _phase(model, rs)
        _resistances(model, st, wk, rs)
        _free_elements(model, st, wk, rs)
        _blocks(model, st, wk, rs)
        _free_springs(model, st, wk)
        if not _observe(model, st, out, wk, rs):
            break
        _switches(model, st, out, wk, rs)
        _records(model, st, out, wk, rs)
        if rs.t >= rs.t_end_limit:
            break
    _finish(model, st, out, wk, rs)
    return rs.status
