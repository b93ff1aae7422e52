"""The brakes' record and force law (engine/dynamics/brakes.py)."""

from __future__ import annotations

import numpy as np
import pytest

from beltstudy.engine.conveyor import Scenario
from beltstudy.engine.dynamics import build_system
from beltstudy.engine.dynamics.brakes import brake_force, brake_fraction, set_at
from beltstudy.engine.dynamics.laws import padded_curves
from beltstudy.engine.statics import solve_steady
from tests.engine.conftest import hand_conv


def test_brake_fraction_ramp_and_curve():
    """The ramp reaches the full force at ramp_s; a force curve is followed between its
    points and held after the last."""
    ct = np.zeros(16)
    cf = np.zeros(16)
    assert brake_fraction(0.5, 1.0, ct, cf, 0) == pytest.approx(0.5)
    assert brake_fraction(1.0, 1.0, ct, cf, 0) == 1.0
    assert brake_fraction(-0.1, 1.0, ct, cf, 0) == 0.0
    ct[:2] = [0.0, 3.0]
    cf[:2] = [0.5, 1.0]
    assert brake_fraction(0.0, 1.0, ct, cf, 2) == 0.5
    assert brake_fraction(1.5, 1.0, ct, cf, 2) == pytest.approx(0.75)
    assert brake_fraction(10.0, 1.0, ct, cf, 2) == 1.0


def test_the_record_holds_the_conveyor_files_brakes():
    """build_brakes (through build_system): a given force in N, the delay and ramp, a force
    curve padded to the kernel's width with its number of points, the hold flag, the shaft of
    the braked pulley; the law gives force x fraction, full once delay and ramp (or the curve's
    last time) have run from the command."""
    conv = hand_conv(brakes=[
        {"position": "head", "force_kn": 40.0, "delay_s": 0.5, "ramp_s": 2.0},
        {"position": "tail", "force_kn": 10.0, "delay_s": 0.2,
         "force_curve": [[0.0, 0.2], [1.0, 0.6], [3.0, 1.0]], "hold": False}])
    st = solve_steady(conv, model="din", n_elements=40)
    brakes = build_system(conv, Scenario(elements=40), st).model.brakes
    assert brakes.force.tolist() == [40e3, 10e3]
    assert brakes.delay.tolist() == [0.5, 0.2] and brakes.ramp[0] == 2.0
    assert brakes.curve_n.tolist() == [0, 3] and brakes.hold.tolist() == [1, 0]
    assert brakes.curve_t[1, :3].tolist() == [0.0, 1.0, 3.0]
    assert brakes.t_cmd.tolist() == [-1.0, -1.0]
    # by hand: half the ramp -> half the force; the curve between its points
    assert brake_force(brakes, 0, 1.0, 0.0) == pytest.approx(20e3)
    assert brake_force(brakes, 1, 2.0, 3.0) == pytest.approx(10e3 * 0.8)
    assert brake_force(brakes, 0, -0.01, 1.0) == 0.0
    t_cmd = brakes.t_cmd.copy()
    t_cmd[:] = [10.0, 20.0]
    commanded = brakes._replace(t_cmd=t_cmd)
    assert set_at(commanded, 0) == pytest.approx(10.0 + 0.5 + 2.0)
    assert set_at(commanded, 1) == pytest.approx(20.0 + 0.2 + 3.0)


def test_padded_curves():
    """Curves as the kernel takes them: zero-padded to the width, with their lengths; a curve
    longer than the width is refused."""
    xs, ys, ns = padded_curves([((0.0, 1.0), (1.0, 2.0)), ()], width=4)
    assert xs.shape == ys.shape == (2, 4) and ns.tolist() == [2, 0]
    assert xs[0].tolist() == [0.0, 1.0, 0.0, 0.0] and ys[0, :2].tolist() == [1.0, 2.0]
    with pytest.raises(ValueError, match="more than 4 points"):
        padded_curves([tuple((float(i), 0.0) for i in range(5))], width=4)
