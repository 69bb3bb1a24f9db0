"""A full sign-off in a real browser (issue 31): upload, tolerances and the job typed into the
test page, the ISO 14253-1 verdict with the interactive plot, a certificate issued through the
register (not a DRAFT), listed with its SHA-256 and downloaded byte for byte."""

from __future__ import annotations

import hashlib
import time

import pytest
from selenium.webdriver.common.by import By
from selenium.webdriver.support.ui import WebDriverWait

from tests.web.conftest import replaced, shot, start_server, stop_server
from tests.web.test_signoff import JOB, LAB, data_file


@pytest.fixture(scope="module")
def lab_server(tmp_path_factory):
    """The workbench with a laboratory's user configuration (name, address, code PM, E_VE)."""
    d = tmp_path_factory.mktemp("signoff")
    (d / "config.toml").write_text(LAB, encoding="utf-8")
    proc, base = start_server(d, env={"AXISCAL_CONFIG": str(d / "config.toml")})
    yield base, d
    stop_server(proc)


def _press(browser, button: str, then: str, timeout: float = 60) -> None:
    """Click ``button`` and wait until htmx has swapped the sign-off in (the old one gone) and
    the element ``then`` is there (or the page has changed, for a redirect)."""
    old = browser.find_element(By.ID, "signoff-body")
    browser.find_element(By.ID, button).click()
    WebDriverWait(browser, timeout).until(replaced(old))
    WebDriverWait(browser, timeout).until(lambda b: b.find_elements(By.ID, then))


def _type(browser, name: str, text: str) -> None:
    el = browser.find_element(By.NAME, name)
    el.clear()
    el.send_keys(text)


def test_full_signoff_from_upload_to_an_issued_certificate(lab_server, browser):
    base, d = lab_server
    (d / "x_axis.csv").write_bytes(data_file())
    browser.get(base + "/upload")
    browser.find_element(By.NAME, "file").send_keys(str(d / "x_axis.csv"))
    browser.find_element(By.CSS_SELECTOR, "form button").click()
    WebDriverWait(browser, 30).until(lambda b: "/tests/1" in b.current_url and b.execute_script(
        "return document.readyState") == "complete" and b.execute_script(
        "return !!window.htmx"))
    assert browser.find_element(By.ID, "no-certificates")

    _type(browser, "tol_E", "15")                      # no job yet: a DRAFT, no number
    _press(browser, "issue-certificate", "draft")
    draft = browser.find_element(By.ID, "draft").text
    assert "Customer: customer name" in draft                # issue 40: the field's label
    assert "Approved by (authorised signatory): name of the person authorising" in draft
    assert "/tests/1" in browser.current_url and "certificate=" not in browser.current_url
    browser.execute_script("document.getElementById('draft').scrollIntoView()")
    shot(browser, "signoff_draft")
    for name, value in {"tol_A": "20", "tol_E": "15", "tol_R": "5.5", **JOB}.items():
        _type(browser, name, value)
    browser.execute_script("document.getElementById('signoff-form').scrollIntoView()")
    shot(browser, "signoff_form")
    _press(browser, "show-verdict", "verdicts")
    cells = {r.find_elements(By.TAG_NAME, "td")[0].text: r.find_elements(By.TAG_NAME, "td")[-1]
             .text for r in browser.find_elements(By.CSS_SELECTOR, "#verdicts tbody tr")}
    assert cells == {"A": "PASS: conformance proven", "E": "PASS: conformance proven",
                     "R": "ZONE: uncertainty zone"}
    assert "ZONE: uncertainty zone" in browser.find_element(By.ID, "overall").text
    chart = browser.find_element(By.CSS_SELECTOR, "#signoff-body .uplot-chart")
    WebDriverWait(browser, 10).until(lambda b: chart.find_elements(By.TAG_NAME, "canvas"))
    legend = chart.text
    assert "tolerance A = 20 (PASS), upper" in legend and "readings↑ (runs 1–5)" in legend
    assert "x̄↑ + 2s" in legend
    browser.execute_script("document.getElementById('signoff-body').scrollIntoView()")
    shot(browser, "signoff_verdict")

    _press(browser, "issue-certificate", "certificates")       # the form kept every field
    assert "certificate=PM-2026-00001" in browser.current_url
    assert "Certificate PM-2026-00001 issued" in browser.find_element(By.ID, "issued").text
    row = browser.find_element(By.CSS_SELECTOR, "#certificates tbody tr")
    tds = [td.text for td in row.find_elements(By.TAG_NAME, "td")]
    assert tds[:3] == ["PM-2026-00001", time.strftime("%Y-%m-%d"), "issued"]
    sha = tds[4]
    cells = [r.find_elements(By.TAG_NAME, "td")[-1].text     # the verdict it was issued with
             for r in browser.find_elements(By.CSS_SELECTOR, "#verdicts tbody tr")]
    assert cells == ["PASS: conformance proven", "PASS: conformance proven",
                     "ZONE: uncertainty zone"]
    assert browser.find_element(By.NAME, "customer_name").get_attribute("value") == \
        JOB["customer_name"]
    browser.execute_script("document.getElementById('signoff').scrollIntoView()")
    shot(browser, "signoff_issued")
    row.find_element(By.LINK_TEXT, "download").click()
    pdf = browser.downloads / "PM-2026-00001.pdf"
    WebDriverWait(browser, 30).until(lambda b: pdf.exists() and pdf.stat().st_size > 0)
    time.sleep(0.5)
    data = pdf.read_bytes()
    assert data.startswith(b"%PDF") and hashlib.sha256(data).hexdigest() == sha
    import io

    from pypdf import PdfReader

    text = "".join(p.extract_text() for p in PdfReader(io.BytesIO(data)).pages)
    assert "PM-2026-00001" in text and "DRAFT" not in text and "Example Machining AG" in text
    assert "VMC8-0042" in text
