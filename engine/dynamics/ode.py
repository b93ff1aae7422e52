"""The kernel's equations as a continuous-time ODE, for a general-purpose integrator.

Used to check the Euler-X kernel against ``scipy.integrate.solve_ivp`` (RK45): same model
records (``System.model``, :mod:`beltstudy.engine.dynamics.records`), same laws (resistance
regularised with ``clip(v / v_eps)``, Ernst tangent stiffness, the standard linear solid's
relaxing arm and the mesh viscosity, vfd drives on one speed loop with torque following,
feedforward, torque limits and conditional integration, the gravity take-up carriage), without
the parts that are not smooth: every pulley shaft sticks to its belt element (build the System
with ``DynamicsOptions(slip=False)``), and there is no holding at rest, brake, holdback, end
stop or slack. The state is ``[v (n), elastic tension (n), arm tension (n), x_takeup, u_takeup,
integrator]``; the run starts from rest at the start command (``pre_rest_s = 0``).
"""

from __future__ import annotations

import numpy as np

from beltstudy.engine.dynamics import profiles
from beltstudy.engine.dynamics.model import System
from beltstudy.engine.dynamics.reference import _law

__all__ = ["initial_state", "rhs", "tension"]


def initial_state(sys: System) -> np.ndarray:
    """The belt at rest with its at-rest tensions, the speed loop's integrator holding it."""
    n = sys.n
    y = np.zeros(3 * n + 3)
    y[n:2 * n] = np.maximum(sys.tension_rest_n, 0.0)
    y[3 * n + 2] = sys.hold_force_n
    return y


def _arm(sys: System) -> tuple[float, float]:
    """(ratio of the arm's stiffness to the static one, relaxation time [s]); (0, inf) without
    an arm."""
    sp = sys.model.springs
    if sys.damping != "belt" or not sp.eb_dyn > sp.eb:
        return 0.0, np.inf
    return (sp.eb_dyn - sp.eb) / sp.eb, sys.relaxation_s


def tension(sys: System, y: np.ndarray) -> np.ndarray:
    """Total tension of every spring [N]: elastic plus arm plus mesh viscosity ``alpha Z dv``,
    never below zero. ``y`` is one state or states in columns."""
    n = sys.n
    sp = sys.model.springs
    col = (slice(None),) + (None,) * (y.ndim - 1)
    v, te, td = y[:n], y[n:2 * n], y[2 * n:3 * n]
    dv = np.roll(v, -1, axis=0) - v + sp.car_ind[col] * y[3 * n + 1]
    visc = sp.viscosity[col] * dv
    return np.where(te >= 0.0, np.maximum(te + td + visc, 0.0), 0.0)


def rhs(t: float, y: np.ndarray, sys: System) -> np.ndarray:
    """dy/dt at time t after the start command (relative formulation, vfd drives)."""
    n = sys.n
    m = sys.model
    cyc, ctl, drives, nodes, sp, tu = m.cycle, m.control, m.drives, m.nodes, m.springs, m.takeup
    v, te, td = y[:n], y[n:2 * n], y[2 * n:3 * n]
    u, integ = y[3 * n + 1], y[3 * n + 2]
    T = tension(sys, y)
    # the speed loop on the master's shaft, every drive giving its share of the output U
    v_ref, a_ref = profiles.start_reference(cyc.start_ctrl, t, cyc.t_start, cyc.v_d)
    f_ff = ctl.ff * (ctl.m_tot * a_ref + ctl.f_res * min(max(v_ref / ctl.v_ff, 0.0), 1.0))
    master = ctl.master
    e_v = v_ref - v[drives.node[master]]
    U = f_ff + integ + ctl.kp * e_v
    force = np.zeros(n)
    for k, node in enumerate(drives.node):
        f = drives.share[k] * U
        force[node] += np.clip(f, -drives.lim0[k], drives.lim0[k])
    f_m = drives.share[master] * U
    sat = abs(f_m) > drives.lim0[master]
    d_integ = 0.0 if sat and e_v * f_m >= 0.0 else ctl.ki * e_v
    # elements, each shaft's mass on its pulley element
    mass = nodes.mass.copy()
    np.add.at(mass, m.shafts.node, m.shafts.mass)
    R = _law(m.law, nodes, v, T) * np.clip(v / cyc.v_eps, -1.0, 1.0)
    dv = (T - np.roll(T, 1) - nodes.gravity - R + force) / mass
    du = 0.0
    if tu.gravity:
        i = tu.node
        du = (tu.weight - T[i - 1] - T[i]) / tu.mass
    # springs: Ernst tangent modulus, the arm relaxing towards zero
    rate = (np.roll(v, -1) - v + sp.car_ind * u) / sp.len_m
    t3 = np.maximum(te, sp.t_floor) ** 3
    kt = sp.eb * t3 / (t3 + sp.a_ernst * sp.eb)
    ratio, tau = _arm(sys)
    dtd = ratio * kt * rate - td / tau
    return np.concatenate([dv, kt * rate, dtd, [u, du, d_integ]])
