"""ISO 230-2:2014 evaluation: a hand-worked example, an independent re-implementation, invariants."""

import math
import statistics

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from hypothesis.extra.numpy import arrays

from axiscal.datasets import PositioningDataset
from axiscal.errors import InputError, InsufficientRunsError
from axiscal.standards.iso230_2 import (
    PARAMETER_NAMES,
    evaluate,
    minimum_linear_targets,
    minimum_rotary_targets,
)

HAND_UP = [[1, 2, 3], [4, 4, 4], [0, 2, 4]]
HAND_DOWN = [[-1, -1, -1], [2, 3, 4], [1, 1, 1]]


def hand_dataset():
    return PositioningDataset.from_arrays("linear", [0, 100, 200], HAND_UP, HAND_DOWN)


def test_hand_worked_example_per_target():
    """Worked by hand from ISO 230-2:2014 clause 3 (seed 001 eqs 2-12), integers chosen so every
    step is exact:

    target 0:   x↑ = 1, 2, 3   -> x̄↑ = 2, s↑ = 1;   x↓ = -1,-1,-1 -> x̄↓ = -1, s↓ = 0
    target 100: x↑ = 4, 4, 4   -> x̄↑ = 4, s↑ = 0;   x↓ = 2, 3, 4  -> x̄↓ = 3,  s↓ = 1
    target 200: x↑ = 0, 2, 4   -> x̄↑ = 2, s↑ = 2;   x↓ = 1, 1, 1  -> x̄↓ = 1,  s↓ = 0
    x̄_i = 0.5, 3.5, 1.5; B_i = 3, 1, 1; R↑_i = 4, 0, 8; R↓_i = 0, 4, 0;
    R_i = max(2+0+3, 4, 0) = 5, max(0+2+1, 0, 4) = 4, max(4+0+1, 8, 0) = 8.
    """
    r = evaluate(hand_dataset())
    np.testing.assert_allclose(r.mean_up, [2, 4, 2])
    np.testing.assert_allclose(r.mean_down, [-1, 3, 1])
    np.testing.assert_allclose(r.s_up, [1, 0, 2])
    np.testing.assert_allclose(r.s_down, [0, 1, 0])
    np.testing.assert_allclose(r.mean_bi, [0.5, 3.5, 1.5])
    np.testing.assert_allclose(r.reversal, [3, 1, 1])
    np.testing.assert_allclose(r.R_up_i, [4, 0, 8])
    np.testing.assert_allclose(r.R_down_i, [0, 4, 0])
    np.testing.assert_allclose(r.R_i, [5, 4, 8])
    assert r.n_up.tolist() == [3, 3, 3] and r.n_down.tolist() == [3, 3, 3]


def test_hand_worked_example_axis_parameters():
    """Same example, axis parameters (seed 001 eqs 6, 7, 13-21), by hand:

    E↑ = 4 - 2 = 2; E↓ = 3 - (-1) = 4; E = 4 - (-1) = 5; M = 3.5 - 0.5 = 3;
    A↑ = max(4, 4, 6) - min(0, 4, -2) = 8; A↓ = max(-1, 5, 1) - min(-1, 1, 1) = 6;
    A = max(6, 5) - min(-2, -1) = 8; R↑ = 8; R↓ = 4; R = 8; B = 3; B̄ = 5/3.
    """
    r = evaluate(hand_dataset())
    expected = dict(A=8, A_up=8, A_down=6, E=5, E_up=2, E_down=4, M=3, R=8, R_up=8, R_down=4,
                    B=3, B_mean=5 / 3)
    for k, v in expected.items():
        assert getattr(r, k) == pytest.approx(v, abs=1e-12), k
    assert r.bidirectional


def reference_evaluation(targets, up, down):
    """An independent, loop-by-loop implementation with the statistics module (no NumPy)."""
    m = len(targets)
    xu = [statistics.fmean([v for v in up[i] if not math.isnan(v)]) for i in range(m)]
    xd = [statistics.fmean([v for v in down[i] if not math.isnan(v)]) for i in range(m)]
    su = [statistics.stdev([v for v in up[i] if not math.isnan(v)]) for i in range(m)]
    sd = [statistics.stdev([v for v in down[i] if not math.isnan(v)]) for i in range(m)]
    Bi = [xu[i] - xd[i] for i in range(m)]
    Ri = [max(2 * su[i] + 2 * sd[i] + abs(Bi[i]), 4 * su[i], 4 * sd[i]) for i in range(m)]
    xbar = [(xu[i] + xd[i]) / 2 for i in range(m)]
    return dict(
        A=max(max(xu[i] + 2 * su[i], xd[i] + 2 * sd[i]) for i in range(m))
        - min(min(xu[i] - 2 * su[i], xd[i] - 2 * sd[i]) for i in range(m)),
        A_up=max(xu[i] + 2 * su[i] for i in range(m)) - min(xu[i] - 2 * su[i] for i in range(m)),
        A_down=max(xd[i] + 2 * sd[i] for i in range(m)) - min(xd[i] - 2 * sd[i] for i in range(m)),
        E=max(xu + xd) - min(xu + xd), E_up=max(xu) - min(xu), E_down=max(xd) - min(xd),
        M=max(xbar) - min(xbar), R=max(Ri), R_up=4 * max(su), R_down=4 * max(sd),
        B=max(abs(b) for b in Bi), B_mean=statistics.fmean(Bi),
    )


finite = st.floats(-50, 50, allow_nan=False, allow_infinity=False)


@st.composite
def datasets(draw, min_runs=2):
    m = draw(st.integers(2, 7))
    n = draw(st.integers(min_runs, 6))
    steps = draw(st.lists(st.floats(0.5, 100), min_size=m - 1, max_size=m - 1))
    targets = np.concatenate([[0.0], np.cumsum(steps)])
    up = draw(arrays(float, (m, n), elements=finite))
    down = draw(arrays(float, (m, n), elements=finite))
    return PositioningDataset.from_arrays("linear", targets, up, down)


@given(datasets())
@settings(max_examples=80, deadline=None)
def test_agrees_with_independent_implementation(ds):
    r = evaluate(ds)
    ref = reference_evaluation(ds.targets, ds.up.tolist(), ds.down.tolist())
    for k, v in ref.items():
        assert getattr(r, k) == pytest.approx(v, rel=1e-9, abs=1e-9), k


@given(datasets(), st.data())
@settings(max_examples=60, deadline=None)
def test_invariant_to_order_of_runs(ds, data):
    """CONVENTIONS habit 9: evaluation is invariant to the order of runs."""
    n = ds.up.shape[1]
    perm_up = data.draw(st.permutations(range(n)))
    perm_down = data.draw(st.permutations(range(n)))
    shuffled = PositioningDataset.from_arrays("linear", ds.targets, ds.up[:, perm_up],
                                              ds.down[:, perm_down])
    a, b = evaluate(ds).parameters(), evaluate(shuffled).parameters()
    for k in PARAMETER_NAMES:
        assert a[k] == pytest.approx(b[k], rel=1e-9, abs=1e-9), k


@given(datasets(), st.floats(-1000, 1000))
@settings(max_examples=60, deadline=None)
def test_constant_offset_leaves_parameters_unchanged(ds, c):
    """Adding one constant to every deviation leaves A, E, M, R and B (and B̄) unchanged."""
    shifted = PositioningDataset.from_arrays("linear", ds.targets, ds.up + c, ds.down + c)
    a, b = evaluate(ds).parameters(), evaluate(shifted).parameters()
    for k in PARAMETER_NAMES:
        assert a[k] == pytest.approx(b[k], rel=1e-9, abs=1e-7), k


@given(datasets())
@settings(max_examples=60, deadline=None)
def test_sign_flip_keeps_parameters_and_negates_mean_reversal(ds):
    flipped = PositioningDataset.from_arrays("linear", ds.targets, -ds.up, -ds.down)
    a, b = evaluate(ds).parameters(), evaluate(flipped).parameters()
    for k in PARAMETER_NAMES:
        expect = -a[k] if k == "B_mean" else a[k]
        assert b[k] == pytest.approx(expect, rel=1e-9, abs=1e-9), k


@given(datasets())
@settings(max_examples=30, deadline=None)
def test_unit_change_scales_every_parameter(ds):
    r_um = evaluate(ds)
    r_mm = evaluate(ds.with_deviation_unit("mm"))
    assert r_mm.deviation_unit == "mm"
    for k in PARAMETER_NAMES:
        assert r_mm.parameters()[k] == pytest.approx(r_um.parameters()[k] * 1e-3, rel=1e-9, abs=1e-12)


def test_unidirectional_gives_only_its_figures():
    ds = PositioningDataset.from_arrays("linear", [0, 100, 200], HAND_UP)
    r = evaluate(ds)
    assert r.A_up == pytest.approx(8) and r.E_up == pytest.approx(2) and r.R_up == pytest.approx(8)
    for k in ("A", "A_down", "E", "E_down", "M", "R", "R_down", "B", "B_mean"):
        assert getattr(r, k) is None, k
    assert any("do not apply" in w for w in r.warnings)
    assert not r.bidirectional


def test_fewer_than_five_runs_warns_and_one_run_is_an_error():
    r = evaluate(hand_dataset())
    assert any("3 runs" in w and "5" in w for w in r.warnings)
    one = PositioningDataset.from_arrays("linear", [0, 100, 200], [[1], [2], [3]], [[1], [2], [3]])
    with pytest.raises(InsufficientRunsError, match=r"1 reading\(s\) at target 0 mm.*at least 2"):
        evaluate(one)


def test_missing_readings_are_evaluated_from_what_exists_and_counted():
    up = [[1, 2, 3, np.nan], [4, 4, 4, 4], [0, 2, 4, 2]]
    down = [[-1, -1, -1, -1], [2, 3, 4, 3], [np.nan, 1, 1, np.nan]]
    r = evaluate(PositioningDataset.from_arrays("linear", [0, 100, 200], up, down))
    assert r.n_up.tolist() == [3, 4, 4] and r.n_down.tolist() == [4, 4, 2]
    assert r.mean_up[0] == pytest.approx(2.0) and r.s_up[0] == pytest.approx(1.0)
    assert r.missing == 3
    assert any("3 reading(s) missing" in w for w in r.warnings)
    # a target left with a single reading cannot give a repeatability
    down[2][1] = np.nan
    with pytest.raises(InsufficientRunsError, match="target 200 mm in direction -"):
        evaluate(PositioningDataset.from_arrays("linear", [0, 100, 200], up, down))


def _full_turn(closure_arcsec, rng):
    targets = np.arange(0, 361, 45.0)
    base = 3 * np.sin(np.radians(targets))
    up = base[:, None] + rng.normal(0, 0.1, (9, 5))
    down = base[:, None] - 1 + rng.normal(0, 0.1, (9, 5))
    up[-1] += closure_arcsec
    down[-1] += closure_arcsec
    return PositioningDataset.from_arrays("rotary", targets, up, down)


def test_full_turn_keeps_0_and_360_apart_and_reports_closure():
    """Seed 001 Table 3 lists 0° and 360° as targets 0 and 8 of one test; they are the same
    physical position, so 8 distinct positions meet ISO 230-2 Table 1 (8 for > 180°)."""
    rng = np.random.default_rng(0)
    r = evaluate(_full_turn(0.0, rng))
    assert r.targets.size == 9 and r.distinct_positions == 8
    assert abs(r.closure_up) < 0.3 and abs(r.closure_down) < 0.3
    assert not any("closure" in w for w in r.warnings)
    assert not any("target positions" in w for w in r.warnings)
    drifted = evaluate(_full_turn(2.0, rng))
    assert drifted.closure_up == pytest.approx(2.0, abs=0.3)
    assert any("closure in direction +" in w for w in drifted.warnings)


def test_full_turn_merge_pools_360_into_0():
    ds = _full_turn(0.0, np.random.default_rng(1))
    r = evaluate(ds, full_turn="merge")
    assert r.targets.tolist() == [0, 45, 90, 135, 180, 225, 270, 315]
    assert r.n_up[0] == 10 and r.n_up[1] == 5
    assert r.mean_up[0] == pytest.approx(np.mean(np.concatenate([ds.up[0], ds.up[-1]])))
    assert r.closure_up is None
    with pytest.raises(InputError, match="full_turn"):
        evaluate(ds, full_turn="wrap")


def test_too_few_targets_warns_with_the_rule():
    r = evaluate(PositioningDataset.from_arrays("rotary", [0, 90, 180, 270], [[0, 1]] * 4, [[0, 1]] * 4))
    assert any("at least 8" in w and "Table 1" in w for w in r.warnings)


def test_minimum_target_counts():
    """Seed 001 Table 1 (ISO 230-2 Table 1) and ISO 230-2 §5.2 (5 per metre, at least 5)."""
    assert [minimum_rotary_targets(t) for t in (10, 90, 90.01, 180, 180.01, 720)] == [3, 3, 5, 5, 8, 8]
    assert [minimum_linear_targets(t) for t in (100, 1000, 1200, 2000)] == [5, 5, 6, 10]
    with pytest.raises(InputError):
        minimum_rotary_targets(0)


def test_result_str_and_table_are_readable():
    r = evaluate(hand_dataset())
    text = str(r)
    # the symbols of ISO 230-2:2014 clause 3, µm and 0.01 µm, not the code's keys and "um"
    assert "A  =     8.00 µm" in text and "B̄  =     1.67 µm" in text and "A↑ =" in text
    assert "um" not in text.replace("µm", "") and "B_mean" not in text
    # one column on screen (the bar over B is a combining mark: it takes no column)
    assert len({line.replace("\u0304", "").index("=") for line in text.splitlines()[1:13]}) == 1
    rows = r.target_table()
    assert rows[1]["mean_bi"] == pytest.approx(3.5) and rows[0]["n_up"] == 3


def _no_scatter_full_turn(closure_arcsec):
    """Readings with no scatter, formed as a real capture forms them: the actual angle in
    degrees (target + 0.01″ + a 0.05″ once-per-turn error + closure at 360°) minus the target,
    × 3600.
    At 360° one unit in the last place of the angle is 5.7e-14° = 2e-10″ (IEEE 754 binary64),
    so the difference of the means at 0° and 360° is float rounding, not a closure."""
    targets = np.arange(0, 361, 45.0)
    err_deg = 0.05 / 3600 * np.sin(np.radians(targets)) + 0.01 / 3600
    err_deg[-1] += closure_arcsec / 3600
    actual = targets + err_deg
    dev = (actual - targets) * 3600.0
    up = np.repeat(dev[:, None], 5, axis=1)
    return PositioningDataset.from_arrays("rotary", targets, up, up - 1.0)


def test_no_scatter_gives_no_false_closure_warning():
    """Issue 21: with no scatter 3 standard errors = 0, and the rounding of the angle at 360°
    (~1e-10″) alone must not warn; a closure of 0.01″ with no scatter is real and still warns."""
    clean = evaluate(_no_scatter_full_turn(0.0))
    assert 0 < abs(clean.closure_up) < 1e-8          # the rounding the data carry
    assert not any("closure" in w for w in clean.warnings)
    real = evaluate(_no_scatter_full_turn(0.01))
    assert real.closure_up == pytest.approx(0.01, abs=1e-8)
    assert any("closure in direction +" in w for w in real.warnings)
