"""A take-up remedy names the steady checks its take-up breaks that the run's did not
(``engine/run.py``, ``_takeup_steady_words``)."""

from __future__ import annotations

from beltstudy.engine.conveyor import Scenario, parse_conveyor
from beltstudy.engine.statics import solve_steady


def curved_route(**takeup) -> dict:
    """A 2.2 km steel-cord route (ST1250, 1000 t/h at 4 m/s): 600 m falling 12 m into a
    concave curve, 900 m rising 54 m round a horizontal curve of R 1500 m (superelevation
    3 deg), 700 m rising 7 m; a head drive and a head gravity take-up."""
    return {
        "name": "curved-2200", "speed_m_s": 4.0,
        "belt": {"type": "ST1250", "width_m": 1.0, "compound": "standard"},
        "material": {"capacity_t_h": 1000, "density_t_m3": 1.2, "surcharge_deg": 20},
        "profile": [{"length_m": 600, "lift_m": -12, "curve_radius_m": 800},
                    {"length_m": 900, "lift_m": 54, "horizontal_radius_m": 1500,
                     "superelevation_deg": 3},
                    {"length_m": 700, "lift_m": 7}],
        "idlers": {"carry": {"spacing_m": 1.5, "roll_diameter_m": 0.127, "rolls": 3,
                             "trough_deg": 35, "cema_class": "C"},
                   "return": {"spacing_m": 3.0, "roll_diameter_m": 0.127, "rolls": 1,
                              "cema_class": "C"}},
        "drives": [{"position": "head", "wrap_deg": 210, "friction": 0.35, "share": 1.0,
                    "pulley_diameter_m": 1.0, "inertia_kg_m2": 400, "torque_limit": 1.5}],
        "takeup": {"type": "gravity", "position": "head", "mass_kg": "auto", "travel_m": 15,
                   **takeup},
        "holdback": True,
        "sag_limit_pct": {"carry": 1.5, "return": 3.0},
        "accessories": {"head_kn": 1.5, "tail_kn": 0.8},
    }


def test_a_remedy_s_take_up_names_the_horizontal_curve_it_pulls_the_belt_off():
    """The route's coast stop sagged past 1.5 % and its remedy asked for a 21,388 kg take-up,
    naming the safety factor it lowers (6.42 against 6.70) and nothing else; at that take-up
    the belt runs to the inside of its horizontal curve (175.0 kN at the curve's end against
    the 141.4 kN its loaded weight holds there), which the auto take-up does not. The remedy
    now says so, and says nothing where the take-up breaks no other steady check."""
    from beltstudy.engine.run import _takeup_steady_words

    conv = parse_conveyor(curved_route())
    scn = Scenario(stop={"mode": "coast"})
    auto = solve_steady(conv, model="din")
    assert not any(w.startswith("horizontal curve") for w in auto.warnings), auto.warnings
    heavy = solve_steady(parse_conveyor(curved_route(mass_kg=21388)), model="din")
    (curve,) = [w for w in heavy.warnings if w.startswith("horizontal curve 1")]
    words = _takeup_steady_words(conv, scn, "din", None, 21388.0, True, auto.warnings)
    assert words.startswith("; with the take-up of 21,388 kg the steady state also warns: "
                            "horizontal curve 1 (profile.1, 600 to 1500 m from the tail"), words
    assert curve.split("; ")[0] in words and "belt safety factor" not in words
    # a take-up the curve still holds breaks nothing new
    assert _takeup_steady_words(conv, scn, "din", None, auto.takeup_mass_kg * 1.05, True,
                                auto.warnings) == ""
