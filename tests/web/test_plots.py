"""The study and run figures of beltstudy.service.charts on small hand-made tables."""

from __future__ import annotations

import numpy as np
import pandas as pd
import pytest

from beltstudy.service import charts
from beltstudy.service.store import query


@pytest.fixture(autouse=True)
def _close_figures():
    yield
    charts._plt().close("all")


def _texts(fig) -> str:
    return " ".join(t.get_text() for t in fig.findobj(match=lambda a: hasattr(a, "get_text")))


def _runs(dynamic: bool = True) -> pd.DataFrame:
    rows = []
    for model, scale in (("cema", 1.0), ("nonlin", 0.8)):
        for load in ("full", "empty"):
            for temp in (-20.0, 0.0, 20.0):
                for stop in (10.0, 20.0):
                    # a small stop-time term keeps every row's power distinct, so each point
                    # of a figure can be traced back to exactly one row
                    power = scale * ((100 - temp) * (1.0 if load == "full" else 0.4) + stop / 100)
                    rows.append({
                        "run_id": f"{model}{load}{temp}{stop}", "friction_model": model,
                        "load": load, "temperature_c": temp, "stop_time_target_s": stop,
                        "status": "ok", "power_kw": power,
                        "t_max_dyn_kn": (200.0 / stop) * scale if dynamic else np.nan,
                        "stop_time_s": stop * 1.05 if dynamic else np.nan,
                    })
    return pd.DataFrame(rows)


AXES = ["friction_model", "load", "temperature_c", "stop_time_target_s"]


def assert_lines_never_join_other_axis_values(fig, runs, x, y, others):
    """Every point of every line is one row of ``runs``, and all points of a line share the
    values of every other varying axis: a line joining (or averaging) points of different
    axis values fails here."""
    keys_seen = []
    n_points = 0
    for ax in fig.axes:
        for line in ax.get_lines():
            keys = set()
            for xv, yv in zip(line.get_xdata(), line.get_ydata(), strict=True):
                match = runs[np.isclose(runs[x].astype(float), xv)
                             & np.isclose(runs[y].astype(float), yv, rtol=1e-12)]
                assert len(match) == 1, f"point ({xv}, {yv}) of '{line.get_label()}' is no row"
                keys.add(tuple(str(match.iloc[0][c]) for c in others))
                n_points += 1
            assert len(keys) == 1, f"line '{line.get_label()}' joins {sorted(keys)}"
            keys_seen.append(keys.pop())
    assert len(keys_seen) == len(set(keys_seen)), "two lines for one combination"
    return n_points


def test_power_temperature_draws_a_line_per_combination_of_the_other_axes():
    runs = _runs()
    fig = charts.power_temperature_figure(runs, axes=AXES)
    lines = [ln for ax in fig.axes for ln in ax.get_lines()]
    assert len(lines) == 2 * 2 * 2  # models x loads x stop times, no averaging
    others = ["friction_model", "load", "stop_time_target_s"]
    assert assert_lines_never_join_other_axis_values(
        fig, runs, "temperature_c", "power_kw", others) == len(runs)
    cema_full = next(ln for ln in lines if ln.get_label() == "cema, load full, "
                     "stop_time_target_s 10")
    np.testing.assert_allclose(cema_full.get_xdata(), [-20, 0, 20])
    np.testing.assert_allclose(cema_full.get_ydata(), [120.1, 100.1, 80.1], rtol=1e-12)


def test_many_combinations_become_small_multiples():
    runs = _runs()
    runs = pd.concat([runs.assign(belt_type=b) for b in ("ST1600", "ST2000")],
                     ignore_index=True)
    runs["power_kw"] += np.where(runs["belt_type"] == "ST2000", 1000.0, 0.0)
    fig = charts.power_temperature_figure(runs, axes=[*AXES, "belt_type"])
    panels = [ax for ax in fig.axes if ax.get_lines()]
    assert len(panels) == 2  # one per friction model, 8 lines each
    assert {ax.get_title() for ax in panels} == {"cema", "nonlin"}
    assert assert_lines_never_join_other_axis_values(
        fig, runs, "temperature_c", "power_kw",
        ["friction_model", "load", "stop_time_target_s", "belt_type"]) == len(runs)


def test_the_join_check_catches_a_joined_line():
    """The check above is not vacuous: a figure averaging over the stop times (as this page
    drew before) fails it."""
    plt = charts._plt()
    runs = _runs()
    fig, ax = plt.subplots()
    part = runs[(runs["friction_model"] == "cema") & (runs["load"] == "full")]
    curve = part.groupby("temperature_c")["power_kw"].mean()
    ax.plot(curve.index, curve.values)
    with pytest.raises(AssertionError, match="is no row"):
        assert_lines_never_join_other_axis_values(fig, runs, "temperature_c", "power_kw",
                                                  ["friction_model", "load"])
    fig, ax = plt.subplots()
    part = part[part["temperature_c"] == 0.0]
    ax.plot(part["temperature_c"], part["power_kw"], marker="o")  # two stop times, one line
    with pytest.raises(AssertionError, match="joins"):
        assert_lines_never_join_other_axis_values(
            fig, runs, "temperature_c", "power_kw", ["friction_model", "stop_time_target_s"])


def test_points_that_share_a_temperature_on_one_line_are_not_joined():
    """A sampled study's runs (friction factor drawn per run) share their temperatures: the
    points of one friction model at one temperature are drawn as points, while a line with
    one point per temperature stays a line."""
    rng = np.random.default_rng(3)
    rows = [{"run_id": f"s{i}", "friction_model": "din", "temperature_c": temp,
             "status": "ok", "power_kw": 100.0 + rng.normal()}
            for i, temp in enumerate([-10.0, 20.0] * 4)]
    runs = pd.DataFrame(rows)
    fig = charts.power_temperature_figure(runs, axes=["friction_model", "temperature_c"])
    lines = [ln for ax in fig.axes for ln in ax.get_lines() if len(ln.get_xdata())]
    assert len(lines) == 1 and len(lines[0].get_xdata()) == 8
    assert lines[0].get_linestyle() == "None"
    assert lines[0].get_marker() not in (None, "", "None")
    fig = charts.power_temperature_figure(_runs(), axes=AXES)
    assert all(ln.get_linestyle() != "None" for ax in fig.axes for ln in ax.get_lines()
               if len(ln.get_xdata()) > 1)


def test_power_temperature_without_a_temperature_axis_uses_the_scenario_value():
    runs = _runs().drop(columns=["temperature_c"])
    fig = charts.power_temperature_figure(runs, temperature_c=5.0,
                                         axes=["friction_model", "load"])
    assert all(set(ln.get_xdata()) == {5.0} for ax in fig.axes for ln in ax.get_lines())


def test_peak_tension_against_achieved_stop_time_a_line_per_other_combination():
    runs = _runs()
    runs["t_max_dyn_kn"] += runs["temperature_c"] / 1000 + np.where(runs["load"] == "full",
                                                                    0.5, 0.0)
    fig = charts.peak_dynamic_tension_figure(runs, axes=AXES)
    assert assert_lines_never_join_other_axis_values(
        fig, runs.assign(x=runs["stop_time_s"]), "x", "t_max_dyn_kn",
        ["friction_model", "load", "temperature_c"]) == len(runs)
    labels = {ln.get_label() for ax in fig.axes for ln in ax.get_lines()}
    assert "load full, temperature_c -20" in labels  # panels by model: 12 lines
    panel = next(ax for ax in fig.axes if ax.get_lines())
    assert "whole transient" in panel.get_ylabel()


def test_peak_tension_uses_the_stop_phase_columns_when_the_runs_have_them():
    runs = _runs()
    runs["t_max_stop_kn"] = runs["t_max_dyn_kn"] * 0.9 + runs["temperature_c"] / 1000 + \
        np.where(runs["load"] == "full", 0.5, 0.0)
    runs["t_min_stop_kn"] = 5.0 + runs["temperature_c"] / 1000 + runs["stop_time_s"] / 1000 + \
        np.where(runs["load"] == "full", 0.5, 0.0) + np.where(
            runs["friction_model"] == "cema", 0.25, 0.0)
    fig = charts.peak_dynamic_tension_figure(runs, axes=AXES)
    tops = [ax for ax in fig.axes if ax.get_lines() and "peak" in ax.get_ylabel()]
    lows = [ax for ax in fig.axes if ax.get_lines() and "lowest" in ax.get_ylabel()]
    assert tops and lows and all("stop phase" in ax.get_ylabel() for ax in tops + lows)
    data = runs.assign(x=runs["stop_time_s"])
    for y, axes_ in (("t_max_stop_kn", tops), ("t_min_stop_kn", lows)):
        fig_part = type("F", (), {"axes": axes_})()
        assert assert_lines_never_join_other_axis_values(
            fig_part, data, "x", y, ["friction_model", "load", "temperature_c"]) == len(runs)


def test_steady_only_results_give_the_no_transient_figure():
    fig = charts.peak_dynamic_tension_figure(_runs(dynamic=False))
    assert charts.NO_TRANSIENT in _texts(fig)
    fig = charts.transient_figure(pd.DataFrame(), None)
    assert charts.NO_TRANSIENT in _texts(fig)


def test_ratio_figure_from_the_compare_summary():
    runs = _runs()
    axes = ["friction_model", "load", "temperature_c", "stop_time_target_s"]
    summary = query.compare(runs, axes, "cema", "nonlin", ["power_kw", "t_max_dyn_kn"])
    fig = charts.ratio_figure(summary["summary"])
    assert len(fig.axes) == 2 * 3  # two metrics x three axes
    heights = [p.get_height() for ax in fig.axes for p in ax.patches]
    np.testing.assert_allclose(heights, 0.8, rtol=1e-12)
    # a summary without ratios: every pair has a failed run (a metric no run has a value
    # of is refused by compare itself, tests/service/test_compare_asked_names.py)
    failed = _runs().assign(status="failed")
    empty = query.compare(failed, axes, "cema", "nonlin", ["t_max_dyn_kn"])
    assert "no pairs" in _texts(charts.ratio_figure(empty["summary"]))


def test_transient_figure_eight_points_round_the_loop_and_speed_below():
    t = np.arange(0.0, 10.0, 0.5)
    s = np.linspace(0.0, 2000.0, 41)
    surface = pd.DataFrame(
        [{"t_s": ti, "s_m": si, "tension_kn": 50 + si / 100 + ti, "velocity_m_s": ti / 4}
         for ti in t for si in s]
    )
    ts = pd.DataFrame({"t_s": t, "v_drive_m_s": t / 4, "v_tail_m_s": t / 4 - 0.1,
                       "t_head_in_kn": 60 + t})
    fig = charts.transient_figure(ts, surface, "fig4")
    top, bottom = fig.axes
    assert len(top.get_lines()) == 8
    assert [ln.get_label() for ln in top.get_lines()][0] == "0 m round the loop"
    assert [ln.get_label() for ln in top.get_lines()][-1] == "2000 m round the loop"
    assert {ln.get_label() for ln in bottom.get_lines()} == {"drive pulley", "tail pulley"}
    # without the long table, the key points are drawn
    fig = charts.transient_figure(ts, None)
    assert [ln.get_label() for ln in fig.axes[0].get_lines()] == ["head in (T1)"]


def test_transient_figure_probes_the_extremes_and_names_carry_and_return():
    """Probes at the highest and lowest tension, every probe named by strand and distance
    from the tail: on a 1 km conveyor the return strand runs from the head (s = 1000 m) back
    to the tail, so s = 1600 m round the loop is the return at 400 m from the tail."""
    t = np.arange(0.0, 10.0, 0.5)
    s = np.linspace(0.0, 2000.0, 41)
    surface = pd.DataFrame([{"t_s": ti, "s_m": si, "tension_kn": 50 + si / 100 + ti}
                            for ti in t for si in s])

    def locate(x):
        return ("carry", x) if x <= 1000 else ("return", 2000 - x)

    fig = charts.transient_figure(None, surface, "a long title " * 12,
                                 extremes={"highest tension": 1012.0,
                                           "lowest tension": 1590.0}, locate=locate)
    labels = [ln.get_label() for ln in fig.axes[0].get_lines()]
    assert len(labels) == 10
    assert "carry, 0 m from the tail" in labels
    assert "highest tension: carry, 1000 m from the tail" in labels
    assert "lowest tension: return, 400 m from the tail" in labels
    assert "\n" in fig._suptitle.get_text()  # the long title wraps


def test_an_axis_that_changes_nothing_is_drawn_once_and_named():
    """Steady power does not depend on the stop time: one line per model and load, not two
    identical ones on top of each other, and the figure says so."""
    runs = _runs()
    runs["power_kw"] = runs["power_kw"] - runs["stop_time_target_s"] / 100 * np.where(
        runs["friction_model"] == "cema", 1.0, 0.8)
    fig = charts.power_temperature_figure(runs, axes=AXES)
    lines = [ln for ax in fig.axes for ln in ax.get_lines()]
    assert len(lines) == 4
    assert "the same for every value of stop_time_target_s" in _texts(fig)
    assert assert_lines_never_join_other_axis_values(
        fig, runs.drop_duplicates(["friction_model", "load", "temperature_c"]),
        "temperature_c", "power_kw", ["friction_model", "load"]) == 12


def test_an_axis_zipped_with_the_temperature_runs_along_the_x_axis():
    """DIN's f zipped with the temperature changes with it: one line per model and load
    through all temperatures (not one dot per f), the x label names the zipped axis."""
    runs = _runs()
    runs = runs[runs["stop_time_target_s"] == 10.0].drop(columns=["stop_time_target_s"])
    runs["models.din.f_carry"] = runs["temperature_c"].map({-20.0: 0.025, 0.0: 0.02,
                                                            20.0: 0.017})
    fig = charts.power_temperature_figure(
        runs, axes=["friction_model", "load", "temperature_c", "models.din.f_carry"],
        groups=[["temperature_c", "models.din.f_carry"]])
    lines = [ln for ax in fig.axes for ln in ax.get_lines()]
    assert len(lines) == 4 and all(len(ln.get_xdata()) == 3 for ln in lines)
    assert "with models.din.f_carry" in fig.axes[0].get_xlabel()
    assert_lines_never_join_other_axis_values(fig, runs, "temperature_c", "power_kw",
                                              ["friction_model", "load"])


def test_runs_that_did_not_stop_are_counted_by_the_engines_stop_window():
    """The runs without a stop time are those whose belt was not at rest within the stop
    window (the engine's one rule, ``stop_window_s``): the note counts them and names it."""
    runs = _runs()
    runs["stop_window_s"] = 300.0
    runs.loc[runs.index[:3], "stop_time_s"] = np.nan
    fig = charts.peak_dynamic_tension_figure(runs, axes=AXES)
    assert "3 runs that did not stop within 300 s of the stop command" in _texts(fig)


def test_a_dynamic_study_whose_runs_all_failed_is_not_called_steady_only():
    """Every run of a dynamic study failed: the transient figures said 'no transient data
    (dynamics: false)' and the power figure 'no steady results yet' for a finished study."""
    runs = _runs().assign(status="failed", power_kw=np.nan, t_max_dyn_kn=np.nan,
                          stop_time_s=np.nan)
    for fig in (charts.peak_dynamic_tension_figure(runs, axes=AXES),
                charts.phase_peaks_figure(runs, axes=AXES),
                charts.power_temperature_figure(runs, axes=AXES)):
        text = _texts(fig)
        assert charts.NO_TRANSIENT not in text and "yet" not in text
        assert f"no results: all {len(runs)} finished runs failed" in text
    fig = charts.phase_peaks_figure(runs.iloc[:0], axes=AXES)
    assert "no finished runs yet" in _texts(fig) and charts.NO_TRANSIENT not in _texts(fig)


def _numbered(ax) -> bool:
    """The axis shows numbers under it (after a draw)."""
    return any(t.get_visible() and t.get_text() for t in ax.get_xticklabels())


def test_every_named_x_axis_is_numbered_when_the_last_row_of_panels_is_short():
    """Four panels of the stop figure on a grid three wide: with sharex, matplotlib numbers
    only the grid's last row, so the three panels of the first row (their lower axes above
    the two unused ones) said 'stop time achieved [s]' with no numbers under it (a 1.8 km
    incline study: friction model x temperature panels, colours by stop mode)."""
    rows = []
    for k, (model, temp, mode, mass) in enumerate(
            (m, t, s, w) for m in ("din", "nonlin") for t in (-25.0, 20.0)
            for s in ("coast", "brake", "controlled") for w in ("auto", "3000")):
        rows.append({"run_id": f"r{k}", "friction_model": model, "temperature_c": temp,
                     "scenario.stop.mode": mode, "takeup.mass_kg": mass, "status": "warning",
                     "t_max_stop_kn": 200.0 + k, "t_min_stop_kn": 3.0 + k / 10,
                     "t_max_dyn_kn": 260.0 + k, "stop_time_s": 5.0 + k / 5})
    runs = pd.DataFrame(rows)
    axes = ["friction_model", "temperature_c", "scenario.stop.mode", "takeup.mass_kg"]
    # the phase figure with three panels (start peak and low, stop peak) on a 2 x 2 grid
    three = runs.drop(columns=["t_min_stop_kn", "t_max_dyn_kn"]).assign(
        t_max_start_kn=runs["t_max_stop_kn"] + 5, t_min_start_kn=runs["t_min_stop_kn"] + 1)
    for fig, panels in ((charts.peak_dynamic_tension_figure(runs, axes=axes), 4),
                        (charts.phase_peaks_figure(three, axes=axes), 2)):
        fig.canvas.draw()
        named = [ax for ax in fig.axes if ax.get_visible() and ax.axison and ax.get_xlabel()]
        assert len(named) == panels
        assert all(_numbered(ax) for ax in named), [ax.get_xlabel() for ax in named
                                                    if not _numbered(ax)]


def test_the_highest_tension_probe_shows_the_peak_at_an_element_end():
    """A 1.8 km incline with two head drives: its peak, 219 kN, is reported at 1800 m, the
    end of the carry's last element (centre 1782 m, 216 kN) where the first drive pulley's
    element (centre 1801.7 m, 87 kN past the drive) begins. The nearest centre is the
    pulley's, so the bold 'highest tension' curve drew 87 kN under a 195 kN carry probe.
    Given the peak's value, the probe is the position on either side whose trace reaches it."""
    t = np.arange(0.0, 10.0, 0.5)
    s = np.array([1710.0, 1746.0, 1782.0, 1801.7454, 1821.4906, 1857.4906])
    level = {1710.0: 209.0, 1746.0: 212.5, 1782.0: 216.3, 1801.7454: 86.7, 1821.4906: 77.9,
             1857.4906: 77.6}
    surface = pd.DataFrame([{"t_s": ti, "s_m": si, "tension_kn": level[si] * (0.5 + ti / 19)}
                            for ti in t for si in s])

    def locate(x):
        return ("carry", x) if x <= 1800 else ("return", 3600 - x)

    def bold(fig):
        line = next(ln for ln in fig.axes[0].get_lines()
                    if ln.get_label().startswith("highest tension"))
        return line.get_label(), float(np.max(line.get_ydata()))

    label, peak = bold(charts.transient_figure(
        None, surface, extremes={"highest tension": (1800.0, 219.1)}, locate=locate))
    assert label == "highest tension: carry, 1782 m from the tail"
    assert peak == pytest.approx(216.3 * (0.5 + 9.5 / 19))
    # without the value the nearest centre is kept (the former rule)
    label, _ = bold(charts.transient_figure(
        None, surface, extremes={"highest tension": 1800.0}, locate=locate))
    assert label.startswith("highest tension: return")


@pytest.mark.parametrize("column, label", [
    ("temperature_c", "temperature_c [°C]"), ("takeup.mass_kg", "takeup.mass_kg [kg]"),
    ("stop_time_target_s", "stop_time_target_s [s]"),
    ("drives.0.speed_loop_rad_s", "drives.0.speed_loop_rad_s [rad/s]"),
    ("drives.1.inertia_kg_m2", "drives.1.inertia_kg_m2 [kg m²]"),
    ("material.capacity_t_h", "material.capacity_t_h [t/h]"),
    ("models.nonlin.drag_per_roll_n", "models.nonlin.drag_per_roll_n [N]"),
    ("friction_model", "friction_model"), ("load", "load"),
    ("scenario.stop.mode", "scenario.stop.mode")])
def test_axis_labels_carry_the_unit_of_the_column(column, label):
    assert charts.axis_label(column) == label


def test_the_peaks_and_ratio_figures_name_the_unit_of_their_x_axis():
    """The report's start and stop peaks figure and the ratio figure labelled the x axis with
    the bare column ('temperature_c'), where the power figure said 'temperature [°C]'."""
    runs = _runs()
    runs["t_max_start_kn"] = runs["t_max_dyn_kn"] + 1.0
    runs["t_max_stop_kn"] = runs["t_max_dyn_kn"]
    fig = charts.phase_peaks_figure(runs, axes=AXES)
    labels = {ax.get_xlabel() for ax in fig.axes if ax.get_xlabel()}
    assert labels == {"temperature_c [°C]"}
    summary = query.compare(runs, AXES, "cema", "nonlin", ["power_kw"])
    fig = charts.ratio_figure(summary["summary"])
    labels = {ax.get_xlabel() for ax in fig.axes if ax.get_xlabel()}
    assert labels == {"load", "temperature_c [°C]", "stop_time_target_s [s]"}


def test_a_stop_whose_lowest_tension_is_zero_is_drawn_whole_inside_the_frame():
    # a brake stop of a 1 km fabric belt went slack (t_min_stop_kn 0.0 at 3.82 s): the
    # figure began its lowest-tension axis at exactly 0, so that run, the worst one, was a
    # half marker on the frame line
    runs = _runs()
    runs["t_min_dyn_kn"] = 5.0 + runs["stop_time_s"] / 100 + runs["temperature_c"] / 1000
    runs.loc[0, "t_min_dyn_kn"] = 0.0
    fig = charts.peak_dynamic_tension_figure(runs, axes=AXES)
    fig.canvas.draw()
    lows = [ax for ax in fig.axes if ax.get_lines() and "lowest" in ax.get_ylabel()]
    assert lows
    zero_points = 0
    for ax in lows:
        box = ax.get_window_extent()
        for line in ax.get_lines():
            radius_px = line.get_markersize() / 2 * fig.dpi / 72
            for xv, yv in zip(line.get_xdata(), line.get_ydata(), strict=True):
                if yv != 0.0:
                    continue
                zero_points += 1
                _, y_px = ax.transData.transform((xv, yv))
                assert y_px - radius_px >= box.y0, "the point at zero tension is clipped"
        assert ax.get_ylim()[0] < 0.0 < ax.get_ylim()[1]
    assert zero_points == 1


def test_an_axis_of_auto_beside_numbers_is_drawn_as_categories():
    """A dynamic study with ``takeup.mass_kg: [auto, 3000]``: the stop figure read the axis
    as numbers (any value was one) and the report stopped on "Unable to parse string 'auto'".
    The axis is drawn as its two categories."""
    runs = pd.DataFrame({
        "run_id": ["a", "b"], "status": ["ok", "ok"], "friction_model": ["din", "din"],
        "takeup.mass_kg": ["auto", 3000], "t_max_start_kn": [50.0, 48.0],
        "t_max_stop_kn": [40.0, 39.0], "stop_time_s": [9.0, 9.5]})
    fig = charts.phase_peaks_figure(runs, axes=["takeup.mass_kg"])
    fig.canvas.draw()
    labels = {t.get_text() for ax in fig.axes for t in ax.get_xticklabels()}
    assert {"auto", "3000"} <= labels, labels
