"""A custom belt (no catalogue ``type``) is of the ``belt.kind`` its file gives.

The kind of a custom belt was read from its modulus alone (steel cord above 30 000 kN/m), the
file's ``kind`` ignored without a word: a textile belt of 60 000 kN/m written ``kind: fabric``
was checked as steel cord (CEMA transition factor 3.6 B instead of 1.8 B, the running safety
factor minimum 6.7 instead of 10, the wave modulus 1.1 x instead of 1.5 x the static one), and
a steel-cord belt of 25 000 kN/m written ``kind: steel_cord`` as fabric. Without a ``kind`` the
modulus rule stands.
"""

from __future__ import annotations

import pytest

from beltstudy.engine import catalog, solve_steady
from beltstudy.engine.conveyor import parse_conveyor
from tests.conftest import hand_conveyor_dict


def _belt(**over) -> dict:
    b = {"width_m": 1.0, "rating_kn_m": 1000, "modulus_kn_m": 60000,
         "carcass_mass_kg_m2": 20.0, "top_cover_mm": 0, "bottom_cover_mm": 0}
    b.update(over)
    return b


def test_the_file_kind_of_a_custom_belt_is_its_kind():
    fabric = catalog.resolve_belt(parse_conveyor(hand_conveyor_dict(
        belt=_belt(kind="fabric"))).belt)
    assert fabric.kind == "fabric"
    # wave modulus: fabric 1.5 x the static 60 000 kN/m (steel cord would be 1.1 x: 66 000)
    assert fabric.dynamic_modulus_kn_m == pytest.approx(1.5 * 60000)
    steel = catalog.resolve_belt(parse_conveyor(hand_conveyor_dict(
        belt=_belt(kind="steel_cord", modulus_kn_m=25000))).belt)
    assert steel.kind == "steel"
    assert steel.dynamic_modulus_kn_m == pytest.approx(1.1 * 25000)
    # no kind: the modulus decides, as before
    assert catalog.resolve_belt(parse_conveyor(hand_conveyor_dict()).belt).kind == "steel"
    assert catalog.resolve_belt(parse_conveyor(hand_conveyor_dict(
        belt=_belt(modulus_kn_m=25000))).belt).kind == "fabric"


def test_a_fabric_custom_belt_gets_the_fabric_transition_and_safety_minimum():
    conv = parse_conveyor(hand_conveyor_dict(belt=_belt(kind="fabric")))
    s = solve_steady(conv, model="din").summary
    # CEMA 7th ed. Table 7.29, 35 deg trough, fabric: 1.8 / 2.4 / 3.2 x B under 60 % /
    # 60-90 % / over 90 % of the rated tension, rating / 10 for fabric = 100 kN on 1 m
    u = s["t1_kn"] / (1000 * 1.0 / 10.0)
    k = 1.8 if u < 0.6 else (2.4 if u <= 0.9 else 3.2)
    assert s["transition_head_m"] == pytest.approx(k * 1.0)
    # the same belt without kind is steel cord by its modulus: 3.6 / 5.2 / 6.8 x B with the
    # rated tension rating / 6.7
    s_steel = solve_steady(parse_conveyor(hand_conveyor_dict()), model="din").summary
    u = s_steel["t1_kn"] / (1000 * 1.0 / 6.7)
    k = 3.6 if u < 0.6 else (5.2 if u <= 0.9 else 6.8)
    assert s_steel["transition_head_m"] == pytest.approx(k * 1.0)
