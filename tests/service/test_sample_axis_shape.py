"""A sampled axis written as one value or as a list (SPEC 7.2 takes a distribution): the
error names the axis and the two shapes that would do, a distribution or a grid axis; it
said only '5 is not of type "object"'."""

from __future__ import annotations

import pytest

from beltstudy.service.door.studyfile import resolve_study
from beltstudy.service.errors import Invalid
from tests.service.conftest import tiny_study


@pytest.mark.parametrize("value, mean, tail", [
    (5, "5", "a fixed value belongs in the conveyor or the scenario"),
    ("hot", "...", "a fixed value belongs in the conveyor or the scenario"),
    ([-20, 30], "...", "a list of values is a grid axis (grid:)"),
])
def test_a_sampled_axis_that_is_no_distribution_says_what_is(value, mean, tail):
    study = tiny_study("sampled", grid={"friction_model": ["din"]}, sample={
        "n": 16, "method": "lhs", "seed": 7, "axes": {"temperature_c": value}})
    with pytest.raises(Invalid) as exc:
        resolve_study(study)
    msg = exc.value.message
    assert msg.startswith("sample.axes.temperature_c: ")
    assert "is not of type \"object\": a sampled axis is a distribution, e.g. {dist: uniform, " \
        f"low: ..., high: ...}} or {{dist: normal, mean: {mean}, sd: ...}}; {tail}" in msg
