"""The positioning commands: iso230-2, plan, simulate, demo (typer CliRunner)."""

import json

import numpy as np
import pytest
from typer.testing import CliRunner

from axiscal.cli import app

runner = CliRunner()

GOOD = """# target_unit=mm deviation_unit=um machine=VMC axis=X
target,direction,run,deviation
""" + "".join(f"{t},{d},{r},{v}\n" for t, base in ((0, 1.0), (200, 2.0), (400, -1.0), (600, 0.5), (800, 3.0))
              for r in range(1, 6) for d, v in (("+", base + 0.1 * r), ("-", base - 2 + 0.1 * r)))


@pytest.fixture
def good(tmp_path):
    p = tmp_path / "x.csv"
    p.write_text(GOOD)
    return p


def test_table_output(good):
    r = runner.invoke(app, ["iso230-2", str(good)])
    assert r.exit_code == 0, r.output
    assert "ISO 230-2:2014 positioning test — VMC X" in r.stdout
    assert "Axis parameters [µm]" in r.stdout
    assert "reversal value" in r.stdout
    assert "2.00" in r.stdout  # B = 2 µm by construction (every x↓ is x↑ - 2)


def test_json_output_keys_and_values(good):
    r = runner.invoke(app, ["iso230-2", str(good), "--json"])
    assert r.exit_code == 0, r.output
    d = json.loads(r.stdout)
    for key in ("A", "A_up", "A_down", "E", "E_up", "E_down", "M", "R", "R_up", "R_down", "B",
                "B_mean", "unit", "targets", "warnings"):
        assert key in d, key
    assert d["unit"] == "um" and len(d["targets"]) == 5
    assert d["B"] == pytest.approx(2.0) and d["B_mean"] == pytest.approx(2.0)
    assert d["E"] == pytest.approx(3.3 - (-3 + 0.3))  # max x̄↑ at 800 minus min x̄↓ at 400
    assert d["warnings"] == []


def test_plot_and_report_files(good, tmp_path):
    png, html = tmp_path / "p.png", tmp_path / "r.html"
    r = runner.invoke(app, ["iso230-2", str(good), "--plot", str(png), "--report", str(html),
                            "--draft"])   # no laboratory configured: a draft (issue 28)
    assert r.exit_code == 0, r.output
    assert png.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    page = html.read_text()
    assert "<svg" in page and "ISO 230-2:2014" in page and "VMC" in page
    assert "Reversal value" in page
    # self-contained: nothing is loaded from elsewhere (namespace URIs in the SVG are names only)
    for external in ('src="http', "src='http", 'href="http', "<link", "<script", "@import"):
        assert external not in page, external


@pytest.mark.parametrize("content, args, message", [
    (None, [], "no such file"),
    ("target,dir,run,deviation\n0,+,1,1\n", ["--target-unit", "mm", "--deviation-unit", "um"], "must name the columns"),
    ("target,direction,run,deviation\n0,+,1,1\n0,+,2,x\n", ["--target-unit", "mm", "--deviation-unit", "um"], ":3: deviation 'x' is not a number"),
    ("target,direction,run,deviation\n0,+,1,1\n", ["--target-unit", "mm", "--deviation-unit", "parsec"], "unknown unit 'parsec'"),
    ("target,direction,run,deviation\n0,+,1,1\n100,+,1,2\n", ["--target-unit", "mm", "--deviation-unit", "um"], "1 reading(s) at target 0 mm in direction +; ISO 230-2 needs at least 2"),
])
def test_user_errors_are_one_line_and_exit_2(tmp_path, content, args, message):
    p = tmp_path / "in.csv"
    if content is not None:
        p.write_text(content)
    r = runner.invoke(app, ["iso230-2", str(p), *args])
    assert r.exit_code == 2
    assert r.stdout == ""
    assert r.stderr.count("\n") == 1 and r.stderr.startswith("axiscal: error: ")
    assert message in r.stderr
    assert "Traceback" not in r.output


def test_unwritable_output_is_refused_before_work(good, tmp_path):
    r = runner.invoke(app, ["iso230-2", str(good), "--report", str(tmp_path / "no" / "r.html")])
    assert r.exit_code == 2 and "folder" in r.stderr and "does not exist" in r.stderr


def test_plan_commands(tmp_path):
    r = runner.invoke(app, ["plan", "rotary", "--travel", "360", "--json"])
    assert r.exit_code == 0, r.output
    d = json.loads(r.stdout)
    assert d["targets"] == [0, 45, 90, 135, 180, 225, 270, 315, 360]
    assert d["n_measurements"] == 90
    csv = tmp_path / "plan.csv"
    r = runner.invoke(app, ["plan", "linear", "--length", "800", "--csv", str(csv)])
    assert r.exit_code == 0 and "5 targets" in r.stdout
    assert csv.read_text().splitlines()[1].startswith("seq,kind,position")
    r = runner.invoke(app, ["plan", "linear", "--length", "1500", "--targets", "4"])
    assert r.exit_code == 2 and "at least 8" in r.stderr


def test_simulate_json_and_data_round_trip(tmp_path):
    from importlib import resources

    cfg = tmp_path / "lin.toml"
    cfg.write_text(resources.files("axiscal.data").joinpath("demo_linear.toml").read_text("utf-8"))
    data = tmp_path / "sim.csv"
    r = runner.invoke(app, ["simulate", str(cfg), "--json", "--data", str(data)])
    assert r.exit_code == 0, r.output
    d = json.loads(r.stdout)
    assert abs(d["E"] - d["truth"]["E"]) < 1.5
    again = json.loads(runner.invoke(app, ["iso230-2", str(data), "--json"]).stdout)
    assert again["E"] == pytest.approx(d["E"], abs=1e-9)
    bad = tmp_path / "bad.toml"
    bad.write_text("[axis]\nkind='linear'\nbacklash=3\n[test]\nlength_mm=100\n")
    r = runner.invoke(app, ["simulate", str(bad)])
    assert r.exit_code == 2 and "bad.toml:3: unknown key [axis] backlash" in r.stderr
    bad.write_text("[axis\n")
    r = runner.invoke(app, ["simulate", str(bad)])
    assert r.exit_code == 2 and "not valid TOML" in r.stderr


def test_demo_writes_reports(tmp_path):
    out = tmp_path / "demo"
    r = runner.invoke(app, ["demo", "--out", str(out)])
    assert r.exit_code == 0, r.output
    for name in ("index.html", "linear_report.html", "rotary_report.html", "linear_iso230-2.png",
                 "rotary_calibration_report.html",
                 "rotary_data.csv"):
        assert (out / name).stat().st_size > 0, name
    assert "Measured beside the simulation's truth" in r.stdout
    from pypdf import PdfReader

    for name in ("linear", "rotary"):     # the customer certificates (make demo)
        text = "\n".join(p.extract_text() for p in PdfReader(out / f"{name}_certificate.pdf").pages)
        assert "Overall verdict" in text and "page 1 of" in text and "truth" not in text


def test_tolerances_give_verdicts_and_exit_code(good, tmp_path):
    """B = 2 µm by construction: B=2.5 passes, B=1 fails (exit 1); a bad item is a user error."""
    r = runner.invoke(app, ["iso230-2", str(good), "--tolerance", "B=2.5", "--tolerance", "E=10", "--json"])
    assert r.exit_code == 0, r.output
    d = json.loads(r.stdout)
    assert d["accepted"] is True and [a["parameter"] for a in d["acceptance"]] == ["E", "B"]
    html = tmp_path / "r.html"
    r = runner.invoke(app, ["iso230-2", str(good), "--tolerance", "B=1", "--report", str(html),
                            "--draft"])
    assert r.exit_code == 1 and "FAIL" in r.stdout
    assert 'class="bad">FAIL' in html.read_text()
    r = runner.invoke(app, ["iso230-2", str(good), "--tolerance", "Q=1"])
    assert r.exit_code == 2 and "not an ISO 230-2 parameter" in r.stderr
    r = runner.invoke(app, ["iso230-2", str(good), "--tolerance", "A:1"])
    assert r.exit_code == 2 and "write NAME=VALUE" in r.stderr


def test_plot_extension_is_checked_before_any_work(good, tmp_path):
    r = runner.invoke(app, ["iso230-2", str(good), "--plot", str(tmp_path / "p.gif")])
    assert r.exit_code == 2 and "use a .png, .svg or .pdf extension" in r.stderr
    assert not (tmp_path / "p.gif").exists()


def test_rotary_closure_in_the_terminal_table_and_the_report(tmp_path):
    """The README says the 0°/360° closure is reported: it must be in the parameters table and
    the HTML report, not only in --json. Injected: the 360° readings are 2 arcsec above 0°'s."""
    from typer.testing import CliRunner

    from axiscal.cli import app

    rows = ["target,direction,run,deviation"]
    for run in range(1, 4):
        for t in range(0, 361, 45):
            for d in ("+", "-"):
                rows.append(f"{t},{d},{run},{(2.0 if t == 360 else 0.0) + 0.01 * run:.3f}")
    f = tmp_path / "c.csv"
    f.write_text("# target_unit=deg deviation_unit=arcsec axis=C\n" + "\n".join(rows) + "\n")
    r = CliRunner().invoke(app, ["iso230-2", str(f), "--report", str(tmp_path / "r.html"),
                                 "--draft"],
                           env={"COLUMNS": "160"})
    assert r.exit_code == 0, r.output
    line = next(ln for ln in r.stdout.splitlines() if "closure↑" in ln)
    assert "2.00" in line and "360°" in line
    html = (tmp_path / "r.html").read_text()
    assert "Closure ↑" in html and "Closure ↓" in html


def test_a_plan_of_more_readings_than_a_calibration_takes_is_refused(tmp_path):
    """10,000 targets x 100 runs ran for minutes in `simulate` (each allowed alone): a plan holds
    at most 20,000 readings a direction, said with both numbers."""
    r = runner.invoke(app, ["plan", "linear", "--length", "800", "--targets", "10000",
                            "--runs", "100"])
    assert r.exit_code == 2
    assert "10000 targets x 100 runs is 1000000 readings a direction" in r.stderr


def test_a_long_per_target_table_shows_its_ends_and_says_what_is_left(tmp_path):
    """A rich table of 10,000 rows took 40 s to draw: the terminal shows the first and last 50
    targets and names the rest; --json keeps every target."""
    from axiscal.datasets import PositioningDataset
    from axiscal.io.csv import format_positioning_csv

    rng = np.random.default_rng(3)
    t = np.linspace(0, 1000, 400)
    f = tmp_path / "many.csv"
    f.write_text(format_positioning_csv(PositioningDataset.from_arrays(
        "linear", t, rng.normal(0, 1, (400, 2)), rng.normal(0, 1, (400, 2)))))
    r = runner.invoke(app, ["iso230-2", str(f)], env={"COLUMNS": "160"})
    assert r.exit_code == 0, r.output
    assert "300 more" in r.stdout and "400 targets: the first and last 50 are shown" in r.stdout
    assert f"{t[-1]:g}" in r.stdout and f"{t[200]:g} " not in r.stdout
    d = json.loads(runner.invoke(app, ["iso230-2", str(f), "--json"]).stdout)
    assert len(d["targets"]) == 400
