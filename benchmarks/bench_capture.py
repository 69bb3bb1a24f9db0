"""A one-minute 50 kHz dynamic capture (``.rtx``, 3·10^6 readings, 24 MB) read and captured
(issue 12): time (aim: under 2 s) beside reading the same bytes with ``numpy.fromfile`` in the
same run, and the peak memory (tracemalloc, NumPy's allocations included) against the file's
size (aim: under 10x)."""

from __future__ import annotations

import tempfile
import time
import tracemalloc
from pathlib import Path

import numpy as np

from axiscal.io.measured import parse_plan_csv
from axiscal.io.rtx import format_rtx, read_rtx
from axiscal.machines.config import axis_from_config
from axiscal.procedures.capture import capture_test
from axiscal.procedures.positioning import plan_linear
from axiscal.procedures.record_simulation import RecordSettings, simulate_record

from _timing import best_of


def run() -> list[dict]:
    axis = axis_from_config({"name": "X", "kind": "linear", "travel_mm": [-10, 410],
                             "scale_error_ppm": 5.0, "backlash_um": 2.0,
                             "repeatability_um": 0.2})
    plan = parse_plan_csv(plan_linear(400, n_targets=5, runs=1, dwell=5.0).to_csv())
    t, x, _ = simulate_record(plan, axis, np.random.default_rng(0),
                              RecordSettings(sample_rate=50000.0, speed=0.1))
    with tempfile.TemporaryDirectory() as d:
        p = Path(d) / "minute.rtx"
        p.write_bytes(format_rtx(x * 1e6, 50000.0))
        size = p.stat().st_size

        def job():
            capture_test(read_rtx(p), plan, window=0.5)

        seconds = best_of(job, repeat=3)
        ref = best_of(lambda: np.fromfile(p, dtype="<f8"), repeat=3)
        tracemalloc.start()
        job()
        peak = tracemalloc.get_traced_memory()[1]
        tracemalloc.stop()
    return [dict(name=f"capture of a {t[-1]:.0f} s 50 kHz .rtx ({t.size:.2g} readings), "
                      "read + stops + match (time / fromfile)",
                 value=seconds, unit="s", reference=f"numpy.fromfile {ref * 1e3:.1f} ms",
                 ratio=seconds / ref, aim="< 2 s"),
            dict(name="capture peak memory / file size", value=peak / 2 ** 20, unit="MiB",
                 reference=f"file {size / 2 ** 20:.1f} MiB", ratio=peak / size,
                 aim="< 10x the file")]
