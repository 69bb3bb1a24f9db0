"""ISO 230-4 circular test and its squareness diagnosis (axiscal.standards.iso230_4)."""

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from axiscal.errors import InputError
from axiscal.machines.xy_plane import XYPlaneMachine
from axiscal.procedures.squareness import BallbarTest, measure_ballbar
from axiscal.standards.iso230_4 import CircularRun, arc_coverage, evaluate_circular


def _machine(**kw):
    base = dict(length_x=0.8, length_y=0.8, squareness=12e-6, scale_x=8e-6, scale_y=-4e-6,
                backlash_x=6e-6, backlash_y=-3e-6)
    base.update(kw)
    return XYPlaneMachine(**base)


def test_squareness_backlash_and_scale_mismatch_are_recovered_separately():
    """Truth test: a simulated ballbar (R = 150 mm) on a machine with squareness 12 µm/m, scale
    errors +8/-4 µm/m and backlash 6/-3 µm recovers each within 0.05 µm/m or 0.05 µm
    (budget: second-order terms of µm deviations on a 150 mm radius)."""
    test = BallbarTest(centre=(0.05, -0.02), radius=0.15, n_points=720)
    r = evaluate_circular(measure_ballbar(_machine(), test), test.radius)
    assert r.squareness.um_per_m == pytest.approx(12.0, abs=0.05)
    assert r.scale_mismatch * 1e6 == pytest.approx(12.0, abs=0.05)
    assert r.backlash_x * 1e6 == pytest.approx(6.0, abs=0.05)
    assert r.backlash_y * 1e6 == pytest.approx(-3.0, abs=0.05)
    assert r.fit_rms < 0.01e-6
    assert r.arc_deg == pytest.approx(360.0)


@pytest.mark.parametrize("changed", ["squareness", "scale_x", "backlash_x"])
def test_each_error_alone_leaves_the_others_at_zero(changed):
    """Separation: a machine with only one of the three errors shows zero for the other two."""
    zero = dict(squareness=0.0, scale_x=0.0, scale_y=0.0, backlash_x=0.0, backlash_y=0.0)
    zero[changed] = 10e-6
    test = BallbarTest(radius=0.1)
    r = evaluate_circular(measure_ballbar(_machine(**zero), test), test.radius)
    got = {"squareness": r.squareness.excess, "scale_x": r.scale_mismatch,
           "backlash_x": r.backlash_x}
    for key, value in got.items():
        expect = 10e-6 if key == changed else 0.0
        assert value == pytest.approx(expect, abs=0.02e-6), key


def test_partial_arc_of_220_degrees():
    """Seed 004: squareness from partial arcs down to 220°; a 230° arc recovers all three."""
    test = BallbarTest(radius=0.15, n_points=231, arc_deg=230.0, start_deg=-25.0)
    r = evaluate_circular(measure_ballbar(_machine(), test), test.radius)
    assert r.arc_deg == pytest.approx(230.0, abs=1.1)
    assert r.squareness.um_per_m == pytest.approx(12.0, abs=0.1)
    assert r.backlash_x * 1e6 == pytest.approx(6.0, abs=0.1)
    short = BallbarTest(radius=0.15, n_points=181, arc_deg=180.0)
    with pytest.raises(InputError, match="220"):
        evaluate_circular(measure_ballbar(_machine(), short), short.radius)


def test_G_H_F_by_their_definitions():
    """ISO 230-4 §3: F about the nominal centre, G about the least-squares centre, H the largest
    CW/CCW difference. Built from known terms: an offset circle (centre terms), a 2 µm ripple and
    a 1.5 µm direction-dependent radius."""
    phi = np.radians(np.arange(0, 360, 0.5))
    ripple = 1e-6 * np.cos(5 * phi)  # peak-to-valley 2 µm
    centre = 3e-6 * np.cos(phi)
    ccw = CircularRun(phi, centre + ripple + 0.75e-6, "ccw")
    cw = CircularRun(phi, centre + ripple - 0.75e-6, "cw")
    r = evaluate_circular([ccw, cw], 0.1)
    assert r.G_ccw == pytest.approx(2e-6, rel=1e-3)
    assert r.G_cw == pytest.approx(2e-6, rel=1e-3)
    assert r.H == pytest.approx(1.5e-6, rel=1e-9)
    assert r.F_max == pytest.approx(np.max(centre + ripple) + 0.75e-6)
    assert r.F_min == pytest.approx(np.min(centre + ripple) - 0.75e-6)
    assert r.squareness.um_per_m == pytest.approx(0.0, abs=1e-6)
    d = r.as_dict()
    assert d["H_um"] == pytest.approx(1.5)
    assert "circular test" in str(r)


def test_one_direction_warns_and_leaves_backlash_out():
    test = BallbarTest(radius=0.1)
    ccw, _ = measure_ballbar(_machine(backlash_x=0.0, backlash_y=0.0), test)
    r = evaluate_circular([ccw], 0.1)
    assert r.backlash_x is None and r.H is None
    assert r.squareness.um_per_m == pytest.approx(12.0, abs=0.05)
    assert any("one direction" in w for w in r.warnings)


def test_bad_runs_are_refused():
    phi = np.radians(np.arange(0, 360, 10.0))
    run = CircularRun(phi, 0 * phi, "ccw")
    with pytest.raises(InputError, match="one CCW and/or one CW"):
        evaluate_circular([run, run], 0.1)
    with pytest.raises(InputError, match="direction"):
        CircularRun(phi, 0 * phi, "up")
    with pytest.raises(InputError, match="radius"):
        evaluate_circular([run], -1.0)
    with pytest.raises(InputError):
        CircularRun(phi[:3], phi[:3])
    assert arc_coverage(phi) == pytest.approx(360.0)


@settings(max_examples=40, deadline=None)
@given(st.floats(-20e-6, 20e-6), st.floats(-30e-6, 30e-6), st.floats(-10e-6, 10e-6),
       st.integers(0, 2**31))
def test_radius_offset_and_reading_order_do_not_change_the_diagnosis(offset, sq, bx, seed):
    """Property: a ballbar length error (constant on every reading) and the order of the
    readings change neither squareness, scale mismatch, backlash, G nor H."""
    m = XYPlaneMachine(squareness=sq, backlash_x=bx)
    test = BallbarTest(radius=0.1, n_points=90)
    ccw, cw = measure_ballbar(m, test)
    a = evaluate_circular([ccw, cw], 0.1)
    p = np.random.default_rng(seed).permutation(90)
    shifted = [CircularRun(r.angles[p], r.deviations[p] + offset, r.direction) for r in (cw, ccw)]
    b = evaluate_circular(shifted, 0.1)
    for key in ("scale_mismatch", "backlash_x", "backlash_y", "G_ccw", "G_cw", "H"):
        assert getattr(b, key) == pytest.approx(getattr(a, key), abs=1e-12), key
    assert b.squareness.excess == pytest.approx(a.squareness.excess, abs=1e-12)
    assert a.squareness.excess == pytest.approx(sq, abs=2e-9)


def test_minimum_zone_G_is_exact_and_never_wider_than_the_lsc_value():
    """ISO 230-4 G: minimum radial separation of two concentric circles. For a path with a
    one-sided bump the least-squares centre is pulled off and its band is wider; the minimum zone
    is checked against a brute-force search over centres."""
    phi = np.radians(np.arange(0, 360, 2.0))
    dev = 2e-6 * np.exp(-((phi - 1.0) / 0.3) ** 2) + 0.5e-6 * np.cos(3 * phi)
    r = evaluate_circular([CircularRun(phi, dev, "ccw")], 0.1)
    assert r.G_ccw <= r.G_lsc_ccw + 1e-15
    assert r.G_ccw < 0.97 * r.G_lsc_ccw
    grid = np.linspace(-2e-6, 2e-6, 161)
    best = min(np.ptp(dev - a * np.cos(phi) - b * np.sin(phi)) for a in grid for b in grid)
    assert r.G_ccw <= best + 1e-15
    assert r.G_ccw == pytest.approx(best, rel=0.02)


# -- Review of standards/iso230_4.py: conditioning of the minimum-zone circular deviation G. ----------

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
