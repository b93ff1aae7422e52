"""``POST /calibrations`` and ``beltstudy calibrate`` (SPEC 7.3) on rows as plants write them: a
per-section load as a list, a time column, an empty last column, decimal commas, a start the
model refuses."""

from __future__ import annotations

import pytest
from fastapi.testclient import TestClient

from beltstudy.service.api.app import create_app
from tests.conftest import CONVEYORS

BASE = {"conveyor": "conveyors/overland-4km.yaml", "model": "din", "fit": ["f_carry"]}


@pytest.fixture
def client(data_dir, make_settings):
    return TestClient(create_app(make_settings(data_dir)))


def test_a_per_section_load_list_is_accepted_over_rest(client):
    """overland-4km has five carry sections; load [1, 1, 1, 0, 0] (MeasuredRow.load is
    str | float | list[float], 'as in a scenario') was answered 422 'measured.0.load: expected
    a number, got [1.0, ...]'. It fits as the text "1,1,1,0,0" does."""
    answers = []
    for load in ([1, 1, 1, 0, 0], "1,1,1,0,0"):
        r = client.post("/calibrations", json={**BASE, "measured": [
            {"load": load, "temperature_c": 10, "power_kw": 900},
            {"load": 0.5, "temperature_c": 10, "power_kw": 800}]})
        assert r.status_code == 200, r.text
        answers.append(r.json())
    assert answers[0]["fit"] == answers[1]["fit"]
    assert answers[0]["residuals"] == answers[1]["residuals"]


def test_a_time_key_over_rest_says_calibration_takes_steady_states(client):
    """A row with time_s was answered "unknown key 'time_s'; did you mean 'te_kn'?"."""
    r = client.post("/calibrations", json={**BASE, "measured": [
        {"time_s": 0, "load": 0.5, "temperature_c": 10, "power_kw": 620}]})
    assert r.status_code == 422
    assert r.json()["message"] == (
        "measured.0.time_s: unknown key 'time_s'; calibration takes steady states, one row "
        "each, not a time series: give each steady stretch of the log as one row (its mean "
        "load, temperature and power) and drop 'time_s'")


@pytest.mark.parametrize(("text", "message"), [
    (b"time_s,load,temperature_c,power_kw\n0,0.5,10,620\n",
     "line 1: unknown column 'time_s'; calibration takes steady states, one row each, not a "
     "time series"),
    # Excel's trailing ',' after an empty last column
    (b"load,temperature_c,power_kw,\n0.5,10,620,\n0.8,5,800,\n",
     "line 1: the last column has no name (a trailing ',' on each line, as a spreadsheet "
     "writes an empty last column): remove the empty last column"),
    (b"load,,power_kw\n0.5,10,620\n", "line 1: column 2 has no name; name it (load, "
     "temperature_c, power_kw, te_kn, t_tight_kn, speed_m_s) or remove it"),
    # a decimal comma without quotes splits 0,5 into two cells
    (b"load,temperature_c,power_kw\n0,5,10,620\n",
     "line 2: 4 cells, but the header names 3 columns; give one cell per column; a decimal "
     "comma splits a number in two ('0,5' for 0.5 reads as the cells 0 and 5): write the "
     "numbers with a decimal point"),
    (b'load,temperature_c,power_kw\n0.5,10,"620,3"\n',
     "line 2: power_kw '620,3' is written with a decimal comma; write 620.3"),
])
def test_csv_words_name_the_fix(tmp_path, capsys, text, message):
    """A time column was answered "did you mean 'te_kn'?", an empty last column 'unknown
    column 4 (no name)', '0,5,10,620' only '4 cells, but the header names 3', and a quoted
    '620,3' '"620,3" is not of type "number"'."""
    from beltstudy.service.cli import main

    path = tmp_path / "plant.csv"
    path.write_bytes(text)
    assert main(["calibrate", str(CONVEYORS / "overland-4km.yaml"), "--measured", str(path),
                 "--model", "din", "--fit", "f_carry"]) == 2
    err = capsys.readouterr().err
    assert err.startswith(f"error: {path}: {message}"), err
    assert len(err.strip().splitlines()) == 1


def test_a_start_the_model_refuses_names_the_fit_option(tmp_path, capsys):
    """--fit f_carry=5 was refused as 'models.din.f_carry: ...', a study's field the user
    never typed."""
    from beltstudy.service.cli import main

    path = tmp_path / "plant.csv"
    path.write_text("load,temperature_c,power_kw\n0.5,10,620\n0.8,5,800\n")
    assert main(["calibrate", str(CONVEYORS / "overland-4km.yaml"), "--measured", str(path),
                 "--model", "din", "--fit", "f_carry=5"]) == 2
    err = capsys.readouterr().err
    assert err.startswith("error: fit: 'f_carry=5': the start of f_carry is out of the "
                          "model's range: a friction factor between 0 and 1 (DIN 22101: 0.010 "
                          "to about 0.04; got 5)"), err
    assert "models.din" not in err
