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

#: Sub-command modules, in the order they appear in ``--help``.
COMMAND_MODULES = ("static", "sweep", "simulate", "study", "calibrate")


def build_parser() -> argparse.ArgumentParser:
    parser = argparse.ArgumentParser(
        prog="beltstudy",
        description="Belt conveyor friction models, Euler-X transient simulation and "
        "parameter studies on Dask.",
    )
    sub = parser.add_subparsers(dest="command", metavar="COMMAND")
    for name in COMMAND_MODULES:
        module = importlib.import_module(f"beltstudy.service.cli.{name}")
        module.register(sub)
    return parser


def main(argv: list[str] | None = None) -> int:
    parser = build_parser()
    args = parser.parse_args(argv)
    if not getattr(args, "func", None):
        parser.print_help()
        return 2
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
