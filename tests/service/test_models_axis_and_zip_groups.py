"""A model parameter given both under ``models:`` and as an axis is refused; zip groups are
said as SPEC has them.

``models: {din: {f_carry: 0.015}}`` with ``grid: {"models.din.f_carry": [0.01, 0.02]}`` was
taken (202) and 0.015 never used: every din run takes the axis's value. It is refused naming
both places, as the same field in the grid and a zip group is. Where the fixed value is read
(the design basis of another model's runs, ``design: {friction_model: din}``) it is taken.

SPEC 6.3 has a zip group as "axes that vary together (equal lengths), crossed with grid", with
no least number: ``zip: []`` (no groups) and a group of one axis (crossed with the grid as a
grid axis is) are taken, and the empty group's refusal no longer asks for "two or more axes".
"""

from __future__ import annotations

import pytest
from fastapi.testclient import TestClient

from beltstudy.service.api.app import create_app
from beltstudy.service.door.studyfile import resolve_study
from beltstudy.service.errors import Invalid


@pytest.fixture
def client(data_dir, make_settings):
    return TestClient(create_app(make_settings(data_dir)))


def _written(data_dir) -> list[str]:
    root = data_dir / "studies"
    return sorted(p.name for p in root.iterdir()) if root.exists() else []


@pytest.mark.parametrize(("over", "models", "place"), [
    ({"grid": {"models.din.f_carry": [0.01, 0.02]}}, {"din": {"f_carry": 0.015}},
     "grid.models.din.f_carry"),
    ({"grid": {"temperature_c": [0, 20]},
      "zip": [{"models.din.f_carry": [0.01, 0.02], "load": ["full", "empty"]}]},
     {"din": {"f_carry": 0.015}}, "zip.0.models.din.f_carry"),
    ({"grid": {"models.din.f_carry": [0.01, 0.02]}}, {"iso5048": {"f_carry": 0.015}},
     "grid.models.din.f_carry"),
    ({"grid": {"temperature_c": [0, 20]},
      "sample": {"n": 4, "method": "lhs", "seed": 1,
                 "axes": {"models.din.f_carry": {"dist": "uniform", "low": 0.01,
                                                 "high": 0.02}}}},
     {"din": {"f_carry": 0.015}}, "sample.axes.models.din.f_carry"),
])
def test_a_parameter_under_models_and_on_an_axis_is_a_422_naming_both(
        client, data_dir, make_study, over, models, place):
    written = next(iter(models))
    r = client.post("/studies", json=make_study(model="din", models=models, **over))
    assert r.status_code == 422, r.text
    message = r.json()["message"]
    assert message.startswith(f"models.{written}.f_carry and {place} both set "
                              "models.din.f_carry: give it in one of them"), message
    assert "0.015" in message, message
    assert _written(data_dir) == []


def test_other_parameters_and_a_fixed_value_that_is_read_are_taken(make_study):
    # another parameter of the model beside the axis: read by every din run
    study = resolve_study(make_study(model="din", models={"din": {"f_return": 0.01}},
                                     grid={"models.din.f_carry": [0.01, 0.02]}))
    assert study.total == 2
    # a design model's fixed value sizes the other model's runs
    resolve_study(make_study(models={"din": {"f_carry": 0.015}},
                             grid={"friction_model": ["cema", "din"],
                                   "models.din.f_carry": [0.01, 0.02]},
                             design={"friction_model": "din"}))


def test_a_zip_group_of_one_axis_and_no_groups_are_taken_as_spec_has_them(make_study):
    grid = make_study(grid={"temperature_c": [0, 10]})
    zipped = make_study(grid={"friction_model": ["din"]}, zip=[{"temperature_c": [0, 10]}])
    assert resolve_study(zipped).total == resolve_study(grid).total == 2
    assert resolve_study(make_study(zip=[])).total == 6


def test_the_empty_groups_refusal_asks_for_what_a_group_may_be(client, make_study):
    r = client.post("/studies", json=make_study(zip=[{}]))
    assert r.status_code == 422, r.text
    message = r.json()["message"]
    assert message.startswith("zip.0: empty group; give one or more axes"), message
    assert "two or more" not in message, message
    # following it: a group of one axis
    with pytest.raises(Invalid, match="^zip.0"):
        resolve_study(make_study(zip=[{}]))
    resolve_study(make_study(zip=[{"load": ["full", "empty"]}]))
