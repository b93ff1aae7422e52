"""Shared fixtures: paths to the example conveyors, a small hand-calculable conveyor and the
transient fields of a run's summary."""

from __future__ import annotations

from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
CONVEYORS = ROOT / "studies" / "conveyors"

#: The transient fields every run with dynamics reports (SPEC section 4).
TRANSIENT_FIELDS = (
    "t_max_dyn_kn", "t_max_dyn_at_m", "t_max_dyn_time_s", "t_min_dyn_kn", "t_min_dyn_at_m",
    "t_min_dyn_time_s", "dyn_factor", "drive_force_max_kn", "drive_power_max_kw",
    "velocity_max_m_s", "velocity_min_m_s", "takeup_travel_m", "start_time_s", "stop_time_s",
    "wave_loop_time_s", "stop_wave_ratio", "sag_max_dyn_pct", "slip_margin_min_dyn",
    "safety_factor_dyn",
)


def hand_conveyor_dict(**over) -> dict:
    """A 1 km conveyor rising 50 m, with round numbers for hand calculations.

    m'_G = 20 kg/m (custom belt, covers 0), m'_L = 720 / (3.6 x 4) = 50 kg/m,
    m'_R carry = 12.5 / 1.25 = 10 kg/m, m'_R return = 7.5 / 2.5 = 3 kg/m.
    """
    d = {
        "name": "hand",
        "speed_m_s": 4.0,
        "belt": {"width_m": 1.0, "rating_kn_m": 1000, "modulus_kn_m": 60000,
                 "carcass_mass_kg_m2": 20.0, "top_cover_mm": 0, "bottom_cover_mm": 0},
        "material": {"capacity_t_h": 720, "density_t_m3": 1.0},
        "profile": [{"length_m": 1000, "lift_m": 50}],
        "idlers": {
            "carry": {"spacing_m": 1.25, "roll_diameter_m": 0.133, "rolls": 3, "trough_deg": 35,
                      "rotating_mass_kg": 12.5, "seal_drag_n": 5.0},
            "return": {"spacing_m": 2.5, "roll_diameter_m": 0.133, "rolls": 1,
                       "rotating_mass_kg": 7.5, "seal_drag_n": 3.0},
        },
        "drives": [{"position": "head", "wrap_deg": 200, "friction": 0.35, "share": 1.0,
                    "pulley_diameter_m": 1.0}],
        "takeup": {"type": "gravity", "position": "tail", "mass_kg": "auto"},
        "sag_limit_pct": {"carry": 3.0, "return": 5.0},
        "accessories": {"head_kn": 1.0, "tail_kn": 0.5},
    }
    for key, val in over.items():
        d[key] = val
    return d


@pytest.fixture
def hand_dict():
    return hand_conveyor_dict()


@pytest.fixture
def hand_conveyor():
    from beltstudy.engine.conveyor import parse_conveyor

    return parse_conveyor(hand_conveyor_dict())
