"""A sample axis given without its ``dist`` (SPEC 7.2): the key to add and the words it
takes, as any missing field is named; Pydantic's "Unable to extract tag using discriminator
'dist'" was passed on as it was, naming neither."""

from __future__ import annotations

import pytest

from beltstudy.service.door.studyfile import resolve_study
from beltstudy.service.errors import Invalid
from tests.service.conftest import tiny_study


def test_a_sample_axis_without_dist_names_the_key_and_its_values():
    study = tiny_study("sampled", grid={"friction_model": ["din"]}, sample={
        "n": 16, "method": "lhs", "seed": 7,
        "axes": {"temperature_c": {"low": -25, "high": 35}}})
    with pytest.raises(Invalid) as exc:
        resolve_study(study)
    assert exc.value.message == (
        "sample.axes.temperature_c.dist: required field is missing; give dist: one of "
        "uniform, normal, lognormal, triangular")
