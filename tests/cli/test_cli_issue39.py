"""Issue 39, as a hostile user found it: every case of the issue as a regression test.

Outputs that would destroy an input or the history, text injected into controller files, numbers
that are not numbers, archives that jam the register, streams and environments, half-done work.
A refusal is ONE line ``axiscal: error: ...`` with exit 2, nothing written, every input
byte-identical (:func:`_assertions.one_error_line`).
"""

from __future__ import annotations

import hashlib
import json
from pathlib import Path

import pytest
from typer.testing import CliRunner

from axiscal.cli import app

from _assertions import one_error_line

runner = CliRunner()
ROOT = Path(__file__).resolve().parents[2]
POS = ("# machine=VMC-800 axis=X target_unit=mm deviation_unit=um\n"
       "target,direction,run,deviation\n"
       + "".join(f"{t},{d},{r},{0.001 * t + 0.5 * r + (d == '-'):.3f}\n"
                 for r in (1, 2) for t in (0, 100, 200, 300) for d in "+-"))


def _run(*args, **kw):
    return runner.invoke(app, [str(a) for a in args], **kw)


def _sha(p: Path) -> str:
    return hashlib.sha256(p.read_bytes()).hexdigest()


@pytest.fixture(scope="module")
def lin(tmp_path_factory) -> Path:
    """A simulated positioning test of the demo's linear axis (21 targets over 800 mm)."""
    d = tmp_path_factory.mktemp("lin")
    r = _run("simulate", ROOT / "src/axiscal/data/demo_linear.toml", "--data", d / "lin.csv")
    assert r.exit_code == 0, r.output
    return d / "lin.csv"


# -- 2. text injected into controller files -------------------------------------------------
def test_a_ren_axis_with_a_line_break_adds_no_line(lin, tmp_path):
    """Issue 39: ``--axis $'X\\nCompensation spacing : 1 mm'`` added a line to a ``.ren``."""
    out = tmp_path / "t.ren"
    r = _run("compensate", lin, "--spacing", 40, "-c", "renishaw-ren", "--axis",
             "X\nCompensation spacing : 1 mm", "--out", out)
    assert r.exit_code == 0, r.output
    lines = out.read_text().splitlines()
    assert lines[1] == "Axis : X_Compensation_spacing_1_mm"
    assert sum(ln.startswith("Compensation spacing") for ln in lines) == 1
    assert "axis name in the source data" in r.output   # cleaned, and said


def test_a_json_metadata_axis_with_a_line_break_adds_no_line(lin, tmp_path):
    """Issue 39: the same through ``metadata.axis`` of a JSON data file."""
    from axiscal.io import parse_positioning
    from axiscal.io.json import format_positioning_json

    d = json.loads(format_positioning_json(parse_positioning(lin.read_text())))
    d["metadata"]["axis"] = "X\nCompensation spacing : 1 mm"
    src = tmp_path / "lin.json"
    src.write_text(json.dumps(d))
    out = tmp_path / "t.ren"
    assert _run("compensate", src, "--spacing", 40, "-c", "renishaw-ren", "--out",
                out).exit_code == 0
    assert sum(ln.startswith("Compensation spacing") for ln in out.read_text().splitlines()) == 1


@pytest.mark.parametrize("controller, option, words", [
    ("siemens-840d", "machine_axis=X1]=0\nM30\n;[", ["machine_axis", "machine axis name"]),
    ("fanuc", "axis_number=99999999999999999999", ["axis_number", "1 … 32"]),
    ("fanuc", "axis_number=-3", ["axis_number"]),
    ("fanuc", "reference_number=-5", ["reference_number"]),
    ("linuxcnc", "joint=99", ["joint", "0 … 15"]),
    ("heidenhain", "driving_axis=X\nBEGIN", ["driving_axis", "axis letter"]),
])
def test_a_writer_option_outside_its_grammar_is_refused(lin, tmp_path, controller, option,
                                                        words):
    """Issue 39: ``-o machine_axis=$'X1]=0\\nM30\\n;['`` wrote ``M30`` into an 840D table;
    ``-o axis_number=99999999999999999999`` wrote ``N3620A99999999999999999999P0``."""
    out = tmp_path / "t.txt"
    one_error_line(_run("compensate", lin, "--spacing", 40, "-c", controller, "-o", option,
                        "--out", out), *words)
    assert not out.exists()
