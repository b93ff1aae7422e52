"""`beltstudy static` names what set each drive's rated power on that drive's row.

A conveyor with two drives rated in the file and a third left to the auto size: the run's
``rated_power_governed_by`` joins the drives' constraints (``given+peripheral_force``), and the
table printed that joined text on every drive's row, so the two given motors read as if the
peripheral force had set them too. Each row now says its own: ``given`` for a rating the file
gives, the constraint behind the auto size for the other.
"""

from __future__ import annotations

import subprocess
import sys

import pytest
import yaml

from beltstudy.service.cli.common import design_lines, drive_governed

EXE = [sys.executable, "-m", "beltstudy.service.cli"]

CONVEYOR = {
    "name": "three-drives-one-auto",
    "speed_m_s": 4.5,
    "belt": {"type": "ST3150", "width_m": 1.4},
    "material": {"capacity_t_h": 3000, "density_t_m3": 1.7, "loading_speed_m_s": 0.0},
    "profile": [{"length_m": 2000, "lift_m": 150}],
    "idlers": {
        "carry": {"spacing_m": 1.5, "roll_diameter_m": 0.152, "rolls": 3, "trough_deg": 35,
                  "cema_class": "D"},
        "return": {"spacing_m": 3.0, "roll_diameter_m": 0.152, "rolls": 1, "cema_class": "C"},
    },
    "drives": [
        {"position": "head", "wrap_deg": 200, "friction": 0.35, "share": 0.5,
         "pulley_diameter_m": 1.4, "inertia_kg_m2": 1500, "rated_power_kw": 1000},
        {"position": "head", "wrap_deg": 200, "friction": 0.35, "share": 0.3,
         "pulley_diameter_m": 1.4, "inertia_kg_m2": 1500, "rated_power_kw": 600},
        {"position": "tail", "wrap_deg": 180, "friction": 0.35, "share": 0.2,
         "pulley_diameter_m": 1.4, "inertia_kg_m2": 1000},
    ],
    "takeup": {"type": "gravity", "position": "tail", "mass_kg": "auto", "travel_m": 10},
    "holdback": True,
}


def _row(out: str, label: str) -> str:
    return next(line for line in out.splitlines() if line.strip().startswith(label))


def test_each_drive_row_says_what_set_its_own_rated_power(tmp_path):
    path = tmp_path / "three-drives.yaml"
    path.write_text(yaml.safe_dump(CONVEYOR))
    p = subprocess.run([*EXE, "static", str(path)], capture_output=True, text=True,
                       timeout=120)
    assert p.returncode == 0, p.stderr
    # the given ratings as given; the auto one 1.25 x its share of Te x v / 0.95 (the motor
    # power through the default drive train), Te by hand (DIN,
    # f 0.020, C(2000 m) 1.05): belt (20.4 + 1.15 x 14) x 1.4 = 51.1 kg/m, load 3000 / (3.6 x
    # 4.5) = 185.19 kg/m, rolls 18.5 x 1.4 / 1.5 = 17.27 and 17.0 x 1.4 / 3 = 7.93 kg/m,
    # cos = 0.99718: carry 0.02 x 9.81 x 2000 x (17.27 + 236.29 x 0.99718) = 99.23 kN,
    # return 392.4 x (7.93 + 51.1 x 0.99718) = 23.11 kN, secondary 0.05 x 122.34 = 6.12 kN,
    # lift 185.19 x 9.81 x 150 = 272.50 kN: Te 400.96 kN, 0.2 x 400.96 x 4.5 x 1.25 / 0.95 =
    # 474.8 kW
    for label, kw, why in (("rated power, drive 1", 1000.0, "given"),
                           ("rated power, drive 2", 600.0, "given"),
                           ("rated power, drive 3", 474.8, "peripheral_force")):
        row = _row(p.stdout, label)
        assert float(row.split()[-3]) == pytest.approx(kw, rel=1e-3), row
        assert row.split()[-1] == why, row


def test_drive_governed_splits_the_joined_constraints():
    assert drive_governed("given+peripheral_force", True) == "given"
    assert drive_governed("given+peripheral_force", False) == "peripheral_force"
    assert drive_governed("given+running_resistance @ full", False) == \
        "running_resistance @ full"
    assert drive_governed("peripheral_force", False) == "peripheral_force"
    assert drive_governed("given", True) == "given"
    assert drive_governed("given+peripheral_force", None) == "given+peripheral_force"
    assert drive_governed(None, True) is None
    s = {"takeup_pretension_kn": 100.0, "drive1_rated_power_kw": 1000.0,
         "drive2_rated_power_kw": 454.0, "rated_power_governed_by": "given+peripheral_force"}
    rows = [r for r in design_lines(s, drives_given=[True, False]) if "rated power" in r]
    assert rows[0].split()[-1] == "given" and rows[1].split()[-1] == "peripheral_force"
