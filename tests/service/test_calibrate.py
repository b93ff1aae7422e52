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
    assert r.json()["message"] == "measured[0]: give the measured power_kw or te_kn"
    r = client.post("/calibrations", json={**body, "conveyor": "../etc/passwd"})
    assert r.status_code == 422 and "studies directory" in r.json()["message"]
