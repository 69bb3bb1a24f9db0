"""``axiscal compensate-environment``, ``capture`` and ``formats`` (issue 12)."""

from __future__ import annotations

import json

import numpy as np
import pytest
from typer.testing import CliRunner

from axiscal.cli import app
from axiscal.io.rtx import format_rtx
from axiscal.machines.config import axis_from_config
from axiscal.procedures.environment import simulate_raw_test
from axiscal.procedures.positioning import plan_linear
from axiscal.procedures.record_simulation import RecordSettings, simulate_record
from axiscal.io.measured import format_environment_log, format_raw_readings, parse_plan_csv
from axiscal.standards.iso230_2 import evaluate

runner = CliRunner()
AXIS = {"name": "X", "kind": "linear", "travel_mm": [-10, 810], "scale_error_ppm": 5.0,
        "backlash_um": 2.0, "repeatability_um": 0.2}


def _write_raw(tmp_path):
    plan = plan_linear(800, runs=3, dwell=2.0)
    raw, log, truth = simulate_raw_test(
        plan, axis_from_config(AXIS), np.random.default_rng(5),
        lambda t: (20.0 + t / 300, 101325.0, 45.0, 20.3 + t / 600), dead_path=0.15)
    (tmp_path / "raw.csv").write_text(format_raw_readings(raw, "machine=VMC-800 axis=X"))
    (tmp_path / "env.csv").write_text(format_environment_log(log))
    return truth


def test_compensate_environment_from_files(tmp_path):
    truth = _write_raw(tmp_path)
    r = runner.invoke(app, ["compensate-environment", str(tmp_path / "raw.csv"), "--environment",
                            str(tmp_path / "env.csv"), "--out", str(tmp_path / "d.csv"),
                            "--json"])
    assert r.exit_code == 0, r.output
    d = json.loads(r.stdout)
    assert "Ciddor (1996)" in d["applied"] and d["readings"] == 30
    r = runner.invoke(app, ["iso230-2", str(tmp_path / "d.csv"), "--json"])
    got = json.loads(r.stdout)
    assert got["E"] == pytest.approx(evaluate(truth).E, abs=0.05)    # 4-decimal log, 1e-9 mm


@pytest.mark.parametrize("mutate, words", [
    (lambda env: env.replace("time_s,air", "time,air"), "lacks time_s"),
    (lambda env: "\n".join(env.splitlines()[:4]) + "\n", "outside the environment log"),
    (lambda env: env.replace(",20.0000,", ",200.0000,", 1), "validity"),
])
def test_bad_environment_logs_are_one_line_and_write_nothing(tmp_path, mutate, words):
    _write_raw(tmp_path)
    env = tmp_path / "env.csv"
    env.write_text(mutate(env.read_text()))
    r = runner.invoke(app, ["compensate-environment", str(tmp_path / "raw.csv"),
                            "--environment", str(env), "--out", str(tmp_path / "d.csv")])
    assert r.exit_code == 2 and words in r.stderr, r.stderr
    assert len(r.stderr.strip().splitlines()) == 1
    assert not (tmp_path / "d.csv").exists()


def test_capture_an_rtx_record(tmp_path):
    r = runner.invoke(app, ["plan", "linear", "--length", "800", "--runs", "2", "--dwell", "2",
                            "--csv", str(tmp_path / "plan.csv")])
    assert r.exit_code == 0, r.output
    plan = parse_plan_csv((tmp_path / "plan.csv").read_text())
    t, x, truth = simulate_record(plan, axis_from_config(AXIS), np.random.default_rng(6),
                                  RecordSettings(sample_rate=1000.0))
    (tmp_path / "run.rtx").write_bytes(format_rtx(x * 1e6, 1000.0, Axis="X"))
    r = runner.invoke(app, ["capture", str(tmp_path / "run.rtx"), "--plan",
                            str(tmp_path / "plan.csv"), "--out", str(tmp_path / "d.csv"),
                            "--window", "0.5", "--plot", str(tmp_path / "dyn.png"), "--json"])
    assert r.exit_code == 0, r.output
    d = json.loads(r.stdout)
    assert d["measurements"] == plan.targets.size * 4
    e = json.loads(runner.invoke(app, ["iso230-2", str(tmp_path / "d.csv"), "--json"]).stdout)
    assert e["E"] == pytest.approx(evaluate(truth).E, abs=0.05)
    assert (tmp_path / "dyn.png").stat().st_size > 20_000
    short = tmp_path / "short.rtx"
    short.write_bytes((tmp_path / "run.rtx").read_bytes()[:-100])
    r = runner.invoke(app, ["capture", str(short), "--plan", str(tmp_path / "plan.csv"),
                            "--out", str(tmp_path / "e.csv")])
    assert r.exit_code == 2 and "truncated" in r.stderr and not (tmp_path / "e.csv").exists()


def test_formats_lists_every_format():
    r = runner.invoke(app, ["formats", "--json"])
    assert r.exit_code == 0
    names = [f["name"] for f in json.loads(r.stdout)]
    assert any("dynamic capture" in n for n in names) and any("Environment log" in n
                                                             for n in names)
    assert len(names) >= 20


def test_compensate_environment_plots_and_reports_what_it_did(tmp_path):
    """The correction at each reading (compensated − raw) is, at the far end of an 800 mm axis
    read with the vacuum wavelength, about −(n − 1)·800 mm ≈ −217 µm (n − 1 ≈ 271 ppm for 20 °C,
    101325 Pa, Ciddor 1996) less the material's expansion, and it is drawn and reported."""
    _write_raw(tmp_path)
    r = runner.invoke(app, ["compensate-environment", str(tmp_path / "raw.csv"), "--environment",
                            str(tmp_path / "env.csv"), "--out", str(tmp_path / "d.csv"),
                            "--plot", str(tmp_path / "e.png"), "--report", str(tmp_path / "e.html")])
    assert r.exit_code == 0, r.output
    assert (tmp_path / "e.png").read_bytes()[:4] == b"\x89PNG"
    page = (tmp_path / "e.html").read_text()
    assert "Environmental compensation of raw.csv" in page and "Ciddor (1996)" in page
    assert "<svg" in page and "ISO 1" in page


def test_reading_corrections_are_the_air_and_the_material(tmp_path):
    from axiscal.io.measured import read_environment_log, read_raw_readings
    from axiscal.procedures.environment import compensate_raw_readings

    _write_raw(tmp_path)
    raw = read_raw_readings(tmp_path / "raw.csv")
    ds, detail = compensate_raw_readings(raw, read_environment_log(tmp_path / "env.csv"),
                                         detail=True)
    far = np.argmax(raw.targets)
    change = detail.deviation_um[far] - detail.raw_deviation_um[far]
    # 0.8 m read with the vacuum wavelength: the air at 20-21 °C shortens it by n - 1, between
    # 270 and 272 ppm; the material at 20.3-20.8 °C (11.5 ppm/K) by up to 9.2 ppm more (µm = m·ppm)
    assert -0.8 * (272 + 11.5 * 0.8) < change < -0.8 * (270 + 11.5 * 0.3)
    assert detail.times.shape == detail.deviation_um.shape == raw.readings.shape


@pytest.mark.parametrize("bad, words", [
    ("12.0,0,+,1,abc", "raw.csv:3: reading 'abc' is not a number"),
    ("12.0,0,sideways,1,0.1", "raw.csv:3: direction 'sideways': use + or -"),
    ("12.0,0,+,1,nan", "raw.csv:3: reading 'nan' is not a finite number"),
    ("12.0,0,+,1", "raw.csv:3: 4 cells where the header has 5"),
    ("12.0,0,+,1,1e308", "raw.csv:3: reading 1e308 is out of range"),
])
def test_raw_readings_read_directly_or_checked_give_the_same_errors(tmp_path, bad, words):
    """The raw-readings reader converts plain lines directly and the rest through the checked
    cells: a bad cell still names its column and line (streamed from a file, or from text)."""
    from axiscal.errors import DataFormatError
    from axiscal.io.measured import parse_raw_readings, read_raw_readings

    text = f"# reading_unit=mm\ntime_s,target,direction,run,reading\n{bad}\n13.0,0,+,2,0.1\n"
    f = tmp_path / "raw.csv"
    f.write_text(text)
    for read in (lambda: read_raw_readings(f), lambda: parse_raw_readings(text, str(f))):
        with pytest.raises(DataFormatError) as exc:
            read()
        assert words in str(exc.value), str(exc.value)


def test_raw_readings_streamed_equal_the_text_and_the_written_file(tmp_path):
    from axiscal.io.measured import parse_raw_readings, read_raw_readings

    _write_raw(tmp_path)
    a = read_raw_readings(tmp_path / "raw.csv")
    b = parse_raw_readings((tmp_path / "raw.csv").read_text(), str(tmp_path / "raw.csv"))
    for name in ("times", "targets", "directions", "runs", "readings"):
        np.testing.assert_array_equal(getattr(a, name), getattr(b, name))
    assert a.dead_path == pytest.approx(0.15) and a.meta["machine"] == "VMC-800"
    assert set(a.directions) == {"+", "-"} and a.runs.dtype.kind == "i"
