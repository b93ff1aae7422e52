"""The transient model as named records: what the kernel reads, what it updates, what it
returns.

:func:`beltstudy.engine.dynamics.model.build_system` assembles the constant records section by
section (the cycle, the belt's elements and springs, the resistance law, the implicit blocks,
the pulley shafts, the drives, the brakes, the take-up, the speed loop, the recorded springs)
and holds them in one :class:`Model`; :func:`beltstudy.engine.dynamics.simulate.simulate` adds a
fresh :class:`State`, :class:`Out` and :class:`Work` and calls the kernel
(:func:`beltstudy.engine.dynamics.kernel.run_cycle`) with the four. The numpy reference
(:mod:`beltstudy.engine.dynamics.reference`) reads the same records.

Records are named tuples of float64 / int64 arrays and scalars, which numba compiles as
structs (the brakes' record is defined with their law in
:mod:`beltstudy.engine.dynamics.brakes`); the run's scalars, the per-drive and per-shaft results and the time-series records are
numpy structured arrays (:data:`RUN`, :data:`DRIVE_RESULT`, :data:`SHAFT_SLIP`,
:data:`RECORD`, :data:`DRIVE_RECORD`): fields by name in the kernel (``rs.vmax``) and in
Python (``out.run["vmax"]``). Units SI; per-element arrays have length n, per-spring arrays
length n (spring j joins elements j and j + 1, cyclic). Arrays a run changes (marked *state*)
are fresh for every run (:func:`beltstudy.engine.dynamics.simulate.fresh_model`).
"""

from __future__ import annotations

from typing import NamedTuple

import numpy as np

from beltstudy.engine.dynamics.brakes import Brakes

__all__ = ["Cycle", "Nodes", "Law", "Lin", "Springs", "Blocks", "Shafts", "Drives", "Brakes",
           "Takeup", "Control", "Probes", "Model", "State", "Out", "Work", "RUN",
           "DRIVE_RESULT", "SHAFT_SLIP", "RECORD", "DRIVE_RECORD"]


class Cycle(NamedTuple):
    """The cycle: step and phase times [s], speeds [m/s], the scenario's codes.

    ``dt`` the step; ``t_pre`` the rest before the start command; ``t_start``, ``t_run``,
    ``t_stop`` the start, run and stop times of the scenario; ``stop_max`` the stop window
    (``DynamicsOptions.stop_window_s``: a belt not at rest this long after the stop command
    did not stop, and the run ends there); ``post_rest`` the rest after the belt has stopped; ``t_end`` an earlier end of
    the run (0: none, verification runs); ``rec_dt`` and ``surf_dt`` the spacing of the records
    and of the surface; ``v_d`` the design speed, ``v_eps`` the resistance's regularisation
    speed, ``v_fail`` the speed taken as divergence; ``start_ctrl``
    (:mod:`beltstudy.engine.dynamics.profiles`), ``stop_mode`` and ``formulation``
    (:mod:`beltstudy.engine.dynamics.codes`); ``hold_node`` the element held at rest;
    ``t_hand`` the start's hand-over from the hold to the drives (0: at the start command;
    :func:`beltstudy.engine.dynamics.model.handover_time_s`)."""

    dt: float
    t_pre: float
    t_start: float
    t_run: float
    t_stop: float
    stop_max: float
    post_rest: float
    t_end: float
    rec_dt: float
    surf_dt: float
    v_d: float
    v_eps: float
    v_fail: float
    start_ctrl: int
    stop_mode: int
    formulation: int
    hold_node: int
    t_hand: float


class Nodes(NamedTuple):
    """Belt elements: moving mass [kg] (a plain pulley's own mass included), dt / mass
    [s/kg], gravity along the belt [N], weight of the mean speed (the belt's mass without
    pulleys) [kg], sag weight ``g (m'_G + m'_L) cos(a) S / 8`` [N] and the resistance law's
    sag cap (each also over the reference sag: ``sw_ref``, ``hsm_ref``)."""

    mass: np.ndarray
    hm: np.ndarray
    gravity: np.ndarray
    w_mean: np.ndarray
    sag_w: np.ndarray
    hs_cap: np.ndarray
    sw_ref: np.ndarray
    hsm_ref: np.ndarray


class Law(NamedTuple):
    """The resistance law (``beltstudy.engine.law``), terms merged by exponents: coefficients
    (K, n) [N], speed and sag exponents (``pvv``, ``psv``) with their codes (``pvc``, ``psc``:
    :func:`beltstudy.engine.dynamics.model.exponent_codes`), the elements of sparse terms
    (``t_idx[t_ptr[k]:t_ptr[k + 1]]`` for a term with ``t_sparse[k] == 1``), the reference
    sag ratio ``hs_ref``, whether any term depends on the tension (``any_ps``), the accuracy
    of the expanded law (``rtol``) and how the kernel evaluates it (``mode``: once, exactly every
    step, or expanded between exact evaluations; ``codes.LAW_*``)."""

    coef: np.ndarray
    pvc: np.ndarray
    pvv: np.ndarray
    psc: np.ndarray
    psv: np.ndarray
    t_sparse: np.ndarray
    t_ptr: np.ndarray
    t_idx: np.ndarray
    hs_ref: float
    any_ps: bool
    rtol: float
    mode: int


class Lin(NamedTuple):
    """The resistance law's expansion per element (:mod:`beltstudy.engine.dynamics.linlaw`):
    ``R0 = k + gu u + guu u^2 + gx T + gxx T^2 + gux u T`` [N] (``u = |v|``, T the mean
    tension); the window round the expansion point as bounds on the speed (``ulo``, ``uhi``
    [m/s]) and the mean tension (``tlo``, ``thi`` [N]); all float32, *state*.

    The law for its element-wise evaluation (:func:`beltstudy.engine.dynamics.passes.law_refresh`):
    per element a row of 16 (``erow``): sag weight and sag cap over the reference sag, the
    tension below which the sag ratio is at its cap [N], the window sizes (relative speed,
    creep [m/s], relative tension; ``linlaw.BIG`` where no term depends on it), two zeros, the
    coefficients padded to ``K_LIN`` terms with zero ones; each term's speed and sag factor
    rows (``rs``, ``rq``); the weights of the sums over the terms (``wk``, rows 1, p, p (p -
    1), q, q (q + 1), p q); the speed and sag exponents taken by exp and log (``upow``,
    ``qpow``) and ``npow`` = their numbers and whether a sag exponent is 0.5 or 1.5. Scratch
    (*state*): the flags of the elements outside their windows (``flag``, padded to whole
    words, ``flag64`` its view by words), their indices (room for padding), the gathered,
    factor and output rows of the evaluation (``sg``, ``sf``, ``so``)."""

    k: np.ndarray
    gu: np.ndarray
    guu: np.ndarray
    gx: np.ndarray
    gxx: np.ndarray
    gux: np.ndarray
    ulo: np.ndarray
    uhi: np.ndarray
    tlo: np.ndarray
    thi: np.ndarray
    erow: np.ndarray
    rs: np.ndarray
    rq: np.ndarray
    wk: np.ndarray
    upow: np.ndarray
    qpow: np.ndarray
    npow: np.ndarray
    flag: np.ndarray
    flag64: np.ndarray
    idx: np.ndarray
    sg: np.ndarray
    sf: np.ndarray
    so: np.ndarray


class Springs(NamedTuple):
    """Springs (the belt between element centres).

    Physical: length [m], Ernst's ``a = (w S)^2 / 12`` [N^2], floor tension [N] (the tangent
    modulus is held below it) and the floor modulus [N], Kelvin-Voigt viscosity of the mesh
    ``alpha Z`` [N s/m], carriage coupling (1 beside the gravity take-up), chord strain at the
    running tension (the reference of the belt length a slack span gathers), the static and
    dynamic stiffness E B, E_dyn B [N].

    For the step: dt / length [s/m], ``a EB``, the strain tension at the floor (EB times the
    chord strain there) and the floor modulus over EB, the mesh viscosity per strain increment
    ``alpha Z len / dt`` [N], the relaxing arm's decay over a step and gain per unit tangent
    stiffness and strain increment (``e_damp``, ``g_damp``); the free element and spring
    ranges ([start, end) rows); ``limited`` (1/0): the free springs' mesh viscosity limited
    (:func:`beltstudy.engine.dynamics.passes.visc_limiter`)."""

    len_m: np.ndarray
    a_ernst: np.ndarray
    t_floor: np.ndarray
    k_floor: np.ndarray
    viscosity: np.ndarray
    car_ind: np.ndarray
    eps_run: np.ndarray
    eb: float
    eb_dyn: float
    dl: np.ndarray
    a_eb: np.ndarray
    s_floor: np.ndarray
    kfl_eb: np.ndarray
    kvs: np.ndarray
    e_damp: float
    g_damp: float
    seg_node: np.ndarray
    seg_spring: np.ndarray
    limited: int = 0


class Blocks(NamedTuple):
    """Implicit blocks (the master drive's first): element ranges ``ptr``, their elements,
    carriage flag, each block element's left spring and mass / dt [kg/s]; the shaft of every
    element (-1 none)."""

    ptr: np.ndarray
    nodes: np.ndarray
    car: np.ndarray
    left: np.ndarray
    mdt: np.ndarray
    node_shaft: np.ndarray


class Shafts(NamedTuple):
    """Pulley shafts (every drive pulley and braked or holdback pulley): element, reduced
    mass [kg], e^(mu theta) - 1 static and sliding (static < 0: never slips, verification),
    drive (-1 none), holdback flag; *state*: speed at the rim [m/s], slip direction (0 stuck,
    +1 shaft faster, -1 belt faster); per step: brake force on the shaft [N] and the brake
    force it gave [N]."""

    node: np.ndarray
    mass: np.ndarray
    cs: np.ndarray
    ck: np.ndarray
    drive: np.ndarray
    hb: np.ndarray
    vs: np.ndarray
    slip: np.ndarray
    fb: np.ndarray
    fb_out: np.ndarray


class Drives(NamedTuple):
    """Drives in file order: shaft, element, share, force limit [N] (and the one in force this
    step, *state*), rated force [N], control and coupling codes, motor curve (points per
    drive), fill time [s], motor mass behind a coupling [kg] (at least 1), trip time [s];
    *state* per step: force law mode (0 linear ``f0 + f1 v``, 1 share of the speed loop's
    output, 2 imposed shaft speed), ``f0``, ``f1``, saturation; coupling linearisation
    ``(P, D, c_s)`` and the motor speed; the force a slipping torque follower's speed window
    adds to its share (``win_f``, within its limit; 0 otherwise); outputs: force at the rim
    and force passed to the belt, the force when the power went off, the force at the rim at the step's start (the
    law of the step at the shaft's speed before it: with the force linear in the shaft speed
    and that speed monotone over the step, the force's extremes over a step are at its
    ends)."""

    shaft: np.ndarray
    node: np.ndarray
    share: np.ndarray
    lim0: np.ndarray
    lim: np.ndarray
    rated: np.ndarray
    control: np.ndarray
    coupling: np.ndarray
    curve_x: np.ndarray
    curve_y: np.ndarray
    curve_n: np.ndarray
    fill_s: np.ndarray
    motor_mass: np.ndarray
    trip_s: np.ndarray
    mode: np.ndarray
    f0: np.ndarray
    f1: np.ndarray
    sat: np.ndarray
    win_f: np.ndarray
    lin_p: np.ndarray
    lin_d: np.ndarray
    lin_cs: np.ndarray
    vm: np.ndarray
    force: np.ndarray
    ft: np.ndarray
    f_trip: np.ndarray
    f_start: np.ndarray


class Takeup(NamedTuple):
    """The take-up: gravity (a carriage that moves) or fixed, its pulley element, the
    counterweight's weight [N] and the carriage's inertia [kg], its travel from the rest
    position (``lo``, ``hi`` [m]) and the running position [m]."""

    gravity: bool
    node: int
    weight: float
    mass: float
    lo: float
    hi: float
    x_run: float


class Control(NamedTuple):
    """The drives' control: all vfd (``vfd``) or dol, the master drive (the speed loop's),
    the loop's gains ``Kp = 2 omega_c M`` [N s/m] and ``Ki = omega_c^2 M`` [N/m] on the mass
    the loop sees (``model.loop_inertia``) and its bandwidth [rad/s], all moving mass
    (``m_tot``) [kg], the running resistance the feedforward carries (Te less
    the net gravity) [N] and the reference speed at which it is complete [m/s], the open-loop
    force of a verification start [N], the followers' speed window [m/s], the time after the
    start command from which the master's tracking error counts (one wave loop time) [s], the
    rigid-body feedforward ``ff x (m_tot a_ref + f_res ...)`` on (1.0) or off (0.0)."""

    vfd: bool
    master: int
    kp: float
    ki: float
    bandwidth: float
    m_tot: float
    f_res: float
    v_ff: float
    f_const: float
    window: float
    t_track: float
    ff: float


class Probes(NamedTuple):
    """What the records read: the springs of the key points (entering the first head pulley,
    leaving the last head drive pulley), the tail pulley element, the probe springs round the
    loop and the springs of the surface."""

    s_head_in: int
    s_head_out: int
    i_tail: int
    probes: np.ndarray
    surface: np.ndarray


class Model(NamedTuple):
    """The transient model: every constant record of a conveyor and scenario (the arrays
    marked *state* are reset for each run)."""

    cycle: Cycle
    nodes: Nodes
    law: Law
    lin: Lin
    springs: Springs
    blocks: Blocks
    shafts: Shafts
    drives: Drives
    brakes: Brakes
    takeup: Takeup
    control: Control
    probes: Probes


class State(NamedTuple):
    """Belt state: velocity [m/s], elastic tension, strain tension (EB times the chord
    strain), arm and total tension [N]."""

    v: np.ndarray
    te: np.ndarray
    ts: np.ndarray
    td: np.ndarray
    tt: np.ndarray


#: The run's scalars (one record, ``Out.run``): the time, the step count and the phase
#: switches; the take-up, speed loop and holding force; this step's drive totals; the
#: extremes with their times; what was reached when; slack; the status. Times [s], speeds
#: [m/s], forces [N], powers [W], work [J], lengths [m]; -1 for a time not reached.
RUN = np.dtype([
    ("status", np.int64), ("div_where", np.int64), ("steps", np.int64), ("t", np.float64),
    ("t_end_limit", np.float64), ("t_stopcmd", np.float64), ("inv_w_sum", np.float64),
    # the speed a controlled stop's ramp starts from (-1 until the stop command)
    ("v_stop0", np.float64),
    # phases of this step
    ("phase", np.int64), ("started", np.bool_), ("stopping", np.bool_), ("was_off", np.bool_),
    ("pi", np.bool_), ("pi_started", np.bool_), ("hold", np.int64),
    ("v_ref", np.float64), ("a_ref", np.float64), ("f0u", np.float64), ("f1u", np.float64),
    ("U", np.float64), ("u_known", np.bool_),
    # take-up, speed loop, holding force
    ("x_tu", np.float64), ("u_tu", np.float64),
    ("integ", np.float64), ("hold_f", np.float64),
    # this step's totals and the state's extremes
    ("vsum", np.float64), ("v_mean", np.float64), ("f_tot", np.float64),
    ("p_tot", np.float64), ("f_brake", np.float64), ("tlo", np.float64), ("thi", np.float64),
    ("vlo", np.float64), ("vhi", np.float64), ("n_out", np.int64), ("law_evals", np.int64),
    # the cycle's extremes
    ("vmax", np.float64), ("vmax_t", np.float64), ("vmin", np.float64), ("vmin_t", np.float64),
    ("tmax", np.float64), ("tmax_t", np.float64), ("tmin", np.float64), ("tmin_t", np.float64),
    ("xmin", np.float64), ("xmax", np.float64), ("fmax", np.float64), ("fmax_t", np.float64),
    ("pmax", np.float64), ("slip_min", np.float64), ("slip_min_t", np.float64),
    ("w_drive", np.float64),
    # events
    ("endstop", np.int64), ("endstop_t", np.float64), ("endstop_speed", np.float64),
    ("start_ach", np.float64), ("stop_ach", np.float64), ("stopped", np.bool_),
    # the mass-weighted mean speed integrated from the stop command until the stop is achieved
    ("stop_dist", np.float64),
    ("t_stopped", np.float64), ("t_trip", np.float64), ("hold_set", np.float64),
    # slack
    ("slack_max", np.float64), ("slack_at", np.int64), ("slack_time", np.float64),
    ("slack_dur", np.float64), ("slack_first", np.float64), ("slack_m", np.float64),
    # records and envelope segments
    ("nrec", np.int64), ("nsurf", np.int64), ("seg", np.int64),
    # the speed loop's output at the step's start (the master's shaft speed before the step)
    ("u0", np.float64),
    # the master's tracking (largest |v_ref - v_master| after Control.t_track, when), the
    # carriage's range in the start (start to stop command) and in the stop, the highest
    # mean belt speed in the start and when
    ("verr_max", np.float64), ("verr_t", np.float64), ("xlo_start", np.float64),
    ("xhi_start", np.float64), ("xlo_stop", np.float64), ("xhi_stop", np.float64),
    ("vmean_hi", np.float64), ("vmean_hi_t", np.float64),
    # this step's holdback force (the reaction its brakes do not give), the largest holdback
    # and brake forces over the run [N]
    ("f_hb", np.float64), ("fhb_max", np.float64), ("fbr_max", np.float64),
], align=True)

#: Per drive: largest |force| at the rim [N] and |power| [W] after the start command, smallest
#: slip margin and when, time slipping [s], belt length slipped [m], first and last time
#: slipping (-1 never); after the start command: time with |force| at the rim above the rated
#: force [s], time at the speed loop's torque limit [s], the force squared integrated [N^2 s]
#: and the time it was integrated over [s] (until the belt is at rest after the stop: the RMS
#: force, :mod:`beltstudy.engine.drives`); when the largest force was [s] and the part of the
#: time above the rated force after the stop command [s] (the overload's phase).
DRIVE_RESULT = np.dtype([
    ("fmax", np.float64), ("pmax", np.float64), ("slip_min", np.float64),
    ("slip_min_t", np.float64), ("slip_s", np.float64), ("slip_m", np.float64),
    ("slip_first", np.float64), ("slip_last", np.float64),
    ("over_s", np.float64), ("lim_s", np.float64), ("f2_int", np.float64),
    ("rms_s", np.float64), ("fmax_t", np.float64), ("over_stop_s", np.float64)], align=True)

#: Per shaft: time slipping [s], belt length slipped [m], first and last time (-1 never).
SHAFT_SLIP = np.dtype([
    ("slip_s", np.float64), ("slip_m", np.float64), ("first", np.float64),
    ("last", np.float64)], align=True)

#: Key points per record: SPEC section 5 (time, master shaft and tail speed, drive force, head
#: in and out, tail and take-up tension, take-up position, lowest and highest tension), then
#: the mean and reference speed, brake force, drive power, largest |speed|, the slack and the
#: holdback's force.
RECORD = np.dtype([
    ("t", np.float64), ("v_drive", np.float64), ("v_tail", np.float64), ("f_drive", np.float64),
    ("t_head_in", np.float64), ("t_head_out", np.float64), ("t_tail", np.float64),
    ("t_takeup", np.float64), ("x_tu", np.float64), ("t_min", np.float64),
    ("t_max", np.float64), ("v_mean", np.float64), ("f_brake", np.float64), ("v_ref", np.float64),
    ("p_drive", np.float64), ("v_abs", np.float64), ("slack_m", np.float64),
    ("f_holdback", np.float64)], align=True)

#: Per drive and record: force at the rim (drive side) [N], shaft speed at the rim [m/s],
#: force the pulley passes to the belt [N], the motor's speed at the rim [m/s] (behind a fluid
#: coupling its own, else the shaft's).
DRIVE_RECORD = np.dtype([("f", np.float64), ("v", np.float64), ("ft", np.float64),
                         ("vm", np.float64)], align=True)


class Out(NamedTuple):
    """Outputs: records (:data:`RECORD`; probe tensions and speeds; :data:`DRIVE_RECORD` per
    drive), the surface (times with tensions, speeds), the envelopes of the current segment
    with their times, the finished segments (per segment: max, its time, min, its time per
    spring; start and end time), the per-drive results (:data:`DRIVE_RESULT`), the per-shaft
    slip (:data:`SHAFT_SLIP`) and the run's scalars (:data:`RUN`, one record)."""

    rec: np.ndarray
    rec_t: np.ndarray
    rec_v: np.ndarray
    rec_d: np.ndarray
    surf_t: np.ndarray
    surf_v: np.ndarray
    t_max: np.ndarray
    t_min: np.ndarray
    t_max_t: np.ndarray
    t_min_t: np.ndarray
    seg_env: np.ndarray
    seg_time: np.ndarray
    drv: np.ndarray
    shs: np.ndarray
    run: np.ndarray


class Work(NamedTuple):
    """Scratch arrays of the block solve (length BLOCK_MAX), of the resistance pass and the
    springs' marks for more Newton steps (length n), the envelope snapshots of the last record
    (length n); per block row the slip a shaft left in this step when its speed crossed the
    belt's (``crossed``: its direction, twice it once the shaft slides on at the belt's speed;
    0 none)."""

    dg: np.ndarray
    lo: np.ndarray
    up: np.ndarray
    cl: np.ndarray
    rw: np.ndarray
    rhs: np.ndarray
    crhs: np.ndarray
    cuc: np.ndarray
    kd: np.ndarray
    kc: np.ndarray
    kr: np.ndarray
    wd: np.ndarray
    wl: np.ndarray
    wu: np.ndarray
    wc: np.ndarray
    wr: np.ndarray
    sol: np.ndarray
    sol2: np.ndarray
    ucoef: np.ndarray
    bA: np.ndarray
    bB: np.ndarray
    v_old: np.ndarray
    rpos: np.ndarray
    fexp: np.ndarray
    fz: np.ndarray
    stuck: np.ndarray
    bdir: np.ndarray
    bforce: np.ndarray
    c_lo: np.ndarray
    c_hi: np.ndarray
    fixed: np.ndarray
    fixv: np.ndarray
    shk: np.ndarray
    vsn: np.ndarray
    Ac: np.ndarray
    r0: np.ndarray
    phi: np.ndarray
    lnv: np.ndarray
    lnphi: np.ndarray
    t_max_snap: np.ndarray
    t_min_snap: np.ndarray
    more: np.ndarray
    crossed: np.ndarray
