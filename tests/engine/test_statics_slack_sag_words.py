"""A strand whose steady tension is at or below zero has no sag ratio: h/S = w / T is taken
as w / max(T, 1 N), which printed 'sag on the return strand 12653.77 % exceeds
sag_limit_pct.return = 3.00 %' for a 2 km, 100 m lift ST2000 belt on a 300 kg take-up. The
warning now says the strand is slack there, and keeps the tension that meets the limit
(DIN 22101: h/S = g m' cos(a) S / (8 T))."""
from __future__ import annotations

import math
import re

from beltstudy.engine.conveyor import parse_conveyor
from beltstudy.engine.statics import solve_steady

G = 9.81

STEEP = {  # 150 m, 40 m lift, EP630/4 5+2, 0.8 m
    "name": "steep-fabric", "speed_m_s": 2.5,
    "belt": {"type": "EP630/4", "width_m": 0.8, "top_cover_mm": 5, "bottom_cover_mm": 2},
    "material": {"capacity_t_h": 250, "density_t_m3": 1.6},
    "profile": [{"length_m": 150, "lift_m": 40}],
    "idlers": {"carry": {"spacing_m": 1.2, "roll_diameter_m": 0.102, "rolls": 3,
                         "trough_deg": 35, "cema_class": "C"},
               "return": {"spacing_m": 3.0, "roll_diameter_m": 0.102, "rolls": 1,
                          "cema_class": "C"}},
    "drives": [{"position": "head", "wrap_deg": 200, "friction": 0.30, "share": 1.0,
                "pulley_diameter_m": 0.63, "inertia_kg_m2": 20, "rated_power_kw": 45,
                "torque_limit": 1.5, "control": "dol", "coupling": "fluid"}],
    "takeup": {"type": "gravity", "position": "tail", "mass_kg": 30, "travel_m": 2},
    "holdback": True,
    "accessories": {"head_kn": 0.3, "tail_kn": 0.2},
}


def test_a_slack_return_strand_is_named_slack_not_given_a_sag_percentage():
    # a 30 kg take-up, far below the 2 026 kg the slip limit needs
    msg = solve_steady(parse_conveyor(STEEP), model="din", n_elements=100).summary["message"]
    said = re.search(r"the return strand is slack \(tension (-[\d.]+) kN [^)]*\): its sag "
                     r"there has no bound, far beyond sag_limit_pct.return = 3.00 %; "
                     r"([\d.]+) kN there keeps it within", msg)
    assert said, msg
    assert float(said.group(1)) <= 0.0
    # hand: belt mass (6.6 kg/m2 carcass + 7 mm of cover at 1.15 kg/m2/mm) x 0.8 m, return
    # idlers 3 m apart, 40 m lift over 150 m of belt
    m_belt = (6.6 + 7 * 1.15) * 0.8
    cos_a = math.sqrt(1.0 - (40.0 / 150.0) ** 2)
    need_kn = G * m_belt * cos_a * 3.0 / 8.0 / 0.03 / 1e3
    assert abs(float(said.group(2)) - need_kn) <= 0.01, (said.group(2), need_kn)  # 3 figures
    assert "sag on the return strand" not in msg
    # a strand in tension keeps its percentage
    assert re.search(r"sag on the carry strand [\d.]+ % exceeds sag_limit_pct.carry", msg), msg
