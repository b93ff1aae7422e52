"""``slack_at_m`` and ``slack_time_s`` are where and when the slack spans had gathered most
(``slack_max_m``), as docs/dynamics.md says, not where and when the belt first went slack, as
docs/results.md (generated from beltstudy.engine.results) said. A 1 km fabric belt (EP800/4,
3 then 8 deg, 300 t/h) stopped by a head brake first went slack at t = 94.66 s, 250 m from the
tail (t_min_dyn_kn 0.0 there and then, the time series' slack_m first above 0 at 94.70 s), while
the row said slack_at_m 460 m and slack_time_s 95.14 s, the moment its 1.27 m of slack peaked."""
from __future__ import annotations

import numpy as np
import pytest

from beltstudy.engine import results as R
from beltstudy.engine.conveyor import Scenario, parse_conveyor
from beltstudy.engine.run import run_one

FABRIC = {
    "name": "fabric-1km-brake",
    "speed_m_s": 3.15,
    "belt": {"type": "EP800/4", "width_m": 1.0, "top_cover_mm": 5, "bottom_cover_mm": 2,
             "compound": "standard"},
    "material": {"capacity_t_h": 300, "density_t_m3": 1.2},
    "profile": [{"length_m": 500, "lift_m": 26.2}, {"length_m": 500, "lift_m": 69.6}],
    "idlers": {"carry": {"spacing_m": 1.2, "roll_diameter_m": 0.127, "rolls": 3,
                         "trough_deg": 35, "cema_class": "C"},
               "return": {"spacing_m": 3.0, "roll_diameter_m": 0.127, "rolls": 1,
                          "cema_class": "C"}},
    "drives": [{"position": "head", "wrap_deg": 210, "friction": 0.35, "share": 1.0,
                "pulley_diameter_m": 0.8, "inertia_kg_m2": 60, "rated_power_kw": 250,
                "torque_limit": 1.5}],
    "takeup": {"type": "gravity", "position": "tail", "mass_kg": "auto", "travel_m": 6},
    "brakes": [{"position": "head", "force_kn": "auto", "delay_s": 0.5}],
    "holdback": True,
}


def test_slack_time_and_place_are_those_of_the_largest_slack_not_the_first():
    scn = Scenario(start={"time_s": 30}, run_s=5, stop={"mode": "brake"}, record_dt_s=0.02)
    res = run_one(parse_conveyor(FABRIC), scn, model="din")
    s, ts = res.summary, res.timeseries
    t, slack = ts["t_s"].to_numpy(), ts["slack_m"].to_numpy()
    assert s["slack_max_m"] > 0.5
    t_first, t_most = t[np.argmax(slack > 0.0)], t[np.argmax(slack)]
    assert t_most - t_first > 0.2  # the two moments differ by far more than a sample
    # the summary's time is the largest slack's, not the first
    assert s["slack_time_s"] == pytest.approx(t_most, abs=0.021)
    assert s["slack_time_s"] > t_first + 0.2
    assert slack.max() == pytest.approx(s["slack_max_m"], rel=0.02)
    # the belt first went slack where its tension first reached zero: another span, earlier
    assert s["t_min_dyn_kn"] == 0.0
    assert s["t_min_dyn_time_s"] == pytest.approx(t_first, abs=0.021)
    assert s["t_min_dyn_at_m"] != s["slack_at_m"]


def test_the_results_table_says_slack_time_and_place_are_the_largest_slack_s():
    for name in ("slack_at_m", "slack_time_s"):
        said = R.field(name).meaning
        assert "slack_max_m" in said
        assert "not where the belt first went slack" in said or \
            "not when the belt first went slack" in said
