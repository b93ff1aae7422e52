"""The brakes' force while they hold the belt at rest before the start (engine/dynamics/
simulate.py, ``brake_hold_kn``): the kernel holds the first brake's pulley by the rest's
constraint, and ``f_brake_kn`` read 0 there, in the series and in the summary (a 1.8 km
decline's brake held 204.4 kN for the 2 s before the start)."""
from __future__ import annotations

import numpy as np
import pytest

from beltstudy.engine.conveyor import Scenario, load_mapping, parse_conveyor
from beltstudy.engine.run import run_one
from tests.conftest import CONVEYORS


def test_a_decline_s_brake_gives_the_net_gravity_pull_at_rest_before_the_start():
    """slope-5pct's belt on a 300 m section falling 30 m with an auto head brake, coasting to
    rest: before the start command (t < 2 s) the brake holds the loaded belt's pull down the
    decline. At rest there is no resistance and the belt's own weight is the same on both
    strands, so the pull is the load's, m'_L g |H|, the steady solution's lift term (-lift).
    The coast stop does not set the brake, so the run's largest brake force is that hold."""
    d = load_mapping(CONVEYORS / "slope-5pct.yaml")
    d["profile"] = [{"length_m": 300, "lift_m": -30}]
    d["brakes"] = [{"position": "head", "force_kn": "auto"}]
    res = run_one(parse_conveyor(d), Scenario(elements=30, record_dt_s=0.1, run_s=5,
                                              stop={"mode": "coast"}), model="din")
    s, ts = res.summary, res.timeseries
    pull_kn = -s["te_components_kn"]["lift"]
    assert pull_kn > 0.0
    t, fb = ts["t_s"].to_numpy(), ts["f_brake_kn"].to_numpy()
    before = t < 2.0 - 1e-9
    assert before.sum() >= 5
    assert np.allclose(fb[before], pull_kn, rtol=0.01), (fb[before], pull_kn)
    assert s["f_brake_kn"] == pytest.approx(pull_kn, rel=0.01)
