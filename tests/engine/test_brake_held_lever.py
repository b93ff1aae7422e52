"""A brake stop's levers offer 'a longer stop.time_s for an auto brake sized by it' only where
the stop time sizes the brake. A 300 m, 15 m lift incline's auto head brake asked for a 2 s
stop needs 22.1 kN by the rigid-body rule, its pulley grips 1.35 kN in the stop, so the brake
falls back to holding the loaded belt at rest (1.2 x the net gravity pull): a longer stop time
leaves it there, yet the lever was offered beside the note saying so."""
from __future__ import annotations

from types import SimpleNamespace

import pytest

from beltstudy.engine.conveyor import Scenario, parse_conveyor
from beltstudy.engine.dynamics.simulate import _brake_held
from beltstudy.engine.run import brakes_timed, run_one
from tests.conftest import incline300_dict

G = 9.81

# 300 m, 15 m lift, 200 t/h at 2 m/s, one head drive, an auto head brake
INCLINE = incline300_dict(brakes=[{"position": "head", "force_kn": "auto", "delay_s": 0.5}])


@pytest.mark.parametrize("governed, timed", [
    (None, None), ("", None), ("stop_time", True), ("grip", True), ("holding", False),
    ("given", False), ("holding @ inclines", False), ("stop_time @ full, cema, -25 C", True),
    ("holding+given", False), ("holding+stop_time", True)])
def test_what_set_the_brake_says_whether_the_stop_time_moves_it(governed, timed):
    assert brakes_timed(governed) is timed
    known = SimpleNamespace(brakes_timed=timed, model=SimpleNamespace(brakes=None))
    if timed is not None:
        assert _brake_held(known) is (not timed)


def test_a_brake_held_at_the_holding_force_by_its_grip_is_not_offered_a_longer_stop_time():
    res = run_one(parse_conveyor(INCLINE),
                  Scenario(elements=60, run_s=20, stop={"mode": "brake", "time_s": 2}),
                  model="din")
    msg = res.summary["message"]
    assert res.summary["brake_governed_by"] == "holding"
    assert "set by holding the loaded belt at rest" in msg and "beyond the grip" in msg, msg
    # the hold by hand: 1.2 x the lift's pull, g m'_L H (m'_L = 200 / (3.6 x 2) kg/m), and
    # the belt's own weight cancels round the loop
    m_load = 200 / (3.6 * 2.0)
    assert res.summary["brake_force_kn"] == pytest.approx(1.2 * G * m_load * 15 / 1e3, rel=0.02)
    assert "a longer stop.time_s for an auto brake sized by it" not in msg
