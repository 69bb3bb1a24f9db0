"""Corrections in a real browser (issue 31): a machine named with a "/" reachable from every
link, rename, merge and withdraw through the forms, the audit trail visible (screenshots
test-artifacts/web/corrections_*.png)."""

from __future__ import annotations

import numpy as np
from selenium.webdriver.common.by import By
from selenium.webdriver.support.ui import WebDriverWait

from tests.store.test_history import _dataset, _raw
from tests.web.conftest import replaced, shot

SLASH = "DMU 50 S/N 1234"


def _upload(browser, base, path, machine):
    browser.get(base + "/upload")
    browser.find_element(By.NAME, "file").send_keys(str(path))
    browser.find_element(By.NAME, "machine").send_keys(machine)
    browser.find_element(By.CSS_SELECTOR, "form button").click()
    WebDriverWait(browser, 20).until(lambda d: "/tests/" in d.current_url)


def _correct(browser, form_id: str, by="A. Ng", reason="", **fields):
    """Open the corrections panel, fill one form, send it, wait for the next page."""
    browser.find_element(By.CSS_SELECTOR, "#corrections summary").click()
    form = browser.find_element(By.ID, form_id)
    for name, value in fields.items():
        el = form.find_element(By.NAME, name)
        if el.tag_name == "select":
            el.find_element(By.XPATH, f".//option[normalize-space()='{value}']").click()
        else:
            el.clear()
            el.send_keys(value)
    form.find_element(By.NAME, "by").send_keys(by)
    form.find_element(By.NAME, "reason").send_keys(reason)
    old = browser.find_element(By.TAG_NAME, "h1")
    form.find_element(By.TAG_NAME, "button").click()
    if form_id.startswith("merge"):          # issue 40: a merge asks first (every test moves)
        from selenium.webdriver.support import expected_conditions as ec

        alert = WebDriverWait(browser, 10).until(ec.alert_is_present())
        assert "Every test" in alert.text
        alert.accept()
    WebDriverWait(browser, 20).until(replaced(old))          # the answer's page is here
    WebDriverWait(browser, 20).until(
        lambda d: d.execute_script("return document.readyState") == "complete")


def _trail(browser) -> list[list[str]]:
    return [[td.text for td in tr.find_elements(By.TAG_NAME, "td")]
            for tr in browser.find_elements(By.CSS_SELECTOR, "#audit tbody tr")]


def test_rename_merge_withdraw_with_the_audit_trail(server, browser, tmp_path):
    rng = np.random.default_rng(12)
    for k in range(3):
        p = tmp_path / f"x{k}.csv"
        p.write_bytes(_raw(_dataset(rng, machine="", date=f"202{k}-04-01", offset=k)))
        _upload(browser, server, p, SLASH)
    p = tmp_path / "y.csv"
    p.write_bytes(_raw(_dataset(rng, machine="", axis="Y")))
    _upload(browser, server, p, "DMU 50")

    browser.get(server + "/")                        # the "/" machine, reachable by its link
    browser.find_element(By.LINK_TEXT, SLASH).click()
    assert browser.find_element(By.TAG_NAME, "h1").text == SLASH
    assert len(browser.find_elements(By.CSS_SELECTOR, "#tests tbody tr")) == 3
    browser.find_element(By.LINK_TEXT, "X").click()
    assert browser.find_element(By.TAG_NAME, "h1").text == SLASH
    slash_page = browser.current_url.split("?")[0]

    _correct(browser, "rename-machine", name="DMU 50 / 1234", reason="as on the plate")
    assert browser.find_element(By.TAG_NAME, "h1").text == "DMU 50 / 1234"
    assert _trail(browser)[0][1:4] == ["A. Ng", "machine 'DMU 50 S/N 1234' renamed "
                                       "'DMU 50 / 1234'", "as on the plate"]

    browser.get(server + "/tests/2")
    _correct(browser, "withdraw-test", reason="beam clipped on run 3")
    banner = browser.find_element(By.ID, "withdrawn").text
    assert "Withdrawn: beam clipped on run 3" in banner
    shot(browser, "corrections_withdrawn_test")

    browser.get(server + "/")
    browser.find_element(By.LINK_TEXT, "DMU 50").click()
    _correct(browser, "merge-machine", into="DMU 50 / 1234", reason="one machine, two names")
    assert browser.current_url.split("?")[0] == slash_page
    assert browser.find_element(By.TAG_NAME, "h1").text == "DMU 50 / 1234"
    rows = browser.find_elements(By.CSS_SELECTOR, "#tests tbody tr")
    assert len(rows) == 4 and len(browser.find_elements(By.CSS_SELECTOR, "tr.withdrawn")) == 1
    whats = [r[2] for r in _trail(browser)]
    assert whats[0].startswith("machine 'DMU 50' (id ") and whats[1:] == [
        "test 2 withdrawn", "machine 'DMU 50 S/N 1234' renamed 'DMU 50 / 1234'"]
    shot(browser, "corrections_machine")

    browser.find_element(By.LINK_TEXT, "Audit trail").click()
    assert len(_trail(browser)) == 3
    assert "Nothing is deleted" in browser.page_source
    shot(browser, "corrections_audit_trail")
    browser.find_element(By.LINK_TEXT, "test 2 withdrawn").click()
    assert "/tests/2" in browser.current_url and browser.find_element(By.ID, "withdrawn")
