# Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
"""The modules of mjfanalysis import one another one way only: no import circle, at module level
or inside a function (a lazy import still ties the two modules together)."""
import ast
from pathlib import Path

PACKAGE = Path(__file__).resolve().parents[2] / "analysis" / "mjfanalysis"


def _imports(path: Path) -> set[str]:
    """The sibling modules `path` imports (relative or as mjfanalysis.X), anywhere in the file."""
    found = set()
    for node in ast.walk(ast.parse(path.read_text())):
        if isinstance(node, ast.ImportFrom):
            if node.level == 1 and node.module:
                found.add(node.module.split(".")[0])
            elif node.level == 1:
                found.update(alias.name for alias in node.names)
            elif node.module and node.module.startswith("mjfanalysis."):
                found.add(node.module.split(".")[1])
        elif isinstance(node, ast.Import):
            found.update(a.name.split(".")[1] for a in node.names
                         if a.name.startswith("mjfanalysis."))
    return found


def _graph() -> dict[str, set[str]]:
    modules = {p.stem: p for p in PACKAGE.glob("*.py") if p.stem != "__init__"}
    return {name: _imports(path) & modules.keys() for name, path in modules.items()}


def _cycle(graph: dict[str, set[str]]) -> list[str] | None:
    state = {}  # 1: on the current path, 2: done

    def visit(node, path):
        state[node] = 1
        for nxt in sorted(graph[node]):
            if state.get(nxt) == 1:
                return path + [node, nxt]
            if nxt not in state:
                found = visit(nxt, path + [node])
                if found:
                    return found
        state[node] = 2
        return None

    for start in sorted(graph):
        if start not in state:
            found = visit(start, [])
            if found:
                return found
    return None


def test_the_graph_is_read():
    graph = _graph()
    assert "varied" in graph["io"] and "varied" in graph["sweep_plot"]
    assert "sweep_plot" in graph["io"]  # Sweep.plot's lazy import counts


def test_no_import_circle():
    assert _cycle(_graph()) is None


def test_a_circle_is_found():
    assert _cycle({"a": {"b"}, "b": {"c"}, "c": {"a"}}) is not None
    assert _cycle({"a": {"b"}, "b": set()}) is None
