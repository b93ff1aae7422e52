"""The envelope is cut at the start and stop commands on any step (SPEC 6.4's phases).

The kernel cut the envelope at the first step past a command when the step before it, ``t -
dt``, was not past it; ``t - dt`` rounds differently from that step's own time ``(k - 1) dt``:
with the stop command at 62 s on a 1 ms step, t = 62001 x 0.001 = 62.001000000000005 and t - dt
= 62.00000000000001 > 62, the cut was never made, the start phase had no figures and the stop's took the start's peak (a 1 km
fabric belt: ``t_max_stop_kn`` 86.02 kN "at 15.4 s", 47 s before its stop command)."""

from __future__ import annotations

import pytest

from beltstudy.engine.conveyor import Scenario, parse_conveyor
from beltstudy.engine.run import run_one
from tests.conftest import hand_conveyor_dict

T_PRE_S = 2.0  # the rest before the start command (docs/dynamics.md)


@pytest.mark.parametrize("dt_s", [0.001, None])
def test_each_phase_has_its_own_figures_on_a_step_whose_rounding_misses_the_command(dt_s):
    start_s, run_s = 30.0, 30.0
    t_stop_cmd = T_PRE_S + start_s + run_s
    k = int(t_stop_cmd / 0.001) + 1  # the first 1 ms step past the stop command
    assert k * 0.001 > t_stop_cmd and (k - 1) * 0.001 <= t_stop_cmd
    assert k * 0.001 - 0.001 > t_stop_cmd  # the rounding the kernel's cut missed
    scn = Scenario(start={"control": "s-curve", "time_s": start_s}, run_s=run_s,
                   stop={"mode": "coast"}, elements=12,
                   **({"dt_s": dt_s} if dt_s is not None else {}))
    s = run_one(parse_conveyor(hand_conveyor_dict()), scn, model="din").summary
    if dt_s is not None:
        assert s["dt_used_s"] == dt_s
    assert s["t_max_start_kn"] is not None and s["t_min_start_kn"] is not None
    assert T_PRE_S <= s["t_max_start_time_s"] <= t_stop_cmd
    assert s["t_max_stop_time_s"] >= t_stop_cmd and s["t_min_stop_time_s"] >= t_stop_cmd
    # the cycle's extremes are a phase's (or the rest's before the start, at the steady
    # tensions: never above the start's peak)
    assert s["t_max_dyn_kn"] == max(s["t_max_start_kn"], s["t_max_stop_kn"])
    # the start's peak (the s-curve's acceleration, about 1.2 x steady) is the cycle's on
    # this incline, and the coast stop's, falling from the running tensions, is below it
    assert s["t_max_stop_kn"] < s["t_max_start_kn"]
