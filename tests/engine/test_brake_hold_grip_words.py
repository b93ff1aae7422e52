"""An auto brake set by holding because its pulley's grip cut the stop time's force says that
chain, not a stop force smaller than the holding one.

A 1 km, -60 m decline (the hand conveyor, 10 s brake stop, head brake) needs 53.05 kN to stop
in 10 s, more than the 35.32 kN that holds it at rest; its head pulley passes 19.4 kN in the
stop, so holding sets the brake. The note read 'set by holding the loaded belt at rest ...,
not by the stop time 10 s (which needs 53.05 kN); it is beyond the grip ...', as if the stop
asked less than holding (the 3 km overland of p12 read the same with 85.67 against 18.39 kN).
"""

import re

import pytest

from beltstudy.engine.conveyor import Scenario
from beltstudy.engine.design import auto_sizes, moving_mass_kg
from beltstudy.engine.loop import G
from beltstudy.engine.statics import solve_steady
from tests.engine.conftest import hand_conv


def test_holding_set_by_the_grip_says_the_stop_force_is_beyond_the_grip():
    """Hold: 1.2 x m'_L g H = 1.2 x 50 x 9.81 x 60 = 35 316 N. Stop: v_1 = v - Te d / M,
    F = (M v_1 - Te t_b) / (t_b - r / 2) with d 0.5 s, r 1 s, t_b 9.5 s (Te < 0: the belt
    gains speed in the delay)."""
    conv = hand_conv(profile=[{"length_m": 1000, "lift_m": -60}],
                     brakes=[{"position": "head", "force_kn": "auto", "delay_s": 0.5,
                              "ramp_s": 1.0}])
    sizes = auto_sizes(conv, Scenario(stop={"mode": "brake", "time_s": 10.0}), model="din")
    hold = 1.2 * 50.0 * G * 60.0
    assert sizes["brake_governed_by"] == ["holding"]
    assert sizes["brake_force_kn"][0] == pytest.approx(hold / 1e3, rel=1e-9)
    st = solve_steady(conv, model="din")
    m, te = moving_mass_kg(conv, st), st.te_n
    need = (m * (4.0 - te * 0.5 / m) - te * 9.5) / (9.5 - 0.5)
    assert need > hold
    note = sizes["brake_note"]
    said = re.search(r"not by the stop time 10 s: that needs ([0-9.]+) kN, beyond the grip of "
                     r"drive 1's pulley \(head\) in the stop \(([0-9.]+) kN", note)
    assert said, note
    assert float(said.group(1)) == pytest.approx(need / 1e3, rel=1e-3)
    assert float(said.group(2)) < hold / 1e3
    assert "held to that grip it would fall below the holding force" in note
    assert "the holding force 35.32 kN is beyond the grip too" in note
