"""The 'less brake force' lever of a slip that outlasts the brakes' ramp (simulate.py
_brake_past_full) keeps the force that holds the loaded belt at rest, HOLD_MARGIN x its net
gravity pull. On an incline whose holdback holds the belt at rest that floor is not the
brake's: a 600 m, 40 m lift incline with a holdback and an auto brake on drive 1 (31.39 kN,
1.2 x the 26.16 kN pull) slid after the brake reached full force and was told 'not less force
on this one: its 31.39 kN is what holds the loaded belt at rest' beside the note saying its
holdback already holds it. And a brake at the floor already, its size rounded up at six
figures by a study's design, was told 'less brake force on this one (now 56.06 kN; a given
force_kn of at least 56.1 kN)'."""
from __future__ import annotations

import numpy as np
import pytest

from beltstudy.engine.checks import HOLD_MARGIN
from beltstudy.engine.conveyor import Scenario, parse_conveyor
from beltstudy.engine.dynamics import DynamicsOptions, build_system
from beltstudy.engine.dynamics.simulate import _brake_past_full
from beltstudy.engine.run import run_one
from beltstudy.engine.statics import solve_steady, up3

G = 9.81

INCLINE = {
    "name": "incline-600-holdback", "speed_m_s": 2.5,
    "belt": {"type": "EP800/4", "width_m": 1.0},
    "material": {"capacity_t_h": 600, "density_t_m3": 1.2},
    "profile": [{"length_m": 200, "lift_m": 0}, {"length_m": 400, "lift_m": 40}],
    "idlers": {"carry": {"spacing_m": 1.2, "roll_diameter_m": 0.133, "rolls": 3,
                         "trough_deg": 35},
               "return": {"spacing_m": 3.0, "roll_diameter_m": 0.133, "rolls": 1}},
    "drives": [{"position": "head", "wrap_deg": 190, "friction": 0.35, "share": 0.6,
                "pulley_diameter_m": 0.63, "inertia_kg_m2": 80, "torque_limit": 1.5},
               {"position": "head", "wrap_deg": 190, "friction": 0.35, "share": 0.4,
                "pulley_diameter_m": 0.63, "inertia_kg_m2": 60, "torque_limit": 1.5}],
    "takeup": {"type": "gravity", "position": "tail", "mass_kg": "auto", "travel_m": 4},
    "brakes": [{"drive": 1, "force_kn": "auto", "delay_s": 0.2}],
    "holdback": True,
}
BRAKE = Scenario(elements=80, run_s=20, stop={"mode": "brake"})


def test_a_holdback_holds_the_incline_so_its_brake_has_no_holding_floor():
    res = run_one(parse_conveyor(INCLINE), BRAKE, model="din")
    s = res.summary
    # the holding size by hand: 1.2 x g m'_L H, m'_L = 600 / (3.6 x 2.5) kg/m
    assert s["brake_force_kn"] == pytest.approx(HOLD_MARGIN * G * 600 / 9.0 * 40 / 1e3,
                                                rel=0.01)
    msg = s["message"]
    assert "the belt still slid after the brakes on this pulley reached full force" in msg, msg
    assert "is what holds the loaded belt at rest" not in msg, msg
    # no floor, but by the stop's undamped bound this pulley passes no brake force at all
    # (tests/engine/test_brake_slip_no_grip.py): so less force is not offered either, nor,
    # in the note, a given force 'within the grip'
    assert "passes no brake force" in msg, msg
    assert "not less force on this one: by the stop's undamped bound" in msg, msg
    assert "within the grip" not in msg, msg
    # where the pulley's grip is not known (or has room) less force is the lever, with no
    # floor: the holdback holds the belt at rest
    conv = parse_conveyor(INCLINE)
    steady = solve_steady(conv, model="din", temperature_c=BRAKE.temperature_c,
                          load=BRAKE.load, n_elements=80)
    system = build_system(conv, BRAKE, steady, DynamicsOptions())
    levers, _why = _brake_past_full(system, 0, system.stop_command_s + 60.0)
    force_kn = float(system.model.brakes.force[0]) / 1e3
    assert f"or less brake force on this one (now {force_kn:.4g} kN; a given force_kn)" \
        in levers, levers


def test_a_brake_at_its_holding_floor_is_not_offered_less_force():
    """The same incline without its holdback: the brake's floor is 1.2 x the pull. Set at the
    floor rounded up at six figures (a study's design size), the lever must not offer less
    force with a least of 3 figures above it; set well above, it offers the floor."""
    conv = parse_conveyor({**INCLINE, "holdback": False})
    scn = BRAKE
    steady = solve_steady(conv, model="din", temperature_c=scn.temperature_c, load=scn.load,
                          n_elements=80)
    system = build_system(conv, scn, steady, DynamicsOptions())
    pull_kn = float(np.sum(system.model.nodes.gravity)) / 1e3
    floor_kn = HOLD_MARGIN * abs(pull_kn)
    t_late = system.stop_command_s + 60.0  # long after the brake's delay and ramp
    system.model.brakes.force[0] = float(f"{floor_kn:.6g}") * 1e3 + 1e-3  # up at 6 figures
    levers, _why = _brake_past_full(system, 0, t_late)
    assert "or less brake force" not in levers, levers
    assert f"not less force on this one: its {floor_kn:.4g} kN" in levers
    system.model.brakes.force[0] = 2.0 * floor_kn * 1e3
    levers, _why = _brake_past_full(system, 0, t_late)
    assert f"a given force_kn of at least {up3(floor_kn):g} kN" in levers, levers
