"""One output, one width: where ``belt.type: auto`` finds no catalogue belt that passes, its
warning names the width at which the heaviest belt passes, solved again at that width with the
belt's own weight (engine.beltselect._width_needed), and the safety factor's warning beside it
named the same belt's width at the present tensions: 'at these tensions ST5400 needs a width of
at least 1.46 m (more with its own weight)' beside 'ST5400 passes at a width of 1.49 m'. The
safety factor's words now give the selection's figure.

The figure is checked by the definition of the safety factor (DIN 22101, PHYSICS section 1):
S = k_N B / T_max, with the catalogue rating k_N = 5400 kN/m of ST5400 and T_max the largest
steady tension of the belt at that width, at least 6.7 running and 2/3 x 6.7 at start-up, and
below 6.7 a centimetre narrower.
"""

from __future__ import annotations

import re

from beltstudy.engine.beltselect import BeltChoice, Candidate, run_message
from beltstudy.engine.conveyor import Scenario, parse_conveyor
from beltstudy.engine.run import run_one
from beltstudy.engine.statics import solve_steady, startup_tensions

#: A 3 km, 186 m decline carrying 6 000 t/h at 4 m/s on 1.2 m: no steel belt of the
#: catalogue passes at that width.
HEAVY = {
    "name": "heavy-auto", "speed_m_s": 4.0,
    "belt": {"type": "auto", "kind": "steel_cord", "width_m": 1.2},
    "material": {"capacity_t_h": 6000, "density_t_m3": 1.7, "loading_speed_m_s": 0.0},
    "profile": [{"length_m": 1200, "lift_m": -60}, {"length_m": 1800, "lift_m": -126}],
    "idlers": {"carry": {"spacing_m": 1.2, "roll_diameter_m": 0.152, "rolls": 3,
                         "trough_deg": 35, "cema_class": "D"},
               "return": {"spacing_m": 3.0, "roll_diameter_m": 0.152, "rolls": 1,
                          "cema_class": "C"}},
    "drives": [{"position": "head", "wrap_deg": 210, "friction": 0.35, "share": 1.0,
                "pulley_diameter_m": 1.25, "inertia_kg_m2": 1500, "rated_power_kw": 1000,
                "torque_limit": 1.5}],
    "takeup": {"type": "gravity", "position": "tail", "mass_kg": "auto", "travel_m": 12},
    "brakes": [{"position": "head", "force_kn": "auto", "delay_s": 1.0}],
    "holdback": False,
    "sag_limit_pct": {"carry": 1.5, "return": 3.0},
    "accessories": {"head_kn": 2.0, "tail_kn": 1.0},
}
RATING_KN_M = 5400.0  # ST5400, engine/data/belts.csv
SF_MIN = 6.7
WIDTH = re.compile(r"ST5400 (?:passes at a width of|(?:needs|would need) a width of at least) "
                   r"([0-9.]+) m")


def _factors(width_m: float) -> tuple[float, float]:
    """Running and start-up safety factors of ST5400 at ``width_m``, by S = k_N B / T_max."""
    st = solve_steady(parse_conveyor({**HEAVY, "belt": {"type": "ST5400", "width_m": width_m}}),
                      model="din")
    return (RATING_KN_M * width_m / (float(st.tension_n.max()) / 1e3),
            RATING_KN_M * width_m / (float(startup_tensions(st).max()) / 1e3))


def test_the_safety_factor_words_give_the_width_the_selection_solved():
    s = run_one(parse_conveyor(HEAVY), Scenario(), model="din", dynamics=False).summary
    msg = s["message"]
    assert "no catalogue belt passes the safety factors; the heaviest, ST5400" in msg, msg
    assert "belt safety factor" in msg and "is below the minimum 6.70" in msg, msg
    widths = {float(w) for w in WIDTH.findall(msg)}
    assert len(WIDTH.findall(msg)) >= 2, msg  # the safety factor's words and the selection's
    assert len(widths) == 1, msg  # one figure
    (w,) = widths
    # by hand: at w the belt passes running and at start-up, a centimetre narrower it fails
    running, start = _factors(w)
    assert running >= SF_MIN and start >= 2.0 / 3.0 * SF_MIN, (w, running, start)
    assert _factors(round(w - 0.01, 2))[0] < SF_MIN
    # and it is more than the estimate at the present tensions (1.2 m x 6.7 / S at 1.2 m)
    at_12 = _factors(1.2)[0]
    assert w > 1.2 * SF_MIN / at_12


def _choice(width_needed_m):
    c = Candidate("ST5400", 63.8, 6480.0, 1172.1, 1100.0, 5.53, 5.89, "din", "din", False)
    return BeltChoice("steel_cord", SF_MIN, 2.0 / 3.0 * SF_MIN, (c,), c, None, False, 1.2,
                      width_needed_m)


def test_without_a_solved_width_both_give_the_selections_estimate():
    """No solved width (not found within its tries): the safety factor's estimate (running,
    this case) gives way to the selection's, 1.2 m x the larger shortfall of running (6.7 /
    5.53) and start-up (4.467 / 5.89), up to the centimetre: 1.2 x 1.2116 = 1.4539 -> 1.46 m."""
    words = ("belt safety factor 5.53 is below the minimum 6.70 (...): a belt rated at least "
             "6545 kN/m at this width (stronger than any catalogue steel belt: ...; at these "
             "tensions ST5400 needs a width of at least 1.45 m (more with its own weight), or "
             "a belt of its own)")
    s = {"status": "warning", "message": words}
    run_message(s, _choice(None))
    found = {float(w) for w in WIDTH.findall(s["message"])}
    assert found == {1.46}, s["message"]
    # a solved width replaces the estimate in both
    s = {"status": "warning", "message": words}
    run_message(s, _choice(1.49))
    assert {float(w) for w in WIDTH.findall(s["message"])} == {1.49}, s["message"]
    assert "solved again at that width" in s["message"].split("; belt.type auto")[0]
