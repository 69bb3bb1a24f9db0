"""Issue 40 in a real browser (Chromium, signed in): a real ESS ecmc file uploaded, the sign-off
finished on the page alone (the laboratory, E_VE by an uploaded drift check, tolerances), a
numbered certificate; the machine's name corrected in the history and an amendment issued whose
PDF carries the new name. Then an ended session on the sign-off form (the login, and back to the
form with what was typed), a refused request shown at the form, and Back after log-out.
Screenshots at 1280 px and 412 px in /tmp/i40a/ and test-artifacts/web/."""

from __future__ import annotations

import io
import shutil
import time
from pathlib import Path

import pytest
from selenium.webdriver.common.by import By
from selenium.webdriver.support.ui import WebDriverWait

from axiscal.web.security import UserFile
from tests.web.conftest import replaced, shot, start_server, stop_server
from tests.web.test_signoff_history import DRIFT, ECMC, JOB_FORM, LAB_FORM, USER

SHOTS = Path("/tmp/i40a")


@pytest.fixture(scope="module")
def bench(tmp_path_factory):
    """The workbench with accounts (eng, an engineer and the laboratory's signatory) and a user
    configuration without a laboratory: the history keeps it."""
    d = tmp_path_factory.mktemp("signoff40")
    (d / "config.toml").write_text(USER, encoding="utf-8")
    users = UserFile.load(d / "users.toml")
    users.add("eng", "engineer", "correct horse battery")
    users.add("sig", "engineer", "correct horse battery")    # the signatory who approves
    (d / "drift.csv").write_bytes(DRIFT)
    proc, base = start_server(d, "--users", str(d / "users.toml"),
                              env={"AXISCAL_CONFIG": str(d / "config.toml")})
    yield base, d
    stop_server(proc)


def _shot(browser, name: str) -> None:
    p = shot(browser, name)
    SHOTS.mkdir(parents=True, exist_ok=True)
    shutil.copy(p, SHOTS / p.name)


def _log_in(browser, base: str, path: str = "/login", name: str = "eng") -> None:
    if path:
        browser.get(base + path)
    browser.find_element(By.NAME, "username").send_keys(name)
    browser.find_element(By.NAME, "password").send_keys("correct horse battery")
    button = browser.find_element(By.CSS_SELECTOR, "main form.card button")
    button.click()
    WebDriverWait(browser, 20).until(replaced(button))


def _as(browser, base: str, name: str) -> None:
    """Log out and in again as ``name``, then open test 1."""
    browser.find_element(By.CSS_SELECTOR, "header form button").click()
    WebDriverWait(browser, 20).until(lambda b: "/login" in b.current_url)
    _log_in(browser, base, path="", name=name)
    browser.get(base + "/tests/1")
    WebDriverWait(browser, 20).until(_ready)


def _type(browser, name: str, text: str) -> None:
    el = browser.find_element(By.NAME, name)
    el.clear()
    el.send_keys(text)


def _press(browser, button: str, then: str, timeout: float = 60) -> None:
    old = browser.find_element(By.ID, "signoff-body")
    browser.find_element(By.ID, button).click()
    WebDriverWait(browser, timeout).until(replaced(old))
    try:
        WebDriverWait(browser, timeout).until(lambda b: b.find_elements(By.ID, then))
    except Exception:
        errors = [e.text for e in browser.find_elements(By.CSS_SELECTOR, "[role=alert]")]
        raise AssertionError(f"no #{then}; the page says: {errors}") from None


def _upload(browser, base: str) -> None:
    """The real ecmc file uploaded on the page (it becomes test 1), with the date and instrument
    typed at upload."""
    browser.get(base + "/upload")
    browser.find_element(By.NAME, "file").send_keys(str(ECMC))
    for name, value in (("machine", "MCU1025 bench"), ("date", "2026-03-02"),
                        ("instrument", "Encoder IOC_TEST:m0s012-Enc01")):
        _type(browser, name, value)
    browser.find_element(By.CSS_SELECTOR, "main form button").click()
    WebDriverWait(browser, 60).until(lambda b: "/tests/1" in b.current_url and _ready(b))


def _ready(browser) -> bool:
    return browser.execute_script("return document.readyState") == "complete" and \
        browser.execute_script("return !!window.htmx")


def _form(browser, fields: dict) -> None:
    for name, value in fields.items():
        if name == "signatory" or name == "signatory_role":     # signed in: the approver is eng
            continue
        _type(browser, name, value)


def test_signoff_of_a_real_file_finished_on_the_page_then_amended(bench, browser):
    base, d = bench
    browser.set_window_size(1280, 1600)
    _log_in(browser, base)
    _upload(browser, base)
    # the form starts from the stored test: the date and the instrument typed at upload
    assert browser.find_element(By.NAME, "date").get_attribute("value") == "2026-03-02"
    assert browser.find_element(By.NAME, "instrument1_name").get_attribute("value") == \
        "Encoder IOC_TEST:m0s012-Enc01"

    _type(browser, "tol_E", "8")                       # not complete: the items, by label
    _type(browser, "operator", "A. Operator")
    _press(browser, "issue-certificate", "draft")
    links = {a.text: a.get_attribute("href").rsplit("#", 1)[1]
             for a in browser.find_elements(By.CSS_SELECTOR, "#draft li a")}
    assert links["Customer"] == "f-customer_name" and links["Laboratory name"] == "f-lab_name"
    assert links["Drift check file (E_VE measured beside this test)"] == "f-drift_check"
    draft = browser.find_element(By.ID, "draft").text
    for words in ("[customer]", "[machine]", "--uncertainty", "--by", "axiscal config"):
        assert words not in draft
    browser.execute_script("document.getElementById('draft').scrollIntoView()")
    _shot(browser, "i40a_draft_1280")
    browser.find_element(By.LINK_TEXT, "Customer").click()
    assert browser.current_url.endswith("#f-customer_name")

    _form(browser, {**LAB_FORM, **JOB_FORM,      # eng prepares, sig (on the list) approves
                    "lab_signatories": "B. Signatory, Head of laboratory\nsig, Deputy head"})
    # the sign-off form's field, not the drift-check box of the test page above it
    browser.find_element(By.ID, "i-drift_check").send_keys(str(d / "drift.csv"))
    browser.execute_script("document.getElementById('laboratory').scrollIntoView()")
    _shot(browser, "i40a_form_1280")
    _press(browser, "save-for-approval", "saved-for-approval")
    _as(browser, base, "sig")                 # the approver finds the form as eng saved it
    assert browser.find_element(By.NAME, "customer_name").get_attribute("value") == \
        JOB_FORM["customer_name"]
    assert "awaiting approval" in browser.find_element(By.ID, "awaiting-approval").text
    browser.execute_script("document.getElementById('authorisation').scrollIntoView()")
    _shot(browser, "i40a_awaiting_approval_1280")
    _press(browser, "issue-certificate", "certificates")
    assert "certificate=PM-2026-00001" in browser.current_url
    assert "E_VE = 0.6 µm" in browser.find_element(By.ID, "drift-kept").text
    row = browser.find_element(By.CSS_SELECTOR, "#certificates tbody tr")
    assert [td.text for td in row.find_elements(By.TAG_NAME, "td")][:3] == \
        ["PM-2026-00001", time.strftime("%Y-%m-%d"), "issued"]
    browser.execute_script("document.getElementById('signoff').scrollIntoView()")
    _shot(browser, "i40a_issued_1280")

    # the machine's name corrected in the history, on its page (audit-trailed)
    browser.get(base + "/")
    browser.find_element(By.LINK_TEXT, "MCU1025 bench").click()
    WebDriverWait(browser, 20).until(lambda b: b.find_elements(By.ID, "corrections"))
    browser.find_element(By.CSS_SELECTOR, "#corrections summary").click()
    form = browser.find_element(By.ID, "rename-machine")
    name = form.find_element(By.NAME, "name")
    name.clear()
    name.send_keys("ESS MCU1025 test stand")
    form.find_element(By.NAME, "reason").send_keys("the stand's name in the ESS register")
    button = form.find_element(By.TAG_NAME, "button")
    button.click()
    WebDriverWait(browser, 20).until(replaced(button))

    _as(browser, base, "eng")
    _type(browser, "amend_reason", "machine name corrected")
    _press(browser, "save-for-approval", "saved-for-approval")
    _as(browser, base, "sig")
    _press(browser, "issue-amendment", "certificates")
    assert "certificate=PM-2026-00002" in browser.current_url
    rows = {r.find_elements(By.TAG_NAME, "td")[0].text: r for r in
            browser.find_elements(By.CSS_SELECTOR, "#certificates tbody tr")}
    assert "superseded" in rows["PM-2026-00001"].text
    rows["PM-2026-00002"].find_element(By.LINK_TEXT, "download").click()
    pdf = browser.downloads / "PM-2026-00002.pdf"
    WebDriverWait(browser, 30).until(lambda b: pdf.exists() and pdf.stat().st_size > 0)
    time.sleep(0.5)
    from pypdf import PdfReader

    text = " ".join(" ".join(p.extract_text().split())
                    for p in PdfReader(io.BytesIO(pdf.read_bytes())).pages)
    assert "Machine ESS MCU1025 (ESS MCU1025 test stand)" in text
    assert "machine name corrected" in text and "PM-2026-00001" in text
    assert "DRAFT" not in text and "EVE = 0.6 µm (drift check)" in text

    browser.set_window_size(412, 915)                       # a phone
    browser.get(base + "/tests/1#signoff")
    WebDriverWait(browser, 20).until(_ready)
    _shot(browser, "i40a_signoff_412")
    wide = browser.execute_script(       # the sign-off's parts fit the phone's 412 px
        "return Math.max(...['signoff-form', 'certificates'].map(i => "
        "document.getElementById(i).closest('section, .scroll, form')"
        ".getBoundingClientRect().right))")
    assert wide <= 412, wide
    browser.execute_script("document.getElementById('laboratory').scrollIntoView()")
    _shot(browser, "i40a_laboratory_412")
    browser.set_window_size(1280, 1600)


def test_ended_session_refusal_and_back_after_log_out(bench, browser):
    base, _ = bench
    browser.set_window_size(1280, 1600)
    browser.get(base + "/tests/1")
    if "/login" in browser.current_url:
        _log_in(browser, base, path="")
    WebDriverWait(browser, 20).until(lambda b: "/tests/1" in b.current_url and _ready(b))
    if not browser.find_elements(By.ID, "signoff-form"):     # run alone (or on another xdist
        _upload(browser, base)                               # worker than the test above)
    # a refused request (403: the form's token out of date) is said at the form, typing kept
    _type(browser, "customer_name", "Typed before the refusal")
    browser.execute_script("document.querySelector('meta[name=csrf-token]').content = 'x';"
                           "document.querySelector('#signoff-form [name=csrf]').value = 'x'")
    browser.find_element(By.ID, "show-verdict").click()
    box = WebDriverWait(browser, 20).until(
        lambda b: b.find_elements(By.CSS_SELECTOR, "#signoff-form > .request-error"))[0]
    assert "Refused (403)" in box.text and "CSRF" in box.text
    assert browser.find_element(By.NAME, "customer_name").get_attribute("value") == \
        "Typed before the refusal"
    box.location_once_scrolled_into_view
    _shot(browser, "i40a_refused_1280")

    # the session ends (the server no longer knows the cookie): the login, then the form again
    browser.get(base + "/tests/1")
    WebDriverWait(browser, 20).until(_ready)
    _type(browser, "customer_name", "Typed before the session ended")
    _type(browser, "tol_E", "7.5")
    cookie = browser.get_cookie("axiscal_session")
    browser.delete_cookie("axiscal_session")
    browser.add_cookie({"name": cookie["name"], "value": "ended" * 8, "path": "/"})
    browser.find_element(By.ID, "show-verdict").click()
    WebDriverWait(browser, 20).until(lambda b: "/login" in b.current_url)
    assert "expired=1" in browser.current_url
    assert "Your session has ended" in browser.find_element(By.ID, "expired").text
    _shot(browser, "i40a_expired_login_1280")
    _log_in(browser, base, path="")
    WebDriverWait(browser, 20).until(lambda b: "/tests/1" in b.current_url and _ready(b))
    assert browser.find_element(By.NAME, "customer_name").get_attribute("value") == \
        "Typed before the session ended"
    assert browser.find_element(By.NAME, "tol_E").get_attribute("value") == "7.5"
    assert "filled in again" in browser.find_element(By.ID, "restored").text
    _shot(browser, "i40a_restored_1280")

    # Back after log-out shows the login, not the signed-in page (Cache-Control: no-store)
    browser.find_element(By.CSS_SELECTOR, "header form button").click()
    WebDriverWait(browser, 20).until(lambda b: "/login" in b.current_url)
    browser.back()
    WebDriverWait(browser, 20).until(lambda b: b.execute_script(
        "return document.readyState") == "complete")
    assert "/login" in browser.current_url
    assert not browser.find_elements(By.ID, "signoff-form")
    assert "eng (engineer)" not in browser.find_element(By.TAG_NAME, "header").text
