"""The workbench's squareness from two stored straightness tests kept as a test (issue 40): the
"Keep as a test" form (POST, CSRF-checked, an engineer's) stores the squareness as a test of kind
``squareness`` whose numbers are the page's (one evaluation), links the two straightness tests it
came from, and offers its report and sign-off; a post without the token or by a viewer stores
nothing.

The trajectories are the project's examples (``examples/squareness_L180_*.csv``, Chapman,
Calibration of machine squareness, machine 1, L set-up at 180°)."""

from __future__ import annotations

import re
from pathlib import Path

import pytest
from fastapi.testclient import TestClient

from axiscal.store import open_store
from axiscal.web.app import create_app
from tests.web.conftest import log_in
from tests.web.test_signoff import LAB

EXAMPLES = Path(__file__).resolve().parents[2] / "examples"
FORM = {"first": "1", "second": "2", "config": "L", "orientation": "180", "prism_error": "2",
        "reference": "least_squares", "square": "optics"}


def _upload(c, token):
    for name in ("squareness_L180_x.csv", "squareness_L180_y.csv"):
        r = c.post("/upload", data={"csrf": token, "machine": "VMC-800",
                                    "date": "2026-11-20"},
                   files={"file": (name, (EXAMPLES / name).read_bytes(), "text/csv")})
        assert r.status_code == 200, r.text[-500:]


def _token(c, path="/") -> str:
    return re.search(r'csrf-token" content="([^"]+)"', c.get(path).text).group(1)


@pytest.fixture
def client(tmp_path, monkeypatch):
    cfg = tmp_path / "config.toml"
    cfg.write_text(LAB + "[squareness_uncertainty]\nsquare_error = 1.0\n", encoding="utf-8")
    monkeypatch.setenv("AXISCAL_CONFIG", str(cfg))
    c = TestClient(create_app(f"sqlite:///{tmp_path / 'h.sqlite'}"), base_url="http://127.0.0.1")
    c.token = _token(c)
    _upload(c, c.token)
    c.url = f"sqlite:///{tmp_path / 'h.sqlite'}"
    return c


def _figures(html: str) -> tuple[str, str]:
    """The squareness and its U as the squareness page shows them."""
    value = re.search(r'id="squareness-value">([^<]+)<', html).group(1)
    U = re.search(r"U \(k = 2\) = ([^<]+)<", html).group(1)
    return value, U


def test_keep_stores_the_page_result_linked_to_its_two_tests(client):
    """The kept test's record is the page's evaluation: the squareness the page shows, its U
    with the configuration's inputs (square error 1 arcsec given), every option; its page
    names and links tests 1 and 2, shows the figure and budget and offers the sign-off."""
    page = client.get("/squareness", params=FORM).text
    assert 'id="squareness-keep"' in page and 'name="csrf"' in page
    value, U = _figures(page)
    r = client.post("/squareness/keep", data={"csrf": client.token, **FORM},
                    follow_redirects=False)
    assert r.status_code == 303, r.text[-800:]
    assert r.headers["location"] == "/tests/3?kept=squareness#made-from"
    st = open_store(client.url)
    t = st.get(3)
    rec = t.record()
    assert (t.summary.kind, t.summary.machine, t.summary.axis) == ("squareness", "VMC-800", "XY")
    assert t.summary.tested_at.strftime("%Y-%m-%d") == "2026-11-20" and t.summary.date_known
    q = t.result["quantities"]["squareness"]
    assert f"{q['value']:+.2f}" == value and rec.budget.U_text("squareness") == U.strip()
    assert t.result["uncertainty_inputs"] == {"square_error": 1.0}
    assert (t.result["config"], t.result["orientation"], t.result["prism_error_arcsec"]) == \
        ("L", 180, 2.0)
    assert rec.dataset.sha256 == (st.get(1).sha256, st.get(2).sha256)
    shown = client.get("/tests/3?kept=squareness").text
    made = re.search(r'<div class="card" id="made-from">(.*?)</div>', shown, re.S).group(1)
    assert '<a href="/tests/1">straightness test 1</a> (axis X' in made
    assert '<a href="/tests/2">straightness test 2</a> (axis Y' in made
    assert 'id="kind-figure"' in shown and '<table id="biaxial">' in shown
    assert '<table id="budget">' in shown and 'id="signoff-form"' in shown
    assert 'name="tol_squareness"' in shown
    rows = re.search(r'<table id="biaxial">.*?<tbody>(.*?)</tbody>', shown, re.S).group(1)
    assert f"<td class=\"num\">{q['value']:.3f}</td>" in rows
    report = client.get("/tests/3/report.html")
    assert report.status_code == 200 and "Squareness, bi-axial L 180°" in report.text
    again = client.post("/squareness/keep", data={"csrf": client.token, **FORM},
                        follow_redirects=False)          # the same bytes: the same test
    assert again.headers["location"].startswith("/tests/3?") and len(st.tests()) == 3
    st.close()


def test_the_kept_test_is_signed_off_with_the_record_u(client):
    """The sign-off's verdict of the kept test states the certificate record's value and U
    (:func:`axiscal.report.kind_certificate.certificate_record`), ISO 14253-1 against 100
    µm/m."""
    from axiscal.report.kind_certificate import certificate_record

    client.post("/squareness/keep", data={"csrf": client.token, **FORM})
    r = client.post("/tests/3/signoff", data={"csrf": client.token, "action": "verdict",
                                              "tol_squareness": "100"})
    assert r.status_code == 200, r.text[-800:]
    st = open_store(client.url)
    f = certificate_record(st.get(3).record(), {"squareness": 100.0}).figures[0]
    st.close()
    row = re.search(r'<table id="verdicts">.*?<tbody>(.*?)</tbody>', r.text, re.S).group(1)
    assert f'<td class="num">{f.U_text}</td>' in row and "conformance proven" in row.lower()


def test_keep_without_the_token_or_by_a_viewer_stores_nothing(client, tmp_path, users,
                                                              monkeypatch):
    r = client.post("/squareness/keep", data=FORM)                    # no CSRF token
    assert r.status_code == 403 and "CSRF" in r.text
    r = client.post("/squareness/keep", data={"csrf": "forged", **FORM})
    assert r.status_code == 403
    bad = client.post("/squareness/keep", data={"csrf": client.token, **FORM, "second": "1"})
    assert bad.status_code == 400 and "with itself" in bad.text
    st = open_store(client.url)
    assert len(st.tests()) == 2
    st.close()
    v = TestClient(create_app(client.url, users, require_login=True),
                   base_url="http://127.0.0.1")
    assert log_in(v, "view", "staple battery horse").status_code == 303
    page = v.get("/squareness", params=FORM).text
    assert 'id="squareness-keep"' not in page
    r = v.post("/squareness/keep", data={"csrf": _token(v), **FORM})
    assert r.status_code == 403 and "viewer" in r.text
    st = open_store(client.url)
    assert len(st.tests()) == 2
    st.close()
