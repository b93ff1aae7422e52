"""The belt, idler and compound catalogues (engine/catalog.py): sources, ids and overrides."""

from __future__ import annotations

import pytest

from beltstudy.engine import catalog
from beltstudy.engine.conveyor import parse_conveyor
from tests.conftest import hand_conveyor_dict


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
