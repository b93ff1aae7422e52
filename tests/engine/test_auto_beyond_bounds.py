"""An auto size beyond what a file may give is said, as the take-up's already was, and a
study keeps it auto (tests/service/test_basis_beyond_bounds.py) so its runs size their own
and say it instead of failing on a field the user never wrote.

valley-booster with ``drives.0.efficiency: 1e-6`` sized a 1.3 TW motor that ``static`` called
``ok``; in a study every run failed on ``drives.0.rated_power_kw`` (which the file leaves
out) with a hint to read it as watts. A 30 km, -15 km route's auto holding brake (30 656 kN)
failed the same way on ``brakes.0.force_kn``.
"""
from __future__ import annotations

from beltstudy.engine.conveyor import FORCE_MAX_KN, POWER_MAX_KW, load_mapping, parse_conveyor
from beltstudy.engine.loop import G
from beltstudy.engine.statics import solve_steady
from tests.conftest import CONVEYORS


def _steady(data: dict):
    return solve_steady(parse_conveyor(data), model="din")


def test_an_auto_motor_beyond_any_conveyor_motor_is_said_with_its_cause():
    data = load_mapping(CONVEYORS / "valley-booster.yaml")
    data["drives"][0]["efficiency"] = 1e-6
    res = _steady(data)
    assert res.status == "warning"
    assert "drive 1's auto rated power" in res.message, res.message
    assert f"a file may give at most {POWER_MAX_KW:,.0f} kW" in res.message
    assert "drives.0.efficiency 1e-06" in res.message
    # the efficiency itself is noted below any gear unit's
    assert "note: drives.0.efficiency 1e-06 is below a conveyor drive train's" in res.message
    # the file as shipped (efficiency 0.95, a motor within the bound) says neither
    plain = _steady(load_mapping(CONVEYORS / "valley-booster.yaml"))
    assert "auto rated power" not in plain.message
    assert "is below a conveyor drive train's" not in plain.message


def test_an_auto_holding_brake_beyond_any_belt_is_said():
    data = load_mapping(CONVEYORS / "downhill-regen.yaml")
    data["profile"] = [{"length_m": 30000, "lift_m": -15000}]
    res = _steady(data)
    m_l = 2500 / 3.6 / 4.0  # the design load [kg/m], 2500 t/h at 4 m/s
    assert "the auto brakes' holding size (1.2 x the loaded belt's net gravity pull" in \
        res.message, res.message
    assert f"a file may give at most {FORCE_MAX_KN:,.0f} kN" in res.message
    # by hand: 1.2 x the load's pull alone is already beyond the bound
    assert 1.2 * m_l * G * 15000 / 1e3 > FORCE_MAX_KN
