"""A real workbench server (``axiscal serve`` in a subprocess on 127.0.0.1) and a real browser
(Debian's chromium driven by Selenium through Debian's chromium-driver) for the web tests."""

from __future__ import annotations

import os
import socket
import subprocess
import sys
import time
import urllib.request
from pathlib import Path

import pytest

ARTIFACTS = Path(__file__).resolve().parents[2] / "test-artifacts" / "web"


def _free_port() -> int:
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


def start_server(folder: Path, *args: str, env: dict | None = None):
    """``axiscal serve ARGS`` on a free port over a fresh SQLite history in ``folder``; returns
    (process, base URL) once it answers."""
    port = _free_port()
    env = {**os.environ, "AXISCAL_DB": f"sqlite:///{folder / 'history.sqlite'}", **(env or {})}
    if "--workers" not in args:      # one process: the per-process limits the tests count
        args = ("--workers", "1", *args)
    proc = subprocess.Popen([sys.executable, "-m", "axiscal", "serve", "--port", str(port), *args],
                            env=env, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE)
    base = f"http://127.0.0.1:{port}"
    deadline = time.monotonic() + 30
    while True:
        try:
            urllib.request.urlopen(base + "/login", timeout=1).read()
            return proc, base
        except OSError:
            if proc.poll() is not None or time.monotonic() > deadline:
                proc.kill()
                raise RuntimeError("the workbench did not start: "
                                   + proc.stderr.read().decode(errors="replace"))
            time.sleep(0.1)


def stop_server(proc) -> None:
    proc.terminate()
    proc.wait(10)


@pytest.fixture(scope="module")
def server(tmp_path_factory):
    """The workbench on a fresh SQLite history; yields its base URL."""
    proc, base = start_server(tmp_path_factory.mktemp("web"))
    yield base
    stop_server(proc)


@pytest.fixture(scope="module")
def browser(tmp_path_factory):
    """Headless Chromium (Debian's), downloads into a temporary folder (``browser.downloads``)."""
    driver = make_browser(tmp_path_factory)
    yield driver
    driver.quit()


def make_browser(tmp_path_factory, *flags: str):
    """A headless Chromium with these further command-line flags (the caller quits it)."""
    from selenium import webdriver
    from selenium.webdriver.chrome.service import Service

    downloads = tmp_path_factory.mktemp("downloads")
    opts = webdriver.ChromeOptions()
    opts.binary_location = "/usr/bin/chromium"
    for flag in ("--headless", "--no-sandbox", "--disable-gpu", "--disable-quic",
                 "--no-first-run", "--disable-background-networking",
                 "--disable-component-update", "--disable-sync", "--window-size=1280,1600"):
        opts.add_argument(flag)
    for flag in flags:
        opts.add_argument(flag)
    opts.add_argument(f"--user-data-dir={tmp_path_factory.mktemp('profile')}")
    opts.add_experimental_option("prefs", {"download.default_directory": str(downloads),
                                           "download.prompt_for_download": False})
    driver = webdriver.Chrome(service=Service("/usr/bin/chromedriver"), options=opts)
    driver.execute_cdp_cmd("Page.setDownloadBehavior",
                           {"behavior": "allow", "downloadPath": str(downloads)})
    driver.downloads = downloads
    ARTIFACTS.mkdir(parents=True, exist_ok=True)
    return driver


def replaced(element):
    """A wait condition: ``element`` is no longer in the page (the answer's page or the swapped
    section is there). Selenium's ``staleness_of`` knows only StaleElementReferenceException;
    Chromium may instead answer "Node with given id does not belong to the document" while the
    old page is torn down, which means the same."""
    from selenium.common.exceptions import StaleElementReferenceException, WebDriverException

    def gone(_driver) -> bool:
        try:
            element.is_enabled()
            return False
        except StaleElementReferenceException:
            return True
        except WebDriverException as e:
            if "does not belong to the document" in str(e):
                return True
            raise
    return gone


def shot(driver, name: str) -> Path:
    """A screenshot kept in test-artifacts/web/ (to be looked at)."""
    p = ARTIFACTS / f"{name}.png"
    driver.save_screenshot(str(p))
    return p


@pytest.fixture
def users(tmp_path):
    """A users file with an engineer (eng) and a viewer (view)."""
    from axiscal.web.security import UserFile

    f = UserFile.load(tmp_path / "users.toml")
    f.add("eng", "engineer", "correct horse battery")
    f.add("view", "viewer", "staple battery horse")
    return tmp_path / "users.toml"


def positioning_file() -> bytes:
    """A bidirectional ISO 230-2 test of an 800 mm axis of machine VMC-800 as tidy CSV bytes
    (9 targets, 5 runs, seeded: E about 10.6 µm), the file the page and sign-off tests upload."""
    import numpy as np

    from axiscal.datasets import Metadata, PositioningDataset
    from axiscal.io.csv import format_positioning_csv

    rng = np.random.default_rng(9)
    t = np.linspace(0, 800, 9)
    up = rng.normal(1.0, 0.5, (9, 5)) + t[:, None] * 0.01
    return format_positioning_csv(PositioningDataset(
        "linear", t, up, up - 2.0, "mm", "um",
        Metadata(machine="VMC-800", axis="X", date="2026-03-01"))).encode()


def log_in(client, name, password, **kw):
    """POST /login by a TestClient; the answer, not followed."""
    return client.post("/login", data={"username": name, "password": password, "next": "/"},
                       follow_redirects=False, **kw)
