"""The ballbar and straightness pages in a real browser (Debian's chromium): the diagnosis a
shop-floor engineer reads equals ``ballbar analyze`` on the same file, the polar plot loads
under the page's Content-Security-Policy, and screenshots are kept to be looked at."""

from __future__ import annotations

import json
from pathlib import Path

import pytest
from selenium.webdriver.common.by import By
from selenium.webdriver.support.ui import WebDriverWait
from typer.testing import CliRunner

from axiscal.cli import app

from tests.web.conftest import shot
from tests.web.test_kind_pages import _ballbar_file, _positioning

EXAMPLES = Path(__file__).resolve().parents[2] / "examples"
runner = CliRunner()


def _upload(browser, base, path: Path, machine: str = "DMU 50") -> str:
    browser.get(base + "/upload")
    browser.find_element(By.NAME, "file").send_keys(str(path))
    browser.find_element(By.NAME, "machine").send_keys(machine)
    browser.find_element(By.CSS_SELECTOR, "form button").click()
    WebDriverWait(browser, 60).until(lambda d: "/upload" not in d.current_url
                                     or d.find_elements(By.CSS_SELECTOR, ".error"))
    return browser.current_url


def _full_page_shot(browser, name: str) -> Path:
    """A screenshot of the whole page (the window made as tall as the page first)."""
    height = browser.execute_script("return document.documentElement.scrollHeight")
    browser.set_window_size(1280, min(max(height, 800), 6000))
    try:
        return shot(browser, name)
    finally:
        browser.set_window_size(1280, 1600)


def test_ballbar_page_in_a_browser_equals_ballbar_analyze(server, browser, tmp_path):
    path = _ballbar_file(tmp_path)
    url = _upload(browser, server, path)
    assert "/tests/" in url, browser.find_element(By.CSS_SELECTOR, ".error").text
    j = json.loads(runner.invoke(app, ["ballbar", "analyze", str(path), "--json"]).stdout)
    rows = [[c.text for c in r.find_elements(By.TAG_NAME, "td")]
            for r in browser.find_elements(By.CSS_SELECTOR, "#diagnosis tbody tr")]
    assert [(float(r[2]), r[3], float(r[4]), r[6]) for r in rows] == [
        (pytest.approx(t["value"], abs=5e-4), t["unit"], pytest.approx(t["effect_um"], abs=5e-4),
         t["advice"]) for t in j["ranking"]]
    folded = [li.text for li in browser.find_elements(By.CSS_SELECTOR, "#folded li")]
    assert folded == [f["statement"] for f in j["iso230_4"]["folded"] if f["material"]]
    img = browser.find_element(By.ID, "kind-figure")
    assert browser.execute_script("return arguments[0].complete && arguments[0].naturalWidth",
                                  img) > 300, "the polar plot did not load"
    _full_page_shot(browser, "ballbar_page")


def test_straightness_page_in_a_browser(server, browser):
    url = _upload(browser, server, EXAMPLES / "squareness_L180_x.csv")
    assert "/tests/" in url
    out = json.loads(runner.invoke(app, ["straightness", str(EXAMPLES / "squareness_L180_x.csv"),
                                         "--json"]).stdout)
    j, U = out["methods"], out["uncertainty_budget"]["U_display"]
    cells = [c.text for c in browser.find_elements(By.CSS_SELECTOR,
                                                   "#straightness tbody tr:first-child td")]
    assert cells[1:] == [f"{j['least_squares']['straightness_um']:.3f}", U["straightness"],
                         f"{j['least_squares']['slope_um_per_m']:.3f}", U["slope"]]
    assert "e-06" not in browser.page_source
    img = browser.find_element(By.ID, "kind-figure")
    assert browser.execute_script("return arguments[0].naturalWidth", img) > 300
    _full_page_shot(browser, "straightness_page")


def test_trend_of_an_axis_whose_tests_share_a_date(server, browser):
    """The XY axis's trend link (squareness, not E) draws on a date axis around the one date
    of its tests: a month in view, not decades."""
    import datetime as dt

    url = _upload(browser, server, EXAMPLES / "squareness_diagonal_600x800.csv", "One date")
    assert "/tests/" in url
    browser.find_element(By.LINK_TEXT, "the axis's history").click()
    browser.find_element(By.PARTIAL_LINK_TEXT, "trend of Squareness").click()   # its label
    WebDriverWait(browser, 20).until(lambda d: d.find_elements(By.CSS_SELECTOR,
                                                               ".uplot-chart canvas"))
    lo, hi, x = browser.execute_script(
        "var u = document.querySelector('.uplot-chart').uplot;"
        "return [u.scales.x.min, u.scales.x.max, u.data[0][0]];")
    assert lo < x < hi and hi - lo == pytest.approx(30 * 86400)
    shown = browser.find_element(By.XPATH, "//table[thead/tr/th[.='date']]//tbody//td").text
    assert dt.datetime.fromtimestamp(x, dt.timezone.utc).date().isoformat() == shown.split()[0]
    assert shown.endswith("no date")         # the file gives none: the day stored, marked
    _full_page_shot(browser, "trend_one_date")


def test_trend_draws_the_predicted_crossing(server, browser, tmp_path):
    """Three yearly positioning tests of a drifting axis and a tolerance: the plot holds the
    fitted line and the crossing point on the tolerance at the date the summary states."""
    for date, offset in (("2024-01-10", 2.0), ("2025-01-10", 4.0), ("2026-01-10", 6.0)):
        p = tmp_path / f"{date}.csv"
        p.write_bytes(_positioning(date, offset))
        assert "/tests/" in _upload(browser, server, p, machine="VMC")
    browser.get(server + "/trend?machine=VMC&axis=X&parameter=E&tolerance=30")
    WebDriverWait(browser, 20).until(lambda d: d.find_elements(By.CSS_SELECTOR,
                                                               ".uplot-chart canvas"))
    labels = browser.execute_script(
        "return document.querySelector('.uplot-chart').uplot.series.map(s => s.label);")
    crossing = next(x for x in labels if x.startswith("predicted crossing"))
    summary = browser.find_element(By.ID, "trend-summary").text
    assert f"reaches the tolerance 30 µm on {crossing.split()[-1]}" in summary
    _full_page_shot(browser, "trend_crossing")


def test_diagonal_page_in_a_browser_shows_the_cli_U(server, browser):
    """The diagonal test's page: squareness and its U (k = 2) as ``squareness diagonal``
    prints them (ISO 230-6:2002; ISO/TR 230-9 budget), with the budget's contributors."""
    from axiscal.standards.iso230_9 import format_uncertainty

    path = EXAMPLES / "squareness_diagonal_600x800.csv"
    assert "/tests/" in _upload(browser, server, path)
    j = json.loads(runner.invoke(app, ["squareness", "diagonal", "--file", str(path),
                                       "--json"]).stdout)
    rows = {r.find_elements(By.TAG_NAME, "td")[0].text: r.find_elements(By.TAG_NAME, "td")[1].text
            for r in browser.find_elements(By.CSS_SELECTOR, "#diagonal tbody tr")}
    assert rows["U (k = 2) of the squareness"] == format_uncertainty(j["U_um_per_m"])
    browser.find_element(By.CSS_SELECTOR, "details:has(#budget) summary").click()  # folded
    names = [r.find_element(By.TAG_NAME, "td").text
             for r in browser.find_elements(By.CSS_SELECTOR, "#budget tbody tr")]
    assert names == [c["name"] for c in j["uncertainty"]]
    _full_page_shot(browser, "diagonal_page")
