"""The study and run pages write numbers in engineering format with their column's unit
(``static/app.js``: ``fmtCell``), checked by running the page's own functions in node."""

from __future__ import annotations

import json
import shutil
import subprocess
from importlib import resources

import pytest

NODE = shutil.which("node")


@pytest.mark.skipif(NODE is None, reason="node is not installed")
def test_cells_are_engineering_numbers_with_units():
    src = resources.files("beltstudy.service.web").joinpath("static", "app.js").read_text()
    part = src[src.index("function fmtNumber"):src.index("// A message cell")]
    cases = [["power_kw", 16886.3], ["t_max_dyn_kn", 1.2e-5], ["velocity_max_m_s", 4.5123],
             ["takeup_mass_kg", 15000], ["temperature_c", -20], ["status", "ok"],
             ["slip_margin", 1.23456], ["holdback_torque_knm", 2500.0]]
    script = part + f"\nconsole.log(JSON.stringify({json.dumps(cases)}.map(([c, v]) => " \
        "fmtCell(c, v))));"
    out = subprocess.run([NODE, "-e", script], capture_output=True, text=True, timeout=60)
    assert out.returncode == 0, out.stderr
    nb, thin = "\u00a0", "\u202f"
    assert json.loads(out.stdout) == [
        f"16{thin}886{nb}kW", f"1.2 × 10⁻⁵{nb}kN", f"4.512{nb}m/s", f"15{thin}000{nb}kg",
        f"-20{nb}°C", "ok", "1.235", f"2{thin}500{nb}kN·m"]
