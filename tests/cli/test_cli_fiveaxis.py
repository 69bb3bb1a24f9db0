"""``axiscal fiveaxis plan | simulate | identify`` (issue 43): one library call each, the same
numbers on every path, and bad input as one line with exit code 2 and nothing written."""

from __future__ import annotations

import json
import re
from importlib import resources

import pytest
from typer.testing import CliRunner

import axiscal
from axiscal.cli import app

runner = CliRunner()
AC = resources.files("axiscal.data").joinpath("fiveaxis_ac.toml")


def _json(*args):
    r = runner.invoke(app, [str(a) for a in args] + ["--json"])
    assert r.exit_code == 0, r.output
    return json.loads(r.stdout)


@pytest.fixture(scope="module")
def run(tmp_path_factory):
    out = tmp_path_factory.mktemp("fx") / "run"
    return out, _json("fiveaxis", "simulate", "--out", out, "--seed", 4)


def test_plan_says_rank_condition_and_the_unseen_before_measuring():
    d = _json("fiveaxis", "plan", "--machine", "bc")
    assert d["tilt_axis"] == "B" and d["rank"] == d["columns"] == 8 + 3 * 3
    assert d["identifiable"][4] == "E_B0B+E_B0C" and d["unidentified"][0]["name"] == "E_C0C"
    assert 1 < d["condition"] < 100 and [s["poses"] for s in d["setups"]] == [60, 60, 18]
    assert "E_B0C := 0" in d["convention"] and "LinuxCNC" in d["convention"]


def test_identify_from_the_written_files_equals_the_simulation(run):
    out, sim = run
    files = sorted(out.glob("*.csv"))
    assert [f.name for f in files] == ["1_probing.csv", "2_probing.csv", "3_r-test.csv"]
    got = _json("fiveaxis", "identify", *files)
    for a, b in zip(sim["errors"], got["errors"]):
        assert a["name"] == b["name"] and a["value"] == pytest.approx(b["value"], abs=2e-3)
        assert abs(a["deviation"]) <= (2.0 if a["unit"] == "µrad" else 1.0)
    assert sim["truth"]["E_C0C"] == 50.0 and "truth" not in got
    api = axiscal.fiveaxis.identify(AC, files).to_dict()
    assert api["errors"] == got["errors"]
    # every key of the JSON objects is documented in the command module
    doc = __import__("axiscal.cli.fiveaxis", fromlist=["x"]).__doc__
    documented = set(re.findall(r"``([A-Za-z_][A-Za-z0-9_]*)``", doc))
    keys = set(sim) | set(sim["errors"][0]) | set(sim["plan"]) | set(_json("fiveaxis", "plan"))
    assert keys <= documented, keys - documented


def test_identify_prints_iso_names_and_units(run):
    out, _ = run
    r = runner.invoke(app, ["fiveaxis", "identify", str(out / "1_probing.csv")])
    assert r.exit_code == 0, r.output
    assert re.search(r"E_X0C = [+-]\d+\.\d\d µm, U = \d\.\d\d µm \(k = 2\)", r.stdout)
    assert "E_A0A+E_A0C = " in r.stdout and "µrad" in r.stdout
    assert "E_C0C: not identified" in r.stdout and "E_C0C =" not in r.stdout


@pytest.mark.parametrize("edit, message", [
    (lambda t: re.sub(r"(?m)^3,.*\n", "", t), r"pose 3 is missing"),
    (lambda t: t.replace("\n2,0.000000,30.000000,", "\n2,0.000000,nan,", 1), r"C_deg = nan"),
    (lambda t: t.replace("sphere_radius_mm = 12.500000", "sphere_radius_mm = 12.4"),
     r"fitted radius 14\.\d+ mm differs .* by \+0\.1\d+ mm, beyond the tolerance 0\.02 mm"),
    (lambda t: t.replace("pose,A_deg,C_deg", "pose,C_deg,C_deg"), r"rotary axis C named twice"),
    (lambda t: re.sub(r"(?m)^(1,)0\.000000,", r"\g<1>-120,", t),
     r"axis A: angle -120 deg is outside the travel -110 to 30 deg"),
])
def test_bad_files_give_one_line_and_exit_2(run, tmp_path, edit, message):
    out, _ = run
    bad = tmp_path / "bad.csv"
    bad.write_text(edit((out / "1_probing.csv").read_text("utf-8")), "utf-8")
    r = runner.invoke(app, ["fiveaxis", "identify", str(bad), "--json"])
    assert r.exit_code == 2 and r.stdout == ""
    assert re.search(message, r.stderr), r.stderr
    assert r.stderr.startswith("axiscal: error: ") and r.stderr.count("\n") == 1


def test_a_simulation_refused_writes_nothing(tmp_path):
    cfg = tmp_path / "m.toml"
    cfg.write_text(AC.read_text("utf-8").replace("A_deg = [0, -45, -90]", "A_deg = [0, -45, -130]"),
                   "utf-8")
    r = runner.invoke(app, ["fiveaxis", "simulate", str(cfg), "--out", str(tmp_path / "o")])
    assert r.exit_code == 2 and "axis A: angle -130 deg is outside the travel" in r.stderr
    assert not (tmp_path / "o").exists()
    cfg.write_text(AC.read_text("utf-8").replace('rotary = ["A", "C"]', 'rotary = ["A", "A"]'),
                   "utf-8")
    r = runner.invoke(app, ["fiveaxis", "plan", str(cfg)])
    assert r.exit_code == 2 and "rotary axis A named twice" in r.stderr


def test_compensate_writes_the_pins_and_the_neutral_table(run, tmp_path):
    out, _ = run
    files = [str(f) for f in sorted(out.glob("*.csv"))]
    d = _json("fiveaxis", "compensate", *files, "--out", tmp_path / "trt.hal", "--table",
              tmp_path / "trt.csv", "--offsets", tmp_path / "trtcomp.json", "--sinumerik",
              tmp_path / "carr.spf", "--verify")
    assert d["component"] == "xyzac-trt-kins"
    assert d["pins_mm"]["x-rot-point"]["after"] == pytest.approx(0.020, abs=0.001)
    assert set(d["not_held_urad"]) == {"E_B0A", "E_C0A", "E_B0C"}
    assert [s["label"] for s in d["verify"]["setups"]][0] == "sphere 1"
    hal = (tmp_path / "trt.hal").read_text("ascii")
    assert "setp xyzac-trt-kins.z-offset -60.01" in hal and "HOME_OFFSET += +0.003" in hal
    table = (tmp_path / "trt.csv").read_text("utf-8").splitlines()
    assert table[0] == "parameter,before,after,unit,takes" and len(table) == 9
    eo = json.loads((tmp_path / "trtcomp.json").read_text("utf-8"))
    assert eo == d["external_offsets"] and eo["tilt"] == "A"
    assert eo["nominal"]["c"][1] == [0.0, 0.0, 1.0] and eo["actual"]["c"][1][0] != 0.0
    spf = (tmp_path / "carr.spf").read_text("utf-8")
    assert '$TC_CARR23[1]="P"' in spf and d["sinumerik"]["values"]["$TC_CARR21"] == "A"
    doc = __import__("axiscal.cli.fiveaxis", fromlist=["x"]).__doc__
    documented = set(re.findall(r"``([A-Za-z_][A-Za-z0-9_-]*)``", doc))
    e = d["verify"]["setups"][0]["explained"]
    assert e["expected_um"] == pytest.approx(e["unmodelled_um"] + e["noise_um"])
    assert e["unmodelled_um"] == d["verify"]["setups"][0]["after_unmodelled_um"]
    keys = set(d) | set(d["verify"]) | set(d["verify"]["setups"][0]) | set(e)
    assert keys <= documented, keys - documented


def test_identify_plot_draws_the_lines_and_the_values(run, tmp_path):
    out, _ = run
    png = tmp_path / "lines.png"
    r = runner.invoke(app, ["fiveaxis", "identify", str(out / "1_probing.csv"), "--plot",
                            str(png)])
    assert r.exit_code == 0, r.output
    assert png.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n" and png.stat().st_size > 20_000
    bad = runner.invoke(app, ["fiveaxis", "identify", str(out / "1_probing.csv"), "--plot",
                              str(tmp_path / "x.txt")])
    assert bad.exit_code == 2 and not (tmp_path / "x.txt").exists()


def test_a_spindle_head_states_its_convention_and_gets_no_trt_pins(tmp_path):
    d = _json("fiveaxis", "plan", "--machine", "head")
    assert d["kind"] == "head-table" and [u["name"] for u in d["unidentified"]] == [
        "E_B0B", "E_C0C"]
    assert "E_X0C and E_X0B are taken relative to the tool tip at B = 0" in d["convention"]
    sim = _json("fiveaxis", "simulate", "--machine", "head", "--out", tmp_path)
    assert all(abs(e["deviation"]) < (2.0 if e["unit"] == "µrad" else 1.0) for e in sim["errors"])
    r = runner.invoke(app, ["fiveaxis", "compensate", *sim["files"], "--machine", "head"])
    assert r.exit_code == 2 and "spindle head" in r.stderr and "5axiskins" in r.stderr


def test_reports_show_the_values_and_the_truth_only_for_a_simulation(run, tmp_path):
    out, _ = run
    real = tmp_path / "identify.html"
    r = runner.invoke(app, ["fiveaxis", "identify", str(out / "1_probing.csv"), "--report",
                            str(real)])
    assert r.exit_code == 0, r.output
    page = real.read_text("utf-8")
    # ISO 230 symbols with their subscripts, as every report writes them
    assert "E<sub>A0A</sub>+E<sub>A0C</sub>" in page and "U (k = 2)" in page and "<svg" in page
    assert "E<sub>C0C</sub>: not identified" in page and "Simulation report" not in page
    sim = tmp_path / "simulate.html"
    r = runner.invoke(app, ["fiveaxis", "simulate", "--report", str(sim)])
    assert r.exit_code == 0, r.output
    assert "Simulation report" in sim.read_text("utf-8") and "identified − true" in \
        sim.read_text("utf-8")
