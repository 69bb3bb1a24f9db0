"""Review of standards/iso230_6.py and iso230_7.py against cases worked out independently."""

from __future__ import annotations

import math

import numpy as np
import pytest

from axiscal.standards.iso230_6 import diagonal_squareness
from axiscal.standards.iso230_7 import MotionErrorData, evaluate


@pytest.mark.parametrize("theta", [25e-6, -40e-6])
@pytest.mark.parametrize("x, y", [(0.8, 0.8), (0.6, 0.8), (0.75, 0.25)])
def test_diagonal_formula_and_sign_on_exact_geometry(theta, x, y):
    """ISO 230-6 / seed 004 Method 5: squareness = D0 (D1 − D2)/(2XY). Independent check by exact
    plane geometry, no linearisation: a machine whose +Y axis leans by θ towards −X puts the
    commanded point (x, y) at (x − θy, y), so the angle between +X and +Y is 90° + atan θ
    (positive θ: larger than 90°, the seed's positive sign). D1 runs (X, 0) → (0, Y), along
    (−X, +Y); D2 runs (0, 0) → (X, Y)."""
    d0 = math.hypot(x, y)
    d1 = math.dist((x, 0.0), (-theta * y, y))
    d2 = math.dist((0.0, 0.0), (x - theta * y, y))
    r = diagonal_squareness(x, y, d1 - d0, d2 - d0)
    angle_excess = math.atan(theta)  # angle between +X and (−θ, 1), minus 90°
    assert r.squareness.excess == pytest.approx(angle_excess, abs=1e-9 * abs(theta) * 100)
    assert (r.squareness.excess > 0) == (theta > 0)
    assert r.squareness.angle_note.endswith(("larger than 90°" if theta > 0 else
                                             "smaller than 90°"))


def test_error_motion_values_worked_by_hand():
    """ISO 230-7:2015 §3 with a fixed sensitive direction, four angles, two runs, by hand:

    runs = 5 + 3 cos θ + cos 2θ ± (0.2, 0, 0, 0)  (µm, at θ = 0, 90, 180, 270°)
    synchronous = 5 + 3 cos θ + cos 2θ; its fundamental is 3 cos θ (amplitude 3).
    Radial (fundamental and PC centre removed): runs (1.2, −1, 1, −1) and (0.8, −1, 1, −1):
      total = 1.2 − (−1) = 2.2, synchronous = 1 − (−1) = 2, asynchronous = 0.4.
    Axial (fundamental kept, mean removed): runs (4.2, −1, −2, −1) and (3.8, −1, −2, −1):
      total = 4.2 − (−2) = 6.2, synchronous = 4 − (−2) = 6, asynchronous = 0.4.
    Location of the axis average line: y0 = 5."""
    th = np.radians([0.0, 90.0, 180.0, 270.0])
    base = 5 + 3 * np.cos(th) + np.cos(2 * th)
    bump = np.array([0.2, 0.0, 0.0, 0.0])
    runs = 1e-6 * np.vstack([base + bump, base - bump])
    z = np.zeros_like(runs)
    r = evaluate(MotionErrorData(th, ez=z, ey=z, ex=z, dy=runs, dz=runs))
    radial, axial = r.motion("radial Y"), r.motion("axial")
    um = 1e-6
    assert (radial.total, radial.synchronous, radial.asynchronous) == pytest.approx(
        (2.2 * um, 2.0 * um, 0.4 * um), abs=1e-15)
    assert (axial.total, axial.synchronous, axial.asynchronous) == pytest.approx(
        (6.2 * um, 6.0 * um, 0.4 * um), abs=1e-15)
    assert radial.fundamental == pytest.approx(3 * um, abs=1e-15)
    assert radial.fundamental_removed and not axial.fundamental_removed
    assert r.location.y0 == pytest.approx(5 * um, abs=1e-15)
