"""The conveyor contract: validation errors name the field and the fix."""

from __future__ import annotations

import pytest

from beltstudy.engine import catalog
from beltstudy.engine.conveyor import (
    InputError,
    Scenario,
    load_conveyor,
    parse_conveyor,
    parse_scenario,
)
from beltstudy.engine.loop import build_loop
from tests.conftest import CONVEYORS, hand_conveyor_dict


@pytest.mark.parametrize("path", sorted(CONVEYORS.glob("*.yaml")), ids=lambda p: p.name)
def test_examples_load(path):
    conv = load_conveyor(path)
    assert conv.length_m > 0


def _err(d) -> str:
    with pytest.raises(InputError) as ei:
        parse_conveyor(d)
    msg = str(ei.value)
    assert "\n" not in msg
    return msg


def test_negative_length():
    msg = _err(hand_conveyor_dict(profile=[{"length_m": -5, "lift_m": 0}]))
    assert "profile.0.length_m" in msg and "greater than 0" in msg


def test_zero_speed():
    msg = _err(hand_conveyor_dict(speed_m_s=0))
    assert "speed_m_s" in msg


def test_unknown_belt_type_lists_valid():
    d = hand_conveyor_dict()
    d["belt"] = {"type": "ST2100", "width_m": 1.2}
    msg = _err(d)
    assert "belt.type" in msg and "ST2100" in msg and "ST2000" in msg


def test_misspelt_key_suggests_nearest():
    d = hand_conveyor_dict()
    d["idlers"]["carry"]["spacng_m"] = 1.2
    msg = _err(d)
    assert "idlers.carry.spacng_m" in msg and "did you mean 'spacing_m'" in msg
    d = hand_conveyor_dict(speeed_m_s=3)
    assert "did you mean 'speed_m_s'" in _err(d)


def test_shares_must_sum_to_one():
    d = hand_conveyor_dict()
    d["drives"][0]["share"] = 0.6
    assert "shares sum to 0.6" in _err(d)


def test_a_belt_without_mass_is_refused():
    d = hand_conveyor_dict()
    d["belt"] = {"width_m": 1.0, "rating_kn_m": 500, "modulus_kn_m": 6000,
                 "carcass_mass_kg_m2": 0.0, "top_cover_mm": 0, "bottom_cover_mm": 0}
    msg = _err(d)
    assert "belt.carcass_mass_kg_m2" in msg and "greater than or equal to 0.1" in msg


def test_bounds_beyond_practice_name_the_field():
    d = hand_conveyor_dict()
    d["idlers"]["carry"]["spacing_m"] = 9e15
    assert "idlers.carry.spacing_m" in _err(d)
    d = hand_conveyor_dict()
    d["belt"]["width_m"] = 5e-324
    assert "belt.width_m" in _err(d)


def test_lift_longer_than_length():
    assert "lift_m" in _err(hand_conveyor_dict(profile=[{"length_m": 10, "lift_m": 12}]))


def test_fixed_takeup_mass_is_an_error():
    d = hand_conveyor_dict(takeup={"type": "fixed", "mass_kg": 1000})
    assert "pretension_kn" in _err(d)


def test_custom_belt_needs_fields():
    d = hand_conveyor_dict()
    del d["belt"]["modulus_kn_m"]
    assert "modulus_kn_m" in _err(d)


def test_belt_overrides_replace_catalogue():
    d = hand_conveyor_dict()
    d["belt"] = {"type": "ST2000", "width_m": 1.0, "top_cover_mm": 0, "bottom_cover_mm": 0,
                 "carcass_mass_kg_m2": 30.0, "modulus_kn_m": 100000}
    conv = parse_conveyor(d)
    b = catalog.resolve_belt(conv.belt)
    assert b.mass_kg_m == pytest.approx(30.0)  # covers 0: exactly the given mass per metre
    assert b.modulus_kn_m == 100000 and b.rating_kn_m == 2000


def test_catalogue_sources_and_ids():
    ids = set(catalog.belts())
    for want in ("ST1000", "ST1250", "ST1600", "ST2000", "ST2500", "ST3150", "ST4000", "ST5400",
                 "EP400/3", "EP630/4", "EP800/4", "EP1000/5", "EP1250/5", "EP1600/4"):
        assert want in ids
    for b in catalog.belts().values():
        assert b.source.strip()
        if b.kind == "steel":  # PHYSICS section 4: modulus 72 x rating
            assert b.modulus_kn_m == pytest.approx(72 * b.rating_kn_m)
    for i in catalog.idlers():
        assert i.source.strip()
    assert set(catalog.compounds()) >= {"standard", "lrr", "cold", "fire-resistant"}


def test_scenario_errors():
    with pytest.raises(InputError, match="stop.mode"):
        parse_scenario({"stop": {"mode": "slam", "time_s": 3}})
    with pytest.raises(InputError, match="run_s"):
        parse_scenario({"run_s": -1})
    with pytest.raises(InputError, match="did you mean 'temperature_c'"):
        parse_scenario({"temperatur_c": 3})
    assert parse_scenario({"scenario": {"load": 0.5}}).load_fraction == 0.5
    assert Scenario(load="empty").load_fraction == 0.0


def test_loop_layout(hand_conveyor):
    loop = build_loop(hand_conveyor, 1.0, n_elements=40)
    assert loop.nc == 20 and loop.strand[loop.i_head] == 2 and loop.strand[-1] == 3
    assert loop.dx_m[:20].sum() == pytest.approx(1000.0)
    # return strand runs the profile backwards: its slope is negated, it ends at the tail
    assert loop.sin_a[0] == pytest.approx(0.05) and loop.sin_a[loop.i_head + 1] == -0.05
    assert loop.z_end_m[loop.nc - 1] == pytest.approx(50.0)
    assert abs(loop.z_end_m[-2]) < 1e-9
    # element count from a target length
    assert build_loop(hand_conveyor, 1.0, target_dx_m=10.0).nc == 100
    # masses per metre (PHYSICS 1)
    assert loop.mL_kg_m[0] == pytest.approx(50.0) and loop.mL_kg_m[loop.i_head + 1] == 0
    assert loop.mR_kg_m[0] == pytest.approx(10.0)
    assert loop.mR_kg_m[loop.i_head + 1] == pytest.approx(3.0)
