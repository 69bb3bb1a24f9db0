"""``axiscal iso230-2 --report x.pdf --job`` and ``axiscal config``: certificates from the CLI."""

import json
import sys
from pathlib import Path

import pytest
from typer.testing import CliRunner

from axiscal.cli import app
from axiscal.cli.demo import JOB_TOML

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "report"))
from pdf_pages import pdf_text, render_pages  # noqa: E402

runner = CliRunner()

# the job file the README shows and make demo writes (customer, machine, conditions, E and R)
JOB = JOB_TOML
USER = """
[company]
name = "Precision Metrology GmbH"
logo = "logo.svg"
[operator]
name = "J. Keller"
[certificate]
number_prefix = "PM-"
[uncertainty]
e_ve = 0.8
e_ve_source = "drift check"
"""
LOGO = (
    '<svg xmlns="http://www.w3.org/2000/svg" width="40" height="40"><rect width="40" '
    'height="40" fill="#0b5fa5"/></svg>'
)


def _data(tmp_path):
    r = runner.invoke(
        app,
        [
            "simulate",
            str(
                Path(__file__).resolve().parents[2]
                / "src"
                / "axiscal"
                / "data"
                / "demo_linear.toml"
            ),
            "--data",
            str(tmp_path / "x.csv"),
        ],
    )
    assert r.exit_code == 0, r.output
    return tmp_path / "x.csv"


def test_pdf_certificate_from_the_command_line(tmp_path):
    data = _data(tmp_path)
    (tmp_path / "config.toml").write_text(USER)
    (tmp_path / "logo.svg").write_text(LOGO)
    (tmp_path / "job.toml").write_text(JOB)
    env = {"AXISCAL_CONFIG": str(tmp_path / "config.toml")}
    pdf = tmp_path / "cert.pdf"
    r = runner.invoke(
        app,
        [
            "iso230-2",
            str(data),
            "--job",
            str(tmp_path / "job.toml"),
            "--report",
            str(pdf),
            "--paper",
            "Letter",
            "--json",
        ],
        env=env,
    )
    assert r.exit_code == 0, r.output
    d = json.loads(r.stdout)
    assert d["accepted"] is True and d["decision_rule"] == "iso14253-1"
    assert d["acceptance"][0]["outcome"] == "conformance proven"
    assert d["uncertainty"]["E"] == d["acceptance"][0]["U"] > 0
    text = "\n".join(pdf_text(pdf))
    assert "Precision Metrology GmbH" in text and "VMC8-0042" in text and "PM-" in text
    assert f"{d['uncertainty']['E']:.2f}" in text and "page 1 of" in text
    assert render_pages(pdf, "certificate_cli_letter")


def test_zone_exits_1_and_simple_rule_is_selectable(tmp_path):
    """E = 11.92 µm, U(E) ≈ 2.4 µm against E ≤ 12.5: in the uncertainty zone (exit 1, conformance
    not proven); with --rule simple it passes (exit 0)."""
    data = _data(tmp_path)
    env = {"AXISCAL_CONFIG": str(tmp_path / "none.toml")}
    r = runner.invoke(app, ["iso230-2", str(data), "--tolerance", "E=12.5", "--json"], env=env)
    assert r.exit_code == 1
    assert json.loads(r.stdout)["acceptance"][0]["outcome"] == "uncertainty zone"
    r = runner.invoke(
        app, ["iso230-2", str(data), "--tolerance", "E=12.5", "--rule", "simple"], env=env
    )
    assert r.exit_code == 0 and "simple decision rule" in r.stdout
    r = runner.invoke(
        app, ["iso230-2", str(data), "--rule", "guess", "--tolerance", "E=1"], env=env
    )
    assert r.exit_code == 2 and "use iso14253-1 or simple" in r.stderr


def test_bad_job_file_is_one_line(tmp_path):
    data = _data(tmp_path)
    (tmp_path / "job.toml").write_text("[machine]\nserial_number = 3\n")
    r = runner.invoke(
        app,
        [
            "iso230-2",
            str(data),
            "--job",
            str(tmp_path / "job.toml"),
            "--report",
            str(tmp_path / "c.html"),
        ],
        env={"AXISCAL_CONFIG": str(tmp_path / "none.toml")},
    )
    assert r.exit_code == 2 and "job.toml:2: unknown key [machine] serial_number" in r.stderr
    assert not (tmp_path / "c.html").exists()


def test_config_init_and_show(tmp_path):
    env = {"AXISCAL_CONFIG": str(tmp_path / "sub" / "config.toml")}
    r = runner.invoke(app, ["config", "--json"], env=env)
    assert r.exit_code == 0 and json.loads(r.stdout)["exists"] is False
    r = runner.invoke(app, ["config", "--init"], env=env)
    assert r.exit_code == 0 and (tmp_path / "sub" / "config.toml").exists()
    d = json.loads(runner.invoke(app, ["config", "--json"], env=env).stdout)
    # the template declares no uncertainty input: each is assumed by its rule and shown so
    assert d["config"]["company"]["name"] and d["config"]["uncertainty"] == {}
    r = runner.invoke(app, ["config", "--init"], env=env)
    assert r.exit_code == 2 and "exists" in r.stderr


def test_squareness_commands_state_their_uncertainty(tmp_path):
    """biaxial, diagonal and circular carry U (k = 2) by their method's budget; the user
    configuration's [squareness_uncertainty] inputs act on it."""
    ex = Path(__file__).resolve().parents[2] / "examples"
    env = {"AXISCAL_CONFIG": str(tmp_path / "none.toml")}
    cases = [["biaxial", str(ex / "squareness_L180_x.csv"), str(ex / "squareness_L180_y.csv"),
              "--orientation", "180"],
             ["diagonal", "--file", str(ex / "squareness_diagonal_600x800.csv")],
             ["circular", str(ex / "squareness_ballbar_150mm.csv")]]
    for args in cases:
        r = runner.invoke(app, ["squareness", *args, "--json"], env=env)
        assert r.exit_code == 0, r.output
        d = json.loads(r.stdout)
        assert d["U_um_per_m"] > 0 and all(c["clause"] for c in d["uncertainty"])
    (tmp_path / "c.toml").write_text("[squareness_uncertainty]\ntransducer_accuracy = 1.0\n")
    r = runner.invoke(app, ["squareness", *cases[2], "--json"],
                      env={"AXISCAL_CONFIG": str(tmp_path / "c.toml")})
    assert json.loads(r.stdout)["U_um_per_m"] == pytest.approx(2 * d["U_um_per_m"], rel=1e-9)
    (tmp_path / "c.toml").write_text("[squareness_uncertainty]\nprobe = 1.0\n")
    r = runner.invoke(app, ["squareness", *cases[2]], env={"AXISCAL_CONFIG": str(tmp_path / "c.toml")})
    assert r.exit_code == 2 and "squareness_uncertainty" in r.stderr
