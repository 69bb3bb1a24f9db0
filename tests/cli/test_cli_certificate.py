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
address = ["Messweg 12", "70565 Stuttgart"]
logo = "logo.svg"
[operator]
name = "J. Keller"
[certificate]
number_prefix = "PM-"
signatory = "Dr. M. Braun"
signatory_role = "Head of laboratory"
[[instrument]]
name = "Laser interferometer"
serial = "L-1"
certificate = "C-77"
due = "2099-04-30"
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


def _issue(tmp_path, *extra, env=None):
    return runner.invoke(app, ["iso230-2", str(tmp_path / "x.csv"), "--job",
                               str(tmp_path / "job.toml"), "--db", _db(tmp_path), *extra],
                         env=env or {"AXISCAL_CONFIG": str(tmp_path / "config.toml")})


def _db(tmp_path) -> str:
    return f"sqlite:///{tmp_path / 'h.sqlite'}"


def _setup(tmp_path, user=USER):
    data = _data(tmp_path)
    (tmp_path / "config.toml").write_text(user)
    (tmp_path / "logo.svg").write_text(LOGO)
    (tmp_path / "job.toml").write_text(JOB)
    return data


def test_pdf_certificate_from_the_command_line(tmp_path):
    """Every mandatory item given (user configuration + the README's job file): issued, numbered
    by the register from number_prefix (PM-{year}-{counter:05d}), kept with its SHA-256."""
    _setup(tmp_path)
    pdf = tmp_path / "cert.pdf"
    r = _issue(tmp_path, "--report", str(pdf), "--paper", "Letter", "--json")
    assert r.exit_code == 0, r.output
    d = json.loads(r.stdout)
    assert d["accepted"] is True and d["decision_rule"] == "iso14253-1"
    assert d["acceptance"][0]["outcome"] == "conformance proven"
    # the verdict is decided with the U printed (issue 38): two digits, rounded up
    assert d["acceptance"][0]["U"] == float(d["uncertainty_display"]["E"]) >= d["uncertainty"]["E"]
    year = __import__("datetime").date.today().year
    number = f"PM-{year}-00001"
    assert f"issued certificate {number}" in r.stderr
    text = "\n".join(pdf_text(pdf))
    assert "Precision Metrology GmbH" in text and "VMC8-0042" in text and number in text
    assert d["uncertainty_display"]["E"] in text and "page 1 of" in text
    assert "Purchase order 4711" in text and "15 *" in text     # customer-supplied, marked
    assert render_pages(pdf, "certificate_cli_letter")
    r = runner.invoke(app, ["certificate", "show", number, "--db", _db(tmp_path), "--out",
                            str(tmp_path / "again.pdf"), "--json"])
    assert r.exit_code == 0 and json.loads(r.stdout)["status"] == "issued"
    assert (tmp_path / "again.pdf").read_bytes() == pdf.read_bytes()


def test_same_file_twice_is_refused_and_a_reissue_amends(tmp_path):
    """Issue 38: the same command run twice issued a second certificate of the same test; now
    the second is refused (exit 2, one line naming the first and how to amend it, nothing
    written). A reissue: a new number that replaces the old (printed on it, with the reason),
    the old kept and marked superseded."""
    _setup(tmp_path)
    year = __import__("datetime").date.today().year
    r = _issue(tmp_path, "--report", str(tmp_path / "c1.html"))
    assert r.exit_code == 0 and f"issued certificate PM-{year}-00001" in r.stderr
    r = _issue(tmp_path, "--report", str(tmp_path / "c2.html"))
    assert r.exit_code == 2 and len(r.stderr.strip().splitlines()) == 1, r.output
    assert (f"has certificate PM-{year}-00001 of PM" in r.stderr
            and f"certificate reissue PM-{year}-00001" in r.stderr)
    assert not (tmp_path / "c2.html").exists()
    (tmp_path / "fix.toml").write_text('[machine]\nserial = "VMC8-0043"\n'
                                       '[tolerance]\nE = 12\n')
    r = runner.invoke(app, ["certificate", "reissue", f"PM-{year}-00001", "--reason",
                            "serial number corrected", "--job", str(tmp_path / "fix.toml"),
                            "--out", str(tmp_path / "c3.html"), "--db", _db(tmp_path)])
    assert r.exit_code == 0, r.output
    html = (tmp_path / "c3.html").read_text()
    assert f"replaces certificate PM-{year}-00001. Reason: serial number corrected" in html
    # issue 38: every changed field old → new, and every result whose verdict changed
    # by the certificate's own labels, never the configuration's keys (issue 40)
    assert "Serial number: VMC8-0042 → VMC8-0043" in html and "[machine]" not in html
    assert "Tolerance E: 15 → 12" in html and "tolerance E: 15 → 12" in html
    assert "verdict E: conformance proven → uncertainty zone" in html
    shown = runner.invoke(app, ["certificate", "show", f"PM-{year}-00002", "--db",
                                _db(tmp_path), "--json"])
    changes = json.loads(shown.stdout)["changes"]
    assert {"what": "overall verdict", "old": "conformance proven",
            "new": "uncertainty zone"} in changes
    assert "VMC8-0043" in html and f"PM-{year}-00002" in html
    rows = json.loads(runner.invoke(app, ["certificate", "list", "--db", _db(tmp_path),
                                          "--json"]).stdout)
    by = {x["number"]: x for x in rows}
    assert by[f"PM-{year}-00001"]["status"] == "superseded"
    assert by[f"PM-{year}-00001"]["replaced_by"] == f"PM-{year}-00002"
    assert by[f"PM-{year}-00002"]["replaces"] == f"PM-{year}-00001"
    r = runner.invoke(app, ["certificate", "reissue", f"PM-{year}-00001", "--reason", "x",
                            "--out", str(tmp_path / "c4.html"), "--db", _db(tmp_path)])
    assert r.exit_code == 2 and "already superseded" in r.stderr
    assert not (tmp_path / "c4.html").exists()


@pytest.mark.parametrize("config, said", [
    (None, "AXISCAL_CONFIG names"),            # points at a file that does not exist
    ("", "is empty"),
    ("template", "still the template of 'axiscal config --init'"),
])
def test_draft_names_what_is_missing_and_exits_3(tmp_path, config, said):
    """A configuration absent, empty or still the template is said; the certificate is a DRAFT
    (exit 3, each missing item on stderr); with --draft the same page and exit 0."""
    from axiscal.io.user_config import TEMPLATE

    _setup(tmp_path)
    cfg = tmp_path / "config.toml"
    if config is None:
        cfg.unlink()
    else:
        cfg.write_text(TEMPLATE if config == "template" else config)
    r = _issue(tmp_path, "--report", str(tmp_path / "d.pdf"))
    assert r.exit_code == 3, r.output
    assert "is a DRAFT, not a certificate; missing:" in r.stderr and said in r.stderr
    texts = pdf_text(tmp_path / "d.pdf")
    assert all("DRAFT" in t for t in texts) and "not a certificate" in texts[0]
    r = _issue(tmp_path, "--report", str(tmp_path / "d.pdf"), "--draft")
    assert r.exit_code == 0 and said in r.stderr
    # a draft is not kept: the register was never made, and listing it makes none (issue 39)
    r = runner.invoke(app, ["certificate", "list", "--db", _db(tmp_path)])
    assert r.exit_code == 2 and "no history database" in r.stderr


def test_overdue_instrument_and_late_test_date(tmp_path):
    """An instrument due before the test: DRAFT naming it. A test dated after the date of issue:
    refused, one line, nothing written."""
    _setup(tmp_path, USER.replace("2099-04-30", "2020-01-01"))
    r = _issue(tmp_path, "--report", str(tmp_path / "d.html"))
    assert r.exit_code == 3 and "due 2020-01-01, overdue on the date of calibration" in r.stderr
    (tmp_path / "job.toml").write_text(JOB.replace('date = "2026-11-20"', 'date = "2999-01-01"'))
    r = _issue(tmp_path, "--report", str(tmp_path / "late.html"))
    assert r.exit_code == 2 and len(r.stderr.strip().splitlines()) == 1
    assert "date of test 2999-01-01 is after the date of issue" in r.stderr
    assert not (tmp_path / "late.html").exists()


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


def test_withdrawn_test_is_not_certified_and_show_marks_a_later_withdrawal(tmp_path):
    """Issue 38: 'certificate show' of a certificate whose test was withdrawn afterwards says
    so; the JSON carries test_withdrawn and the register's key, the laboratory's code."""
    _setup(tmp_path)
    year = __import__("datetime").date.today().year
    assert _issue(tmp_path, "--report", str(tmp_path / "c1.html")).exit_code == 0
    r = runner.invoke(app, ["history", "withdraw", "1", "--by", "QA", "--reason",
                            "reflector loose", "--db", _db(tmp_path)])
    assert r.exit_code == 0, r.output
    r = runner.invoke(app, ["certificate", "show", f"PM-{year}-00001", "--db", _db(tmp_path)])
    assert r.exit_code == 0 and "TEST WITHDRAWN after issue: reflector loose" in r.stdout
    assert "WARNING: the test of this certificate was withdrawn" in r.stdout
    d = json.loads(runner.invoke(app, ["certificate", "show", f"PM-{year}-00001", "--db",
                                       _db(tmp_path), "--laboratory", "PMG", "--json"]).stdout)
    assert d["test_withdrawn"] == "reflector loose" and d["laboratory"] == "PMG"
    assert d["laboratory_name"] == "Precision Metrology GmbH"
    r = runner.invoke(app, ["certificate", "reissue", f"PM-{year}-00001", "--reason", "x",
                            "--out", str(tmp_path / "c2.html"), "--db", _db(tmp_path)])
    assert r.exit_code == 2 and "is withdrawn (reflector loose)" in r.stderr


def test_a_date_of_issue_in_the_future_is_refused_and_nothing_kept(tmp_path):
    """Issue 38: '[certificate] issued = 2031-01-01' was numbered NKL-2031-00001 today. Now
    refused in one line (exit 2); no certificate, no file and no test kept."""
    _setup(tmp_path)
    (tmp_path / "job.toml").write_text(JOB + '\n[certificate]\nissued = "2031-01-01"\n'
                                       if "[certificate]" not in JOB else
                                       JOB.replace("[certificate]",
                                                   '[certificate]\nissued = "2031-01-01"'))
    r = _issue(tmp_path, "--report", str(tmp_path / "f.html"))
    assert r.exit_code == 2 and "date of issue 2031-01-01 is in the future" in r.stderr
    assert len(r.stderr.strip().splitlines()) == 1 and not (tmp_path / "f.html").exists()
    from axiscal.store import open_store

    s = open_store(_db(tmp_path))
    assert s.certificates() == [] and s.tests() == []
