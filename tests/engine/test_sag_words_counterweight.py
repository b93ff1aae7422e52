"""The transient sag warning names the tension the take-up must add per strand and the
counterweight that gives it: 'the take-up must add at least 0.997 kN' did not say whether it
was the counterweight's weight (m g) or the tension on each of its strands (m g / 2), a
factor of two in the mass."""
from __future__ import annotations

import math
import re

import pytest

from beltstudy.engine.conveyor import Scenario, parse_conveyor
from beltstudy.engine.dynamics import DynamicsOptions, build_system, simulate
from beltstudy.engine.statics import solve_steady

G = 9.81

STEEP = {
    "name": "steep-fabric-dol", "speed_m_s": 2.5,
    "belt": {"type": "EP630/4", "width_m": 0.8, "top_cover_mm": 5, "bottom_cover_mm": 2},
    "material": {"capacity_t_h": 250, "density_t_m3": 1.6},
    "profile": [{"length_m": 150, "lift_m": 40}],
    "idlers": {"carry": {"spacing_m": 1.2, "roll_diameter_m": 0.108, "rolls": 3,
                         "trough_deg": 35, "cema_class": "C"},
               "return": {"spacing_m": 3.0, "roll_diameter_m": 0.108, "rolls": 1,
                          "cema_class": "C"}},
    "drives": [{"position": "head", "wrap_deg": 200, "friction": 0.30, "share": 1.0,
                "pulley_diameter_m": 0.63, "inertia_kg_m2": 20, "rated_power_kw": 45,
                "torque_limit": 1.5, "control": "dol", "coupling": "fluid"}],
    "takeup": {"type": "gravity", "position": "tail", "mass_kg": 2026, "travel_m": 2},
    "holdback": True,
    "accessories": {"head_kn": 0.3, "tail_kn": 0.2},
}


def test_the_sag_warning_names_the_tension_per_strand_and_the_counterweight():
    conv = parse_conveyor(STEEP)
    scn = Scenario(run_s=10, elements=100)  # a coast stop: the carry behind the tail sags
    st = solve_steady(conv, model="din", load=scn.load, n_elements=100)
    sys_ = build_system(conv, scn, st, DynamicsOptions())
    res = simulate(sys_, steady_summary=st.summary, conveyor=conv)
    m = re.search(r"transient sag on the carry strand ([\d.]+) % exceeds the limit 1.5 % \(low "
                  r"tension ([\d.]+) kN .*?so the take-up must add at least ([\d.]+) kN on each "
                  r"of its two strands \(a counterweight of at least ([\d,]+) kg, "
                  r"takeup.mass_kg, now ([\d,]+) kg\)", res.message)
    assert m, res.message
    add_kn = float(m.group(3))
    # by hand: the sag goes as 1 / T, so the span needs T_low x sag / limit; the take-up's
    # weight m g is shared by its two strands, so each kN on a strand is 2 kN of weight
    # (the message's figures are rounded to 3 significant figures)
    t_low_kn, sag = float(m.group(2)), float(m.group(1))
    assert add_kn == pytest.approx(t_low_kn * sag / 1.5 - t_low_kn, rel=2e-2)
    assert int(m.group(5).replace(",", "")) == 2026
    assert int(m.group(4).replace(",", "")) == math.ceil((2026 * G + 2e3 * add_kn) / G)
