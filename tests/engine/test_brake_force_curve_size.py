"""An auto brake with a ``force_curve`` is sized by that curve, not by the ``ramp_s`` it does
not read.

The transient model follows a brake's force curve and ignores its ``ramp_s``; the rigid-body
size of an auto brake (``design.brake_forces``) took the ramp all the same (default 1 s), so a
curve that builds over 8 s was sized as a 1 s ramp: on a 526 t overland with Te 121.8 kN and a
12 s stop, 58.4 kN asked where the curve needs 85.7 kN, and the stop ran long.
"""

import pytest

from beltstudy.engine.conveyor import Scenario
from beltstudy.engine.design import brake_forces, brake_stop_time
from tests.engine.conftest import hand_conv

# a rigid belt of round numbers: 100 t from 4 m/s against Te 20 kN, level (no holding force)
M, V, TE = 100_000.0, 4.0, 20_000.0


def _sized(brake: dict, stop_s: float) -> float:
    conv = hand_conv(brakes=[brake])
    scn = Scenario(stop={"mode": "brake", "time_s": stop_s})
    kn, why, _note = brake_forces(conv, scn, M, TE, 0.0, None)
    assert why == ["stop_time"]
    return kn[0]


def test_auto_brake_sized_by_its_force_curve():
    """Delay 0.5 s, curve 0.5 of the force at once rising to full at 3 s, 8 s stop.

    v_1 = 4 - 20 000 x 0.5 / 100 000 = 3.9 m/s; t_b = 7.5 s; the brake's impulse
    M v_1 - Te t_b = 390 000 - 150 000 = 240 000 N s; the curve's integral over t_b is
    (0.5 + 1) / 2 x 3 + 1 x 4.5 = 6.75 s, so F_b = 240 000 / 6.75 = 35 555.6 N (a 1 s ramp
    would give 240 000 / 7 = 34 285.7 N)."""
    brake = {"position": "head", "force_kn": "auto", "delay_s": 0.5,
             "force_curve": [[0, 0.5], [3, 1.0]]}
    assert _sized(brake, 8.0) == pytest.approx(240_000 / 6.75 / 1e3, rel=1e-9)


def test_a_curve_starting_late_is_zero_before_its_first_point():
    """Curve [[2, 0.4], [6, 1]] (zero for 2 s, then 0.4 rising to 1 at 6 s), delay 0.5 s,
    10 s stop: t_b = 9.5 s, impulse 390 000 - 190 000 = 200 000 N s, integral
    0 x 2 + 0.7 x 4 + 1 x 3.5 = 6.3 s, F_b = 31 746.0 N; its rigid stop time is the 10 s."""
    brake = {"position": "head", "force_kn": "auto", "delay_s": 0.5,
             "force_curve": [[2, 0.4], [6, 1.0]]}
    kn = _sized(brake, 10.0)
    assert kn == pytest.approx(200_000 / 6.3 / 1e3, rel=1e-9)
    curve = ((0.0, 0.0), (2.0, 0.0), (2.0, 0.4), (6.0, 1.0))
    assert brake_stop_time(M, V, TE, kn * 1e3, 0.5, 1.0, curve) == pytest.approx(10.0, rel=1e-9)


def test_a_ramp_written_as_a_curve_sizes_as_the_ramp():
    """[[0, 0], [8, 1]] is an 8 s ramp: 12 s stop, delay 0.5 s, t_b 11.5 s, impulse
    M v_1 - Te t_b = 390 000 - 230 000 = 160 000 N s over t_b - r / 2 = 7.5 s: 21 333.3 N,
    the same as ``ramp_s: 8`` (the default 1 s ramp gave 160 000 / 11 = 14 545.5 N)."""
    curve = {"position": "head", "force_kn": "auto", "delay_s": 0.5,
             "force_curve": [[0, 0.0], [8, 1.0]]}
    ramp = {"position": "head", "force_kn": "auto", "delay_s": 0.5, "ramp_s": 8.0}
    assert _sized(curve, 12.0) == pytest.approx(160_000 / 7.5 / 1e3, rel=1e-9)
    assert _sized(ramp, 12.0) == pytest.approx(160_000 / 7.5 / 1e3, rel=1e-9)


def test_a_ramp_beside_a_force_curve_is_said_to_be_not_read():
    """A brake with a force curve follows the curve: a 30 kN head brake on an 800 m incline with
    ``force_curve: [[0, 0.5], [3, 1]]`` stopped in 5.055 s with ``ramp_s`` 1 and 5 alike, with
    no word that the 5 s ramp was not read. It is now said, naming the field; the default
    ramp beside a curve, and a ramp without one, are not."""
    from beltstudy.engine.statics import solve_steady

    def notes(**brake):
        conv = hand_conv(brakes=[{"position": "head", "force_kn": 30, **brake}])
        return [m for m in solve_steady(conv, model="din").message.split("; ")
                if "brakes.0.ramp_s" in m]

    said = notes(ramp_s=5.0, force_curve=[[0, 0.5], [3, 1.0]])
    assert len(said) == 1 and said[0].startswith("note: brakes.0.ramp_s 5 s is not read"), said
    assert "force_curve" in said[0]
    assert notes(force_curve=[[0, 0.5], [3, 1.0]]) == []
    assert notes(ramp_s=5.0) == []
