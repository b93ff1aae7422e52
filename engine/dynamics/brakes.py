"""The brakes of the transient model: their record, how it is built from the conveyor file,
and the force law the kernel and the numpy reference both apply (PHYSICS section 5.1).

A brake acts on a pulley shaft (a drive's, or the head or tail pulley's) through the pulley's
friction. Its force builds linearly over ``ramp_s`` after ``delay_s``, or follows its
``force_curve`` (fraction of the force against the time since it was applied, linear between
the points, the last value held); ``force_kn: auto`` is sized by
:func:`beltstudy.engine.design.brake_forces`. When a brake is commanded and released (stop
mode, ``hold``) is the kernel's (:func:`beltstudy.engine.dynamics.kernel._brake_forces`); what
force a commanded brake gives is :func:`brake_force`, here, so a new brake law changes this
module (and the conveyor file's fields) only.
"""

from __future__ import annotations

from typing import NamedTuple

import numpy as np
from numba import njit

from beltstudy.engine import design
from beltstudy.engine.dynamics.fastmath import OPTS
from beltstudy.engine.dynamics.laws import padded_curves

__all__ = ["Brakes", "build_brakes", "brake_force", "brake_fraction", "set_at"]


class Brakes(NamedTuple):
    """Brakes in file order: shaft, element, full force [N], delay and ramp [s], force curve
    (points per brake: time [s], fraction of the full force), hold flag; *state*: command time
    (-1 not commanded), released flag."""

    shaft: np.ndarray
    node: np.ndarray
    force: np.ndarray
    delay: np.ndarray
    ramp: np.ndarray
    curve_t: np.ndarray
    curve_f: np.ndarray
    curve_n: np.ndarray
    hold: np.ndarray
    t_cmd: np.ndarray
    released: np.ndarray


def build_brakes(conv, scn, loop, shaft_index: dict, total_mass: float, te: float,
                 gravity_sum: float, notes: list[str], steady=None) -> Brakes:
    """The brakes of a conveyor in file order, on the shafts of ``shaft_index`` (element ->
    shaft), with their forces (auto ones sized for the scenario's stop by
    :func:`beltstudy.engine.design.brake_forces` from the moving mass [kg], Te [N] and the net
    gravity pull [N], within the braked pulleys' grip in the stop with the ``steady``
    solution; a sizing note is added to ``notes``)."""
    force = []
    if conv.brakes:
        kn, _why, note = design.brake_forces(conv, scn, total_mass, te, gravity_sum, steady)
        force = [f * 1e3 for f in kn]
        if note:
            notes.append(note)
    nb = len(conv.brakes)
    bt, bf, bn = padded_curves([tuple(b.force_curve or ()) for b in conv.brakes])
    return Brakes(
        shaft=np.array([shaft_index[loop.brake_element(b)] for b in conv.brakes], dtype=np.int64),
        node=np.array([loop.brake_element(b) for b in conv.brakes], dtype=np.int64),
        force=np.array(force, dtype=np.float64),
        delay=np.array([b.delay_s for b in conv.brakes], dtype=np.float64),
        ramp=np.array([b.ramp_s for b in conv.brakes], dtype=np.float64),
        curve_t=bt, curve_f=bf, curve_n=bn,
        hold=np.array([1 if b.hold else 0 for b in conv.brakes], dtype=np.int64),
        t_cmd=np.full(nb, -1.0), released=np.zeros(nb, dtype=np.int64))


@njit(inline="always", **OPTS)
def brake_fraction(tau, ramp, ct, cf, nc):
    """Fraction of a brake's force ``tau`` seconds after it was applied (past its delay): a
    linear ramp over ``ramp`` [s], or the curve of ``nc`` points (times ``ct`` [s], fractions
    ``cf``)."""
    if tau < 0.0:
        return 0.0
    if nc > 0:
        if tau <= ct[0]:
            return cf[0] if tau >= ct[0] else 0.0
        k = 1
        while k < nc and tau > ct[k]:
            k += 1
        if k >= nc:
            return cf[nc - 1]
        return cf[k - 1] + (cf[k] - cf[k - 1]) * (tau - ct[k - 1]) / (ct[k] - ct[k - 1])
    if ramp <= 0.0 or tau >= ramp:
        return 1.0
    return tau / ramp


@njit(inline="always", **OPTS)
def brake_force(brakes, b, tau, v):
    """Force of brake ``b`` [N] ``tau`` seconds after its delay ran out (negative before),
    its shaft turning at ``v`` [m/s at the rim]: the full force times
    :func:`brake_fraction` (the law does not depend on the speed)."""
    return brakes.force[b] * brake_fraction(tau, brakes.ramp[b], brakes.curve_t[b],
                                            brakes.curve_f[b], brakes.curve_n[b])


@njit(inline="always", **OPTS)
def set_at(brakes, b):
    """The time brake ``b``, commanded at ``brakes.t_cmd[b]``, gives its full force [s]: the
    command, its delay and its ramp (or its force curve's last time)."""
    nc = brakes.curve_n[b]
    full = brakes.curve_t[b, nc - 1] if nc > 0 else brakes.ramp[b]
    return brakes.t_cmd[b] + brakes.delay[b] + full
