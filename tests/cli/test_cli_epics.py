"""EPICS camonitor logs on the command line (issue 29): iso230-2, evaluate and capture read a log
by content, print what they found and assumed, and refuse a misfit in one line."""

from __future__ import annotations

import json
import sys
from pathlib import Path

import pytest
from typer.testing import CliRunner

from axiscal.cli import app
from axiscal.io.ecmc import read_ecmc
from axiscal.standards.iso230_2 import evaluate

sys.path.insert(0, str(Path(__file__).parents[1] / "io"))
from test_epics import DATA, REF, SP, _ecmc_log, _plan_csv  # noqa: E402

runner = CliRunner()
ECMC = DATA / "mcu1025_fat_sat_ISO230.dat"


@pytest.fixture()
def log(tmp_path):
    ref_ds, text = _ecmc_log(ECMC)
    p = tmp_path / "axis1.log"
    p.write_text(text)
    plan = tmp_path / "plan.csv"
    plan.write_text(_plan_csv(ref_ds.targets, ref_ds.n_runs))
    return p, plan


def test_iso230_2_of_a_log_gives_the_ecmc_files_numbers(log):
    """tests/data/ecmc/mcu1025_fat_sat_ISO230.dat (ecmccfg, GPL-3.0) read directly and as the
    log of its steps: the same A, E, M, R, B (µm); the notes say what was assumed."""
    p, _ = log
    r = runner.invoke(app, ["iso230-2", str(p), "--setpoint-pv", SP, "--reference-pv", REF,
                            "--json"])
    assert r.exit_code == 0, r.output
    d = json.loads(r.stdout)
    expected = evaluate(read_ecmc(ECMC))
    for k in ("A", "E", "M", "R", "B"):
        assert d[k] == pytest.approx(getattr(expected, k), abs=1e-6)
    assert d["notes"].startswith("EPICS camonitor log: setpoint " + SP)
    assert "unit mm (assumed: the log carries none)" in d["notes"]
    assert "unit mm (assumed" in r.stderr          # also shown beside the terminal result


def test_evaluate_reads_a_log_too(log):
    p, _ = log
    r = runner.invoke(app, ["evaluate", str(p), "-s", "iso230-2:2014", "--setpoint-pv", SP,
                            "--reference-pv", REF, "--targets", "15,25.2,35.4,45.6,55.8",
                            "--json"])
    assert r.exit_code == 0, r.output
    params = json.loads(r.stdout)["standards"][0]["parameters"]
    assert params["A"]["value"] == pytest.approx(evaluate(read_ecmc(ECMC)).A, abs=1e-6)


def test_capture_of_a_log_with_the_plan(log, tmp_path):
    p, plan = log
    out = tmp_path / "data.csv"
    r = runner.invoke(app, ["capture", str(p), "--plan", str(plan), "--out", str(out),
                            "--setpoint-pv", SP, "--reference-pv", REF, "--json"])
    assert r.exit_code == 0, r.output
    d = json.loads(r.stdout)
    assert d["measurements"] == 50 and d["overruns"] == 10 and d["stops"] == 61
    assert d["sample_rate_hz"] is None and "matched to the plan" in d["notes"]
    r = runner.invoke(app, ["iso230-2", str(out), "--json"])
    assert json.loads(r.stdout)["A"] == pytest.approx(evaluate(read_ecmc(ECMC)).A, abs=1e-6)


@pytest.mark.parametrize("args, words", [
    ([], "holds 4 PVs"),
    (["--setpoint-pv", "IOC:none", "--reference-pv", REF], "PV 'IOC:none' is not in the log"),
    (["--setpoint-pv", SP, "--reference-pv", REF, "--targets", "15,x"], "--targets '15,x'"),
    (["--setpoint-pv", SP, "--reference-pv", REF, "--targets", "15,20"],
     "target 20 mm is never reached"),
])
def test_refusals_are_one_line(log, args, words):
    p, _ = log
    r = runner.invoke(app, ["iso230-2", str(p), *args])
    assert r.exit_code == 2 and words in r.output and "Traceback" not in r.output
    assert len(r.output.strip().splitlines()) == 1


def test_log_options_on_another_file_and_laser_options_on_a_log(log, tmp_path):
    p, plan = log
    csv = tmp_path / "x.csv"
    csv.write_text("# target_unit=mm deviation_unit=um\ntarget,direction,run,deviation\n"
                   "0,+,1,0\n0,+,2,1\n10,+,1,0\n10,+,2,1\n")
    r = runner.invoke(app, ["iso230-2", str(csv), "--setpoint-pv", SP])
    assert r.exit_code == 2 and "applies to an EPICS camonitor log" in r.output
    out = tmp_path / "o.csv"
    r = runner.invoke(app, ["capture", str(p), "--plan", str(plan), "--out", str(out),
                            "--setpoint-pv", SP, "--reference-pv", REF, "--unit", "mm"])
    assert r.exit_code == 2 and "--unit applies to a laser record" in r.output
    assert not out.exists()


def test_formats_lists_the_camonitor_log_with_its_source():
    r = runner.invoke(app, ["formats", "--json"])
    entry = next(f for f in json.loads(r.stdout) if f["name"].startswith("EPICS camonitor"))
    assert entry["read"] and not entry["write"] and "tool_lib.c" in entry["described_in"]


def test_history_of_a_log_read_with_options_is_refused_before_anything_is_stored(log, tmp_path):
    """The history keeps the file as it came and re-reads it without options."""
    p, _ = log
    db = f"sqlite:///{tmp_path / 'h.sqlite'}"
    r = runner.invoke(app, ["iso230-2", str(p), "--setpoint-pv", SP, "--reference-pv", REF,
                            "--history", "--machine", "M", "--db", db])
    assert r.exit_code == 2 and "--history keeps the file as it came" in r.output
    assert not (tmp_path / "h.sqlite").exists()


def test_the_certificate_states_what_the_log_reader_assumed(log, tmp_path):
    p, _ = log
    html = tmp_path / "c.html"
    r = runner.invoke(app, ["iso230-2", str(p), "--setpoint-pv", SP, "--reference-pv", REF,
                            "--report", str(html), "--draft"])
    assert html.exists(), r.output
    text = html.read_text()
    assert "Assumptions and deviations" in text and "EPICS camonitor log: setpoint" in text
    assert "unit mm (assumed: the log carries none)" in text


def test_history_add_keeps_a_log_of_two_pvs(tmp_path):
    """A log holding only the setpoint and the reference is read alone (the PVs found), so the
    history can keep it as it came and re-read it."""
    ref_ds, text = _ecmc_log(ECMC, extras=False)
    p = tmp_path / "two.log"
    p.write_text(text)
    db = f"sqlite:///{tmp_path / 'h.sqlite'}"
    r = runner.invoke(app, ["history", "add", str(p), "--machine", "MCU1025", "--axis", "X",
                            "--db", db])
    assert r.exit_code == 0 and "iso230-2" in r.output, r.output
    r = runner.invoke(app, ["history", "show", "1", "--db", db, "--json"])
    assert json.loads(r.stdout)["parameters"]["A"]["value"] == pytest.approx(
        evaluate(ref_ds).A, abs=1e-6)


@pytest.mark.parametrize("command", ["iso230-2", "evaluate"])
def test_a_refusal_after_reading_a_log_is_one_line_without_its_notes(log, command):
    """Issue 39: a camonitor refusal came after a notes line (two lines). The notes of what the
    reader assumed are printed once the evaluation has succeeded."""
    p, _ = log
    extra = ["--standard", "iso230-2:2014"] if command == "evaluate" else []
    r = runner.invoke(app, [command, str(p), *extra, "--setpoint-pv", SP, "--reference-pv", REF,
                            "--uncertainty", "e_ve=1e200"])
    assert r.exit_code == 2 and "e_ve" in r.stderr, r.output
    assert len(r.stderr.strip().splitlines()) == 1 and "camonitor" not in r.stderr
