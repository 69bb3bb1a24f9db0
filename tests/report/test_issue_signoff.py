"""report.issue.sign_off: the verdict the workbench shows is the command line's (issue 31)."""

from __future__ import annotations

import json

import pytest
from typer.testing import CliRunner

from axiscal.cli import app
from axiscal.io import parse_positioning
from axiscal.report.issue import sign_off
from axiscal.standards.iso230_2 import evaluate
from axiscal.standards.iso14253_1 import Outcome
from tests.web.test_signoff import LAB, data_file


@pytest.fixture
def lab(tmp_path, monkeypatch):
    cfg = tmp_path / "config.toml"
    cfg.write_text(LAB, encoding="utf-8")
    monkeypatch.setenv("AXISCAL_CONFIG", str(cfg))
    f = tmp_path / "x.csv"
    f.write_bytes(data_file())
    return f


def test_sign_off_equals_iso230_2_tolerance_json(lab):
    """Outcome, U and the unprovable warning per parameter as `axiscal iso230-2 --tolerance
    --json` prints them (one evaluation, one decision rule: ISO 14253-1:2017 §5.2-5.4)."""
    from axiscal.io.user_config import load_user_config

    out = CliRunner().invoke(app, ["iso230-2", str(lab), "--tolerance", "A=2", "--tolerance",
                                   "E=15", "--tolerance", "R=5.5", "--json"])
    assert out.exit_code == 1                      # a tolerance not proven met
    cli = json.loads(out.stdout)
    ds = parse_positioning(data_file().decode(), "x.csv")
    so = sign_off(ds, evaluate(ds), load_user_config(), {"A": 2.0, "E": 15.0, "R": 5.5})
    got = {d.parameter: (d.outcome.value, d.U) for d in so.decisions}
    want = {a["parameter"]: (a["outcome"], a["U"]) for a in cli["acceptance"]}
    assert got.keys() == want.keys() == {"A", "E", "R"}
    for k in got:
        assert got[k][0] == want[k][0] and got[k][1] == pytest.approx(want[k][1], rel=1e-12)
    assert so.overall is Outcome.NONCONFORMS
    assert list(so.warnings) == cli["warnings"]
    assert "overall: non-conformance proven" in str(so)


def test_sign_off_refuses_an_unknown_parameter(lab):
    from axiscal.errors import InputError

    ds = parse_positioning(data_file().decode(), "x.csv")
    with pytest.raises(InputError, match="not an ISO 230-2 parameter"):
        sign_off(ds, evaluate(ds), {}, {"Q": 1.0})
    assert sign_off(ds, evaluate(ds), {}, {}).overall is None
