"""The controlled stop a coast's high-stress words offer, confirmed by rerunning the cycle
(``engine/run.py``, ``_controlled_stop_time``)."""

from __future__ import annotations

import re

from beltstudy.engine.conveyor import Scenario, parse_conveyor
from beltstudy.engine.run import run_one


def plant_belt() -> dict:
    """A 350 m fabric incline rising 18 m (EP400/3, 0.65 m, 150 t/h at 2 m/s), one vfd head
    drive with a light shaft (30 kg m2) and a screw take-up: it coasts to rest in about 4.2 s,
    under 5 wave loop times (5 x 1.92 s)."""
    return {
        "name": "plant-350", "speed_m_s": 2.0,
        "belt": {"type": "EP400/3", "width_m": 0.65, "compound": "standard"},
        "material": {"capacity_t_h": 150, "density_t_m3": 1.3, "loading_speed_m_s": 0.0},
        "profile": [{"length_m": 350, "lift_m": 18}],
        "idlers": {"carry": {"spacing_m": 1.2, "roll_diameter_m": 0.102, "rolls": 3,
                             "trough_deg": 30, "cema_class": "B"},
                   "return": {"spacing_m": 3.0, "roll_diameter_m": 0.102, "rolls": 1,
                              "cema_class": "B"}},
        "drives": [{"position": "head", "wrap_deg": 190, "friction": 0.3, "share": 1.0,
                    "pulley_diameter_m": 0.5, "inertia_kg_m2": 30, "torque_limit": 1.6}],
        "takeup": {"type": "fixed", "position": "tail", "pretension_kn": "auto"},
        "holdback": True,
        "sag_limit_pct": {"carry": 1.5, "return": 3.0},
        "accessories": {"head_kn": 0.3, "tail_kn": 0.2},
    }


def test_the_controlled_stop_a_coast_is_offered_stops_in_5_wave_loop_times():
    """The coast's words offered "stop.time_s at least 11 s (enough for a belt that follows its
    s-curve, at rest from 0.884 of it ...)": asked, the belt stopped in 8.77 s, under the
    9.59 s of 5 wave loop times (its mean speed rested at 0.80 of the curve), still a
    high-stress stop. The cycle is rerun with the controlled stop, the time scaled by what
    each rerun gave, and the words name the time that met 5 loops. Checked by a run of its
    own at that time: its stop takes at least 5 wave loop times."""
    conv = parse_conveyor(plant_belt())
    coast = run_one(conv, Scenario(stop={"mode": "coast"}), model="din", remedy=True).summary
    need = 5.0 * coast["wave_loop_time_s"]
    assert coast["stop_time_s"] < need
    m = re.search(r"a controlled stop \(vfd drives\) would be slower than that, with "
                  r"stop\.time_s of ([\d.]+) s \(this cycle rerun with the controlled stop: "
                  r"([^()]*), at least 5 wave loop times", coast["message"])
    assert m, coast["message"]
    asked = float(m.group(1))
    # the s-curve's own least time (need / 0.884, rounded up) was a rerun that fell short
    first = re.match(r"([\d.]+) s stopped it in ([\d.]+) s", m.group(2))
    assert first and float(first.group(1)) < asked and float(first.group(2)) < need
    ctrl = run_one(conv, Scenario(stop={"mode": "controlled", "time_s": asked}),
                   model="din").summary
    assert ctrl["stop_time_s"] >= need, (ctrl["stop_time_s"], need)
    assert "high-stress stop" not in ctrl["message"]
