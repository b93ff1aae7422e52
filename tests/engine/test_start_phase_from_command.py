"""The start phase runs from the start command to the stop command (SPEC 6.4).

A loaded decline held at rest by its holding brake carries its highest tension at rest: the
brake holds the whole downhill pull of the load at one pulley, where running shares it with
the resistances. The start phase's figures included the rest before the start command, so
``t_max_start_time_s`` was 0.0, before the start command at 2 s, and a start's lowest
tension could be the settling of the initial state in the rest's first steps
(downhill-regen's ``t_min_start_time_s`` 0.006 s).
"""

from __future__ import annotations

import pytest

from beltstudy.engine import parse_conveyor
from beltstudy.engine.conveyor import Scenario
from beltstudy.engine.dynamics.model import DynamicsOptions
from beltstudy.engine.run import run_one

PRE_REST_S = DynamicsOptions().pre_rest_s


def _decline() -> dict:
    drive = dict(wrap_deg=200, friction=0.35, share=0.5, pulley_diameter_m=0.8)
    return dict(
        name="steep-decline", speed_m_s=3.5, belt={"type": "ST1600", "width_m": 1.05},
        material={"capacity_t_h": 1200, "density_t_m3": 1.6, "surcharge_deg": 20},
        profile=[{"length_m": 300, "lift_m": 0}, {"length_m": 900, "lift_m": -150}],
        idlers={"carry": {"spacing_m": 1.2, "roll_diameter_m": 0.127, "rolls": 3,
                          "trough_deg": 35},
                "return": {"spacing_m": 3.0, "roll_diameter_m": 0.127, "rolls": 1}},
        drives=[dict(drive, position="tail"), dict(drive, position="head")],
        takeup={"type": "fixed", "position": "head", "pretension_kn": "auto"},
        brakes=[{"position": "tail", "force_kn": "auto", "delay_s": 0.5}])


@pytest.mark.parametrize("options", [{}, {"elements": 400}], ids=["defaults", "finer-mesh"])
def test_the_start_phase_begins_at_the_start_command(options):
    scn = Scenario(start={"control": "s-curve", "time_s": 20}, run_s=10,
                   stop={"mode": "coast"}, **options)
    s = run_one(parse_conveyor(_decline()), scn, model="din").summary
    # the held decline's highest tension is at rest, before the start command
    assert s["t_max_dyn_time_s"] < PRE_REST_S
    # the start's own extremes are from the start command on (the belt is still held at its
    # rest tensions then, so the start's highest tension may equal the rest's, stamped at the
    # start command, not before it)
    for key in ("t_max_start_time_s", "t_min_start_time_s"):
        assert s[key] >= PRE_REST_S, (key, s[key])
    assert s["t_max_start_kn"] <= s["t_max_dyn_kn"]
    assert s["t_min_start_kn"] >= s["t_min_dyn_kn"]
    # the stop phase: after the stop command
    t_stop_cmd = PRE_REST_S + 20.0 + 10.0
    assert s["t_max_stop_time_s"] >= t_stop_cmd
