"""The Euler-X transient engine (PHYSICS section 5, seed paper section 3).

``build_system`` assembles the element arrays once per conveyor and scenario, ``simulate``
runs the numba kernel over the whole rest -> start -> run -> stop -> rest cycle and decodes
the SPEC fields; ``reference`` holds the slow numpy implementation of the same equations.

Rooms: ``model`` (the System), ``arrays`` (the kernel's argument groups), ``codes`` (array
layouts, status codes, limits), ``fastmath`` (exp/log and LLVM helpers), ``passes`` (the
vectorised passes), ``blocks`` (the implicit pulley blocks: solver, slip, drives, brakes),
``laws`` (motor, coupling and brake laws), ``profiles`` (speed references), ``kernel`` (one
step as a sequence of passes), ``simulate`` (prepare and decode).
"""

from beltstudy.engine.dynamics.model import DynamicsOptions, System, build_system
from beltstudy.engine.dynamics.simulate import TransientResult, simulate

__all__ = ["DynamicsOptions", "System", "build_system", "TransientResult", "simulate"]
