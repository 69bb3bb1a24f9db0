"""Issue 40, the outside review's minor defects (11): an empty trend parameter takes the page's
default, a day the calendar lacks is said to be no date (not "write it as YYYY-MM-DD", as it
was), compare names the other standards by their names (ISO 230-2:1988, not the registry's
key) and prints no "-0.000"."""

from __future__ import annotations

import html
import re

import pytest
from fastapi.testclient import TestClient

from axiscal.web.app import create_app
from tests.web.test_kind_pages import _positioning


@pytest.fixture(scope="module")
def bench(tmp_path_factory):
    d = tmp_path_factory.mktemp("minors")
    with pytest.MonkeyPatch.context() as mp:
        mp.setenv("AXISCAL_CONFIG", str(d / "none.toml"))
        c = TestClient(create_app(f"sqlite:///{d / 'h.sqlite'}"), base_url="http://127.0.0.1")
        c.token = re.search(r'csrf-token" content="([^"]+)"', c.get("/").text).group(1)
        for date, offset in (("2025-01-10", 2.0), ("2026-01-10", 2.0)):
            r = c.post("/upload", data={"csrf": c.token},
                       files={"file": (f"{date}.csv", _positioning(date, offset), "text/csv")})
            assert r.status_code == 200
        yield c


def test_empty_trend_parameter_is_the_default(bench):
    r = bench.get("/trend", params={"machine": "VMC", "axis": "X", "parameter": ""})
    assert r.status_code == 200 and "Trend of E: VMC X" in r.text


def test_a_day_the_calendar_lacks(bench):
    r = bench.post("/upload", data={"csrf": bench.token, "date": "2026-02-30"},
                   files={"file": ("x.csv", _positioning("", 3.0), "text/csv")})
    assert r.status_code == 400 and "2026-02-30 is not a date" in html.unescape(r.text)
    from axiscal.errors import InputError
    from axiscal.report.certificate_content import parse_date

    with pytest.raises(InputError, match="date of test: 2026-02-30 is not a date"):
        parse_date("2026-02-30", "date of test")


def test_compare_names_the_standards_and_has_no_negative_zero(bench):
    """The two files have the same readings (seeded alike), so every change is zero, printed
    0.000 through the one number filter (:func:`axiscal.report.labels.fixed`, whose doctest
    shows -0.0001 printed 0.000, not "-0.000")."""
    page = html.unescape(bench.get("/compare", params={"a": 1, "b": 2}).text)
    assert "R↑ (ISO 230-2:1988)" in page and "(iso230-2:1988)" not in page
    assert "R (JIS B 6192 / B 0182)" in page
    assert "-0.000" not in page and ">0.000<" in page
