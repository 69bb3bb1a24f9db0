"""The drift check behind E_VE (ISO 230-2:2014 Annex A.5) planned, simulated and kept WITH its
positioning test in the history (issue 44): ``axiscal thermal plan/simulate --test drift-check``
makes it, ``axiscal iso230-2 TEST --drift-check DC --history`` stores the test with it; the
stored record holds the drift check's readings, its E_VE (the range of the readings, measured)
and the budget made with it; the history's evaluation, the command's and the workbench's test
page give the same E_VE."""

import json

import numpy as np
import pytest
from fastapi.testclient import TestClient
from typer.testing import CliRunner

from axiscal import api
from axiscal.cli import app
from axiscal.errors import InputError
from axiscal.io.drift import read_drift_check
from axiscal.store.history import prepare

runner = CliRunner()


def _ok(*args):
    r = runner.invoke(app, [str(a) for a in args])
    assert r.exit_code == 0, r.output
    return r


@pytest.fixture(scope="module")
def files(tmp_path_factory):
    d = tmp_path_factory.mktemp("dc")
    plan = json.loads(_ok("thermal", "plan", "--test", "drift-check", "--duration-h", 1,
                          "--json").stdout)
    assert plan["test"] == "drift-check" and plan["duration_h"] == 1 and plan["samples"] == 61
    dc, pos = d / "dc.csv", d / "p.csv"
    _ok("thermal", "simulate", "--test", "drift-check", "--duration-h", 1, "--out", dc,
        "--seed", 4)
    _ok("simulate", "src/axiscal/data/demo_linear.toml", "--data", pos)
    return d, dc, pos


def _u_eve(budget: dict) -> dict:
    return [c for c in budget["contributors"] if c["name"] == "u_EVE"][0]


def test_drift_check_is_stored_with_its_test_and_shown(files, monkeypatch):
    d, dc, pos = files
    monkeypatch.setenv("AXISCAL_CONFIG", str(d / "none.toml"))
    db = f"sqlite:///{d / 'h.sqlite'}"
    cmd = json.loads(_ok("iso230-2", pos, "--drift-check", dc, "--json").stdout)
    r = _ok("iso230-2", pos, "--drift-check", dc, "--history", "--db", db)
    assert "with its drift check" in r.output
    readings = read_drift_check(dc)
    with api.History(db) as h:
        t = h.tests()[0]
        stored = h.get(t.id)
        kept = stored.result["drift_check"]
        assert kept["readings"] == pytest.approx(readings.tolist(), abs=0)
        assert kept["e_ve"] == pytest.approx(np.ptp(readings), abs=1e-12)
        assert kept["standard"] == "ISO 230-2:2014 Annex A.5" and kept["unit"] == "um"
        assert kept["filename"] == "dc.csv" and kept["samples"] == readings.size
        inputs = stored.result["uncertainty_inputs"]
        assert inputs["e_ve"] == kept["e_ve"] and inputs["e_ve_source"] == "drift check"
        again = h.evaluation(t.id).to_dict()
    # one record, every path: the history's budget names the measured E_VE as the command's
    assert _u_eve(again["uncertainty_budget"]) == _u_eve(cmd["uncertainty_budget"])
    assert "drift check" in _u_eve(cmd["uncertainty_budget"])["basis"]
    from axiscal.web.app import create_app

    c = TestClient(create_app(db), base_url="http://127.0.0.1")
    page = c.get(f"/tests/{t.id}").text
    block = page.split('id="drift-check"')[1].split("</div>")[0]
    assert "ISO 230-2:2014 Annex A.5" in block and f"{np.ptp(readings):.4f} µm" in block
    assert "measured" in block and f"{readings.size} readings" in block


def test_a_drift_check_only_goes_with_a_positioning_test_and_e_ve_once(files, tmp_path):
    """A drift check beside a straightness file, or with E_VE also declared for the test: one
    line, nothing stored (``prepare`` touches no database)."""
    d, dc, pos = files
    raw = pos.read_bytes()
    with pytest.raises(InputError, match="given twice"):
        prepare(raw, "p.csv", uncertainty={"e_ve": 0.3}, drift_check=(dc.read_bytes(), "dc.csv"))
    straight = tmp_path / "s.csv"
    straight.write_text("position,deviation\n0,0\n100,1\n200,0.5\n300,0.2\n")
    with pytest.raises(InputError, match="goes with a positioning test"):
        prepare(straight.read_bytes(), "s.csv", kind="straightness",
                drift_check=(dc.read_bytes(), "dc.csv"))
    bad = tmp_path / "bad.csv"
    bad.write_text("reading\n0.1\n")
    r = runner.invoke(app, ["iso230-2", str(pos), "--drift-check", str(bad), "--history",
                            "--db", f"sqlite:///{tmp_path / 'h.sqlite'}"])
    assert r.exit_code == 2 and "at least 2" in r.output
    assert not (tmp_path / "h.sqlite").exists()


def test_history_add_keeps_the_drift_check_too(files, tmp_path, monkeypatch):
    """``axiscal history add TEST --drift-check DC``: the same record as ``iso230-2 --history``
    (one path into the store, :func:`axiscal.store.kinds.drift_check_record`)."""
    d, dc, pos = files
    monkeypatch.setenv("AXISCAL_CONFIG", str(d / "none.toml"))
    db = f"sqlite:///{tmp_path / 'h.sqlite'}"
    out = json.loads(_ok("history", "add", pos, "--drift-check", dc, "--db", db,
                         "--json").stdout)
    with api.History(db) as h:
        kept = h.get(out["id"]).result["drift_check"]
    assert kept["e_ve"] == pytest.approx(np.ptp(read_drift_check(dc)), abs=1e-12)
    r = _ok("history", "add", pos, "--drift-check", dc, "--db", db)
    assert "already stored" in r.stdout and "not stored: --drift-check" in r.output
