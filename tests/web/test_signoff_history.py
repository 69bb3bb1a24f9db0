"""Issue 40: a sign-off finished in the workbench alone. The laboratory and a drift check are
given on the form and kept in the history; the form starts from the stored test; the budget is
the stored test's (its inputs, the drift check's E_VE); and the certificate the workbench issues
carries, field by field, what ``axiscal iso230-2 FILE --job --drift-check --report --db``
issues for the same inputs. Then the register's rules: an amendment with a reason (the machine's
corrected name printed), no second issue, no certificate of a withdrawn test."""

from __future__ import annotations

import io
import re
from pathlib import Path

import pytest
from fastapi.testclient import TestClient
from typer.testing import CliRunner

from axiscal.web.app import create_app

ECMC = Path(__file__).resolve().parents[1] / "data" / "ecmc" / "mcu1025_fat_sat_ISO230.dat"
#: A drift check of the ESS test's set-up (µm): E_VE = 0.42 − (−0.18) = 0.60 µm.
DRIFT = b"time_s,reading\n0,0.05\n300,0.42\n600,-0.18\n900,0.11\n"
#: The server's user configuration: no laboratory in it (the history keeps it).
USER = '[certificate]\npaper = "A4"\n'
LAB_FORM = {"lab_name": "Präzision Messtechnik GmbH",
            "lab_address": "Werkstrasse 1\n70173 Stuttgart",
            "lab_code": "PM", "lab_signatories": "B. Signatory, Head of laboratory",
            "lab_cmc": "E=1.0, A=1.0"}
JOB_FORM = {"customer_name": "European Spallation Source ERIC",
            "customer_address": "Partikelgatan 2\n224 84 Lund",
            "machine_maker": "ESS", "machine_model": "MCU1025", "machine_serial": "m0s012",
            "machine_location": "ESS motion lab", "air_temperature": "20.4",
            "material_temperature": "20.6", "date": "2026-03-02",
            "instrument1_name": "Encoder IOC_TEST:m0s012-Enc01", "instrument1_serial": "E-1",
            "instrument1_certificate": "ESS-C-12", "instrument1_due": "2027-06-30",
            "operator": "A. Operator", "signatory": "B. Signatory",
            "signatory_role": "Head of laboratory", "specification": "ESS acceptance, ISO 230-2",
            "tol_E": "8", "tol_A": "10", "tol_R": "5"}
#: The same inputs as a job file of the command line.
JOB_TOML = """\
[company]
name = "Präzision Messtechnik GmbH"
address = ["Werkstrasse 1", "70173 Stuttgart"]
code = "PM"
[[signatory]]
name = "B. Signatory"
role = "Head of laboratory"
[uncertainty.linear]
cmc = { E = 1.0, A = 1.0 }
[customer]
name = "European Spallation Source ERIC"
address = ["Partikelgatan 2", "224 84 Lund"]
[machine]
name = "MCU1025 bench"
maker = "ESS"
model = "MCU1025"
serial = "m0s012"
location = "ESS motion lab"
[conditions]
date = "2026-03-02"
air_temperature = 20.4
material_temperature = 20.6
[[instrument]]
name = "Encoder IOC_TEST:m0s012-Enc01"
serial = "E-1"
certificate = "ESS-C-12"
due = "2027-06-30"
[operator]
name = "A. Operator"
[certificate]
signatory = "B. Signatory"
signatory_role = "Head of laboratory"
specification = "ESS acceptance, ISO 230-2"
"""


@pytest.fixture
def bench(tmp_path, monkeypatch):
    (tmp_path / "config.toml").write_text(USER, encoding="utf-8")
    monkeypatch.setenv("AXISCAL_CONFIG", str(tmp_path / "config.toml"))
    c = TestClient(create_app(f"sqlite:///{tmp_path / 'web.sqlite'}"),
                   base_url="http://127.0.0.1")
    c.token = re.search(r'csrf-token" content="([^"]+)"', c.get("/").text).group(1)
    r = c.post("/upload", data={"csrf": c.token, "machine": "MCU1025 bench",
                                "date": "2026-03-02",
                                "instrument": "Encoder IOC_TEST:m0s012-Enc01"},
               files={"file": (ECMC.name, ECMC.read_bytes(), "text/plain")})
    assert r.status_code == 200 and "/tests/1" in str(r.url)
    return c


def _sign(c, action, files=None, **fields):
    return c.post("/tests/1/signoff", data={"csrf": c.token, "action": action, **fields},
                  files=files, follow_redirects=False)


def _value(page: str, name: str) -> str:
    m = re.search(rf'name="{name}" value="([^"]*)"', page)
    return m.group(1) if m else ""


def _pdf_lines(data: bytes) -> list[str]:
    from pypdf import PdfReader

    return [ln.strip() for p in PdfReader(io.BytesIO(data)).pages
            for ln in p.extract_text().splitlines() if ln.strip()]


def test_workbench_certificate_is_the_command_lines(bench, tmp_path):
    """Same test file, laboratory, job, drift check and tolerances: the certificate the
    workbench issues and the one ``axiscal iso230-2 --report`` issues carry the same fields,
    line by line of the PDF (number, values, U, verdicts, E_VE, item, people), and the
    register keeps the same entries."""
    page = bench.get("/tests/1").text          # the form starts from the stored test
    assert _value(page, "date") == "2026-03-02"
    assert _value(page, "instrument1_name") == "Encoder IOC_TEST:m0s012-Enc01"
    r = _sign(bench, "issue", files={"drift_check": ("drift.csv", DRIFT, "text/csv")},
              **LAB_FORM, **JOB_FORM)
    assert r.status_code == 303, r.text[-3000:]
    assert r.headers["location"].startswith("/tests/1?certificate=PM-")
    st = bench.app.state.store
    web = st.certificate(st.certificates()[0].number)

    from axiscal.cli import app

    (tmp_path / "job.toml").write_text(JOB_TOML, encoding="utf-8")
    (tmp_path / "drift.csv").write_bytes(DRIFT)
    out = CliRunner().invoke(app, [
        "iso230-2", str(ECMC), "--job", str(tmp_path / "job.toml"), "--drift-check",
        str(tmp_path / "drift.csv"), "--tolerance", "E=8", "--tolerance", "A=10",
        "--tolerance", "R=5", "--report", str(tmp_path / "cli.pdf"), "--db",
        f"sqlite:///{tmp_path / 'cli.sqlite'}"])
    assert out.exit_code in (0, 1), out.output            # 1: a tolerance not met
    from axiscal.store import open_store

    cli_store = open_store(f"sqlite:///{tmp_path / 'cli.sqlite'}")
    cli = cli_store.certificate(cli_store.certificates()[0].number)
    for field in ("number", "laboratory", "laboratory_name", "customer", "issued",
                  "prepared_by", "approved_by", "approved_role", "status", "media_type"):
        assert getattr(web, field) == getattr(cli, field), field
    w_unc, c_unc = web.inputs["config"]["uncertainty"], cli.inputs["config"]["uncertainty"]
    assert w_unc == c_unc and w_unc["e_ve"] == pytest.approx(0.60)
    assert web.inputs["tolerances"] == cli.inputs["tolerances"] == {"E": 8.0, "A": 10.0,
                                                                    "R": 5.0}
    w_lines, c_lines = _pdf_lines(web.document), _pdf_lines(cli.document)
    assert len(w_lines) == len(c_lines)
    # the one difference allowed: the history keeps an axis name in capitals (the command
    # line prints the file's "IOC_TEST:Axis1-PosSet"); issue 40's names part, not the numbers
    diff = [(a, b) for a, b in zip(w_lines, c_lines) if a != b]
    assert all(a.upper() == b.upper() and ("AXIS1" in a or "POSSET" in a) for a, b in diff), diff
    text = "\n".join(w_lines)
    assert "EVE = 0.6 µm (drift check)" in text and "DRAFT" not in text
    assert "ESS MCU1025 (MCU1025 bench)" in text


def test_amendment_carries_the_corrected_name_and_the_register_rules_hold(bench):
    """Also: the laboratory's fields are refused in their label's words, kept in the history
    when a certificate is issued with them (an audit entry), and start the next form."""
    from axiscal.store.corrections import audit
    from axiscal.store.laboratory import laboratory

    st = bench.app.state.store
    r = _sign(bench, "verdict", tol_E="8", lab_cmc="E:1")
    assert r.status_code == 400
    assert "CMC [µm] (the laboratory&#39;s least U per parameter" in r.text
    r = _sign(bench, "issue", files={"drift_check": ("drift.csv", DRIFT, "text/csv")},
              **LAB_FORM, **JOB_FORM)
    assert r.status_code == 303
    assert laboratory(st)["company"] == {"name": LAB_FORM["lab_name"], "code": "PM",
                                         "address": ["Werkstrasse 1", "70173 Stuttgart"]}
    assert laboratory(st)["uncertainty"]["linear"]["cmc"] == {"E": 1.0, "A": 1.0}
    a = next(x for x in audit(st) if x.action == "laboratory")
    assert (a.by, a.reason) == ("A. Operator", "used for certificate PM-2026-00001 of test 1")
    assert next(x for x in audit(st) if x.action == "drift-check").new["e_ve"] == 0.6
    page = bench.get("/tests/1").text                       # the form starts from it now
    assert _value(page, "lab_name") == LAB_FORM["lab_name"]
    for name in ("customer_name", "machine_serial", "air_temperature", "instrument1_due"):
        assert _value(page, name) == JOB_FORM[name], name     # and from its certificate
    r = bench.post("/upload", data={"csrf": bench.token, "machine": "MCU1025 bench",
                                    "date": "2026-09-14"},   # the next test of the machine
                   files={"file": ("again.dat", ECMC.read_bytes() + b"\n", "text/plain")})
    assert "/tests/2" in str(r.url)
    page = bench.get("/tests/2").text     # the machine's last certificate; its own date
    assert (_value(page, "customer_name"), _value(page, "date"),
            _value(page, "air_temperature")) == (JOB_FORM["customer_name"], "2026-09-14", "")
    assert _value(page, "lab_cmc") == "E=1, A=1"
    first = st.certificates()[0].number
    page = bench.get(f"/tests/1?certificate={first}").text
    assert 'id="issue-amendment"' in page and 'id="issue-certificate"' not in page
    # a second issue is refused in the form's words; an amendment needs its reason
    r = _sign(bench, "issue", **LAB_FORM, **JOB_FORM)
    assert r.status_code == 400 and "a second certificate is an amendment" in r.text
    r = _sign(bench, "amend", **LAB_FORM, **JOB_FORM)
    assert "Reason for the amendment: say why" in r.text and len(st.certificates()) == 1
    # the machine's name corrected in the history (audit-trailed), then the amendment
    from axiscal.store.corrections import rename_machine

    rename_machine(st, "MCU1025 bench", "ESS MCU1025 test stand", by="eng",
                   reason="the stand's name in the ESS register")
    r = _sign(bench, "amend", **LAB_FORM, **JOB_FORM,
              amend_reason="machine name corrected")
    assert r.status_code == 303, r.text[-3000:]
    recs = {c.number: c for c in st.certificates()}
    new = next(c for c in recs.values() if c.replaces == first)
    assert recs[first].status == "superseded" and new.reason == "machine name corrected"
    text = " ".join(_pdf_lines(st.certificate(new.number).document))   # lines wrap
    assert "Machine ESS MCU1025 (ESS MCU1025 test stand)" in text
    assert "machine name corrected" in text and first in text
    assert "Machine: MCU1025 bench → ESS MCU1025 test stand" in text    # its label, no key
    assert "[machine]" not in text and "[company]" not in text
    # the test page's preview (DRAFT) is the sign-off's certificate as its form stands now: the
    # laboratory, item, date and instrument of the certificate just issued (defect 6: it read
    # the server's configuration and the file's names alone)
    preview = _pdf_lines(bench.get("/tests/1/certificate.pdf").content)
    issued = _pdf_lines(st.certificate(new.number).document)
    assert "DRAFT" in preview[0] and "[company]" not in " ".join(preview)
    assert _section(preview) == _section(issued)
    assert "ESS MCU1025 test stand" in " ".join(_section(preview))
    # the axis renamed in the history, then an amendment: it names the axis as the history does
    # now (it kept the certificate's first axis: only the machine's name was carried)
    from axiscal.store.corrections import rename_axis

    old_axis = st.get(1).summary.axis
    rename_axis(st, "ESS MCU1025 test stand", old_axis, "X", by="eng",
                reason="the stand's axis is its X")
    r = _sign(bench, "amend", **LAB_FORM, **JOB_FORM, amend_reason="axis named X")
    assert r.status_code == 303, r.text[-3000:]
    newest = next(c for c in st.certificates() if c.replaces == new.number)
    text = " ".join(_pdf_lines(st.certificate(newest.number).document))
    assert f"Axis: {old_axis} → X" in text, text[-2500:]
    # a withdrawn test is never certified: no button, and the register's refusal in words
    from axiscal.store.corrections import withdraw

    withdraw(st, 1, by="eng", reason="encoder cable loose")
    page = bench.get("/tests/1").text
    assert 'id="signoff-withdrawn"' in page and 'id="issue-amendment"' not in page
    r = _sign(bench, "amend", **LAB_FORM, **JOB_FORM, amend_reason="again")
    assert r.status_code == 400 and "a withdrawn test is never certified" in r.text
    assert len(st.certificates()) == 3


def _section(lines: list[str]) -> list[str]:
    """A certificate's laboratory, its "Customer and item calibrated" section, date of test and
    first instrument, the number and date of issue left out (a preview has neither)."""
    start = lines.index("Customer and item calibrated")
    end = next(i for i, ln in enumerate(lines) if ln.startswith("Test conditions"))
    lab = [ln for ln in lines[:start] if ln in (LAB_FORM["lab_name"], "Werkstrasse 1")]
    item = [re.sub(r"Certificate number .*", "", ln) for ln in lines[start + 1:end]]
    date = [m.group(0) for ln in lines if (m := re.search(r"Date of test \S+", ln))]
    inst = [ln for ln in lines if JOB_FORM["instrument1_name"] in ln]
    return lab + item + date + inst[:1]


def test_laboratory_page_edits_what_the_history_keeps(bench):
    """The laboratory page: shown from the configuration until kept; an engineer's change needs
    a reason and is an audit entry; an emptied field removes its value."""
    from axiscal.store.corrections import audit
    from axiscal.store.laboratory import laboratory

    st = bench.app.state.store
    assert "Not kept in the history yet" in bench.get("/laboratory").text
    form = {"csrf": bench.token, **LAB_FORM, "instrument1_name": "Laser XL-80",
            "instrument1_due": "2027-01-31", "by": "A. Operator"}
    r = bench.post("/laboratory", data=form, follow_redirects=False)
    assert r.status_code == 400 and "Reason: say why the laboratory changes" in r.text
    assert 'value="Präzision Messtechnik GmbH"' in r.text and laboratory(st) == {}
    r = bench.post("/laboratory", data={**form, "reason": "accreditation renewed"},
                   follow_redirects=False)
    assert r.status_code == 303
    lab = laboratory(st)
    assert lab["signatory"] == [{"name": "B. Signatory", "role": "Head of laboratory"}]
    assert lab["instrument"] == [{"name": "Laser XL-80", "due": "2027-01-31"}]
    r = bench.post("/laboratory", data={**form, "lab_signatories": "", "reason": "left"},
                   follow_redirects=False)
    assert r.status_code == 303 and "signatory" not in laboratory(st)
    page = bench.get("/laboratory?saved=1").text
    assert 'id="saved"' in page and "accreditation renewed" in page
    assert [a.reason for a in audit(st) if a.action == "laboratory"] == \
        ["left", "accreditation renewed"]


def test_messages_speak_the_forms_words():
    """The library's words of a job file become the form's labels (issue 40: "[customer] name",
    "--uncertainty e_ve=VALUE" and "--by NAME" were shown on the page)."""
    from axiscal.web.signoff_form import missing_fields, plain

    assert plain("[customer] name: the character '☃' (U+2603, SNOWMAN) is in no font") == \
        "Customer: the character '☃' (U+2603, SNOWMAN) is in no font"
    assert plain("date of calibration (not in the data file; give [conditions] date)") == \
        "date of calibration"
    items = ["input of the uncertainty budget: environmental variation error E_VE (not given, "
             "so U leaves it out: declare it with --uncertainty e_ve=VALUE)",
             "calibration due date of the instrument 'Laser'",
             "name of the person who prepared the certificate ([operator] name)",
             "approval by an authorised signatory: 'eng' is not one of the laboratory's "
             "(B. Signatory; [[signatory]] name and role)"]
    out = missing_fields(items, {"instrument2_name": "Laser"}, signed_in=True)
    assert [(label, anchor) for label, anchor, _ in out] == [
        ("Drift check file (E_VE measured beside this test)", "f-drift_check"),
        ("Instrument 2: due (YYYY-MM-DD)", "f-instrument2_due"),
        ("Operator (carried out the test)", "f-operator"),
        ("Authorised signatories (one a line: name, role)", "f-lab_signatories")]
    for _, _, words in out:
        assert "[" not in words and "--" not in words and "VALUE" not in words, words
