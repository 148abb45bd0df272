# SPDX-License-Identifier: BSD-3-Clause
"""The shape of the gencoord package: each stage a sub-package, no import cycle, small
modules and functions, and the folders docs/design.md's diagram names."""

from __future__ import annotations

import ast
import re
import unittest
from pathlib import Path

REPOSITORY = Path(__file__).resolve().parents[2]
PACKAGE = REPOSITORY / "python" / "gencoord"
MAX_MODULE_LINES = 400
MAX_FUNCTION_LINES = 60


def module_name(path: Path) -> str:
    parts = path.relative_to(PACKAGE.parent).with_suffix("").parts
    return ".".join(parts[:-1] if parts[-1] == "__init__" else parts)


def modules() -> dict[str, Path]:
    return {module_name(p): p for p in sorted(PACKAGE.rglob("*.py"))}


def imports_of(path: Path, known: dict[str, Path]) -> set[str]:
    """The package's modules that `path` imports anywhere in it (lazy imports too, as they
    run too)."""
    found = set()
    tree = ast.parse(path.read_text(encoding="utf-8"))
    # imports for annotations only (`if TYPE_CHECKING:`) never run
    typing_only = {id(inner) for node in ast.walk(tree)
                   if isinstance(node, ast.If) and ast.unparse(node.test) == "TYPE_CHECKING"
                   for inner in ast.walk(node)}
    for node in ast.walk(tree):
        if id(node) in typing_only:
            continue
        if isinstance(node, ast.Import):
            names = [alias.name for alias in node.names]
        elif isinstance(node, ast.ImportFrom) and node.module and node.level == 0:
            # `from gencoord.x import y`: y may be a module of the package x
            names = [node.module] + [f"{node.module}.{alias.name}" for alias in node.names]
        else:
            continue
        found.update(name for name in names if name in known)
    return found


def import_cycle(graph: dict[str, set[str]]) -> list[str] | None:
    """One cycle of the graph, or None (depth-first search, colouring each module)."""
    state: dict[str, int] = {}
    stack: list[str] = []

    def visit(node: str) -> list[str] | None:
        state[node] = 1
        stack.append(node)
        for target in sorted(graph[node]):
            if state.get(target) == 1:
                return stack[stack.index(target):] + [target]
            if target not in state:
                cycle = visit(target)
                if cycle:
                    return cycle
        stack.pop()
        state[node] = 2
        return None

    for node in sorted(graph):
        if node not in state:
            cycle = visit(node)
            if cycle:
                return cycle
    return None


class PackageLayoutTest(unittest.TestCase):

    def test_no_import_cycle(self):
        known = modules()
        # a package's __init__ is imported with each of its modules; an edge from a module
        # into its own package's __init__ is that, not a cycle
        graph = {name: {target for target in imports_of(path, known)
                        if not name.startswith(target + ".")}
                 for name, path in known.items()}
        self.assertIsNone(import_cycle(graph))

    def test_the_cycle_finder_finds_one(self):
        self.assertEqual(import_cycle({"a": {"b"}, "b": {"c"}, "c": {"a"}}),
                         ["a", "b", "c", "a"])
        self.assertIsNone(import_cycle({"a": {"b"}, "b": {"c"}, "c": set()}))

    def test_modules_and_functions_are_small(self):
        long = []
        for name, path in modules().items():
            text = path.read_text(encoding="utf-8")
            lines = text.count("\n")
            if lines > MAX_MODULE_LINES:
                long.append(f"{name}: {lines} lines")
            for node in ast.walk(ast.parse(text)):
                if isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef)):
                    length = node.end_lineno - node.lineno + 1
                    if length > MAX_FUNCTION_LINES:
                        long.append(f"{name}.{node.name}: {length} lines")
        self.assertEqual(long, [])

    def test_the_design_diagram_names_every_folder(self):
        design = (REPOSITORY / "docs" / "design.md").read_text(encoding="utf-8")
        diagram = design[design.index("<!-- package layout -->"):]
        diagram = diagram[:diagram.index("```", diagram.index("```") + 3)]
        named = set(re.findall(r"^  ([a-z_]+)/", diagram, re.MULTILINE))
        folders = {p.name for p in PACKAGE.iterdir() if p.is_dir() and p.name != "__pycache__"}
        self.assertEqual(named, folders)
        for folder in folders:
            self.assertTrue((PACKAGE / folder / "__init__.py").is_file(), folder)


if __name__ == "__main__":
    unittest.main()
