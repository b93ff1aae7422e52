"""The carry idlers in the design report: the verdict rows judge the load per set against
the CEMA rating of the set's class and the bearing life L10 against the class's basis
(docs/checks.md, "Idler load and bearing life"), and a run whose idlers are past them is in a
failure group of its own, in its own words.

A design study whose 24 runs each warned "carry idler load 2323 N per set ... exceeds the
CEMA B rating 1824 N" showed both idler rows as "no limit" and no idler group in section 2:
the failed rating was named only inside the full message text. The runs here carry the
engine's own words and figures (:func:`solve_steady` on a short conveyor with class B sets
at three pitches), so the report is checked against what the engine judges.
"""

from __future__ import annotations

import re
from functools import cache

import pandas as pd
import pytest

from beltstudy.engine import parse_conveyor, solve_steady
from beltstudy.service import charts
from beltstudy.service.door.studyfile import resolve_study
from beltstudy.service.web.numbers import GROUP, UNIT_SPACE
from beltstudy.service.web.report import report_html
from beltstudy.service.web.verdicts import (
    CAUSES,
    cause_groups,
    finding_clauses,
    study_limits,
    verdict_rows,
)

#: Carry idler pitches [m] of the three runs with class B sets: within the rating (1.2 m),
#: above it (5 m: about 2 210 N on 1 824 N), above it with a bearing life below 30 000 h
#: (9 m).
PITCHES = (1.2, 5.0, 9.0)


@pytest.fixture(autouse=True)
def _close_figures():
    yield
    charts._plt().close("all")


def _conveyor(web, cema_class: str | None = "B") -> dict:
    """The study's conveyor: the tiny one, its carry sets of ``cema_class``."""
    conv = web.tiny_conveyor("idlers")
    if cema_class:
        conv["idlers"]["carry"]["cema_class"] = cema_class
    return conv


@cache
def _engine_run(spacing_m: float, cema_class: str = "B") -> tuple[str, float, float]:
    """The engine's message, ``idler_load_carry_n`` [N] and ``idler_l10_h`` [h] of the tiny
    conveyor with its carry sets of ``cema_class`` at ``spacing_m``."""
    conv = {"name": "idlers", "speed_m_s": 2.5,
            "belt": {"type": "EP630/4", "width_m": 0.8},
            "material": {"capacity_t_h": 300, "density_t_m3": 1.0},
            "profile": [{"length_m": 150, "lift_m": 4}, {"length_m": 150, "lift_m": 8}],
            "idlers": {"carry": {"spacing_m": spacing_m, "trough_deg": 30,
                                 "cema_class": cema_class},
                       "return": {"spacing_m": 3.0, "rolls": 1}},
            "drives": [{"position": "head", "pulley_diameter_m": 0.6, "inertia_kg_m2": 20}]}
    r = solve_steady(parse_conveyor(conv))
    return r.message, r.summary["idler_load_carry_n"], r.summary["idler_l10_h"]


def _runs(classes: tuple[str, ...] = ("B", "B", "B")) -> pd.DataFrame:
    rows = []
    for k, (pitch, cls) in enumerate(zip(PITCHES, classes, strict=True)):
        message, load, l10 = _engine_run(pitch, cls)
        rows.append({"run_id": f"p{k}", "friction_model": "din", "temperature_c": 20.0,
                     "status": "warning" if "CEMA" in message else "ok", "message": message,
                     "idler_load_carry_n": load, "idler_l10_h": l10, "power_kw": 10.0,
                     "t_max_kn": 20.0, "t_min_kn": 3.0})
    return pd.DataFrame(rows)


def _rows(conveyor: dict, runs: pd.DataFrame) -> dict[str, dict]:
    rows = verdict_rows(runs, study_limits({"conveyor": conveyor}, 10.0, 0.75))
    return {r["column"]: r for r in rows}


def test_the_engine_warns_as_the_runs_here_assume():
    """The hand-made table's premise: the engine's own verdicts at the three pitches."""
    said = [m for m, _, _ in (_engine_run(p) for p in PITCHES)]
    assert "exceeds the CEMA B rating 1824 N" not in said[0]
    assert "exceeds the CEMA B rating 1824 N" in said[1] and "bearing life" not in said[1]
    assert "exceeds the CEMA B rating 1824 N" in said[2]
    assert "is below the CEMA B basis 30000 h" in said[2]


def test_idler_rows_are_judged_against_the_rating_of_the_class(web):
    runs = _runs()
    rows = _rows(_conveyor(web), runs)
    load, life = rows["idler_load_carry_n"], rows["idler_l10_h"]
    # CEMA 502's class B rating and the 30 000 h basis (engine/data/idler_ratings.csv)
    assert load["limit"] == pytest.approx(1824.0)
    assert life["limit"] == pytest.approx(30000.0)
    # past as the runs' own warnings say: two above the rating, one below the life
    assert load["past"] == 2 and load["n"] == 3
    assert life["past"] == 1 and life["n"] == 3
    assert load["row"]["run_id"] == "p2" and life["row"]["run_id"] == "p2"
    assert "CEMA 502 load rating" in load["limit_text"] and "B 1" in load["limit_text"]


def test_the_report_shows_the_idler_rows_past_their_limit(web):
    conv = _conveyor(web)
    study = resolve_study(web.tiny_study(name="idlers", conveyor=conv),
                          studies_dir=web.ROOT / "studies")
    doc = {"id": study.id, "name": study.name, "engine_version": study.engine_version,
           "finished_at": 0.0, "study": study.to_json()}
    html = report_html(doc, _runs(), {"state": "done", "done": 3, "total": 3})
    s1 = re.search(r'<section id="s1">(.*?)</section>', html, re.S).group(1)
    load = re.search(r"<tr><td>idler load per carry set.*?</tr>", s1, re.S).group(0)
    assert "no limit" not in load
    assert f"1{GROUP}824{UNIT_SPACE}N" in load and "past the limit in 2 of 3 runs" in load
    life = re.search(r"<tr><td>idler bearing life L10.*?</tr>", s1, re.S).group(0)
    assert f"30{GROUP}000{UNIT_SPACE}h" in life and "past the limit in 1 of 3 runs" in life
    # section 2: the idler group, its count and each run's words with its fix
    s2 = re.search(r'<section id="s2">(.*?)</section>', html, re.S).group(1)
    assert "<li><b>2</b> of 3 runs overloaded its carry idlers" in s2
    group = re.search(r"<h3>Overloaded its carry idlers.*?</table>", s2, re.S).group(0)
    assert sorted(re.findall(r"<code class=id>(\w+)</code>", group)) == ["p1", "p2"]
    assert "a heavier class or a closer pitch" in group


def test_each_run_is_judged_by_its_own_class(web):
    """A grid axis of ``idlers.carry.cema_class`` judges each run by its own class: the 5 m
    pitch's 2 210 N is within class C's 4 003 N."""
    runs = _runs(("B", "C", "B"))
    runs["idlers.carry.cema_class"] = ["B", "C", "B"]
    rows = _rows(_conveyor(web), runs)
    load = rows["idler_load_carry_n"]
    assert load["past"] == 1  # only the 9 m pitch of class B
    assert "B 1" in load["limit_text"] and "C 4" in load["limit_text"]


def test_without_a_class_the_rating_a_run_names_is_its_limit(web):
    """A run's warning names its rating (a class this report's catalogue lacks, or a study
    file without the class): that is the run's limit; a study whose sets have no class and
    whose runs warn of none has no limit (the engine judges no class-less set)."""
    runs = _runs()
    rows = _rows(_conveyor(web, cema_class=None), runs)
    load = rows["idler_load_carry_n"]
    assert load["past"] == 2
    assert load["limit"] == pytest.approx(1824.0)  # the governing run names it
    quiet = runs.assign(message="", status="ok")
    assert _rows(_conveyor(web, cema_class=None), quiet)["idler_load_carry_n"]["limit"] is None


def test_the_idler_group_shows_each_finding_with_its_fix():
    cause = next(c for c in CAUSES if c.key == "idlers")
    runs = _runs()
    groups = {c.key: part for c, part, _ in cause_groups(runs)}
    assert sorted(groups["idlers"]["run_id"]) == ["p1", "p2"]
    said = finding_clauses(runs.loc[2, "message"], cause.words)
    assert [s.split(" ")[2] for s in said] == ["load", "bearing"]
    assert all("closer pitch" in s for s in said)
    # a convex curve's idler overload is an idler finding too (engine/curves.py)
    convex = ("curve 2 (convex, R 400 m at 900 m): each carry idler set carries 4321 N (3000 N "
              "of belt and design load over 1.5 m and 1321 N of the tension 352.3 kN pressing "
              "round the curve, T S / R), above the CEMA C rating 4003 N: a heavier class")
    only = pd.DataFrame([{"run_id": "cv", "status": "warning", "message": convex}])
    assert [c.key for c, _, _ in cause_groups(only) if c.key == "idlers"] == ["idlers"]
    assert finding_clauses(convex, cause.words) == [convex]
