"""VDI/DGQ 3441 Pa and U as Bosch Rexroth (Linearmodule R310DE 2402, p. 151) defines them:
hand-worked examples, an independent implementation and agreement with ISO 230-2:2014 where both
define the same quantity (the invariants of every standard: test_positioning_standards)."""

import math
import statistics

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from axiscal.datasets import PositioningDataset
from axiscal.errors import InputError
from axiscal.standards.vdi3441 import NOT_EVALUATED, evaluate
from tests.standards.test_iso230_2 import HAND_UP, datasets, hand_dataset


def test_hand_worked_example():
    """No public worked example of VDI/DGQ 3441 exists; worked by hand from Rexroth's words
    ("Umkehrspanne: difference of the mean values of the two approach directions, at every
    measuring position"; "Positionsabweichung: largest difference of the mean values of all
    measuring positions"):

    up   = [1,2,3] [4,4,4] [0,2,4]:    x̄↑ = 2, 4, 2
    down = [-1,-1,-1] [2,3,4] [1,1,1]: x̄↓ = -1, 3, 1
    U_j = |x̄↑ - x̄↓| = 3, 1, 1 -> U = 3, Ū = 5/3
    x̄_j = (x̄↑ + x̄↓)/2 = 0.5, 3.5, 1.5 -> Pa = 3.5 - 0.5 = 3
    """
    r = evaluate(hand_dataset())
    np.testing.assert_allclose(r.U_j, [3, 1, 1])
    np.testing.assert_allclose(r.mean, [0.5, 3.5, 1.5])
    assert (r.Pa, r.U) == (3.0, 3.0) and r.U_mean == pytest.approx(5 / 3)
    p = r.parameters()
    assert set(p) == {"Pa", "U", "U_mean"} and p["Pa"][1] == "um" and "Rexroth" in p["Pa"][2]
    assert set(NOT_EVALUATED) == {"P", "Ps"}
    # targets 0, 100, 200 are evenly spaced: the uneven-spacing rule is named
    assert any("uneven intervals" in w for w in r.warnings)


def test_a_missing_reading_does_not_turn_reversal_into_position_deviation():
    """The reading documented in the module: x̄_j = (x̄_j↑ + x̄_j↓)/2. A pure reversal (every x↑ = 1,
    every x↓ = -1) with one reading missing has no position deviation: Pa = 0, U = 2 (pooling
    every approach would give x̄ = 1/9 at the target with the gap, and Pa = 0.111)."""
    up, down = np.ones((4, 5)), -np.ones((4, 5))
    down[2, 0] = math.nan
    ds = PositioningDataset.from_arrays("linear", [0, 130, 420, 1000], up, down)
    r = evaluate(ds)
    assert r.Pa == 0.0 and r.U == 2.0 and r.U_mean == 2.0


def reference(up, down):
    """Independent loop implementation with the statistics module (no NumPy)."""
    means, spans = [], []
    for u, d in zip(up, down):
        means.append(0.5 * (statistics.fmean(u) + statistics.fmean(d)))
        spans.append(abs(statistics.fmean(u) - statistics.fmean(d)))
    return max(means) - min(means), max(spans), statistics.fmean(spans)


@given(datasets(min_runs=1))
@settings(max_examples=60, deadline=None)
def test_agrees_with_independent_implementation(ds):
    r = evaluate(ds)
    Pa, U, Um = reference(ds.up.tolist(), ds.down.tolist())
    assert (r.Pa, r.U, r.U_mean) == pytest.approx((Pa, U, Um), rel=1e-9, abs=1e-9)


@given(datasets())
@settings(max_examples=40, deadline=None)
def test_sign_flip_negates_the_position_means(ds):
    """Order of runs, offset and sign flip on Pa, U, Ū: test_positioning_standards (every
    standard); here the per-target means, which flip with the readings."""
    a = evaluate(ds)
    b = evaluate(PositioningDataset.from_arrays("linear", ds.targets, -ds.up, -ds.down))
    np.testing.assert_allclose(b.mean, -a.mean, atol=1e-9)
    np.testing.assert_allclose(b.U_j, a.U_j, atol=1e-9)


@given(datasets(min_runs=3), st.data())
@settings(max_examples=40, deadline=None)
def test_agrees_with_iso230_2_where_both_define_the_same_quantity(ds, data):
    """VDI's Pa is ISO 230-2:2014's range of the mean bidirectional positioning error M (eq. 19) and
    VDI's largest reversal span is ISO's reversal value B (eq. 6): computed independently here,
    they must agree, with readings missing too."""
    from axiscal.standards import iso230_2

    up, down = ds.up.copy(), ds.down.copy()
    for arr in (up, down):  # leave one reading out at some targets (2 stay: ISO needs them)
        for i in data.draw(st.lists(st.integers(0, arr.shape[0] - 1), max_size=3)):
            arr[i, 0] = math.nan
    ds = PositioningDataset.from_arrays("linear", ds.targets, up, down)
    iso, vdi = iso230_2.evaluate(ds), evaluate(ds)
    assert vdi.Pa == pytest.approx(iso.M, rel=1e-9, abs=1e-9)
    assert vdi.U == pytest.approx(iso.B, rel=1e-9, abs=1e-9)


def test_one_direction_or_an_empty_target_is_refused_naming_the_rule():
    uni = PositioningDataset.from_arrays("linear", [0, 100], HAND_UP[:2], [[], []])
    with pytest.raises(InputError, match="both sides"):
        evaluate(uni)
    gap = PositioningDataset.from_arrays("linear", [0, 100], [[1, 2], [1, 2]],
                                         [[0, 0], [math.nan, math.nan]])
    with pytest.raises(InputError, match="target 100 mm has no reading ↓"):
        evaluate(gap)


def test_single_approach_is_evaluated_with_a_warning():
    ds = PositioningDataset.from_arrays("linear", [0, 30, 100], [[1], [2], [0]], [[0], [0], [1]])
    r = evaluate(ds)
    assert r.U == 2.0 and any("several times" in w for w in r.warnings)
