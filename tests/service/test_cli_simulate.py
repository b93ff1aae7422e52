"""The ``beltstudy simulate`` command: the JSON summary, the time series and the plot, a scenario
file with overrides, one-line errors for bad input (exit 2)."""

from __future__ import annotations

import json

import pandas as pd
import pytest

from beltstudy.engine.dynamics.simulate import TIMESERIES_COLUMNS
from tests.conftest import CONVEYORS, TRANSIENT_FIELDS

SLOPE = CONVEYORS / "slope-5pct.yaml"


def test_cli_simulate_json_timeseries_plot(tmp_path, capsys):
    from beltstudy.service.cli import main

    ts_path = tmp_path / "ts.parquet"
    png = tmp_path / "fig4.png"
    code = main(["simulate", str(SLOPE), "--model", "din", "--elements", "40",
                 "--start-time-s", "15", "--run-s", "5", "--stop-mode", "controlled",
                 "--stop-time-s", "10", "--json", "--timeseries", str(ts_path),
                 "--plot", str(png)])
    out = capsys.readouterr().out
    assert code == 0
    s = json.loads(out)
    assert s["stop_mode"] == "controlled" and s["elements_used"] == 42
    for key in TRANSIENT_FIELDS + ("status", "message"):
        assert key in s
    # checked by default: meshes of about half and twice the run's, a bar on each figure
    coarse, run, fine = (int(x) for x in s["accuracy_elements"].split("/"))
    assert run == 42 and abs(coarse - 21) <= 2 and abs(fine - 84) <= 2
    assert s["t_max_dyn_kn_err"] >= 0.0 and s["stop_time_s_err"] >= 0.0
    ts = pd.read_parquet(ts_path)
    assert tuple(ts.columns[: len(TIMESERIES_COLUMNS)]) == TIMESERIES_COLUMNS
    assert png.stat().st_size > 10_000


def test_cli_scenario_file_with_overrides(tmp_path, capsys):
    from beltstudy.service.cli import main

    scn = tmp_path / "scn.yaml"
    scn.write_text("scenario:\n  load: empty\n  start: {control: linear, time_s: 12}\n"
                   "  run_s: 3\n  stop: {mode: coast}\n  elements: 40\n")
    code = main(["simulate", str(SLOPE), "--scenario", str(scn), "--stop-mode", "controlled",
                 "--stop-time-s", "30", "--start-control", "s-curve", "--start-time-s", "60",
                 "--json", "--no-check"])
    s = json.loads(capsys.readouterr().out)
    assert code == 0
    assert "accuracy_elements" not in s and "t_max_dyn_kn_err" not in s
    assert s["load"] == "empty" and s["stop_mode"] == "controlled"
    assert s["elements_used"] == 42 and s["status"] != "failed"


@pytest.mark.parametrize("argv,expect", [
    (["--stop-mode", "brake"], "scenario.stop.mode"),
    (["--run-s", "-3"], "--run-s"),
    (["--dt-s", "2", "--elements", "40"], "scenario.dt_s"),
    (["--model", "nonlinn"], "unknown model"),
])
def test_cli_bad_input_one_line_exit_2(argv, expect, capsys):
    from beltstudy.service.cli import main

    code = main(["simulate", str(SLOPE), *argv])
    err = capsys.readouterr().err
    assert code == 2
    assert err.startswith("error: ") and expect in err
    assert err.count("\n") == 1


def test_cli_outputs_in_a_missing_folder_fail_before_the_run(tmp_path, capsys):
    from beltstudy.service.cli import main

    for option, name in (("--timeseries", "ts.csv"), ("--plot", "fig.png")):
        out = tmp_path / "missing" / name
        assert main(["simulate", str(SLOPE), option, str(out)]) == 2
        err = capsys.readouterr().err
        assert err == f"error: cannot write {out}: the folder {out.parent} does not exist\n"


def test_cli_simulate_plot_probes_the_extremes_by_their_values(tmp_path, capsys, monkeypatch):
    """The plot's bold probes are given the peak's and the low's value with their position,
    so a peak at an element's end is drawn on the side that reaches it (see
    tests/web/test_plots.py::test_the_highest_tension_probe_shows_the_peak_at_an_element_end)."""
    from beltstudy.service import charts
    from beltstudy.service.cli import main, simulate

    seen = {}
    real = charts.transient_figure

    def spy(*args, **kwargs):
        seen.update(kwargs.get("extremes") or {})
        return real(*args, **kwargs)

    monkeypatch.setattr(simulate, "transient_figure", spy)
    code = main(["simulate", str(SLOPE), "--model", "din", "--elements", "40",
                 "--start-time-s", "15", "--run-s", "5", "--stop-time-s", "10",
                 "--no-check", "--json", "--plot", str(tmp_path / "fig.png")])
    s = json.loads(capsys.readouterr().out)
    assert code == 0
    assert seen["highest tension"] == (s["t_max_dyn_at_m"], s["t_max_dyn_kn"],
                                       s["t_max_dyn_time_s"])
    assert seen["lowest tension"] == (s["t_min_dyn_at_m"], s["t_min_dyn_kn"],
                                      s["t_min_dyn_time_s"])


def test_cli_simulate_plot_title_says_a_dol_start_not_the_scenario_start_curve(
        tmp_path, capsys, monkeypatch):
    """A dol drive with a fluid coupling does not read start.time_s (docs/drives.md): an 800 m,
    5 % incline on a 400 kW dol motor started in 13.7 s, and its plot's title said 's-curve
    start 60 s', the scenario's curve that no drive followed (here slope-5pct.yaml's drive made
    dol with a fluid coupling)."""
    import yaml

    from beltstudy.service.cli import main, simulate

    conv = yaml.safe_load(SLOPE.read_text())
    for d in conv["drives"]:
        d.update(control="dol", coupling="fluid")
    path = tmp_path / "dol.yaml"
    path.write_text(yaml.safe_dump(conv))
    titles = []
    real = simulate.transient_figure

    def spy(*args, **kwargs):
        titles.append(kwargs["title"])
        return real(*args, **kwargs)

    monkeypatch.setattr(simulate, "transient_figure", spy)
    code = main(["simulate", str(path), "--model", "din", "--elements", "40",
                 "--start-time-s", "60", "--run-s", "5", "--stop-mode", "coast",
                 "--no-check", "--no-remedy", "--json", "--plot", str(tmp_path / "fig.png")])
    s = json.loads(capsys.readouterr().out)
    assert code == 0 and s["start_time_s"] is not None
    assert "s-curve" not in titles[0] and "60 s" not in titles[0]
    assert "dol start (fluid coupling)" in titles[0]
