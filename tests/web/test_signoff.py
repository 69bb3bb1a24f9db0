"""Sign-off in the workbench (issue 31): tolerances and the job on the test page, the ISO 14253-1
verdict by the library's :func:`axiscal.report.issue.sign_off` (the command line's), a
certificate numbered by the history's register, listed with its SHA-256 and downloadable."""

from __future__ import annotations

import hashlib
import re

import pytest
from fastapi.testclient import TestClient

from axiscal.web.app import create_app
from tests.web.conftest import positioning_file as data_file   # E about 10.6 µm

LAB = """\
[company]
name = "Präzision Messtechnik GmbH"
address = ["Werkstrasse 1", "70173 Stuttgart"]
code = "PM"
[uncertainty]
e_ve = 0.3
e_ve_source = "declared"
"""
#: The job of cli/demo.py's job file, as the form carries it (plus the instrument, operator and
#: signatory that job file leaves to the user configuration).
JOB = {"customer_name": "Example Machining AG",
       "customer_address": "Industriestrasse 4\n73728 Esslingen",
       "machine_maker": "Example", "machine_model": "VMC-800", "machine_serial": "VMC8-0042",
       "machine_location": "Hall 2, cell 5",
       "air_temperature": "20.3", "material_temperature": "20.5",
       "instrument1_name": "Laser interferometer", "instrument1_serial": "L-77",
       "instrument1_certificate": "DKD-1234", "instrument1_due": "2027-01-31",
       "operator": "A. Operator", "signatory": "B. Signatory",
       "signatory_role": "Head of laboratory",
       "specification": "Purchase order 4711 (positioning tolerances of the VMC-800 acceptance)"}


@pytest.fixture
def client(tmp_path, monkeypatch):
    cfg = tmp_path / "config.toml"
    cfg.write_text(LAB, encoding="utf-8")
    monkeypatch.setenv("AXISCAL_CONFIG", str(cfg))
    c = TestClient(create_app(f"sqlite:///{tmp_path / 'h.sqlite'}"), base_url="http://127.0.0.1")
    c.token = re.search(r'csrf-token" content="([^"]+)"', c.get("/").text).group(1)
    r = c.post("/upload", data={"csrf": c.token},
               files={"file": ("x.csv", data_file(), "text/csv")})
    assert r.status_code == 200 and str(r.url).endswith("/tests/1?stored=new")
    return c


def _sign(c, action="verdict", **fields):
    return c.post("/tests/1/signoff", data={"csrf": c.token, "action": action, **fields},
                  follow_redirects=False)


def _library_signoff(tolerances, job_cfg):
    """The verdict as the command line computes it (report.issue.sign_off)."""
    from axiscal.io import parse_positioning
    from axiscal.io.user_config import load_user_config, merge
    from axiscal.report.issue import sign_off
    from axiscal.standards.iso230_2 import evaluate

    ds = parse_positioning(data_file().decode(), "x.csv")
    return sign_off(ds, evaluate(ds), merge(load_user_config(), job_cfg), tolerances)


def test_test_page_has_the_form_and_no_certificate_yet(client):
    page = client.get("/tests/1").text
    assert 'id="signoff-form"' in page and 'name="tol_E"' in page and 'name="tol_A"' in page
    assert 'name="customer_name"' in page and 'name="instrument1_due"' in page
    assert 'id="no-certificates"' in page


def test_verdict_is_the_libraries(client):
    """Per parameter and overall, the same outcomes and U as report.issue.sign_off (A 11.89,
    E 9.96, R 5.43 µm; U of A and E 2.5 µm, of R 0.17 µm): PASS, FAIL and ZONE all shown."""
    tol = {"A": 2.0, "E": 15.0, "R": 5.5}
    so = _library_signoff(tol, {"conditions": {"material_temperature": 20.5}})
    assert [d.outcome.short for d in so.decisions] == ["FAIL", "PASS", "ZONE"]
    r = _sign(client, tol_A="2", tol_E="15", tol_R="5.5", material_temperature="20.5")
    assert r.status_code == 200
    table = r.text[r.text.index('id="verdicts"'):]
    for d in so.decisions:
        row = re.search(rf"<tr><td>{d.parameter}</td>(.*?)</tr>", table).group(1)
        assert f"{d.outcome.short}: {d.outcome.value}" in row
        assert f'<td class="num">{so.budget.U_text(d.parameter)}</td>' in row
        assert f'<td class="num">{d.value:.3f}</td>' in row
    assert 'Overall: <strong class="fail">FAIL: non-conformance proven' in r.text
    # A = 2 µm is not larger than its U: the warning of iso14253_1.unprovable, word for word
    assert so.warnings and so.warnings[0] in r.text.replace("&#39;", "'")
    plot = re.search(r'<script type="application/json" id="signoff-plot-1">(.*?)</script>',
                     r.text, re.S).group(1)
    assert "tolerance E = 15 (PASS), upper" in plot and "tolerance A = 2 (FAIL), lower" in plot
    assert "#1e7b34" in plot and "#d62728" in plot and "readings" in plot and "+ 2s" in plot


def test_a_bad_tolerance_is_named_on_the_page(client):
    r = _sign(client, tol_E="ten")
    assert r.status_code == 400 and "tolerance E = &#39;ten&#39;: not a number" in r.text
    r = _sign(client, air_temperature="900")
    assert "air temperature [°C] = 900: give a number from -50 to 100" in r.text


def test_htmx_gets_the_section_alone_with_its_error(client):
    """htmx swaps only 2xx answers: the section comes back 200 with the error in it."""
    r = client.post("/tests/1/signoff", data={"csrf": client.token, "tol_Q": "1",
                                              "tol_E": "-3"}, headers={"HX-Request": "true"})
    assert r.status_code == 200 and "<html" not in r.text and 'id="signoff-body"' in r.text
    assert 'id="signoff-error"' in r.text and "tolerance E = -3: give a number from 0" in r.text


def test_incomplete_job_is_not_numbered_and_names_what_is_missing(client):
    r = _sign(client, "issue", tol_E="15", customer_name="Example Machining AG")
    assert r.status_code == 200 and 'id="draft"' in r.text
    # issue 40: each item by its field's label, linked to the field; no file's or option's words
    assert '<a href="#f-customer_address">Customer address (one line each)</a>: customer ' \
        'address' in r.text
    assert '<a href="#f-machine_serial">Serial number</a>: serial number of the machine ' \
        'calibrated' in r.text
    assert 'id="f-machine_serial"' in r.text
    draft = r.text[r.text.index('id="draft"'):r.text.index("no number was taken")]
    for words in ("[customer]", "[machine]", "--uncertainty", "--by", "[[", "axiscal config"):
        assert words not in draft, words
    assert client.get("/tests/1").text.count('id="no-certificates"') == 1


def test_complete_job_issues_a_numbered_certificate_listed_with_its_sha256(client):
    r = _sign(client, "issue", tol_E="15", tol_A="20", **JOB)
    assert r.status_code == 303, r.text[-2000:]
    assert r.headers["location"] == "/tests/1?certificate=PM-2026-00001#signoff"
    page = client.get(r.headers["location"]).text
    row = re.search(r'<table id="certificates">.*?<tbody>(.*?)</tbody>', page, re.S).group(1)
    assert "<td>PM-2026-00001</td>" in row and "Example Machining AG" in row
    sha = re.search(r"<code>([0-9a-f]{64})</code>", row).group(1)
    doc = client.get("/tests/1/certificate?number=PM-2026-00001")
    assert doc.status_code == 200 and doc.content.startswith(b"%PDF")
    assert hashlib.sha256(doc.content).hexdigest() == sha
    # issue 38: a second certificate of the same test is refused (an amendment is a reissue)
    r2 = _sign(client, "issue", tol_E="15", **JOB)
    assert r2.status_code == 400
    assert "a second certificate is an amendment" in r2.text
    assert client.get("/tests/1/certificate?number=PM-2026-00002").status_code == 404


def test_htmx_issue_answers_with_a_redirect_header(client):
    r = client.post("/tests/1/signoff", data={"csrf": client.token, "action": "issue", **JOB},
                    headers={"HX-Request": "true"})
    assert r.status_code == 200 and r.headers["HX-Redirect"].startswith(
        "/tests/1?certificate=PM-2026-00001")


def test_signoff_needs_the_csrf_token(client):
    r = client.post("/tests/1/signoff", data={"csrf": "wrong", "action": "issue", **JOB})
    assert r.status_code == 403 and "CSRF" in r.text
    assert 'id="no-certificates"' in client.get("/tests/1").text


def test_a_viewer_sees_certificates_but_cannot_sign_off(tmp_path, monkeypatch, users):
    from tests.web.conftest import log_in

    cfg = tmp_path / "config.toml"
    cfg.write_text(LAB, encoding="utf-8")
    monkeypatch.setenv("AXISCAL_CONFIG", str(cfg))
    c = TestClient(create_app(f"sqlite:///{tmp_path / 'h.sqlite'}", users, require_login=True),
                   base_url="http://127.0.0.1")
    log_in(c, "eng", "correct horse battery")
    tok = re.search(r'csrf-token" content="([^"]+)"', c.get("/").text).group(1)
    c.post("/upload", data={"csrf": tok}, files={"file": ("x.csv", data_file(), "text/csv")})
    c.cookies.clear()
    log_in(c, "view", "staple battery horse")
    page = c.get("/tests/1").text
    assert 'id="no-certificates"' in page and 'id="signoff-form"' not in page
    tok = re.search(r'csrf-token" content="([^"]+)"', page).group(1)
    r = c.post("/tests/1/signoff", data={"csrf": tok, "action": "issue", **JOB})
    assert r.status_code == 403 and "viewer" in r.text
    assert 'id="no-certificates"' in c.get("/tests/1").text


def _rotary_file() -> bytes:
    """A rotary ISO 230-2 test of the C axis of the same machine VMC-800 (deg, arcsec)."""
    import numpy as np

    from axiscal.datasets import Metadata, PositioningDataset
    from axiscal.io.csv import format_positioning_csv

    rng = np.random.default_rng(3)
    t = np.linspace(0, 315, 8)
    up = rng.normal(2.0, 0.8, (8, 5))
    return format_positioning_csv(PositioningDataset(
        "rotary", t, up, up - 3.0, "deg", "arcsec",
        Metadata(machine="VMC-800", axis="C", date="2026-03-02"))).encode()


def test_tolerances_prefill_only_from_the_same_axis_and_kind(client):
    """Review defect 2: after a certificate of VMC-800 X with E ≤ 30 µm, a rotary C test of
    VMC-800 starts with no tolerance of E (30 would be arcsec there); a second X test of the
    machine starts with E = 30 (the same axis and kind), and both start from the certificate's
    customer."""
    assert _sign(client, "issue", tol_E="30", **JOB).status_code == 303
    r = client.post("/upload", data={"csrf": client.token},
                    files={"file": ("c.csv", _rotary_file(), "text/csv")})
    assert str(r.url).endswith("/tests/2?stored=new"), r.url
    page = client.get("/tests/2").text
    assert re.search(r'name="tol_E" value=""', page)
    assert 'name="customer_name" value="Example Machining AG"' in page
    again = data_file().replace(b"2026-03-01", b"2026-03-05")   # another test of X
    assert again != data_file()
    r = client.post("/upload", data={"csrf": client.token},
                    files={"file": ("x2.csv", again, "text/csv")})
    assert str(r.url).endswith("/tests/3?stored=new"), r.url
    assert 'name="tol_E" value="30"' in client.get("/tests/3").text
