"""The report's route verdicts (docs/web.md, sections 1 and 2): the vertical curves' lift-off
and radius, the horizontal curves' two tensions, and the group of runs that left their
idlers or their line, from real steady runs of the hand conveyor (tests/conftest.py:
m'_G 20 kg/m, 500 m flat then 500 m rising 50 m)."""

from __future__ import annotations

import math
import re

import pandas as pd
import pytest

from beltstudy.engine import Scenario, run_one
from beltstudy.engine.conveyor import parse_conveyor
from beltstudy.service.door.studyfile import resolve_study
from beltstudy.service.web.report import report_html
from beltstudy.service.web.verdicts import (
    cause_groups,
    finding_clauses,
    study_limits,
    verdict_rows,
)
from tests.conftest import hand_conveyor_dict

G = 9.81


def _valley(radius_m: float) -> dict:
    return hand_conveyor_dict(profile=[
        {"length_m": 500, "lift_m": 0, "curve_radius_m": radius_m},
        {"length_m": 500, "lift_m": 50}])


def _bend(radius_m: float, tilt_deg: float) -> dict:
    return hand_conveyor_dict(profile=[{"length_m": 1000, "lift_m": 50,
                                        "horizontal_radius_m": radius_m,
                                        "superelevation_deg": tilt_deg}])


def _runs(conveyors: dict[str, tuple[dict, dict]]) -> pd.DataFrame:
    """One steady run per conveyor, with the axis columns a study's rows carry."""
    rows = []
    for run_id, (conv, axes) in conveyors.items():
        s = run_one(parse_conveyor(conv), Scenario(), model="din", dynamics=False).summary
        rows.append({**s, **axes, "run_id": run_id})
    return pd.DataFrame(rows)


@pytest.fixture(scope="module")
def valley_runs() -> pd.DataFrame:
    """The curve of 180 m lifts the empty belt running (it needs about 215 m), that of 240 m
    only at start-up (it needs about 265 m there), that of 3 000 m never."""
    return _runs({f"r{r:g}": (_valley(r), {"profile.0.curve_radius_m": r})
                  for r in (180.0, 240.0, 3000.0)})


def _rows(runs: pd.DataFrame, conveyor: dict) -> dict[str, dict]:
    limits = study_limits({"conveyor": conveyor}, 8.0, 0.75)
    return {r["column"]: r for r in verdict_rows(runs, limits) if r["verdict"].group == "Routes"}


def test_vertical_curve_verdicts_follow_the_runs_own_lift_off_verdicts(valley_runs):
    rows = _rows(valley_runs, _valley(3000.0))
    lifts = valley_runs["curve1_liftoff"].astype(bool)
    lifts_start = valley_runs["curve1_liftoff_start"].astype(bool)
    assert list(valley_runs.loc[lifts, "run_id"]) == ["r180"]
    assert list(valley_runs.loc[lifts_start, "run_id"]) == ["r180", "r240"]
    running, start = rows["curve1_tension_kn"], rows["curve1_tension_start_kn"]
    assert (running["past"], running["n"]) == (1, 3)
    assert (start["past"], start["n"]) == (2, 3)
    # the limit shown is the governing run's lift-off tension R m'_G g cos(a): R 180 m, the
    # steepest element of the arc just under asin(0.1)
    assert running["row"]["run_id"] == "r180"
    hand = 180.0 * 20.0 * G * math.cos(math.asin(0.1)) / 1e3
    assert running["limit"] == pytest.approx(hand, rel=5e-3)


def test_the_radius_a_curve_needs_is_judged_against_each_runs_own_radius(valley_runs):
    """The radius is a grid axis here: each run against its own curve_radius_m (the base
    conveyor's 3 000 m would pass every run)."""
    rows = _rows(valley_runs, _valley(3000.0))
    running, start = rows["curve1_radius_min_m"], rows["curve1_radius_min_start_m"]
    need = valley_runs.set_index("run_id")["curve1_radius_min_m"]
    assert 180.0 < need["r180"] and need["r240"] < 240.0
    assert (running["past"], running["limit"], running["row"]["run_id"]) == (1, 180.0, "r180")
    assert start["past"] == 2
    # without the axis column, every run is judged against the file's radius
    plain = _rows(valley_runs.drop(columns="profile.0.curve_radius_m"), _valley(3000.0))
    assert plain["curve1_radius_min_m"]["past"] == 0
    assert plain["curve1_radius_min_m"]["limit"] == 3000.0


def test_runs_that_lift_the_belt_are_a_group_with_the_radius_that_avoids_it(valley_runs):
    groups = {c.key: (c, part) for c, part, _ in cause_groups(valley_runs)}
    cause, part = groups["route"]
    assert list(part["run_id"]) == ["r180", "r240"]
    said = finding_clauses(part.iloc[0]["message"], cause.words)
    assert any("lifts off its carry idlers" in c for c in said)
    # the fix names the radius the run needs, curve1_radius_min_m rounded up (about 215 m)
    need = math.ceil(part.iloc[0]["curve1_radius_min_m"])
    assert 200 < need < 230
    # with its finding, as one entry (the finding's fix goes on in the clause after it)
    assert any("lifts off its carry idlers" in c and f"; a radius of at least {need} m" in c
               for c in said), said
    # the run-back note the runs also carry is not a route finding
    assert not any(c.startswith("note: ") for c in said)


def test_horizontal_curve_rows_count_each_side_of_the_one_verdict():
    """R 300 m flat: the belt runs to the inside (its tension above what its weight holds);
    R 20 000 m at 6 deg: the loaded belt runs out down the superelevation (its tension below
    the R q(-d) it needs); R 2 000 m at 6 deg holds it."""
    runs = _runs({"in": (_bend(300.0, 0.0), {}), "out": (_bend(20000.0, 6.0), {}),
                  "held": (_bend(2000.0, 6.0), {})})
    assert list(runs["hcurve1_ok"]) == [False, False, True]
    rows = _rows(runs, _bend(2000.0, 6.0))
    low, high = rows["hcurve1_t_low_kn"], rows["hcurve1_t_high_kn"]
    assert (low["past"], low["row"]["run_id"]) == (1, "out")
    assert (high["past"], high["row"]["run_id"]) == (1, "in")
    assert low["value"] < low["limit"] and high["value"] > high["limit"]
    cause, part = {c.key: (c, p) for c, p, _ in cause_groups(runs)}["route"]
    assert list(part["run_id"]) == ["in", "out"]
    said = finding_clauses(part.iloc[1]["message"], cause.words)
    # the finding with its fix, one entry
    assert any("runs out of the curve" in c and "; less superelevation" in c for c in said)


def test_the_report_shows_the_route_verdicts(web, valley_runs):
    study = resolve_study(web.tiny_study(name="valley", conveyor=_valley(3000.0),
                                         grid={"profile.0.curve_radius_m": [180, 240, 3000]}),
                          studies_dir=web.ROOT / "studies")
    doc = {"id": study.id, "name": study.name, "engine_version": study.engine_version,
           "finished_at": 0.0, "study": study.to_json()}
    html = report_html(doc, valley_runs, {"state": "done", "done": 3, "total": 3})
    s1 = re.search(r'<section id="s1">(.*?)</section>', html, re.S).group(1)
    assert "Routes" in s1 and "curve1_radius_min_m" in s1
    assert "past the limit in 1 of 3 runs" in s1
    s2 = re.search(r'<section id="s2">(.*?)</section>', html, re.S).group(1)
    assert "left its idlers or its line at a curve" in s2


def test_a_convex_curve_has_no_lift_off_rows():
    """A valley of 0 % into +10 % (concave, R 3 000 m) and a crest of +10 % into 0 %
    (convex, R 400 m): the engine gives the crest no lift-off tension, yet the report listed
    'highest steady tension, vertical curve 2 (concave: judged against the empty belt's lift-off
    tension ...)' with the bare column name 'curve2_liftoff_tension_kn' as its limit and
    'within' by curve2_liftoff, false at a crest (p13: a 1 km booster conveyor with a crest of
    R 300 m, 40.36 kN). The crest keeps its radius row; the valley keeps its lift-off rows
    against R m'_G g cos(a) = 3 000 x 20 x 9.81 x cos(asin 0.1) / 1e3 = 585.6 kN."""
    conv = hand_conveyor_dict(profile=[
        {"length_m": 500, "lift_m": 0, "curve_radius_m": 3000},
        {"length_m": 500, "lift_m": 50, "curve_radius_m": 400},
        {"length_m": 300, "lift_m": 0}])
    runs = _runs({"r1": (conv, {})})
    assert list(runs[["curve1_kind", "curve2_kind"]].iloc[0]) == ["concave", "convex"]
    assert pd.isna(runs["curve2_liftoff_tension_kn"].iloc[0])
    rows = _rows(runs, conv)
    assert "curve2_tension_kn" not in rows and "curve2_tension_start_kn" not in rows
    assert "curve2_radius_min_m" in rows and rows["curve2_radius_min_m"]["limit"] == 400.0
    hand = 3000.0 * 20.0 * G * math.cos(math.asin(0.1)) / 1e3
    for column in ("curve1_tension_kn", "curve1_tension_start_kn"):
        assert rows[column]["limit"] == pytest.approx(hand, rel=5e-3)
        assert rows[column]["past"] == 0
