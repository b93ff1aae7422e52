"""A dol motor named oversized beside a start slip is judged against the engine's own size for
it, the auto motor's rule (engine.drives.rated_power_kw): 1.25 x the motor power of the larger
of Te and the running resistance, ``F v / eta`` when the motor drives and ``|F v| eta`` when
it holds a regenerating belt back. An empty run is judged at the full load too; on a loaded
decline that full load regenerates, and the words took its need as |Te| v / eta: a 100 m,
25 m-fall decline's 60 kW motor was '2.2 x the 28 kW the engine would size it at', where the
engine sizes 25 kW (11 % apart at eta 0.95)."""

from __future__ import annotations

import pytest

from beltstudy.engine.conveyor import Scenario, parse_conveyor
from beltstudy.engine.design import auto_sizes
from beltstudy.engine.run import run_one
from beltstudy.engine.statics import solve_steady
from tests.conftest import short30_dict

G = 9.81
V, ETA, RATED_KW = 2.0, 0.95, 60.0
CAPACITY_T_H, FALL_M = 400.0, 25.0

DECLINE = short30_dict()
DECLINE.update(name="decline100-dol", profile=[{"length_m": 100, "lift_m": -FALL_M}])
DECLINE["material"]["capacity_t_h"] = CAPACITY_T_H
DECLINE["drives"][0].update(control="dol", coupling="none", rated_power_kw=RATED_KW)


def test_an_empty_runs_motor_is_judged_on_the_regenerating_full_load_through_eta():
    conv = parse_conveyor(DECLINE)
    full = solve_steady(conv, model="din", load="full")
    resistance = float(full.resistance_n.sum())
    # by hand: the loaded belt's net gravity pull is the material's fall, m'_L g H (the belt's
    # own weight cancels round the loop), m'_L = Q / (3.6 v); Te = R - m'_L g H
    m_l = CAPACITY_T_H / (3.6 * V)
    te_full = resistance - m_l * G * FALL_M
    assert full.te_n == pytest.approx(te_full, rel=1e-9)
    assert te_full < -10e3  # it regenerates, |Te| well above the running resistance
    need_kw = 1.25 * abs(te_full) * V * ETA / 1e3  # the motor takes |Te| v eta in
    assert need_kw > 1.25 * resistance * V / ETA / 1e3  # Te, not the resistance, sets it
    assert need_kw == pytest.approx(25.0, abs=0.1)

    res = run_one(conv, Scenario(load="empty"), model="din", dynamics=True, remedy=False,
                  check=False)
    s = res.summary
    assert s["drive1_slip_s"] > 0.0, s["message"]  # the oversized dol motor slips its start
    assert s["te_kn"] > 0.0  # the empty belt is driven: judged, at the full load's need
    said = f"is {RATED_KW / need_kw:.1f} x the {need_kw:.0f} kW the engine would size it at"
    assert said in s["message"], s["message"]
    assert "times its drive train's efficiency 0.95" in s["message"], s["message"]
    wrong_kw = 1.25 * abs(te_full) * V / ETA / 1e3  # 27.7 kW
    assert f"the {wrong_kw:.0f} kW the engine would size it at" not in s["message"]

    # the engine's auto motor at the full load is that same figure
    auto = parse_conveyor({**DECLINE, "drives": [{**DECLINE["drives"][0],
                                                  "rated_power_kw": None}]})
    sized = auto_sizes(auto, Scenario(load="full"), model="din")
    assert sized["drive_rated_power_kw"][0] == pytest.approx(need_kw, rel=1e-9)
    assert sized["drive_rated_power_governed_by"][0] == "peripheral_force"
