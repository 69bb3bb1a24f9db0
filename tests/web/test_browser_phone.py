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


def test_pages_fit_a_412_px_screen(server, browser, tmp_path):
    p = tmp_path / "vmc.csv"
    p.write_bytes(positioning_file())
    test = _upload(browser, server, p)
    ballbar = _upload(browser, server, _ballbar_file(tmp_path))
    volumetric = _upload(browser, server, _volumetric_file(tmp_path))
    machine = browser.find_element(By.CSS_SELECTOR, "a[href^='/machine/']").get_attribute("href")
    pages = {"test": test, "ballbar": ballbar, "volumetric": volumetric, "machine": machine,
             "upload": server + "/upload",
             "trend": server + "/trend?machine=VMC-800&axis=X&parameter=R%E2%86%91"}
    try:
        for name, url in pages.items():
            browser.set_window_size(412, 900)
            browser.get(url)
            WebDriverWait(browser, 20).until(
                lambda d: d.execute_script("return document.readyState") == "complete")
            time.sleep(0.2)                          # the plots draw after the page loads
            assert _overflow(browser) == [], name
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
