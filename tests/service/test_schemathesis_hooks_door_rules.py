"""The schemathesis hooks hold two door rules the schema cannot state, so a generated study
that breaks one is skipped instead of counted as a schema-valid request rejected (ST202; a
40-example run, seed 23, on engine 0.6.17 found both):

- idler sets given by ``count`` are spread over the whole route, and the pitch it makes,
  route / count, must be 0.1 to 20 m (``Conveyor``'s check): ``idlers.carry.count: 2`` over a
  5e-324 m route was refused (422, 'a pitch of 0 m, outside 0.1 to 20 m');
- a conveyor axis's list index must exist in the base conveyor, inline or a shipped file.
"""

from __future__ import annotations

import copy

import pytest

from beltstudy.engine.conveyor import InputError, parse_conveyor
from tests.service.schemathesis_hooks import filter_body

BODY = {
    "name": "0",
    "conveyor": {
        "name": "0", "speed_m_s": 0.01, "drives": [{}],
        "belt": {"modulus_kn_m": 1.0, "carcass_mass_kg_m2": 0.1, "rating_kn_m": 1.0,
                 "bottom_cover_mm": 6.1, "top_cover_mm": 0.0, "width_m": 0.1,
                 "dynamic_modulus_kn_m": 1.0, "kind": None},
        "idlers": {"carry": {"count": 2}, "return": {"count": 8}},
        "material": {"capacity_t_h": 0.0},
        "profile": [{"length_m": 5e-324}],
    },
    "grid": {"accessories": [{"ploughs": [{"at_m": 0.0}]}]},
}


def _with_route(length_m: float, carry: int, ret: int) -> dict:
    body = copy.deepcopy(BODY)
    body["conveyor"]["profile"] = [{"length_m": length_m}]
    body["conveyor"]["idlers"] = {"carry": {"count": carry}, "return": {"count": ret}}
    return body


@pytest.mark.parametrize("length_m, carry, ret, sent", [
    (5e-324, 2, 8, False),  # the body the fuzzing sent: carry pitch 2.5e-324 m
    (100.0, 2, 8, False),  # carry pitch 50 m, beyond 20 m
    (100.0, 400, 2000, False),  # return pitch 0.05 m, below 0.1 m
    (100.0, 400, 8, True),  # carry 0.25 m, return 12.5 m: within the range
])
def test_the_hook_skips_exactly_the_counts_the_conveyor_refuses(length_m, carry, ret, sent):
    body = _with_route(length_m, carry, ret)
    try:
        parse_conveyor(body["conveyor"])
        accepted = True
    except (InputError, ValueError) as err:
        assert "is a pitch of" in str(err)
        accepted = False
    assert accepted is sent
    assert filter_body(None, body) is sent


def test_the_fuzzed_body_is_refused_by_the_conveyor_and_skipped_by_the_hook():
    with pytest.raises((InputError, ValueError), match="pitch of 0 m, outside 0.1 to 20 m"):
        parse_conveyor(BODY["conveyor"])
    assert filter_body(None, copy.deepcopy(BODY)) is False


def test_a_count_within_the_pitch_range_is_still_sent():
    body = _with_route(1000.0, 800, 333)  # pitches 1.25 m and 3.0 m
    parse_conveyor(body["conveyor"])
    assert filter_body(None, body) is True


def test_an_axis_indexing_a_list_the_shipped_conveyor_lacks_is_skipped():
    """Fuzzing (seed 23) sent grid axis ``accessories.ploughs.0`` over
    ``conveyors/slope-5pct.yaml``, which has no ploughs: the service refused it (422, "index 0
    is out of range") and schemathesis reported ST202. The hooks now skip an axis whose list
    index the base conveyor, inline or a shipped file, does not have."""
    body = {"name": "00", "conveyor": "conveyors/slope-5pct.yaml",
            "grid": {"accessories.ploughs.0": [{"at_m": 0.0}, {"at_m": 10.0}],
                     "accessories.scrapers": [[]]}}
    assert filter_body(None, body) is False
    body["grid"] = {"accessories.head_kn": [1.0, 3.0]}  # no index: still sent
    assert filter_body(None, body) is True


def test_a_belt_axis_that_overfills_the_cross_section_is_skipped():
    """Fuzzing (seed 23) sent grid axis ``belt: [{width_m: 0.1, ...}]`` over
    ``conveyors/fabric-1km.yaml`` (300 t/h at 3.15 m/s): the conveyor's fill check refused it
    (422, 'fills the belt's cross-section to 2.49e+04 %; at most 300 %') and schemathesis
    reported ST202. The hooks now run the conveyor's registered checks of the whole."""
    belt = {"bottom_cover_mm": 0.0, "carcass_mass_kg_m2": 0.1, "modulus_kn_m": 1.0,
            "rating_kn_m": 1.0, "top_cover_mm": 0.0, "width_m": 0.1}
    body = {"name": "0", "conveyor": "conveyors/fabric-1km.yaml", "grid": {"belt": [belt]}}
    assert filter_body(None, body) is False
    body["grid"] = {"belt": [{**belt, "width_m": 1.0}]}  # 1 m: the file's own width fills
    assert filter_body(None, body) is True


def test_a_variant_the_conveyor_refuses_with_its_base_is_skipped():
    """Fuzzing (seed 23) sent ``conveyor.takeup.position: [return, tail]`` over
    ``conveyors/valley-booster.yaml``, whose take-up sits along the return (``at_m: 5950``):
    the tail variant was refused (422, 'at_m: 5950 m goes with position return'). An axis
    value's schema cannot know the base's other fields; the hooks skip a variant the conveyor
    refuses when it accepts the base."""
    body = {"name": "zg+", "conveyor": "conveyors/valley-booster.yaml",
            "grid": {"conveyor.takeup.position": ["return", "tail"]}}
    assert filter_body(None, body) is False
    body["grid"] = {"conveyor.speed_m_s": [4.0, 4.5]}
    assert filter_body(None, body) is True
