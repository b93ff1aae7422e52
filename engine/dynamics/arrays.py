"""The kernel's arguments, grouped by what they describe (plain float64 / int64 arrays).

Named tuples that numba compiles as structs: the kernel is called by keyword with one of each
(:func:`beltstudy.engine.dynamics.kernel.run_cycle`), and its passes take the groups they need. Built
by :func:`beltstudy.engine.dynamics.simulate.prepare` from a :class:`~beltstudy.engine.dynamics.model.System`.
Units SI; per-element arrays have length n, per-spring arrays length n (spring j joins
elements j and j + 1).
"""

from __future__ import annotations

from typing import NamedTuple

import numpy as np

__all__ = ["Nodes", "Law", "Lin", "Springs", "Blocks", "Shafts", "Drives", "Brakes", "State", "Out",
           "Work"]


class Nodes(NamedTuple):
    """Belt elements: moving mass [kg], dt / mass [s/kg], gravity along the belt [N], weight
    of the mean speed [kg], sag weight and sag cap over the reference sag [N, -]."""

    mass: np.ndarray
    hm: np.ndarray
    gravity: np.ndarray
    w_mean: np.ndarray
    sw_ref: np.ndarray
    hsm_ref: np.ndarray


class Law(NamedTuple):
    """The resistance law (``beltstudy.engine.law``), terms merged by exponents, with exponent codes
    and the elements of sparse terms."""

    coef: np.ndarray
    pvc: np.ndarray
    pvv: np.ndarray
    psc: np.ndarray
    psv: np.ndarray
    t_sparse: np.ndarray
    t_ptr: np.ndarray
    t_idx: np.ndarray


class Lin(NamedTuple):
    """The resistance law's expansion per element (:mod:`beltstudy.engine.dynamics.linlaw`): ``R0 = k +
    gu u + guu u^2 + gx T + gxx T^2 + gux u T`` [N] (``u = |v|``, T the mean tension); the
    window round the expansion point as bounds on the speed (``ulo``, ``uhi`` [m/s]) and the
    mean tension (``tlo``, ``thi`` [N]); all float32.

    The law for its element-wise evaluation (:func:`beltstudy.engine.dynamics.passes.law_refresh`): per
    element a row of 16 (``erow``): sag weight and sag cap over the reference sag, the tension
    below which the sag ratio is at its cap [N], the window sizes (relative speed, creep
    [m/s], relative tension; ``linlaw.BIG`` where no term depends on it), two zeros, the
    coefficients padded to ``K_LIN`` terms with zero ones; each term's speed and sag factor
    rows (``rs``, ``rq``); the weights of the sums over the terms (``wk``, rows 1, p, p (p -
    1), q, q (q + 1), p q); the speed and sag exponents taken by exp and log (``upow``,
    ``qpow``) and ``npow`` = their numbers and whether a sag exponent is 0.5 or 1.5. Scratch: the
    flags of the elements outside their windows (``flag``, padded to whole words, ``flag64``
    its view by words), their indices (room for padding), the gathered, factor and output
    rows of the evaluation (``sg``, ``sf``, ``so``)."""

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
    """Springs: dt / length, Ernst constant times EB, floor tension, strain tension at the floor
    (EB times the chord strain there) and floor modulus over EB,
    mesh viscosity per strain increment [N], carriage coupling (1 beside the gravity take-up),
    length [m], chord strain at the running tension (the reference of the belt length a slack
    span gathers); free element and spring ranges ([start, end) rows)."""

    dl: np.ndarray
    a_eb: np.ndarray
    t_floor: np.ndarray
    s_floor: np.ndarray
    kfl_eb: np.ndarray
    kvs: np.ndarray
    car_ind: np.ndarray
    len_m: np.ndarray
    eps_run: np.ndarray
    seg_node: np.ndarray
    seg_spring: np.ndarray


class Blocks(NamedTuple):
    """Implicit blocks: element ranges ``ptr``, their elements, carriage flag, each block
    element's left spring and mass / dt; the shaft of every element (-1 none)."""

    ptr: np.ndarray
    nodes: np.ndarray
    car: np.ndarray
    left: np.ndarray
    mdt: np.ndarray
    node_shaft: np.ndarray


class Shafts(NamedTuple):
    """Pulley shafts (every drive pulley and braked or holdback pulley): element, reduced
    mass [kg], e^(mu theta) - 1 static and sliding, drive (-1 none), holdback flag; state:
    speed at the rim [m/s], slip direction (0 stuck, +1 shaft faster, -1 belt faster); per
    step: brake force on the shaft [N] and the brake force it gave [N]."""

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
    """Drives in file order: shaft, share, force limit [N] (and the one in force this step),
    rated force [N], control and
    coupling codes, motor curve (points per drive), fill time, motor mass [kg], trip time;
    per step: force law mode (0 linear ``f0 + f1 v``, 1 share of the speed loop's output,
    2 imposed shaft speed), ``f0``, ``f1``, saturation; coupling linearisation ``(P, D, c_s)``
    and the motor speed; outputs: force at the rim and force passed to the belt."""

    shaft: np.ndarray
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
    lin_p: np.ndarray
    lin_d: np.ndarray
    lin_cs: np.ndarray
    vm: np.ndarray
    force: np.ndarray
    ft: np.ndarray
    f_trip: np.ndarray


class Brakes(NamedTuple):
    """Brakes: shaft, full force [N], delay and ramp [s], force curve (points per brake),
    hold flag; state: command time (-1 not commanded), released flag."""

    shaft: np.ndarray
    force: np.ndarray
    delay: np.ndarray
    ramp: np.ndarray
    curve_t: np.ndarray
    curve_f: np.ndarray
    curve_n: np.ndarray
    hold: np.ndarray
    t_cmd: np.ndarray
    released: np.ndarray


class State(NamedTuple):
    """Belt state: velocity [m/s], elastic tension, strain tension (EB times the chord strain),
    arm and total tension [N]; ``misc`` = take-up
    position [m] and speed [m/s], speed-loop integrator [N], holding force [N]."""

    v: np.ndarray
    te: np.ndarray
    ts: np.ndarray
    td: np.ndarray
    tt: np.ndarray
    misc: np.ndarray


class Out(NamedTuple):
    """Outputs: records (key points, probes, per drive), surface, envelopes of the current
    segment and the finished segments, per-drive results, per-shaft slip (time [s], belt
    length [m], first and last time [s]) and run scalars."""

    rec: np.ndarray
    rec_t: np.ndarray
    rec_v: np.ndarray
    rec_d: np.ndarray
    surf_t: np.ndarray
    surf_v: np.ndarray
    probes: np.ndarray
    surf_idx: np.ndarray
    t_max: np.ndarray
    t_min: np.ndarray
    t_max_t: np.ndarray
    t_min_t: np.ndarray
    seg_env: np.ndarray
    seg_time: np.ndarray
    drv: np.ndarray
    shs: np.ndarray
    res: np.ndarray


class Work(NamedTuple):
    """Scratch arrays of the block solve (length BLOCK_MAX), of the resistance pass and the
    springs' marks for more Newton steps (length n)."""

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
