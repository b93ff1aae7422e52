"""Conveyors shared by the engine tests: the hand conveyor over two sections (load patterns)
and the hand conveyor with its drives changed."""

from __future__ import annotations

import numpy as np

from beltstudy.engine.conveyor import parse_conveyor
from tests.conftest import hand_conveyor_dict

#: Hand numbers of the two-section conveyor (tests/conftest.py: hand_conveyor_dict):
#: m'_G = 20, m'_L = 50 (design), m'_R = 10 carry, 3 return [kg/m]; f = 0.020 both strands.
MG, ML, MRC, MRR, F = 20.0, 50.0, 10.0, 3.0, 0.020
L1, H1, L2, H2 = 500.0, 25.0, 500.0, -20.0


def two_sections(**over):
    """The hand conveyor over a rise then a fall, secondary resistances and accessories off
    (C = 1 is passed to the model), so Te is main resistances plus material lift."""
    d = hand_conveyor_dict(profile=[{"length_m": L1, "lift_m": H1},
                                    {"length_m": L2, "lift_m": H2}],
                           accessories={"head_kn": 0.0, "tail_kn": 0.0})
    d.update(over)
    return parse_conveyor(d)


DIN = {"f_carry": F, "f_return": F, "c": 1.0}


def hand_conv(**over):
    """The hand conveyor with top-level fields replaced, parsed."""
    return parse_conveyor(hand_conveyor_dict(**over))


def hand_drive(**over):
    """The hand conveyor's head drive (200 deg, mu 0.35, 1 m pulley, 50 kg m2) as a dict, with
    fields replaced."""
    d = {"position": "head", "wrap_deg": 200, "friction": 0.35, "share": 1.0,
         "pulley_diameter_m": 1.0, "inertia_kg_m2": 50.0}
    d.update(over)
    return d


def dual_head(**over):
    """The hand conveyor on two head drives sharing the force half and half."""
    d = hand_conveyor_dict(drives=[hand_drive(share=0.5, inertia_kg_m2=20),
                                   hand_drive(share=0.5, inertia_kg_m2=20)], **over)
    return parse_conveyor(d)


def steep_incline(brake_force="auto", **over):
    """The hand conveyor over 1.5 km rising 150 m (10 %), a 50 t gravity take-up at the tail,
    a head brake (0.5 s delay, 0.5 s ramp) on the head drive's pulley, a 2 500 kN belt."""
    belt = {"width_m": 1.0, "rating_kn_m": 2500, "modulus_kn_m": 60000,
            "carcass_mass_kg_m2": 20.0, "top_cover_mm": 0, "bottom_cover_mm": 0}
    d = hand_conveyor_dict(profile=[{"length_m": 1500, "lift_m": 150}], belt=belt,
                           brakes=[{"position": "head", "force_kn": brake_force,
                                    "delay_s": 0.5, "ramp_s": 0.5}],
                           takeup={"type": "gravity", "position": "tail", "mass_kg": 50000})
    d.update(over)
    return parse_conveyor(d)


def assert_settles_to_statics(conv, st, start_s: float, run_s: float = 120.0):
    """Start ``conv`` from rest by an s-curve of ``start_s`` and run ``run_s`` (the transient
    model of the steady solution ``st``), up to the step before the stop command: the run has
    not failed and every boundary tension is the steady one within 1 %. Returns (system,
    result)."""
    from beltstudy.engine.conveyor import Scenario
    from beltstudy.engine.dynamics import build_system, simulate

    scn = Scenario(start={"control": "s-curve", "time_s": start_s}, run_s=run_s)
    sys = build_system(conv, scn, st)
    res = simulate(sys, t_end_s=sys.stop_command_s - sys.dt_s)
    T = res.raw["tension"]
    assert res.status != "failed"
    assert np.max(np.abs(T - st.tension_n) / st.tension_n) < 0.01
    return sys, res


#: The head drives of :func:`steep_16deg_dict`: dol through fill-controlled fluid couplings.
STEEP_16DEG_DRIVE = {"position": "head", "wrap_deg": 200, "friction": 0.35, "share": 0.5,
                     "pulley_diameter_m": 0.8, "inertia_kg_m2": 80, "rated_power_kw": 250,
                     "control": "dol", "coupling": "fluid_fill_controlled",
                     "coupling_fill_s": 20}


def steep_16deg_dict(**over):
    """A 400 m, 16 deg (110.3 m lift) EP1250/5 incline at 2.5 m/s carrying 600 t/h on two dol
    head drives through fill-controlled couplings (:data:`STEEP_16DEG_DRIVE`), an auto gravity
    take-up at the tail and a holdback (a designer's sign-off conveyor), top-level fields
    replaced by ``over``."""
    d = {
        "name": "steep-16deg", "speed_m_s": 2.5,
        "belt": {"type": "EP1250/5", "width_m": 1.0, "top_cover_mm": 6, "bottom_cover_mm": 2},
        "material": {"capacity_t_h": 600, "density_t_m3": 1.4},
        "profile": [{"length_m": 400, "lift_m": 110.3}],
        "idlers": {"carry": {"spacing_m": 1.0, "roll_diameter_m": 0.127, "rolls": 3,
                             "trough_deg": 35, "cema_class": "C"},
                   "return": {"spacing_m": 3.0, "roll_diameter_m": 0.127, "rolls": 1,
                              "cema_class": "C"}},
        "drives": [dict(STEEP_16DEG_DRIVE), dict(STEEP_16DEG_DRIVE)],
        "takeup": {"type": "gravity", "position": "tail", "mass_kg": "auto", "travel_m": 4},
        "holdback": True,
        "accessories": {"head_kn": 1.0, "tail_kn": 0.5},
    }
    d.update(over)
    return d


def decline_2500_dict(**over):
    """A 2.5 km steel-cord decline falling 120 m (ST1600 1.2 m wide, 2000 t/h at 4 m/s, net
    pull m'_L g H = 138.9 x 9.81 x 120 = 163.5 kN) on one vfd head drive, an auto gravity
    take-up at the tail and an auto brake on the head drive's pulley (a designer's sign-off
    conveyor), top-level fields replaced by ``over``."""
    d = {
        "name": "decline-2500", "speed_m_s": 4.0,
        "belt": {"type": "ST1600", "width_m": 1.2},
        "material": {"capacity_t_h": 2000, "density_t_m3": 1.6},
        "profile": [{"length_m": 2500, "lift_m": -120}],
        "idlers": {"carry": {"spacing_m": 1.2, "roll_diameter_m": 0.152, "rolls": 3,
                             "trough_deg": 35, "cema_class": "D"},
                   "return": {"spacing_m": 3.0, "roll_diameter_m": 0.152, "rolls": 1,
                              "cema_class": "C"}},
        "drives": [{"position": "head", "wrap_deg": 210, "friction": 0.35, "share": 1.0,
                    "pulley_diameter_m": 1.25, "inertia_kg_m2": 1500,
                    "rated_power_kw": 800}],
        "takeup": {"type": "gravity", "position": "tail", "mass_kg": "auto"},
        "brakes": [{"position": "head", "force_kn": "auto", "delay_s": 1.0}],
        "accessories": {"head_kn": 2.0, "tail_kn": 1.0},
    }
    d.update(over)
    return d
