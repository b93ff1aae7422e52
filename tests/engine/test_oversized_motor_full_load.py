"""A start slip of a dol drive names a motor above the engine's own size for it. The engine
sizes a motor at the full load (an auto motor of a run below it is installed for the full load
too, engine.sizing.installed_at_full_load), so an empty run's motor is judged against the full
load's force, not the empty belt's: a 30 m belt with a 15 kW dol motor, run empty, was told
'3.4 x the 4 kW the engine would size it at' (the empty Te, 1.77 kN) instead of 2.9 x 5 kW."""

from __future__ import annotations

import math

import pytest

from beltstudy.engine.conveyor import Scenario, parse_conveyor
from beltstudy.engine.run import run_one
from tests.conftest import short30_dict

LBF_N = 4.4482216152605

SHORT = short30_dict()
SHORT["name"] = "short30-dol"
SHORT["drives"][0].update(control="dol", coupling="none")


def test_an_empty_runs_oversized_motor_is_judged_at_full_load():
    conv = parse_conveyor(SHORT)
    res = run_one(conv, Scenario(load="empty"), model="din", dynamics=True, remedy=False,
                  check=False)
    s = res.summary
    assert s["drive1_slip_s"] > 0.0, s["message"]  # the dol start slips (no coupling)
    # DIN below 80 m, by hand: f g L per strand on the input masses, the feed I_m v and the
    # pulley allowances (200 lbf the drive pulley, 150 lbf the take-up pulley)
    m_g, m_l = s["belt_mass_kg_m"], 200.0 / 3.6 / 2.0
    m_ro, m_ru = s["idler_mass_carry_kg_m"], s["idler_mass_return_kg_m"]
    te_full = (0.02 * 9.81 * 30.0 * ((m_ro + m_g + m_l) + (m_ru + m_g))
               + 200.0 / 3.6 * 2.0 + (200.0 + 150.0) * LBF_N)
    te_empty = 0.02 * 9.81 * 30.0 * ((m_ro + m_g) + (m_ru + m_g)) + (200.0 + 150.0) * LBF_N
    assert s["te_kn"] * 1e3 == pytest.approx(te_empty, rel=1e-3)
    need_kw = 1.25 * te_full * 2.0 / 0.95 / 1e3  # 5.37 kW: the motor power, through eta
    assert need_kw == pytest.approx(5.37, abs=0.01)
    said = f"is {15.0 / need_kw:.1f} x the {need_kw:.0f} kW the engine would size it at"
    assert said in s["message"], s["message"]
    wrong = f"is {15.0 / (1.25 * te_empty * 2.0 / 0.95 / 1e3):.1f} x the"
    assert wrong not in s["message"]
    assert math.isclose(15.0 / need_kw, 2.79, abs_tol=0.01)
