"""JIS B 0182-1993 terms 342 and 346 (jis_b6192): hand-worked example, independent implementation,
invariants (order of runs, constant offset, sign flip)."""

import statistics

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from axiscal.datasets import PositioningDataset
from axiscal.errors import InputError, InsufficientRunsError
from axiscal.standards.jis_b6192 import evaluate
from tests.standards.test_iso230_2 import HAND_UP, datasets, hand_dataset


def test_hand_worked_example():
    """Worked by hand from JIS B 0182-1993 term 342 (B_i = x̄↑ - x̄↓) and term 346
    (R_i = max[3s↑ + 3s↓ + |B_i|; 6s↑; 6s↓]); no public worked example exists.

    up   = [1,2,3] [4,4,4] [0,2,4]:  x̄↑ = 2, 4, 2;   s↑ = 1, 0, 2
    down = [-1,-1,-1] [2,3,4] [1,1,1]: x̄↓ = -1, 3, 1; s↓ = 0, 1, 0
    B_i = 3, 1, 1
    R_i = max(3+0+3, 6, 0) = 6;  max(0+3+1, 0, 6) = 6;  max(6+0+1, 12, 0) = 12
    R = 12, B = 3 (ISO 230-2:2014 gives R = 8 for the same test: 2s instead of 3s).
    """
    r = evaluate(hand_dataset())
    np.testing.assert_allclose(r.reversal, [3, 1, 1])
    np.testing.assert_allclose(r.R_i, [6, 6, 12])
    assert (r.R, r.B) == (12.0, 3.0)
    p = r.parameters()
    assert p["R"][0] == 12.0 and p["R"][1] == "um" and "term 346" in p["R"][2]


def reference(up, down):
    """Independent loop implementation with the statistics module (no NumPy, no ISO code)."""
    Ri, Bi = [], []
    for u, d in zip(up, down):
        su, sd = statistics.stdev(u), statistics.stdev(d)
        b = statistics.fmean(u) - statistics.fmean(d)
        Bi.append(abs(b))
        Ri.append(max(3 * su + 3 * sd + abs(b), 6 * su, 6 * sd))
    return max(Ri), max(Bi)


@given(datasets())
@settings(max_examples=60, deadline=None)
def test_agrees_with_independent_implementation(ds):
    r = evaluate(ds)
    R, B = reference(ds.up.tolist(), ds.down.tolist())
    assert r.R == pytest.approx(R, rel=1e-9, abs=1e-9)
    assert r.B == pytest.approx(B, rel=1e-9, abs=1e-9)


@given(datasets(), st.data())
@settings(max_examples=40, deadline=None)
def test_invariant_to_order_of_runs(ds, data):
    n = ds.up.shape[1]
    pu, pd = data.draw(st.permutations(range(n))), data.draw(st.permutations(range(n)))
    shuffled = PositioningDataset.from_arrays("linear", ds.targets, ds.up[:, pu], ds.down[:, pd])
    a, b = evaluate(ds), evaluate(shuffled)
    assert (a.R, a.B) == pytest.approx((b.R, b.B), rel=1e-9, abs=1e-9)


@given(datasets(), st.floats(-1000, 1000))
@settings(max_examples=40, deadline=None)
def test_constant_offset_leaves_R_and_B_unchanged(ds, c):
    a = evaluate(ds)
    b = evaluate(PositioningDataset.from_arrays("linear", ds.targets, ds.up + c, ds.down + c))
    assert (a.R, a.B) == pytest.approx((b.R, b.B), rel=1e-9, abs=1e-7)


@given(datasets())
@settings(max_examples=40, deadline=None)
def test_sign_flip_keeps_R_and_B_and_negates_B_i(ds):
    a = evaluate(ds)
    b = evaluate(PositioningDataset.from_arrays("linear", ds.targets, -ds.up, -ds.down))
    assert (a.R, a.B) == pytest.approx((b.R, b.B), rel=1e-9, abs=1e-9)
    np.testing.assert_allclose(b.reversal, -a.reversal, atol=1e-9)


def test_unidirectional_and_single_run_are_refused_naming_the_rule():
    uni = PositioningDataset.from_arrays("linear", [0, 100], HAND_UP[:2], [[], []])
    with pytest.raises(InputError, match="term 346"):
        evaluate(uni)
    one = PositioningDataset.from_arrays("linear", [0, 100], [[1], [2]], [[0], [1]])
    with pytest.raises(InsufficientRunsError):
        evaluate(one)


@given(datasets())
@settings(max_examples=40, deadline=None)
def test_reversal_agrees_with_iso230_2_and_repeatability_is_never_smaller(ds):
    """JIS B 0182 term 342 and ISO 230-2:2014 eq. 5-6 define the same reversal value (shared code);
    the JIS repeatability (3s/6s) is at least the ISO one (2s/4s) term by term."""
    from axiscal.standards import iso230_2

    iso, jis = iso230_2.evaluate(ds), evaluate(ds)
    assert jis.B == pytest.approx(iso.B, rel=1e-12, abs=1e-12)
    assert jis.R >= iso.R - 1e-9
