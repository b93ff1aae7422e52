"""``belt.type: auto``: the lightest catalogue belt of a kind that passes the running and
start-up safety factors (engine/beltselect.py, docs/belts.md).

Every verdict is checked by hand from the definitions: the safety factor is the catalogue
rating k_N [kN/m] x the width B [m] over the largest tension [kN] (DIN 22101; PHYSICS section
1), the running minimum 6.7 for steel cord and 10 for fabric (the project's defaults,
``SAFETY_FACTOR_MIN``), the start-up minimum 2/3 of it; the belt mass per metre is (carcass +
1.15 kg/m2/mm x covers) x B (PHYSICS section 4).
"""

from __future__ import annotations

import numpy as np
import pytest

from beltstudy.engine import catalog
from beltstudy.engine.beltselect import (
    SteadyCase,
    candidates,
    resolve_auto_belt,
    run_cases,
    select_belt,
    with_belt,
)
from beltstudy.engine.conveyor import load_mapping, parse_conveyor
from beltstudy.engine.errors import InputError
from beltstudy.engine.loop import rotating_parts
from beltstudy.engine.run import run_one, transient_safety_min
from beltstudy.engine.statics import solve_steady, startup_tensions
from tests.conftest import CONVEYORS, hand_conveyor_dict

STEEL_MIN, FABRIC_MIN = 6.7, 10.0


def auto_file(name: str, kind: str = "steel_cord", **belt) -> dict:
    """An example conveyor file with ``belt.type: auto`` (width and covers kept)."""
    d = load_mapping(CONVEYORS / f"{name}.yaml")
    d["belt"] = {**d["belt"], "type": "auto", "kind": kind, **belt}
    return d


def hand_factors(conv, belt_id: str, model: str) -> tuple[float, float]:
    """Running and start-up safety factors of one catalogue belt by the definition:
    k_N B / max T, the tensions of that belt's own steady solve (its masses, its take-up)."""
    trial = with_belt(conv, belt_id)
    res = solve_steady(trial, model=model)
    rating_kn = catalog.belts()[belt_id].rating_kn_m * conv.belt.width_m
    return (rating_kn / (res.tension_n.max() / 1e3),
            rating_kn / (startup_tensions(res).max() / 1e3))


@pytest.mark.parametrize("name, model", [("overland-4km", "din"), ("overland-4km", "nonlin"),
                                         ("overland-16km", "nonlin")])
def test_example_overlands_pick_a_belt_that_passes_and_the_next_lighter_fails(name, model):
    conv = parse_conveyor(auto_file(name))
    choice = select_belt(conv, [SteadyCase(model)])
    assert choice.passed and choice.lighter is not None
    start_min = 2.0 / 3.0 * STEEL_MIN
    sf, sf_start = hand_factors(conv, choice.belt_id, model)
    assert sf >= STEEL_MIN and sf_start >= start_min
    assert choice.chosen.safety_factor == pytest.approx(sf, rel=1e-9)
    assert choice.chosen.safety_factor_start == pytest.approx(sf_start, rel=1e-9)
    lt, lt_start = hand_factors(conv, choice.lighter.id, model)
    assert lt < STEEL_MIN or lt_start < start_min
    # the lighter one is the one just below in mass per metre (PHYSICS 4), steel cord only
    masses = {}
    for belt_id, row in catalog.belts().items():
        if row.kind == "steel":
            masses[belt_id] = (row.carcass_mass_kg_m2 + 1.15 * (conv.belt.top_cover_mm
                               + conv.belt.bottom_cover_mm)) * conv.belt.width_m
    order = sorted(masses, key=masses.get)
    assert order.index(choice.lighter.id) == order.index(choice.belt_id) - 1
    # and every belt lighter than it fails too: the choice is the lightest that passes
    for belt_id in order[:order.index(choice.belt_id)]:
        a, b = hand_factors(conv, belt_id, model)
        assert a < STEEL_MIN or b < start_min, belt_id
    note = choice.note()
    assert choice.belt_id in note and choice.lighter.id in note and "fails" in note


def test_the_belt_changes_the_masses_tensions_and_take_up():
    """Each candidate is its own steady solve: a heavier belt has a larger belt mass, a
    larger largest tension and (auto) another counterweight."""
    conv = parse_conveyor(auto_file("overland-4km"))
    light = solve_steady(with_belt(conv, "ST1000"), model="din").summary
    heavy = solve_steady(with_belt(conv, "ST5400"), model="din").summary
    # (32.5 - 7.4) kg/m2 x 1.2 m more belt (same covers)
    assert heavy["belt_mass_kg_m"] - light["belt_mass_kg_m"] == pytest.approx(
        (32.5 - 7.4) * 1.2, rel=1e-9)
    assert heavy["t_max_kn"] > light["t_max_kn"]
    assert heavy["takeup_mass_kg"] != pytest.approx(light["takeup_mass_kg"], rel=1e-3)


def test_none_passes_uses_the_heaviest_with_a_warning():
    """overland-16km under DIN's f = 0.020 (default) needs more than ST5400 at 1.2 m."""
    conv = parse_conveyor(auto_file("overland-16km"))
    choice = select_belt(conv, [SteadyCase("din")])
    assert not choice.passed and choice.belt_id == "ST5400"
    sf, _ = hand_factors(conv, "ST5400", "din")
    assert sf < STEEL_MIN
    assert "no catalogue belt passes" in choice.warning() and choice.note() == ""
    # the width it needs: more than B x 6.7 / S at these tensions (the factor is k_N B / T_max
    # and a wider belt pulls harder), solved again at the width named
    assert choice.width_needed_m > 1.2 * STEEL_MIN / sf
    assert f"ST5400 passes at a width of {choice.width_needed_m:.2f} m" in choice.warning()
    run = run_one(conv, _scenario(), model="din", dynamics=False)
    assert run.summary["status"] == "warning"
    assert run.summary["belt_type_used"] == "ST5400"
    assert "no catalogue belt passes" in run.summary["message"]


def _scenario():
    from beltstudy.engine.conveyor import parse_scenario

    return parse_scenario({})


def test_short_conveyor_picks_the_lightest_catalogue_belt():
    """A 60 m conveyor's tensions are a few kN: the lightest belt of each kind passes."""
    for kind, lightest in (("fabric", "EP400/3"), ("steel_cord", "ST1000")):
        conv = parse_conveyor(hand_conveyor_dict(
            belt={"type": "auto", "kind": kind, "width_m": 0.8},
            profile=[{"length_m": 60, "lift_m": 3}]))
        assert candidates(conv)[0][0] == lightest
        choice = select_belt(conv, [SteadyCase("din")])
        assert choice.belt_id == lightest and choice.passed and choice.lighter is None
        res = solve_steady(with_belt(conv, lightest), model="din")
        sf = catalog.belts()[lightest].rating_kn_m * 0.8 / (res.tension_n.max() / 1e3)
        assert sf >= (FABRIC_MIN if kind == "fabric" else STEEL_MIN)
        assert "lightest" in choice.note()


def test_fabric_kind_picks_a_fabric_belt():
    conv = parse_conveyor(auto_file("fabric-1km", kind="fabric"))
    choice = select_belt(conv, [SteadyCase("din")])
    assert choice.passed
    assert catalog.belts()[choice.belt_id].kind == "fabric"
    assert {c.id for c in choice.tried} <= {k for k, r in catalog.belts().items()
                                            if r.kind == "fabric"}
    sf, sf_start = hand_factors(conv, choice.belt_id, "din")
    assert sf >= FABRIC_MIN and sf_start >= 2.0 / 3.0 * FABRIC_MIN
    assert choice.safety_factor_min == FABRIC_MIN


def test_conveyor_safety_factor_min_is_the_minimum():
    """A lower minimum of the file picks a lighter belt on overland-4km (din): ST1600's 6.50
    passes 6.0."""
    conv = parse_conveyor({**auto_file("overland-4km"), "safety_factor_min": 6.0})
    choice = select_belt(conv, [SteadyCase("din")])
    assert choice.safety_factor_min == 6.0 and choice.safety_factor_start_min == 4.0
    assert transient_safety_min(conv, "steel") == pytest.approx(4.0)
    sf, sf_start = hand_factors(conv, choice.belt_id, "din")
    assert sf >= 6.0 and sf_start >= 4.0
    lt, lt_start = hand_factors(conv, choice.lighter.id, "din")
    assert lt < 6.0 or lt_start < 4.0


def test_startup_tensions_by_hand():
    """DIN 22101's start-up force p_A Te (p_A = 1.5) on a level belt, head drive, tail take-up:
    the excess 0.5 Te accelerates every moving mass M at a = 0.5 Te / M; the take-up holds
    its mean tension, so the tension at the head's tight side rises by the inertia force of
    what lies between the take-up and it, the loaded carry strand (m'_G + m'_L + m'_R) L:
    dT1 = 0.5 Te (20 + 50 + 10) kg/m x 1000 m / M, with M = 103 000 kg of belt, load and
    idlers plus the rotating parts (pulleys, motor). The tail pulley's half share is left
    out: 2 % tolerance."""
    conv = parse_conveyor(hand_conveyor_dict(profile=[{"length_m": 1000, "lift_m": 0}]))
    res = solve_steady(conv, model="din", params={"f_carry": 0.02, "f_return": 0.02, "c": 1.0})
    T, S = res.tension_n, startup_tensions(res)
    i = int(np.argmax(T))
    m_total = 103_000.0 + rotating_parts(conv, res.loop).total_kg
    assert S[i] - T[i] == pytest.approx(0.5 * res.te_n * 80_000.0 / m_total, rel=0.02)
    # the slip_start sizing uses the same tensions: at the auto take-up's governing
    # constraint the drive sits at its capstan limit at start-up
    assert res.takeup_governed_by == "slip_start"
    assert res.summary["slip_margin_start"] == pytest.approx(1.0, rel=1e-6)


def test_run_one_uses_and_reports_the_choice():
    conv = parse_conveyor(auto_file("overland-4km"))
    res = run_one(conv, _scenario(), model="din", dynamics=False)
    choice = select_belt(conv, [SteadyCase("din")])
    s = res.summary
    assert s["belt_type_used"] == choice.belt_id
    assert s["belt_rating_kn"] == pytest.approx(
        catalog.belts()[choice.belt_id].rating_kn_m * 1.2, rel=1e-12)
    assert s["status"] == "ok" and "note: belt.type auto" in s["message"]
    assert choice.lighter.id in s["message"]
    # a given belt reports its type too, and no note
    given = run_one(parse_conveyor(load_mapping(CONVEYORS / "overland-4km.yaml")), _scenario(),
                    model="din", dynamics=False).summary
    assert given["belt_type_used"] == "ST2000" and "belt.type auto" not in given["message"]


def test_a_part_load_run_picks_at_full_load_too():
    """The belt is installed once: an empty run picks the belt the full load needs."""
    conv = parse_conveyor(auto_file("overland-4km"))
    cases = run_cases(conv, "din", None, 20.0, "empty")
    assert [c.load for c in cases] == ["empty", "full"]
    assert resolve_auto_belt(conv, cases)[1].belt_id == select_belt(
        conv, [SteadyCase("din")]).belt_id
    assert len(run_cases(conv, "din", None, 20.0, "full")) == 1


def test_given_belt_unchanged():
    conv = parse_conveyor(load_mapping(CONVEYORS / "overland-4km.yaml"))
    assert resolve_auto_belt(conv, [SteadyCase("din")]) == (conv, None)


@pytest.mark.parametrize("belt, needle", [
    ({"type": "auto"}, r"type: auto needs belt\.kind.*steel_cord.*fabric"),
    ({"type": "auto", "kind": "steel"}, r"belt\.kind: Input should be 'steel_cord' or 'fabric'"),
    ({"type": "auto", "kind": "steel_cord", "rating_kn_m": 2000},
     r"type: auto takes no rating_kn_m"),
    ({"type": "auto", "kind": "fabric", "modulus_kn_m": 5000, "carcass_mass_kg_m2": 9},
     r"type: auto takes no modulus_kn_m, carcass_mass_kg_m2"),
    ({"type": "ST2000", "kind": "fabric"}, r"belt\.kind: fabric does not match ST2000"),
])
def test_bad_belt_input_is_named(belt, needle):
    d = load_mapping(CONVEYORS / "overland-4km.yaml")
    with pytest.raises(InputError, match=needle):
        parse_conveyor({**d, "belt": {**d["belt"], **belt}})


def test_auto_is_not_a_belt():
    conv = parse_conveyor(auto_file("overland-4km"))
    with pytest.raises(InputError, match="belt.type: auto is a choice"):
        solve_steady(conv, model="din")


def test_catalogue_kinds_are_the_file_kinds():
    assert {r.kind for r in catalog.belts().values()} == set(catalog.KIND_OF_FILE.values())


def test_a_factor_just_below_its_minimum_is_not_printed_equal_to_it():
    """A candidate at 6.5487 against a minimum 6.549 (a file's ``safety_factor_min``) fails;
    at two decimals the note read "6.55 running < 6.55 (margin -0 %)". The pair is printed
    at the decimals that show it: 6.5487 < 6.5490, margin 100 (6.5487 / 6.549 - 1) =
    -0.005 %. A factor within the pass tolerance of its minimum reads equal and +0 %."""
    from beltstudy.engine.beltselect import Candidate
    c = Candidate("ST1600", 32.88, 1920.0, 293.2, 376.8, 6.5487, 5.10, "din", "din", False)
    words = c.factors(6.549, 2.0 / 3.0 * 6.549)
    assert words.startswith("6.5487 running < 6.5490 (margin -0.005 %")
    assert "5.10 at start-up >= 4.37 (margin +17 %" in words
    at = Candidate("ST1600", 32.88, 1920.0, 293.2, 376.8, 6.7 * (1 - 1e-12), 5.10, "din",
                   "din", True)
    assert at.factors(6.7, 4.4667).startswith("6.70 running >= 6.70 (margin +0 %")


def test_the_steady_safety_warning_prints_its_factor_below_its_minimum():
    """slope-5pct (ST2000, 1.2 m) runs at S = 2400 kN / T_max = 6.776. With
    ``safety_factor_min`` 1.00005 x that (6.7763) the steady warning read "belt safety factor
    6.78 is below the minimum 6.78"; the two now print apart. At the minimum up to float
    noise (S_min = S (1 + 1e-12)) the belt passes, as belt.type: auto's own test takes it,
    and the run has no safety warning."""
    import re

    d = load_mapping(CONVEYORS / "slope-5pct.yaml")
    sf = solve_steady(parse_conveyor(d), model="din").summary["safety_factor"]
    assert sf == pytest.approx(6.776, abs=1e-3)
    d["safety_factor_min"] = sf * 1.00005
    msg = solve_steady(parse_conveyor(d), model="din").message
    m = re.search(r"belt safety factor ([0-9.]+) is below the minimum ([0-9.]+)", msg)
    assert m is not None, msg
    assert float(m.group(1)) < float(m.group(2))
    d["safety_factor_min"] = sf * (1 + 1e-12)
    assert "belt safety factor" not in solve_steady(parse_conveyor(d), model="din").message


STEEP_FABRIC = {  # 300 m rising 50 m, fabric auto, a 10.5 running minimum
    "name": "c1-steep-fabric", "speed_m_s": 2.5,
    "belt": {"type": "auto", "kind": "fabric", "width_m": 1.0, "top_cover_mm": 6,
             "bottom_cover_mm": 3},
    "material": {"capacity_t_h": 800, "density_t_m3": 1.6},
    "profile": [{"length_m": 300, "lift_m": 50}],
    "idlers": {"carry": {"spacing_m": 1.2, "roll_diameter_m": 0.133, "rolls": 3,
                         "trough_deg": 35, "rotating_mass_kg": 18, "seal_drag_n": 1.0},
               "return": {"spacing_m": 3.0, "roll_diameter_m": 0.133, "rolls": 1,
                          "rotating_mass_kg": 10, "seal_drag_n": 1.0}},
    "drives": [{"position": "head", "wrap_deg": 200, "friction": 0.35, "share": 1.0,
                "pulley_diameter_m": 0.63, "inertia_kg_m2": 40, "rated_power_kw": 250,
                "torque_limit": 1.5}],
    "takeup": {"type": "gravity", "position": "tail", "mass_kg": "auto"},
    "holdback": True,
    "safety_factor_min": 10.5,
}


def test_the_pick_passes_every_case_on_the_take_up_installed_once():
    """A study installs an auto take-up once, the largest over its design cases (here DIN's
    start-up slip sets it); each candidate was judged with the take-up each case would size
    for itself, so EP1000/5 was picked at 10.51 >= 10.5 (CEMA, -20 C, on its own lighter
    take-up) and ran at 10.49 on the installed one. Judged on the installed take-up, the pick
    passes every case on it, by hand (rating x width / T_max), and the next lighter fails."""
    conv = parse_conveyor(STEEP_FABRIC)
    din = {"f_carry": 0.02, "f_return": 0.02}
    cases = [SteadyCase(m, din if m == "din" else {}, t, load, 40)
             for m in ("din", "cema") for t in (-20.0, 20.0) for load in ("full", "empty")]
    choice = select_belt(conv, cases)
    assert choice.passed
    picked = with_belt(conv, choice.belt_id)
    own = [solve_steady(picked, model=c.model, params=c.params, temperature_c=c.temperature_c,
                        load=c.load, n_elements=40) for c in cases]
    installed = max(r.takeup_mass_kg for r in own)
    held = parse_conveyor({**STEEP_FABRIC, "belt": {**STEEP_FABRIC["belt"],
                                                    "type": choice.belt_id},
                           "takeup": {**STEEP_FABRIC["takeup"], "mass_kg": installed}})
    rating_kn = catalog.belts()[choice.belt_id].rating_kn_m * 1.0
    for c in cases:
        res = solve_steady(held, model=c.model, params=c.params, temperature_c=c.temperature_c,
                           load=c.load, n_elements=40)
        assert rating_kn / (res.tension_n.max() / 1e3) >= 10.5 * (1 - 1e-9), c
    lighter = choice.lighter
    assert lighter is not None and not lighter.passes
    assert lighter.safety_factor < 10.5


def test_no_belt_passes_names_a_width_that_passes_when_solved_again():
    """6 km rising 430 m at 3 000 t/h on a 1 m steel-cord belt (DIN f 0.012): the strongest
    catalogue belt, ST5400, reaches 4.007 against 6.7. The width that scales its factor at
    fixed tensions, 1.0 x 6.7 / 4.007 = 1.672 m, was offered 'about 1.67 m' and gave 6.21 there
    (a wider belt is heavier and pulls harder). The width named is solved again with the
    belt's weight at it: the heaviest belt passes at it and fails a centimetre narrower."""
    d = {"name": "c2-overland-steel", "speed_m_s": 5.0,
         "belt": {"type": "auto", "kind": "steel_cord", "width_m": 1.0},
         "material": {"capacity_t_h": 3000, "density_t_m3": 1.8},
         "profile": [{"length_m": 3000, "lift_m": 30}, {"length_m": 3000, "lift_m": 400}],
         "idlers": {"carry": {"spacing_m": 1.5, "roll_diameter_m": 0.159, "rolls": 3,
                              "trough_deg": 35, "rotating_mass_kg": 22, "seal_drag_n": 1.3},
                    "return": {"spacing_m": 3.0, "roll_diameter_m": 0.159, "rolls": 2,
                               "trough_deg": 10, "rotating_mass_kg": 15, "seal_drag_n": 1.0}},
         "drives": [{"position": "head", "wrap_deg": 200, "friction": 0.35, "share": 0.5,
                     "pulley_diameter_m": 1.25},
                    {"position": "head", "wrap_deg": 180, "friction": 0.35, "share": 0.5,
                     "pulley_diameter_m": 1.25}],
         "takeup": {"type": "gravity", "position": "tail", "mass_kg": "auto"},
         "holdback": True}
    din = {"f_carry": 0.012, "f_return": 0.012}
    case = [SteadyCase("din", din, 20.0, "full", None)]
    choice = select_belt(parse_conveyor(d), case)
    assert not choice.passed and choice.belt_id == "ST5400"
    width = choice.width_needed_m
    assert width is not None and width > 1.0 * 6.7 / choice.chosen.safety_factor + 0.05
    assert f"ST5400 passes at a width of {width:.2f} m (belt.width_m, now 1 m" in (
        choice.warning())

    def factor(w):
        conv = parse_conveyor({**d, "belt": {"type": "ST5400", "width_m": w}})
        res = solve_steady(conv, model="din", params=din)
        return catalog.belts()["ST5400"].rating_kn_m * w / (res.tension_n.max() / 1e3)

    assert factor(width) >= 6.7 * (1 - 1e-9)
    assert factor(round(width - 0.01, 2)) < 6.7
