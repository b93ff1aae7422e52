"""The CLI maps errors by type: user mistakes are one line and exit 2, anything else raises."""

from __future__ import annotations

import argparse

import pytest

import beltstudy.service.cli as cli
from beltstudy.engine.errors import InputError
from beltstudy.service.errors import Conflict, Invalid, NotFound, ServiceError, Unavailable


def _raising(monkeypatch, exc: BaseException) -> None:
    def build_parser():
        parser = argparse.ArgumentParser()

        def func(_args):
            raise exc

        parser.set_defaults(func=func)
        return parser

    monkeypatch.setattr(cli, "build_parser", build_parser)


@pytest.mark.parametrize("exc", [InputError("must be > 0", field="scenario.run_s"),
                                 Invalid("grid: empty"), NotFound("study 'x' not found"),
                                 Conflict("being deleted"), Unavailable("no service")])
def test_user_errors_are_one_line_and_exit_2(monkeypatch, capsys, exc):
    _raising(monkeypatch, exc)
    assert cli.main([]) == 2
    err = capsys.readouterr().err
    assert err == f"error: {exc}\n"


def test_a_service_error_prints_its_user_message(monkeypatch, capsys):
    class Custom(ServiceError):
        @property
        def user_message(self) -> str:
            return "said for people"

    _raising(monkeypatch, Custom("raw"))
    assert cli.main([]) == 2
    assert capsys.readouterr().err == "error: said for people\n"


def test_an_error_named_like_a_user_error_is_not_one(monkeypatch):
    """Only the types count: an unrelated exception class called Invalid is a bug."""
    Invalid = type("Invalid", (RuntimeError,), {})
    _raising(monkeypatch, Invalid("boom"))
    with pytest.raises(RuntimeError, match="boom"):
        cli.main([])


def test_input_error_keeps_its_field_apart():
    exc = InputError("unknown model 'x'", field="friction_model")
    assert str(exc) == "friction_model: unknown model 'x'"
    assert (exc.field, exc.reason) == ("friction_model", "unknown model 'x'")
    from beltstudy.engine.conveyor import InputError as FromConveyor

    assert FromConveyor is InputError
