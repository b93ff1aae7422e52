"""The result contract: ``beltstudy.engine.results`` defines every result of a run, and the Parquet
``runs`` schema, the ``--json`` output of ``beltstudy static`` / ``simulate``, the REST rows
and the table in ``docs/results.md`` hold exactly those fields: none computed and dropped,
none stored or printed without a definition."""

from __future__ import annotations

import json
import re

import pytest

from beltstudy.engine import results as R
from beltstudy.service.cli import main
from beltstudy.service.store.columns import INPUT_COLUMNS, flatten_summary, runs_schema_for_axes
from beltstudy.service.store.query import row_to_json
from tests.conftest import CONVEYORS, ROOT

#: What the CLI's --json echoes of its inputs besides the results.
CLI_INPUTS = {"conveyor", "friction_model", "temperature_c", "load", "stop_mode", "formulation"}
#: Two drives, one brake: per-drive and brake fields are all filled.
CONVEYOR = CONVEYORS / "overland-4km.yaml"
#: Its pulleys: two head drives, the tail take-up pulley, the tail drive (docs/checks.md).
PULLEYS = 4
NON_TE = [g for g in R.GROUPS if g is not R.TE_COMPONENTS]


def _json(capsys, *argv: str) -> dict:
    assert main(list(argv)) in (0, 1)
    return json.loads(capsys.readouterr().out)


def _fields(keys) -> set[str]:
    """Field names (``drive{i}_*``) of column names; a name with no field stays as it is."""
    out = set()
    for k in keys:
        try:
            out.add(R.field(k).name)
        except KeyError:
            out.add(k)
    return out


def _docs_table_fields() -> list[str]:
    text = (ROOT / "docs" / "results.md").read_text()
    return re.findall(r"^\| `([^`]+)` \|", text, flags=re.M)


@pytest.fixture(scope="module")
def simulate_json() -> dict:
    out = {}

    def run(capsys):
        if not out:
            out.update(_json(capsys, "simulate", str(CONVEYOR), "--model", "nonlin",
                             "--elements", "40", "--start-time-s", "30", "--run-s", "2",
                             "--stop-mode", "brake", "--json", "--no-check"))
        return out

    return run


def test_every_field_has_a_unit_and_a_meaning():
    assert len(R.FIELDS) == sum(len(g.fields) for g in R.ALL_GROUPS)  # no name twice
    for f in R.FIELDS.values():
        assert f.unit and f.meaning and f.label, f
        suffix = {"kN": "_kn", "kW": "_kw", "m": "_m", "s": "_s", "%": "_pct", "kg": "_kg",
                  "kg/m": "_kg_m", "m/s": "_m_s", "N": "_n", "h": "_h",
                  "kNm": "_knm"}.get(f.unit)
        # SPEC: every key that carries a unit ends in it (an error bar: its figure's name,
        # then _err or _converged, SPEC 7.4)
        name = f.name.removesuffix("_err").removesuffix("_converged")
        # SPEC 7.4 names this one with its unit inside (liftoff_max_kn_over)
        name = name.removesuffix("_over") if name == "liftoff_max_kn_over" else name
        if suffix:
            assert name.endswith(suffix), f.name


def test_parquet_runs_schema_holds_exactly_the_defined_fields():
    axes = [{"column": "temperature_c", "values": [-20, 20]}]
    names = runs_schema_for_axes(axes).names
    results = [n for n in names if n not in INPUT_COLUMNS and n != "temperature_c"]
    assert len(results) == len(set(results))
    assert set(results) == set(R.columns())
    assert _fields(results) == {f.name for g in R.GROUPS for f in g}
    schema = runs_schema_for_axes(axes)
    for name in results:
        text = R.field(name).text
        assert (schema.field(name).type == "string") == text, name
        assert (schema.field(name).type == "bool") == R.field(name).flag, name


def test_simulate_json_holds_exactly_the_defined_fields(capsys, simulate_json):
    s = simulate_json(capsys)
    assert s["status"] != "failed", s["message"]
    results = set(s) - CLI_INPUTS - {R.TE_COMPONENTS_KEY}
    # no curves on this conveyor: no curve{k}_* / hcurve{k}_* fields
    expected = {c for g in NON_TE for f in g
                for c in f.columns(drives=3, pulleys=PULLEYS, curves=0, hcurves=0)}
    assert results == expected
    assert set(s[R.TE_COMPONENTS_KEY]) <= set(R.TE_PARTS)
    assert set(s[R.TE_COMPONENTS_KEY]) == {"idler_rotation", "indentation", "belt_flexure",
                                           "material_flexure", "lift", "feed", "secondary",
                                           "accessories"}


def test_static_json_holds_the_steady_fields(capsys):
    s = _json(capsys, "static", str(CONVEYOR), "--json")
    results = set(s) - CLI_INPUTS - {R.TE_COMPONENTS_KEY}
    steady = (R.STEADY, R.STEADY_DRIVE, R.DESIGN, R.DESIGN_DRIVE, R.DESIGN_BASIS,
              R.CHECKS, R.BOOKKEEPING, R.DRIVE_POWER)
    assert results == {c for g in steady for f in g
                       for c in f.columns(drives=3, pulleys=PULLEYS)}


def test_rest_rows_hold_the_stored_fields(capsys, simulate_json):
    row = {"study_id": "0" * 16, "run_id": "1" * 16, "friction_model": "nonlin",
           "engine_version": "x", **flatten_summary(simulate_json(capsys))}
    out = row_to_json(row)
    results = set(out) - set(INPUT_COLUMNS) - {R.TE_COMPONENTS_KEY}
    assert results == {c for g in NON_TE for f in g for c in f.columns()}
    assert set(out[R.TE_COMPONENTS_KEY]) <= set(R.TE_PARTS)


def test_docs_table_holds_exactly_the_defined_fields():
    listed = _docs_table_fields()
    assert len(listed) == len(set(listed))
    assert set(listed) == set(R.FIELDS)
    assert (ROOT / "docs" / "results.md").read_text() == R.markdown(), (
        "docs/results.md is stale: python -m beltstudy.engine.results > docs/results.md")


def test_a_result_without_a_definition_is_refused():
    R.check_summary({"te_kn": 1.0, "drive6_slip_m": 0.0, "te_components_kn": {"lift": 1.0}})
    with pytest.raises(KeyError, match="te_new_part_kn"):
        R.check_summary({"te_kn": 1.0, "te_new_part_kn": 2.0})
    with pytest.raises(KeyError, match="drive7_slip_m"):
        R.check_summary({"drive7_slip_m": 0.0})
    R.check_summary({f"pulley{R.MAX_PULLEYS}_resultant_kn": 1.0})
    beyond = f"pulley{R.MAX_PULLEYS + 1}_resultant_kn"
    with pytest.raises(KeyError, match=beyond):
        R.check_summary({beyond: 1.0})
    with pytest.raises(KeyError, match="pulley1_new_kn"):
        R.check_summary({"pulley1_new_kn": 1.0})
