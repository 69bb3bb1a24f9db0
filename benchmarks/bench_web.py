"""Workbench under load (issues 31 and 40): 20 people browsing and 3 uploading at once against
``axiscal serve --workers 2`` on 127.0.0.1, with a history of 1,000 tests on one axis, beside the
same pages for one person alone, in :data:`RUNS` runs.

A person browsing loops: the machine's history page (1,000 tests, the newest 100 shown, as the
workbench pages them), then a test page. A person uploading loops: an upload of a new test (the
POST and the stored test's page it is sent on to). Two loads: *people* pause between their
requests (:data:`PAUSES`: a second's look at each page, two seconds to pick the next file), and
*no pause* (each of the 23 sends its next request as soon as the last is answered: a load
generator, the busiest case, as issue 31 measured it). Each run: one person browsing alone and one
uploading alone (:data:`SINGLE_SECONDS` each, no pause: the reference), then the 23 at once,
with pauses and without (:data:`SECONDS` each). Reported: the median over the runs of each run's
p95 latency per page kind (with every run's figure) beside the median of the single-person p95
(ratio = 23 people / 1 person; aims: pages p95 under 200 ms, an upload under 500 ms, no error)
with the median p50 and the largest latency, requests per second, errors, and whether every
accepted upload is in the database afterwards. Beside them, what bounds the latency: the CPU
the server's processes used per request (user + system time of the ``axiscal serve`` process
and its workers, from ``/proc``, over the phase) and the CPU the clients used per request (this
process, which sends every request), and the load average during the phase (other work on the
same cores). Evaluations are kept by :mod:`axiscal.store.cache` in a cache folder of this run
(``AXISCAL_CACHE``), made when the history is filled, as an upload does.

``AXISCAL_BENCH_RUNS`` sets the number of runs (default :data:`RUNS`), for a quick look.
``AXISCAL_BENCH_PIN=1`` runs the server on the first core and the clients on the second
(``sched_setaffinity``, as ``taskset``; Linux): what the clients' own share of the CPU does to
the figures (other work on the machine still shares both cores).
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

BROWSING, UPLOADING, SECONDS, SINGLE_SECONDS, TESTS, WORKERS, RUNS = 20, 3, 20.0, 6.0, 1000, 2, 5
#: Seconds a person pauses after a page (browsing) and after an upload (picking the next file).
PAUSES = (1.0, 2.0)
#: Most requests one phase makes (a bound besides the time).
MAX_REQUESTS = 20_000
#: The page kinds and their aims (p95, ms).
AIMS = {"history page (1,000 tests)": 200, "test page": 200, "upload": 500}


def _file(k: int) -> bytes:
    rng = np.random.default_rng(k)
    t = np.linspace(0, 800, 21)
    up = rng.normal(0, 1, (21, 5))
    return format_positioning_csv(PositioningDataset(
        "linear", t, up, up - 2, "mm", "um",
        Metadata(machine="VMC-800", axis="X",
                 date=f"{1990 + k // 365 % 30}-{k // 31 % 12 + 1:02d}-{k % 28 + 1:02d}"))).encode()


def _browse(c, lat, errors, k: int, seed: int, pause: float = 0.0, stop=None) -> None:
    for i, (kind, call) in enumerate((
            ("history page (1,000 tests)", lambda: c.get("/machine/1")),
            ("test page", lambda: c.get(f"/tests/{1 + (k * 37 + seed) % TESTS}")))):
        if i and pause:
            stop.wait(pause)
        t0 = time.perf_counter()
        r = call()
        lat.setdefault(kind, []).append(time.perf_counter() - t0)
        if r.status_code != 200:
            errors.append((kind.split(" ")[0], r.status_code))


def _upload(c, token, lat, errors, uploaded, k: int, seed: int) -> None:
    n = 10_000_000 + seed * 100_000 + k
    t0 = time.perf_counter()
    r = c.post("/upload", data={"csrf": token},
               files={"file": (f"u{n}.csv", _file(n), "text/csv")})
    lat.setdefault("upload", []).append(time.perf_counter() - t0)
    if r.status_code != 200 or "/tests/" not in str(r.url):
        errors.append(("upload", r.status_code))
    else:
        uploaded.append(n)


def _person(base, stop, lat, errors, uploaded, seed, budget, uploads: bool, pauses):
    import httpx

    c = httpx.Client(base_url=base, timeout=60, follow_redirects=True)
    token = re.search(r'csrf-token" content="([^"]+)"', c.get("/").text).group(1)
    rng = np.random.default_rng(seed)
    stop.wait(rng.uniform(0, pauses[1]))             # people do not start in step
    k = 0
    while not stop.is_set() and next(budget, None) is not None:
        if uploads:
            _upload(c, token, lat, errors, uploaded, k, seed)
        else:
            _browse(c, lat, errors, k, seed, pauses[0], stop)
        k += 1
        stop.wait(pauses[1] if uploads else pauses[0])


def _cpu_seconds(pid: int) -> float:
    """User + system CPU seconds of process ``pid`` and of every process below it (Linux
    ``/proc``; 0 where there is none): the server's master and its worker processes."""
    ticks = os.sysconf("SC_CLK_TCK") if hasattr(os, "sysconf") else 100
    parents, total = {}, 0.0
    for d in Path("/proc").glob("[0-9]*"):
        try:
            fields = (d / "stat").read_text().rsplit(")", 1)[1].split()
        except OSError:
            continue
        parents[int(d.name)] = (int(fields[1]), (int(fields[11]) + int(fields[12])) / ticks)
    wanted = {pid}
    grew = True
    while grew:
        more = {p for p, (pp, _) in parents.items() if pp in wanted} - wanted
        wanted |= more
        grew = bool(more)
    for p in wanted:
        total += parents.get(p, (0, 0.0))[1]
    return total


def _phase(base, browsing: int, uploading: int, seconds: float, first_seed: int,
           pauses=(0.0, 0.0), server: int = 0):
    """``browsing`` + ``uploading`` people for ``seconds`` (or :data:`MAX_REQUESTS` loops at
    most), pausing ``pauses`` (after a page, after an upload): (latencies by kind, errors,
    uploads, seconds elapsed, CPU seconds of the server ``server`` (a pid) and of the clients,
    load average at the end)."""
    lat, errors, uploaded = {}, [], []
    cpu0, mine0 = _cpu_seconds(server), time.process_time()
    stop = threading.Event()
    budget = iter(range(MAX_REQUESTS // 2))          # shared by the people's loops
    people = [False] * browsing + [True] * uploading
    threads = [threading.Thread(target=_person, args=(base, stop, lat, errors, uploaded,
                                                      first_seed + i, budget, up, pauses))
               for i, up in enumerate(people)]
    t0 = time.perf_counter()
    for t in threads:
        t.start()
    deadline = t0 + seconds
    while time.perf_counter() < deadline and any(t.is_alive() for t in threads):
        time.sleep(0.05)
    stop.set()
    for t in threads:
        t.join(60)
    return (lat, errors, uploaded, time.perf_counter() - t0, _cpu_seconds(server) - cpu0,
            time.process_time() - mine0, os.getloadavg()[0])


def _pinned() -> bool:
    return os.environ.get("AXISCAL_BENCH_PIN", "") not in ("", "0") and \
        hasattr(os, "sched_setaffinity") and (os.cpu_count() or 1) >= 2


def _serve(url: str, cache: str):
    with socket.socket() as so:
        so.bind(("127.0.0.1", 0))
        port = so.getsockname()[1]
    pin = (lambda: os.sched_setaffinity(0, {0})) if _pinned() else None
    proc = subprocess.Popen([sys.executable, "-m", "axiscal", "serve", "--port", str(port),
                             "--db", url, "--workers", str(WORKERS)],
                            stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL,
                            env={**os.environ, "AXISCAL_CACHE": cache}, preexec_fn=pin)
    return proc, f"http://127.0.0.1:{port}"


def run(runs: int = RUNS) -> list[dict]:
    before = os.environ.get("AXISCAL_CACHE")
    cores = os.sched_getaffinity(0) if _pinned() else None
    try:
        return _run(runs)
    finally:
        if cores is not None:
            os.sched_setaffinity(0, cores)
        if before is None:
            os.environ.pop("AXISCAL_CACHE", None)
        else:
            os.environ["AXISCAL_CACHE"] = before


def _run(runs: int) -> list[dict]:
    import httpx

    runs = int(os.environ.get("AXISCAL_BENCH_RUNS", runs))
    with tempfile.TemporaryDirectory() as d:
        os.environ["AXISCAL_CACHE"] = cache = str(Path(d) / "cache")
        url = f"sqlite:///{Path(d) / 'h.sqlite'}"
        s = open_store(url)
        for k in range(TESTS):
            s.add(_file(k), f"t{k}.csv")
        s.close()
        proc, base = _serve(url, cache)
        if _pinned():
            os.sched_setaffinity(0, {1})                 # the clients: the other core
        results = []
        try:
            for _ in range(300):
                try:
                    httpx.get(base + "/plan", timeout=1)
                    break
                except httpx.HTTPError:
                    time.sleep(0.1)
            for r in range(runs):
                seed, pid = 1000 * (r + 1), proc.pid
                alone = _merged(_phase(base, 1, 0, SINGLE_SECONDS, seed, server=pid),
                                _phase(base, 0, 1, SINGLE_SECONDS, seed + 100, server=pid))
                results.append((alone, _phase(base, BROWSING, UPLOADING, SECONDS, seed + 200,
                                              PAUSES, server=pid),
                                _phase(base, BROWSING, UPLOADING, SECONDS, seed + 300,
                                       server=pid)))
        finally:
            proc.terminate()
            proc.wait(30)
        stored = len(open_store(url).tests())
    return _rows(results, stored)


def _merged(a, b):
    lat = {**a[0], **b[0]}
    return (lat, a[1] + b[1], a[2] + b[2], a[3] + b[3], a[4] + b[4], a[5] + b[5],
            max(a[6], b[6]))


def _rows(results, stored) -> list[dict]:
    people = f"{BROWSING} browsing + {UPLOADING} uploading"
    pin = "; server on core 0, clients on core 1" if _pinned() else ""
    loads = ((f"1 person (browsing, then uploading){pin}", 0),
             (f"{people}, pausing {PAUSES[0]:g} s / {PAUSES[1]:g} s{pin}", 1),
             (f"{people}, no pause{pin}", 2))
    n1 = sum(sum(len(v) for v in r[0][0].values()) for r in results)
    t1 = sum(r[0][3] for r in results)
    errors = [e for r in results for phase in r for e in phase[1]]
    uploads = sum(len(phase[2]) for r in results for phase in r)
    rows = [dict(name=f"workbench: errors ({len(results)} runs)", value=len(errors),
                 unit="requests", aim="0",
                 reference=", ".join(sorted({f"{k} {c}" for k, c in errors})) or None),
            dict(name="workbench: uploads lost (accepted but not in the database)",
                 value=TESTS + uploads - stored, unit="tests", aim="0")]
    for load, j in loads:
        n = sum(sum(len(v) for v in r[j][0].values()) for r in results)
        t = sum(r[j][3] for r in results)
        loadavg = [r[j][6] for r in results]
        vs = " (/ 1 person)" if j else ""
        rows.append(dict(name=f"workbench, {WORKERS} workers, {load}: requests per second{vs}",
                         value=n / t, unit="req/s",
                         reference=f"1 person {n1 / t1:.0f} req/s; load average "
                                   f"{min(loadavg):.1f}-{max(loadavg):.1f}",
                         ratio=(n / t) / (n1 / t1) if j else None))
        server, clients = (sum(r[j][k] for r in results) for k in (4, 5))
        rows.append(dict(name=f"workbench, {load}: server CPU per request (/ clients' CPU)",
                         value=server / max(n, 1) * 1e3, unit="ms/req",
                         reference=f"clients {clients / max(n, 1) * 1e3:.1f} ms/req; server "
                                   f"{server / t:.2f} of a core, clients {clients / t:.2f}",
                         ratio=server / clients if clients else None))
        for kind, aim in AIMS.items():
            per_run = [np.asarray(r[j][0][kind]) * 1e3 for r in results if r[j][0].get(kind)]
            ref = [float(np.percentile(r[0][0][kind], 95)) * 1e3 for r in results
                   if r[0][0].get(kind)]
            if not per_run or not ref:
                continue
            p95 = [float(np.percentile(v, 95)) for v in per_run]
            p50 = float(np.median([np.percentile(v, 50) for v in per_run]))
            worst = max(float(v.max()) for v in per_run)
            mid, alone = float(np.median(p95)), float(np.median(ref))
            rows.append(dict(
                name=f"workbench p95, {load}: {kind}{vs}", value=mid, unit="ms",
                reference=f"p50 {p50:.0f} ms, max {worst:.0f} ms; runs' p95 "
                          f"{' '.join(f'{v:.0f}' for v in p95)} ms"
                          + (f"; 1 person p95 {alone:.0f} ms" if j else ""),
                ratio=mid / alone if j else None, aim=f"< {aim} ms" if j else None))
    return rows
