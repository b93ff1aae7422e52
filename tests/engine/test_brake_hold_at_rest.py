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


def test_a_brake_a_coast_stop_never_applies_is_not_in_the_run_s_brake_force():
    """A brake without ``hold`` is never applied in a coast stop, and its law is not read:
    runs that differ only in it are one run (engine/reads.py, ``conveyor_as_read``). Its
    force in the row was the first merged grid point's (one run of two studies read 150 kN
    in one and 80 kN in the other). The row now gives the brakes applied: none, so null; in
    a brake stop the same brake's force."""
    d = load_mapping(CONVEYORS / "slope-5pct.yaml")
    d["profile"] = [{"length_m": 300, "lift_m": 15}]
    rows = {}
    for kn in (150.0, 80.0):
        d["brakes"] = [{"position": "head", "force_kn": kn, "hold": False}]
        for mode in ("coast", "brake"):
            scn = Scenario(elements=30, run_s=5, stop={"mode": mode})
            rows[kn, mode] = run_one(parse_conveyor(d), scn, model="din").summary
    assert rows[150.0, "coast"]["brake_force_kn"] is None
    assert rows[80.0, "coast"]["brake_force_kn"] is None
    assert rows[150.0, "coast"]["brake_governed_by"] is None
    assert rows[150.0, "brake"]["brake_force_kn"] == 150.0
    assert rows[80.0, "brake"]["brake_force_kn"] == 80.0


def test_a_decline_s_rebound_after_its_stop_is_not_offered_a_holdback():
    """downhill-regen (a loaded decline: at rest the belt pulls forwards) with a 225 t take-up,
    brake stop: after the stop its mean speed dips backwards (about 0.06 m/s) until the
    holding brake holds, the stretch relaxing. It was told "a holdback on the head pulley ...
    which takes the pull as the belt stops, would avoid it": on a decline there is no backward
    pull for a holdback to take. It is said as the stop's swing back, without the holdback."""
    d = load_mapping(CONVEYORS / "downhill-regen.yaml")
    d["takeup"] = {**d["takeup"], "mass_kg": 225348}
    scn = Scenario(elements=200, start={"control": "s-curve", "time_s": 60}, run_s=30,
                   stop={"mode": "brake", "time_s": 20})
    res = run_one(parse_conveyor(d), scn, model="nonlin")
    s, ts = res.summary, res.timeseries
    t, v = ts["t_s"].to_numpy(), ts["v_mean_m_s"].to_numpy()
    after = t > 2.0 + 60.0 + 30.0
    assert v[after].min() < -0.01 * 4.0 < v[-1] + 0.01 * 4.0, (v[after].min(), v[-1])
    msg = s["message"]
    # its brake was at full force before the belt stopped: the swing back is the stretch
    # relaxing about the held pulley, which no brake timing changes either
    assert "the belt swung back after it stopped" in msg, msg
    assert "neither a holdback nor a brake that sets sooner would avoid it" in msg
    assert "rolled back after it stopped" not in msg
    assert "holdback: true" not in msg and "takes the pull as the belt stops" not in msg
