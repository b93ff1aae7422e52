"""``belt.type: auto`` is the lightest catalogue belt that passes the steady and the transient
safety factors (SPEC 7.1). The steady checks (running, and DIN 22101's rigid-body start-up)
picked ST1000 for a 500 m, 25 m incline on a dol drive behind a 20 t take-up, whose stress
waves then ran it at a transient safety factor of 2.93 against 4.47, and its note called
ST1000 the lightest belt that passes. The run now goes on to the heavier catalogue belts and
is of the first whose own run passes."""
from __future__ import annotations

from beltstudy.engine.beltselect import candidates, with_belt
from beltstudy.engine.conveyor import Scenario, parse_conveyor
from beltstudy.engine.run import run_one, transient_safety_min


def _incline(belt: dict) -> dict:
    idler = {"roll_diameter_m": 0.152}
    return {
        "name": "short", "speed_m_s": 4.5, "belt": belt,
        "material": {"capacity_t_h": 2000, "density_t_m3": 1.6, "loading_speed_m_s": 0.0},
        "profile": [{"length_m": 500, "lift_m": 25}],
        "idlers": {"carry": {**idler, "spacing_m": 1.5, "rolls": 3, "trough_deg": 35,
                             "cema_class": "D"},
                   "return": {**idler, "spacing_m": 3.0, "rolls": 1, "cema_class": "C"}},
        "drives": [{"position": "head", "wrap_deg": 210, "friction": 0.35, "share": 1.0,
                    "pulley_diameter_m": 1.25, "inertia_kg_m2": 1500, "rated_power_kw": 1250,
                    "torque_limit": 1.5, "control": "dol"}],
        "takeup": {"type": "gravity", "position": "tail", "mass_kg": 20000, "travel_m": 10},
        "holdback": True, "sag_limit_pct": {"carry": 1.5, "return": 3.0},
        "accessories": {"head_kn": 2.0, "tail_kn": 1.0},
    }


def test_an_auto_belt_passes_the_transient_safety_factor_of_its_run():
    scn = Scenario.model_validate({"start": {"time_s": 10}, "run_s": 10})
    auto = parse_conveyor(_incline({"type": "auto", "kind": "steel_cord", "width_m": 1.2}))
    res = run_one(auto, scn, model="din")
    s = res.summary
    need = transient_safety_min(auto, "steel")
    chosen = s["belt_type_used"]
    assert s["safety_factor_dyn"] >= need, s["message"]
    # every lighter catalogue belt of the kind fails in its own run, steady or transient
    ids = [c[0] for c in candidates(auto)]
    for lighter in ids[:ids.index(chosen)]:
        run = run_one(with_belt(auto, lighter), scn, model="din").summary
        assert run["safety_factor_dyn"] < need or run["safety_factor"] < 6.7, lighter
    # the words: the steady choice, its transient factor, the belt of the run
    assert "note: belt.type auto (steel_cord): ST1000, the lightest catalogue belt that " \
        "passes the steady checks, ran at a transient safety factor of 2.93 against the " \
        "minimum 4.47" in s["message"], s["message"]
    assert f"{chosen} (" in s["message"] and "is the belt of this run" in s["message"]
    # the same belt given runs alike (the auto run is that run, its words aside)
    given = run_one(with_belt(auto, chosen), scn, model="din").summary
    assert given["safety_factor_dyn"] == s["safety_factor_dyn"]
    assert given["t_max_dyn_kn"] == s["t_max_dyn_kn"]
