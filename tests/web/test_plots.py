"""The study and run figures of service.plots on small hand-made tables."""

from __future__ import annotations

import numpy as np
import pandas as pd
import pytest

from service import plots, results


@pytest.fixture(autouse=True)
def _close_figures():
    yield
    plots._plt().close("all")


def _texts(fig) -> str:
    return " ".join(t.get_text() for t in fig.findobj(match=lambda a: hasattr(a, "get_text")))


def _runs(dynamic: bool = True) -> pd.DataFrame:
    rows = []
    for model, scale in (("cema", 1.0), ("nonlin", 0.8)):
        for load in ("full", "empty"):
            for temp in (-20.0, 0.0, 20.0):
                for stop in (10.0, 20.0):
                    power = scale * (100 - temp) * (1.0 if load == "full" else 0.4)
                    rows.append({
                        "run_id": f"{model}{load}{temp}{stop}", "friction_model": model,
                        "load": load, "temperature_c": temp, "stop_time_target_s": stop,
                        "status": "ok", "power_kw": power,
                        "t_max_dyn_kn": (200.0 / stop) * scale if dynamic else np.nan,
                        "stop_time_s": stop * 1.05 if dynamic else np.nan,
                    })
    return pd.DataFrame(rows)


def test_power_temperature_draws_a_line_per_model_and_load():
    fig = plots.power_temperature_figure(_runs())
    lines = fig.axes[0].get_lines()
    assert len(lines) == 4  # 2 models x 2 loads
    # each point is the mean over the stop-time axis
    cema_full = next(ln for ln in lines if ln.get_label() == "cema, load full")
    np.testing.assert_allclose(cema_full.get_xdata(), [-20, 0, 20])
    np.testing.assert_allclose(cema_full.get_ydata(), [120, 100, 80], rtol=1e-12)


def test_power_temperature_without_a_temperature_axis_uses_the_scenario_value():
    runs = _runs().drop(columns=["temperature_c"])
    fig = plots.power_temperature_figure(runs, temperature_c=5.0)
    assert all(set(ln.get_xdata()) == {5.0} for ln in fig.axes[0].get_lines())


def test_peak_dynamic_tension_per_model_against_achieved_stop_time():
    fig = plots.peak_dynamic_tension_figure(_runs())
    lines = {ln.get_label(): ln for ln in fig.axes[0].get_lines()}
    assert set(lines) == {"cema", "nonlin"}
    np.testing.assert_allclose(lines["cema"].get_xdata(), [10.5, 21.0])
    np.testing.assert_allclose(lines["cema"].get_ydata(), [20.0, 10.0])


def test_steady_only_results_give_the_no_transient_figure():
    fig = plots.peak_dynamic_tension_figure(_runs(dynamic=False))
    assert plots.NO_TRANSIENT in _texts(fig)
    fig = plots.transient_figure(pd.DataFrame(), None)
    assert plots.NO_TRANSIENT in _texts(fig)


def test_ratio_figure_from_the_compare_summary():
    runs = _runs()
    axes = ["friction_model", "load", "temperature_c", "stop_time_target_s"]
    summary = results.compare(runs, axes, "cema", "nonlin", ["power_kw", "t_max_dyn_kn"])
    fig = plots.ratio_figure(summary["summary"])
    assert len(fig.axes) == 2 * 3  # two metrics x three axes
    heights = [p.get_height() for ax in fig.axes for p in ax.patches]
    np.testing.assert_allclose(heights, 0.8, rtol=1e-12)
    empty = results.compare(_runs(dynamic=False), axes, "cema", "nonlin", ["t_max_dyn_kn"])
    assert "no pairs" in _texts(plots.ratio_figure(empty["summary"]))


def test_transient_figure_eight_points_round_the_loop_and_speed_below():
    t = np.arange(0.0, 10.0, 0.5)
    s = np.linspace(0.0, 2000.0, 41)
    surface = pd.DataFrame(
        [{"t_s": ti, "s_m": si, "tension_kn": 50 + si / 100 + ti, "velocity_m_s": ti / 4}
         for ti in t for si in s]
    )
    ts = pd.DataFrame({"t_s": t, "v_drive_m_s": t / 4, "v_tail_m_s": t / 4 - 0.1,
                       "t_head_in_kn": 60 + t})
    fig = plots.transient_figure(ts, surface, "fig4")
    top, bottom = fig.axes
    assert len(top.get_lines()) == 8
    assert [ln.get_label() for ln in top.get_lines()][0] == "s = 0 m"
    assert [ln.get_label() for ln in top.get_lines()][-1] == "s = 2000 m"
    assert {ln.get_label() for ln in bottom.get_lines()} == {"drive pulley", "tail pulley"}
    # without the long table, the key points are drawn
    fig = plots.transient_figure(ts, None)
    assert [ln.get_label() for ln in fig.axes[0].get_lines()] == ["head in (T1)"]
