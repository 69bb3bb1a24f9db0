"""Issue 40, the workbench's second half: one vocabulary (the standard's symbols on the pages,
the keys in ``title`` attributes and the API), a trend chooser that takes R↑, tests without a
date kept out of the drift fit, a drift rounded as a certificate rounds it, no compare of a test
with itself or of a withdrawn test, the upload form's machine a fallback, dates checked."""

from __future__ import annotations

import datetime as dt
import html
import re

import numpy as np
import pytest
from fastapi.testclient import TestClient

from axiscal.web.app import create_app


def _positioning(date: str, offset: float, machine: str = "VMC", axis: str = "X") -> bytes:
    from axiscal.datasets import Metadata, PositioningDataset
    from axiscal.io.csv import format_positioning_csv

    rng = np.random.default_rng(int(offset * 10))
    t = np.linspace(0, 800, 9)
    up = rng.normal(1.0, 0.3, (9, 5)) + t[:, None] * offset / 800
    return format_positioning_csv(PositioningDataset(
        "linear", t, up, up - 2.0, "mm", "um",
        Metadata(machine=machine, axis=axis, date=date))).encode()


@pytest.fixture(scope="module")
def site(tmp_path_factory):
    """Three dated tests of VMC X, one without a date, one withdrawn later by a test."""
    d = tmp_path_factory.mktemp("words")
    mp = pytest.MonkeyPatch()
    mp.setenv("AXISCAL_CONFIG", str(d / "none.toml"))
    c = TestClient(create_app(f"sqlite:///{d / 'h.sqlite'}"), base_url="http://127.0.0.1")
    token = re.search(r'csrf-token" content="([^"]+)"', c.get("/").text).group(1)
    ids = []
    for date, off in (("2024-01-10", 1.0), ("2025-01-10", 2.0), ("2026-01-10", 3.0),
                      ("", 9.0)):
        r = c.post("/upload", data={"csrf": token},
                   files={"file": (f"t{off}.csv", _positioning(date, off), "text/csv")})
        assert r.status_code == 200, r.text[-300:]
        ids.append(int(str(r.url).split("/tests/")[1].split("?")[0]))
    yield c, token, ids
    mp.undo()


def test_trend_chooser_offers_the_axis_parameters_by_symbol_and_takes_r_up(site):
    """The trend page lists the parameters the axis's tests have, labelled by the symbols of
    ISO 230-2:2014 clause 3 with the key as the option's value; R↑ (as the pages write it) is
    the same page as R_up; a name the axis lacks is said beside the chooser (400), no error
    page."""
    c, _, _ = site
    by_symbol = c.get("/trend", params={"machine": "VMC", "axis": "X", "parameter": "R↑"})
    by_key = c.get("/trend", params={"machine": "VMC", "axis": "X", "parameter": "R_up"})
    assert by_symbol.status_code == 200 and by_key.status_code == 200
    assert '<option value="R_up" title="R_up" selected>R↑ [µm]</option>' in by_symbol.text
    assert '<option value="B_mean" title="B_mean">B̄ [µm]</option>' in by_symbol.text
    assert "<h1>Trend of R↑: VMC X</h1>" in by_symbol.text
    assert 'name="parameter" value=' not in by_symbol.text          # no free box
    bad = c.get("/trend", params={"machine": "VMC", "axis": "X", "parameter": "Q"})
    assert bad.status_code == 400 and "has no parameter 'Q'" in html.unescape(bad.text)
    assert '<select name="parameter"' in bad.text and "Something needs attention" not in bad.text


def test_undated_test_is_marked_and_left_out_of_the_drift_fit(site):
    """A test whose file gives no date (stored on the day of upload) is listed, marked, and not
    in the fit: the drift equals :func:`axiscal.store.analysis.fit_trend` of the three dated
    tests alone (ISO/TS 28037:2010 clause 6), and the page says so."""
    from axiscal.store import trend
    from axiscal.store.analysis import fit_trend

    c, _, ids = site
    tr = trend(c.app.state.store, "VMC", "X", "E")
    assert tr.dated == (True, True, True, False) and tr.undated == 1
    alone = fit_trend("E", tr.dates[:3], tr.values[:3], "um")
    assert tr.drift == pytest.approx(alone.drift) and tr.u_drift == pytest.approx(alone.u_drift)
    page = c.get("/trend", params={"machine": "VMC", "axis": "X", "parameter": "E"}).text
    assert "1 test without a date in the file" in page and "left out of the drift fit" in page
    assert f'<a href="/tests/{ids[3]}">' in page and "no date</span>" in page
    drift = re.search(r'id="drift">([^<]+)<', page).group(1)
    assert drift == tr.drift_text() and "e+" not in drift


def test_drift_is_rounded_as_a_certificate_rounds_a_value_and_its_uncertainty():
    """ILAC-P14:09/2020 §5.3 (format_value): U to two significant digits, rounded up, the value
    to the same last digit: a drift of 40.3 ± 143.2 µm/year is '+40 ± 150', never '1.4e+02'."""
    from axiscal.store.analysis import Trend

    tr = Trend("E", (), np.array([]), "um", 40.3, 143.2, None, None, None, None, None)
    assert tr.drift_text() == "+40 ± 150 µm/year"
    small = Trend("E", (), np.array([]), "um", -0.0123, 0.00412, None, None, None, None, None)
    assert small.drift_text() == "-0.0123 ± 0.0042 µm/year"


def test_compare_refuses_a_test_with_itself_and_a_withdrawn_test_is_not_offered(site):
    """Compare names two different tests; the compare table labels parameters by symbol (key in
    the title); a withdrawn test leaves the test page's compare list."""
    c, token, ids = site
    same = c.get(f"/compare?a={ids[0]}&b={ids[0]}")
    assert same.status_code == 400 and "compared with itself" in html.unescape(same.text)
    page = c.get(f"/compare?a={ids[0]}&b={ids[1]}").text
    assert '<td title="R_up">R↑</td>' in page and '<td title="B_mean">B̄</td>' in page
    assert ">A_up<" not in page and ">B_mean<" not in page
    listed = c.get(f"/tests/{ids[1]}").text.split('id="compare-with"')[1].split("</ul>")[0]
    assert f"a={ids[0]}&amp;b={ids[1]}" in listed
    r = c.post(f"/tests/{ids[0]}/withdraw", data={"csrf": token, "by": "A. Ng",
                                                  "reason": "beam clipped"})
    assert r.status_code == 200
    listed = c.get(f"/tests/{ids[1]}").text.split('id="compare-with"')[1].split("</ul>")[0]
    assert f"a={ids[0]}&amp;" not in listed and f"a={ids[2]}&amp;" in listed
    c.post(f"/tests/{ids[0]}/reinstate", data={"csrf": token, "by": "A. Ng", "reason": "ok"})


def test_upload_machine_is_a_fallback_the_axis_case_is_said_and_dates_are_checked(site):
    """"Machine (if the file does not name it)" does what it says: a file naming its machine
    keeps that name (the typed one is said not used); "x1" stored as "X1" is said; a date before
    1950 or in the future is refused with its reason, nothing stored."""
    c, token, _ = site
    r = c.post("/upload", data={"csrf": token, "machine": "Typed", "axis": "x1"},
               files={"file": ("named.csv", _positioning("2023-05-01", 4.0, "Named"),
                               "text/csv")})
    assert r.status_code == 200 and "<h1>Test" in r.text and "Named X1" in r.text
    notes = html.unescape(r.text.split('id="typed-names"')[1].split("</div>")[0])
    assert "“Typed” was not used" in notes and "“x1” is stored as “X1”" in notes
    r = c.post("/upload", data={"csrf": token, "machine": "Typed"},
               files={"file": ("anon.csv", _positioning("2023-05-02", 5.0, ""), "text/csv")})
    assert "<h1>Test" in r.text and "Typed X" in r.text and 'id="typed-names"' not in r.text
    before = len(c.app.state.store.tests())
    for date, words in (("1900-01-01", "is before 1950"), ("2999-01-01", "is in the future")):
        r = c.post("/upload", data={"csrf": token, "date": date},
                   files={"file": (f"{date}.csv", _positioning("", 6.0), "text/csv")})
        assert r.status_code == 400 and f"date {date} {words}" in r.text
    future = (dt.date.today() + dt.timedelta(days=30)).isoformat()
    r = c.post("/upload", data={"csrf": token},
               files={"file": ("f.csv", _positioning(future, 7.0), "text/csv")})
    assert r.status_code == 400 and "in the future" in r.text
    assert len(c.app.state.store.tests()) == before


def test_ballbar_parameters_are_named_in_words_and_units_head_every_column(tmp_path):
    """A ballbar test's parameter table shows labels (Reversal spike X decay length), the key
    only in the title; a positioning test's per-target table has its unit in every head."""
    from tests.web.test_kind_pages import _ballbar_file

    c = TestClient(create_app(f"sqlite:///{tmp_path / 'h.sqlite'}"), base_url="http://127.0.0.1")
    token = re.search(r'csrf-token" content="([^"]+)"', c.get("/").text).group(1)
    path = _ballbar_file(tmp_path)
    page = c.post("/upload", data={"csrf": token, "machine": "DMU 50"},
                  files={"file": (path.name, path.read_bytes(), "text/csv")}).text
    table = page.split('id="parameters"')[1].split("</table>")[0]
    assert ">Reversal spike X decay length<" in table and ">reversal_spike_x_decay<" not in table
    assert 'title="reversal_spike_x_decay' in table
    page = c.post("/upload", data={"csrf": token},
                  files={"file": ("p.csv", _positioning("2024-02-02", 1.5), "text/csv")}).text
    thead = page.split('id="targets"><thead>')[1].split("</thead>")[0]
    heads = re.findall(r"<th[^>]*>(.*?)</th>", thead)
    assert heads[0] == "target [mm]" and all(h.endswith("[µm]") for h in heads[1:]), heads


def test_workbench_table_axis_field_adds_no_line(site):
    """Issue 40: the Renishaw .REN written from the page with the Axis field
    ``X\\r\\nSpacing=1\\r\\nEOF`` has exactly the lines of the table named X (the name cleaned
    by the writers' one rule, :func:`~axiscal.compensation.controllers._common.safe_axis_name`),
    the source name in a note."""
    c, token, ids = site
    lines = {}
    for axis in ("X", "X\r\nSpacing=1\r\nEOF"):
        r = c.post(f"/tests/{ids[1]}/compensation", data={
            "csrf": token, "controller": "renishaw-ren", "spacing": "100", "axis": axis})
        assert r.status_code == 200
        lines[axis] = r.text.splitlines()
    hostile = lines["X\r\nSpacing=1\r\nEOF"]
    assert len(hostile) == len(lines["X"]) and not [ln for ln in hostile
                                                   if ln.startswith(("Spacing", "EOF"))]
    assert not any(ch in ln for ln in hostile for ch in "\r\x00")


def test_plot_and_report_name_the_machine_and_axis_as_corrected(tmp_path, monkeypatch):
    """After a rename in the history, the test page's plot and its report name the machine and
    axis as the history keeps them, not as the file wrote them."""
    monkeypatch.setenv("AXISCAL_CACHE", str(tmp_path / "cache"))
    c = TestClient(create_app(f"sqlite:///{tmp_path / 'h.sqlite'}"), base_url="http://127.0.0.1")
    token = re.search(r'csrf-token" content="([^"]+)"', c.get("/").text).group(1)
    r = c.post("/upload", data={"csrf": token},
               files={"file": ("p.csv", _positioning("2024-02-02", 1.0, "VMC old"), "text/csv")})
    tid = int(str(r.url).split("/tests/")[1].split("?")[0])
    assert "positioning deviations, X axis" in r.text
    mid = c.app.state.store.get(tid).summary.machine_id
    for path, data in ((f"/machine/{mid}/rename", {"name": "VMC Nord"}),
                       (f"/machine/{mid}/rename-axis", {"axis": "X", "name": "X1"})):
        assert c.post(path, data={"csrf": token, "by": "A. Ng", "reason": "plate",
                                  **data}).status_code == 200
    page = c.get(f"/tests/{tid}").text
    assert "positioning deviations, X1 axis" in page
    report = c.get(f"/tests/{tid}/report.html").text
    assert "VMC Nord X1" in re.search(r"<h1>(.*?)</h1>", report).group(1)
