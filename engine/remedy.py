"""What avoids a drive's slip in the start or in the stop: the take-up and the start (stop)
time, found by rerunning.

A pulley slips in a start when the force its drive asks for exceeds what its slack-side
tension lets it pass, ``T_slack (e^(mu theta) - 1)``. Both sides of that inequality are
dynamic: the accelerating force and the slack-side tension's dip as the start's stress wave
runs round the loop (a follower at the tail sees the take-up's tension only a wave time
later), so statics does not give the take-up or the start time that avoids the slip (on the
16.8 km overland a take-up sized by statics for start-up slip slips in a 60 s start, and one
half again as heavy still slips at the tail drive). The figures here come from the transient
model itself: the start (and the run, up to the stop command) is rerun on the same mesh with
a heavier take-up, or a longer start, grown by steps until no drive slips and then bisected.

Each figure is the smallest value found with no slip, to :data:`REL_TOL` of itself, searched
up to :data:`TAKEUP_MAX` times the take-up and :data:`START_MAX` times the start time (at
least :data:`RIGID_MAX` x the rigid body's start time, :func:`time_top_s`); beyond that the
figure is None ("not within ... x"). A rerun costs about a run's start; the search
takes up to about a dozen each. Dol drives start on their motor curve whatever
``start.time_s`` is (their coupling sets how fast the torque comes on), so on a conveyor with
no vfd drive only the take-up is searched and the start time is None.

A slip in the stop (``phase="stop"``: a drive that slipped after the stop command) is searched
the same way with the whole cycle rerun (a rerun costs a cycle): the take-up, and for a
controlled stop ``stop.time_s`` (up to :data:`STOP_MAX` x the run's), with "no drive slips in
the stop" as the test; a coast or brake stop has no stop time of the search's to lengthen
(their levers are a controlled stop, the brakes' force and ramp), so only the take-up is
searched. Where the start slipped too, its take-up figure is tried first (``takeup_try``):
where it also avoids the stop's slip, one figure serves both (``takeup_shared``; the stop's
own least may be lower, not searched), else the search grows from it, so the stop's figure
is above the start's and, the slip margin growing with the take-up, avoids both.
"""

from __future__ import annotations

from dataclasses import dataclass

from beltstudy.engine.conveyor import Conveyor, Scenario
from beltstudy.engine.design import moving_mass_kg
from beltstudy.engine.dynamics import DynamicsOptions, build_system, simulate
from beltstudy.engine.statics import STARTUP_FACTOR, solve_steady

#: Bisection tolerance of each figure (relative).
REL_TOL = 0.02
#: Search limits: the take-up (mass or pretension) and the start time, times the run's own.
TAKEUP_MAX = 4.0
START_MAX = 6.0
#: Search limit of a controlled stop's ``stop.time_s``, times the run's own.
STOP_MAX = 6.0
#: The time searches reach at least this many times the rigid body's time (:func:`time_top_s`).
RIGID_MAX = 2.0
#: Growth factor of the bracketing steps.
GROW = 1.3


@dataclass(frozen=True)
class SlipRemedy:
    """Figures that avoid the slip of a start or a stop (None: not found within the search
    limit, or not searched).

    takeup_mass_kg : gravity take-up counterweight [kg] (None for a fixed take-up)
    takeup_tension_kn : fixed take-up pretension [kN] (None for a gravity take-up)
    start_time_s : start time [s] with the run's take-up (a start's slip)
    reruns : int, how many starts (for a stop's slip: cycles) were rerun
    phase : ``start`` or ``stop``, the slip searched
    stop_time_s : a controlled stop's ``stop.time_s`` [s] with the run's take-up (a stop's slip)
    takeup_shared : the take-up is the start's figure (``takeup_try``), which avoids the
        stop's slip too
    """

    takeup_mass_kg: float | None
    takeup_tension_kn: float | None
    start_time_s: float | None
    reruns: int
    phase: str = "start"
    stop_time_s: float | None = None
    takeup_shared: bool = False
    #: the longest start (stop) time the search tried [s] (:func:`time_top_s`; None: none)
    time_top_s: float | None = None


def _steady(conveyor: Conveyor, scenario: Scenario, model: str, params):
    n = None if scenario.elements == "auto" else int(scenario.elements)
    return solve_steady(conveyor, model=model, params=params,
                        temperature_c=scenario.temperature_c, load=scenario.load, n_elements=n)


def slipped_in_stop(tr) -> bool:
    """Whether a drive's slip on its pulley reached the stop of the transient ``tr``
    (:class:`~beltstudy.engine.dynamics.simulate.TransientResult`): its last slip, kept by the
    drive's record (``raw["drive_slip_last_s"]``), after the stop command. The slip warning
    says the same in words ("during the stop", "from the start into the stop")."""
    t_cmd = tr.system.stop_command_s
    return any(float(t) > t_cmd for t in tr.raw["drive_slip_last_s"])


def _slips(conveyor: Conveyor, scenario: Scenario, model: str, params, options,
           steady=None, phase: str = "start") -> bool:
    """Whether any drive slips between the start command and the stop command (``phase``
    ``start``), or in the stop of the whole cycle (``stop``: :func:`slipped_in_stop`; a run
    that fails counts as a slip). ``steady``: the conveyor's steady solve when known; the
    start and stop times do not change it."""
    steady = steady or _steady(conveyor, scenario, model, params)
    if steady.status == "failed":
        return True
    system = build_system(conveyor, scenario, steady, options)
    if phase == "stop":
        tr = simulate(system)
        return tr.status == "failed" or slipped_in_stop(tr)
    tr = simulate(system, t_end_s=system.stop_command_s)
    return any(tr.summary.get(f"drive{i + 1}_slip_s", 0.0) > 0.0
               for i in range(len(system.model.drives.share)))


def rigid_time_s(conveyor: Conveyor, scenario: Scenario, steady, stop: bool) -> float:
    """The start (stop) time [s] from which a rigid belt asks its drives for no more than
    the statics allow for (0 where there is none):

    * start (an s-curve or linear vfd start): the drives at ``STARTUP_FACTOR`` x Te, the
      checks' start-up force (DIN 22101), accelerate the moving mass M at
      ``a = (STARTUP_FACTOR - 1) Te / M``; the s-curve peaks at ``2 v / T``, the linear start
      runs at ``v / T``: ``T = 2 v / a`` (``v / a``);
    * controlled stop (a reverse s-curve): its peak deceleration ``2 v / T`` is within the
      coast's ``Te / M``, so the drives never brake the belt, from ``T = 2 M v / Te``.

    A regenerative belt (Te <= 0) or a torque start has none."""
    te = float(steady.te_n)
    if te <= 0.0:
        return 0.0
    m = moving_mass_kg(conveyor, steady)
    v = float(conveyor.speed_m_s)
    if stop:
        return 2.0 * m * v / te if scenario.stop.mode == "controlled" else 0.0
    shape = {"s-curve": 2.0, "linear": 1.0}.get(scenario.start.control, 0.0)
    return shape * v * m / ((STARTUP_FACTOR - 1.0) * te)


def time_top_s(conveyor: Conveyor, scenario: Scenario, steady, stop: bool) -> float:
    """How far the start (stop) time search goes [s]: :data:`START_MAX` (:data:`STOP_MAX`) x
    the run's time, and at least :data:`RIGID_MAX` x :func:`rigid_time_s`. A 10 s start of a
    3 km belt that slipped was searched only up to 60 s and the run said 'a longer start
    would not' avoid the slip, while 87 s did (the rigid body's start time was 48 s)."""
    t0 = float((scenario.stop if stop else scenario.start).time_s)
    return max((STOP_MAX if stop else START_MAX) * t0,
               RIGID_MAX * rigid_time_s(conveyor, scenario, steady, stop))


def _smallest(ok, x0: float, x_max: float) -> tuple[float | None, int]:
    """Smallest x in (x0, x_max] with ok(x), assuming ok is monotone: grow by GROW until ok,
    then bisect to REL_TOL. Returns (x or None, calls)."""
    lo, x, calls = x0, x0 * GROW, 0
    while True:
        calls += 1
        if ok(x):
            break
        lo = x
        if x >= x_max:
            return None, calls
        x = min(x * GROW, x_max)
    hi = x
    while hi - lo > REL_TOL * hi:
        mid = 0.5 * (lo + hi)
        calls += 1
        if ok(mid):
            hi = mid
        else:
            lo = mid
    return hi, calls


def reads_start_time(conveyor: Conveyor) -> bool:
    """Whether the start follows ``start.time_s``: a vfd drive's speed loop ramps over it; dol
    drives start on their motor curve (through their couplings) whatever it is, so a longer
    start is no remedy for them."""
    return any(d.control == "vfd" for d in conveyor.drives)


def reads_stop_time(scenario: Scenario) -> bool:
    """Whether the stop follows ``stop.time_s`` so that a longer one is the search's lever: a
    controlled stop (the drives ease the belt down over it). A coast has none; a brake stop's
    levers are its brakes' force and ramp (``stop.time_s`` only sizes an auto brake)."""
    return scenario.stop.mode == "controlled"


def slip_remedy(conveyor: Conveyor, scenario: Scenario, *, model: str, params=None,
                options: DynamicsOptions | None = None, elements: int | str,
                takeup_mass_kg: float | None = None,
                takeup_tension_kn: float | None = None, say=None, phase: str = "start",
                takeup_try: float | None = None) -> SlipRemedy | None:
    """The take-up and the start time that avoid a start's slip (see the module docstring);
    the start time only where the start reads it (:func:`reads_start_time`: a vfd drive).
    With ``phase="stop"``: the take-up and the stop time that avoid a stop's slip, the whole
    cycle rerun; the stop time only for a controlled stop (:func:`reads_stop_time`).

    Parameters
    ----------
    conveyor, scenario, model, params, options
        The run whose start (stop) slipped.
    elements : int or "auto"
        The element count the run asked for (its ``scenario.elements``), so the reruns use
        the run's own mesh. Not the count it used: the loop's cut adds an element or two to
        the asked count, and asking for the used count would give a finer mesh, whose
        stability limit a fixed ``dt_s`` valid for the run can exceed.
    takeup_mass_kg, takeup_tension_kn : float, optional
        The take-up the run used (gravity counterweight [kg], fixed pretension [kN]), as its
        summary gives them (auto sizes resolved).
    say : callable, optional
        Told ``what`` is searched once the rerun confirms that the start (stop) slips, before
        the search's reruns (not when the slip was in the other phase alone).
    phase : str
        ``start`` (a slip between the start and the stop command) or ``stop``.
    takeup_try : float, optional
        A stop's search: the take-up found for the start's slip, tried first (one rerun): where
        it avoids the stop's slip too it is the figure (``takeup_shared``), else the search
        grows from it.

    Returns None when the start (stop) does not slip on the rerun (the slip was in the other
    phase).
    """
    opts = options or DynamicsOptions()
    scn = scenario.model_copy(update={"elements": elements if elements == "auto"
                                      else int(elements)})
    gravity = conveyor.takeup.type == "gravity"
    base = takeup_mass_kg if gravity else takeup_tension_kn
    field = "mass_kg" if gravity else "pretension_kn"
    stop = phase == "stop"

    def with_takeup(x: float) -> Conveyor:
        return conveyor.model_copy(update={"takeup": conveyor.takeup.model_copy(
            update={field: float(x)})})

    def slips(c: Conveyor, s: Scenario, st=None) -> bool:
        return _slips(c, s, model, params, opts, st, phase=phase)

    fixed = conveyor if base is None else with_takeup(base)
    steady = _steady(fixed, scn, model, params)
    if not slips(fixed, scn, steady):
        return None
    timed = reads_stop_time(scenario) if stop else reads_start_time(conveyor)
    if say is not None:
        if stop:
            what = ("the take-up and the stop time (stop.time_s) that avoid it (about a dozen "
                    "reruns of the whole cycle each)" if timed else
                    "the take-up that avoids it (about ten reruns of the whole cycle; " + (
                        "a coast stop has no stop.time_s to lengthen)"
                        if scenario.stop.mode == "coast" else
                        "a brake stop's own levers, its brakes' force and ramp, are not "
                        "searched)"))
            say(f"a drive slips in the stop: rerunning the cycle to find {what}")
        else:
            what = ("the take-up and the start time that avoid it (about a dozen reruns)"
                    if timed else
                    "the take-up that avoids it (about ten reruns; a dol start does not read "
                    "start.time_s)")
            say(f"a drive slips in the start: rerunning the start to find {what}")
    reruns = 1
    tu, shared = None, False
    if base is not None and base > 0.0:
        top = TAKEUP_MAX * float(base)
        x0 = float(base)
        if takeup_try is not None and float(base) < takeup_try < top:
            reruns += 1
            shared = not slips(with_takeup(takeup_try), scn)
            if takeup_try * GROW <= top:  # the steps grow from it within the limit
                x0 = float(takeup_try)
        if shared:
            tu = float(takeup_try)
        else:
            tu, k = _smallest(lambda x: not slips(with_takeup(x), scn), x0, top)
            reruns += k
    which = scenario.stop if stop else scenario.start
    t0 = float(which.time_s)

    def with_time(t: float) -> Scenario:
        key = "stop" if stop else "start"
        return scn.model_copy(update={key: getattr(scn, key).model_copy(
            update={"time_s": t})})

    st, t_top = None, None
    if timed:
        t_top = time_top_s(fixed, scn, steady, stop)
        st, k = _smallest(lambda t: not slips(fixed, with_time(t), steady), t0, t_top)
        reruns += k
    return SlipRemedy(takeup_mass_kg=tu if gravity else None,
                      takeup_tension_kn=None if gravity else tu,
                      start_time_s=None if stop else st, reruns=reruns, phase=phase,
                      stop_time_s=st if stop else None, takeup_shared=shared,
                      time_top_s=t_top)


@dataclass(frozen=True)
class FinerCheck:
    """The figures of a :class:`SlipRemedy` tried on a mesh finer than the run's.

    elements : the finer mesh's element count (asked)
    takeup : the take-up (mass [kg] or pretension [kN]) with which no drive slips on the finer
        mesh: the run's figure where it holds there, else the one found there (None: not
        found within the search limit, or nothing to try)
    start_time_s : the same for the start time (a stop's check: for ``stop.time_s``)
    takeup_moved, start_moved : whether the run's figure slipped on the finer mesh
    reruns : int, how many starts (a stop's check: cycles) were rerun on the finer mesh
    """

    elements: int
    takeup: float | None
    start_time_s: float | None
    takeup_moved: bool
    start_moved: bool
    reruns: int


def confirm_finer(conveyor: Conveyor, scenario: Scenario, rem: SlipRemedy, *, model: str,
                  params=None, options: DynamicsOptions | None = None, elements: int,
                  takeup_base: float | None) -> FinerCheck:
    """Try the figures of ``rem`` (found on the run's mesh) on the finer mesh of ``elements``
    and, where a drive still slips there, search that mesh as :func:`slip_remedy` does, up
    from the run's figure (to the same limits, :data:`TAKEUP_MAX` x ``takeup_base`` and
    :data:`START_MAX` x the run's start time; a stop's remedy, ``rem.phase`` ``stop``: the
    whole cycle for a slip in the stop, and :data:`STOP_MAX` x the run's ``stop.time_s``).

    A slip margin is an extreme read behind the start's front, which the mesh smears: on a
    finer mesh the front is sharper and the slack side's dip deeper, so the least take-up or
    start time that avoids the slip can grow with the mesh (a 600 m incline's two dol drives
    with fluid couplings: 18.9 t on 53 elements, 20.2 t on 103, 22.1 t on 205, 23.8 t on
    409), and the figure found at the edge of the slip on the run's mesh slips on a finer one.
    ``options`` are the run's with the step rule the finer mesh uses (a fixed ``dt_s`` kept at
    its fraction of the stability limit: ``beltstudy.engine.run``)."""
    opts = options or DynamicsOptions()
    scn = scenario.model_copy(update={"elements": int(elements)})
    gravity = conveyor.takeup.type == "gravity"
    field = "mass_kg" if gravity else "pretension_kn"
    stop = rem.phase == "stop"

    def with_takeup(x: float) -> Conveyor:
        return conveyor.model_copy(update={"takeup": conveyor.takeup.model_copy(
            update={field: float(x)})})

    def slips(c: Conveyor, s: Scenario, steady=None) -> bool:
        return _slips(c, s, model, params, opts, steady, phase=rem.phase)

    reruns = 0
    tu = rem.takeup_mass_kg if gravity else rem.takeup_tension_kn
    tu_moved = False
    if tu is not None:
        reruns += 1
        if slips(with_takeup(tu), scn):
            tu_moved = True
            hi = TAKEUP_MAX * float(takeup_base) if takeup_base else TAKEUP_MAX * float(tu)
            tu, k = _smallest(lambda x: not slips(with_takeup(x), scn), float(tu),
                              max(hi, float(tu)))
            reruns += k
    st = rem.stop_time_s if stop else rem.start_time_s
    st_moved = False
    if st is not None:
        fixed = conveyor if takeup_base is None else with_takeup(takeup_base)
        steady = _steady(fixed, scn, model, params)
        key = "stop" if stop else "start"

        def with_time(t: float) -> Scenario:
            return scn.model_copy(update={key: getattr(scn, key).model_copy(
                update={"time_s": t})})

        reruns += 1
        if slips(fixed, with_time(st), steady):
            st_moved = True
            t_max = (rem.time_top_s if rem.time_top_s is not None else
                     (STOP_MAX if stop else START_MAX) * float(getattr(scenario, key).time_s))
            st, k = _smallest(lambda t: not slips(fixed, with_time(t), steady), float(st),
                              max(t_max, float(st)))
            reruns += k
    return FinerCheck(elements=int(elements), takeup=tu, start_time_s=st,
                      takeup_moved=tu_moved, start_moved=st_moved, reruns=reruns)


#: How a transient sag warning begins (:func:`beltstudy.engine.dynamics.simulate._sag_words`).
SAG_WARNING = "transient sag on the "


def sagged(tr) -> bool:
    """Whether the transient ``tr`` sagged past a limit: it warned of a transient sag, or a
    span went slack (its sag past every limit), or it failed."""
    return (tr.status == "failed" or any(w.startswith(SAG_WARNING) for w in tr.warnings)
            or (tr.summary.get("slack_max_m") or 0.0) > 0.0)


def _sags(conveyor: Conveyor, scenario: Scenario, model: str, params, options) -> bool:
    """Whether the whole cycle of ``conveyor`` sags past a limit (:func:`sagged`)."""
    steady = _steady(conveyor, scenario, model, params)
    if steady.status == "failed":
        return True
    # the conveyor gives the sag limits (without it the transient judges no sag)
    return sagged(simulate(build_system(conveyor, scenario, steady, options),
                           steady_summary=steady.summary, conveyor=conveyor))


@dataclass(frozen=True)
class SagRemedy:
    """The take-up that keeps a cycle's transient sag within its limits, found by rerunning.

    takeup : counterweight [kg] (gravity) or pretension [kN] (fixed) with no sag past a limit
        (None: none up to :data:`TAKEUP_MAX` x the run's)
    reruns : int, whole cycles rerun
    run_takeup : the figure found on the run's mesh (``takeup`` is the finer mesh's where
        that one still sagged there)
    finer_elements : the finer mesh tried (None: not tried)
    """

    takeup: float | None
    reruns: int
    run_takeup: float | None = None
    finer_elements: int | None = None


def sag_remedy(conveyor: Conveyor, scenario: Scenario, *, model: str, params=None,
               options: DynamicsOptions | None = None, elements: int | str,
               takeup: float | None, finer: tuple | None = None, say=None
               ) -> SagRemedy | None:
    """The least take-up (counterweight [kg] or pretension [kN], ``takeup`` the run's) with
    which the whole cycle, rerun on the run's mesh, sags past no limit: grown by :data:`GROW`
    up to :data:`TAKEUP_MAX` x the run's and bisected to :data:`REL_TOL`. A transient sag
    comes from the lowest tension of a stop's (start's) wave, and how much of a take-up
    change reaches that span then depends on the wave and on what the change does to the
    stop: a heavier take-up lets a brake's pulley grip more and stop the belt harder, so the
    tension the sag warning asks for (the whole change reaching the span) is a floor that
    may not avoid it (a 400 m plant belt's brake stop: 2 911 kg asked, 2.66 % sag against
    1.5 % with it; 3 527 kg found, 3 659 kg on a mesh twice as fine). With ``finer`` (the
    scenario and options of a checked run's finer mesh) the figure is tried there too and
    searched up from there where it still sags (a transient sag grows as the mesh sharpens
    the front). None without a take-up figure to grow."""
    if takeup is None or not takeup > 0.0:
        return None
    opts = options or DynamicsOptions()
    scn = scenario.model_copy(update={"elements": elements if elements == "auto"
                                      else int(elements)})
    field = "mass_kg" if conveyor.takeup.type == "gravity" else "pretension_kn"

    def with_takeup(x: float) -> Conveyor:
        return conveyor.model_copy(update={"takeup": conveyor.takeup.model_copy(
            update={field: float(x)})})

    if say is not None:
        say("a transient sag past its limit: rerunning the cycle to find the take-up that "
            "avoids it (about ten reruns of the whole cycle)")
    top = TAKEUP_MAX * float(takeup)
    tu, reruns = _smallest(lambda x: not _sags(with_takeup(x), scn, model, params, opts),
                           float(takeup), top)
    run_tu, fine_n = tu, None
    if finer is not None and tu is not None:
        fine_scn, fine_opts = finer
        fine_n = int(fine_scn.elements)
        reruns += 1
        if _sags(with_takeup(tu), fine_scn, model, params, fine_opts):
            tu, k = _smallest(lambda x: not _sags(with_takeup(x), fine_scn, model, params,
                                                  fine_opts), float(tu), max(top, float(tu)))
            reruns += k
    return SagRemedy(takeup=tu, reruns=reruns, run_takeup=run_tu, finer_elements=fine_n)


def brake_pulley_slid(tr, brakes: list[int]) -> bool:
    """Whether the pulley of the brakes ``brakes`` (indices in the file's ``brakes``) slid
    after the stop command in the transient ``tr`` (``raw["brake_pulley_slip"]``; a run that
    failed counts as a slide)."""
    if tr.status == "failed":
        return True
    t_cmd = tr.system.stop_command_s
    return any(set(slid["brakes"]) & set(brakes) and slid["last_s"] >= t_cmd
               for slid in tr.raw.get("brake_pulley_slip", ()))


def brake_force_remedy(conveyor: Conveyor, scenario: Scenario, *, model: str, params=None,
                       options: DynamicsOptions | None = None, elements: int | str,
                       forces_n: list[float], brakes: list[int],
                       takeup_mass_kg: float | None = None,
                       takeup_tension_kn: float | None = None
                       ) -> tuple[float | None, float | None, int]:
    """The largest force of the brakes ``brakes`` on one pulley with which that pulley does
    not slide in the stop, the whole cycle rerun on the run's mesh (``elements``, as
    :func:`slip_remedy`): their forces ``forces_n`` [N] (every brake of the file, as the run
    applied them; auto sizes in) divided together by a factor grown by :data:`GROW` from 1
    until the pulley holds, then bisected to :data:`REL_TOL`; the other brakes and the take-up
    (``takeup_mass_kg`` or ``takeup_tension_kn``, the run's) as they were. A smaller brake
    force lowers the slack side's fall in the stop (the brake's own front and the stop's
    deceleration), so the pulley passes it. Searched by :func:`_smallest` on the divisor of
    the forces. Returns ``(force [N], the stop time that force makes [s], reruns)``; force
    None where even 1/20 of it slides."""
    opts = options or DynamicsOptions()
    scn = scenario.model_copy(update={"elements": elements if elements == "auto"
                                      else int(elements)})
    tu = conveyor.takeup
    if tu.type == "gravity" and takeup_mass_kg is not None:
        tu = tu.model_copy(update={"mass_kg": float(takeup_mass_kg)})
    elif tu.type != "gravity" and takeup_tension_kn is not None:
        tu = tu.model_copy(update={"pretension_kn": float(takeup_tension_kn)})
    part = sum(forces_n[b] for b in brakes)
    stop_s: dict[float, float | None] = {}

    def holds(scale: float) -> bool:
        given = [b.model_copy(update={"force_kn": forces_n[i] * (scale if i in brakes else 1.0)
                                      / 1e3}) for i, b in enumerate(conveyor.brakes)]
        c = conveyor.model_copy(update={"brakes": given, "takeup": tu})
        steady = _steady(c, scn, model, params)
        if steady.status == "failed":
            return False
        tr = simulate(build_system(c, scn, steady, opts), conveyor=c)
        stop_s[scale] = tr.summary.get("stop_time_s")
        return not brake_pulley_slid(tr, brakes)

    # the force divided by x: the least x that holds is the largest force (_smallest's search)
    x, calls = _smallest(lambda x: holds(1.0 / x), 1.0, 20.0)
    if x is None:
        return None, None, calls
    return part / x, stop_s.get(1.0 / x), calls
