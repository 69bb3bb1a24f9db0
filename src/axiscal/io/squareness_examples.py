"""The example files of ``examples/squareness_*.csv``, made from the simulated machines.

:func:`example_files` returns the text of each file, so the files can be regenerated and a test
checks that the shipped files are exactly what this code makes (their provenance).

* ``squareness_L180_x.csv`` / ``squareness_L180_y.csv`` — Chapman, Calibration of machine squareness Machine 3, "L" test in
  orientation 180° (corner top-right), 800 × 800 mm, 17 points, indicator noise 0.05 µm:
  squareness about +65 µm/m (Chapman, Calibration of machine squareness Figure 16).
* ``squareness_ballbar_150mm.csv`` — 150 mm ballbar on a machine with squareness 12 µm/m, scale
  errors +8 / −4 µm/m and backlash 6 / −3 µm, 1° steps both ways, noise 0.1 µm.
* ``squareness_diagonal_600x800.csv`` — multi-point diagonals, 600 × 800 mm, 11 points per
  diagonal, on a machine with squareness 15 µm/m and 20 µm/m scale error on both axes.
"""

from __future__ import annotations

import numpy as np

from axiscal.machines.xy_plane import XYPlaneMachine, seed004_machine
from axiscal.procedures.squareness import (
    BallbarTest,
    BiaxialTest,
    DiagonalTest,
    measure_ballbar,
    measure_biaxial,
    measure_diagonal,
)

__all__ = ["example_files"]


def example_files() -> dict[str, str]:
    """File name → CSV text of every squareness example (deterministic, seeded)."""
    from axiscal.io.ballbar import BallbarData, format_ballbar
    from axiscal.io.straightness import StraightnessData, format_straightness

    rng = np.random.default_rng(20260522)
    r = measure_biaxial(seed004_machine(3), BiaxialTest("L", 180), rng=rng, noise=0.05e-6)
    files = {
        "squareness_L180_x.csv": format_straightness(
            StraightnessData(r.x_positions, r.x_deviations, "X", "Y")),
        "squareness_L180_y.csv": format_straightness(
            StraightnessData(r.y_positions, r.y_deviations, "Y", "X")),
    }
    m = XYPlaneMachine(squareness=12e-6, scale_x=8e-6, scale_y=-4e-6, backlash_x=6e-6,
                       backlash_y=-3e-6)
    runs = measure_ballbar(m, BallbarTest(radius=0.15, n_points=360), rng=rng, noise=0.1e-6)
    files["squareness_ballbar_150mm.csv"] = format_ballbar(BallbarData(0.15, runs))
    m = XYPlaneMachine(0.6, 0.8, squareness=15e-6, scale_x=20e-6, scale_y=20e-6)
    d = measure_diagonal(m, DiagonalTest(size=(0.6, 0.8)), rng=rng, noise=0.05e-6)
    lines = ["# length_x_mm=600 length_y_mm=800 position_unit=mm error_unit=um",
             "diagonal,position,error"]
    for key, errors in (("D1", d.errors_d1), ("D2", d.errors_d2)):
        lines += [f"{key},{s * 1e3:.6f},{e * 1e6:.4f}" for s, e in zip(d.s, errors)]
    files["squareness_diagonal_600x800.csv"] = "\n".join(lines) + "\n"
    return files
