"""The transient figure marks each extreme at its time and value. A 30 m belt's coast stop
peaked at 4.912 kN, 1.8 m from the tail, at t = 92.604 s; the bold 'highest tension' probe is
drawn from the surface, sampled every 1.32 s, whose samples there (91.31 s, 92.63 s) hold about
4.34 kN: the curve named 'highest tension' never came near the run's 4.912 kN and ran below
the thin probes' 4.8 kN."""

from __future__ import annotations

import numpy as np
import pandas as pd
import pytest

from beltstudy.service import charts


def _surface() -> pd.DataFrame:
    # two element centres either side of 1.8 m, sampled every 1.3233 s as the run's surface was
    t = np.arange(70) * 1.3233
    rows = []
    for ti in t:
        rows.append({"t_s": ti, "s_m": 1.5, "tension_kn": 4.336 if ti > 10 else 3.875})
        rows.append({"t_s": ti, "s_m": 2.1, "tension_kn": 4.342 if ti > 10 else 3.875})
    return pd.DataFrame(rows)


def _highest(fig):
    return [ln for ln in fig.axes[0].get_lines() if ln.get_label().startswith("highest tension")]


def test_the_highest_tension_is_marked_at_its_time_and_value():
    fig = charts.transient_figure(None, _surface(),
                                  extremes={"highest tension": (1.8, 4.912, 92.604)})
    lines = _highest(fig)
    # the figure reaches the run's peak, where and when the run found it
    assert max(float(np.max(ln.get_ydata())) for ln in lines) == pytest.approx(4.912, abs=1e-9)
    marks = [ln for ln in lines if len(ln.get_xdata()) == 1]
    assert marks, [ln.get_label() for ln in lines]
    assert float(marks[0].get_xdata()[0]) == pytest.approx(92.604, abs=1e-9)
    assert "4.912 kN at t = 92.6 s" in marks[0].get_label()


def test_without_a_time_only_the_probe_is_drawn():
    fig = charts.transient_figure(None, _surface(), extremes={"highest tension": (1.8, 4.912)})
    lines = _highest(fig)
    assert len(lines) == 1 and float(np.max(lines[0].get_ydata())) == pytest.approx(4.342)
