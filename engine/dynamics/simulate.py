"""Python wrapper: System -> kernel arrays -> run -> TransientResult (SPEC sections 4 and 5).

:func:`simulate` is the one entry point of the transient engine: it converts the
:class:`~engine.dynamics.model.System` to the plain arrays of the numba kernel
(:func:`engine.dynamics.kernel.run_cycle`), runs the whole cycle and turns the kernel's
outputs into the SPEC fields (transient summary, key-point time series, surface, envelopes)
and the warnings.
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass, field

import numpy as np
import pandas as pd

from engine.dynamics import kernel as K
from engine.dynamics.model import System

__all__ = ["TransientResult", "KernelInput", "prepare", "simulate", "TIMESERIES_COLUMNS",
           "SURFACE_COLUMNS"]

#: SPEC section 5 key-point columns, in order (extra columns follow them).
TIMESERIES_COLUMNS = ("t_s", "v_drive_m_s", "v_tail_m_s", "f_drive_kn", "t_head_in_kn",
                      "t_head_out_kn", "t_tail_kn", "t_takeup_kn", "x_takeup_m", "t_min_kn",
                      "t_max_kn")
#: Extra key-point columns (not in SPEC, additive): mean belt speed, speed reference,
#: brake force, drive power.
EXTRA_COLUMNS = ("v_mean_m_s", "v_ref_m_s", "f_brake_kn", "p_drive_kw")
SURFACE_COLUMNS = ("t_s", "s_m", "tension_kn", "velocity_m_s")

#: Speed at which a run counts as diverged, as a multiple of the design speed.
V_FAIL_FACTOR = 100.0


@dataclass(eq=False)
class KernelInput:
    """The kernel's arguments by name, in the order of
    :func:`engine.dynamics.kernel.run_cycle` (outputs are filled in place)."""

    args: dict

    def call(self) -> int:
        return int(K.run_cycle(*self.args.values()))


def _codes(values: np.ndarray) -> np.ndarray:
    """Exponent codes: 0 -> 0, 0.5 -> 1, 1 -> 2, 1.5 -> 3, 2 -> 4, other -> 5 (pow)."""
    table = {0.0: 0, 0.5: 1, 1.0: 2, 1.5: 3, 2.0: 4}
    return np.array([table.get(float(x), 5) for x in values], dtype=np.int64)


def _ranges(mask: np.ndarray) -> np.ndarray:
    """Contiguous [start, end) index ranges where mask is true, shape (k, 2)."""
    idx = np.flatnonzero(mask)
    if idx.size == 0:
        return np.zeros((0, 2), dtype=np.int64)
    cuts = np.flatnonzero(np.diff(idx) > 1)
    starts = np.concatenate(([idx[0]], idx[cuts + 1]))
    ends = np.concatenate((idx[cuts] + 1, [idx[-1] + 1]))
    return np.ascontiguousarray(np.column_stack([starts, ends]), dtype=np.int64)


def prepare(sys: System, t_end_s: float | None = None) -> KernelInput:
    """Convert a System to the kernel's arrays (fresh state: the belt at rest).

    ``t_end_s`` ends the run at that time [s] instead of after the stop (verification)."""
    n = sys.n
    if sys.damping == "sls":
        e_damp = math.exp(-sys.dt_s / sys.tau_s)
        g_damp = (1.0 - e_damp) * sys.c_visc_ns / (sys.stiffness_n * sys.dt_s)
    elif sys.damping == "kv":
        e_damp = 0.0
        g_damp = sys.c_visc_ns / (sys.stiffness_n * sys.dt_s)
    else:
        e_damp, g_damp = 0.0, 0.0
    fp = np.zeros(K.FP.SIZE)
    fp[K.FP.DT] = sys.dt_s
    fp[K.FP.T_PRE] = sys.pre_rest_s
    fp[K.FP.T_START] = sys.start_s
    fp[K.FP.T_RUN] = sys.run_s
    fp[K.FP.T_STOP] = sys.stop_s
    fp[K.FP.V_D] = sys.v_design
    fp[K.FP.V_EPS] = sys.v_eps
    fp[K.FP.EB] = sys.stiffness_n
    fp[K.FP.E_DAMP] = e_damp
    fp[K.FP.G_DAMP] = g_damp
    fp[K.FP.HS_REF] = sys.hs_ref
    fp[K.FP.HS_MAX] = sys.hs_max
    fp[K.FP.KP] = sys.kp
    fp[K.FP.KI] = sys.ki
    fp[K.FP.M_TOT] = sys.total_mass_kg
    fp[K.FP.TU_W] = sys.takeup_weight_n
    fp[K.FP.TU_M] = sys.takeup_inertia_kg
    fp[K.FP.TU_LO] = sys.takeup_lo_m
    fp[K.FP.TU_HI] = sys.takeup_hi_m
    fp[K.FP.REC_DT] = sys.record_dt_s
    fp[K.FP.SURF_DT] = sys.surface_dt_s
    fp[K.FP.STOP_MAX] = sys.stop_max_s
    fp[K.FP.POST_REST] = sys.post_rest_s
    fp[K.FP.F_CONST] = sys.force_start_n
    fp[K.FP.V_FAIL] = V_FAIL_FACTOR * sys.v_design
    fp[K.FP.F_RES] = sys.te_n - float(sys.gravity_n.sum())
    fp[K.FP.V_FF] = sys.v_ff_m_s
    fp[K.FP.T_END] = float(t_end_s) if t_end_s else 0.0
    ip = np.zeros(K.IP.SIZE, dtype=np.int64)
    ip[K.IP.N] = n
    ip[K.IP.START_CTRL] = sys.start_control
    ip[K.IP.STOP_MODE] = sys.stop_mode
    ip[K.IP.FORMULATION] = sys.formulation
    ip[K.IP.TU_GRAVITY] = 1 if sys.takeup_gravity else 0
    ip[K.IP.I_TU] = sys.i_takeup
    ip[K.IP.I_TAIL] = sys.i_tail
    ip[K.IP.ANY_PS] = 1 if np.any(sys.ps != 0.0) else 0
    ip[K.IP.M_NODE] = int(sys.drive_node[0])
    ip[K.IP.HOLD_NODE] = int(sys.hold_node)

    # blocks: the master drive's block first (slaves use its controller output)
    blocks = sorted(sys.blocks, key=lambda b: 0 if int(sys.drive_node[0]) in b else 1)
    if max(len(b) for b in blocks) + 1 > K.BLOCK_MAX:
        raise ValueError("implicit block larger than the kernel's BLOCK_MAX")
    in_block = np.zeros(n, dtype=bool)
    for b in blocks:
        in_block[b] = True
    blk_ptr = np.concatenate(([0], np.cumsum([len(b) for b in blocks]))).astype(np.int64)
    blk_nodes = np.concatenate([np.asarray(b, dtype=np.int64) for b in blocks])
    blk_car = np.array([1 if (sys.takeup_gravity and sys.i_takeup in b) else 0
                        for b in blocks], dtype=np.int64)
    node_drive = np.full(n, -1, dtype=np.int64)
    for k, d in enumerate(sys.drive_node):
        node_drive[int(d)] = k
    node_hb = np.zeros(n, dtype=np.int64)
    if sys.holdback_node >= 0:
        node_hb[sys.holdback_node] = 1

    t0 = np.maximum(sys.tension_rest_n, 0.0)
    nrec = int(math.ceil(sys.t_max_s / sys.record_dt_s)) + 3
    nsurf = int(math.ceil(sys.t_max_s / sys.surface_dt_s)) + 3
    npr = len(sys.probe_springs)
    nsf = len(sys.surface_springs)
    f64 = np.float64

    def arr(x, dtype=f64):
        return np.ascontiguousarray(x, dtype=dtype)

    # terms with few non-zero elements (feed, pulleys, accessories) are evaluated on those
    # elements only: t_idx[t_ptr[k]:t_ptr[k + 1]] for a term with t_sparse[k] == 1
    t_sparse, t_ptr, t_idx = [], [0], []
    for k in range(sys.coef.shape[0]):
        nz = np.flatnonzero(sys.coef[k])
        sparse = len(nz) <= max(8, n // 16)
        t_sparse.append(1 if sparse else 0)
        if sparse:
            t_idx.extend(int(j) for j in nz)
        t_ptr.append(len(t_idx))

    args = dict(
        fp=fp, ip=ip, mass=arr(sys.mass_kg), hm=arr(sys.dt_s / sys.mass_kg),
        gravity=arr(sys.gravity_n), sw=arr(sys.sag_w_n), coef=arr(sys.coef),
        pvc=_codes(sys.pv), pvv=arr(sys.pv), psc=_codes(sys.ps), psv=arr(sys.ps),
        w_mean=arr(sys.belt_mass_kg), t_sparse=arr(t_sparse, np.int64),
        t_ptr=arr(t_ptr, np.int64), t_idx=arr(t_idx or [0], np.int64),
        dl=arr(sys.dt_s / sys.len_m),
        a_eb=arr(sys.a_ernst * sys.stiffness_n), t_floor=arr(sys.t_floor_n),
        kfl_eb=arr(sys.k_floor_n / sys.stiffness_n), car_ind=arr(sys.carriage_coupling),
        seg_node=_ranges(~in_block), seg_spring=_ranges(~sys.implicit),
        blk_ptr=blk_ptr, blk_nodes=blk_nodes, blk_car=blk_car,
        node_drive=node_drive, node_hb=node_hb,
        d_node=arr(sys.drive_node, np.int64), d_share=arr(sys.drive_share),
        d_lim=arr(sys.drive_limit_n), d_euler=arr(sys.drive_euler),
        b_node=arr(sys.brake_node, np.int64), b_force=arr(sys.brake_force_n),
        b_delay=arr(sys.brake_delay_s),
        v=np.zeros(n), te=t0.copy(), td=np.zeros(n),
        tt=t0.copy(), state=np.array([0.0, 0.0, 0.0, sys.hold_force_n]),
        probes=arr(sys.probe_springs, np.int64), surf_idx=arr(sys.surface_springs, np.int64),
        rec=np.zeros((nrec, K.REC.SIZE)), rec_t=np.zeros((nrec, npr)),
        rec_v=np.zeros((nrec, npr)), surf_t=np.zeros((nsurf, nsf + 1)),
        surf_v=np.zeros((nsurf, nsf)), t_max=np.zeros(n), t_min=np.zeros(n),
        t_max_t=np.zeros(n), t_min_t=np.zeros(n), d_force=np.zeros(len(sys.drive_node)),
        res=np.zeros(K.RES.SIZE),
    )
    return KernelInput(args=args)


@dataclass(eq=False)
class TransientResult:
    """Outputs of one transient cycle. Forces in the DataFrames in [kN], SI elsewhere.

    Attributes
    ----------
    status : str
        ``ok``, ``warning`` or ``failed``.
    message : str
        Why, in words ("" when ok).
    warnings : list of str
        Every limit crossed during the transient.
    summary : dict
        SPEC section 4 transient fields.
    timeseries : pandas.DataFrame
        SPEC section 5 key points at ``record_dt_s`` (plus ``v_mean_m_s``, ``v_ref_m_s``,
        ``f_brake_kn``, ``p_drive_kw``).
    traces : pandas.DataFrame
        ``t_s`` and the tension [kN] at the probe springs round the loop (Fig. 4), columns
        named ``T@<s>m``.
    surface : pandas.DataFrame
        Long table ``t_s, s_m, tension_kn, velocity_m_s`` at a coarser spacing.
    envelope : pandas.DataFrame
        Per spring: ``s_m``, ``t_max_kn``, ``t_max_time_s``, ``t_min_kn``, ``t_min_time_s``.
    system : System
    raw : dict
        Kernel scalars by name (``RES``), final state arrays and run bookkeeping.
    """

    status: str
    message: str
    warnings: list[str]
    summary: dict
    timeseries: pd.DataFrame
    traces: pd.DataFrame
    surface: pd.DataFrame
    envelope: pd.DataFrame
    system: System
    raw: dict = field(default_factory=dict)


def run_kernel(sys: System, t_end_s: float | None = None) -> tuple[KernelInput, float]:
    """Prepare and run the kernel; returns the inputs (holding outputs) and wall time [s]."""
    ki = prepare(sys, t_end_s)
    t0 = time.perf_counter()
    ki.call()
    return ki, time.perf_counter() - t0


def simulate(sys: System, *, steady_summary: dict | None = None, conveyor=None,
             safety_factor_min: float | None = None, t_end_s: float | None = None
             ) -> TransientResult:
    """Run the whole cycle for a System and decode the results.

    Parameters
    ----------
    sys : System
        From :func:`engine.dynamics.model.build_system`.
    steady_summary : dict, optional
        Statics summary (for ``dyn_factor`` = t_max_dyn / t_max).
    conveyor : Conveyor, optional
        For the sag limits and the belt rating in the warnings.
    safety_factor_min : float, optional
        Minimum belt safety factor during the transient; below it a warning is raised.
    t_end_s : float, optional
        End the run at this time [s] (verification runs; the stop may not be reached).
    """
    ki, wall = run_kernel(sys, t_end_s)
    return decode(sys, ki, wall, steady_summary=steady_summary, conveyor=conveyor,
                  safety_factor_min=safety_factor_min)


def decode(sys: System, ki: KernelInput, wall_s: float, *, steady_summary=None, conveyor=None,
           safety_factor_min=None) -> TransientResult:
    """Turn kernel outputs into a :class:`TransientResult`."""
    a = ki.args
    v, te, td, tt, state = a["v"], a["te"], a["td"], a["tt"], a["state"]
    rec, rec_t, surf_t, surf_v = a["rec"], a["rec_t"], a["surf_t"], a["surf_v"]
    t_max, t_min, t_max_t, t_min_t = a["t_max"], a["t_min"], a["t_max_t"], a["t_min_t"]
    d_force, res = a["d_force"], a["res"]
    r = {name: float(res[idx]) for name, idx in vars(K.RES).items()
         if not name.startswith("_") and name != "SIZE"}
    nrec = int(r["NREC"])
    nsurf = int(r["NSURF"])
    s_end = sys.s_end_m

    cols = {
        "t_s": rec[:nrec, K.REC.T],
        "v_drive_m_s": rec[:nrec, K.REC.V_DRIVE],
        "v_tail_m_s": rec[:nrec, K.REC.V_TAIL],
        "f_drive_kn": rec[:nrec, K.REC.F_DRIVE] / 1e3,
        "t_head_in_kn": rec[:nrec, K.REC.T_HEAD_IN] / 1e3,
        "t_head_out_kn": rec[:nrec, K.REC.T_HEAD_OUT] / 1e3,
        "t_tail_kn": rec[:nrec, K.REC.T_TAIL] / 1e3,
        "t_takeup_kn": rec[:nrec, K.REC.T_TAKEUP] / 1e3,
        "x_takeup_m": rec[:nrec, K.REC.X_TU],
        "t_min_kn": rec[:nrec, K.REC.T_MIN] / 1e3,
        "t_max_kn": rec[:nrec, K.REC.T_MAX] / 1e3,
        "v_mean_m_s": rec[:nrec, K.REC.V_MEAN],
        "v_ref_m_s": rec[:nrec, K.REC.V_REF],
        "f_brake_kn": rec[:nrec, K.REC.F_BRAKE] / 1e3,
        "p_drive_kw": rec[:nrec, K.REC.P_DRIVE] / 1e3,
    }
    timeseries = pd.DataFrame(cols)
    traces = pd.DataFrame({"t_s": rec[:nrec, K.REC.T]})
    for k, j in enumerate(sys.probe_springs):
        traces[f"T@{s_end[j]:.0f}m"] = rec_t[:nrec, k] / 1e3
    idx = sys.surface_springs
    ts = surf_t[:nsurf, 0]
    surface = pd.DataFrame({
        "t_s": np.repeat(ts, len(idx)),
        "s_m": np.tile(s_end[idx], nsurf),
        "tension_kn": surf_t[:nsurf, 1:].ravel() / 1e3,
        "velocity_m_s": surf_v[:nsurf].ravel(),
    })
    envelope = pd.DataFrame({"s_m": s_end, "t_max_kn": t_max / 1e3, "t_max_time_s": t_max_t,
                             "t_min_kn": t_min / 1e3, "t_min_time_s": t_min_t})

    summary, warnings = transient_summary(sys, r, t_max, t_max_t, t_min, t_min_t,
                                          steady_summary=steady_summary, conveyor=conveyor,
                                          safety_factor_min=safety_factor_min)
    if int(r["STATUS"]) == K.DIVERGED:
        status = "failed"
        message = (f"diverged: non-finite or runaway speed (> {V_FAIL_FACTOR:g} x design) at "
                   f"t = {r['T_END']:.4g} s with dt = {sys.dt_s:.3g} s; the run was stopped")
    elif int(r["STATUS"]) == K.SLACK:
        status = "failed"
        j = int(r["SLACK_AT"])
        message = (f"the belt went slack beyond the model's range at {s_end[j]:.0f} m, "
                   f"t = {r['T_END']:.1f} s ({100 * r['SLACK']:.0f} % of the span length stored "
                   f"as slack; the belt would pile up or leave the idlers): the run was stopped "
                   f"there. Raise the take-up tension or soften the stop (brake force, brake "
                   f"position, stop time)")
        if warnings:
            message += "; also: " + "; ".join(warnings)
    elif warnings:
        status = "warning"
        message = "; ".join(warnings)
    else:
        status, message = "ok", ""
    raw = dict(r)
    raw.update(v=v.copy(), te=te.copy(), td=td.copy(), tension=tt.copy(),
               x_takeup=float(state[0]), u_takeup=float(state[1]), integrator=float(state[2]),
               drive_force=d_force.copy(), wall_s=wall_s,
               element_steps=float(r["STEPS"]) * sys.n)
    return TransientResult(status=status, message=message, warnings=warnings, summary=summary,
                           timeseries=timeseries, traces=traces, surface=surface,
                           envelope=envelope, system=sys, raw=raw)


def transient_summary(sys: System, r: dict, t_max, t_max_t, t_min, t_min_t, *,
                      steady_summary=None, conveyor=None, safety_factor_min=None):
    """SPEC section 4 transient fields and the warnings."""
    s_end = sys.s_end_m
    jmax = int(np.argmax(t_max))
    jmin = int(np.argmin(t_min))
    t_max_dyn = float(t_max[jmax])
    t_min_dyn = float(t_min[jmin])
    steady_tmax = None
    if steady_summary and steady_summary.get("t_max_kn"):
        steady_tmax = float(steady_summary["t_max_kn"]) * 1e3
    else:
        steady_tmax = float(np.max(sys.steady_tension_n))
    # sag from the minimum envelope: element j between springs j - 1 and j
    t_el = 0.5 * (np.roll(t_min, 1) + t_min)
    idler = sys.sag_w_n > 0.0
    sag = np.where(idler, 100.0 * sys.sag_w_n / np.maximum(t_el, 1.0), 0.0)
    sag = np.minimum(sag, 100.0)
    t_stop_ach = r["STOP_ACH"] if r["STOP_ACH"] >= 0 else None
    t_start_ach = r["START_ACH"] if r["START_ACH"] >= 0 else None
    stop_for_ratio = t_stop_ach if t_stop_ach is not None else None
    rating = None
    if conveyor is not None:
        from engine.catalog import resolve_belt

        rating = resolve_belt(conveyor.belt).rating_n
    summary = {
        "t_max_dyn_kn": t_max_dyn / 1e3,
        "t_max_dyn_at_m": float(s_end[jmax]),
        "t_max_dyn_time_s": float(r["TMAX_T"]),
        "t_min_dyn_kn": t_min_dyn / 1e3,
        "t_min_dyn_at_m": float(s_end[jmin]),
        "t_min_dyn_time_s": float(r["TMIN_T"]),
        "dyn_factor": t_max_dyn / steady_tmax if steady_tmax > 0 else None,
        "drive_force_max_kn": r["FMAX"] / 1e3,
        "drive_power_max_kw": r["PMAX"] / 1e3,
        "velocity_max_m_s": r["VMAX"],
        "velocity_min_m_s": r["VMIN"],
        "takeup_travel_m": r["XMAX"] - r["XMIN"],
        "start_time_s": t_start_ach,
        "stop_time_s": t_stop_ach,
        "wave_loop_time_s": sys.wave_loop_time_s,
        "stop_wave_ratio": (stop_for_ratio / sys.wave_loop_time_s
                            if stop_for_ratio is not None else None),
        "sag_max_dyn_pct": float(sag.max()) if idler.any() else 0.0,
        "slip_margin_min_dyn": r["SLIP_MIN"] if r["SLIP_MIN"] < 1e299 else None,
        "safety_factor_dyn": (rating / t_max_dyn if rating and t_max_dyn > 0 else None),
        "dt_s": sys.dt_s,
        "elements": sys.n,
    }
    w: list[str] = list(sys.warnings)
    if int(r["STATUS"]) == K.DIVERGED:
        return summary, w
    if t_min_dyn <= 0.0:
        w.append(f"belt goes slack (zero tension) during the transient at "
                 f"{s_end[jmin]:.0f} m, t = {r['TMIN_T']:.1f} s")
    if conveyor is not None:
        lim = conveyor.sag_limit_pct
        for code, name, limit in ((0, "carry", lim.carry), (1, "return", lim.return_)):
            mask = sys_strand_mask(sys, code)
            if mask.any():
                smax = float(sag[mask].max())
                if smax > limit:
                    j = int(np.flatnonzero(mask)[np.argmax(sag[mask])])
                    w.append(f"transient sag on the {name} strand {smax:.2f} % exceeds the limit "
                             f"{limit:g} % (low tension {t_el[j] / 1e3:.3g} kN at "
                             f"{sys.s_end_m[j] - 0.5 * sys.dx_m[j]:.0f} m)")
    slip = summary["slip_margin_min_dyn"]
    if slip is not None and slip < 1.0:
        w.append(f"drive slip during the transient: slip margin {slip:.3f} < 1 at "
                 f"t = {r['SLIP_MIN_T']:.1f} s")
    sf = summary["safety_factor_dyn"]
    if sf is not None and safety_factor_min is not None and sf < safety_factor_min:
        w.append(f"belt safety factor {sf:.2f} during the transient is below {safety_factor_min:g} "
                 f"(peak {t_max_dyn / 1e3:.4g} kN at {s_end[jmax]:.0f} m)")
    if summary["stop_wave_ratio"] is not None and summary["stop_wave_ratio"] < 5.0:
        w.append(f"stop in {t_stop_ach:.1f} s is faster than 5 wave loop times "
                 f"(5 x {sys.wave_loop_time_s:.1f} s): a high-stress stop")
    if r["ENDSTOP"] > 0:
        w.append(f"take-up carriage reached its end stop at t = {r['ENDSTOP_T']:.1f} s "
                 f"(travel {sys.takeup_hi_m - sys.takeup_lo_m:.3g} m)")
    if t_start_ach is None:
        w.append("the belt never reached 99 % of design speed during the start")
    if r["STOPPED"] < 0.5:
        w.append(f"the belt did not stop within {sys.stop_max_s:.0f} s of the stop command "
                 f"(mean speed {r['V_MEAN_END']:.2f} m/s at the end)")
    return summary, w


def sys_strand_mask(sys: System, code: int) -> np.ndarray:
    """Elements of a strand (0 carry, 1 return) with idlers."""
    return (sys.strand == code) & (sys.sag_w_n > 0.0)
