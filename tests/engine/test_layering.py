"""The engine stands without the service: no engine test (nor a conftest or helper the engine
tests load) imports ``beltstudy.service`` or the service's tests, and no engine module imports
the service.

Read from the files' syntax trees, so an import inside a function counts as much as one at the
top, and nothing is imported to check it.
"""

from __future__ import annotations

import ast
from pathlib import Path

TESTS = Path(__file__).resolve().parents[1]
ROOT = TESTS.parent
#: Modules an engine test must not import, with their submodules.
SERVICE = ("beltstudy.service", "tests.service", "tests.web")


def imported_modules(tree: ast.AST) -> list[tuple[int, str]]:
    """Every module a file imports, with its line: ``import a.b`` gives ``a.b``, ``from a
    import b`` gives ``a.b`` (``b`` may be a submodule), ``importlib.import_module("a.b")`` and
    ``__import__("a.b")`` with a literal name give ``a.b``. Relative imports are not used in
    the tests and are reported by their dots."""
    found = []
    for node in ast.walk(tree):
        if isinstance(node, ast.Import):
            found += [(node.lineno, a.name) for a in node.names]
        elif isinstance(node, ast.ImportFrom):
            base = "." * node.level + (node.module or "")
            found += [(node.lineno, f"{base}.{a.name}" if base else a.name) for a in node.names]
        elif (isinstance(node, ast.Call) and node.args
              and isinstance(node.args[0], ast.Constant) and isinstance(node.args[0].value, str)
              and ((isinstance(node.func, ast.Attribute) and node.func.attr == "import_module")
                   or (isinstance(node.func, ast.Name)
                       and node.func.id in ("import_module", "__import__")))):
            found.append((node.lineno, node.args[0].value))
    return found


def service_imports(path: Path) -> list[str]:
    """``file:line module`` for each import of the service (or its tests) in the file."""
    tree = ast.parse(path.read_text(), str(path))
    return [f"{path.relative_to(ROOT)}:{line} {name}" for line, name in imported_modules(tree)
            if any(name == s or name.startswith(s + ".") for s in SERVICE)]


def engine_test_files() -> list[Path]:
    """The engine's test files and helpers, and the conftest every test loads."""
    return sorted((TESTS / "engine").rglob("*.py")) + [TESTS / "conftest.py"]


def test_the_import_reader_sees_every_form():
    tree = ast.parse(
        "import beltstudy.service.cli\n"
        "from beltstudy import service\n"
        "from beltstudy.service.studies import StudyService\n"
        "def f():\n"
        "    from tests.service.conftest import tiny_study\n"
        "    return importlib.import_module('beltstudy.service.tasks')\n"
        "import beltstudy.engine.run\n"
        "from tests.conftest import CONVEYORS\n")
    assert sorted(name for _, name in imported_modules(tree)) == [
        "beltstudy.engine.run", "beltstudy.service", "beltstudy.service.cli",
        "beltstudy.service.studies.StudyService", "beltstudy.service.tasks",
        "tests.conftest.CONVEYORS", "tests.service.conftest.tiny_study"]


def test_engine_tests_never_import_the_service():
    found = [hit for path in engine_test_files() for hit in service_imports(path)]
    assert not found, "engine tests import the service: " + "; ".join(found)


def test_the_engine_never_imports_the_service():
    found = [hit for path in sorted((ROOT / "engine").rglob("*.py"))
             for hit in service_imports(path)]
    assert not found, "the engine imports the service: " + "; ".join(found)
