"""A belt that rolls back after its stop until its holding brake holds it (no holdback):
a loaded 5 % incline coasting to rest, its head brake set once the belt has stopped
(``brakes[].hold``) after its delay and ramp. The belt's lift outpulls its resistances at
rest, so it runs back while the brake's force builds; the run said nothing (the run-back
check reads only the run's end, where the brake holds it). It is a note naming when, how
fast and how far, with the holdback that avoids it; with the holdback there is none."""
from __future__ import annotations

import re

import numpy as np
import pytest

from beltstudy.engine import load_conveyor
from beltstudy.engine.conveyor import Scenario
from beltstudy.engine.run import run_one
from tests.conftest import CONVEYORS


def _run(holdback: bool):
    conv = load_conveyor(CONVEYORS / "slope-5pct.yaml").model_copy(update={
        "holdback": holdback})
    conv = type(conv).model_validate({**conv.model_dump(), "brakes": [
        {"position": "head", "force_kn": 400, "delay_s": 0.5, "ramp_s": 1.0, "hold": True}]})
    scn = Scenario(elements=60, start={"time_s": 30}, run_s=10, stop={"mode": "coast"},
                   record_dt_s=0.05)
    return run_one(conv, scn, model="din")


def test_a_roll_back_until_the_brake_holds_is_noted_with_how_far():
    res = _run(holdback=False)
    msg = res.summary["message"]
    said = re.search(r"the belt rolled back after it stopped until its holding brake held it: "
                     r"its mean speed was below -([\d.]+) m/s from t = ([\d.]+) to ([\d.]+) s, "
                     r"at most ([\d.]+) m/s backwards \(t = [\d.]+ s\), about ([\d.e+-]+) m of "
                     r"belt and its load run back while the brake set \(delay_s 0\.5, ramp_s "
                     r"1\); a holdback on the head pulley \(holdback: true\)", msg)
    assert said, msg
    limit, t0, t1, v_back, dist = (float(g) for g in said.groups())
    assert limit == pytest.approx(0.01 * 4.5, rel=1e-3)  # 1 % of design speed
    # against the records: the fastest backward mean speed and the distance run back
    ts = res.timeseries
    after = ts["t_s"] > 2.0 + 30.0 + 10.0 + 1e-9  # after the stop command: rest, start, run
    v = ts.loc[after, "v_mean_m_s"].to_numpy()
    t = ts.loc[after, "t_s"].to_numpy()
    assert v_back == pytest.approx(-v.min(), rel=1e-2)
    neg = np.minimum(v, 0.0)
    assert dist == pytest.approx(-np.trapezoid(neg, t), rel=2e-2)
    assert 0.0 < t1 - t0 < 10.0 and v[-1] > -limit  # at rest again: held, not running away
    assert "runs back after the stop" not in msg  # not the warning of a belt still going


def test_no_roll_back_note_with_a_holdback():
    res = _run(holdback=True)
    assert "rolled back" not in res.summary["message"]
