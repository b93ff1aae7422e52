"""The verdicts of a study and the runs that did not pass, from its runs table alone.

Two declarative lists drive the design report's first two sections
(:mod:`beltstudy.service.web.report`):

* :data:`VERDICTS`: one :class:`Verdict` per design quantity (power and utilisation per drive,
  belt safety factor, T_max and T_min per phase, take-up, brakes, the stop, slip, sag,
  pulleys, idlers). A row is shown only when its column is in the runs table with a value, so
  a column a newer engine adds (``drive{i}_utilisation``, ``pulley{j}_resultant_kn``, ...)
  gets its row as soon as the runs carry it. ``{i}`` and ``{j}`` stand for the drive and
  pulley numbers found in the table.
* :data:`CAUSES`: one :class:`Cause` per way a run can fail to pass (failed, ran away, did not
  stop, never got going, overloaded a drive, slipped, went slack, sagged past its limit, ...), each detected
  from the columns (and, where the engine says it only in words, from the run's message).

Everything here is a pure function of a pandas DataFrame and the study's JSON.
"""

from __future__ import annotations

import math
import re
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Any

import pandas as pd

from beltstudy.engine import OVERLOAD_S_MAX
from beltstudy.engine.wording import gnum
from beltstudy.service.web.numbers import eng

__all__ = ["Verdict", "VERDICTS", "Cause", "CAUSES", "verdict_rows", "cause_groups",
           "expand", "numeric", "transient_ran", "not_stopped", "never_going", "clauses"]


@dataclass(frozen=True)
class Verdict:
    """One design quantity of the verdict table.

    ``column`` may hold ``{i}`` (drives), ``{j}`` (pulleys) or ``{k}`` (vertical or horizontal
    curves): one row per number present.
    ``worst`` is ``max`` or ``min``. ``limit`` is a number, a column of the same run (with the
    same ``{i}``/``{j}``/``{k}``), or a key of the study's limits (:func:`study_limits`); None:
    no limit to judge against (the value is shown). ``ok``: a boolean column that is the run's
    own verdict (a run with it false is past the limit); ``bad``: one true when the run is past
    it (``curve{k}_liftoff``). Where either is given, it judges (a limit beside it is shown,
    and picks the side a failed verdict is past): the engine judges a curve element by element,
    which the curve's extremes against its tightest limit would not (a highest tension on one
    element above the lowest limit of another is no lift-off). ``null_worst``: a missing value
    in a run
    whose transient ran is the worst of all (a stop time of a run that did not stop).
    ``magnitude``: judged by its size whatever its sign (a regenerating drive's power is
    negative); the governing run's value is shown with its sign. ``judged_only``: the runs
    whose limit is missing are not judged and their values not shown (a stop's ratio to the
    wave loop time of a belt that never reached its running speed). ``said``: a regular
    expression of the engine's own warning for the quantity; a run whose message says it is
    past the limit whatever the number (the run's verdict in words, where the runs carry no
    verdict column: a carry idler set above its CEMA rating).
    """

    group: str
    quantity: str
    column: str
    worst: str
    unit: str
    limit: float | str | None = None
    ok: str | None = None
    bad: str | None = None
    at: str | None = None
    null_worst: str = ""
    magnitude: bool = False
    judged_only: bool = False
    said: str = ""


#: The limit of a concave vertical curve's tensions: the empty belt's lift-off tension, which
#: the engine gives only a concave curve (a convex one's row would read 'concave' without a
#: limit, and 'within' by its lift-off verdict, which is false there).
LIFTOFF_LIMIT = "curve{k}_liftoff_tension_kn"

#: The verdict table, in its order. Columns a run does not carry are left out.
VERDICTS: tuple[Verdict, ...] = (
    # drives
    Verdict("Drives", "power required, drive {i}", "drive{i}_power_required_kw", "max", "kW",
            "drive{i}_rated_power_kw"),
    Verdict("Drives", "utilisation, drive {i} (required / rated)", "drive{i}_utilisation",
            "max", "-", 1.0),
    # the engine warns beyond OVERLOAD_S_MAX (IEC 60034-1's 15 s of excess torque, docs/drives.md)
    Verdict("Drives", "time over rating, drive {i}", "drive{i}_overload_s", "max", "s",
            OVERLOAD_S_MAX),
    # the engine warns where the RMS force is above the rated force P_N / v (docs/drives.md)
    Verdict("Drives", "RMS (thermal) force, drive {i}", "drive{i}_force_rms_kn", "max", "kN",
            "rated_force"),
    Verdict("Drives", "power at the drive pulleys, steady (all drives; regenerating < 0)",
            "power_kw", "max", "kW", "rated_at_pulleys", magnitude=True),
    Verdict("Drives", "largest drive power, transient (all drives)", "drive_power_max_kw", "max",
            "kW"),
    Verdict("Drives", "largest force, drive {i}, transient", "drive{i}_force_max_kn", "max",
            "kN"),
    Verdict("Drives", "largest power, drive {i}, transient", "drive{i}_power_max_kw", "max",
            "kW"),
    Verdict("Drives", "holdback torque", "holdback_torque_knm", "max", "kNm"),
    # belt
    Verdict("Belt", "belt type used", "belt_type_used", "text", ""),
    Verdict("Belt", "belt safety factor, steady", "safety_factor", "min", "-", "sf_steady"),
    Verdict("Belt", "belt safety factor, transient", "safety_factor_dyn", "min", "-",
            "sf_dyn"),
    Verdict("Belt", "largest tension, steady", "t_max_kn", "max", "kN", "t_allow_steady",
            at="t_max_at_m"),
    Verdict("Belt", "largest tension, start", "t_max_start_kn", "max", "kN", "t_allow_dyn",
            at="t_max_start_at_m"),
    Verdict("Belt", "largest tension, stop", "t_max_stop_kn", "max", "kN", "t_allow_dyn",
            at="t_max_stop_at_m"),
    Verdict("Belt", "largest tension, transient", "t_max_dyn_kn", "max", "kN", "t_allow_dyn",
            at="t_max_dyn_at_m"),
    Verdict("Belt", "lowest tension, steady", "t_min_kn", "min", "kN", 0.0, at="t_min_at_m"),
    Verdict("Belt", "lowest tension, start", "t_min_start_kn", "min", "kN", 0.0,
            at="t_min_start_at_m"),
    Verdict("Belt", "lowest tension, stop", "t_min_stop_kn", "min", "kN", 0.0,
            at="t_min_stop_at_m"),
    Verdict("Belt", "lowest tension, transient", "t_min_dyn_kn", "min", "kN", 0.0,
            at="t_min_dyn_at_m"),
    Verdict("Belt", "belt gathered by slack spans", "slack_max_m", "max", "m", 0.0,
            at="slack_at_m"),
    Verdict("Belt", "largest sag, steady", "sag_max_pct", "max", "%", "sag"),
    Verdict("Belt", "largest sag, transient", "sag_max_dyn_pct", "max", "%", "sag"),
    # the design load's volume flow over what the cross-section carries at design speed
    # (engine/capacity.py, ISO 5048): above 100 % the load does not fit the belt
    Verdict("Belt", "cross-section fill at design speed (ISO 5048)", "fill_pct", "max", "%",
            100.0),
    # take-up
    Verdict("Take-up", "take-up mass", "takeup_mass_kg", "max", "kg"),
    Verdict("Take-up", "take-up pretension", "takeup_pretension_kn", "max", "kN"),
    Verdict("Take-up", "take-up travel, whole cycle", "takeup_travel_m", "max", "m", "travel"),
    Verdict("Take-up", "take-up travel, start", "takeup_travel_start_m", "max", "m", "travel"),
    Verdict("Take-up", "take-up travel, stop", "takeup_travel_stop_m", "max", "m", "travel"),
    # a carriage whose travel (max - min position) is the whole carriage travel went from one
    # end stop to the other: at the limit is past it (_past); its impact speed is the next row
    Verdict("Take-up", "carriage speed at an end stop", "takeup_endstop_speed_m_s", "max",
            "m/s", 0.0),
    # stop
    Verdict("Stop", "brake force (all brakes)", "brake_force_kn", "max", "kN"),
    Verdict("Stop", "holdback force", "f_holdback_kn", "max", "kN"),
    Verdict("Stop", "stop time achieved", "stop_time_s", "max", "s",
            null_worst="did not stop"),
    Verdict("Stop", "stopping distance", "stop_distance_m", "max", "m",
            null_worst="did not stop"),
    # the 5-wave-loop rule (Harrison after Funke 1973): a stop faster than 5 wave loop times
    # is a high-stress stop (SPEC 4's warnings); judged of a belt that reached design speed
    Verdict("Stop", "stop time over the wave loop time", "stop_wave_ratio", "min", "-",
            "wave", judged_only=True),
    # slip
    Verdict("Slip", "slip margin, running", "slip_margin", "min", "-", 1.0),
    Verdict("Slip", "slip margin, start-up (DIN 22101)", "slip_margin_start", "min", "-", 1.0),
    # a drive pulley that slipped is past the limit whatever its recorded margin: the margin
    # is read from the springs beside the pulley, whose element's inertia is in them (a run
    # that slipped 1.92 s reported 1.000011, and the row counted 22 runs where the time
    # slipping counted 24)
    Verdict("Slip", "slip margin, transient (1 while a drive pulley slips: the time slipping "
            "says how long)", "slip_margin_min_dyn", "min", "-", 1.0,
            said=r"drive \d+ \([^)]*\) slipped on its pulley"),
    Verdict("Slip", "time slipping, drive {i}", "drive{i}_slip_s", "max", "s", 0.0),
    # pulleys and idlers
    Verdict("Pulleys", "minimum diameter, pulley {j}", "pulley{j}_diameter_min_m", "max", "m",
            ok="pulley{j}_diameter_min_ok"),
    Verdict("Pulleys", "resultant (shaft) force, pulley {j}, steady", "pulley{j}_resultant_kn",
            "max", "kN"),
    Verdict("Pulleys", "resultant (shaft) force, pulley {j}, transient",
            "pulley{j}_resultant_dyn_kn", "max", "kN"),
    Verdict("Pulleys", "transition length, head", "transition_head_m", "max", "m"),
    Verdict("Pulleys", "transition length, tail", "transition_tail_m", "max", "m"),
    # the carry set's load against the CEMA rating of its class, and its middle roll's
    # bearing life against the class's L10 basis (engine/checks.py ``_idlers``,
    # docs/checks.md "Idler load and bearing life"); judged only where the file gives a
    # cema_class, as the engine judges it
    Verdict("Idlers", "idler load per carry set", "idler_load_carry_n", "max", "N",
            "idler_rating", said=r"(?:^|; )carry idler load \d+ N per set [^;]*exceeds the CEMA"),
    Verdict("Idlers", "idler bearing life L10", "idler_l10_h", "min", "h", "idler_l10",
            said=r"(?:^|; )carry idler bearing life L10 \d+ h [^;]*is below the CEMA"),
    # routes (docs/routes.md): a concave curve lifts the empty belt off its idlers above its
    # lift-off tension R m'_G g cos(a); a convex curve's radius is judged by the edge strain
    # (the run's message names a curve below it); a horizontal curve holds the belt between
    # its two tensions
    Verdict("Routes", "highest steady tension, vertical curve {k} (concave: judged against "
            "the empty belt's lift-off tension, element by element)", "curve{k}_tension_kn",
            "max", "kN", LIFTOFF_LIMIT, bad="curve{k}_liftoff"),
    Verdict("Routes", "highest start-up tension, vertical curve {k} (concave, rigid-body "
            "estimate)", "curve{k}_tension_start_kn", "max", "kN",
            LIFTOFF_LIMIT, bad="curve{k}_liftoff_start"),
    Verdict("Routes", "highest at-rest tension, vertical curve {k} (concave, an estimate: "
            "the take-up's tension and the belt's weight)", "curve{k}_tension_rest_kn", "max",
            "kN", LIFTOFF_LIMIT, bad="curve{k}_liftoff_rest"),
    Verdict("Routes", "smallest radius vertical curve {k} needs, steady",
            "curve{k}_radius_min_m", "max", "m", "curve_radius"),
    Verdict("Routes", "smallest radius vertical curve {k} needs at start-up (concave)",
            "curve{k}_radius_min_start_m", "max", "m", "curve_radius"),
    Verdict("Routes", "smallest radius vertical curve {k} needs held at rest (concave)",
            "curve{k}_radius_min_rest_m", "max", "m", "curve_radius"),
    Verdict("Routes", "tension over the lift-off tension at the concave curves, transient "
            "(negative: the margin left)", "liftoff_max_kn_over", "max", "kN", 0.0,
            at="liftoff_at_m"),
    Verdict("Routes", "lowest steady tension, horizontal curve {k}", "hcurve{k}_t_low_kn",
            "min", "kN", "hcurve{k}_tension_min_kn", ok="hcurve{k}_ok"),
    Verdict("Routes", "highest steady tension, horizontal curve {k}", "hcurve{k}_t_high_kn",
            "max", "kN", "hcurve{k}_tension_max_kn", ok="hcurve{k}_ok"),
)


def numeric(runs: pd.DataFrame, column: str) -> pd.Series | None:
    """``runs[column]`` as floats, or None when the table lacks it or has no value in it."""
    if column not in runs.columns:
        return None
    values = pd.to_numeric(runs[column], errors="coerce")
    return values if values.notna().any() else None


def expand(pattern: str, columns) -> list[tuple[str, dict[str, str]]]:
    """The columns matching ``pattern`` (``drive{i}_utilisation``), with the numbers found:
    ``[("drive1_utilisation", {"i": "1"}), ...]`` in number order; ``[(pattern, {})]`` for a
    plain column name present."""
    if "{" not in pattern:
        return [(pattern, {})] if pattern in columns else []
    regex = re.compile("^" + re.escape(pattern).replace(r"\{i\}", r"(?P<i>\d+)")
                       .replace(r"\{j\}", r"(?P<j>\d+)").replace(r"\{k\}", r"(?P<k>\d+)")
                       + "$")
    found = []
    for c in columns:
        m = regex.match(str(c))
        if m:
            found.append((c, m.groupdict()))
    return sorted(found, key=lambda cm: [int(v) for v in cm[1].values()])


def transient_ran(runs: pd.DataFrame) -> pd.Series:
    """Rows whose transient ran (a transient column has a value)."""
    for c in ("t_max_dyn_kn", "wave_loop_time_s", "dt_used_s"):
        if c in runs.columns:
            return pd.to_numeric(runs[c], errors="coerce").notna()
    return pd.Series(False, index=runs.index)


def _message(runs: pd.DataFrame) -> pd.Series:
    if "message" not in runs.columns:
        return pd.Series("", index=runs.index)
    return runs["message"].fillna("").astype(str)


def _status(runs: pd.DataFrame) -> pd.Series:
    if "status" not in runs.columns:
        return pd.Series("ok", index=runs.index)
    return runs["status"].fillna("").astype(str)


def _ran_away(runs: pd.DataFrame) -> pd.Series:
    return _message(runs).str.contains(r"\bran (?:away|back)\b", regex=True)


def _no_stop_time(runs: pd.DataFrame) -> pd.Series:
    """Rows whose transient ran without a stop time."""
    if "stop_time_s" not in runs.columns:
        return pd.Series(False, index=runs.index)
    return transient_ran(runs) & pd.to_numeric(runs["stop_time_s"], errors="coerce").isna()


def never_going(runs: pd.DataFrame) -> pd.Series:
    """Runs whose belt never got going: a transient without a stop time whose belt neither
    ran away nor did not stop. A run leaves its stop time empty only for those three (and a
    failure): a belt below 1 % of design speed at the stop command made no stop (SPEC 4),
    which is not a belt that did not stop (the report counted a 2 kW drive that never moved
    its belt as a stop that failed, and its empty stop time as the worst stop)."""
    return (_no_stop_time(runs) & ~_message(runs).str.contains("did not stop", regex=False)
            & ~_ran_away(runs) & (_status(runs) != "failed"))


def not_stopped(runs: pd.DataFrame) -> pd.Series:
    """Runs whose belt did not stop within the stop window: the message says so (a run
    without a stop time says it, ran away or never got going, :func:`never_going`); runs
    that ran away or failed are their own causes."""
    return (_message(runs).str.contains("did not stop", regex=False) & ~_ran_away(runs)
            & (_status(runs) != "failed"))


def _any_over(runs: pd.DataFrame, pattern: str, limit: float) -> pd.Series:
    out = pd.Series(False, index=runs.index)
    for c, _ in expand(pattern, runs.columns):
        out |= pd.to_numeric(runs[c], errors="coerce").fillna(-math.inf) > limit
    return out


#: The engine's words for a drive past its rating in the transient (engine/drives.py
#: ``transient_checks``: above its rated force beyond OVERLOAD_S_MAX, at its torque limit, or
#: an RMS force above the rating) and for a torque limit below the running force.
_DRIVE_PAST_RATING = (r"above its rated force|at its torque limit|held at its torque limit"
                      r"|motor overheats|cannot hold the belt")


#: The word of an overload, not the missed controlled stop's pointer to the run's other
#: warnings (engine/run.py ``missed_controlled_stop``: "the run's slip, torque-limit and
#: overload warnings, where it has them, say what held it back"), which every run whose
#: belt did not follow the stop curve carries, overloaded or not.
_OVERLOAD = r"overload(?! warnings)"


def _overloaded(runs: pd.DataFrame) -> pd.Series:
    msg = _message(runs).str.lower()
    out = (_any_over(runs, "drive{i}_utilisation", 1.0)
           | _any_over(runs, "drive{i}_overload_s", OVERLOAD_S_MAX)
           | msg.str.contains(_OVERLOAD, regex=True) | msg.str.contains("short by", regex=False)
           | msg.str.contains(_DRIVE_PAST_RATING, regex=True))
    power, rated = numeric(runs, "power_kw"), numeric(runs, "rated_power_kw")
    if power is not None and rated is not None:  # steady power above the installed rating
        out |= (power > rated).fillna(False)
    return out


def _required_power_known(runs: pd.DataFrame) -> bool:
    """Whether the runs carry the motor power each drive needs (``drive{i}_power_required_kw``,
    its drive train's efficiency included): the engine judges the rating by it and says so in
    the message, so the power at the pulleys is not judged against the rating here."""
    return any(numeric(runs, c) is not None
               for c, _ in expand("drive{i}_power_required_kw", runs.columns))


def _overload_words(row: pd.Series) -> str:
    """The steady power against the rating, in words, when the run's message has none (a run
    without ``drive{i}_power_required_kw``, whose per-drive sentence the engine writes)."""
    if any(c.startswith("drive") and c.endswith("_power_required_kw") and pd.notna(row.get(c))
           for c in row.index):
        return ""
    power = pd.to_numeric(pd.Series([row.get("power_kw")]), errors="coerce").iloc[0]
    rated = pd.to_numeric(pd.Series([row.get("rated_power_kw")]), errors="coerce").iloc[0]
    if pd.notna(power) and pd.notna(rated) and power > rated:
        return (f"steady running needs {eng(power, 'kW')} at the drive pulleys, "
                f"{eng(rated, 'kW')} rated: short by {eng(power - rated, 'kW')}")
    return ""


def _slipped(runs: pd.DataFrame) -> pd.Series:
    """Time slipping, a running slip margin below 1, or, for a run without a transient (its
    start not simulated), DIN 22101's start-up margin (1.5 x Te) below 1: the one check of
    its start. A run whose start was simulated is judged by what its pulleys did."""
    out = _any_over(runs, "drive{i}_slip_s", 0.0)
    margin = numeric(runs, "slip_margin")
    if margin is not None:
        out |= (margin < 1.0).fillna(False)
    start = numeric(runs, "slip_margin_start")
    if start is not None:
        out |= (~transient_ran(runs) & (start < 1.0)).fillna(False)
    return out | _message(runs).str.contains(_SLIPPED, regex=True)


#: The engine's words for a pulley that slipped: a drive's (``drive 1 (head) slipped on its
#: pulley``), a braked pulley's (``the head brake's pulley slipped: ...``) and a drive at
#: start-up or running (``slip at drive 1 (head) at start-up ...``); not the remedy of a belt
#: that ran away (``..., or, where a drive pulley slipped, a heavier take-up``), which says
#: it of every run-away whether its pulleys slipped or not.
_SLIPPED = r"slipped on its pulley|(?<!where a drive )pulley slipped"
#: The clauses the slip group shows: the findings and the remedies that say the slip (a dol
#: motor sized above its need: '... then avoids the slip'), not every clause with the word
#: (a safety factor's 'a take-up no heavier than the slip and sag limits need').
_SLIP_WORDS = _SLIPPED + r"|\bslip at |avoids the slip|slip.margin"


def _slack(runs: pd.DataFrame) -> pd.Series:
    return (_any_over(runs, "slack_max_m", 0.0)
            | _message(runs).str.contains("goes slack", regex=False))


#: A sag warning of the steady solution (``sag on the carry strand ...``) and of the transient
#: (``transient sag on the carry strand ...``).
_SAG = r"sag on the \w+ strand [\d.]+ % exceeds"


def _end_stop(runs: pd.DataFrame) -> pd.Series:
    """Runs whose take-up carriage reached an end stop: an impact speed above 0, no clearance
    left (``takeup_endstop_gap_m`` 0) or the message saying so. Its travel column stays within
    the carriage travel (the stop held it), so the travel verdict alone does not show it."""
    out = (_any_over(runs, "takeup_endstop_speed_m_s", 0.0)
           | _message(runs).str.contains("take-up carriage reached", regex=False))
    gap = numeric(runs, "takeup_endstop_gap_m")
    if gap is not None:
        out |= (gap <= 0.0).fillna(False)
    return out


def _sagged(runs: pd.DataFrame, phase: str | None = None) -> pd.Series:
    """Runs that sagged past a limit: any, or only ``steady`` or only ``transient`` (the
    verdict rows of ``sag_max_pct`` and ``sag_max_dyn_pct``). Their message warns of the sag,
    or the belt went slack there (:func:`_slack_no_sag`: a slack span's sag has no value, past
    every limit). Counted by the warning alone, a study whose take-up was drawn from 0.5 to
    30 t told 'went slack 19 / 40' and 'sagged past its limit 7 / 40' (of its 19 slack runs
    one, whose message warned of the other strand's sag), where 25 of the 40 had."""
    msg = _message(runs)
    out = pd.Series(False, index=runs.index)
    for name, words, column in (("steady", r"(?<!transient )" + _SAG, "sag_max_pct"),
                                ("transient", r"transient " + _SAG, "sag_max_dyn_pct")):
        if phase not in (None, name):
            continue
        out |= msg.str.contains(words, regex=True)
        if column in runs.columns:  # not numeric(): a column with no value at all is all slack
            values = pd.to_numeric(runs[column], errors="coerce")
            out |= _slack_no_sag_of(column, runs, values).fillna(False).astype(bool)
    return out


#: The engine's route warnings (engine/curves.py, engine/hcurves.py): a concave curve that
#: lifts the empty belt (running, at start-up, in the transient), a convex curve below its
#: radius or past its idlers' rating, a grade change without a curve judged as its survey
#: circle, and a horizontal curve the belt runs out of or to the inside of; not the notes
#: that name curve_radius_m (``note: profile.2.curve_radius_m ...``).
_ROUTE = (r"lift-off (?:in|at rest)|lifts off its|^curve \d+ \((?:concave|convex), R |grade change without "
          r"a vertical curve|^horizontal curve \d+ \(profile(?: section |\.\d)")


#: What the route warnings name as their fix, each a clause after its finding: the radius
#: that keeps the belt on its idlers or in its line, the superelevation.
_ROUTE_FIX = (r"^a radius of at least \d+ m|^no radius holds it|^a tighter radius"
              r"|^less superelevation")


def _route(runs: pd.DataFrame) -> pd.Series:
    """Runs whose belt leaves its idlers or its line at a curve: a lift-off verdict
    (``curve{k}_liftoff``, ``curve{k}_liftoff_start``, ``curve{k}_liftoff_rest``,
    ``liftoff_max_kn_over`` above 0), a
    horizontal curve's ``hcurve{k}_ok`` false, or a route warning in the message."""
    out = _any_over(runs, "liftoff_max_kn_over", 0.0)
    for pattern, bad in (("curve{k}_liftoff", True), ("curve{k}_liftoff_start", True),
                         ("curve{k}_liftoff_rest", True), ("hcurve{k}_ok", False)):
        for c, _ in expand(pattern, runs.columns):
            out |= runs[c].astype("boolean").eq(bad).fillna(False).astype(bool)
    said = _message(runs).map(lambda m: any(
        not c.startswith("note: ") and re.search(_ROUTE, c) for c in clauses(m, "")))
    return out | said.astype(bool)


def _safety(runs: pd.DataFrame) -> pd.Series:
    return _message(runs).str.contains("safety factor", regex=False) & _message(
        runs).str.contains("below", regex=False)


def _pulleys(runs: pd.DataFrame) -> pd.Series:
    out = pd.Series(False, index=runs.index)
    for c, _ in expand("pulley{j}_diameter_min_ok", runs.columns):
        out |= runs[c].astype("boolean").fillna(True).eq(False).astype(bool)
    return out


#: The engine's words of a stop faster than 5 wave loop times (engine/dynamics/simulate.py).
_HIGH_STRESS = r"faster than 5 wave loop times"


def _high_stress(runs: pd.DataFrame) -> pd.Series:
    """Runs whose stop the engine judged a high-stress stop (5-wave-loop rule): the engine
    judges a belt that reached its running speed only, so its words decide, not the ratio
    (a belt that never got going has a ratio and no such stop)."""
    return _message(runs).str.contains(_HIGH_STRESS, regex=True)


#: The engine's words for carry idlers past their CEMA class (engine/checks.py ``_idlers``:
#: a set's load above the class's rating, its middle roll's bearing life L10 below the
#: class's basis; engine/curves.py ``convex_idler_warnings``: the same on a convex curve,
#: where the tension pressing round it adds to the load).
_IDLERS = (r"(?:exceeds|above) the CEMA \w+ rating \d+ N|is below the CEMA \w+ basis \d+ h")
#: The findings the idler group shows: the straight run's two warnings and a convex curve's
#: (whose clause opens with the curve and names the idler set).
_IDLER_WORDS = (r"^carry idler (?:load|bearing life)|each carry idler set carries .*(?:"
                + _IDLERS + ")")


def _idlers(runs: pd.DataFrame) -> pd.Series:
    """Runs whose carry idlers are past their CEMA class: the engine's warning of a set's
    load above the rating or a bearing life below the L10 basis (straight run or convex
    curve). The engine judges only a set with a ``cema_class``, and says so in words: the
    runs carry no rating column."""
    said = _message(runs).map(lambda m: any(
        not c.startswith("note: ") and re.search(_IDLERS, c) for c in clauses(m, "")))
    return said.astype(bool)


@dataclass(frozen=True)
class Cause:
    """One way a run does not pass: ``detect(runs)`` flags its rows; ``columns`` (patterns
    with ``{i}``) are the figures that show the cause, ``words`` a regular expression picking
    the clauses of the message that name it."""

    key: str
    title: str
    detect: Callable[[pd.DataFrame], pd.Series]
    columns: tuple[str, ...] = ()
    words: str = ""
    note: str = field(default="")
    explain: Callable[[pd.Series], str] | None = None


#: The failure groups, in the report's order. A run is listed in every group it belongs to.
CAUSES: tuple[Cause, ...] = (
    Cause("failed", "failed (no result)", lambda r: _status(r) == "failed", (),
          r".", "the run stopped with an error; its message says where and why"),
    Cause("ran_away", "ran away", _ran_away, ("velocity_max_m_s", "velocity_min_m_s"),
          r"ran (?:away|back)|could not hold it back"),
    Cause("not_stopped", "did not stop", not_stopped,
          ("stop_time_s", "brake_force_kn", "velocity_min_m_s"), r"did not stop|never"),
    Cause("missed_stop", "stopped slower than the stop time asked (of its auto brakes or "
          "its drives in a controlled stop)",
          lambda r: _message(r).str.contains("stop missed its stop.time_s", regex=False),
          ("stop_time_s", "stop_time_target_s", "brake_force_kn"), r"missed its stop"),
    Cause("never_going", "never got going (no stop to judge)", never_going,
          ("start_time_s", "power_kw", "drive{i}_power_required_kw", "drive{i}_utilisation"),
          r"never reached|cannot hold|short by|force limit"),
    Cause("short_of_speed", "never reached design speed in the start (stopped from below it)",
          lambda r: (_message(r).str.contains("never reached 99 % of design speed",
                                              regex=False) & ~never_going(r)),
          ("start_time_s", "power_kw", "drive{i}_utilisation"), r"never reached 99 %"),
    Cause("overload", "overloaded a drive", _overloaded,
          ("power_kw", "rated_power_kw", "drive{i}_utilisation", "drive{i}_overload_s",
           "drive{i}_power_required_kw"),
          _OVERLOAD + r"|short by|rated (?:force|power|\d)|rated_power|larger motor",
          explain=_overload_words),
    Cause("slip", "slipped on a drive pulley", _slipped,
          ("drive{i}_slip_s", "drive{i}_slip_margin_min", "slip_margin", "slip_margin_start",
           "takeup_mass_kg"),
          _SLIP_WORDS),
    Cause("holding", "holding brakes cannot hold the loaded belt at rest",
          lambda r: _message(r).str.contains("holding brakes cannot hold", regex=False),
          ("brake_force_kn", "holdback_torque_knm"), r"holding brakes cannot hold"),
    Cause("end_stop", "reached a take-up end stop", _end_stop,
          ("takeup_endstop_speed_m_s", "takeup_endstop_gap_m", "takeup_travel_m"),
          r"take-up carriage reached|end stop"),
    # a pulley's slack side is no slack span: the at-rest grip clause ("slack side 0 kN ...
    # slack-side tension") was shown as what a slack run says, before its slack clause
    Cause("slack", "went slack", _slack, ("slack_max_m", "slack_duration_s", "t_min_dyn_kn"),
          r"slack(?![ -]side)"),
    Cause("sag", "sagged past its limit", _sagged, ("sag_max_pct", "sag_max_dyn_pct"),
          _SAG + r"|the sag goes as|its sag there has no bound|slack(?![ -]side)"),
    Cause("route", "left its idlers or its line at a curve (vertical or horizontal)", _route,
          ("liftoff_max_kn_over", "curve{k}_tension_kn", "curve{k}_liftoff_tension_kn",
           "curve{k}_radius_min_m", "hcurve{k}_t_low_kn", "hcurve{k}_tension_min_kn",
           "hcurve{k}_t_high_kn", "hcurve{k}_tension_max_kn"), _ROUTE + "|" + _ROUTE_FIX),
    Cause("marginal", "marginal: a figure within its error bar of the limit (the verdict "
          "may flip on a finer mesh)",
          lambda r: _message(r).str.contains("marginal:", regex=False), (), r"marginal"),
    Cause("high_stress", "stopped faster than 5 wave loop times (a high-stress stop)",
          _high_stress, ("stop_time_s", "wave_loop_time_s", "stop_wave_ratio"),
          _HIGH_STRESS),
    Cause("overspeed", "ran above the overspeed trip (110 % of design speed)",
          lambda r: _message(r).str.contains("overspeed in the", regex=False) & ~_ran_away(r),
          ("velocity_max_m_s",), r"overspeed"),
    Cause("safety", "belt safety factor below its minimum", _safety,
          ("safety_factor", "safety_factor_dyn"), r"safety factor"),
    Cause("pulley", "pulley below its minimum diameter", _pulleys,
          ("pulley{j}_diameter_min_m",), r"pulley"),
    Cause("fill", "over-filled its belt's cross-section (the design load does not fit it, "
          "ISO 5048)", lambda r: _any_over(r, "fill_pct", 100.0), ("fill_pct",),
          r"^fill_pct \d+ %"),
    Cause("idlers", "overloaded its carry idlers (a set above its CEMA rating or a bearing "
          "life below the L10 basis)", _idlers,
          ("idler_load_carry_n", "idler_load_roll_n", "idler_l10_h",
           "curve{k}_idler_load_extra_n"), _IDLER_WORDS),
)


def clauses(message: Any, words: str) -> list[str]:
    """The clauses of a run's message (joined by ``; ``) that match ``words``."""
    if not isinstance(message, str) or not message:
        return []
    parts, depth, start = [], 0, 0
    for k, ch in enumerate(message):  # "; " inside parentheses belongs to its clause
        depth += {"(": 1, ")": -1}.get(ch, 0)
        if depth <= 0 and message.startswith("; ", k):
            parts.append(message[start:k])
            start = k + 2
    parts.append(message[start:])
    return [c for c in parts if c and re.search(words, c, re.IGNORECASE)]


#: The words that end what would avoid a finding (the engine's warnings end their fix so).
AVOID = "would avoid"
#: The opening words of the engine's findings that name their own fix: such a clause is a
#: warning of its own, never the fix of the clause before it, even where that clause (the
#: last of a warning whose remedies do not end in AVOID: a stop faster than the wave
#: criterion, a belt that ran away, an overspeed) has none.
_OPENS_FINDING = re.compile(
    r"(?:take-up carriage reached|belt safety factor [\d.]+ |(?:transient )?sag on the \w+ "
    r"strand|the belt (?:goes slack|ran |did not stop|never )|drive \d+ \([^)]*\) "
    r"(?:slipped|needs|was above)|slip at drive|overspeed in the|stop in [\d.]+ s is faster"
    r"|brake stop missed|the holding brakes cannot hold|the \w+ brake's pulley slipped"
    r"|not settled while running|the speed loop did not track|the running phase is short"
    r"|lift-off (?:in|at) |curve \d+ \((?:concave|convex)|grade change without"
    r"|carry idler (?:load|bearing life) )")

#: The opening words of a clause that goes on with the clause before it: what the finding
#: before it would take (``a longer start``, ``less brake force``, ``a controlled stop ...
#: would be slower``, ``or more inertia``), or more of its figures (``its tensions ranged``,
#: ``19.4 kN there keeps it within``). A warning's remedies without AVOID at their end were
#: left as clauses of their own: the report's overspeed group showed the settling warning's
#: "a longer run_s shows whether the swing decays (docs/dynamics.md, Settling and overspeed)"
#: for the overspeed and dropped its "a gentler start stretches it less: a longer start", and
#: a high-stress stop's group showed no fix at all.
_GOES_ON = re.compile(
    r"(?:a |an |or |less |more |no |its |with |at least |that, |so |the start then "
    r"|CEMA's |-?\d)")


def said_clauses(message: Any) -> list[tuple[str, str]]:
    """The clauses of a run's message (:func:`clauses`) as ``(finding, what it says)``: a
    clause naming what would avoid a finding (``... would avoid it``) joins the clause before
    it, when that one has no fix of its own, and so does a clause that goes on with the one
    before it (:data:`_GOES_ON`: a remedy without AVOID at its end, or more of the finding's
    figures). A warning cuts its finding from its fix with
    "; " as the message cuts warnings, so a failure group showed a slip without the take-up
    or start time that avoids it, and the last section listed the fix as a clause of its
    own. A clause that opens a finding of its own (:data:`_OPENS_FINDING`) is never joined:
    a take-up end stop after a stop's remedies ('... a flywheel of ...') was read as their
    fix, so the end-stop group showed another clause for the run, and a transient safety
    factor after a run-away's remedies was missing from the safety factor group."""
    out: list[tuple[str, str]] = []
    for part in clauses(message, ""):
        # a note or a marginal verdict is a sentence of its own, whatever it ends with
        opens = part.startswith(("note: ", "marginal: ")) or bool(_OPENS_FINDING.match(part))
        joins = (AVOID in part and AVOID not in out[-1][1]) or bool(_GOES_ON.match(part)) \
            if out else False
        if joins and not opens:
            out[-1] = (out[-1][0], f"{out[-1][1]}; {part}")
        else:
            out.append((part, part))
    return out


def finding_clauses(message: Any, words: str) -> list[str]:
    """What a run says (:func:`said_clauses`, each finding with its fix) of the findings
    matching ``words``, its warnings only where one matches: a note (``note: ...``) names
    checks and fields (``slip_margin_start``) without being a finding, so it is what a run
    says of a cause only when no warning of the run matches."""
    found = [said for finding, said in said_clauses(message)
             if re.search(words, finding, re.IGNORECASE)]
    said = [c for c in found if not c.startswith("note: ")]
    return said or found


#: The last group: a run with status warning that no cause above names (a speed loop that did
#: not track its reference, ...), so that every run that did not pass is in section 2.
OTHER = Cause("other", "warned of something else (what the run says)",
              lambda r: _status(r) == "warning", (), r".")


def cause_groups(runs: pd.DataFrame) -> list[tuple[Cause, pd.DataFrame, list[str]]]:
    """Every cause with runs in it: ``(cause, its rows, the figure columns present)``; last,
    :data:`OTHER`, the runs with a warning that no cause names."""
    out = []
    if not len(runs):
        return out
    named = pd.Series(False, index=runs.index)
    for cause in (*CAUSES, OTHER):
        mask = cause.detect(runs).fillna(False).astype(bool)
        if cause is OTHER:
            mask &= ~named
        named |= mask
        if not mask.any():
            continue
        cols = [c for p in cause.columns for c, _ in expand(p, runs.columns)
                if numeric(runs[mask], c) is not None]
        out.append((cause, runs[mask], cols))
    return out


# ---------------------------------------------------------------------- verdict rows
def idler_ratings() -> dict[str, dict[str, float]]:
    """The engine's idler catalogue by CEMA class (:func:`beltstudy.engine.checks.
    idler_ratings`): ``{"B": {"carry_rating_n": 1824.0, "l10_min_h": 30000.0, ...}, ...}``,
    the load rating of a troughing set [N] and the L10 life [h] the rating holds at."""
    from beltstudy.engine.checks import idler_ratings as engine_ratings

    return engine_ratings()


#: The rating a run's own warning names (``... exceeds the CEMA B rating 1824 N``) [N] and
#: the L10 basis (``... is below the CEMA B basis 30000 h``) [h]: the limit of a run whose
#: class this catalogue does not hold.
_SAID_RATING = re.compile(r"carry idler load \d+ N per set [^;]*exceeds the CEMA \w+ rating "
                          r"(\d+) N")
_SAID_BASIS = re.compile(r"carry idler bearing life L10 \d+ h [^;]*is below the CEMA \w+ "
                         r"basis (\d+) h")


#: A named limit: ``(runs, **numbers) -> (the limit per row [unit of the quantity] or None,
#: words)``; ``numbers`` the drive or pulley number of the verdict's column (``i="1"``).
Limit = Callable[..., tuple[pd.Series | None, str]]


def study_limits(study: dict, sf_min: float, sf_ratio: float,
                 sf_words: str = "DIN 22101 minimum",
                 sf_of: Callable[[pd.DataFrame], pd.Series] | None = None
                 ) -> dict[str, Limit]:
    """The study's named limits (:attr:`Verdict.limit` names them): the belt safety factor
    ``sf_min`` steady and ``sf_ratio * sf_min`` transient, the tension they allow
    (``belt_rating_kn`` / safety factor), the sag limits and the take-up travel. ``sf_of``:
    each run's own minimum (``runs -> Series``; a study whose runs use belts of both kinds
    judges each by its own), ``sf_min`` where it gives none."""
    conv = study.get("conveyor") or {}
    sag = conv.get("sag_limit_pct") or {}
    carry, ret = sag.get("carry"), sag.get("return")
    length = sum(p.get("length_m", 0.0) for p in conv.get("profile", []))
    travel = (conv.get("takeup") or {}).get("travel_m") or 0.015 * length

    def per_run(runs: pd.DataFrame, axis: str, value: float | None) -> pd.Series:
        """``value`` for every run, or the run's own where a conveyor axis sets it (a
        ``takeup.travel_m`` axis: each run is judged against its own carriage travel)."""
        out = pd.Series(value, index=runs.index, dtype=float)
        own = numeric(runs, axis)
        return out if own is None else own.fillna(out)

    def const(value: float, words: str, axis: str = "") -> Limit:
        return lambda runs, **_: (per_run(runs, axis, value), words)

    def run_sf(runs: pd.DataFrame) -> pd.Series:
        own = sf_of(runs) if sf_of is not None else None
        base = pd.Series(sf_min, index=runs.index, dtype=float)
        return base if own is None else pd.to_numeric(own, errors="coerce").fillna(base)

    def mixed(sf: pd.Series) -> bool:
        return sf.round(9).nunique() > 1

    def sf_limit(ratio: float, words: str) -> Limit:
        def f(runs, **_):
            sf = run_sf(runs)
            if mixed(sf):
                return ratio * sf, (f"{words}, of each run's belt: " + ", ".join(
                    f"{gnum(ratio * v, 3)}" for v in sorted(sf.unique())))
            return ratio * sf, words
        return f

    def allow(ratio: float) -> Limit:
        def f(runs, **_):
            rating = numeric(runs, "belt_rating_kn")
            if rating is None:
                return None, ""
            sf = ratio * run_sf(runs)
            if mixed(sf):
                return rating / sf, ("belt rating / the safety factor of each run's belt ("
                                     + ", ".join(f"{gnum(v, 3)}" for v in sorted(sf.unique())) + ")")
            return rating / sf, f"belt rating / {gnum(float(sf.iloc[0]) if len(sf) else 0, 3)}"
        return f

    def rated_force(runs, i: str = "1", **_):
        # a drive's rated force P_N / v at design speed, the engine's (docs/drives.md)
        rated = numeric(runs, f"drive{i}_rated_power_kw")
        speed = per_run(runs, "speed_m_s", conv.get("speed_m_s"))
        if rated is None or not speed.notna().any():
            return None, ""
        return rated / speed, "rated force (rated power / speed)"

    def sag_limit(runs, **_):
        if carry is None or ret is None:
            return None, ""
        words = f"carry {carry:g} %, return {ret:g} %"
        # the column is the larger of both strands: a number to judge against only when the
        # strands share their limit; else the runs' messages name the strand past its limit
        return (pd.Series(float(carry), index=runs.index) if carry == ret else None), words

    def curve_radius(runs, k: str = "1", **_):
        # curve k's radius: the profile section whose end is the curve's junction
        # (curve{k}_at_m), as the file gives it (a curve shorter than an idler pitch is judged
        # as a grade change and has no curve{k} fields)
        # (each run's own section lengths and radii where a grid axis sets them)
        at = numeric(runs, f"curve{k}_at_m")
        if at is None:
            return None, ""
        out = pd.Series(math.nan, index=runs.index)
        end = pd.Series(0.0, index=runs.index)
        for i, sec in enumerate(conv.get("profile", [])):
            end = end + per_run(runs, f"profile.{i}.length_m", sec.get("length_m", 0.0))
            radius = per_run(runs, f"profile.{i}.curve_radius_m", sec.get("curve_radius_m"))
            here = radius.notna() & ((end - at).abs() <= 0.5)
            out[here] = radius[here]
        return out, "the curve's radius (profile curve_radius_m)"

    def wave_rule(runs, **_):
        # 5 wave loop times where the engine judged the stop (a belt that reached its running
        # speed: start_time_s, or the words of a high-stress stop); none elsewhere
        judged = _high_stress(runs)
        start = numeric(runs, "start_time_s")
        if start is not None:
            judged |= start.notna()
        return (pd.Series(5.0, index=runs.index).where(judged),
                "5 wave loop times (Harrison after Funke 1973; judged where the belt reached "
                "its running speed)")

    def idler_limit(key: str, said: re.Pattern, unit: str, words: str) -> Limit:
        # each run's carry class (the file's, or a grid axis's idlers.carry.cema_class), its
        # catalogue value; none without a class (the engine judges no class-less set, and
        # leaves idler_l10_h null); a class this catalogue lacks: the value its warning names
        carry_set = (conv.get("idlers") or {}).get("carry") or {}

        def f(runs, **_):
            cls = pd.Series(carry_set.get("cema_class"), index=runs.index, dtype=object)
            axis = "idlers.carry.cema_class"
            if axis in runs.columns:
                cls = runs[axis].where(runs[axis].notna(), cls)
            table = idler_ratings()
            out = pd.to_numeric(cls.map(lambda c: (table.get(c) or {}).get(key)
                                        if isinstance(c, str) else None), errors="coerce")
            named = pd.to_numeric(_message(runs).str.extract(said, expand=False),
                                  errors="coerce")
            out = out.fillna(named).astype(float)
            if not out.notna().any():
                return None, ""
            classes = sorted({c for c in cls.dropna().astype(str)})
            values = ", ".join(f"{c} {eng(table[c][key], unit)}" for c in classes if c in table)
            return out, (f"{words} of the carry class, {values or 'as each run says'} "
                         "(engine/data/idler_ratings.csv)")
        return f

    def rated_at_pulleys(runs, **_):
        # the motor power needed (efficiency included) is judged per drive where the runs
        # carry it; the power at the pulleys against the rating would disagree with it
        if _required_power_known(runs):
            return None, ("the rating is judged by the power each drive needs, its drive "
                          "train's efficiency included (power required, drive i)")
        return numeric(runs, "rated_power_kw"), "rated_power_kw"

    return {
        "rated_at_pulleys": rated_at_pulleys,
        "sf_steady": sf_limit(1.0, sf_words),
        "sf_dyn": sf_limit(sf_ratio, f"{gnum(sf_ratio, 3)} x the minimum, transient"),
        "t_allow_steady": allow(1.0),
        "t_allow_dyn": allow(sf_ratio),
        "sag": sag_limit,
        "travel": const(travel, "carriage travel", "takeup.travel_m"),
        "rated_force": rated_force,
        "curve_radius": curve_radius,
        "wave": wave_rule,
        "idler_rating": idler_limit("carry_rating_n", _SAID_RATING, "N",
                                    "CEMA 502 load rating"),
        "idler_l10": idler_limit("l10_min_h", _SAID_BASIS, "h", "CEMA 502-2004 L10 basis"),
    }


def _slack_no_sag(v: Verdict, runs: pd.DataFrame, values: pd.Series) -> pd.Series:
    """Runs of a sag row without a sag value because the belt went slack: a slack span's sag
    has no bound, past every limit. Transient: a run whose transient ran without
    ``sag_max_dyn_pct``; steady: a run without ``sag_max_pct`` whose steady lowest tension
    ``t_min_kn`` is at or below zero (a steady run slack at -2.84 kN was left out of the steady
    sag row, which read 0.78 % against 1.5 %, 'past the limit in 2 of 8 runs' of 16)."""
    return _slack_no_sag_of(v.column, runs, values)


def _slack_no_sag_of(column: str, runs: pd.DataFrame, values: pd.Series) -> pd.Series:
    """:func:`_slack_no_sag` for the sag column ``column``."""
    if column == "sag_max_dyn_pct":
        return transient_ran(runs) & values.isna()
    if column == "sag_max_pct":
        t_min = numeric(runs, "t_min_kn")
        if t_min is not None:
            return values.isna() & (t_min <= 0.0).fillna(False)
    return values.isna() & False


def _limits_of(v: Verdict, runs: pd.DataFrame, nums: dict[str, str], limits: dict[str, Limit]
               ) -> tuple[pd.Series | None, str]:
    """The limit of ``v`` for every row of ``runs`` and its words."""
    if v.limit is None:
        return None, ""
    if isinstance(v.limit, int | float):
        return pd.Series(float(v.limit), index=runs.index), ""
    name = v.limit.format(**nums) if nums else v.limit
    if name in limits:
        return limits[name](runs, **nums)
    return numeric(runs, name), name


#: A take-up travel within this fraction of the carriage travel is the whole of it: the
#: carriage at its end stop (the engine's contact leaves 4.499999999 m of a 4.5 m travel).
TRAVEL_AT_STOP = 1e-6


def _past(v: Verdict, values: pd.Series, runs: pd.DataFrame, lim: pd.Series | None,
          ok_col: str | None, bad_col: str | None = None) -> pd.Series:
    """Rows past the limit: beyond the number, their own verdict column false (``ok``) or true
    (``bad``), the message naming it (sag), or no value where a missing one is the worst (did
    not stop)."""
    past = pd.Series(False, index=runs.index)
    beyond = pd.Series(False, index=runs.index)
    if lim is not None:
        known = values.notna() & lim.notna()
        if v.limit == "travel":  # the whole travel used: the carriage reached its end stops
            beyond = known & (values >= lim * (1.0 - TRAVEL_AT_STOP))
        elif v.worst == "max":
            beyond = known & (values > lim)
        else:  # a lowest tension of 0 is slack: at the limit is past it
            beyond = known & ((values <= lim) if v.limit == 0.0 else (values < lim))
    if v.ok or v.bad:
        # the run's own verdict judges, element by element; where a limit is shown too, the
        # row counts the runs whose verdict fails on its side (a horizontal curve's one
        # verdict is past its lower limit or its upper one; the extremes against the limits
        # are only known to be beyond them where the verdict fails)
        own = pd.Series(False, index=runs.index)
        if ok_col and ok_col in runs.columns:
            own |= runs[ok_col].astype("boolean").fillna(True).eq(False).astype(bool)
        if bad_col and bad_col in runs.columns:
            own |= runs[bad_col].astype("boolean").fillna(False).astype(bool)
        unknown = values.isna() | lim.isna() if lim is not None else True
        past |= own & (beyond | unknown)
    else:
        past |= beyond
    if v.limit == "sag":
        past |= _sagged(runs, "transient" if v.column == "sag_max_dyn_pct" else "steady")
    if v.null_worst:
        past |= transient_ran(runs) & values.isna()
    if v.said:  # the engine's own warning of the quantity: past, whatever the number
        past |= _message(runs).str.contains(v.said, regex=True)
    return past


def _worst(v: Verdict, values: pd.Series, lim: pd.Series | None,
           past: pd.Series | None = None) -> tuple[Any, bool]:
    """The row with the worst value; where the limit differs between runs (a rated power
    that is a grid axis), the worst against its own limit (value / limit, or value - limit
    where a limit is 0 or below), and True. A row judged by the runs' own verdicts (``ok``,
    ``bad``) is governed by a run past it where one is: a horizontal curve's lowest tension
    was governed by a run that ran to the inside (every run's lowest tension the same), not by
    the one that ran out."""
    if past is not None and (v.ok or v.bad) and values.where(past).notna().any():
        values = values.where(past)
    if lim is not None and lim.notna().any() and lim.dropna().nunique() > 1:
        rel = values / lim if (lim.dropna() > 0).all() else values - lim
        if rel.notna().any():
            return (rel.idxmax() if v.worst == "max" else rel.idxmin()), True
    return (values.idxmax() if v.worst == "max" else values.idxmin()), False


def verdict_rows(runs: pd.DataFrame, limits: dict[str, Limit]) -> list[dict]:
    """One row per :data:`VERDICTS` entry (and drive / pulley) present in ``runs``:
    ``{"verdict", "label", "column", "row", "value", "limit", "limit_text", "past", "n",
    "missing"}``; ``row`` is the governing run (the worst value; for ``null_worst`` the first
    run with the value missing); ``past`` the number of runs past the limit."""
    ok = runs[_status(runs) != "failed"] if len(runs) else runs
    out = []
    for v in VERDICTS:
        for column, nums in expand(v.column, ok.columns):
            if v.worst == "text":
                texts = ok[column].dropna().astype(str)
                if len(texts):
                    counts = texts.value_counts()
                    row = ok.loc[texts.index[0]]
                    out.append({"verdict": v, "label": v.quantity.format(**nums),
                                "column": column, "row": row, "value": ", ".join(counts.index),
                                "limit": None, "limit_text": "", "past": 0, "n": len(texts),
                                "missing": 0})
                continue
            values = numeric(ok, column)
            if values is None:
                continue
            # a transient without a stop time did not stop (ran away included)
            # (a belt that never got going made no stop: its stop time is missing, not worst)
            unstopped = (transient_ran(ok) & values.isna() & ~never_going(ok) if v.null_worst
                         else values.isna() & False)
            missing = int(unstopped.sum())
            if missing:  # the governing run: one that did not stop, before one that ran away
                first = unstopped & not_stopped(ok)
                idx = (first if first.any() else unstopped).idxmax()
            lim, text = _limits_of(v, ok, nums, limits)
            if v.judged_only and lim is not None:
                values = values.where(lim.notna())
                if not values.notna().any():
                    continue
            if v.limit == LIFTOFF_LIMIT and lim is None:
                # a convex curve (crest): the engine gives it no lift-off tension, and its
                # tensions are not judged against one (its radius row judges it)
                continue
            judged = values.abs() if v.magnitude else values
            ok_col = v.ok.format(**nums) if v.ok else None
            bad_col = v.bad.format(**nums) if v.bad else None
            past = _past(v, judged, ok, lim, ok_col, bad_col)
            ok_col = ok_col or bad_col
            relative = False
            if not missing:
                idx, relative = _worst(v, judged, lim, past)
                text = f"{text}; the worst against its own limit" if relative else text
            row = ok.loc[idx]
            slack = _slack_no_sag(v, ok, values)
            value_text = ""
            if slack.any():  # a slack span's sag has no value: it is past every sag limit
                past |= slack
                k = int(slack.sum())
                when = " in the steady state" if v.column == "sag_max_pct" else ""
                text = (f"{text}; {k} run{'s' if k != 1 else ''} went slack{when} (no sag "
                        "value: past every limit)")
                if not past.loc[idx]:  # the worst value is within: a slack run governs
                    value_text = f"no value: went slack{when}" + (
                        f" (largest value {eng(values.max(), v.unit)}, run "
                        f"{ok.loc[idx].get('run_id')})" if values.notna().any() else "")
                    idx = slack.idxmax()
                    row = ok.loc[idx]
            limit = None if lim is None or pd.isna(lim.loc[idx]) else float(lim.loc[idx])
            # runs whose error bars put this figure within its bar of the limit (the engine's
            # "marginal: <figure> ... against limit ...", engine/accuracy.py)
            marginal = int(_message(ok).str.contains(f"marginal: {column} ",
                                                     regex=False).sum())
            value = None if missing or value_text else float(values.loc[idx])
            if (v.limit == "travel" and value is not None and limit is not None
                    and value >= limit * (1.0 - TRAVEL_AT_STOP)):
                value = limit  # at its end stop: the whole travel, not 4.499999999 of 4.5 m
            out.append({"verdict": v, "label": v.quantity.format(**nums), "column": column,
                        "marginal": marginal, "relative": relative,
                        "row": row,
                        "value": value,
                        "value_text": value_text,
                        "limit": limit, "limit_text": text, "past": int(past.sum()),
                        # every run with a value, and those past without one (did not
                        # stop, went slack, a sag warning without its figure)
                        # (a belt that never got going made no stop: not counted)
                        "n": int((values.notna() | unstopped | slack
                                  | (past & ~never_going(ok))).sum()),
                        "missing": missing,
                        # of those, the runs that ran away (section 2's own group)
                        "ran_away": int((unstopped & _ran_away(ok)).sum()),
                        "ok_col": ok_col,
                        "ok_judged": (int(ok[ok_col].notna().sum())
                                      if ok_col and ok_col in ok.columns else None)})
    return out
