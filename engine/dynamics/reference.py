"""The slow, obvious numpy implementation of the kernel's equations (STYLE: a reference path
beside the numba kernel, tested against it).

Same model (:class:`~engine.dynamics.model.System`), same scheme as
:mod:`engine.dynamics.kernel`, written for reading rather than speed: whole-array numpy
operations, exact ``np.power`` for the resistance law, ``np.linalg.solve`` for the implicit
blocks and a plain loop over their active set. Use it on small models and short times.
"""

from __future__ import annotations

import numpy as np

from engine.dynamics import profiles
from engine.dynamics.model import BRAKE, CONTROLLED, SUPPORT, System

__all__ = ["ReferenceResult", "run_reference"]

SLACK_LIMIT = 0.05
#: Fastest slack storage of the belt's own motion [x design speed] (as in the kernel).
SLACK_RATE_MAX = 4.0
V_FAIL_FACTOR = 100.0


class ReferenceResult(dict):
    """Final state and summary quantities (same names as the kernel's outputs)."""


def _law(sys: System, v: np.ndarray, T: np.ndarray) -> np.ndarray:
    """R0_j = sum_k coef[k, j] |v_j|^pv[k] phi_j^ps[k] (magnitude, before regularisation)."""
    tm = 0.5 * (np.roll(T, 1) + T)
    phi = np.minimum(sys.sag_w_n / np.maximum(tm, 1.0), sys.hs_max) / sys.hs_ref
    av = np.abs(v)
    total = np.zeros(sys.n)
    for k in range(sys.coef.shape[0]):
        speed = np.ones(sys.n) if sys.pv[k] == 0 else np.power(av, sys.pv[k])
        sag = np.ones(sys.n) if sys.ps[k] == 0 else np.power(phi, sys.ps[k])
        total += sys.coef[k] * speed * sag
    return total


def _tangent(sys: System, te: np.ndarray, idx=slice(None)) -> np.ndarray:
    """Ernst tangent modulus EB_eq = EB / (1 + a EB / T^3), T held at the floor below it."""
    tc = np.maximum(te, sys.t_floor_n[idx])
    return sys.stiffness_n / (1.0 + sys.a_ernst[idx] * sys.stiffness_n / tc**3)


def _damper(sys: System) -> tuple[float, float]:
    """(decay factor over a step, gain per unit tangent stiffness and strain increment)."""
    dt = sys.dt_s
    if sys.damping == "sls":
        e = np.exp(-dt / sys.tau_s)
        return float(e), float((1.0 - e) * sys.c_visc_ns / (sys.stiffness_n * dt))
    if sys.damping == "kv":
        return 0.0, float(sys.c_visc_ns / (sys.stiffness_n * dt))
    return 0.0, 0.0


def run_reference(sys: System, t_end_s: float | None = None) -> ReferenceResult:
    """Integrate the cycle with numpy; stop at ``t_end_s`` if given.

    Returns a dict with the final ``v``, ``te``, ``td``, ``tension``, ``x_takeup``,
    ``integrator``, the envelopes ``t_max``/``t_min``, ``steps``, ``t_end``, ``status``
    (0 ok, 1 diverged, 2 slack), the drive work ``w_drive`` and ``start_ach``/``stop_ach``.
    """
    n, dt = sys.n, sys.dt_s
    v_d, v_eps = sys.v_design, sys.v_eps
    e_damp, g_damp = _damper(sys)
    M = sys.mass_kg
    G = sys.gravity_n
    dl = dt / sys.len_m
    car_ind = sys.carriage_coupling
    hold = sys.hold_node
    w = sys.belt_mass_kg
    f_res = sys.te_n - float(G.sum())
    in_block = np.zeros(n, dtype=bool)
    for b in sys.blocks:
        in_block[b] = True
    blocks = sorted(sys.blocks, key=lambda b: 0 if int(sys.drive_node[0]) in b else 1)
    drive_of = {int(d): k for k, d in enumerate(sys.drive_node)}

    te = np.maximum(sys.tension_rest_n, 0.0)
    td = np.zeros(n)
    T = te.copy()
    v = np.zeros(n)
    x_tu, u_tu = 0.0, 0.0
    integ, hold_f = 0.0, sys.hold_force_n
    t_max, t_min = T.copy(), T.copy()
    t_pre = sys.pre_rest_s
    t_stopcmd = t_pre + sys.start_s + sys.run_s
    t_limit = t_stopcmd + sys.stop_max_s + sys.post_rest_s
    if t_end_s is not None:
        t_limit = min(t_limit, t_end_s)
    pi_started = False
    status = 0
    w_drive = 0.0
    start_ach = stop_ach = -1.0
    stopped = False
    step = 0
    t_new = 0.0
    max_steps = int(t_limit / dt) + 2
    while step < max_steps:
        step += 1
        t_new = step * dt
        started = t_new > t_pre
        stopping = t_new > t_stopcmd
        a_ref = 0.0
        if not stopping:
            v_ref, a_ref = profiles.start_reference(sys.start_control, t_new - t_pre,
                                                    sys.start_s, v_d)
        elif sys.stop_mode == CONTROLLED:
            v_ref, a_ref = profiles.stop_reference(t_new - t_stopcmd, sys.stop_s, v_d)
        else:
            v_ref = 0.0
        if not started:
            mode = "hold"
        elif sys.formulation == SUPPORT:
            mode = "imposed" if (not stopping or sys.stop_mode == CONTROLLED) else "free"
        elif sys.start_control == profiles.FORCE and not stopping:
            mode = "open"
        elif not stopping or sys.stop_mode == CONTROLLED:
            mode = "pi"
        else:
            mode = "free"
        if mode == "pi" and not pi_started:
            integ, pi_started = hold_f, True
        ramp = 1.0
        if sys.start_control == profiles.TORQUE and not stopping:
            ramp = min(max((t_new - t_pre) / sys.start_s, 0.0), 1.0)
        f_ff = sys.total_mass_kg * a_ref + f_res * min(max(v_ref / sys.v_ff_m_s, 0.0), 1.0)
        braking = stopping and sys.stop_mode == BRAKE

        R = _law(sys, v, T)
        rp, rn = np.maximum(R, 0.0), np.minimum(R, 0.0)
        # free elements: explicit, resistance implicit in closed form
        h = dt / M
        vs = v + h * (T - np.roll(T, 1) - G - rn * np.clip(v / v_eps, -1.0, 1.0))
        e = h * rp
        v_free = np.where(np.abs(vs) <= v_eps + e, vs * v_eps / (v_eps + e),
                          vs - np.sign(vs) * e)
        v_new = np.where(in_block, v, v_free)

        # blocks
        u_new = u_tu
        for blk in blocks:
            m = len(blk)
            car = sys.takeup_gravity and sys.i_takeup in blk
            nu = m + 1 if car else m
            springs = blk[:-1]
            kt = _tangent(sys, te[springs], springs) * (1.0 + g_damp)
            slack = te[springs] < 0.0
            A_s = np.where(slack, 0.0, te[springs] + e_damp * td[springs])
            B_s = np.where(slack, 0.0, kt * dl[springs])
            cind = car_ind[springs] if car else np.zeros(m - 1)
            vo = v[blk]
            fixed = np.zeros(m, dtype=bool)
            fixv = np.zeros(m)
            p_diag = np.zeros(m)
            fdrv = np.zeros(m)
            master = -1
            fb = np.zeros(m)
            hb = np.zeros(m, dtype=bool)
            for k, j in enumerate(blk):
                if braking:
                    for bn, bf, bd in zip(sys.brake_node, sys.brake_force_n, sys.brake_delay_s,
                                          strict=True):
                        if bn == j and t_new > t_stopcmd + bd:
                            fb[k] += bf
                hb[k] = j == sys.holdback_node
                if mode == "hold" and j == hold:
                    fixed[k], fixv[k] = True, 0.0
                dk = drive_of.get(j, -1)
                if dk < 0 or mode == "hold":
                    continue
                lim = (sys.drive_limit_n[dk] * ramp
                       + sys.drive_share[dk] * abs(hold_f) * (1.0 - ramp))
                if mode == "imposed":
                    fixed[k], fixv[k] = True, v_ref
                elif mode == "pi" and dk == 0:
                    master = k
                    p_diag[k] = sys.kp
                    fdrv[k] = sys.drive_share[0] * (f_ff + integ) + sys.kp * v_ref
                elif mode == "pi":
                    fdrv[k] = np.clip(sys.drive_share[dk] * (f_ff + integ), -lim, lim)
                elif mode == "open":
                    fdrv[k] = sys.drive_share[dk] * sys.force_start_n
            zone = np.where(vo > v_eps, 1.0, np.where(vo < -v_eps, -1.0, 0.0))
            can = (fb > 0) | hb
            stuck = can & ((np.abs(vo) <= 1e-12) | (hb & (vo < 0)))
            bdir = np.where(vo >= 0.0, 1.0, -1.0)
            c_lo = -fb
            c_hi = np.where(hb, np.inf, fb)
            car_fixed, car_v, sat = False, 0.0, False
            for _ in range(16):
                A = np.zeros((nu, nu))
                b = np.zeros(nu)
                for k, j in enumerate(blk):
                    A[k, k] = M[j] / dt + p_diag[k]
                    b[k] = (M[j] / dt * vo[k] - G[j] + fdrv[k]
                            - rn[j] * np.clip(vo[k] / v_eps, -1.0, 1.0))
                    if zone[k] == 0.0:
                        A[k, k] += rp[j] / v_eps
                    else:
                        b[k] -= zone[k] * rp[j]
                    if fb[k] > 0 and not stuck[k]:
                        b[k] -= bdir[k] * fb[k]
                    if k == 0:
                        b[k] -= T[(j - 1) % n]
                    else:  # implicit spring on the left pulls back
                        A[k, k] += B_s[k - 1]
                        A[k, k - 1] -= B_s[k - 1]
                        b[k] -= A_s[k - 1]
                        if car:
                            A[k, m] += B_s[k - 1] * cind[k - 1]
                    if k == m - 1:
                        b[k] += T[j]
                    else:  # implicit spring on the right pulls forward
                        A[k, k] += B_s[k]
                        A[k, k + 1] -= B_s[k]
                        b[k] += A_s[k]
                        if car:
                            A[k, m] -= B_s[k] * cind[k]
                if car:
                    A[m, m] = sys.takeup_inertia_kg / dt
                    b[m] = sys.takeup_inertia_kg / dt * u_tu + sys.takeup_weight_n
                    for k in range(m - 1):
                        if cind[k]:
                            A[m, k + 1] += B_s[k]
                            A[m, k] -= B_s[k]
                            A[m, m] += B_s[k]
                            b[m] -= A_s[k]
                Ac, bc = A.copy(), b.copy()
                for k in range(m):
                    if fixed[k] or stuck[k]:
                        Ac[k, :] = 0.0
                        Ac[k, k] = 1.0
                        bc[k] = fixv[k] if fixed[k] else 0.0
                if car and car_fixed:
                    Ac[m, :] = 0.0
                    Ac[m, m] = 1.0
                    bc[m] = car_v
                x = np.linalg.solve(Ac, bc)
                again = False
                if master >= 0 and not sat:
                    lim = (sys.drive_limit_n[0] * ramp
                           + sys.drive_share[0] * abs(hold_f) * (1.0 - ramp))
                    fm = sys.drive_share[0] * (f_ff + integ) + sys.kp * (v_ref - x[master])
                    if abs(fm) > lim:
                        sat, again = True, True
                        p_diag[master] = 0.0
                        fdrv[master] = np.copysign(lim, fm)
                if car and not car_fixed:
                    x_try = x_tu + dt * x[m]
                    if x_try > sys.takeup_hi_m or x_try < sys.takeup_lo_m:
                        car_fixed, again = True, True
                        stop = sys.takeup_hi_m if x_try > sys.takeup_hi_m else sys.takeup_lo_m
                        car_v = (stop - x_tu) / dt
                for k in range(m):
                    if fixed[k]:
                        zone[k] = 1.0 if fixv[k] > v_eps else (-1.0 if fixv[k] < -v_eps else 0.0)
                        continue
                    if stuck[k]:
                        react = A[k] @ x - A[k, k] * x[k] - b[k]
                        if react > c_hi[k] or react < c_lo[k]:
                            stuck[k] = False
                            bdir[k] = -1.0 if react > c_hi[k] else 1.0
                            again = True
                    elif hb[k] and x[k] < 0.0:
                        stuck[k], again = True, True
                    elif fb[k] > 0 and x[k] * bdir[k] < 0.0:
                        stuck[k], again = True, True
                    z = 0.0 if stuck[k] else (1.0 if x[k] > v_eps else
                                              (-1.0 if x[k] < -v_eps else 0.0))
                    if z != zone[k]:
                        zone[k], again = z, True
                if not again:
                    break
            if car:
                u_new = x[m]
            for k, j in enumerate(blk):
                v_new[j] = x[k]
                if mode == "hold" and j == hold:
                    hold_f = A[k] @ x - b[k]
                dk = drive_of.get(j, -1)
                if dk < 0:
                    continue
                if fixed[k] and mode != "hold":
                    f = A[k] @ x - b[k] + fdrv[k] - p_diag[k] * x[k]
                elif k == master and not sat:
                    f = sys.drive_share[0] * (f_ff + integ) + sys.kp * (v_ref - x[k])
                else:
                    f = fdrv[k]
                w_drive += f * 0.5 * (vo[k] + x[k]) * dt
                if dk == 0 and mode == "pi":
                    e_v = v_ref - x[k]
                    if not sat or e_v * fdrv[k] < 0.0:
                        integ += dt * sys.ki * e_v
        if sys.takeup_gravity:
            u_tu = u_new
            x_tu = min(max(x_tu + dt * u_tu, sys.takeup_lo_m), sys.takeup_hi_m)

        # every spring from the new velocities (the carriage stretches its two springs)
        de = (np.roll(v_new, -1) - v_new) * dl + car_ind * (u_tu if sys.takeup_gravity else 0.0) * dl
        kt = _tangent(sys, te)
        e1 = te + kt * de
        # crossing the floor in one step: the rest of the increment at the floor modulus
        tfl = sys.t_floor_n
        e1 = np.where((e1 < tfl) & (te > tfl), tfl + (e1 - tfl) * sys.k_floor_n / kt, e1)
        d1 = np.where(e1 >= 0.0, e_damp * td + g_damp * kt * de, 0.0)
        te, td = e1, d1
        T = np.maximum(e1 + d1, 0.0)
        v = v_new
        t_max = np.maximum(t_max, T)
        t_min = np.minimum(t_min, T)

        v_mean = float(w @ v) / float(w.sum())
        if not np.isfinite(v).all() or np.abs(v).max() > V_FAIL_FACTOR * v_d:
            status = 1
            break
        if started and start_ach < 0 and v_mean >= 0.99 * v_d:
            start_ach = t_new - t_pre
        if stopping and not stopped and v_mean < 0.01 * v_d:
            stopped = True
            stop_ach = t_new - t_stopcmd
            t_limit = min(t_limit, t_new + sys.post_rest_s)
        if float(np.min(te / sys.k_floor_n)) < -SLACK_LIMIT:
            j = int(np.argmin(te / sys.k_floor_n))
            slack_m = -te[j] / sys.k_floor_n[j] * sys.len_m[j]
            reach = sys.len_m[j] + SLACK_RATE_MAX * v_d * dt
            status = 2 if slack_m <= reach else 1
            break
        if t_new >= t_limit:
            break
    return ReferenceResult(v=v, te=te, td=td, tension=T, x_takeup=float(x_tu),
                           u_takeup=float(u_tu),
                           integrator=integ, t_max=t_max, t_min=t_min, steps=step,
                           t_end=t_new, status=status, w_drive=w_drive, start_ach=start_ach,
                           stop_ach=stop_ach)
