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
   (:func:`passes.spring_pass`);
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
from beltstudy.engine.dynamics.fastmath import OPTS
from beltstudy.engine.dynamics.laws import brake_fraction, coupling_torque, motor_force
from beltstudy.engine.dynamics.passes import (
    extremes,
    law_flagged,
    law_refresh,
    node_pass,
    observe,
    observe_lin,
    resistance,
    slack_zones,
    spring_pass,
)
from beltstudy.engine.dynamics.profiles import FORCE, TORQUE, start_reference, stop_reference

__all__ = ["run_cycle"]

# what the drives do in a step
HOLD, RUN, OFF = C.HOLD, C.RUN, C.OFF


@njit(inline="always", **OPTS)
def _drive_laws(drives, shafts, fp, ip, phase, t, t_pre, t_trip, stopping, first_off):
    """Each drive's force law for this step (modes of :class:`~beltstudy.engine.dynamics.arrays.Drives`):
    the speed loop's share (vfd running, relative formulation), an imposed shaft speed (vfd
    running, moving support), the motor curve through its coupling linearised in the shaft
    speed (dol), the open-loop force (verification), or the decaying force after a trip."""
    nd = drives.share.shape[0]
    v_d = fp[C.FP_V_D]
    dt = fp[C.FP_DT]
    support = ip[C.IP_FORMULATION] == C.SUPPORT
    for dk in range(nd):
        drives.sat[dk] = 0
        drives.lim[dk] = drives.lim0[dk]
        drives.lin_d[dk] = 0.0
        s = drives.shaft[dk]
        vs = shafts.vs[s]
        fac = 1.0
        if phase == OFF:
            # power off: the motor's torque falls to zero over its trip time
            if first_off:
                drives.f_trip[dk] = drives.force[dk]
            ts = drives.trip_s[dk]
            fac = 0.0 if ts <= 0.0 else max(0.0, 1.0 - (t - t_trip) / ts)
        if phase == HOLD:
            drives.mode[dk] = 0
            drives.f0[dk] = 0.0
            drives.f1[dk] = 0.0
            continue
        if drives.control[dk] == C.DOL:
            drives.mode[dk] = 0
            rated = drives.rated[dk]
            n = drives.curve_n[dk]
            if drives.coupling[dk] == C.COUPLING_NONE:
                f, df = motor_force(drives.curve_x[dk], drives.curve_y[dk], n, rated, v_d, vs)
                f *= fac
                df *= fac
                f1 = min(df, 0.0)
                drives.f0[dk] = f - f1 * vs
                drives.f1[dk] = f1
            else:
                vm = drives.vm[dk]
                fm, dfm = motor_force(drives.curve_x[dk], drives.curve_y[dk], n, rated, v_d, vm)
                fm *= fac
                dfm *= fac
                a1 = min(dfm, 0.0)
                a0 = fm - a1 * vm
                fill = 1.0
                if drives.coupling[dk] == C.COUPLING_FILL:
                    fill = min(max((t - t_pre) / drives.fill_s[dk], 0.0), 1.0)
                tc, dtm, dts = coupling_torque(rated, v_d, vm, vs, fill)
                cm = max(dtm, 0.0)
                cs = min(dts, 0.0)
                c0 = tc - cm * vm - cs * vs
                mmd = drives.motor_mass[dk] / dt
                den = mmd - a1 + cm
                p = mmd * vm + a0 - c0
                drives.f0[dk] = c0 + cm * p / den
                drives.f1[dk] = cs * (mmd - a1) / den
                drives.lin_p[dk] = p
                drives.lin_d[dk] = den
                drives.lin_cs[dk] = cs
        elif phase == OFF:
            drives.mode[dk] = 0
            drives.f0[dk] = drives.f_trip[dk] * fac
            drives.f1[dk] = 0.0
        elif support:
            drives.mode[dk] = 2
        elif ip[C.IP_START_CTRL] == FORCE and not stopping:
            drives.mode[dk] = 0
            drives.f0[dk] = drives.share[dk] * fp[C.FP_F_CONST]
            drives.f1[dk] = 0.0
        else:
            drives.mode[dk] = 1


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
def _cut_segment(seg, t, tt, out, wk):
    """Close the envelope segment ``seg`` at time t and start the next from the tensions now."""
    _envelope_times(t, out.t_max, out.t_min, wk.t_max_snap, wk.t_min_snap, out.t_max_t,
                    out.t_min_t)
    n = tt.shape[0]
    for j in range(n):
        out.seg_env[seg, 0, j] = out.t_max[j]
        out.seg_env[seg, 1, j] = out.t_max_t[j]
        out.seg_env[seg, 2, j] = out.t_min[j]
        out.seg_env[seg, 3, j] = out.t_min_t[j]
        out.t_max[j] = tt[j]
        out.t_min[j] = tt[j]
        out.t_max_t[j] = t
        out.t_min_t[j] = t
        wk.t_max_snap[j] = tt[j]
        wk.t_min_snap[j] = tt[j]
    out.seg_time[seg, 1] = t
    if seg + 1 < out.seg_time.shape[0]:
        out.seg_time[seg + 1, 0] = t
    return seg + 1


@njit(**OPTS)
def _record(nrec, t, st, ip, shafts, drives, x_tu, f_tot, v_mean, f_brake, v_ref, p_tot, tlo,
            thi, vabs, slack_m, out):
    rec = out.rec
    if nrec >= rec.shape[0]:
        return nrec
    tt = st.tt
    v = st.v
    i_tu = ip[C.IP_I_TU]
    ms = drives.shaft[ip[C.IP_M_DRIVE]]
    rec[nrec, C.REC_T] = t
    rec[nrec, C.REC_V_DRIVE] = shafts.vs[ms]
    rec[nrec, C.REC_V_TAIL] = v[ip[C.IP_I_TAIL]]
    rec[nrec, C.REC_F_DRIVE] = f_tot
    rec[nrec, C.REC_T_HEAD_IN] = tt[ip[C.IP_S_HEAD_IN]]
    rec[nrec, C.REC_T_HEAD_OUT] = tt[ip[C.IP_S_HEAD_OUT]]
    rec[nrec, C.REC_T_TAIL] = tt[ip[C.IP_I_TAIL]]
    rec[nrec, C.REC_T_TAKEUP] = 0.5 * (tt[i_tu - 1] + tt[i_tu])
    rec[nrec, C.REC_X_TU] = x_tu
    rec[nrec, C.REC_T_MIN] = tlo
    rec[nrec, C.REC_T_MAX] = thi
    rec[nrec, C.REC_V_MEAN] = v_mean
    rec[nrec, C.REC_F_BRAKE] = f_brake
    rec[nrec, C.REC_V_REF] = v_ref
    rec[nrec, C.REC_P_DRIVE] = p_tot
    rec[nrec, C.REC_V_ABS] = vabs
    rec[nrec, C.REC_SLACK_M] = slack_m
    for k in range(out.probes.shape[0]):
        out.rec_t[nrec, k] = tt[out.probes[k]]
        out.rec_v[nrec, k] = v[out.probes[k]]
    for dk in range(drives.share.shape[0]):
        out.rec_d[nrec, dk, C.RECD_F] = drives.force[dk]
        out.rec_d[nrec, dk, C.RECD_V] = shafts.vs[drives.shaft[dk]]
        out.rec_d[nrec, dk, C.RECD_FT] = drives.ft[dk]
    return nrec + 1


@njit(**OPTS)
def _record_surface(nsurf, t, v, tt, out):
    if nsurf >= out.surf_t.shape[0]:
        return nsurf
    out.surf_t[nsurf, 0] = t
    idx = out.surf_idx
    for k in range(idx.shape[0]):
        out.surf_t[nsurf, k + 1] = tt[idx[k]]
        out.surf_v[nsurf, k] = v[idx[k]]
    return nsurf + 1


@njit(inline="always", **OPTS)
def _brake_forces(brakes, shafts, t, t_stopcmd, stopping, brake_mode, stopped, t_stopped):
    """Command, release and current force of every brake; the force on each shaft. Returns
    the time the last holding brake is fully set (-1 while one is not)."""
    ns = shafts.fb.shape[0]
    for s in range(ns):
        shafts.fb[s] = 0.0
    nb = brakes.shaft.shape[0]
    any_hold = False
    pending = False
    latest = -1.0
    for b in range(nb):
        if stopping and brakes.t_cmd[b] < 0.0 and brakes.released[b] == 0:
            if brake_mode:
                brakes.t_cmd[b] = t_stopcmd
            elif brakes.hold[b] == 1 and stopped:
                brakes.t_cmd[b] = t_stopped
        if brakes.hold[b] == 0 and stopped and brakes.t_cmd[b] >= 0.0:
            brakes.released[b] = 1  # a brake without hold is released once the belt stopped
        f = 0.0
        if brakes.t_cmd[b] >= 0.0 and brakes.released[b] == 0:
            tau = t - brakes.t_cmd[b] - brakes.delay[b]
            f = brakes.force[b] * brake_fraction(tau, brakes.ramp[b], brakes.curve_t[b],
                                                  brakes.curve_f[b], brakes.curve_n[b])
        shafts.fb[brakes.shaft[b]] += f
        if brakes.hold[b] == 1:
            any_hold = True
            if brakes.t_cmd[b] < 0.0:
                pending = True
            else:
                nc = brakes.curve_n[b]
                full = brakes.curve_t[b, nc - 1] if nc > 0 else brakes.ramp[b]
                latest = max(latest, brakes.t_cmd[b] + brakes.delay[b] + full)
    if not any_hold or pending or t < latest:
        return -1.0
    return latest


@njit(**OPTS)
def run_cycle(fp, ip, nodes, law, lin, sp, blocks, shafts, drives, brakes, st, out, wk):
    """Integrate the whole cycle (see the module docstring for one step).

    Arrays are prepared by :func:`beltstudy.engine.dynamics.simulate.prepare` (groups in
    :mod:`beltstudy.engine.dynamics.arrays`). The state (``st``, the shafts' speeds and slip, the
    drives' motor speeds) is updated in place and holds the final state on return; ``out``
    receives the records, the surface, the envelope segments, the per-drive results and the
    run scalars of :data:`beltstudy.engine.dynamics.codes.RES`.
    """
    n = ip[C.IP_N]
    dt = fp[C.FP_DT]
    t_pre = fp[C.FP_T_PRE]
    t_start = fp[C.FP_T_START]
    t_stopcmd = t_pre + t_start + fp[C.FP_T_RUN]
    t_stopdur = fp[C.FP_T_STOP]
    v_d = fp[C.FP_V_D]
    v_eps = fp[C.FP_V_EPS]
    eb = fp[C.FP_EB]
    e_damp = fp[C.FP_E_DAMP]
    g_damp = fp[C.FP_G_DAMP]
    kp = fp[C.FP_KP]
    ki = fp[C.FP_KI]
    m_tot = fp[C.FP_M_TOT]
    rec_dt = fp[C.FP_REC_DT]
    surf_dt = fp[C.FP_SURF_DT]
    post_rest = fp[C.FP_POST_REST]
    f_res = fp[C.FP_F_RES]
    v_ff = fp[C.FP_V_FF]
    v_fail = fp[C.FP_V_FAIL]
    start_ctrl = ip[C.IP_START_CTRL]
    stop_mode = ip[C.IP_STOP_MODE]
    support = ip[C.IP_FORMULATION] == C.SUPPORT
    tu_gravity = ip[C.IP_TU_GRAVITY] == 1
    any_ps = ip[C.IP_ANY_PS] == 1
    master = ip[C.IP_M_DRIVE]
    hold_node = ip[C.IP_HOLD_NODE]
    vfd = ip[C.IP_CONTROL] == C.VFD
    v_runaway = C.RUNAWAY_FACTOR * v_d
    n_shaft = shafts.node.shape[0]
    div_where = 0
    window = C.SPEED_WINDOW * v_d
    nd = drives.share.shape[0]
    nblk = blocks.ptr.shape[0] - 1
    law_mode = ip[C.IP_LAW_MODE]
    res = out.res
    drv = out.drv
    v = st.v
    te = st.te
    ts = st.ts
    td = st.td
    tt = st.tt
    r0 = wk.r0

    x_tu = st.misc[0]
    u_tu = st.misc[1]
    integ = st.misc[2]
    hold_f = st.misc[3]
    w_sum = 0.0
    for j in range(n):
        w_sum += nodes.w_mean[j]
    inv_w_sum = 1.0 / w_sum
    if law_mode == C.LAW_CONST:
        for j in range(n):
            r0[j] = law.coef[0, j]
    elif law_mode == C.LAW_LINEAR:
        # the exact law at the initial state, and its expansion about it, for every element
        for j in range(n):
            lin.idx[j] = j
        law_refresh(lin.idx, n, v, tt, lin, r0)
    n_out = 0  # elements outside their windows (expanded law), found by the last observe
    law_evals = 0  # exact evaluations of an element's law after the first
    for j in range(n):
        out.t_max[j] = tt[j]
        out.t_min[j] = tt[j]
        out.t_max_t[j] = 0.0
        out.t_min_t[j] = 0.0
        wk.t_max_snap[j] = tt[j]
        wk.t_min_snap[j] = tt[j]
    for dk in range(nd):
        drv[dk, C.DRV_FMAX] = 0.0
        drv[dk, C.DRV_PMAX] = 0.0
        drv[dk, C.DRV_SLIP_MIN] = 1e300
        drv[dk, C.DRV_SLIP_MIN_T] = 0.0
        drv[dk, C.DRV_SLIP_S] = 0.0
        drv[dk, C.DRV_SLIP_M] = 0.0
        drv[dk, C.DRV_SLIP_FIRST] = -1.0
        drv[dk, C.DRV_SLIP_LAST] = -1.0
    out.seg_time[0, 0] = 0.0
    seg = 0
    for s in range(shafts.node.shape[0]):
        out.shs[s, 0] = 0.0
        out.shs[s, 1] = 0.0
        out.shs[s, 2] = -1.0
        out.shs[s, 3] = -1.0

    status = C.OK
    vmax = 0.0
    vmax_t = 0.0
    vmin = 0.0
    vmin_t = 0.0
    gmin, gmax = extremes(tt)
    gmax_t = 0.0
    gmin_t = 0.0
    xmin = x_tu
    xmax = x_tu
    fmax = 0.0
    fmax_t = 0.0
    pmax = 0.0
    slip_min = 1e300
    slip_min_t = 0.0
    endstop = 0
    endstop_t = -1.0
    endstop_speed = 0.0
    w_drive = 0.0
    start_ach = -1.0
    stop_ach = -1.0
    stopped = False
    t_stopped = -1.0
    t_trip = -1.0
    hold_set = -1.0
    slack_max = 0.0
    slack_at = -1
    slack_time = -1.0
    slack_dur = 0.0
    slack_first = -1.0
    slack_m = 0.0
    t_end_limit = t_stopcmd + fp[C.FP_STOP_MAX] + post_rest
    if fp[C.FP_T_END] > 0.0:
        t_end_limit = min(t_end_limit, fp[C.FP_T_END])
    pi_started = False
    was_off = False
    f_tot = 0.0
    p_tot = 0.0
    f_brake = 0.0
    v_ref = 0.0
    max_steps = int(t_end_limit / dt) + 2
    step = 0
    t_new = 0.0
    if not vfd:
        for dk in range(nd):
            drives.vm[dk] = 0.0

    v_mean = 0.0
    for j in range(n):
        v_mean += nodes.w_mean[j] * v[j]
    v_mean *= inv_w_sum
    nrec = _record(0, 0.0, st, ip, shafts, drives, x_tu, 0.0, v_mean, 0.0, 0.0, 0.0, gmin,
                   gmax, 0.0, 0.0, out)
    nsurf = _record_surface(0, 0.0, v, tt, out)

    while step < max_steps:
        step += 1
        t_new = step * dt
        # ---------------------------------------------------------------- phase
        started = t_new > t_pre
        stopping = t_new > t_stopcmd
        a_ref = 0.0
        if not stopping:
            v_ref, a_ref = start_reference(start_ctrl, t_new - t_pre, t_start, v_d)
        elif stop_mode == C.CONTROLLED:
            v_ref, a_ref = stop_reference(t_new - t_stopcmd, t_stopdur, v_d)
        else:
            v_ref = 0.0
        if stopping and t_trip < 0.0:
            if stop_mode != C.CONTROLLED:
                t_trip = t_stopcmd
            elif hold_set >= 0.0:
                t_trip = hold_set
        if not started:
            phase = HOLD
        elif t_trip >= 0.0 and t_new > t_trip:
            phase = OFF
        else:
            phase = RUN
        hold_set = _brake_forces(brakes, shafts, t_new, t_stopcmd, stopping,
                                 stop_mode == C.BRAKE, stopped, t_stopped)
        _drive_laws(drives, shafts, fp, ip, phase, t_new, t_pre, t_trip, stopping,
                    phase == OFF and not was_off)
        was_off = phase == OFF
        pi = phase == RUN and vfd and not support and (start_ctrl != FORCE or stopping)
        if pi and not pi_started:
            integ = hold_f
            pi_started = True
        if start_ctrl == TORQUE and not stopping and phase == RUN:
            ramp = min(max((t_new - t_pre) / t_start, 0.0), 1.0)
            for dk in range(nd):
                drives.lim[dk] = drives.lim0[dk] * ramp + drives.share[dk] * abs(hold_f) * (
                    1.0 - ramp)
        # rigid-body feedforward: inertia plus the running resistance (Te less the net
        # gravity, which the integrator already holds from rest), regularised like the belt
        f_ff = m_tot * a_ref + f_res * min(max(v_ref / v_ff, 0.0), 1.0)
        f0u = f_ff + integ + kp * v_ref
        f1u = -kp

        # ---------------------------------------------------------------- resistances
        if law_mode == C.LAW_EXACT:
            resistance(r0, v, tt, law.coef, law.pvc, law.pvv, law.psc, law.psv, nodes.sw_ref,
                       nodes.hsm_ref, any_ps, wk.phi, wk.lnv, wk.lnphi, law.t_sparse,
                       law.t_ptr, law.t_idx)
        elif law_mode == C.LAW_LINEAR and n_out > 0:
            # r0 holds the expanded law at this state (the last observe); the elements outside
            # their windows are evaluated exactly and expanded again
            m = law_flagged(lin.flag64, lin.idx, n_out)
            law_evals += m
            law_refresh(lin.idx, m, v, tt, lin, r0)

        # ---------------------------------------------------------------- free elements
        vsum = 0.0
        for k in range(sp.seg_node.shape[0]):
            vsum += node_pass(sp.seg_node[k, 0], sp.seg_node[k, 1], v, tt, nodes.hm,
                              nodes.gravity, r0, v_eps, nodes.w_mean)

        # ---------------------------------------------------------------- blocks
        f_tot = 0.0
        p_tot = 0.0
        f_brake = 0.0
        u_new = u_tu
        U = 0.0
        u_known = not pi
        for bk in range(nblk):
            (U, u_known, u_b, hit, hf, fbk, vs_b, ft_b, pt_b, w_b) = block_step(
                bk, blocks, shafts, drives, sp, nodes, st, wk, dt, v_eps, eb, e_damp, g_damp,
                hold_node if phase == HOLD else -1, v_ref, window, f0u, f1u, U, u_known, master,
                tu_gravity, x_tu, u_tu, fp[C.FP_TU_LO], fp[C.FP_TU_HI], fp[C.FP_TU_W],
                fp[C.FP_TU_M])
            if tu_gravity and blocks.car[bk] == 1:
                u_new = u_b
                if hit >= 0.0:
                    endstop += 1
                    if endstop_t < 0.0:
                        endstop_t = t_new
                    endstop_speed = max(endstop_speed, hit)
            if not math.isnan(hf):
                hold_f = hf
            f_brake += fbk
            vsum += vs_b
            f_tot += ft_b
            p_tot += pt_b
            w_drive += w_b
        if pi:
            # conditional integration: not further into the torque limit
            e_v = v_ref - shafts.vs[drives.shaft[master]]
            if drives.sat[master] == 0 or e_v * drives.f0[master] < 0.0:
                integ += dt * ki * e_v
        if tu_gravity:
            u_tu = u_new
            x_tu += dt * u_tu
            x_tu = min(max(x_tu, fp[C.FP_TU_LO]), fp[C.FP_TU_HI])
            xmin = min(xmin, x_tu)
            xmax = max(xmax, x_tu)

        # ---------------------------------------------------------------- free springs
        for k in range(sp.seg_spring.shape[0]):
            spring_pass(sp.seg_spring[k, 0], sp.seg_spring[k, 1], v, te, ts, td, tt, sp.dl,
                        sp.t_floor, sp.s_floor, sp.kfl_eb, sp.a_eb, eb, e_damp, g_damp, sp.kvs,
                        wk.more)

        # ---------------------------------------------------------------- observe
        v_mean = vsum * inv_w_sum
        if law_mode == C.LAW_LINEAR:
            tlo, thi, vlo, vhi, n_out = observe_lin(tt, v, out.t_max, out.t_min, lin.ulo,
                                                    lin.uhi, lin.tlo, lin.thi, lin.flag, lin.k,
                                                    lin.gu, lin.guu, lin.gx, lin.gxx, lin.gux,
                                                    r0)
        else:
            tlo, thi, vlo, vhi = observe(tt, v, out.t_max, out.t_min)
        if not math.isfinite(vsum) or vhi > v_fail or vlo < -v_fail:
            status = C.DIVERGED
            div_where = -1
            break
        # the shafts (a slipping one leaves the belt) and the motors behind couplings
        for s in range(n_shaft):
            if not abs(shafts.vs[s]) <= v_fail:  # also NaN
                status = C.DIVERGED
                div_where = s
        for dk in range(nd):
            if not abs(drives.vm[dk]) <= v_fail:
                status = C.DIVERGED
                div_where = -2 - dk
        if status == C.DIVERGED:
            break
        if abs(v_mean) > v_runaway:
            status = C.RUNAWAY  # a physical result: the belt could not be held
            break
        if vhi > vmax:
            vmax = vhi
            vmax_t = t_new
        if vlo < vmin:
            vmin = vlo
            vmin_t = t_new
        if thi > gmax:
            gmax = thi
            gmax_t = t_new
        if tlo < gmin:
            gmin = tlo
            gmin_t = t_new
        if started:
            af = abs(f_tot)
            if af > fmax:
                fmax = af
                fmax_t = t_new
            if abs(p_tot) > pmax:
                pmax = abs(p_tot)
            for dk in range(nd):
                s = drives.shaft[dk]
                j = shafts.node[s]
                jm = j - 1 if j > 0 else n - 1
                f = abs(drives.force[dk])
                if f > drv[dk, C.DRV_FMAX]:
                    drv[dk, C.DRV_FMAX] = f
                pw = abs(drives.force[dk] * shafts.vs[s])
                if pw > drv[dk, C.DRV_PMAX]:
                    drv[dk, C.DRV_PMAX] = pw
                hi_ = max(tt[j], tt[jm])
                lo_ = max(min(tt[j], tt[jm]), 1.0)
                mg = (shafts.cs[s] + 1.0) * lo_ / hi_ if hi_ > 0.0 else 1e300
                if mg < drv[dk, C.DRV_SLIP_MIN]:
                    drv[dk, C.DRV_SLIP_MIN] = mg
                    drv[dk, C.DRV_SLIP_MIN_T] = t_new
                if mg < slip_min:
                    slip_min = mg
                    slip_min_t = t_new
                if shafts.slip[s] != 0.0:
                    drv[dk, C.DRV_SLIP_S] += dt
                    drv[dk, C.DRV_SLIP_M] += abs(shafts.vs[s] - v[j]) * dt
                    if drv[dk, C.DRV_SLIP_FIRST] < 0.0:
                        drv[dk, C.DRV_SLIP_FIRST] = t_new
                    drv[dk, C.DRV_SLIP_LAST] = t_new
            for s in range(shafts.node.shape[0]):
                if shafts.slip[s] != 0.0:
                    out.shs[s, 0] += dt
                    out.shs[s, 1] += abs(shafts.vs[s] - v[shafts.node[s]]) * dt
                    if out.shs[s, 2] < 0.0:
                        out.shs[s, 2] = t_new
                    out.shs[s, 3] = t_new
            if start_ach < 0.0 and v_mean >= 0.99 * v_d:
                start_ach = t_new - t_pre
        if stopping and stop_ach < 0.0 and v_mean < 0.01 * v_d:
            stop_ach = t_new - t_stopcmd
        # stopped (holding brakes set, the rest begins): at 1 % of design speed, and on a
        # controlled stop once its reference has run out
        if stopping and not stopped and v_mean < 0.01 * v_d and (
                stop_mode != C.CONTROLLED or t_new >= t_stopcmd + t_stopdur):
            stopped = True
            t_stopped = t_new
            t_end_limit = min(t_end_limit, t_new + post_rest)
            if fp[C.FP_T_END] > 0.0:
                t_end_limit = min(t_end_limit, fp[C.FP_T_END])
        # slack: the belt length gathered by the slack spans, the time with a slack span,
        # and the envelope cut when the belt first goes slack
        if tlo <= 0.0 and started:
            slack_dur += dt
            total, deep = slack_zones(ts, tt, eb, sp.len_m, sp.eps_run)
            slack_m = total
            if total > slack_max:
                slack_max = total
                slack_at = deep
                slack_time = t_new
            if slack_first < 0.0:
                slack_first = t_new
                if seg + 1 < out.seg_time.shape[0]:
                    seg = _cut_segment(seg, t_new, tt, out, wk)
        elif slack_m > 0.0:
            slack_m = 0.0
        if stopping and t_new - dt <= t_stopcmd and seg + 1 < out.seg_time.shape[0]:
            seg = _cut_segment(seg, t_new, tt, out, wk)

        # ---------------------------------------------------------------- records
        if t_new + 0.5 * dt >= nrec * rec_dt:
            nrec = _record(nrec, t_new, st, ip, shafts, drives, x_tu, f_tot, v_mean, f_brake,
                           v_ref, p_tot, tlo, thi, max(vhi, -vlo), slack_m, out)
            _envelope_times(t_new, out.t_max, out.t_min, wk.t_max_snap, wk.t_min_snap,
                            out.t_max_t, out.t_min_t)
        if t_new + 0.5 * dt >= nsurf * surf_dt:
            nsurf = _record_surface(nsurf, t_new, v, tt, out)
        if t_new >= t_end_limit:
            break

    if status != C.DIVERGED and nrec > 0 and out.rec[nrec - 1, C.REC_T] < t_new - 0.5 * dt:
        tlo, thi = extremes(tt)
        vlo, vhi = extremes(v)
        nrec = _record(nrec, t_new, st, ip, shafts, drives, x_tu, f_tot, v_mean, f_brake,
                       v_ref, p_tot, tlo, thi, max(vhi, -vlo), slack_m, out)
    _envelope_times(t_new, out.t_max, out.t_min, wk.t_max_snap, wk.t_min_snap, out.t_max_t,
                    out.t_min_t)
    # archive the last segment
    for j in range(n):
        out.seg_env[seg, 0, j] = out.t_max[j]
        out.seg_env[seg, 1, j] = out.t_max_t[j]
        out.seg_env[seg, 2, j] = out.t_min[j]
        out.seg_env[seg, 3, j] = out.t_min_t[j]
    out.seg_time[seg, 1] = t_new
    st.misc[0] = x_tu
    st.misc[1] = u_tu
    st.misc[2] = integ
    st.misc[3] = hold_f
    res[C.RES_STATUS] = status
    res[C.RES_T_END] = t_new
    res[C.RES_STEPS] = step
    res[C.RES_START_ACH] = start_ach
    res[C.RES_STOP_ACH] = stop_ach
    res[C.RES_VMAX] = vmax
    res[C.RES_VMAX_T] = vmax_t
    res[C.RES_VMIN] = vmin
    res[C.RES_VMIN_T] = vmin_t
    res[C.RES_XMIN] = xmin
    res[C.RES_XMAX] = xmax
    res[C.RES_FMAX] = fmax
    res[C.RES_FMAX_T] = fmax_t
    res[C.RES_PMAX] = pmax
    res[C.RES_SLIP_MIN] = slip_min
    res[C.RES_SLIP_MIN_T] = slip_min_t
    res[C.RES_ENDSTOP] = endstop
    res[C.RES_ENDSTOP_T] = endstop_t
    res[C.RES_ENDSTOP_SPEED] = endstop_speed
    res[C.RES_NREC] = nrec
    res[C.RES_NSURF] = nsurf
    res[C.RES_W_DRIVE] = w_drive
    res[C.RES_T_STOPCMD] = t_stopcmd
    res[C.RES_STOPPED] = 1.0 if stopped else 0.0
    res[C.RES_T_STOPPED] = t_stopped
    res[C.RES_V_MEAN_END] = v_mean
    res[C.RES_I_END] = integ
    res[C.RES_TMAX] = gmax
    res[C.RES_TMAX_T] = gmax_t
    res[C.RES_TMIN] = gmin
    res[C.RES_TMIN_T] = gmin_t
    res[C.RES_SLACK_MAX] = slack_max
    res[C.RES_SLACK_AT] = slack_at
    res[C.RES_SLACK_TIME] = slack_time
    res[C.RES_SLACK_DUR] = slack_dur
    res[C.RES_SLACK_FIRST] = slack_first
    res[C.RES_NSEG] = seg + 1
    res[C.RES_HOLD_SET] = hold_set
    res[C.RES_TRIP] = t_trip
    res[C.RES_LAW_EVALS] = law_evals
    res[C.RES_DIV_WHERE] = div_where
    return status
