"""The simulated XY plane of seed 004 Appendix I (axiscal.machines.xy_plane)."""

import numpy as np
import pytest

from axiscal.errors import InputError
from axiscal.machines.xy_plane import (
    QuadraticBend,
    TabulatedProfile,
    XYPlaneMachine,
    airy_points_bend,
    seed004_machine,
)
from axiscal.procedures.squareness import BiaxialTest, evaluate_biaxial, measure_biaxial


def test_equation_3_with_yaw():
    """Seed 004 Equation 3: actual = [x - y(θ0 + 8Sx/L²), y + 4Sx²/L²]."""
    m = XYPlaneMachine(0.8, 0.8, squareness=15e-6, x_straightness=QuadraticBend(10e-6, 0.8),
                       x_yaw=True)
    x, y = 0.3, -0.25
    ax, ay = m.actual(x, y)
    assert ax == pytest.approx(x - y * (15e-6 + 8 * 10e-6 * x / 0.64), abs=1e-15)
    assert ay == pytest.approx(y + 4 * 10e-6 * x**2 / 0.64, abs=1e-15)


def test_equation_4_without_yaw():
    """Seed 004 Equation 4: actual = [x - yθ0, y + 4Sx²/L²]."""
    m = seed004_machine(2)
    ax, ay = m.actual(0.3, -0.25)
    assert ax == pytest.approx(0.3 + 0.25 * 15e-6, abs=1e-15)
    assert ay == pytest.approx(-0.25 + 4 * 10e-6 * 0.09 / 0.64, abs=1e-15)


def test_local_squareness_matches_the_numerical_jacobian():
    """The analytic local squareness equals the angle between the numerically differentiated
    local X and Y directions, on every seed machine and at several points."""
    h = 1e-4
    for n in range(1, 8):
        m = seed004_machine(n)
        for x, y in [(0.0, 0.0), (0.2, -0.1), (-0.3, 0.1)]:
            xp = np.array(m.actual(x + h, y)) - np.array(m.actual(x - h, y))
            yp = np.array(m.actual(x, y + h)) - np.array(m.actual(x, y - h))
            angle = np.arccos(xp @ yp / np.linalg.norm(xp) / np.linalg.norm(yp)) - np.pi / 2
            assert float(m.local_squareness(x, y)) == pytest.approx(angle, abs=2e-9), (n, x, y)


def test_rigid_yaw_keeps_local_squareness_uniform():
    """Seed 004 Machines 3 and 5: "uniform local and global squareness distortion of 15 µm/m"."""
    xs = np.linspace(-0.4, 0.4, 9)
    for n in (3, 5):
        assert np.allclose(seed004_machine(n).local_squareness(xs, xs[::-1]), 15e-6, atol=1e-12)
    assert np.ptp(seed004_machine(2).local_squareness(xs, 0 * xs)) == pytest.approx(100e-6)


def test_airy_profile_has_flat_ends_and_the_requested_straightness():
    p = airy_points_bend(0.75, 10e-6)
    u = np.linspace(-0.375, 0.375, 2001)
    assert np.ptp(p(u)) == pytest.approx(10e-6, rel=1e-6)
    assert abs(p.slope(0.375)) < 1e-3 * np.abs(p.slope(u)).max()
    assert p(0.0) == pytest.approx(p(u).min())  # the middle sags lowest
    assert p(0.375) == pytest.approx(p(u).max())


def test_prism_error_is_corrected_in_every_orientation():
    """Truth test: an optical square 2 arcsec (9.7 µm/m) off 90° biases the raw result by the
    orientation's sign; the correction recovers 15 µm/m in all four orientations."""
    m = seed004_machine(1)
    eps = 2 * 4.8481368e-6
    for o in (0, 90, 180, 270):
        test = BiaxialTest("L", o, square_error=eps)
        readings = measure_biaxial(m, test)
        raw = evaluate_biaxial(readings).squareness.um_per_m
        fixed = evaluate_biaxial(readings, square_error=eps).squareness.um_per_m
        assert abs(raw - 15.0) == pytest.approx(eps * 1e6, abs=1e-6)
        assert fixed == pytest.approx(15.0, abs=1e-6)


def test_noisy_indicator_needs_a_generator_and_averages_out():
    m = seed004_machine(1)
    test = BiaxialTest("+", 0, n_points=201)
    with pytest.raises(InputError, match="Generator"):
        measure_biaxial(m, test, noise=0.1e-6)
    rng = np.random.default_rng(4)
    r = evaluate_biaxial(measure_biaxial(m, test, rng=rng, noise=0.1e-6))
    assert r.squareness.um_per_m == pytest.approx(15.0, abs=0.5)  # ~0.07 µm/m standard error
    assert r.first.deviation > 0.2e-6


def test_bad_machines_are_refused():
    with pytest.raises(InputError, match="length_x"):
        XYPlaneMachine(length_x=0.0)
    with pytest.raises(InputError, match="squareness"):
        XYPlaneMachine(squareness=0.5)
    with pytest.raises(InputError, match="machine=8"):
        seed004_machine(8)
    with pytest.raises(InputError):
        TabulatedProfile(np.array([0.0, 1.0]), np.array([0.0, 1.0]))
    with pytest.raises(InputError, match="config"):
        BiaxialTest("X")
