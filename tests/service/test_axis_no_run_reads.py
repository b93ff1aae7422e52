"""An axis over a field no run reads is refused at the door, over HTTP and on the command line.

The conveyor's ``name`` is free text: no run reads it, so ``grid: {name: [a, b]}`` was taken
(202, total 2) as two runs with different ids and the same results. It is refused as a steady
study refuses an axis of the stop time (``_check_read``): more than one value would be runs
that differ in nothing a run reads. ``grid: {dynamics: [true, false]}`` was refused "did you
mean 'name'?", pointing at that non-axis; it says ``dynamics`` is a field of the study.
"""

from __future__ import annotations

import pytest
import yaml
from fastapi.testclient import TestClient

from beltstudy.service.api.app import create_app
from beltstudy.service.cli import main
from beltstudy.service.door.studyfile import resolve_study
from tests.service.conftest import ROOT


def _probe(**over) -> dict:
    """The probe's study: the example slope conveyor by path, steady."""
    return {"name": "probe", "conveyor": "conveyors/slope-5pct.yaml", "dynamics": False, **over}


@pytest.fixture
def client(data_dir, make_settings):
    return TestClient(create_app(make_settings(data_dir)))


@pytest.mark.parametrize(("body", "field"), [
    ({"grid": {"name": ["a", "b"]}}, "grid.name"),
    ({"grid": {"conveyor.name": ["a", "b"]}}, "grid.conveyor.name"),
    ({"grid": {"temperature_c": [0, 20]}, "zip": [{"name": ["a", "b"],
                                                   "load": ["full", "empty"]}]}, "zip.0.name"),
])
def test_an_axis_of_the_conveyor_name_is_a_422_naming_it(client, data_dir, body, field):
    r = client.post("/studies", json=_probe(**body))
    assert r.status_code == 422, r.text
    message = r.json()["message"]
    assert message.startswith(f"{field}: no run reads the conveyor's name"), message
    assert "2 values would be 2 runs with the same results" in message, message
    assert "drop the axis" in message, message
    assert not (data_dir / "studies").exists() or not list((data_dir / "studies").iterdir())


def test_one_value_of_the_name_sets_it_as_any_field_set_once():
    """As a steady study takes one value of the stop time: the field set, one run."""
    study = resolve_study(_probe(grid={"name": ["renamed"], "temperature_c": [0, 20]}),
                          studies_dir=ROOT / "studies")
    assert study.total == 2


def test_the_schema_states_one_value_of_the_name(client):
    study = client.get("/openapi.json").json()["components"]["schemas"]["StudyDoc"]
    for grid in (study["properties"]["grid"], study["properties"]["zip"]["items"]):
        for axis in ("name", "conveyor.name"):
            assert grid["properties"][axis]["maxItems"] == 1, grid["properties"][axis]


def test_beltstudy_run_refuses_it_in_one_line(env, capsys, tmp_path):
    path = tmp_path / "probe.yaml"
    conveyor = ROOT / "studies" / "conveyors" / "slope-5pct.yaml"
    path.write_text(yaml.safe_dump(_probe(conveyor=str(conveyor), grid={"name": ["a", "b"]})))
    assert main(["run", str(path)]) == 2
    err = capsys.readouterr().err
    assert err.startswith("error: grid.name: no run reads the conveyor's name"), err
    assert len(err.strip().splitlines()) == 1


def test_a_study_field_as_an_axis_says_so_not_a_non_axis(client):
    r = client.post("/studies", json=_probe(grid={"dynamics": [True, False]}))
    assert r.status_code == 422, r.text
    message = r.json()["message"]
    assert "did you mean 'name'" not in message, message
    assert message.startswith("grid.dynamics: 'dynamics' is a field of the study, not an "
                              "axis"), message
    assert "one study per value" in message, message
    # model: the friction_model axis is the one that varies it
    r = client.post("/studies", json=_probe(grid={"model": ["din", "cema"]}))
    assert r.status_code == 422, r.text
    assert "friction_model: [din, cema]" in r.json()["message"], r.text
