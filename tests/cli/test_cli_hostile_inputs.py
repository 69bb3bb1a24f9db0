"""Regression tests of the hostile inputs of issue 11: each once gave a traceback, a hang, a
numpy warning or a silent absurd result; each must now give exit 2 and one line naming what the
user wrote, in the user's unit (no internal field, no SI value)."""

from __future__ import annotations

import os
from pathlib import Path

import pytest
from typer.testing import CliRunner

from axiscal.cli import app

EXAMPLES = Path(__file__).resolve().parents[2] / "examples"
runner = CliRunner()


def _one_line_error(args, *needles):
    r = runner.invoke(app, [str(a) for a in args])
    assert r.exit_code == 2, r.output
    lines = r.stderr.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("axiscal: error: "), r.stderr
    assert "Traceback" not in r.output and "Warning" not in r.stderr
    for n in needles:
        assert n in lines[0], lines[0]
    return lines[0]


def _edit(tmp_path, example, old, new, name="c.toml"):
    text = (EXAMPLES / example).read_text()
    lines = [new if ln.startswith(old) else ln for ln in text.splitlines()]
    assert any(ln == new for ln in lines), f"{old!r} not in {example}"
    p = tmp_path / name
    p.write_text("\n".join(lines) + "\n")
    return p


@pytest.mark.parametrize("args, needles", [
    (["--duration-min", "1e308"], ["--duration-min = 1e308 min", "10080 min"]),
    (["--duration-min", "-5"], ["--duration-min = -5 min", "more than 0 min"]),
    (["--duration-min", "10000", "--interval-s", "0.01"], ["readings", "--interval-s"]),
])
def test_motion_stability_options_bounded(args, needles):
    _one_line_error(["motion", "stability", *args], *needles)


@pytest.mark.parametrize("command, example", [
    ("home", "scale_single.toml"), ("gantry", "scale_gantry.toml")])
def test_scale_counts_per_period_bounded(tmp_path, command, example):
    """1e9 counts per period once needed 60 GiB (home), 8e6 never finished (gantry)."""
    for n in (1_000_000_000, 8_000_000):
        p = _edit(tmp_path, example, "counts_per_period", f"counts_per_period = {n}")
        _one_line_error(["scale", command, p], f"counts_per_period = {n}", "at most 4096",
                        f"{p}:")


@pytest.mark.parametrize("old, new, needle", [
    ("dead_path_mm", "dead_path_mm = 1e308", "[laser] dead_path_mm = 1e308 mm"),
    ("temperature_rate", "temperature_rate = 1e308", "[air] temperature_rate = 1e308 K/s"),
    ("period_um", "period_um = -20", "[compensator] period_um = -20 µm"),
    ("period_um", "period_mm = -20", "unknown key [compensator] period_mm"),
])
def test_scale_config_messages_name_what_was_written(tmp_path, old, new, needle):
    p = _edit(tmp_path, "scale_single.toml", old, new)
    line = _one_line_error(["scale", "home", p], needle)
    assert "-0.02" not in line and "e-05" not in line


@pytest.mark.parametrize("args", [["motion", "simulate"], ["motion", "stability"],
                                  ["motion", "repeatability"], ["scale", "home"],
                                  ["scale", "gantry"]])
def test_empty_config_refused(tmp_path, args):
    p = tmp_path / "empty.toml"
    p.write_text("# nothing\n")
    _one_line_error([*args, p], "empty")


def test_scale_gantry_needs_gantry_table(tmp_path):
    p = tmp_path / "g.toml"
    p.write_text("[compensator]\nperiod_um = 20\n")
    _one_line_error(["scale", "gantry", p], "[gantry] is missing")


def test_absurd_values_in_data_files_refused(tmp_path):
    text = (EXAMPLES / "squareness_L180_x.csv").read_text().replace("-350,7.63698181", "-350,1e308")
    (tmp_path / "s.csv").write_text(text)
    _one_line_error(["straightness", tmp_path / "s.csv"], "1e308", "s.csv:4")
    rows = "\n".join(f"1,{a},{'1e308' if a == 0 else 0},0,0,0,0" for a in range(0, 360, 90))
    (tmp_path / "m.csv").write_text("run,angle_deg,ez_arcsec,ey_arcsec,ex_arcsec,dy_um,dz_um\n"
                                    + rows + "\n")
    _one_line_error(["motion", "analyze", tmp_path / "m.csv"], "ez_arcsec 1e308 is out of range")


def test_motion_simulate_harmonic_bounded(tmp_path):
    p = _edit(tmp_path, "motion_indexing_table.toml", "harmonics", "harmonics = [[1, 1e308, 0]]")
    _one_line_error(["motion", "simulate", p], "harmonics")


@pytest.mark.parametrize("args, needle", [
    (["squareness", "diagonal", "--d1", "1e308", "--d2", "0", "--x-length", "600",
      "--y-length", "800"], "--d1 = 1e308 µm"),
    (["squareness", "diagonal", "--d1", "1", "--d2", "0", "--x-length", "-600",
      "--y-length", "800"], "--x-length = -600 mm"),
    (["squareness", "circular", str(EXAMPLES / "squareness_ballbar_150mm.csv"), "--radius",
      "1e308"], "--radius = 1e308 mm"),
])
def test_squareness_options_bounded(args, needle):
    _one_line_error(args, needle)


def test_compensate_verify_names_unknown_table(tmp_path):
    p = tmp_path / "c.toml"
    p.write_text((EXAMPLES / "compensation_linear.toml").read_text() + "\n[foo]\nx = 1\n")
    _one_line_error(["compensate", "--verify", p], "unknown table [foo]")


def test_output_files_get_the_umask_mode_and_keep_it(tmp_path):
    """tempfile.mkstemp gave 0600 to every output; a plain write under umask 022 gives 0644,
    and overwriting a file keeps its mode."""
    from axiscal.io._files import write_text_atomic

    old = os.umask(0o022)
    try:
        p = write_text_atomic(tmp_path / "r.html", "x")
        assert p.stat().st_mode & 0o777 == 0o644
        os.chmod(p, 0o640)
        write_text_atomic(p, "y")
        assert p.stat().st_mode & 0o777 == 0o640 and p.read_text() == "y"
    finally:
        os.umask(old)


def test_compensate_verify_test_value_of_wrong_type(tmp_path):
    """Found by the fuzz harness: measurement_sigma = "text" ended in float()'s ValueError."""
    lines = (EXAMPLES / "compensation_linear.toml").read_text().splitlines()
    text = "\n".join('measurement_sigma = "text"' if ln.startswith("measurement_sigma") else ln
                     for ln in lines)
    assert 'measurement_sigma = "text"' in text
    p = tmp_path / "c.toml"
    p.write_text(text)
    _one_line_error(["compensate", "--verify", p], "measurement_sigma")


_EX = Path(__file__).resolve().parents[2] / "examples"
_DATA = Path(__file__).resolve().parents[2] / "src/axiscal/data"
_CONFIGS = [
    (["simulate"], _DATA / "demo_linear.toml", "test"),
    (["compensate", "--verify"], _DATA / "demo_compensation.toml", "compensation"),
    (["rotary", "simulate"], _EX / "rotary_turntable.toml", "setup"),
    (["motion", "simulate"], _EX / "motion_indexing_table.toml", "test"),
    (["scale", "home"], _EX / "scale_single.toml", "laser"),
    (["scale", "gantry"], _EX / "scale_gantry.toml", "gantry"),
    (["ballbar", "simulate"], _EX / "ballbar_sim.toml", "test"),
]


@pytest.mark.parametrize("command, example, table", _CONFIGS, ids=lambda v: str(v))
@pytest.mark.parametrize("slip", ["table", "key"])
def test_every_configuration_names_an_unknown_table_or_key_in_one_style(tmp_path, command,
                                                                         example, table, slip):
    """Issue 11: four wordings of the same mistake ("unknown key(s) x; allowed:", "top level:
    unknown key(s)", "x: unknown key (known: ...)", "unknown section") and some without the file;
    now every reader says ``FILE:LINE: unknown table [foo]`` or ``FILE:LINE: unknown key [t] k``."""
    import re

    text = example.read_text()
    if slip == "table":
        text += "\n[foo]\nx = 1\n"
        want = r"unknown table \[foo\]"
    else:
        text = re.sub(rf"^\[{table}\]\s*$", f"[{table}]\ntypo_key = 1", text, count=1,
                      flags=re.M)
        want = rf"unknown key \[{table}\] typo_key"
    f = tmp_path / "c.toml"
    f.write_text(text)
    extra = ["--out", str(tmp_path / "o.csv")] if command[0] == "ballbar" else []
    r = runner.invoke(app, [*command, str(f), *extra])
    assert r.exit_code == 2, r.output
    line = text.splitlines().index("[foo]" if slip == "table" else "typo_key = 1") + 1
    assert re.fullmatch(rf"axiscal: error: {re.escape(str(f))}:{line}: {want}; known: [\w, .]+\n",
                        r.stderr), r.stderr
