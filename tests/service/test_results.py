"""Filters and the friction-model comparison (service/store/query.py)."""

from __future__ import annotations

import math

import pandas as pd
import pytest

from beltstudy.service.errors import Invalid
from beltstudy.service.store.query import apply_filters, compare, row_to_json


def _runs() -> pd.DataFrame:
    rows = []
    for model, scale in (("cema", 1.0), ("nonlin", 0.8)):
        for t in (-20.0, 20.0):
            for load in ("full", "empty"):
                power = (100.0 if load == "full" else 40.0) * scale * (1.5 if t < 0 else 1.0)
                rows.append(
                    {
                        "run_id": f"{model}{t}{load}",
                        "status": "ok",
                        "friction_model": model,
                        "temperature_c": t,
                        "load": load,
                        "power_kw": power,
                        "t_max_dyn_kn": float("nan"),
                    }
                )
    return pd.DataFrame(rows)


def test_compare_pairs_runs_differing_only_in_model():
    out = compare(
        _runs(),
        ["friction_model", "temperature_c", "load"],
        "cema",
        "nonlin",
        ["power_kw"],
    )
    assert len(out["pairs"]) == 4
    for p in out["pairs"]:
        assert p["power_kw_ratio"] == pytest.approx(0.8)
    s = out["summary"]["power_kw"]
    assert s["overall"] == {
        "n": 4,
        "mean": pytest.approx(0.8),
        "min": pytest.approx(0.8),
        "max": pytest.approx(0.8),
        "opposite_sign": 0,
    }
    assert set(s["by_axis"]) == {"temperature_c", "load"}
    assert set(s["by_axis"]["load"]) == {"full", "empty"}
    # a metric no run has a value of (steady rows: no transient figure) is refused, not
    # answered with n 0 (test_compare_asked_names)
    with pytest.raises(Invalid, match="^metrics: 't_max_dyn_kn' has no values in this study"):
        compare(_runs(), ["friction_model", "temperature_c", "load"], "cema", "nonlin",
                ["power_kw", "t_max_dyn_kn"])
    # a study still running is answered with what it has: its later runs may have a value
    out = compare(_runs(), ["friction_model", "temperature_c", "load"], "cema", "nonlin",
                  ["power_kw", "t_max_dyn_kn"], settled=False)
    assert out["summary"]["t_max_dyn_kn"]["overall"]["n"] == 0
    assert out["summary"]["power_kw"]["overall"]["n"] == 4


def test_compare_lists_only_what_differs_and_ratios_as_magnitudes():
    """A din parameter axis is read by neither cema nor nonlin (their rows have it null),
    and a drive force that is negative under one model (regenerating) gives a magnitude ratio
    with its sign named, not -0.127."""
    runs = _runs()
    runs["models.din.f_carry"] = None
    runs["drive_force_max_kn"] = [100.0, 40.0, -12.7 / 0.8, 10.0] * 2
    runs.loc[runs["friction_model"] == "nonlin", "drive_force_max_kn"] = \
        [80.0, 32.0, 12.7, 8.0]
    out = compare(runs, ["friction_model", "temperature_c", "load", "models.din.f_carry"],
                  "cema", "nonlin", ["drive_force_max_kn"])
    assert out["same_in_all_pairs"] == {"models.din.f_carry": None}
    assert all("models.din.f_carry" not in p for p in out["pairs"])
    assert set(out["summary"]["drive_force_max_kn"]["by_axis"]) == {"temperature_c", "load"}
    by_run = {p["run_id_baseline"]: p for p in out["pairs"]}
    # 12.7 / |-15.875| = 0.8 as a magnitude, marked opposite; the others 0.8, same sign
    assert by_run["cema20.0full"]["drive_force_max_kn_ratio"] == pytest.approx(0.8)
    assert by_run["cema20.0full"]["drive_force_max_kn_sign"] == "opposite"
    assert {p["drive_force_max_kn_sign"] for k, p in by_run.items()
            if k != "cema20.0full"} == {"same"}
    assert all(p["drive_force_max_kn_ratio"] == pytest.approx(0.8) for p in out["pairs"])
    assert out["summary"]["drive_force_max_kn"]["overall"]["opposite_sign"] == 1


def test_a_value_one_model_does_not_write_gives_no_ratio_not_a_zero():
    """te_idler_rotation_kn is written by Non-Lin only (null under CEMA), te_main_carry_kn by
    CEMA only: a missing value gave a ratio of 0.0 with sign 'zero' (|NaN| compared as no
    larger than the zero band, so it was set to 0), saying Non-Lin's main carry resistance
    was nil, and pulled the mean ratio down. A pair with a missing value has no ratio and no
    sign; the other pairs keep theirs."""
    runs = _runs()
    cema = runs["friction_model"] == "cema"
    runs["te_main_carry_kn"] = runs["power_kw"].where(cema)
    runs["te_idler_rotation_kn"] = runs["power_kw"].where(~cema)
    # one metric with a value under both models in two pairs and a missing candidate in two
    runs["f_kn"] = runs["power_kw"]
    runs.loc[~cema & (runs["temperature_c"] < 0), "f_kn"] = float("nan")
    out = compare(runs, ["friction_model", "temperature_c", "load"], "cema", "nonlin",
                  ["te_main_carry_kn", "te_idler_rotation_kn", "f_kn"])
    for m in ("te_main_carry_kn", "te_idler_rotation_kn"):
        assert [(p[f"{m}_ratio"], p[f"{m}_sign"]) for p in out["pairs"]] == [(None, None)] * 4
        assert out["summary"][m]["overall"]["n"] == 0
    by_t = {(p["temperature_c"], p["load"]): p for p in out["pairs"]}
    assert [by_t[(-20.0, load)]["f_kn_ratio"] for load in ("full", "empty")] == [None, None]
    assert [by_t[(-20.0, load)]["f_kn_sign"] for load in ("full", "empty")] == [None, None]
    assert all(by_t[(20.0, load)]["f_kn_ratio"] == pytest.approx(0.8) for load in ("full", "empty"))
    assert out["summary"]["f_kn"]["overall"]["n"] == 2
    assert out["summary"]["f_kn"]["overall"]["mean"] == pytest.approx(0.8)
    # the steady-only metric of _runs (null in every run) is refused by name
    # (test_compare_asked_names), not answered with every sign null
    with pytest.raises(Invalid, match="'t_max_dyn_kn' has no values in this study"):
        compare(_runs(), ["friction_model", "temperature_c", "load"], "cema", "nonlin",
                ["t_max_dyn_kn"])


def test_compare_pairs_a_run_with_the_other_model_s_runs_at_each_of_its_parameters():
    """A din parameter axis (two f_carry values): the din runs have it, the nonlin runs do
    not read it (null: any value). Each nonlin run pairs with the din run of each f_carry at
    its temperature and load: 4 x 2 = 8 pairs, the axis listed per pair and per value."""
    base = _runs()
    nonlin = base[base["friction_model"] == "nonlin"].assign(**{"models.din.f_carry": None})
    dins = []
    for f, scale in ((0.012, 1.0), (0.020, 1.25)):
        d = base[base["friction_model"] == "cema"].assign(
            friction_model="din", **{"models.din.f_carry": f})
        d["run_id"] = d["run_id"].str.replace("cema", f"din{f}")
        d["power_kw"] = d["power_kw"] * scale
        dins.append(d)
    runs = pd.concat([*dins, nonlin], ignore_index=True)
    out = compare(runs, ["friction_model", "temperature_c", "load", "models.din.f_carry"],
                  "din", "nonlin", ["power_kw"])
    assert len(out["pairs"]) == 8
    by_f = out["summary"]["power_kw"]["by_axis"]["models.din.f_carry"]
    assert by_f["0.012"]["mean"] == pytest.approx(0.8)
    assert by_f["0.02"]["mean"] == pytest.approx(0.8 / 1.25)
    assert {p["models.din.f_carry"] for p in out["pairs"]} == {0.012, 0.02}


def test_compare_refuses_unknown_models_and_metrics():
    runs = _runs()
    with pytest.raises(Invalid, match="candidate: model 'visco' is not in this study"):
        compare(runs, ["friction_model"], "cema", "visco", ["power_kw"])
    with pytest.raises(Invalid, match="metrics: unknown metric 'powr'"):
        compare(runs, ["friction_model"], "cema", "nonlin", ["powr"])
    with pytest.raises(Invalid, match="candidate: 'cema' is the baseline too"):
        compare(runs, ["friction_model"], "cema", "cema", ["power_kw"])


def test_compare_names_the_nearest_metric_and_a_text_column():
    """A near miss ('powr_kw', as filter=, sort= and columns= already answer) names the
    metric meant; a text column is said to be no number, not 'unknown'."""
    runs = _runs()
    with pytest.raises(Invalid, match=r"unknown metric 'powr_kw' \(did you mean 'power_kw'\?\)"):
        compare(runs, ["friction_model"], "cema", "nonlin", ["powr_kw"])
    with pytest.raises(Invalid, match="metrics: 'status' is not a number in this study's rows"):
        compare(runs, ["friction_model"], "cema", "nonlin", ["status"])


def test_compare_refuses_a_metric_twice_and_an_axis_as_metric():
    runs = _runs()
    axes = ["friction_model", "temperature_c", "load"]
    with pytest.raises(Invalid, match="metrics: 'power_kw' is listed twice"):
        compare(runs, axes, "cema", "nonlin", ["power_kw", "power_kw"])
    with pytest.raises(Invalid, match="metrics: 'temperature_c' is an axis of this study"):
        compare(runs, axes, "cema", "nonlin", ["temperature_c"])


def test_filters_compare_numbers_as_numbers():
    runs = _runs()
    assert len(apply_filters(runs, ["temperature_c=20"])) == 4
    assert len(apply_filters(runs, ["load=full", "friction_model=cema"])) == 2
    with pytest.raises(Invalid, match="this study has no column 'nope'; columns: run_id"):
        apply_filters(runs, ["nope=1"])
    with pytest.raises(Invalid, match=r"no column 'temprature_c' \(did you mean "
                                      r"'temperature_c'\?\); columns:"):
        apply_filters(runs, ["temprature_c=20"])
    with pytest.raises(Invalid, match="not column=value"):
        apply_filters(runs, ["temperature_c"])
    # a value no number can equal keeps no row
    assert len(apply_filters(runs, ["temperature_c=warm"])) == 0
    assert len(apply_filters(runs, ["temperature_c=nan"])) == 0


def test_rows_fold_parts_into_components_and_nan_into_null():
    out = row_to_json(
        {"te_kn": 3.0, "te_lift_kn": 1.0, "te_feed_kn": float("nan"), "power_kw": math.nan}
    )
    assert out == {"te_kn": 3.0, "power_kw": None, "te_components_kn": {"lift": 1.0}}


def test_pairs_with_a_failed_run_have_no_ratio():
    runs = _runs()
    runs.loc[(runs["friction_model"] == "nonlin") & (runs["load"] == "empty"), "status"] = "failed"
    out = compare(runs, ["friction_model", "temperature_c", "load"], "cema", "nonlin", ["power_kw"])
    assert out["failed_pairs"] == 2 and len(out["pairs"]) == 4
    assert out["summary"]["power_kw"]["overall"]["n"] == 2
    assert out["summary"]["power_kw"]["by_axis"]["load"]["empty"]["n"] == 0


def test_compare_gives_no_ratio_over_a_zero_written_with_round_off():
    """A minimum tension of -4e-14 kN under the baseline is zero written with round-off: its
    ratio was 1.2e14 and the mean of four ratios 3e13; now it has no ratio and sign 'zero'."""
    runs = _runs()
    runs["t_min_stop_kn"] = [5.0, 2.0, -4e-14, 1.0, 4.0, 1.6, 4.8, 0.0]
    out = compare(runs, ["friction_model", "temperature_c", "load"], "cema", "nonlin",
                  ["t_min_stop_kn"])
    by_run = {p["run_id_baseline"]: p for p in out["pairs"]}
    assert by_run["cema20.0full"]["t_min_stop_kn_ratio"] is None
    assert by_run["cema20.0full"]["t_min_stop_kn_sign"] == "zero"
    assert by_run["cema20.0empty"]["t_min_stop_kn_ratio"] == 0.0
    assert by_run["cema20.0empty"]["t_min_stop_kn_sign"] == "zero"
    overall = out["summary"]["t_min_stop_kn"]["overall"]
    assert overall["n"] == 3
    assert overall["mean"] == pytest.approx((0.8 + 0.8 + 0.0) / 3)
    assert overall["opposite_sign"] == 0


def test_a_number_filters_a_mixed_axis_stored_as_text():
    """``takeup.mass_kg: [auto, 3000]`` is stored as text ('auto', '3000.0'); the study page
    offers the grid's values, so its filter sends 3000 and the page said '0 of 24 runs match
    the filters' where 12 runs have 3000 kg. A number now matches such a column by value."""
    runs = pd.DataFrame({"run_id": list("abcd"),
                         "takeup.mass_kg": ["3000.0", "auto", "3000.0", "500.0"]})
    for text in ("3000", "3000.0", "3e3"):
        assert list(apply_filters(runs, [f"takeup.mass_kg={text}"])["run_id"]) == ["a", "c"]
    assert list(apply_filters(runs, ["takeup.mass_kg=auto"])["run_id"]) == ["b"]
    assert len(apply_filters(runs, ["takeup.mass_kg=30"])) == 0
    assert len(apply_filters(runs, ["takeup.mass_kg=nan"])) == 0
    assert len(apply_filters(runs, ["takeup.mass_kg=Auto"])) == 0


def test_a_list_axis_value_filters_by_what_it_holds():
    """A load list ``[0.5, 1.0]`` is stored as JSON text; ``load=[0.5,1]`` (as a user types it)
    found no row. It now matches by the list's numbers; another list, another length or a
    malformed one keeps no row, and a word still matches as text."""
    runs = pd.DataFrame({"run_id": list("abcd"),
                         "load": ["[0.5, 1.0]", "full", "[1.0, 0.5]", "[0.5, 1.0, 1.0]"]})
    for text in ("[0.5,1]", "[0.5, 1.0]", "[5e-1, 1]"):
        assert list(apply_filters(runs, [f"load={text}"])["run_id"]) == ["a"], text
    assert list(apply_filters(runs, ["load=[1,0.5]"])["run_id"]) == ["c"]
    assert len(apply_filters(runs, ["load=[0.5]"])) == 0
    assert len(apply_filters(runs, ["load=[0.5,"])) == 0
    assert list(apply_filters(runs, ["load=full"])["run_id"]) == ["b"]


@pytest.mark.parametrize("asked", [[], ["power_kw", "t_max_stop_kn", "t_min_stop_kn"]])
def test_the_default_metrics_of_a_steady_study_are_its_power_alone(asked):
    """A steady-only study has no stop-phase figures: the defaults (power and the stop's
    peak and lowest tensions, what the route passes when metrics= is left out) compared
    power and two columns of nulls (n 0 each). They now keep the metrics some run has a
    value of; the 0.8 ratio of power stands."""
    runs = _runs()
    runs["t_max_stop_kn"] = float("nan")
    runs["t_min_stop_kn"] = float("nan")
    out = compare(runs, ["friction_model", "temperature_c", "load"], "cema", "nonlin", asked)
    assert out["metrics"] == ["power_kw"]
    assert set(out["summary"]) == {"power_kw"}
    assert out["summary"]["power_kw"]["overall"]["mean"] == pytest.approx(0.8)
    # a dynamic study keeps all three
    runs["t_max_stop_kn"] = runs["power_kw"]
    runs["t_min_stop_kn"] = runs["power_kw"]
    out = compare(runs, ["friction_model", "temperature_c", "load"], "cema", "nonlin", asked)
    assert out["metrics"] == ["power_kw", "t_max_stop_kn", "t_min_stop_kn"]


def test_a_yes_no_column_with_nulls_filters_by_true_and_false():
    """A failed run's null makes a yes/no column an object column of True, False and None;
    ``filter=pulley1_diameter_min_ok=true`` (the value as the JSON rows show it) compared
    text with 'True' and kept no row, while ``=True`` kept them. Either spelling now keeps
    the rows with that value, and a null row neither."""
    runs = pd.DataFrame({"run_id": list("abcd"),
                         "pulley1_diameter_min_ok": [True, None, False, True]})
    assert runs["pulley1_diameter_min_ok"].dtype == object
    for text in ("true", "True", "TRUE"):
        assert list(apply_filters(runs, [f"pulley1_diameter_min_ok={text}"])["run_id"]) == [
            "a", "d"]
    assert list(apply_filters(runs, ["pulley1_diameter_min_ok=false"])["run_id"]) == ["c"]
    assert len(apply_filters(runs, ["pulley1_diameter_min_ok=yes"])) == 0
    # a boolean column without nulls, as before
    full = pd.DataFrame({"run_id": list("ab"), "ok": [True, False]})
    assert list(apply_filters(full, ["ok=true"])["run_id"]) == ["a"]
