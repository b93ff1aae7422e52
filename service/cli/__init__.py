"""The ``beltstudy`` command line.

Each sub-command lives in its own module with a ``register(subparsers)`` function that adds
its parser and sets ``func``. User mistakes (:class:`beltstudy.engine.errors.InputError` and every
:class:`beltstudy.service.errors.ServiceError`: an invalid study, an unknown id, a service that does
not answer) print one line and exit with status 2; no traceback. So does an ``OSError`` on a
file the user named (the one the error names: a name too long, a folder for a file).
"""

from __future__ import annotations

import argparse
import importlib
import sys

from beltstudy.engine import InputError
from beltstudy.service.errors import ServiceError, file_problem
from beltstudy.service.settings import unknown_variables

#: Sub-command modules, in the order they appear in ``--help``.
COMMAND_MODULES = ("static", "sweep", "simulate", "study", "calibrate")

#: Which module registers each command. A command given on the command line imports only its
#: own module: importing them all (the study commands' Dask and HTTP client, the calibration's
#: fitting) took ``beltstudy static`` from 0.66 to 1.5 s of CPU before it read its file.
#: ``tests/test_cli_static.py`` checks this table against what the modules register.
COMMANDS = {
    "static": "static",
    "sweep-temperature": "sweep",
    "simulate": "simulate",
    "serve": "study",
    "submit": "study",
    "run": "study",
    "status": "study",
    "results": "study",
    "report": "study",
    "compare": "study",
    "uncertainty": "study",
    "demo": "study",
    "calibrate": "calibrate",
}


def build_parser(command: str | None = None) -> argparse.ArgumentParser:
    """The parser of every command, or only of ``command`` (one of :data:`COMMANDS`)."""
    parser = argparse.ArgumentParser(
        prog="beltstudy",
        description="Belt conveyor friction models, Euler-X transient simulation and "
        "parameter studies on Dask.",
    )
    sub = parser.add_subparsers(dest="command", metavar="COMMAND")
    names = (COMMANDS[command],) if command in COMMANDS else COMMAND_MODULES
    for name in names:
        module = importlib.import_module(f"beltstudy.service.cli.{name}")
        module.register(sub)
    return parser


def _command(argv: list[str]) -> str | None:
    """The command named on the command line, when it is the first word and a known one."""
    return argv[0] if argv and argv[0] in COMMANDS else None


def main(argv: list[str] | None = None) -> int:
    argv = sys.argv[1:] if argv is None else list(argv)
    command = _command(argv)
    parser = build_parser(command) if command else build_parser()
    args = parser.parse_args(argv)
    if not getattr(args, "func", None):
        parser.print_help()
        return 2
    for line in unknown_variables():  # a misspelt BELTSTUDY_ setting, else ignored in silence
        print(f"warning: {line}", file=sys.stderr)
    try:
        code = args.func(args)
    except InputError as exc:
        print(f"error: {exc}", file=sys.stderr)
        return 2
    except ServiceError as exc:
        print(f"error: {exc.user_message}", file=sys.stderr)
        return 2
    except BrokenPipeError:  # output piped into head, less, ...
        sys.stderr.close()
        return 0
    except OSError as exc:
        if exc.filename is None:  # not about a file the user named: a bug or the machine
            raise
        # reading or writing a file the user named (a name over the file system's limit, a
        # folder that is a file, no permission): one line naming it, whichever command
        print(f"error: {file_problem(exc)}", file=sys.stderr)
        return 2
    except KeyboardInterrupt:
        print("interrupted", file=sys.stderr)
        return 130
    return int(code or 0)


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
