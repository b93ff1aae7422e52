"""Assemble the transient model once per conveyor and scenario (PHYSICS section 5).

The loop's elements are the masses, the element boundaries are the springs: spring ``j``
joins element ``j`` and ``j + 1`` (cyclic), has length ``(dx_j + dx_{j+1}) / 2`` and carries
the boundary tension ``T[j]`` of statics. Everything the kernel needs is computed here as
plain float64 arrays (:class:`System`); the kernel and the numpy reference only read them.

Design decisions (documented in ``docs/dynamics.md``):

* **Masses**: ``M_j = (m'_G + m'_L + m'_R) dx_j``; drive pulley elements add the drive
  inertia ``J (2 / D)^2``; other pulley elements add an estimate of the pulley's own
  reduced mass (:func:`pulley_reduced_mass_kg`, override with
  ``DynamicsOptions.pulley_mass_kg``).
* **Belt segments**: elastic tension advanced with the Ernst *tangent* modulus
  ``EB_eq = EB / (1 + (w S)^2 EB / (12 T^3))`` (the chord law ``eps = T / EB - (w S)^2 /
  (24 T^2)`` integrated incrementally); below the tension where the sag ratio reaches the
  law's cap ``hs_max`` the modulus is held constant, and a belt never pushes (slack strain
  is remembered so a slack span must first be taken up before it pulls again).
* **Damping**: a standard linear solid. The viscous part of the Kelvin-Voigt element is a
  dashpot ``C'`` in series with a stiff spring ``EB / mu``: at low frequencies it is the
  Kelvin-Voigt damper, and its force is advanced by the exact exponential of its relaxation
  time ``tau = mu C' / EB``, so the step stays proportional to ``dx / c`` on any mesh (an
  explicit Kelvin-Voigt term forces ``dt ~ dx^2``: see ``benchmarks/bench_dynamics.py``).
  ``C'`` gives the loop's lowest mode (estimated ``pi / (2 t_loop)``) the modal damping ratio
  ``damping_ratio``. ``damping="kv"`` gives the plain explicit Kelvin-Voigt term (with its
  smaller step), ``damping="off"`` none.
* **Implicit blocks**: the springs on both sides of every pulley element are solved
  implicitly together with the pulley and its neighbouring elements (and the take-up
  carriage): short springs round light pulleys would otherwise set the step.
* **Step**: ``dt = dt_safety x 2 / omega_max`` with the per-element (Gershgorin) bound
  ``omega_max^2 = max_j 2 (K_{j-1} + K_j) / M_j`` over the explicit springs,
  ``K = EB (1 + 1/mu) / len`` unsoftened; for a uniform chain ``2 / omega_max = dx / c``.
* **At rest**: the belt is held by its brakes (or the master drive when it has none) with
  the at-rest tensions (take-up plus gravity, no resistance); a fixed take-up's at-rest
  level keeps the loop length of statics' running state.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from engine.conveyor import Conveyor, InputError, Scenario
from engine.dynamics import profiles
from engine.law import ResistanceLaw
from engine.loop import G, Loop
from engine.statics import rest_hold_element, rest_walk

__all__ = [
    "DynamicsOptions",
    "System",
    "build_system",
    "pulley_reduced_mass_kg",
    "stability_limit_s",
    "chord_strain",
    "check_scenario",
    "implicit_blocks",
    "brake_force_auto",
    "COAST",
    "BRAKE",
    "CONTROLLED",
    "RELATIVE",
    "SUPPORT",
]

COAST, BRAKE, CONTROLLED = 0, 1, 2
RELATIVE, SUPPORT = 0, 1
STOP_CODES = {"coast": COAST, "brake": BRAKE, "controlled": CONTROLLED}
START_CODES = {"s-curve": profiles.S_CURVE, "linear": profiles.LINEAR,
               "torque": profiles.TORQUE}

#: Steel density for the pulley estimate [kg/m3].
STEEL_KG_M3 = 7850.0


@dataclass(frozen=True)
class DynamicsOptions:
    """Model and numerical settings of the transient engine (defaults are the engine's).

    Attributes
    ----------
    damping : str
        ``"sls"`` (default: Kelvin-Voigt damper relaxed as a standard linear solid, exact
        exponential update), ``"kv"`` (plain explicit Kelvin-Voigt) or ``"off"``.
    damping_ratio : float
        Modal damping ratio of the loop's lowest mode [-] (PHYSICS 5: a few percent), taken
        as the quarter-wave mode over the whole loop, ``pi / (2 t_loop)``.
    glassy_ratio : float
        ``mu``: the series spring of the damper is ``EB / mu`` [-]; the high-frequency
        stiffness is ``EB (1 + 1 / mu)``. Lowered automatically to ``0.2 / damping_ratio``
        when needed (the SLS cannot reach a damping ratio above ``1 / (4 mu)``).
    ernst : bool
        Sag-dependent tangent stiffness (on by default, PHYSICS 5).
    resistances : bool
        Friction model resistances on (switch off only for verification runs).
    gravity : bool
        Gravity along the belt on (verification runs only).
    v_eps_m_s : float
        Regularisation speed of the resistances: ``R = R0 clip(v / v_eps, -1, 1)`` [m/s].
    dt_safety : float
        Automatic step as a fraction of the stability limit (0.5: half the limit).
    controller_bandwidth_rad_s : float
        Rigid-body bandwidth ``omega_c`` of the PI speed controller [rad/s], capped at half
        the loop's fundamental ``2 pi / t_loop``: ``Kp = 2 omega_c M``, ``Ki = omega_c^2 M``
        with M the loop's moving mass. A rigid-body feedforward ``M a_ref + (Te - sum G)``
        carries the known forces.
    pre_rest_s, post_rest_s : float
        Rest before the start command and after the belt has stopped [s]; post-rest
        ``None`` = max(5 s, one wave loop time).
    pulley_mass_kg : float or None
        Reduced mass of each non-drive pulley [kg]; None = :func:`pulley_reduced_mass_kg`.
    force_start_n : float or None
        Open-loop constant drive force during the start and run [N] (verification).
    probes : int
        Number of springs recorded at ``record_dt_s`` round the loop (Fig. 4 traces).
    surface_points, surface_samples : int
        Size of the tension/velocity surface: at most this many springs and time samples.
    """

    damping: str = "sls"
    damping_ratio: float = 0.05
    glassy_ratio: float = 4.0
    ernst: bool = True
    resistances: bool = True
    gravity: bool = True
    v_eps_m_s: float = 0.01
    dt_safety: float = 0.5
    controller_bandwidth_rad_s: float = 0.5
    pre_rest_s: float = 2.0
    post_rest_s: float | None = None
    pulley_mass_kg: float | None = None
    force_start_n: float | None = None
    probes: int = 8
    surface_points: int = 200
    surface_samples: int = 300


@dataclass(eq=False)
class System:
    """Everything the kernel reads, as plain arrays and numbers. SI units throughout.

    Node (element) arrays have length n; spring arrays have length n, spring j joining
    element j and j + 1 (cyclic).
    """

    n: int
    i_head: int
    i_tail: int
    i_takeup: int
    strand: np.ndarray  # int8 strand codes of the loop (engine.loop)
    # nodes
    mass_kg: np.ndarray  # moving mass incl. drive / pulley inertia
    belt_mass_kg: np.ndarray  # (m'_G + m'_L + m'_R) dx: weights of the mean speed
    gravity_n: np.ndarray  # (m'_G + m'_L) g dx sin(a)
    sag_w_n: np.ndarray
    coef: np.ndarray  # (K, n) merged resistance terms [N]
    pv: np.ndarray  # (K,)
    ps: np.ndarray  # (K,)
    hs_ref: float
    hs_max: float
    # springs
    len_m: np.ndarray
    stiffness_n: float  # EB
    a_ernst: np.ndarray  # (w S)^2 / 12 per spring [N^2]
    t_floor_n: np.ndarray  # tangent modulus held constant below this tension
    k_floor_n: np.ndarray  # tangent modulus at the floor [N]
    carriage_coupling: np.ndarray  # 1 on the two springs beside the gravity take-up, else 0
    implicit: np.ndarray  # bool per spring: solved implicitly (beside a pulley)
    blocks: list  # element indices of each implicit block
    # damping
    damping: str
    c_visc_ns: float  # C' [N s] (tension per unit strain rate)
    tau_s: float  # relaxation time of the damper [s] (0 for "kv")
    glassy_factor: float  # high-frequency stiffness / EB
    # initial state
    tension_rest_n: np.ndarray
    hold_node: int
    hold_force_n: float
    # step
    dt_s: float
    dt_limit_s: float
    wave_loop_time_s: float
    wave_speed_m_s: np.ndarray  # per element, unsoftened
    # drives (slots: one per drive element; slot 0 is the master)
    drive_node: np.ndarray
    drive_share: np.ndarray
    drive_limit_n: np.ndarray
    drive_euler: np.ndarray  # e^{mu theta}
    drive_rated_n: np.ndarray
    kp: float
    ki: float
    v_ff_m_s: float  # reference speed at which the resistance feedforward is complete
    total_mass_kg: float
    # brakes (slots)
    brake_node: np.ndarray
    brake_force_n: np.ndarray
    brake_delay_s: np.ndarray
    holdback_node: int
    # take-up
    takeup_gravity: bool
    takeup_weight_n: float
    takeup_inertia_kg: float
    takeup_lo_m: float
    takeup_hi_m: float
    takeup_run_m: float
    # scenario
    v_design: float
    v_eps: float
    start_control: int
    start_s: float
    run_s: float
    stop_mode: int
    stop_s: float
    formulation: int
    force_start_n: float
    pre_rest_s: float
    post_rest_s: float
    stop_max_s: float
    record_dt_s: float
    surface_dt_s: float
    probe_springs: np.ndarray
    surface_springs: np.ndarray
    steady_tension_n: np.ndarray
    te_n: float
    dx_m: np.ndarray
    s_end_m: np.ndarray  # position of each spring (element end) from the tail [m]
    notes: list[str] = field(default_factory=list)  # informational
    warnings: list[str] = field(default_factory=list)  # limits crossed before the start

    @property
    def stop_command_s(self) -> float:
        return self.pre_rest_s + self.start_s + self.run_s

    @property
    def t_max_s(self) -> float:
        return self.stop_command_s + self.stop_max_s + self.post_rest_s



# --------------------------------------------------------------------------------------
# Helpers


def pulley_reduced_mass_kg(diameter_m: float, belt_width_m: float) -> float:
    """Estimated reduced mass of a non-drive pulley at the belt line [kg].

    A welded drum pulley is modelled as a thin steel shell of diameter D, face B + 0.2 m and
    wall 12 mm + 1 % of D, plus 30 % for the end discs (a thin shell has J (2/D)^2 = m).
    An estimate, not a catalogue value: give ``DynamicsOptions.pulley_mass_kg`` when the
    pulley data are known.

    Parameters
    ----------
    diameter_m : float
        Pulley diameter D [m].
    belt_width_m : float
        Belt width B [m].
    """
    wall = 0.012 + 0.01 * diameter_m
    return 1.3 * STEEL_KG_M3 * math.pi * diameter_m * (belt_width_m + 0.2) * wall


def chord_strain(tension_n, a_ernst, stiffness_n, t_floor_n, k_floor_n):
    """Elastic strain of a span from the Ernst chord law, up to a constant [-].

    ``eps(T) = T / EB - a / (2 T^2)`` with ``a = (w S)^2 / 12`` (so ``d eps / dT =
    1 / EB_eq``); below ``t_floor`` the tangent modulus is held at ``k_floor``.
    """
    T = np.asarray(tension_n, dtype=np.float64)
    tf = np.maximum(t_floor_n, 1e-300)
    e_floor = tf / stiffness_n - a_ernst / (2.0 * tf * tf)
    Tc = np.maximum(T, tf)
    e = Tc / stiffness_n - a_ernst / (2.0 * Tc * Tc)
    return np.where(T >= tf, e, e_floor - (tf - T) / k_floor_n)


def _merge_law(law: ResistanceLaw) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Merge terms with the same (pv, ps) exponents: the kernel evaluates each pair once."""
    keys: dict[tuple[float, float], np.ndarray] = {}
    for k in range(law.coef.shape[0]):
        key = (float(law.pv[k]), float(law.ps[k]))
        keys[key] = keys.get(key, 0.0) + law.coef[k]
    items = [(k, c) for k, c in keys.items() if np.any(c != 0.0)] or [((0.0, 0.0), law.coef[0] * 0)]
    coef = np.ascontiguousarray(np.vstack([c for _, c in items]), dtype=np.float64)
    pv = np.array([k[0] for k, _ in items], dtype=np.float64)
    ps = np.array([k[1] for k, _ in items], dtype=np.float64)
    return coef, pv, ps


def implicit_blocks(strand: np.ndarray) -> tuple[np.ndarray, list[list[int]]]:
    """Springs taken implicitly and the blocks of elements they join.

    Spring j (between elements j and j + 1) is implicit when either element is a pulley
    (strand code >= 2). A block is a run of consecutive implicit springs with the elements
    they join, in loop order; the tail pulley is the last element, so the tail block wraps
    (``[n - 2, n - 1, 0]``).

    Returns
    -------
    implicit : ndarray of bool, shape (n,)
    blocks : list of list of int
        Element indices of each block, consecutive along the loop.
    """
    n = len(strand)
    pulley = np.asarray(strand) >= 2
    implicit = pulley | np.roll(pulley, -1)
    if implicit.all():
        raise InputError("scenario.elements: too few elements for the transient model (every "
                         "spring touches a pulley); use at least 8")
    start = int(np.flatnonzero(~implicit)[0])  # begin the scan on an explicit spring
    blocks: list[list[int]] = []
    current: list[int] = []
    for k in range(1, n + 1):
        j = (start + k) % n
        if implicit[j]:
            if not current:
                current = [j]
            current.append((j + 1) % n)
        elif current:
            blocks.append(current)
            current = []
    if current:
        blocks.append(current)
    return implicit, blocks


def stability_limit_s(mass_kg, len_m, stiffness_n, glassy_factor=1.0, implicit=None,
                      c_visc_ns=0.0) -> float:
    """Step limit ``2 / omega_max`` of the explicit part of the scheme [s].

    ``omega_max^2 = max_j 2 (K_{j-1} + K_j) / M_j`` over the explicit springs (``K =
    EB glassy_factor / len``, unsoftened; a Gershgorin bound, exactly ``dx / c`` for a uniform
    chain). Springs marked ``implicit`` (beside pulleys) are solved implicitly and do not
    limit the step. With ``c_visc_ns > 0`` the explicit Kelvin-Voigt limit per element,
    ``(2 / omega_j) (sqrt(1 + zeta_j^2) - zeta_j)``, ``zeta_j = (c_{j-1} + c_j) / (M_j omega_j)``
    with ``c = C' / len``.
    """
    n = len(mass_kg)
    exp_ = np.ones(n) if implicit is None else (~np.asarray(implicit)).astype(float)
    K = stiffness_n * glassy_factor / len_m * exp_
    Ksum = K + np.roll(K, 1)
    w = np.sqrt(2.0 * Ksum / mass_kg)
    ok = w > 0.0
    if not ok.any():
        return math.inf
    w = w[ok]
    if c_visc_ns > 0.0:
        c = c_visc_ns / len_m * exp_
        zeta = ((c + np.roll(c, 1))[ok]) / (mass_kg[ok] * w)
        lim = (2.0 / w) * (np.sqrt(1.0 + zeta * zeta) - zeta)
    else:
        lim = 2.0 / w
    return float(lim.min())


def check_scenario(scn: Scenario, conv: Conveyor, opts: DynamicsOptions | None = None) -> None:
    """Reject impossible scenarios before any computing; messages name the field."""
    opts = opts or DynamicsOptions()
    for name, val in (("scenario.start.time_s", scn.start.time_s),
                      ("scenario.stop.time_s", scn.stop.time_s),
                      ("scenario.record_dt_s", scn.record_dt_s)):
        if not (val > 0.0 and math.isfinite(val)):
            raise InputError(f"{name}: must be a positive time in seconds (got {val!r})")
    if not (scn.run_s >= 0.0 and math.isfinite(scn.run_s)):
        raise InputError(f"scenario.run_s: must be zero or a positive time in seconds "
                         f"(got {scn.run_s!r})")
    if scn.dt_s != "auto" and not (float(scn.dt_s) > 0.0):
        raise InputError(f"scenario.dt_s: must be 'auto' or a positive step (got {scn.dt_s!r})")
    if scn.stop.mode == "brake":
        if not conv.brakes:
            raise InputError("scenario.stop.mode: 'brake' needs brakes, and this conveyor has "
                             "none (conveyor 'brakes' is empty); use 'coast' or 'controlled', "
                             "or add a brake")
        delays = [b.delay_s for b in conv.brakes if b.force_kn == "auto"]
        if delays and scn.stop.time_s <= max(delays):
            raise InputError(
                f"scenario.stop.time_s: {scn.stop.time_s:g} s is not longer than the brake "
                f"delay ({max(delays):g} s, brakes[].delay_s); an auto-sized brake cannot stop "
                "the belt in that time")
    if scn.formulation == "support" and scn.start.control == "torque":
        raise InputError("scenario.start.control: 'torque' needs formulation 'relative' (the "
                         "moving-support formulation imposes the drive pulley's motion)")
    if opts.damping not in ("sls", "kv", "off"):
        raise InputError(f"damping: unknown '{opts.damping}'; valid: sls, kv, off")


# --------------------------------------------------------------------------------------


def build_system(conv: Conveyor, scn: Scenario, steady, options: DynamicsOptions | None = None
                 ) -> System:
    """Build the transient model from a steady solution.

    Parameters
    ----------
    conv : Conveyor
    scn : Scenario
    steady : SteadyResult-like
        Needs ``loop``, ``law``, ``tension_n`` (running boundary tensions [N]),
        ``drive_force_n`` (per element [N]) and ``takeup_mass_kg`` (gravity take-up [kg]).
    options : DynamicsOptions, optional

    Raises
    ------
    InputError
        Impossible scenario (names the field): brake stop without brakes, fixed step above
        the stability limit, torque start with the support formulation, non-positive times.
    """
    opts = options or DynamicsOptions()
    check_scenario(scn, conv, opts)
    loop: Loop = steady.loop
    law: ResistanceLaw = steady.law
    n = loop.n
    notes: list[str] = []
    v_d = float(loop.speed_m_s)
    EB = float(loop.belt.stiffness_n)
    dx = loop.dx_m
    nxt = np.roll(np.arange(n), -1)

    # ---- masses
    belt_mass = loop.mass_kg.copy()
    mass = belt_mass.copy()
    drive_inertia = np.zeros(n)
    drive_nodes: dict[int, list] = {}
    for d in conv.drives:
        node = loop.i_head if d.position == "head" else loop.i_tail
        drive_nodes.setdefault(node, []).append(d)
        drive_inertia[node] += d.inertia_kg_m2 * (2.0 / d.pulley_diameter_m) ** 2
    mass += drive_inertia
    for node in sorted({loop.i_head, loop.i_tail, loop.i_takeup}):
        if node in drive_nodes:
            continue  # the drive's inertia already includes its pulley
        if opts.pulley_mass_kg is not None:
            mass[node] += float(opts.pulley_mass_kg)
        else:
            diam = 2.0 * dx[node] / math.pi  # pulley elements are half a circumference
            mass[node] += pulley_reduced_mass_kg(diam, loop.belt.width_m)
    total_mass = float(mass.sum())

    # ---- forces
    gravity = loop.gravity_n.copy() if opts.gravity else np.zeros(n)
    coef, pv, ps = _merge_law(law)
    if not opts.resistances:
        coef = np.zeros((1, n))
        pv = np.zeros(1)
        ps = np.zeros(1)

    # ---- springs
    len_m = 0.5 * (dx + dx[nxt])
    wS2 = (8.0 * loop.sag_w_n) ** 2  # (w S)^2 per element [N^2]
    a_el = (dx * wS2 + dx[nxt] * wS2[nxt]) / (dx + dx[nxt]) / 12.0
    if not opts.ernst:
        a_el = np.zeros(n)
    t_floor = np.maximum(np.sqrt(12.0 * a_el) / (8.0 * law.hs_max), 1.0)
    k_floor = EB * t_floor**3 / (t_floor**3 + a_el * EB)
    carriage = np.zeros(n)
    gravity_tu = conv.takeup.type == "gravity"
    itu = loop.i_takeup
    if gravity_tu:
        carriage[itu - 1] = 1.0
        carriage[itu] = 1.0

    # ---- waves
    rho = (loop.mG_kg_m + loop.mL_kg_m + loop.mR_kg_m)
    c_wave = np.sqrt(EB / rho)
    t_loop = float(np.sum(dx / c_wave))

    # ---- damping (C' so that the loop's lowest mode has damping_ratio). The lowest mode is
    # estimated as the quarter wave over the whole loop, pi / (2 t_loop): the master drive
    # pins the belt and a gravity take-up is a free end (the closed ring's 2 pi / t_loop is
    # four times higher); Kelvin-Voigt-like damping falls with frequency, so the ratio is
    # set where it is smallest.
    zeta = float(opts.damping_ratio)
    w1 = 0.5 * math.pi / t_loop
    mu = float(opts.glassy_ratio)
    if opts.damping == "off" or zeta <= 0.0:
        damping, c_visc, tau, glassy = "off", 0.0, 0.0, 1.0
    elif opts.damping == "kv":
        damping, c_visc, tau, glassy = "kv", 2.0 * zeta * EB / w1, 0.0, 1.0
    else:
        if mu * zeta > 0.2:
            mu = 0.2 / zeta
            notes.append(f"glassy_ratio lowered to {mu:.3g} for damping_ratio {zeta:g}")
        # zeta = (y / 2) / (1 + mu^2 y^2), y = C' w1 / EB; the smaller root
        y = (0.5 - math.sqrt(0.25 - 4.0 * mu * mu * zeta * zeta)) / (2.0 * mu * mu * zeta)
        damping, c_visc = "sls", y * EB / w1
        tau = mu * c_visc / EB
        glassy = 1.0 + 1.0 / mu

    # ---- take-up
    tu_weight = 0.0
    tu_inertia = 1.0
    if gravity_tu:
        m_tu = float(steady.takeup_mass_kg)
        tu_weight = m_tu * G
        tu_inertia = m_tu + float(conv.takeup.carriage_mass_kg)

    # ---- step
    implicit, blocks = implicit_blocks(loop.strand)
    dt_lim = stability_limit_s(mass, len_m, EB, glassy, implicit,
                               c_visc if damping == "kv" else 0.0)
    if scn.dt_s == "auto":
        dt = opts.dt_safety * dt_lim
    else:
        dt = float(scn.dt_s)
        if dt > dt_lim:
            raise InputError(
                f"scenario.dt_s: {dt:g} s is above the stability limit {dt_lim:.4g} s of this "
                f"model ({n} elements, shortest spring {len_m.min():.3g} m); use 'auto' or a "
                f"step below {dt_lim:.4g} s")

    # ---- drives
    T_run = np.asarray(steady.tension_n, dtype=np.float64)
    R_run = law.evaluate(v_d, 0.5 * (np.roll(T_run, 1) + T_run)) if law.tension_dependent \
        else law.evaluate(v_d)
    te = float(np.sum(steady.drive_force_n))
    r_sum = float(np.sum(R_run))
    slots = sorted(drive_nodes.items(), key=lambda kv: -sum(d.share for d in kv[1]))
    d_node, d_share, d_lim, d_eut, d_rated = [], [], [], [], []
    for node, ds in slots:
        share = sum(d.share for d in ds)
        rated = 0.0
        lim = 0.0
        for d in ds:
            if d.rated_power_kw is not None:
                r = d.rated_power_kw * 1e3 / v_d
            else:
                r = 1.25 * d.share * max(abs(te), r_sum)
            rated += r
            lim += d.torque_limit * r
        d_node.append(node)
        d_share.append(share)
        d_lim.append(lim)
        d_rated.append(rated)
        d_eut.append(math.exp(sum(d.friction * math.radians(d.wrap_deg) for d in ds)))
    # the speed loop stays below the loop's lowest elastic mode (a rigid-body design above
    # it would let the drive ring against the belt)
    wc = min(float(opts.controller_bandwidth_rad_s), 0.5 * w1)
    # the feedforward of the running resistance ramps in with the reference speed, reaching
    # full when the reference has run for one wave loop time (the time the motion needs to
    # spread round the belt)
    v_ff, _ = profiles.start_reference(START_CODES[scn.start.control],
                                       min(t_loop, float(scn.start.time_s)),
                                       float(scn.start.time_s), v_d)
    v_ff = max(float(v_ff), float(opts.v_eps_m_s))
    kp = 2.0 * wc * total_mass
    ki = wc * wc * total_mass

    # ---- hold at rest and the at-rest tensions: the brakes hold a stopped belt when it has
    # any (a friction drive could not hold a loaded incline or decline by itself), else the
    # master drive
    hold = rest_hold_element(conv, loop)
    assert conv.brakes or hold == d_node[0]
    hold_force = float(gravity.sum())
    T_rest = rest_walk(loop, hold, gravity)  # relative to T[itu - 1] = 0; fix the level
    if gravity_tu:
        # the carriage carries both strands: T_in + T_out = m g (the element holding the belt
        # at rest may be the take-up pulley itself)
        T_rest += 0.5 * (tu_weight - T_rest[itu - 1] - T_rest[itu])
    else:
        T_rest += _fixed_takeup_level(T_rest, T_run, len_m, a_el, EB, t_floor, k_floor)
    warns: list[str] = []
    if T_rest.min() < 0.0:
        k = int(np.argmin(T_rest))
        warns.append(f"held at rest the belt is slack at {loop.s_m[k] + dx[k]:.0f} m (the "
                     f"take-up leaves {T_rest[k] / 1e3:.3g} kN there): raise the take-up "
                     "tension")

    # carriage travel: centred between the rest position (x = 0) and the running one (the
    # belt stretches while running and the counterweight drops to take up the extra length:
    # x grows by half the stretch, two strands), the rest position always inside the travel
    travel = conv.takeup.travel_m if conv.takeup.travel_m is not None else 0.015 * loop.length_m
    x_run = 0.0
    if gravity_tu:
        eps_rest = chord_strain(np.maximum(T_rest, 0.0), a_el, EB, t_floor, k_floor)
        eps_run = chord_strain(T_run, a_el, EB, t_floor, k_floor)
        x_run = 0.5 * float(np.sum(len_m * (eps_run - eps_rest)))
    mid = 0.5 * min(max(x_run, -travel), travel)
    tu_lo, tu_hi = mid - 0.5 * travel, mid + 0.5 * travel

    # ---- brakes
    b_node, b_force, b_delay = [], [], []
    stop_mode = STOP_CODES[scn.stop.mode]
    if conv.brakes:
        auto = [b for b in conv.brakes if b.force_kn == "auto"]
        fixed_total = sum(b.force_kn * 1e3 for b in conv.brakes if b.force_kn != "auto")
        auto_each = 0.0
        if auto:
            delay = max(b.delay_s for b in auto)
            f_total = brake_force_auto(total_mass, v_d, te, float(gravity.sum()),
                                       scn.stop.time_s, delay)
            auto_each = max(f_total - fixed_total, 0.0) / len(auto)
        for b in conv.brakes:
            b_node.append(loop.i_head if b.position == "head" else loop.i_tail)
            b_force.append(auto_each if b.force_kn == "auto" else b.force_kn * 1e3)
            b_delay.append(b.delay_s)
    holdback = loop.i_head if conv.holdback else -1

    # ---- durations
    post = opts.post_rest_s if opts.post_rest_s is not None else max(5.0, t_loop)
    coast_est = total_mass * v_d / te if te > 0 else scn.stop.time_s
    stop_max = 3.0 * max(scn.stop.time_s, coast_est) + 2.0 * t_loop + 10.0
    start_s = float(scn.start.time_s)
    t_total = opts.pre_rest_s + start_s + scn.run_s + stop_max + post
    steps = t_total / dt
    if steps * n > 5e10:
        raise InputError(
            f"scenario.dt_s / scenario.elements: {steps:.3g} steps of {n} elements is too much "
            "work for one run; use fewer elements or a larger step")
    surf_dt = max(scn.record_dt_s, t_total / max(opts.surface_samples, 1))

    # ---- probes and surface springs
    s_end = loop.s_m + dx
    L_tot = float(s_end[-1])
    k = max(int(opts.probes), 1)
    targets = (np.arange(k) + 0.5) * L_tot / k
    probes = np.unique(np.clip(np.searchsorted(s_end, targets), 0, n - 1))
    stride = max(1, int(math.ceil(n / max(opts.surface_points, 1))))
    surf = np.arange(0, n, stride)

    sys = System(
        n=n, i_head=loop.i_head, i_tail=loop.i_tail, i_takeup=itu, strand=loop.strand.copy(),
        mass_kg=mass, belt_mass_kg=belt_mass, gravity_n=gravity, sag_w_n=loop.sag_w_n.copy(),
        coef=coef, pv=pv, ps=ps, hs_ref=float(law.hs_ref), hs_max=float(law.hs_max),
        len_m=len_m, stiffness_n=EB, a_ernst=a_el, t_floor_n=t_floor, k_floor_n=k_floor,
        carriage_coupling=carriage, implicit=implicit, blocks=blocks,
        damping=damping, c_visc_ns=c_visc, tau_s=tau, glassy_factor=glassy,
        tension_rest_n=T_rest, hold_node=hold, hold_force_n=hold_force,
        dt_s=dt, dt_limit_s=dt_lim, wave_loop_time_s=t_loop, wave_speed_m_s=c_wave,
        drive_node=np.array(d_node, dtype=np.int64), drive_share=np.array(d_share),
        drive_limit_n=np.array(d_lim), drive_euler=np.array(d_eut),
        drive_rated_n=np.array(d_rated), kp=kp, ki=ki, v_ff_m_s=v_ff,
        total_mass_kg=total_mass,
        brake_node=np.array(b_node, dtype=np.int64), brake_force_n=np.array(b_force, dtype=float),
        brake_delay_s=np.array(b_delay, dtype=float), holdback_node=holdback,
        takeup_gravity=gravity_tu, takeup_weight_n=tu_weight, takeup_inertia_kg=tu_inertia,
        takeup_lo_m=tu_lo, takeup_hi_m=tu_hi, takeup_run_m=x_run,
        v_design=v_d, v_eps=float(opts.v_eps_m_s),
        start_control=(profiles.FORCE if opts.force_start_n is not None
                       else START_CODES[scn.start.control]),
        start_s=start_s, run_s=float(scn.run_s), stop_mode=stop_mode,
        stop_s=float(scn.stop.time_s),
        formulation=RELATIVE if scn.formulation == "relative" else SUPPORT,
        force_start_n=float(opts.force_start_n or 0.0),
        pre_rest_s=float(opts.pre_rest_s), post_rest_s=float(post), stop_max_s=stop_max,
        record_dt_s=float(scn.record_dt_s), surface_dt_s=surf_dt,
        probe_springs=probes.astype(np.int64), surface_springs=surf.astype(np.int64),
        steady_tension_n=T_run.copy(), te_n=te, dx_m=dx.copy(), s_end_m=s_end, notes=notes,
        warnings=warns,
    )
    return sys


def brake_force_auto(total_mass_kg: float, v_d: float, te_n: float, gravity_sum_n: float,
                     stop_s: float, delay_s: float) -> float:
    """Total brake force for a rigid-body stop in ``stop_s`` [N].

    The belt coasts for ``delay_s`` decelerating at ``Te / M`` (accelerating when Te < 0,
    a regenerative belt), then the brake ``F_b`` and the running resistance stop it:
    ``F_b = M v_1 / (t_stop - t_delay) - Te`` with ``v_1 = v - Te t_delay / M``. At least
    1.2 x the net gravity pull of the loaded loop, so the brake holds the belt at rest.

    Parameters
    ----------
    total_mass_kg : float
        All moving mass reduced to the belt line [kg].
    v_d : float
        Design speed [m/s].
    te_n : float
        Steady peripheral force (resistance + gravity) [N].
    gravity_sum_n : float
        Net gravity force round the loop (material lift) [N].
    stop_s, delay_s : float
        Target stop time and brake delay [s].
    """
    v1 = v_d - te_n * delay_s / total_mass_kg
    if v1 <= 0.0:
        f = 0.0
    else:
        f = total_mass_kg * v1 / (stop_s - delay_s) - te_n
    return max(f, 1.2 * abs(gravity_sum_n), 0.0)


def _fixed_takeup_level(T_rel, T_run, len_m, a_el, EB, t_floor, k_floor) -> float:
    """Level of the at-rest tensions of a fixed take-up: the belt has the same length at rest
    as in the running state of statics (the loop length is fixed), found by bisection [N]."""
    target = float(np.sum(len_m * chord_strain(T_run, a_el, EB, t_floor, k_floor)))

    def excess(level):
        return float(np.sum(len_m * chord_strain(T_rel + level, a_el, EB, t_floor, k_floor))) \
            - target

    lo = -float(T_rel.max()) - abs(target) * EB - 1.0
    hi = float(np.abs(T_run).max()) + abs(float(T_rel.min())) + 1.0
    while excess(hi) < 0.0:
        hi *= 2.0
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        if excess(mid) < 0.0:
            lo = mid
        else:
            hi = mid
        if hi - lo < 1e-9 * max(1.0, abs(hi)):
            break
    return 0.5 * (lo + hi)
