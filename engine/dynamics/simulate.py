"""Python wrapper: System -> run -> TransientResult (SPEC sections 4-6).

:func:`simulate` is the one entry point of the transient engine: it gives the
:class:`~beltstudy.engine.dynamics.model.System`'s records fresh state arrays, the belt at
rest, output buffers and scratch (:func:`fresh_run`), runs the whole cycle
(:func:`beltstudy.engine.dynamics.kernel.run_cycle`) and turns the outputs, read by name, into
the SPEC fields (transient summary, per phase, per drive, slack), the key-point time series,
the surface, the envelopes and the warnings.
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass, field
from functools import cached_property
from types import SimpleNamespace

import numpy as np
import pandas as pd

from beltstudy.engine import design
from beltstudy.engine.catalog import resolve_belt
from beltstudy.engine.checks import HOLD_MARGIN
from beltstudy.engine.conveyor import SAG_LIMIT_RTOL
from beltstudy.engine.drives import (
    COUPLING_NEXT,
    RATED_POWER_FACTOR,
    motor_size_kw,
    transient_checks,
)
from beltstudy.engine.dynamics import codes as C
from beltstudy.engine.dynamics import records as R
from beltstudy.engine.dynamics.cache import first_compile
from beltstudy.engine.dynamics.kernel import PAUSED, run_cycle
from beltstudy.engine.dynamics.model import COUPLING_CODES, System, chord_strain
from beltstudy.engine.dynamics.profiles import LINEAR, S_CURVE, start_reference, stop_reference
from beltstudy.engine.loop import DEFAULT_PULLEY_DIAMETER_M, G, _drive_given_kg
from beltstudy.engine.reads import unread_brakes
from beltstudy.engine.statics import up3
from beltstudy.engine.wording import gnum

__all__ = ["TransientResult", "KernelRun", "fresh_run", "fresh_model", "simulate", "decode",
           "span_sag_pct", "not_stopped_words",
           "TIMESERIES_COLUMNS", "SURFACE_COLUMNS", "V_FAIL_FACTOR"]

#: SPEC section 5 key-point columns, in order (extra and per-drive columns follow them).
TIMESERIES_COLUMNS = ("t_s", "v_drive_m_s", "v_tail_m_s", "f_drive_kn", "t_head_in_kn",
                      "t_head_out_kn", "t_tail_kn", "t_takeup_kn", "x_takeup_m", "t_min_kn",
                      "t_max_kn")
SURFACE_COLUMNS = ("t_s", "s_m", "tension_kn", "velocity_m_s")
V_FAIL_FACTOR = C.V_FAIL_FACTOR
#: The time-series columns from the records: (column, field of
#: :data:`~beltstudy.engine.dynamics.records.RECORD`, divisor to the column's unit).
_SERIES = (("t_s", "t", 1.0), ("v_drive_m_s", "v_drive", 1.0), ("v_tail_m_s", "v_tail", 1.0),
           ("f_drive_kn", "f_drive", 1e3), ("t_head_in_kn", "t_head_in", 1e3),
           ("t_head_out_kn", "t_head_out", 1e3), ("t_tail_kn", "t_tail", 1e3),
           ("t_takeup_kn", "t_takeup", 1e3), ("x_takeup_m", "x_tu", 1.0),
           ("t_min_kn", "t_min", 1e3), ("t_max_kn", "t_max", 1e3),
           ("v_mean_m_s", "v_mean", 1.0), ("v_ref_m_s", "v_ref", 1.0),
           ("f_brake_kn", "f_brake", 1e3), ("p_drive_kw", "p_drive", 1e3),
           ("v_abs_max_m_s", "v_abs", 1.0), ("slack_m", "slack_m", 1.0),
           ("f_holdback_kn", "f_holdback", 1e3))
STRAND_NAMES = {0: "carry", 1: "return", 2: "head pulley", 3: "tail pulley",
                4: "take-up pulley"}


@dataclass(eq=False)
class KernelRun:
    """One run of the kernel: the model with fresh state arrays, the belt at rest, the output
    buffers and scratch (:mod:`beltstudy.engine.dynamics.records`); :meth:`call` runs the
    whole cycle and fills them in place."""

    model: R.Model
    state: R.State
    out: R.Out
    work: R.Work
    #: the smallest slip margin of any drive pulley from the start of the run to the stop
    #: command and from the stop command on (None: the run ended before it), set by
    #: :meth:`cycle` (or :meth:`merge_slip` for a run continued from a shared start)
    slip_min_start: float | None = None
    slip_min_stop: float | None = None

    def call(self, t_pause: float = -1.0) -> int:
        """Run the cycle (on from where it paused); ``t_pause`` >= 0 pauses before the first
        step past it (:data:`~beltstudy.engine.dynamics.kernel.PAUSED` returned)."""
        with first_compile(run_cycle):  # one process compiles a cold kernel, others load it
            return int(run_cycle(self.model, self.state, self.out, self.work, float(t_pause)))

    def pause_slip(self) -> tuple:
        """At the stop command (paused there): keep the run's and each drive's smallest slip
        margin so far (the start's) and start them again for the stop's own, and the margin
        of the state at the command (:meth:`slip_margin_now`), where the stop begins."""
        run, drv = self.out.run, self.out.drv
        kept = (float(run["slip_min"][0]), float(run["slip_min_t"][0]),
                drv["slip_min"].copy(), drv["slip_min_t"].copy(), self.slip_margin_now())
        run["slip_min"][0] = 1e300
        drv["slip_min"] = 1e300
        return kept

    def slip_margin_now(self) -> float:
        """The smallest slip margin of the drive pulleys in the present state, ``e^(mu theta)
        T_slack / (T_slack + |F_belt|)`` with the lower tension beside each pulley and the force
        it passes (the capstan law's ratio, 1 at the grip; a sliding pulley 1 at most, 0 with
        its slack side slack), read as the kernel reads it after every step (1e300 without
        drives, or with every pulley sticking slack on both sides)."""
        m, tt = self.model, self.state.tt
        n = tt.shape[0]
        best = 1e300
        for dk, s in enumerate(m.drives.shaft):
            j = int(m.shafts.node[s])
            jm = j - 1 if j > 0 else n - 1
            hi = max(tt[j], tt[jm])
            lo_t = min(tt[j], tt[jm])
            e, ft = m.shafts.cs[s] + 1.0, abs(m.drives.ft[dk])
            if m.shafts.slip[s] != 0.0:
                best = min(best, 0.0 if lo_t <= 0.0 else min(e * lo_t / (lo_t + ft), 1.0))
            elif hi > 0.0:
                lo = max(lo_t, 1.0)
                best = min(best, e * lo / (lo + ft))
        return best

    def merge_slip(self, kept: tuple) -> None:
        """After the stop (:meth:`pause_slip` gave ``kept``): the phases' smallest margins
        (``slip_min_start``, ``slip_min_stop``), and the cycle's back in the records, the
        earlier phase's on a tie, as one uninterrupted run keeps its first (the kernel
        replaces a smallest margin only by a smaller one): bit for bit the same records."""
        run, drv = self.out.run, self.out.drv
        m0, t0, d0, dt0, m_cmd = kept
        m1 = float(run["slip_min"][0])
        self.slip_min_start = m0 if m0 < 1e299 else None
        # the stop begins at the command, from the tensions there: its first step has the
        # drive force already cut (a coast's trip), and the ratio it leaves falls within a
        # step or two, so a minimum over the steps after the command alone depends on the
        # step (slope-5pct's coast on 40 elements: 1.97, 1.76, 1.55 at dt, dt / 2, dt / 4,
        # against 1.435 at the command). The command's state belongs to the start too, so
        # its margin is not below the start's (max: the same reading to the last bit).
        m_stop = min(m1, max(m_cmd, m0))
        self.slip_min_stop = m_stop if m_stop < 1e299 else None
        if m0 <= m1:
            run["slip_min"][0], run["slip_min_t"][0] = m0, t0
        first = d0 <= drv["slip_min"]
        drv["slip_min"] = np.where(first, d0, drv["slip_min"])
        drv["slip_min_t"] = np.where(first, dt0, drv["slip_min_t"])

    def cycle(self, t_stop_cmd: float) -> int:
        """The whole cycle (from rest), paused at the stop command ``t_stop_cmd`` [s] for the
        phases' smallest slip margins; step for step the same run as one call."""
        status = self.call(t_stop_cmd)
        if status != PAUSED:  # ended before the stop command: the start's alone
            m = float(self.out.run["slip_min"][0])
            self.slip_min_start = m if m < 1e299 else None
            return status
        kept = self.pause_slip()
        status = self.call()
        self.merge_slip(kept)
        return status

    @property
    def run(self) -> np.void:
        """The run's scalars (:data:`~beltstudy.engine.dynamics.records.RUN`)."""
        return self.out.run[0]


def fresh_model(model: R.Model, t_end_s: float | None = None) -> R.Model:
    """The model with fresh copies of every array a run changes (marked *state* in
    :mod:`beltstudy.engine.dynamics.records`): the shafts at rest and sticking, the drives'
    per-step laws, the brakes not commanded, the expanded law not yet evaluated. ``t_end_s``
    ends the run at that time [s] instead of after the stop (verification)."""
    sh, dr, br, lin = model.shafts, model.drives, model.brakes, model.lin
    ns, nd = sh.node.shape[0], dr.share.shape[0]

    def z(k=nd):
        return np.zeros(k)

    shafts = sh._replace(vs=z(ns), slip=z(ns), fb=z(ns), fb_out=z(ns))
    drives = dr._replace(lim=dr.lim0.copy(), mode=np.zeros(nd, dtype=np.int64), f0=z(), f1=z(),
                         sat=np.zeros(nd, dtype=np.int64), win_f=z(), lin_p=z(), lin_d=z(),
                         lin_cs=z(),
                         vm=z(), force=z(), ft=z(), f_trip=z(), f_start=z())
    brakes = br._replace(t_cmd=np.full(br.shaft.shape[0], -1.0),
                         released=np.zeros(br.shaft.shape[0], dtype=np.int64))
    flag = np.zeros_like(lin.flag)
    lin = lin._replace(k=np.zeros_like(lin.k), gu=np.zeros_like(lin.gu),
                       guu=np.zeros_like(lin.guu), gx=np.zeros_like(lin.gx),
                       gxx=np.zeros_like(lin.gxx), gux=np.zeros_like(lin.gux),
                       ulo=np.zeros_like(lin.ulo), uhi=np.zeros_like(lin.uhi),
                       tlo=np.zeros_like(lin.tlo), thi=np.zeros_like(lin.thi), flag=flag,
                       flag64=flag.view(np.uint64), idx=np.zeros_like(lin.idx),
                       sg=np.zeros_like(lin.sg), sf=np.zeros_like(lin.sf),
                       so=np.zeros_like(lin.so))
    cycle = model.cycle._replace(t_end=float(t_end_s) if t_end_s else 0.0)
    return model._replace(cycle=cycle, shafts=shafts, drives=drives, brakes=brakes, lin=lin)


def rest_state(sys: System) -> R.State:
    """The belt at rest: no speed, the at-rest tensions (not below zero) and their strain."""
    sp = sys.model.springs
    t0 = np.maximum(sys.tension_rest_n, 0.0)
    s0 = sp.eb * chord_strain(t0, sp.a_ernst, sp.eb, sp.t_floor, sp.k_floor)
    n = sys.n
    return R.State(v=np.zeros(n), te=t0.copy(), ts=s0, td=np.zeros(n), tt=t0.copy())


def _applied(sys: System) -> np.ndarray:
    """Which brakes the run applies: those whose law it reads (engine/reads.py,
    ``unread_brakes``, the one rule: every brake in a brake stop, else those with ``hold``)."""
    brakes = sys.model.brakes
    unread = set(unread_brakes(
        {"brakes": [{"hold": bool(h)} for h in np.asarray(brakes.hold)]},
        {"stop": {"mode": "brake" if sys.model.cycle.stop_mode == C.BRAKE else "coast"}},
        dynamics=True))
    return np.array([i not in unread for i in range(len(brakes.force))], dtype=bool)


def _applied_brake_kn(sys: System) -> float | None:
    """The force of the brakes the run applies together [kN] (:func:`_applied`); None where
    it applies none (a coast stop's brake without ``hold`` read the first merged grid point's
    force: one run of two studies gave 150 kN in one and 80 kN in the other)."""
    on = _applied(sys)
    return float(np.asarray(sys.model.brakes.force)[on].sum()) / 1e3 if on.any() else None


def brake_hold_kn(sys: System, r) -> float:
    """The force the brakes give holding the belt at rest before the start command [kN]: the
    reaction at the held element (the first brake's pulley, :func:`~beltstudy.engine.statics.
    rest_hold_element`) within the set force of the brakes on it; 0 without brakes. The
    kernel holds that element by the rest's constraint, not by a brake's Coulomb law, so its
    brake total read 0 there: a 1.8 km decline's brake held 204.4 kN for the 2 s before the
    start while ``f_brake_kn`` read 0 in the series and the summary. A brake the run never
    applies (without ``hold``, in a coast or controlled stop) holds nothing here either."""
    brakes = sys.model.brakes
    if not len(brakes.force):
        return 0.0
    on = (np.asarray(brakes.node) == int(sys.model.cycle.hold_node)) & _applied(sys)
    if not on.any():
        return 0.0
    return min(abs(float(r["hold_f"])), float(np.sum(np.asarray(brakes.force)[on]))) / 1e3


def output_buffers(sys: System) -> R.Out:
    """The output buffers of a run, sized by the cycle; the run record holds the belt at rest
    (take-up at its rest position, holding force)."""
    m = sys.model
    n = sys.n
    nd = m.drives.share.shape[0]
    ns = m.shafts.node.shape[0]
    # the kernel records at most once a step: a spacing below the step gives one per step
    nrec = int(math.ceil(sys.t_max_s / max(m.cycle.rec_dt, m.cycle.dt))) + 3
    nsurf = int(math.ceil(sys.t_max_s / max(m.cycle.surf_dt, m.cycle.dt))) + 3
    npr = m.probes.probes.shape[0]
    nsf = m.probes.surface.shape[0]
    run = np.zeros(1, dtype=R.RUN)
    run["hold_f"] = sys.hold_force_n
    return R.Out(rec=np.zeros(nrec, dtype=R.RECORD), rec_t=np.zeros((nrec, npr)),
                 rec_v=np.zeros((nrec, npr)), rec_d=np.zeros((nrec, nd), dtype=R.DRIVE_RECORD),
                 surf_t=np.zeros((nsurf, nsf + 1)), surf_v=np.zeros((nsurf, nsf)),
                 t_max=np.zeros(n), t_min=np.zeros(n), t_max_t=np.zeros(n), t_min_t=np.zeros(n),
                 seg_env=np.zeros((C.SEG_MAX, 4, n)), seg_time=np.zeros((C.SEG_MAX, 2)),
                 drv=np.zeros(nd, dtype=R.DRIVE_RESULT),
                 shs=np.zeros(max(ns, 1), dtype=R.SHAFT_SLIP), run=run)


def work_arrays(n: int) -> R.Work:
    """Scratch of the block solve (BLOCK_MAX) and of the passes (n)."""
    bm = C.BLOCK_MAX

    def z():
        return np.zeros(bm)

    return R.Work(dg=z(), lo=z(), up=z(), cl=z(), rw=z(), rhs=z(), crhs=z(), cuc=z(), kd=z(),
                  kc=z(), kr=z(), wd=z(), wl=z(), wu=z(), wc=z(), wr=z(), sol=z(), sol2=z(),
                  ucoef=z(), bA=z(), bB=z(), v_old=z(), rpos=z(), fexp=z(), fz=z(), stuck=z(),
                  bdir=z(), bforce=z(), c_lo=z(), c_hi=z(), fixed=z(), fixv=z(),
                  shk=np.zeros(bm, dtype=np.int64), vsn=z(), Ac=np.zeros((bm, bm)),
                  r0=np.zeros(n), phi=np.zeros(n), lnv=np.zeros(n), lnphi=np.zeros(n),
                  t_max_snap=np.zeros(n), t_min_snap=np.zeros(n), more=np.zeros(n),
                  crossed=z())


def fresh_run(sys: System, t_end_s: float | None = None) -> KernelRun:
    """A run of the System from rest: fresh state arrays, output buffers and scratch.

    ``t_end_s`` ends the run at that time [s] instead of after the stop (verification)."""
    return KernelRun(model=fresh_model(sys.model, t_end_s), state=rest_state(sys),
                     out=output_buffers(sys), work=work_arrays(sys.n))


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
        ``f_brake_kn``, ``p_drive_kw``, ``v_abs_max_m_s``, ``slack_m``, ``f_holdback_kn``
        (the holdback's force, apart from the brakes' ``f_brake_kn``) and per drive
        ``f_drive{i}_kn``, ``v_drive{i}_m_s``, ``f_belt{i}_kn`` (force the pulley passes to
        the belt), ``v_motor{i}_m_s`` (the motor's speed at the rim: behind a fluid coupling its
        own, else the shaft's).
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
        Kernel scalars by name (``RES``), final state arrays and run bookkeeping (with
        ``drive_slip_last_s``, each drive's last slip on its pulley [s], -1 where it did not).
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


def run_kernel(sys: System, t_end_s: float | None = None) -> tuple[KernelRun, float]:
    """Run the kernel from rest; returns the run (holding the outputs) and wall time [s]."""
    kr = fresh_run(sys, t_end_s)
    t0 = time.perf_counter()
    kr.cycle(sys.stop_command_s)
    return kr, time.perf_counter() - t0


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
    kr, wall = run_kernel(sys, t_end_s)
    return decode(sys, kr, wall, steady_summary=steady_summary, conveyor=conveyor,
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
    reference, the rest before it included, or later to when the belt first reached 99 % of
    design speed, ``System.t_start_end_s``), ``running`` (to the stop command), ``stop``."""
    end = sys.model.cycle.t_pre + sys.model.cycle.t_start
    at_speed = getattr(sys, "t_start_end_s", None)  # (a reader's system may not carry it)
    if at_speed is not None:
        end = max(end, min(at_speed, t_stop_cmd))
    if t_s <= end:
        return "start"
    return "running" if t_s <= t_stop_cmd else "stop"


def diverged_words(sys: System, where_code: int, t_s: float, conveyor=None) -> str:
    """The message of a diverged run: what left the finite range (the belt, a pulley shaft, a
    motor behind its coupling), when, with which step, and what avoids it."""
    def drive_name(k: int) -> str:
        pos = f" ({conveyor.drives[k].where})" if conveyor is not None else ""
        return f"drive {k + 1}{pos}"

    fix = "a shorter step (scenario.dt_s: auto, or more elements)"
    if where_code == -1:
        what = "the belt's speed"
    elif where_code >= 0:
        k = int(sys.model.shafts.drive[where_code])
        what = (f"the pulley shaft of {drive_name(k)}" if k >= 0 else
                f"the shaft of the braked pulley at element {int(sys.model.shafts.node[where_code])}")
        fix = ("more inertia on that shaft (inertia_kg_m2, flywheel_kg_m2) or " + fix)
    else:
        what = f"the motor of {drive_name(-2 - where_code)} behind its coupling"
        fix = "more motor inertia (motor_inertia_kg_m2) or " + fix
    return (f"diverged: {what} became non-finite or passed {V_FAIL_FACTOR:g} x the design speed "
            f"at t = {gnum(t_s)} s with dt = {gnum(sys.dt_s, 3)} s; the run was stopped; {fix} may "
            "avoid it")


def runaway_words(sys: System, t_s: float, v_mean: float, t_stop_cmd: float,
                  rested_s: float | None = None) -> str:
    """The warning of a run that ended because the belt ran away (mean speed past
    :data:`~beltstudy.engine.dynamics.codes.RUNAWAY_FACTOR` x design either way at ``t_s``).
    ``rested_s``: when the belt came to rest in its stop, for one that set off again from
    rest (a decline whose brakes without ``hold`` let go once it rested)."""
    phase = _PHASE_WORDS[_run_phase(sys, t_s, t_stop_cmd)]
    more = heavier_takeup(sys)
    if v_mean > 0.0:
        # how much: the loaded decline's pull at speed is -Te (gravity less the running
        # resistance), at rest its net gravity pull (the hold force, negative downhill)
        pull = ""
        if sys.te_n < 0.0:
            pull = (f" (the belt pulls {gnum(-sys.te_n / 1e3)} kN forwards at speed, -Te, and "
                    f"{gnum(max(-sys.hold_force_n, 0.0) / 1e3)} kN at rest, its net gravity "
                    "pull: what the brakes and drives must take at the belt line)")
        # brakes act in a brake stop only (and hold once the belt rests): in a coast or a
        # controlled stop more force on brakes that never act changes nothing (a 3 km decline
        # doubled to 800 kN ran away in its coast at the same t = 110.2 s)
        brake_stop = getattr(getattr(sys.model, "cycle", None), "stop_mode", C.BRAKE) == C.BRAKE
        levers = ("more brake force, brakes that act in this stop (stop.mode: brake, hold)"
                  if brake_stop else "brakes that act in the stop (stop.mode: brake: in this "
                  "stop no brake acts, so more brake force would not)")
        what = ("the belt ran away forwards", "the drives and brakes could not hold it back"
                f"{pull}: {levers}, or, where a drive pulley slipped, {more}")
        hold = getattr(getattr(sys.model, "brakes", None), "hold", None)
        loose = ([f"brakes.{int(b)}" for b in np.flatnonzero(np.asarray(hold) == 0)]
                 if hold is not None else [])
        if rested_s is not None and rested_s >= 0.0:
            # at rest, then off again: the brakes that let go at rest (hold: false), or too
            # little holding force for the net gravity pull
            why = (f"{', '.join(loose)} without hold let go once it rested" if loose else
                   "its brakes could not hold it at rest" if hold is not None and len(hold)
                   else "nothing held it at rest (it has no brakes)")
            need = HOLD_MARGIN * max(-sys.hold_force_n, 0.0)
            what = (f"the belt came to rest at t = {gnum(rested_s)} s and then ran away "
                    "forwards", f"{why}{pull}: brakes that hold once the belt rests "
                    "(brakes[].hold: true)"
                    + (f" of at least {gnum(need / 1e3)} kN in all ({HOLD_MARGIN:g} x the net "
                       "gravity pull; force_kn: auto sizes them so)" if need > 0.0 else ""))
    else:
        pull = ""
        if sys.hold_force_n > 0.0:
            pull = (f" (at rest the belt pulls {gnum(sys.hold_force_n / 1e3)} kN back, its net "
                    "gravity pull: what a holdback or brakes must take at the belt line)")
        what = ("the belt ran back", f"nothing held it against the lift{pull}: a holdback "
                f"(holdback: true), brakes that hold, or, where a drive pulley slipped, {more}")
    return (f"{what[0]} {phase}: its mean speed reached {gnum(abs(v_mean), 3)} m/s "
            f"({C.RUNAWAY_FACTOR:g} x the design speed) at t = {gnum(t_s)} s and the run was "
            f"ended there; {what[1]}")


#: Each coupling code's name in a conveyor file (the inverse of the model's map).
COUPLING_WORDS = {code: word for word, code in COUPLING_CODES.items()}


def start_levers(sys: System) -> list[str]:
    """What makes this conveyor's start gentler, by its drives' control: a longer ramp
    (``start.time_s``) where a vfd drive follows one; for dol drives the coupling, which sets
    how fast their torque comes on (none: a fluid coupling; a constant-fill fluid coupling: a
    fill-controlled one; a fill-controlled one: a longer fill, ``coupling_fill_s``). A dol
    start does not read ``start.time_s``, so it is not offered there."""
    dr = sys.model.drives
    levers: list[str] = []
    if (dr.control == C.VFD).any():
        levers.append("a longer start (start.time_s)")
    fitted = {COUPLING_WORDS[int(c)] for c in dr.coupling[dr.control == C.DOL]}
    levers += [f"{lever} on the dol drives" for coupling, lever in COUPLING_NEXT.items()
               if coupling in fitted]
    return levers


def oversized_motor_words(sys: System, which=None) -> list[str]:
    """Each dol drive whose motor is more than 5 % above the engine's own size for it
    (:func:`~beltstudy.engine.drives.motor_size_kw`, the auto motor's rule:
    :data:`RATED_POWER_FACTOR` x the motor power of its share of the larger of Te and the
    running resistance, through its drive train's efficiency, ``F v / eta`` driving and
    ``|F v| eta`` regenerating, at each load case the engine sizes motors at,
    ``System.motor_cases``; beyond a catalogue size's rounding), in words for a start's slip. A dol start's force is the motor's (its
    curve, or ``STALL`` x its rated force through a fluid coupling), so an oversized motor
    starts harder than it needs. Not a cure by itself: on a 500 m, 40 m-lift incline whose
    450 kW motor (203 kW needed) slipped through its fluid coupling, no take-up up to 4 x
    avoided the slip; at 300, 250 and 203 kW take-ups of 30.4, 24.1 and 19.8 t did (a 250 m,
    14 deg plant incline likewise: none at 1 000 kW, one at the auto size). A run whose own
    belt regenerates is left out: its motor is sized by its other duties. ``which``: the
    drives to judge (all by default)."""
    dr = sys.model.drives
    te, v = float(getattr(sys, "te_n", 0.0) or 0.0), float(getattr(sys, "v_design", 0.0))
    rated = getattr(dr, "rated", None)
    eta = getattr(sys, "drive_efficiency", None)
    # the engine sizes a motor at the full load too (System.motor_cases): an empty run's
    # steady power alone (a 30 m belt's 1.77 kN against 2.04 kN full) undersizes it
    cases = getattr(sys, "motor_cases", None) or ((te, 0.0),)
    said = []
    for k in np.flatnonzero(dr.control == C.DOL) if rated is not None and te > 0.0 else ():
        e_k = 1.0 if eta is None else float(eta[k])
        sizes = [motor_size_kw(float(dr.share[k]), e_k, t, r, v) for t, r in cases]
        i = max(range(len(sizes)), key=lambda c: (sizes[c][0], -c))  # the own case on a tie
        need_kw = sizes[i][0]
        now_kw = float(rated[k]) * v / 1e3
        if now_kw > 1.05 * need_kw and (which is None or int(k) in which):
            said.append(f"drive {k + 1}'s motor (drives.{k}.rated_power_kw, now {now_kw:.0f} kW) "
                        f"is {now_kw / need_kw:.1f} x the {need_kw:.0f} kW the engine would "
                        f"size it at ({RATED_POWER_FACTOR:g} x its share of "
                        f"{_motor_case_words(cases[i], sizes[i][1], i > 0, v, e_k)}), "
                        "and a dol start's force grows with the motor's rating: a motor nearer "
                        "its need starts more gently, and less take-up tension then avoids the "
                        "slip (rerun to check)")
    return said


def _motor_case_words(case: tuple[float, float], why: str, full: bool, v: float,
                      eta: float) -> str:
    """What set the engine's motor size in :func:`oversized_motor_words`: the case (the run's
    steady state, or the full load, ``full``), the force (Te, or the running resistance
    [N], ``why``) and how the efficiency ``eta`` enters (divided driving, multiplied
    regenerating)."""
    te, res = case
    regen = why == "peripheral_force" and te < 0.0
    force = (f"regenerating {gnum(-te / 1e3, 3)} kN" if regen else f"{gnum(te / 1e3, 3)} kN"
             if why == "peripheral_force" else f"running resistance {gnum(res / 1e3, 3)} kN")
    if full:
        what = f"the full load's {force} x {v:g} m/s, the case it sizes motors for"
    elif why == "peripheral_force":
        what = "the steady power"
    else:
        what = f"the steady {force} x {v:g} m/s"
    if regen:
        return (f"{what}, times its drive train's efficiency {eta:g}: the losses come off the "
                "power a regenerating belt gives the motor")
    return f"{what}, through its drive train's efficiency"


def vfd_fields(sys: System) -> str:
    """The fields that make every dol drive a vfd one, in words: ``drives.k.control: vfd``,
    with ``coupling: none`` where the drive has a fluid coupling (a vfd drive takes none, the
    conveyor file refuses one)."""
    drv = sys.model.drives
    return ", ".join(
        f"drives.{k}.control: vfd" + (" with coupling: none"
                                      if int(drv.coupling[k]) != C.COUPLING_NONE else "")
        for k, c in enumerate(drv.control) if c == C.DOL)


def stop_levers(sys: System | None, slip: bool = False) -> list[str]:
    """What makes this run's stop softer, by its stop mode: a longer ``stop.time_s`` for a
    controlled stop; less brake force or a longer brake ramp (``brakes[].ramp_s``) for a
    brake stop; a coast stop has no setting of its own, so the lever is a controlled stop
    (the drives easing the belt down over ``stop.time_s``), which needs vfd drives (a
    scenario asking it of a conveyor with a dol drive is refused,
    :func:`beltstudy.engine.dynamics.model.check_scenario`): with a dol drive the coast is
    lengthened by more inertia on the drive shafts (``drives[].flywheel_kg_m2``), or the
    drives made vfd for a controlled stop (:func:`vfd_fields`). For a pulley that slips in
    the stop (``slip``) more inertia is no lever: the shaft's inertia is what its grip must
    slow (a 400 m, 16 deg incline's head pulley slid 0.05 s in its coast stop, 0.18 s with a
    19 000 kg m2 flywheel and 0.33 s with 38 000). Without ``sys``: the general words."""
    if sys is None:
        return ["a softer stop (stop time, brake force)"]
    mode = sys.model.cycle.stop_mode
    if mode == C.CONTROLLED:
        return ["a longer stop (stop.time_s)"]
    if mode == C.BRAKE:
        # stop.time_s sizes an auto brake only: not offered where every brake's force is
        # written in (``System.auto_brakes`` False; None: not known, offered as for one), nor
        # where the auto brake is set by holding the loaded belt at rest, above what the stop
        # time asks (:func:`_auto_brake_held`: a longer stop.time_s leaves it as it is)
        timed = ("" if getattr(sys, "auto_brakes", None) is False or _brake_held(sys)
                 else ", a longer stop.time_s for an auto brake sized by it")
        slower = ("a force curve that builds more slowly, brakes[].force_curve"
                  if _curve_brakes(sys) else "a longer brake ramp brakes[].ramp_s")
        return [f"a softer brake stop (less brake force{timed}, {slower})"]
    if (sys.model.drives.control == C.DOL).any():
        coast = [] if slip else ["a longer coast (more inertia on the drive shafts, "
                                 "drives[].flywheel_kg_m2)"]
        return coast + [f"vfd drives and a controlled stop ({vfd_fields(sys)}, stop.mode: "
                        "controlled: a dol motor cannot follow a stopping curve)"]
    return ["a controlled stop instead of the coast (stop.mode: controlled, the drives "
            "easing the belt down over stop.time_s)"]


def _or(words: list[str]) -> str:
    """``a``, ``a or b``, ``a, b or c``."""
    return words[0] if len(words) == 1 else ", ".join(words[:-1]) + " or " + words[-1]


def heavier_takeup(sys: System | None, why: str = "") -> str:
    """The take-up lever of a message: ``a heavier take-up`` for a gravity take-up, ``a higher
    take-up pretension (takeup.pretension_kn)`` for a fixed (screw or winch) one, which has no
    counterweight to make heavier; ``why`` is added in the brackets (``more slack-side
    tension``)."""
    tu = getattr(getattr(sys, "model", None), "takeup", None)
    return design.lever_words(tu is None or bool(tu.gravity), why)


def slip_levers(first: str, last: str, sys: System | None = None, unbroken: bool = False
                ) -> list[str]:
    """What would avoid a slip from phase ``first`` to phase ``last``: a heavier take-up
    always, a gentler start when it began in the start (:func:`start_levers` of ``sys``; a
    longer ``start.time_s`` without it), a softer stop when it reached the stop, unless it ran
    on into the stop without a break (``unbroken``) from an earlier phase: then the stop only
    inherited it (a 300 m belt on a 2 kN screw take-up slipped from t = 8.9 s to 92.1 s, the
    stop command at 92.0 s, and was offered a controlled stop for it)."""
    fixes = [heavier_takeup(sys, "more slack-side tension")]
    # slipping without a break through steady running into the stop, or from within running:
    # the running tensions slip it, which no gentler start changes (a carry booster of 90 deg
    # wrap slipped from 6.8 s to 122 s, its steady margin 0.70, and was offered a longer
    # start); the pulley's own grip and its share of the force are the levers
    steady = (first == "running") or (first == "start" and last == "stop" and unbroken)
    if steady:
        shares = getattr(getattr(getattr(sys, "model", None), "drives", None), "share", None)
        fixes.append(GRIP_WORDS + (SHARE_WORDS if shares is not None and len(shares) > 1
                                   else ""))
    elif first == "start":
        fixes += (start_levers(sys) if sys is not None else ["a longer start (start.time_s)"])
    if last == "stop" and not (unbroken and first != "stop"):
        fixes += stop_levers(sys, slip=True)
    return fixes


#: The levers of a drive pulley that slips in steady running, on its own pulley
#: (engine/statics.py's slip warning names the friction and wrap it needs).
GRIP_WORDS = ("more grip on that pulley (a lagged pulley, drives[].friction, or a snub pulley, "
              "drives[].wrap_deg)")
#: ... and, where other drives can take it, less of the force on it.
SHARE_WORDS = " or a smaller share of the drive force on it (drives[].share)"


def slip_words(first: str, last: str, sys: System | None = None, unbroken: bool = False
               ) -> tuple[str, str]:
    """How a slip message names a slip from phase ``first`` to phase ``last`` (``start``,
    ``running``, ``stop``), and what would avoid it (:func:`slip_levers`)."""
    when = _PHASE_WORDS[first] if first == last else \
        f"from {_PHASE_NAMES[first]} into {_PHASE_NAMES[last]}"
    return when, _or(slip_levers(first, last, sys, unbroken))


def _segments(sys: System, out, r: dict):
    """The envelope segments as (t0, t1, t_max, t_max_t, t_min, t_min_t)."""
    nseg = int(r["seg"]) + 1
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


def decode(sys: System, kr: KernelRun, wall_s: float, *, steady_summary=None, conveyor=None,
           safety_factor_min=None) -> TransientResult:
    """Turn kernel outputs into a :class:`TransientResult`."""
    out, st = kr.out, kr.state
    rec = out.rec
    run = kr.run
    r = {name: run[name].item() for name in R.RUN.names}
    nrec = int(r["nrec"])
    nsurf = int(r["nsurf"])
    s_end = sys.s_end_m

    rc = rec[:nrec]
    cols = {name: np.ascontiguousarray(rc[field]) / scale for name, field, scale in _SERIES}
    held_kn = brake_hold_kn(sys, r)
    if held_kn > 0.0:
        before = np.asarray(rc["t"]) < sys.model.cycle.t_pre
        cols["f_brake_kn"] = np.where(before, np.maximum(cols["f_brake_kn"], held_kn),
                                      cols["f_brake_kn"])
    rec_d = out.rec_d[:nrec]
    for i in range(sys.model.drives.share.shape[0]):
        cols[f"f_drive{i + 1}_kn"] = np.ascontiguousarray(rec_d["f"][:, i]) / 1e3
        cols[f"v_drive{i + 1}_m_s"] = np.ascontiguousarray(rec_d["v"][:, i])
        cols[f"f_belt{i + 1}_kn"] = np.ascontiguousarray(rec_d["ft"][:, i]) / 1e3
        cols[f"v_motor{i + 1}_m_s"] = np.ascontiguousarray(rec_d["vm"][:, i])
    probes = sys.model.probes
    trace_data = (cols["t_s"], out.rec_t[:nrec],
                  [f"T@{s_end[j]:.0f}m" for j in probes.probes])
    idx = probes.surface
    surface_data = (out.surf_t[:nsurf, 0], s_end[idx], out.surf_t[:nsurf, 1:], out.surf_v[:nsurf])
    segs = _segments(sys, out, r)
    whole = _extremes(sys, segs)
    summary, warnings = transient_summary(sys, r, out, segs, steady_summary=steady_summary,
                                          slip_phases=(kr.slip_min_start, kr.slip_min_stop),
                                          conveyor=conveyor,
                                          safety_factor_min=safety_factor_min)
    notes = (list(sys.notes) + holdback_notes(sys, summary, steady_summary, conveyor, cols)
             + rollback_notes(sys, conveyor, cols))
    if int(r["status"]) == C.DIVERGED:
        status = "failed"
        message = diverged_words(sys, int(r["div_where"]), float(r["t"]), conveyor)
    elif warnings:
        status = "warning"
        message = "; ".join(warnings)
    else:
        status, message = "ok", ""
    if notes:
        message = "; ".join([m for m in (message, "note: " + "; ".join(notes)) if m])
    raw = dict(r)
    raw.update(t_end=r["t"], v=st.v.copy(), te=st.te.copy(), ts=st.ts.copy(), td=st.td.copy(),
               tension=st.tt.copy(), x_takeup=r["x_tu"], u_takeup=r["u_tu"],
               integrator=r["integ"], drive_force=kr.model.drives.force.copy(),
               shaft_speed=kr.model.shafts.vs.copy(), shaft_slip=kr.model.shafts.slip.copy(),
               drive_slip_last_s=np.array(out.drv["slip_last"], dtype=np.float64),
               drive_slip_first_s=np.array(out.drv["slip_first"], dtype=np.float64),
               wall_s=wall_s, element_steps=float(r["steps"]) * sys.n, segments=segs,
               brake_pulley_slip=_brake_pulley_slips(sys, out))
    return TransientResult(status=status, message=message, warnings=warnings, summary=summary,
                           series=cols, system=sys, raw=raw, trace_data=trace_data,
                           surface_data=surface_data, envelope_data=(s_end, whole))


def _brake_pulley_slips(sys: System, out) -> list[dict]:
    """Each braked pulley without a drive that slid: its brakes (indices in the file's
    ``brakes``), the time it slid [s] and its first and last time [s] (a drive pulley's slip is
    the drive's, ``drive{i}_slip_*``)."""
    brakes = sys.model.brakes
    slid: dict[int, dict] = {}
    if brakes is None:
        return []
    for b in range(brakes.shaft.shape[0]):
        k = int(brakes.shaft[b])
        h = out.shs[k]
        if sys.model.shafts.drive[k] >= 0 or h["slip_s"] <= 0.0:
            continue
        slid.setdefault(k, {"brakes": [], "slip_s": float(h["slip_s"]),
                            "first_s": float(h["first"]), "last_s": float(h["last"])})
        slid[k]["brakes"].append(b)
    return list(slid.values())


def holdback_notes(sys: System, summary: dict, steady_summary: dict | None, conveyor,
                   cols: dict) -> list[str]:
    """The note of a holdback that took more after the stop command than the loaded belt's
    pull at rest (``hold_force_n``, what it holds with the belt still): the belt's stretch
    swinging back onto the held pulley (a 150 m, 15 deg incline: 25.2 kN at the belt line,
    7.94 kNm, 1.49 x its pull of 16.9 kN). Names the peak (read at the records), when, its
    torque on the head pulley, the ratio and CEMA's static rule beside it
    (``holdback_torque_knm``, which credits half the running resistance against the pull,
    :func:`beltstudy.engine.checks.holdback_torque_nm`); [] otherwise. The rest before the
    start is not read: the belt settling onto the holdback from its initial state there
    (2-8 % over the pull on a 4 km overland) is the model's start, not a load the plant
    sees."""
    rule = (steady_summary or {}).get("holdback_torque_knm")
    pull_kn = float(sys.hold_force_n) / 1e3
    if conveyor is None or not summary.get("f_holdback_kn") or "f_holdback_kn" not in cols:
        return []
    t = np.asarray(cols["t_s"], float)
    after = t > sys.stop_command_s
    f = np.asarray(cols["f_holdback_kn"], float)[after]
    if pull_kn <= 0.0 or not f.size or float(f.max()) <= pull_kn * (1.0 + 1e-6):
        return []
    k = int(np.argmax(f))
    f_kn, t_peak = float(f[k]), float(t[after][k])
    heads = [d for d in conveyor.drives if d.position == "head"]
    d_m = float(heads[0].pulley_diameter_m) if heads else DEFAULT_PULLEY_DIAMETER_M
    torque = f_kn * d_m / 2.0
    cema = (f"; CEMA's static rule (holdback_torque_knm) sizes it for {gnum(float(rule), 3)} kNm, "
            "crediting half the running resistance against the pull" if rule else "")
    return [f"the holdback took up to {gnum(f_kn)} kN at the belt line after the stop (t = "
            f"{gnum(t_peak)} s, read at the records; {gnum(torque, 3)} kNm on the {d_m:g} m head "
            f"pulley), {f_kn / pull_kn:.2f} x the loaded belt's pull at rest ({gnum(pull_kn)} kN): "
            f"the belt's stretch swinging back onto it{cema}; a holdback rated for the "
            "larger, with its maker's service factor on top"]


def _brakes_full_at(cols: dict, t0: float) -> tuple[float, float] | None:
    """The first record time at or after ``t0`` [s] at which the brakes' force together was
    within 1 % of its largest from ``t0`` on, and that largest [kN]; None without brake force."""
    if "f_brake_kn" not in cols:
        return None
    t = np.asarray(cols["t_s"], float)
    f = np.asarray(cols["f_brake_kn"], float)
    after = t >= t0 - 1e-9
    if not after.any():
        return None
    t, f = t[after], f[after]
    top = float(np.max(f))
    if not top > 0.0:
        return None
    k = int(np.flatnonzero(f >= 0.99 * top)[0])
    return float(t[k]), top


def rollback_notes(sys: System, conveyor, cols: dict) -> list[str]:
    """The note of a belt that rolled back after its stop until its holding brake held it
    (``brakes[].hold``, set once the belt has stopped, through its delay and ramp), on a
    conveyor without a holdback: its mass-weighted mean speed below ``-REST_FRACTION`` x
    design speed after the stop command, at rest again by the run's end (a belt still running
    back then is :func:`runback_words`'s warning). Names when, how fast, how far (the
    trapezoidal integral of the negative mean speed over the records after the command) and
    the holdback that avoids it. A loaded 2 km, 5 % incline without a holdback, coasting to
    rest on a head brake with hold (0.5 s delay, 1 s ramp), ran back at up to 0.14 m/s for
    about 1.7 s, some 0.2 m of belt and its load, and the run said nothing. On a decline,
    where the loaded belt pulls forwards at rest, the backward speed is the stop's elastic
    rebound, said so, without the holdback."""
    if conveyor is None or conveyor.holdback or not any(
            b.hold for b in getattr(conveyor, "brakes", None) or []):
        return []
    pull_kn = float(sys.hold_force_n) / 1e3  # the loaded belt's pull at rest, back positive
    t = np.asarray(cols["t_s"], float)
    v = np.asarray(cols["v_mean_m_s"], float)
    after = t > sys.stop_command_s + 1e-9
    t, v = t[after], v[after]
    limit = REST_FRACTION * sys.v_design
    back = np.flatnonzero(v < -limit)
    if not back.size or v[-1] < -limit:
        return []
    k = int(np.argmin(v))
    neg = np.minimum(v, 0.0)
    dist = float(-np.sum(0.5 * (neg[1:] + neg[:-1]) * np.diff(t))) if t.size > 1 else 0.0
    held = [b for b in conveyor.brakes if b.hold]
    timing = ", ".join(dict.fromkeys(f"delay_s {b.delay_s:g}, ramp_s {b.ramp_s:g}"
                                     for b in held))
    set_at = _brakes_full_at(cols, t[0] if t.size else math.inf)
    if set_at is not None and set_at[0] <= t[back[0]] + 1e-9:
        # the brakes were at full force before the belt moved back (a brake stop, its brakes
        # set as it slowed): the backward speed is the belt's stretch relaxing and its take-up
        # swinging back about the held pulleys. A 600 m level belt on a 12.7 t take-up, brake
        # at full force 4.8 s before it stopped, swung back 0.95 m and was told a brake that
        # sets sooner would hold it sooner; set sooner (delay 0.1 s, ramp 0.2 s) it swung
        # back 0.99 m
        swing = ("its take-up carriage swinging back with it"
                 if conveyor.takeup.type == "gravity" else "its stretch swinging about them")
        return [f"the belt swung back after it stopped: its mean speed was below "
                f"-{gnum(limit, 3)} m/s from t = {gnum(t[back[0]])} to {gnum(t[back[-1]])} s, "
                f"at most {gnum(-v[k], 3)} m/s backwards (t = {gnum(t[k])} s), about "
                f"{gnum(dist, 3)} m of belt, with its brakes at full force ({gnum(set_at[1])} "
                f"kN together) since t = {gnum(set_at[0])} s: the belt's stretch relaxing about "
                f"the braked pulleys, {swing}, not a run-back the brakes let through, so "
                "neither a holdback nor a brake that sets sooner would avoid it"]
    if sys.hold_force_n <= 0.0:
        # a decline (or level) belt: gravity pulls it forwards at rest, so a backward mean
        # speed is the stop's elastic rebound (the stretch relaxing), which a holdback, taking
        # a backward pull, would not avoid (downhill-regen was offered one for 0.06 m/s)
        return [f"the belt rebounded after it stopped until its holding brake held it: its mean "
                f"speed was below -{gnum(limit, 3)} m/s from t = {gnum(t[back[0]])} to "
                f"{gnum(t[back[-1]])} s, at most {gnum(-v[k], 3)} m/s backwards (t = "
                f"{gnum(t[k])} s), about {gnum(dist, 3)} m of belt while the brake set "
                f"({timing}): the belt's stretch relaxing after the stop, not a run-back (at "
                f"rest the loaded belt pulls {gnum(-pull_kn)} kN forwards, so a holdback would "
                "take nothing); a holding brake that sets sooner (a shorter delay_s or "
                "ramp_s) holds its pulley sooner"]
    return [f"the belt rolled back after it stopped until its holding brake held it: its mean "
            f"speed was below -{gnum(limit, 3)} m/s from t = {gnum(t[back[0]])} to "
            f"{gnum(t[back[-1]])} s, at most {gnum(-v[k], 3)} m/s backwards (t = {gnum(t[k])} s), "
            f"about {gnum(dist, 3)} m of belt and its load run back while the brake set "
            f"({timing}); a holdback on the head pulley (holdback: true), which takes the "
            "pull as the belt stops, would avoid it"]


def _exact_times(ext: dict | None, segs, r: dict) -> dict | None:
    """``ext`` (:func:`_extremes` of ``segs``) with the exact time of the whole cycle's
    largest or lowest tension where that extreme is this part's own (the same value, its
    time inside the part). The envelopes' times are stamped at the first record
    after the envelope grew, so they run late by up to ``record_dt_s``; the whole cycle's
    extremes carry the step's own time. Without this, a phase holding the cycle's peak gave
    the same tension as ``t_max_dyn_kn`` at a time up to ``record_dt_s`` later."""
    if ext is None or not segs:
        return ext
    t0, t1 = segs[0][0], segs[-1][1]
    out = dict(ext)
    for key, name in (("tmax", "t_max"), ("tmin", "t_min")):
        value, t_exact = float(r[key]), float(r[key + "_t"])
        if ext[name] == value and t0 <= t_exact <= t1 and math.isfinite(value):
            out[name + "_t"] = t_exact
    return out


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


def _travel(r: dict, phase: str) -> float:
    """The carriage's travel within a phase (``start``: start to stop command; ``stop``: stop
    command to the end) [m]; 0 when the phase did not run."""
    lo, hi = float(r[f"xlo_{phase}"]), float(r[f"xhi_{phase}"])
    return hi - lo if hi >= lo else 0.0


#: Plant overspeed protection trips at this fraction of design speed (docs/dynamics.md,
#: "Settling and overspeed", gives the source).
OVERSPEED_FRACTION = 1.10
#: The running phase has settled when its mean belt speed over the judged window swings
#: (highest less lowest) by no more than this fraction of design speed: +-1 %, the tracking
#: criterion of docs/dynamics.md (PHYSICS 5.2).
SETTLE_SWING = 0.02
#: A drive's force over the judged window swinging about its mean by more than this fraction of
#: its rated force has not settled either (a limit cycle of torque followers with the mean speed
#: held): the step from a "uniform" driven machine (a uniformly loaded belt conveyor, application
#: factor K_A 1.00) to "light shocks" (K_A 1.25) in the gear rating tables (AGMA 2003, ISO 6336,
#: DIN 3990-41), so a drive that swings more no longer runs the duty its gear was rated for
#: (docs/dynamics.md, "Settling and overspeed").
SETTLE_FORCE = 0.25
#: The judged window: the running phase's last half, and at least its last this many wave loop
#: times (a take-up's swing can be slower than a wave loop); judged when it begins at least
#: one wave loop time after the start's reference reached design speed.
SETTLE_LOOPS = 3.0


def swing_and_period(t: np.ndarray, v: np.ndarray) -> tuple[float, float | None]:
    """Highest less lowest of ``v`` and the period of its swing from the crossings of its mean
    [s] (two crossings a period apart; from two, half a period apart; None with fewer)."""
    if len(v) < 2:
        return 0.0, None
    d = v - float(v.mean())
    cross = np.flatnonzero(np.signbit(d[:-1]) != np.signbit(d[1:]))
    period = (2.0 * float(t[cross[-1]] - t[cross[0]]) / (len(cross) - 1)
              if len(cross) >= 2 else None)
    return float(v.max() - v.min()), period


def _stop_overspeed(sys: System, r: dict, out) -> list[str]:
    """The stop's overspeed, from the records after the stop command (the kernel's
    ``vmean_hi`` ends at it): a regenerating decline whose drives let go before its brakes
    bite runs on under gravity (a 1.5 km, 150 m decline with a 3 s brake delay reached 5.01
    m/s, 125 % of its 4 m/s, and nothing was said). A run that ran away is said as such."""
    if int(r["status"]) == C.RUNAWAY:
        return []
    rec = out.rec[:int(r["nrec"])]
    after = np.flatnonzero(rec["t"] > sys.stop_command_s)
    if not after.size:
        return []
    k = after[int(np.argmax(rec["v_mean"][after]))]
    v_hi, v_d = float(rec["v_mean"][k]), sys.v_design
    if v_hi <= OVERSPEED_FRACTION * v_d:
        return []
    mode = sys.model.cycle.stop_mode
    # a controlled stop needs vfd drives (a scenario asking it of a dol drive is refused,
    # model.check_scenario): with a dol drive the lever is vfd drives and a controlled stop (a
    # 450 m dol decline's brake stop reached 141 % and was told 'a controlled stop
    # (stop.mode: controlled)', which its rerun refused)
    controlled = ("a controlled stop (stop.mode: controlled, the drives holding the belt back "
                  "down its stopping curve)")
    if (sys.model.drives.control == C.DOL).any():
        controlled = (f"vfd drives and a controlled stop ({vfd_fields(sys)}, stop.mode: "
                      "controlled, the drives holding the belt back down its stopping curve: "
                      "a dol motor cannot follow one)")
    if mode == C.BRAKE:
        sooner = ("brakes[].force_curve" if _curve_brakes(sys) else "brakes[].ramp_s")
        fix = (f"brakes that bite sooner (a shorter brakes[].delay_s or {sooner}) or "
               f"{controlled}")
    elif mode == C.CONTROLLED:
        fix = ("more drive force to hold it back (drives[].torque_limit or rated_power_kw) or "
               "brakes")
    else:
        fix = f"{controlled} or a brake stop (stop.mode: brake)"
    return [f"overspeed in the stop: the mean belt speed reached {gnum(v_hi, 3)} m/s, "
            f"{100.0 * v_hi / v_d:.0f} % of design speed, at t = {float(rec['t'][k]):.1f} s, "
            f"{float(rec['t'][k]) - sys.stop_command_s:.1f} s after the stop command (plant "
            f"overspeed switches trip at {100.0 * OVERSPEED_FRACTION:.0f} %; read at the "
            f"records): gravity outpulled what held it back; {fix} would avoid it"]


def judged_from(sys: System, r: dict) -> tuple[float, float | None]:
    """Where the running phase's judged window starts [s] and the time from the rest's end
    the mean belt speed first reached 99 % of design speed (``start_ach``; negative: never;
    None: not recorded). The window is the running phase's last half, at least its last
    :data:`SETTLE_LOOPS` wave loop times, from one wave loop time after the ramp at the
    earliest; and from the time the belt reached design speed, since a belt still climbing to
    it at its drives' force limit is not running yet (a 30 m belt climbing from 1.27 to 2.0
    m/s over the window was told its speed "still swings by 0.724 m/s"). The settling check
    (:func:`running_warnings`) and the stop's flywheel (:func:`_running_low`) read it."""
    cyc, t1, t_loop = sys.model.cycle, sys.stop_command_s, sys.wave_loop_time_s
    t0 = max(t1 - max(SETTLE_LOOPS * t_loop, 0.5 * cyc.t_run), cyc.t_pre + cyc.t_start + t_loop)
    reached = float(r["start_ach"]) if "start_ach" in r else None
    if reached is not None and reached >= 0.0:
        t0 = max(t0, cyc.t_pre + reached)
    return t0, reached


def running_warnings(sys: System, r: dict, out, names=None) -> list[str]:
    """The start's overspeed (the mean belt speed above :data:`OVERSPEED_FRACTION` of design
    speed before the stop command), the stop's (:func:`_stop_overspeed`) and a running phase
    that has not settled (its mean speed swinging by more than :data:`SETTLE_SWING` of design speed over its last
    :data:`SETTLE_LOOPS` wave loop times, or, with the mean speed within that, a drive's force
    swinging about its mean by more than :data:`SETTLE_FORCE` of its rated force), in words.
    ``names``: each drive's name (default ``drive k``)."""
    w: list[str] = []
    v_d = sys.v_design
    cyc = sys.model.cycle
    if float(r["vmean_hi"]) > OVERSPEED_FRACTION * v_d:
        w.append(f"overspeed in the start: the mean belt speed reached {gnum(r['vmean_hi'], 3)} m/s, "
                 f"{100.0 * r['vmean_hi'] / v_d:.0f} % of design speed, at t = "
                 f"{r['vmean_hi_t']:.1f} s (plant overspeed switches trip at "
                 f"{100.0 * OVERSPEED_FRACTION:.0f} %): the belt released the stretch of "
                 "its acceleration; a gentler start stretches it less: "
                 + _or(start_levers(sys)))
    w += _stop_overspeed(sys, r, out)
    t1 = sys.stop_command_s
    t_loop = sys.wave_loop_time_s
    # the judged window; a running phase shorter than SETTLE_LOOPS + 1 wave loop times is
    # judged from one wave loop time after the ramp on (what the stop starts from)
    t0, reached = judged_from(sys, r)
    rec = out.rec[:int(r["nrec"])]
    t_end = float(rec["t"][-1]) if len(rec) else 0.0
    if t1 - t0 < 0.5 * t_loop or (int(r["status"]) != C.OK and t_end < t1):
        # too little of the running phase is past the start to judge, or the run ended
        # (ran away, diverged) before the stop command; one that ended in the stop has its
        # whole running phase to judge
        return w
    short = ""
    if t0 > t1 - SETTLE_LOOPS * t_loop + 1e-9:
        short = (f"; the running phase is short (run_s {gnum(cyc.t_run, 3)} s): a run_s of at least "
                 f"{_up_s((SETTLE_LOOPS + 1.0) * t_loop)} s ({SETTLE_LOOPS + 1.0:g} wave loop "
                 "times) shows whether it settles")
    m = (rec["t"] >= t0) & (rec["t"] <= t1)
    swing, period = swing_and_period(rec["t"][m], rec["v_mean"][m])
    climbing = (reached is not None and reached < 0.0
                and bool(np.all(np.diff(rec["v_mean"][m]) >= 0.0)))
    if swing > SETTLE_SWING * v_d and not climbing:
        per = (f"a period of {gnum(period, 3)} s" if period
               else "a period longer than the window")
        w.append(f"not settled while running: the mean belt speed still swings by {gnum(swing, 3)} "
                 f"m/s ({100.0 * swing / v_d:.1f} % of design speed, {per}) from t = "
                 f"{t0:.0f} s to the stop command at {t1:.0f} s, so the stop starts from a "
                 f"swinging belt; {_settle_levers(sys)} (docs/dynamics.md, Settling and "
                 f"overspeed){short}")
        return w
    rec_d = getattr(out, "rec_d", None)
    swings = [] if rec_d is None else _force_swings(sys, rec, rec_d[:len(rec)], m, names)
    if swings:
        w.append(f"not settled while running: the mean belt speed holds (within {gnum(swing, 3)} m/s) "
                 f"but {'; '.join(swings)}, from t = {t0:.0f} s to the stop command at "
                 f"{t1:.0f} s: more than +-{100.0 * SETTLE_FORCE:.0f} % of the rated force "
                 "takes a drive out of the uniform duty its gear is rated for (application "
                 "factor 1.25 against 1.00); "
                 + ("drives that follow the master's torque from a wave's travel away run in "
                    "such a limit cycle under a fast speed loop, and a slower one "
                    f"({_loop_field(sys)}) settles them"
                    if getattr(sys.model.control, "vfd", True) else _settle_levers(sys))
                 + f" (docs/dynamics.md, Settling and overspeed){short}")
    return w


#: The tracking criterion (docs/dynamics.md, "Tracking"; PHYSICS 5.1): a vfd start keeps the
#: master pulley within this fraction of design speed of its reference from one wave loop time
#: after the start command, and the mean belt speed within it once the reference has moved.
TRACK_FRACTION = 0.02


def _tracks_a_ramp(sys: System) -> bool:
    """Whether the master's speed loop follows a start ramp, so its tracking error is a figure
    (``drive{i}_speed_error_max_pct``): vfd drives, an s-curve or linear start, the relative
    formulation. A torque start's reference is design speed from the start command while its
    force limit ramps (a 1 km belt's read 99.9 %: the start's lag, not the loop's tracking); a
    force start and the support formulation run no loop until the stop (it read 0)."""
    cyc = sys.model.cycle
    return bool(sys.model.control.vfd and cyc.formulation != C.SUPPORT
                and cyc.start_ctrl in (S_CURVE, LINEAR))


def tracking_warnings(sys: System, r: dict, out, names=None) -> list[str]:
    """A speed-controlled start (s-curve or linear, vfd drives, relative formulation) that does
    not follow its reference, in words: (1) the mean belt speed ahead of the reference by more
    than :data:`TRACK_FRACTION` of design speed in the first wave loop time after the hold let
    go (the records): the belt held at rest on a pulley a wave's travel from the master's loop
    runs forward at the hold's release with the part of the holding force the drives on that
    pulley do not take (docs/dynamics.md, "The start from rest"); (2) the master pulley off its
    reference by more than that after one wave loop time (``verr_max``, every step), unless the
    master reached its torque limit (the drive checks name that limit, which explains the lag);
    after a run ahead at the release, the master's lag is its aftermath and is named with it.
    ``names``: each drive's name (default ``drive k``)."""
    model = sys.model
    cyc, ctl, drives = model.cycle, model.control, model.drives
    if (not ctl.vfd or cyc.formulation == C.SUPPORT or cyc.start_ctrl not in (S_CURVE, LINEAR)
            or int(r["status"]) == C.DIVERGED):
        return []
    names = names or [f"drive {i + 1}" for i in range(drives.share.shape[0])]
    v_d = sys.v_design
    t_loop = sys.wave_loop_time_s
    m = int(ctl.master)
    err = float(r["verr_max"])
    t_err = float(r["verr_t"])
    lag = ""
    if err > TRACK_FRACTION * v_d and not float(out.drv[m]["lim_s"]) > 0.0:
        lag = (f"the master pulley ({names[m]}) was {gnum(err, 3)} m/s ({100.0 * err / v_d:.1f} % of "
               f"design speed) off its reference at t = {t_err:.1f} s")
    ahead = _ahead_at_release(sys, r, out, names)
    if ahead:
        return [ahead + (f"; then {lag}" if lag else "")]
    if not lag:
        return []
    in_start = t_err <= cyc.t_pre + cyc.t_start + t_loop
    # the loop's lag falls with the reference's acceleration: measured on a 300 m incline as
    # 1 / T (s-curve) and T^-0.65 (linear); the advice takes T^-0.5, and 10 % more
    t_need = math.ceil(cyc.t_start * (err / (TRACK_FRACTION * v_d)) ** 2 * 1.1)
    if in_start:
        lever = (f"a longer start (start.time_s {t_need:.0f} s or more: the loop's lag falls with "
                 "the reference's acceleration), "
                 + ("an s-curve start (start.control: s-curve: a ramp's corners step the "
                    "acceleration), " if cyc.start_ctrl == LINEAR else "")
                 + f"or a faster speed loop ({_loop_field(sys)})")
        when = "in the " + ("s-curve" if cyc.start_ctrl == S_CURVE else "linear") + " start"
    else:
        lever = f"a faster speed loop ({_loop_field(sys)})"
        when = "while running"
    return [f"the speed loop did not track its reference: {lag}, {when} (criterion: within "
            f"{100.0 * TRACK_FRACTION:.0f} % from one wave loop time, {gnum(t_loop, 3)} s, after the "
            f"start command; docs/dynamics.md, Tracking): {lever}"]


def _ahead_at_release(sys: System, r: dict, out, names) -> str:
    """The mean belt speed ahead of the start's reference by more than
    :data:`TRACK_FRACTION` of design speed from the start command to one wave loop time after
    the hold let go, in words with the hold's share and what hands it over on one shaft; ""
    when it did not run ahead."""
    model = sys.model
    cyc, ctl, drives = model.cycle, model.control, model.drives
    v_d = sys.v_design
    t_loop = sys.wave_loop_time_s
    m = int(ctl.master)
    rec = out.rec[:int(r["nrec"])]
    t_rel = cyc.t_pre + cyc.t_hand
    win = (rec["t"] > cyc.t_pre) & (rec["t"] <= t_rel + t_loop) & (rec["t"] <= sys.stop_command_s)
    if not win.any():
        return ""
    ahead = rec["v_mean"][win] - rec["v_ref"][win]
    k = int(np.argmax(ahead))
    if ahead[k] <= TRACK_FRACTION * v_d:
        return ""
    node = np.asarray(drives.node, dtype=np.int64)
    held = [i for i in range(node.shape[0]) if int(node[i]) == int(cyc.hold_node)]
    cause = ""
    if m not in held:
        loop_m = float(sys.s_end_m[-1])
        gap = abs(float(sys.s_end_m[int(cyc.hold_node)]) - float(sys.s_end_m[int(node[m])]))
        travel = min(gap, loop_m - gap) / loop_m * t_loop
        share = float(sum(float(drives.share[i]) for i in held))
        where = (f"the pulley of {', '.join(names[i] for i in held)}" if held
                 else "a braked pulley without a drive")
        cause = (f"; {where} held the belt at rest ({gnum(abs(float(r['hold_f'])) / 1e3)} kN) and "
                 f"its drives took {100.0 * share:.0f} % of that at the hand-over: the rest "
                 f"must come from the master's loop on {names[m]}, about {travel:.2g} s of wave "
                 "travel away, and the belt runs until it arrives; the belt held at rest on the "
                 f"master's pulley (the first brake on {names[m]}, where its grip holds the belt "
                 "at rest: the run warns when it does not) or the held pulley's drive made the "
                 "master (the largest drives[i].share) hands the hold over on one shaft")
    return (f"the belt ran ahead of the start as its hold let go (t = {t_rel:.1f} s): the mean "
            f"belt speed reached {gnum(rec['v_mean'][win][k], 3)} m/s at t = {rec['t'][win][k]:.1f} s "
            f"against a reference of {rec['v_ref'][win][k]:.2g} m/s, "
            f"{100.0 * ahead[k] / v_d:.1f} % of design speed ahead (criterion: within "
            f"{100.0 * TRACK_FRACTION:.0f} %; docs/dynamics.md, The start from rest){cause}")


#: Drives further apart than this share of the loop are at both ends [-]: a follower's torque
#: reaches the belt a wave's travel from the master's loop.
SPREAD_FRACTION = 0.05


def _loop_field(sys: System) -> str:
    """The one field that sets the speed loop, the master drive's (a follower's is refused at
    the door: :class:`beltstudy.engine.conveyor.Drive`), and the bandwidth the run used, so a
    warning's lever names what to change and from what: ``drives.0.speed_loop_rad_s, now 5
    rad/s``."""
    ctl = sys.model.control
    return f"drives.{int(ctl.master)}.speed_loop_rad_s, now {gnum(float(ctl.bandwidth), 3)} rad/s"


def _settle_levers(sys: System) -> str:
    """What may settle a swinging running phase: with the drives at one end a slower speed
    loop; with drives a wave's travel apart no setting is known to settle every belt (a
    slower loop made a 7 km head-and-tail overland swing more: 0.17 to 0.49 m/s at 1 rad/s,
    and settled a 5 km one), nor does moving the drives to one end (a 2.9 km head-and-tail
    belt swung 83-93 % of design speed and 23 % with its drives at the head, but a 5 km one
    3.5 % and 11.9 %, a 10 km one with a booster 5.5 % and 8.4 %), so the words say that and
    name what shows it: a rerun with another loop speed, a longer running phase (a swing that
    decays)."""
    if not getattr(sys.model.control, "vfd", True):
        # dol drives run no speed loop (drives[].speed_loop_rad_s is refused for them): their
        # motors' curves and couplings set their force, and a coupling still filling at the
        # stop command keeps it changing (a 900 m head-and-tail belt on fill-controlled
        # couplings of 120 s, stopped at 82 s, was told a slower speed loop; with run_s 120 s
        # it settled)
        fill = getattr(sys.model.drives, "fill_s", None)
        filling = float(np.max(fill)) if fill is not None and len(fill) else 0.0
        cyc = sys.model.cycle
        t_cmd = float(cyc.t_start) + float(cyc.t_run)
        late = (f"; the couplings fill over {gnum(filling, 3)} s, past the stop command "
                f"{gnum(t_cmd, 3)} s after the start command, so their force is still changing: a "
                f"run_s of at least {_up_s(filling - float(cyc.t_start) + 4.0 * sys.wave_loop_time_s)} "
                "s lets them fill (rerun to check that it settles)" if filling > t_cmd else "")
        return ("the drives are dol, without a speed loop (their motor curves and couplings "
                "set their force): a longer run_s shows whether the swing decays" + late)
    pos = sys.s_end_m[np.asarray(sys.model.drives.node, dtype=np.int64)]
    loop = float(sys.s_end_m[-1])
    if len(pos) > 1 and float(pos.max() - pos.min()) > SPREAD_FRACTION * loop:
        return ("with drives a wave's travel apart the followers answer the master's loop "
                "late, and no speed loop setting or drive layout is known to settle every such "
                "belt (a slower loop or the drives at one end settle some and swing others "
                f"more: rerun to check {_loop_field(sys)}; a longer run_s shows whether "
                "the swing decays)")
    # drives at one end: a slower loop damps a swing the loop drives, but not a strand's own
    # mode with its node at the drive (a 1.6 km fabric decline swung 26.6 % of design speed
    # at 5 rad/s and 24.4 % at 1 rad/s, a quarter wave of its carry, 4 L / c = 22.4 s); a
    # gentler start excites the belt's modes less (its acceleration has less content at their
    # frequency: the same decline settled from a 300 s start)
    return (f"a slower speed loop ({_loop_field(sys)}) may swing less, and a gentler start "
            f"excites the swing less ({_or(start_levers(sys))}): rerun to check; a longer "
            "run_s shows whether the swing decays")


def _force_swings(sys: System, rec, rec_d, m, names=None) -> list[str]:
    """Each drive whose force over the records ``m`` (``rec``, and ``rec_d`` per drive) swings
    about its mean by more than :data:`SETTLE_FORCE` of its rated force, in words (lowest and
    highest force, rated force, period)."""
    drives = sys.model.drives
    out = []
    t = rec["t"][m]
    for i in range(drives.rated.shape[0]):
        f = rec_d["f"][:, i][m]
        rated = float(drives.rated[i])
        if len(f) < 2 or not rated > 0.0:
            continue
        swing, period = swing_and_period(t, f)
        if 0.5 * swing > SETTLE_FORCE * rated:
            name = names[i] if names else f"drive {i + 1}"
            per = (f"a period of {gnum(period, 3)} s" if period
                   else "a period longer than the window")
            out.append(f"the force of {name} swings between {gnum(f.min() / 1e3, 3)} and "
                       f"{gnum(f.max() / 1e3, 3)} kN (rated {gnum(rated / 1e3, 3)} kN, {per})")
    return out


def _drive_names(sys: System, conveyor=None) -> list[str]:
    """Each drive's name in the warnings: ``drive k (where)`` (``drive k`` without the
    conveyor)."""
    if conveyor is not None:
        return [f"drive {i + 1} ({d.where})" for i, d in enumerate(conveyor.drives)]
    return [f"drive {i + 1}" for i in range(sys.model.drives.share.shape[0])]


def _brake_past_full(sys: System, i: int, t_last: float) -> tuple[str, str] | None:
    """What avoids drive ``i``'s slip in a brake stop (a slip that began in the stop) when brakes act on its shaft and the belt
    still slid after they had all reached full force (``t_last`` past the stop command, their
    delay and their ramp or force curve): then the full force is beyond the pulley's grip and a
    longer ramp only delays the slip (a 3 km decline's 112 kN holding brake on its head drive:
    17.0 s and 25.6 m of slip with a 1 s ramp, 20.1 s and 34.1 m with a 5 s one). The levers
    are the grip (a heavier take-up) and the force on that pulley (part of it on a brake on
    another pulley, or less of it). Less of it is not offered where the pulley's grip in the
    stop (``System.brake_grip``, the undamped bound of the design note) is nothing or below
    the force that holds the loaded belt at rest: a 100 m, 15 m lift belt on a 6 kN fixed
    take-up slid with 20 kN on its head drive and with the 10 kN that holds it too. Returns the
    levers and the reason (after "would avoid it"); None where the rule does not apply."""
    brakes = sys.model.brakes
    if sys.model.cycle.stop_mode != C.BRAKE or brakes is None:
        return None
    on = [b for b in range(brakes.shaft.shape[0])
          if int(sys.model.shafts.drive[int(brakes.shaft[b])]) == i]
    if not on:
        return None
    full = max(float(brakes.delay[b]) + (float(brakes.curve_t[b, int(brakes.curve_n[b]) - 1])
                                         if int(brakes.curve_n[b]) > 0 else float(brakes.ramp[b]))
               for b in on)
    t_full = sys.stop_command_s + full
    if t_last <= t_full:
        return None
    force_kn = float(np.sum(brakes.force[on])) / 1e3
    # the brakes' force holds the loaded belt at rest too: less of it on this pulley only down
    # to the holding size (HOLD_MARGIN x the net gravity pull), none below; an incline's
    # holdback holds it at rest instead (engine/checks.py holding_warning), so there no floor
    pull = float(np.sum(sys.model.nodes.gravity))
    held_back = pull > 0.0 and bool(np.any(sys.model.shafts.hb))
    floor_kn = 0.0 if held_back else HOLD_MARGIN * abs(pull) / 1e3
    others_kn = float(np.sum(brakes.force)) / 1e3 - force_kn
    least_kn = max(floor_kn - others_kn, 0.0)
    if least_kn < 1e-6:  # 1 mN: a pull that cancels round the loop (an empty belt) is rounding
        least_kn = 0.0  # noise ('at least 5.12e-17 kN'), not a force to hold
    # the least force advised is rounded up at three figures: a force at the floor already
    # (a study's design brake, its size rounded up at six) was told 'less brake force (now
    # 56.06 kN; a given force_kn of at least 56.1 kN)'
    grip_kn = (sys.brake_grip(int(brakes.node[on[0]])) / 1e3
               if getattr(sys, "brake_grip", None) is not None else None)
    if grip_kn is not None and grip_kn <= 0.0:
        # the design note's bound: unbraked, the fall of its slack side already slides it
        less = (" (not less force on this one: by the stop's undamped bound its pulley passes "
                "no brake force at all, as the note on the brake grip says)")
    elif grip_kn is not None and grip_kn < least_kn:
        less = (f" (not less force on this one: by the stop's undamped bound its pulley passes "
                f"at most {gnum(grip_kn, 3)} kN, below the {up3(least_kn):g} kN that with the "
                f"others holds the loaded belt at rest, {HOLD_MARGIN:g} x its net gravity pull)")
    elif (up3(least_kn) if least_kn > 0.0 else 0.0) < force_kn * (1.0 - 1e-6):
        less = (f" or less brake force on this one (now {gnum(force_kn)} kN; a given force_kn"
                + (f" of at least {up3(least_kn):g} kN, which with the others holds the loaded "
                   f"belt at rest, {HOLD_MARGIN:g} x its net gravity pull)" if least_kn > 0.0
                   else ")"))
    elif others_kn > 0.0:
        # with the other brakes: their sum is the holding size, not this brake's own force (a
        # 1.8 km decline's head and tail brakes of 122.6 kN each: 'its 122.6 kN is ... 1.2 x
        # its net gravity pull', which was 204.4 kN)
        less = (f" (not less force on this one: its {gnum(force_kn)} kN with the others' "
                f"{gnum(others_kn)} kN is what holds the loaded belt at rest, {HOLD_MARGIN:g} x "
                "its net gravity pull)")
    else:
        less = (f" (not less force on this one: its {gnum(force_kn)} kN is what holds the loaded "
                f"belt at rest, {HOLD_MARGIN:g} x its net gravity pull)")
    return (f"{heavier_takeup(sys, 'more slack-side tension')} or part of the brake force on a "
            f"brake on another pulley (brakes[].position or drive){less}",
            f": the belt still slid after the brakes on this pulley reached full force (t = "
            f"{t_full:.1f} s), so a longer ramp (brakes[].ramp_s) would not")


def _slip_warnings(sys: System, r: dict, out, conveyor=None) -> list[str]:
    """The run's events in words: a runaway, each drive's slip on its pulley (when, how long,
    how much belt, what avoids it), each braked plain pulley's slip."""
    w: list[str] = []
    t_stop_cmd = sys.stop_command_s
    drv = out.drv
    nd = drv.shape[0]
    brakes = sys.model.brakes
    names = _drive_names(sys, conveyor)
    if int(r["status"]) == C.RUNAWAY:
        w.append(runaway_words(sys, float(r["t"]), float(r["v_mean"]), t_stop_cmd,
                               rested_s=float(r["t_stopped"]) if r["stopped"] else None))
    for i in range(nd):
        slip_s = float(drv[i]["slip_s"])
        if slip_s > 0.0:
            t0 = float(drv[i]["slip_first"])
            t1 = float(drv[i]["slip_last"])
            # slipping all along from its first to its last time (within 1 %: the slip
            # time is summed by steps, the two times stamped at records)
            unbroken = slip_s >= 0.99 * (t1 - t0)
            when, fix = slip_words(_run_phase(sys, t0, t_stop_cmd),
                                   _run_phase(sys, t1, t_stop_cmd), sys, unbroken)
            rested = float(r["t_stopped"]) if r["stopped"] else -1.0
            past = (_brake_past_full(sys, i, t1)
                    if _run_phase(sys, t0, t_stop_cmd) == "stop" else None)
            if 0.0 <= rested <= t0:
                # slipping once the belt rested: the pulley holding the stopped belt's net pull
                # slides, which no softer or longer stop changes (a 350 m incline's braked head
                # pulley slid at t = 63.5 s, after its 10 s stop, and was offered a longer stop)
                when = f"at rest (the belt stopped at t = {rested:.1f} s)"
                fix = (f"{heavier_takeup(sys, 'more slack-side tension')} or a brake or "
                       "holdback on another pulley holding the stopped belt (no stop setting "
                       "changes what holds it at rest)")
                past = None
            why = ""
            if past is not None:
                fix, why = past
            sm = float(drv[i]["slip_min"])
            if sm >= 1e299:
                margin = "the belt slack on both sides of the pulley while it slipped"
            elif sm <= 0.0:
                margin = ("its slack side went slack while it slipped: no grip, slip margin 0")
            elif abs(sm - 1.0) <= 1e-9:
                # a sliding pulley's margin is 1 (at its grip), whatever the slide: its time
                # and the belt slipped say how much
                margin = "at its grip while it slid"
            else:
                margin = f"lowest slip margin {sm:.2f}"

            w.append(f"{names[i]} slipped on its pulley {when}: from t = {t0:.1f} "
                     f"to {t1:.1f} s, {slip_s:.2f} s in all, {gnum(drv[i]['slip_m'], 3)} m of belt "
                     f"slipped ({margin}); {fix} would avoid it{why}")
            if _run_phase(sys, t0, t_stop_cmd) == "start":
                w.extend(oversized_motor_words(sys, {i}))
    shs = out.shs
    for b in range(brakes.shaft.shape[0]):
        k = int(brakes.shaft[b])
        if sys.model.shafts.drive[k] >= 0 or shs[k]["slip_s"] <= 0.0:
            continue  # a drive's slip is reported with the drive
        name = conveyor.brakes[b].where if conveyor is not None else f"brake {b + 1}"
        h = shs[k]
        w.append(f"the {name} brake's pulley slipped: the brake held it while the belt slid "
                 f"over it from t = {h['first']:.1f} to {h['last']:.1f} s, {h['slip_s']:.2f} s "
                 f"in all, {gnum(h['slip_m'], 3)} m of belt slipped; more tension on that pulley "
                 "(take-up position or mass) or a smaller brake force would avoid it")
    return w


def _drive_loads(sys: System, out, conveyor=None, steady_summary=None
                 ) -> tuple[dict, list[str]]:
    """Each drive's time above its rated force and RMS force over the cycle, and the
    warnings of an overloaded drive (:func:`beltstudy.engine.drives.transient_checks`)."""
    drives = sys.model.drives
    nd = out.drv.shape[0]
    names = ([f"drive {i + 1} ({d.where})" for i, d in enumerate(conveyor.drives)]
             if conveyor is not None else [f"drive {i + 1}" for i in range(nd)])
    te = steady_summary.get("te_kn") if steady_summary else None
    running = drives.share * float(te) * 1e3 if te is not None else None
    cyc = sys.model.cycle
    controlled = cyc.stop_mode == C.CONTROLLED
    # each drive's share of the rigid-body force at the controlled stop's peak deceleration
    # (the s-curve's, at half the stop time: 2 v / t_stop)
    a_peak = abs(stop_reference(0.5 * cyc.t_stop, cyc.t_stop, cyc.v_d)[1]) if controlled else 0.0
    # and at the start's (the s-curve's 2 v / t_start, the ramp's v / t_start); a torque start
    # has no speed curve
    a_start = (abs(start_reference(cyc.start_ctrl, 0.5 * cyc.t_start, cyc.t_start, cyc.v_d)[1])
               if cyc.start_ctrl in (S_CURVE, LINEAR) else math.nan)
    mass = drives.share * sys.model.control.m_tot
    return transient_checks(names, out.drv, drives.rated, drives.lim0,
                            drives.control == C.VFD, sys.v_design, cyc.t_start,
                            running, [COUPLING_WORDS[int(c)] for c in drives.coupling],
                            stop_s=cyc.t_stop if controlled else None,
                            stop_accel_n=mass * a_peak, start_accel_n=mass * a_start)


def span_sag_pct(sys: System, env_min_n: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Sag at each span's low end [%] (0 off the idlers, at most 100) from a minimum tension
    envelope [N], and that low-end tension [N] (the lower of the span's two springs)."""
    t_low = np.minimum(np.roll(env_min_n, 1), env_min_n)
    sag_w = sys.model.nodes.sag_w
    sag = np.where(sag_w > 0.0, 100.0 * sag_w / np.maximum(t_low, 1.0), 0.0)
    return np.minimum(sag, 100.0), t_low


def transient_summary(sys: System, r: dict, out, segs, *, steady_summary=None, conveyor=None,
                      safety_factor_min=None, slip_phases: tuple = (None, None)):
    """SPEC section 4 and 6.4 transient fields and the warnings; ``slip_phases`` the smallest
    slip margins of the start and the stop (:meth:`KernelRun.cycle`)."""
    s_end = sys.s_end_m
    brakes = sys.model.brakes
    tu = sys.model.takeup
    whole = _extremes(sys, segs)
    t_max_dyn = float(r["tmax"])
    t_min_dyn = float(r["tmin"])
    jmax = whole["j_max"]
    jmin = whole["j_min"]
    steady_tmax = (float(steady_summary["t_max_kn"]) * 1e3
                   if steady_summary and steady_summary.get("t_max_kn")
                   else float(np.max(sys.steady_tension_n)))
    sag, t_low = span_sag_pct(sys, whole["env_min"])
    idler = sys.model.nodes.sag_w > 0.0
    t_stop_cmd = sys.stop_command_s
    t_stop_ach = r["stop_ach"] if r["stop_ach"] >= 0 else None
    t_start_ach = r["start_ach"] if r["start_ach"] >= 0 else None
    if (t_start_ach is not None
            and sys.model.cycle.t_pre + t_start_ach > t_stop_cmd + 0.5 * sys.dt_s):
        # the start phase ends at the stop command (SPEC 6.4): a belt that first reached 99 %
        # of design speed after it (running away in the stop: a 1.47 km route read a start of
        # 38.4 s, 16 s into its coast) made no start
        t_start_ach = None
    # the words' start lasts until the belt is at speed (a 2 km route's slipping drives pulled
    # it up to speed 10 s after its 15 s start reference, and a lift-off at 3.28 of 4 m/s was
    # said to be in steady running, with only the radius to avoid it)
    sys.t_start_end_s = (None if t_start_ach is None
                         else sys.model.cycle.t_pre + t_start_ach)
    # a stop is achieved when the mean speed *falls* below REST_FRACTION of design speed: a
    # belt already below it at the stop command (it never got going, or it runs backwards:
    # an incline running back at -4.4 % of design speed read "stopped in 0.006 s") made no
    # stop, and has no stop time, distance or wave ratio (the kernel, which tests the signed
    # mean speed, marks it achieved at the first step)
    v_cmd = _speed_at(out, r, t_stop_cmd)  # the first record is at t = 0: never None here
    if (t_stop_ach is not None and v_cmd is not None
            and v_cmd < C.REST_FRACTION * sys.v_design):
        t_stop_ach = None
    rating = None
    if conveyor is not None:
        rating = resolve_belt(conveyor.belt).rating_n
    # phases (SPEC 6.4): start = start command to stop command, stop = stop command to the
    # end; the rest before the start command is a segment of its own (the kernel cuts one
    # at the start command), in the whole cycle's figures only
    eps = 1.5 * sys.dt_s
    t_start_cmd = float(sys.model.cycle.t_pre)
    start_segs = [s for s in segs if s[0] >= t_start_cmd and s[1] <= t_stop_cmd + eps]
    stop_segs = [s for s in segs if s[1] > t_stop_cmd + eps]
    first_slack = r["slack_first"]
    pre = [s for s in segs if first_slack < 0 or s[1] <= first_slack + eps]
    post = [s for s in segs if first_slack >= 0 and s[1] > first_slack + eps]
    ext_pre = _extremes(sys, pre)
    ext_post = _exact_times(_extremes(sys, post), post, r)
    summary = {
        "t_max_dyn_kn": t_max_dyn / 1e3,
        "t_max_dyn_at_m": float(s_end[jmax]),
        "t_max_dyn_time_s": float(r["tmax_t"]),
        "t_min_dyn_kn": t_min_dyn / 1e3,
        "t_min_dyn_at_m": float(s_end[jmin]),
        "t_min_dyn_time_s": float(r["tmin_t"]),
        "dyn_factor": t_max_dyn / steady_tmax if steady_tmax > 0 else None,
        "drive_force_max_kn": r["fmax"] / 1e3,
        "drive_power_max_kw": r["pmax"] / 1e3,
        "velocity_max_m_s": r["vmax"],
        "velocity_min_m_s": r["vmin"],
        "takeup_travel_m": r["xmax"] - r["xmin"],
        "takeup_travel_start_m": _travel(r, "start") if tu.gravity else 0.0,
        "takeup_travel_stop_m": _travel(r, "stop") if tu.gravity else 0.0,
        "start_time_s": t_start_ach,
        "stop_time_s": t_stop_ach,
        "stop_distance_m": float(r["stop_dist"]) if t_stop_ach is not None else None,
        "stop_window_s": float(sys.model.cycle.stop_max),
        "f_holdback_kn": (float(r["fhb_max"]) / 1e3 if (sys.model.shafts.hb == 1).any()
                          else None),
        "f_brake_kn": (max(float(r["fbr_max"]) / 1e3, brake_hold_kn(sys, r))
                       if len(brakes.force) else None),
        "wave_loop_time_s": sys.wave_loop_time_s,
        "stop_wave_ratio": (t_stop_ach / sys.wave_loop_time_s
                            if t_stop_ach is not None else None),
        # a slack span's sag has no value (the belt leaves the idlers): none, and the slack
        # warning says it
        "sag_max_dyn_pct": (None if idler.any() and t_low[idler].min() <= 0.0
                            else float(sag.max()) if idler.any() else 0.0),
        "slip_margin_min_dyn": r["slip_min"] if r["slip_min"] < 1e299 else None,
        "slip_margin_min_start_dyn": slip_phases[0],
        "slip_margin_min_stop_dyn": slip_phases[1],
        "safety_factor_dyn": (rating / t_max_dyn if rating and t_max_dyn > 0 else None),
        **_phase_fields(sys, "start", _exact_times(_extremes(sys, start_segs), start_segs, r)),
        **_phase_fields(sys, "stop", _exact_times(_extremes(sys, stop_segs), stop_segs, r)),
        "t_max_pre_slack_kn": ext_pre["t_max"] / 1e3 if ext_pre else None,
        "t_max_post_slack_kn": ext_post["t_max"] / 1e3 if ext_post else None,
        "t_max_post_slack_at_m": float(s_end[ext_post["j_max"]]) if ext_post else None,
        "t_max_post_slack_time_s": ext_post["t_max_t"] if ext_post else None,
        "slack_max_m": r["slack_max"],
        "slack_at_m": float(s_end[int(r["slack_at"])]) if r["slack_at"] >= 0 else None,
        "slack_time_s": r["slack_time"] if r["slack_time"] >= 0 else None,
        "slack_duration_s": r["slack_dur"],
        "takeup_endstop_speed_m_s": r["endstop_speed"],
        "takeup_endstop_gap_m": _endstop_gap(sys, r),
        # filled by beltstudy.engine.remedy when a run asks for them (run_one(remedy=True))
        "slip_free_takeup_mass_kg": None,
        "slip_free_takeup_kn": None,
        "slip_free_start_time_s": None,
        "brake_force_kn": _applied_brake_kn(sys),
        "rated_power_kw": float(sys.model.drives.rated.sum()) * sys.v_design / 1e3,
        "dt_used_s": sys.dt_s,
        "elements_used": sys.n,
    }
    drv = out.drv
    nd = drv.shape[0]
    for i in range(nd):
        summary[f"drive{i + 1}_force_max_kn"] = float(drv[i]["fmax"]) / 1e3
        summary[f"drive{i + 1}_power_max_kw"] = float(drv[i]["pmax"]) / 1e3
        sm = float(drv[i]["slip_min"])
        summary[f"drive{i + 1}_slip_margin_min"] = sm if sm < 1e299 else None
        summary[f"drive{i + 1}_slip_s"] = float(drv[i]["slip_s"])
        summary[f"drive{i + 1}_slip_m"] = float(drv[i]["slip_m"])
        summary[f"drive{i + 1}_speed_error_max_pct"] = (
            100.0 * float(r["verr_max"]) / sys.v_design
            if i == sys.model.control.master and _tracks_a_ramp(sys) else None)
    loads, overloads = _drive_loads(sys, out, conveyor, steady_summary)
    summary.update(loads)
    w: list[str] = list(sys.warnings)
    if int(r["status"]) == C.DIVERGED:
        return summary, w
    w += _slip_warnings(sys, r, out, conveyor)
    w += overloads
    w += running_warnings(sys, r, out, _drive_names(sys, conveyor))
    w += tracking_warnings(sys, r, out, _drive_names(sys, conveyor))
    if r["slack_max"] > 0.0 or r["slack_first"] >= 0.0:
        j = int(r["slack_at"]) if r["slack_at"] >= 0 else jmin
        w.append(_slack_words(sys, r, j))
    if conveyor is not None:
        lim = conveyor.sag_limit_pct
        for code, name, limit in ((0, "carry", lim.carry), (1, "return", lim.return_)):
            mask = (sys.strand == code) & idler
            if mask.any():
                smax = float(sag[mask].max())
                if smax > limit * (1.0 + SAG_LIMIT_RTOL) and t_low[mask].min() > 0.0:
                    jj = int(np.flatnonzero(mask)[np.argmax(sag[mask])])
                    w.append(_sag_words(sys, name, smax, limit, jj, t_low[jj], whole,
                                        (steady_summary or {}).get("takeup_tension_kn")))
    sf = summary["safety_factor_dyn"]
    if sf is not None and safety_factor_min is not None and sf < safety_factor_min:
        w.append(_transient_safety_words(sys, conveyor, sf, safety_factor_min, t_max_dyn,
                                         jmax, float(r["tmax_t"])))
    # the 5-wave-loop rule judges a stop from design speed: a belt that never came near it
    # is told that instead (below), not told that its stop from a crawl was fast; a belt
    # held a few per cent below it by its fluid couplings' running slip stops from its
    # running speed and is judged
    at_speed = t_start_ach is not None or (v_cmd is not None
                                            and v_cmd >= RUNNING_FRACTION * sys.v_design)
    if (summary["stop_wave_ratio"] is not None and summary["stop_wave_ratio"] < 5.0
            and at_speed):
        w.append(_fast_stop_words(sys, t_stop_ach, summary, steady_tmax, conveyor,
                                  _running_low(sys, out, r, v_cmd)))
    w += _cycle_end_words(sys, r, out, t_start_ach, v_cmd, steady_summary=steady_summary,
                          conveyor=conveyor)
    return summary, w


def _cycle_end_words(sys: System, r: dict, out, t_start_ach: float | None, v_cmd: float | None,
                     *, steady_summary: dict | None = None, conveyor=None) -> list[str]:
    """The warnings read from the whole cycle's records: an end stop reached, a start short of
    design speed (``t_start_ach`` None; ``v_cmd`` the mean speed at the stop command), a belt
    not at rest when the stop window ended, or one that runs back after its stop."""
    w = []
    t_stop_cmd = sys.stop_command_s
    if r["endstop"] > 0:
        w.append(endstop_words(sys, r, out))
    ran_away = int(r["status"]) == C.RUNAWAY  # the run ended early: said above
    if t_start_ach is None and not ran_away:
        w.append(_short_of_speed_words(sys, v_cmd or 0.0, t_stop_cmd,
                                       limited=bool((out.drv["lim_s"] > 0.0).any()),
                                       grip=_grip_words(sys, r, out, _drive_names(sys, conveyor)),
                                       rise=_speed_rise(out, r, t_stop_cmd,
                                                        sys.model.cycle.t_run)))
    # a run cut before its stop window ended (``t_end_s``, verification) is not judged on it
    window_end = t_stop_cmd + sys.model.cycle.stop_max
    if not r["stopped"] and not ran_away and float(r["t"]) >= window_end - 0.5 * sys.dt_s:
        braked = {int(k) for k in sys.model.brakes.shaft}
        sliding = any(out.shs[k]["slip_s"] > 0.0 and out.shs[k]["last"] > sys.stop_command_s
                      for k in braked)
        w.append(not_stopped_words(sys, float(r["v_mean"]), sliding,
                                   late=_window_tail(sys, out, r)))
    elif not ran_away:  # a belt that never stopped is told so above, a holdback with it
        w += runback_words(sys, out, r, steady_summary, conveyor)
        w += runon_words(sys, out, r, conveyor)
    return w


def runon_words(sys: System, out, r: dict, conveyor=None) -> list[str]:
    """The warning of a belt that came to rest and then runs on forwards ([] otherwise): its
    mass-weighted mean speed is above ``REST_FRACTION`` x design speed at the run's end,
    after the rest began (``r["t_stopped"]``): a loaded decline's net gravity pull outpulls
    what holds it at rest. A 600 m decline whose 150 kN head brake had ``hold: false`` let
    go once the belt rested, and the belt set off downhill again (0.77 m/s and speeding up
    when the run ended, 'ok'). Says since when, how fast, how far (the trapezoidal integral
    of the mean speed over the records after the rest began) and what holds it: holding
    brakes of at least the pull (a holdback holds a belt running back only)."""
    rec = out.rec[:int(r["nrec"])]
    t_rest = float(r["t_stopped"])
    limit = REST_FRACTION * sys.v_design
    after = rec["t"] > t_rest + 1e-9
    if not r["stopped"] or t_rest < 0.0 or not after.any():
        return []
    t, v = np.asarray(rec["t"][after], float), np.asarray(rec["v_mean"][after], float)
    if v[-1] <= limit:
        return []
    slow = np.flatnonzero(v <= limit)
    k0 = int(slow[-1]) + 1 if slow.size else 0  # the last stretch above the criterion
    pos = np.maximum(v, 0.0)
    dist = float(np.sum(0.5 * (pos[1:] + pos[:-1]) * np.diff(t))) if t.size > 1 else 0.0
    pull = max(-float(sys.hold_force_n), 0.0)
    brakes = list(getattr(conveyor, "brakes", None) or [])
    loose = [f"brakes.{i}" for i, b in enumerate(brakes) if not b.hold]
    held = [b for b in brakes if b.hold and b.force_kn != "auto"]
    why = (f"{', '.join(loose)} without hold let go once it rested" if loose else
           "its holding brakes give less than that" if held else "nothing holds it")
    need = (f" of at least {gnum(HOLD_MARGIN * pull / 1e3)} kN in all ({HOLD_MARGIN:g} x the "
            "pull; force_kn: auto sizes them so)" if pull > 0.0 else "")
    return [f"the belt runs on after its stop: it came to rest at t = {gnum(t_rest)} s, its "
            f"mean speed has been above {gnum(limit, 3)} m/s ({100.0 * REST_FRACTION:g} % of "
            f"design speed) since t = {gnum(t[k0])} s and was {gnum(v[-1], 3)} m/s forwards at the "
            f"run's end (t = {gnum(t[-1])} s), about {gnum(dist, 3)} m of belt run on by then (its "
            f"net gravity pull at rest, {gnum(pull / 1e3)} kN at the belt line, outpulls the "
            f"resistances and {why}); brakes that hold once the belt rests (brakes[].hold: "
            f"true){need} would avoid it"]


def runback_words(sys: System, out, r: dict, steady_summary: dict | None = None,
                  conveyor=None) -> list[str]:
    """The warning of a belt that runs back after its stop ([] otherwise): its mass-weighted
    mean speed (the records' ``v_mean``, the speed the stop's rest criterion reads) is still
    below ``-REST_FRACTION`` x design speed at the run's end, the belt moving backwards as a
    whole over its pulleys because the lift outpulls the resistances at rest and nothing holds
    it. Not a passing dip: after a stop on a holdback the belt's stretch relaxes and its mean
    speed can fall a few per cent below zero for a second or two, then rests (a 2 km 5 %
    incline on its holdback: -0.136 m/s, 3 % of design, and at rest by the run's end). Names
    since when it ran back (the start of the last stretch below the criterion), its fastest
    backward mean speed, how far the belt ran back after the stop command by the run's end
    (the trapezoidal integral of the negative mean speed over the records, an estimate at
    ``record_dt_s``) and the holdback torque statics computes (CEMA's rule,
    ``holdback_torque_knm``) or a holding brake that avoids it.

    A conveyor with a holdback (``holdback: true``) is not told: its head pulley cannot turn
    back, so a backward mean speed there is the belt's stretch relaxing onto the held pulley
    (the take-up carriage returning), not the belt running back over its pulleys; fabric-1km's
    coast stop, its drive pulley held at 0 m/s, still relaxed at -0.12 m/s at the run's end and
    was told 'nothing holds it' and offered the holdback it has. A belt sliding on its held
    pulley is the slip check's to say.

    A brake with ``hold: true`` (set once the belt has stopped, in every stop mode) holds its
    pulley the same way: while the drive pulley's recorded speed is not running back at the
    run's end, the backward mean speed is the belt relaxing onto (or sliding on) the held
    pulley. A 10 km, +60 m overland on three vfd drives with 120 and 60 kN holding brakes at
    head and tail, coasting, its drive pulleys at 0 m/s from about 115 s, relaxed at -0.087
    m/s at the run's end and was told 'nothing holds it' and offered 'brakes[].hold: true',
    which it had. A held pulley that turns back (a brake too weak to hold) is still warned."""
    if conveyor is not None and conveyor.holdback:
        return []
    rec = out.rec[:int(r["nrec"])]
    after = rec["t"] > sys.stop_command_s + 1e-9
    t, v = np.asarray(rec["t"][after], float), np.asarray(rec["v_mean"][after], float)
    limit = REST_FRACTION * sys.v_design
    if not t.size or v[-1] >= -limit:
        return []
    if (conveyor is not None and any(b.hold for b in getattr(conveyor, "brakes", None) or [])
            and "v_drive" in (rec.dtype.names or ())
            and float(rec["v_drive"][after][-1]) >= -limit):
        return []
    fwd = np.flatnonzero(v >= -limit)
    k0 = int(fwd[-1]) + 1 if fwd.size else 0  # the last stretch below the criterion
    k = k0 + int(np.argmin(v[k0:]))
    neg = np.minimum(v, 0.0)
    dist = float(-np.sum(0.5 * (neg[1:] + neg[:-1]) * np.diff(t))) if t.size > 1 else 0.0
    torque = (steady_summary or {}).get("holdback_torque_knm")
    # how much: the net gravity pull a holdback or a holding brake must take at the belt line
    pull = f"{gnum(sys.hold_force_n / 1e3)} kN at the belt line"
    holdback = ("a holdback on the head pulley (holdback: true)"
                + (f" of at least {gnum(torque, 3)} kNm (CEMA's static backstop rule, "
                   "holdback_torque_knm; the stop's roll-back onto it can take more, which "
                   "the rerun with holdback: true names)" if torque else ""))
    return [f"the belt runs back after the stop: its mean speed has been below -{gnum(limit, 3)} "
            f"m/s (-{100.0 * REST_FRACTION:g} % of design speed) since t = {gnum(t[k0])} s, "
            f"{gnum(t[k0] - sys.stop_command_s, 3)} s after the stop command, reached "
            f"{gnum(-v[k], 3)} m/s backwards at t = {gnum(t[k])} s and was still {gnum(-v[-1], 3)} m/s "
            f"backwards at the run's end (t = {gnum(t[-1])} s), about {gnum(dist, 3)} m of belt run "
            f"back by then (the lift's pull at rest, {pull}, outpulls the resistances and "
            "nothing holds it); "
            f"{holdback} or a brake that holds once the belt rests (brakes[].hold: true) "
            "would avoid it"]


#: A belt whose mean speed at the stop command is at least this fraction of design speed ran
#: at its running speed, and its stop is judged by the 5-wave-loop rule although it never
#: reached 99 % of design speed: a constant-fill fluid coupling runs at 1.5-4 % slip at rated
#: torque (docs/dynamics.md, *Drives, dol*; Voith's and Nordell's starting papers), so the
#: pulley of a dol drive behind one turns that much slower than its motor; 5 % holds that
#: with the motor's own slip at an overload.
RUNNING_FRACTION = 0.95


def _speed_at(out, r: dict, t_s: float) -> float | None:
    """The mass-weighted mean belt speed at the last record at or before ``t_s`` [m/s] (None
    when there is none)."""
    rec = out.rec[:int(r["nrec"])]
    before = np.flatnonzero(rec["t"] <= t_s + 1e-9)
    return float(rec["v_mean"][before[-1]]) if before.size else None


def drives_force_limit(dr, master: int) -> float:
    """The most the vfd drives give the belt together [N]: the master's force limit
    (``torque_limit`` x its rated force, ``lim0``) and each drive that follows the master's
    torque at its share of what the master gives at its limit, within its own limit:
    ``sum_k min(share_k lim_m / share_m, lim_k)`` (the kernel's ``_saturate_master`` and
    ``_share_force``). Summing every drive's own limit overstates it wherever a follower's
    limit over its share is the larger: a 5 km overland's 0.4-share booster, limit 133.3 kN,
    gives 0.4 / 0.6 x 166.7 = 111.1 kN beside its 166.7 kN master, 277.8 kN in all, not 300."""
    lim0 = np.asarray(dr.lim0, dtype=float)
    share = np.asarray(dr.share, dtype=float)
    if share[master] <= 0.0:
        return float(np.sum(lim0))
    u = lim0[master] / share[master]
    return float(np.sum(np.minimum(share * u, lim0)))


#: A start short of design speed whose mean speed rose less than this share of a rigid
#: body's acceleration at the drives' force limit over the end of the running phase had
#: stopped gaining: the time a rigid body still needs is then no remedy.
FLAT_RISE = 0.25


def _speed_rise(out, r: dict, t_stop_cmd: float, t_run: float) -> tuple[float, float] | None:
    """The mean belt speed's least-squares slope [m/s2] over the last ``min(run_s, 10 s)``
    (at least 1 s) before the stop command, from the records, and that window [s]; None with
    fewer than 3 records in it. A slope, not two samples: a belt swinging at 92-99 % of
    design speed reads any rise between two of them."""
    window = max(min(t_run, 10.0), 1.0)
    rec = out.rec[:int(r["nrec"])]
    t = rec["t"]
    m = (t >= t_stop_cmd - window - 1e-9) & (t <= t_stop_cmd + 1e-9)
    if int(m.sum()) < 3:
        return None
    tt, vv = t[m], rec["v_mean"][m]
    dt = tt - tt.mean()
    return float((dt * (vv - vv.mean())).sum() / (dt * dt).sum()), window


def _short_of_speed_words(sys: System, v_cmd: float, t_stop_cmd: float,
                          limited: bool = True, grip: str = "",
                          rise: tuple[float, float] | None = None) -> str:
    """The warning of a start that never reached 99 % of design speed: the mean speed the belt
    ran at when the stop was commanded and, for dol drives behind fluid couplings, that their
    running slip holds the pulleys below the motors' speed, and what would meet design speed;
    for vfd drives the force limit against Te (a limit not above Te never gets there; drives
    that never reached it (``limited`` False) leave the belt's own stretch; else the rigid
    body's time still needed at the limit, and the run_s that gives it, unless its mean speed
    had stopped rising: ``rise``, :func:`_speed_rise`). A drive pulley that
    slipped through the start (``grip``, :func:`_grip_words`) is what held the belt back
    instead, whatever the drives' force: a 400 m belt on a 2 kN screw take-up slipped its
    drive pulley from 9.7 s to the stop command and crawled at 3.1e-5 m/s, and was told the
    belt's stretch held it back and a longer run_s would show when it got there (after a
    300 s run it crawled at 3.4e-5 m/s)."""
    v_d = sys.v_design
    if abs(v_cmd) < 1e-9 * v_d:  # round-off about rest: said as 0, not as -8.6e-20, -0.0 %
        v_cmd = 0.0
    words = (f"the belt never reached 99 % of design speed during the start (its mean speed "
             f"was {gnum(v_cmd)} m/s, {100.0 * v_cmd / v_d:.1f} % of design speed, at the stop "
             f"command at t = {t_stop_cmd:.1f} s)")
    dr = sys.model.drives
    fluid = (dr.control == C.DOL) & (dr.coupling != COUPLING_CODES["none"])
    te = float(getattr(sys, "te_n", 0.0) or 0.0)
    lim = drives_force_limit(dr, sys.model.control.master) if hasattr(dr, "lim0") else math.nan
    vfd = bool((dr.control == C.VFD).all()) and te > 0.0 and math.isfinite(lim)
    if vfd and lim <= te:
        # the drives cannot hold design speed at all (the steady check names the torque limit)
        words += (f"; the drives' force limit, {gnum(lim / 1e3)} kN in all (torque_limit x the "
                  "rated force, a drive following the master's torque at its share of the "
                  f"master's limit), is not above the running resistance Te {gnum(te / 1e3)} kN, "
                  "so no start reaches design speed: a higher torque_limit or larger motors "
                  "(drives[].rated_power_kw) would")
    elif grip:
        words += grip
    elif vfd and not limited:
        # the drives had force to spare: the belt's own stretch held its mean speed back (a
        # 1 km belt at 0.05 m/s at 66 % after a 30 s start and 5 s run; a rigid body at the
        # force limit would have been there in a fraction of a millisecond)
        words += ("; the drives never reached their force limit, so the belt's own stretch held "
                  "its mean speed back (a slow or long belt pays its running stretch in through "
                  "the take-up): a longer run_s shows when it gets there")
    elif vfd and v_cmd < v_d and rise is not None and rise[0] < FLAT_RISE * (lim - te) / \
            sys.model.control.m_tot:
        # no longer gaining as a body at the force limit would: the time is not what it lacks
        # (a 200 m incline on a 12 kN screw take-up swung at 92-99 % from 17 s, its tail
        # drive's slack side going slack, and was told a run_s of 35 s, then 49 s, then 68 s)
        a_rb = (lim - te) / sys.model.control.m_tot
        words += (f"; its mean speed had stopped rising: over the last {gnum(rise[1], 3)} s "
                  f"before the stop command it gained {gnum(rise[0], 2)} m/s2 on average, "
                  f"against the {gnum(a_rb, 3)} m/s2 of a rigid body at the drives' force limit "
                  f"({gnum(lim / 1e3)} kN in all against Te {gnum(te / 1e3)} kN), so a longer "
                  "run_s would not let it get there: what holds it back is in the run's other "
                  "warnings (a drive pulley that slips, a belt that goes slack, a speed that "
                  "swings), whose levers would")
    elif vfd and v_cmd < v_d:
        # still accelerating at the stop command: the time it still needed at the drives'
        # force limit, rigid body (the waves add to it)
        more = sys.model.control.m_tot * (v_d - v_cmd) / (lim - te)
        words += (f"; at the drives' force limit ({gnum(lim / 1e3)} kN in all against Te "
                  f"{gnum(te / 1e3)} kN) a rigid body needs about {gnum(more, 3)} s more to reach it: "
                  f"a run_s of at least {_up_s(sys.model.cycle.t_run + more)} s, a longer "
                  "start.time_s that the drives can follow, or more drive force (a higher "
                  "torque_limit or larger motors) would let it get there (rerun to check)")
    if fluid.any() and v_cmd >= RUNNING_FRACTION * v_d:
        words += ("; the dol drives' fluid couplings run at their slip under load (1.5-4 % at "
                  "rated torque), so the pulleys turn that much slower than the motors: a "
                  "motor curve in pulley speeds at the gear ratio that gives design speed with "
                  "the coupling's slip (drives[].motor_curve, its speeds divided by the "
                  f"running ratio {v_cmd / v_d:.3f}) would meet it")
    return words


def _grip_words(sys: System, r: dict, out, names: list[str]) -> str:
    """The words of a start that its drive pulleys' grip held back ("" where none did): a
    drive whose pulley was slipping at the stop command (its last slip not before the step
    before it) and had slipped for at least half the time from its first slip in the start to
    the stop command (what it slipped after the command, at most ``slip_last - t_stop``, is
    taken off its slip time). The force such a pulley passes to the belt is its grip, the
    slack-side tension times ``e^(mu theta) - 1``, whatever the drive's force limit, so more
    slack-side tension (the slip warning's remedy) is the lever; the mean speed's rise at the
    end of the run before the stop command (:func:`_speed_rise`), at which rate a longer run_s
    would reach design speed, says whether time would do it too."""
    t_cmd = sys.stop_command_s
    held = []
    for i, d in enumerate(out.drv):
        t0, t1, slip_s = float(d["slip_first"]), float(d["slip_last"]), float(d["slip_s"])
        if slip_s <= 0.0 or t0 > t_cmd or t1 < t_cmd - 1.5 * sys.dt_s:
            continue
        before = slip_s - max(t1 - t_cmd, 0.0)
        if before >= 0.5 * (t_cmd - t0):
            held.append(f"{names[i]} slipped on its pulley from t = {t0:.1f} s to the stop "
                        f"command ({gnum(min(before, t_cmd - t0), 3)} s of those {gnum(t_cmd - t0, 3)} s)")
    if not held:
        return ""
    words = (f"; {' and '.join(held)}, so the pulley's grip (its slack-side tension times "
             "e^(mu theta) - 1), not the drives' force limit nor the belt's stretch, held the "
             f"belt back: {heavier_takeup(sys, 'more slack-side tension')}, the slip warning's "
             "remedy, would let it grip and reach design speed")
    t_run = float(sys.model.cycle.t_run)
    v_cmd, slope = _speed_at(out, r, t_cmd), _speed_rise(out, r, t_cmd, t_run)
    if t_run <= 0.0 or v_cmd is None or slope is None:
        return words
    # the pace at the end of the run, a least-squares slope (the rise over the whole run read
    # a 200 m incline, flat at 92-99 % from 17 s, as reaching design speed in 4 s more: told
    # a run_s of 35 s, then 49 s, then 68 s, it never got there)
    rate, window = slope
    v_d = sys.v_design
    more = (v_d - v_cmd) / rate if rate > 0.0 else math.inf
    pace = (f"its mean speed rose {gnum(rate, 2)} m/s2 on average over the last "
            f"{gnum(window, 3)} s before the stop command, a pace that reaches design speed "
            f"in about {gnum(more, 3)} s more" if rate > 0.0 else
            f"its mean speed did not rise over the last {gnum(window, 3)} s before the stop "
            f"command ({gnum(rate, 2)} m/s2 on average)")
    if more <= 10.0 * (t_run + float(sys.model.cycle.t_start)):
        return words + f"; {pace}: a run_s of at least {_up_s(t_run + more)} s would too"
    return words + f"; {pace}, so a longer run_s would not"


def _endstop_gap(sys: System, r: dict) -> float | None:
    """The least clearance [m] between the carriage's travel in the run (``xmin`` to ``xmax``)
    and its end stops (``lo``, ``hi``, :func:`~beltstudy.engine.dynamics.model._takeup`): 0
    when it reached one (the stop holds it there), None without a gravity take-up; an end the
    carriage starts at (x = 0, the rest position) counts only when the run hit it. The
    figure the end-stop verdict is judged on with its error bar when the carriage reached no
    stop (:func:`beltstudy.engine.accuracy.marginal_verdicts`)."""
    tu = sys.model.takeup
    if not tu.gravity:
        return None
    if r["endstop"] > 0:
        return 0.0
    # the carriage starts at rest at x = 0, which is an end of the travel where the running
    # stretch needs all of it (or more): resting there is no reach (a 300 kg take-up on a
    # loaded decline moved 0.0094 m of its 0.5 m from the rest end, hit nothing, and read
    # gap 0 and 'reached a take-up end stop' in the report)
    tol = 1e-6 * max(tu.hi - tu.lo, 1e-3)
    low = float(r["xmin"]) - tu.lo if tu.lo < -tol else math.inf
    high = tu.hi - float(r["xmax"]) if tu.hi > tol else math.inf
    return max(min(low, high), 0.0)


def _first_at_end(t: np.ndarray, x: np.ndarray, x_end: float, tol: float,
                  t_kernel: float) -> float | None:
    """The first time [s] the records hold the carriage at its end stop ``x_end`` (within
    ``tol``), after it first left it when it starts there (the rest position on that stop);
    the kernel's first hit ``t_kernel`` where it falls within the record spacing before it
    (the records stamp it up to a spacing late). None when no record holds it there."""
    at = np.abs(x - x_end) <= tol
    if at.size and at[0]:
        away = np.flatnonzero(~at)
        if not away.size:
            return None
        at[:int(away[0])] = False
    k = np.flatnonzero(at)
    if not k.size:
        return None
    k0 = int(k[0])
    if k0 > 0 and float(t[k0 - 1]) < t_kernel <= float(t[k0]) + 1e-9:
        return t_kernel
    return float(t[k0])


def _endstop_reach(sys: System, r: dict, out=None) -> dict:
    """The end stops the carriage reached, ``lo`` and ``hi`` (:func:`endstop_words`), each
    with the time it first reached it [s], in the order of those times. The run's extremes
    (``xmin``, ``xmax``, every step's) say which ends it reached; the records (``out``) say
    when. The kernel's own first-hit time (``endstop_t``) is its first touch of any stop,
    t = 0 for a carriage whose rest position is an end (the running stretch needs all the
    travel or more) pressing on that stop from rest: a tail-drive belt whose carriage ran to
    its running end at 12.5 s and a head-drive one whose carriage reached it at 13.3 s were
    both told t = 0.0 s. An end at the rest position is a hit only where nothing else explains
    the kernel's (the other end not reached), at the time the records show the carriage back
    on it after it left, else the kernel's. Without records every end has the kernel's time."""
    tu = sys.model.takeup
    tol = 1e-6 * max(tu.hi - tu.lo, 1e-3)
    t_hit = float(r["endstop_t"])
    reached = {"hi": float(r["xmax"]) >= tu.hi - tol, "lo": float(r["xmin"]) <= tu.lo + tol}
    rec = out.rec[:int(r["nrec"])] if out is not None else None
    times = {}
    for end, x_end in (("hi", tu.hi), ("lo", tu.lo)):
        other = reached["lo" if end == "hi" else "hi"]
        if not reached[end] or (abs(x_end) <= tol and other):
            continue
        t = _first_at_end(rec["t"], rec["x_tu"], x_end, tol, t_hit) if rec is not None else None
        if t is None and rec is not None and abs(x_end) > tol and other:
            # touched between two records, with the kernel's time the other end's: the record
            # nearest the end
            t = float(rec["t"][int(np.argmax(rec["x_tu"]) if end == "hi"
                                   else np.argmin(rec["x_tu"]))])
        times[end] = t_hit if t is None else t
    return dict(sorted(times.items(), key=lambda e: e[1]))


#: How the end-stop warning names an end: ``x`` grows with the belt's stretch
#: (:func:`~beltstudy.engine.dynamics.model._takeup`), so the high end is where the
#: counterweight is lowest, the low end where the carriage is drawn in.
_END_WORDS = {"hi": "counterweight at its lowest: the belt stretched more than the travel "
                    "allows",
              "lo": "carriage drawn in: the belt shortened more than the travel allows"}


def _endstop_levers(sys: System, reach: dict, run_end: str, short: bool) -> str:
    """What besides a longer travel avoids the end stops ``reach`` (:func:`_endstop_reach`),
    in words ("" when nothing else does): where the running position is beyond the travel
    (``short``) nothing; else per end a heavier take-up at the rest end on the low side (its
    weight resists the pull that draws the carriage in; at the high end its weight is what
    drops it), and a gentler start (stop) where the end was first reached in the start (stop),
    whose fronts swing the carriage past its running position. Two ends reached need both
    ends' levers together."""
    if short:
        return ""
    per_end = []
    for end, t_end in reach.items():
        levers = []
        if end == "lo" and run_end == "hi":
            levers.append("a heavier take-up, which resists the pull drawing it in")
        phase = _run_phase(sys, t_end, sys.stop_command_s)
        if phase in ("start", "stop"):
            ways = start_levers(sys) if phase == "start" else stop_levers(sys)
            levers.append(f"a gentler {phase}, which swings the carriage less past its "
                          f"running position ({_or(ways)})")
        per_end.append((end, levers))
    if not all(levers for _, levers in per_end):
        return ""
    if len(per_end) == 1 or per_end[0][1] == per_end[1][1]:
        return "".join(f", or {lever}" for lever in per_end[0][1])
    both = [f"{_or(levers)} for the {'running' if end == run_end else 'rest'} end"
            for end, levers in per_end]
    return f", or {both[0]} together with {both[1]}"


def endstop_words(sys: System, r: dict, out=None) -> str:
    """The warning of a gravity take-up carriage that reached an end stop: which ends and when
    it first reached each (:func:`_endstop_reach`, from the records ``out``), its fastest impact
    [m/s], where the carriage ran against its travel, and what avoids it. The running end is
    the one on the side of the running position ``x_run``: the high end (counterweight at its
    lowest) where the belt stretches as it runs, the low end (carriage drawn in) where it runs
    shorter than at rest (a tail drive with the take-up at the head: its carriage, running at
    -0.102 m against 0.1 m of travel, was told it reached the running end 'stretched' and
    offered a heavier take-up, with which it still hit). How far it would have run without the
    stop the run cannot tell: the cure is a longer ``takeup.travel_m`` (rerun until no end stop
    is reached); where the running position lies beyond the travel that alone (the running
    stretch's need named); else :func:`_endstop_levers`. At the running end a heavier take-up is
    not offered: the stretch between rest and running comes from the drive force (``x_run``);
    the counterweight adds to rest and running tension alike and changes it only by the sag
    law's part (a stiffer chord at higher tension), little against the elastic part."""
    tu = sys.model.takeup
    tol = 1e-6 * max(tu.hi - tu.lo, 1e-3)
    run_end = "hi" if tu.x_run >= 0.0 else "lo"
    reach = _endstop_reach(sys, r, out)
    if not reach:  # the kernel's hit with no end in the extremes (round-off): its own time
        reach = {run_end: float(r["endstop_t"])}
    named = [f"the {'running' if end == run_end else 'rest'} end ({_END_WORDS[end]})"
             for end in reach]
    if out is None:  # the kernel's one time: the first hit of any stop
        which = " and ".join(named) + f" at t = {float(r['endstop_t']):.1f} s"
    else:
        which = " and ".join(f"{name} at t = {t_end:.1f} s"
                             for name, t_end in zip(named, reach.values(), strict=True))
    short = tu.x_run > tu.hi - tol if run_end == "hi" else tu.x_run < tu.lo + tol
    need = ""
    if short:
        need = (f", the running stretch alone needs {gnum(abs(tu.x_run), 3)} m" +
                (" (the belt runs shorter than at rest)" if run_end == "lo" else ""))
    return (f"take-up carriage reached {which} at up to {r['endstop_speed']:.2f} m/s: its "
            f"travel is {gnum(tu.hi - tu.lo, 3)} m (takeup.travel_m; from {gnum(tu.lo, 3)} to "
            f"{gnum(tu.hi, 3)} m about the rest position, running position {gnum(tu.x_run, 3)} m{need}): "
            "a longer takeup.travel_m (rerun until no end stop is reached: how far the carriage "
            "would have run is not known from this run)"
            + _endstop_levers(sys, reach, run_end, short) + " would avoid it")


def past_limit(value: float, limit: float, digits: int = 2) -> str:
    """``value`` with ``digits`` decimals, more where that would print it as the ``limit`` it
    passed (a sag of 1.5003 % against 1.5 % is '1.5003', not '1.50')."""
    for d in range(digits, 8):
        text = f"{value:.{d}f}"
        if float(text) != limit:
            return text
    return f"{value:.12g}"  # past by less than 1e-7: the figures that show it


def _sag_at_rest_too(sys: System, j: int, limit_pct: float) -> str:
    """Words for a strand whose worst sag is in a phase but that sags past ``limit_pct`` at
    rest too (its spans at the at-rest tensions, ``tension_rest_n``): a phase's lever (a
    gentler start, a softer stop) leaves that part, which only the take-up changes; "" when
    the belt at rest is within the limit. A 110 m fixed take-up conveyor sagged 2.13 % in its
    coast stop and 1.90 % at rest; told 'a higher pretension or a controlled stop', the
    controlled stop still sagged 1.90 %."""
    rest = getattr(sys, "tension_rest_n", None)
    nodes = getattr(getattr(sys, "model", None), "nodes", None)
    if rest is None or nodes is None or getattr(sys, "strand", None) is None:
        return ""
    sag, _ = span_sag_pct(sys, np.asarray(rest, float))
    on = (np.asarray(sys.strand) == sys.strand[j]) & (nodes.sag_w > 0.0)
    worst = float(np.max(sag[on])) if on.any() else 0.0
    if worst <= limit_pct * (1.0 + SAG_LIMIT_RTOL):
        return ""
    # three figures, more where they would read as the limit it passed (1.5005 % read '1.5 %'
    # against 1.5 %)
    shown = f"{gnum(worst, 3)}"
    if float(shown) <= limit_pct:
        shown = past_limit(worst, limit_pct)
    return (f"; the strand sags {shown} % at rest too (before the start), which only the "
            "take-up changes")


def _sag_words(sys: System, strand: str, sag_pct: float, limit_pct: float, j: int,
               t_low_n: float, whole: dict, pretension_kn: float | None = None) -> str:
    """The warning of a transient sag past its limit at the span ending at node ``j``: how
    much, where, when and in which phase (the time its lower spring reached its lowest
    tension), the tension that keeps the span within the limit (the sag ratio goes as 1 / T,
    DIN 22101) and what raises the tension there in that phase: for a gravity take-up the
    counterweight, for a fixed one the pretension (``pretension_kn``, the run's, per strand
    as ``takeup.pretension_kn`` is) that adds it."""
    env, env_t = whole["env_min"], whole["env_min_t"]
    k = j if env[j] <= env[j - 1] else j - 1
    t_at = float(env_t[k])
    phase = _run_phase(sys, t_at, sys.stop_command_s)
    # lowest before the start command: the belt at rest, which no start or stop setting
    # changes (a 110 m fixed take-up conveyor sagged 1.90 % at t = 0.0 s and was told 'a
    # longer start (start.time_s)': with a 60 s start in place of 53 s it sagged 1.90 % still)
    at_rest = t_at <= float(sys.model.cycle.t_pre)
    need_kn = t_low_n * sag_pct / limit_pct / 1e3
    add_kn = up3(need_kn - t_low_n / 1e3)
    tu = getattr(sys.model, "takeup", None)
    # a gravity take-up holds m g / 2 on each of its two strands: the tension a span gains
    # from it is half its weight's gain
    mass = (f" on each of its two strands (a counterweight of at least "
            f"{math.ceil((tu.weight + 2e3 * add_kn) / G)} kg, takeup.mass_kg, now "
            f"{tu.weight / G:.0f} kg)" if tu is not None and tu.gravity else "")
    if tu is not None and not tu.gravity and pretension_kn is not None:
        # rounded up to 10 N: the least pretension that adds add_kn
        least = math.ceil((pretension_kn + add_kn) * 100.0 - 1e-9) / 100.0
        mass = (f" (a pretension of at least {least:g} kN, "
                f"takeup.pretension_kn, now {gnum(pretension_kn)} kN)")
    more = heavier_takeup(sys)
    fixes = {"start": _or([more] + start_levers(sys)),
             "running": f"{heavier_takeup(sys, 'more tension at the take-up')} or closer idlers",
             "stop": _or([more, *stop_levers(sys)]
                         + (["a brake nearer the low-tension side"]
                            if sys.model.cycle.stop_mode == C.BRAKE else []))}[phase]
    when = _PHASE_WORDS[phase]
    if at_rest:
        when = "at rest before the start"
        fixes = f"{more} (no start or stop setting changes the tension at rest)"
    rest_too = "" if at_rest else _sag_at_rest_too(sys, j, limit_pct)
    shown = past_limit(sag_pct, limit_pct)
    return (f"transient sag on the {strand} strand {shown} % exceeds the limit "
            f"{limit_pct:g} % (low tension {gnum(t_low_n / 1e3, 3)} kN near {where(sys, j)} at t = "
            f"{t_at:.1f} s, {when}); {up3(need_kn):g} kN there keeps it within "
            f"(the sag goes as 1 / T), so the take-up must add at least "
            f"{add_kn:g} kN{mass}, more where the transient passes only part of "
            f"a take-up change to that span (rerun to confirm){rest_too}: {fixes} would "
            "avoid it")


def _slack_words(sys: System, r: dict, j: int) -> str:
    """The warning of a belt that went slack: the largest length stored, near node ``j``, when
    and for how long, and what would avoid it in the phases it was slack in (its first slack
    span's and its largest's, :func:`_run_phase`): more take-up tension always; more carriage
    travel for a gravity take-up only (a fixed, screw or winch, take-up has none) whose
    carriage reached an end stop in the run; a gentler
    start (:func:`start_levers`) for a slack start; a softer stop (:func:`stop_levers`), and in
    a brake stop a brake nearer the low-tension side, for a slack stop. A 250 m, 14 deg dol
    incline on a screw take-up that went slack in its start was told 'more take-up travel, a
    longer stop or a brake nearer the low-tension side', none of which it has or which acts
    in a start."""
    t_max = max(float(r["slack_time"]), float(r["slack_first"]))
    t_first = float(r["slack_first"]) if r["slack_first"] >= 0.0 else t_max
    phases = {_run_phase(sys, t, sys.stop_command_s) for t in (t_first, t_max)}
    tu = getattr(sys.model, "takeup", None)
    fixes = [heavier_takeup(sys)]
    # travel only where the carriage reached an end stop: one that stayed short of its stops
    # took up all it could (a valley's coast went slack by 2.14 m with the carriage 17.4 m
    # short of its end stop, and by 2.14 m again with 80 m of travel)
    if tu is None or (tu.gravity and r["endstop"] > 0):
        fixes.append("more take-up travel (takeup.travel_m)")
    if "start" in phases:
        fixes += start_levers(sys)
    if "stop" in phases:
        fixes += stop_levers(sys)
        if sys.model.cycle.stop_mode == C.BRAKE:
            fixes.append("a brake nearer the low-tension side")
    dur = float(r["slack_dur"])
    # tenths of a second, or two significant figures below 0.05 s, which tenths read as 0.0
    # (an 18 deg incline's coast held by its holdback was slack for 0.041 s: "0.0 s in all")
    dur_words = f"{dur:.1f}" if dur >= 0.05 else f"{dur:.2g}"
    return (f"the belt goes slack: its slack spans gather up to {gnum(r['slack_max'], 3)} m of belt "
            f"near {where(sys, j)} at t = {t_max:.1f} s, slack for {dur_words} s in "
            "all (the one-dimensional model does not follow the belt leaving the idlers or "
            "piling up; a slack span's sag is past every sag limit and has no value, so "
            f"sag_max_dyn_pct is empty); {_or(fixes)} would avoid it")


def _transient_safety_words(sys: System, conveyor, sf: float, sf_min: float, t_max_n: float,
                            j: int, t_at: float) -> str:
    """The transient safety factor warning: how much, where and when the peak was (its phase),
    the belt rating per metre of width that meets the minimum (``S_min T_max / B``) and what
    lowers the peak in that phase."""
    phase = _run_phase(sys, t_at, sys.stop_command_s)
    belt = resolve_belt(conveyor.belt) if conveyor is not None else None
    fixes = []
    if belt is not None:
        need_kn_m = math.ceil(sf_min * t_max_n / belt.width_m / 1e3)
        fixes.append(f"a belt rated at least {need_kn_m} kN/m at this width (now "
                     f"{belt.rating_kn_m:.0f} kN/m)")
    # a start or stop setting lowers the transient's peak, never the running tension: where
    # running alone is below the minimum (a tail-driven incline's 390 kN running peak gave
    # 4.10 against 4.47), those levers cannot meet it
    run_kn = float(np.max(sys.steady_tension_n)) / 1e3
    running_short = (belt is not None and run_kn > 0.0
                     and belt.rating_n / 1e3 / run_kn < sf_min * (1.0 - 1e-9))
    if not running_short:
        fixes += {"start": start_levers(sys), "running": [],
                  "stop": stop_levers(sys)}[phase]
    fix = f": {_or(fixes)} would avoid it" if fixes else ""
    if running_short:
        fix += (f" (the running tension alone, {gnum(run_kn)} kN, gives "
                f"{belt.rating_n / 1e3 / run_kn:.2f}, below {gnum(sf_min, 3)}: no start or stop "
                "setting meets it)")
    # below 1 the peak is past the belt's breaking strength: said as what it is, not only as
    # a factor below the minimum
    broken = (f"; below 1, the peak is above the belt's breaking strength "
              f"({gnum(belt.rating_n / 1e3)} kN): the belt would break"
              if belt is not None and sf < 1.0 else "")
    return (f"belt safety factor {sf:.2f} during the transient is below {gnum(sf_min, 3)} (peak "
            f"{gnum(t_max_n / 1e3)} kN near {where(sys, j)} at t = {t_at:.1f} s, "
            f"{_PHASE_WORDS[phase]}){broken}{fix}")


def _up_s(t_s: float) -> str:
    """A time that must be reached [s], rounded up where it is shown (to 0.1 s below 10 s,
    to whole seconds above), so that the time a message names meets the criterion."""
    if t_s < 10.0:
        return f"{math.ceil(t_s * 10.0 - 1e-9) / 10.0:g}"
    return f"{math.ceil(t_s - 1e-9):.0f}"


#: The rest criterion of a stop's achieved time (:data:`~beltstudy.engine.dynamics.codes.
#: REST_FRACTION`, the kernel's).
REST_FRACTION = C.REST_FRACTION


def ramp_rest_fraction() -> float:
    """The fraction of a controlled stop's ``stop.time_s`` at which its s-curve reference
    (:func:`~beltstudy.engine.dynamics.profiles.stop_reference`) falls below
    :data:`REST_FRACTION` of design speed, by bisection: a belt that follows the reference is
    at rest by the achieved-time criterion that much before the ramp ends (about 0.885)."""
    lo, hi = 0.0, 1.0
    for _ in range(60):
        mid = 0.5 * (lo + hi)
        if stop_reference(mid, 1.0, 1.0)[0] > REST_FRACTION:
            lo = mid
        else:
            hi = mid
    return hi


def _coast_s(sys: System) -> float:
    """The rigid-body coast stop with every drive and brake off, ``M v / Te`` [s]: the moving
    mass (belt, load, idler rolls, shafts and motors) at design speed against the running
    resistance and lift (inf when Te <= 0, a belt that gravity keeps moving)."""
    te = float(sys.te_n)
    return sys.model.control.m_tot * sys.v_design / te if te > 0.0 else math.inf


def _coasts_within(sys: System, need_s: float) -> bool:
    """True when the belt coasts to rest with its brakes off (:func:`_coast_s`) sooner than
    ``need_s``: then less brake force cannot make a brake stop that slow."""
    return _coast_s(sys) < need_s


def _gravity_pull_n(sys: System) -> float:
    """The loop's net gravity resistance [N] (negative: gravity pulls the belt forward, a
    decline); 0 where the system carries no elements' gravity (a stand-in of the words)."""
    gravity = getattr(getattr(sys.model, "nodes", None), "gravity", None)
    return float(np.sum(gravity)) if gravity is not None else 0.0


def _brake_held(sys: System) -> bool:
    """True when a longer stop.time_s leaves the run's auto brakes as they are: what set their
    size where the run knows it (``System.brakes_timed``: a brake set by holding the belt at
    rest, also where its pulley's grip held the stop time's force below the holding one: a
    300 m incline's head brake asked 22.1 kN for a 2 s stop, its grip 1.35 kN, set at the
    4.9 kN that holds the belt), else :func:`_auto_brake_held`."""
    timed = getattr(sys, "brakes_timed", None)
    return (not timed) if timed is not None else _auto_brake_held(sys)


def _brake_history(sys: System) -> tuple | None:
    """The run's brakes' force history for the rigid-body words
    (:func:`beltstudy.engine.design.brake_profile` of the brakes as the kernel holds them):
    None where every brake ramps over ``ramp_s``. A brake with a ``force_curve`` does not read
    its ``ramp_s``; the words took the ramp (a 30 kN brake on the curve [[0, 0.5], [3, 1]]
    was quoted 'with the brakes' 0.5 s delay and 1 s ramp')."""
    br = sys.model.brakes
    if getattr(br, "curve_n", None) is None:  # a stand-in without curves: ramps
        return None
    each = [SimpleNamespace(
        force_curve=[(float(br.curve_t[b, k]), float(br.curve_f[b, k]))
                     for k in range(int(br.curve_n[b]))] or None,
        ramp_s=float(br.ramp[b])) for b in range(len(br.force))]
    return design.brake_profile(each) if each else None


def _curve_brakes(sys: System | None) -> bool:
    """Whether a brake of the run follows a ``force_curve`` (its ``ramp_s`` unread)."""
    br = getattr(getattr(sys, "model", None), "brakes", None)
    return (br is not None and bool(len(br.force)) and getattr(br, "curve_n", None) is not None
            and bool((br.curve_n > 0).any()))


def _auto_brake_held(sys: System) -> bool:
    """True when the run's auto brakes are set by holding the loaded belt at rest
    (``HOLD_MARGIN`` x its net gravity pull, :func:`beltstudy.engine.design.brake_forces`),
    above the force a rigid-body stop in ``stop.time_s`` asks: a longer stop time then leaves
    their force as it is."""
    brakes = getattr(sys.model, "brakes", None)
    if brakes is None or not len(brakes.force):
        return False
    hold = HOLD_MARGIN * abs(_gravity_pull_n(sys))
    cyc = sys.model.cycle
    delay = float(np.max(brakes.delay))
    ramp = float(np.max(brakes.ramp))
    stop_n = design.brake_force_auto(float(sys.model.control.m_tot), float(sys.v_design),
                                     float(sys.te_n), float(cyc.t_stop), delay, ramp,
                                     _brake_history(sys))
    return hold > 0.0 and not stop_n >= hold


def _gripped_stop_s(sys: System) -> tuple[float, float, float] | None:
    """Where an auto brake is held to its pulley's grip (``System.brakes_gripped``): the
    rigid-body stop time [s] of the run's brakes at their force now, below which no
    stop.time_s changes the brake; the one at the holding force, ``HOLD_MARGIN`` x the net
    gravity pull, the longest stop an auto brake gives (inf without a pull); and that force
    [N] (:func:`beltstudy.engine.design.brake_stop_time`, the brakes' delay and ramp or force
    curve). None otherwise or where the belt does not stop on them."""
    brakes = getattr(sys.model, "brakes", None)
    if not getattr(sys, "brakes_gripped", None) or brakes is None or not len(brakes.force):
        return None
    curve = _brake_history(sys)
    ramp = float(np.max(brakes.ramp)) if len(brakes.ramp) else 0.0
    m, v, te = float(sys.model.control.m_tot), float(sys.v_design), float(sys.te_n)
    delay = float(np.max(brakes.delay))
    t = design.brake_stop_time(m, v, te, float(np.sum(brakes.force)), delay, ramp, curve)
    if not (math.isfinite(t) and t > 0.0):
        return None
    hold = HOLD_MARGIN * abs(_gravity_pull_n(sys))
    t_hold = (design.brake_stop_time(m, v, te, hold, delay, ramp, curve) if hold > 0.0
              else math.inf)
    return t, t_hold, hold


def _given_brake_words(sys: System, need_s: float, t_stop: float, auto: bool = False) -> str:
    """What brake force would make a brake stop last ``need_s`` [s] (5 wave loop times): the
    rigid-body total force with the brakes' delay and ramp
    (:func:`~beltstudy.engine.design.brake_force_auto`, the stop at zero speed, moved out by
    the rest criterion's last stretch, ``REST_FRACTION v / a`` at the deceleration the force
    gives) against the brakes' total now, as ``a smaller given force_kn: at most ...`` (``a
    smaller brake force (brakes[].force_kn)`` where a brake is ``auto``)."""
    lever = "a smaller brake force (brakes[].force_kn)" if auto else "a smaller given force_kn"
    brakes = getattr(sys.model, "brakes", None)
    if brakes is None or not len(brakes.force):
        return lever
    now_n = float(np.sum(brakes.force))
    m, v, te = float(sys.model.control.m_tot), float(sys.v_design), float(sys.te_n)
    delay = float(np.max(brakes.delay)) if len(brakes.delay) else 0.0
    ramp = float(np.max(brakes.ramp)) if len(brakes.ramp) else 0.0
    curve = _brake_history(sys)
    if curve is not None:
        # the time the history reaches its last value stands for the ramp below
        ramp = max((t for t, f in curve if f != curve[-1][1]), default=0.0)
        ramp = min((t for t, _f in curve if t > ramp), default=ramp)
    force = design.brake_force_auto(m, v, te, need_s, delay, ramp, curve)
    for _ in range(3):
        if not (math.isfinite(force) and te + force > 0.0):
            break
        force = design.brake_force_auto(m, v, te, need_s + REST_FRACTION * v * m / (te + force),
                                        delay, ramp, curve)
    if not math.isfinite(force) or force >= now_n:
        return lever
    how = (f"{delay:g} s delay and their force curve (full at {ramp:g} s)" if curve is not None
           else f"{delay:g} s delay and {ramp:g} s ramp")
    said = (f"{lever}: at most about {gnum(force / 1e3, 3)} kN in all, now "
            f"{gnum(now_n / 1e3)} kN (rigid body, {gnum(m / 1e3)} t from {v:g} m/s against Te "
            f"{gnum(te / 1e3)} kN with the brakes' {how}, a stop "
            f"of {gnum(need_s, 3)} s against {gnum(t_stop, 3)} s now; ")
    pull = _gravity_pull_n(sys)
    hold = HOLD_MARGIN * abs(pull)
    if pull < 0.0 and force < hold:
        # a decline: gravity pulls the stopped belt forward, which no holdback holds, and a
        # brake holding it at rest needs HOLD_MARGIN x the pull, more than the stop's force.
        # The curve rises over the brakes' own ramp: set at once (a curve starting at the
        # fraction) the force is a step, whose front at the braked pulley dipped a 1.6 km
        # decline's slip margin to 0.96 on fine meshes (1.31 on the automatic one), where
        # the same curve ramped over 1 s kept 1.31 on every mesh
        full = max(hold, now_n)
        frac = force / full
        t_held = max(math.ceil(need_s - delay), 1)
        rise = ramp if ramp > 0.0 else 1.0
        start = f"[0, 0], [{ramp:g}, {frac:.2f}]" if ramp > 0.0 else f"[0, {frac:.2f}]"
        curve = f"[{start}, [{t_held:g}, {frac:.2f}], [{t_held + rise:g}, 1]]"
        keep = (f"keep a holding force of {gnum(hold / 1e3)} kN ({HOLD_MARGIN:g} x the pull)"
                if now_n < hold else f"keep its {gnum(now_n / 1e3)} kN for holding")
        return (said + f"so light a brake does not hold the loaded belt at rest on this "
                f"decline, whose net gravity pull is {gnum(abs(pull) / 1e3)} kN: {keep} and ease "
                f"the stop with brakes[].force_curve {curve}, about {frac:.2f} of it, reached "
                "over the brake's ramp, until the belt has stopped, then all of it)")
    return said + "a holdback or a holding brake set at rest holds the belt once stopped)"


#: The margin on 5 wave loop times that the flywheel advice sizes its rigid-body coast for:
#: the elastic belt's mean speed, whose fall below 1 % of design speed ends the measured stop,
#: swings about the rigid body's against a heavy flywheel (a 1.2 km EP800/4 belt with 103 t
#: of flywheel at the belt line came to rest 0.3 to 0.5 % before its rigid body).
COAST_MARGIN = 0.02


def _brake_impulse_ns(sys: System, t_s: float) -> float:
    """The momentum the run's brakes take out of the belt from the stop command to ``t_s``
    [N s]: their force in all over the longest delay, then their ramp or shared force curve
    (:func:`beltstudy.engine.design.brake_impulse_per_n`), as the stop's other rigid-body
    words take them (:func:`_given_brake_words`)."""
    br = getattr(sys.model, "brakes", None)
    if br is None or not len(br.force):
        return 0.0
    curve = _brake_history(sys)
    ramp = float(np.max(br.ramp)) if len(br.ramp) else 0.0
    return float(np.sum(br.force)) * design.brake_impulse_per_n(
        t_s - float(np.max(br.delay)), ramp, curve)


def _running_low(sys: System, out, r: dict, v_cmd: float | None) -> float | None:
    """The speed a stop's inertia advice starts from [m/s]: the mean belt speed at the stop
    command, or the lowest of the running phase's judged window (:func:`running_warnings`'
    window) where it swings below that. A coast from the crest of a 0.231 m/s swing (4.107
    m/s) sized flywheels that, given, met the stop at 3.954 m/s and fell 0.2 s short of 5
    wave loop times; from the swing's low the rigid body asks the most any phase asks."""
    if v_cmd is None:
        return None
    rec = out.rec[:int(r["nrec"])]
    t1 = sys.stop_command_s
    m = (rec["t"] >= min(judged_from(sys, r)[0], t1)) & (rec["t"] <= t1)
    if not m.any():
        return v_cmd
    return min(float(v_cmd), float(rec["v_mean"][m].min()))


def _coast_inertia_words(sys: System, need_s: float, conveyor=None, v_run: float | None = None,
                         t_stop: float | None = None, braked: bool = False) -> str:
    """How much inertia on the drive shafts makes a coast last ``need_s`` [s] (5 wave loop
    times), in words. The measured stop runs from the stop command, at the running speed
    ``v_run`` (the mean belt speed then: a dol drive's slip speed, a few per mille below design
    speed), until the mean speed falls below ``REST_FRACTION`` of design speed, so the rigid
    body's coast is ``M (v_run - REST_FRACTION v) / Te``; it reaches ``need_s (1 +
    COAST_MARGIN)`` (the margin for the elastic belt's swing about the rigid body) with ``M =
    need_s (1 + COAST_MARGIN) Te / (v_run - REST_FRACTION v)`` moving [kg], so the drives'
    shafts must carry ``dM = M - M_now`` more at the belt line, each its share; a drive's
    flywheel (on the pulley side of a coupling) of ``J_fw + (m_shaft + share dM - m_given) (D /
    2)^2`` [kg m2] gives it (its shaft carries the larger of the given inertia and the pulley's
    shell). The stop as it is (``t_stop``) is quoted against its own rigid-body time. A trip
    time only lengthens the coast. ``more inertia on the drive shafts`` alone where Te <= 0 (the
    belt does not coast to rest) or no inertia is missing. ``v_run`` None: design speed.

    ``braked``: a brake stop whose brakes stay on: the momentum to take out is then Te's and
    the brakes' (:func:`_brake_impulse_ns`), ``M dv = Te t + I_b(t)``. A 2 km incline on a
    given 50 kN brake was told the coast's 100 484 kg m2, and with it stopped in 12.2 s against
    the 14.2 s asked (212 + 50 kN took the momentum out, not 212)."""
    te, v = float(sys.te_n), float(sys.v_design)
    m_now = float(sys.model.control.m_tot)
    v0 = v if v_run is None else float(v_run)
    dv = v0 - REST_FRACTION * v
    if te <= 0.0 or v <= 0.0 or dv <= 0.0:
        return "more inertia on the drive shafts"
    target = need_s * (1.0 + COAST_MARGIN)
    impulse = _brake_impulse_ns(sys, target) if braked else 0.0
    m_need = (target * te + impulse) / dv
    dm = m_need - m_now
    if dm <= 0.0:
        return "more inertia on the drive shafts"
    if impulse > 0.0:
        now = (f" (the stop as it is, {gnum(t_stop)} s measured)" if t_stop is not None else "")
        auto = [f"brakes.{i}.force_kn" for i, b in enumerate(conveyor.brakes)
                if b.force_kn == "auto"] if conveyor is not None else []
        # an auto brake is sized again with the inertia (it grows with the moving mass): the
        # advice holds with the brakes as they are, so it names them to be given
        pin = (f" (give {', '.join(auto)} their present forces: auto, they are sized again "
               "with the inertia and the stop is shorter)" if auto else "")
        head = (f"more inertia on the drive shafts: a rigid-body brake stop from the running "
                f"speed {gnum(v0)} m/s to rest ({100.0 * REST_FRACTION:g} % of design speed, "
                f"{gnum(REST_FRACTION * v, 3)} m/s, where the stop time ends) with the brakes as "
                f"they are{pin}, M (v_run - v_rest) = Te t + the brakes' impulse I_b(t), of "
                f"{gnum(target)} s (5 wave loop times and {100.0 * COAST_MARGIN:g} % for the "
                f"elastic belt's swing about the rigid body) needs M = ({gnum(target)} s x "
                f"{gnum(te / 1e3)} kN + {gnum(impulse / 1e3)} kN s) / {gnum(dv)} m/s = "
                f"{gnum(m_need / 1e3)} t moving, {gnum(dm / 1e3)} t more than the "
                f"{gnum(m_now / 1e3)} t now at the belt line{now}")
    else:
        now = (f" (the stop as it is: {gnum(m_now / 1e3)} t x {gnum(dv)} m/s / {gnum(te / 1e3)} kN = "
               f"{gnum(m_now * dv / te)} s rigid, {gnum(t_stop)} s measured)" if t_stop is not None
               else "")
        head = (f"more inertia on the drive shafts: a rigid-body coast from the running speed "
                f"{gnum(v0)} m/s to rest ({100.0 * REST_FRACTION:g} % of design speed, "
                f"{gnum(REST_FRACTION * v, 3)} m/s, "
                f"where the stop time ends), M (v_run - v_rest) / Te, of {gnum(target)} s (5 wave "
                f"loop times and {100.0 * COAST_MARGIN:g} % for the elastic belt's swing about "
                f"the rigid body) needs M = {gnum(target)} s x {gnum(te / 1e3)} kN / {gnum(dv)} m/s = "
                f"{gnum(m_need / 1e3)} t moving, {gnum(dm / 1e3)} t more than the "
                f"{gnum(m_now / 1e3)} t now at the belt line{now}")
    if conveyor is None:
        return head
    dr = sys.model.drives
    parts = []
    for k, d in enumerate(conveyor.drives):
        share = float(dr.share[k])
        if share <= 0.0:
            continue
        red = (2.0 / d.pulley_diameter_m) ** 2
        m_shaft = float(sys.model.shafts.mass[int(dr.shaft[k])])
        given = _drive_given_kg(d)[0]
        j_fw = d.flywheel_kg_m2 + (m_shaft + share * dm - given) / red
        parts.append(f"drives.{k}.flywheel_kg_m2 {math.ceil(j_fw):,} kg m2 (now "
                     f"{d.flywheel_kg_m2:,.0f}; {gnum(share * dm / 1e3)} t at the belt line, x "
                     f"(D / 2)^2, D {d.pulley_diameter_m:g} m)")
    return head + (f", a flywheel of {' and '.join(parts)}" if parts else "") + _start_cost(
        sys, dm)


def _start_cost(sys: System, dm: float) -> str:
    """What ``dm`` [kg] more at the belt line asks of the start, in words: a speed curve's
    start (s-curve, linear) accelerates it at the curve's peak, ``dm a_peak`` more drive force
    beside the drives' rated force in all; a dol or torque start takes longer instead (the
    same force drives more mass). A flywheel sized for the coast alone overloaded a 60 m
    conveyor's start by 12 % (33.07 against 29.57 kN rated) without a word."""
    cyc = sys.model.cycle
    if cyc.start_ctrl not in (S_CURVE, LINEAR) or (sys.model.drives.control == C.DOL).all():
        return (f"; the start then takes longer (the same force accelerates {gnum(dm / 1e3)} t "
                "more)")
    a = abs(start_reference(cyc.start_ctrl, 0.5 * cyc.t_start, cyc.t_start, cyc.v_d)[1])
    rated = float(np.sum(sys.model.drives.rated))
    against = (f", against the drives' {gnum(rated / 1e3)} kN rated in all" if rated > 0.0
               else "")
    return (f"; the start then accelerates it too: {gnum(dm / 1e3)} t x {gnum(a, 3)} m/s2 (its peak "
            f"acceleration) = {gnum(dm * a / 1e3, 3)} kN more drive force{against}")


def _fast_stop_words(sys: System, t_stop: float, summary: dict, steady_tmax: float,
                     conveyor=None, v_cmd: float | None = None) -> str:
    """The warning of a stop faster than 5 wave loop times (Harrison after Funke 1973): the
    stop's tensions against the running ones, and what would lengthen it: for a brake stop
    the given brake force that would (:func:`_given_brake_words`), and an auto brake's
    stop time only where a brake is auto (``stop.time_s`` sizes no given brake); for a coast
    the flywheel from the mean belt speed at the stop command ``v_cmd``
    (:func:`_coast_inertia_words`)."""
    cyc = sys.model.cycle
    t_min_run = float(np.min(sys.steady_tension_n)) / 1e3
    hi, lo = summary.get("t_max_stop_kn"), summary.get("t_min_stop_kn")
    seen = ""
    if hi is not None and lo is not None:
        ranges = (f"{gnum(lo)} to {gnum(hi)} kN against {gnum(t_min_run)} to "
                  f"{gnum(steady_tmax / 1e3)} kN running")
        # the rule is of thumb: where this stop's tensions stayed within the running range
        # (an empty belt's stop), it is said beside the name, not left to contradict it
        calm = (lo >= t_min_run * (1.0 - 1e-3) and hi <= steady_tmax / 1e3 * (1.0 + 1e-3))
        seen = (f" by that rule, though its tensions stayed within the running range ({ranges})"
                if calm else f"; its tensions ranged {ranges}")
    need = 5.0 * sys.wave_loop_time_s
    if cyc.stop_mode == C.CONTROLLED:
        # a stop that follows its curve scales with the asked time; one held back (a drive's
        # torque limit, slip, the belt's own elasticity: longer than asked) does not: the
        # curve that rests after 5 loops when followed, ramp_rest_fraction() of it, is the
        # least to ask
        scaled = max(need * cyc.t_stop / t_stop, need / ramp_rest_fraction())
        unbraked = _unbraked_stop_s(sys)
        asked = max(scaled, unbraked)
        lag = (f"; the belt did not follow the {cyc.t_stop:g} s curve: it took "
               f"{t_stop:.1f} s" if t_stop > cyc.t_stop else "")
        floor = (f", and at least {_unbraked_words(sys, unbraked)}" if unbraked > scaled
                 else "")
        # scaled from this stop, the figure assumes the belt rests at the same fraction of a
        # longer curve; it rests a little sooner (a 200 m, 0.2 m/s belt: 0.800 of 1.9 s, 0.792
        # of 2.1 s), so the figure can fall short by a step of its rounding: say to rerun
        fix = (f"a controlled stop of stop.time_s {_up_s(asked)} s or more would be slower "
               f"than that (this stop's time scaled to 5 wave loop times{lag}{floor}; rerun "
               "to check)")
    elif cyc.stop_mode == C.BRAKE and not _coasts_within(sys, need):
        auto = getattr(sys, "auto_brakes", None)
        if auto is None:
            auto = conveyor is None or any(b.force_kn == "auto" for b in conveyor.brakes)
        given = _given_brake_words(sys, need, t_stop, auto)
        held = _brake_held(sys) if auto else False
        gripped = _gripped_stop_s(sys) if auto and not held else None
        if gripped is not None:
            # held to its pulley's grip, the brake keeps that force until the asked time's
            # rigid-body force falls below it: a stop.time_s up to the grip's own rigid-body
            # stop (t_grip) changes nothing (8 s asked, then the 8.8 s advised, both stopped in
            # 11.89 s at the same 157.1 kN). Past it the stop scales with the asked time as
            # this run's stop did with its rigid-body one, down to the holding force, whose
            # own stop (t_hold) is the longest an auto brake gives
            t_grip, t_hold, hold = gripped
            asked = need * t_grip / t_stop
            grip = (f"the auto brake is held to its pulley's grip, whose rigid-body stop takes "
                    f"{gnum(t_grip, 3)} s")
            if asked <= t_hold:
                fix = (f"less brake force would be slower than that: {given}, or a stop.time_s "
                       f"of {_up_s(asked)} s or more ({grip}: a stop.time_s below that leaves "
                       "it as it is)")
            else:
                fix = (f"less brake force would be slower than that: {given} (no stop.time_s "
                       f"would: {grip}, and no auto brake falls below the holding force "
                       f"{gnum(hold / 1e3)} kN, {HOLD_MARGIN:g} x the net gravity pull, whose "
                       f"rigid-body stop takes about {gnum(t_hold, 3)} s)")
        elif auto and not held:
            # an auto brake's stop scales with its asked time as a controlled one's does
            asked = need * cyc.t_stop / t_stop if cyc.t_stop > 0.0 else need
            fix = (f"less brake force would be slower than that: {given}, or for an auto "
                   f"brake sized by the stop time a stop.time_s of {_up_s(asked)} s or more "
                   "(an auto brake set by holding keeps its force whatever the stop time)")
        elif held:
            # sized by holding the belt at rest: a longer stop.time_s does not change it
            fix = (f"less brake force would be slower than that: {given} (the auto brake is "
                   "set by holding the belt at rest, so stop.time_s does not change it)")
        else:
            # every brake is given: stop.time_s sizes nothing, the force is the lever
            fix = f"less brake force would be slower than that: {given}"
    else:
        # a coast stop, or a brake stop of a belt that coasts to rest within 5 wave loop
        # times on its own resistances (no brake setting makes it slower): the drives must
        # hold it back, or more inertia must carry it
        coast = ""
        if cyc.stop_mode == C.BRAKE:
            coast = (f"no brake setting makes it slower: with the brakes off the belt coasts "
                     f"to rest in about {_coast_s(sys):.2g} s (rigid body, M v / Te = "
                     f"{gnum(sys.model.control.m_tot / 1e3)} t x {sys.v_design:g} m/s / "
                     f"{gnum(sys.te_n / 1e3)} kN), itself faster than 5 wave loop times; ")
        # a belt that follows the s-curve rests at ramp_rest_fraction() of stop.time_s; a long
        # or soft belt's mass-weighted mean speed rests sooner (a 1.5 km fabric belt at 0.78,
        # a 7 km steel-cord overland at 0.81 of the ramp), so this is the least to ask, not
        # one that is sure to meet 5 loops: say so, and where the figure that does comes from
        frac = ramp_rest_fraction()
        # a controlled stop needs every drive on a vfd (a dol motor on the line cannot follow a
        # stopping curve, and the run refuses stop.mode controlled): where one is dol, say what
        # makes it possible
        drv = getattr(sys.model, "drives", None)
        dol = drv is not None and bool((drv.control == C.DOL).any())
        how = ("a controlled stop (vfd drives)" if not dol else
               f"a controlled stop on vfd drives ({vfd_fields(sys)}, now dol: a motor on the "
               "line cannot follow a stopping curve; then stop.mode: controlled)")
        unbraked = _unbraked_stop_s(sys)
        floor = (f", and at least {_unbraked_words(sys, unbraked)}" if unbraked > need / frac
                 else "")
        fix = (f"{coast}{how} would be slower than that, with stop.time_s at "
               f"least {_up_s(max(need / frac, unbraked))} s (enough for a belt that follows "
               f"its s-curve, at rest from {frac:.3f} of it{floor}; a long or soft belt's mean "
               "speed comes to rest sooner and needs more: rerun the controlled stop, whose "
               "own warning names the time to ask), or " + _coast_inertia_words(
                   sys, need, conveyor, v_cmd, t_stop, braked=cyc.stop_mode == C.BRAKE))
    # three figures: at 0.1 s a 1.519 s stop against 5 x 0.333 s read 'stop in 1.5 s is faster
    # than 5 wave loop times (5 x 0.3 s)'
    # a stop time asked below the criterion asks for the high-stress stop itself: said, as
    # a brake stop that missed its asked 8 s was told both too slow and too fast (13 s)
    asked_fast = (f" (the stop.time_s asked, {cyc.t_stop:g} s, is itself shorter than "
                  f"that)" if cyc.stop_mode in (C.BRAKE, C.CONTROLLED)
                  and 0.0 < cyc.t_stop < need else "")
    return (f"stop in {gnum(t_stop, 3)} s is faster than 5 wave loop times (5 x "
            f"{gnum(sys.wave_loop_time_s, 3)} s = {gnum(need, 3)} s){asked_fast}: a high-stress "
            f"stop{seen}; {fix}")


def _unbraked_stop_s(sys: System) -> float:
    """The shortest controlled stop whose s-curve the drives follow without braking [s]: its
    steepest deceleration, ``2 v / T`` (:func:`~beltstudy.engine.dynamics.profiles.
    stop_reference`), within the coast's ``Te / M``, so ``T = 2 v M / Te``; 0 where the belt
    does not coast to rest (Te <= 0). On a steeper curve the drives brake the belt faster than
    it coasts: a 120 m fabric belt that coasted to rest in 3.01 s, stopped on the 3.6 s curve
    asked of it, rested in 2.70 s with a higher peak (its 2 v M / Te is 5.95 s). Pushing only,
    the drives leave the rigid body no deceleration above its coast's, so it rests no sooner
    than it coasts."""
    te = float(sys.te_n)
    return 2.0 * sys.v_design * sys.model.control.m_tot / te if te > 0.0 else 0.0


def _unbraked_words(sys: System, t_s: float) -> str:
    """:func:`_unbraked_stop_s` in words, with its figures."""
    return (f"2 v M / Te = 2 x {sys.v_design:g} m/s x {gnum(sys.model.control.m_tot / 1e3)} t / "
            f"{gnum(sys.te_n / 1e3)} kN = {gnum(t_s, 3)} s, so that the curve's steepest deceleration "
            "2 v / T stays within the coast's Te / M and the drives never brake the belt: "
            "braked, it rests sooner than it coasts")


#: The last part of the stop window whose change of the mean speed says whether a belt that
#: did not stop settled at a speed: a tenth of the window (30 s of 300 s).
LATE_FRACTION = 0.1


def _window_tail(sys: System, out, r: dict) -> tuple[float, float] | None:
    """The last tenth of the stop window (:data:`LATE_FRACTION`) [s] and the mean belt speed
    at its beginning [m/s] (the records), for :func:`not_stopped_words`; None without a
    record there."""
    span = LATE_FRACTION * float(sys.model.cycle.stop_max)
    v_then = _speed_at(out, r, float(r["t"]) - span)
    return (span, v_then) if v_then is not None and span > 0.0 else None


def _coasts_on_words(sys: System, v_end: float, late: tuple[float, float] | None) -> str:
    """Why a belt that no brake slows, its resistance above gravity's pull at design speed
    (Te > 0), did not stop in the stop window, in words. Where the rigid-body coast ``M v /
    Te`` (:func:`_coast_s`) is beyond the window, that (a 2 km, 78 m decline, Te +0.52 kN:
    4.00 -> 3.51 m/s in 300 s). Where it is within it, the resistances fell as the belt
    slowed, to gravity's pull down the decline: the speed the belt coasts on at (``late``:
    the mean speed's change over the window's last tenth, from the records). A 20 m, 5 m
    decline at 4.5 m/s (Te +1.82 kN at design speed, its feed's resistance falling with the
    speed) coasted on at 1.23 m/s, and was told a rigid-body coast to rest takes about 22.2 s,
    'beyond the window' of 300 s."""
    te, m = float(sys.te_n), sys.model.control.m_tot
    window = float(sys.model.cycle.stop_max)
    brake = ("a brake would stop it (brakes with force_kn: auto sizes one for stop.mode brake "
             "and its stop.time_s)")
    coast = _coast_s(sys)
    if coast > window:
        # resistance above the pull, barely: it slows, too slowly for the window, not kept
        # moving by gravity
        return (f"its resistance exceeds gravity's pull by only Te = {gnum(te / 1e3, 3)} kN, so "
                f"it slows at about Te / M = {te / m:.2g} m/s2: a rigid-body coast to rest "
                f"takes about {gnum(coast, 3)} s (M v / Te), beyond the window; a brake would stop it "
                "sooner (brakes with force_kn: auto sizes one for stop.mode brake and its "
                "stop.time_s)")
    rigid = (f"a rigid body at its design-speed resistance (Te = {gnum(te / 1e3, 3)} kN above "
             f"gravity's pull) would coast to rest in about {gnum(coast, 3)} s (M v / Te), within "
             "the window, but its resistances fall as it slows")
    if late is None:
        return f"{rigid}; {brake}"
    span, v_then = late
    dv = v_end - v_then
    change = f"its mean speed changed {dv:+.2g} m/s over the window's last {span:.0f} s"
    if abs(dv) > 0.01 * abs(v_end):
        return f"{rigid}, so it slows far more slowly than a rigid body ({change}); {brake}"
    pull = -_gravity_pull_n(sys)
    down = (f"its pull down the decline, {gnum(pull / 1e3)} kN ({change})" if pull > 0.0 else
            f"gravity's pull ({change})")
    return (f"{rigid}: it coasts on at about {gnum(v_end, 3)} m/s, where they match {down}, so "
            f"gravity keeps it moving: {brake}")


def not_stopped_words(sys: System, v_end: float, sliding: bool = False,
                      late: tuple[float, float] | None = None) -> str:
    """The warning of a run whose belt did not come to rest within the stop window
    (``DynamicsOptions.stop_window_s``, the one rule for every run): the window, the mean belt
    speed at its end [m/s] and what would stop it; ``sliding`` when a braked pulley slipped in
    the stop (the belt slid over it: more brake force would not help); ``late`` the last part
    of the window [s] and the mean speed at its start [m/s] (:func:`_window_tail`), which say
    whether an unbraked belt settled at a speed (:func:`_coasts_on_words`)."""
    cyc = sys.model.cycle
    brakes = sys.model.brakes
    total_kn = float(brakes.force.sum()) / 1e3
    if v_end < 0.0:
        fix = ("a holdback (holdback: true) or brakes that hold (brakes[].hold) would hold it "
               "against the lift")
    elif not len(brakes.force) and float(sys.te_n) > 0.0:
        fix = _coasts_on_words(sys, v_end, late)
    elif not len(brakes.force):
        fix = ("gravity keeps it moving against its resistance: a brake would stop it (brakes "
               "with force_kn: auto sizes one for stop.mode brake and its stop.time_s)")
    elif sliding:
        fix = (f"its brakes ({gnum(total_kn)} kN in all) are beyond the grip of their pulley, "
               f"which slid in the stop: more slack-side tension there ({heavier_takeup(sys)}) "
               "or part of the brake force on another pulley would let them stop it")
    elif cyc.stop_mode != C.BRAKE:
        fix = (f"its brakes ({gnum(total_kn)} kN) act only once it rests: a brake stop "
               "(stop.mode: brake) would stop it")
    else:
        fix = (f"its brakes ({gnum(total_kn)} kN in all) do not stop it: a larger brake force "
               "(brakes[].force_kn, auto sizes it for the stop time) would")
    return (f"the belt did not stop within the stop window of {cyc.stop_max:.0f} s after the "
            f"stop command (the same for every run, docs/dynamics.md): its mean speed was "
            f"still {gnum(v_end, 3)} m/s ({100.0 * v_end / cyc.v_d:.0f} % of design speed) at the "
            f"window's end; {fix}")
