"""Python wrapper: System -> kernel arrays -> run -> TransientResult (SPEC sections 4-6).

:func:`simulate` is the one entry point of the transient engine: it converts the
:class:`~beltstudy.engine.dynamics.model.System` to the kernel's array groups
(:mod:`beltstudy.engine.dynamics.arrays`), runs the whole cycle (:func:`beltstudy.engine.dynamics.kernel.run_cycle`,
called by keyword) and turns the outputs into the SPEC fields (transient summary, per phase,
per drive, slack), the key-point time series, the surface, the envelopes and the warnings.
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass, field
from functools import cached_property

import numpy as np
import pandas as pd

from beltstudy.engine.dynamics import arrays as A
from beltstudy.engine.dynamics import codes as C
from beltstudy.engine.dynamics.kernel import run_cycle
from beltstudy.engine.dynamics.linlaw import (
    BIG,
    K_LIN,
    element_windows,
    law_windows,
    sparse_terms,
    x_cap,
)
from beltstudy.engine.dynamics.model import System, chord_strain
from beltstudy.engine.dynamics.passes import CHUNK, N_F, N_G, N_O, law_rows

__all__ = ["TransientResult", "KernelInput", "prepare", "simulate", "decode",
           "TIMESERIES_COLUMNS", "SURFACE_COLUMNS", "V_FAIL_FACTOR", "exponent_codes"]

#: SPEC section 5 key-point columns, in order (extra and per-drive columns follow them).
TIMESERIES_COLUMNS = ("t_s", "v_drive_m_s", "v_tail_m_s", "f_drive_kn", "t_head_in_kn",
                      "t_head_out_kn", "t_tail_kn", "t_takeup_kn", "x_takeup_m", "t_min_kn",
                      "t_max_kn")
SURFACE_COLUMNS = ("t_s", "s_m", "tension_kn", "velocity_m_s")
V_FAIL_FACTOR = C.V_FAIL_FACTOR
STRAND_NAMES = {0: "carry", 1: "return", 2: "head pulley", 3: "tail pulley",
                4: "take-up pulley"}


@dataclass(eq=False)
class KernelInput:
    """The kernel's arguments by name (groups of :mod:`beltstudy.engine.dynamics.arrays`); outputs are
    filled in place."""

    args: dict

    def call(self) -> int:
        return int(run_cycle(**self.args))

    def __getattr__(self, name):
        args = self.__dict__.get("args", {})
        if name in args:
            return args[name]
        raise AttributeError(name)


def exponent_codes(values: np.ndarray) -> np.ndarray:
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


def _curves(curves, width) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Pad a list of point lists to arrays (k, CURVE_MAX) and their lengths."""
    k = max(len(curves), 1)
    xs = np.zeros((k, width))
    ys = np.zeros((k, width))
    ns = np.zeros(k, dtype=np.int64)
    for i, c in enumerate(curves):
        if len(c) > width:
            raise ValueError(f"a curve has more than {width} points")
        ns[i] = len(c)
        for p, (x, y) in enumerate(c):
            xs[i, p] = x
            ys[i, p] = y
    return xs, ys, ns


def damper_coefficients(sys: System) -> tuple[float, float]:
    """(decay of the relaxing arm over a step, its gain per unit tangent stiffness and strain
    increment): the arm's tension ``d`` advances as ``d' = e d + g kt de`` (exact exponential
    of the standard linear solid's arm of stiffness ``(E_dyn - E) B``, relaxation time tau)."""
    if sys.damping != "belt" or not sys.stiffness_dyn_n > sys.stiffness_n:
        return 0.0, 0.0
    h = sys.dt_s / sys.relaxation_s
    e = math.exp(-h)
    ratio = (sys.stiffness_dyn_n - sys.stiffness_n) / sys.stiffness_n
    return e, ratio * (1.0 - e) / h


def linear_law_arrays(sys: System, windows) -> A.Lin:
    """The arrays of the law's expansion (:class:`~beltstudy.engine.dynamics.arrays.Lin`), filled by
    the kernel; per-element window sizes from ``windows`` (:func:`linlaw.law_windows`; None:
    the law is evaluated exactly and the arrays are not used)."""
    n = sys.n
    nk = sys.coef.shape[0]
    sw_ref = sys.sag_w_n / sys.hs_ref
    hsm_ref = sys.hs_cap / sys.hs_ref
    if windows is None:
        du = d0 = dx = np.full(n, BIG)
        pv, ps = np.zeros(1), np.zeros(1)
    else:
        du, d0, dx = element_windows(sys.coef, sys.pv, sys.ps, sw_ref, hsm_ref, sys.v_eps,
                                     windows)
        pv, ps = sys.pv, sys.ps
    rs, rq, upow, qpow, npow, wk = law_rows(pv, ps)
    erow = np.zeros((n, 8 + K_LIN))
    erow[:, 0] = sw_ref
    erow[:, 1] = hsm_ref
    erow[:, 2] = x_cap(sw_ref, hsm_ref)
    erow[:, 3] = du
    erow[:, 4] = d0
    erow[:, 5] = dx
    if windows is not None:
        erow[:, 8:8 + nk] = sys.coef.T
    n8 = 8 * ((n + 7) // 8)
    flag = np.zeros(n8, dtype=np.uint8)

    def z():
        return np.zeros(n, dtype=np.float32)

    return A.Lin(k=z(), gu=z(), guu=z(), gx=z(), gxx=z(), gux=z(), ulo=z(), uhi=z(), tlo=z(),
                 thi=z(), erow=erow, rs=rs, rq=rq, wk=wk, upow=upow, qpow=qpow, npow=npow,
                 flag=flag, flag64=flag.view(np.uint64),
                 idx=np.zeros(n + 8, dtype=np.int64), sg=np.zeros(N_G * CHUNK),
                 sf=np.zeros(N_F * CHUNK), so=np.zeros(N_O * CHUNK))


def prepare(sys: System, t_end_s: float | None = None) -> KernelInput:
    """Convert a System to the kernel's arrays (fresh state: the belt at rest).

    ``t_end_s`` ends the run at that time [s] instead of after the stop (verification)."""
    n = sys.n
    dt = sys.dt_s
    e_damp, g_damp = damper_coefficients(sys)
    f64 = np.float64

    def arr(x, dtype=f64):
        return np.ascontiguousarray(x, dtype=dtype)

    fp = np.zeros(C.FP.SIZE)
    fp[C.FP.DT] = dt
    fp[C.FP.T_PRE] = sys.pre_rest_s
    fp[C.FP.T_START] = sys.start_s
    fp[C.FP.T_RUN] = sys.run_s
    fp[C.FP.T_STOP] = sys.stop_s
    fp[C.FP.V_D] = sys.v_design
    fp[C.FP.V_EPS] = sys.v_eps
    fp[C.FP.EB] = sys.stiffness_n
    fp[C.FP.E_DAMP] = e_damp
    fp[C.FP.G_DAMP] = g_damp
    fp[C.FP.KP] = sys.kp
    fp[C.FP.KI] = sys.ki
    fp[C.FP.M_TOT] = sys.total_mass_kg
    fp[C.FP.TU_W] = sys.takeup_weight_n
    fp[C.FP.TU_M] = sys.takeup_inertia_kg
    fp[C.FP.TU_LO] = sys.takeup_lo_m
    fp[C.FP.TU_HI] = sys.takeup_hi_m
    fp[C.FP.REC_DT] = sys.record_dt_s
    fp[C.FP.SURF_DT] = sys.surface_dt_s
    fp[C.FP.STOP_MAX] = sys.stop_max_s
    fp[C.FP.POST_REST] = sys.post_rest_s
    fp[C.FP.F_CONST] = sys.force_start_n
    fp[C.FP.V_FAIL] = V_FAIL_FACTOR * sys.v_design
    fp[C.FP.F_RES] = sys.te_n - float(sys.gravity_n.sum())
    fp[C.FP.V_FF] = sys.v_ff_m_s
    fp[C.FP.T_END] = float(t_end_s) if t_end_s else 0.0
    fp[C.FP.HS_REF] = sys.hs_ref
    ip = np.zeros(C.IP.SIZE, dtype=np.int64)
    ip[C.IP.N] = n
    ip[C.IP.START_CTRL] = sys.start_control
    ip[C.IP.STOP_MODE] = sys.stop_mode
    ip[C.IP.FORMULATION] = sys.formulation
    ip[C.IP.TU_GRAVITY] = 1 if sys.takeup_gravity else 0
    ip[C.IP.I_TU] = sys.i_takeup
    ip[C.IP.I_TAIL] = sys.i_tail
    ip[C.IP.ANY_PS] = 1 if np.any(sys.ps != 0.0) else 0
    ip[C.IP.M_DRIVE] = sys.master
    ip[C.IP.HOLD_NODE] = sys.hold_node
    ip[C.IP.CONTROL] = int(sys.drive_control[0])
    ip[C.IP.S_HEAD_IN] = sys.spring_head_in
    ip[C.IP.S_HEAD_OUT] = sys.spring_head_out
    windows = law_windows(sys.coef, sys.pv, sys.ps, sys.resistance_rtol)
    if sys.coef.shape[0] == 1 and sys.pv[0] == 0.0 and sys.ps[0] == 0.0:
        ip[C.IP.LAW_MODE] = C.LAW_CONST
    else:
        ip[C.IP.LAW_MODE] = C.LAW_EXACT if windows is None else C.LAW_LINEAR

    nodes = A.Nodes(mass=arr(sys.mass_kg), hm=arr(dt / sys.mass_kg), gravity=arr(sys.gravity_n),
                    w_mean=arr(sys.belt_mass_kg), sw_ref=arr(sys.sag_w_n / sys.hs_ref),
                    hsm_ref=arr(sys.hs_cap / sys.hs_ref))
    # terms with few non-zero elements (feed, pulleys, accessories) are evaluated on those
    # elements only: t_idx[t_ptr[k]:t_ptr[k + 1]] for a term with t_sparse[k] == 1
    t_sparse, t_ptr, t_idx = [], [0], []
    for k, sparse in enumerate(sparse_terms(sys.coef)):
        t_sparse.append(1 if sparse else 0)
        if sparse:
            t_idx.extend(int(j) for j in np.flatnonzero(sys.coef[k]))
        t_ptr.append(len(t_idx))
    law = A.Law(coef=arr(sys.coef), pvc=exponent_codes(sys.pv), pvv=arr(sys.pv),
                psc=exponent_codes(sys.ps), psv=arr(sys.ps), t_sparse=arr(t_sparse, np.int64),
                t_ptr=arr(t_ptr, np.int64), t_idx=arr(t_idx or [0], np.int64))

    lin = linear_law_arrays(sys, windows)

    # blocks: the master drive's block first (the others use the speed loop's output)
    m_node = int(sys.drive_node[sys.master])
    blocks = sorted(sys.blocks, key=lambda b: 0 if m_node in b else 1)
    if max(len(b) for b in blocks) + 1 > C.BLOCK_MAX:
        raise ValueError("implicit block larger than the kernel's BLOCK_MAX")
    in_block = np.zeros(n, dtype=bool)
    for b in blocks:
        in_block[b] = True
    blk_nodes = np.concatenate([np.asarray(b, dtype=np.int64) for b in blocks])
    node_shaft = np.full(n, -1, dtype=np.int64)
    for k, node in enumerate(sys.shaft_node):
        node_shaft[int(node)] = k
    bl = A.Blocks(
        ptr=np.concatenate(([0], np.cumsum([len(b) for b in blocks]))).astype(np.int64),
        nodes=blk_nodes,
        car=np.array([1 if (sys.takeup_gravity and sys.i_takeup in b) else 0 for b in blocks],
                     dtype=np.int64),
        left=arr([(j - 1) % n for j in blk_nodes], np.int64),
        mdt=arr(sys.mass_kg[blk_nodes] / dt), node_shaft=node_shaft)
    springs = A.Springs(
        dl=arr(dt / sys.len_m), a_eb=arr(sys.a_ernst * sys.stiffness_n),
        t_floor=arr(sys.t_floor_n),
        s_floor=arr(sys.stiffness_n * chord_strain(sys.t_floor_n, sys.a_ernst, sys.stiffness_n,
                                                   sys.t_floor_n, sys.k_floor_n)),
        kfl_eb=arr(sys.k_floor_n / sys.stiffness_n),
        kvs=arr(sys.mesh_viscosity * sys.impedance_ns_m * sys.len_m / dt),
        car_ind=arr(sys.carriage_coupling), len_m=arr(sys.len_m),
        eps_run=arr(chord_strain(sys.steady_tension_n, sys.a_ernst, sys.stiffness_n,
                                 sys.t_floor_n, sys.k_floor_n)),
        seg_node=_ranges(~in_block), seg_spring=_ranges(~sys.implicit))
    ns = len(sys.shaft_node)
    shafts = A.Shafts(node=arr(sys.shaft_node, np.int64), mass=arr(sys.shaft_mass_kg),
                      cs=arr(sys.shaft_euler - 1.0), ck=arr(sys.shaft_euler_kinetic - 1.0),
                      drive=arr(sys.shaft_drive, np.int64),
                      hb=arr(sys.shaft_holdback, np.int64), vs=np.zeros(ns), slip=np.zeros(ns),
                      fb=np.zeros(ns), fb_out=np.zeros(ns))
    nd = len(sys.drive_share)
    cx, cy, cn = _curves(sys.drive_curves, C.CURVE_MAX)
    drives = A.Drives(
        shaft=arr(sys.drive_shaft, np.int64), share=arr(sys.drive_share),
        lim0=arr(sys.drive_limit_n), lim=np.array(sys.drive_limit_n, dtype=f64),  # a copy: per step
        rated=arr(sys.drive_rated_n),
        control=arr(sys.drive_control, np.int64), coupling=arr(sys.drive_coupling, np.int64),
        curve_x=cx, curve_y=cy, curve_n=cn, fill_s=arr(sys.drive_fill_s),
        motor_mass=arr(np.maximum(sys.drive_motor_mass_kg, 1.0)), trip_s=arr(sys.drive_trip_s),
        mode=np.zeros(nd, dtype=np.int64), f0=np.zeros(nd), f1=np.zeros(nd),
        sat=np.zeros(nd, dtype=np.int64), lin_p=np.zeros(nd), lin_d=np.zeros(nd),
        lin_cs=np.zeros(nd), vm=np.zeros(nd), force=np.zeros(nd), ft=np.zeros(nd),
        f_trip=np.zeros(nd))
    nb = len(sys.brake_shaft)
    bt, bf, bn = _curves(sys.brake_curves, C.CURVE_MAX)
    brakes = A.Brakes(
        shaft=arr(sys.brake_shaft, np.int64) if nb else np.zeros(0, dtype=np.int64),
        force=arr(sys.brake_force_n), delay=arr(sys.brake_delay_s), ramp=arr(sys.brake_ramp_s),
        curve_t=bt, curve_f=bf, curve_n=bn, hold=arr(sys.brake_hold, np.int64),
        t_cmd=np.full(max(nb, 0), -1.0), released=np.zeros(nb, dtype=np.int64))

    t0 = np.maximum(sys.tension_rest_n, 0.0)
    s0 = sys.stiffness_n * chord_strain(t0, sys.a_ernst, sys.stiffness_n, sys.t_floor_n,
                                        sys.k_floor_n)
    state = A.State(v=np.zeros(n), te=t0.copy(), ts=s0, td=np.zeros(n), tt=t0.copy(),
                    misc=np.array([0.0, 0.0, 0.0, sys.hold_force_n]))
    # the kernel records at most once a step: a spacing below the step gives one per step
    nrec = int(math.ceil(sys.t_max_s / max(sys.record_dt_s, sys.dt_s))) + 3
    nsurf = int(math.ceil(sys.t_max_s / max(sys.surface_dt_s, sys.dt_s))) + 3
    npr = len(sys.probe_springs)
    nsf = len(sys.surface_springs)
    out = A.Out(rec=np.zeros((nrec, C.REC.SIZE)), rec_t=np.zeros((nrec, npr)),
                rec_v=np.zeros((nrec, npr)), rec_d=np.zeros((nrec, nd, C.RECD.SIZE)),
                surf_t=np.zeros((nsurf, nsf + 1)), surf_v=np.zeros((nsurf, nsf)),
                probes=arr(sys.probe_springs, np.int64),
                surf_idx=arr(sys.surface_springs, np.int64), t_max=np.zeros(n),
                t_min=np.zeros(n), t_max_t=np.zeros(n), t_min_t=np.zeros(n),
                seg_env=np.zeros((C.SEG_MAX, 4, n)), seg_time=np.zeros((C.SEG_MAX, 2)),
                drv=np.zeros((nd, C.DRV.SIZE)), shs=np.zeros((max(ns, 1), 4)),
                res=np.zeros(C.RES.SIZE))
    bm = C.BLOCK_MAX

    def z():
        return np.zeros(bm)

    work = A.Work(dg=z(), lo=z(), up=z(), cl=z(), rw=z(), rhs=z(), crhs=z(), cuc=z(), kd=z(),
                  kc=z(), kr=z(), wd=z(), wl=z(), wu=z(), wc=z(), wr=z(), sol=z(), sol2=z(),
                  ucoef=z(), bA=z(), bB=z(), v_old=z(), rpos=z(), fexp=z(), fz=z(), stuck=z(),
                  bdir=z(), bforce=z(), c_lo=z(), c_hi=z(), fixed=z(), fixv=z(),
                  shk=np.zeros(bm, dtype=np.int64), vsn=z(), Ac=np.zeros((bm, bm)),
                  r0=np.zeros(n), phi=np.zeros(n), lnv=np.zeros(n), lnphi=np.zeros(n),
                  t_max_snap=np.zeros(n), t_min_snap=np.zeros(n), more=np.zeros(n))
    return KernelInput(args=dict(fp=fp, ip=ip, nodes=nodes, law=law, lin=lin, sp=springs,
                                 blocks=bl, shafts=shafts, drives=drives, brakes=brakes,
                                 st=state, out=out, wk=work))


@dataclass(eq=False)
class TransientResult:
    """Outputs of one transient cycle. Forces in the DataFrames in [kN], SI elsewhere.

    The tables are decoded into plain arrays (``series``, :meth:`surface_arrays`); the pandas
    DataFrames below are built from them on first access, so a caller that stores arrays
    (the study service's workers) never pays for them.

    Attributes
    ----------
    status : str
        ``ok``, ``warning`` or ``failed`` (a diverged integration only).
    message : str
        Why, in words ("" when ok): every limit crossed, then notes.
    warnings : list of str
        Every limit crossed during the transient.
    summary : dict
        SPEC section 4 and 6.4 transient fields.
    series : dict of str to ndarray
        The columns of ``timeseries`` as float64 arrays, in order.
    timeseries : pandas.DataFrame
        SPEC section 5 key points at ``record_dt_s``, then ``v_mean_m_s``, ``v_ref_m_s``,
        ``f_brake_kn``, ``p_drive_kw``, ``v_abs_max_m_s``, ``slack_m`` and per drive
        ``f_drive{i}_kn``, ``v_drive{i}_m_s``, ``f_belt{i}_kn`` (force the pulley passes to
        the belt).
    traces : pandas.DataFrame
        ``t_s`` and the tension [kN] at the probe springs round the loop (Fig. 4), columns
        named ``T@<s>m``.
    surface : pandas.DataFrame
        Long table ``t_s, s_m, tension_kn, velocity_m_s`` at a coarser spacing (the columns
        of :meth:`surface_arrays`).
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
    series: dict
    system: System
    raw: dict = field(default_factory=dict)
    #: (times [s], probe tensions [N] per time and probe, column names)
    trace_data: tuple = field(default=(), repr=False)
    #: (times [s], spring positions [m], tension [N] and speed [m/s] per time and spring)
    surface_data: tuple = field(default=(), repr=False)
    #: per spring: positions [m] and the whole-cycle extremes (``_extremes``)
    envelope_data: tuple = field(default=(), repr=False)

    @cached_property
    def timeseries(self) -> pd.DataFrame:
        return pd.DataFrame(self.series)

    @cached_property
    def traces(self) -> pd.DataFrame:
        t, tension, names = self.trace_data
        cols = {"t_s": t}
        for k, name in enumerate(names):
            cols[name] = tension[:, k] / 1e3
        return pd.DataFrame(cols)

    def surface_arrays(self) -> dict[str, np.ndarray]:
        """The surface as long float64 columns ``t_s``, ``s_m``, ``tension_kn``,
        ``velocity_m_s``: every sampled time with every sampled spring, time-major."""
        t, s, tension, velocity = self.surface_data
        return {
            "t_s": np.repeat(t, len(s)),
            "s_m": np.tile(s, len(t)),
            "tension_kn": tension.ravel() / 1e3,
            "velocity_m_s": velocity.ravel(),
        }

    @cached_property
    def surface(self) -> pd.DataFrame:
        return pd.DataFrame(self.surface_arrays(), copy=False)

    @cached_property
    def envelope(self) -> pd.DataFrame:
        s_end, whole = self.envelope_data
        return pd.DataFrame({"s_m": s_end, "t_max_kn": whole["env_max"] / 1e3,
                             "t_max_time_s": whole["env_max_t"],
                             "t_min_kn": whole["env_min"] / 1e3,
                             "t_min_time_s": whole["env_min_t"]})

    def envelope_kn(self) -> tuple[np.ndarray, np.ndarray]:
        """Highest and lowest tension of every spring over the cycle [kN]."""
        whole = self.envelope_data[1]
        return whole["env_max"] / 1e3, whole["env_min"] / 1e3


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
        From :func:`beltstudy.engine.dynamics.model.build_system`.
    steady_summary : dict, optional
        Statics summary (for ``dyn_factor`` = t_max_dyn / t_max).
    conveyor : Conveyor, optional
        For the sag limits, the belt rating and the drive names in the warnings.
    safety_factor_min : float, optional
        Minimum belt safety factor during the transient; below it a warning is raised.
    t_end_s : float, optional
        End the run at this time [s] (verification runs; the stop may not be reached).
    """
    ki, wall = run_kernel(sys, t_end_s)
    return decode(sys, ki, wall, steady_summary=steady_summary, conveyor=conveyor,
                  safety_factor_min=safety_factor_min)


def where(sys: System, j: int) -> str:
    """Words for the position of spring j: strand and distance from the tail [m]."""
    s = float(sys.s_end_m[j])
    code = int(sys.strand[j])
    if code == 1:  # the return strand runs back to the tail
        return f"{float(sys.s_end_m[-1]) - s:.0f} m from the tail on the return"
    if code == 0:
        return f"{s:.0f} m from the tail on the carry"
    return f"the {STRAND_NAMES.get(code, 'pulley')}"


#: How a slip message names the phase it happened in, and a span of phases.
_PHASE_WORDS = {"start": "during the start", "running": "while running", "stop": "during the stop"}
_PHASE_NAMES = {"start": "the start", "running": "steady running", "stop": "the stop"}


def _run_phase(sys: System, t_s: float, t_stop_cmd: float) -> str:
    """The phase of the cycle at time ``t_s`` [s]: ``start`` (to the end of the start
    reference, the rest before it included), ``running`` (to the stop command), ``stop``."""
    if t_s <= sys.pre_rest_s + sys.start_s:
        return "start"
    return "running" if t_s <= t_stop_cmd else "stop"


def diverged_words(sys: System, where_code: int, t_s: float, conveyor=None) -> str:
    """The message of a diverged run: what left the finite range (the belt, a pulley shaft, a
    motor behind its coupling), when, with which step, and what avoids it."""
    def drive_name(k: int) -> str:
        pos = f" ({conveyor.drives[k].position})" if conveyor is not None else ""
        return f"drive {k + 1}{pos}"

    fix = "a shorter step (scenario.dt_s: auto, or more elements)"
    if where_code == -1:
        what = "the belt's speed"
    elif where_code >= 0:
        k = int(sys.shaft_drive[where_code])
        what = (f"the pulley shaft of {drive_name(k)}" if k >= 0 else
                f"the shaft of the braked pulley at element {int(sys.shaft_node[where_code])}")
        fix = ("more inertia on that shaft (inertia_kg_m2, flywheel_kg_m2) or " + fix)
    else:
        what = f"the motor of {drive_name(-2 - where_code)} behind its coupling"
        fix = "more motor inertia (motor_inertia_kg_m2) or " + fix
    return (f"diverged: {what} became non-finite or passed {V_FAIL_FACTOR:g} x the design speed "
            f"at t = {t_s:.4g} s with dt = {sys.dt_s:.3g} s; the run was stopped; {fix} may "
            "avoid it")


def runaway_words(sys: System, t_s: float, v_mean: float, t_stop_cmd: float) -> str:
    """The warning of a run that ended because the belt ran away (mean speed past
    :data:`~beltstudy.engine.dynamics.codes.RUNAWAY_FACTOR` x design either way at ``t_s``)."""
    phase = _PHASE_WORDS[_run_phase(sys, t_s, t_stop_cmd)]
    if v_mean > 0.0:
        what = ("the belt ran away forwards", "the drives and brakes could not hold it back: "
                "more brake force, brakes that act in this stop (stop.mode: brake, hold), or, "
                "where a drive pulley slipped, a heavier take-up")
    else:
        what = ("the belt ran back", "nothing held it against the lift: a holdback "
                "(holdback: true), brakes that hold, or, where a drive pulley slipped, a heavier "
                "take-up")
    return (f"{what[0]} {phase}: its mean speed reached {abs(v_mean):.3g} m/s "
            f"({C.RUNAWAY_FACTOR:g} x the design speed) at t = {t_s:.4g} s and the run was "
            f"ended there; {what[1]}")


def slip_words(first: str, last: str) -> tuple[str, str]:
    """How a slip message names a slip from phase ``first`` to phase ``last`` (``start``,
    ``running``, ``stop``), and what would avoid it: a heavier take-up always, a longer start
    when it began in the start, a softer stop when it reached the stop."""
    when = _PHASE_WORDS[first] if first == last else \
        f"from {_PHASE_NAMES[first]} into {_PHASE_NAMES[last]}"
    fixes = ["a heavier take-up (more slack-side tension)"]
    if first == "start":
        fixes.append("a longer start (start.time_s)")
    if last == "stop":
        fixes.append("a softer stop (stop time, brake force)")
    fix = fixes[0] if len(fixes) == 1 else ", ".join(fixes[:-1]) + " or " + fixes[-1]
    return when, fix


def _segments(sys: System, out, r: dict):
    """The envelope segments as (t0, t1, t_max, t_max_t, t_min, t_min_t)."""
    nseg = int(r["NSEG"])
    segs = []
    for k in range(nseg):
        env = out.seg_env[k]
        segs.append((float(out.seg_time[k, 0]), float(out.seg_time[k, 1]), env[0], env[1],
                     env[2], env[3]))
    return segs


def _extremes(sys: System, segs) -> dict | None:
    """Largest and lowest tension over a set of segments: value [N], spring, time [s], and per
    spring the envelopes and their times (from the first segment holding each extreme). A
    diverged run's envelopes may hold NaN: the extremes are of the finite values."""
    if not segs:
        return None
    hi = np.array([s[2] for s in segs])
    lo = np.array([s[4] for s in segs])
    cols = np.arange(hi.shape[1])
    kmax = np.argmax(np.where(np.isnan(hi), -np.inf, hi), axis=0)
    kmin = np.argmin(np.where(np.isnan(lo), np.inf, lo), axis=0)
    tmax, tmin = hi[kmax, cols], lo[kmin, cols]
    tmax_t = np.array([s[3] for s in segs])[kmax, cols]
    tmin_t = np.array([s[5] for s in segs])[kmin, cols]
    jmax = int(np.nanargmax(tmax)) if np.isfinite(tmax).any() else 0
    jmin = int(np.nanargmin(tmin)) if np.isfinite(tmin).any() else 0
    return dict(t_max=float(tmax[jmax]), j_max=jmax, t_max_t=float(tmax_t[jmax]),
                t_min=float(tmin[jmin]), j_min=jmin, t_min_t=float(tmin_t[jmin]), env_min=tmin,
                env_max=tmax, env_max_t=tmax_t, env_min_t=tmin_t)


def decode(sys: System, ki: KernelInput, wall_s: float, *, steady_summary=None, conveyor=None,
           safety_factor_min=None) -> TransientResult:
    """Turn kernel outputs into a :class:`TransientResult`."""
    a = ki.args
    out, st = a["out"], a["st"]
    rec = out.rec
    r = {name: float(out.res[idx]) for name, idx in vars(C.RES).items()
         if not name.startswith("_") and name != "SIZE"}
    nrec = int(r["NREC"])
    nsurf = int(r["NSURF"])
    s_end = sys.s_end_m

    cols = {
        "t_s": rec[:nrec, C.REC.T],
        "v_drive_m_s": rec[:nrec, C.REC.V_DRIVE],
        "v_tail_m_s": rec[:nrec, C.REC.V_TAIL],
        "f_drive_kn": rec[:nrec, C.REC.F_DRIVE] / 1e3,
        "t_head_in_kn": rec[:nrec, C.REC.T_HEAD_IN] / 1e3,
        "t_head_out_kn": rec[:nrec, C.REC.T_HEAD_OUT] / 1e3,
        "t_tail_kn": rec[:nrec, C.REC.T_TAIL] / 1e3,
        "t_takeup_kn": rec[:nrec, C.REC.T_TAKEUP] / 1e3,
        "x_takeup_m": rec[:nrec, C.REC.X_TU],
        "t_min_kn": rec[:nrec, C.REC.T_MIN] / 1e3,
        "t_max_kn": rec[:nrec, C.REC.T_MAX] / 1e3,
        "v_mean_m_s": rec[:nrec, C.REC.V_MEAN],
        "v_ref_m_s": rec[:nrec, C.REC.V_REF],
        "f_brake_kn": rec[:nrec, C.REC.F_BRAKE] / 1e3,
        "p_drive_kw": rec[:nrec, C.REC.P_DRIVE] / 1e3,
        "v_abs_max_m_s": rec[:nrec, C.REC.V_ABS],
        "slack_m": rec[:nrec, C.REC.SLACK_M],
    }
    rec_d = out.rec_d
    for i in range(len(sys.drive_share)):
        cols[f"f_drive{i + 1}_kn"] = rec_d[:nrec, i, C.RECD.F] / 1e3
        cols[f"v_drive{i + 1}_m_s"] = rec_d[:nrec, i, C.RECD.V]
        cols[f"f_belt{i + 1}_kn"] = rec_d[:nrec, i, C.RECD.FT] / 1e3
    trace_data = (cols["t_s"], out.rec_t[:nrec],
                  [f"T@{s_end[j]:.0f}m" for j in sys.probe_springs])
    idx = sys.surface_springs
    surface_data = (out.surf_t[:nsurf, 0], s_end[idx], out.surf_t[:nsurf, 1:], out.surf_v[:nsurf])
    segs = _segments(sys, out, r)
    whole = _extremes(sys, segs)
    summary, warnings = transient_summary(sys, r, out, segs, steady_summary=steady_summary,
                                          conveyor=conveyor,
                                          safety_factor_min=safety_factor_min)
    notes = list(sys.notes)
    if int(r["STATUS"]) == C.DIVERGED:
        status = "failed"
        message = diverged_words(sys, int(r["DIV_WHERE"]), float(r["T_END"]), conveyor)
    elif warnings:
        status = "warning"
        message = "; ".join(warnings)
    else:
        status, message = "ok", ""
    if notes:
        message = "; ".join([m for m in (message, "note: " + "; ".join(notes)) if m])
    raw = dict(r)
    raw.update(v=st.v.copy(), te=st.te.copy(), ts=st.ts.copy(), td=st.td.copy(), tension=st.tt.copy(),
               x_takeup=float(st.misc[0]), u_takeup=float(st.misc[1]),
               integrator=float(st.misc[2]), drive_force=a["drives"].force.copy(),
               shaft_speed=a["shafts"].vs.copy(), shaft_slip=a["shafts"].slip.copy(),
               wall_s=wall_s, element_steps=float(r["STEPS"]) * sys.n, segments=segs)
    return TransientResult(status=status, message=message, warnings=warnings, summary=summary,
                           series=cols, system=sys, raw=raw, trace_data=trace_data,
                           surface_data=surface_data, envelope_data=(s_end, whole))


def _phase_fields(sys: System, prefix: str, ext: dict | None) -> dict:
    keys = ("kn", "at_m", "time_s")
    if ext is None:
        return {f"t_max_{prefix}_{k}": None for k in keys} | {
            f"t_min_{prefix}_{k}": None for k in keys}
    return {
        f"t_max_{prefix}_kn": ext["t_max"] / 1e3,
        f"t_max_{prefix}_at_m": float(sys.s_end_m[ext["j_max"]]),
        f"t_max_{prefix}_time_s": ext["t_max_t"],
        f"t_min_{prefix}_kn": ext["t_min"] / 1e3,
        f"t_min_{prefix}_at_m": float(sys.s_end_m[ext["j_min"]]),
        f"t_min_{prefix}_time_s": ext["t_min_t"],
    }


def transient_summary(sys: System, r: dict, out, segs, *, steady_summary=None, conveyor=None,
                      safety_factor_min=None):
    """SPEC section 4 and 6.4 transient fields and the warnings."""
    s_end = sys.s_end_m
    whole = _extremes(sys, segs)
    t_max_dyn = float(r["TMAX"])
    t_min_dyn = float(r["TMIN"])
    jmax = whole["j_max"]
    jmin = whole["j_min"]
    steady_tmax = (float(steady_summary["t_max_kn"]) * 1e3
                   if steady_summary and steady_summary.get("t_max_kn")
                   else float(np.max(sys.steady_tension_n)))
    # sag at each span's low end, from the minimum envelope
    t_min_env = whole["env_min"]
    t_low = np.minimum(np.roll(t_min_env, 1), t_min_env)
    idler = sys.sag_w_n > 0.0
    sag = np.where(idler, 100.0 * sys.sag_w_n / np.maximum(t_low, 1.0), 0.0)
    sag = np.minimum(sag, 100.0)
    t_stop_cmd = sys.stop_command_s
    t_stop_ach = r["STOP_ACH"] if r["STOP_ACH"] >= 0 else None
    t_start_ach = r["START_ACH"] if r["START_ACH"] >= 0 else None
    rating = None
    if conveyor is not None:
        from beltstudy.engine.catalog import resolve_belt

        rating = resolve_belt(conveyor.belt).rating_n
    # phases: start = start command to stop command, stop = stop command to the end
    eps = 1.5 * sys.dt_s
    start_segs = [s for s in segs if s[1] <= t_stop_cmd + eps]
    stop_segs = [s for s in segs if s[1] > t_stop_cmd + eps]
    first_slack = r["SLACK_FIRST"]
    pre = [s for s in segs if first_slack < 0 or s[1] <= first_slack + eps]
    post = [s for s in segs if first_slack >= 0 and s[1] > first_slack + eps]
    ext_pre = _extremes(sys, pre)
    ext_post = _extremes(sys, post)
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
        "stop_wave_ratio": (t_stop_ach / sys.wave_loop_time_s
                            if t_stop_ach is not None else None),
        "sag_max_dyn_pct": float(sag.max()) if idler.any() else 0.0,
        "slip_margin_min_dyn": r["SLIP_MIN"] if r["SLIP_MIN"] < 1e299 else None,
        "safety_factor_dyn": (rating / t_max_dyn if rating and t_max_dyn > 0 else None),
        **_phase_fields(sys, "start", _extremes(sys, start_segs)),
        **_phase_fields(sys, "stop", _extremes(sys, stop_segs)),
        "t_max_pre_slack_kn": ext_pre["t_max"] / 1e3 if ext_pre else None,
        "t_max_post_slack_kn": ext_post["t_max"] / 1e3 if ext_post else None,
        "t_max_post_slack_at_m": float(s_end[ext_post["j_max"]]) if ext_post else None,
        "t_max_post_slack_time_s": ext_post["t_max_t"] if ext_post else None,
        "slack_max_m": r["SLACK_MAX"],
        "slack_at_m": float(s_end[int(r["SLACK_AT"])]) if r["SLACK_AT"] >= 0 else None,
        "slack_time_s": r["SLACK_TIME"] if r["SLACK_TIME"] >= 0 else None,
        "slack_duration_s": r["SLACK_DUR"],
        "takeup_endstop_speed_m_s": r["ENDSTOP_SPEED"],
        # filled by beltstudy.engine.remedy when a run asks for them (run_one(remedy=True))
        "slip_free_takeup_mass_kg": None,
        "slip_free_takeup_kn": None,
        "slip_free_start_time_s": None,
        "brake_force_kn": float(sys.brake_force_n.sum()) / 1e3 if len(sys.brake_force_n)
        else None,
        "rated_power_kw": float(sys.drive_rated_n.sum()) * sys.v_design / 1e3,
        "dt_used_s": sys.dt_s,
        "elements_used": sys.n,
    }
    drv = out.drv
    for i in range(len(sys.drive_share)):
        summary[f"drive{i + 1}_force_max_kn"] = float(drv[i, C.DRV.FMAX]) / 1e3
        summary[f"drive{i + 1}_power_max_kw"] = float(drv[i, C.DRV.PMAX]) / 1e3
        sm = float(drv[i, C.DRV.SLIP_MIN])
        summary[f"drive{i + 1}_slip_margin_min"] = sm if sm < 1e299 else None
        summary[f"drive{i + 1}_slip_s"] = float(drv[i, C.DRV.SLIP_S])
        summary[f"drive{i + 1}_slip_m"] = float(drv[i, C.DRV.SLIP_M])
    w: list[str] = list(sys.warnings)
    if int(r["STATUS"]) == C.DIVERGED:
        return summary, w
    names = [f"drive {i + 1}" for i in range(len(sys.drive_share))]
    if conveyor is not None:
        names = [f"drive {i + 1} ({d.position})" for i, d in enumerate(conveyor.drives)]
    if int(r["STATUS"]) == C.RUNAWAY:
        w.append(runaway_words(sys, float(r["T_END"]), float(r["V_MEAN_END"]), t_stop_cmd))
    for i in range(len(sys.drive_share)):
        slip_s = float(drv[i, C.DRV.SLIP_S])
        if slip_s > 0.0:
            t0 = float(drv[i, C.DRV.SLIP_FIRST])
            t1 = float(drv[i, C.DRV.SLIP_LAST])
            when, fix = slip_words(_run_phase(sys, t0, t_stop_cmd),
                                   _run_phase(sys, t1, t_stop_cmd))
            w.append(f"{names[i]} slipped on its pulley {when}: from t = {t0:.1f} "
                     f"to {t1:.1f} s, {slip_s:.2f} s in all, {drv[i, C.DRV.SLIP_M]:.3g} m of belt "
                     f"slipped (lowest slip margin {drv[i, C.DRV.SLIP_MIN]:.2f}); {fix} would "
                     "avoid it")
    shs = out.shs
    for b in range(len(sys.brake_shaft)):
        k = int(sys.brake_shaft[b])
        if sys.shaft_drive[k] >= 0 or shs[k, 0] <= 0.0:
            continue  # a drive's slip is reported with the drive
        name = conveyor.brakes[b].where if conveyor is not None else f"brake {b + 1}"
        w.append(f"the {name} brake's pulley slipped: the brake held it while the belt slid "
                 f"over it from t = {shs[k, 2]:.1f} to {shs[k, 3]:.1f} s, {shs[k, 0]:.2f} s in "
                 f"all, {shs[k, 1]:.3g} m of belt slipped; more tension on that pulley (take-up "
                 "position or mass) or a smaller brake force would avoid it")
    if r["SLACK_MAX"] > 0.0 or r["SLACK_FIRST"] >= 0.0:
        j = int(r["SLACK_AT"]) if r["SLACK_AT"] >= 0 else jmin
        w.append(
            f"the belt goes slack: its slack spans gather up to {r['SLACK_MAX']:.3g} m of belt near "
            f"{where(sys, j)} at t = {max(r['SLACK_TIME'], r['SLACK_FIRST']):.1f} s, slack "
            f"for {r['SLACK_DUR']:.1f} s in "
            "all (the one-dimensional model does not follow the belt leaving the idlers or "
            "piling up); a heavier take-up, more take-up travel, a longer stop or a brake "
            "nearer the low-tension side would avoid it")
    if conveyor is not None:
        lim = conveyor.sag_limit_pct
        for code, name, limit in ((0, "carry", lim.carry), (1, "return", lim.return_)):
            mask = (sys.strand == code) & idler
            if mask.any():
                smax = float(sag[mask].max())
                if smax > limit and t_low[mask].min() > 0.0:
                    jj = int(np.flatnonzero(mask)[np.argmax(sag[mask])])
                    w.append(f"transient sag on the {name} strand {smax:.2f} % exceeds the "
                             f"limit {limit:g} % (low tension {t_low[jj] / 1e3:.3g} kN near "
                             f"{where(sys, jj)})")
    sf = summary["safety_factor_dyn"]
    if sf is not None and safety_factor_min is not None and sf < safety_factor_min:
        w.append(f"belt safety factor {sf:.2f} during the transient is below "
                 f"{safety_factor_min:g} (peak {t_max_dyn / 1e3:.4g} kN near "
                 f"{where(sys, jmax)})")
    if summary["stop_wave_ratio"] is not None and summary["stop_wave_ratio"] < 5.0:
        w.append(f"stop in {t_stop_ach:.1f} s is faster than 5 wave loop times "
                 f"(5 x {sys.wave_loop_time_s:.1f} s): a high-stress stop")
    if r["ENDSTOP"] > 0:
        w.append(f"take-up carriage reached its end stop at t = {r['ENDSTOP_T']:.1f} s at "
                 f"{r['ENDSTOP_SPEED']:.2f} m/s (travel {sys.takeup_hi_m - sys.takeup_lo_m:.3g} "
                 "m): more take-up travel or a heavier take-up would avoid it")
    ran_away = int(r["STATUS"]) == C.RUNAWAY  # the run ended early: said above
    if t_start_ach is None and not ran_away:
        w.append("the belt never reached 99 % of design speed during the start")
    if r["STOPPED"] < 0.5 and not ran_away:
        w.append(f"the belt did not stop within {sys.stop_max_s:.0f} s of the stop command "
                 f"(mean speed {r['V_MEAN_END']:.2f} m/s at the end)")
    return summary, w


def sys_strand_mask(sys: System, code: int) -> np.ndarray:
    """Elements of a strand (0 carry, 1 return) with idlers."""
    return (sys.strand == code) & (sys.sag_w_n > 0.0)
