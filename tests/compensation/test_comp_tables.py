"""Compensation tables: sign, interpolation, extrapolation, directions, modulo, rounding."""

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from axiscal.compensation.tables import CompensationTable, table_from_deviations, table_from_result
from axiscal.datasets import PositioningDataset
from axiscal.errors import InputError
from axiscal.standards.iso230_2 import evaluate
from axiscal.compensation.squareness import squareness_compensation
from axiscal.compensation.tables import MAX_TABLE_POINTS
from axiscal.standards.iso230_1 import Squareness


def _result():
    """Hand-made test: x̄↑ = 1, 3, 5 µm and x̄↓ = -1, 1, 3 µm at 0, 100, 200 mm (B_i = 2 µm)."""
    ds = PositioningDataset.from_arrays("linear", [0, 100, 200],
                                        up=[[1, 1], [3, 3], [5, 5]], down=[[-1, -1], [1, 1], [3, 3]])
    return evaluate(ds)


def test_correction_is_minus_the_mean_bidirectional_deviation():
    """Unidirectional table: correction = −x̄_i (seed 001 eq. 4: x̄_i = (x̄↑ + x̄↓)/2 = 0, 2, 4)."""
    t = table_from_result(_result(), 100)
    assert t.up.tolist() == [0.0, -2.0, -4.0]
    assert t.down.tolist() == t.up.tolist()
    assert not t.bidirectional and t.backlash == 0.0


def test_bidirectional_tables_and_backlash_equal_the_mean_reversal():
    """up = −x̄↑, down = −x̄↓; backlash = mean(down − up) = B̄ = 2 µm (seed 001 eq. 7)."""
    r = _result()
    t = table_from_result(r, 50, bidirectional=True)
    assert t.positions.tolist() == [0, 50, 100, 150, 200]
    assert t.up.tolist() == [-1, -2, -3, -4, -5]
    assert t.down.tolist() == [1, 0, -1, -2, -3]
    assert t.backlash == pytest.approx(r.B_mean)
    assert np.allclose(t.mean, t.up + t.backlash / 2)
    assert t.correction_at(25.0, -1) == pytest.approx(0.5)
    assert t.correction_at(25.0, +1) == pytest.approx(-1.5)


def test_bidirectional_needs_both_directions():
    ds = PositioningDataset.from_arrays("linear", [0, 100, 200], up=[[1, 1], [3, 3], [5, 5]])
    with pytest.raises(InputError, match="positive direction only"):
        table_from_result(evaluate(ds), 50, bidirectional=True)


def test_extrapolation_hold_and_linear():
    """Points beyond the last target: 'hold' keeps the end value, 'linear' continues the slope."""
    hold = table_from_deviations([0, 100], [0.0, 10.0], spacing=50, end=200)
    lin = table_from_deviations([0, 100], [0.0, 10.0], spacing=50, end=200, extrapolation="linear")
    assert hold.up.tolist() == [0, -5, -10, -10, -10]
    assert lin.up.tolist() == [0, -5, -10, -15, -20]
    assert hold.extrapolation == "hold" and lin.extrapolation == "linear"
    with pytest.raises(InputError, match="extrapolation"):
        table_from_deviations([0, 100], [0.0, 1.0], spacing=50, extrapolation="cubic")


def test_range_ends_at_first_point_beyond_end():
    t = table_from_deviations([0, 95], [0.0, 1.0], spacing=20)
    assert t.end == 100.0 and t.n_points == 6


def test_rounding_to_resolution():
    t = table_from_deviations([0, 3], [0.0, 1.0], spacing=1, resolution=0.25)
    assert t.up.tolist() == [0.0, -0.25, -0.75, -1.0]   # −1/3 → −0.25, −2/3 → −0.75
    assert t.resolution == 0.25


def test_rotary_full_turn_closes_on_itself_and_pools_0_and_360():
    """0° and 360° are one physical position: their deviations are averaged, the table closes."""
    th = np.arange(0, 361, 45.0)
    dev = np.sin(np.radians(th)) * 3.0
    dev[-1] = 1.0                     # 360° measured 1 arcsec off the 0° reading (closure)
    t = table_from_deviations(th, dev, spacing=30, modulo=True, axis_kind="rotary",
                              position_unit="deg", correction_unit="arcsec")
    assert t.modulo and t.n_points == 13
    assert t.up[0] == t.up[-1] == pytest.approx(-0.5)
    assert t.correction_at(390.0) == pytest.approx(t.correction_at(30.0))


def test_modulo_spacing_must_divide_360():
    with pytest.raises(InputError, match="does not divide 360"):
        table_from_deviations([0, 180, 360], [0, 1, 0], spacing=50, modulo=True,
                              axis_kind="rotary", position_unit="deg", correction_unit="arcsec")


def test_zeroed_at_reference_keeps_shape():
    t = table_from_deviations([0, 100, 200], [2.0, -1.0, 4.0], spacing=100).with_reference(100)
    z = t.zeroed_at_reference()
    assert z.up[1] == 0.0 and np.allclose(np.diff(z.up), np.diff(t.up))
    with pytest.raises(InputError, match="outside the table"):
        t.with_reference(500)


def test_table_refuses_bad_input():
    with pytest.raises(InputError, match="at least 2"):
        CompensationTable("X", "linear", "mm", "um", 0.0, 1.0, [1.0], [1.0])
    with pytest.raises(InputError, match="spacing"):
        CompensationTable("X", "linear", "mm", "um", 0.0, 0.0, [1.0, 2.0], [1.0, 2.0])
    with pytest.raises(InputError, match="NaN"):
        table_from_deviations([0, 1], [0.0, np.nan], spacing=1)


@settings(max_examples=40, deadline=None)
@given(st.lists(st.floats(-50, 50), min_size=3, max_size=12), st.floats(-20, 20))
def test_constant_offset_shifts_every_correction(devs, offset):
    """Adding a constant to every deviation subtracts it from every correction."""
    t = np.arange(len(devs)) * 10.0
    a = table_from_deviations(t, devs, spacing=5)
    b = table_from_deviations(t, np.add(devs, offset), spacing=5)
    assert np.allclose(b.up, a.up - offset, atol=1e-9)


@settings(max_examples=40, deadline=None)
@given(st.lists(st.floats(-50, 50), min_size=9, max_size=9))
def test_table_reproduces_deviations_at_targets(devs):
    """Where table points and targets coincide, correction = −deviation exactly."""
    t = np.linspace(0, 400, 9)
    tab = table_from_deviations(t, devs, spacing=50)
    assert np.allclose(tab.correction_at(t), -np.asarray(devs), atol=1e-9)


# -- Table sizes are bounded before anything is allocated (CLI review: --spacing 1e-9 tried to ----------
# allocate 1.5 TiB for 2e11 points and died with numpy's MemoryError traceback).

def test_tiny_spacing_is_refused_naming_the_count():
    with pytest.raises(InputError, match=r"200000000001 table points; at most 100000"):
        table_from_deviations([0, 200], [1.0, 2.0], spacing=1e-9)


def test_denormal_spacing_is_refused_not_overflowed():
    with pytest.raises(InputError, match="infinitely many table points"):
        table_from_deviations([0, 200], [1.0, 2.0], spacing=5e-324)


def test_modulo_table_count_is_bounded_too():
    with pytest.raises(InputError, match="table points; at most"):
        table_from_deviations([0, 180, 360], [1.0, 2.0, 1.0], spacing=360 / 10**7, modulo=True,
                              axis_kind="rotary", position_unit="deg", correction_unit="arcsec")


def test_the_limit_itself_is_allowed():
    """Exactly MAX_TABLE_POINTS points: 0 … (MAX-1)·spacing."""
    t = table_from_deviations([0, MAX_TABLE_POINTS - 1], [1.0, 2.0], spacing=1.0)
    assert t.n_points == MAX_TABLE_POINTS


def test_squareness_table_count_is_bounded():
    c = squareness_compensation(Squareness(40e-6, ("X", "Z")), aligned_axis="Z")
    with pytest.raises(InputError, match="table points; at most"):
        c.table(0.0, 1.0, 1e-12)
