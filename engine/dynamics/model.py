"""Assemble the transient model once per conveyor and scenario (PHYSICS section 5).

The loop's elements are the masses, the element boundaries are the springs: spring ``j``
joins element ``j`` and ``j + 1`` (cyclic), has length ``(dx_j + dx_{j+1}) / 2`` and carries
the boundary tension ``T[j]`` of statics. Everything the kernel needs is computed here as
plain arrays (:class:`System`); the kernel and the numpy reference only read them.

Design decisions (documented in ``docs/dynamics.md``):

* **Masses**: ``M_j = (m'_G + m'_L + m'_R) dx_j``; a plain pulley element adds an estimate of
  the pulley's own reduced mass (:func:`pulley_reduced_mass_kg`). Every drive pulley (and a
  braked or holdback pulley) has a **shaft** with its own mass, the rotating parts reduced to
  the belt line ``(J + J_flywheel) (2 / D)^2`` (with a fluid coupling, the motor's share
  ``J_motor (2 / D)^2`` is a separate mass behind the coupling), joined to the belt by
  capstan friction: it sticks while the force it passes stays within ``T_slack (e^(mu theta)
  - 1)`` and slips beyond (:mod:`beltstudy.engine.dynamics.blocks`).
* **Belt segments**: the static modulus E B (elongation, take-up travel) advanced with the
  Ernst *tangent* modulus ``EB_eq = EB / (1 + (w S)^2 EB / (12 T^3))`` (the chord law
  ``eps = T / EB - (w S)^2 / (24 T^2)`` integrated incrementally); below the tension where
  the sag ratio reaches ``HS_FLOOR`` the modulus is held constant; a belt never pushes, and
  a slack span stores its slack length and must be taken up before it pulls again.
* **Dynamic modulus and damping from belt data**: a standard linear solid whose relaxed
  modulus is the static one and whose instantaneous modulus is the belt's dynamic modulus
  (``dynamic_modulus_kn_m``, catalogue): a relaxing arm of stiffness ``(E_dyn - E) B`` with the
  belt's relaxation time, advanced by its exact exponential. Fronts travel at ``c = sqrt(E_dyn
  B / rho')`` with height ``Z dv``, ``Z = sqrt(E_dyn B rho')``; the static modulus governs the
  settled elongation. A **mesh viscosity** ``alpha Z dv`` per spring (``alpha`` =
  ``DynamicsOptions.mesh_viscosity``) damps the modes the mesh cannot resolve (damping ratio
  ``alpha`` at the mesh's highest mode, vanishing in proportion to the element length on the
  resolved waves), so peaks after sudden events converge with the mesh instead of ringing.
* **Implicit blocks**: the springs on both sides of every pulley element are solved
  implicitly together with the pulleys, their shafts and neighbouring elements (and the
  take-up carriage): short springs round light pulleys would otherwise set the step.
* **Step**: ``dt = dt_safety x`` the explicit stability limit (:func:`stability_limit_s`: the
  per-element Gershgorin bound with the instantaneous stiffness and the mesh viscosity);
  ``dt`` stays proportional to ``dx / c``.
* **Drives**: ``vfd`` drives run one speed loop on the master drive's own shaft speed (the
  largest share) with torque following (every vfd drive gives its share of the loop's
  output); ``dol`` drives follow their motor curve, through a fluid coupling when fitted.
* **At rest**: the belt is held by its brakes (or the master drive when it has none) with the
  at-rest tensions (take-up plus gravity, no resistance); a fixed take-up's at-rest level
  keeps the loop length of statics' running state.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from beltstudy.engine import design
from beltstudy.engine.conveyor import Conveyor, InputError, Scenario
from beltstudy.engine.dynamics import profiles
from beltstudy.engine.dynamics.codes import (
    BRAKE,
    COAST,
    CONTROLLED,
    COUPLING_FILL,
    COUPLING_FLUID,
    COUPLING_NONE,
    DOL,
    RELATIVE,
    SUPPORT,
    VFD,
)
from beltstudy.engine.law import ResistanceLaw
from beltstudy.engine.loop import G, Loop, rotating_parts
from beltstudy.engine.statics import master_drive, rest_hold_element, rest_walk

__all__ = [
    "DynamicsOptions",
    "System",
    "build_system",
    "stability_limit_s",
    "chord_strain",
    "check_scenario",
    "implicit_blocks",
    "speed_loop_bandwidth",
    "COAST",
    "BRAKE",
    "CONTROLLED",
    "RELATIVE",
    "SUPPORT",
    "HS_FLOOR",
]

STOP_CODES = {"coast": COAST, "brake": BRAKE, "controlled": CONTROLLED}
START_CODES = {"s-curve": profiles.S_CURVE, "linear": profiles.LINEAR,
               "torque": profiles.TORQUE}
COUPLING_CODES = {"none": COUPLING_NONE, "fluid": COUPLING_FLUID,
                  "fluid_fill_controlled": COUPLING_FILL}

#: Sag ratio h/S below whose tension the Ernst tangent modulus is held constant: the range of
#: the parabolic sag model (10 %).
HS_FLOOR = 0.10


@dataclass(frozen=True)
class DynamicsOptions:
    """Model and numerical settings of the transient engine (defaults are the engine's).

    Attributes
    ----------
    damping : str
        ``"belt"`` (default: the belt's standard linear solid from its static and dynamic
        moduli and relaxation time, plus the mesh viscosity) or ``"off"`` (verification).
    mesh_viscosity : float
        ``alpha``: Kelvin-Voigt viscosity ``alpha Z dv`` per spring [-], the damping ratio of the
        mesh's highest mode (0.1: the step shrinks by 10 %).
    ernst : bool
        Sag-dependent tangent stiffness (on by default, PHYSICS 5).
    resistances : bool
        Friction model resistances on (switch off only for verification runs).
    gravity : bool
        Gravity along the belt on (verification runs only).
    v_eps_m_s : float
        Regularisation speed of the resistances: ``R = R0 clip(v / v_eps, -1, 1)`` [m/s].
    resistance_rtol : float
        Accuracy of the resistance law between its exact evaluations [-] (0 to 0.01): a law
        with fractional exponents (Non-Lin) is evaluated exactly for an element when its
        speed or mean tension leaves the window round its expansion point, and expanded to
        second order about that point in between, the windows sized so the resistance stays
        within this fraction of the exact law at every step (:mod:`beltstudy.engine.dynamics.linlaw`).
        0 evaluates the exact law every step.
    dt_safety : float
        Automatic step as a fraction of the stability limit (0.5: half the limit).
    controller_bandwidth_rad_s : float or None
        Bandwidth ``omega_c`` of the vfd speed loop [rad/s]; None = :func:`speed_loop_bandwidth`
        (a quarter of the loop's wave frequency ``2 pi / t_loop``). ``Kp = 2 omega_c M``,
        ``Ki = omega_c^2 M`` with M all moving mass; a rigid-body feedforward ``M a_ref + (Te -
        sum G)`` carries the known forces.
    pre_rest_s, post_rest_s : float
        Rest before the start command and after the belt has stopped [s]; post-rest
        ``None`` = max(5 s, one wave loop time), plus the time holding brakes and the drives'
        trip take.
    pulley_mass_kg : float or None
        Reduced mass of each plain pulley [kg]; None = :func:`pulley_reduced_mass_kg`.
    force_start_n : float or None
        Open-loop constant drive force during the start and run [N] (verification).
    slip : bool
        Capstan friction with slip at the drive pulleys (on); off = every shaft sticks to the
        belt whatever force it passes (verification).
    probes : int
        Number of springs recorded at ``record_dt_s`` round the loop (Fig. 4 traces).
    surface_points, surface_samples : int
        Size of the tension/velocity surface: at most this many springs and time samples.
    """

    damping: str = "belt"
    mesh_viscosity: float = 0.1
    ernst: bool = True
    resistances: bool = True
    gravity: bool = True
    v_eps_m_s: float = 1e-4
    resistance_rtol: float = 1e-3
    dt_safety: float = 0.5
    controller_bandwidth_rad_s: float | None = None
    pre_rest_s: float = 2.0
    post_rest_s: float | None = None
    pulley_mass_kg: float | None = None
    force_start_n: float | None = None
    slip: bool = True
    probes: int = 8
    surface_points: int = 200
    surface_samples: int = 300


@dataclass(eq=False)
class System:
    """Everything the kernel reads, as plain arrays and numbers. SI units throughout.

    Node (element) arrays have length n; spring arrays have length n, spring j joining
    element j and j + 1 (cyclic). Shafts, drives and brakes are listed in their own arrays.
    """

    n: int
    i_head: int
    i_tail: int
    i_takeup: int
    strand: np.ndarray  # int8 strand codes of the loop (beltstudy.engine.loop)
    # nodes
    mass_kg: np.ndarray  # moving mass of the belt element (and a plain pulley's own mass)
    belt_mass_kg: np.ndarray  # (m'_G + m'_L + m'_R) dx: weights of the mean speed
    gravity_n: np.ndarray  # (m'_G + m'_L) g dx sin(a)
    sag_w_n: np.ndarray
    hs_cap: np.ndarray  # sag ratio cap of the resistance law per element
    coef: np.ndarray  # (K, n) merged resistance terms [N]
    pv: np.ndarray  # (K,)
    ps: np.ndarray  # (K,)
    hs_ref: float
    # springs
    len_m: np.ndarray
    stiffness_n: float  # static E B
    stiffness_dyn_n: float  # dynamic E_dyn B
    a_ernst: np.ndarray  # (w S)^2 / 12 per spring [N^2]
    t_floor_n: np.ndarray  # tangent modulus held constant below this tension
    k_floor_n: np.ndarray  # tangent modulus at the floor [N]
    carriage_coupling: np.ndarray  # 1 on the two springs beside the gravity take-up, else 0
    implicit: np.ndarray  # bool per spring: solved implicitly (beside a pulley)
    blocks: list  # element indices of each implicit block
    impedance_ns_m: np.ndarray  # Z = sqrt(E_dyn B rho') per spring [N s/m]
    # damping
    damping: str
    relaxation_s: float  # relaxation time of the arm [s] (inf without an arm)
    mesh_viscosity: float  # alpha
    # initial state
    tension_rest_n: np.ndarray
    hold_node: int
    hold_force_n: float
    # step
    dt_s: float
    dt_limit_s: float
    wave_loop_time_s: float
    wave_speed_m_s: np.ndarray  # per element, dynamic modulus, unsoftened
    # shafts (one per drive, braked or holdback pulley)
    shaft_node: np.ndarray
    shaft_mass_kg: np.ndarray
    shaft_euler: np.ndarray  # e^(mu theta) static
    shaft_euler_kinetic: np.ndarray  # e^(mu_k theta) sliding
    shaft_drive: np.ndarray  # drive index or -1
    shaft_holdback: np.ndarray  # 1 with a holdback
    # drives (file order)
    drive_node: np.ndarray
    drive_shaft: np.ndarray
    drive_share: np.ndarray
    drive_rated_n: np.ndarray
    drive_limit_n: np.ndarray
    drive_control: np.ndarray
    drive_coupling: np.ndarray
    drive_curves: list  # motor curve per drive: ((x, y), ...)
    drive_fill_s: np.ndarray
    drive_motor_mass_kg: np.ndarray
    drive_trip_s: np.ndarray
    master: int
    kp: float
    ki: float
    bandwidth_rad_s: float
    v_ff_m_s: float  # reference speed at which the resistance feedforward is complete
    total_mass_kg: float
    # brakes (file order)
    brake_shaft: np.ndarray
    brake_node: np.ndarray
    brake_force_n: np.ndarray
    brake_delay_s: np.ndarray
    brake_ramp_s: np.ndarray
    brake_curves: list  # force curve per brake, () for a linear ramp
    brake_hold: np.ndarray
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
    spring_head_in: int  # spring entering the first head pulley (T1)
    spring_head_out: int  # spring leaving the last head drive pulley (T2)
    notes: list[str] = field(default_factory=list)  # informational, for the message
    warnings: list[str] = field(default_factory=list)  # limits crossed before the start
    resistance_rtol: float = 1e-3  # accuracy of the law between exact evaluations (linlaw)

    @property
    def stop_command_s(self) -> float:
        return self.pre_rest_s + self.start_s + self.run_s

    @property
    def t_max_s(self) -> float:
        return self.stop_command_s + self.stop_max_s + self.post_rest_s

    @property
    def shaft_mass_total_kg(self) -> float:
        return float(self.shaft_mass_kg.sum() + self.drive_motor_mass_kg.sum())


# --------------------------------------------------------------------------------------
# Helpers


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


def speed_loop_bandwidth(wave_loop_time_s: float) -> float:
    """Default bandwidth of the vfd speed loop [rad/s]: a quarter of the loop's wave frequency,
    ``omega_c = pi / (2 t_loop)``.

    A speed loop that controls a flexible load through a colocated sensor must stay below the
    load's first anti-resonance, the frequency at which the belt held at the drive pulley
    rings (Ellis, Control System Design Guide, on resonance in servo loops; PHYSICS 5.1: the
    speed loop's bandwidth is bounded by the wave loop time). Held at the drive, the loop
    rings as a string of its whole length, ``omega_a = pi / t_loop``; the bandwidth is half
    of that.
    """
    return 0.5 * math.pi / wave_loop_time_s


def _merge_law(coef, pv, ps) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Merge terms with the same (pv, ps) exponents: the kernel evaluates each pair once."""
    keys: dict[tuple[float, float], np.ndarray] = {}
    for k in range(coef.shape[0]):
        key = (float(pv[k]), float(ps[k]))
        keys[key] = keys.get(key, 0.0) + coef[k]
    items = [(k, c) for k, c in keys.items() if np.any(c != 0.0)] or [((0.0, 0.0), coef[0] * 0)]
    merged = np.ascontiguousarray(np.vstack([c for _, c in items]), dtype=np.float64)
    return (merged, np.array([k[0] for k, _ in items], dtype=np.float64),
            np.array([k[1] for k, _ in items], dtype=np.float64))


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


#: Steps per drive-train time (:func:`drive_train_time_s`) the automatic step takes at least.
DRIVE_STEPS = 2.0


def drive_train_time_s(conv: Conveyor, parts, rated_n: np.ndarray, v_d: float
                       ) -> tuple[float, int]:
    """The fastest direct-on-line drive train: the time [s] its lightest rotating body (the
    pulley shaft with the motor, or behind a fluid coupling the motor and the pulley side each)
    would take to reach design speed unloaded at the drive's rated force, ``m v_d / F_r``, and
    that drive's index (``inf`` and -1 without dol drives).

    A dol drive's force is the motor curve (and the coupling characteristic) linearised in the
    shaft and motor speeds over one step; the curves have kinks (synchronous speed, the
    coupling's slip through zero, the capstan limit, a holdback), and a step longer than
    about half this time lets a light shaft jump across them and back every step instead of
    settling (a chatter that grows into a runaway). Real drive trains take seconds (a motor's
    run-up time unloaded), far above the belt's step; a shaft given a few kg m2 for megawatts
    does not, and then sets the step. VFD drives are held by their speed loop and torque limit.
    """
    t, which = math.inf, -1
    for node, k in parts.shaft_drive.items():
        d = conv.drives[k]
        if d.control != "dol" or rated_n[k] <= 0.0:
            continue
        m = parts.shaft_mass[node]
        if parts.motor_mass[k] > 0.0:
            m = min(m, parts.motor_mass[k])
        if m * v_d / rated_n[k] < t:
            t, which = m * v_d / rated_n[k], k
    return t, which


def stability_limit_s(mass_kg, len_m, stiffness_n, implicit=None, viscosity_ns=None) -> float:
    """Step limit ``2 / omega_max`` of the explicit part of the scheme [s].

    ``omega_max^2 = max_j 2 (K_{j-1} + K_j) / M_j`` over the explicit springs (``K =
    stiffness / len`` with the instantaneous, unsoftened stiffness; a Gershgorin bound,
    exactly ``dx / c`` for a uniform chain). Springs marked ``implicit`` (beside pulleys) are
    solved implicitly and do not limit the step. With ``viscosity_ns`` (the Kelvin-Voigt
    coefficient per spring, tension per relative speed [N s/m]) the explicit Kelvin-Voigt
    limit per element, ``(2 / omega_j) (sqrt(1 + zeta_j^2) - zeta_j)``, ``zeta_j =
    (c_{j-1} + c_j) / (M_j omega_j)``.
    """
    n = len(mass_kg)
    exp_ = np.ones(n) if implicit is None else (~np.asarray(implicit)).astype(float)
    K = stiffness_n / len_m * exp_
    Ksum = K + np.roll(K, 1)
    w = np.sqrt(2.0 * Ksum / mass_kg)
    ok = w > 0.0
    if not ok.any():
        return math.inf
    w = w[ok]
    if viscosity_ns is not None:
        c = np.asarray(viscosity_ns) * exp_
        zeta = ((c + np.roll(c, 1))[ok]) / (mass_kg[ok] * w)
        lim = (2.0 / w) * (np.sqrt(1.0 + zeta * zeta) - zeta)
    else:
        lim = 2.0 / w
    return float(lim.min())


#: Most time-series samples a run may ask for (``record_dt_s`` over the cycle): a million is
#: 28 hours at the default 0.1 s, far beyond any start and stop, and 17 columns of float64.
MAX_SAMPLES = 1e6


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
    # the time series: one sample every record_dt_s over the whole cycle (the rests and the
    # stop's allowance come on top of these times)
    times = (("scenario.start.time_s", float(scn.start.time_s)),
             ("scenario.run_s", float(scn.run_s)), ("scenario.stop.time_s", float(scn.stop.time_s)))
    t_cycle = sum(t for _, t in times)
    samples = t_cycle / scn.record_dt_s
    if samples > MAX_SAMPLES:
        name, longest = max(times, key=lambda x: x[1])
        if t_cycle / Scenario.model_fields["record_dt_s"].default <= MAX_SAMPLES:
            raise InputError(
                f"scenario.record_dt_s: {scn.record_dt_s:g} s over a cycle of {t_cycle:g} s "
                f"(start, run and stop) is {samples:.3g} time-series samples, more than "
                f"{MAX_SAMPLES:.0e}; use a spacing of at least {t_cycle / MAX_SAMPLES:.3g} s")
        raise InputError(
            f"{name}: {longest:g} s makes a cycle of {t_cycle:g} s, {samples:.3g} time-series "
            f"samples at scenario.record_dt_s {scn.record_dt_s:g} s, more than "
            f"{MAX_SAMPLES:.0e}: a transient run simulates every step of it; give the "
            "start, run and stop times in seconds (a start takes seconds to minutes)")
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
    dol = [i for i, d in enumerate(conv.drives) if d.control == "dol"]
    if dol and scn.stop.mode == "controlled":
        raise InputError(
            f"scenario.stop.mode: 'controlled' needs vfd drives (drives[{dol[0]}].control is "
            "'dol': a motor on the line cannot follow a stopping curve); use 'coast' or "
            "'brake'")
    if dol and scn.formulation == "support":
        raise InputError("scenario.formulation: 'support' imposes the drive pulleys' speed, "
                         f"which needs vfd drives (drives[{dol[0]}].control is 'dol')")
    if scn.formulation == "support" and scn.start.control == "torque":
        raise InputError("scenario.start.control: 'torque' needs formulation 'relative' (the "
                         "moving-support formulation imposes the drive pulley's motion)")
    if opts.damping not in ("belt", "off"):
        raise InputError(f"damping: unknown '{opts.damping}'; valid: belt, off")
    if not (0.0 <= opts.resistance_rtol <= 0.01):
        raise InputError(f"resistance_rtol: must be between 0 (the exact law every step) and "
                         f"0.01 (got {opts.resistance_rtol!r})")


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
        the stability limit, torque start with the support formulation, non-positive times,
        a controlled stop with dol drives.
    """
    opts = options or DynamicsOptions()
    check_scenario(scn, conv, opts)
    loop: Loop = steady.loop
    law: ResistanceLaw = steady.law
    n = loop.n
    notes: list[str] = []
    v_d = float(loop.speed_m_s)
    belt = loop.belt
    EB = float(belt.stiffness_n)
    EBd = float(belt.dynamic_stiffness_n)
    dx = loop.dx_m
    nxt = np.roll(np.arange(n), -1)

    # ---- shafts: every drive pulley, and the braked and holdback pulleys
    mass = loop.mass_kg.copy()
    belt_mass = mass.copy()
    parts = rotating_parts(conv, loop, opts.pulley_mass_kg)
    shafts: dict[int, dict] = {}
    for node, m in parts.shaft_mass.items():
        p = loop.pulley_at(node)
        shafts[node] = dict(mass=m, euler=p.euler, euler_k=p.euler_kinetic,
                            drive=parts.shaft_drive.get(node, -1),
                            hb=1 if (conv.holdback and node == loop.i_head) else 0)
    for node, m in parts.plain_mass.items():
        mass[node] += m
    drive_motor = np.array(parts.motor_mass, dtype=float)
    shaft_nodes = sorted(shafts)
    shaft_index = {node: k for k, node in enumerate(shaft_nodes)}
    sh_mass = np.array([shafts[s]["mass"] for s in shaft_nodes], dtype=float)
    sh_eu = np.array([shafts[s]["euler"] for s in shaft_nodes], dtype=float)
    sh_euk = np.array([shafts[s]["euler_k"] for s in shaft_nodes], dtype=float)
    if not opts.slip:
        sh_eu[:] = 0.0  # e^(mu theta) - 1 < 0: the kernel's code for a shaft that never slips
    total_mass = float(mass.sum() + sh_mass.sum() + drive_motor.sum())

    # ---- forces
    gravity = loop.gravity_n.copy() if opts.gravity else np.zeros(n)
    coef, pv, ps = _merge_law(law.coef, law.pv, law.ps)
    if not opts.resistances:
        coef, pv, ps = np.zeros((1, n)), np.zeros(1), np.zeros(1)
    hs_cap = np.broadcast_to(np.asarray(law.hs_max, dtype=float), (n,)).copy()

    # ---- springs
    len_m = 0.5 * (dx + dx[nxt])
    wS2 = (8.0 * loop.sag_w_n) ** 2  # (w S)^2 per element [N^2]
    a_el = (dx * wS2 + dx[nxt] * wS2[nxt]) / (dx + dx[nxt]) / 12.0
    if not opts.ernst:
        a_el = np.zeros(n)
    t_floor = np.maximum(np.sqrt(12.0 * a_el) / (8.0 * HS_FLOOR), 1.0)
    k_floor = EB * t_floor**3 / (t_floor**3 + a_el * EB)
    carriage = np.zeros(n)
    gravity_tu = conv.takeup.type == "gravity"
    itu = loop.i_takeup
    if gravity_tu:
        carriage[itu - 1] = 1.0
        carriage[itu] = 1.0

    # ---- waves (dynamic modulus)
    rho = loop.mG_kg_m + loop.mL_kg_m + loop.mR_kg_m
    c_wave = np.sqrt(EBd / rho)
    t_loop = float(np.sum(dx / c_wave))
    rho_spring = (rho * dx + rho[nxt] * dx[nxt]) / (dx + dx[nxt])
    impedance = np.sqrt(EBd * rho_spring)

    # ---- damping: the belt's standard linear solid and the mesh viscosity
    if opts.damping == "off":
        damping, tau, alpha = "off", math.inf, 0.0
    else:
        damping, tau, alpha = "belt", float(belt.relaxation_s), float(opts.mesh_viscosity)
    glassy = EBd if damping == "belt" else EB
    viscosity = alpha * impedance  # [N s/m] per spring

    # ---- take-up
    tu_weight = 0.0
    tu_inertia = 1.0
    if gravity_tu:
        m_tu = float(steady.takeup_mass_kg)
        tu_weight = m_tu * G
        tu_inertia = m_tu + float(conv.takeup.carriage_mass_kg)

    # ---- step
    implicit, blocks = implicit_blocks(loop.strand)
    dt_lim = stability_limit_s(mass, len_m, glassy, implicit, viscosity)
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
    rated = np.array(design.rated_power_kw(conv, te, r_sum)[0]) * 1e3 / v_d
    limit = np.array([d.torque_limit for d in conv.drives]) * rated
    t_train, k_train = drive_train_time_s(conv, parts, rated, v_d)
    if t_train / DRIVE_STEPS < dt:
        if scn.dt_s == "auto":
            notes.append(f"the step is {t_train / DRIVE_STEPS:.3g} s, not {dt:.3g} s: it resolves "
                         f"the fastest dol drive train ({t_train:.3g} s to reach design speed "
                         "unloaded at rated force): a heavier inertia_kg_m2 allows a longer step")
            dt = t_train / DRIVE_STEPS
        else:
            notes.append(f"scenario.dt_s {dt:.3g} s is longer than the fastest dol drive train "
                         f"({t_train:.3g} s to reach design speed unloaded at rated force): its "
                         "shaft and motor speeds may not be resolved, 'auto' resolves them")
    master = master_drive(conv)
    wc = (float(opts.controller_bandwidth_rad_s) if opts.controller_bandwidth_rad_s is not None
          else speed_loop_bandwidth(t_loop))
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
    b_force = []
    if conv.brakes:
        kn, _why, note = design.brake_forces(conv, scn, total_mass, te, float(gravity.sum()))
        b_force = [f * 1e3 for f in kn]
        if note:
            notes.append(note)

    # ---- durations
    hold_time = max([b.delay_s + (b.force_curve[-1][0] if b.force_curve else b.ramp_s)
                     for b in conv.brakes if b.hold] or [0.0])
    trip = max(d.trip_s for d in conv.drives)
    post = opts.post_rest_s if opts.post_rest_s is not None else (
        max(5.0, t_loop) + hold_time + trip)
    coast_est = total_mass * v_d / te if te > 0 else scn.stop.time_s
    stop_max = 3.0 * max(scn.stop.time_s, coast_est) + 2.0 * t_loop + 10.0
    start_s = float(scn.start.time_s)
    t_total = opts.pre_rest_s + start_s + scn.run_s + stop_max + post
    steps = t_total / dt
    if steps * n > 5e10:
        if scn.dt_s == "auto" and t_train / DRIVE_STEPS <= dt:
            raise InputError(
                f"drives[{k_train}].inertia_kg_m2: {steps:.3g} steps of {n} elements is too much work for "
                f"one run; the step, {dt:.3g} s, resolves the fastest dol drive train "
                f"({t_train:.3g} s to reach design speed unloaded at rated force): give the drives "
                "their real inertia (motor, coupling, gear and pulley reduced to the pulley shaft)")
        raise InputError(
            f"scenario.dt_s / scenario.elements: {steps:.3g} steps of {n} elements is too much "
            f"work for one run (over 5e10 element-steps): a cycle of {t_total:.4g} s (start "
            f"{start_s:g} s, run {scn.run_s:g} s, up to {stop_max:.4g} s for the stop, the "
            f"rests) at a step of {dt:.3g} s; use fewer elements or a larger step, or shorter "
            "times")
    surf_dt = max(scn.record_dt_s, t_total / max(opts.surface_samples, 1))

    # ---- probes and surface springs
    s_end = loop.s_m + dx
    L_tot = float(s_end[-1])
    k = max(int(opts.probes), 1)
    targets = (np.arange(k) + 0.5) * L_tot / k
    probes = np.unique(np.clip(np.searchsorted(s_end, targets), 0, n - 1))
    stride = max(1, int(math.ceil(n / max(opts.surface_points, 1))))
    surf = np.arange(0, n, stride)
    head_drives = [loop.drive_elements[i] for i, d in enumerate(conv.drives)
                   if d.position == "head"]
    s_head_out = max(head_drives) if head_drives else loop.i_head

    return System(
        n=n, i_head=loop.i_head, i_tail=loop.i_tail, i_takeup=itu, strand=loop.strand.copy(),
        mass_kg=mass, belt_mass_kg=belt_mass, gravity_n=gravity, sag_w_n=loop.sag_w_n.copy(),
        hs_cap=hs_cap, coef=coef, pv=pv, ps=ps, hs_ref=float(law.hs_ref),
        len_m=len_m, stiffness_n=EB, stiffness_dyn_n=EBd, a_ernst=a_el, t_floor_n=t_floor,
        k_floor_n=k_floor, carriage_coupling=carriage, implicit=implicit, blocks=blocks,
        impedance_ns_m=impedance, damping=damping, relaxation_s=tau, mesh_viscosity=alpha,
        tension_rest_n=T_rest, hold_node=hold, hold_force_n=hold_force,
        dt_s=dt, dt_limit_s=dt_lim, wave_loop_time_s=t_loop, wave_speed_m_s=c_wave,
        shaft_node=np.array(shaft_nodes, dtype=np.int64), shaft_mass_kg=sh_mass,
        shaft_euler=sh_eu, shaft_euler_kinetic=sh_euk,
        shaft_drive=np.array([shafts[s]["drive"] for s in shaft_nodes], dtype=np.int64),
        shaft_holdback=np.array([shafts[s]["hb"] for s in shaft_nodes], dtype=np.int64),
        drive_node=np.array(loop.drive_elements, dtype=np.int64),
        drive_shaft=np.array([shaft_index[e] for e in loop.drive_elements], dtype=np.int64),
        drive_share=np.array([d.share for d in conv.drives]), drive_rated_n=rated,
        drive_limit_n=limit,
        drive_control=np.array([VFD if d.control == "vfd" else DOL for d in conv.drives],
                               dtype=np.int64),
        drive_coupling=np.array([COUPLING_CODES[d.coupling] for d in conv.drives],
                                dtype=np.int64),
        drive_curves=[tuple(d.curve) for d in conv.drives],
        drive_fill_s=np.array([d.coupling_fill_s for d in conv.drives]),
        drive_motor_mass_kg=drive_motor,
        drive_trip_s=np.array([d.trip_s for d in conv.drives]),
        master=master, kp=kp, ki=ki, bandwidth_rad_s=wc, v_ff_m_s=v_ff,
        total_mass_kg=total_mass,
        brake_shaft=np.array([shaft_index[loop.brake_element(b)] for b in conv.brakes],
                             dtype=np.int64),
        brake_node=np.array([loop.brake_element(b) for b in conv.brakes], dtype=np.int64),
        brake_force_n=np.array(b_force, dtype=float),
        brake_delay_s=np.array([b.delay_s for b in conv.brakes], dtype=float),
        brake_ramp_s=np.array([b.ramp_s for b in conv.brakes], dtype=float),
        brake_curves=[tuple(b.force_curve or ()) for b in conv.brakes],
        brake_hold=np.array([1 if b.hold else 0 for b in conv.brakes], dtype=np.int64),
        takeup_gravity=gravity_tu, takeup_weight_n=tu_weight, takeup_inertia_kg=tu_inertia,
        takeup_lo_m=tu_lo, takeup_hi_m=tu_hi, takeup_run_m=x_run,
        v_design=v_d, v_eps=float(opts.v_eps_m_s),
        start_control=(profiles.FORCE if opts.force_start_n is not None
                       else START_CODES[scn.start.control]),
        start_s=start_s, run_s=float(scn.run_s), stop_mode=STOP_CODES[scn.stop.mode],
        stop_s=float(scn.stop.time_s),
        formulation=RELATIVE if scn.formulation == "relative" else SUPPORT,
        force_start_n=float(opts.force_start_n or 0.0),
        pre_rest_s=float(opts.pre_rest_s), post_rest_s=float(post), stop_max_s=stop_max,
        record_dt_s=float(scn.record_dt_s), surface_dt_s=surf_dt,
        probe_springs=probes.astype(np.int64), surface_springs=surf.astype(np.int64),
        steady_tension_n=T_run.copy(), te_n=te, dx_m=dx.copy(), s_end_m=s_end,
        spring_head_in=(loop.i_head - 1) % n, spring_head_out=int(s_head_out),
        notes=notes, warnings=warns, resistance_rtol=float(opts.resistance_rtol),
    )
