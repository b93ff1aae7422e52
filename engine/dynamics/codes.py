"""Codes, array layouts and limits shared by the kernel, the numpy reference and the wrapper.

The kernel takes its scalars in two arrays, ``fp`` (float64) and ``ip`` (int64), and returns
its results in ``res`` (run scalars), ``drv`` (per drive), ``rec`` (key points per record),
``rec_d`` (per drive per record) and the envelope segments. The index names below are the one
place those layouts are defined; Python callers read them through the namespaces ``FP``,
``IP``, ``RES``, ``DRV``, ``REC`` and ``RECD``.
"""

from __future__ import annotations

from beltstudy.engine.conveyor import CURVE_POINTS_MAX

__all__ = ["FP", "IP", "RES", "DRV", "REC", "RECD", "OK", "DIVERGED", "RUNAWAY", "V_FAIL_FACTOR",
           "RUNAWAY_FACTOR",
           "BLOCK_MAX", "CURVE_MAX", "SEG_MAX", "VFD", "DOL", "COUPLING_NONE", "COUPLING_FLUID",
           "COUPLING_FILL", "COAST", "BRAKE", "CONTROLLED", "RELATIVE", "SUPPORT"]

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
#: Largest implicit block (elements + carriage) the solver takes.
BLOCK_MAX = 16
#: Most points of a motor curve or a brake force curve.
CURVE_MAX = CURVE_POINTS_MAX  # beltstudy.engine.conveyor refuses longer curves at the door
#: Envelope segments: the cycle is cut at the stop command and when the belt first goes
#: slack, so per-phase and before/after-slack extremes come from whole segments.
SEG_MAX = 3

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

(FP_DT, FP_T_PRE, FP_T_START, FP_T_RUN, FP_T_STOP, FP_V_D, FP_V_EPS, FP_EB, FP_E_DAMP,
 FP_G_DAMP, FP_KP, FP_KI, FP_M_TOT, FP_TU_W, FP_TU_M, FP_TU_LO, FP_TU_HI, FP_REC_DT,
 FP_SURF_DT, FP_STOP_MAX, FP_POST_REST, FP_F_CONST, FP_V_FAIL, FP_F_RES, FP_V_FF, FP_T_END,
 FP_HS_REF, FP_SIZE) = range(28)
(IP_N, IP_START_CTRL, IP_STOP_MODE, IP_FORMULATION, IP_TU_GRAVITY, IP_I_TU, IP_I_TAIL,
 IP_ANY_PS, IP_M_DRIVE, IP_HOLD_NODE, IP_CONTROL, IP_S_HEAD_IN, IP_S_HEAD_OUT,
 IP_LAW_MODE, IP_SIZE) = range(15)
#: how the kernel evaluates the resistance law (IP_LAW_MODE): once (one constant term), exactly
#: every step, or expanded between exact evaluations (beltstudy.engine.dynamics.linlaw)
LAW_CONST, LAW_EXACT, LAW_LINEAR = 0, 1, 2
(RES_STATUS, RES_T_END, RES_STEPS, RES_START_ACH, RES_STOP_ACH, RES_VMAX, RES_VMAX_T, RES_VMIN,
 RES_VMIN_T, RES_XMIN, RES_XMAX, RES_FMAX, RES_FMAX_T, RES_PMAX, RES_SLIP_MIN, RES_SLIP_MIN_T,
 RES_ENDSTOP, RES_ENDSTOP_T, RES_ENDSTOP_SPEED, RES_NREC, RES_NSURF, RES_W_DRIVE,
 RES_T_STOPCMD, RES_STOPPED, RES_T_STOPPED, RES_V_MEAN_END, RES_I_END, RES_TMAX, RES_TMAX_T,
 RES_TMIN, RES_TMIN_T, RES_SLACK_MAX, RES_SLACK_AT, RES_SLACK_TIME, RES_SLACK_DUR,
 RES_SLACK_FIRST, RES_NSEG, RES_HOLD_SET, RES_TRIP, RES_LAW_EVALS, RES_DIV_WHERE, RES_SIZE) = range(42)
#: RES_DIV_WHERE of a diverged run: -1 the belt, s >= 0 pulley shaft s, -2 - k drive k's motor
#: per drive: largest |force| at the rim and |power| after the start command, smallest slip
#: margin and when, time slipping, belt length slipped, first and last time slipping
(DRV_FMAX, DRV_PMAX, DRV_SLIP_MIN, DRV_SLIP_MIN_T, DRV_SLIP_S, DRV_SLIP_M, DRV_SLIP_FIRST,
 DRV_SLIP_LAST, DRV_SIZE) = range(9)
(REC_T, REC_V_DRIVE, REC_V_TAIL, REC_F_DRIVE, REC_T_HEAD_IN, REC_T_HEAD_OUT, REC_T_TAIL,
 REC_T_TAKEUP, REC_X_TU, REC_T_MIN, REC_T_MAX, REC_V_MEAN, REC_F_BRAKE, REC_V_REF, REC_P_DRIVE,
 REC_V_ABS, REC_SLACK_M, REC_SIZE) = range(18)
#: per drive and record: force at the rim (drive side), shaft speed at the rim, force the
#: pulley passes to the belt
(RECD_F, RECD_V, RECD_FT, RECD_SIZE) = range(4)


def _namespace(prefix: str) -> type:
    """A read-only view of the module constants with ``prefix`` for Python callers."""
    names = {k[len(prefix):]: v for k, v in globals().items()
             if k.startswith(prefix) and isinstance(v, int)}
    return type(prefix.rstrip("_"), (), names)


FP = _namespace("FP_")
IP = _namespace("IP_")
RES = _namespace("RES_")
DRV = _namespace("DRV_")
REC = _namespace("REC_")
RECD = _namespace("RECD_")
