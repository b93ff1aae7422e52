"""The ``beltstudy simulate`` table keeps small figures readable: a 30 m belt's automatic time
step (about 2.3e-4 s) was printed as "0.000 s"."""

from __future__ import annotations

import re

import numpy as np
import yaml

from beltstudy.service.cli.simulate import _fmt
from tests.conftest import short30_dict

SHORT = short30_dict()


def test_fmt_small_figures_keep_three_significant_figures():
    # 2.3022e-4 s to three decimals is 0.000; three significant figures keep it within 0.1 %
    assert abs(float(_fmt(2.3022e-4)) - 2.3022e-4) <= 1e-3 * 2.3022e-4
    assert abs(float(_fmt(-4.0e-4)) + 4.0e-4) <= 1e-3 * 4.0e-4
    # a figure that three decimals show stays as it was, and zero stays 0.000
    assert _fmt(4.912) == "       4.912"
    assert _fmt(0.0) == "       0.000"
    assert _fmt(0.006259) == "     0.00626"
    # a halved step reads apart from the automatic one (both read "0.001" before)
    assert _fmt(0.0005) == "      0.0005" and _fmt(0.000809) == "    0.000809"
    assert _fmt(0.0123) == "       0.012"
    assert len(_fmt(1e-9)) == 12


def test_fmt_counts_print_as_integers():
    # elements_used (an int in the summary) read "202.000 -" beside figures with units
    assert _fmt(202) == f"{202:>12d}"
    assert _fmt(np.int64(202)) == f"{202:>12d}"
    assert _fmt(202.0) == "     202.000"  # a figure that happens to be whole stays a figure


def test_simulate_table_time_step_of_a_short_belt_is_not_zero(tmp_path, capsys):
    from beltstudy.service.cli import main

    conv = tmp_path / "short30.yaml"
    conv.write_text(yaml.safe_dump(SHORT))
    code = main(["simulate", str(conv), "--no-check", "--no-remedy",
                 "--start-time-s", "5", "--run-s", "2"])
    out = capsys.readouterr().out
    assert code in (0, 1), out
    m = re.search(r"^\s+time step\s+(\S+) s$", out, re.M)
    assert m, out
    dt = float(m.group(1))
    assert re.search(r"^\s+elements\s+\d+ -$", out, re.M), out  # a count, no decimals
    # the automatic mesh cuts the 61.7 m loop into about 200 elements, dx ~ 0.3 m; the return
    # strand's wave speed is about 590 m/s (sqrt(EB / rho')), so the explicit limit dx / c is
    # ~ 5e-4 s: the step is below it, and above zero
    assert 0.0 < dt < 5.2e-4, out
