"""Calibration history at fleet scale (issue 13): 100 machines × 10 axes × 10 years of monthly
ISO 230-2 tests (12,000 tests of 41 targets × 10 runs × 2 directions: ~10^7 readings), on SQLite
and on a throw-away PostgreSQL server.

Reported: insert throughput (tests/s, readings/s) beside the floor of the same work without a
database (reading and evaluating each file, measured in the same run), the latency of ``trend``
for one axis (aim: under 100 ms), and the database size per test. ``AXISCAL_BENCH_HISTORY_SCALE``
(default 1.0) scales the number of machines for a quicker look.
"""

from __future__ import annotations

import os
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

from axiscal.datasets import Metadata, PositioningDataset
from axiscal.io.csv import format_positioning_csv
from axiscal.store import open_store, trend
from axiscal.store.kinds import evaluate_file

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "tools"))


def _files(n_machines: int):
    rng = np.random.default_rng(0)
    targets = np.linspace(0, 800, 41)
    for m in range(n_machines):
        for a in range(10):
            drift = rng.uniform(0.2, 1.0)
            for month in range(120):
                up = rng.normal(drift * month / 12, 1.0, (41, 10))
                ds = PositioningDataset("linear", targets, up, up - 2.0, "mm", "um", Metadata(
                    machine=f"M{m:03d}", axis=f"A{a}",
                    date=f"{2015 + month // 12}-{month % 12 + 1:02d}-15"))
                yield format_positioning_csv(ds).encode()


def _insert(url: str, n_machines: int) -> dict:
    s = open_store(url)
    t0 = time.perf_counter()
    n = 0
    for raw in _files(n_machines):
        s.add(raw, f"t{n}.csv")
        n += 1
    dt_insert = time.perf_counter() - t0
    times = []
    for _ in range(5):
        t1 = time.perf_counter()
        trend(s, "M000", "A0", "E", tolerance=100.0)
        times.append(time.perf_counter() - t1)
    s.close()
    return {"tests": n, "insert_s": dt_insert, "trend_s": min(times)}


def run() -> list[dict]:
    scale = float(os.environ.get("AXISCAL_BENCH_HISTORY_SCALE", "1.0"))
    n_machines = max(1, int(round(100 * scale)))
    sample = [raw for raw, _ in zip(_files(1), range(200))]
    t0 = time.perf_counter()
    for k, raw in enumerate(sample):
        evaluate_file(raw, f"{k}.csv")
    floor = (time.perf_counter() - t0) / len(sample)            # s per test without a database
    readings = 41 * 10 * 2
    rows = []
    with tempfile.TemporaryDirectory() as d:
        db = Path(d) / "h.sqlite"
        r = _insert(f"sqlite:///{db}", n_machines)
        size = sum(p.stat().st_size for p in Path(d).glob("h.sqlite*"))
        rows += _rows("SQLite", r, floor, readings, size)
    import pgtest

    url, stop = pgtest.start()
    try:
        r = _insert(url, n_machines)
        import psycopg

        host = url.split("host=", 1)[1]
        with psycopg.connect(host=host, user="axiscal", dbname="postgres") as c:
            size = c.execute("select pg_database_size('postgres')").fetchone()[0]
        rows += _rows("PostgreSQL", r, floor, readings, size)
    finally:
        stop()
    return rows


def _rows(name, r, floor, readings, size):
    per = r["insert_s"] / r["tests"]
    return [
        dict(name=f"history {name}: insert {r['tests']} tests (time per test / evaluate only)",
             value=r["tests"] / r["insert_s"], unit="tests/s",
             reference=f"evaluate without storing {1 / floor:.0f} tests/s", ratio=per / floor),
        dict(name=f"history {name}: readings stored per second", value=readings / per,
             unit="readings/s"),
        dict(name=f"history {name}: trend of one axis (120 tests)", value=r["trend_s"] * 1e3,
             unit="ms", aim="< 100 ms"),
        dict(name=f"history {name}: database size per test", value=size / r["tests"] / 1024,
             unit="KiB/test", reference=f"CSV file {len(next(_files(1))) / 1024:.1f} KiB"),
    ]
