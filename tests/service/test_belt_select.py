"""``belt.type: auto`` through the service: ``beltstudy static --suggest-belt`` and a study
holding the belt as a design value (docs/belts.md).

The verdicts are checked by hand from the definition safety factor = rating k_N [kN/m] x
width B [m] / largest tension [kN] against the running minimum 6.7 (steel cord) and 2/3 of it
at start-up.
"""

from __future__ import annotations

import json

import pandas as pd
import pytest
import yaml

from beltstudy.engine import catalog
from beltstudy.engine.beltselect import SteadyCase, select_belt, with_belt
from beltstudy.engine.conveyor import load_mapping, parse_conveyor
from beltstudy.engine.statics import solve_steady
from beltstudy.service.cli import main
from beltstudy.service.door.studyfile import resolve_study
from tests.conftest import CONVEYORS
from tests.service.conftest import ROOT

STEEL_MIN = 6.7


def _auto(name: str = "overland-4km") -> dict:
    d = load_mapping(CONVEYORS / f"{name}.yaml")
    d["belt"] = {**d["belt"], "type": "auto", "kind": "steel_cord"}
    return d


@pytest.fixture
def auto_file(tmp_path):
    path = tmp_path / "overland-4km-auto.yaml"
    path.write_text(yaml.safe_dump(_auto()))
    return path


def test_suggest_belt_json_table(auto_file, capsys):
    assert main(["static", str(auto_file), "--model", "din", "--suggest-belt", "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    sel = out["belt_selection"]
    rows = {r["belt"]: r for r in sel["candidates"]}
    assert set(rows) == {k for k, r in catalog.belts().items() if r.kind == "steel"}
    for r in sel["candidates"]:  # safety factor = k_N B / T_max, each row by hand
        k_n = catalog.belts()[r["belt"]].rating_kn_m
        assert r["safety_factor"] == pytest.approx(k_n * 1.2 / r["t_max_kn"], rel=1e-9)
        assert r["safety_factor_start"] == pytest.approx(k_n * 1.2 / r["t_max_start_kn"],
                                                         rel=1e-9)
        assert r["passes"] == (r["safety_factor"] >= STEEL_MIN
                               and r["safety_factor_start"] >= 2 / 3 * STEEL_MIN)
    masses = [r["mass_kg_m"] for r in sel["candidates"]]
    assert masses == sorted(masses)
    first = next(r["belt"] for r in sel["candidates"] if r["passes"])
    assert sel["chosen"] == first == out["belt_type_used"] and sel["passed"]
    i = [r["belt"] for r in sel["candidates"]].index(first)
    assert sel["next_lighter"] == sel["candidates"][i - 1]["belt"]
    assert not rows[sel["next_lighter"]]["passes"]
    # the steady results are of the choice
    assert out["belt_rating_kn"] == pytest.approx(catalog.belts()[first].rating_kn_m * 1.2)
    assert "note: belt.type auto" in out["message"] and out["status"] == "ok"


def test_suggest_belt_table_for_a_given_belt(capsys):
    """A file with a belt type: the suggestion is printed, the results stay the file's."""
    assert main(["static", str(CONVEYORS / "overland-4km.yaml"), "--model", "nonlin",
                 "--suggest-belt"]) == 0
    text = capsys.readouterr().out
    assert "belt selection: steel_cord belts" in text and "<- choice" in text
    assert "belt ST2000" in text  # the file's belt, used for the results
    assert "SF running" in text and text.count(" fail") >= 1


def test_suggest_belt_table_prints_a_factor_just_below_its_minimum_apart(tmp_path, capsys):
    """The --suggest-belt table printed safety factors at two decimals: a candidate just below
    its minimum read '6.78 ... fail' under 'minimum safety factor 6.78'. The table now prints
    them at the decimals that part them, the header's minima too."""
    import re

    d = load_mapping(CONVEYORS / "slope-5pct.yaml")
    sf = solve_steady(parse_conveyor(d), model="din").summary["safety_factor"]
    d["safety_factor_min"] = sf * 1.00005  # ST2000 misses by 0.005 %
    path = tmp_path / "tight.yaml"
    path.write_text(yaml.safe_dump(d))
    main(["static", str(path), "--model", "din", "--suggest-belt"])
    text = capsys.readouterr().out
    head = re.search(r"minimum safety factor ([0-9.]+) running", text)
    row = re.search(r"\n  ST2000 .* ([0-9.]+) +([0-9.]+)  fail", text)
    assert head and row, text
    assert float(row.group(1)) < float(head.group(1)), (row.group(1), head.group(1))


def test_static_auto_without_suggest_reports_belt_type_used(auto_file, capsys):
    assert main(["static", str(auto_file), "--model", "nonlin", "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    assert "belt_selection" not in out
    assert out["belt_type_used"] == select_belt(parse_conveyor(_auto()),
                                                [SteadyCase("nonlin")]).belt_id


def test_static_auto_without_kind_is_one_line(tmp_path, capsys):
    d = _auto()
    del d["belt"]["kind"]
    path = tmp_path / "bad.yaml"
    path.write_text(yaml.safe_dump(d))
    assert main(["static", str(path)]) == 2
    err = capsys.readouterr().err
    assert "belt.kind" in err and "steel_cord" in err and "fabric" in err
    assert err.count("\n") == 1


def test_study_holds_the_belt_chosen_over_its_design_cases(finished_study, data_dir):
    """din needs ST2000 on overland-4km, nonlin ST1250: a study over both models holds the
    belt that passes at both (every case's factors by hand), for every run."""
    study = {"name": "belt-auto", "conveyor": _auto(), "scenario": {"elements": 60},
             "grid": {"friction_model": ["din", "nonlin"], "load": ["full", "empty"]},
             "dynamics": False}
    resolved = resolve_study(study, studies_dir=ROOT / "studies")
    (entry,) = resolved.designs
    chosen = entry["sizes"]["belt"]["type"]
    lighter = entry["sizes"]["belt"]["next_lighter"]["type"]
    conv = parse_conveyor(_auto())

    def factor(belt_id: str, model: str) -> float:
        res = solve_steady(with_belt(conv, belt_id), model=model, n_elements=60)
        return catalog.belts()[belt_id].rating_kn_m * 1.2 / (res.tension_n.max() / 1e3)

    assert all(factor(chosen, m) >= STEEL_MIN for m in ("din", "nonlin"))
    assert any(factor(lighter, m) < STEEL_MIN for m in ("din", "nonlin"))
    assert {r.conveyor["belt"]["type"] for r in resolved.runs} == {chosen}
    runs = pd.read_parquet(data_dir / "studies" / finished_study(data_dir, study) / "runs")
    assert len(runs) == 4 and set(runs["belt_type_used"]) == {chosen}
    # one take-up for the design, sized on the chosen belt
    assert runs["takeup_mass_kg"].nunique() == 1
    # the study report's design basis names it
    from beltstudy.service.web.report import _design_section

    html = _design_section(resolved.to_json())
    assert "belt (type: auto)" in html and chosen in html


def test_report_limits_of_an_auto_fabric_belt():
    """The report judges a fabric auto belt against the fabric minimum (10), not steel's."""
    from beltstudy.service.web.report import _sf_min

    d = _auto()
    d["belt"] = {**d["belt"], "kind": "fabric"}
    assert _sf_min({"conveyor": d}) == 10.0


def test_sweep_temperature_holds_one_auto_belt(auto_file, tmp_path, capsys):
    """The sweep is one design: the belt that passes at every model and temperature."""
    code = main(["sweep-temperature", str(auto_file), "--models", "din,nonlin", "--from", "-30",
                 "--to", "20", "--step", "50", "--out", str(tmp_path / "out")])
    assert code == 0
    text = capsys.readouterr().out
    assert "belt.type auto (steel_cord)" in text
    conv = parse_conveyor(_auto())
    cases = [SteadyCase(m, None, t) for m in ("din", "nonlin") for t in (-30.0, 20.0)]
    choice = select_belt(conv, cases)
    assert f"{choice.belt_id} (" in text.splitlines()[0]
    for m, t in [(c.model, c.temperature_c) for c in cases]:  # passes everywhere, by hand
        res = solve_steady(with_belt(conv, choice.belt_id), model=m, temperature_c=t)
        k_n = catalog.belts()[choice.belt_id].rating_kn_m
        assert k_n * 1.2 / (res.tension_n.max() / 1e3) >= STEEL_MIN


def test_the_catalogue_route_says_kind_as_a_conveyor_file_does(data_dir, make_settings):
    """GET /catalog/belts: ``kind`` is what ``belt: {type: auto, kind: ...}`` takes (SPEC
    7.1: steel_cord | fabric), not the data file's column value (steel)."""
    from fastapi.testclient import TestClient

    from beltstudy.engine.conveyor import Belt
    from beltstudy.service.api.app import create_app

    belts = TestClient(create_app(make_settings(data_dir))).get("/catalog/belts").json()["belts"]
    kinds = {b["id"]: b["kind"] for b in belts}
    assert kinds["ST2000"] == "steel_cord" and kinds["EP630/4"] == "fabric"
    assert set(kinds.values()) == {"steel_cord", "fabric"}
    for kind in set(kinds.values()):  # each one a file takes
        Belt.model_validate({"type": "auto", "kind": kind, "width_m": 1.2})
