"""No function in ``engine/`` or ``service/`` over 150 lines of code (its docstring, blank
lines and comment lines excluded) nor with more than 12 parameters (issue 25's rule for rooms
a newcomer can change). Read from the syntax trees."""

from __future__ import annotations

import ast
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
MAX_LINES, MAX_PARAMS = 150, 12


def function_sizes(source: str) -> list[tuple[str, int, int, int]]:
    """(name, line, code lines, parameters) of every function and method in ``source``."""
    lines = source.splitlines()
    out = []
    for node in ast.walk(ast.parse(source)):
        if not isinstance(node, ast.FunctionDef | ast.AsyncFunctionDef):
            continue
        a = node.args
        params = (len(a.posonlyargs) + len(a.args) + len(a.kwonlyargs)
                  + (a.vararg is not None) + (a.kwarg is not None))
        body = node.body
        if (isinstance(body[0], ast.Expr) and isinstance(body[0].value, ast.Constant)
                and isinstance(body[0].value.value, str)):
            body = body[1:]
        code = 0
        if body:
            span = lines[body[0].lineno - 1:node.end_lineno]
            code = sum(1 for t in span if t.strip() and not t.strip().startswith("#"))
        out.append((node.name, node.lineno, code, params))
    return out


def test_the_counter_skips_the_docstring_blanks_and_comments():
    src = ('def f(a, b, *c, d=1, **e):\n    """doc\n\n    more"""\n    # note\n\n'
           '    x = 1\n    return x\n')
    assert function_sizes(src) == [("f", 1, 2, 5)]


def test_no_function_over_150_lines_or_12_parameters():
    found = [f"{path.relative_to(ROOT)}:{line} {name}: {code} lines, {params} parameters"
             for pkg in ("engine", "service") for path in sorted((ROOT / pkg).rglob("*.py"))
             for name, line, code, params in function_sizes(path.read_text())
             if code > MAX_LINES or params > MAX_PARAMS]
    assert not found, "; ".join(found)
