"""Drive, coupling and brake laws of the transient model (engine/dynamics/laws.py)."""

from __future__ import annotations

import numpy as np
import pytest

from beltstudy.engine.dynamics.laws import brake_fraction


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
