"""The design report's conveyor table says what the study's runs say: a brake on a drive's
shaft is placed at that drive, and a belt.type: auto conveyor has its capacity check (the
runs carry fill_pct; the table had dropped it)."""

from __future__ import annotations

from beltstudy.engine import capacity, parse_conveyor, with_belt
from beltstudy.service.door.studyfile import resolve_study
from beltstudy.service.web.report import _conveyor_section, _fill


def _conveyor(**over) -> dict:
    conv = {
        "name": "tiny",
        "speed_m_s": 2.5,
        "belt": {"type": "EP630/4", "width_m": 0.8},
        "material": {"capacity_t_h": 300, "density_t_m3": 1.0},
        "profile": [{"length_m": 150, "lift_m": 4}, {"length_m": 150, "lift_m": 8}],
        "idlers": {"carry": {"spacing_m": 1.2, "trough_deg": 30},
                   "return": {"spacing_m": 3.0, "rolls": 1}},
        "drives": [{"position": "head", "pulley_diameter_m": 0.6, "inertia_kg_m2": 20}],
    }
    conv.update(over)
    return conv


def test_a_brake_on_a_drive_shaft_is_placed_at_that_drive():
    """brakes: [{drive: 2}] printed an empty position cell (the brake has no position)."""
    conv = parse_conveyor(_conveyor(
        drives=[{"position": "head", "share": 0.6, "pulley_diameter_m": 0.6},
                {"position": "carry", "at_m": 200, "share": 0.4, "pulley_diameter_m": 0.6}],
        brakes=[{"position": "head", "force_kn": 5, "delay_s": 0.5},
                {"drive": 2, "force_kn": 4, "delay_s": 1.0}])).model_dump(mode="json",
                                                                           by_alias=True)
    html = _conveyor_section(conv, None)
    assert '<td>2</td><td>drive 2 (carry at 200 m)</td><td class="num ">4</td>' in html
    assert '<td>1</td><td>head</td><td class="num ">5</td>' in html


def test_an_auto_belt_has_its_capacity_check_on_the_belt_its_design_chose():
    """belt: {type: auto}: the report's capacity check raised on the unchosen belt and was
    left out, while every run of the study carries fill_pct (66.6 % for a 1 m belt probed
    through every door); it is now the fill on the design's belt, which depends on the width
    and trough alone."""
    study = resolve_study({"name": "auto-belt-fill", "dynamics": False,
                           "conveyor": _conveyor(belt={"type": "auto", "kind": "fabric",
                                                       "width_m": 0.8}),
                           "grid": {"friction_model": ["din"]}}).to_json()
    chosen = study["designs"][0]["sizes"]["belt"]["type"]
    fill = _fill(study)
    assert fill is not None
    conv = with_belt(parse_conveyor(_conveyor(belt={"type": "auto", "kind": "fabric",
                                                    "width_m": 0.8})), chosen)
    assert fill["fill_pct"] == capacity(conv).fill_pct
    # the width and trough set it: any belt of that width fills it alike
    assert abs(fill["fill_pct"] - capacity(parse_conveyor(_conveyor())).fill_pct) < 1e-12
    assert "capacity check (ISO 5048)" in _conveyor_section(study["conveyor"], fill)


def test_an_auto_belt_s_verdicts_say_where_the_tension_is():
    """belt: {type: auto}: the verdict table's 'where' cell was empty for every tension of
    the study (the report's loop could not be cut on the unchosen belt), while a given belt
    said 'carry, 1 200 m from the tail'. On the tiny conveyor (300 m of carry, then the head
    drive pulley of 0.6 m, its arc more than 0.5 m) 150 m is on the carry and 300.5 m on the
    head pulley."""
    from beltstudy.service.web.numbers import UNIT_SPACE
    from beltstudy.service.web.report import _locator, _where_on_loop

    study = resolve_study({"name": "auto-belt-where", "dynamics": False,
                           "conveyor": _conveyor(belt={"type": "auto", "kind": "fabric",
                                                       "width_m": 0.8}),
                           "grid": {"friction_model": ["din"]}}).to_json()
    locate = _locator(study)
    assert locate is not None
    assert _where_on_loop(locate, 150.0) == f"carry, 150{UNIT_SPACE}m from the tail"
    assert _where_on_loop(locate, 300.5) == "head pulley"
