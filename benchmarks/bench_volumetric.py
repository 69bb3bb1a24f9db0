"""Volumetric error map benchmark (issue 18).

The error field on a 50 × 50 × 50 grid from the 21 measured functions of a simulated machine
(aim: under 0.5 s), beside a floor measured in the same run: one linear field ``a·x + b·y + c·z``
per component on the same grid (the least work any map of three components must do).
"""

from __future__ import annotations

import numpy as np

from axiscal.machines.three_axis import simulated_machine
from axiscal.procedures.volumetric import measure_errors
from axiscal.standards.volumetric import map_volume

from _timing import best_of


def run() -> list[dict]:
    rng = np.random.default_rng(0)
    m = simulated_machine(rng)
    e = measure_errors(m, rng, tool_offset=(0, 0, -0.1))
    n = 50
    t = best_of(lambda: map_volume(e, n))
    X, Y, Z = np.meshgrid(*(np.linspace(*e.travel[a], n) for a in "XYZ"), indexing="ij")
    ref = best_of(lambda: np.stack([1e-6 * X + 2e-6 * Y + 3e-6 * Z for _ in range(3)]))
    return [dict(name="volumetric error map, 50³ grid, 21 functions (time / linear field)",
                 value=t, unit="s", reference=f"3 linear fields {ref * 1e3:.1f} ms",
                 ratio=t / ref, aim="< 0.5 s")]
