"""A loaded incline that can run back when stopped, with nothing to hold it, gets a note.

The engine computed the holdback torque such a belt needs (CEMA's backstop rule, pull less half
the running resistance) but said nothing when the file had no holdback: the 31 m published
revert conveyor (benchmarks/conveyors/helix-revert-31m.yaml: lift pull 2.14 kN, resistances at
rest 2.13 kN) crept back after a coast stop, still running back at 0.04 m/s five seconds later,
with status ok and not a word. A note, not a warning: the steady run is not where the belt runs
back, and the status of the steady figures stays theirs.
"""

from __future__ import annotations

import re
from types import SimpleNamespace

import numpy as np
import pytest

from beltstudy.engine.conveyor import parse_conveyor
from beltstudy.engine.loop import G
from beltstudy.engine.statics import solve_steady
from tests.conftest import hand_conveyor_dict


def _solve(**over):
    d = hand_conveyor_dict()
    d.update(over)
    return solve_steady(parse_conveyor(d), model="din")


def test_an_incline_without_holdback_notes_the_pull_and_the_holdback_it_needs():
    """The hand conveyor lifts 50 kg/m by 50 m: a pull of 50 x 9.81 x 50 = 24.5 kN back,
    against half its running resistance; the warning names both and the holdback torque."""
    res = _solve()
    s = res.summary
    assert 50 * G * 50 == pytest.approx(24525, rel=1e-4)
    assert s["holdback_torque_knm"] > 0
    assert "note: the loaded belt can run back when it stops" in s["message"]
    assert "its lift pulls 24.5 kN back" in s["message"]
    assert f"at least {s['holdback_torque_knm']:.3g} kNm (holdback: true)" in s["message"]
    assert not any("run back" in w for w in res.warnings)  # a note


@pytest.mark.parametrize("over", [
    {"holdback": True},
    {"brakes": [{"position": "head", "force_kn": 40.0, "delay_s": 0.5}]},  # hold: true default
    {"profile": [{"length_m": 1000, "lift_m": 0}]},
    {"profile": [{"length_m": 1000, "lift_m": -20}]},
])
def test_no_run_back_note_where_something_holds_or_nothing_pulls(over):
    assert "run back" not in _solve(**over).summary["message"]


def test_a_brake_that_does_not_hold_at_rest_does_not_hold_the_belt():
    res = _solve(brakes=[{"position": "head", "force_kn": 40.0, "delay_s": 0.5,
                          "hold": False}])
    assert "can run back when it stops" in res.summary["message"]


# ------------------------------------------------------------------ the transient's warning
def _records(t, v):
    rec = np.zeros(len(t), dtype=[("t", float), ("v_mean", float)])
    rec["t"], rec["v_mean"] = t, v
    return SimpleNamespace(rec=rec), {"nrec": len(t)}


def test_a_sustained_run_back_is_warned_a_passing_dip_is_not():
    """Design speed 2 m/s, stop command at 10 s, records every 0.5 s. The criterion is the
    stop's rest criterion mirrored: the mean speed below -1 % of design (-0.02 m/s), still at
    the run's end. A belt relaxing onto its holdback dips to -0.1 m/s (5 %) and rests: no
    warning. A belt creeping back: -0.02 from 12 s, -0.05 from 12.5 s to the end at 15 s;
    by hand the distance is the trapezoid of the negative speeds: 0.5 x (0 + 0.02) / 2 +
    0.5 x (0.02 + 0.05) / 2 + 2.5 x 0.05 = 0.005 + 0.0175 + 0.125 = 0.1475 m."""
    from beltstudy.engine.dynamics.simulate import runback_words

    sysm = SimpleNamespace(stop_command_s=10.0, v_design=2.0, hold_force_n=24_530.0)
    t = np.arange(0.0, 15.01, 0.5)
    dip = np.where(t < 11.0, 2.0 - 0.2 * t, 0.0)
    dip[(t > 11.9) & (t < 13.1)] = -0.1
    assert runback_words(sysm, *_records(t, dip)) == []
    creep = np.where(t <= 10.0, 2.0, 0.0)
    creep[t >= 11.5] = 0.0
    creep[t >= 12.0] = -0.02
    creep[t >= 12.5] = -0.05
    (w,) = runback_words(sysm, *_records(t, creep), {"holdback_torque_knm": 1.234})
    assert "since t = 12.5 s, 2.5 s after the stop command" in w, w  # -0.02 is not below
    assert "reached 0.05 m/s backwards" in w and "still 0.05 m/s backwards" in w
    dist = float(re.search(r"about ([\d.]+) m of belt run back", w).group(1))
    assert dist == pytest.approx(0.1475, abs=0.0006)
    assert "holdback: true) of at least 1.23 kNm" in w and "brakes[].hold: true" in w
    assert "(the lift's pull at rest, 24.53 kN at the belt line, outpulls" in w


def test_the_revert_conveyor_runs_back_after_a_coast_stop_unless_held():
    """The published 31 m revert conveyor (lift pull 2.14 kN against 2.13 kN of resistance
    at rest, holdback: false) creeps back after a coast stop: warned, with the holdback torque
    statics computes; with its holdback the belt rests and nothing is said."""
    from beltstudy.engine.conveyor import Scenario, load_conveyor
    from beltstudy.engine.run import run_one
    from tests.conftest import ROOT

    conv = load_conveyor(ROOT / "benchmarks" / "conveyors" / "helix-revert-31m.yaml")
    scn = Scenario.model_validate({"start": {"time_s": 5.0}, "run_s": 5.0,
                                   "stop": {"mode": "coast"}, "elements": 60})
    s = run_one(conv, scn, model="din").summary
    assert "the belt runs back after the stop" in s["message"], s["message"]
    assert f"of at least {s['holdback_torque_knm']:.3g} kNm" in s["message"]
    pull = float(re.search(r"the lift's pull at rest, ([\d.]+) kN", s["message"]).group(1))
    assert pull == pytest.approx(2.14, abs=0.01)  # the lift pull above
    assert s["status"] == "warning"
    held = run_one(conv.model_copy(update={"holdback": True}), scn, model="din").summary
    assert "runs back" not in held["message"], held["message"]


def test_a_belt_relaxing_onto_its_holdback_is_not_said_to_run_back():
    """A holdback holds the head pulley: a backward mean speed after the stop is the belt's
    stretch relaxing onto it, not a run-back. studies/conveyors/fabric-1km.yaml (holdback:
    true, 3 and 8 deg rises) coasting to rest on 40 elements: its drive pulley is held at
    0 m/s from about 97.6 s while the mean speed falls to about -0.26 m/s, relaxing (the run
    then goes on until it is back within 1 % of design speed, -0.0315 m/s: a belt moving is
    not at rest); it was warned 'nothing holds it' and offered 'a holdback (holdback: true)',
    the one it has. The same records on a conveyor without a holdback are still warned."""
    from beltstudy.engine.conveyor import Scenario, load_conveyor
    from beltstudy.engine.dynamics.simulate import runback_words
    from beltstudy.engine.run import run_one
    from tests.conftest import ROOT

    sysm = SimpleNamespace(stop_command_s=10.0, v_design=2.0, hold_force_n=24_530.0)
    t = np.arange(0.0, 15.01, 0.5)
    creep = np.where(t <= 10.0, 2.0, -0.05)
    assert runback_words(sysm, *_records(t, creep), None, SimpleNamespace(holdback=True)) == []
    assert len(runback_words(sysm, *_records(t, creep), None,
                             SimpleNamespace(holdback=False))) == 1

    conv = load_conveyor(ROOT / "studies" / "conveyors" / "fabric-1km.yaml")
    assert conv.holdback
    scn = Scenario.model_validate({"stop": {"mode": "coast"}, "elements": 40})
    res = run_one(conv, scn, model="din")
    ts = res.transient.timeseries
    after = ts[ts.t_s > res.transient.system.stop_command_s]
    assert after.v_mean_m_s.min() < -0.05 * conv.speed_m_s  # relaxing onto the holdback
    assert after.v_mean_m_s.iloc[-1] >= -0.01 * conv.speed_m_s  # and at rest at the end
    assert (after.v_drive_m_s.iloc[-20:] >= 0.0).all()  # the held pulley does not turn back
    assert "runs back" not in res.summary["message"], res.summary["message"]


def test_a_belt_relaxing_onto_a_holding_brake_is_not_told_to_set_hold():
    """A brake with hold: true holds its pulley once the belt has stopped, as a holdback does.
    A 10 km overland (+60 m) with 120 and 60 kN holding brakes at head and tail, coasting: its
    drive pulleys rested at 0 m/s from about 115 s while the mean speed relaxed to -0.087 m/s
    (below -1 % of 5 m/s) at the run's end; it was told 'nothing holds it' and offered
    'brakes[].hold: true', which it had. The same records with the drive pulley turning back
    (a brake too weak to hold) or with hold: false are still warned. Design speed 2 m/s,
    stop command at 10 s: the criterion is -0.02 m/s."""
    from beltstudy.engine.dynamics.simulate import runback_words

    sysm = SimpleNamespace(stop_command_s=10.0, v_design=2.0, hold_force_n=24_530.0)
    t = np.arange(0.0, 15.01, 0.5)
    rec = np.zeros(len(t), dtype=[("t", float), ("v_mean", float), ("v_drive", float)])
    rec["t"] = t
    rec["v_mean"] = np.where(t <= 10.0, 2.0, -0.05)
    rec["v_drive"] = np.where(t <= 10.0, 2.0, 0.0)  # the held pulley rests
    out, r = SimpleNamespace(rec=rec), {"nrec": len(t)}
    held = SimpleNamespace(holdback=False, brakes=[SimpleNamespace(hold=True)])
    assert runback_words(sysm, out, r, None, held) == []
    released = SimpleNamespace(holdback=False, brakes=[SimpleNamespace(hold=False)])
    assert len(runback_words(sysm, out, r, None, released)) == 1
    back = rec.copy()
    back["v_drive"] = np.where(t <= 10.0, 2.0, -0.05)  # the braked pulley turns back
    (w,) = runback_words(sysm, SimpleNamespace(rec=back), r, None, held)
    assert "the belt runs back after the stop" in w
