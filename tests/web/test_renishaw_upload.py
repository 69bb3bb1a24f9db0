"""A Renishaw .rtl uploaded to the workbench: stored, evaluated, its conditions on the
certificate."""

from __future__ import annotations

import io
import re
import sys
from pathlib import Path

from fastapi.testclient import TestClient

from axiscal.web.app import create_app

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "io"))
from test_renishaw import (R1_DN, R1_UP, R2_DN, R2_UP, REAL_ENVIRONMENT, T7,  # noqa: E402
                           renishaw_text)


def test_rtl_upload_and_the_certificate_shows_the_files_conditions(tmp_path, monkeypatch):
    monkeypatch.setenv("AXISCAL_CONFIG", str(tmp_path / "none.toml"))
    user = {"Machine": "VMC 800", "Serial No": "", "Date": "2016-12-12 10:46:00", "By": "RJ",
            "Axis": "X", "Location": "", "TITLE": ""}
    raw = renishaw_text("rtl", T7, [R1_UP, R1_DN, R2_UP, R2_DN], user=user,
                        environment=REAL_ENVIRONMENT).encode()
    c = TestClient(create_app(f"sqlite:///{tmp_path / 'h.sqlite'}"),
                   base_url="http://127.0.0.1")
    tok = re.search(r'csrf-token" content="([^"]+)"', c.get("/").text).group(1)
    r = c.post("/upload", data={"csrf": tok},
               files={"file": ("x.rtl", raw, "application/octet-stream")})
    assert r.status_code == 200 and "/tests/1" in str(r.url), r.text[:500]
    pdf = c.get("/tests/1/certificate.pdf")
    assert pdf.status_code == 200
    from pypdf import PdfReader

    text = "".join(p.extract_text() for p in PdfReader(io.BytesIO(pdf.content)).pages)
    # the means of the file's start and end records (Paolico/AxisCorection's real lines)
    assert "VMC 800" in text and "20.3611" in text and "99044.2" in text, text[:2000]
