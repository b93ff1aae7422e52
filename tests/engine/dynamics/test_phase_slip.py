"""Each phase's smallest slip margin (``slip_margin_min_start_dyn``, ``..._stop_dyn``): the
run pauses at the stop command, keeps the start's smallest margin and starts the stop's; the
records are those of one uninterrupted run, bit for bit."""

from __future__ import annotations

import math

import numpy as np

from beltstudy.engine.conveyor import Scenario, load_conveyor
from beltstudy.engine.dynamics import build_system, simulate
from beltstudy.engine.dynamics.model import with_step
from beltstudy.engine.dynamics.simulate import fresh_run
from beltstudy.engine.run import run_one
from beltstudy.engine.statics import solve_steady
from tests.conftest import CONVEYORS


def test_the_phases_slip_margins_leave_the_run_as_one_call_gives_it():
    """fabric-1km with a 4 s start and a 3 s controlled stop slips from the start into the
    stop. Run in one call and run paused at the stop command, the run's scalars, the drive
    records and the state are identical; the phases' margins are the smallest before and
    after the stop command, and the cycle's is the smaller of the two."""
    conv = load_conveyor(CONVEYORS / "fabric-1km.yaml")
    scn = Scenario(elements=40, start={"time_s": 4}, stop={"mode": "controlled", "time_s": 3})
    sys = build_system(conv, scn, solve_steady(conv, model="din", n_elements=40))
    one = fresh_run(sys)
    one.call()
    two = fresh_run(sys)
    two.cycle(sys.stop_command_s)
    assert one.out.run.tobytes() == two.out.run.tobytes()
    assert one.out.drv.tobytes() == two.out.drv.tobytes()
    assert np.array_equal(one.state.tt, two.state.tt) and np.array_equal(one.state.v, two.state.v)
    cyc = float(one.out.run["slip_min"][0])
    assert min(two.slip_min_start, two.slip_min_stop) == cyc
    assert two.slip_min_start >= cyc and two.slip_min_stop >= cyc
    # the summary's, from run_one (the same path)
    s = run_one(conv, scn, model="din").summary
    assert s["slip_margin_min_dyn"] == cyc
    assert s["slip_margin_min_start_dyn"] == two.slip_min_start
    assert s["slip_margin_min_stop_dyn"] == two.slip_min_stop
    # a run ended before the stop command (a verification run's end) has no stop's margin
    early = simulate(sys, t_end_s=10.0).summary
    assert early["slip_margin_min_stop_dyn"] is None
    assert early["slip_margin_min_start_dyn"] == early["slip_margin_min_dyn"] is not None


def test_a_coast_stops_slip_margin_begins_at_the_tensions_of_the_power_failure():
    """slope-5pct (one head drive, mu 0.35 on 210 deg: e^(mu theta) = 3.607) coasting on 40
    elements. At the power failure the belt still carries its running tensions, about 357 kN
    tight and 142 kN slack at the head pulley: a margin of 3.607 x 142 / 357 = 1.435, and the
    ratio falls from there once the drive force is cut. The stop's smallest margin was read
    from the steps after the command alone, one step into the fall: 1.97, 1.76 and 1.55 at
    the automatic step, half and a quarter of it. It is now at most the command's, whatever
    the step."""
    conv = load_conveyor(CONVEYORS / "slope-5pct.yaml")
    scn = Scenario(elements=40, stop={"mode": "coast"})
    sys0 = build_system(conv, scn, solve_steady(conv, model="din", n_elements=40))
    e_mu_theta = math.exp(0.35 * math.radians(210.0))
    stops = []
    for k in (1, 2):
        sys = with_step(sys0, sys0.model.cycle.dt / k)
        paused = fresh_run(sys)
        paused.call(sys.stop_command_s)
        j = int(sys.model.shafts.node[sys.model.drives.shaft[0]])
        tight, slack = sorted((paused.state.tt[j - 1], paused.state.tt[j]), reverse=True)
        assert 350e3 < tight < 365e3 and 135e3 < slack < 150e3  # running, as above
        hand = e_mu_theta * slack / tight
        kr = fresh_run(sys)
        kr.cycle(sys.stop_command_s)
        assert kr.slip_min_stop <= hand * (1.0 + 1e-12)
        assert kr.slip_min_stop >= kr.slip_min_start  # the start's 1.107 stays the cycle's
        stops.append(kr.slip_min_stop)
    np.testing.assert_allclose(stops, 1.435, rtol=2e-3)
    np.testing.assert_allclose(stops[1], stops[0], rtol=1e-3)
