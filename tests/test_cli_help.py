"""Every command's ``--help`` gives each option's default where it has one, with the value the
command uses; ``simulate``'s scenario options give the SPEC section 2 default they fall back to."""

from __future__ import annotations

import argparse

import pytest

import beltstudy.service.cli as cli
from beltstudy.engine import Scenario


def _parser(command: str) -> argparse.ArgumentParser:
    sub = next(a for a in cli.build_parser(command)._actions
               if isinstance(a, argparse._SubParsersAction))
    return sub.choices[command]


def _options(command: str):
    return [a for a in _parser(command)._actions
            if a.option_strings and not isinstance(a, argparse._HelpAction)]


def _help(parser: argparse.ArgumentParser, action: argparse.Action) -> str:
    return " ".join(parser._get_formatter()._expand_help(action).split())


@pytest.mark.parametrize("command", list(cli.COMMANDS))
def test_every_option_says_what_it_is_and_its_default(command):
    parser = _parser(command)
    for action in _options(command):
        name = action.option_strings[-1]
        assert action.help, f"{command} {name}: no help text"
        if (action.default in (None, False, argparse.SUPPRESS) or action.required
                or action.nargs == 0):  # a switch: its help says what it turns off
            continue
        text = _help(parser, action)
        assert "default" in text, f"{command} {name}: default {action.default!r} unsaid: {text}"
        shown = action.default if isinstance(action.default, str) else f"{action.default:g}"
        assert shown in text, f"{command} {name}: says another default than {shown}: {text}"


def test_simulate_scenario_options_name_the_scenario_default():
    scn = Scenario()
    parser = _parser("simulate")
    expect = {"--temperature-c": f"{scn.temperature_c:g}", "--load": str(scn.load),
              "--start-control": scn.start.control, "--start-time-s": f"{scn.start.time_s:g}",
              "--run-s": f"{scn.run_s:g}", "--stop-mode": scn.stop.mode,
              "--stop-time-s": f"{scn.stop.time_s:g}", "--formulation": scn.formulation,
              "--elements": str(scn.elements), "--record-dt-s": f"{scn.record_dt_s:g}"}
    helps = {a.option_strings[-1]: _help(parser, a) for a in _options("simulate")}
    for option, value in expect.items():
        assert f"else {value}" in helps[option], (option, helps[option])


def test_sweep_output_folder_is_o_as_in_results_and_report():
    parser = cli.build_parser("sweep-temperature")
    for spelling in ("-o", "--out", "--output"):
        args = parser.parse_args(["sweep-temperature", "c.yaml", spelling, "outdir"])
        assert args.out == "outdir"
