"""Drive checks: the motor power each drive needs against its rating, and its load in the
transient cycle (SPEC 7.4; docs/drives.md).

Steady, every run (:func:`steady_checks`, from :func:`beltstudy.engine.statics.solve_steady`):

* ``drive{i}_power_required_kw``: the motor power drive i needs at the run's steady state,
  its force at the pulley ``F_i`` (its share of the peripheral force Te) times the design speed
  through the drive train (gear unit and coupling, ``drives[i].efficiency``,
  :data:`~beltstudy.engine.conveyor.DRIVE_EFFICIENCY` by default):
  ``P_M = F_i v / eta`` when the motor drives the belt, ``P_M = |F_i v| eta`` when it holds a
  regenerating belt back (the losses then come off the power the motor takes in);
* ``drive{i}_utilisation = P_M / P_N`` against the rated power ``P_N`` the run used
  (``drives[i].rated_power_kw``, or the auto size of :func:`beltstudy.engine.design.
  rated_power_kw`); above 1 a warning names the drive and the shortfall in kW.

Transient (:func:`transient_checks`, from :mod:`beltstudy.engine.dynamics.simulate`; the
kernel accumulates them step by step, :data:`beltstudy.engine.dynamics.records.DRIVE_RESULT`):

* ``drive{i}_overload_s``: the time after the start command with the force at the pulley
  above the drive's rated force ``P_N / v`` (the force the transient model rates the drive
  at, the one its torque limit multiplies);
* ``drive{i}_force_rms_kn``: the root mean square of that force from the start command until
  the belt is at rest after the stop (the end of the run when it never stops), the thermal
  equivalent load of the cycle (a motor's heating follows its losses, which grow with the
  square of its current, nearly the square of its torque: the equivalent-torque method of
  motor selection for a duty cycle, IEC 60034-1's duty types S4-S10).

Warnings name the drive, how long it was above its rating and by how much, whether it sat at
its torque limit, and what would avoid it (a longer start, a larger motor).

References
----------
DIN 22101:2011-12, Continuous conveyors - Belt conveyors for loose bulk materials - Basis for
calculation and dimensioning: the motor power from the power at the drive pulleys through
the drive train's efficiency, divided for motoring and multiplied for regenerating operation
(*unverified*: the standard's text could not be checked here; the rule as quoted in belt
makers' design manuals that follow it).
CEMA, Belt Conveyors for Bulk Materials, 7th ed. (2014): motor power from Te V over the drive
efficiency (*unverified*, as above).
IEC 60034-1:2017, Rotating electrical machines - Rating and performance: momentary excess
torque of induction motors, 60 % over rated torque for 15 s (clause 9.4), occasional excess
current 1.5 x rated for 2 min up to 315 kW (clause 9.3) (*unverified*, as above).
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING

from beltstudy.engine.wording import gnum

if TYPE_CHECKING:  # the conveyor model, for the annotations only
    from beltstudy.engine.conveyor import Conveyor

__all__ = ["OVERLOAD_S_MAX", "RATED_POWER_FACTOR", "GIVEN", "rated_power_kw", "power_required_kw",
           "motor_size_kw",
           "kw_at_least", "up3", "down3", "apart", "steady_checks", "transient_checks", "WATTS_RATIO", "watts_notes"]

#: Longest time a drive may run above its rated force in a cycle without a warning [s]: the
#: 15 s for which IEC 60034-1 (clause 9.4, *unverified*) has an induction motor withstand
#: 60 % excess torque. Longer than that the motor's own overload rating decides.
OVERLOAD_S_MAX = 15.0

#: Installed drive power as a multiple of the motor power the steady state needs [-] (the
#: engine's default of ``drives[].rated_power_kw``: x 1.25 the power at the pulley through the
#: drive train's efficiency, :func:`rated_power_kw`). The project's estimate: SPEC
#: section 1 gives no default, and DIN 22101 leaves the reserve to the designer (unverified).
RATED_POWER_FACTOR = 1.25
#: ``*_governed_by`` of a size given in the conveyor file.
GIVEN = "given"


def rated_power_kw(conv: Conveyor, te_n: float, resistance_n: float
                   ) -> tuple[list[float], list[str]]:
    """Rated power of each drive [kW] and what set it: the file's value (``given``), else
    ``RATED_POWER_FACTOR`` x the motor power (:func:`power_required_kw`, through the drive's
    ``efficiency``) of the drive's share of the larger need: |Te| (``peripheral_force``; a
    regenerating belt's motor takes in ``|F v| eta``) or the running resistance [N], which
    the motor drives the belt against (``running_resistance``), at the design speed. Sized
    on the pulley's power alone, an auto motor behind a drive train of efficiency below
    ``1 / RATED_POWER_FACTOR`` (0.8) fell short of the power its own check asks
    (:func:`steady_checks`): 58 kW installed against 61.9 kW needed at 0.75."""
    v = float(conv.speed_m_s)
    kw, gov = [], []
    for d in conv.drives:
        if d.rated_power_kw is not None:
            kw.append(float(d.rated_power_kw))
            gov.append(GIVEN)
            continue
        size, why = _auto_kw(d, te_n, resistance_n, v)
        kw.append(size)
        gov.append(why)
    return kw, gov


def _auto_kw(drive, te_n: float, resistance_n: float, v: float) -> tuple[float, str]:
    """One drive's auto rated power [kW] and what set it (:func:`rated_power_kw`)."""
    return motor_size_kw(float(drive.share), float(drive.efficiency), te_n, resistance_n, v)


def motor_size_kw(share: float, efficiency: float, te_n: float, resistance_n: float,
                  speed_m_s: float) -> tuple[float, str]:
    """The auto rated power of a drive [kW] and what set it (``peripheral_force`` or
    ``running_resistance``), the rule of :func:`rated_power_kw` for one load case.

    Parameters
    ----------
    share : float
        The drive's share of the peripheral force [-].
    efficiency : float
        Its drive train's efficiency, motor shaft to pulley [-].
    te_n : float
        Peripheral force Te [N] (negative: the belt regenerates).
    resistance_n : float
        Running resistance, the force the motor drives the belt against [N].
    speed_m_s : float
        Design speed [m/s].

    Notes
    -----
    ``RATED_POWER_FACTOR x max(P(share Te), P(share R))`` with the motor power
    :func:`power_required_kw`: ``F v / eta`` motoring, ``|F v| eta`` regenerating.
    """
    by_te = power_required_kw(share * te_n, speed_m_s, efficiency)
    by_res = power_required_kw(share * resistance_n, speed_m_s, efficiency)
    return (RATED_POWER_FACTOR * max(by_te, by_res),
            "peripheral_force" if by_te >= by_res else "running_resistance")


#: A given rated power this many times what an auto size would install is read as a power
#: written in W for kW [-]: a motor sized anywhere from half to twice the need and written in
#: watts is 500 to 2 000 x it, while no built drive is hundreds of times its belt's need
#: (motors come in steps of about 1.25 x, the smallest a fraction of a kW).
WATTS_RATIO = 500.0


def watts_notes(conv: Conveyor, te_n: float, resistance_n: float) -> list[str]:
    """The notes of given rated powers :data:`WATTS_RATIO` or more times what an auto size
    would install (:func:`rated_power_kw`): ``rated_power_kw: 15000`` for a 15 kW motor
    passed with a utilisation of 0.0003 and a transient driven by a 15 MW motor."""
    notes = []
    for i, d in enumerate(conv.drives):
        need = _auto_kw(d, te_n, resistance_n, float(conv.speed_m_s))[0]
        if d.rated_power_kw is None or not need > 0.0:
            continue
        ratio = float(d.rated_power_kw) / need
        if 0.0 < ratio <= 1.0 / WATTS_RATIO:
            # the other way: 1.25 for a 1250 kW motor, written in MW
            notes.append(
                f"note: drives.{i}.rated_power_kw {float(d.rated_power_kw):.6g} kW is 1/"
                f"{1.0 / ratio:,.0f} of the {figures(need)} kW an auto size installs for drive "
                f"{i + 1} ({d.where}); rated_power_kw is in kW: if it was written in MW, it "
                f"is {figures(float(d.rated_power_kw) * 1e3, True)} kW")
        if ratio >= WATTS_RATIO:
            notes.append(
                f"note: drives.{i}.rated_power_kw {figures(float(d.rated_power_kw), True)} kW "
                f"is {ratio:,.0f} x the {figures(need)} kW an auto size installs for drive "
                f"{i + 1} ({d.where}: {RATED_POWER_FACTOR:g} x the motor power of its share "
                f"{d.share:g} of the larger of |Te| and the running resistance, "
                f"{gnum(max(abs(te_n), resistance_n) / 1e3, 3)} kN, x {conv.speed_m_s:g} m/s "
                f"through its efficiency {float(d.efficiency):g}); "
                f"rated_power_kw is in kW: if it was written in W, it is "
                f"{figures(float(d.rated_power_kw) / 1e3)} kW")
    return notes


def power_required_kw(force_n: float, speed_m_s: float, efficiency: float) -> float:
    """The motor power a drive needs for a force at its pulley [kW].

    Parameters
    ----------
    force_n : float
        Force the pulley passes to the belt, driving positive [N] (negative: the drive holds
        a regenerating belt back).
    speed_m_s : float
        Belt speed [m/s].
    efficiency : float
        Drive train efficiency from the motor shaft to the pulley (gear unit, coupling) [-].

    Returns
    -------
    float
        The motor power's magnitude [kW]: ``F v / eta`` motoring, ``|F v| eta`` regenerating.

    Notes
    -----
    The motor supplies the pulley's power and the drive train's losses when it drives; when
    it brakes a regenerating belt the losses are taken from the belt's power before it
    reaches the motor (DIN 22101, CEMA; *unverified*, see the module's references).
    """
    p = force_n * speed_m_s
    return (p / efficiency if p >= 0.0 else -p * efficiency) / 1e3


def kw_at_least(kw: float) -> int:
    """A power [kW] as a rating to advise: the whole kilowatt at or above it. Rounded to the
    nearest, 998.3 kW needed was advised as a motor of "at least 998 kW", whose utilisation
    is 1.0003: the advice did not pass. The 1e-9 keeps a need of a whole kilowatt (up to
    float noise) at that kilowatt, within the check's own 1e-9."""
    return math.ceil(kw * (1.0 - 1e-9))


def up3(x: float, digits: int = 3) -> float:
    """``x`` rounded up at three (``digits``) significant figures, for a least value a warning
    advises (a tension, a pretension, a brake force that must make up a whole): rounded to the
    nearest, a sag short of 804.25 N was advised as "0.804 kN more per strand", which left the
    span 0.25 N short and warned again. The 1e-9 keeps a value already of that many figures
    (up to float noise) as it is."""
    if not math.isfinite(x) or x <= 0.0:
        return x
    step = 10.0 ** (math.floor(math.log10(x)) - (digits - 1))
    return float(f"{math.ceil(x / step - 1e-9) * step:.{digits}g}")


def down3(x: float, digits: int = 3) -> float:
    """``x`` rounded down at three (``digits``) significant figures, for a largest value a
    warning or an error advises (a capacity, a design load, a brake force found to hold its
    pulley): taken, it passes. The 1e-9 keeps a value already of that many figures (up to
    float noise) as it is."""
    if not math.isfinite(x) or x <= 0.0:
        return x
    step = 10.0 ** (math.floor(math.log10(x)) - (digits - 1))
    return float(f"{math.floor(x / step + 1e-9) * step:.{digits}g}")


def figures(value: float, thousands: bool = False) -> str:
    """A quantity in a message [any unit]: whole units from 10 up, two significant figures
    below, so a small value keeps its figures (a motor rated 0.2 kW was 'rated 0 kW', a need
    of 0.7 kW 'short by 1 kW') and a large one is not cut to powers of ten (17000, not
    '1.7e+04' as ``:.2g`` gives); ``thousands``: whole units with separators (17,000)."""
    if abs(value) >= 10 or not math.isfinite(value):
        return f"{value:,.0f}" if thousands else f"{value:.0f}"
    return f"{value:.2g}"


def _rating(kw: float) -> str:
    """A rated power in words [kW]: as :func:`figures`, with three significant figures below
    10 kW, so a rating given as 1.25 reads 1.25 (it read 1.2)."""
    return f"{gnum(kw, 3)}" if 0.0 < abs(kw) < 10.0 else figures(kw)


def apart(value: float, limit: float, decimals: int = 2, rtol: float = 1e-9
          ) -> tuple[str, str]:
    """A value and the limit it is judged against, printed [any unit] so that the printed
    pair compares as the numbers do: at ``decimals`` decimals, more (up to 6) where rounding
    would print them equal though one is below the other by more than ``rtol`` (a safety
    factor 6.5487 against a minimum 6.549 read '6.55 < 6.55'; a utilisation 60.04 % over
    the band edge 60 % read '60 %' while its band is the one above). Within ``rtol`` they are
    equal, as the checks' own tolerances take them."""
    equal = abs(value - limit) <= rtol * max(abs(limit), abs(value))
    for d in range(decimals, 7):
        a, b = f"{value:.{d}f}", f"{limit:.{d}f}"
        if equal or (float(a) - float(b)) * (value - limit) > 0.0:
            return a, b
    return a, b


def steady_checks(conv, forces_n, speed_m_s: float, te_n: float, rated_kw
                  ) -> tuple[dict, list[str]]:
    """The steady drive fields and the warnings of a drive short of power.

    Parameters
    ----------
    conv : Conveyor
        For each drive's position, share and efficiency.
    forces_n : sequence of float
        Each drive's force at its pulley, file order [N] (driving positive).
    speed_m_s : float
        Design speed [m/s].
    te_n : float
        Peripheral force Te [N].
    rated_kw : sequence of float
        Each drive's rated power as the run uses it [kW].

    Returns
    -------
    fields : dict
        ``drive{i}_power_required_kw`` [kW] and ``drive{i}_utilisation`` [-].
    warnings : list of str
    """
    fields: dict = {}
    warnings: list[str] = []
    for i, (d, f, rated) in enumerate(zip(conv.drives, forces_n, rated_kw, strict=True),
                                      start=1):
        eta = float(d.efficiency)
        need = power_required_kw(float(f), speed_m_s, eta)
        fields[f"drive{i}_power_required_kw"] = need
        fields[f"drive{i}_utilisation"] = need / rated if rated > 0 else None
        if need > rated * (1.0 + 1e-9) and math.isfinite(need):
            how = ("holds back" if f < 0 else "needs")
            regen = ", regenerating: x efficiency" if f < 0 else " / efficiency"
            warnings.append(
                f"drive {i} ({d.where}) {how} {figures(need)} kW at {speed_m_s:g} m/s "
                f"({d.share:g} x Te {te_n / 1e3:.1f} kN{regen} {eta:g}), rated "
                f"{_rating(rated)} kW: short by {figures(need - rated)} kW (utilisation "
                f"{need / rated:.2f}); a motor of at least {kw_at_least(need)} kW "
                f"(drives.{i - 1}.rated_power_kw), or the load shared by more drives, "
                "would avoid it")
        # a vfd caps its force at torque_limit x the rated force P_N / v (as the transient
        # does, engine/dynamics/model.py): a cap below the running force never lets the
        # belt reach design speed
        cap = float(d.torque_limit) * rated * 1e3 / speed_m_s
        if d.control == "vfd" and abs(float(f)) > cap * (1.0 + 1e-9) and math.isfinite(cap):
            warnings.append(
                f"drive {i} ({d.where}) force limit {cap / 1e3:.1f} kN (torque_limit "
                f"{d.torque_limit:g} x rated {_rating(rated)} kW / {speed_m_s:g} m/s) is "
                "below its "
                f"running force {abs(float(f)) / 1e3:.1f} kN: it cannot hold the belt at "
                f"design speed; a torque_limit of at least "
                f"{math.ceil(abs(float(f)) / (rated * 1e3 / speed_m_s) * 100 - 1e-6) / 100:.2f} "
                f"(drives.{i - 1}.torque_limit) or a larger motor would avoid it")
    return fields, warnings


#: What brings a dol drive's torque on more slowly, by its coupling (``Drive.coupling``): the
#: next coupling, or a slower fill of the one it has.
COUPLING_NEXT = {"none": "a fluid coupling",
                 "fluid": "a fill-controlled coupling (coupling: fluid_fill_controlled)",
                 "fluid_fill_controlled": "a slower coupling fill (a longer coupling_fill_s)"}
#: What softens a dol drive's start in an overload warning: :data:`COUPLING_NEXT` or a vfd.
DOL_SOFTER = {k: f"{v}, a vfd" for k, v in COUPLING_NEXT.items()}


def _rate_within(motor: str, what: str, force_n: float) -> str:
    """The cure of an overload whose rigid-body acceleration or deceleration force (``what``,
    ``force_n`` [N]) keeps within what the rating leaves: the force above the rating follows
    the belt's waves and swing, which a longer start or stop would not remove."""
    longer = "start" if what.startswith("start") else "stop"
    # inside the motor's brackets, so the caller's "would avoid it" follows the motor
    return (f"{motor[:-1]}; the {what} ({gnum(force_n / 1e3, 3)} kN on this drive) keeps within "
            "the rating, so the force above it comes from the belt's waves and swing, which a "
            f"longer {longer} would not remove)")


def _seconds(duration_s: float) -> str:
    """A duration in words to 0.1 s, and to two figures below it (``0.04 s``, not ``0.0 s``:
    a drive at its torque limit for a few steps was said to be there 'for 0.0 s')."""
    return f"{duration_s:.1f} s" if duration_s >= 0.095 else f"{duration_s:.2g} s"


def _time_at_least(seconds: float) -> int:
    """A start or stop time [s] to advise: the whole second at or above the rigid-body
    estimate. Rounded to the nearest, an estimate of 177.05 s at a 177 s start was advised as
    "about 177 s", the start already run, which does not clear the warning."""
    return math.ceil(seconds * (1.0 - 1e-9))


def _swung_start(start_s: float, fmax: float, f_run: float, f_acc: float, rated: float,
                 need: int) -> str:
    """The second start-time figure [s] of a vfd start's overload, beside the rigid-body one
    (``need``): the run's own peak above its running force, ``fmax - f_run`` [N], scaled as
    1 / t as the rigid body's ``f_acc`` is, where it is larger. The belt's swing about the
    rigid body (the wave the s-curve's jerk sends round the loop) grows with the acceleration
    too, and the rigid-body figure leaves it out: a 5 km route's 60 s start over its rating
    was told about 128 s, and at 128 s its drives were still over for 19.6 s (its peak 12 kN
    above the rigid body's). A peak at the hand-over from rest does not scale so; the words
    say to read the peak's time. "" where the run's peak is within the rigid body's."""
    if not fmax - f_run > f_acc:
        return ""
    swung = _time_at_least(start_s * (fmax - f_run) / (rated - f_run))
    if swung <= need:
        return ""
    return (f", about {swung} s with the run's own peak above its running force "
            f"({gnum((fmax - f_run) / 1e3)} kN against the rigid body's {gnum(f_acc / 1e3)} kN) "
            "scaled as 1 / t: the belt's swing about the rigid body, which that estimate "
            "leaves out, unless the peak is the hand-over from rest (its time above); rerun "
            "to check")


def _swing_start(start_s: float, fmax: float, f_run: float, f_acc: float, rated: float) -> str:
    """A longer start for a vfd start whose rigid-body acceleration force ``f_acc`` [N] keeps
    within what the rating leaves but whose run went above it: the run's own peak above its
    running force, ``fmax - f_run`` [N], scaled as 1 / t, ``t (F_max - F_run) / (F_rated -
    F_run)``. The force above the rigid body's is the belt's swing about it (the take-up and
    the far belt letting go once the stretch front has passed, docs/dynamics.md, Settling),
    which the start's acceleration excites, so a gentler start excites less of it: a 6 km
    overland over its rating by 10 % at a 156 s start was over for 26.8 s, by 3 % at 185 s,
    and within the rating at 250 s (this estimate: 222 s). Words were "which a longer start
    would not remove"."""
    need = _time_at_least(start_s * (fmax - f_run) / (rated - f_run))
    return (f"a longer start (start.time_s, now {start_s:g} s; about {need} s with the run's "
            f"own peak above its running force ({gnum((fmax - f_run) / 1e3)} kN) scaled as "
            f"1 / t: the start's rigid-body acceleration ({gnum(f_acc / 1e3, 3)} kN on this "
            "drive) keeps within the rating, so the force above it is the belt's swing about "
            "the rigid body, which a gentler start excites less, unless the peak is the "
            "hand-over from rest (its time above); rerun to check)")


def transient_checks(names, drv, rated_n, limit_n, vfd, speed_m_s: float, start_s: float,
                     running_n=None, coupling=None, stop_s: float | None = None,
                     stop_accel_n=None, start_accel_n=None) -> tuple[dict, list[str]]:
    """The transient drive fields and the warnings of a drive overloaded in the cycle.

    Parameters
    ----------
    names : sequence of str
        Each drive's name for the warnings (``drive 1 (head)``).
    drv : numpy structured array
        The kernel's per-drive results (:data:`~beltstudy.engine.dynamics.records.
        DRIVE_RESULT`): ``fmax`` [N], ``fmax_t``, ``over_s``, ``over_stop_s``, ``lim_s``,
        ``rms_s`` [s], ``f2_int`` [N^2 s].
    rated_n, limit_n : sequence of float
        Each drive's rated force ``P_N / v`` and torque limit (as a force at the pulley) [N].
    vfd : sequence of bool
        Whether each drive is on a variable-speed drive (its start time is the scenario's).
    speed_m_s : float
        Design speed [m/s].
    start_s : float
        The scenario's start time [s].
    running_n : sequence of float, optional
        Each drive's steady running force [N] (its share of Te): the start time that keeps the
        force within the rating is estimated from it.
    coupling : sequence of str, optional
        Each drive's coupling (``none``, ``fluid``, ``fluid_fill_controlled``): a dol drive's
        softer start is offered by it (:data:`DOL_SOFTER`; ``none`` without it).
    stop_s : float, optional
        The stop time of a controlled stop [s] (None for a coast or brake stop, in which the
        drives are off): an overload mostly after the stop command is cured by a longer stop,
        not a longer start.
    stop_accel_n : sequence of float, optional
        Each drive's share of the rigid-body deceleration force at the controlled stop's peak
        deceleration, ``share x m a_peak`` [N]: the stop time that keeps the force within the
        rating is estimated from it (the force the run reached may be capped by the pulley's
        grip or the torque limit, so it would under-estimate).
    start_accel_n : sequence of float, optional
        The same at the start's peak acceleration, ``share x m a_peak`` [N] (NaN for a torque
        start, which has no speed curve: its estimate comes from the largest force reached).

    Returns
    -------
    fields : dict
        ``drive{i}_overload_s`` [s] and ``drive{i}_force_rms_kn`` [kN] (None when the cycle
        ended at the start command).
    warnings : list of str
    """
    fields: dict = {}
    warnings: list[str] = []
    for k, name in enumerate(names):
        i = k + 1
        d = drv[k]
        over_s, lim_s, rms_s = float(d["over_s"]), float(d["lim_s"]), float(d["rms_s"])
        rms = math.sqrt(float(d["f2_int"]) / rms_s) if rms_s > 0.0 else None
        fields[f"drive{i}_overload_s"] = over_s
        fields[f"drive{i}_force_rms_kn"] = rms / 1e3 if rms is not None else None
        rated = float(rated_n[k])
        fmax = float(d["fmax"])
        at_limit = lim_s > 0.0 and fmax >= float(limit_n[k]) * (1.0 - 1e-6)
        hot = rms is not None and rms > rated
        if rated <= 0.0 or not (over_s > OVERLOAD_S_MAX or at_limit or hot):
            continue
        pct = 100.0 * (fmax / rated - 1.0)
        over_stop = float(d["over_stop_s"])
        in_stop = over_stop > over_s - over_stop  # the larger part of the overload's time
        split = (f" ({over_s - over_stop:.1f} s in the start and run, {over_stop:.1f} s in the "
                 "stop)" if over_stop > 0.0 else "")
        if fmax > rated:
            said = (f"{name} was above its rated force ({gnum(rated / 1e3)} kN) for {_seconds(over_s)} "
                    f"of the cycle{split}, at most {pct:.0f} % over its rating "
                    f"({gnum(fmax / 1e3)} kN at t = {float(d['fmax_t']):.1f} s)")
            if at_limit:
                said += (f", at its torque limit ({gnum(float(limit_n[k]) / 1e3)} kN) for "
                         f"{_seconds(lim_s)}")
        else:  # a torque limit below the rating: never above the rating, held at the limit
            said = (f"{name} was held at its torque limit ({gnum(float(limit_n[k]) / 1e3)} kN, "
                    f"{100.0 * float(limit_n[k]) / rated:.0f} % of its rated force "
                    f"{gnum(rated / 1e3)} kN) for {_seconds(lim_s)} of the cycle (first at t = "
                    f"{float(d['fmax_t']):.1f} s)")
        if hot:
            said += (f"; its RMS force over the cycle, {gnum(rms / 1e3)} kN, is above the "
                     "rating (the motor overheats when the cycle repeats)")
        f_run = float(running_n[k]) if running_n is not None else None
        # the force the motor must give is at least the largest reached and the running
        # force; a force held at the torque limit shows only a lower bound of the need
        kw = max(fmax, abs(f_run) if f_run is not None else 0.0) * speed_m_s / 1e3
        if at_limit:
            within = (f"more than {figures(kw)} kW: its force was held at its torque limit, so the "
                      "run does not show how much more it needs")
        else:
            within = f"at least {kw_at_least(kw)} kW keeps it within"
        motor = f"a larger motor ({within})"
        f_acc = (float(start_accel_n[k]) if start_accel_n is not None
                 and math.isfinite(float(start_accel_n[k])) else None)
        f_dec = float(stop_accel_n[k]) if stop_accel_n is not None else None
        phase = "stop" if in_stop else "start"
        if f_run is not None and abs(f_run) >= rated:
            # running (or holding back) itself needs more than the rating: no start or stop
            # keeps the force within it
            fix = (f"{motor}, or the load shared by more drives (its running force, "
                   f"{gnum(f_run / 1e3)} kN, is itself above the rating: no {phase} avoids it)")
        elif in_stop and not (vfd[k] and stop_s is not None):
            fix = motor  # the drives are off in a coast or brake stop
        elif in_stop and f_run is not None and f_dec is not None and f_dec <= rated + f_run:
            fix = _rate_within(motor, "stop's rigid-body deceleration", f_dec)
        elif in_stop:
            # braking the belt: a slower stop asks less of the drive, a longer start nothing
            longer = f"a longer stop (stop.time_s, now {stop_s:g} s"
            if f_run is not None and f_dec is not None:
                # rigid body: F = f_run - m a, the peak deceleration as 1 / stop time
                need = _time_at_least(stop_s * f_dec / (rated + f_run))
                longer += (f"; about {need} s keeps the force within the rating, a "
                           "rigid-body estimate")
            fix = f"{longer}) or {motor}"
        elif vfd[k] and f_run is not None and f_run < 0.0:
            # a regenerating drive holds the belt back hardest at rest and creeping speed,
            # before the speed-dependent resistances build up; the acceleration eases it
            fix = (f"a larger motor ({within}; the drive holds back "
                   "the belt's downhill pull hardest at low speed, before the running "
                   "resistances build up, which a longer start would not shorten)")
        elif (vfd[k] and f_run is not None and f_acc is not None and f_acc <= rated - f_run
              and fmax > rated):
            fix = f"{_swing_start(start_s, fmax, f_run, f_acc, rated)} or {motor}"
        elif vfd[k] and f_run is not None and f_acc is not None and f_acc <= rated - f_run:
            fix = _rate_within(motor, "start's rigid-body acceleration", f_acc)
        elif vfd[k]:
            longer = f"a longer start (start.time_s, now {start_s:g} s"
            if f_run is not None and f_acc is not None:
                # rigid body: F = f_run + m a, the peak acceleration as 1 / start time
                need = _time_at_least(start_s * f_acc / (rated - f_run))
                longer += (f"; about {need} s keeps the force within the rating, a "
                           "rigid-body estimate")
                longer += _swung_start(start_s, fmax, f_run, f_acc, rated, need)
            elif f_run is not None and rated < fmax:
                # a torque start (no speed curve): from the largest force the run reached
                need = _time_at_least(start_s * (fmax - f_run) / (rated - f_run))
                longer += (f"; about {need} s keeps the force within the rating, a "
                           "rigid-body estimate")
            fix = f"{longer}) or {motor}"
        else:
            # a dol motor's start force is its torque curve (and coupling) times its rating:
            # a larger motor starts as far over its own rating, only for a shorter time, and
            # pulls the belt harder (a larger slip and overspeed risk), so it keeps nothing
            # within the rating; the RMS force (set by the running load) it does bring within
            softer = DOL_SOFTER[coupling[k] if coupling is not None else "none"]
            rms_fix = (f", and at least {kw_at_least(rms * speed_m_s / 1e3)} kW brings the RMS "
                       "force within" if hot else "")
            fix = (f"a softer start ({softer}) or a larger motor, which shortens the time over "
                   f"its rating{rms_fix} but not the {pct:.0f} % over it (a dol motor's start "
                   "force is its torque curve times its rating, so a larger one starts the "
                   "belt harder)")
        warnings.append(f"{said}; {fix} would avoid it")
    return fields, warnings

