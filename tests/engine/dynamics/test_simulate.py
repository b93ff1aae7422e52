"""What a run says (engine/dynamics/simulate.py): the slip message's phases and fixes, the
slipping drive named, a slack stop reported, and the results per phase."""

from __future__ import annotations

import re

import pytest

from beltstudy.engine.conveyor import Scenario, load_conveyor
from beltstudy.engine.dynamics.simulate import slip_words
from beltstudy.engine.run import run_one
from tests.conftest import CONVEYORS


def test_overland_60s_start_names_the_slipping_drive():
    conv = load_conveyor(CONVEYORS / "overland-16km.yaml")
    r = run_one(conv, Scenario(start={"time_s": 60}, run_s=30,
                               stop={"mode": "controlled", "time_s": 40}), model="din")
    s = r.summary
    assert s["status"] == "warning"
    slipped = [i for i in (1, 2) if s[f"drive{i}_slip_s"] > 0.0]
    assert slipped
    for i in slipped:
        assert s[f"drive{i}_slip_m"] > 0.0
        pos = conv.drives[i - 1].position
        assert f"drive {i} ({pos}) slipped on its pulley" in s["message"]
    assert "m of belt slipped" in s["message"] and "s in all" in s["message"]
    # the phases named are those of the slip's first and last time (2 s at rest, a 60 s
    # start, 30 s running, then the stop)
    def phase(t):
        return "start" if t <= 62.0 else ("running" if t <= 92.0 else "stop")

    words = {"start": "the start", "running": "steady running", "stop": "the stop"}
    alone = {"start": "during the start", "running": "while running", "stop": "during the stop"}
    found = list(re.finditer(r"slipped on its pulley (.*?): from t = ([\d.]+) to ([\d.]+) s",
                             s["message"]))
    assert len(found) == len(slipped)
    for m in found:
        p0, p1 = phase(float(m.group(2))), phase(float(m.group(3)))
        want = alone[p0] if p0 == p1 else f"from {words[p0]} into {words[p1]}"
        assert m.group(1) == want, m.group(0)
    assert "a longer start (start.time_s)" in s["message"]  # the slips began in the start


def test_a_slip_message_names_its_phases_and_the_fixes_that_apply():
    """Every pair of first and last phase: the words, and the fixes that apply to it."""
    take_up = "a heavier take-up (more slack-side tension)"
    start = "a longer start (start.time_s)"
    stop = "a softer stop (stop time, brake force)"
    assert slip_words("start", "start") == ("during the start", f"{take_up} or {start}")
    assert slip_words("running", "running") == ("while running", take_up)
    assert slip_words("stop", "stop") == ("during the stop", f"{take_up} or {stop}")
    assert slip_words("start", "running") == ("from the start into steady running",
                                              f"{take_up} or {start}")
    assert slip_words("start", "stop") == ("from the start into the stop",
                                           f"{take_up}, {start} or {stop}")
    assert slip_words("running", "stop") == ("from steady running into the stop",
                                             f"{take_up} or {stop}")


def test_a_slack_stop_reports_where_when_and_how_much():
    """A 3 s controlled stop of the fabric belt slackens the carry: the run ends with a
    warning naming the slack (belt length, where, when, for how long) and what avoids it,
    the peak after slack apart from the one before, and all its results."""
    conv = load_conveyor(CONVEYORS / "fabric-1km.yaml")
    r = run_one(conv, Scenario(elements=400, stop={"mode": "controlled", "time_s": 3}),
                model="din")
    s = r.summary
    assert s["status"] == "warning"
    assert s["slack_max_m"] > 0.05
    assert 0.0 <= s["slack_at_m"] <= 1000.0  # on the carry
    assert s["slack_time_s"] > 2.0 + 60.0 + 30.0  # during the stop
    assert s["slack_duration_s"] > 0.0
    assert s["t_min_stop_kn"] == 0.0
    assert s["t_max_post_slack_kn"] is not None and s["t_max_pre_slack_kn"] is not None
    msg = s["message"]
    assert "slack spans gather up to" in msg and "m of belt near" in msg and "from the tail on the carry" in msg
    assert "heavier take-up" in msg
    assert r.timeseries["slack_m"].max() > 0.0


def test_results_per_phase():
    """Start and stop extremes with where and when; the whole-cycle extremes are theirs."""
    conv = load_conveyor(CONVEYORS / "slope-5pct.yaml")
    r = run_one(conv, Scenario(elements=80, stop={"mode": "controlled", "time_s": 30}),
                model="din")
    s = r.summary
    t_stop = 2.0 + 60.0 + 30.0
    assert s["t_max_dyn_kn"] == pytest.approx(max(s["t_max_start_kn"], s["t_max_stop_kn"]),
                                              rel=1e-9)
    assert s["t_min_dyn_kn"] == pytest.approx(min(s["t_min_start_kn"], s["t_min_stop_kn"]),
                                              rel=1e-9)
    assert s["t_max_start_time_s"] <= t_stop + 0.2 < s["t_max_stop_time_s"] + 0.2
    assert s["t_min_stop_time_s"] >= t_stop - 0.2
    ts = r.timeseries
    start = ts[ts["t_s"] <= t_stop]
    assert s["t_max_start_kn"] >= start["t_max_kn"].max() * 0.999
