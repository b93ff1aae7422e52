"""A calibration input's problem is one message with its fix, the same from ``beltstudy
calibrate`` (a CSV) and ``POST /calibrations`` (rows in the body): 201 rows (a 413 over REST,
as the README's limits say), no rows, a cell written with its unit, a row without its
temperature or load."""

from __future__ import annotations

import csv
import io

import pytest
from fastapi.testclient import TestClient

from beltstudy.service.api.app import create_app
from tests.conftest import CONVEYORS

BASE = {"conveyor": "conveyors/overland-4km.yaml", "model": "din", "fit": ["f_carry"]}
ROW = {"load": 0.5, "temperature_c": 10, "power_kw": 600}


@pytest.fixture
def client(data_dir, make_settings):
    return TestClient(create_app(make_settings(data_dir)))


def _cli(tmp_path, capsys, rows: list[dict]) -> tuple[str, str]:
    """The command line's one-line refusal of ``rows`` written as a CSV (cells left out of a
    row are empty), and the file's path."""
    from beltstudy.service.cli import main

    text = io.StringIO()
    writer = csv.DictWriter(text, ["load", "temperature_c", "power_kw"], lineterminator="\n")
    writer.writeheader()
    writer.writerows(rows)
    path = tmp_path / "plant.csv"
    path.write_text(text.getvalue())
    assert main(["calibrate", str(CONVEYORS / "overland-4km.yaml"), "--measured", str(path),
                 "--model", "din", "--fit", "f_carry"]) == 2
    err = capsys.readouterr().err.strip()
    assert len(err.splitlines()) == 1 and "Traceback" not in err, err
    return err, str(path)


def test_too_many_rows_is_a_413_with_the_fix_the_command_line_gives(client, tmp_path, capsys):
    """REST answered 422 'measured: List should have at most 200 items after validation, not
    201' (Pydantic's words, no fix; the README says a 413 whose fix is fewer rows)."""
    rows = [{**ROW, "load": round(0.3 + i / 1000, 3)} for i in range(201)]
    said = ("more than 200 measured rows (201); a calibration takes at most 200 (each costs a "
            "steady solve per step of the fit): give fewer steady states, or averages of "
            "repeated readings at the same load and temperature")
    r = client.post("/calibrations", json={**BASE, "measured": rows})
    assert r.status_code == 413, r.text
    assert r.json() == {"error": "too_large", "message": f"measured: {said}"}
    err, path = _cli(tmp_path, capsys, rows)
    assert err == f"error: {path}: {said}"


def test_no_rows_says_what_to_give(client, tmp_path, capsys):
    """REST answered 'measured: List should have at least 1 item after validation, not 0'."""
    fix = ("give one row per measured steady state (load, temperature_c, and power_kw or "
           "te_kn)")
    r = client.post("/calibrations", json={**BASE, "measured": []})
    assert r.status_code == 422
    assert r.json()["message"] == f"measured: no measured rows; {fix}"
    err, path = _cli(tmp_path, capsys, [])
    assert err == f"error: {path}: no measured rows below the header (line 1); {fix}"


@pytest.mark.parametrize(("row", "said"), [
    # the command line dropped the fix REST gives
    ({**ROW, "power_kw": "580 kW"},
     'measured.1.power_kw: "580 kW" is not of type "number": write the number alone, in kW: '
     "580"),
    # both said only 'required field is missing'
    ({"load": 1.0, "power_kw": 800},
     "measured.1.temperature_c: required field is missing: give the ambient temperature of "
     "the measurement [C]"),
    ({"temperature_c": 10, "power_kw": 800},
     "measured.1.load: required field is missing: give the load case of the measurement "
     "(full, empty or a fraction of the design load)"),
])
def test_a_row_problem_has_the_same_fix_on_both_doors(client, tmp_path, capsys, row, said):
    rows = [ROW, row]
    r = client.post("/calibrations", json={**BASE, "measured": rows})
    assert r.status_code == 422
    assert r.json()["message"] == said
    err, path = _cli(tmp_path, capsys, rows)
    assert err == f"error: {path}: line 3: {said}"
