"""The inertia a high-stress coast is told starts from the running phase's low, not from the
crest of a swing the run itself reports. A 3.5 km overland swinging by 0.231 m/s was sized
from 4.107 m/s at the stop command; given, the flywheels met the stop at 3.954 m/s and the
coast fell short of 5 wave loop times (27.41 against 27.6 s)."""
from __future__ import annotations

from types import SimpleNamespace

import numpy as np

from beltstudy.engine.dynamics.simulate import SETTLE_LOOPS, _running_low


def _run(v_of_t, t_end=100.0, dt=0.1):
    t = np.arange(0.0, t_end + dt / 2, dt)
    rec = np.zeros(len(t), dtype=[("t", float), ("v_mean", float)])
    rec["t"], rec["v_mean"] = t, v_of_t(t)
    sys = SimpleNamespace(stop_command_s=t_end, wave_loop_time_s=5.0,
                          model=SimpleNamespace(cycle=SimpleNamespace(t_run=30.0, t_pre=2.0,
                                                                      t_start=60.0)))
    return sys, SimpleNamespace(rec=rec), {"nrec": len(t)}


def test_the_low_of_a_swing_before_the_command_is_taken():
    # 4 m/s with a 0.115 m/s swing of 12 s period; the command at a crest
    def swing(t):
        return 4.0 + 0.115 * np.cos(2 * np.pi * (t - 100.0) / 12.0)

    sys, out, r = _run(swing)
    v_cmd = float(swing(np.array([100.0]))[0])
    low = _running_low(sys, out, r, v_cmd)
    # the window: max(3 loop times, half the run) = 15 s back, past the ramp and a loop
    assert max(SETTLE_LOOPS * 5.0, 15.0) == 15.0
    assert low < v_cmd and abs(low - (4.0 - 0.115)) < 1e-3


def test_a_settled_belt_keeps_its_speed_at_the_command():
    sys, out, r = _run(lambda t: np.full_like(t, 4.0))
    assert _running_low(sys, out, r, 4.0) == 4.0
    assert _running_low(sys, out, r, None) is None


def test_a_belt_still_climbing_is_read_from_the_time_it_reached_speed():
    # climbing from 3.6 to 4.0 m/s until t = 95 s, then at 4.0: the climb is not running
    sys, out, r = _run(lambda t: np.minimum(3.6 + 0.4 * (t - 85.0) / 10.0, 4.0))
    assert _running_low(sys, out, r, 4.0) < 3.9  # without the reach time, the climb counts
    r["start_ach"] = 95.0 - 2.0  # reached 99 % at 95 s (start_ach counts from the rest's end)
    assert _running_low(sys, out, r, 4.0) > 0.99 * 4.0
