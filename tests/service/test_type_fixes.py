"""A value of the wrong type gets its fix, not only its field and type.

Hurried inputs named the field but said nothing of what to write: ``speed_m_s: 4.5 m/s``,
``length_m: 2 km``, ``width_m: 1200mm``, ``speed_m_s: 4,5``, ``sag_limit_pct: {carry: 1.5%}``,
``wrap_deg: 210°``, ``mass_kg: 18 t``, ``temperature_c: 20 C``, an empty ``speed_m_s:``,
``dynamics: 0``, ``drives:`` written as a mapping and ``takeup:`` as a list were each
``FIELD: VALUE is not of type "TYPE"`` and no more. The fix now follows
(:func:`beltstudy.service.door.messages.type_fix`), in a conveyor file (``beltstudy static``),
a scenario file (``beltstudy simulate --scenario``) and at the REST doors alike; the messages
that had a fix keep it as it was.
"""

from __future__ import annotations

import pytest
import yaml
from fastapi.testclient import TestClient

from beltstudy.service.api.app import create_app
from beltstudy.service.cli import main
from tests.conftest import ROOT

CONVEYOR = ROOT / "studies" / "conveyors" / "slope-5pct.yaml"


def _conveyor(**over) -> dict:
    """The slope conveyor with dotted fields set (``profile.0.length_m``)."""
    data = yaml.safe_load(CONVEYOR.read_text(encoding="utf-8"))
    for dotted, value in over.items():
        *keys, last = (int(k) if k.isdigit() else k for k in dotted.split("."))
        target = data
        for key in keys:
            target = target[key]
        target[last] = value
    return data


@pytest.mark.parametrize(("over", "said"), [
    ({"speed_m_s": "4.5 m/s"},
     'speed_m_s: "4.5 m/s" is not of type "number": write the number alone, in m/s: 4.5'),
    ({"profile.0.length_m": "2 km"}, 'profile.0.length_m: "2 km" is not of type "number": '
     "write the number alone, in m: 2000 (2 km)"),
    ({"belt.width_m": "1200mm"}, 'belt.width_m: "1200mm" is not of type "number": write the '
     "number alone, in m: 1.2 (1200 mm)"),
    ({"speed_m_s": "4,5"}, 'speed_m_s: "4,5" is not of type "number": write 4.5: a decimal '
     "point"),
    ({"sag_limit_pct.carry": "1.5%"}, 'sag_limit_pct.carry: "1.5%" is not of type "number": '
     "write the number alone, in %: 1.5"),
    ({"drives.0.wrap_deg": "210°"}, 'drives.0.wrap_deg: "210°" is not of type "number": write '
     "the number alone, in deg: 210"),
    ({"takeup.mass_kg": "18 t"}, 'takeup.mass_kg: "18 t" is not of type "number" or \'auto\': '
     "write the number alone, in kg: 18000 (18 t)"),
    ({"material.capacity_t_h": "555 kg/s"}, 'material.capacity_t_h: "555 kg/s" is not of type '
     '"number": write the number alone, in t/h: 1998 (555 kg/s)'),
    ({"speed_m_s": None}, 'speed_m_s: null is not of type "number": give a value or remove '
     "the key"),
    ({"belt": "ST2000"}, 'belt: "ST2000" is not of type "object": write a mapping `{key: '
     "value, ...}`"),
    # words where a number goes, and a count with a fraction
    ({"material.capacity_t_h": "lots"}, 'material.capacity_t_h: "lots" is not of type '
     '"number": write a number, in t/h'),
    ({"idlers.carry.rolls": 2.5}, 'idlers.carry.rolls: 2.5 is not of type "integer": write a '
     "whole number (2 or 3)"),
    # the fixes a value had keep their words
    ({"speed_m_s": "4.5"}, 'speed_m_s: "4.5" is not of type "number": write 4.5 without '
     "quotes"),
])
def test_a_conveyor_file_with_a_hurried_value_gets_its_fix(tmp_path, capsys, over, said):
    path = tmp_path / "c.yaml"
    path.write_text(yaml.safe_dump(_conveyor(**over), allow_unicode=True), encoding="utf-8")
    assert main(["static", str(path)]) == 2
    assert capsys.readouterr().err == f"error: {path}: {said}\n"


@pytest.mark.parametrize(("text", "said"), [
    ("drives:\n  position: head\n  wrap_deg: 210\n",
     'drives: {"position":"head","wrap_deg":210} is not of type "array": write a list: one '
     "`- {...}` item per entry"),
    ("takeup:\n  - {type: gravity, position: tail}\n",
     'takeup: [{"type":"gravity","position":"tail"}] is not of type "object": write a '
     "mapping `{key: value, ...}`"),
])
def test_a_wrong_container_in_a_conveyor_file_says_the_one_to_write(tmp_path, capsys, text,
                                                                     said):
    lines = CONVEYOR.read_text(encoding="utf-8").splitlines(keepends=True)
    key = text.split(":")[0]
    start = next(i for i, line in enumerate(lines) if line.startswith(f"{key}:"))
    end = next((i for i in range(start + 1, len(lines)) if lines[i][:1].isalpha()), len(lines))
    path = tmp_path / "c.yaml"
    path.write_text("".join(lines[:start]) + text + "".join(lines[end:]), encoding="utf-8")
    assert main(["static", str(path)]) == 2
    assert capsys.readouterr().err == f"error: {path}: {said}\n"


def test_a_scenario_file_with_units_gets_its_fix(tmp_path, capsys):
    path = tmp_path / "sc.yaml"
    path.write_text("scenario:\n  temperature_c: 20 C\n  run_s: 10 s\n", encoding="utf-8")
    assert main(["simulate", str(CONVEYOR), "--scenario", str(path)]) == 2
    assert capsys.readouterr().err == (
        'error: scenario.temperature_c: "20 C" is not of type "number": write the number '
        'alone, in C: 20; scenario.run_s: "10 s" is not of type "number": write the number '
        "alone, in s: 10\n")


@pytest.fixture
def client(data_dir, make_settings):
    with TestClient(create_app(make_settings(data_dir))) as c:
        yield c


@pytest.mark.parametrize(("over", "said"), [
    ({"dynamics": 0}, 'dynamics: 0 is not of type "boolean": write true or false'),
    ({"grid": {"temperature_c": ["0 C", 10]}}, 'grid.temperature_c.0: "0 C" is not of type '
     '"number": write the number alone, in C: 0'),
    ({"conveyor": "CONV", "scenario": {"temperature_c": "20 C"}}, 'scenario.temperature_c: '
     '"20 C" is not of type "number": write the number alone, in C: 20'),
    ({"conveyor": "INLINE"}, 'conveyor.drives: {"position":"head","pulley_diameter_m":0.6,'
     '"inertia_kg_m2":20} is not of type "array": write a list: one `- {...}` item per entry'),
])
def test_post_studies_gives_the_fix(client, data_dir, make_study, make_conveyor, over, said):
    body = make_study(**over)
    if body["conveyor"] == "CONV":
        body["conveyor"] = "conveyors/slope-5pct.yaml"
    elif body["conveyor"] == "INLINE":
        conv = make_conveyor()
        body["conveyor"] = {**conv, "drives": conv["drives"][0]}
    r = client.post("/studies", json=body)
    assert r.status_code == 422 and r.json()["message"] == said, r.json()
    assert not (data_dir / "studies").exists() or not any((data_dir / "studies").iterdir())


def test_post_calibrations_gives_the_fix_for_a_measured_value_with_its_unit(client):
    rows = [{"load": "full", "temperature_c": 20.0, "power_kw": "280.5 kW"},
            {"load": "full", "temperature_c": 0.0, "power_kw": 300.0}]
    r = client.post("/calibrations", json={"conveyor": "conveyors/slope-5pct.yaml",
                                           "model": "din", "fit": ["f_carry"], "measured": rows})
    assert r.status_code == 422
    assert r.json()["message"] == ('measured.0.power_kw: "280.5 kW" is not of type "number": '
                                   "write the number alone, in kW: 280.5")


@pytest.mark.parametrize(("got", "error_type", "path", "fix"), [
    ("1,200", "float_type", ("belt", "width_m"),
     "write 1.200: a decimal point, or 1200 if the comma separates thousands"),
    ("20 F", "float_type", ("temperature_c",),
     "write the number alone, in C (convert 20 F to C)"),
    ("3 rolls", "int_type", ("idlers", "carry", "rolls"), "write the number alone: 3"),
    (None, "float_type", ("grid", "temperature_c", 1), "give a value or remove the item"),
    (1, "bool_type", ("holdback",), "write true or false"),
    (2, "bool_type", ("holdback",), ""),
    ("fast", "float_type", ("speed_m_s",), "write a number, in m/s"),
    ("lots", "float_type", ("holdback_factor",), "write a number"),
])
def test_the_fix_by_the_value_and_the_field(got, error_type, path, fix):
    from beltstudy.service.door.messages import type_fix

    assert type_fix(got, error_type, path) == fix
