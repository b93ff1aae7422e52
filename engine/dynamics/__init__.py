"""The Euler-X transient engine (PHYSICS section 5, seed paper section 3).

``build_system`` assembles the element arrays once per conveyor and scenario, ``simulate``
runs the numba kernel over the whole rest -> start -> run -> stop -> rest cycle and decodes
the SPEC fields; ``reference`` holds the slow numpy implementation of the same equations.
"""

from engine.dynamics.model import DynamicsOptions, System, build_system
from engine.dynamics.simulate import TransientResult, simulate

__all__ = ["DynamicsOptions", "System", "build_system", "TransientResult", "simulate"]
