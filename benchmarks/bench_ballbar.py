"""Ballbar diagnosis benchmark (issue 17).

The full diagnosis (ISO 230-4 G/H/F and every separated term) of a 360° trace of 10,000 points in
each direction (aim: under 50 ms), compared with one least-squares fit of the five-harmonic model
on the same 20,000 readings (``numpy.linalg.lstsq``), measured in the same run.
"""

from __future__ import annotations

import numpy as np

from axiscal.standards.ballbar_diagnosis import diagnose
from axiscal.standards.iso230_4 import CircularRun, _harmonics

from _timing import best_of


def run() -> list[dict]:
    rng = np.random.default_rng(0)
    n, radius, feed = 10_000, 0.1, 1000 / 6e4
    phi = np.linspace(0, 2 * np.pi, n, endpoint=False)
    runs = []
    for d, s in (("ccw", 1.0), ("cw", -1.0)):
        dr = (-1e-6 * np.sin(2 * phi) + 0.7e-6 * np.cos(2 * phi)
              - 2.5e-6 * s * np.sign(np.sin(phi)) * np.cos(phi) + rng.normal(0, 1e-7, n))
        runs.append(CircularRun(phi, dr, d))
    diagnose(runs, radius, feed=feed)                       # warm-up (scipy import)
    t = best_of(lambda: diagnose(runs, radius, feed=feed))
    a = np.vstack([_harmonics(phi)] * 2)
    y = np.concatenate([r.deviations for r in runs])
    ref = best_of(lambda: np.linalg.lstsq(a, y, rcond=None))
    return [dict(name="ballbar diagnosis, 360° x 10,000 points both ways (time / lstsq)",
                 value=t, unit="s", reference=f"5-column lstsq {ref * 1e3:.2f} ms",
                 ratio=t / ref, aim="< 50 ms")]
