"""Workbench under load (issue 15): 20 concurrent clients browsing and uploading for 30 s against
``axiscal serve`` on 127.0.0.1, with a history of 1,000 tests on one axis.

Each client loops: the machine's history page (1,000 tests, the newest 100 shown, as the
workbench pages them), a test page, and every fifth loop
an upload of a new test. Reported: requests per second, p95 latency per page kind (aim: p95
under 200 ms for the history page of 1,000 tests), errors (aim: none) and whether every
accepted upload is in the database afterwards. The reference is a bare ``GET /static/htmx.min.js``
(the server's floor for one request) measured in the same run.
"""

from __future__ import annotations

import os
import re
import socket
import subprocess
import sys
import tempfile
import threading
import time
from pathlib import Path

import numpy as np

from axiscal.datasets import Metadata, PositioningDataset
from axiscal.io.csv import format_positioning_csv
from axiscal.store import open_store

CLIENTS, SECONDS, TESTS = 20, 30.0, 1000


def _file(k: int) -> bytes:
    rng = np.random.default_rng(k)
    t = np.linspace(0, 800, 21)
    up = rng.normal(0, 1, (21, 5))
    return format_positioning_csv(PositioningDataset(
        "linear", t, up, up - 2, "mm", "um",
        Metadata(machine="VMC-800", axis="X",
                 date=f"{1990 + k // 365 % 30}-{k // 31 % 12 + 1:02d}-{k % 28 + 1:02d}"))).encode()


def _client(base, stop, lat, errors, uploaded, seed):
    import httpx

    c = httpx.Client(base_url=base, timeout=60)
    token = re.search(r'csrf-token" content="([^"]+)"', c.get("/").text).group(1)
    k = 0
    while not stop.is_set():
        for kind, call in (("history page (1,000 tests)", lambda: c.get("/machines/VMC-800")),
                           ("test page", lambda: c.get(f"/tests/{1 + (k * 37 + seed) % TESTS}"))):
            t0 = time.perf_counter()
            r = call()
            lat.setdefault(kind, []).append(time.perf_counter() - t0)
            if r.status_code != 200:
                errors.append((kind.split(" ")[0], r.status_code))
        if k % 5 == 0:
            n = 10_000_000 + seed * 100_000 + k
            t0 = time.perf_counter()
            r = c.post("/upload", data={"csrf": token},
                       files={"file": (f"u{n}.csv", _file(n), "text/csv")})
            lat.setdefault("upload", []).append(time.perf_counter() - t0)
            if r.status_code != 200 or "/tests/" not in str(r.url):
                errors.append(("upload", r.status_code))
            else:
                uploaded.append(n)
        k += 1


def run() -> list[dict]:
    import httpx

    with tempfile.TemporaryDirectory() as d:
        url = f"sqlite:///{Path(d) / 'h.sqlite'}"
        s = open_store(url)
        for k in range(TESTS):
            s.add(_file(k), f"t{k}.csv")
        s.close()
        with socket.socket() as so:
            so.bind(("127.0.0.1", 0))
            port = so.getsockname()[1]
        proc = subprocess.Popen([sys.executable, "-m", "axiscal", "serve", "--port", str(port),
                                 "--db", url], stdout=subprocess.DEVNULL,
                                stderr=subprocess.DEVNULL, env=os.environ)
        base = f"http://127.0.0.1:{port}"
        try:
            for _ in range(300):
                try:
                    httpx.get(base + "/plan", timeout=1)
                    break
                except httpx.HTTPError:
                    time.sleep(0.1)
            floor = []
            with httpx.Client(base_url=base) as c:
                for _ in range(50):
                    t0 = time.perf_counter()
                    c.get("/static/htmx.min.js")
                    floor.append(time.perf_counter() - t0)
            lat, errors, uploaded = {}, [], []
            stop = threading.Event()
            threads = [threading.Thread(target=_client, args=(base, stop, lat, errors, uploaded,
                                                              i)) for i in range(CLIENTS)]
            t0 = time.perf_counter()
            for t in threads:
                t.start()
            time.sleep(SECONDS)
            stop.set()
            for t in threads:
                t.join(60)
            elapsed = time.perf_counter() - t0
        finally:
            proc.terminate()
            proc.wait(10)
        stored = len(open_store(url).tests())
    total = sum(len(v) for v in lat.values())
    ref = float(np.percentile(floor, 95))
    rows = [dict(name=f"workbench: {CLIENTS} clients for {SECONDS:.0f} s, requests per second",
                 value=total / elapsed, unit="req/s"),
            dict(name="workbench: errors", value=len(errors), unit="requests", aim="0",
                 reference=", ".join(sorted({f"{k} {c}" for k, c in errors})) or None),
            dict(name="workbench: uploads lost (accepted but not in the database)",
                 value=TESTS + len(uploaded) - stored, unit="tests", aim="0")]
    for kind, v in lat.items():
        p95 = float(np.percentile(v, 95))
        rows.append(dict(name=f"workbench p95: {kind} (/ static file p95)", value=p95 * 1e3,
                         unit="ms", reference=f"static file {ref * 1e3:.1f} ms", ratio=p95 / ref,
                         aim="< 200 ms" if kind.startswith("history") else None))
    return rows
