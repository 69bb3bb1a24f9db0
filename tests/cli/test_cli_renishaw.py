"""Renishaw .rtl/.rta/.ren through the commands: evaluate, history add, compensate, formats."""

import json
import sys
from pathlib import Path

import pytest
from typer.testing import CliRunner

from axiscal.cli import app

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "io"))
from test_renishaw import (R1_DN, R1_UP, R2_DN, R2_UP, REAL_ENVIRONMENT, T7,  # noqa: E402
                           renishaw_text, tidy_csv)

from _assertions import one_error_line  # noqa: E402

runner = CliRunner()


@pytest.fixture
def files(tmp_path):
    rtl = tmp_path / "x.rtl"
    rtl.write_bytes(renishaw_text("rtl", T7, [R1_UP, R1_DN, R2_UP, R2_DN],
                                  environment=REAL_ENVIRONMENT).encode())
    csv = tmp_path / "x.csv"
    csv.write_text(tidy_csv(T7, [R1_UP, R2_UP], [R1_DN, R2_DN], "mm", "um"))
    return rtl, csv


def _json(args):
    r = runner.invoke(app, args)
    assert r.exit_code == 0, r.output
    return json.loads(r.stdout)


def test_evaluate_gives_the_same_numbers_as_the_tidy_csv(files):
    rtl, csv = files
    a = _json(["evaluate", str(rtl), "-s", "iso230-2:2014", "--json"])
    b = _json(["evaluate", str(csv), "-s", "iso230-2:2014", "--json"])
    na, nb = _numbers(a), _numbers(b)
    # E = max x̄ − min x̄ = x̄↓(200 mm) − x̄↑(500 mm)
    #   = (3.1 + 3.4)/2 − (−1.5 − 1.2)/2 = 4.6 µm
    assert a["standards"][0]["parameters"]["E"]["value"] == pytest.approx(4.6, abs=1e-12)
    assert len(na) > 10 and na == nb


def _numbers(d):
    """Every number of a JSON result except the conditions (the CSV has none) and the
    quantities' block, whose U rests on those conditions (its values are the parameters')."""
    out = []

    def walk(x, key=""):
        if isinstance(x, dict):
            for k in sorted(x):
                if k not in ("environment", "metadata", "source", "file", "conditions",
                             "quantities", "uncertainty_inputs"):
                    walk(x[k], k)
        elif isinstance(x, list):
            for v in x:
                walk(v, key)
        elif isinstance(x, (int, float)) and not isinstance(x, bool):
            out.append((key, x))
    walk(d)
    return out


def test_history_add_keeps_the_files_conditions_and_a_damaged_file_leaves_nothing(files, tmp_path):
    rtl, _ = files
    db = f"sqlite:///{tmp_path / 'h.db'}"
    bad = tmp_path / "bad.rtl"
    bad.write_bytes(rtl.read_bytes()[: len(rtl.read_bytes()) // 2])
    one_error_line(runner.invoke(app, ["history", "add", str(bad), "--machine", "M", "--db", db]),
                   "truncated")
    r = runner.invoke(app, ["history", "add", str(rtl), "--machine", "M", "--db", db, "--json"])
    assert r.exit_code == 0, r.output
    listed = _json(["history", "list", "--db", db, "--json"])
    text = json.dumps(listed)
    assert text.count('"iso230-2"') >= 1 and "bad.rtl" not in text and "2019-05-12" in text


def test_compensate_writes_a_ren_reads_it_back_and_converts_it(files, tmp_path):
    rtl, _ = files
    ren = tmp_path / "X.REN"
    r = runner.invoke(app, ["compensate", str(rtl), "--controller", "renishaw-ren",
                            "--spacing", "100", "--out", str(ren)])
    assert r.exit_code == 0, r.output
    assert ren.read_bytes().count(b"\r\n") > 10
    d = _json(["compensate", "--read", str(ren), str(rtl), "--json"])
    assert d["controller"] == "renishaw-ren" and d["largest_residual"] <= 0.05 + 1e-9
    ini = tmp_path / "X.INI"
    r = runner.invoke(app, ["compensate", "--read", str(ren), "--to", "siemens-840d",
                            "--out", str(ini)])
    assert r.exit_code == 0, r.output
    assert ini.read_text().startswith("%_N_AX_EEC_INI")
    one_error_line(runner.invoke(app, ["compensate", "--read", str(ren), "--out",
                                       str(tmp_path / "y.ini")]), "--to")
    assert not (tmp_path / "y.ini").exists()


def test_a_rotary_simulation_is_refused_as_rtl_and_nothing_is_written(tmp_path):
    out = tmp_path / "r.rtl"
    cfg = Path(__file__).resolve().parents[2] / "src" / "axiscal" / "data" / "demo_rotary.toml"
    one_error_line(runner.invoke(app, ["simulate", str(cfg), "--data", str(out)]), ".rta")
    assert not out.exists()


def test_formats_lists_the_renishaw_exports():
    r = runner.invoke(app, ["formats"])
    assert r.exit_code == 0
    for ext in (".rtl", ".rta", ".ren"):
        assert ext in r.stdout
