"""Packaging (issue 33): ``python -m build`` makes a wheel and an sdist; the wheel installs into a
clean virtual environment (no source tree on its path) and runs the public API and
``axiscal demo`` from there; its package data is all inside; installing it pulls no development
dependency.

Offline by design: the wheel is built without build isolation (hatchling comes from the dev
extra) and installed with ``--no-deps --no-index``; its runtime dependencies come from the project
venv's site-packages, named in a ``.pth`` file of the clean venv. Lines of a ``.pth`` are added
to ``sys.path`` as plain folders, so the editable install's own ``.pth`` in that folder (the path
to ``src/``) is NOT processed: ``axiscal`` can only be imported from the wheel.

The clean venv is a plain ``pip install axiscal`` (issue 37): the modules of the ``web`` extra,
present in the project venv, are made unimportable there by a second ``.pth`` whose ``import``
line sets them to None in ``sys.modules`` (as Python treats a module that is not installed), so
the README's API example, ``axiscal demo`` and ``axiscal serve``'s one-line "install the web
extra" run as they would without it. The sdist holds only files git tracks. The wheel is built
once per run: ONE test builds and checks it, so ``pytest -n 2`` (whose workers would each run a
module fixture) does not build it twice; about a minute with the demo.
"""

from __future__ import annotations

import json
import os
import re
import subprocess
import sys
import sysconfig
import zipfile
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
PACKAGE = ROOT / "src" / "axiscal"
#: Distributions that only develop axiscal: none may be a requirement of the wheel.
DEV_ONLY = {"pytest", "pytest-xdist", "pytest-benchmark", "hypothesis", "mypy", "build",
            "selenium", "httpx", "pypdf", "ref-index", "sphinx", "numpydoc", "hatchling"}


def _run(args, **kw) -> subprocess.CompletedProcess:
    r = subprocess.run([str(a) for a in args], capture_output=True, text=True, **kw)
    assert r.returncode == 0, f"{args}: {r.stdout}\n{r.stderr}"
    return r


def _build(out: Path) -> None:
    _run([sys.executable, "-m", "build", "--no-isolation", "--outdir", out, ROOT], cwd=ROOT)


#: The importable modules of the ``web`` extra (pyproject.toml) and those they bring.
WEB_MODULES = ("fastapi", "uvicorn", "starlette", "python_multipart", "multipart", "argon2")


def _install(wheel: Path, env: Path) -> Path:
    """A clean venv at ``env`` with the wheel installed, the project's dependencies by ``.pth``
    and the ``web`` extra hidden; returns its python."""
    _run([sys.executable, "-m", "venv", "--without-pip", env])
    py = env / "bin" / "python"
    _run([sys.executable, "-m", "pip", "--python", py, "install", "--quiet", "--no-deps",
          "--no-index", wheel])
    site = Path(_run([py, "-c", "import sysconfig; print(sysconfig.get_paths()['purelib'])"])
                .stdout.strip())
    (site / "project-deps.pth").write_text(sysconfig.get_paths()["purelib"] + "\n", "utf-8")
    (site / "zz-no-web-extra.pth").write_text(
        f"import sys; sys.modules.update(dict.fromkeys({WEB_MODULES!r}))\n", "utf-8")
    return py


def _clean_env() -> dict:
    return {k: v for k, v in os.environ.items() if k not in ("PYTHONPATH", "PYTHONHOME")}


def test_wheel_builds_installs_clean_and_runs(tmp_path):
    """Build; the wheel holds all package data and requires no development tool; installed in a
    clean venv it runs the public API and ``axiscal demo`` from outside the repository."""
    dist = tmp_path / "dist"
    _build(dist)
    (wheel,) = dist.glob("axiscal-*.whl")
    (sdist,) = dist.glob("axiscal-*.tar.gz")
    assert sdist.stat().st_size > 0
    _check_sdist(sdist)
    _check_package_data(wheel)
    _check_requirements(wheel)
    py = _install(wheel, tmp_path / "env")
    _check_installed(py, tmp_path / "env", tmp_path / "work")
    _check_readme_example(py, tmp_path / "work")
    _check_serve_without_web(tmp_path / "env", tmp_path / "work")


def _check_sdist(sdist: Path) -> None:
    """Every member of the sdist is a file git tracks (the include list of pyproject.toml; a
    stray file inside an included folder would still be packed, and fails here)."""
    import tarfile

    with tarfile.open(sdist) as t:
        members = {m.name.split("/", 1)[1] for m in t.getmembers() if m.isfile()}
    assert {"pyproject.toml", "README.md", "src/axiscal/__init__.py"} <= members
    tracked = subprocess.run(["git", "ls-files"], cwd=ROOT, capture_output=True, text=True)
    if tracked.returncode != 0:   # not a git checkout (an unpacked sdist): nothing to compare
        return
    stray = members - set(tracked.stdout.splitlines()) - {"PKG-INFO"}
    assert not stray, (f"the sdist packs files git does not track: {sorted(stray)[:10]} "
                       "(remove them or name them in .gitignore)")


def _readme_example() -> str:
    """The Python block of the README's "Documentation and the Python API" section."""
    text = (ROOT / "README.md").read_text("utf-8")
    section = text.split("## Documentation and the Python API", 1)[1]
    return section.split("```python\n", 1)[1].split("```", 1)[0]


def _check_readme_example(py: Path, work: Path) -> None:
    """The README's API example, as written, on a simulated ``x_axis.csv``: its report and its
    Siemens table are written; ``to_dict()`` gives E."""
    _run([py.parent / "axiscal", "simulate",
          Path(_run([py, "-c", "import axiscal; print(axiscal.__path__[0])"], cwd=work,
                    env=_clean_env()).stdout.strip()) / "data" / "demo_linear.toml",
          "--data", "x_axis.csv"], cwd=work, env=_clean_env())
    code = _readme_example() + "\nprint(ev.to_dict()['E'])\n"
    assert "axiscal.read(\"x_axis.csv\")" in code
    r = _run([py, "-c", code], cwd=work, env={**_clean_env(), "MPLBACKEND": "Agg"})
    assert float(r.stdout.split()[-1]) > 0
    assert (work / "x_axis.html").stat().st_size > 0 and (work / "x.ini").stat().st_size > 0


def _check_serve_without_web(env: Path, work: Path) -> None:
    """``axiscal serve`` without the web extra: one line naming it, exit 2, no traceback."""
    r = subprocess.run([env / "bin" / "axiscal", "serve"], cwd=work, env=_clean_env(),
                       capture_output=True, text=True, timeout=120)
    assert r.returncode == 2, r.stderr
    assert r.stderr == ("axiscal: error: axiscal serve needs the web extra: pip install "
                        "'axiscal[web]' (fastapi is not installed)\n")


def _check_package_data(wheel: Path) -> None:
    names = set(zipfile.ZipFile(wheel).namelist())
    data = {f"axiscal/{p.relative_to(PACKAGE).as_posix()}" for p in PACKAGE.rglob("*")
            if p.is_file() and p.suffix not in (".py", ".pyc") and "__pycache__" not in p.parts}
    assert data, "no package data found"
    assert data <= names, f"missing from the wheel: {sorted(data - names)}"
    for must in ("axiscal/py.typed", "axiscal/web/static/htmx.min.js",
                 "axiscal/report/templates/base.html", "axiscal/data/demo_linear.toml",
                 "axiscal/store/migrations/env.py"):
        assert must in names


def _check_requirements(wheel: Path) -> None:
    with zipfile.ZipFile(wheel) as z:
        meta = z.read(next(n for n in z.namelist() if n.endswith("METADATA"))).decode()
    required = [line.split(":", 1)[1].strip() for line in meta.splitlines()
                if line.startswith("Requires-Dist:") and "extra ==" not in line]
    names = {re.split(r"[\s;\[<>=!~]", r, maxsplit=1)[0].lower() for r in required}
    assert "numpy" in names and "matplotlib" in names
    assert not names & DEV_ONLY, f"runtime requirements include {names & DEV_ONLY}"


def _check_installed(py: Path, env: Path, work: Path) -> None:
    work.mkdir()
    code = ("import json, axiscal; sim = axiscal.simulate(axiscal.__path__[0] + "
            "'/data/demo_linear.toml'); ev = axiscal.evaluate(sim.dataset); "
            "print(json.dumps({'file': axiscal.__file__, 'E': ev.to_dict()['E'], "
            "'sim_E': sim.to_dict()['E'], 'version': axiscal.__version__}))")
    out = json.loads(_run([py, "-c", code], cwd=work, env=_clean_env()).stdout)
    assert Path(out["file"]).resolve().is_relative_to(env.resolve())
    assert out["E"] == pytest.approx(out["sim_E"], rel=1e-12) and out["E"] > 0
    import axiscal

    assert out["version"] == axiscal.__version__
    _run([env / "bin" / "axiscal", "demo", "--out", "demo"], cwd=work, env=_clean_env())
    assert (work / "demo" / "index.html").is_file()
    assert (work / "demo" / "linear_report.html").is_file()
