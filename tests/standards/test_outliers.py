"""Grubbs' test on the runs of one target: readings that alone set A or R are said, never dropped."""

from pathlib import Path

import numpy as np
import pytest

from axiscal.datasets import PositioningDataset
from axiscal.standards.iso230_2 import evaluate
from axiscal.standards.outliers import grubbs_critical, grubbs_p_value, positioning_outliers

ECMC = Path(__file__).parents[1] / "data" / "ecmc" / "mcu1025_fat_sat_ISO230.dat"


@pytest.mark.parametrize("n, table", [(3, 1.155), (5, 1.715), (10, 2.290), (25, 2.822)])
def test_critical_values_match_astm_e178(n, table):
    """ASTM E178-16a Table 1, upper 2.5 % (two-sided 5 %): 1.155 (n 3), 1.715 (5), 2.290 (10),
    2.822 (25). The Bonferroni form the table uses is within 1e-3 of it (n = 3: 1.1543, where
    the largest possible G is 1.1547)."""
    assert grubbs_critical(n) == pytest.approx(table, abs=1e-3)
    assert grubbs_p_value(grubbs_critical(n), n) == pytest.approx(0.05, rel=1e-6)


def test_p_value_monotone_and_bounded():
    """p falls as G grows; below 3 readings there is no test (p = 1)."""
    ps = [grubbs_p_value(g, 7) for g in np.linspace(0.5, 2.2, 20)]
    assert all(a >= b for a, b in zip(ps, ps[1:]))
    assert grubbs_p_value(5.0, 2) == 1.0


def test_real_ess_axis_first_run_named_as_setting_r_and_a():
    """The real ESS MCU1025 file: R = 204.76 µm rests on one reading of +93.18 µm (run 1 ↑ at
    15 mm); it is named with the parameters it sets, and kept (R unchanged)."""
    import axiscal

    data = axiscal.read(ECMC)
    r = evaluate(data)
    assert r.R == pytest.approx(204.76, abs=0.01)          # evaluated with the reading
    first = [o for o in r.outliers if o.sets]
    assert len(first) == 1
    o = first[0]
    assert (o.target, o.direction, o.run) == (15.0, "up", 1)
    assert o.value == pytest.approx(93.18, abs=0.01)
    assert {"R", "R↑", "A", "A↑"} <= set(o.sets)
    assert o.G > o.G_critical
    assert any("+93.18 µm" in w and "sets R↑" in w for w in r.warnings)


def test_clean_data_has_no_outlier_and_order_invariance():
    """Normal readings: nothing flagged; a flagged reading stays flagged whatever the run order."""
    rng = np.random.default_rng(3)
    up = rng.normal(0, 1, (6, 5))
    down = rng.normal(0, 1, (6, 5))
    ds = PositioningDataset.from_arrays("linear", np.arange(6) * 100.0, up, down, "mm", "um")
    assert evaluate(ds).outliers == ()
    up[2, 3] = 40.0
    ds = PositioningDataset.from_arrays("linear", np.arange(6) * 100.0, up, down, "mm", "um")
    got = positioning_outliers(ds.targets, ds.up, ds.down, evaluate(ds))
    assert [(o.target, o.run) for o in got] == [(200.0, 4)]
    perm = up[:, [3, 0, 1, 2, 4]]
    ds2 = PositioningDataset.from_arrays("linear", np.arange(6) * 100.0, perm, down, "mm", "um")
    assert [(o.target, o.run) for o in evaluate(ds2).outliers] == [(200.0, 1)]


def test_normal_readings_raise_a_false_alarm_rarely_over_the_whole_test():
    """Each of the m target-direction groups is tested at 5 %/m (Bonferroni): 200 simulated
    tests of normal readings (21 targets, 5 runs each way) flag a reading in about 5 % of the
    tests at most, not in most of them (at 5 % per group, 42 groups flag one in 88 %)."""
    rng = np.random.default_rng(11)
    flagged = 0
    for _ in range(200):
        ds = PositioningDataset.from_arrays("linear", np.arange(21) * 40.0,
                                            rng.normal(0, 1, (21, 5)), rng.normal(0, 1, (21, 5)),
                                            "mm", "um")
        flagged += bool(evaluate(ds).outliers)
    assert flagged <= 20                       # 5 % of 200 is 10; a binomial bound
