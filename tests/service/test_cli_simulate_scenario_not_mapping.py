"""beltstudy simulate with a scenario file whose start or stop is no mapping: 'start: null'
was read as no start (POST /studies refuses the same scenario, 422 'scenario.start: null is
not of type "object"'), and with --start-time-s / --stop-time-s the option was written into
it: a TypeError traceback ('NoneType' object does not support item assignment; list indices
must be integers). Each is now one line naming the field, exit 2, before anything runs."""

from __future__ import annotations

import pytest
import yaml

import beltstudy.service.cli as cli
from beltstudy.service.examples import TINY_CONVEYOR, TINY_SCENARIO


@pytest.mark.parametrize(("field", "value", "options", "needle"), [
    ("start", None, [], 'scenario.start: null is not of type "object"'),
    ("start", None, ["--start-time-s", "3"], 'scenario.start: null is not of type "object"'),
    ("stop", [1], ["--stop-time-s", "3"], 'scenario.stop: [1] is not of type "object"'),
    ("stop", "coast", ["--stop-mode", "coast"], 'scenario.stop: "coast" is not of type'),
])
def test_a_start_or_stop_that_is_no_mapping_is_refused_naming_it(tmp_path, capsys, field,
                                                                   value, options, needle):
    conveyor = tmp_path / "tiny.yaml"
    conveyor.write_text(yaml.safe_dump(TINY_CONVEYOR))
    scenario = tmp_path / "scenario.yaml"
    scenario.write_text(yaml.safe_dump({"scenario": {**TINY_SCENARIO, field: value}}))
    code = cli.main(["simulate", str(conveyor), "--scenario", str(scenario), "--no-check",
                     "--no-remedy", *options])
    err = capsys.readouterr().err.strip()
    assert code == 2, err
    assert err.startswith(f"error: {needle}"), err
    assert "\n" not in err


@pytest.mark.parametrize(("stray", "needle"), [
    ({"extra": 1}, "extra: unknown key beside the 'scenario:' mapping"),
    ({"run_s": 10}, "run_s: a scenario field outside the 'scenario:' mapping"),
])
def test_a_key_beside_the_scenario_mapping_is_named_not_the_mapping(tmp_path, capsys, stray,
                                                                      needle):
    # 'scenario: {...}' and 'extra: 1' was told 'scenario.scenario: unknown key', which
    # asks the user to drop the valid wrapper; the stray key is the fault
    conveyor = tmp_path / "tiny.yaml"
    conveyor.write_text(yaml.safe_dump(TINY_CONVEYOR))
    scenario = tmp_path / "scenario.yaml"
    scenario.write_text(yaml.safe_dump({"scenario": dict(TINY_SCENARIO), **stray}))
    code = cli.main(["simulate", str(conveyor), "--scenario", str(scenario), "--no-check",
                     "--no-remedy"])
    err = capsys.readouterr().err.strip()
    assert code == 2, err
    assert err.startswith(f"error: {scenario}: {needle}"), err
    assert "scenario.scenario" not in err and "\n" not in err
