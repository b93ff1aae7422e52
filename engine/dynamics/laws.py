"""Drive and coupling laws of the transient model (PHYSICS section 5.1).

Small scalar functions compiled for the kernel and called as they are by the numpy reference,
so both integrate the same laws. Forces are at the pulley rim (torque over the pulley radius)
and speeds at the belt line (shaft speed times the pulley radius), both in SI.

* **Induction motor on the line** (``dol``): force ``F_r y(v / v_d)`` with ``y`` the motor
  curve (torque over rated torque against speed over the design speed, piecewise linear,
  :data:`beltstudy.engine.conveyor.DEFAULT_MOTOR_CURVE` by default) and ``F_r`` the rated force, rated
  power over design speed. Below standstill the locked-rotor value holds; above the last
  point (synchronous speed) the motor generates: the last segment continues over its own
  mirror, and beyond it the curve is mirrored about synchronous speed (:func:`motor_force`).
* **Fluid coupling** between motor and pulley: a hydrodynamic coupling's torque follows the
  similarity law ``T ~ rho n_in^2 D^5`` (the square of the input speed), rising with slip
  ``s = 1 - n_out / n_in``. The characteristic used is a smooth one through the rated point
  and the stall point: ``T = T_r (v_m / v_d)^2 STALL (1 - e^{-s/s0}) / (1 - e^{-1/s0})``,
  rated torque at ``RATED_SLIP`` = 3 % slip (constant-fill couplings run at 1.5-4 % slip at
  rated torque) and ``STALL`` = 1.6 x rated torque at full slip (constant-fill couplings limit
  the starting torque to roughly 1.2-2 x rated, PHYSICS 5.1; Voith's and Nordell's starting
  papers). A fill-controlled coupling's torque is that times its fill, rising from empty to
  full over ``coupling_fill_s``.

The brakes' law is with their record in :mod:`beltstudy.engine.dynamics.brakes`.
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit

from beltstudy.engine.dynamics.codes import CURVE_MAX
from beltstudy.engine.dynamics.fastmath import OPTS

__all__ = ["curve", "padded_curves", "motor_force", "coupling_torque", "STALL", "RATED_SLIP",
           "SLIP_SCALE"]

#: Stall torque of a constant-fill fluid coupling over its rated torque [-].
STALL = 1.6
#: Slip of a fluid coupling at rated torque and full input speed [-].
RATED_SLIP = 0.03


def _slip_scale() -> float:
    """s0 with STALL (1 - e^{-RATED_SLIP/s0}) / (1 - e^{-1/s0}) = 1, by bisection."""
    lo, hi = 1e-4, 1.0
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        val = STALL * (1.0 - math.exp(-RATED_SLIP / mid)) / (1.0 - math.exp(-1.0 / mid))
        if val > 1.0:
            lo = mid
        else:
            hi = mid
    return 0.5 * (lo + hi)


#: Slip scale s0 of the coupling characteristic [-].
SLIP_SCALE = _slip_scale()
_NORM = STALL / (1.0 - math.exp(-1.0 / SLIP_SCALE))


@njit(inline="always", **OPTS)
def curve(xs, ys, n, x):
    """Piecewise linear ``y(x)`` through ``n`` points and its slope: the first value below the
    first point, the last segment continued above the last point."""
    if x <= xs[0]:
        return ys[0], 0.0
    k = 1
    while k < n - 1 and x > xs[k]:
        k += 1
    slope = (ys[k] - ys[k - 1]) / (xs[k] - xs[k - 1])
    return ys[k - 1] + slope * (x - xs[k - 1]), slope


@njit(inline="always", **OPTS)
def motor_force(xs, ys, n, f_rated, v_d, v):
    """Motor force at the rim [N] and its slope in speed [N s/m] at rim speed ``v``.

    Above synchronous speed ``x_s`` (the curve's last, zero-torque point) the motor generates.
    Over the mirror of the last segment (up to ``2 x_s - x_{n-2}``) that segment continues;
    beyond it the torque is the motoring curve mirrored about synchronous speed, ``y(x) =
    -y(2 x_s - x)``: Kloss's torque-slip law ``T / T_b = 2 / (s / s_b + s_b / s)`` is odd in the
    slip ``s`` when the stator resistance is neglected, so the generating breakdown torque is
    the motoring one (R. Fischer, *Elektrische Maschinen*, Carl Hanser Verlag, the induction
    machine's Kloss formula; with the stator resistance it is somewhat larger). Far above
    synchronous speed the torque stays at minus the locked-rotor value. The plain continuation
    of the last segment had no bound: a shaft 9 % above synchronous speed (a light pulley
    overshooting in a dol start) met about -5 x rated torque, twice any breakdown torque."""
    x = v / v_d
    x_syn = xs[n - 1]
    if x > 2.0 * x_syn - xs[n - 2]:
        y, dy = curve(xs, ys, n, 2.0 * x_syn - x)
        return -f_rated * y, f_rated * dy / v_d
    y, dy = curve(xs, ys, n, x)
    return f_rated * y, f_rated * dy / v_d


@njit(inline="always", **OPTS)
def coupling_torque(t_rated, v_d, vm, vs, fill):
    """Fluid coupling force at the rim [N] with input (motor) speed ``vm`` and output (pulley)
    speed ``vs`` [m/s], and its derivatives in ``vm`` and ``vs``."""
    if fill <= 0.0 or vm == 0.0:
        return 0.0, 0.0, 0.0
    k = t_rated * fill / (v_d * v_d)
    d = vm - vs
    avm = abs(vm)
    s = abs(d) / avm
    sg = 1.0 if d >= 0.0 else -1.0
    if s >= 1.0:
        phi = _NORM * (1.0 - math.exp(-1.0 / SLIP_SCALE))
        dphi = 0.0
    else:
        e = math.exp(-s / SLIP_SCALE)
        phi = _NORM * (1.0 - e)
        dphi = _NORM * e / SLIP_SCALE
    t = sg * k * vm * vm * phi
    # s = |vm - vs| / |vm|: ds/dvs = -sg / |vm|, ds/dvm = sg vs / (vm |vm|)
    dt_dvs = -k * vm * vm * dphi / avm
    dt_dvm = sg * k * (2.0 * vm * phi) + k * vm * vm * dphi * vs / (vm * avm)
    return t, dt_dvm, dt_dvs


def padded_curves(curves, width: int = CURVE_MAX) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """A list of point lists ``[(x, y), ...]`` as the kernel takes curves: arrays (k, width)
    of the x and y values, padded with zeros, and each curve's number of points."""
    k = max(len(curves), 1)
    xs = np.zeros((k, width))
    ys = np.zeros((k, width))
    ns = np.zeros(k, dtype=np.int64)
    for i, c in enumerate(curves):
        if len(c) > width:
            raise ValueError(f"a curve has more than {width} points")
        ns[i] = len(c)
        for p, (x, y) in enumerate(c):
            xs[i, p] = x
            ys[i, p] = y
    return xs, ys, ns
