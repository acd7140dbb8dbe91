"""The document package imports in one direction (issue 12: pipeline.py <->
objects.py <-> viewproviders.py imported each other).

Every import between the package's modules counts, also the ones inside
functions (a lazy import still ties the modules together); the graph must have
no cycle.
"""

import ast
import os

from conftest import REPO_DIR

PACKAGE = os.path.join(REPO_DIR, "LeatherCutWorkbench", "document")


def imports_of(path):
    """Names of the sibling modules ``path`` imports (``from . import x``, ``from .x import y``)."""
    tree = ast.parse(open(path, encoding="utf-8").read(), path)
    out = set()
    for node in ast.walk(tree):
        if isinstance(node, ast.ImportFrom) and node.level == 1:
            if node.module:
                out.add(node.module.split(".")[0])
            else:
                out.update(a.name for a in node.names)
    return out


def graph():
    mods = {f[:-3] for f in os.listdir(PACKAGE) if f.endswith(".py") and f != "__init__.py"}
    return {m: imports_of(os.path.join(PACKAGE, m + ".py")) & mods for m in mods}


def find_cycle(g):
    state = {}

    def visit(m, path):
        state[m] = "open"
        for n in sorted(g[m]):
            if state.get(n) == "open":
                return path[path.index(n):] + [n]
            if n not in state:
                found = visit(n, path + [n])
                if found:
                    return found
        state[m] = "done"
        return None

    for m in sorted(g):
        if m not in state:
            found = visit(m, [m])
            if found:
                return found
    return None


def test_document_modules_import_without_cycles():
    g = graph()
    assert {"pipeline", "objects", "viewproviders"} <= set(g)
    assert find_cycle(g) is None, " -> ".join(find_cycle(g))


def test_the_cycle_finder_sees_a_lazy_import_cycle():
    assert find_cycle({"a": {"b"}, "b": {"c"}, "c": {"a"}}) == ["a", "b", "c", "a"]
    assert find_cycle({"a": {"b"}, "b": set()}) is None
