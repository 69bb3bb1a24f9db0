"""Workbench under load (issue 31): 20 concurrent clients browsing and uploading against
``axiscal serve --workers 2`` on 127.0.0.1, with a history of 1,000 tests on one axis, and one
client alone in the same run.

Each client loops: the machine's history page (1,000 tests, the newest 100 shown, as the
workbench pages them), a test page, and every fifth loop an upload of a new test. Bounded: each
phase stops after :data:`SECONDS` (one client: :data:`SINGLE_SECONDS`) or :data:`MAX_REQUESTS`
requests, whichever comes first. Reported: requests per second, p95 latency per page kind at 20
clients (aim: p95 under 200 ms, no error) beside the same page's p95 for one client alone (the
reference, measured in the same run: ratio = 20 clients / 1 client), and whether every accepted
upload is in the database afterwards. Evaluations are kept by :mod:`axiscal.store.cache` in a
cache folder of this run (``AXISCAL_CACHE``), made when the history is filled, as an upload does.
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

CLIENTS, SECONDS, SINGLE_SECONDS, TESTS, WORKERS = 20, 30.0, 10.0, 1000, 2
#: Most requests one phase makes (a bound besides the time).
MAX_REQUESTS = 20_000


def _file(k: int) -> bytes:
    rng = np.random.default_rng(k)
    t = np.linspace(0, 800, 21)
    up = rng.normal(0, 1, (21, 5))
    return format_positioning_csv(PositioningDataset(
        "linear", t, up, up - 2, "mm", "um",
        Metadata(machine="VMC-800", axis="X",
                 date=f"{1990 + k // 365 % 30}-{k // 31 % 12 + 1:02d}-{k % 28 + 1:02d}"))).encode()


def _client(base, stop, lat, errors, uploaded, seed, budget):
    import httpx

    c = httpx.Client(base_url=base, timeout=60, follow_redirects=True)
    token = re.search(r'csrf-token" content="([^"]+)"', c.get("/").text).group(1)
    k = 0
    while not stop.is_set() and next(budget, None) is not None:
        for kind, call in (("history page (1,000 tests)", lambda: c.get("/machine/1")),
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


def _phase(base, clients: int, seconds: float, first_seed: int):
    """``clients`` clients for ``seconds`` (or :data:`MAX_REQUESTS` loops of three requests at
    most): (latencies by kind, errors, uploads, seconds elapsed)."""
    lat, errors, uploaded = {}, [], []
    stop = threading.Event()
    budget = iter(range(MAX_REQUESTS // 3))          # shared by the clients' loops
    threads = [threading.Thread(target=_client, args=(base, stop, lat, errors, uploaded,
                                                      first_seed + i, budget))
               for i in range(clients)]
    t0 = time.perf_counter()
    for t in threads:
        t.start()
    deadline = t0 + seconds
    while time.perf_counter() < deadline and any(t.is_alive() for t in threads):
        time.sleep(0.05)
    stop.set()
    for t in threads:
        t.join(60)
    return lat, errors, uploaded, time.perf_counter() - t0


def _serve(url: str, cache: str):
    with socket.socket() as so:
        so.bind(("127.0.0.1", 0))
        port = so.getsockname()[1]
    proc = subprocess.Popen([sys.executable, "-m", "axiscal", "serve", "--port", str(port),
                             "--db", url, "--workers", str(WORKERS)],
                            stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL,
                            env={**os.environ, "AXISCAL_CACHE": cache})
    return proc, f"http://127.0.0.1:{port}"


def run() -> list[dict]:
    before = os.environ.get("AXISCAL_CACHE")
    try:
        return _run()
    finally:
        if before is None:
            os.environ.pop("AXISCAL_CACHE", None)
        else:
            os.environ["AXISCAL_CACHE"] = before


def _run() -> list[dict]:
    import httpx

    with tempfile.TemporaryDirectory() as d:
        os.environ["AXISCAL_CACHE"] = cache = str(Path(d) / "cache")
        url = f"sqlite:///{Path(d) / 'h.sqlite'}"
        s = open_store(url)
        for k in range(TESTS):
            s.add(_file(k), f"t{k}.csv")
        s.close()
        proc, base = _serve(url, cache)
        try:
            for _ in range(300):
                try:
                    httpx.get(base + "/plan", timeout=1)
                    break
                except httpx.HTTPError:
                    time.sleep(0.1)
            one = _phase(base, 1, SINGLE_SECONDS, 1000)
            many = _phase(base, CLIENTS, SECONDS, 0)
        finally:
            proc.terminate()
            proc.wait(30)
        stored = len(open_store(url).tests())
    return _rows(one, many, stored)


def _rows(one, many, stored) -> list[dict]:
    lat1, err1, up1, t1 = one
    lat, errors, uploaded, elapsed = many
    n1, n = sum(len(v) for v in lat1.values()), sum(len(v) for v in lat.values())
    rows = [dict(name=f"workbench, {WORKERS} workers: 1 client, requests per second",
                 value=n1 / t1, unit="req/s"),
            dict(name=f"workbench, {WORKERS} workers: {CLIENTS} clients, requests per second "
                 "(/ 1 client)", value=n / elapsed, unit="req/s",
                 reference=f"1 client {n1 / t1:.0f} req/s", ratio=(n / elapsed) / (n1 / t1)),
            dict(name="workbench: errors (1 and 20 clients)", value=len(errors) + len(err1),
                 unit="requests", aim="0",
                 reference=", ".join(sorted({f"{k} {c}" for k, c in errors + err1})) or None),
            dict(name="workbench: uploads lost (accepted but not in the database)",
                 value=TESTS + len(uploaded) + len(up1) - stored, unit="tests", aim="0")]
    for kind, v in lat.items():
        p95, ref = float(np.percentile(v, 95)), float(np.percentile(lat1[kind], 95))
        rows.append(dict(name=f"workbench p95 at {CLIENTS} clients: {kind} (/ 1 client)",
                         value=p95 * 1e3, unit="ms", reference=f"1 client p95 {ref * 1e3:.1f} ms",
                         ratio=p95 / ref, aim="< 200 ms"))
    return rows
