"""``axiscal thermal plan | simulate | evaluate | model | compensate``: thin over the library,
one record on every path, bad input one line with exit 2 and nothing written."""

import json

import numpy as np
import pytest
from typer.testing import CliRunner

import axiscal
from axiscal.cli import app
from axiscal.io.drift import read_drift_check

runner = CliRunner()


def _ok(*args):
    r = runner.invoke(app, [str(a) for a in args])
    assert r.exit_code == 0, r.output
    return r


def _json(*args):
    return json.loads(_ok(*args, "--json").stdout)


def test_plan_json_holds_the_defaults():
    d = _json("thermal", "plan", "--test", "spindle")
    assert d["run_h"] == 4 and d["stop_h"] == 1 and d["speed_fraction"] == 0.5
    assert d["samples"] == 301


@pytest.fixture(scope="module")
def linear_logs(tmp_path_factory):
    folder = tmp_path_factory.mktemp("thermal")
    logs = []
    for seed, duty, start in ((1, 0.8, 8), (2, 0.5, 13), (3, 1.0, 2)):
        p = folder / f"x{seed}.csv"
        d = _json("thermal", "simulate", "--test", "linear", "--duty", duty, "--start-h", start,
                  "--seed", seed, "--out", p)
        logs.append((p, d))
    return logs


def test_simulate_writes_the_log_evaluate_reads_the_same_figures(linear_logs):
    path, sim = linear_logs[0]
    ev = _json("thermal", "evaluate", path)
    assert ev == axiscal.evaluate_thermal(path).to_dict()     # one evaluation, every path
    # the simulation's own figures come back from its log (rounded to 0.1 nm); against the
    # truth: tests/standards/test_iso230_3_coverage.py
    by_name = {f["name"]: f for f in sim["evaluation"]["figures"]}
    for f in ev["figures"]:
        assert f["value"] == pytest.approx(by_name[f["name"]]["value"], abs=2e-3), f["name"]
        assert f["U"] == pytest.approx(by_name[f["name"]]["U"], rel=0.05, abs=2e-3), f["name"]
    assert set(sim["truth"]) == {f["name"] for f in ev["figures"]} - {"duration"}
    assert ev["clause"] == "ISO 230-3:2020 Clause 7"


def test_model_and_sinumerik_compensation(linear_logs):
    (a, _), (b, _), (c, _) = linear_logs
    both = _json("thermal", "compensate", a, "--validate", b, "--test", c, "--verify", "--seed",
                 7, "--start-h", 18, "--duty", 0.9)
    test = [s for s in both["model"]["scores"] if s["role"] == "test"][0]
    assert test["source"] == str(c) and test["max_error_share_of_range"]["P2"] <= 0.2
    comp = both["sinumerik"]
    # applied on the twin to a run it was not fitted on (same thermal history without it):
    # the drift at both targets falls by at least 80 %
    assert min(both["verify"]["reduction"].values()) >= 0.8, both["verify"]
    assert comp["MD32750 $MA_TEMP_COMP_TYPE"] == 3
    assert comp["SD43920 $SA_TEMP_COMP_REF_POSITION"]["value"] == pytest.approx(40.0)
    text = _ok("thermal", "model", a, "--validate", b, "--channels", "P2").stdout
    assert text.startswith("thermal model of the linear test") and "validation run" in text


def test_controller_files_from_the_model(linear_logs, tmp_path):
    """--sinumerik-out: K3's data (MD32750 = 3, SD43920 = P0 = 40 mm) with K0(T) and tanβ(T)
    for the PLC as comments, the JSON's coefficients; --linuxcnc-out: the component, its HAL
    file and thermcomp.json with the same coefficients in mm/K. --on-controller alone (without
    --verify) is refused in one line."""
    (a, _), (b, _), _ = linear_logs
    sd, lc = tmp_path / "x_temp.txt", tmp_path / "lcnc"
    d = _json("thermal", "compensate", a, "--validate", b, "--sinumerik-out", sd,
              "--linuxcnc-out", lc)
    text = sd.read_text()
    assert "$MA_TEMP_COMP_TYPE[AX1]=3" in text
    assert "$SA_TEMP_COMP_REF_POSITION[AX1]=40.000000" in text
    k0 = d["sinumerik"]["SD43900 $SA_TEMP_COMP_ABS_VALUE"]["k0_mm_per_K"]
    tc = json.loads((lc / "thermcomp.json").read_text())
    assert tc["sensors"] == d["sinumerik"]["sensors"] and len(k0) == len(tc["sensors"])
    assert tc["k0_mm_per_K"] == pytest.approx(k0, abs=1e-12)
    assert tc["p0_mm"] == pytest.approx(40.0)
    assert (lc / "axiscal_thermcomp.py").exists() and (lc / "axiscal_thermcomp.hal").exists()
    assert sorted(d["files"]) == sorted([str(sd)] + [str(lc / n) for n in (
        "thermcomp.json", "axiscal_thermcomp.py", "axiscal_thermcomp.hal")])
    r = runner.invoke(app, ["thermal", "compensate", str(a), "--validate", str(b),
                            "--on-controller"])
    assert r.exit_code == 2 and "give --verify too" in r.output
    assert len(r.output.strip().splitlines()) == 1


JOB = """
[company]
name = "Precision Metrology GmbH"
address = ["Messweg 12", "Stuttgart"]
code = "PM"
[operator]
name = "J. Keller"
[customer]
name = "Example Machining AG"
address = ["Industriestr. 4", "Esslingen"]
[machine]
maker = "Example"
model = "VMC-800"
serial = "VMC8-0042"
location = "Hall 2"
[conditions]
date = "2026-11-20"
air_temperature = 20.4
material_temperature = 20.6
measuring_line = "100 mm above the table centre"
feed = "2000 mm/min"
dwell = "4 s"
[[instrument]]
name = "Laser interferometer"
serial = "L-1"
certificate = "C-77"
due = "2027-04-30"
[certificate]
signatory = "Dr. M. Braun"
signatory_role = "Head of laboratory"
specification = "Contract 4711"
"""


def test_drift_check_gives_iso230_2_a_measured_e_ve(tmp_path, monkeypatch):
    """The simulated drift check (ISO 230-2:2014 Annex A.5) is read by the existing
    ``iso230-2 --drift-check`` path: its E_VE is the range of the readings, named measured; with
    a complete job (no E_VE declared in it) the certificate is issued, not a draft, and names
    the drift check."""
    monkeypatch.setenv("AXISCAL_CONFIG", str(tmp_path / "none.toml"))
    dc = tmp_path / "dc.csv"
    d = _json("thermal", "simulate", "--test", "drift-check", "--duration-h", 1, "--out", dc,
              "--seed", 4)
    readings = read_drift_check(dc)
    assert d["e_ve_um"] == pytest.approx(np.ptp(readings), abs=1e-6)
    pos = tmp_path / "p.csv"
    _ok("simulate", "src/axiscal/data/demo_linear.toml", "--data", pos)
    budget = _json("iso230-2", pos, "--drift-check", dc)["uncertainty_budget"]
    eve = [c for c in budget["contributors"] if c["name"] == "u_EVE"][0]
    assert "drift check" in eve["basis"] and f"{np.ptp(readings):.4f}" in eve["basis"]
    job, cert = tmp_path / "job.toml", tmp_path / "c.html"
    job.write_text(JOB)
    _ok("iso230-2", pos, "--job", job, "--drift-check", dc, "--tolerance", "E=25", "--report",
        cert, "--db", f"sqlite:///{tmp_path / 'h.sqlite'}")
    html = cert.read_text("utf-8")
    assert "DRAFT" not in html and "PM-2026-00001" in html
    assert f" = {np.ptp(readings):.4f} µm (drift check)" in html


@pytest.mark.parametrize("args, words", [
    (["plan", "--test", "oven"], "thermal test 'oven'"),
    (["plan", "--test", "linear", "--p1-mm", "5000", "--p2-mm", "10"], "outside the travel"),
    (["plan", "--test", "spindle", "--interval-s", "900"], "at most 300 s"),
    (["simulate", "--test", "spindle", "--run-h", "1"], "needs at least 4 h"),
    (["plan", "--test", "spindle", "--speed-programme", "0.5;30"], "FRACTION:MINUTES"),
])
def test_bad_input_is_one_line_exit_2(tmp_path, args, words):
    out = tmp_path / "never.csv"
    extra = ["--out", str(out)] if args[0] == "simulate" else []
    r = runner.invoke(app, ["thermal", *args, *extra])
    assert r.exit_code == 2, r.output
    assert words in r.output and "Traceback" not in r.output
    assert len(r.output.strip().splitlines()) == 1
    assert not out.exists()


def test_a_bad_log_is_refused_and_nothing_written(tmp_path, linear_logs):
    path, _ = linear_logs[0]
    lines = path.read_text().splitlines()
    head = next(i for i, l in enumerate(lines) if l.startswith("time_s"))
    del lines[head + 40: head + 50]                           # a 10-minute hole
    bad = tmp_path / "bad.csv"
    bad.write_text("\n".join(lines) + "\n")
    plot = tmp_path / "bad.png"
    r = runner.invoke(app, ["thermal", "evaluate", str(bad), "--plot", str(plot)])
    assert r.exit_code == 2 and "a gap of" in r.output and not plot.exists()


def test_reports_keep_the_truth_to_simulations(tmp_path, linear_logs):
    """``evaluate --report``: the figures and the plot, no truth; ``simulate --report``: the
    truth under the simulation banner."""
    path, _ = linear_logs[0]
    r1, r2 = tmp_path / "e.html", tmp_path / "s.html"
    _ok("thermal", "evaluate", path, "--report", r1)
    _ok("thermal", "simulate", "--test", "spindle", "--report", r2)
    e, s = r1.read_text("utf-8"), r2.read_text("utf-8")
    assert "ISO 230-3:2020 Clause 7" in e and "<svg" in e and "Simulation truth" not in e
    assert "Simulation truth" in s and "simulation-banner" in s and "ISO 230-3:2020 Clause 6" in s


def test_e_ve_from_an_etve_record_is_said_to_be_declared(tmp_path):
    """ISO 230-2 Annex A.5's E_VE from an ETVE record: the range of one direction over the
    window, said to be the machine's response to the room only, to be declared."""
    log = tmp_path / "etve.csv"
    _ok("thermal", "simulate", "--test", "etve", "--out", log)
    d = _json("thermal", "evaluate", log, "--e-ve", "X,1,2")["e_ve"]
    data = axiscal.read_thermal(log)
    m = (data.time >= 3600) & (data.time <= 3 * 3600)
    assert d["value_um"] == pytest.approx(np.ptp(data.displacements["X"][m]) * 1e6, abs=1e-6)
    assert d["source"] == "declared" and "without" in d["what"]
    r = runner.invoke(app, ["thermal", "evaluate", str(log), "--e-ve", "X,23,5"])
    assert r.exit_code == 2 and "outside the log" in r.output


def test_rotary_table_test_round_trips_through_its_log(tmp_path):
    """ISO 230-3:2020 Clause 8: ``simulate --test rotary`` on the rotary-table twin writes the
    log, ``evaluate`` reads it and gives the simulation's figures (one evaluation, every path);
    the shipped VMC twin has no rotary table and is refused in one line."""
    log = tmp_path / "rot.csv"
    sim = _json("thermal", "simulate", "--test", "rotary", "--config",
                "src/axiscal/data/thermal_rotary_table.toml", "--out", log, "--seed", 2)
    ev = _json("thermal", "evaluate", log)
    assert ev["clause"] == "ISO 230-3:2020 Clause 8" and ev["test"] == "rotary"
    assert ev == axiscal.evaluate_thermal(log).to_dict()
    by_name = {f["name"]: f for f in sim["evaluation"]["figures"]}
    for f in ev["figures"]:
        assert f["value"] == pytest.approx(by_name[f["name"]]["value"], abs=2e-3)
    r = runner.invoke(app, ["thermal", "plan", "--test", "rotary"])
    assert r.exit_code == 2 and "rotary table" in r.output
