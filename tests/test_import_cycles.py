"""No import cycles among the modules of ``engine/`` and ``service/`` (installed as
``beltstudy.engine`` and ``beltstudy.service``).

Every ``import`` and ``from ... import`` counts, at module level and inside functions: a
cycle hidden in a function is still two modules that need each other. An import of a
package counts as an import of its ``__init__``; ``from package import name`` counts as an
import of the submodule ``package.name`` when that is a module, else of the package.
"""

from __future__ import annotations

import ast
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
PACKAGES = ("engine", "service")


def module_files() -> dict[str, Path]:
    """Dotted module name -> file, for every module of the packages."""
    out = {}
    for pkg in PACKAGES:
        for path in sorted((ROOT / pkg).rglob("*.py")):
            parts = list(path.relative_to(ROOT).with_suffix("").parts)
            if parts[-1] == "__init__":
                parts.pop()
            out[".".join(["beltstudy", *parts])] = path
    return out


def imports_of(name: str, path: Path, modules: set[str]) -> set[str]:
    """The project modules ``name`` imports (anywhere in the file)."""
    is_pkg = path.name == "__init__.py"
    found = set()
    for node in ast.walk(ast.parse(path.read_text(), str(path))):
        if isinstance(node, ast.Import):
            targets = [a.name for a in node.names]
        elif isinstance(node, ast.ImportFrom):
            base = node.module or ""
            if node.level:
                anchor = name.split(".") if is_pkg else name.split(".")[:-1]
                anchor = anchor[: len(anchor) - (node.level - 1)]
                base = ".".join(anchor + ([base] if base else []))
            targets = [f"{base}.{a.name}" if f"{base}.{a.name}" in modules else base
                       for a in node.names]
        else:
            continue
        for target in targets:
            while target and target not in modules:  # import beltstudy.engine.x.y of a name
                target = target.rpartition(".")[0]
            if target and target != name:
                found.add(target)
    return found


def import_graph() -> dict[str, set[str]]:
    files = module_files()
    return {name: imports_of(name, path, set(files)) for name, path in files.items()}


def find_cycles(graph: dict[str, set[str]]) -> list[list[str]]:
    """The strongly connected components with more than one module (Tarjan), each as one
    cycle through its modules."""
    index: dict[str, int] = {}
    low: dict[str, int] = {}
    stack: list[str] = []
    on_stack: set[str] = set()
    comps: list[list[str]] = []

    def visit(v: str) -> None:
        index[v] = low[v] = len(index)
        stack.append(v)
        on_stack.add(v)
        for w in sorted(graph.get(v, ())):
            if w not in index:
                visit(w)
                low[v] = min(low[v], low[w])
            elif w in on_stack:
                low[v] = min(low[v], index[w])
        if low[v] == index[v]:
            comp = []
            while True:
                w = stack.pop()
                on_stack.discard(w)
                comp.append(w)
                if w == v:
                    break
            if len(comp) > 1:
                comps.append(comp)

    for v in sorted(graph):
        if v not in index:
            visit(v)
    return [_cycle_in(graph, set(c)) for c in comps]


def _cycle_in(graph: dict[str, set[str]], comp: set[str]) -> list[str]:
    """One cycle through the first module of a strongly connected component."""
    start = min(comp)
    paths = {start: [start]}
    todo = [start]
    while todo:
        v = todo.pop(0)
        for w in sorted(graph[v] & comp):
            if w == start:
                return paths[v] + [start]
            if w not in paths:
                paths[w] = paths[v] + [w]
                todo.append(w)
    return sorted(comp)


def test_the_cycle_finder_finds_a_cycle():
    graph = {"a": {"b"}, "b": {"c"}, "c": {"a"}, "d": {"a"}}
    assert find_cycles(graph) == [["a", "b", "c", "a"]]
    assert find_cycles({"a": {"b"}, "b": set()}) == []


def test_the_graph_sees_function_level_and_relative_imports():
    graph = import_graph()
    assert "beltstudy.engine.conveyor" in graph["beltstudy.engine.run"]
    # beltstudy.service.dask.tasks imports the engine's run module only inside run_spec()
    assert "beltstudy.engine.run" in graph["beltstudy.service.dask.tasks"]


def test_no_import_cycles_in_engine_or_service():
    cycles = find_cycles(import_graph())
    assert not cycles, "import cycles: " + "; ".join(" -> ".join(c) for c in cycles)


def reachable(graph: dict[str, set[str]], start: str) -> set[str]:
    """Every module ``start`` imports, directly or through others."""
    seen: set[str] = set()
    todo = [start]
    while todo:
        for w in graph.get(todo.pop(), ()):
            if w not in seen:
                seen.add(w)
                todo.append(w)
    return seen


def test_the_door_reaches_neither_the_workers_nor_the_faces():
    """The study door (parse, study model, study file, schema) stands before the Dask side
    and the faces: none of its modules imports, even through others, the executor, jobs or
    worker tasks, the study service, the API, the CLI or the web pages."""
    graph = import_graph()
    beyond = ("beltstudy.service.dask", "beltstudy.service.api", "beltstudy.service.cli",
              "beltstudy.service.web", "beltstudy.service.studies")
    door = [m for m in graph if m.startswith("beltstudy.service.door")]
    assert door
    for module in door:
        reached = sorted(m for m in reachable(graph, module) if m.startswith(beyond))
        assert not reached, f"{module} reaches {', '.join(reached)}"


#: Engine modules the service must not import: it reaches them through the engine's public
#: API (``beltstudy.engine``'s ``__init__``), issue 25's rule.
ENGINE_INSIDES = ("beltstudy.engine.statics", "beltstudy.engine.design",
                  "beltstudy.engine.dynamics", "beltstudy.engine.loop")


def test_the_service_reaches_statics_design_dynamics_and_loop_only_through_the_engine_api():
    graph = import_graph()
    found = sorted(f"{m} imports {w}" for m, ws in graph.items()
                   if m.startswith("beltstudy.service") for w in ws
                   if any(w == e or w.startswith(e + ".") for e in ENGINE_INSIDES))
    assert not found, "; ".join(found)
