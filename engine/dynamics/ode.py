"""The kernel's equations as a continuous-time ODE, for a general-purpose integrator.

Used to check the Euler-X kernel against ``scipy.integrate.solve_ivp`` (RK45): same model
arrays (:class:`~beltstudy.engine.dynamics.model.System`), same laws (resistance regularised with
``clip(v / v_eps)``, Ernst tangent stiffness, the standard linear solid's relaxing arm and the
mesh viscosity, vfd drives on one speed loop with torque following, feedforward, torque limits
and conditional integration, the gravity take-up carriage), without the parts that are not
smooth: every pulley shaft sticks to its belt element (build the System with
``DynamicsOptions(slip=False)``), and there is no holding at rest, brake, holdback, end stop or
slack. The state is ``[v (n), elastic tension (n), arm tension (n), x_takeup, u_takeup,
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
    if sys.damping != "belt" or not sys.stiffness_dyn_n > sys.stiffness_n:
        return 0.0, np.inf
    return (sys.stiffness_dyn_n - sys.stiffness_n) / sys.stiffness_n, sys.relaxation_s


def tension(sys: System, y: np.ndarray) -> np.ndarray:
    """Total tension of every spring [N]: elastic plus arm plus mesh viscosity ``alpha Z dv``,
    never below zero. ``y`` is one state or states in columns."""
    n = sys.n
    col = (slice(None),) + (None,) * (y.ndim - 1)
    v, te, td = y[:n], y[n:2 * n], y[2 * n:3 * n]
    dv = np.roll(v, -1, axis=0) - v + sys.carriage_coupling[col] * y[3 * n + 1]
    visc = sys.mesh_viscosity * sys.impedance_ns_m[col] * dv
    return np.where(te >= 0.0, np.maximum(te + td + visc, 0.0), 0.0)


def rhs(t: float, y: np.ndarray, sys: System) -> np.ndarray:
    """dy/dt at time t after the start command (relative formulation, vfd drives)."""
    n = sys.n
    v, te, td = y[:n], y[n:2 * n], y[2 * n:3 * n]
    u, integ = y[3 * n + 1], y[3 * n + 2]
    T = tension(sys, y)
    # the speed loop on the master's shaft, every drive giving its share of the output U
    v_ref, a_ref = profiles.start_reference(sys.start_control, t, sys.start_s, sys.v_design)
    f_res = sys.te_n - float(sys.gravity_n.sum())
    f_ff = sys.total_mass_kg * a_ref + f_res * min(max(v_ref / sys.v_ff_m_s, 0.0), 1.0)
    e_v = v_ref - v[sys.drive_node[sys.master]]
    U = f_ff + integ + sys.kp * e_v
    force = np.zeros(n)
    for k, node in enumerate(sys.drive_node):
        f = sys.drive_share[k] * U
        force[node] += np.clip(f, -sys.drive_limit_n[k], sys.drive_limit_n[k])
    f_m = sys.drive_share[sys.master] * U
    sat = abs(f_m) > sys.drive_limit_n[sys.master]
    d_integ = 0.0 if sat and e_v * f_m >= 0.0 else sys.ki * e_v
    # elements, each shaft's mass on its pulley element
    mass = sys.mass_kg.copy()
    np.add.at(mass, sys.shaft_node, sys.shaft_mass_kg)
    R = _law(sys, v, T) * np.clip(v / sys.v_eps, -1.0, 1.0)
    dv = (T - np.roll(T, 1) - sys.gravity_n - R + force) / mass
    du = 0.0
    if sys.takeup_gravity:
        i = sys.i_takeup
        du = (sys.takeup_weight_n - T[i - 1] - T[i]) / sys.takeup_inertia_kg
    # springs: Ernst tangent modulus, the arm relaxing towards zero
    rate = (np.roll(v, -1) - v + sys.carriage_coupling * u) / sys.len_m
    t3 = np.maximum(te, sys.t_floor_n) ** 3
    kt = sys.stiffness_n * t3 / (t3 + sys.a_ernst * sys.stiffness_n)
    ratio, tau = _arm(sys)
    dtd = ratio * kt * rate - td / tau
    return np.concatenate([dv, kt * rate, dtd, [u, du, d_integ]])
