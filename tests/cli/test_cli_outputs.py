"""Output files and option combinations: refused before any work, one line, nothing on disk.

Found by trying a shop-floor user's slips: ``--report r.png`` wrote HTML into a .png,
``plan --csv plan.pdf`` and ``simulate --data d.png`` wrote CSV under the wrong name, a Heidenhain
table written under another name than the one its .CMA names could never be loaded,
``compensate DATA --plot p.png`` or ``--verify CFG --bidirectional`` silently ignored the option,
``--option detection_unit=abc`` and an unknown option of a cross-axis table ended in tracebacks,
and ``--seed -1`` raised numpy's ValueError.
"""

import os
from pathlib import Path

import pytest
from typer.testing import CliRunner

from axiscal.cli import app
from tests.cli._assertions import one_error_line

runner = CliRunner()
ROOT = Path(__file__).resolve().parents[2]
LINEAR_TOML = ROOT / "src/axiscal/data/demo_linear.toml"
ROTARY_TOML = ROOT / "examples/rotary_turntable.toml"
MOTION_TOML = ROOT / "examples/motion_indexing_table.toml"
LOOP_TOML = ROOT / "examples/compensation_linear.toml"
DATA = "# target_unit=mm deviation_unit=um axis=X\ntarget,direction,run,deviation\n" + "".join(
    f"{t},{d},{r},{0.1 * r + t / 100}\n" for t in (0, 100, 200, 300, 400) for r in range(1, 6)
    for d in "+-")
MOTION = "run,angle_deg,ez_arcsec,ey_arcsec,ex_arcsec,dy_um,dz_um\n" + "".join(
    f"{r},{a},{a / 90},0,0,0,0\n" for r in (1, 2) for a in range(0, 360, 30))


@pytest.fixture
def work(tmp_path):
    (tmp_path / "d.csv").write_text(DATA)
    (tmp_path / "m.csv").write_text(MOTION)
    old = os.getcwd()
    os.chdir(tmp_path)
    yield tmp_path
    os.chdir(old)


def _refused(work, args, *words):
    before = set(os.listdir(work))
    r = runner.invoke(app, [str(a) for a in args])
    one_error_line(r, *words)
    assert set(os.listdir(work)) == before, "a file was written before the error"


@pytest.mark.parametrize("args, words", [
    (["iso230-2", "d.csv", "--report", "r.png"], ["report file r.png", ".html"]),
    (["simulate", LINEAR_TOML, "--report", "r.docx"], ["report file r.docx", ".pdf"]),
    (["simulate", LINEAR_TOML, "--data", "d.png"], ["data file d.png", ".csv or .json"]),
    (["rotary", "simulate", ROTARY_TOML, "--report", "r.png"], ["report file r.png"]),
    (["plan", "linear", "--length", "800", "--csv", "plan.pdf"], ["plan CSV file plan.pdf"]),
    (["plan", "rotary", "--csv", "plan.txt"], ["plan CSV file plan.txt", ".csv"]),
    (["motion", "simulate", MOTION_TOML, "--csv", "m.png"], ["csv file m.png"]),
    (["motion", "analyze", "m.csv", "--report", "r.txt"], ["report file r.txt"]),
    (["compensate", "d.csv", "--out", "t.png"], ["csv table t.png", ".csv"]),
    (["compensate", "d.csv", "-c", "siemens-840d", "--out", "t.pdf"], [".ini or .txt"]),
    (["compensate", "d.csv", "-c", "heidenhain", "--spacing", "128", "--out", "t.csv"],
     ["X.CMA names the table X.COM", "--out X.COM"]),
    (["compensate", "d.csv", "-c", "heidenhain", "--spacing", "128", "--out", "Y.COM"],
     ["names the table X.COM"]),
    (["compensate", "--verify", LOOP_TOML, "--out", "x.png"], ["siemens-840d table x.png"]),
])
def test_output_file_of_the_wrong_kind(work, args, words):
    _refused(work, args, *words)


@pytest.mark.parametrize("args, words", [
    (["compensate", "d.csv", "--plot", "p.png"], ["a table from SOURCE does not use --plot"]),
    (["compensate", "d.csv", "--seed", "5"], ["does not use --seed"]),
    (["compensate", "--verify", LOOP_TOML, "--bidirectional"], ["--verify does not use --bidirectional"]),
    (["compensate", "--verify", LOOP_TOML, "d.csv", "--resolution", "1"],
     ["--verify does not use SOURCE, --resolution; drop them"]),
    (["compensate", "--read", "d.csv", "--out", "o.csv"], ["--read writes --out only with --to NAME"]),
    (["compensate", "--squareness", "40", "--axes", "XZ", "--aligned", "Z", "--start", "0",
      "--end", "100", "--spacing", "10", "--bidirectional"], ["--squareness does not use --bidirectional"]),
    (["compensate", "d.csv", "-c", "fanuc", "-o", "detection_unit=abc"],
     ["detection_unit='abc' must be a number"]),
    (["compensate", "d.csv", "-c", "linuxcnc", "-o", "file_type=0.5"], ["must be a whole number"]),
    (["compensate", "d.csv", "-c", "siemens-840d", "-o", "zero_ends=maybe"], ["true or false"]),
    (["compensate", "--squareness", "40", "--axes", "XZ", "--aligned", "Z", "--start", "0",
      "--end", "100", "--spacing", "10", "-c", "siemens-840d", "-o", "bogus=1"],
     ["unknown option(s) bogus"]),
    (["compensate", "--squareness", "40", "--axes", "XZ", "--aligned", "Z", "--start", "0",
      "--end", "100", "--spacing", "10", "-c", "heidenhain", "-o", "driving_axis=Y"],
     ["driving_axis is set by the command"]),
    (["compensate", "--squareness", "40", "--axes", "XZ", "--aligned", "Z", "--start", "0",
      "--end", "100", "--spacing", "10", "-o", "x=1"], ["the csv table takes no options"]),
    (["compensate", "--verify", LOOP_TOML, "--seed", "-1"], ["'--seed'", "x>=0"]),
    (["simulate", LINEAR_TOML, "--seed", "-1"], ["'--seed'"]),
    (["demo", "--out", "demo", "--seed", "-1"], ["'--seed'"]),
    (["plan", "linear", "--length", "800", "--seed", "-2"], ["'--seed'"]),
])
def test_options_the_command_would_ignore_or_choke_on(work, args, words):
    _refused(work, args, *words)


def test_an_option_text_stays_text(work):
    """``machine_axis=01`` is the machine axis named 01, not the number 1."""
    r = runner.invoke(app, ["compensate", "d.csv", "-c", "siemens-840d", "-o", "machine_axis=01"])
    assert r.exit_code == 0, r.output
    assert "[0,01]" in r.stdout


def test_the_right_names_still_write(work):
    r = runner.invoke(app, ["compensate", "d.csv", "-c", "heidenhain", "--spacing", "128",
                            "--out", "x.com"])
    assert r.exit_code == 0, r.output
    assert (work / "x.com").read_text().startswith("BEGIN X.COM") and (work / "X.CMA").exists()
    r = runner.invoke(app, ["plan", "rotary", "--csv", "PLAN.CSV"])
    assert r.exit_code == 0 and (work / "PLAN.CSV").read_text().count("\n") > 10


UNWRITABLE = Path("/proc/axiscal-review")   # procfs: no file can be created there, even by root


@pytest.mark.parametrize("args", [
    ["plan", "rotary", "--csv", UNWRITABLE.with_suffix(".csv")],
    ["iso230-2", "d.csv", "--report", UNWRITABLE.with_suffix(".html")],
    ["iso230-2", "d.csv", "--plot", UNWRITABLE.with_suffix(".png")],
    ["compensate", "d.csv", "--out", UNWRITABLE.with_suffix(".csv")],
    ["demo", "--out", UNWRITABLE],
])
def test_a_folder_that_cannot_be_written_is_one_line(work, args):
    """PermissionError / FileNotFoundError from tempfile.mkstemp used to end in a traceback."""
    _refused(work, args, "cannot ")


def test_a_pipe_or_device_is_not_read(work):
    """read_text on /dev/zero read forever; a FIFO blocked until a writer came."""
    os.mkfifo(work / "fifo.csv")
    for name in ("fifo.csv", "/dev/zero"):
        r = runner.invoke(app, ["iso230-2", name])
        assert r.exit_code == 2 and "is not a regular file" in r.stderr, r.output


@pytest.mark.parametrize("args, words", [
    (["iso230-2", "a" * 300 + ".csv"], ["File name too long"]),
    (["iso230-2", "d.csv", "--report", "a" * 300 + ".html"], ["cannot write report"]),
    (["iso230-2", "d.csv", "--report", "b" * 300 + "/x.html"], ["cannot write report", "too long"]),
    (["iso230-2", "d.csv", "--plot", "d.csv/x.png"], ["cannot write plot", "Not a directory"]),
])
def test_impossible_path_names_are_one_line(work, args, words):
    """Path.exists() raises OSError (ENAMETOOLONG) instead of answering: it was a traceback."""
    _refused(work, args, *words)


def test_read_compares_only_data_in_the_table_units(work):
    """Rotary data (deg, arcsec) was compared with a linear table and printed as '330 mm ... um'."""
    rot = ROOT / "src/axiscal/data/demo_rotary.toml"
    assert runner.invoke(app, ["simulate", str(rot), "--data", "rot.csv"]).exit_code == 0
    assert runner.invoke(app, ["compensate", "d.csv", "-c", "linuxcnc", "--out", "lin.comp"]).exit_code == 0
    _refused(work, ["compensate", "--read", "lin.comp", "-c", "linuxcnc", "rot.csv"],
             "rot.csv is in deg and arcsec, the table in mm and um")


#: Every command that simulates (draws random numbers) — found by name or listed here.
_SIMULATIONS = {"demo", "simulate", "motion stability", "motion repeatability", "scale home",
                "scale gantry", "plan linear"}


def test_every_simulation_takes_seed_and_every_result_command_prints_json():
    """The audit of issue 11 as a test: a new simulation without --seed, or a new result command
    without --json, fails here (the commands are found by walking the app)."""
    from tests.cli.test_cli_fuzz import _commands

    missing = []
    for name, cmd in _commands():
        opts = {o for p in cmd.params for o in getattr(p, "opts", [])}
        if (name.endswith("simulate") or name in _SIMULATIONS) and "--seed" not in opts:
            missing.append(f"{name}: no --seed")
        if name not in ("serve", "demo") and "--json" not in opts:
            missing.append(f"{name}: no --json")
    assert not missing, missing


@pytest.mark.parametrize("args", [
    ["motion", "simulate", str(MOTION_TOML)],
    ["motion", "stability", "--duration-min", "3"],
    ["motion", "repeatability", str(MOTION_TOML), "--runs", "2"],
    ["rotary", "simulate", str(ROTARY_TOML)],
    ["scale", "home", str(ROOT / "examples/scale_single.toml")],
    ["scale", "gantry", str(ROOT / "examples/scale_gantry.toml")],
    ["squareness", "simulate", "--machine", "3", "--noise", "0.5"],
])
def test_seed_reproduces_a_simulation_and_another_seed_changes_it(args):
    def run(seed):
        r = runner.invoke(app, [*args, "--json", "--seed", str(seed)])
        assert r.exit_code == 0, r.output
        return r.stdout

    assert run(5) == run(5)
    assert run(5) != run(6)


@pytest.mark.parametrize("args", [
    ["motion", "simulate", str(MOTION_TOML)],
    ["motion", "stability", "--duration-min", "3"],
    ["motion", "repeatability", str(MOTION_TOML), "--runs", "2"],
    ["rotary", "simulate", str(ROTARY_TOML)],
])
def test_plot_writes_a_picture(tmp_path, args):
    out = tmp_path / "p.png"
    r = runner.invoke(app, [*args, "--plot", str(out)])
    assert r.exit_code == 0, r.output
    assert out.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n" and f"wrote plot {out}" in r.stderr


def test_motion_analyze_plots_the_polar_error_motions(tmp_path):
    data = tmp_path / "m.csv"
    data.write_text(MOTION)
    out = tmp_path / "polar.svg"
    r = runner.invoke(app, ["motion", "analyze", str(data), "--plot", str(out)])
    assert r.exit_code == 0, r.output
    assert "<svg" in out.read_text()


@pytest.mark.parametrize("args, title, simulation", [
    (["straightness", str(ROOT / "examples/squareness_L180_x.csv")], "Straightness", False),
    (["squareness", "circular", str(ROOT / "examples/squareness_ballbar_150mm.csv")],
     "Circular test", False),
    (["squareness", "simulate", "--machine", "3"], "Squareness by every method", True),
    (["scale", "home", str(ROOT / "examples/scale_single.toml")], "Laser scale referencing",
     True),
    (["compensate", "--verify", str(LOOP_TOML)], "Compensation verified by re-measuring", True),
    (["squareness", "biaxial", str(ROOT / "examples/squareness_L180_x.csv"),
      str(ROOT / "examples/squareness_L180_y.csv"), "--orientation", "180"],
     "Squareness, bi-axial L 180°", False),
    (["squareness", "diagonal", "--file", str(ROOT / "examples/squareness_diagonal_600x800.csv")],
     "Squareness from two diagonals", False),
])
def test_report_of_a_result_holds_the_method_the_plot_and_every_figure(tmp_path, args, title,
                                                                      simulation):
    """The commands whose result is a few figures and a plot write a report too (issue 11)."""
    import html as html_lib
    import json

    out = tmp_path / "r.html"
    r = runner.invoke(app, [*args, "--report", str(out)])
    assert r.exit_code == 0, r.output
    page = out.read_text()
    assert f"<h1>{title}" in page and "<svg" in page and "Results" in page
    assert ("simulation report" in page.lower()) == simulation
    # every number of the --json result is in the page's table, under its label with its unit
    # and with the decimals of that unit (issue 28: one label table, one decimal policy)
    # an expanded uncertainty U as the terminal gives it: two significant digits, rounded up
    # (JCGM 100:2008 §7.2.6)
    from axiscal.report.labels import fmt, label, quantity, split_key
    from axiscal.standards.uncertainty_reporting import format_uncertainty

    d = json.loads(runner.invoke(app, [*args, "--json"]).stdout)
    for key, value in ((k, v) for k, v in d.items() if isinstance(v, float)):
        unit = quantity(key, d.get("unit"))[1]
        text = format_uncertainty(value) if split_key(key)[0] == "U" else fmt(value, unit)
        shown = f"<td>{label(key, d.get('unit'))}</td><td>{text}</td>"
        assert html_lib.unescape(shown) in html_lib.unescape(page), shown
    assert "_um" not in page.split("<body>")[1].split("<svg")[0]


def test_history_compare_and_trend_write_reports(tmp_path, monkeypatch):
    monkeypatch.setenv("AXISCAL_DB", f"sqlite:///{tmp_path / 'h.sqlite'}")
    for i, shift in enumerate((0.0, 0.5, 1.0)):
        f = tmp_path / f"t{i}.csv"
        f.write_text(DATA.replace("axis=X", f"axis=X machine=M date=2026-0{i + 1}-01")
                     .replace(",0.1,", f",{0.1 + shift},"))
        assert runner.invoke(app, ["history", "add", str(f)]).exit_code == 0
    r = runner.invoke(app, ["history", "compare", "1", "3", "--report", str(tmp_path / "c.html")])
    assert r.exit_code == 0, r.output
    assert "Tests 1 and 3 compared" in (tmp_path / "c.html").read_text()
    r = runner.invoke(app, ["history", "trend", "--machine", "M", "--axis", "X", "--report",
                            str(tmp_path / "t.html")])
    assert r.exit_code == 0, r.output
    page = (tmp_path / "t.html").read_text()
    assert "E of M X over time" in page and "ISO/TS 28037" in page and "<svg" in page
