"""Sign-off in the workbench of a test that is not a positioning test (issue 40): the form is
offered only where the kind has an uncertainty budget (a diagonal squareness test here), its
verdict is the certificate's own call (:func:`axiscal.report.kind_certificate.
certificate_record` of the stored record), and a complete form ends in a numbered certificate;
a straightness test (no budget in axiscal) has no form, and a sign-off posted for it is
refused in one line naming why; a ballbar test's form offers its G and H (the figures with U)."""

from __future__ import annotations

import re

import pytest
from fastapi.testclient import TestClient

from axiscal.web.app import create_app
from tests.report.test_kind_certificate import BALLBAR, DIAGONAL, STRAIGHTNESS
from tests.web.test_signoff import JOB, LAB


@pytest.fixture
def client(tmp_path, monkeypatch):
    cfg = tmp_path / "config.toml"
    cfg.write_text(LAB, encoding="utf-8")
    monkeypatch.setenv("AXISCAL_CONFIG", str(cfg))
    c = TestClient(create_app(f"sqlite:///{tmp_path / 'h.sqlite'}"), base_url="http://127.0.0.1")
    c.token = re.search(r'csrf-token" content="([^"]+)"', c.get("/").text).group(1)
    for name, text in (("diagonal.csv", DIAGONAL), ("straightness.csv", STRAIGHTNESS),
                       ("ballbar.csv", BALLBAR)):
        r = c.post("/upload", data={"csrf": c.token, "machine": "VMC-800"},
                   files={"file": (name, text.encode(), "text/csv")})
        assert r.status_code == 200, r.text[-500:]
    return c


def test_a_diagonal_test_is_signed_off_and_a_straightness_test_is_not(client, tmp_path):
    """Squareness 9.375 µm/m (tests/report/test_kind_certificate.py) against 20 µm/m:
    conformance proven, with the U the certificate prints; then issued and numbered."""
    from axiscal.report.kind_certificate import certificate_record
    from axiscal.store import open_store

    page = client.get("/tests/1").text
    assert 'id="signoff-form"' in page and 'name="tol_squareness"' in page
    assert 'id="signoff-link"' in page and 'name="drift_check"' not in page
    assert 'name="air_temperature"' not in page
    straight = client.get("/tests/2").text
    assert 'id="signoff-form"' not in straight and 'id="signoff-link"' not in straight
    r = client.post("/tests/2/signoff", data={"csrf": client.token, "action": "verdict"})
    assert r.status_code == 400 and "no uncertainty budget for straightness tests in axiscal: " \
        in r.text
    ballbar = client.get("/tests/3").text       # G and H have U (iso230_9_ballbar)
    assert 'id="signoff-form"' in ballbar and 'name="tol_G_ccw"' in ballbar
    assert 'name="tol_H"' in ballbar and 'name="tol_residual_rms"' not in ballbar

    r = client.post("/tests/1/signoff", data={"csrf": client.token, "action": "verdict",
                                              "tol_squareness": "20"})
    assert r.status_code == 200
    st = open_store(f"sqlite:///{tmp_path / 'h.sqlite'}")
    f = certificate_record(st.get(1).record(), {"squareness": 20.0}).figures[0]
    row = re.search(r'<table id="verdicts">.*?<tbody>(.*?)</tbody>', r.text, re.S).group(1)
    assert f'<td class="num">{f.U_text}</td>' in row and f'<td class="num">{f.value:.3f}</td>' \
        in row and "PASS: conformance proven" in row

    r = client.post("/tests/1/signoff", data={"csrf": client.token, "action": "issue",
                                              "tol_squareness": "20", "date": "2026-11-20",
                                              **JOB}, follow_redirects=False)
    assert r.status_code == 303, r.text[-1500:]
    number = re.search(r"certificate=([^#&]+)", r.headers["location"]).group(1)
    doc = client.get(f"/tests/1/certificate?number={number}")
    assert doc.status_code == 200 and doc.content.startswith(b"%PDF")
    assert st.certificate(number).test_id == 1
    from tests.report.pdf_pages import pdf_text

    (tmp_path / "c.pdf").write_bytes(doc.content)
    text = " ".join(pdf_text(tmp_path / "c.pdf"))
    assert "DRAFT" not in text and number in text and "conformance proven" in text.lower()
    assert f"{f.value_text} {f.U_text} 2 µm/m 20" in " ".join(text.split()), text[-1500:]


def test_a_ballbar_sign_off_lists_the_ballbar_not_the_laboratorys_laser(client):
    """Issue 40: the laboratory keeps a laser interferometer; a ballbar test's form (and so
    its certificate) lists the test's own instrument, typed at upload, alone."""
    from axiscal.store.laboratory import set_laboratory

    set_laboratory(client.app.state.store, {"instrument": [
        {"name": "Laser interferometer", "serial": "L-77"},
        {"name": "QC20-W ballbar", "serial": "B-5", "certificate": "C-9"}]},
        by="eng", reason="instruments")
    r = client.post("/upload", data={"csrf": client.token, "machine": "VMC-800",
                                     "instrument": "QC20-W ballbar"},
                    files={"file": ("bb2.csv", (BALLBAR + "\n").encode(), "text/csv")})
    page = client.get(str(r.url).split("?")[0]).text
    value = {k: (re.search(rf'name="{k}" value="([^"]*)"', page) or [None, ""])[1]
             for k in ("instrument1_name", "instrument1_serial", "instrument2_name")}
    assert value == {"instrument1_name": "QC20-W ballbar", "instrument1_serial": "B-5",
                     "instrument2_name": ""}
