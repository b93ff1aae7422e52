"""The report judges each run's belt safety factor against the minimum of its own belt's kind
(DIN 22101: 6.7 steel cord, 10 fabric), not the study conveyor's, where a ``belt_type`` axis
mixes both kinds."""

from __future__ import annotations

import pandas as pd
import pytest

from beltstudy.engine import TRANSIENT_SAFETY_RATIO
from beltstudy.service import charts
from beltstudy.service.web.report import _allowed_lines, _sf_of_runs
from beltstudy.service.web.verdicts import study_limits, verdict_rows

STEEL_MIN, FABRIC_MIN = 6.7, 10.0


def _study(safety_factor_min: float | None = None) -> dict:
    conv = {"belt": {"type": "ST1000"}, "profile": [{"length_m": 1200, "lift_m": 48}]}
    if safety_factor_min is not None:
        conv["safety_factor_min"] = safety_factor_min
    return {"conveyor": conv, "dynamics": True,
            "axes": [{"column": "belt_type"}]}


def _runs() -> pd.DataFrame:
    """Two steel cord runs (ST1000, 1000 kN) and two fabric (EP800/4, 800 kN): the EP
    runs' steady factors 7.09 and 12.0, transient 5.0 and 7.5; the ST runs' 8.0 and 7.0,
    transient 6.0 and 5.0."""
    rows = [("a", "ST1000", 1000.0, 8.0, 6.0), ("b", "ST1000", 1000.0, 7.0, 5.0),
            ("c", "EP800/4", 800.0, 7.09, 5.0), ("d", "EP800/4", 800.0, 12.0, 7.5)]
    out = []
    for run_id, belt, rating, sf, sf_dyn in rows:
        out.append({"run_id": run_id, "status": "ok", "belt_type": belt,
                    "belt_type_used": belt, "belt_rating_kn": rating,
                    "safety_factor": sf, "t_max_kn": rating / sf,
                    "safety_factor_dyn": sf_dyn, "t_max_dyn_kn": rating / sf_dyn})
    return pd.DataFrame(out)


def _rows(study: dict, runs: pd.DataFrame) -> dict[str, dict]:
    limits = study_limits(study, STEEL_MIN, TRANSIENT_SAFETY_RATIO, sf_of=_sf_of_runs(study))
    return {r["column"]: r for r in verdict_rows(runs, limits)}


def test_each_run_is_judged_by_its_own_belts_minimum():
    rows = _rows(_study(), _runs())
    # by hand: steady, past where sf < 6.7 (steel) or < 10 (fabric): run c (7.09 < 10)
    assert rows["safety_factor"]["past"] == 1
    # transient, past where sf_dyn < 2/3 x 6.7 = 4.47 (steel) or < 6.67 (fabric): run c
    assert rows["safety_factor_dyn"]["past"] == 1
    assert rows["safety_factor_dyn"]["row"]["run_id"] == "c"
    # the tension a belt allows: run c's 800 / 10 = 80 kN against its 112.8 kN
    steady = rows["t_max_kn"]
    assert steady["past"] == 1 and steady["row"]["run_id"] == "c"
    assert steady["limit"] == pytest.approx(800.0 / FABRIC_MIN)
    assert "each run's belt" in steady["limit_text"]


def test_the_conveyors_own_minimum_holds_for_every_belt():
    """A conveyor that gives safety_factor_min is judged by it whatever the belt."""
    rows = _rows(_study(safety_factor_min=7.05), _runs())
    assert rows["safety_factor"]["past"] == 1  # run b, 7.0 < 7.05; run c 7.09 passes
    assert rows["safety_factor"]["row"]["run_id"] == "b"


def test_one_kind_keeps_one_limit():
    runs = _runs()
    steel = runs[runs["belt_type_used"] == "ST1000"].reset_index(drop=True)
    rows = _rows(_study(), steel)
    assert rows["safety_factor"]["past"] == 0
    assert rows["t_max_kn"]["limit_text"] == f"belt rating / {STEEL_MIN:.3g}"
    assert _allowed_lines(_study(), steel) == [
        (pytest.approx(1000.0 / (TRANSIENT_SAFETY_RATIO * STEEL_MIN)), "")]


def test_the_start_and_stop_figure_draws_the_tension_each_belt_allows():
    lines = _allowed_lines(_study(), _runs())
    by_belt = {belts: value for value, belts in lines}
    assert by_belt["ST1000"] == pytest.approx(1000.0 / (TRANSIENT_SAFETY_RATIO * STEEL_MIN))
    assert by_belt["EP800/4"] == pytest.approx(800.0 / (TRANSIENT_SAFETY_RATIO * FABRIC_MIN))
    runs = _runs().assign(t_max_start_kn=150.0, t_min_start_kn=10.0, temperature_c=20.0)
    fig = charts.phase_peaks_figure(runs, allowed_kn=lines, axes=["belt_type"])
    drawn = {round(float(ln.get_ydata()[0]), 6) for ax in fig.axes for ln in ax.get_lines()
             if len(set(ln.get_ydata())) == 1 and ln.get_ydata()[0] > 0}
    assert drawn == {round(v, 6) for v, _ in lines}
    texts = " ".join(t.get_text() for t in fig.legends[0].get_texts())
    assert "(EP800/4)" in texts and "(ST1000)" in texts
    charts._plt().close("all")
