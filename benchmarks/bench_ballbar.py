"""Ballbar diagnosis benchmark (issues 17 and 27).

The full diagnosis (ISO 230-4 G/H/F, every separated term and what the ISO 230-4 fit folds
together) of a 360° test of 10,000 points in each direction, aim under 50 ms: it now runs on every
upload and history import. Two traces: the simulated test of ``examples/ballbar_sim.toml`` (servo
mismatch, reversal spikes, cyclic error, lateral play, noise; its sample rate raised to give
10,000 points a direction) and a plain one (squareness, scale, backlash, noise).

Reference, measured in the same run on the same 20,000 readings: one least-squares fit
(``numpy.linalg.lstsq``) of the diagnosis's own final model, its 17 linear columns and the 4
columns of the chosen cyclic pitches. Any diagnosis has to do at least that fit once, so the
ratio says what the searches (spike decays, cyclic pitches), ISO 230-4's minimum-zone G and the
ranking cost on top of it. The last row is the plain test's CPU time of the calling thread (the
diagnosis wakes no BLAS thread), what the work costs whatever else shares the cores.
"""

from __future__ import annotations

import dataclasses
import time
from pathlib import Path

import numpy as np

from axiscal.standards import ballbar_diagnosis as bd
from axiscal.standards.iso230_4 import CircularRun, _common

from _timing import best_of

N = 10_000
EXAMPLE = Path(__file__).resolve().parents[1] / "examples" / "ballbar_sim.toml"


def _simulated() -> tuple[list, float, float]:
    """The example's test with N samples a direction (seed 1)."""
    from axiscal.cli.ballbar_simulate import _build, _load
    from axiscal.procedures.ballbar import simulate_ballbar

    plane, bar, test = _build(_load(EXAMPLE))
    feed = test["feed_mm_per_min"] / 6e4
    duration = 2 * np.pi * bar.length / feed
    bar = dataclasses.replace(bar, sample_rate=(N + 0.5) / duration)
    runs = simulate_ballbar(plane, bar, feed, rng=np.random.default_rng(1))
    assert len(runs[0].angles) == N
    return list(runs), bar.length, feed


def _plain() -> tuple[list, float, float]:
    rng = np.random.default_rng(0)
    phi = np.linspace(0, 2 * np.pi, N, endpoint=False)
    runs = []
    for d, s in (("ccw", 1.0), ("cw", -1.0)):
        dr = (-1e-6 * np.sin(2 * phi) + 0.7e-6 * np.cos(2 * phi)
              - 2.5e-6 * s * np.sign(np.sin(phi)) * np.cos(phi) + rng.normal(0, 1e-7, N))
        runs.append(CircularRun(phi, dr, d))
    return runs, 0.1, 1000 / 6e4


def _reference(runs, radius):
    """The design matrix of the diagnosis's final fit and the readings (CCW then CW rows)."""
    by = {r.direction: r for r in runs}
    phi, ccw, cw = _common(by["ccw"], by["cw"], 360.0)
    y = np.concatenate([ccw, cw])
    fit = bd._fit(phi, y, radius)
    m = bd._columns(phi, radius)
    nf, nd = 15, bd._DECAYS.size
    spikes = [nf + int(np.argmin(abs(bd._DECAYS - fit.decay[0]))),
              nf + nd + int(np.argmin(abs(bd._DECAYS - fit.decay[1])))]
    cyc, _ = bd._cyclic(phi, y - m[:, :nf] @ fit.c[:nf], radius)
    return np.column_stack([m[:, list(range(nf)) + spikes], cyc]), y


def run() -> list[dict]:
    rows = []
    for name, make in (("simulated", _simulated), ("plain", _plain)):
        runs, radius, feed = make()
        bd.diagnose(runs, radius, feed=feed)                    # warm-up (scipy's import)
        t = best_of(lambda: bd.diagnose(runs, radius, feed=feed), repeat=7)
        a, y = _reference(runs, radius)
        ref = best_of(lambda: np.linalg.lstsq(a, y, rcond=None), repeat=7)
        rows.append(dict(name=f"ballbar diagnosis 2 x 10,000 points, {name} (time / lstsq)",
                         value=t * 1e3, unit="ms",
                         reference=f"lstsq of its {a.shape[1]} final columns {ref * 1e3:.2f} ms",
                         ratio=t / ref, aim="< 50 ms"))
    cpu = best_of(lambda: bd.diagnose(runs, radius, feed=feed), repeat=7, clock=time.thread_time)
    rows.append(dict(name="  the same, CPU time of the calling thread (plain)", value=cpu * 1e3,
                     unit="ms", reference=f"wall {t * 1e3:.1f} ms; a busy machine shows the "
                     "difference", aim="< 50 ms"))
    return rows
