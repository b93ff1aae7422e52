"""``beltstudy calibrate`` and ``POST /calibrations`` (SPEC 7.3) as a user meets them."""

from __future__ import annotations

import json
import subprocess
import sys

import numpy as np
import pytest
from fastapi.testclient import TestClient

from beltstudy.engine import load_conveyor, solve_steady
from beltstudy.service.api.app import create_app
from tests.conftest import CONVEYORS

EXE = [sys.executable, "-m", "beltstudy.service.cli"]
TRUTH = 0.0237


def _rows(noise=0.01, seed=3):
    conv = load_conveyor(CONVEYORS / "overland-4km.yaml")
    rng = np.random.default_rng(seed)
    out = []
    for load in (0.2, 0.4, 0.6, 0.8, 1.0):
        p = solve_steady(conv, model="din", params={"f_carry": TRUTH}, temperature_c=5.0,
                         load=load).summary["power_kw"]
        out.append({"load": load, "temperature_c": 5.0,
                    "power_kw": round(p * (1 + noise * rng.standard_normal()), 2)})
    return out


def test_cli_json_answer(tmp_path):
    csv = tmp_path / "plant.csv"
    csv.write_text("load,temperature_c,power_kw\n" + "".join(
        f"{r['load']},{r['temperature_c']},{r['power_kw']}\n" for r in _rows()))
    p = subprocess.run([*EXE, "calibrate", str(CONVEYORS / "overland-4km.yaml"), "--measured",
                        str(csv), "--model", "din", "--fit", "f_carry", "--param",
                        "f_return=0.020", "--json"], capture_output=True, text=True, timeout=120)
    assert p.returncode == 0, p.stderr
    out = json.loads(p.stdout)
    fit = out["fit"]["f_carry"]
    assert abs(fit["value"] - TRUTH) / TRUTH < 0.01 and abs(fit["value"] - TRUTH) <= 2 * fit["se"]
    assert out["models"]["din"]["f_return"] == 0.020
    assert len(out["residuals"]) == 5 and out["not_identifiable"] == []
    text = subprocess.run([*EXE, "calibrate", str(CONVEYORS / "overland-4km.yaml"),
                           "--measured", str(csv), "--model", "din", "--fit", "f_carry"],
                          capture_output=True, text=True, timeout=120).stdout
    assert "models:\n  din:\n    f_carry: 0.02" in text


def test_a_fit_that_warns_offers_its_models_block_commented_out(tmp_path):
    """Readings written in MW (the model computes about 1000 x each): the fit ends at its
    bound, f_carry about 0, status warning, the notes say the readings look written in MW.
    Its models block is not one to paste as it is: it is printed commented out, under a
    heading that names the status; a fit that is ok prints it plain (test above)."""
    csv = tmp_path / "plant_mw.csv"
    csv.write_text("load,temperature_c,power_kw\n" + "".join(
        f"{r['load']},{r['temperature_c']},{r['power_kw'] / 1000:.4f}\n" for r in _rows()))
    from beltstudy.service.cli.calibrate import format_calibration

    p = subprocess.run([*EXE, "calibrate", str(CONVEYORS / "overland-4km.yaml"), "--measured",
                        str(csv), "--model", "din", "--fit", "f_carry", "--json"],
                       capture_output=True, text=True, timeout=120)
    out = json.loads(p.stdout)
    assert out["status"] == "warning" and any("MW" in n for n in out["notes"])
    text = format_calibration(out)
    head, block = text.split("models block for a study", 1)[1].split("\n", 1)
    assert "status is warning" in head
    assert block.splitlines()[:2] == ["# models:", "#   din:"]
    assert "\nmodels:" not in text


def test_cli_unknown_name_exits_2(tmp_path):
    csv = tmp_path / "plant.csv"
    csv.write_text("load,temperature_c,power_kw\nfull,5,900\n")
    p = subprocess.run([*EXE, "calibrate", str(CONVEYORS / "overland-4km.yaml"), "--measured",
                        str(csv), "--model", "nonlin", "--fit", "seal_drag"],
                       capture_output=True, text=True, timeout=120)
    assert p.returncode == 2
    assert "fit: 'seal_drag' is not a parameter of model nonlin" in p.stderr
    assert "drag_per_roll_n" in p.stderr and "Traceback" not in p.stderr


@pytest.fixture
def client(data_dir, make_settings):
    return TestClient(create_app(make_settings(data_dir)))


def test_post_calibrations(client):
    body = {"conveyor": "conveyors/overland-4km.yaml", "measured": _rows(), "model": "din",
            "fit": ["f_carry=0.015"]}
    r = client.post("/calibrations", json=body)
    assert r.status_code == 200, r.text
    out = r.json()
    assert out["fit"]["f_carry"]["start"] == 0.015
    assert abs(out["fit"]["f_carry"]["value"] - TRUTH) / TRUTH < 0.01
    assert set(out) >= {"fit", "residuals", "not_identifiable", "models"}


def test_post_calibrations_names_the_bad_field(client):
    body = {"conveyor": "conveyors/overland-4km.yaml", "model": "din", "fit": ["f_carry"],
            "measured": [{"load": "full", "temperature_c": 5}]}
    r = client.post("/calibrations", json=body)
    assert r.status_code == 422
    assert r.json()["message"] == "measured.0: give the measured power_kw or te_kn"
    r = client.post("/calibrations", json={**body, "conveyor": "../etc/passwd"})
    assert r.status_code == 422 and "studies directory" in r.json()["message"]


def test_an_unknown_model_names_the_requests_field_model(client):
    """POST /calibrations with model: xx answered 'friction_model: unknown model', the name of
    a study's grid axis, not of this body's field: it is 'model: ...'."""
    body = {"conveyor": "conveyors/overland-4km.yaml", "measured": _rows(), "model": "dinx",
            "fit": ["f_carry"]}
    r = client.post("/calibrations", json=body)
    assert r.status_code == 422, r.text
    assert r.json()["message"].startswith("model: unknown model 'dinx' (did you mean 'din'?)")


def test_a_held_parameter_names_the_requests_own_field(client, tmp_path):
    """A bad held parameter was named models.din.<name>, a path of a study, not of this
    request: the body's field is params.<name>, the command line's --param <name>."""
    body = {"conveyor": "conveyors/overland-4km.yaml", "measured": _rows(), "model": "iso5048",
            "fit": ["f_carry"]}
    r = client.post("/calibrations", json={**body, "params": {"f_retrun": 0.02}})
    assert r.status_code == 422
    assert r.json()["message"].startswith("params.f_retrun: unknown parameter of model 'din'")
    r = client.post("/calibrations", json={**body, "params": {"f_return": -1}})
    assert r.status_code == 422
    assert r.json()["message"].startswith("params.f_return: a friction factor between 0 and 1")
    csv = tmp_path / "plant.csv"
    csv.write_text("load,temperature_c,power_kw\nfull,5,900\n0.5,5,500\n")
    p = subprocess.run([*EXE, "calibrate", str(CONVEYORS / "overland-4km.yaml"), "--measured",
                        str(csv), "--model", "din", "--fit", "f_carry", "--param",
                        "f_return=-1"], capture_output=True, text=True, timeout=120)
    assert p.returncode == 2 and "Traceback" not in p.stderr
    assert p.stderr.startswith("error: --param f_return: a friction factor between 0 and 1")


def test_a_held_parameter_that_is_no_number_is_named_on_the_command_line(tmp_path, capsys):
    """--param f_return=nan was refused as 'error: PLANT.csv: params.f_return: ...': the CSV
    named for a value the command line gave, under the request's field name. It is the
    command line's --param f_return now, and a bad row beside it keeps its file and line."""
    from beltstudy.service.cli import main

    csv = tmp_path / "plant.csv"
    csv.write_text("load,temperature_c,power_kw\nfull,5,900\n0.5,5,500\n")
    args = ["calibrate", str(CONVEYORS / "overland-4km.yaml"), "--measured", str(csv),
            "--model", "din", "--fit", "f_carry", "--param", "f_return=nan"]
    assert main(args) == 2
    err = capsys.readouterr().err
    assert err.strip() == "error: --param f_return: Input should be a finite number (got nan)"
    csv.write_text("load,temperature_c,power_kw\nfull,5,900\n0.5,5,abc\n")
    assert main(args) == 2
    err = capsys.readouterr().err
    assert err.startswith(f"error: {csv}: line 3: measured.1.power_kw: ")
    assert err.strip().endswith("; --param f_return: Input should be a finite number (got nan)")


# ------------------------------------------------------------------ the measurement CSV
def test_a_folder_given_as_the_measurements_is_named_a_folder(tmp_path):
    from beltstudy.engine.errors import InputError
    from beltstudy.service.cli.calibrate import read_measured

    with pytest.raises(InputError, match=r"^--measured: .*: is a folder, not a file; give a "
                                         r"file in it$"):
        read_measured(str(tmp_path), [])



HEADER = "load,temperature_c,power_kw"


@pytest.mark.parametrize("encoding", ["utf-8-sig", "utf-16"])
def test_csv_from_excel_or_notepad_reads_as_utf8(tmp_path, encoding):
    """Excel's "CSV UTF-8" (a byte order mark, CRLF) and UTF-16 with its byte order mark."""
    from beltstudy.service.cli.calibrate import read_measured

    path = tmp_path / "plant.csv"
    path.write_bytes(f"{HEADER}\r\n0.5,12,417.5\r\n\r\nfull,20,741.9\r\n".encode(encoding))
    assert read_measured(str(path)) == [
        {"load": "0.5", "temperature_c": "12", "power_kw": "417.5"},
        {"load": "full", "temperature_c": "20", "power_kw": "741.9"}]


@pytest.mark.parametrize(("text", "message"), [
    (b"load;temperature_c;power_kw\n0,5;12;417,5\n",
     "line 1: the columns are separated by ';'; the file must be comma-separated with a "
     "decimal point"),
    # a spreadsheet's copy and paste: tabs (was "unknown column 'load\ttemperature_c\t...';
    # did you mean 'temperature_c'?")
    (b"load\ttemperature_c\tpower_kw\n0.5\t12\t417.5\n",
     "line 1: the columns are separated by tabs; the file must be comma-separated with a "
     "decimal point"),
    (b"load,temperature_c,power_kw,power_kw\n0.5,12,417,9999\n",
     "line 1: column 'power_kw' given twice (columns 3 and 4); give each column once"),
    (b"load,temp_c,power_kw\n0.5,12,417\n",
     "line 1: unknown column 'temp_c'; did you mean 'temperature_c'?"),
    # a file that is no measured data at all (a conveyor's YAML given to --measured) was
    # refused column by column from its comment line; a header of near misses keeps its hints
    (b"# A 5 % slope conveyor, modelled on Harrison (2008), Fig. 2\nname: slope-5pct\n",
     "line 1 names none of the measured-data columns (load, temperature_c, power_kw, te_kn, "
     "t_tight_kn, speed_m_s): --measured takes a CSV file whose first line names them"),
    (b"Load,Temperature,Power\n0.5,12,417\n", "unknown column 'Load'; did you mean 'load'?"),
    (b"load,temperature_c,power_kw\n0.5,12,417,5\n",
     "line 2: 4 cells, but the header names 3 columns"),
    ("load,temperature_c,power_kw\n# Förderband\n".encode("latin-1"),
     "not UTF-8 text (byte 0xf6 at line 2, column 4): save it as UTF-8"),
    (b"load,temperature_c,power_kw\n0.5,12,nan\n",
     "measured.0.power_kw: Input should be a finite number"),
    # a cell beyond the csv module's field limit, more rows than a calibration takes (counted
    # before any is read into a row), a file far beyond 200 rows of numbers
    (b"load,temperature_c,power_kw\n1.0,22," + b"7" * 200_000 + b"\n",
     "line 2: not a CSV row (field larger than field limit (131072))"),
    (b"load,temperature_c,power_kw\n" + b"0.5,12,417.5\n" * 201,
     "more than 200 measured rows (201); a calibration takes at most 200"),
    (b"load,temperature_c,power_kw\n" + b"0.5,12,417.5\n" * 80_000, "MB; a calibration reads "
     "at most 200 rows"),
    # a row's problem names the row's line (blank lines counted)
    (b"load,temperature_c,power_kw\n0.5,12,417.5\n\n1.0,12,0\n",
     "line 4: measured.1.power_kw: a measured power_kw must not be 0"),
    (b"load,temperature_c,power_kw,speed_m_s\n0.5,12,417.5,500\n",
     "line 2: measured.0.speed_m_s: Input should be less than or equal to 30"),
    (b'load,temperature_c,power_kw\n"1,0,0,0,0,0,0,0",12,417.5\n',
     "line 2: measured.0.load: 8 fractions for"),
    # a column every row needs, missing from the header, is said once for the header (not
    # once per row, nor as 'measured.0: give the measured ...'); an empty file or a header
    # without rows in words, not pydantic's 'List should have at least 1 item'
    (b"load,power_kw\n0.2,47.7\n0.5,67.9\n0.8,88.1\n",
     "line 1: no column 'temperature_c'; every row needs its ambient temperature [C]"),
    (b"load,temperature_c\n0.2,5\n0.5,10\n",
     "line 1: no column 'power_kw' or 'te_kn'; give the measured power at the drive pulleys"),
    (b"load,temperature_c,power_kw\n", "no measured rows below the header (line 1); give one "
     "row per measured steady state (load, temperature_c, and power_kw or te_kn)"),
    (b"", "empty: give a header line (load,temperature_c,power_kw) and one row per measured"),
])
def test_csv_problems_are_one_line_naming_the_file(tmp_path, capsys, text, message):
    from beltstudy.service.cli import main

    path = tmp_path / "plant.csv"
    path.write_bytes(text)
    assert main(["calibrate", str(CONVEYORS / "overland-4km.yaml"), "--measured", str(path),
                 "--model", "din", "--fit", "f_carry"]) == 2
    err = capsys.readouterr().err
    assert err.startswith(f"error: {path}: ") and message in err, err
    assert len(err.strip().splitlines()) == 1 and "Traceback" not in err


def test_post_calibrations_says_problems_as_the_study_door_does(client):
    body = {"conveyor": "conveyors/overland-4km.yaml", "model": "din", "fit": ["f_carry"],
            "measured": _rows()[:2]}
    bad = json.loads(json.dumps(body))
    bad["measured"][1]["temp_c"] = 3
    r = client.post("/calibrations", json=bad)
    assert r.status_code == 422
    assert r.json()["message"] == ("measured.1.temp_c: unknown key 'temp_c'; did you mean "
                                   "'temperature_c'?")
    r = client.post("/calibrations", json={**body, "paramz": {}})
    assert r.json()["message"] == "paramz: unknown key 'paramz'; did you mean 'params'?"
    r = client.post("/calibrations", json={**body, "conveyor": {"name": "x", "sped_m_s": 2}})
    msg = r.json()["message"]
    assert "conveyor.sped_m_s: unknown key 'sped_m_s'; did you mean 'speed_m_s'?" in msg
    assert "conveyor.speed_m_s: required field is missing" in msg
    assert "inline" not in msg and "body." not in msg
    text = json.dumps(body).replace(str(body["measured"][0]["power_kw"]), "NaN", 1)
    r = client.post("/calibrations", content=text, headers={"content-type": "application/json"})
    assert r.status_code == 422
    assert r.json()["message"].startswith("measured.0.power_kw: NaN is not a number")


def test_post_calibrations_reads_the_body_as_post_studies_does(client):
    """YAML or JSON by Content-Type, 415 for any other, syntax errors with line and column,
    an empty body said as empty: the study door's reading, one function for both routes."""
    import yaml

    body = {"conveyor": "conveyors/overland-4km.yaml", "model": "din", "fit": ["f_carry"],
            "measured": _rows()[:2]}
    r = client.post("/calibrations", content=yaml.safe_dump(body).encode(),
                    headers={"content-type": "application/yaml"})
    assert r.status_code == 200, r.text
    assert set(r.json()["fit"]) == {"f_carry"}
    r = client.post("/calibrations", content=json.dumps(body).encode(),
                    headers={"content-type": "text/plain"})
    assert r.status_code == 415
    assert r.json()["message"].startswith("Content-Type: 'text/plain' is not read here; send "
                                          "a calibration as application/json or YAML")
    r = client.post("/calibrations", content=b'{"model": "din",\n "fit": [f_carry]}',
                    headers={"content-type": "application/json"})
    assert r.status_code == 422
    assert r.json()["message"].startswith("body: not valid JSON at line 2, column 10")
    r = client.post("/calibrations", content=b"model: din\nfit: [f_carry\n",
                    headers={"content-type": "application/yaml"})
    assert r.status_code == 422 and "body: not valid YAML at line" in r.json()["message"]
    r = client.post("/calibrations", content=b"", headers={"content-type": "application/json"})
    assert r.status_code == 422
    assert r.json()["message"] == "body: empty; send a calibration as JSON or YAML"
    r = client.post("/calibrations", json=[body])
    assert r.status_code == 422 and "body: expected a mapping" in r.json()["message"]
    spec = client.get("/openapi.json").json()
    content = spec["paths"]["/calibrations"]["post"]["requestBody"]["content"]
    assert content["application/yaml"]["schema"] == {"$ref": "#/components/schemas/CalibrationIn"}
    assert "measured" in spec["components"]["schemas"]["CalibrationIn"]["properties"]


def test_a_fit_stuck_at_a_bound_is_a_warning_in_our_words(client):
    """Data no value of f_carry >= 0 can reach (a loaded uphill belt measured at 5 kW, less
    than its lift alone takes): status warning, the parameter at its bound and the residual
    named, never SciPy's text. Measured regenerating (-5 kW), the reading's sign leads."""
    body = {"conveyor": "conveyors/slope-5pct.yaml", "model": "din", "fit": ["f_carry"],
            "measured": [{"load": "full", "temperature_c": 20, "power_kw": 5}]}
    r = client.post("/calibrations", json=body)
    assert r.status_code == 200, r.text
    out = r.json()
    assert out["status"] == "warning"
    import re

    assert re.match(r"f_carry ends at the bound 0 \(the data would take it below, which model "
                    r"din does not allow\) and the fit still misses the measurements by \d+ % "
                    r"\(rms relative residual\)\. Check the measured values", out["message"])
    assert "termination" not in out["message"] and "`" not in out["message"]
    assert out["fit"]["f_carry"]["value"] < 1e-6
    body["measured"][0]["power_kw"] = -5
    out = client.post("/calibrations", json=body).json()
    assert out["status"] == "warning"
    assert out["message"].startswith("1 of 1 measured values have the other sign than the "
                                     "fit's"), out["message"]
    good = client.post("/calibrations", json={**body, "measured": _rows()[:3],
                                              "conveyor": "conveyors/overland-4km.yaml"}).json()
    assert good["status"] == "ok"
    assert re.match(r"converged: rms relative residual [\d.e+-]+ % over 3 measured values$",
                    good["message"]), good["message"]


def test_the_verdict_of_a_fit_names_the_bound_and_what_would_help():
    """Each branch of the status and message (engine/calibration.py ``_verdict``)."""
    from types import SimpleNamespace

    from beltstudy.engine.calibration import _verdict

    done = SimpleNamespace(success=True, nfev=12, x=np.zeros(2))  # two names fitted
    small, large = np.full(4, 0.01), np.full(4, 0.3)
    assert _verdict(done, [], small, "din") == {
        "status": "ok", "message": "converged: rms relative residual 1 % over 4 measured values"}
    out = _verdict(done, ["m_star"], small, "nonlin")
    assert out["status"] == "warning"
    assert out["message"].startswith("m_star ends at the bound 0 (the data would take it below, "
                                     "which model nonlin does not allow); the fit matches the "
                                     "measurements to 1 % (rms relative residual) without it")
    alone = _verdict(SimpleNamespace(success=True, nfev=12, x=np.zeros(1)), ["m_star"], small,
                     "nonlin")
    assert alone["message"].startswith("m_star ends at the bound 0 (the data would take it "
                                       "below, which model nonlin does not allow); at the bound "
                                       "the fit meets the measurements to 1 %"), alone
    out = _verdict(done, ["f_carry", "f_return"], large, "din")
    assert out["status"] == "warning"
    assert out["message"].startswith("f_carry, f_return end at the bound 0 (the data would take "
                                     "them below, which model din does not allow) and the fit "
                                     "still misses the measurements by 30 %")
    out = _verdict(SimpleNamespace(success=False, nfev=400), [], large, "din")
    assert out == {"status": "failed", "message": "the fit stopped after 400 evaluations "
                   "without converging (rms relative residual 30 %): start it nearer the "
                   "answer (NAME=START) or fit fewer names"}


@pytest.mark.parametrize(("where", "value", "message"), [
    (("measured", 0, "power_kw"), "125", 'measured.0.power_kw: "125" is not of type "number"'),
    (("measured", 0, "temperature_c"), True,
     'measured.0.temperature_c: true is not of type "number"'),
    (("params",), {"f_return": "0.01"}, 'is not of type "number"'),
])
def test_post_calibrations_holds_values_to_their_json_types(client, where, value, message):
    """As a study's body: "125" is no number and true no temperature (it was fitted)."""
    body = {"conveyor": "conveyors/overland-4km.yaml", "model": "din", "fit": ["f_carry"],
            "measured": _rows()[:2]}
    node = body
    for key in where[:-1]:
        node = node[key]
    node[where[-1]] = value
    r = client.post("/calibrations", json=body)
    assert r.status_code == 422, r.text
    assert message in r.json()["message"], r.json()


def test_the_fit_names_each_row_with_its_line_in_the_file(tmp_path, capsys):
    """The fit counts rows from 0 (as ``measured.K``) while the file's errors and an editor
    count lines from 1 with the header on line 1: a CSV user read 'row 3' as the third data
    line. The CLI now puts each row's line beside it, in the words and the residuals, blank
    lines skipped: a second reading of load 0.6 15 % high as the sixth row, after a blank line,
    is row 5 on line 8, and an outlier's sentence gets its line the same way."""
    from beltstudy.service.cli import main
    from beltstudy.service.cli.calibrate import _rows_with_lines

    rows = _rows(noise=0.005)
    out = {**rows[2], "power_kw": round(rows[2]["power_kw"] * 1.15, 2)}
    text = "load,temperature_c,power_kw\n" + "".join(
        f"{r['load']},{r['temperature_c']},{r['power_kw']}\n" for r in rows) + "\n" + (
        f"{out['load']},{out['temperature_c']},{out['power_kw']}\n")
    csv = tmp_path / "plant.csv"
    csv.write_text(text)
    assert text.splitlines()[7].startswith(f"{out['load']},")  # line 8 of the file
    args = ["calibrate", str(CONVEYORS / "overland-4km.yaml"), "--measured", str(csv),
            "--model", "din", "--fit", "f_carry", "--param", "f_return=0.020"]
    main(args)
    said = capsys.readouterr().out
    assert "rows 2 and 5 (lines 4 and 8) read one steady state (load 0.6, 5 C)" in said, said
    assert "  row  line  measured" in said
    main([*args, "--json"])
    answer = json.loads(capsys.readouterr().out)
    assert [r["line"] for r in answer["residuals"]] == [2, 3, 4, 5, 6, 8]
    one = _rows_with_lines({"message": "row 5 (load 0.6, 5 C): measured power_kw 1024 lies",
                            "notes": [], "residuals": []}, [2, 3, 4, 5, 6, 8])
    assert one["message"] == "row 5 (line 8: load 0.6, 5 C): measured power_kw 1024 lies"
