"""Issue 40: the workbench on a phone (412 px wide, a Pixel-sized screen) in Debian's Chromium:
no page is wider than the screen (a wide table scrolls inside its own box), the test page's
sections fold, the upload page shows the EPICS settings only for an EPICS log; screenshots kept
at 412 px to be looked at."""

from __future__ import annotations

import time

from selenium.webdriver.common.by import By
from selenium.webdriver.support.ui import Select, WebDriverWait

from tests.web.conftest import positioning_file, shot
from tests.web.test_kind_pages import _ballbar_file


def _upload(browser, base, path) -> str:
    browser.get(base + "/upload")
    browser.find_element(By.NAME, "file").send_keys(str(path))
    browser.find_element(By.NAME, "machine").send_keys("VMC-800")
    browser.find_element(By.CSS_SELECTOR, "form button").click()
    WebDriverWait(browser, 60).until(lambda d: "/tests/" in d.current_url)
    return browser.current_url.split("?")[0]


def _volumetric_file(tmp_path):
    """A volumetric configuration with its errors inline (``volumetric simulate`` then
    ``volumetric map --inline``), the file the history keeps of a volumetric test."""
    from typer.testing import CliRunner

    from axiscal.cli import app

    for args in (["volumetric", "simulate", "--out", tmp_path / "vol", "--points", "5"],
                 ["volumetric", "map", tmp_path / "vol" / "volumetric.toml", "--inline",
                  tmp_path / "vol.toml"]):
        r = CliRunner().invoke(app, [str(a) for a in args])
        assert r.exit_code == 0, r.output
    return tmp_path / "vol.toml"


def _overflow(browser) -> list[str]:
    """What sticks out beyond the screen's width outside a scrolling box (empty: nothing)."""
    return browser.execute_script(
        "const w = document.documentElement.clientWidth;"
        "return document.documentElement.scrollWidth > w ? Array.from("
        "document.querySelectorAll('body *')).filter(e => !e.closest('.scroll') &&"
        " e.getBoundingClientRect().right > w + 1).slice(0, 5).map(e => e.tagName + '#' + e.id"
        " + '.' + e.className) .concat(['scrollWidth ' + document.documentElement.scrollWidth])"
        " : [];")


def _audit_rows(browser, base, test: str, tmp_path) -> None:
    """Entries of the audit trail with what overflowed a phone (defect 9): a drift check (its
    SHA-256, a long file name) and the laboratory (an address list, a table of inputs)."""
    drift = tmp_path / "drift-check-of-the-vmc-800-x-axis-before-the-test.csv"
    drift.write_text("time_s,reading\n0,0.05\n300,0.42\n600,-0.18\n")
    browser.get(test)         # kept through the sign-off form's field (the page's one)
    browser.find_element(By.ID, "i-drift_check").send_keys(str(drift))
    browser.find_element(By.NAME, "operator").send_keys("A. Operator")
    browser.execute_script("document.getElementById('show-verdict').click()")
    WebDriverWait(browser, 30).until(lambda d: d.find_elements(By.ID, "drift-kept"))
    browser.get(base + "/laboratory")
    form = browser.find_element(By.ID, "laboratory-form")
    for name, text in (("lab_name", "Präzisionsmesstechnik Berlin-Brandenburg GmbH"),
                       ("lab_address", "Werkstr. 5\n12345 Berlin"), ("lab_e_ve", "2"),
                       ("by", "A. Operator"), ("reason", "the laboratory's identity")):
        form.find_element(By.NAME, name).send_keys(text)
    form.find_element(By.ID, "save-laboratory").click()
    WebDriverWait(browser, 30).until(lambda d: "saved=1" in d.current_url)


def test_pages_fit_a_412_px_screen(server, browser, tmp_path):
    p = tmp_path / "vmc.csv"
    p.write_bytes(positioning_file())
    test = _upload(browser, server, p)
    p.write_bytes(positioning_file() + b"\n")          # a second test of the axis, to compare
    second = _upload(browser, server, p)
    ballbar = _upload(browser, server, _ballbar_file(tmp_path))
    volumetric = _upload(browser, server, _volumetric_file(tmp_path))
    machine = browser.find_element(By.CSS_SELECTOR, "a[href^='/machine/']").get_attribute("href")
    _audit_rows(browser, server, test, tmp_path)
    ids = test.rsplit("/", 1)[1], second.rsplit("/", 1)[1]
    pages = {"test": test, "ballbar": ballbar, "volumetric": volumetric, "machine": machine,
             "upload": server + "/upload", "audit": server + "/audit",
             "laboratory": server + "/laboratory",
             "compare": server + f"/compare?a={ids[0]}&b={ids[1]}",
             "trend": server + "/trend?machine=VMC-800&axis=X&parameter=R%E2%86%91"}
    try:
        for name, url in pages.items():
            browser.set_window_size(412, 900)
            browser.get(url)
            WebDriverWait(browser, 20).until(
                lambda d: d.execute_script("return document.readyState") == "complete")
            time.sleep(0.2)                          # the plots draw after the page loads
            assert _overflow(browser) == [], name
            assert browser.execute_script(           # no page scrolls sideways (defect 9)
                "return document.documentElement.scrollWidth") <= 412, name
            if name in ("test", "compare", "trend"):  # each chart takes the screen's width
                widths = browser.execute_script(
                    "return Array.from(document.querySelectorAll('.uplot-chart'))"
                    ".filter(e => e.uplot).map(e => e.uplot.width)")
                assert widths and max(widths) <= 412, (name, widths)
            if name == "audit":                       # readable values, no Python literals
                trail = browser.find_element(By.ID, "audit").text
                assert "address: Werkstr. 5, 12345 Berlin" in trail, trail
                assert "source of E_VE" in trail and "['" not in trail and "{'" not in trail
            height = browser.execute_script("return document.documentElement.scrollHeight")
            browser.set_window_size(412, min(height + 120, 6000))
            shot(browser, f"phone_{name}_412")
        browser.get(test)
        folded = browser.find_elements(By.CSS_SELECTOR, "details#per-target:not([open])")
        assert folded and browser.find_element(By.ID, "key-figures").is_displayed()
        browser.get(server + "/upload")
        epics = browser.find_element(By.ID, "epics-settings")
        assert not epics.is_displayed()                      # capture is the default
        Select(browser.find_element(By.NAME, "kind")).select_by_value("epics")
        assert epics.is_displayed()
    finally:
        browser.set_window_size(1280, 1600)
