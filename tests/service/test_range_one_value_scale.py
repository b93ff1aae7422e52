"""A range of one value gives that value. The values of a range are rounded to 12 digits of
the range's own scale (so -0.3 + 3 x 0.1 is 0, as the list gives it), and the scale took in
the step even where the step is never taken: ``{start: 20, stop: 20, step: 1e20}`` gave [0],
a temperature of 20 C run at 0 C without a word, and schemathesis (seed 23) found
``belt.modulus_kn_m: {start: 2e6, stop: 7.3e8, step: -5.8e307}`` turned into modulus 0,
refused as 'greater than or equal to 1 (got 0)', a schema-valid request rejected (ST202)."""

from __future__ import annotations

import pytest

from beltstudy.service.door.study import RangeSpec


@pytest.mark.parametrize("start, stop, step, values", [
    (20.0, 20.0, 1e20, [20]),  # one value: the start, by hand
    (2e6, 730227373.1809189, -5.77989302856734e307, [2000000]),  # the fuzzed axis
    (0.125, 0.125, 1e13, [0.125]),
    (-7.5, 1e290, 1e301, [-7.5]),  # stop far away, within the 1e-6 step tolerance
])
def test_a_range_of_one_value_is_its_start(start, stop, step, values):
    assert RangeSpec(start=start, stop=stop, step=step).values() == values


def test_ranges_of_several_values_keep_their_rounding():
    assert RangeSpec(start=-0.3, stop=0.3, step=0.1).values() == [-0.3, -0.2, -0.1, 0.0, 0.1,
                                                                   0.2, 0.3]
    assert RangeSpec(start=-30, stop=30, step=5).values() == list(range(-30, 31, 5))
