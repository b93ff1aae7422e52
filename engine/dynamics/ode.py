"""The kernel's equations as a continuous-time ODE, for a general-purpose integrator.

Used to check the Euler-X kernel against ``scipy.integrate.solve_ivp`` (RK45) in the
benchmark: same model arrays (:class:`~engine.dynamics.model.System`), same laws (resistance
regularised with ``clip(v / v_eps)``, Ernst tangent stiffness, standard-linear-solid
damper, PI speed controller with feedforward and torque limit, gravity take-up carriage),
without the parts that are not smooth (holding at rest, brakes, holdback, end stops, slack).
The state is ``[v (n), elastic tension (n), damper tension (n), x_takeup, u_takeup,
integrator]``; the run starts from rest at the start command.
"""

from __future__ import annotations

import numpy as np

from engine.dynamics import profiles
from engine.dynamics.model import System
from engine.dynamics.reference import _law

__all__ = ["initial_state", "rhs", "tension"]


def initial_state(sys: System) -> np.ndarray:
    """The belt at rest with its at-rest tensions, the controller holding the belt."""
    n = sys.n
    y = np.zeros(3 * n + 3)
    y[n:2 * n] = np.maximum(sys.tension_rest_n, 0.0)
    y[3 * n + 2] = sys.hold_force_n
    return y


def tension(sys: System, y: np.ndarray) -> np.ndarray:
    """Total tension of every spring [N]."""
    n = sys.n
    return np.maximum(y[n:2 * n] + y[2 * n:3 * n], 0.0)


def rhs(t: float, y: np.ndarray, sys: System) -> np.ndarray:
    """dy/dt at time t after the start command (relative formulation, PI drive)."""
    n = sys.n
    v = y[:n]
    te = y[n:2 * n]
    td = y[2 * n:3 * n]
    u, integ = y[3 * n + 1], y[3 * n + 2]
    T = np.maximum(te + td, 0.0)
    v_ref, a_ref = profiles.start_reference(sys.start_control, t, sys.start_s, sys.v_design)
    f_res = sys.te_n - float(sys.gravity_n.sum())
    f_ff = sys.total_mass_kg * a_ref + f_res * min(max(v_ref / sys.v_ff_m_s, 0.0), 1.0)
    force = np.zeros(n)
    for k, node in enumerate(sys.drive_node):
        lim = sys.drive_limit_n[k]
        if k == 0:
            f = sys.drive_share[0] * (f_ff + integ) + sys.kp * (v_ref - v[node])
        else:
            f = sys.drive_share[k] * (f_ff + integ)
        force[node] += min(max(f, -lim), lim)
    R = _law(sys, v, T)
    dv = (T - np.roll(T, 1) - sys.gravity_n - R * np.clip(v / sys.v_eps, -1.0, 1.0)
          + force) / sys.mass_kg
    du = 0.0
    if sys.takeup_gravity:
        i = sys.i_takeup
        du = (sys.takeup_weight_n - T[i - 1] - T[i]) / sys.takeup_inertia_kg
    rate = (np.roll(v, -1) - v + sys.carriage_coupling * u) / sys.len_m
    tc = np.maximum(te, sys.t_floor_n)
    kt = sys.stiffness_n / (1.0 + sys.a_ernst * sys.stiffness_n / tc**3)
    dte = kt * rate
    if sys.damping == "sls":
        dtd = (sys.c_visc_ns * kt / sys.stiffness_n * rate - td) / sys.tau_s
    else:
        dtd = np.zeros(n)
    dI = sys.ki * (v_ref - v[sys.drive_node[0]])
    return np.concatenate([dv, dte, dtd, [u, du, dI]])
