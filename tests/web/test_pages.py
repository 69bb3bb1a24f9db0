"""Workbench pages with the calibration certificate's numbers (issues 14 and 15)."""

from __future__ import annotations

import io
import re

from fastapi.testclient import TestClient

from axiscal.standards.iso230_2 import evaluate
from axiscal.standards.iso230_9 import positioning_budget, round_up
from axiscal.web.app import create_app
from tests.web.conftest import positioning_file as _file


def test_test_page_shows_U_and_the_pdf_certificate_downloads(tmp_path, monkeypatch):
    monkeypatch.setenv("AXISCAL_CONFIG", str(tmp_path / "none.toml"))
    c = TestClient(create_app(f"sqlite:///{tmp_path / 'h.sqlite'}"),
                   base_url="http://127.0.0.1")
    tok = re.search(r'csrf-token" content="([^"]+)"', c.get("/").text).group(1)
    r = c.post("/upload", data={"csrf": tok}, files={"file": ("x.csv", _file(), "text/csv")})
    assert r.status_code == 200 and "/tests/1" in str(r.url)
    from axiscal.io import parse_positioning

    ds = parse_positioning(_file().decode(), "x.csv")
    u_e = positioning_budget(ds, evaluate(ds)).U("E")   # shown rounded up, 2 significant digits
    assert "U (k = 2)" in r.text and f'<td class="num">{round_up(u_e):.1f}</td>' in r.text
    pdf = c.get("/tests/1/certificate.pdf")
    assert pdf.status_code == 200 and pdf.content.startswith(b"%PDF")
    from pypdf import PdfReader

    text = "".join(p.extract_text() for p in PdfReader(io.BytesIO(pdf.content)).pages)
    assert "page 1 of" in text and "VMC-800" in text
    assert c.get("/tests/1/certificate.pdf?paper=Legal").status_code == 400


def test_test_page_shows_every_standard_and_its_report_downloads(tmp_path, monkeypatch):
    """A positioning test's page lists the other standards' parameters under their own names,
    the ones not evaluated with the reason, and offers the report by every standard."""
    monkeypatch.setenv("AXISCAL_CONFIG", str(tmp_path / "none.toml"))
    c = TestClient(create_app(f"sqlite:///{tmp_path / 'h.sqlite'}"),
                   base_url="http://127.0.0.1")
    tok = re.search(r'csrf-token" content="([^"]+)"', c.get("/").text).group(1)
    page = c.post("/upload", data={"csrf": tok}, files={"file": ("x.csv", _file(), "text/csv")})
    assert page.status_code == 200
    from axiscal.io import parse_positioning
    from axiscal.standards import vdi3441

    ds = parse_positioning(_file().decode(), "x.csv")
    params = page.text.split('id="parameters"')[1].split("</table>")[0]
    assert "jis-b6192:R" not in params  # the ISO 230-2:2014 table keeps its own parameters
    # by the symbols of ISO 230-2:2014 clause 3, the key (for history trend) in the cell's title
    assert ">A↑</td>" in params and ">B̄</td>" in params and ">A_up</td>" not in params
    assert 'title="A_up (the name axiscal history trend --parameter takes)"' in params
    # the uncertainty's assumptions one to a line, not one paragraph
    notes = page.text.split('id="budget-notes">')[1].split("</ul>")[0]
    assert notes.count("<li>") >= 3 and "assumed" in notes
    others = page.text.split('id="standards"')[1].split("</table>")[0]
    assert "VDI/DGQ 3441" in others and f"{vdi3441.evaluate(ds).Pa:.3f}" in others
    assert "position scatter: not evaluated" in others and "ISO 230-2:1988" in others
    assert "NMTBA" in page.text.split('id="standards"')[1]
    rep = c.get("/tests/1/standards.html")
    assert rep.status_code == 200 and "by every positioning standard" in rep.text
    assert "Rexroth R310DE" in rep.text and "<svg" in rep.text
