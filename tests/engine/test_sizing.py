"""A design sized over its cases: the largest of each size, what set it and where
(engine/sizing.py)."""

from __future__ import annotations

import pytest

from beltstudy.engine.conveyor import Scenario, parse_conveyor
from beltstudy.engine.design import auto_sizes
from beltstudy.engine.errors import InputError
from beltstudy.engine.sizing import DesignCase, SizingError, size_over_cases
from tests.conftest import hand_conveyor_dict
from tests.engine.conftest import steep_incline

BRAKED = hand_conveyor_dict(brakes=[{"position": "head", "force_kn": "auto", "delay_s": 0.5}])
CASES = [
    DesignCase("din", (), 20.0),
    DesignCase("din", (("f_carry", 0.03),), 20.0),
    DesignCase("cema", (), -20.0),
]


def _each(conv, cases, stop_s=None):
    out = []
    for c in cases:
        scn = Scenario(load="full", temperature_c=c.temperature_c, elements=c.elements)
        if stop_s is not None:
            scn = scn.model_copy(update={"stop": scn.stop.model_copy(
                update={"mode": "brake", "time_s": stop_s})})
        out.append(auto_sizes(conv, scn, model=c.model, params=dict(c.params)))
    return out


def _first_largest(values):
    return max(range(len(values)), key=lambda i: (values[i], -i))


def test_each_size_is_the_largest_over_the_cases_with_what_set_it_and_where():
    conv = parse_conveyor(BRAKED)
    sized = size_over_cases(conv, CASES, load="full", stop_times=[8.0])
    each = _each(conv, CASES)

    masses = [s["takeup_mass_kg"] for s in each]
    i = _first_largest(masses)
    assert sized.takeup.value == masses[i]
    assert (sized.takeup.governed_by, sized.takeup.case) == (each[i]["takeup_governed_by"],
                                                             CASES[i])

    power = [s["drive_rated_power_kw"][0] for s in each]
    j = _first_largest(power)
    assert len(sized.drives) == 1
    assert sized.drives[0].value == power[j] and sized.drives[0].case == CASES[j]
    assert sized.drives[0].governed_by == each[j]["drive_rated_power_governed_by"][0]

    totals = [sum(s["brake_force_kn"]) for s in each]
    k = _first_largest(totals)
    assert sized.brakes_holding.force_kn == tuple(each[k]["brake_force_kn"])
    assert sized.brakes_holding.governed_by == tuple(each[k]["brake_governed_by"])
    assert sized.brakes_holding.case == CASES[k]

    braked = _each(conv, CASES, stop_s=8.0)
    totals = [sum(s["brake_force_kn"]) for s in braked]
    k = _first_largest(totals)
    assert list(sized.brakes_by_stop) == [8.0]
    assert sized.brakes_by_stop[8.0].force_kn == tuple(braked[k]["brake_force_kn"])
    assert sized.brakes_by_stop[8.0].case == CASES[k]
    assert sized.failed_cases == ()


def test_sizes_the_file_gives_are_not_sized():
    given = hand_conveyor_dict(takeup={"type": "gravity", "position": "tail", "mass_kg": 9000})
    given["drives"] = [{**given["drives"][0], "rated_power_kw": 500}]
    sized = size_over_cases(parse_conveyor(given), CASES[:1])
    assert sized.takeup is None and sized.drives == (None,)
    assert sized.brakes_holding is None and sized.brakes_by_stop == {}


def test_a_case_names_its_model_the_parameters_it_changes_and_its_temperature():
    assert CASES[0].label() == "din, 20 C"
    assert CASES[1].label() == "din (f_carry=0.03), 20 C"
    assert DesignCase("din", (("f_carry", 0.02),), -5.0).label() == "din, -5 C"


def test_a_load_that_does_not_fit_the_profile_is_a_sizing_error_naming_the_load():
    conv = parse_conveyor(BRAKED)
    with pytest.raises(SizingError) as info:
        size_over_cases(conv, CASES[:1], load=[0.5, 0.5], design="belt=EP630")
    assert isinstance(info.value, InputError)
    assert info.value.field == "load"
    assert info.value.reason.endswith("(conveyor design belt=EP630)")


def test_a_brake_beyond_its_grip_is_held_at_the_least_grip_over_the_cases():
    """The 10 % incline's 3 s stop needs more than its head pulley passes at every case: the
    design's brake is the least of the cases' grips (a force every case's pulley passes), at
    that case, ``grip``; a 3.5 s stop is within every case's grip and stays the largest
    need (stop_time)."""
    conv = steep_incline()
    sized = size_over_cases(conv, CASES, load="full", stop_times=[3.0, 3.5])
    braked = _each(conv, CASES, stop_s=3.0)
    grips = [s["brake_grip_kn"] for s in braked]
    k = min(range(len(grips)), key=lambda i: grips[i])
    assert all(s["brake_governed_by"] == ["grip"] for s in braked)
    assert sized.brakes_by_stop[3.0].force_kn == pytest.approx((grips[k],), rel=1e-6)
    assert sized.brakes_by_stop[3.0].governed_by == ("grip",)
    assert sized.brakes_by_stop[3.0].case == CASES[k]
    within = _each(conv, CASES, stop_s=3.5)
    totals = [sum(s["brake_force_kn"]) for s in within]
    j = _first_largest(totals)
    assert totals[j] < min(s["brake_grip_kn"] for s in within)
    assert sized.brakes_by_stop[3.5].force_kn == tuple(within[j]["brake_force_kn"])
    assert sized.brakes_by_stop[3.5].governed_by == ("stop_time",)
