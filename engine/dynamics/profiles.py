"""Speed references for starting and stopping (PHYSICS section 5).

The s-curve is Harrison's cycloid (Harrison 1983, cited in the seed paper section 1):
a velocity history whose acceleration starts and ends at zero, so the belt is set in motion
without a step in acceleration and with the least wave excitation,

    v(t) = v_s [t/T - sin(2 pi t/T) / (2 pi)],      a(t) = (v_s / T) [1 - cos(2 pi t/T)].

The linear ramp has a constant acceleration v_s / T. A controlled stop follows the reverse
curve v_s - v(t). These functions are used by the numba kernel (compiled, ``inline``) and by
the numpy reference, so both integrate the same references.
"""

from __future__ import annotations

import math

from numba import njit

__all__ = ["S_CURVE", "LINEAR", "TORQUE", "FORCE", "start_reference", "stop_reference"]

#: Start control codes used by the kernel.
S_CURVE, LINEAR, TORQUE, FORCE = 0, 1, 2, 3
TWO_PI = 2.0 * math.pi


@njit(cache=True, inline="always")
def start_reference(control: int, tau: float, duration_s: float, v_s: float):
    """Speed reference and its derivative during a start.

    Parameters
    ----------
    control : int
        ``S_CURVE`` (cycloid), ``LINEAR`` (ramp) or ``TORQUE``/``FORCE`` (reference is the
        design speed at once; the drive force limit ramps instead).
    tau : float
        Time since the start command [s] (clipped to [0, duration_s]).
    duration_s : float
        Start time T [s].
    v_s : float
        Design speed [m/s].

    Returns
    -------
    v_ref : float
        Reference speed [m/s].
    a_ref : float
        Reference acceleration [m/s2].
    """
    if tau <= 0.0:
        if control >= TORQUE:
            return v_s, 0.0
        return 0.0, 0.0
    if tau >= duration_s or control >= TORQUE:
        return v_s, 0.0
    x = tau / duration_s
    if control == S_CURVE:
        return (v_s * (x - math.sin(TWO_PI * x) / TWO_PI),
                v_s / duration_s * (1.0 - math.cos(TWO_PI * x)))
    return v_s * x, v_s / duration_s


@njit(cache=True, inline="always")
def stop_reference(tau: float, duration_s: float, v_s: float):
    """Reverse s-curve from ``v_s`` to rest over ``duration_s`` [m/s, m/s2]."""
    if tau <= 0.0:
        return v_s, 0.0
    if tau >= duration_s:
        return 0.0, 0.0
    x = tau / duration_s
    return (v_s * (1.0 - (x - math.sin(TWO_PI * x) / TWO_PI)),
            -v_s / duration_s * (1.0 - math.cos(TWO_PI * x)))
