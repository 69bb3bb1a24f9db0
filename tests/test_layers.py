"""The layering of ARCHITECTURE.md: a module imports only from its own layer or the ones before it.

errors/units/datasets -> physics -> standards -> machines -> instruments -> procedures ->
compensation -> io/report/store -> api (the public API) -> cli/web. The check reads every
module's import statements (including imports inside functions) with ``ast``; it does not import
anything.
"""

import ast
from pathlib import Path

import axiscal

LAYER = {"errors": 1, "units": 1, "datasets": 1, "_parse": 1, "_json": 1, "_schema": 1, "physics": 2, "standards": 3,
         "machines": 4, "instruments": 5, "procedures": 6, "compensation": 7, "io": 8,
         "report": 8, "store": 8, "data": 8, "api": 8.5, "cli": 9, "web": 9, "__main__": 9}
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
