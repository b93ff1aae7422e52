"""Assemble the transient model once per conveyor and scenario (PHYSICS section 5).

The loop's elements are the masses, the element boundaries are the springs: spring ``j``
joins element ``j`` and ``j + 1`` (cyclic), has length ``(dx_j + dx_{j+1}) / 2`` and carries
the boundary tension ``T[j]`` of statics. Everything the kernel needs is computed here, section
by section, as the named records of :mod:`beltstudy.engine.dynamics.records` (held by
:class:`System`); the kernel and the numpy reference only read them.

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
  resolved waves), so peaks after sudden events converge with the mesh instead of ringing;
  on the free springs it is limited (Christensen's monotonised central limiter,
  :func:`beltstudy.engine.dynamics.passes.visc_limiter`): off where the strain rate varies
  smoothly, so it does not diffuse a front over ``sqrt(alpha dx L)`` as it runs.
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
from dataclasses import dataclass, field, replace

import numpy as np

from beltstudy.engine import design
from beltstudy.engine.chord import HS_FLOOR, chord_springs, chord_strain, length_level
from beltstudy.engine.conveyor import (
    Conveyor,
    InputError,
    Scenario,
    curve_arc_m,
    route_points,
)
from beltstudy.engine.dynamics import profiles
from beltstudy.engine.dynamics.brakes import build_brakes
from beltstudy.engine.dynamics.codes import (
    BLOCK_MAX,
    BRAKE,
    COAST,
    CONTROLLED,
    COUPLING_FILL,
    COUPLING_FLUID,
    COUPLING_NONE,
    DOL,
    LAW_CONST,
    LAW_EXACT,
    LAW_LINEAR,
    RELATIVE,
    SPEED_WINDOW,
    SUPPORT,
    V_FAIL_FACTOR,
    VFD,
)
from beltstudy.engine.dynamics.laws import padded_curves
from beltstudy.engine.dynamics.linlaw import (
    BIG,
    K_LIN,
    element_windows,
    law_windows,
    sparse_terms,
    x_cap,
)
from beltstudy.engine.dynamics.passes import CHUNK, N_F, N_G, N_O, law_rows
from beltstudy.engine.dynamics.records import (
    Blocks,
    Control,
    Cycle,
    Drives,
    Law,
    Lin,
    Model,
    Nodes,
    Probes,
    Shafts,
    Springs,
    Takeup,
)
from beltstudy.engine.law import ResistanceLaw
from beltstudy.engine.loop import G, Loop, rotating_parts, shell_floor_notes
from beltstudy.engine.statics import (
    master_drive,
    rest_grip_words,
    rest_hold_element,
    rest_walk,
)
from beltstudy.engine.wording import gnum

__all__ = [
    "DynamicsOptions",
    "System",
    "build_system",
    "with_step",
    "with_law",
    "with_probes",
    "law_record",
    "exponent_codes",
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
        Bandwidth ``omega_c`` of the vfd speed loop [rad/s], closed on the master pulley's own
        speed; overrides the master drive's ``speed_loop_rad_s``; None =
        :func:`speed_loop_bandwidth` (the drive's, else :data:`DEFAULT_SPEED_LOOP_RAD_S`).
        ``Kp = 2 omega_c M``, ``Ki = omega_c^2 M`` with M the mass the loop sees within its
        bandwidth (:func:`loop_inertia`).
    speed_feedforward : bool
        Add the rigid-body feedforward ``M a_ref + (Te - sum G)`` (M all moving mass) to the
        speed loop's output. Off: a long belt does not move as one body while the reference
        rises, and on the example conveyors the loop tracks better without it.
    handover_s : float or None
        vfd drives on pulleys other than the one holding the belt at rest build their
        share of the holding force over this time from the start command, the hold then
        lets go and the speed loop starts from that force [s]; None = :data:`HANDOVER_S`,
        0 = at once (engine 0.6.5).
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
    viscosity_limiter : bool
        The free springs' mesh viscosity limited where the strain rate varies smoothly
        (:func:`beltstudy.engine.dynamics.passes.visc_limiter`: Christensen's monotonised
        central limiter, on by default); off = the plain Kelvin-Voigt term of engine 0.4.
    stop_window_s : float
        The one "did not stop" rule [s]: a run whose belt has not come to rest (mean speed
        below 1 % of design speed; a controlled stop also past its stop time) within this
        time of the stop command did not stop, and its simulation ends there; a run whose belt
        rests ends after the post-rest. The same for every run, so a study compares like with
        like. 300 s: coming to rest within it takes a mean deceleration of at least
        ``v / 300 s`` (0.027 m/s^2 at 8 m/s), a retarding force of 0.27 % of the moving
        weight, a third or less of the rolling resistance of the lightest-running level
        belts (equivalent friction factor 0.006 to 0.010, the lower end *unverified*;
        docs/dynamics.md *The stop window*); a belt that still moves after it is held on the move by gravity and needs a
        brake. A controlled or brake stop's ``stop.time_s`` must lie within it.
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
    speed_feedforward: bool = False
    pre_rest_s: float = 2.0
    post_rest_s: float | None = None
    pulley_mass_kg: float | None = None
    force_start_n: float | None = None
    slip: bool = True
    probes: int = 8
    surface_points: int = 200
    surface_samples: int = 300
    viscosity_limiter: bool = True
    stop_window_s: float = 300.0
    handover_s: float | None = None


@dataclass(eq=False)
class System:
    """The transient model of one conveyor and scenario (PHYSICS section 5).

    ``model`` holds the kernel's records (:class:`~beltstudy.engine.dynamics.records.Model`:
    the cycle, elements, springs, law, blocks, shafts, drives, brakes, take-up, speed loop and
    the recorded springs); the other fields describe the model to a reader (where each element
    lies, the rest and running tensions, the waves, what the build noted). SI units
    throughout; per-element arrays have length n.
    """

    model: Model
    strand: np.ndarray  # int8 strand codes per element (beltstudy.engine.loop)
    s_end_m: np.ndarray  # position of each spring (element end) from the tail [m]
    dx_m: np.ndarray  # element length [m]
    i_head: int  # the first head pulley element
    blocks: list  # element indices of each implicit block, in loop order
    implicit: np.ndarray  # bool per spring: solved implicitly (beside a pulley)
    tension_rest_n: np.ndarray  # at-rest tensions, the initial state [N]
    hold_force_n: float  # force holding the belt at rest [N]
    steady_tension_n: np.ndarray  # running tensions of statics [N]
    te_n: float  # effective tension of statics [N]
    wave_loop_time_s: float  # time a front takes round the loop [s]
    wave_speed_m_s: np.ndarray  # per element, dynamic modulus, unsoftened [m/s]
    dt_limit_s: float  # stability limit of the explicit part [s]
    damping: str  # "belt" or "off"
    relaxation_s: float  # relaxation time of the arm [s] (inf without an arm)
    mesh_viscosity: float  # alpha
    notes: list[str] = field(default_factory=list)  # informational, for the message
    warnings: list[str] = field(default_factory=list)  # limits crossed before the start
    #: a brake of the run is auto (sized by the stop time or by holding) although the conveyor
    #: it runs has its force written in (a study's design basis, a run below full load): the
    #: stop's advice then offers stop.time_s; None: read the conveyor given to the words
    auto_brakes: bool | None = None
    #: when the start ends for the run's words [s]: the end of the start reference or, later,
    #: when the belt first reached 99 % of design speed (a belt its slipping drives still pull
    #: up to speed is starting, not running); None: the end of the start reference
    t_start_end_s: float | None = None
    #: a longer stop.time_s changes an auto brake's force: its size is set by the stop time
    #: or by its pulley's grip against the stop time's need (``brake_governed_by`` names
    #: ``stop_time`` or ``grip``); False where every brake is set by holding the belt at rest
    #: or given; None: not known (the words judge it from the system, ``_auto_brake_held``)
    brakes_timed: bool | None = None
    #: an auto brake of the run is held below the stop time's need by its pulley's grip
    #: (``brake_governed_by`` names ``grip``): a longer stop.time_s changes it only once the
    #: rigid-body force for that time falls below the grip; None: not known
    brakes_gripped: bool | None = None
    #: the load cases the engine sizes a motor at, each (Te, running resistance) [N], Te signed
    #: (negative: regenerating): the run's own and, below the full load, the full load's, as
    #: an auto motor of such a run is installed (:func:`beltstudy.engine.sizing.
    #: installed_at_full_load`, :func:`beltstudy.engine.drives.motor_size_kw`); None: the
    #: run's own Te alone
    motor_cases: tuple[tuple[float, float], ...] | None = None
    #: each drive's train efficiency, motor shaft to pulley (``drives[i].efficiency``) [-]: the
    #: engine sizes a motor on the power at its shaft; None: 1 (the words size on the pulley)
    drive_efficiency: np.ndarray | None = None
    #: the largest brake force [N] the braked pulley at an element passes in a brake stop, the
    #: undamped bound (:func:`beltstudy.engine.stopgrip.brake_grip_n` bound to the run's
    #: conveyor, steady solution and brakes): a stop slip's words offer less force on a pulley
    #: only where the holding force fits within it; None: not known (less force is offered)
    brake_grip: object | None = None

    @property
    def n(self) -> int:
        """Number of elements (and springs)."""
        return int(self.model.nodes.mass.shape[0])

    @property
    def dt_s(self) -> float:
        """The step [s]."""
        return self.model.cycle.dt

    @property
    def v_design(self) -> float:
        """The design speed [m/s]."""
        return self.model.cycle.v_d

    @property
    def stop_command_s(self) -> float:
        """Time of the stop command [s]."""
        c = self.model.cycle
        return c.t_pre + c.t_start + c.t_run

    @property
    def t_max_s(self) -> float:
        """The longest the cycle may last [s]."""
        c = self.model.cycle
        return self.stop_command_s + c.stop_max + c.post_rest


# --------------------------------------------------------------------------------------
# Helpers


#: Time over which vfd drives build the holding torque at the start command before the belt's
#: hold is released [s] (docs/dynamics.md, *The start from rest*): the drive's torque ramp
#: between brake and motor, 0.1 to 0.5 s, 0.3 s by default (KEB COMBIVERT F5, LF.79); drives
#: take the holding torque before the brake opens and the speed ramp starts (the "release
#: torque" of CG Emotron VFX, parameter 33I; a "torque preload" of up to 0.8 s, Curtis
#: 1232E-1238E, EM brake menu).
HANDOVER_S = 0.3

#: Default bandwidth of the vfd speed loop closed on the master pulley's own speed [rad/s]
#: (PHYSICS 5.1): plant drives of large conveyors run it at a few rad/s (docs/dynamics.md,
#: "Speed loop", gives the sources).
DEFAULT_SPEED_LOOP_RAD_S = 5.0


def speed_loop_bandwidth(conv=None, opts: DynamicsOptions | None = None) -> float:
    """Bandwidth ``omega_c`` of the vfd speed loop [rad/s]: the options' override, else the
    master drive's ``speed_loop_rad_s``, else :data:`DEFAULT_SPEED_LOOP_RAD_S`.

    The loop is closed on the master pulley's own speed (colocated): it stays stable above the
    belt's first anti-resonance, so its bandwidth is set by the drive (plant practice, a few
    rad/s), not by the wave loop time; only a loop closed on belt speed far from the drive is
    bounded by the wave loop time (PHYSICS 5.1).
    """
    if opts is not None and opts.controller_bandwidth_rad_s is not None:
        return float(opts.controller_bandwidth_rad_s)
    if conv is not None:
        bw = conv.drives[master_drive(conv)].speed_loop_rad_s
        if bw is not None:
            return float(bw)
    return DEFAULT_SPEED_LOOP_RAD_S


def loop_inertia(conv, loop: Loop, shafts: Shafts, shaft_index: dict, c_wave: np.ndarray,
                 wc: float, total_mass: float) -> float:
    """The mass the speed loop sees within its bandwidth, per unit of its output ``U`` [kg].

    At ``omega_c`` the master pulley feels its own shaft and those of the drives beside it at
    the same end (their force is the same ``U`` in shares), and the belt on each side as far
    as a wave runs in ``1 / omega_c``: ``(Z_in + Z_out) / omega_c`` with ``Z = rho' c``. Those
    drives pass ``s_end U`` (their shares' sum), so the gains on ``U`` are sized on
    ``(m_shafts + sum Z / omega_c) / s_end``; never more than all moving mass (a short, stiff
    belt moves as one body within the bandwidth, PHYSICS 6).
    """
    m = master_drive(conv)
    pos = (conv.drives[m].position, conv.drives[m].at_m)  # a booster: its own position
    ends = [i for i, d in enumerate(conv.drives) if (d.position, d.at_m) == pos]
    s_end = sum(conv.drives[i].share for i in ends)
    m_sh = sum(float(shafts.mass[shaft_index[int(loop.drive_elements[i])]]) for i in ends)
    n = loop.n
    rho = loop.mass_kg / loop.dx_m
    z = rho * c_wave
    lo = min(int(loop.drive_elements[i]) for i in ends)
    hi = max(int(loop.drive_elements[i]) for i in ends)
    z_sum = float(z[(lo - 1) % n] + z[(hi + 1) % n])
    return min(total_mass, (m_sh + z_sum / wc) / max(s_end, 1e-9))


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
    if scn.record_dt_s > scn.start.time_s:
        # the records carry more than the time series: the speed at the stop command, the
        # tracking and settling checks and the stop's overspeed are read from them (60 s on a
        # 20 s start kept 2 samples of a 37.7 s cycle, its two ends)
        default = Scenario.model_fields["record_dt_s"].default
        raise InputError(
            f"scenario.record_dt_s: {scn.record_dt_s:g} s is longer than the start "
            f"(scenario.start.time_s {scn.start.time_s:g} s): the time series and the checks "
            "read from it (the speed at the stop command, tracking, settling, the stop's "
            f"overspeed) would have no sample inside the start; give at most "
            f"{scn.start.time_s:g} s, or leave it out (the default {default:g} s)")
    if samples > MAX_SAMPLES:
        name, longest = max(times, key=lambda x: x[1])
        if t_cycle / Scenario.model_fields["record_dt_s"].default <= MAX_SAMPLES:
            raise InputError(
                f"scenario.record_dt_s: {scn.record_dt_s:g} s over a cycle of {t_cycle:g} s "
                f"(start, run and stop) is {gnum(samples, 3)} time-series samples, more than "
                f"{MAX_SAMPLES:.0e}; use a spacing of at least {gnum(t_cycle / MAX_SAMPLES, 3)} s")
        raise InputError(
            f"{name}: {longest:g} s makes a cycle of {t_cycle:g} s, {gnum(samples, 3)} time-series "
            f"samples at scenario.record_dt_s {scn.record_dt_s:g} s, more than "
            f"{MAX_SAMPLES:.0e}: a transient run simulates every step of it; give the "
            "start, run and stop times in seconds (a start takes seconds to minutes)")
    if scn.dt_s != "auto" and not (float(scn.dt_s) > 0.0):
        raise InputError(f"scenario.dt_s: must be 'auto' or a positive step (got {scn.dt_s!r})")
    if scn.dt_s != "auto":
        # the work of one run (refused beyond 5e10 element-steps when the model is built,
        # :func:`_cycle`), here from what the scenario alone fixes: the cycle is at least the
        # rest before the start, the start, the run, the stop window and 5 s of rest after it,
        # on the elements asked (an automatic mesh: 2 at the least, the loop's floor)
        n_least = int(scn.elements) if scn.elements != "auto" else 2
        t_least = (opts.pre_rest_s + float(scn.start.time_s) + float(scn.run_s)
                   + float(opts.stop_window_s) + 5.0)
        steps = t_least / float(scn.dt_s)
        if steps * n_least > 5e10:
            of = f" of {n_least} elements" if scn.elements != "auto" else ""
            raise InputError(
                f"scenario.dt_s: {float(scn.dt_s):g} s makes at least {gnum(steps, 3)} steps{of}, "
                "too much work for one run (over 5e10 element-steps; "
                f"a cycle of at least {gnum(t_least)} s: start {float(scn.start.time_s):g} s, "
                f"run {float(scn.run_s):g} s, up to {opts.stop_window_s:g} s for the stop, "
                "the rests); use dt_s: auto (the stability limit's step), or a larger step")
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
            f"scenario.stop.mode: 'controlled' needs vfd drives (drives.{dol[0]}.control is "
            "'dol': a motor on the line cannot follow a stopping curve); use 'coast' or "
            "'brake'")
    if dol and scn.formulation == "support":
        raise InputError("scenario.formulation: 'support' imposes the drive pulleys' speed, "
                         f"which needs vfd drives (drives.{dol[0]}.control is 'dol')")
    if scn.formulation == "support" and scn.start.control == "torque":
        raise InputError("scenario.start.control: 'torque' needs formulation 'relative' (the "
                         "moving-support formulation imposes the drive pulley's motion)")
    if not (opts.stop_window_s > 0.0 and math.isfinite(opts.stop_window_s)):
        raise InputError(f"stop_window_s: must be a positive time in seconds (got "
                         f"{opts.stop_window_s!r})")
    if scn.stop.mode in ("controlled", "brake") and scn.stop.time_s >= opts.stop_window_s:
        raise InputError(
            f"scenario.stop.time_s: a {scn.stop.mode} stop of {scn.stop.time_s:g} s does not "
            f"end within the stop window of {opts.stop_window_s:g} s (stop_window_s: a run "
            "whose belt is not at rest that long after the stop command did not stop, the "
            "same window for every run); give a shorter stop time")
    if opts.damping not in ("belt", "off"):
        raise InputError(f"damping: unknown '{opts.damping}'; valid: belt, off")
    if not (0.0 <= opts.resistance_rtol <= 0.01):
        raise InputError(f"resistance_rtol: must be between 0 (the exact law every step) and "
                         f"0.01 (got {opts.resistance_rtol!r})")


# --------------------------------------------------------------------------------------
# The records, section by section


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


def _i64(x) -> np.ndarray:
    return np.ascontiguousarray(x, dtype=np.int64)


def _f64(x) -> np.ndarray:
    return np.ascontiguousarray(x, dtype=np.float64)


def _shafts(conv: Conveyor, loop: Loop, opts: DynamicsOptions):
    """The pulley shafts (every drive pulley, and the braked and holdback pulleys) with their
    reduced masses and capstan factors; the element masses with the plain pulleys' own. Returns
    (element mass [kg], Shafts, shaft of each pulley element, rotating parts)."""
    mass = loop.mass_kg.copy()
    parts = rotating_parts(conv, loop, opts.pulley_mass_kg)
    nodes = sorted(parts.shaft_mass)
    for node, m in parts.plain_mass.items():
        mass[node] += m
    euler = np.array([loop.pulley_at(s).euler for s in nodes], dtype=float)
    euler_k = np.array([loop.pulley_at(s).euler_kinetic for s in nodes], dtype=float)
    if not opts.slip:
        euler[:] = 0.0  # e^(mu theta) - 1 < 0: the kernel's code for a shaft that never slips
    ns = len(nodes)
    shafts = Shafts(
        node=_i64(nodes), mass=_f64([parts.shaft_mass[s] for s in nodes]), cs=_f64(euler - 1.0),
        ck=_f64(euler_k - 1.0), drive=_i64([parts.shaft_drive.get(s, -1) for s in nodes]),
        hb=_i64([1 if (conv.holdback and s == loop.i_head) else 0 for s in nodes]),
        vs=np.zeros(ns), slip=np.zeros(ns), fb=np.zeros(ns), fb_out=np.zeros(ns))
    return mass, shafts, {node: k for k, node in enumerate(nodes)}, parts


def law_record(coef: np.ndarray, pv: np.ndarray, ps: np.ndarray, hs_ref: float,
               rtol: float) -> Law:
    """The law's record for terms of coefficients (K, n) [N] and speed and sag exponents:
    its sparse terms, whether any term depends on the tension, and how the kernel evaluates it
    (once for one constant term; expanded between exact evaluations to ``rtol`` where
    :func:`linlaw.law_windows` gives windows; exactly every step otherwise)."""
    coef = _f64(coef)
    pv = _f64(pv)
    ps = _f64(ps)
    # terms with few non-zero elements (feed, pulleys, accessories) are evaluated on those
    # elements only: t_idx[t_ptr[k]:t_ptr[k + 1]] for a term with t_sparse[k] == 1
    t_sparse, t_ptr, t_idx = [], [0], []
    for k, sparse in enumerate(sparse_terms(coef)):
        t_sparse.append(1 if sparse else 0)
        if sparse:
            t_idx.extend(int(j) for j in np.flatnonzero(coef[k]))
        t_ptr.append(len(t_idx))
    if coef.shape[0] == 1 and pv[0] == 0.0 and ps[0] == 0.0:
        mode = LAW_CONST
    else:
        mode = LAW_EXACT if law_windows(coef, pv, ps, rtol) is None else LAW_LINEAR
    return Law(coef=coef, pvc=exponent_codes(pv), pvv=pv, psc=exponent_codes(ps), psv=ps,
               t_sparse=_i64(t_sparse), t_ptr=_i64(t_ptr), t_idx=_i64(t_idx or [0]),
               hs_ref=float(hs_ref), any_ps=bool(np.any(ps != 0.0)), rtol=float(rtol),
               mode=mode)


def _law(n: int, law: ResistanceLaw, opts: DynamicsOptions) -> Law:
    """The friction model's law with terms of equal exponents merged (the kernel evaluates
    each pair once), or none (verification)."""
    coef, pv, ps = _merge_law(law.coef, law.pv, law.ps)
    if not opts.resistances:
        coef, pv, ps = np.zeros((1, n)), np.zeros(1), np.zeros(1)
    return law_record(coef, pv, ps, law.hs_ref, opts.resistance_rtol)


def _lin(law: Law, nodes: Nodes, v_eps: float) -> Lin:
    """The arrays of the law's expansion (:class:`~beltstudy.engine.dynamics.records.Lin`),
    filled by the kernel; the per-element window sizes of :func:`linlaw.law_windows` (none when
    the law is evaluated exactly: the arrays are then not used)."""
    n = nodes.mass.shape[0]
    nk = law.coef.shape[0]
    sw_ref, hsm_ref = nodes.sw_ref, nodes.hsm_ref
    windows = law_windows(law.coef, law.pvv, law.psv, law.rtol)
    if windows is None:
        du = d0 = dx = np.full(n, BIG)
        pv, ps = np.zeros(1), np.zeros(1)
    else:
        du, d0, dx = element_windows(law.coef, law.pvv, law.psv, sw_ref, hsm_ref, v_eps,
                                     windows)
        pv, ps = law.pvv, law.psv
    rs, rq, upow, qpow, npow, wk = law_rows(pv, ps)
    erow = np.zeros((n, 8 + K_LIN))
    erow[:, 0] = sw_ref
    erow[:, 1] = hsm_ref
    erow[:, 2] = x_cap(sw_ref, hsm_ref)
    erow[:, 3] = du
    erow[:, 4] = d0
    erow[:, 5] = dx
    if windows is not None:
        erow[:, 8:8 + nk] = law.coef.T
    n8 = 8 * ((n + 7) // 8)
    flag = np.zeros(n8, dtype=np.uint8)

    def z():
        return np.zeros(n, dtype=np.float32)

    return Lin(k=z(), gu=z(), guu=z(), gx=z(), gxx=z(), gux=z(), ulo=z(), uhi=z(), tlo=z(),
               thi=z(), erow=erow, rs=rs, rq=rq, wk=wk, upow=upow, qpow=qpow, npow=npow,
               flag=flag, flag64=flag.view(np.uint64), idx=np.zeros(n + 8, dtype=np.int64),
               sg=np.zeros(N_G * CHUNK), sf=np.zeros(N_F * CHUNK), so=np.zeros(N_O * CHUNK))


def _nodes(loop: Loop, mass: np.ndarray, law: ResistanceLaw, opts: DynamicsOptions,
           hs_ref: float) -> Nodes:
    """The elements' masses, gravity and sag (``hm`` is set with the step)."""
    n = loop.n
    gravity = loop.gravity_n.copy() if opts.gravity else np.zeros(n)
    hs_cap = np.broadcast_to(np.asarray(law.hs_max, dtype=float), (n,)).copy()
    return Nodes(mass=_f64(mass), hm=np.zeros(n), gravity=_f64(gravity),
                 w_mean=_f64(loop.mass_kg), sag_w=_f64(loop.sag_w_n), hs_cap=_f64(hs_cap),
                 sw_ref=_f64(loop.sag_w_n / hs_ref), hsm_ref=_f64(hs_cap / hs_ref))


def _springs(loop: Loop, conv: Conveyor, opts: DynamicsOptions, T_run: np.ndarray,
             implicit: np.ndarray, in_block: np.ndarray) -> tuple[Springs, np.ndarray]:
    """The springs' physical data (length, Ernst's sag term, floor, the mesh viscosity of the
    dynamic modulus, the carriage coupling, the running strain); the step's forms are set by
    :func:`_step_forms`. Returns the record and the wave speed per element [m/s]."""
    n = loop.n
    dx = loop.dx_m
    nxt = np.roll(np.arange(n), -1)
    EB = float(loop.belt.stiffness_n)
    EBd = float(loop.belt.dynamic_stiffness_n)
    len_m, a_el, t_floor, k_floor = chord_springs(loop, opts.ernst)
    carriage = np.zeros(n)
    if conv.takeup.type == "gravity":
        carriage[loop.i_takeup - 1] = 1.0
        carriage[loop.i_takeup] = 1.0
    # waves (dynamic modulus) and the mesh viscosity alpha Z per spring [N s/m]
    rho = loop.mG_kg_m + loop.mL_kg_m + loop.mR_kg_m
    c_wave = np.sqrt(EBd / rho)
    rho_spring = (rho * dx + rho[nxt] * dx[nxt]) / (dx + dx[nxt])
    alpha = 0.0 if opts.damping == "off" else float(opts.mesh_viscosity)
    viscosity = alpha * np.sqrt(EBd * rho_spring)
    z = np.zeros(n)
    if implicit[n - 2] == 0 or implicit[n - 1] == 0:
        # the limiter of a free spring reads the next spring's increment without wraparound
        raise ValueError("the springs beside the last element (the tail pulley) must be implicit")
    return Springs(
        len_m=_f64(len_m), a_ernst=_f64(a_el), t_floor=_f64(t_floor), k_floor=_f64(k_floor),
        viscosity=_f64(viscosity), car_ind=_f64(carriage),
        eps_run=_f64(chord_strain(T_run, a_el, EB, t_floor, k_floor)), eb=EB, eb_dyn=EBd,
        dl=z, a_eb=_f64(a_el * EB),
        s_floor=_f64(EB * chord_strain(t_floor, a_el, EB, t_floor, k_floor)),
        kfl_eb=_f64(k_floor / EB), kvs=z, e_damp=0.0, g_damp=0.0,
        seg_node=_ranges(~in_block), seg_spring=_ranges(~implicit),
        limited=1 if (opts.viscosity_limiter and alpha > 0.0) else 0), c_wave


def _blocks(blocks_list: list, master_node: int, n: int, shaft_index: dict,
            takeup_gravity: bool, i_takeup: int) -> Blocks:
    """The implicit blocks, the master drive's block first (the others use the speed loop's
    output); ``mdt`` is set with the step."""
    blocks = sorted(blocks_list, key=lambda b: 0 if master_node in b else 1)
    if max(len(b) for b in blocks) + 1 > BLOCK_MAX:
        raise ValueError("implicit block larger than the kernel's BLOCK_MAX")
    nodes = np.concatenate([np.asarray(b, dtype=np.int64) for b in blocks])
    node_shaft = np.full(n, -1, dtype=np.int64)
    for node, k in shaft_index.items():
        node_shaft[int(node)] = k
    return Blocks(
        ptr=np.concatenate(([0], np.cumsum([len(b) for b in blocks]))).astype(np.int64),
        nodes=nodes,
        car=_i64([1 if (takeup_gravity and i_takeup in b) else 0 for b in blocks]),
        left=_i64([(j - 1) % n for j in nodes]), mdt=np.zeros(len(nodes)),
        node_shaft=node_shaft)


def _damper(damping: str, springs: Springs, relaxation_s: float, dt: float
            ) -> tuple[float, float]:
    """(decay of the relaxing arm over a step, its gain per unit tangent stiffness and strain
    increment): the arm's tension ``d`` advances as ``d' = e d + g kt de`` (exact exponential
    of the standard linear solid's arm of stiffness ``(E_dyn - E) B``, relaxation time tau)."""
    if damping != "belt" or not springs.eb_dyn > springs.eb:
        return 0.0, 0.0
    h = dt / relaxation_s
    e = math.exp(-h)
    ratio = (springs.eb_dyn - springs.eb) / springs.eb
    return e, ratio * (1.0 - e) / h


def _step_forms(model: Model, dt: float, damping: str, relaxation_s: float) -> Model:
    """The records' forms for the step dt: dt / mass, dt / length, the mesh viscosity per
    strain increment, the arm's decay and gain, the blocks' mass / dt."""
    sp = model.springs
    e_damp, g_damp = _damper(damping, sp, relaxation_s, dt)
    springs = sp._replace(dl=_f64(dt / sp.len_m), kvs=_f64(sp.viscosity * sp.len_m / dt),
                          e_damp=e_damp, g_damp=g_damp)
    nodes = model.nodes._replace(hm=_f64(dt / model.nodes.mass))
    blocks = model.blocks._replace(mdt=_f64(model.nodes.mass[model.blocks.nodes] / dt))
    return model._replace(cycle=model.cycle._replace(dt=dt), nodes=nodes, springs=springs,
                          blocks=blocks)


def with_step(sys: System, dt: float) -> System:
    """The same model with the step dt [s] (no stability check: verification)."""
    return replace(sys, model=_step_forms(sys.model, float(dt), sys.damping, sys.relaxation_s))


def with_law(sys: System, coef: np.ndarray, pv: np.ndarray, ps: np.ndarray) -> System:
    """The same model with another resistance law (terms of coefficients (K, n) [N], speed
    and sag exponents, taken as they are), evaluated the way the kernel chooses for it
    (verification)."""
    m = sys.model
    law = law_record(coef, pv, ps, m.law.hs_ref, m.law.rtol)
    return replace(sys, model=m._replace(law=law, lin=_lin(law, m.nodes, m.cycle.v_eps)))


def with_probes(sys: System, probes) -> System:
    """The same model recording the springs ``probes`` at every record."""
    m = sys.model
    return replace(sys, model=m._replace(probes=m.probes._replace(probes=_i64(probes))))


def _step(mass, springs, implicit, damping, scn, opts, n) -> tuple[float, float]:
    """The stability limit of the explicit part with the instantaneous stiffness and the mesh
    viscosity, and the step: ``dt_safety`` of it, or the scenario's (refused above it)."""
    glassy = springs.eb_dyn if damping == "belt" else springs.eb
    dt_lim = stability_limit_s(mass, springs.len_m, glassy, implicit, springs.viscosity)
    if scn.dt_s == "auto":
        return opts.dt_safety * dt_lim, dt_lim
    dt = float(scn.dt_s)
    if dt > dt_lim:
        raise InputError(
            f"scenario.dt_s: {dt:g} s is above the stability limit {gnum(dt_lim)} s of this "
            f"model ({n} elements, shortest spring {gnum(springs.len_m.min(), 3)} m); use 'auto' or a "
            f"step below {gnum(dt_lim)} s")
    return dt, dt_lim


def _drive_train_step(conv, scn, parts, rated, v_d, dt, notes) -> tuple[float, float, int]:
    """The step resolving the fastest dol drive train (:func:`drive_train_time_s`): an
    automatic step is shortened to it, a given one kept with a note. Returns (dt, the train's
    time [s], its drive)."""
    t_train, k_train = drive_train_time_s(conv, parts, rated, v_d)
    if t_train / DRIVE_STEPS < dt:
        if scn.dt_s == "auto":
            notes.append(f"the step is {gnum(t_train / DRIVE_STEPS, 3)} s, not {gnum(dt, 3)} s: it resolves "
                         f"the fastest dol drive train ({gnum(t_train, 3)} s to reach design speed "
                         "unloaded at rated force): a heavier inertia_kg_m2 allows a longer step")
            dt = t_train / DRIVE_STEPS
        else:
            notes.append(f"scenario.dt_s {gnum(dt, 3)} s is longer than the fastest dol drive train "
                         f"({gnum(t_train, 3)} s to reach design speed unloaded at rated force): its "
                         "shaft and motor speeds may not be resolved, 'auto' resolves them")
    return dt, t_train, k_train


def _drives(conv: Conveyor, loop: Loop, shaft_index: dict, rated: np.ndarray,
            motor_mass: np.ndarray) -> Drives:
    """The drives in file order: shaft, share, rated force and limit, control, coupling, motor
    curve, fill and trip times, the motor's mass behind a coupling."""
    nd = len(conv.drives)
    limit = np.array([d.torque_limit for d in conv.drives]) * rated
    cx, cy, cn = padded_curves([tuple(d.curve) for d in conv.drives])
    z = np.zeros(nd)
    return Drives(
        shaft=_i64([shaft_index[e] for e in loop.drive_elements]),
        node=_i64(loop.drive_elements), share=_f64([d.share for d in conv.drives]),
        lim0=_f64(limit), lim=np.array(limit, dtype=np.float64), rated=_f64(rated),
        control=_i64([VFD if d.control == "vfd" else DOL for d in conv.drives]),
        coupling=_i64([COUPLING_CODES[d.coupling] for d in conv.drives]),
        curve_x=cx, curve_y=cy, curve_n=cn, fill_s=_f64([d.coupling_fill_s for d in conv.drives]),
        motor_mass=_f64(np.maximum(motor_mass, 1.0)),
        trip_s=_f64([d.trip_s for d in conv.drives]), mode=np.zeros(nd, dtype=np.int64), f0=z,
        f1=z.copy(), sat=np.zeros(nd, dtype=np.int64), win_f=z.copy(), lin_p=z.copy(),
        lin_d=z.copy(),
        lin_cs=z.copy(), vm=z.copy(), force=z.copy(), ft=z.copy(), f_trip=z.copy(),
        f_start=z.copy())


def _control(conv, scn, opts, drives: Drives, total_mass, m_loop, te, gravity_sum, t_loop,
             v_d) -> Control:
    """The speed loop on the master drive's shaft: bandwidth (:func:`speed_loop_bandwidth`),
    gains on the mass the loop sees (``m_loop``, :func:`loop_inertia`), the rigid-body
    feedforward (off unless ``opts.speed_feedforward``: measured on the example conveyors it
    makes the colocated loop track worse, docs/dynamics.md) with the reference speed at which
    its running resistance is complete, the followers' speed window."""
    wc = speed_loop_bandwidth(conv, opts)
    ff = bool(opts.speed_feedforward)
    # the feedforward of the running resistance ramps in with the reference speed, reaching
    # full when the reference has run for one wave loop time (the time the motion needs to
    # spread round the belt)
    v_ff, _ = profiles.start_reference(START_CODES[scn.start.control],
                                       min(t_loop, float(scn.start.time_s)),
                                       float(scn.start.time_s), v_d)
    v_ff = max(float(v_ff), float(opts.v_eps_m_s))
    return Control(vfd=bool(drives.control[0] == VFD), master=master_drive(conv),
                   kp=2.0 * wc * m_loop, ki=wc * wc * m_loop, bandwidth=wc,
                   m_tot=total_mass, f_res=te - gravity_sum, v_ff=v_ff,
                   f_const=float(opts.force_start_n or 0.0), window=SPEED_WINDOW * v_d,
                   t_track=float(t_loop), ff=1.0 if ff else 0.0)


def _rest(conv, loop, springs: Springs, gravity, T_run, tu_weight) -> tuple[int, np.ndarray,
                                                                            list[str]]:
    """The element holding the belt at rest and the at-rest tensions: the brakes hold a
    stopped belt when it has any (a friction drive could not hold a loaded incline or decline
    by itself), else the master drive; the take-up sets their level. Returns (element,
    tensions [N], warnings)."""
    hold = rest_hold_element(conv, loop)
    itu = loop.i_takeup
    T_rest = rest_walk(loop, hold, gravity)  # relative to T[itu - 1] = 0; fix the level
    if conv.takeup.type == "gravity":
        # the carriage carries both strands: T_in + T_out = m g (the element holding the belt
        # at rest may be the take-up pulley itself)
        T_rest += 0.5 * (tu_weight - T_rest[itu - 1] - T_rest[itu])
    else:
        T_rest += length_level(T_rest, T_run, springs.len_m, springs.a_ernst, springs.eb,
                               springs.t_floor, springs.k_floor)
    warns: list[str] = []
    if T_rest.min() < 0.0:
        k = int(np.argmin(T_rest))
        warns.append(f"held at rest the belt is slack at {loop.s_m[k] + loop.dx_m[k]:.0f} m "
                     f"(the take-up leaves {gnum(T_rest[k] / 1e3, 3)} kN there): raise the take-up "
                     "tension")
    warns += _rest_grip(loop, hold, T_rest, conv)
    return hold, T_rest, warns


def _rest_grip(loop, hold: int, T_rest: np.ndarray, conv=None) -> list[str]:
    """:func:`beltstudy.engine.statics.rest_grip_words` of the run's rest state: the transient
    model starts from it all the same (the hold is taken as given), so the run says so."""
    return rest_grip_words(loop, hold, T_rest, conv)


def _takeup(conv, loop, steady, springs: Springs, T_rest, T_run) -> Takeup:
    """The take-up: a gravity take-up's counterweight and carriage, its travel centred between
    the rest position (x = 0) and the running one (the belt stretches while running and the
    counterweight drops to take up the extra length: x grows by half the stretch, two
    strands), the rest position always inside the travel."""
    gravity_tu = conv.takeup.type == "gravity"
    weight, inertia, x_run = 0.0, 1.0, 0.0
    if gravity_tu:
        m_tu = float(steady.takeup_mass_kg)
        weight = m_tu * G
        inertia = m_tu + float(conv.takeup.carriage_mass_kg)
        args = (springs.a_ernst, springs.eb, springs.t_floor, springs.k_floor)
        eps_rest = chord_strain(np.maximum(T_rest, 0.0), *args)
        eps_run = chord_strain(T_run, *args)
        x_run = 0.5 * float(np.sum(springs.len_m * (eps_run - eps_rest)))
    travel = conv.takeup.travel_m if conv.takeup.travel_m is not None else 0.015 * loop.length_m
    mid = 0.5 * min(max(x_run, -travel), travel)
    return Takeup(gravity=gravity_tu, node=int(loop.i_takeup), weight=weight, mass=inertia,
                  lo=mid - 0.5 * travel, hi=mid + 0.5 * travel, x_run=x_run)


def handover_time_s(conv, loop, scn, opts: DynamicsOptions, hold: int) -> float:
    """The start's hand-over time [s]: vfd drives on a pulley other than the one holding the
    belt at rest (``hold``) build their share of the holding force over it after the start
    command while the hold keeps the belt, then the hold lets go and the speed loop starts
    from that force (:data:`HANDOVER_S`). 0 where nothing in the belt changes as the load
    passes from the hold to the drives (every drive on the held pulley), for dol drives (the
    motor's torque from its curve at once, as its contactor closes), the moving-support
    formulation and the verification's constant force."""
    if (conv.drives[0].control != "vfd" or scn.formulation != "relative"
            or opts.force_start_n is not None
            or all(int(e) == int(hold) for e in loop.drive_elements)):
        return 0.0
    return HANDOVER_S if opts.handover_s is None else float(opts.handover_s)


def _places(a: float, nd: int) -> str:
    """``a`` with ``nd`` decimals, trailing zeros dropped (2116.900896 on 1 decimal: 2116.9;
    3000.001 on 4: 3000.001; 2118 on 1: 2118)."""
    text = f"{a:.{nd}f}"
    return text.rstrip("0").rstrip(".") if "." in text else text


def short_element(conv, loop: Loop) -> tuple[str, str] | None:
    """The belt element that sets the automatic step when it is far shorter (under a tenth)
    than the strands' median element: a feed point, booster or take-up close to a profile
    section's end, a vertical curve's arc end or another such point cuts it off. Returns the
    field to move and the words saying where, or None when no element is that short."""
    idler = np.flatnonzero(loop.is_idler)
    if idler.size == 0 or loop.x_m is None:
        return None
    j = int(idler[np.argmin(loop.dx_m[idler])])
    dx = float(loop.dx_m[j])
    apart = 0.1 * float(np.median(loop.dx_m[idler]))
    if dx >= apart:
        return None
    x0 = float(loop.x_m[j])
    ends = (x0 - dx, x0, x0 + dx)  # the element's ends, either way along the route
    cuts = [(name, name, a) for name, a in route_points(conv)]  # (field, words, place)
    at = 0.0
    prof = conv.judged_profile()  # the curves the loop builds (none shorter than a pitch)
    for i, sec in enumerate(prof):
        half = 0.5 * curve_arc_m(prof, i)
        at += sec.length_m
        cuts.append((f"profile.{i}.length_m", f"the end of profile.{i}", at))
        if half > 0.0:
            cuts += [(f"profile.{i}.curve_radius_m", f"an end of the curve after profile.{i}",
                      at + d) for d in (-half, half)]
    tol = 1e-6 * max(1.0, loop.length_m)
    near = [c for c in cuts if any(abs(c[2] - e) <= tol for e in ends)]
    if not near:
        return None
    field = min(near, key=lambda c: (not c[0].endswith(".at_m"),
                                     not c[0].endswith(".curve_radius_m")))[0]
    # places to a tenth of the element: enough to tell its two ends apart, no more
    nd = max(0, min(6, 1 - math.floor(math.log10(dx)))) if dx > 0.0 else 6
    where = " and ".join(f"{words} ({_places(a, nd)} m)" for _, words, a in near)
    said = (f"the automatic step follows the shortest belt element, {gnum(dx, 3)} m long between "
            f"{where} from the tail: ")
    ended = {c[0] for c in near}
    tiny = [i for i in range(1, len(prof)) if f"profile.{i}.length_m" in ended
            and f"profile.{i - 1}.length_m" in ended]
    if tiny and not any(c[0].endswith(".at_m") for c in near):
        # the element is a whole section between two others: its own length is what to change
        # (moving the section before shifts both its ends alike)
        i = tiny[0]
        return f"profile.{i}.length_m", (
            f"{said}profile.{i} is {gnum(prof[i].length_m, 3)} m long; give it "
            f"{math.ceil(apart * 10.0) / 10.0:g} m or more (a tenth of the median element) or "
            "join it to a neighbouring section")
    i = int(field.split(".")[1]) if field.endswith(".curve_radius_m") else -1
    if i >= 0 and any(c[0] == f"profile.{i}.length_m" for c in near):
        # half the curve's own arc (its section's end is the arc's middle): nothing to move,
        # the arc grows with the radius (arc = R |delta|)
        r = float(prof[i].curve_radius_m)
        need = math.ceil(r * apart / (0.5 * curve_arc_m(prof, i)) / 10.0) * 10.0
        return field, (f"{said}a radius of {need:g} m or more ({field}, now {r:g} m) makes "
                       f"each half of the curve's {gnum(curve_arc_m(prof, i), 3)} m arc a tenth of "
                       "the median element or more")
    arc = None
    if i >= 0:
        mid = sum(sec.length_m for sec in prof[:i + 1])
        half = 0.5 * curve_arc_m(prof, i)
        arc = (mid - half - tol, mid + half + tol)
    if arc is not None and any(arc[0] <= a and b <= arc[1] for a, b in
                               ((x0 - dx, x0), (x0, x0 + dx))):
        # the element is a piece of the curve's arc (a turn of more than CURVE_STEP_DEG is cut
        # in pieces): a radius cannot be moved onto another point (a 5 km route was told to),
        # and each piece grows with the radius (R x its turn)
        r = float(prof[i].curve_radius_m)
        need = math.ceil(r * apart / dx / 10.0) * 10.0
        return field, (f"{said}a radius of {need:g} m or more ({field}, now {r:g} m) makes "
                       "each piece of the curve's arc a tenth of the median element or more")
    return field, (f"{said}move {field} onto the other point or "
                   f"{math.ceil(apart * 10.0) / 10.0:g} m or more away from it (a tenth of "
                   "the median element)")


def _cycle(conv, scn, opts, n, dt, t_loop, v_d, hold, drive_train,
           t_hand=0.0, short=None):
    """The cycle's times: the rest after the stop (one wave loop time at least, plus what
    holding brakes and the drives' trip take), the stop window
    (``DynamicsOptions.stop_window_s``, the same for every run), the records' spacing; the work limit of one run (refused beyond, naming what to change)."""
    t_train, k_train = drive_train
    hold_time = max([b.delay_s + (b.force_curve[-1][0] if b.force_curve else b.ramp_s)
                     for b in conv.brakes if b.hold] or [0.0])
    trip = max(d.trip_s for d in conv.drives)
    post = opts.post_rest_s if opts.post_rest_s is not None else (
        max(5.0, t_loop) + hold_time + trip)
    # the one "did not stop" window (DynamicsOptions.stop_window_s), the same for every run
    stop_max = float(opts.stop_window_s)
    start_s = float(scn.start.time_s)
    t_total = opts.pre_rest_s + start_s + scn.run_s + stop_max + post
    steps = t_total / dt
    if steps * n > 5e10:
        if scn.dt_s == "auto" and t_train / DRIVE_STEPS <= dt:
            raise InputError(
                f"drives.{k_train}.inertia_kg_m2: {gnum(steps, 3)} steps of {n} elements is too much "
                f"work for one run; the step, {gnum(dt, 3)} s, resolves the fastest dol drive train "
                f"({gnum(t_train, 3)} s to reach design speed unloaded at rated force): give the "
                "drives their real inertia (motor, coupling, gear and pulley reduced to the "
                "pulley shaft)")
        if scn.dt_s == "auto" and short is not None:
            raise InputError(
                f"{short[0]}: {gnum(steps, 3)} steps of {n} elements is too much work for one run "
                f"(over 5e10 element-steps) at a step of {gnum(dt, 3)} s; {short[1]}")
        raise InputError(
            f"scenario.dt_s / scenario.elements: {gnum(steps, 3)} steps of {n} elements is too much "
            f"work for one run (over 5e10 element-steps): a cycle of {gnum(t_total)} s (start "
            f"{start_s:g} s, run {scn.run_s:g} s, up to {gnum(stop_max)} s for the stop, the "
            f"rests) at a step of {gnum(dt, 3)} s; use fewer elements or a larger step, or shorter "
            "times")
    return Cycle(
        dt=dt, t_pre=float(opts.pre_rest_s), t_start=start_s, t_run=float(scn.run_s),
        t_stop=float(scn.stop.time_s), stop_max=stop_max, post_rest=float(post), t_end=0.0,
        rec_dt=float(scn.record_dt_s),
        surf_dt=max(scn.record_dt_s, t_total / max(opts.surface_samples, 1)), v_d=v_d,
        v_eps=float(opts.v_eps_m_s), v_fail=V_FAIL_FACTOR * v_d,
        start_ctrl=(profiles.FORCE if opts.force_start_n is not None
                    else START_CODES[scn.start.control]),
        stop_mode=STOP_CODES[scn.stop.mode],
        formulation=RELATIVE if scn.formulation == "relative" else SUPPORT, hold_node=int(hold),
        t_hand=float(t_hand))


def _probes(conv, loop, opts) -> Probes:
    """The recorded springs: head in and out, the tail pulley, ``probes`` springs spread round
    the loop, at most ``surface_points`` springs of the surface."""
    n = loop.n
    s_end = loop.s_m + loop.dx_m
    k = max(int(opts.probes), 1)
    targets = (np.arange(k) + 0.5) * float(s_end[-1]) / k
    probes = np.unique(np.clip(np.searchsorted(s_end, targets), 0, n - 1))
    stride = max(1, int(math.ceil(n / max(opts.surface_points, 1))))
    head_drives = [loop.drive_elements[i] for i, d in enumerate(conv.drives)
                   if d.position == "head"]
    s_head_out = max(head_drives) if head_drives else loop.i_head
    return Probes(s_head_in=int((loop.i_head - 1) % n), s_head_out=int(s_head_out),
                  i_tail=int(loop.i_tail), probes=_i64(probes),
                  surface=_i64(np.arange(0, n, stride)))


def _running(conv, steady, law: ResistanceLaw, v_d) -> tuple[np.ndarray, float, np.ndarray]:
    """Statics' running tensions [N], its effective tension [N] and the drives' rated forces
    [N] (:func:`beltstudy.engine.design.rated_power_kw`)."""
    T_run = np.asarray(steady.tension_n, dtype=np.float64)
    R_run = law.evaluate(v_d, 0.5 * (np.roll(T_run, 1) + T_run)) if law.tension_dependent \
        else law.evaluate(v_d)
    te = float(np.sum(steady.drive_force_n))
    rated = np.array(design.rated_power_kw(conv, te, float(np.sum(R_run)))[0]) * 1e3 / v_d
    return T_run, te, rated


def build_system(conv: Conveyor, scn: Scenario, steady, options: DynamicsOptions | None = None
                 ) -> System:
    """Build the transient model from a steady solution, section by section.

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
    n = loop.n
    notes: list[str] = []
    v_d = float(loop.speed_m_s)
    mass, shafts, shaft_index, parts = _shafts(conv, loop, opts)
    notes += shell_floor_notes(conv, loop)
    total_mass = float(mass.sum() + shafts.mass.sum() + np.sum(parts.motor_mass))
    law = _law(n, steady.law, opts)
    nodes = _nodes(loop, mass, steady.law, opts, law.hs_ref)
    T_run, te, rated = _running(conv, steady, steady.law, v_d)
    implicit, blocks_list = implicit_blocks(loop.strand)
    in_block = np.zeros(n, dtype=bool)
    for b in blocks_list:
        in_block[b] = True
    springs, c_wave = _springs(loop, conv, opts, T_run, implicit, in_block)
    t_loop = float(np.sum(loop.dx_m / c_wave))
    damping = "off" if opts.damping == "off" else "belt"
    tau = math.inf if damping == "off" else float(loop.belt.relaxation_s)
    dt, dt_lim = _step(mass, springs, implicit, damping, scn, opts, n)
    dt, *train = _drive_train_step(conv, scn, parts, rated, v_d, dt, notes)
    drives = _drives(conv, loop, shaft_index, rated, np.array(parts.motor_mass, dtype=float))
    gravity_sum = float(nodes.gravity.sum())
    m_loop = loop_inertia(conv, loop, shafts, shaft_index, c_wave,
                          speed_loop_bandwidth(conv, opts), total_mass)
    control = _control(conv, scn, opts, drives, total_mass, m_loop, te, gravity_sum, t_loop,
                       v_d)
    tu_weight = float(steady.takeup_mass_kg) * G if conv.takeup.type == "gravity" else 0.0
    hold, T_rest, warns = _rest(conv, loop, springs, nodes.gravity, T_run, tu_weight)
    takeup = _takeup(conv, loop, steady, springs, T_rest, T_run)
    brakes = build_brakes(conv, scn, loop, shaft_index, total_mass, te, gravity_sum, notes,
                          steady)
    short = short_element(conv, loop)
    if short is not None and scn.dt_s == "auto":
        # the run is right, only slow: say what makes it so
        notes.append(f"{short[1]} (a step of {gnum(dt, 3)} s)")
    cycle = _cycle(conv, scn, opts, n, dt, t_loop, v_d, hold, train,
                   handover_time_s(conv, loop, scn, opts, hold), short)
    model = Model(
        cycle=cycle, nodes=nodes, law=law, lin=_lin(law, nodes, cycle.v_eps), springs=springs,
        blocks=_blocks(blocks_list, int(drives.node[control.master]), n, shaft_index,
                       takeup.gravity, takeup.node),
        shafts=shafts, drives=drives, brakes=brakes, takeup=takeup, control=control,
        probes=_probes(conv, loop, opts))
    return System(
        model=_step_forms(model, dt, damping, tau), strand=loop.strand.copy(),
        s_end_m=loop.s_m + loop.dx_m, dx_m=loop.dx_m.copy(), i_head=int(loop.i_head),
        blocks=blocks_list, implicit=implicit, tension_rest_n=T_rest, hold_force_n=gravity_sum,
        steady_tension_n=T_run.copy(), te_n=te, wave_loop_time_s=t_loop, wave_speed_m_s=c_wave,
        dt_limit_s=dt_lim, damping=damping, relaxation_s=tau,
        mesh_viscosity=0.0 if damping == "off" else float(opts.mesh_viscosity), notes=notes,
        warnings=warns, drive_efficiency=np.array([float(d.efficiency) for d in conv.drives]))
