"""An over-full cross-section in the design report: a verdict row judges ``fill_pct`` against
100 % (the design load's volume flow over what the belt's cross-section carries at design
speed, ISO 5048) and the runs past it are a failure group of their own, in their own words.

A study of a 0.65 m belt at 5 m/s with a capacity axis of 500 and 900 t/h warned "fill_pct
124 %" in two runs: the report had no fill row, listed those runs only under their pulley,
and showed the file's own 68.9 % in its conveyor section. The runs here carry the engine's
words and figures (:func:`solve_steady` on the tiny conveyor at three capacities)."""
from __future__ import annotations

import re
from functools import cache
from html import unescape

import pandas as pd
import pytest

from beltstudy.engine import parse_conveyor, solve_steady
from beltstudy.service import charts
from beltstudy.service.door.studyfile import resolve_study
from beltstudy.service.web.report import report_html
from beltstudy.service.web.verdicts import cause_groups, study_limits, verdict_rows

#: Design capacities [t/h] of the tiny conveyor (0.8 m belt at 2.5 m/s, 1 t/m3): within its
#: cross-section, and two beyond it.
CAPACITIES = (300.0, 900.0, 1100.0)


@pytest.fixture(autouse=True)
def _close_figures():
    yield
    charts._plt().close("all")


@cache
def _engine_run(web, capacity_t_h: float) -> tuple[str, float]:
    conv = web.tiny_conveyor("fill")
    conv["material"] = {**conv["material"], "capacity_t_h": capacity_t_h}
    r = solve_steady(parse_conveyor(conv))
    return r.message, r.summary["fill_pct"]


def _runs(web) -> pd.DataFrame:
    rows = []
    for k, cap in enumerate(CAPACITIES):
        message, fill = _engine_run(web, cap)
        rows.append({"run_id": f"c{k}", "friction_model": "din", "temperature_c": 20.0,
                     "material.capacity_t_h": cap, "status": "warning" if message else "ok",
                     "message": message, "fill_pct": fill, "power_kw": 10.0,
                     "t_max_kn": 20.0, "t_min_kn": 3.0})
    return pd.DataFrame(rows)


def test_the_fill_row_and_group_judge_the_cross_section(web):
    runs = _runs(web)
    assert runs["fill_pct"].iloc[0] < 100.0 < runs["fill_pct"].iloc[1]  # the premise
    assert all(re.search(r"(?:^|; )fill_pct \d+ %", m) for m in runs["message"].iloc[1:])
    rows = {r["column"]: r for r in verdict_rows(runs, study_limits(
        {"conveyor": web.tiny_conveyor("fill")}, 10.0, 0.75))}
    fill = rows["fill_pct"]
    assert fill["limit"] == pytest.approx(100.0)
    assert fill["past"] == 2 and fill["n"] == 3 and fill["row"]["run_id"] == "c2"
    groups = {cause.key: rows_ for cause, rows_, _ in cause_groups(runs)}
    assert sorted(groups["fill"]["run_id"]) == ["c1", "c2"]

    study = resolve_study(web.tiny_study(name="fill", conveyor=web.tiny_conveyor("fill")),
                          studies_dir=web.ROOT / "studies")
    doc = {"id": study.id, "name": study.name, "engine_version": study.engine_version,
           "finished_at": 0.0, "study": study.to_json()}
    html = report_html(doc, runs, {"state": "done", "done": 3, "total": 3})
    s1 = re.search(r'<section id="s1">(.*?)</section>', html, re.S).group(1)
    row = re.search(r"<tr><td>cross-section fill at design speed.*?</tr>", s1, re.S).group(0)
    assert "past the limit in 2 of 3 runs" in row
    s2 = unescape(re.search(r'<section id="s2">(.*?)</section>', html, re.S).group(1))
    assert "<li><b>2</b> of 3 runs over-filled its belt's cross-section" in s2
    group = re.search(r"<h3>Over-filled its belt's cross-section.*?</table>", s2, re.S).group(0)
    assert sorted(re.findall(r"<code class=id>(\w+)</code>", group)) == ["c1", "c2"]
    assert "a speed of at least" in group  # each run's own fix beside it


def test_sizes_a_grid_axis_gives_are_not_said_to_be_the_files(web):
    """A study whose grid sets ``takeup.mass_kg`` (the file: auto) said 'every size is given
    in the file', and its conveyor section 'mass auto': each run's mass came from the axis."""
    from beltstudy.service.web.report import _design_section

    conv = web.tiny_conveyor("given")
    conv["takeup"] = {"type": "gravity", "position": "tail", "mass_kg": "auto"}
    conv["drives"] = [{**d, "rated_power_kw": 50} for d in conv["drives"]]
    study = resolve_study(web.tiny_study(name="given", conveyor=conv,
                                         grid={"takeup.mass_kg": [4100, 3000]}),
                          studies_dir=web.ROOT / "studies")
    said = unescape(_design_section(study.to_json()))
    assert "set per run by the study's grid axes (takeup.mass_kg" in said, said
    plain = resolve_study(web.tiny_study(name="plain", conveyor={
        **conv, "takeup": {"type": "gravity", "position": "tail", "mass_kg": 4000}}),
        studies_dir=web.ROOT / "studies")
    assert "every size is given in the file." in _design_section(plain.to_json())
