"""A drive's given inertia below its pulley shell's estimate is said, not silently replaced.

The transient model gives a drive shaft at least the estimated mass of its own pulley shell
(:func:`beltstudy.engine.loop.pulley_reduced_mass_kg`): a given J below it was replaced
without a word (a 90 m 16 deg incline: 444 kg used against the 202 kg its J implied).
"""

from __future__ import annotations

import math

import pytest

from beltstudy.engine.conveyor import Conveyor, Scenario
from beltstudy.engine.dynamics import build_system
from beltstudy.engine.statics import solve_steady


def _conv(**drive) -> Conveyor:
    return Conveyor.model_validate({
        "name": "short-incline", "speed_m_s": 2.0,
        "belt": {"type": "EP630/4", "width_m": 0.8, "compound": "standard"},
        "material": {"capacity_t_h": 400, "density_t_m3": 1.6, "loading_speed_m_s": 0.0},
        "profile": [{"length_m": 100, "lift_m": 15}],
        "idlers": {"carry": {"spacing_m": 1.2, "roll_diameter_m": 0.133, "rolls": 3,
                             "trough_deg": 35, "cema_class": "C"},
                   "return": {"spacing_m": 3.0, "roll_diameter_m": 0.133, "rolls": 1,
                              "cema_class": "C"}},
        "drives": [{"position": "head", "wrap_deg": 200, "friction": 0.35, "share": 1.0,
                    "pulley_diameter_m": 0.63, **drive}],
        "takeup": {"type": "gravity", "position": "tail", "mass_kg": "auto", "travel_m": 2},
        "holdback": True, "sag_limit_pct": {"carry": 1.5, "return": 3.0}})


def _system(conv: Conveyor):
    st = solve_steady(conv, model="din", n_elements=40)
    sysm = build_system(conv, Scenario(elements=40), st)
    sysm.head_element = int(st.loop.drive_elements[0])
    return sysm


def test_a_given_inertia_below_the_pulley_shell_is_said_with_both_masses():
    """By hand: J 20 kg m2 on a 0.63 m pulley is 20 (2 / 0.63)^2 = 201.6 kg at the belt
    line; the shell (steel 7850 kg/m3, face 0.8 + 0.2 m, wall 12 mm + 1 % of D, + 30 %) is
    1.3 x 7850 x pi x 0.63 x 1.0 x 0.0183 = 369.6 kg; the shaft carries the larger."""
    given = 20.0 * (2.0 / 0.63) ** 2
    shell = 1.3 * 7850.0 * math.pi * 0.63 * 1.0 * (0.012 + 0.01 * 0.63)
    assert given == pytest.approx(201.6, abs=0.05) and shell == pytest.approx(369.6, abs=0.1)
    sysm = _system(_conv(inertia_kg_m2=20.0))
    said = [n for n in sysm.notes if n.startswith("drive 1's given inertia")]
    assert len(said) == 1, sysm.notes
    assert f"is {given:.4g} kg at the belt line" in said[0]
    assert f"pulley's own shell, {shell:.4g} kg" in said[0]
    assert f"so the run used {shell:.4g} kg on that shaft" in said[0]
    assert "drives.0.inertia_kg_m2 20 kg m2" in said[0]
    head = sysm.model.shafts.node.tolist().index(sysm.head_element)
    assert float(sysm.model.shafts.mass[head]) == pytest.approx(shell, rel=1e-9)


@pytest.mark.parametrize("drive", [{"inertia_kg_m2": 100.0}, {}])
def test_an_inertia_above_the_shell_or_none_given_is_not_told(drive):
    """100 kg m2 is 1008 kg at the belt line, above the shell; a drive that gives no inertia
    asks for the estimate."""
    assert not [n for n in _system(_conv(**drive)).notes if "given inertia" in n]
