"""Review of standards/iso230_2.py: the full-turn merge and a worked example by hand."""

from __future__ import annotations

import math

import numpy as np
import pytest

from axiscal.datasets import PositioningDataset
from axiscal.standards.iso230_2 import evaluate


def _full_turn(runs, rng):
    targets = np.arange(0.0, 361.0, 45.0)
    up = rng.normal(0.0, 1.0, (9, runs))
    down = rng.normal(-1.0, 1.0, (9, runs))
    return targets, up, down


def test_merge_does_not_invent_runs_or_missing_readings():
    """Pooling 360° into 0° pads the other targets with NaN columns: those are not missing
    readings, and the test still has the runs it had (3 < 5 must still be warned about)."""
    targets, up, down = _full_turn(3, np.random.default_rng(7))
    ds = PositioningDataset.from_arrays("rotary", targets, up, down)
    sep = evaluate(ds, full_turn="separate")
    mer = evaluate(ds, full_turn="merge")
    assert mer.n_runs == sep.n_runs == 3
    assert mer.missing == sep.missing == 0
    assert not any("missing" in w for w in mer.warnings)
    assert any("3 runs" in w and "asks for 5" in w for w in mer.warnings)
    assert mer.n_up.tolist() == [6, 3, 3, 3, 3, 3, 3, 3]


def test_merge_counts_the_readings_really_missing():
    targets, up, down = _full_turn(5, np.random.default_rng(8))
    up[2, 1] = np.nan
    down[8, 4] = np.nan
    ds = PositioningDataset.from_arrays("rotary", targets, up, down)
    mer = evaluate(ds, full_turn="merge")
    assert mer.missing == 2
    assert mer.n_runs == 5
    assert mer.n_up[2] == 4 and mer.n_down[0] == 9
    assert not any("runs; ISO" in w for w in mer.warnings)


def test_worked_example_by_hand():
    """Two targets, two runs each way, every figure worked out on paper (ISO 230-2:2014
    clause 3, seed 001 eqs. 2-21):

    target 0: up 1, 3 -> mean 2, s = sqrt(2); down 0, 0 -> mean 0, s = 0; B_0 = +2
    target 1: up 2, 2 -> mean 2, s = 0; down 1, 3 -> mean 2, s = sqrt(2); B_1 = 0
    R_0 = max(2 sqrt2 + 0 + 2, 4 sqrt2, 0) = 4 sqrt2;  R_1 = max(0 + 2 sqrt2 + 0, 0, 4 sqrt2)
    E = 2 - 0 = 2;  M = max(1, 2) - min(1, 2) = 1;  B = 2;  mean reversal = (2 + 0)/2 = 1
    A = (2 + 2 sqrt2) - (2 - 2 sqrt2) = 4 sqrt2;  A_up = A_down = 4 sqrt2;  E_up = 0, E_down = 2
    """
    ds = PositioningDataset.from_arrays("linear", [0.0, 100.0], up=[[1, 3], [2, 2]],
                                        down=[[0, 0], [1, 3]])
    r = evaluate(ds)
    r2 = 2 * math.sqrt(2)
    np.testing.assert_allclose(r.s_up, [math.sqrt(2), 0.0])
    np.testing.assert_allclose(r.reversal, [2.0, 0.0])
    np.testing.assert_allclose(r.R_i, [2 * r2, 2 * r2])
    want = dict(A=2 * r2, A_up=2 * r2, A_down=2 * r2, E=2.0, E_up=0.0, E_down=2.0, M=1.0,
                R=2 * r2, R_up=2 * r2, R_down=2 * r2, B=2.0, B_mean=1.0)
    for name, value in want.items():
        assert getattr(r, name) == pytest.approx(value, abs=1e-12), name


def test_no_closure_warning_from_floating_point_rounding():
    """A noise-free full turn whose error is 3 sin θ: at 360° float gives 3 sin(2π) = −7e-16,
    not 0, and with zero scatter the closure test warned about a 7e-16 arcsec 'drift'. A real
    closure (one resolution step, 0.1 arcsec) is still reported."""
    t = np.arange(0.0, 361.0, 45.0)
    up = np.repeat((3 * np.sin(np.radians(t)))[:, None], 5, axis=1)
    r = evaluate(PositioningDataset.from_arrays("rotary", t, up, up - 1.0))
    assert abs(r.closure_up) < 1e-14
    assert not any("closure" in w for w in r.warnings)
    up[-1] += 0.1
    r = evaluate(PositioningDataset.from_arrays("rotary", t, up, up - 1.0))
    assert r.closure_up == pytest.approx(0.1)
    assert any("closure in direction +" in w for w in r.warnings)
