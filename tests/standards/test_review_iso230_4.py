"""Review of standards/iso230_4.py: conditioning of the minimum-zone circular deviation G."""

from __future__ import annotations

import numpy as np
import pytest

from axiscal.standards.iso230_4 import CircularRun, evaluate_circular

PHI = np.radians(np.arange(0.0, 360.0, 1.0))


@pytest.mark.parametrize("offset", [0.0, 1e-4, 2e-3, 5e-2])
def test_g_of_a_two_lobe_path_is_its_peak_to_valley_whatever_the_centre_and_radius(offset):
    """ISO 230-4 §3: G is the minimum radial separation of two concentric circles enveloping
    the path. For Δr = e cos 2φ no shift of the centre can narrow the band (every
    first-harmonic shift a cos φ + b sin φ raises one of the four extremes), so G = 2e exactly.
    A centre offset of 36 µm and a radius offset up to 50 mm must not blur a 2 nm G: before the
    review the LP worked on the raw data and missed by 5e-4 relative."""
    e = 1e-9
    d = offset + 30e-6 * np.cos(PHI) - 20e-6 * np.sin(PHI) + e * np.cos(2 * PHI)
    r = evaluate_circular([CircularRun(PHI, d, "ccw")], 0.1)
    assert r.G_ccw == pytest.approx(2 * e, rel=1e-6, abs=0)
    assert r.G_lsc_ccw == pytest.approx(2 * e, rel=1e-6, abs=0)


@pytest.mark.parametrize("value", [0.0, 1e-6, 5.0, 1e9])
def test_g_of_a_perfect_circle_is_zero(value):
    """A constant Δr (a radius error only) has G = 0; the LP is not asked to divide by a zero
    spread (before the review 1e9 overflowed into an uncaught scipy ValueError)."""
    r = evaluate_circular([CircularRun(PHI, np.full(PHI.size, value), "ccw")], 0.1)
    assert r.G_ccw == pytest.approx(0.0, abs=1e-15 + 1e-15 * value)


def test_minimum_zone_g_against_a_brute_force_centre_search():
    """On random paths the LP's G is never above the least-squares value and equals the best
    band found by a dense search of centre shifts (a, b) around the least-squares centre."""
    rng = np.random.default_rng(3)
    phi = np.radians(np.arange(0.0, 360.0, 15.0))
    for _ in range(5):
        d = rng.normal(0.0, 1e-6, phi.size)
        r = evaluate_circular([CircularRun(phi, d, "ccw")], 0.1)
        assert r.G_ccw <= r.G_lsc_ccw + 1e-18
        design = np.column_stack([np.ones_like(phi), np.cos(phi), np.sin(phi)])
        c, *_ = np.linalg.lstsq(design, d, rcond=None)
        grid = np.linspace(-1.5e-6, 1.5e-6, 301)
        a, b = np.meshgrid(c[1] + grid, c[2] + grid)
        res = d[None, None, :] - a[..., None] * np.cos(phi) - b[..., None] * np.sin(phi)
        brute = float(np.min(res.max(axis=-1) - res.min(axis=-1)))
        assert r.G_ccw <= brute + 1e-15
        assert r.G_ccw >= brute - 2 * 1e-8 * 1.0  # grid step 1e-8 m bounds the search's miss


@pytest.mark.parametrize("angles", [[], [0.3], [0.0, float("nan"), 1.0]])
def test_arc_coverage_refuses_what_has_no_arc(angles):
    """Before the review [] raised numpy's 'zero-size array' ValueError and NaN gave NaN."""
    from axiscal.errors import InputError
    from axiscal.standards.iso230_4 import arc_coverage

    with pytest.raises(InputError, match="at least 2 finite angles"):
        arc_coverage(angles)
