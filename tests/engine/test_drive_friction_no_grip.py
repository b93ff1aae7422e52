"""A drive friction so small that the capstan factor e^(mu theta) is 1 in floating point
(mu theta below about 1.1e-16): the slack side the grip needs, Te / (e^(mu theta) - 1), was a
division by zero, an infinite take-up and tension, and an OverflowError traceback from
beltstudy static (a 500 from POST /studies) where the safety words sized a belt width from it.
It is refused at the door, naming the drive; a pulley that barely grips is still taken."""

from __future__ import annotations

import math

import pytest

from beltstudy.engine.errors import InputError
from beltstudy.engine.statics import solve_steady
from tests.engine.conftest import hand_conv, hand_drive


@pytest.mark.parametrize("mu", [1e-17, 1e-160, 1e-300])
def test_a_friction_whose_capstan_factor_is_one_is_refused_naming_the_drive(mu):
    # 200 deg = 3.49 rad: mu theta <= 3.5e-17, e^(mu theta) = 1 exactly
    assert math.exp(mu * math.radians(200)) == 1.0
    with pytest.raises(InputError) as exc:
        hand_conv(drives=[hand_drive(friction=mu)])
    msg = str(exc.value)
    assert msg.startswith("drives.0: friction ") and "grips nothing" in msg
    assert "\n" not in msg


def test_the_smallest_friction_that_grips_is_still_solved():
    # mu 1e-15 over 200 deg: e^(mu theta) - 1 = 3.49e-15 (2.220446e-16 steps); the take-up the
    # grip needs is far past any counterweight and said so, as for friction 1e-6
    mu = 1e-15
    e = math.exp(mu * math.radians(200))
    assert e - 1.0 == pytest.approx(3.49e-15, rel=0.05)
    res = solve_steady(hand_conv(drives=[hand_drive(friction=mu)]), model="din")
    assert math.isfinite(res.summary["t_max_kn"])
    assert any("beyond any counterweight" in w for w in res.warnings)
