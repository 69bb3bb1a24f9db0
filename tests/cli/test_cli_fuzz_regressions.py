"""Every fault of issue 30 (part A) and of the interface-derived fuzz harness, as a regression test.

Each is refused in ONE line on stderr with exit 2, nothing written, the inputs byte-identical
(:func:`_assertions.one_error_line`); the figures quoted are those of the issue.
"""

from __future__ import annotations

import datetime as dt
import hashlib
import os
import re
from pathlib import Path

import numpy as np
import pytest
from typer.testing import CliRunner

from axiscal.cli import app
from axiscal.errors import MAX_MESSAGE
from axiscal.io.measured import format_environment_log, format_raw_readings
from axiscal.io.rtx import format_rtx
from axiscal.machines.config import axis_from_config
from axiscal.procedures.environment import simulate_raw_test
from axiscal.procedures.positioning import plan_linear

from _assertions import one_error_line

runner = CliRunner()
EXAMPLES = Path(__file__).resolve().parents[2] / "examples"
POS = ("# machine=VMC-800 axis=X target_unit=mm deviation_unit=um\n"
       "target,direction,run,deviation\n"
       + "".join(f"{t},{d},{r},{0.001 * t + 0.5 * r + (d == '-'):.3f}\n"
                 for r in (1, 2) for t in (0, 100, 200, 300) for d in "+-"))


def _sha(p: Path) -> str:
    return hashlib.sha256(p.read_bytes()).hexdigest()


def _run(*args):
    return runner.invoke(app, [str(a) for a in args])


@pytest.fixture
def db(tmp_path):
    """A history with three tests of VMC-800 X a year apart (enough for a trend)."""
    from axiscal.store import open_store

    url = f"sqlite:///{tmp_path / 'h.sqlite'}"
    store = open_store(url)
    for k in range(3):
        store.add(POS.replace(",0.5", f",{0.5 + k}").encode(), f"x{k}.csv",
                  date=dt.date(2020 + k, 1, 1).isoformat())
    return url


# -- ids and database URLs ------------------------------------------------------------------
@pytest.mark.parametrize("args", [
    ["history", "show", "99999999999999999999"],
    ["history", "show", "9223372036854775808"],      # 2**63: OverflowError in SQLite before
    ["history", "show", "0"],
    ["history", "show", "--", "-1"],
    ["history", "compare", "1", "99999999999999999999"],
])
def test_test_ids_beyond_64_bits_are_not_found(args, db):
    one_error_line(_run(*args[:2], "--db", db, *args[2:]), "no test")


@pytest.mark.parametrize("url, driver", [
    ("mysql://u@127.0.0.1:1/x", "MySQLdb"),               # ModuleNotFoundError before
    ("oracle://u@127.0.0.1:1/x", "oracledb"),
    ("mssql://u@127.0.0.1:1/x", "pyodbc"),
    ("sqlite+pysqlcipher:///x.db", "pysqlcipher"),       # and no x.db created
])
def test_a_database_scheme_without_its_driver_is_one_line(url, driver, tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    one_error_line(_run("history", "list", "--db", url), driver, "not installed")
    assert list(tmp_path.iterdir()) == []


def test_a_server_that_does_not_answer_is_one_line():
    one_error_line(_run("history", "list", "--db", "postgresql://127.0.0.1:1/x"),
                   "connection")


@pytest.mark.parametrize("tolerance", ["1e308", "-5", "0"])
def test_trend_tolerance_must_be_positive_and_computable(tolerance, db):
    one_error_line(_run("history", "trend", "--machine", "VMC-800", "--axis", "X",
                        "--tolerance", tolerance, "--db", db), "tolerance", "positive")
    r = _run("history", "trend", "--machine", "VMC-800", "--axis", "X", "--tolerance", "1e99",
             "--db", db, "--json")
    assert r.exit_code == 0, r.output   # large but computable: the line never reaches it


# -- command-line values ----------------------------------------------------------------------
def test_ballbar_seed_must_not_be_negative(tmp_path):
    r = _run("ballbar", "simulate", EXAMPLES / "ballbar_sim.toml", "--out", tmp_path / "t.csv",
             "--seed", "-1")
    one_error_line(r, "--seed")
    assert not (tmp_path / "t.csv").exists()


def test_serve_refuses_an_unknown_role_in_one_line(tmp_path):
    r = _run("serve", "--add-user", "bob", "--role", "god", "--users", tmp_path / "u.toml")
    one_error_line(r, "--role", "viewer or engineer")
    assert not (tmp_path / "u.toml").exists()


@pytest.mark.parametrize("arg, words", [
    ("\udcff", "not UTF-8"), ("VMC\x00800", "NUL")])
def test_an_argument_that_is_not_text_is_one_line(arg, words, tmp_path):
    one_error_line(_run("history", "list", "--machine", arg, "--db",
                        f"sqlite:///{tmp_path / 'h.sqlite'}"), words)
    one_error_line(_run("certificate", "show", arg, "--db", f"sqlite:///{tmp_path / 'h.sqlite'}"),
                   words)


# -- readers: .rtx headers, environment logs -------------------------------------------------
@pytest.fixture
def capture_files(tmp_path):
    r = _run("plan", "linear", "--length", "100", "--csv", tmp_path / "plan.csv")
    assert r.exit_code == 0, r.output
    return tmp_path


@pytest.mark.parametrize("fields, words", [
    ({"Sample_rate": "1e308", "Actual_sample_rate": ""}, "Sample rate"),
    ({"Sample_rate": "nan", "Actual_sample_rate": ""}, "Sample rate"),
    ({"Sample_no": "nan"}, "Sample no"),
])
def test_capture_refuses_absurd_rtx_headers(fields, words, capture_files):
    rtx = capture_files / "run.rtx"
    rtx.write_bytes(format_rtx(np.sin(np.arange(2000) / 100.0), 1000.0, **fields))
    r = _run("capture", rtx, "--plan", capture_files / "plan.csv", "--out",
             capture_files / "d.csv")
    one_error_line(r, words)
    assert not (capture_files / "d.csv").exists()


def _raw_and_env(tmp_path, air=lambda t: 20.0 + t / 300, pressure=101325.0):
    plan = plan_linear(200, runs=2, dwell=2.0)
    axis = axis_from_config({"name": "X", "kind": "linear", "travel_mm": [-10, 210],
                             "scale_error_ppm": 5.0, "backlash_um": 2.0,
                             "repeatability_um": 0.2})
    raw, log, _ = simulate_raw_test(plan, axis, np.random.default_rng(5),
                                    lambda t: (air(t), pressure, 45.0, 20.3), dead_path=0.15)
    (tmp_path / "raw.csv").write_text(format_raw_readings(raw, "machine=M axis=X"))
    (tmp_path / "env.csv").write_text(format_environment_log(log))
    return tmp_path / "raw.csv", tmp_path / "env.csv"


def test_air_in_fahrenheit_under_the_celsius_column_is_named(tmp_path):
    # 68-70 "°C" is 20-21.1 °C read as °F (ISO 1: 20 °C; the air equations are tested to 40 °C)
    raw, env = _raw_and_env(tmp_path, air=lambda t: 68.0 + t / 1000)
    line = one_error_line(_run("compensate-environment", raw, "--environment", env, "--out",
                               tmp_path / "d.csv", "--air-only"), "°F", "20.0")
    assert "air_temperature_c" in line
    assert not (tmp_path / "d.csv").exists()


@pytest.mark.parametrize("pressure, unit", [(101.325, "kPa"), (1013.25, "hPa")])
def test_pressure_in_kpa_or_hpa_under_the_pascal_column_is_named(pressure, unit, tmp_path):
    raw, env = _raw_and_env(tmp_path)
    env.write_text(re.sub(r",101325\.0*,", f",{pressure},", env.read_text()))
    assert f",{pressure}," in env.read_text()
    one_error_line(_run("compensate-environment", raw, "--environment", env, "--out",
                        tmp_path / "d.csv", "--air-only"), unit, "101325")


# -- an inch read as a millimetre (datasets.inch_signature: 25.4 mm exactly) ----------------
def _cells(path: Path, column: int, scale: float, digits: int = 9) -> None:
    """Scale one column of a raw readings CSV (its data lines) in place."""
    lines = path.read_text().splitlines()
    out = []
    for ln in lines:
        cells = ln.split(",")
        if ln.startswith("#") or not cells[0][:1].isdigit():
            out.append(ln)
            continue
        cells[column] = f"{float(cells[column]) * scale:.{digits}f}"
        out.append(",".join(cells))
    path.write_text("\n".join(out) + "\n")


@pytest.mark.parametrize("column, words", [
    (1, ("laser readings are 25.4 × the targets", "targets look like inches read as mm",
         "give target_unit=in")),
    (4, ("laser readings are 1/25.4 of the targets", "laser readings look like inches read as mm",
         "give reading_unit=in")),
])
def test_raw_readings_with_inches_under_a_mm_declaration_are_named(column, words, tmp_path):
    # the example's targets (column 1) or readings (column 4) written in inches, declared mm
    raw = tmp_path / "raw.csv"
    raw.write_text((EXAMPLES / "raw_readings_vmc800_x.csv").read_text())
    _cells(raw, column, 1 / 25.4)
    one_error_line(_run("compensate-environment", raw, "--environment",
                        EXAMPLES / "environment_log_vmc800_x.csv", "--out", tmp_path / "d.csv"),
                   "inch", *words)
    assert not (tmp_path / "d.csv").exists()


def test_the_named_reading_reads_the_file_right(tmp_path):
    """Declaring target_unit=in, as the message says, gives the example's own deviations back
    (the targets in inches to 1e-9 in: 2.5e-5 µm)."""
    raw, env = tmp_path / "raw.csv", EXAMPLES / "environment_log_vmc800_x.csv"
    raw.write_text((EXAMPLES / "raw_readings_vmc800_x.csv").read_text())
    assert _run("compensate-environment", raw, "--environment", env, "--out",
                tmp_path / "mm.csv").exit_code == 0
    _cells(raw, 1, 1 / 25.4)
    raw.write_text(raw.read_text().replace("target_unit=mm", "target_unit=in", 1))
    r = _run("compensate-environment", raw, "--environment", env, "--out", tmp_path / "in.csv")
    assert r.exit_code == 0, r.output

    def deviations(p):
        return np.array([float(ln.split(",")[3]) for ln in p.read_text().splitlines()
                         if ln[:1].isdigit()])

    assert deviations(tmp_path / "in.csv") == pytest.approx(deviations(tmp_path / "mm.csv"),
                                                             abs=1e-3)


def _inch_positioning_files(tmp_path) -> dict:
    """A tidy CSV (actual column), an ecmc file (PSI's real one) and a Renishaw .rtl, each with
    its targets written in inches and its measured positions in mm."""
    import re

    from axiscal.io import parse_positioning
    from axiscal.io.renishaw import format_rtl

    rows = [ln.split(",") for ln in POS.splitlines()[2:]]
    (tmp_path / "a.csv").write_text(
        "# target_unit=mm axis=X\ntarget,direction,run,actual\n" + "".join(
            f"{float(t) / 25.4:.9f},{d},{r},{float(t) + float(x) / 1e3:.6f}\n"
            for t, d, r, x in rows))
    ecmc = (Path(__file__).resolve().parents[1] / "data" / "ecmc" / "sls_fat_sat_ISO230.dat")
    (tmp_path / "e.dat").write_text(re.sub(
        r"(?m)^(TGT_DATA\[\d+\])=(\S+)", lambda m: f"{m[1]}={float(m[2]) / 25.4:.9f}",
        ecmc.read_text()))
    rtl = format_rtl(parse_positioning(POS))
    head, tail = rtl.split("Targets :\r\n", 1)
    targets, rest = tail.split("\r\n", 1)
    t = [float(v) for v in targets.split()]
    dev = re.sub(r"(?m)^(\d+)(\s+)(\d+)(\s+)(\S+)\r$", lambda m: (
        f"{m[1]}{m[2]}{m[3]}{m[4]}"
        f"{float(m[5]) + (t[int(m[3]) - 1] * (1 - 1 / 25.4)) * 1e3:.4f}\r"), rest)
    (tmp_path / "r.rtl").write_text(head + "Targets :\r\n"
                                    + " ".join(f"{v / 25.4:.9f}" for v in t) + "\r\n" + dev,
                                    newline="")
    return {k: tmp_path / k for k in ("a.csv", "e.dat", "r.rtl")}


@pytest.mark.parametrize("name", ["a.csv", "e.dat", "r.rtl"])
def test_positioning_files_with_inch_targets_are_named(name, tmp_path):
    f = _inch_positioning_files(tmp_path)[name]
    one_error_line(_run("iso230-2", f), "inch", "measured positions are 25.4 × the targets",
                   "the targets look like inches read as mm", "+24.4 mm per mm")
    one_error_line(_run("history", "add", f, "--db", f"sqlite:///{tmp_path / 'h.sqlite'}"),
                   "inches read as mm")


# -- no command writes over one of its inputs -----------------------------------------------
def _overwrite_cases(tmp_path):
    (tmp_path / "x.csv").write_text(POS)
    raw, env = _raw_and_env(tmp_path)
    r = _run("plan", "linear", "--length", "100", "--csv", tmp_path / "plan.csv")
    assert r.exit_code == 0
    (tmp_path / "run.rtx").write_bytes(format_rtx(np.zeros(100), 1000.0))
    return [(["compensate", tmp_path / "x.csv", "--out"], tmp_path / "x.csv"),
            (["compensate-environment", raw, "--environment", env, "--out"], raw),
            (["compensate-environment", raw, "--environment", env, "--out"], env),
            (["capture", tmp_path / "run.rtx", "--plan", tmp_path / "plan.csv", "--out"],
             tmp_path / "plan.csv")]


@pytest.mark.parametrize("how", ["same name", "another spelling", "hard link", "symbolic link"])
def test_no_command_writes_over_one_of_its_inputs(how, tmp_path):
    for args, victim in _overwrite_cases(tmp_path):
        before = _sha(victim)
        out = {"same name": victim,
               "another spelling": victim.parent / ".." / victim.parent.name / victim.name,
               "hard link": tmp_path / f"hard{victim.suffix}",
               "symbolic link": tmp_path / f"soft{victim.suffix}"}[how]
        if how == "hard link":
            out.unlink(missing_ok=True)
            os.link(victim, out)
        elif how == "symbolic link":
            out.unlink(missing_ok=True)
            out.symlink_to(victim)
        line = one_error_line(_run(*args, out), "is the input", "destroy")
        assert victim.name in line
        assert _sha(victim) == before, (args, how)


@pytest.mark.parametrize("kind", ["fifo", "loop"])
def test_an_output_that_is_a_fifo_or_a_loop_of_links_is_refused(kind, tmp_path):
    p = tmp_path / "p.png"
    os.mkfifo(p) if kind == "fifo" else os.symlink(p.name, p)
    (tmp_path / "x.csv").write_text(POS)
    one_error_line(_run("iso230-2", tmp_path / "x.csv", "--plot", p), "p.png")


# -- inputs bounded before they are parsed ----------------------------------------------------
BOMB = '{"format": "axiscal.positioning/1", "up": ' + "[" * 100_000 + "]" * 100_000 + "}"


@pytest.mark.parametrize("make_args", [
    lambda t: ["iso230-2", t / "bomb.json"],
    lambda t: ["evaluate", t / "bomb.json", "--standard", "iso230-2:2014"],
    lambda t: ["compensate", t / "bomb.json", "--out", t / "o.csv"],
    lambda t: ["history", "add", t / "bomb.json", "--db", f"sqlite:///{t / 'h.sqlite'}"],
])
def test_json_nested_100000_deep_is_one_line_not_a_recursion_error(make_args, tmp_path):
    (tmp_path / "bomb.json").write_text(BOMB)
    one_error_line(_run(*make_args(tmp_path)), "nest")
    assert not (tmp_path / "o.csv").exists()


def test_an_environment_log_nested_100000_deep_is_one_line(tmp_path):
    raw, _ = _raw_and_env(tmp_path)
    (tmp_path / "bomb.json").write_text('{"samples": ' + BOMB + "}")
    one_error_line(_run("compensate-environment", raw, "--environment", tmp_path / "bomb.json",
                        "--out", tmp_path / "d.csv"), "nest")


@pytest.mark.parametrize("text, words", [
    ("x = " + "[" * 3000 + "]" * 3000 + "\n", "nest more than 64"),
    ("a" + ".a" * 200_000 + " = 1\n", "dotted key"),            # 400 KB: 73-100 s in tomllib
    ('[meta]\nmachine = "' + "x" * 2_000_000 + '"\n', "too large"),   # the 200 MB string's kin
])
@pytest.mark.parametrize("command", [["simulate"], ["ballbar", "simulate"],
                                     ["rotary", "simulate"]])
def test_toml_bombs_are_refused_before_tomllib(text, words, command, tmp_path):
    (tmp_path / "c.toml").write_text(text)
    one_error_line(_run(*command, tmp_path / "c.toml"), "c.toml", words)


def test_an_error_quotes_only_an_excerpt_of_the_input(tmp_path):
    (tmp_path / "x.csv").write_text("# axis=" + "X" * 2**20 + "\n" + POS.split("\n", 1)[1])
    line = one_error_line(_run("iso230-2", tmp_path / "x.csv"))
    assert len(line) <= MAX_MESSAGE + len("axiscal: error: ")


def test_a_one_megabyte_comment_line_is_read_in_linear_time(capture_files):
    plan = capture_files / "plan.csv"
    plan.write_text("# " + "x" * 2**20 + "\n" + plan.read_text())
    rtx = capture_files / "run.rtx"
    rtx.write_bytes(format_rtx(np.zeros(100), 1000.0))
    r = _run("capture", rtx, "--plan", plan, "--out", capture_files / "d.csv")
    one_error_line(r)     # the record does not fit the plan; the 1 MB comment is skipped
    plan.write_text("# axis=" + "x" * 2**20 + "\n" + plan.read_text())
    one_error_line(_run("capture", rtx, "--plan", plan, "--out", capture_files / "d.csv"),
                   "comment line", "key=value")


# -- found by the interface-derived harness ---------------------------------------------------
def test_an_irregularity_of_minus_zero_is_zero():
    r = _run("plan", "linear", "--length", "100", "--irregularity", "-0", "--json")
    assert r.exit_code == 0, r.output     # numpy's ValueError (high - low < 0) before


def test_a_users_file_that_is_a_loop_of_links_is_refused(tmp_path, monkeypatch):
    monkeypatch.setenv("AXISCAL_PASSWORD", "correct horse battery")
    loop = tmp_path / "users.toml"
    loop.symlink_to(loop.name)
    one_error_line(_run("serve", "--add-user", "bob", "--users", loop), "loop of links")
    assert loop.is_symlink()


def test_demo_checks_its_database_before_writing_anything(tmp_path):
    one_error_line(_run("demo", "--out", tmp_path / "demo", "--db", "mysql://u@127.0.0.1:1/x"),
                   "MySQLdb")
    assert list(tmp_path.iterdir()) == []


def test_a_rotary_configuration_value_of_1e308_is_refused_not_overflowed(tmp_path):
    text = (EXAMPLES / "rotary_turntable.toml").read_text()
    assert re.search(r"(?m)^resolution_arcsec\s*=", text)
    (tmp_path / "r.toml").write_text(re.sub(r"(?m)^(resolution_arcsec\s*=).*$", r"\1 1e308",
                                            text))
    one_error_line(_run("rotary", "simulate", tmp_path / "r.toml"), "resolution_arcsec",
                   "out of range")
