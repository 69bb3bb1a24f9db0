"""ISO 230-2:1988 and :2006 unidirectional repeatability (6s and 4s spreads): hand-worked example,
independent implementation, and agreement of 2006 with ISO 230-2:2014 (the invariants of every
standard: test_positioning_standards)."""

import statistics

import pytest
from hypothesis import given, settings

from axiscal.datasets import PositioningDataset
from axiscal.errors import InsufficientRunsError
from axiscal.standards import iso230_2
from axiscal.standards.iso230_2_editions import NOT_EVALUATED, evaluate_1988, evaluate_2006
from tests.standards.test_iso230_2 import HAND_UP, datasets, hand_dataset


def test_hand_worked_example():
    """No public worked example of either edition exists; by hand from the spreads the public
    sources give (1988: six standard deviations, WIT Transactions on Engineering Sciences 23,
    1999; 2006: two standard uncertainties either side, AMT's announcement):

    s↑ = 1, 0, 2 and s↓ = 0, 1, 0 (the ISO 230-2 hand example)
    1988: R↑ = max 6 s↑ = 12, R↓ = max 6 s↓ = 6;  2006: R↑ = 8, R↓ = 4.
    """
    ds = hand_dataset()
    old, new = evaluate_1988(ds), evaluate_2006(ds)
    assert (old.R_up, old.R_down) == (12.0, 6.0)
    assert (new.R_up, new.R_down) == (8.0, 4.0)
    p = old.parameters()
    assert set(p) == {"R_up", "R_down"} and "6s_i↑" in p["R_up"][2] and "WIT" in p["R_up"][2]
    assert set(NOT_EVALUATED) == {"A", "R", "B"}


def reference(runs, k):
    """Independent implementation: k times the largest sample standard deviation."""
    return k * max(statistics.stdev(r) for r in runs)


@given(datasets())
@settings(max_examples=60, deadline=None)
def test_agrees_with_independent_implementation(ds):
    for fn, k in ((evaluate_1988, 6), (evaluate_2006, 4)):
        r = fn(ds)
        assert r.R_up == pytest.approx(reference(ds.up.tolist(), k), rel=1e-9, abs=1e-9)
        assert r.R_down == pytest.approx(reference(ds.down.tolist(), k), rel=1e-9, abs=1e-9)


@given(datasets())
@settings(max_examples=40, deadline=None)
def test_2006_gives_the_2014_values_and_1988_one_and_a_half_times_them(ds):
    """The 2006 band (±2 standard uncertainties) is the 2014 band (eqs. 10, 11, 13, 14); the s
    are shared code, so the agreement is exact; the 1988 spread is 6/4 of it."""
    iso = iso230_2.evaluate(ds)
    new, old = evaluate_2006(ds), evaluate_1988(ds)
    assert (new.R_up, new.R_down) == pytest.approx((iso.R_up, iso.R_down), rel=1e-12, abs=1e-12)
    assert old.R_up == pytest.approx(1.5 * iso.R_up, rel=1e-12, abs=1e-12)


def test_one_direction_gives_that_direction_and_one_reading_is_refused():
    uni = PositioningDataset.from_arrays("linear", [0, 100], HAND_UP[:2], [[], []])
    r = evaluate_1988(uni)
    assert r.R_up == 6.0 and r.R_down is None
    one = PositioningDataset.from_arrays("linear", [0, 100], [[1], [2]], [[0], [1]])
    with pytest.raises(InsufficientRunsError):
        evaluate_1988(one)
