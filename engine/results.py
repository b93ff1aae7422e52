"""Every result of a run, defined once: name, unit and meaning (SPEC sections 4 and 6.4).

A run's summary (``RunResult.summary``, the ``--json`` of ``beltstudy static`` and
``simulate``) holds these fields and no others (:func:`check_summary`); the service's Parquet
``runs`` schema, its REST rows, the CLI tables and the table in ``docs/results.md``
(:func:`markdown`, ``python -m beltstudy.engine.results``) are derived from them. A field added here is
stored, printed and documented; a key a run computes without a field here is an error, so a
result cannot be computed and silently dropped.

Groups, in the order of the runs table: :data:`STEADY`, :data:`STEADY_DRIVE`,
:data:`DESIGN`, :data:`DESIGN_DRIVE`, :data:`TE_COMPONENTS`, :data:`TRANSIENT`,
:data:`PHASE`, :data:`SLACK`, :data:`TRANSIENT_DRIVE`, :data:`DRIVE_POWER`,
:data:`DRIVE_LOAD`, :data:`DESIGN_BASIS`, :data:`CHECKS`, :data:`CHECKS_TRANSIENT`,
:data:`BOOKKEEPING`. Per-drive fields are named with ``{i}``, the drive's 1-based number in
file order (``drive{i}_slip_m``), and stored for drives 1 to :data:`MAX_DRIVES`; per-pulley
fields with ``{j}``, the pulley's 1-based number in loop order (``pulley{j}_resultant_kn``),
stored for pulleys 1 to :data:`MAX_PULLEYS`; per-curve fields with ``{k}``, the vertical
curve's 1-based number in profile order (``curve{k}_liftoff``), for curves 1 to
:data:`MAX_CURVES` (group :data:`CURVES`).
"""

from __future__ import annotations

from dataclasses import dataclass

__all__ = [
    "ResultField",
    "ResultGroup",
    "MAX_DRIVES",
    "MAX_HCURVES",
    "HCURVES",
    "TE_PARTS",
    "STEADY",
    "STEADY_DRIVE",
    "DESIGN",
    "DESIGN_DRIVE",
    "TE_COMPONENTS",
    "TRANSIENT",
    "PHASE",
    "SLACK",
    "TRANSIENT_DRIVE",
    "DRIVE_POWER",
    "DRIVE_LOAD",
    "DESIGN_BASIS",
    "BOOKKEEPING",
    "CHECKS",
    "CHECKS_TRANSIENT",
    "MAX_PULLEYS",
    "MAX_CURVES",
    "CURVES",
    "CURVES_TRANSIENT",
    "GROUPS",
    "DECIDING",
    "ACCURACY",
    "ALL_GROUPS",
    "FIELDS",
    "field",
    "columns",
    "check_summary",
    "summary_columns",
    "markdown",
]

#: Most drive pulleys a conveyor may have (``drives`` in the conveyor file); the per-drive
#: columns run from ``drive1_*`` to this.
MAX_DRIVES = 6
#: Most pulleys a loop may have: every drive its own pulley (at an end or along a strand), a
#: plain pulley at each end without a drive, and a separate take-up pulley (``engine/loop.py``);
#: the per-pulley columns run from
#: ``pulley1_*`` to this.
MAX_PULLEYS = MAX_DRIVES + 3
#: Most vertical curves a route may have (``profile[i].curve_radius_m``); the per-curve
#: columns run from ``curve1_*`` to this.
MAX_CURVES = 8
#: Most horizontal curves a conveyor may have (profile sections with
#: ``horizontal_radius_m``); the per-curve columns run from ``hcurve1_*`` to this.
MAX_HCURVES = 8


@dataclass(frozen=True)
class ResultField:
    """One result: its column name, unit (``-`` for a ratio or count, ``text``), meaning and
    the short label the CLI tables print."""

    name: str
    unit: str
    meaning: str
    label: str = ""

    @property
    def text(self) -> bool:
        return self.unit == "text"

    @property
    def per_drive(self) -> bool:
        return "{i}" in self.name

    @property
    def per_pulley(self) -> bool:
        return "{j}" in self.name

    @property
    def per_curve(self) -> bool:
        """A field per vertical curve (``curve{k}_*``)."""
        return "{k}" in self.name and self.name.startswith("curve")

    @property
    def per_hcurve(self) -> bool:
        """A field per horizontal curve (``hcurve{k}_*``)."""
        return "{k}" in self.name and self.name.startswith("hcurve")

    @property
    def flag(self) -> bool:
        """A yes/no verdict (stored as a boolean column)."""
        return self.unit == "bool"

    def columns(self, drives: int = MAX_DRIVES, pulleys: int = MAX_PULLEYS,
                curves: int = MAX_CURVES, hcurves: int = MAX_HCURVES) -> tuple[str, ...]:
        """The column names: one, or one per drive 1 .. ``drives`` (per pulley 1 ..
        ``pulleys``, per vertical curve 1 .. ``curves``, per horizontal curve 1 ..
        ``hcurves``)."""
        if self.per_curve:
            return tuple(self.name.format(k=k) for k in range(1, curves + 1))
        if self.per_drive:
            return tuple(self.name.format(i=i) for i in range(1, drives + 1))
        if self.per_pulley:
            return tuple(self.name.format(j=j) for j in range(1, pulleys + 1))
        if self.per_hcurve:
            return tuple(self.name.format(k=k) for k in range(1, hcurves + 1))
        return (self.name,)


@dataclass(frozen=True)
class ResultGroup:
    """Fields that belong together (the steady summary, one drive's transient, ...)."""

    key: str
    title: str
    fields: tuple[ResultField, ...]

    def __iter__(self):
        return iter(self.fields)

    def names(self) -> tuple[str, ...]:
        return tuple(f.name for f in self.fields)


def _f(name: str, unit: str, meaning: str, label: str = "") -> ResultField:
    return ResultField(name, unit, meaning, label or meaning)


# -------------------------------------------------------------------------- steady (SPEC 4)
STEADY = ResultGroup("steady", "Steady state (the friction model at design speed)", (
    _f("te_kn", "kN", "total peripheral force Te, the sum of te_components_kn",
       "peripheral force Te"),
    _f("power_kw", "kW", "power at the drive pulleys, Te x design speed (drive efficiency "
       "excluded)", "power at the drive pulleys"),
    _f("t1_kn", "kN", "tight-side tension at the main drive", "T1 tight side, main drive"),
    _f("t2_kn", "kN", "slack-side tension at the main drive", "T2 slack side, main drive"),
    _f("t_max_kn", "kN", "highest steady belt tension", "maximum tension"),
    _f("t_max_at_m", "m", "where t_max_kn is, along the loop from the tail, carry first",
       "  at (from the tail, carry first)"),
    _f("t_min_kn", "kN", "lowest steady belt tension", "minimum tension"),
    _f("t_min_at_m", "m", "where t_min_kn is, along the loop from the tail, carry first",
       "  at"),
    _f("sag_max_pct", "%", "largest sag ratio h/S of a span, running: `g (m'_G + m'_L) cos(a) "
       "S / (8 T)`, the span's weight normal to the belt (PHYSICS 2 writes it without "
       "`cos(a)`: the same on a level belt, 5 % lower on an 18 deg incline); at most 100, "
       "null when a span is slack (tension at or below zero: the slack warning says where)",
       "maximum sag h/S"),
    _f("takeup_mass_kg", "kg", "gravity take-up mass as used (the auto size when auto; null "
       "for a fixed take-up)", "take-up mass"),
    _f("takeup_tension_kn", "kN", "tension the take-up holds in each of its two strands, "
       "running", "take-up tension per strand"),
    _f("slip_margin", "-", "smallest running slip margin of the drive pulleys, "
       "e^(mu theta) / (T_tight / T_slack); above 1 is safe", "slip margin running (>1 safe)"),
    _f("slip_margin_start", "-", "smallest slip margin of the drive pulleys at start-up "
       "(DIN 22101's start-up force, 1.5 x Te, and, with a gravity take-up, breakaway: the "
       "drives holding the net gravity pull at standstill)", "slip margin at start-up"),
    _f("safety_factor", "-", "belt safety factor, belt_rating_kn / t_max_kn",
       "belt safety factor"),
    _f("belt_mass_kg_m", "kg/m", "belt mass per metre", "belt mass"),
    _f("load_mass_kg_m", "kg/m", "material mass per metre on a loaded carry section",
       "material mass"),
    _f("idler_mass_carry_kg_m", "kg/m", "rotating idler mass per metre, carry strand",
       "idler mass carry"),
    _f("idler_mass_return_kg_m", "kg/m", "rotating idler mass per metre, return strand",
       "idler mass return"),
    _f("belt_modulus_kn", "kN", "static axial stiffness of the belt, E x B (force per unit "
       "strain)", "belt stiffness E B (static)"),
    _f("belt_modulus_dyn_kn", "kN", "dynamic axial stiffness of the belt (the wave speeds and "
       "wave_loop_time_s use it)", "belt stiffness E B (dynamic)"),
    _f("belt_rating_kn", "kN", "belt breaking strength, rating x width", "belt rating"),
    _f("wave_speed_carry_m_s", "m/s", "longitudinal wave speed on the loaded carry strand",
       "wave speed carry"),
    _f("wave_speed_return_m_s", "m/s", "longitudinal wave speed on the return strand",
       "wave speed return"),
    _f("steady_iterations", "-", "fixed-point iterations of the steady solve (1 for models "
       "whose resistance does not depend on tension)", "steady solve iterations"),
))

STEADY_DRIVE = ResultGroup("steady_drive", "Per drive pulley, steady (SPEC 6.4)", (
    _f("drive{i}_t_tight_kn", "kN", "tight-side tension at drive i", "tight"),
    _f("drive{i}_t_slack_kn", "kN", "slack-side tension at drive i", "slack"),
    _f("drive{i}_slip_margin", "-", "running slip margin of drive i, e^(mu theta) / "
       "(T_tight / T_slack)", "margin"),
))

# ---------------------------------------------------------------- design and capacity (6.4)
DESIGN = ResultGroup("design", "Design and capacity: the sizes the run used (SPEC 6.4)", (
    _f("takeup_pretension_kn", "kN", "tension per strand the take-up holds (fixed take-up: "
       "its pretension)", "take-up tension per strand"),
    _f("rated_power_kw", "kW", "rated power of all drives together, as the run used it",
       "rated power (all drives)"),
    _f("brake_force_kn", "kN", "brake force of all brakes together, as the run used it "
       "(null without brakes)", "brake force (all brakes)"),
    _f("fill_pct", "%", "design volume flow over the belt cross-section's capacity at design "
       "speed (ISO 5048 / DIN 22101)", "fill (design flow / cross-section)"),
))

DESIGN_DRIVE = ResultGroup("design_drive", "Per drive pulley, design", (
    _f("drive{i}_rated_power_kw", "kW", "rated power of drive i, as the run used it",
       "rated power"),
))

# ------------------------------------------------------------ Te breakdown (SPEC 4)
#: Parts of ``te_components_kn``: the six every model reports, then Non-Lin's finer split of
#: the main resistances, then ``other`` (in a stored row: the sum of parts outside the list).
TE_PARTS = (
    "main_carry", "main_return", "lift", "feed", "secondary", "accessories",
    "idler_rotation", "indentation", "belt_flexure", "material_flexure", "other",
)  # fmt: skip
_TE_MEANING = {
    "main_carry": "main resistance of the carry strand (the friction model's running "
                  "resistance)",
    "main_return": "main resistance of the return strand",
    "lift": "lifting the material (the belt's own lift cancels round the loop)",
    "feed": "accelerating the material at the feed point(s)",
    "secondary": "pulleys and other secondary resistances (DIN's C factor included)",
    "accessories": "scrapers, skirts and ploughs: the lumped head_kn and tail_kn, the feed "
                   "points' skirts (ISO 5048 F_gL), belt cleaners (F_r) and ploughs (F_a)",
    "idler_rotation": "idler rotation: bearings and seals (nonlin, visco)",
    "indentation": "indentation rolling resistance of the cover (nonlin, visco)",
    "belt_flexure": "belt flexure between idlers (nonlin, visco)",
    "material_flexure": "material flexure between idlers (nonlin, visco)",
    "other": "parts outside this list, summed",
}
TE_COMPONENTS = ResultGroup(
    "te_components",
    "Te breakdown: te_components_kn (an object in JSON, te_<part>_kn columns in Parquet; "
    "null where a model has no such part)",
    tuple(_f(f"te_{p}_kn", "kN", f"part of te_kn: {_TE_MEANING[p]}", p) for p in TE_PARTS),
)

# ------------------------------------------------------------------- transient (SPEC 4)
TRANSIENT = ResultGroup("transient", "Transient: the start, run and stop cycle (dynamics on)", (
    _f("t_max_dyn_kn", "kN", "highest belt tension of the cycle", "maximum tension (transient)"),
    _f("t_max_dyn_at_m", "m", "where t_max_dyn_kn is, from the tail, carry first",
       "  at (from the tail, carry first)"),
    _f("t_max_dyn_time_s", "s", "when t_max_dyn_kn is, on the run's clock (the time series' "
       "t_s): from the beginning of the run, which rests DynamicsOptions.pre_rest_s (2 s) "
       "before the start command; the per-phase t_*_time_s are on this clock too",
       "  at time"),
    _f("t_min_dyn_kn", "kN", "lowest belt tension of the cycle", "minimum tension (transient)"),
    _f("t_min_dyn_at_m", "m", "where t_min_dyn_kn is", "  at"),
    _f("t_min_dyn_time_s", "s", "when t_min_dyn_kn is (the run's clock, as "
       "t_max_dyn_time_s: below 2 s it is the belt at rest before the start)", "  at time"),
    _f("dyn_factor", "-", "t_max_dyn_kn / t_max_kn", "dynamic factor t_max_dyn / t_max"),
    _f("drive_force_max_kn", "kN", "largest total drive force", "largest drive force"),
    _f("drive_power_max_kw", "kW", "largest total drive power", "largest drive power"),
    _f("velocity_max_m_s", "m/s", "highest element speed (overshoot)", "highest element speed"),
    _f("velocity_min_m_s", "m/s", "lowest element speed (run-back shows as negative)",
       "lowest element speed (run-back < 0)"),
    _f("takeup_travel_m", "m", "take-up carriage travel, largest less smallest position",
       "take-up carriage travel"),
    _f("takeup_travel_start_m", "m", "take-up carriage travel within the start phase (start "
       "command to stop command), largest less smallest position", "  in the start"),
    _f("takeup_travel_stop_m", "m", "take-up carriage travel within the stop phase (stop "
       "command to the end), largest less smallest position", "  in the stop"),
    _f("start_time_s", "s", "start time achieved: start command until the mass-weighted mean "
       "speed first reaches 99 % of design speed, by the stop command (null if never)",
       "start time achieved"),
    _f("stop_time_s", "s", "stop time achieved: stop command until the mean speed falls below "
       "1 % of design speed (null if never, or if it was below that, backwards included, at "
       "the stop command)", "stop time achieved"),
    _f("stop_distance_m", "m", "stopping distance: the belt's travel (the mass-weighted mean "
       "speed integrated) from the stop command until the stop is achieved (null if never)",
       "stopping distance"),
    _f("stop_window_s", "s", "the stop window: a run whose belt is not at rest (stop_time_s) "
       "this long after the stop command did not stop (the same for every run, "
       "DynamicsOptions.stop_window_s, docs/dynamics.md)", "stop window"),
    _f("f_holdback_kn", "kN", "largest force the holdback (holdback: true, at the head drive "
       "pulley) gives over the run, apart from the brakes' (null without a holdback)",
       "holdback force (largest)"),
    _f("f_brake_kn", "kN", "largest force the brakes give together over the run (their sum "
       "on every shaft; the time series' f_brake_kn at every step), at rest before the start "
       "included, apart from the holdback's (null without brakes)", "brake force (largest)"),
    _f("wave_loop_time_s", "s", "time a stress wave takes once round the loop",
       "wave loop time"),
    _f("stop_wave_ratio", "-", "stop_time_s / wave_loop_time_s (null when the belt did not "
       "stop)", "stop time / wave loop time"),
    _f("sag_max_dyn_pct", "%", "largest sag ratio of a span during the cycle",
       "largest sag (transient)"),
    _f("slip_margin_min_dyn", "-", "smallest slip margin of any drive pulley during the cycle",
       "smallest slip margin (transient)"),
    _f("slip_margin_min_start_dyn", "-", "smallest slip margin of any drive pulley from the "
       "start command to the stop command",
       "  of the start"),
    _f("slip_margin_min_stop_dyn", "-", "smallest slip margin of any drive pulley from the stop "
       "command on (null when the run ended before it)", "  of the stop"),
    _f("safety_factor_dyn", "-", "belt safety factor at the cycle's highest tension, "
       "belt_rating_kn / t_max_dyn_kn", "belt safety factor (transient)"),
    _f("dt_used_s", "s", "time step the integration used (the scenario's dt_s, or the "
       "automatic one)", "time step"),
    _f("elements_used", "-", "elements round the loop the run used: the belt elements (the "
       "scenario's elements, or the automatic count) and one per pulley", "elements"),
))

_PHASE_WORDS = {"max": "highest", "min": "lowest"}
_PHASE_SPAN = {"start": "from the start command to the stop command (the rest before the "
                         "start command is in the whole run's t_max_dyn_kn and t_min_dyn_kn "
                         "only)",
               "stop": "from the stop command to the end"}
PHASE = ResultGroup(
    "phase", "Per phase (SPEC 6.4): start = start command to stop command; stop = stop "
    "command to the end",
    tuple(
        field_
        for p in ("start", "stop")
        for m in ("max", "min")
        for field_ in (
            _f(f"t_{m}_{p}_kn", "kN", f"{_PHASE_WORDS[m]} belt tension {_PHASE_SPAN[p]}",
               f"{_PHASE_WORDS[m]} tension, {p}"),
            _f(f"t_{m}_{p}_at_m", "m", f"where t_{m}_{p}_kn is", "  at"),
            _f(f"t_{m}_{p}_time_s", "s", f"when t_{m}_{p}_kn is", "  at time"),
        )
    ),
)

SLACK = ResultGroup("slack", "Slack (SPEC 6.4)", (
    _f("slack_max_m", "m", "largest belt length gathered by slack spans (0 when never slack)",
       "belt gathered by slack spans (largest)"),
    _f("slack_at_m", "m", "where slack_max_m was gathered: the slack span that had gathered "
       "most at slack_time_s, from the tail, carry first (not where the belt first went slack; "
       "null when it never did)", "  at"),
    _f("slack_time_s", "s", "when slack_max_m was reached (not when the belt first went slack, "
       "which is where t_max_pre_slack_kn ends; null when it never did)", "  at time"),
    _f("slack_duration_s", "s", "time with a slack span", "time with a slack span"),
    _f("t_max_pre_slack_kn", "kN", "highest tension before the belt first went slack (the "
       "whole cycle when it never did)", "highest tension before slack"),
    _f("t_max_post_slack_kn", "kN", "highest tension after the belt first went slack (null "
       "when it never did)", "highest tension after slack"),
    _f("t_max_post_slack_at_m", "m", "where t_max_post_slack_kn is", "  at"),
    _f("t_max_post_slack_time_s", "s", "when t_max_post_slack_kn is", "  at time"),
    _f("takeup_endstop_speed_m_s", "m/s", "take-up carriage speed when it hit an end stop (0 "
       "when it never did)", "take-up speed at an end stop"),
    _f("takeup_endstop_gap_m", "m", "least clearance between the take-up carriage's travel "
       "in the run and its end stops (0 when it reached one; null without a gravity take-up)",
       "take-up clearance to its end stops"),
    _f("slip_free_takeup_mass_kg", "kg", "gravity take-up with which no drive slips in the "
       "start, found by rerunning it (beltstudy.engine.remedy, 2 %; beltstudy simulate; in a checked "
       "run the figure that also holds on the mesh twice as fine; null when not searched, not "
       "found within 4 x or the start did not slip)", "take-up without slip"),
    _f("slip_free_takeup_kn", "kN", "fixed take-up pretension with which no drive slips in "
       "the start, found by rerunning it (as slip_free_takeup_mass_kg)",
       "pretension without slip"),
    _f("slip_free_start_time_s", "s", "start time with which no drive slips, the take-up "
       "unchanged, found by rerunning the start (2 %; null when not searched, not found "
       "within 6 x or the start did not slip)", "start time without slip"),
))

TRANSIENT_DRIVE = ResultGroup("transient_drive", "Per drive pulley, transient (SPEC 6.4)", (
    _f("drive{i}_force_max_kn", "kN", "largest force of drive i", "F max"),
    _f("drive{i}_power_max_kw", "kW", "largest power of drive i", "P max"),
    _f("drive{i}_slip_margin_min", "-", "smallest slip margin of drive i during the cycle",
       "margin min"),
    _f("drive{i}_slip_s", "s", "total time drive i slipped on the belt", "slip"),
    _f("drive{i}_slip_m", "m", "belt length that slipped over drive i", "slipped"),
    _f("drive{i}_speed_error_max_pct", "%", "vfd master drive only (null for the others): "
       "largest |reference - pulley speed| of its speed loop from one wave loop time after the "
       "start command to the stop command, in % of design speed; null where the loop follows "
       "no start ramp (a torque or force start, the support formulation)", "speed err"),
))

# --------------------------------------------------------- drive checks (SPEC 7.4)
DRIVE_POWER = ResultGroup(
    "drive_power", "Per drive pulley, steady power against the rating (SPEC 7.4; "
    "docs/drives.md)", (
        _f("drive{i}_power_required_kw", "kW", "the motor power drive i needs at the steady "
           "state, its force at the pulley (its share of Te) x design speed / "
           "drives[i].efficiency (x efficiency when it holds back a regenerating belt; the "
           "magnitude)", "P req"),
        _f("drive{i}_utilisation", "-", "drive{i}_power_required_kw / "
           "drive{i}_rated_power_kw; above 1 the motor is short of power (a warning)", "util"),
    ))

DRIVE_LOAD = ResultGroup(
    "drive_load", "Per drive pulley, transient load against the rating (SPEC 7.4; "
    "docs/drives.md)", (
        _f("drive{i}_overload_s", "s", "time after the start command with drive i's force at "
           "the pulley above its rated force (rated power / design speed)", "overload"),
        _f("drive{i}_force_rms_kn", "kN", "RMS force of drive i from the start command until "
           "the belt is at rest after the stop (its mean speed below 1 % of design speed, as "
           "stop_time_s; the run's end when it never stops), the cycle's thermal equivalent "
           "load", "F rms"),
    ))

# ------------------------------------------------------------------ the design basis
DESIGN_BASIS = ResultGroup("design_basis", "What set each auto size (text)", (
    _f("takeup_governed_by", "text", "the take-up: slip_start, slip_breakaway, slip_running, "
       "sag_running, sag_at_rest or positive; given when the file gives it; in a study, "
       "' @ <case>' names the design case that set it by what varies among the design's "
       "cases (load, model, temperature: 'slip_breakaway @ declines', SPEC 7.2), and its "
       "model wherever design.friction_model gives it ('slip_start @ visco, -20 C')"),
    _f("rated_power_governed_by", "text", "the rated power: peripheral_force or "
       "running_resistance; given when the file gives it (several joined by +); in a study "
       "with ' @ <case>' as for takeup_governed_by"),
    _f("brake_governed_by", "text", "the brakes: stop_time, holding, or grip (the stop time "
       "asked needs more than the braked pulley passes in the stop: held at its grip, the "
       "message gives the stop time it makes and what would meet the asked one, "
       "docs/dynamics.md *Brakes within their grip*); given when the file gives them "
       "(several joined by +, 'holding+given' for an auto brake beside a given one; null "
       "without brakes); in a study with ' @ <case>' as for takeup_governed_by "
       "('stop_time @ declines')"),
    _f("belt_type_used", "text", "the catalogue belt the run used (custom for a belt without a "
       "type): belt.type: auto picks the lightest of its kind that passes the safety factors "
       "(docs/belts.md)", "belt type used"),
))

# ------------------------------------------------ design checks (SPEC 7.4, docs/checks.md)
_PULLEY_J = ("pulley j: the pulley's 1-based number in loop order (booster drives on the "
             "carry, tail to head; head drives in file order or the plain head pulley, a head "
             "take-up pulley; booster drives and a take-up along the return, head to tail; a "
             "tail take-up pulley before tail drives, tail drives in file order or the plain "
             "tail pulley; pulley{j}_name says which)")
CHECKS = ResultGroup("checks", "Design checks, steady (DIN 22101, ISO 5048, CEMA, ISO 281; "
                     "docs/checks.md)", (
    _f("pulley{j}_name", "text", f"{_PULLEY_J}: drive i (head|tail), head, tail or take-up "
       "(head|tail), and its DIN 22101 pulley group A (drive, high tension), B (low tension) "
       "or C (snub, wrap < 30 deg)", "pulley"),
    _f("pulley{j}_diameter_min_m", "m", "DIN 22101 minimum diameter of pulley j for its "
       "group and the belt's utilisation there (null when the belt's carcass thickness is not "
       "in engine/data/carcass.csv)", "D min"),
    _f("pulley{j}_diameter_min_ok", "bool", "pulley j's diameter meets "
       "pulley{j}_diameter_min_m (null when no minimum, and for a plain or take-up pulley, whose diameter the file does not give)", "D ok"),
    _f("pulley{j}_resultant_kn", "kN", "resultant (shaft) force of the belt on pulley j, "
       "sqrt(T_in^2 + T_out^2 - 2 T_in T_out cos(wrap)), steady running", "resultant"),
    _f("transition_head_m", "m", "minimum transition length from the head pulley to the "
       "first fully troughed idler (CEMA 7th ed. Table 7.29, full trough) for the carry "
       "trough angle, belt kind and the tension there", "transition length, head (min)"),
    _f("transition_tail_m", "m", "minimum transition length at the tail (as "
       "transition_head_m)", "transition length, tail (min)"),
    _f("idler_load_carry_n", "N", "static load per carry idler set, g (m'_G + m'_L) S at the "
       "design load (DIN 22101 / ISO 5048)", "carry idler load per set"),
    _f("idler_load_roll_n", "N", "load on the most loaded roll of a carry set (the middle "
       "roll's share of idler_load_carry_n by trough angle)", "carry idler load, middle roll"),
    _f("idler_l10_h", "h", "ISO 281 L10 life of the middle carry roll's bearings (its load "
       "shared by two; bearing of the CEMA class, engine/data/idler_ratings.csv; null without "
       "a cema_class)", "carry idler bearing life L10"),
    _f("holdback_torque_knm", "kNm", "torque a holdback on the first head pulley must hold: "
       "(net downhill pull of the belt as loaded - 1/2 running friction) x D/2 (CEMA's rule); "
       "0 when the belt cannot run back", "holdback torque (required)"),
))

CHECKS_TRANSIENT = ResultGroup("checks_transient", "Design checks, transient", (
    _f("pulley{j}_resultant_dyn_kn", "kN", "largest resultant force on pulley j during the "
       "cycle, from the highest tensions either side of it in each envelope segment (every "
       "step; an upper bound: the two need not peak together; docs/checks.md)",
       "resultant max"),
))

# ------------------------------------- vertical curves (SPEC 7.4, docs/routes.md part (c))
_CURVE_K = "curve k: the vertical curve's 1-based number in profile order"
CURVES = ResultGroup("curves", "Vertical curves, steady (CEMA, DIN 22101; docs/routes.md)", (
    _f("curve{k}_kind", "text", f"{_CURVE_K}: concave (the grade increasing, a valley) or "
       "convex (a crest)", "curve"),
    _f("curve{k}_at_m", "m", "the junction of the curve's two sections, from the tail along "
       "the carry", "at"),
    _f("curve{k}_tension_kn", "kN", "highest steady tension on curve k: of the carry strand "
       "on a convex curve; of either strand on a concave one (the tension its lift-off is "
       "judged at)", "T on the curve"),
    _f("curve{k}_liftoff_tension_kn", "kN", "concave: the tension at which the empty belt "
       "leaves its idlers there, R m'_G g cos(a) at the curve's steepest point, its steeper "
       "end (the loaded belt, m'_G + m'_L, holds more); null for a convex curve",
       "lift-off tension"),
    _f("curve{k}_liftoff", "bool", "concave: the steady tension on either strand is above the "
       "lift-off tension of the empty belt somewhere on curve k (a warning); false for a "
       "convex curve", "lifts off"),
    _f("curve{k}_radius_min_m", "m", "the smallest radius curve k needs at the steady "
       "tension: concave, max T / (m'_G g cos a) over the curve, both strands; convex, the "
       "troughed belt's edge strain within the admissible (rating / S_min) and its centre in "
       "tension (null for a flat belt, or when the tension is at or above the admissible)",
       "R min"),
    _f("curve{k}_tension_start_kn", "kN", "concave: highest tension on curve k at start-up, "
       "either strand, from the steady start-up walk (the drives at the start-up factor 1.5 "
       "of the slip check, slip_margin_start; a rigid-body estimate, the transient's is "
       "liftoff_*); null for a convex curve", "T at start"),
    _f("curve{k}_liftoff_start", "bool", "concave: the start-up tension on either strand is "
       "above the lift-off tension of the empty belt somewhere on curve k (CEMA 7th ed. sizes "
       "the radius from the tension during starting; a warning where running stays down); "
       "false for a convex curve", "lifts at start"),
    _f("curve{k}_radius_min_start_m", "m", "concave: the smallest radius that keeps the belt "
       "down at start-up, max T_start / (m'_G g cos a) over the curve, both strands (R x "
       "T_start / T_lift); null for a convex curve", "R min at start"),
    _f("curve{k}_tension_rest_kn", "kN", "concave: highest tension on curve k with the belt "
       "held at rest, either strand (the take-up's tension and the belt's weight, no running "
       "resistance: an estimate, the transient's lift-off at rest is liftoff_*); null for a "
       "convex curve", "T at rest"),
    _f("curve{k}_liftoff_rest", "bool", "concave: the at-rest tension on either strand is "
       "above the lift-off tension of the empty belt somewhere on curve k (no start or stop "
       "time changes it); false for a convex curve", "lifts at rest"),
    _f("curve{k}_radius_min_rest_m", "m", "concave: the smallest radius that keeps the belt "
       "down held at rest, max T_rest / (m'_G g cos a) over the curve, both strands (R x "
       "T_rest / T_lift); null for a convex curve", "R min at rest"),
    _f("curve{k}_idler_load_extra_n", "N", "load the belt's tension adds to each carry idler "
       "set on curve k, T S / R (convex; on a concave curve it is taken off)",
       "idler load from the curve"),
))

CURVES_TRANSIENT = ResultGroup("curves_transient", "Vertical curves, transient", (
    _f("liftoff_max_kn_over", "kN", "largest tension over the empty belt's lift-off tension "
       "(R m'_G g cos a) on the concave curves and the concave grade changes given as survey "
       "points (R the circle through them) during the cycle, both strands, every step; "
       "negative: the margin left; null without either", "lift-off, most over"),
    _f("liftoff_at_m", "m", "where liftoff_max_kn_over is, along the loop from the tail, carry "
       "first (null when the belt never lifts)", "  at"),
    _f("liftoff_time_s", "s", "when (null when the belt never lifts)", "  time"),
    _f("liftoff_over_start_kn", "kN", "liftoff_max_kn_over from the start command to the stop "
       "command (start and running)", "  start"),
    _f("liftoff_over_stop_kn", "kN", "liftoff_max_kn_over from the stop command on", "  stop"),
))

BOOKKEEPING = ResultGroup("bookkeeping", "Bookkeeping", (
    _f("status", "text", "ok, warning or failed"),
    _f("message", "text", "why, in words: every crossed limit, or the failure"),
    _f("elapsed_s", "s", "wall time of the run"),
))

# ------------------------------------------------ horizontal curves (SPEC 7.4, docs/routes.md)
HCURVES = ResultGroup("hcurves", "Horizontal curves, steady (SPEC 7.1, 7.4; `{k}` is the "
                      "curve's number in profile order)", (
    _f("hcurve{k}_tension_min_kn", "kN", "lowest belt tension that keeps the belt in "
       "horizontal curve k: below it the loaded belt runs down the superelevation out of the "
       "curve (for the belt as the run loads it, the most loaded element's where a feed "
       "point lies within the curve; 0 when there is no lower limit; docs/routes.md)",
       "T min in curve"),
    _f("hcurve{k}_tension_max_kn", "kN", "highest belt tension the weight of the belt holds "
       "in horizontal curve k before the belt runs to the inside (for the belt as the run "
       "loads it: an empty run gives the empty belt's, the least loaded element's where a "
       "feed point lies within the curve)", "T max in curve"),
    _f("hcurve{k}_t_low_kn", "kN", "lowest steady tension of the run along curve k",
       "tension low"),
    _f("hcurve{k}_t_high_kn", "kN", "highest steady tension of the run along curve k",
       "tension high"),
    _f("hcurve{k}_ok", "bool", "the run's tension along curve k lies within the limits of "
       "each element's own load (within hcurve{k}_tension_min_kn and "
       "hcurve{k}_tension_max_kn where the load is one along the curve)", "in curve"),
))

#: Every group, in the order of the runs table.
GROUPS = (STEADY, STEADY_DRIVE, DESIGN, DESIGN_DRIVE, TE_COMPONENTS, TRANSIENT, PHASE, SLACK,
          TRANSIENT_DRIVE, DRIVE_POWER, DRIVE_LOAD, DESIGN_BASIS, CHECKS, CHECKS_TRANSIENT,
          CURVES, CURVES_TRANSIENT, HCURVES, BOOKKEEPING)

# ------------------------------------------------------------- error bars (SPEC 7.4)
#: The deciding figures of a transient run that get an error bar (SPEC 7.4; per-drive ones
#: with ``{i}``); :mod:`beltstudy.engine.accuracy` bars those a run reports.
DECIDING = (
    "t_max_dyn_kn", "t_min_dyn_kn",
    "t_max_start_kn", "t_min_start_kn", "t_max_stop_kn", "t_min_stop_kn",
    "drive_force_max_kn", "drive_power_max_kw",
    "drive{i}_force_max_kn", "drive{i}_power_max_kw",
    "takeup_travel_m", "takeup_travel_start_m", "takeup_travel_stop_m",
    "takeup_endstop_speed_m_s", "takeup_endstop_gap_m",
    "stop_time_s", "stop_distance_m", "slack_max_m",
    "slip_margin_min_dyn", "slip_margin_min_start_dyn", "slip_margin_min_stop_dyn",
    "safety_factor_dyn", "sag_max_dyn_pct",
    "liftoff_max_kn_over", "liftoff_over_start_kn", "liftoff_over_stop_kn",
)
_SUFFIX_UNIT = (("_kn", "kN"), ("_kw", "kW"), ("_m_s", "m/s"), ("_pct", "%"), ("_m", "m"),
                ("_s", "s"))


def _unit_of(name: str) -> str:
    """The unit of a result name: its field's, else the one its suffix names (a figure
    another part of the engine may add), else ``-``."""
    for g in GROUPS:
        for f in g:
            if f.name == name:
                return f.unit
    return next((u for sfx, u in _SUFFIX_UNIT if name.endswith(sfx)), "-")


#: Not a runs column: the error bars of a run whose accuracy was checked (``beltstudy
#: simulate`` by default, a study's ``accuracy: {sample: ...}`` runs, stored as the
#: ``accuracy`` table), :mod:`beltstudy.engine.accuracy`.
ACCURACY = ResultGroup(
    "accuracy",
    "Error bars (SPEC 7.4): not in the runs table; beltstudy simulate (unless --no-check) "
    "and the accuracy table of a study with accuracy: {sample: ...}",
    (
        _f("accuracy_elements", "text", "the meshes of the check, coarse/the run's/fine "
           "(elements; the step follows the mesh)"),
        _f("accuracy_methods", "text", "how each figure's bar was found: richardson (three "
           "meshes, observed order p, Fs 1.25), gci2 (order assumed, Fs 3), gci3 (three "
           "meshes, order bounded to 0.5-1, Fs 3), growing (differences that grow with "
           "refinement: the gci3 bar at order 0.5, no converged value), spread (not in the "
           "asymptotic range), unchanged"),
    ) + tuple(
        field_
        for fig in DECIDING
        for field_ in (
            _f(f"{fig}_err", _unit_of(fig), f"error bar of {fig} at the run's mesh: a finer "
               "mesh's value lies within it", "+-"),
            _f(f"{fig}_converged", _unit_of(fig), f"Richardson estimate of {fig} on an "
               "infinitely fine mesh (null where not extrapolated)", "converged"),
        )
    ),
)
#: Every group that defines a result: the runs table's, then the error bars.
ALL_GROUPS = GROUPS + (ACCURACY,)
#: Every field by name (per-drive fields under their ``{i}`` name).
FIELDS: dict[str, ResultField] = {f.name: f for g in ALL_GROUPS for f in g}
#: The one key of a summary that is not a column: the Te parts as an object.
TE_COMPONENTS_KEY = "te_components_kn"


def field(name: str) -> ResultField:
    """The field of a column name (``drive2_slip_m`` -> ``drive{i}_slip_m``)."""
    if name in FIELDS:
        return FIELDS[name]
    if name.startswith("drive"):
        head, _, rest = name.partition("_")
        if head[5:].isdigit():
            return FIELDS[f"drive{{i}}_{rest}"]
    if name.startswith("pulley"):
        head, _, rest = name.partition("_")
        if head[6:].isdigit() and f"pulley{{j}}_{rest}" in FIELDS:
            return FIELDS[f"pulley{{j}}_{rest}"]
    if name.startswith("curve"):
        head, _, rest = name.partition("_")
        if head[5:].isdigit() and f"curve{{k}}_{rest}" in FIELDS:
            return FIELDS[f"curve{{k}}_{rest}"]
    if name.startswith("hcurve"):
        head, _, rest = name.partition("_")
        if head[6:].isdigit() and f"hcurve{{k}}_{rest}" in FIELDS:
            return FIELDS[f"hcurve{{k}}_{rest}"]
    raise KeyError(name)


def columns(groups=GROUPS, drives: int = MAX_DRIVES, pulleys: int = MAX_PULLEYS,
            curves: int = MAX_CURVES, hcurves: int = MAX_HCURVES) -> tuple[str, ...]:
    """Every column of these groups, per-drive fields for drives 1 .. ``drives``, per-pulley
    fields for pulleys 1 .. ``pulleys``, per-curve fields for vertical curves 1 .. ``curves``
    and horizontal curves 1 .. ``hcurves``."""
    return tuple(c for g in groups for f in g
                 for c in f.columns(drives, pulleys, curves, hcurves))


def summary_columns(summary: dict) -> list[str]:
    """The columns a summary holds (``te_components_kn`` as ``te_<part>_kn``)."""
    out = [k for k in summary if k != TE_COMPONENTS_KEY]
    for part in summary.get(TE_COMPONENTS_KEY) or {}:
        out.append(f"te_{part if part in TE_PARTS else 'other'}_kn")
    return list(dict.fromkeys(out))


def check_summary(summary: dict) -> dict:
    """Raise ``KeyError`` naming every key of ``summary`` that is not a defined result (a
    computed result would otherwise be dropped by the store); return ``summary``."""
    unknown = []
    for key in summary:
        if key == TE_COMPONENTS_KEY:
            continue
        try:
            f = field(key)
        except KeyError:
            unknown.append(key)
            continue
        if f.per_drive and not 1 <= int(key[5:key.index("_")]) <= MAX_DRIVES:
            unknown.append(key)
        if f.per_pulley and not 1 <= int(key[6:key.index("_")]) <= MAX_PULLEYS:
            unknown.append(key)
        if f.per_curve and not 1 <= int(key[f.name.index("{k}"):key.index("_")]) <= MAX_CURVES:
            unknown.append(key)
        if f.per_hcurve and not 1 <= int(key[f.name.index("{k}"):key.index("_")]) <= MAX_HCURVES:
            unknown.append(key)
    if unknown:
        raise KeyError(f"results not defined in beltstudy.engine.results: {', '.join(unknown)}")
    return summary


def markdown() -> str:
    """The results table of ``docs/results.md`` (regenerate: ``python -m beltstudy.engine.results``)."""
    lines = [
        "# Results of a run",
        "",
        "Generated from `engine/results.py` by `python -m beltstudy.engine.results > docs/results.md`;",
        "a test checks that this table, the Parquet `runs` schema and the `--json` output of",
        "`beltstudy static` / `simulate` hold the same fields. Besides these, a `runs` row has",
        "its inputs: `study_id`, `run_id`, one column per grid axis, `friction_model` and",
        "`engine_version`. Per-drive fields are stored for drives 1 to "
        f"{MAX_DRIVES} (`{{i}}` is",
        "the drive's number in file order; null beyond the conveyor's drives), per-pulley",
        f"fields for pulleys 1 to {MAX_PULLEYS} (`{{j}}`, the pulley's number in loop order,",
        "docs/checks.md), per-curve fields for vertical curves 1 to "
        f"{MAX_CURVES} (`curve{{k}}`, the",
        "curve's number in profile order) and horizontal curves 1 to "
        f"{MAX_HCURVES} (`hcurve{{k}}`), docs/routes.md.",
        "Unit `bool`: a yes/no verdict, a boolean column.",
        "",
    ]
    for g in ALL_GROUPS:
        lines += [f"## {g.title}", "", "| column | unit | meaning |", "|---|---|---|"]
        lines += [f"| `{f.name}` | {f.unit} | {f.meaning} |" for f in g]
        lines.append("")
    return "\n".join(lines)


if __name__ == "__main__":  # pragma: no cover
    print(markdown(), end="")
