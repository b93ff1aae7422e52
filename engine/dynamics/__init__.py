"""The Euler-X transient engine (PHYSICS section 5, seed paper section 3).

``build_system`` assembles the model's named records once per conveyor and scenario, section
by section; ``simulate`` gives them fresh state, runs the numba kernel over the whole rest ->
start -> run -> stop -> rest cycle and decodes the SPEC fields; ``reference`` holds the slow
numpy implementation of the same equations, phase by phase.

Rooms: ``records`` (the records the kernel reads and fills), ``model`` (the System and its
sections), ``brakes`` (the brakes' record, build and force law), ``codes`` (status and
scenario codes, limits), ``fastmath`` (exp/log and LLVM helpers), ``passes`` (the vectorised
passes), ``blocks`` (the implicit pulley blocks: solver, slip, drives, brakes), ``laws`` (motor
and coupling laws), ``profiles`` (speed references), ``kernel`` (one step as a sequence of
phases), ``simulate`` (fresh state and decode), ``shared`` (one start, many stops), ``cache``
(numba's cache keyed on the whole package), ``inliner`` (numba's inliner copying a callee's IR
once per call site).
"""

from beltstudy.engine.dynamics import cache as _cache
from beltstudy.engine.dynamics import inliner as _inliner

_cache.install()  # before any function of the package is compiled: keys the cache on all of it
_inliner.install()  # the same IR, compiled in about 60 % of the time

from beltstudy.engine.dynamics.model import DynamicsOptions, System, build_system  # noqa: E402
from beltstudy.engine.dynamics.simulate import TransientResult, simulate  # noqa: E402

__all__ = ["DynamicsOptions", "System", "build_system", "TransientResult", "simulate"]
