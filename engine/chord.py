"""Ernst's chord law of a sagging span: the length a fixed take-up holds (PHYSICS 5).

A span of belt between two idlers is a spring whose chord stretches with its tension and
shortens with its sag: ``eps(T) = T / EB - a / (2 T^2)`` with ``a = (w S)^2 / 12`` (``w S``
the span's weight [N]: its weight per metre times its length). A fixed (screw or winch)
take-up holds its place, so the loop's chord length: the transient model's at-rest state
keeps the running state's length (:func:`length_level`), and an auto fixed take-up sized to
a sag limit held at rest (:mod:`beltstudy.engine.statics`) is sized on the same length, so
that the rest state the transient starts from meets the limit (a 110 m decline's tail drive
left it 1.5005 % against 1.5 % when the sizing left the sag out of the length).

The law is PHYSICS section 5's (``EB_eq = EB / (1 + (w S)^2 EB / (12 T^3))`` is its tangent);
the transient model's springs (:mod:`beltstudy.engine.dynamics.model`) are built from it.
"""

from __future__ import annotations

import numpy as np

__all__ = ["HS_FLOOR", "LEVEL_RTOL", "chord_strain", "chord_springs", "length_level"]

#: Sag ratio h/S below whose tension the Ernst tangent modulus is held constant: the range of
#: the parabolic sag model (10 %).
HS_FLOOR = 0.10
#: Relative tolerance of :func:`length_level`'s bisection on the level [-].
LEVEL_RTOL = 1e-9


def chord_strain(tension_n, a_ernst, stiffness_n, t_floor_n, k_floor_n):
    """Elastic strain of a span from the Ernst chord law, up to a constant [-].

    ``eps(T) = T / EB - a / (2 T^2)`` with ``a = (w S)^2 / 12`` (so ``d eps / dT =
    1 / EB_eq``); below ``t_floor`` the tangent modulus is held at ``k_floor``.
    """
    T = np.asarray(tension_n, dtype=np.float64)
    tf = np.maximum(t_floor_n, 1e-300)
    e_floor = tf / stiffness_n - a_ernst / (2.0 * tf * tf)
    Tc = np.maximum(T, tf)
    e = Tc / stiffness_n - a_ernst / (2.0 * Tc * Tc)
    return np.where(T >= tf, e, e_floor - (tf - T) / k_floor_n)


def chord_springs(loop, ernst: bool = True) -> tuple[np.ndarray, np.ndarray, np.ndarray,
                                                      np.ndarray]:
    """The loop's springs as the chord law takes them: each spring's length ``len_m`` [m]
    (half of each element beside the boundary it sits on), Ernst's ``a`` [N^2] (``(w S)^2 /
    12``, the two elements' weighted by length; 0 without ``ernst``), the floor tension
    ``t_floor`` [N] (the sag ratio :data:`HS_FLOOR`) and the tangent stiffness below it
    ``k_floor`` [N]."""
    dx = loop.dx_m
    nxt = np.roll(np.arange(loop.n), -1)
    EB = float(loop.belt.stiffness_n)
    len_m = 0.5 * (dx + dx[nxt])
    wS2 = (8.0 * loop.sag_w_n) ** 2  # (w S)^2 per element [N^2]
    a_el = (dx * wS2 + dx[nxt] * wS2[nxt]) / (dx + dx[nxt]) / 12.0
    if not ernst:
        a_el = np.zeros(loop.n)
    t_floor = np.maximum(np.sqrt(12.0 * a_el) / (8.0 * HS_FLOOR), 1.0)
    k_floor = EB * t_floor**3 / (t_floor**3 + a_el * EB)
    return len_m, a_el, t_floor, k_floor


def length_level(T_rel, T_ref, len_m, a_el, EB, t_floor, k_floor) -> float:
    """The level ``c`` [N] at which the tensions ``T_rel + c`` give the loop the chord length
    of the tensions ``T_ref`` [N] (``sum len eps``, :func:`chord_strain`), by bisection to
    :data:`LEVEL_RTOL`: the at-rest level of a fixed take-up from the running tensions, or
    the running level that leaves a wanted rest state."""
    target = float(np.sum(len_m * chord_strain(T_ref, a_el, EB, t_floor, k_floor)))

    def excess(level):
        return float(np.sum(len_m * chord_strain(T_rel + level, a_el, EB, t_floor, k_floor))) \
            - target

    lo = -float(T_rel.max()) - abs(target) * EB - 1.0
    hi = float(np.abs(T_ref).max()) + abs(float(T_rel.min())) + 1.0
    while excess(hi) < 0.0:
        hi *= 2.0
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        if excess(mid) < 0.0:
            lo = mid
        else:
            hi = mid
        if hi - lo < LEVEL_RTOL * max(1.0, abs(hi)):
            break
    return 0.5 * (lo + hi)
