"""ISO 230-6 diagonal squareness (axiscal.standards.iso230_6)."""

import numpy as np
import pytest

from axiscal.errors import InputError
from axiscal.machines.xy_plane import XYPlaneMachine
from axiscal.procedures.squareness import DiagonalTest, evaluate_diagonal, measure_diagonal
from axiscal.standards.iso230_6 import diagonal_squareness, diagonal_squareness_multipoint


def test_equal_travels_reduce_to_the_seed_shortcut():
    """Seed 004 Method 5: with X = Y, squareness = (D1 - D2) / D0."""
    r = diagonal_squareness(0.5, 0.5, 4e-6, -3e-6)
    d0 = np.hypot(0.5, 0.5)
    assert r.nominal == pytest.approx(d0)
    assert r.squareness.excess == pytest.approx(7e-6 / d0)


def test_unequal_travels_use_the_general_formula():
    """Seed 004: squareness = D0 (D1 - D2) / (2XY)."""
    r = diagonal_squareness(0.75, 0.25, 5e-6, 1e-6)
    assert r.squareness.excess == pytest.approx(np.hypot(0.75, 0.25) * 4e-6 / (2 * 0.75 * 0.25))


def test_sign_and_labels_on_a_simulated_machine():
    """Truth test: θ0 = +15 µm/m (angle > 90°) stretches D1 (−X,+Y) and shortens D2 (+X,+Y);
    equal scale errors cancel; backlash is removed by the two-way average."""
    m = XYPlaneMachine(0.75, 0.25, squareness=15e-6, scale_x=20e-6, scale_y=20e-6,
                       backlash_x=5e-6, backlash_y=5e-6)
    readings = measure_diagonal(m, DiagonalTest(size=(0.75, 0.25)))
    r = evaluate_diagonal(readings)
    assert r.error_d1 > 0 > r.error_d2 - 2 * 20e-6 * np.hypot(0.75, 0.25)
    assert r.squareness.um_per_m == pytest.approx(15.0, abs=0.01)
    multi = diagonal_squareness_multipoint(0.75, 0.25, readings.s, readings.errors_d1,
                                           readings.s, readings.errors_d2)
    assert multi.squareness.um_per_m == pytest.approx(15.0, abs=0.01)
    assert multi.slope_d1 is not None and "D1" in str(multi)


def test_bad_travel_is_refused():
    with pytest.raises(InputError, match="length_x"):
        diagonal_squareness(0.0, 0.5, 1e-6, 0.0)
    with pytest.raises(InputError, match="error_d2"):
        diagonal_squareness(0.5, 0.5, 1e-6, float("nan"))
