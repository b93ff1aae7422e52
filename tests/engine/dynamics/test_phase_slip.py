"""Each phase's smallest slip margin (``slip_margin_min_start_dyn``, ``..._stop_dyn``): the
run pauses at the stop command, keeps the start's smallest margin and starts the stop's; the
records are those of one uninterrupted run, bit for bit."""

from __future__ import annotations

import numpy as np

from beltstudy.engine.conveyor import Scenario, load_conveyor
from beltstudy.engine.dynamics import build_system, simulate
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
