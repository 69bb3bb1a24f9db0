"""Password guessing against the workbench (issue 31): a logged-in user's ``GET /plan`` latency
while another client guesses passwords as fast as it can, against ``axiscal serve`` with accounts
on 127.0.0.1.

Before issue 31 every guess ran an Argon2id verification on the event loop: the other user's
``/plan`` went from 4 ms to 278 ms median. Now the verification runs in a worker thread and after
5 wrong passwords the account and the address are locked out (429, no verification). Reported:
``/plan`` median and p95 while guessing, as a ratio to the same page's median measured just before
without guessing (the reference, same run), and how the guesses were answered.
"""

from __future__ import annotations

import os
import subprocess
import sys
import tempfile
import threading
import time
from pathlib import Path

import numpy as np

SAMPLES, GUESSING, PASSWORD = 200, 15.0, "correct horse battery"


def _guess(base: str, stop: threading.Event, answers: list) -> None:
    import httpx

    with httpx.Client(base_url=base, timeout=60) as c:
        k = 0
        while not stop.is_set():
            r = c.post("/login", data={"username": "eng", "password": f"guess {k}", "next": "/"})
            answers.append((time.perf_counter(), r.status_code))
            k += 1


def _plan_latency(c, n: int, seconds: float = 0.0) -> list[tuple[float, float]]:
    """(start, seconds) of ``n`` requests of /plan, or more until ``seconds`` have passed."""
    out, end = [], time.perf_counter() + seconds
    while len(out) < n or time.perf_counter() < end:
        t0 = time.perf_counter()
        r = c.get("/plan")
        out.append((t0, time.perf_counter() - t0))
        if r.status_code != 200:
            raise RuntimeError(f"/plan answered {r.status_code}")
    return out


def _start(d: Path):
    import httpx

    from axiscal.web.security import UserFile

    users = UserFile.load(d / "users.toml")
    users.add("eng", "engineer", PASSWORD)
    users.add("ann", "engineer", PASSWORD)
    import socket

    with socket.socket() as so:
        so.bind(("127.0.0.1", 0))
        port = so.getsockname()[1]
    proc = subprocess.Popen([sys.executable, "-m", "axiscal", "serve", "--port", str(port),
                             "--db", f"sqlite:///{d / 'h.sqlite'}", "--users",
                             str(d / "users.toml")], stdout=subprocess.DEVNULL,
                            stderr=subprocess.DEVNULL, env=os.environ)
    base = f"http://127.0.0.1:{port}"
    for _ in range(300):
        try:
            httpx.get(base + "/login", timeout=1)
            return proc, base
        except httpx.HTTPError:
            time.sleep(0.1)
    proc.kill()
    raise RuntimeError("the workbench did not start")


def run() -> list[dict]:
    import httpx

    with tempfile.TemporaryDirectory() as d:
        proc, base = _start(Path(d))
        try:
            with httpx.Client(base_url=base, timeout=60) as c:
                c.post("/login", data={"username": "ann", "password": PASSWORD, "next": "/"})
                _plan_latency(c, 20)                                    # warm up
                quiet = [v for _, v in _plan_latency(c, SAMPLES)]
                stop, answers = threading.Event(), []
                guesser = threading.Thread(target=_guess, args=(base, stop, answers))
                guesser.start()
                time.sleep(0.5)
                busy = _plan_latency(c, SAMPLES, seconds=GUESSING)
                stop.set()
                guesser.join(60)
        finally:
            proc.terminate()
            proc.wait(10)
    ref = float(np.median(quiet))
    codes = [code for _, code in answers]
    locked_at = next((t for t, code in answers if code == 429), float("inf"))
    rows = []
    for phase, v in (("while wrong passwords are verified", [x for t, x in busy if t < locked_at]),
                     ("while the guesser is locked out", [x for t, x in busy if t >= locked_at])):
        if v:
            med, p95 = float(np.median(v)), float(np.percentile(v, 95))
            rows += [dict(name=f"workbench /plan median {phase}", value=med * 1e3, unit="ms",
                          reference=f"/plan median, nobody guessing {ref * 1e3:.1f} ms",
                          ratio=med / ref, aim="ratio near 1 (before: 4 ms -> 278 ms)"),
                     dict(name=f"workbench /plan p95 {phase}", value=p95 * 1e3, unit="ms",
                          reference=f"/plan median, nobody guessing {ref * 1e3:.1f} ms",
                          ratio=p95 / ref)]
    return rows + [dict(name="password guesses verified (401) before the lock-out",
                        value=codes.count(401), unit="guesses", aim="5 (then 429)"),
                   dict(name=f"password guesses in {GUESSING:.0f} s refused unverified (429)",
                        value=codes.count(429), unit="guesses")]
