"""One start, many stops: runs that agree on everything the kernel reads up to the stop command
share one simulated rest, start and run (issue 29; SPEC section 7 leaves the results as they
are).

The kernel reads a run's stop (the stop mode and time, the brakes' forces, delays, ramps,
force curves and hold flags, the rest after the stop) only once the stop command has passed:
:func:`beltstudy.engine.dynamics.kernel._phase` computes the stop reference and the trip only
while ``stopping``, :func:`~beltstudy.engine.dynamics.kernel._brake_forces` commands a brake only
while ``stopping`` (before it every brake is uncommanded, so its force, delay, ramp, curve and
hold are not read and the holding time stays -1), and the rest after the stop is read when the
belt has come to rest. :data:`STOP_ONLY` names those fields; :func:`start_key` digests every
other array and number of the model, with the rest state the run starts from. Runs with equal
keys step identically up to the stop command, bit for bit, so :func:`simulate_group` runs that
stretch once (:func:`~beltstudy.engine.dynamics.kernel.run_cycle` pauses before the first step
past the stop command), copies the paused state for each run, puts in each run's own stop and
goes on. Each run's results are then bit-identical to its own separate run
(tests/engine/dynamics/test_shared.py).
"""

from __future__ import annotations

import hashlib
import time

import numpy as np

from beltstudy.engine.dynamics.kernel import PAUSED
from beltstudy.engine.dynamics.model import System
from beltstudy.engine.dynamics.simulate import KernelRun, TransientResult, decode, fresh_run

__all__ = ["STOP_ONLY", "start_key", "stop_key", "simulate_group", "group_by_start"]

#: Model fields the kernel reads only after the stop command (record -> fields): the run's stop.
STOP_ONLY = {
    "cycle": ("t_stop", "stop_mode", "post_rest", "t_end"),
    "brakes": ("force", "delay", "ramp", "curve_t", "curve_f", "curve_n", "hold"),
}


def _digest(h, name: str, value) -> None:
    """Feed one field (an array, a nested record or a number) into the hash ``h``."""
    h.update(name.encode())
    if hasattr(value, "_fields"):
        for f in value._fields:
            _digest(h, f"{name}.{f}", getattr(value, f))
    elif isinstance(value, np.ndarray):
        h.update(f"{value.dtype.str}{value.shape}".encode())
        h.update(np.ascontiguousarray(value).tobytes())
    else:
        h.update(repr(value).encode())


def start_key(sys: System) -> str:
    """Digest of everything the kernel reads up to the stop command: every field of the model
    but :data:`STOP_ONLY`, the rest tensions and the holding force the run starts from. Two
    systems with equal keys step alike, bit for bit, until the stop command."""
    h = hashlib.sha256()
    m = sys.model
    for rec in m._fields:
        part = getattr(m, rec)
        skip = STOP_ONLY.get(rec, ())
        for f in part._fields:
            if f not in skip:
                _digest(h, f"{rec}.{f}", getattr(part, f))
    _digest(h, "tension_rest_n", np.asarray(sys.tension_rest_n, dtype=np.float64))
    _digest(h, "hold_force_n", float(sys.hold_force_n))
    return h.hexdigest()


def group_by_start(systems: list[System]) -> list[list[int]]:
    """Indices of ``systems`` grouped by :func:`start_key`, in the order first seen."""
    groups: dict[str, list[int]] = {}
    for i, s in enumerate(systems):
        groups.setdefault(start_key(s), []).append(i)
    return list(groups.values())


def _copy(value):
    """A deep copy of a record tree of arrays (numbers as they are)."""
    if hasattr(value, "_fields"):
        return type(value)(*(_copy(getattr(value, f)) for f in value._fields))
    if isinstance(value, np.ndarray):
        return value.copy()
    return value


#: Records of the model holding arrays a run changes (marked *state* in
#: :mod:`beltstudy.engine.dynamics.records`, reset by
#: :func:`~beltstudy.engine.dynamics.simulate.fresh_model`); a branch copies these and shares
#: the others, which the kernel only reads.
STATEFUL = ("lin", "shafts", "drives", "brakes")


def _branch(paused: KernelRun, sys: System) -> KernelRun:
    """The paused run's state, copied, with ``sys``'s own stop put in (:data:`STOP_ONLY`)."""
    m = paused.model._replace(**{rec: _copy(getattr(paused.model, rec)) for rec in STATEFUL})
    lin = m.lin._replace(flag64=m.lin.flag.view(np.uint64))  # one buffer, two views
    own = sys.model
    cycle = own.cycle._replace(t_end=m.cycle.t_end)
    brakes = m.brakes._replace(**{f: getattr(own.brakes, f).copy()
                                  for f in STOP_ONLY["brakes"]})
    model = m._replace(cycle=cycle, brakes=brakes, lin=lin)
    return KernelRun(model=model, state=_copy(paused.state), out=_copy(paused.out),
                     work=_copy(paused.work))


def simulate_group(systems: list[System], *, steady_summary=None, conveyor=None,
                   safety_factor_min=None, grouped: bool = False) -> list[TransientResult]:
    """The whole cycle of every system, sharing the stretch up to the stop command.

    Parameters
    ----------
    systems : list of System
        With one :func:`start_key` (raises ValueError otherwise): runs of one conveyor, load,
        temperature, model and start that differ only in their stop.
    steady_summary, conveyor, safety_factor_min
        As :func:`beltstudy.engine.dynamics.simulate.simulate`: one for the group, or a list
        with one per system.
    grouped : bool
        The systems are a group of :func:`group_by_start` (their keys are not digested again).

    Returns
    -------
    list of TransientResult
        In the order of ``systems``, each bit-identical to its own separate run; the wall
        time of each is the shared stretch's plus its own.
    """
    if not grouped and len(keys := {start_key(s) for s in systems}) != 1:
        raise ValueError(f"simulate_group: the systems differ before the stop command ({len(keys)}"
                         " start keys); group them with group_by_start")
    # output buffers sized for the longest cycle of the group (their size is not read)
    big = max(range(len(systems)), key=lambda i: systems[i].t_max_s)
    shared = fresh_run(systems[big])
    t0 = time.perf_counter()
    status = shared.call(systems[big].stop_command_s)
    wall0 = time.perf_counter() - t0
    def each(value, i):
        return value[i] if isinstance(value, list) else value

    out = []
    done: dict[str, tuple[KernelRun, float]] = {}  # stop key -> the finished run, its wall
    for i, sys in enumerate(systems):
        key = stop_key(sys)
        if key in done:  # the same stop of the same start: the same kernel run, copied
            first, wall = done[key]
            kr = KernelRun(model=first.model, state=_copy(first.state), out=_copy(first.out),
                           work=first.work, slip_min_start=first.slip_min_start,
                           slip_min_stop=first.slip_min_stop)
        else:
            kr = _branch(shared, sys)
            t1 = time.perf_counter()
            if status == PAUSED:  # each phase's smallest slip margin, as KernelRun.cycle
                kept = kr.pause_slip()
                kr.call()
                kr.merge_slip(kept)
            else:  # the shared stretch ended before the stop command
                m = float(kr.out.run["slip_min"][0])
                kr.slip_min_start = m if m < 1e299 else None
            wall = wall0 + time.perf_counter() - t1
            done[key] = (kr, wall)
        out.append(decode(sys, kr, wall, steady_summary=each(steady_summary, i),
                          conveyor=each(conveyor, i),
                          safety_factor_min=each(safety_factor_min, i)))
    return out


def stop_key(sys: System) -> str:
    """Digest of what the kernel reads from the stop command on (:data:`STOP_ONLY`). Within a
    group of one :func:`start_key`, systems with equal stop keys give the same kernel run, bit
    for bit: :func:`simulate_group` runs it once (runs that differ only in what the law does not
    read, such as DIN's temperature, or CEMA's above 0 C where Kt is 1)."""
    h = hashlib.sha256()
    for rec, fields in STOP_ONLY.items():
        part = getattr(sys.model, rec)
        for f in fields:
            _digest(h, f"{rec}.{f}", getattr(part, f))
    return h.hexdigest()
