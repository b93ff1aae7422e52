"""What the samples say (SPEC 7.4 uncertainty): distributions, exceedance with an interval
and the sensitivity ranking, checked against exact answers."""

from __future__ import annotations

import math

import numpy as np
import pandas as pd
import pytest

from beltstudy.service.door.studyfile import resolve_study
from beltstudy.service.uncertainty import distribution, format_text, summarise, wilson
from tests.service.conftest import tiny_study

# three independent inputs of a sampled study and their standard deviations
AXES = {
    "temperature_c": ({"dist": "uniform", "low": -20, "high": 20}, 40 / math.sqrt(12)),
    "models.din.f_return": ({"dist": "normal", "mean": 0.02, "sd": 0.002}, 0.002),
    "models.din.f_carry": ({"dist": "triangular", "low": 0.01, "mode": 0.02, "high": 0.03},
                           math.sqrt((0.01**2 + 0.02**2 + 0.03**2 - 0.01 * 0.02 - 0.01 * 0.03
                                      - 0.02 * 0.03) / 18)),
}
COEF = {"temperature_c": 1.0, "models.din.f_return": 5000.0, "models.din.f_carry": 1000.0}


def _linear_study(n: int, method: str, seed: int = 11):
    """A resolved sampled study and a runs table whose figure ``y`` is linear in the inputs
    (the rows as the store would hold them: one per run, the axes as columns)."""
    study = resolve_study(tiny_study(
        "linear", grid={"friction_model": ["din"]},
        sample={"n": n, "method": method, "seed": seed,
                "axes": {k: v[0] for k, v in AXES.items()}}))
    rows = []
    for r in study.runs:
        y = sum(COEF[k] * r.axes[k] for k in AXES)
        rows.append({"run_id": r.run_id, "status": "ok", **r.axes, "y": y})
    return study, pd.DataFrame(rows)


def _analytic() -> dict[str, float]:
    var = {k: (COEF[k] * AXES[k][1]) ** 2 for k in AXES}
    total = sum(var.values())
    return {k: v / total for k, v in var.items()}


def test_sobol_indices_of_a_linear_function():
    # S_i = c_i^2 s_i^2 / sum_j c_j^2 s_j^2, and S_Ti = S_i (no interactions)
    study, runs = _linear_study(1024 * 5, "sobol")
    out = summarise(study.to_json(), runs, figures=("y",))
    (cell,) = out["cells"]
    sens = cell["sensitivity"]["y"]
    assert sens["method"].startswith("sobol")
    exact = _analytic()
    # by hand: variances 133.3 (temperature), 100 (f_return), 16.67 (f_carry) of 250
    assert sorted(exact.values()) == pytest.approx([0.0667, 0.4, 0.5333], abs=1e-4)
    for name, s in exact.items():
        assert sens["axes"][name]["S1"] == pytest.approx(s, abs=0.03), name
        assert sens["axes"][name]["ST"] == pytest.approx(s, abs=0.03), name
    assert sens["ranking"] == sorted(exact, key=lambda k: -exact[k])
    # the distribution of y: its mean is sum c_i E[x_i]
    mean = 0.0 + 5000 * 0.02 + 1000 * 0.02
    assert cell["figures"]["y"]["mean"] == pytest.approx(mean, abs=0.2)


def test_lhs_ranks_by_rank_correlation():
    study, runs = _linear_study(400, "lhs")
    sens = summarise(study.to_json(), runs, figures=("y",))["cells"][0]["sensitivity"]["y"]
    assert sens["method"].startswith("spearman")
    exact = _analytic()
    assert sens["ranking"] == sorted(exact, key=lambda k: -exact[k])
    # every input raises y; rho is a rank measure, not a variance share, so only its order
    # and sign are checked
    for name in exact:
        assert sens["axes"][name]["rho"] > 0.1


def test_missing_design_points_fall_back_and_say_so():
    study, runs = _linear_study(64 * 5, "sobol")
    runs.loc[3, "y"] = np.nan
    sens = summarise(study.to_json(), runs, figures=("y",))["cells"][0]["sensitivity"]["y"]
    assert sens["method"].startswith("spearman")
    assert "1 of 320 design points have no value" in sens["note"]


def test_wilson_interval():
    # Agresti & Coull (1998): k = 0 of n = 20 gives [0, 0.161]; 10 of 20 gives [0.299, 0.701]
    assert wilson(0, 20) == pytest.approx((0.0, 0.1611), abs=1e-4)
    assert wilson(10, 20) == pytest.approx((0.2993, 0.7007), abs=1e-4)
    assert wilson(20, 20)[1] == 1.0
    # none of 48 (a limit never passed) is 0 exactly, not a rounding residue such as 6e-18
    assert wilson(0, 48)[0] == 0.0 and wilson(48, 48)[1] == 1.0


def test_exceedance_counts_the_runs_past_each_limit():
    study, runs = _linear_study(20, "lhs")
    runs["slip_margin"] = np.where(np.arange(20) < 5, 0.9, 1.3)  # 5 of 20 slip
    runs["slack_max_m"] = 0.0
    runs.loc[0, "status"] = "failed"  # a failed run counts in no probability
    out = summarise(study.to_json(), runs, figures=("slip_margin",))
    ex = {e["limit"]: e for e in out["cells"][0]["exceedance"]}
    assert set(ex) == {"safety", "slip", "sag", "slack", "overload"}
    assert (ex["slip"]["runs_past"], ex["slip"]["runs"]) == (4, 19)
    assert ex["slip"]["p"] == pytest.approx(4 / 19)
    assert (ex["slip"]["ci_low"], ex["slip"]["ci_high"]) == pytest.approx(wilson(4, 19))
    assert ex["slack"]["runs_past"] == 0 and ex["slack"]["ci_high"] > 0


def test_distribution_quantiles():
    d = distribution(pd.Series(np.arange(101, dtype=float)))
    assert d["quantiles"] == {"p05": 5.0, "p25": 25.0, "p50": 50.0, "p75": 75.0, "p95": 95.0}
    assert d["sd"] == pytest.approx(np.arange(101).std(ddof=1))


def test_a_grid_study_is_not_sampled():
    study = resolve_study(tiny_study())
    out = summarise(study.to_json(), pd.DataFrame())
    assert out["sampled"] is False
    # said plainly (it read "the study has no sample: (SPEC 7.2); ...")
    assert out["message"] == ("the study has no sample (a sample: block, SPEC 7.2): its spread "
                              "is that of its grid, in its runs and compare")
    assert format_text(out) == out["message"]


def test_a_small_sobol_sample_and_an_index_outside_0_1_are_noted():
    """N = 4 base points over 3 axes: indices of the order of their own error (the audit's S1
    = 1.27 with an empty note). The answer says the base sample is small and why, and names
    each index outside [0, 1] as sampling error; the text says both."""
    from beltstudy.service.uncertainty import SOBOL_N_MIN

    study, runs = _linear_study(4 * 5, "sobol")
    # a figure with interactions (a sine of the linear sum): at N = 4 its estimates leave
    # [0, 1]
    y = runs["y"].to_numpy()
    runs["y"] = np.sin(5 * y / y.std())
    out = summarise(study.to_json(), runs, figures=("y",))
    assert out["note"].startswith("base sample N = 4 (20 runs = N (D + 2), D = 3 axes): "
                                  f"Sobol' indices from fewer than N = {SOBOL_N_MIN}")
    assert f"give sample.n >= {SOBOL_N_MIN * 5}" in out["note"]
    sens = out["cells"][0]["sensitivity"]["y"]
    outside = [f"{k} of {n}" for n, v in sens["axes"].items() for k in ("S1", "ST")
               if not 0 <= v[k] <= 1]
    assert outside, sens  # this design's estimates leave [0, 1]
    assert sens["note"].startswith(outside[0]) and "outside [0, 1]" in sens["note"]
    assert "sampling error" in sens["note"]
    text = format_text(out)
    assert f"note: {out['note']}" in text and f"    note: {sens['note']}" in text
    # a large enough design has no size note; within [0, 1], no index note
    big, big_runs = _linear_study(SOBOL_N_MIN * 5, "sobol")
    out = summarise(big.to_json(), big_runs, figures=("y",))
    assert out["note"] == ""
    sens = out["cells"][0]["sensitivity"]["y"]
    assert sens["note"] == "" or "outside [0, 1]" in sens["note"]
    # a Latin hypercube's note is the |rho| of chance: 1.96 / sqrt(20 - 1) = 0.45
    lhs, lhs_runs = _linear_study(20, "lhs")
    note = summarise(lhs.to_json(), lhs_runs, figures=("y",))["note"]
    assert "shows |rho| up to about 0.45 by chance" in note, note


def test_the_chance_level_of_rho_holds_for_an_input_the_figure_does_not_read():
    """Over 400 seeded 24-point Latin hypercubes of a figure that reads f_carry and f_return
    only, the temperature's |rho| passes the noted chance level (1.96 / sqrt(23) = 0.409) in
    about 5 % of them (binomial: 20 expected, 95 % of counts within 11-29). The points are
    the sampler's (``draw``), the ones a resolved study's runs carry (checked on one seed)."""
    from beltstudy.service.door.sample import SampleIn, draw
    from beltstudy.service.uncertainty import chance_rho

    lim = chance_rho(24)
    assert lim == pytest.approx(1.959964 / math.sqrt(23))
    coef = {**COEF, "temperature_c": 0.0}

    def sample(seed: int) -> dict:
        return {"n": 24, "method": "lhs", "seed": seed,
                "axes": {k: v[0] for k, v in AXES.items()}}

    study = resolve_study(tiny_study("linear", grid={"friction_model": ["din"]},
                                     sample=sample(7)))
    drawn = draw(SampleIn.model_validate(sample(7)))
    assert sorted(tuple(r.axes[k] for k in AXES) for r in study.runs) == sorted(
        zip(*(drawn[k] for k in AXES), strict=True))
    past = 0
    for seed in range(400):
        drawn = draw(SampleIn.model_validate(sample(seed)))
        pts = np.array([drawn[k] for k in AXES]).T
        y = pts @ np.array([coef[k] for k in AXES])
        rho = pd.Series(pts[:, 0]).rank().corr(pd.Series(y).rank())
        past += abs(rho) > lim
    assert 8 <= past <= 32, past


def test_rest_and_report_of_a_stored_sampled_study(data_dir, make_settings):
    # a real sampled study run in this process: the take-up mass drawn about the design's
    # own size and the friction uncertain; steady runs of the 60 m conveyor
    from fastapi.testclient import TestClient

    from beltstudy.service.api.app import create_app
    from tests.service.conftest import store_finished

    data = tiny_study("sampled-stored", grid={"friction_model": ["din"]}, sample={
        "n": 4 * 4, "method": "sobol", "seed": 5, "axes": {
            "models.din.f_carry": {"dist": "lognormal", "median": 0.02, "sigma": 0.3},
            "temperature_c": {"dist": "uniform", "low": -20, "high": 30}}})
    sid = store_finished(data_dir, data)
    client = TestClient(create_app(make_settings(data_dir)))
    out = client.get(f"/studies/{sid}/uncertainty").json()
    assert out["sampled"] and out["method"] == "sobol" and out["n"] == 16
    (cell,) = out["cells"]
    assert cell["runs"] == 16 and cell["points_missing"] == 0
    power = cell["figures"]["power_kw"]
    assert power["n"] == 16 and power["quantiles"]["p05"] <= power["quantiles"]["p95"]
    # din has no temperature term: power depends on f_carry alone, so its total index is
    # (all but) everything and temperature's nothing
    s = cell["sensitivity"]["power_kw"]["axes"]
    assert s["models.din.f_carry"]["ST"] > 0.9 and abs(s["temperature_c"]["ST"]) < 0.05
    page = client.get(f"/studies/{sid}/report").text
    assert "Uncertainty of the sampled inputs" in page
    assert page.count('alt="distributions"') == 1 and page.count('alt="ranking"') == 1
    assert "Wilson" in page
    assert client.get("/studies/0123456789abcdef/uncertainty").status_code == 404
    text = format_text(out)
    assert "power_kw" in text and "ST: models.din.f_carry" in text
    assert "slipped on a drive pulley" in text


def test_an_index_just_outside_0_1_is_shown_outside_it():
    """SALib's S1 of a figure one input sets alone came out 1.0005 (f_carry on a DIN belt's
    peak tension, N = 128); the note said 'S1 of f_carry 1: outside [0, 1]'. Its value is
    shown with the digits that put it outside. An index within a share of 1e-4 of [0, 1] is
    the estimator's round-off (an input the figure does not read: S1 -4.2e-8 with S1_conf
    1e-7), which was noted on nearly every figure and buried the notes that matter."""
    from beltstudy.service.uncertainty import _outside_unit

    note = _outside_unit({"f_carry": {"S1": 1.0005005682980321, "ST": 1.000042983507698},
                          "f_return": {"S1": -0.0000142, "ST": 5.1e-06},
                          "temperature_c": {"S1": -4.2e-8, "ST": 0.0},
                          "takeup": {"S1": -0.00317, "ST": 0.02}})
    assert note.startswith("S1 of f_carry 1.0005, S1 of takeup -0.00317: outside [0, 1]"), note
    assert "f_return" not in note and "temperature_c" not in note
    assert _outside_unit({"a": {"S1": -4.2e-8, "ST": 1.00009}}) == ""


def test_a_run_merged_over_sample_points_stands_for_each(data_dir, make_settings):
    """A Sobol' sample of a DIN parameter crossed with friction_model [din, cema]: a cema run
    does not read models.din.f_carry, so the points of Saltelli's design that differ only in
    it are one cema run with that axis null. The answer dropped those points (cema: '4 sample
    points without a run yet' for a finished study, each figure over 8 of 12 points, Spearman
    instead of Sobol' and a rank correlation for f_carry, which cema never reads). Each point
    now has the run it merged into."""
    from fastapi.testclient import TestClient

    from beltstudy.service.api.app import create_app
    from tests.service.conftest import store_finished

    data = tiny_study("sampled-merged", grid={"friction_model": ["din", "cema"]}, sample={
        "n": 3 * 4, "method": "sobol", "seed": 5, "axes": {
            "models.din.f_carry": {"dist": "lognormal", "median": 0.02, "sigma": 0.3},
            "temperature_c": {"dist": "uniform", "low": -20, "high": 30}}})
    study = resolve_study(data)
    cema = [r for r in study.runs if r.model == "cema"]
    points = sum(r.model == "din" for r in study.runs)  # din reads every axis: one a point
    assert len(cema) < points  # some cema runs stand for several points
    sid = store_finished(data_dir, data)
    client = TestClient(create_app(make_settings(data_dir)))
    out = client.get(f"/studies/{sid}/uncertainty").json()
    assert out["points"] == points
    cells = {c["grid"]["friction_model"]: c for c in out["cells"]}
    for model, cell in cells.items():
        assert cell["points_missing"] == 0, model
        assert cell["figures"]["power_kw"]["n"] == out["points"], model
        sens = cell["sensitivity"]["power_kw"]
        assert sens["method"].startswith("sobol"), (model, sens)
        assert {e["runs"] for e in cell["exceedance"]} == {out["points"]}, model
    assert cells["cema"]["runs"] == len(cema)
    # cema does not read f_carry: it explains none of cema's power
    s = cells["cema"]["sensitivity"]["power_kw"]["axes"]
    assert abs(s["models.din.f_carry"]["ST"]) < 1e-9 and s["temperature_c"]["ST"] > 0.9
    assert "without a run yet" not in format_text(out)


def test_round_off_indices_are_printed_as_zero():
    """``beltstudy uncertainty`` printed the total index of an input a figure does not read as
    SALib's round-off ('temperature_c 2.031e-30'); the text and the report's table now say 0
    for anything below 1e-12 in magnitude, either sign, and the JSON keeps the float."""
    from beltstudy.service.web.uncertainty import _cell_tables

    study, runs = _linear_study(16 * 5, "sobol")
    out = summarise(study.to_json(), runs, figures=("y",))
    sens = out["cells"][0]["sensitivity"]["y"]
    first, second, third = sens["ranking"]
    sens["axes"][second]["ST"], sens["axes"][third]["ST"] = 2.031e-30, -1e-31
    text = format_text(out)
    assert "e-30" not in text and "e-31" not in text
    assert f"{second} 0, {third} 0" in text
    assert f"ST: {first} {sens['axes'][first]['ST']:.4g}," in text
    page = _cell_tables(out["cells"][0], lambda head, rows, what: str(rows),
                        lambda v: str(v))
    assert f"{second} (0), {third} (0)" in page and "e-30" not in page
    assert sens["axes"][second]["ST"] == 2.031e-30  # the stored value is the float
