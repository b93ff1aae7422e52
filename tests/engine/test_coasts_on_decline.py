"""A belt that did not stop within the stop window was told a rigid-body coast to rest 'takes
about 22.2 s (M v / Te), beyond the window' of 300 s (engine/dynamics/simulate.py,
``not_stopped_words``): slope-5pct's conveyor on a 20 m section falling 5 m, whose resistance
is above the decline's pull at design speed (Te +1.82 kN) but falls with the speed (the feed
accelerating the material, Q v), coasts on at the speed where the two match. The words now
say that speed, and the rigid-body time is offered as the reason only where it is beyond the
window."""
from __future__ import annotations

import re

import numpy as np
import pytest

from beltstudy.engine.conveyor import Scenario, load_mapping, parse_conveyor
from beltstudy.engine.run import run_one
from tests.conftest import CONVEYORS


def _short_decline() -> dict:
    d = load_mapping(CONVEYORS / "slope-5pct.yaml")
    d["profile"] = [{"length_m": 20, "lift_m": -5}]
    return d


def test_a_decline_whose_resistance_falls_with_speed_coasts_on_where_they_match():
    res = run_one(parse_conveyor(_short_decline()), Scenario(elements=20, record_dt_s=0.5),
                  model="din")
    s, ts = res.summary, res.timeseries
    msg = s["message"]
    assert "did not stop within the stop window of 300 s" in msg, msg
    # by hand (DIN, the loop's resistances at design speed, te_components_kn): all but the
    # feed's keep their size as the belt slows, the feed's, Q v, falls in proportion to the
    # speed; they match the decline's pull (the lift's, negative) at
    # v = v_d (|lift| - (Te - feed - lift)) / feed
    c, v_d = s["te_components_kn"], 4.5
    rest = s["te_kn"] - c["feed"] - c["lift"]
    v_hand = v_d * (-c["lift"] - rest) / c["feed"]
    assert 0.0 < v_hand < v_d
    said = re.search(r"it coasts on at about ([\d.]+) m/s, where they match its pull down the "
                     r"decline, ([\d.]+) kN \(its mean speed changed ([-+\d.e]+) m/s over the "
                     r"window's last 30 s\), so gravity keeps it moving", msg)
    assert said, msg
    assert float(said.group(1)) == pytest.approx(v_hand, rel=0.01)
    # the time series: the mean speed 30 s before the run's end, against its end
    t, v = ts["t_s"].to_numpy(), ts["v_mean_m_s"].to_numpy()
    dv = v[-1] - float(np.interp(t[-1] - 30.0, t, v))
    assert abs(float(said.group(3)) - dv) <= 0.01 * v[-1]
    assert float(said.group(2)) == pytest.approx(-c["lift"], rel=1e-3)  # the lift's pull
    # the rigid-body coast, M v / Te, is within the window: not called beyond it
    coast = re.search(r"would coast to rest in about ([\d.]+) s \(M v / Te\), within the window",
                      msg)
    assert coast and float(coast.group(1)) < 300.0, msg
    assert "beyond the window" not in msg
    assert "a brake would stop it (brakes with force_kn: auto" in msg
    # followed: an auto head brake and a brake stop bring it to rest
    d = _short_decline()
    d["brakes"] = [{"position": "head", "force_kn": "auto"}]
    braked = run_one(parse_conveyor(d), Scenario(elements=20, stop={"mode": "brake"}),
                     model="din").summary
    assert braked["stop_time_s"] is not None, braked["message"]
    assert "did not stop" not in braked["message"]
