"""The steady sag warning sizes the take-up for the slackest span, not for the first slack
one: every span at or below zero tension reads the same ratio, w / 1 N, so the largest ratio
tied at the first slack span and the words advised what that span needed. A 1500 m, -120 m
loaded ST1250 decline (regenerating) on a 5000 kg take-up read 'the carry strand is slack
(tension -0.479 kN 450 m from the tail ...) ... the take-up must hold at least 10.7 kN more
per strand', while the carry reaches -61.4 kN at the head; the advised 7182 kg still left it
slack (and the next run advised 10.4 kN more again)."""
from __future__ import annotations

import copy
import math
import re

from beltstudy.engine.conveyor import parse_conveyor
from beltstudy.engine.statics import solve_steady

G = 9.81

DECLINE = {  # 1500 m, -120 m, 1200 t/h at 4 m/s: regenerates loaded
    "name": "decline-regen-loaded", "speed_m_s": 4.0,
    "belt": {"type": "ST1250", "width_m": 1.0},
    "material": {"capacity_t_h": 1200, "density_t_m3": 1.5},
    "profile": [{"length_m": 1500, "lift_m": -120}],
    "idlers": {"carry": {"spacing_m": 1.2, "roll_diameter_m": 0.152, "rolls": 3,
                         "trough_deg": 35, "rotating_mass_kg": 18.0, "seal_drag_n": 6.7},
               "return": {"spacing_m": 3.0, "roll_diameter_m": 0.152, "rolls": 1,
                          "rotating_mass_kg": 9.0, "seal_drag_n": 4.0}},
    "drives": [{"position": "head", "wrap_deg": 210, "friction": 0.30, "share": 1.0,
                "pulley_diameter_m": 0.8, "inertia_kg_m2": 200, "rated_power_kw": 400}],
    "takeup": {"type": "gravity", "position": "tail", "mass_kg": 5000},
    "accessories": {"head_kn": 1.5, "tail_kn": 1.0},
}


def _hand_carry_head_tension_n(mass_kg: float) -> float:
    """DIN 22101 walk by hand: the carry's tension arriving at the head drive [N]."""
    m_g = 8.7 + 1.15 * (6 + 4)  # ST1250 carcass + 6 + 4 mm covers, 1 m wide [kg/m]
    m_l = 1200 / (3.6 * 4.0)
    cos_a = math.sqrt(1.0 - 0.08 ** 2)
    f_c = 0.02 * G * 1500 * (18.0 / 1.2 + (m_g + m_l) * cos_a)
    f_r = 0.02 * G * 1500 * (9.0 / 3.0 + m_g * cos_a)
    c = 1.06  # DIN 22101 C at L = 1500 m (PHYSICS section 2 table)
    sec_half = 0.5 * (c - 1.0) * (f_c + f_r)  # C(1500 m) = 1.06, half at each end
    t_tu = mass_kg * G / 2.0
    t_tail_out = t_tu + 0.5 * (sec_half + 1000.0)  # the take-up holds the mean at the tail
    return t_tail_out + f_c - (m_g + m_l) * G * 120.0


def test_the_sag_words_size_the_take_up_for_the_slackest_span():
    msg = solve_steady(parse_conveyor(DECLINE), model="din").summary["message"]
    said = re.search(r"the carry strand is slack \(tension (-[\d.]+) kN ([\d.]+) m from the "
                     r"tail on the carry\)[^;]*; ([\d.]+) kN there keeps it within \(the sag "
                     r"goes as 1 / T\), so the take-up must hold at least ([\d.]+) kN more", msg)
    assert said, msg
    t_head = _hand_carry_head_tension_n(5000.0)  # -61.44 kN by hand
    assert abs(float(said.group(1)) * 1e3 - t_head) <= 0.001 * abs(t_head) + 50.0
    assert float(said.group(2)) == 1500.0
    m_t = 8.7 + 11.5 + 1200 / 14.4
    need = G * m_t * math.sqrt(1 - 0.08 ** 2) * 1.2 / 8 / 0.015  # 10.12 kN
    more_kn = float(said.group(4))
    assert abs(more_kn * 1e3 - (need - t_head)) <= 0.01 * (need - t_head)  # 71.6, 3 figures
    # following the words clears the carry's sag warning
    fixed = copy.deepcopy(DECLINE)
    fixed["takeup"]["mass_kg"] = 5000 + math.ceil(2 * more_kn * 1e3 / G)
    after = solve_steady(parse_conveyor(fixed), model="din").summary["message"]
    assert "carry strand" not in after, after
