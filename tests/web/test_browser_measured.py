"""Measured uploads in a real browser (Debian's chromium, issue 31): a capture (a continuous
record and its plan), raw laser readings with their environment log and an EPICS camonitor log
with its settings, each sent through the upload page's form as a shop-floor engineer would; the
figures the test page shows are those the command line gives for the same files, and a
screenshot of each page is kept in test-artifacts/web/ to be looked at."""

from __future__ import annotations

import json

import numpy as np
import pytest
from selenium.webdriver.common.by import By
from selenium.webdriver.support.ui import Select, WebDriverWait
from typer.testing import CliRunner

from axiscal.cli import app
from axiscal.io.measured import parse_plan_csv
from axiscal.io.rtx import format_rtx
from axiscal.machines.config import axis_from_config
from axiscal.procedures.record_simulation import RecordSettings, simulate_record
from tests.cli.test_cli_measured import AXIS, _write_raw
from tests.web.test_browser_kinds import _full_page_shot
from tests.web.test_measured_uploads import _epics_log

runner = CliRunner()
FORM = "form[action='/upload/measured']"


def _cli(*args) -> dict:
    r = runner.invoke(app, [str(a) for a in args])
    assert r.exit_code == 0, r.output
    return json.loads(r.stdout)


def _send(browser, base, kind: str, first, second=None, **fields) -> str:
    """Fill the measured-upload form (kind, files, fields) and send it; the page it leads to."""
    browser.get(base + "/upload")
    form = browser.find_element(By.CSS_SELECTOR, FORM)
    Select(form.find_element(By.NAME, "kind")).select_by_value(kind)
    form.find_element(By.NAME, "file").send_keys(str(first))
    if second is not None:
        form.find_element(By.NAME, "second").send_keys(str(second))
    for name, value in fields.items():
        box = form.find_element(By.NAME, name)
        box.clear()
        box.send_keys(value)
    form.find_element(By.CSS_SELECTOR, "button").click()
    WebDriverWait(browser, 120).until(lambda d: "/tests/" in d.current_url
                                      or d.find_elements(By.CSS_SELECTOR, "[role=alert]"))
    alerts = browser.find_elements(By.CSS_SELECTOR, "[role=alert]")
    assert "/tests/" in browser.current_url, alerts[0].text if alerts else browser.page_source
    return browser.current_url


def _figures(browser) -> dict:
    """The parameter table of the test page: name -> value as written (three decimals)."""
    rows = [[c.text for c in r.find_elements(By.TAG_NAME, "td")]
            for r in browser.find_elements(By.CSS_SELECTOR, "#parameters tbody tr")]
    return {r[0]: r[1] for r in rows}


def _same_as_cli(browser, cli: dict) -> None:
    shown = _figures(browser)
    for k in ("A", "E", "M", "R", "B"):
        assert shown[k] == f"{cli[k]:.3f}", k


def test_a_capture_uploaded_in_a_browser_shows_the_cli_figures(server, browser, tmp_path):
    _cli("plan", "linear", "--length", "800", "--runs", "2", "--dwell", "2", "--csv",
         tmp_path / "plan.csv", "--json")
    plan = parse_plan_csv((tmp_path / "plan.csv").read_text())
    _, x, _ = simulate_record(plan, axis_from_config(AXIS), np.random.default_rng(6),
                              RecordSettings(sample_rate=1000.0))
    (tmp_path / "run.rtx").write_bytes(format_rtx(x * 1e6, 1000.0, Axis="X"))
    found = _cli("capture", tmp_path / "run.rtx", "--plan", tmp_path / "plan.csv", "--out",
                 tmp_path / "d.csv", "--json")
    cli = _cli("iso230-2", tmp_path / "d.csv", "--json")
    _send(browser, server, "capture", tmp_path / "run.rtx", tmp_path / "plan.csv",
          machine="VMC-800 capture", axis="X")
    _same_as_cli(browser, cli)
    assert (f"{found['stops']} stops found, {found['measurements']} measurements matched"
            in browser.page_source)
    _full_page_shot(browser, "measured_capture_page")


def test_raw_readings_and_environment_uploaded_in_a_browser(server, browser, tmp_path):
    _write_raw(tmp_path)
    done = _cli("compensate-environment", tmp_path / "raw.csv", "--environment",
                tmp_path / "env.csv", "--out", tmp_path / "d.csv", "--json")
    cli = _cli("iso230-2", tmp_path / "d.csv", "--json")
    _send(browser, server, "raw", tmp_path / "raw.csv", tmp_path / "env.csv",
          note="after the warm-up")
    _same_as_cli(browser, cli)
    assert done["applied"] in browser.find_element(By.TAG_NAME, "body").text
    _full_page_shot(browser, "measured_raw_page")


def test_an_epics_log_uploaded_in_a_browser(server, browser, tmp_path):
    log, sp, ref = _epics_log(tmp_path)
    cli = _cli("iso230-2", log, "--setpoint-pv", sp, "--reference-pv", ref, "--json")
    _send(browser, server, "epics", log, machine="MCU1025", axis="X", setpoint_pv=sp,
          reference_pv=ref)
    _same_as_cli(browser, cli)
    body = browser.find_element(By.TAG_NAME, "body").text
    assert "--reference-scale not given: 1 (ecmc's REF_GR)" in body
    assert "--rest-window not given: 1 µm" in body
    _full_page_shot(browser, "measured_epics_page")


@pytest.fixture(autouse=True)
def _upload_form_first_shot(request, server, browser):
    """The upload page with the EPICS settings, once, before the first upload of the module."""
    if request.node.name.startswith("test_a_capture"):
        browser.get(server + "/upload")
        _full_page_shot(browser, "measured_upload_form")
    yield
