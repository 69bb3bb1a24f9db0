"""Every ``--json`` output is strict JSON whose keys the command module's docstring documents.

CONVENTIONS habit 10: "``--json`` output is stable and documented". The check found keys the
docstrings left out (``scale gantry``: ``counts_per_period``, ``count_size_nm``; the members of
``plan``'s ``steps``; the table itself in ``compensate``) and a docstring that promised keys the
output did not have (``compensate --read`` "the table keys" without ``controller``;
``--squareness`` without ``extra_files``/``notes``).
"""

import importlib
import json
import os
import re
from pathlib import Path

import pytest
from typer.testing import CliRunner

from axiscal.cli import COMMANDS, app

runner = CliRunner()
ROOT = Path(__file__).resolve().parents[2]
EX = ROOT / "examples"
DATA = ROOT / "src/axiscal/data"

CASES = {
    "iso230-2": ["iso230-2", "lin.csv", "--json", "--tolerance", "A=100"],
    "plan": ["plan", "linear", "--length", "800", "--json"],
    "plan circular": ["plan", "circular", "--radius", "150", "--json"],
    "plan squareness": ["plan", "squareness", "--length", "400", "--json"],
    "plan straightness": ["plan", "straightness", "--length", "400", "--at", "Y=5", "--json"],
    "simulate": ["simulate", DATA / "demo_linear.toml", "--json"],
    "rotary-simulate": ["rotary", "simulate", EX / "rotary_trunnion.toml", "--json"],
    "rotary-budget": ["rotary", "budget", "--alpha", "1", "--beta", "1", "--accuracy", "2", "--json"],
    "straightness": ["straightness", EX / "squareness_L180_x.csv", "--json"],
    "biaxial": ["squareness", "biaxial", EX / "squareness_L180_x.csv", EX / "squareness_L180_y.csv", "--json"],
    "diagonal": ["squareness", "diagonal", "--file", EX / "squareness_diagonal_600x800.csv", "--json"],
    "circular": ["squareness", "circular", EX / "squareness_ballbar_150mm.csv", "--json"],
    "squareness-simulate": ["squareness", "simulate", "--json"],
    "motion-simulate": ["motion", "simulate", EX / "motion_indexing_table.toml", "--json"],
    "motion-stability": ["motion", "stability", "--json", "--duration-min", "5"],
    "motion-repeatability": ["motion", "repeatability", EX / "motion_indexing_table.toml", "--json"],
    "motion-analyze": ["motion", "analyze", "m.csv", "--json"],
    "air": ["air", "--json"],
    "scale-home": ["scale", "home", EX / "scale_single.toml", "--json"],
    "scale-gantry": ["scale", "gantry", EX / "scale_gantry.toml", "--json"],
    "scale-compensate": ["scale", "compensate", "--json"],
    "compensate-table": ["compensate", "lin.csv", "--json"],
    "compensate-verify": ["compensate", "--verify", EX / "compensation_linear.toml", "--json"],
    "compensate-squareness": ["compensate", "--squareness", "40", "--axes", "XZ", "--aligned", "Z",
                              "--start", "-200", "--end", "200", "--spacing", "100", "-c",
                              "heidenhain", "--json"],
    "compensate-read": ["compensate", "--read", "x.comp", "-c", "linuxcnc", "lin.csv", "--json"],
}


@pytest.fixture(scope="module")
def work(tmp_path_factory):
    d = tmp_path_factory.mktemp("json")
    old = os.getcwd()
    os.chdir(d)
    for args in (["simulate", DATA / "demo_linear.toml", "--data", "lin.csv"],
                 ["compensate", "lin.csv", "-c", "linuxcnc", "--spacing", "20", "--out", "x.comp"],
                 ["motion", "simulate", EX / "motion_indexing_table.toml", "--csv", "m.csv"]):
        assert runner.invoke(app, [str(a) for a in args]).exit_code == 0
    yield d
    os.chdir(old)


def _strict(text):
    def refuse(name):
        raise ValueError(f"{name} is not JSON")
    return json.loads(text, parse_constant=refuse)


def _keys(obj, depth=0):
    """Keys of ``obj`` and of the objects one level down (inside lists too)."""
    if isinstance(obj, list):
        return set().union(*(_keys(v, depth) for v in obj[:1])) if obj else set()
    if not isinstance(obj, dict):
        return set()
    out = set(obj)
    if depth < 1:
        for v in obj.values():
            out |= _keys(v, depth + 1)
    return out


@pytest.mark.parametrize("name", sorted(CASES))
def test_json_is_strict_and_documented(work, name):
    args = [str(a) for a in CASES[name]]
    r = runner.invoke(app, args)
    assert r.exit_code == 0, r.output
    d = _strict(r.stdout)
    doc = importlib.import_module(COMMANDS[args[0]]).__doc__
    if ":mod:`axiscal.cli.iso230_2`" in doc:   # simulate's object is iso230-2's plus the truth
        doc += importlib.import_module("axiscal.cli.iso230_2").__doc__
    doc += importlib.import_module("axiscal.standards.quantities").__doc__   # schema 1's block
    documented = set(re.findall(r"``([A-Za-z_][A-Za-z0-9_]*)``", doc))
    # per-channel objects are keyed by channel name (ez_arcsec ...), listed once in the docstring
    missing = sorted(k for k in _keys(d) if k not in documented and not re.fullmatch(r"[A-Z]\d?", k))
    assert not missing, f"{name}: keys not in the {COMMANDS[args[0]]} docstring: {missing}"
