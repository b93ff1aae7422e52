"""The dol motor law on its generating side (engine/dynamics/laws.py ``motor_force``), by hand
on the default motor curve (conveyor.DEFAULT_MOTOR_CURVE: breakdown 2.2 x rated at 0.87,
1.9 at 0.95, rated at 1.0, zero at the synchronous point 1.015, locked rotor 1.6)."""

import numpy as np
import pytest

from beltstudy.engine.conveyor import DEFAULT_MOTOR_CURVE
from beltstudy.engine.dynamics.laws import motor_force, padded_curves

XS, YS, NS = padded_curves([DEFAULT_MOTOR_CURVE])
SLOPE_LAST = (0.0 - 1.0) / (1.015 - 1.0)  # the last segment, -66.67 per unit speed


def force(x: float) -> tuple[float, float]:
    """Force over rated force and its slope at speed x (rated force 1 N, design speed 1 m/s)."""
    return motor_force(XS[0], YS[0], NS[0], 1.0, 1.0, x)


@pytest.mark.parametrize(("x", "y"), [
    (0.5, 1.4),                          # motoring: the curve itself
    (1.0075, SLOPE_LAST * (1.0075 - 1.015)),   # +0.5, below synchronous speed
    (1.02, SLOPE_LAST * (1.02 - 1.015)),       # -0.333: the last segment continued
    (1.03, -1.0),                        # the end of the last segment's mirror
    (1.08, -1.9),                        # mirror of 2 x 1.015 - 1.08 = 0.95
    (1.16, -2.2),                        # mirror of 0.87: the generating breakdown torque
    (2.1, -1.6),                         # mirror below standstill: minus the locked rotor
])
def test_generating_torque_mirrors_the_motoring_curve(x, y):
    """Kloss's law is odd in the slip: y(x_s + d) = -y(x_s - d) beyond the last segment."""
    assert force(x)[0] == pytest.approx(y, rel=1e-9, abs=1e-12)


def test_generating_torque_is_bounded_by_the_breakdown_torque_and_continuous():
    """|y| never exceeds the curve's largest torque (2.2, its breakdown), however fast the
    shaft turns; the plain continuation of the last segment reached -4.9 at 1.088. The force
    is continuous across the switch to the mirror at 2 x_s - x_{n-2} = 1.03, and its slope is
    the derivative of y(x) = -y(2 x_s - x), y'(2 x_s - x)."""
    xs = np.linspace(0.0, 3.0, 30001)
    ys = np.array([force(x)[0] for x in xs])
    assert np.abs(ys).max() == pytest.approx(2.2, rel=1e-12)
    assert force(1.088)[0] == pytest.approx(-(2.2 - 3.75 * (2.03 - 1.088 - 0.87)), rel=1e-9)
    assert np.abs(np.diff(ys)).max() < 66.67 * 1e-4 * 1.001  # no jump: the steepest slope x dx
    assert force(1.08)[1] == pytest.approx(-3.75, rel=1e-9)  # 0.95 -> 0.87: 1.9 -> 2.2
    assert force(2.5)[1] == 0.0
