"""The layering of ARCHITECTURE.md: a module imports only from its own layer or the ones before it.

errors/units/datasets -> physics -> standards -> machines -> instruments -> procedures ->
compensation -> io/report/store -> api (the public API) -> cli/web. The check reads every
module's import statements (including imports inside functions) with ``ast``; it does not import
anything.
"""

import ast
from pathlib import Path

import axiscal

# "data" is package data (configurations, LinuxCNC files, the HAL component axiscal ships): it
# imports nothing of axiscal, so any layer may read it.
LAYER = {"errors": 1, "units": 1, "datasets": 1, "data": 1, "_parse": 1, "_json": 1, "_schema": 1,
         "_frames": 1, "physics": 2, "standards": 3,
         "machines": 4, "instruments": 5, "procedures": 6, "compensation": 7, "programs": 7,
         "io": 8,
         "report": 8, "store": 8, "api": 8.5, "cli": 9, "web": 9, "__main__": 9}
ROOT = Path(axiscal.__file__).parent


def _imported_axiscal_modules(tree):
    for node in ast.walk(tree):
        if isinstance(node, ast.ImportFrom) and node.module and node.module.startswith("axiscal."):
            yield node.lineno, node.module
        elif isinstance(node, ast.Import):
            for alias in node.names:
                if alias.name.startswith("axiscal."):
                    yield node.lineno, alias.name


def test_every_package_has_a_layer():
    tops = {p.name.removesuffix(".py") for p in ROOT.iterdir()
            if (p.suffix == ".py" or (p.is_dir() and (p / "__init__.py").exists()))}
    assert tops - {"__init__"} <= set(LAYER), f"no layer for {tops - {'__init__'} - set(LAYER)}"


def test_no_module_imports_from_a_later_layer():
    bad = []
    for f in ROOT.rglob("*.py"):
        top = f.relative_to(ROOT).parts[0].removesuffix(".py")
        if top == "__init__":
            continue
        for lineno, module in _imported_axiscal_modules(ast.parse(f.read_text("utf-8"))):
            target = module.split(".")[1]
            if LAYER.get(target, 0) > LAYER[top]:
                bad.append(f"{f.relative_to(ROOT)}:{lineno} ({top}) imports {module}")
    assert not bad, "imports against the layering:\n" + "\n".join(bad)


def _module_name(path: Path) -> str:
    parts = list(path.relative_to(ROOT.parent).with_suffix("").parts)
    return ".".join(parts[:-1] if parts[-1] == "__init__" else parts)


def _import_graph() -> dict[str, set[str]]:
    """module -> the axiscal modules it imports, at the top or inside a function (``from P import
    m`` counts as importing the submodule ``P.m`` when there is one); the root package
    ``axiscal`` (whose ``__init__`` only exposes api.py lazily) is left out."""
    files = {_module_name(f): f for f in ROOT.rglob("*.py")}
    graph = {}
    for name, f in files.items():
        package = name if f.name == "__init__.py" else name.rpartition(".")[0]
        targets = set()
        for node in ast.walk(ast.parse(f.read_text("utf-8"))):
            if isinstance(node, ast.ImportFrom):
                base = node.module or ""
                if node.level:
                    up = package.split(".")[: len(package.split(".")) - node.level + 1]
                    base = ".".join(up + ([base] if base else []))
                targets |= {f"{base}.{a.name}" if f"{base}.{a.name}" in files else base
                            for a in node.names}
            elif isinstance(node, ast.Import):
                targets |= {a.name for a in node.names}
        graph[name] = {t for t in targets if t in files and t not in ("axiscal", name)}
    return graph


def _circles(graph: dict[str, set[str]]) -> list[list[str]]:
    """The strongly connected components of more than one module (Tarjan's algorithm)."""
    index, low, stack, on_stack, found = {}, {}, [], set(), []

    def visit(v):
        index[v] = low[v] = len(index)
        stack.append(v)
        on_stack.add(v)
        for w in graph.get(v, ()):
            if w not in index:
                visit(w)
                low[v] = min(low[v], low[w])
            elif w in on_stack:
                low[v] = min(low[v], index[w])
        if low[v] == index[v]:
            component = []
            while not component or component[-1] != v:
                component.append(stack.pop())
                on_stack.discard(component[-1])
            if len(component) > 1:
                found.append(sorted(component))

    for v in sorted(graph):
        if v not in index:
            visit(v)
    return found


def test_the_circle_finder_finds_a_circle_and_counts_imports_inside_functions():
    """The checker below could fail: a two-module circle (and a bystander importing into it) is
    found, and a function-level import of the package is an edge of the graph."""
    assert _circles({"a": {"b"}, "b": {"a"}, "c": {"a"}, "d": set()}) == [["a", "b"]]
    assert _circles({"a": {"b"}, "b": {"c"}, "c": {"a"}}) == [["a", "b", "c"]]
    assert _circles({"a": {"b"}, "b": set()}) == []
    graph = _import_graph()
    # cli/iso230_2 imports store_run only inside its command function
    assert "axiscal.cli._history_store" in graph["axiscal.cli.iso230_2"]


def test_no_import_circles_inside_the_package():
    """No module reaches itself through its imports (top-level or inside functions): a helper two
    modules share lives in a lower module both import (issue 30, "the house")."""
    circles = _circles(_import_graph())
    assert not circles, "import circles:\n" + "\n".join(" <-> ".join(c) for c in circles)
