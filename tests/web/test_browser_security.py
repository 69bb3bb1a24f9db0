"""The hardened workbench in a real browser (issue 31): error pages in the workbench's style with
a way back, a log-out that a copied cookie does not survive, and the lock-out after wrong
passwords said on the login page, a DNS-rebound name and another site's form refused.
Screenshots in test-artifacts/web/ (error_404.png, error_compare.png, login_lockout.png,
rebinding.png, cross_site_post.png)."""

from __future__ import annotations

import pytest
from selenium.webdriver.common.by import By
from selenium.webdriver.support.ui import WebDriverWait

from axiscal.web.security import UserFile
from axiscal.web.sessions import FREE_FAILURES
from tests.web.conftest import make_browser, replaced, shot, start_server, stop_server


@pytest.fixture(scope="module")
def login_server(tmp_path_factory):
    d = tmp_path_factory.mktemp("login")
    users = UserFile.load(d / "users.toml")
    users.add("eng", "engineer", "correct horse battery")
    proc, base = start_server(d, "--users", str(d / "users.toml"))
    yield base
    stop_server(proc)


def _log_in(browser, base, name, password):
    browser.get(base + "/login")
    browser.find_element(By.NAME, "username").send_keys(name)
    browser.find_element(By.NAME, "password").send_keys(password)
    button = browser.find_element(By.CSS_SELECTOR, "form.card button")
    button.click()
    WebDriverWait(browser, 20).until(replaced(button))       # the answer's page is here


def test_error_pages_have_the_workbench_style_and_a_way_back(server, browser):
    browser.get(server + "/plan")
    browser.get(server + "/tests/abc")
    main = browser.find_element(By.TAG_NAME, "main").text
    assert "HTTP 404" in main and "no such page" in main
    assert browser.find_elements(By.CSS_SELECTOR, "header a.brand"), "not the workbench's page"
    assert "{" not in browser.find_element(By.TAG_NAME, "body").text[:5]   # not raw JSON
    shot(browser, "error_404")
    browser.get(server + "/compare?a=1")
    assert "choose two tests" in browser.find_element(By.CSS_SELECTOR, ".error").text
    shot(browser, "error_compare")
    browser.find_element(By.LINK_TEXT, "Back to the machines").click()
    WebDriverWait(browser, 10).until(lambda d: d.title.startswith("Machines"))


def test_a_copied_cookie_is_dead_after_log_out(login_server, browser):
    _log_in(browser, login_server, "eng", "correct horse battery")
    assert "eng (engineer)" in browser.find_element(By.TAG_NAME, "header").text
    cookie = browser.get_cookie("axiscal_session")
    browser.find_element(By.CSS_SELECTOR, "header form button").click()
    WebDriverWait(browser, 10).until(lambda d: "/login" in d.current_url)
    browser.add_cookie({"name": cookie["name"], "value": cookie["value"], "path": "/"})
    browser.get(login_server + "/")
    assert "/login" in browser.current_url


def test_the_lock_out_is_said_on_the_login_page(login_server, browser):
    for _ in range(FREE_FAILURES):
        _log_in(browser, login_server, "eng", "wrong password")
        assert "wrong user name or password" in browser.find_element(By.CSS_SELECTOR,
                                                                     ".error").text
    _log_in(browser, login_server, "eng", "correct horse battery")
    words = browser.find_element(By.CSS_SELECTOR, ".error").text
    assert "too many wrong passwords" in words and "try again in" in words
    assert "/login" in browser.current_url
    shot(browser, "login_lockout")


@pytest.fixture(scope="module")
def rebound(tmp_path_factory):
    """A browser for which evil.example resolves to 127.0.0.1: what DNS rebinding achieves."""
    driver = make_browser(tmp_path_factory, "--host-resolver-rules=MAP evil.example 127.0.0.1")
    yield driver
    driver.quit()


def test_a_rebound_name_gets_no_page_and_no_token(server, rebound):
    port = server.rsplit(":", 1)[1]
    for path in ("/", "/upload", "/plan"):
        rebound.get(f"http://evil.example:{port}{path}")
        assert "does not answer to that host name" in rebound.find_element(
            By.CSS_SELECTOR, ".error").text, path
        token = rebound.find_element(By.CSS_SELECTOR, 'meta[name="csrf-token"]')
        assert token.get_attribute("content") == "", path
    assert not rebound.find_elements(By.NAME, "file")          # no upload form
    shot(rebound, "rebinding")


def test_another_sites_form_is_refused(server, browser, tmp_path):
    """A page elsewhere (here a local file: its Origin is "null") that posts to the workbench."""
    page = tmp_path / "attack.html"
    page.write_text(f'<form method="post" action="{server}/plan"><input name="kind" '
                    'value="linear"><input name="travel" value="800"></form>'
                    '<script>document.forms[0].submit()</script>')
    browser.get(page.as_uri())
    WebDriverWait(browser, 20).until(lambda d: d.current_url.startswith(server))
    assert "sent from another site" in browser.find_element(By.CSS_SELECTOR, ".error").text
    assert "HTTP 403" in browser.find_element(By.TAG_NAME, "main").text
    shot(browser, "cross_site_post")
