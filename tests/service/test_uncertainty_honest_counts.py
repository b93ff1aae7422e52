"""Sampled studies told honestly (SPEC 7.2 ``sample:``, 7.4; docs/uncertainty.md): the size a
Sobol' design really draws in the "too many runs" advice, the runs a distribution leaves out
(a slack strand's unbounded sag, a stop that never came), sample points against runs, and the
small words (a round-off sd, a missing rho, the chance |rho| of a running study, an empty
``axes``)."""

from __future__ import annotations

import math

import numpy as np
import pandas as pd
import pytest

from beltstudy.service.door.sample import sobol_base, sobol_n_within
from beltstudy.service.door.studyfile import resolve_study
from beltstudy.service.errors import Invalid, TooLarge
from beltstudy.service.uncertainty import format_text, sd_text, summarise
from tests.service.conftest import tiny_study

MASS = {"takeup.mass_kg": {"dist": "uniform", "low": 8000, "high": 9000}}


def _sobol(n: int, axes: dict = MASS) -> dict:
    return {"n": n, "method": "sobol", "seed": 1, "axes": axes}


def test_a_too_large_sobol_sample_is_told_the_largest_n_whose_design_fits():
    """Four temperatures x sample.n 6000 over one axis: Saltelli's design draws N (D + 2) =
    3 N points, N a power of two, the nearest to n: 6144 (N = 2048), 24576 runs against
    20000. The advice said 'at most 5000 points with this grid', and n 5000 draws 6144 too
    (5000 - 3072 = 1928 > 6144 - 5000 = 1144). The largest n whose design fits is 1.5 x 3072
    = 4608 (the tie goes to the smaller design); the factor is the design's 6144 points for
    the n written, not 'sample.n 6144'."""
    grid = {"temperature_c": [-10, 0, 10, 20]}
    with pytest.raises(TooLarge) as exc:
        resolve_study(tiny_study("huge", grid=grid, sample=_sobol(6000)))
    assert str(exc.value) == (
        "sample.n: the study has 24576 grid points (runs before identical ones are merged); "
        "the limit is 20000 (temperature_c 4 x the sobol "
        "design's 6144 points for sample.n 6000): give sample.n at most 4608 (method sobol "
        "draws N (D + 2) points, N a power of two, the nearest to n: 4608 draws 3072, 12288 "
        "runs with this grid), or method: lhs with sample.n at most 5000, or split the study "
        "into several")
    # without a grid: 20000 draws 24576 (N = 8192); at most 1.5 x 12288 = 18432
    with pytest.raises(TooLarge) as exc:
        resolve_study(tiny_study("huge", grid={"friction_model": ["din"]},
                                 sample=_sobol(20000)))
    assert "give sample.n at most 18432 (method sobol draws N (D + 2) points, N a power of " \
           "two, the nearest to n: 18432 draws 12288), or method: lhs with sample.n at most " \
           "20000," in str(exc.value)
    # the advice holds at the edge (a smaller limit keeps the test quick): within 2000 runs
    # of 4 temperatures, 500 points: S = 384 (N = 128), n <= 576; 577 draws 768
    assert resolve_study(tiny_study("edge", grid=grid, sample=_sobol(576)),
                         max_runs=2000).grid_points == 4 * 384
    with pytest.raises(TooLarge, match=r"\(temperature_c 4 x the sobol design's 768 points "
                                       r"for sample.n 577\): give sample.n at most 576 "):
        resolve_study(tiny_study("edge", grid=grid, sample=_sobol(577)), max_runs=2000)


def test_sobol_n_within_is_the_largest_n_whose_design_fits():
    """Against every n by brute force: the largest n whose design (sobol_base) has at most
    ``most`` points, for 1 to 4 axes; None where N = 2 is already too many."""
    for d in range(1, 5):
        per = d + 2
        for most in range(1, 40 * per):
            fits = [n for n in range(2 * per, 4 * most + 1) if sobol_base(n, d) * per <= most]
            want = (max(fits), sobol_base(max(fits), d) * per) if fits else None
            assert sobol_n_within(d, most) == want, (d, most)


def test_a_sobol_sample_that_fits_only_as_a_latin_hypercube_is_told_to_change_method():
    """Three axes: the smallest Saltelli design (N = 2) has 2 x 5 = 10 points; with 30 x 10
    = 300 grid points and a limit of 2000 runs only 6 points fit: no sample.n helps a sobol
    sample, a Latin hypercube of 6 does."""
    axes = {"takeup.mass_kg": MASS["takeup.mass_kg"],
            "models.din.f_return": {"dist": "uniform", "low": 0.015, "high": 0.03},
            "models.din.f_carry": {"dist": "uniform", "low": 0.015, "high": 0.03}}
    grid = {"friction_model": ["din"], "temperature_c": {"start": -20, "stop": 9, "step": 1},
            "load": [0.1, 0.2, 0.3, 0.4, 0.5, 0.6, 0.7, 0.8, 0.9, 1.0]}
    with pytest.raises(TooLarge) as exc:
        resolve_study(tiny_study("tight", grid=grid, sample=_sobol(10, axes)), max_runs=2000)
    assert str(exc.value) == (
        "sample.method: the study has 3000 grid points (runs before identical ones are "
        "merged); the limit is 2000 (friction_model 1 x "
        "temperature_c 30 x load 10 x sample.n 10): give method: lhs with sample.n at most 6 (method sobol's smallest design, N = 2, has "
        "2 (D + 2) = 10 points for D = 3 axes, 3000 runs with this grid), or split the study "
        "into several")


def test_an_empty_axes_block_is_told_to_give_an_axis_with_a_dist():
    """``axes: {}`` was refused in pydantic's words ('Dictionary should have at least 1 item
    after validation, not 0'), naming neither what to give nor how."""
    for strict in (False, True):  # a study file, and a POSTed body
        with pytest.raises(Invalid) as exc:
            resolve_study(tiny_study("empty", sample={"n": 8, "method": "lhs", "axes": {}}),
                          strict=strict)
        assert exc.value.message == (
            "sample.axes: give at least one axis with a dist (e.g. temperature_c: "
            "{dist: uniform, low: -25, high: 35})")


def test_slack_runs_without_a_sag_are_counted_past_every_quantile(data_dir):
    """A take-up of 1 to 600 kg on the 60 m conveyor: 2 of 8 points leave the return strand
    slack (t_min_kn -0.845 and -0.442 kN), whose sag has no bound and no value. The
    distribution read 'n 6' in the JSON and nothing in the text, while the same cell counted
    them as sagged. Now: n 6 of 8, the reason (the report's slack rule), and over all 8 with
    the two past every value p75 (position 0.75 x 7 = 5.25, past the 6th) and p95 are
    unbounded."""
    from beltstudy.service.store.parquet import Store
    from tests.service.conftest import store_finished

    data = tiny_study("slack", grid={"friction_model": ["din"]}, sample={
        "n": 8, "method": "lhs", "seed": 5,
        "axes": {"takeup.mass_kg": {"dist": "uniform", "low": 1, "high": 600}}})
    sid = store_finished(data_dir, data)
    store = Store(data_dir)
    runs = store.read_runs(sid)
    slack = runs["sag_max_pct"].isna()
    assert slack.sum() == 2 and (runs.loc[slack, "t_min_kn"] <= 0).all()
    out = summarise(store.read(sid)["study"], runs)
    (cell,) = out["cells"]
    sag = cell["figures"]["sag_max_pct"]
    assert (sag["n"], sag["points"], sag["without_value"], sag["unbounded"]) == (6, 8, 2, 2)
    assert sag["why"] == "slack, sag unbounded"
    assert sag["unbounded_quantiles"] == ["p75", "p95"]
    # the exceedance counts them as sagged, as before
    ex = {e["limit"]: e for e in cell["exceedance"]}
    assert ex["slack"]["runs_past"] == 2 and ex["sag"]["runs_past"] == 8
    # a figure every run has says nothing more
    power = cell["figures"]["power_kw"]
    assert (power["n"], power["without_value"], power["why"]) == (8, 0, "")
    assert ("    n 6 of 8; 2 without a value: slack, sag unbounded (past every bound: p75 and "
            "p95 of all 8 are unbounded); mean, sd and quantiles are of the 6 with a value"
            ) in format_text(out).splitlines()


def _transient_runs(n: int) -> tuple[dict, pd.DataFrame]:
    """A resolved 20-point lhs study and its runs with a transient's columns: stop times
    10.0, 10.1, ... s."""
    study = resolve_study(tiny_study("stops", grid={"friction_model": ["din"]}, sample={
        "n": n, "method": "lhs", "seed": 3,
        "axes": {"models.din.f_carry": {"dist": "uniform", "low": 0.015, "high": 0.03}}}))
    rows = [{"run_id": r.run_id, "status": "ok", **r.axes, "t_max_dyn_kn": 100.0,
             "stop_time_s": 10.0 + 0.1 * k, "message": ""} for k, r in enumerate(study.runs)]
    return study.to_json(), pd.DataFrame(rows)


def test_a_transient_that_did_not_stop_has_an_unbounded_stop_time():
    """Of 20 transients, run 0 did not stop (no stop time: the report's worst) and run 1
    never got going (no stop made: no value, not a bound). The stop time's distribution is
    of the 18 with a value; the one that did not stop lies past every value: over 19, p95 at
    0.95 x 18 = 17.1 reaches past the 18th, unbounded; the one that never moved is no
    bound."""
    study, runs = _transient_runs(20)
    runs.loc[0, ["stop_time_s", "message"]] = [np.nan, "the belt did not stop within 60 s"]
    runs.loc[1, "stop_time_s"] = np.nan  # below 1 % of design speed at the stop command
    d = summarise(study, runs, figures=("stop_time_s",))["cells"][0]["figures"]["stop_time_s"]
    assert (d["n"], d["points"], d["without_value"], d["unbounded"]) == (18, 20, 2, 1)
    assert d["why"] == "1 did not stop, stop_time_s unbounded; 1 never got going, no stop"
    assert d["unbounded_quantiles"] == ["p95"]
    assert d["quantiles"]["p50"] == pytest.approx(np.median(10.0 + 0.1 * np.arange(2, 20)))
    # a failed run has no value either, and is no bound
    runs.loc[2, ["stop_time_s", "status"]] = [np.nan, "failed"]
    d = summarise(study, runs, figures=("stop_time_s",))["cells"][0]["figures"]["stop_time_s"]
    assert d["why"] == ("1 did not stop, stop_time_s unbounded; 1 never got going, no stop; "
                        "1 the run failed") and d["unbounded"] == 1


def test_one_run_standing_for_many_points_is_said_so_and_the_limits_count_points(data_dir):
    """A Latin hypercube of DIN's f_carry (20 points) crossed with friction_model [din,
    cema]: cema does not read f_carry, so its 20 points are 1 run. The text said 'cema: 1
    runs', then 'past / runs 0 / 20', and 'rho: models.din.f_carry -' with no reason. Now
    '1 run standing for 20 sample points', 'past / points', and the note that the figure
    does not vary."""
    from beltstudy.service.store.parquet import Store
    from tests.service.conftest import store_finished

    data = tiny_study("merged", grid={"friction_model": ["din", "cema"]}, sample={
        "n": 20, "method": "lhs", "seed": 4,
        "axes": {"models.din.f_carry": {"dist": "uniform", "low": 0.015, "high": 0.03}}})
    sid = store_finished(data_dir, data)
    store = Store(data_dir)
    out = summarise(store.read(sid)["study"], store.read_runs(sid))
    cells = {c["grid"]["friction_model"]: c for c in out["cells"]}
    assert (cells["cema"]["runs"], cells["cema"]["points"]) == (1, 20)
    assert (cells["din"]["runs"], cells["din"]["points"]) == (20, 20)
    text = format_text(out).splitlines()
    assert "friction_model=cema: 1 run standing for 20 sample points" in text
    assert "friction_model=din: 20 runs" in text
    assert text.count("  limit                                  past / points      p   95 % "
                      "interval") == 2
    sens = cells["cema"]["sensitivity"]["power_kw"]
    assert sens["axes"]["models.din.f_carry"]["rho"] is None
    assert sens["note"] == "the figure does not vary"
    at = text.index(next(t for t in text if t.startswith("friction_model=cema")))
    power = next(i for i in range(at, len(text)) if text[i].startswith("  power_kw "))
    assert text[power].endswith("rho: models.din.f_carry -")
    assert text[power + 1] == "    note: the figure does not vary"
    # the report's section says the same: its limits table counts points, not runs
    from beltstudy.service.web import report as R
    from beltstudy.service.web.uncertainty import uncertainty_section

    html = uncertainty_section(store.read(sid)["study"], store.read_runs(sid), R._table, R._n,
                               R._png, R._figure)
    assert "friction_model = cema: 1 run standing for 20 sample points</h3>" in html
    assert "<th>points past it</th>" in html and "runs past it" not in html


def test_a_figure_that_does_not_vary_prints_sd_0():
    """A lowest tension of 39.97 kN in every run printed sd 7.29e-15 (pandas' round-off);
    below 1e-12 x |mean| the text says 0, a real spread keeps 3 digits."""
    assert sd_text(7.29e-15, 39.97) == "0"
    assert sd_text(1.14e-16, 0.6967) == "0"
    assert sd_text(0.34, 39.04) == "0.34"
    assert sd_text(0.0, 0.0) == "0"
    assert sd_text(3e-7, 1e-6) == "3e-07"  # small against nothing: a spread


def test_the_chance_rho_of_a_running_study_counts_the_points_with_a_run():
    """While a 24-point Latin hypercube runs, 15 points have a run: the chance |rho| is
    1.96 / sqrt(15 - 1) = 0.52, not the design's 1.96 / sqrt(23) = 0.41."""
    study, runs = _transient_runs(24)
    assert 1.959964 / math.sqrt(14) == pytest.approx(0.5238, abs=1e-4)
    note = summarise(study, runs.iloc[:15], figures=("stop_time_s",))["note"]
    assert note.startswith("rank correlations from 15 points with a run (of the 24 drawn): "
                           "an input a figure does not depend on shows |rho| up to about "
                           "0.52 by chance"), note
    assert "up to about 0.41 by chance" in summarise(study, runs, figures=("stop_time_s",))[
        "note"]
    # no run yet: nothing to read
    assert summarise(study, runs.iloc[:0], figures=("stop_time_s",))["note"].startswith(
        "0 points with a run (of the 24 drawn) give no rank correlation to read: wait for "
        "more runs")


def test_a_missing_rho_of_a_latin_hypercube_says_why():
    """A Latin hypercube's rho printed '-' with no note (a Sobol' cell's said 'the figure does
    not vary'): now either method says why, a constant figure or fewer than 3 values (2 runs
    of 20 finished: Spearman's rho of 2 points is +-1 whatever the inputs)."""
    study, runs = _transient_runs(20)
    runs["stop_time_s"] = 11.5
    sens = summarise(study, runs, figures=("stop_time_s",))["cells"][0]["sensitivity"]
    assert sens["stop_time_s"]["axes"]["models.din.f_carry"]["rho"] is None
    assert sens["stop_time_s"]["note"] == "the figure does not vary"
    _, runs = _transient_runs(20)
    sens = summarise(study, runs.iloc[:2], figures=("stop_time_s",))["cells"][0]["sensitivity"]
    assert sens["stop_time_s"]["axes"]["models.din.f_carry"]["rho"] is None
    assert sens["stop_time_s"]["note"] == "2 points with a value: a rank correlation needs 3"


def test_the_report_writes_the_sample_s_numbers_without_e_notation():
    """The report's uncertainty section printed ``takeup.mass_kg normal(mean 1.7e+04, sd 500)``
    and a ranking ``(6.3e-05)``: docs/web.md says numbers are never ``1.689e+4``. They are
    written as the rest of the report writes them."""
    from beltstudy.service.web.uncertainty import _g, _index

    assert _g(17000.0) == "17\u202f000" and _g(500.0) == "500" and _g(None) == "-"
    assert _index(6.3e-05) == "6.3 × 10⁻⁵"
    assert _index(0.4231) == "0.42" and _index(2e-30) == "0" and _index(None) == "-"
    assert "e+" not in _g(1.689e4) and "e-" not in _index(1.2e-7)


def test_a_figure_equal_to_round_off_is_not_ranked():
    """A lowest tension of 129.22343938 kN in half the Sobol' points and one unit in the last
    place above it in the others printed sd 0 and was ranked with a total index of 1.07 on
    the seal drag: it does not vary, as its sd says."""
    from beltstudy.service.uncertainty import sensitivity

    n, d = 32, 2
    sample = {"n": n, "method": "sobol", "seed": 1,
              "axes": {"models.nonlin.seal_drag_factor": {}, "models.din.f_carry": {}}}
    rng = np.random.default_rng(0)
    points = rng.random((n * (d + 2), d))
    y = np.where(points[:, 0] > 0.5, 129.22343938, 129.22343938000003)
    assert np.ptp(y) > 0  # the values differ, by one unit in the last place
    sens = sensitivity(sample, points, y)
    assert sens["note"] == "the figure does not vary"
    assert all(a.get("rho") is None and "ST" not in a for a in sens["axes"].values())
    # a spread beyond round-off is still ranked (by rank correlation on a Latin hypercube)
    lhs = {**sample, "method": "lhs"}
    varied = sensitivity(lhs, points[:n], 100.0 + points[:n, 0])
    assert varied["ranking"][0] == "models.nonlin.seal_drag_factor"
    assert varied["axes"]["models.nonlin.seal_drag_factor"]["rho"] == pytest.approx(1.0)


def test_a_figure_every_run_lacks_beyond_every_bound_is_still_listed(data_dir):
    """Every point slack (a take-up of 1 to 3 kg on the 60 m conveyor): the sag has no value
    in any run, and the figure was left out of the distributions, so the reader never saw
    that it was unbounded everywhere. It is listed with n 0 and the reason."""
    from beltstudy.service.store.parquet import Store
    from tests.service.conftest import store_finished

    data = tiny_study("all-slack", grid={"friction_model": ["din"]}, sample={
        "n": 8, "method": "lhs", "seed": 5,
        "axes": {"takeup.mass_kg": {"dist": "uniform", "low": 1, "high": 3}}})
    sid = store_finished(data_dir, data)
    store = Store(data_dir)
    runs = store.read_runs(sid)
    assert runs["sag_max_pct"].isna().all() and (runs["t_min_kn"] <= 0).all()
    out = summarise(store.read(sid)["study"], runs)
    (cell,) = out["cells"]
    sag = cell["figures"]["sag_max_pct"]
    assert (sag["n"], sag["points"], sag["without_value"], sag["unbounded"]) == (0, 8, 8, 8)
    assert sag["mean"] is None and sag["why"] == "slack, sag unbounded"
    text = format_text(out).splitlines()
    assert ("    n 0 of 8; 8 without a value: slack, sag unbounded (past every bound: every "
            "quantile of all of them is unbounded)") in text


def test_the_report_names_every_figure_s_ranking_note_not_the_first_alone():
    """A ranking note is per figure. The report printed the first figure's only, so a power
    index of 1.2 outside [0, 1] (a share of the variance cannot be: sampling error), which
    ``beltstudy uncertainty`` names, went unsaid where ``power_kw`` was not first."""
    from beltstudy.service.web.uncertainty import _ranking_notes

    method = "sobol (SALib)"
    cell = {"sensitivity": {
        "safety_factor": {"method": method, "note": "", "axes": {}, "ranking": []},
        "power_kw": {"method": method, "note": "ST of temperature_c 1.2: outside [0, 1]",
                     "axes": {}, "ranking": []},
        "te_kn": {"method": method, "note": "ST of temperature_c 1.2: outside [0, 1]",
                  "axes": {}, "ranking": []}}}
    assert _ranking_notes(cell) == ["power_kw, te_kn: ST of temperature_c 1.2: outside [0, 1]"]
    cell["sensitivity"]["power_kw"]["note"] = cell["sensitivity"]["te_kn"]["note"] = ""
    assert _ranking_notes(cell) == []
