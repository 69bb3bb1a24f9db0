"""ISO 230-7 error motion evaluation on synthetic data with known values."""

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from axiscal.errors import InputError, InsufficientRunsError
from axiscal.standards.iso230_7 import (MotionErrorData, evaluate, fundamental, halfrange,
                                        polar_coordinates)
from axiscal.units import ARCSEC, UM

TH = np.radians(np.arange(0, 360, 30.0))


def _data(**kw):
    z = np.zeros((kw.pop("runs", 3), TH.size))
    ch = dict(ez=z, ey=z, ex=z, dy=z, dz=z)
    ch.update(kw)
    return MotionErrorData(TH, **ch)


def test_fundamental_removed_from_radial_kept_in_axial():
    """ISO 230-7: the once-per-turn part of radial motion (centring) is removed, of axial kept.
    Input 5 µm eccentricity plus a 2 µm two-per-turn lobe in both: radial synchronous = 4 µm
    (the lobe's p-v), axial synchronous = p-v of the sum."""
    sig = 5 * UM * np.cos(TH) + 2 * UM * np.cos(2 * TH)
    r = evaluate(_data(dy=np.tile(sig, (3, 1)), dz=np.tile(sig, (3, 1))))
    rad, ax = r.motion("radial Y"), r.motion("axial")
    assert rad.fundamental / UM == pytest.approx(5.0)
    assert rad.synchronous / UM == pytest.approx(4.0)
    assert rad.total / UM == pytest.approx(4.0)
    assert rad.asynchronous == pytest.approx(0.0, abs=1e-15)
    assert ax.synchronous == pytest.approx(np.ptp(sig))
    assert not ax.fundamental_removed and rad.fundamental_removed


def test_asynchronous_is_widest_band_and_total_covers_it():
    """Asynchronous value = largest spread across runs at one angle; total ≥ synchronous."""
    rng = np.random.default_rng(0)
    base = 3 * ARCSEC * np.sin(3 * TH)
    runs = base + rng.normal(0, 0.5 * ARCSEC, (4, TH.size))
    r = evaluate(_data(runs=4, ex=runs))
    m = r.motion("tilt X")
    assert m.asynchronous == pytest.approx(np.max(np.ptp(runs, axis=0)))
    assert m.total >= m.synchronous
    assert m.total <= m.synchronous + m.asynchronous + 1e-15


def test_location_errors_are_means():
    """Axis average line: offsets and tilts are the means over the turn."""
    r = evaluate(_data(dy=np.full((3, TH.size), 2 * UM), ex=np.full((3, TH.size), 4 * ARCSEC),
                       ey=np.full((3, TH.size), -1 * ARCSEC)))
    assert r.location.y0 == pytest.approx(2 * UM)
    assert r.location.a0 == pytest.approx(4 * ARCSEC)
    assert r.location.b0 == pytest.approx(-ARCSEC)
    assert math.isnan(r.location.x0)
    assert "x0 —" in str(r.location)


def test_closing_angle_is_dropped_and_closure_reported():
    th = np.radians(np.arange(0, 361, 30.0))
    z = np.zeros((2, th.size))
    ez = z.copy()
    ez[:, -1] = 1 * ARCSEC
    r = evaluate(MotionErrorData(th, ez=ez, ey=z, ex=z, dy=z, dz=z))
    assert r.theta.size == 12
    assert r.closure["ez"] == pytest.approx(ARCSEC)


def test_positioning_summary_and_single_run_warning():
    ez = np.array([np.sin(TH), np.sin(TH) + 0.1]) * 10 * ARCSEC
    r = evaluate(_data(runs=2, ez=ez))
    assert r.positioning.range / ARCSEC == pytest.approx(10 * np.ptp(np.sin(TH)) , rel=1e-9)
    assert r.positioning.repeatability / ARCSEC == pytest.approx(0.5)
    one = evaluate(_data(runs=1))
    assert math.isnan(one.motion("axial").asynchronous) and one.warnings
    assert "asynchronous" in str(one)


def test_bad_inputs_are_refused():
    with pytest.raises(InputError, match="equally spaced"):
        evaluate(MotionErrorData(np.radians([0, 30, 60, 100]), *(np.zeros((1, 4)),) * 5))
    with pytest.raises(InputError, match="NaN"):
        _data(dy=np.full((3, TH.size), np.nan))
    with pytest.raises(InputError, match="runs"):
        _data(dy=np.zeros((2, TH.size)))
    with pytest.raises(InputError):
        evaluate(_data()).motion("radial X")
    with pytest.raises(InsufficientRunsError):
        halfrange([[1.0, 2.0]])


def test_polar_coordinates():
    x, y = polar_coordinates([0.0, math.pi / 2], [1e-6, 0.0], 10.0, 1e6)
    assert x == pytest.approx([11.0, 0.0], abs=1e-12) and y == pytest.approx([0.0, 10.0])
    assert np.allclose(fundamental(TH, np.cos(TH) + 3), np.cos(TH))


@settings(max_examples=30, deadline=None)
@given(st.floats(-1e-5, 1e-5), st.permutations(range(3)))
def test_invariant_to_offset_and_run_order(offset, order):
    """Adding a constant to every reading and reordering runs changes no error motion value."""
    rng = np.random.default_rng(5)
    runs = rng.normal(0, 1e-6, (3, TH.size))
    a = evaluate(_data(dy=runs, dz=runs, ex=runs))
    b = evaluate(_data(dy=runs[list(order)] + offset, dz=runs[list(order)] + offset, ex=runs))
    for m1, m2 in zip(a.motions, b.motions):
        assert m1.total == pytest.approx(m2.total, abs=1e-15)
        assert m1.synchronous == pytest.approx(m2.synchronous, abs=1e-15)
        assert m1.asynchronous == pytest.approx(m2.asynchronous, abs=1e-15)
