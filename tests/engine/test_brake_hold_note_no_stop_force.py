"""An auto brake set by holding the loaded belt at rest, where the belt coasts to rest within
the asked stop time unaided, said 'not by the stop time 30 s (which needs 0 kN)' (p11's
generated conveyors, seed 11: a 110 m belt at 3.5 m/s, 2 m fall, Te 7.49 kN, coast stop 10.5 s).
The stop needs no brake force; the note now says so in words, and the holding force is kept."""
from __future__ import annotations

import pytest

from beltstudy.engine.conveyor import Scenario, parse_conveyor
from beltstudy.engine.design import brake_forces
from tests.conftest import incline300_dict

G = 9.81
# 300 m, 15 m lift, 200 t/h at 2 m/s, an auto head brake
CONV = parse_conveyor(incline300_dict(brakes=[{"position": "head", "force_kn": "auto",
                                               "delay_s": 0.5, "ramp_s": 1.0}]))


def test_a_stop_needing_no_brake_force_is_said_in_words_not_as_0_kn():
    pull_n = G * 200 / (3.6 * 2.0) * 15  # the lift's pull at rest, g m'_L H: 4087 N
    # 50 t moving at 2 m/s against Te 20 kN: a rigid coast of 50e3 x 2 / 20e3 = 5 s, well
    # within the asked 60 s, so the stop asks nothing of the brake
    kn, gov, note = brake_forces(CONV, Scenario(stop={"mode": "brake", "time_s": 60}),
                                 50e3, 20e3, pull_n)
    assert gov == ["holding"]
    assert kn[0] == pytest.approx(1.2 * pull_n / 1e3, rel=1e-9)  # 4.905 kN
    assert "needs 0 kN" not in note, note
    assert "not by the stop time 60 s (which needs none: the belt coasts to rest" in note, note


def test_a_stop_that_needs_some_force_below_the_hold_still_names_it():
    pull_n = G * 200 / (3.6 * 2.0) * 15
    # 50 t at 2 m/s against Te 1 kN asked to stop in 60 s: rigid coast 100 s, so the stop
    # needs a little force, below the 4.9 kN hold: delay 0.5 s leaves v1 = 2 - 1e3 x 0.5 / 50e3
    # = 1.99 m/s; M v1 = Te t_b + F (t_b - r / 2), t_b = 59.5 s: F = (99.5e3 - 59.5e3) / 59
    f_need = (50e3 * 1.99 - 1e3 * 59.5) / (59.5 - 0.5)
    kn, gov, note = brake_forces(CONV, Scenario(stop={"mode": "brake", "time_s": 60}),
                                 50e3, 1e3, pull_n)
    assert gov == ["holding"]
    assert f"which needs {f_need / 1e3:.4g} kN" in note, note
