"""The speed loop's lever names the one field that sets it, the master drive's, and the
bandwidth the run used: a follower's ``speed_loop_rad_s`` is refused at the door, so the
words ``drives[i].speed_loop_rad_s`` sent a user of a two-drive belt to a refusal."""
from __future__ import annotations

import pytest

from beltstudy.engine.conveyor import Scenario
from beltstudy.engine.dynamics import DynamicsOptions, build_system
from beltstudy.engine.dynamics.simulate import _settle_levers
from beltstudy.engine.statics import solve_steady
from tests.engine.dynamics.test_kernel import conveyor

PAIR = [dict(position="head", wrap_deg=200, friction=0.35, share=0.4, pulley_diameter_m=1.25,
             inertia_kg_m2=800, rated_power_kw=650),
        dict(position="head", wrap_deg=200, friction=0.35, share=0.6, pulley_diameter_m=1.25,
             inertia_kg_m2=800, rated_power_kw=900, speed_loop_rad_s=2.5)]


def test_the_settling_lever_names_the_masters_field_and_its_bandwidth():
    conv = conveyor("slope-5pct", drives=PAIR)  # the master: drive 2, the largest share
    st = solve_steady(conv, model="din", n_elements=40)
    sys_ = build_system(conv, Scenario(), st, DynamicsOptions())
    assert int(sys_.model.control.master) == 1
    assert float(sys_.model.control.bandwidth) == pytest.approx(2.5)
    words = _settle_levers(sys_)
    assert words.startswith("a slower speed loop (drives.1.speed_loop_rad_s, now 2.5 rad/s) "
                            "may swing less")
    with pytest.raises(Exception, match="drives.0.speed_loop_rad_s"):
        conveyor("slope-5pct", drives=[dict(PAIR[0], speed_loop_rad_s=1.0), PAIR[1]])
