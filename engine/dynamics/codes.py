"""Codes and limits shared by the kernel, the numpy reference and the wrapper: run status,
scenario and drive codes, the speed window of torque followers, the kernel's size limits.

The kernel's data are named records (:mod:`beltstudy.engine.dynamics.records`); these are the
values some of their fields take.
"""

from __future__ import annotations

from beltstudy.engine.conveyor import CURVE_POINTS_MAX

__all__ = ["OK", "DIVERGED", "RUNAWAY", "V_FAIL_FACTOR",
           "RUNAWAY_FACTOR", "REST_FRACTION",
           "BLOCK_MAX", "CURVE_MAX", "SEG_MAX", "VFD", "DOL", "COUPLING_NONE", "COUPLING_FLUID",
           "COUPLING_FILL", "COAST", "BRAKE", "CONTROLLED", "RELATIVE", "SUPPORT", "HOLD", "RUN",
           "OFF", "LAW_CONST", "LAW_EXACT", "LAW_LINEAR"]

# run status: ok, diverged (the integration failed), runaway (the belt could not be held)
OK, DIVERGED, RUNAWAY = 0, 1, 2
#: Speed at which a run counts as diverged, as a multiple of the design speed: of any element,
#: pulley shaft or motor (behind a coupling), or any of them not finite.
V_FAIL_FACTOR = 100.0
#: Mean belt speed, as a multiple of the design speed either way, at which the belt has run
#: away (a decline the drives and brakes cannot hold, or a run-back): the run ends there, a
#: physical result with a warning. This project's threshold, not a standard's: the starts of
#: the example conveyors overshoot the design speed by 11 % at most (the 16.8 km overland in a
#: 60 s start), so a belt at twice it is not being held by anything.
RUNAWAY_FACTOR = 2.0
#: A stopping belt is at rest when its mass-weighted mean speed is below this fraction of the
#: design speed: its achieved stop time (``stop_ach``) and the stop window's rule
#: (docs/dynamics.md, *The stop window*).
REST_FRACTION = 0.01
#: Largest implicit block (elements + carriage) the solver takes.
BLOCK_MAX = 16
#: Most points of a motor curve or a brake force curve.
CURVE_MAX = CURVE_POINTS_MAX  # beltstudy.engine.conveyor refuses longer curves at the door
#: Envelope segments: the cycle is cut at the start command, when the belt first goes slack
#: and at the stop command, so per-phase (SPEC 6.4: start = start command to stop command) and
#: before/after-slack extremes come from whole segments.
SEG_MAX = 4

#: Speed window of a torque-following vfd drive, as a fraction of the design speed: a follower
#: gives the master's torque share while its own shaft stays within this of the speed
#: reference, and only what holds it at the window's edge beyond (the master/follower
#: "window control" of industrial drives; 10 % is a typical setting, an estimate).
SPEED_WINDOW = 0.10

# stop modes and formulations (scenario codes)
COAST, BRAKE, CONTROLLED = 0, 1, 2
RELATIVE, SUPPORT = 0, 1
# drive control and couplings
VFD, DOL = 0, 1
COUPLING_NONE, COUPLING_FLUID, COUPLING_FILL = 0, 1, 2
# what the drives do in one step
HOLD, RUN, OFF = 0, 1, 2

#: how the kernel evaluates the resistance law (``Law.mode``): once (one constant term), exactly
#: every step, or expanded between exact evaluations (beltstudy.engine.dynamics.linlaw)
LAW_CONST, LAW_EXACT, LAW_LINEAR = 0, 1, 2
