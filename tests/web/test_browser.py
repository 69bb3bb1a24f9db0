"""The workbench in a real browser (issue 15): upload the demo's files, open the history, compare,
download a compensation table and read it back, a trend, and escaping of hostile text."""

from __future__ import annotations

import json
import time
from pathlib import Path

import numpy as np
import pytest
from selenium.common.exceptions import NoAlertPresentException
from selenium.webdriver.common.by import By
from selenium.webdriver.support.ui import WebDriverWait
from typer.testing import CliRunner

from axiscal.cli import app

from tests.web.conftest import shot

runner = CliRunner()


@pytest.fixture(scope="module")
def demo_files(tmp_path_factory):
    """The demo's linear test and a compensation loop's before/after tests, as files."""
    import tomllib
    from dataclasses import replace
    from importlib import resources

    from axiscal.compensation.loop import run_compensation_loop
    from axiscal.io.csv import format_positioning_csv

    d = tmp_path_factory.mktemp("files")
    cfg = tomllib.loads(resources.files("axiscal.data").joinpath("demo_compensation.toml")
                        .read_text("utf-8"))
    loop = run_compensation_loop(cfg, seed=1)
    out = {}
    for label, ds, date in (("before", loop.before_data, "2026-01-10"),
                            ("after", loop.after_data, "2026-02-10")):
        ds = replace(ds, metadata=replace(ds.metadata, machine="VMC-800", axis="X", date=date))
        p = d / f"{label}.csv"
        p.write_text(format_positioning_csv(ds))
        out[label] = p
    return out


def _upload(browser, base, path: Path, note: str = ""):
    browser.get(base + "/upload")
    browser.find_element(By.NAME, "file").send_keys(str(path))
    if note:
        browser.find_element(By.NAME, "note").send_keys(note)
    browser.find_element(By.CSS_SELECTOR, "form button").click()
    WebDriverWait(browser, 20).until(lambda d: "/upload" not in d.current_url
                                     or d.find_elements(By.CSS_SELECTOR, ".error"))
    return browser.current_url


def _parameters(browser) -> dict:
    rows = browser.find_elements(By.CSS_SELECTOR, "#parameters tbody tr")
    return {r.find_elements(By.TAG_NAME, "td")[0].text: float(r.find_elements(
        By.TAG_NAME, "td")[1].text) for r in rows}


def test_upload_history_compare_table_trend(server, browser, demo_files):
    browser.get(server + "/")
    assert "The history is empty" in browser.page_source
    url = _upload(browser, server, demo_files["before"], note="before compensation")
    assert "/tests/1" in url
    expected = json.loads(runner.invoke(app, ["iso230-2", str(demo_files["before"]),
                                              "--json"]).stdout)
    got = _parameters(browser)
    for k in ("A", "E", "M", "R", "B"):
        assert got[k] == pytest.approx(expected[k], abs=0.0005)
    assert browser.find_elements(By.CSS_SELECTOR, ".uplot-chart canvas"), "no interactive plot"
    shot(browser, "test_page")

    _upload(browser, server, demo_files["after"], note="after compensation")
    browser.get(server + "/")
    browser.find_element(By.LINK_TEXT, "VMC-800").click()
    WebDriverWait(browser, 20).until(lambda d: d.find_elements(By.ID, "tests"))
    shot(browser, "machine_history")
    radios_a = browser.find_elements(By.CSS_SELECTOR, "input[name=a]")
    radios_b = browser.find_elements(By.CSS_SELECTOR, "input[name=b]")
    radios_a[1].click()                    # newest first: row 1 is test 1 (before)
    radios_b[0].click()
    browser.find_element(By.XPATH, "//button[contains(., 'Compare')]").click()
    WebDriverWait(browser, 20).until(lambda d: d.find_elements(By.ID, "comparison"))
    rows = {r.find_elements(By.TAG_NAME, "td")[0].text: r for r in
            browser.find_elements(By.CSS_SELECTOR, "#comparison tbody tr")}
    change_e = float(rows["E"].find_elements(By.TAG_NAME, "td")[3].text)
    assert change_e < -5.0                 # the compensation removed most of E
    shot(browser, "compare")

    browser.get(server + "/tests/1")
    browser.find_element(By.CSS_SELECTOR, "#compensation summary").click()     # folded
    browser.find_element(By.NAME, "controller").send_keys("linuxcnc")
    browser.find_element(By.XPATH, "//button[contains(., 'Write the table')]").click()
    WebDriverWait(browser, 20).until(lambda d: d.find_elements(By.ID, "table-download"))
    assert browser.current_url.endswith("/tests/1")          # answered in the page (htmx)
    assert "linuxcnc" in browser.find_element(By.ID, "tables").text
    browser.find_element(By.ID, "table-download").click()
    deadline = time.monotonic() + 20
    while time.monotonic() < deadline and not [p for p in browser.downloads.iterdir()
                                               if not p.name.endswith(".crdownload")]:
        time.sleep(0.1)
    files = [p for p in browser.downloads.iterdir() if not p.name.endswith(".crdownload")]
    assert len(files) == 1
    from axiscal.compensation.controllers import controller
    from axiscal.compensation.tables import table_from_result
    from axiscal.io import read_positioning
    from axiscal.standards.iso230_2 import evaluate

    back = controller("linuxcnc").parse(files[0].read_text(), str(files[0]))
    table = table_from_result(evaluate(read_positioning(demo_files["before"])), 10.0,
                              bidirectional=True)
    np.testing.assert_allclose(back.correction_at(back.positions, 1),
                               table.correction_at(back.positions, 1), atol=1e-3)

    browser.get(server + "/trend?machine=VMC-800&axis=X&parameter=E&tolerance=15")
    assert browser.find_elements(By.CSS_SELECTOR, ".uplot-chart canvas")
    shot(browser, "trend")


def test_hostile_text_is_shown_not_run(server, browser, demo_files, tmp_path):
    """HTML and script in every text field of the upload end up as text on every page."""
    evil = '<script>window.pwned=1;alert(1)</script><img src=x onerror="window.pwned=2">'
    p = tmp_path / "evil.csv"
    p.write_text(demo_files["before"].read_text().replace("machine=VMC-800", "machine=Evil"))
    browser.get(server + "/upload")
    browser.find_element(By.NAME, "file").send_keys(str(p))
    for name in ("machine", "axis", "note", "instrument"):
        field = browser.find_element(By.NAME, name)
        field.clear()
        field.send_keys(evil if name != "axis" else "X")
    browser.find_element(By.CSS_SELECTOR, "form button").click()
    for url in (browser.current_url, server + "/", server + "/machines/" + evil):
        browser.get(url)
        with pytest.raises(NoAlertPresentException):
            browser.switch_to.alert.text
        assert browser.execute_script("return window.pwned") is None
    assert "&lt;script&gt;" in browser.page_source or "<script>window" not in browser.page_source
    shot(browser, "escaped")


def test_a_bad_file_is_explained_on_the_page_and_stores_nothing(server, browser, tmp_path):
    p = tmp_path / "broken.csv"
    p.write_text("# target_unit=mm deviation_unit=um machine=M axis=X\n"
                 "target,direction,run,deviation\n0,+,1,abc\n")
    _upload(browser, server, p)
    alert = browser.find_element(By.CSS_SELECTOR, ".error").text
    assert "abc" in alert and "Traceback" not in browser.page_source
    shot(browser, "upload_error")
    browser.get(server + "/")
    assert "broken.csv" not in browser.page_source and ">M<" not in browser.page_source
