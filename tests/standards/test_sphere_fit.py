"""The sphere fit of a probing cycle (axiscal.standards.sphere_fit): exact on exact points, the
radius check of KinematicsOpt (0.02 mm), and refusals."""

from __future__ import annotations

import numpy as np
import pytest

from axiscal.errors import InputError
from axiscal.standards.sphere_fit import fit_sphere

D = np.array([[1, 0, 0], [-1, 0, 0], [0, 1, 0], [0, -1, 0], [0, 0, 1.0]])


def test_exact_points_give_the_sphere():
    f = fit_sphere(0.014 * D + [0.1, -0.2, 0.05], expected_radius=0.014)
    np.testing.assert_allclose(f.center, [0.1, -0.2, 0.05], atol=1e-15)
    assert f.radius == pytest.approx(0.014, abs=1e-15) and f.rms < 1e-15 and f.n == 5


def test_a_radius_beyond_the_tolerance_is_refused_and_one_within_it_is_kept():
    """Heidenhain KinematicsOpt refuses a calibration sphere whose measured size departs from
    the entered one by more than its tolerance (0.02 mm by default, the reading here)."""
    pts = 0.014 * D
    fit_sphere(pts, expected_radius=0.014 - 0.019e-3)
    with pytest.raises(InputError, match=r"pose 3: fitted radius 14.0000 mm differs .* by "
                                         r"\+0.0210 mm, beyond the tolerance 0.02 mm"):
        fit_sphere(pts, expected_radius=0.014 - 0.021e-3, label="pose 3")


def test_noisy_points_give_the_centre_within_the_noise():
    rng = np.random.default_rng(0)
    dirs = rng.normal(size=(40, 3))
    dirs /= np.linalg.norm(dirs, axis=1, keepdims=True)
    dirs[:, 2] = np.abs(dirs[:, 2])
    pts = (0.0125 + rng.normal(0, 0.5e-6, (40, 1))) * dirs
    f = fit_sphere(pts)
    assert np.abs(f.center).max() < 1e-6 and f.rms == pytest.approx(0.5e-6, rel=0.4)


@pytest.mark.parametrize("pts, rule", [
    (np.zeros((3, 3)), "at least 4"),
    (np.vstack([0.01 * D[:4], [np.nan, 0, 0]]), "not a finite number"),
    (0.01 * D[:4], "fix no sphere"),
])
def test_bad_points_are_refused(pts, rule):
    with pytest.raises(InputError, match=rule):
        fit_sphere(pts)


def test_the_centre_sensitivity_is_the_fits_own_first_order_response():
    """centre_sensitivity (JCGM 100:2008, 5.1.2: ∂c/∂ε_i) against central finite differences
    of fit_sphere itself: each of the probe's five touch directions (12.5 mm + 1.5 mm stylus)
    moved by ±0.1 µm along its normal; equal within 1e-6 (second order). The same error on
    every touch moves no centre (the radius is fitted)."""
    from axiscal.standards.sphere_fit import centre_sensitivity

    d = np.array([[1, 0, 0], [-1, 0, 0], [0, 1, 0], [0, -1, 0], [0, 0, 1.0]])
    d = np.vstack([d[:4] * np.sqrt(0.5) + [0, 0, np.sqrt(0.5)], d[4:]])   # a probing cycle's 45°
    r, c, h = 14e-3, np.array([0.15, 0.02, 0.06]), 1e-7
    g = centre_sensitivity(d)
    for i in range(len(d)):
        up, down = (c + (r + s * (np.arange(len(d)) == i))[:, None] * d for s in (h, -h))
        fd = (fit_sphere(up).center - fit_sphere(down).center) / (2 * h)
        np.testing.assert_allclose(fd, g[:, i], atol=1e-6)
    # the same error on every touch is a larger radius, not a moved centre
    np.testing.assert_allclose(g.sum(axis=1), 0.0, atol=1e-12)
