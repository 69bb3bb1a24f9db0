"""Sign-off in the workbench of a test that is not a positioning test (issue 40): the form is
offered only where the kind has an uncertainty budget (a diagonal squareness test here), its
verdict is the certificate's own call (:func:`axiscal.report.kind_certificate.
certificate_record` of the stored record), and a complete form ends in a numbered certificate;
a test of a kind without a budget has no form, and a sign-off posted for it is refused in one
line naming why; a ballbar test's form offers its G and H (the figures with U); a straightness
test (standards/iso230_9_straightness.py) shows U beside each figure and is signed off to a
numbered certificate."""

from __future__ import annotations

import re

import pytest
from fastapi.testclient import TestClient

from axiscal.web.app import create_app
from tests.report.test_kind_certificate import BALLBAR, DIAGONAL, STRAIGHTNESS, _without_budget
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


def test_a_diagonal_test_is_signed_off_and_a_kind_without_a_budget_is_not(client, tmp_path,
                                                                          monkeypatch):
    """Squareness 9.375 µm/m (tests/report/test_kind_certificate.py) against 20 µm/m:
    conformance proven, with the U the certificate prints; then issued and numbered. The
    straightness test, its kind made one without a budget (:func:`_without_budget`), has no
    form."""
    from axiscal.report.kind_certificate import certificate_record
    from axiscal.store import open_store

    _without_budget(monkeypatch, "straightness")

    page = client.get("/tests/1").text
    assert 'id="signoff-form"' in page and 'name="tol_squareness"' in page
    assert 'id="signoff-link"' in page and 'id="i-drift_check"' in page     # it reads E_VE
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
    from axiscal.store.kinds import with_uncertainty

    rec = st.get(1).record()                  # with the laboratory's E_VE (0.3 µm, LAB)
    rec = with_uncertainty(rec, {**rec.inputs, "e_ve": 0.3})
    f = certificate_record(rec, {"squareness": 20.0}).figures[0]
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


def test_a_straightness_test_shows_U_and_is_signed_off(client, tmp_path):
    """ISO 230-1:2012 straightness 1.8 µm (least squares) of tests/report/
    test_kind_certificate.py's file: the page states U beside each figure (the stored record's
    budget with the laboratory's E_VE, as the certificate's), the form offers the three figures,
    and a complete sign-off against 20 µm ends in a numbered certificate (not a DRAFT) stating
    the record's value and U."""
    from axiscal.report.kind_certificate import certificate_record
    from axiscal.store import open_store
    from tests.report.pdf_pages import pdf_text

    from axiscal.store.kinds import with_uncertainty

    st = open_store(f"sqlite:///{tmp_path / 'h.sqlite'}")
    rec = st.get(2).record()        # with the laboratory's declared E_VE (LAB: 0.3 µm), as the
    rec = with_uncertainty(rec, {**rec.inputs, "e_ve": 0.3})    # page and certificate state it
    page = client.get("/tests/2").text
    row = re.search(r'<table id="straightness">.*?<tbody>\s*<tr>(.*?)</tr>', page, re.S).group(1)
    assert f'<td class="num">{rec.budget.U_text("straightness")}</td>' in row, row
    assert f'<td class="num">{rec.budget.U_text("slope")}</td>' in row
    assert 'id="signoff-form"' in page
    for name in ("straightness", "straightness_min_zone", "slope"):
        assert f'name="tol_{name}"' in page
    r = client.post("/tests/2/signoff", data={"csrf": client.token, "action": "issue",
                                              "tol_straightness": "20", "date": "2026-11-20",
                                              **JOB}, follow_redirects=False)
    assert r.status_code == 303, r.text[-1500:]
    number = re.search(r"certificate=([^#&]+)", r.headers["location"]).group(1)
    doc = client.get(f"/tests/2/certificate?number={number}")
    assert doc.status_code == 200 and doc.content.startswith(b"%PDF")
    (tmp_path / "s.pdf").write_bytes(doc.content)
    text = " ".join(" ".join(pdf_text(tmp_path / "s.pdf")).split())
    f = next(f for f in certificate_record(rec, {"straightness": 20.0}).figures
             if f.name == "straightness")
    assert "DRAFT" not in text and number in text and st.certificate(number).test_id == 2
    assert f"{f.value_text} {f.U_text} 2 µm 20 conformance proven" in text, text[-1500:]
    top = client.get("/tests/2").text          # the certificate first, at the top of the page
    assert re.search(rf'<p class="pass" id="certified">Certified: <a href="[^"]+">certificate '
                     rf'{re.escape(number)}</a>', top)
    assert top.index('id="certified"') < top.index('id="key-figures"')


def test_a_motion_test_page_shows_U_beside_each_figure_and_offers_the_sign_off(client,
                                                                              tmp_path):
    """A five-motion-error test (ISO 230-7:2015; the shipped three-run file): each total,
    synchronous and asynchronous value on the page has the record's U beside it
    (:mod:`axiscal.standards.iso230_7_uncertainty`), its budget's contributors and inputs are
    listed, and the sign-off offers a tolerance for each figure; a verdict against radial Y
    total 10 µm (7.19 ± 0.19 µm) is conformance proven with the certificate's own U."""
    from axiscal.report.kind_certificate import certificate_record
    from axiscal.store import open_store
    from tests.report.test_kind_certificate import MOTION

    r = client.post("/upload", data={"csrf": client.token, "machine": "HSD-200RT", "axis": "C"},
                    files={"file": ("motion.csv", MOTION.read_bytes(), "text/csv")})
    assert r.status_code == 200, r.text[-500:]
    page = client.get("/tests/4").text
    rec = open_store(f"sqlite:///{tmp_path / 'h.sqlite'}").get(4).record()
    rows = {row[0]: row for row in _rows(page, "motion")}
    assert set(rows) == {"radial Y", "axial", "tilt X", "tilt Y"}
    for name, row in rows.items():
        key = name.replace(" ", "_")
        for i, fig in ((2, "total"), (4, "synchronous"), (6, "asynchronous")):
            assert row[i] == rec.budget.U_text(f"{key}_{fig}") != "—", (name, fig)
    assert rows["radial Y"][1:3] == ["7.187", "0.19"]
    contributors = [row[0] for row in _rows(page, "budget")]
    assert "u_RES,dy" in contributors and "u_REPEAT,dy" in contributors
    assert any(row[0] == "resolution of δy (radial Y)" and row[2] == "assumed"
               for row in _rows(page, "budget-inputs"))
    assert 'id="signoff-form"' in page and 'name="tol_radial_Y_total"' in page
    assert 'name="tol_tilt_Y_asynchronous"' in page

    r = client.post("/tests/4/signoff", data={"csrf": client.token, "action": "verdict",
                                              "tol_radial_Y_total": "10"})
    assert r.status_code == 200
    f = {g.name: g for g in certificate_record(rec, {"radial_Y_total": 10.0}).figures}
    row = re.search(r'<table id="verdicts">.*?<tbody>(.*?)</tbody>', r.text, re.S).group(1)
    assert f'<td class="num">{f["radial_Y_total"].U_text}</td>' in row
    assert "PASS: conformance proven" in row


def _rows(page: str, table_id: str) -> list[list[str]]:
    """The body cells of a table of the page, as text."""
    import html

    body = re.search(rf'<table id="{table_id}">.*?<tbody>(.*?)</tbody>', page, re.S).group(1)
    return [[html.unescape(re.sub(r"<[^>]+>", "", c)).strip()
             for c in re.findall(r"<td[^>]*>(.*?)</td>", tr, re.S)]
            for tr in re.findall(r"<tr>(.*?)</tr>", body, re.S)]


def test_a_diagonal_without_e_ve_is_a_draft_and_a_drift_check_gives_it(tmp_path, monkeypatch):
    """Review defect 3: a laboratory that declares no E_VE and no drift check: the diagonal's
    certificate is not issued, E_VE listed as missing (linked to the drift-check field), never
    "0 µm assumed"; with a drift check kept with the test (E_VE = 0.42 − (−0.18) = 0.60 µm,
    tests/web/test_signoff_history.py) it is issued and states E_VE 0.6 µm."""
    from tests.report.pdf_pages import pdf_text
    from tests.web.test_signoff_history import DRIFT

    cfg = tmp_path / "config.toml"
    cfg.write_text(LAB.split("[uncertainty]")[0], encoding="utf-8")
    monkeypatch.setenv("AXISCAL_CONFIG", str(cfg))
    c = TestClient(create_app(f"sqlite:///{tmp_path / 'h.sqlite'}"), base_url="http://127.0.0.1")
    tok = re.search(r'csrf-token" content="([^"]+)"', c.get("/").text).group(1)
    c.post("/upload", data={"csrf": tok, "machine": "VMC-800"},
           files={"file": ("diagonal.csv", DIAGONAL.encode(), "text/csv")})
    form = {"csrf": tok, "action": "issue", "tol_squareness": "20", "date": "2026-11-20", **JOB}
    r = c.post("/tests/1/signoff", data=form, follow_redirects=False)
    assert r.status_code == 200 and 'id="draft"' in r.text
    assert re.search(r'<a href="#f-drift_check">[^<]*</a>: E_VE', r.text)
    assert c.app.state.store.certificates() == []
    r = c.post("/tests/1/signoff", data=form, follow_redirects=False,
               files={"drift_check": ("drift.csv", DRIFT, "text/csv")})
    assert r.status_code == 303, r.text[-1500:]
    number = re.search(r"certificate=([^#&]+)", r.headers["location"]).group(1)
    (tmp_path / "c.pdf").write_bytes(c.get(f"/tests/1/certificate?number={number}").content)
    text = " ".join(" ".join(pdf_text(tmp_path / "c.pdf")).split())
    assert "DRAFT" not in text and "E_VE 0.6 µm" in text.replace("EVE", "E_VE"), text[-2500:]
    assert "E_VE 0 µm" not in text.replace("EVE", "E_VE")


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
