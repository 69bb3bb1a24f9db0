"""ISO 230-1 reference lines, straightness and squareness (axiscal.standards.iso230_1)."""

import itertools

import numpy as np
import pytest
from hypothesis import example, given, settings
from hypothesis import strategies as st

from axiscal.errors import AxiscalError, InputError, InsufficientRunsError
from axiscal.standards.iso230_1 import (
    Squareness,
    correct_reference_angle,
    end_point_line,
    least_squares_line,
    minimum_zone_line,
    reversal,
    squareness_from_trajectories,
    straightness,
)


def _brute_force_zone(x, y):
    """Minimum band width by trying every line through two readings (O(n^3))."""
    best = np.inf
    for i, j in itertools.combinations(range(len(x)), 2):
        if x[i] != x[j]:
            m = (y[j] - y[i]) / (x[j] - x[i])
            best = min(best, np.ptp(y - m * x))
    return best


def test_minimum_zone_matches_brute_force_on_random_sets():
    """Exact minimum zone: equal to exhaustive search on 300 small random sets (ties in x too)."""
    rng = np.random.default_rng(5)
    checked = 0
    for _ in range(300):
        n = int(rng.integers(3, 14))
        x = rng.uniform(0, 500, n)
        if rng.random() < 0.3:
            x = np.round(x / 100) * 100  # repeated positions
        if np.ptp(x) == 0:
            continue
        y = rng.normal(0, 3, n)
        line = minimum_zone_line(x, y)
        width = np.ptp(y - line.slope * x)
        assert width == pytest.approx(_brute_force_zone(x, y), rel=1e-9, abs=1e-12)
        # the mean line sits in the middle of the band
        r = y - line(x)
        assert r.max() == pytest.approx(-r.min(), abs=1e-9)
        checked += 1
    assert checked > 250


@settings(max_examples=150, deadline=None)
@given(st.lists(st.tuples(st.floats(-1e3, 1e3), st.floats(-50, 50)), min_size=2, max_size=40))
@example([(0.0, 1.0), (1.0, 0.0), (2.2250738585e-313, 0.0)])   # a hull edge of infinite slope
@example([(0.0, 0.0), (1.0, 0.0), (1.0, 1.0), (3.0545204071088712e-93, 0.0), (-1.0, 1.0)])
# ^ a lower-hull vertex whose cross product rounds to 0 beside a point 3e-93 away (was dropped)
def test_minimum_zone_never_wider_than_least_squares_or_end_points(points):
    """Property: the minimum zone is never wider than the least-squares or end-point bands."""
    x = np.array([p[0] for p in points])
    y = np.array([p[1] for p in points])
    if np.ptp(x) == 0:
        return
    span = np.ptp(x)
    if span < 1e-100 or span <= 1e-12 * np.abs(x).max():
        with pytest.raises(InputError, match="too narrow to fit a reference line"):
            straightness(x, y, "minimum_zone")
        return
    mz = straightness(x, y, "minimum_zone").deviation
    ls = straightness(x, y, "least_squares").deviation
    ep = straightness(x, y, "end_point").deviation
    tol = 1e-9 * (1 + np.abs(y).max() + np.abs(x).max())
    assert mz <= ls + tol
    assert mz <= ep + tol


@settings(max_examples=60, deadline=None)
@given(st.floats(-1, 1), st.floats(-100, 100), st.integers(0, 2**31))
def test_adding_a_line_changes_only_the_slope(slope, offset, seed):
    """Property: adding a straight line to the data leaves every straightness unchanged."""
    rng = np.random.default_rng(seed)
    x = np.sort(rng.uniform(0, 800, 25))
    y = rng.normal(0, 2, 25)
    for method in ("least_squares", "end_point", "minimum_zone"):
        a = straightness(x, y, method)
        b = straightness(x, y + slope * x + offset, method)
        assert b.deviation == pytest.approx(a.deviation, rel=1e-7, abs=1e-7)
        assert b.line.slope == pytest.approx(a.line.slope + slope, abs=1e-9)


def test_reference_lines_on_a_known_profile():
    """A symmetric bow 0, 3, 4, 3, 0 µm: all three lines are level; the straightness differs."""
    x = np.array([0, 100, 200, 300, 400.0])
    y = np.array([0, 3, 4, 3, 0.0])
    assert end_point_line(x, y).slope == 0.0
    assert least_squares_line(x, y).slope == pytest.approx(0.0, abs=1e-15)
    mz = minimum_zone_line(x, y)
    assert mz.slope == pytest.approx(0.0, abs=1e-15)
    assert mz.intercept == pytest.approx(2.0)
    assert straightness(x, y, "minimum_zone").deviation == pytest.approx(4.0)
    assert straightness(x, y, "least_squares").deviation == pytest.approx(4.0)


def test_minimum_zone_of_a_large_unsorted_set_uses_the_hull_path():
    """10^4 shuffled readings (Qhull path) agree with the same readings sorted."""
    rng = np.random.default_rng(2)
    x = np.linspace(0, 1000, 10_000)
    y = rng.normal(0, 1, x.size) + 2e-3 * x
    a = minimum_zone_line(x, y)
    p = rng.permutation(x.size)
    b = minimum_zone_line(x[p], y[p])
    assert b.slope == pytest.approx(a.slope, rel=1e-12)
    assert np.ptp(y - a.slope * x) <= np.ptp(y - least_squares_line(x, y).slope * x)


def test_collinear_readings_give_zero_straightness():
    x = np.linspace(0, 1, 200)
    r = straightness(x, 3 * x + 1, "minimum_zone")
    assert r.deviation == pytest.approx(0.0, abs=1e-12)
    assert r.line.slope == pytest.approx(3.0)


@pytest.mark.parametrize("x, y, err", [
    ([1.0], [2.0], InsufficientRunsError),
    ([1.0, 1.0], [2.0, 3.0], InsufficientRunsError),
    ([0.0, 1.0], [2.0, np.nan], InputError),
    ([0.0, 1.0, 2.0], [2.0, 1.0], InputError),
])
def test_bad_input_names_the_problem(x, y, err):
    with pytest.raises(err) as info:
        straightness(x, y, "minimum_zone")
    assert isinstance(info.value, AxiscalError)


def test_unknown_method_is_refused():
    with pytest.raises(InputError, match="method='chebyshev'"):
        straightness([0, 1], [0, 1], "chebyshev")


def test_squareness_sign_conventions():
    """Seed 004 Note 1: X datum gives the seed's sign, Y datum the opposite; the note says >90°."""
    x = np.linspace(-0.4, 0.4, 17)
    r = squareness_from_trajectories(x, 0 * x, x, -15e-6 * x)  # δx = -θ y with θ = 15 µm/m
    s = r.squareness
    assert s.um_per_m == pytest.approx(15.0)
    assert s.arcsec == pytest.approx(15.0 / 4.8481368, rel=1e-6)
    assert s.iso_um_per_m == pytest.approx(15.0)
    assert "larger than 90°" in s.angle_note and "larger than 90°" in str(s)
    y_datum = Squareness(s.excess, ("X", "Y"), datum="Y")
    assert y_datum.iso_um_per_m == pytest.approx(-15.0)
    # ISO right-hand rule in the XZ plane (anti-cyclic pair X, Z): Z referred to X flips sign
    assert Squareness(15e-6, ("X", "Z")).iso_um_per_m == pytest.approx(-15.0)
    assert Squareness(15e-6, ("Y", "Z")).iso_um_per_m == pytest.approx(15.0)
    assert "smaller than 90°" in Squareness(-1e-6).angle_note


def test_squareness_adds_the_tilts_of_both_trajectories():
    """Seed 004 Figure 2: the squareness combines both inclinations; X tilting towards +Y closes
    the angle, Y tilting towards -X opens it."""
    x = np.linspace(0, 0.8, 9)
    r = squareness_from_trajectories(x, 10e-6 * x, x, -25e-6 * x)
    assert r.slope_first == pytest.approx(10e-6)
    assert r.slope_second == pytest.approx(-25e-6)
    assert r.squareness.um_per_m == pytest.approx(15.0)


def test_prism_error_correction_and_reversal():
    """Seed 004 Method 3 / Note 2: a square error enters with the orientation's sign; reversing
    the square and averaging removes it."""
    assert correct_reference_angle(3e-6, 0) == 3e-6
    assert correct_reference_angle(3e-6, 270) == -3e-6
    with pytest.raises(InputError, match="orientation=45"):
        correct_reference_angle(3e-6, 45)
    assert reversal(12.0, 18.0) == (15.0, 3.0)
    with pytest.raises(InputError):
        Squareness(1e-6, ("X", "X"))
    with pytest.raises(InputError):
        Squareness(1e-6, ("X", "Y"), datum="Z")


@pytest.mark.parametrize("sx, sy", [(1.0, 1.0), (1e155, 1e155), (1e-100, 1e-230), (1e300, 1e-300)])
def test_minimum_zone_does_not_depend_on_the_unit(sx, sy):
    """The zone of (0,0) (1,1) (2,0) (3,1) is 1 (the band between y = 0 and y = 1); in any unit,
    however large or small, it scales with the deviations. Before the hull's cross products
    were formed on power-of-two-scaled coordinates, 1e155 overflowed them and 1e-230 underflowed,
    both giving 4/3, wider than least squares (1.2)."""
    x, y = np.array([0, 1, 2, 3.0]) * sx, np.array([0, 1, 0, 1.0]) * sy
    assert straightness(x, y, "minimum_zone").deviation == pytest.approx(sy, rel=1e-12)
