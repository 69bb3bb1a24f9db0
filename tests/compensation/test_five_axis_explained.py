"""Issue 43, Must show: "the largest remaining deviation is explained (noise plus the
unmodelled errors the twin holds) within 1 µm". On the twin (no LinuxCNC), the prediction of
:func:`axiscal.compensation.five_axis.explain_range` (the noise-free deviations after the
correction plus the instruments' noise, propagated to first order through the sphere fit and
the R-test's sensor directions, the range sampled) is checked against the twin's whole
measurement chain run with many noise seeds (simulated touches, the real sphere fit, the
simulated R-test): an independent Monte Carlo of the same quantity."""

from __future__ import annotations

import tomllib
from importlib import resources

import numpy as np
import pytest

from axiscal.api import fiveaxis
from axiscal.compensation.five_axis import trt_correction, verify_on_twin


def _short(name):
    """The example machine with the LinuxCNC loop test's short plans (12 probed poses of
    sphere 1, 6 R-test poses), so the noise dominates what is left after the correction."""
    cfg = tomllib.loads(resources.files("axiscal.data").joinpath(name).read_text("utf-8"))
    t = cfg["machine"]["rotary"][0]
    tilts = ([0, 45, 90], [0, 90]) if t == "B" else ([0, -45, -90], [0, -90])
    return dict(cfg, setup=[dict(cfg["setup"][0], **{f"{t}_deg": tilts[0]},
                                 C_deg=[0, 90, 180, 270]),
                            dict(cfg["setup"][2], **{f"{t}_deg": tilts[1]},
                                 C_deg=[0, 120, 240])])


@pytest.mark.parametrize("name", ["fiveaxis_bc.toml", "fiveaxis_ac.toml"])
def test_what_is_left_after_the_correction_is_the_unmodelled_range_plus_the_noise(name):
    """40 seeds of the twin's verification (noise 0.5 µm per touch and per sensor reading):
    the mean measured range after the correction equals the predicted expectation within
    0.15 µm (the mean's own scatter is about 0.05 µm), at least 85 % of the ranges fall in the
    predicted 95 % interval and at least 90 % within 1 µm of the expectation. Run by hand with
    300 seeds: means within 0.01 µm, 93-97 % in the interval, 98.0-99.7 % within 1 µm (the
    1 µm of the Must show is about a 98 % statement for a single measurement of a 12-pose
    probing set-up, the interval's upper end 0.8 µm above the expectation); 1500 draws of the
    A/C probing set-up through the twin's own touches and sphere fits: 2.5-97.5 % of
    1.26-2.63 µm against the predicted 1.26-2.63 µm, 94.8 % inside. The seed-7 verification
    (the one the CLI prints) is explained within 1 µm and inside the interval: B/C probing
    1.79 µm = 0.83 µm unmodelled + noise, expected 1.98 µm (95 % within 1.39-2.78 µm)."""
    cfg = _short(name)
    sim = fiveaxis.simulate(cfg, seed=2)
    correction = trt_correction(sim.machine.geometry, sim.result)
    machine, plan = fiveaxis.load(cfg)
    v = verify_on_twin(machine, plan, correction, seed=7)
    assert len(v.explained) == 2
    for a, left, e in zip(v.after, v.after_unmodelled, v.explained):
        assert e.unmodelled == pytest.approx(left, abs=1e-12)
        assert 0.3e-6 < e.noise < 2.0e-6 and e.low < e.expected < e.high, e
        assert e.explains(a) and e.low <= a <= e.high, v
        d = e.to_dict(a)
        assert d["explained"] and d["expected_um"] == pytest.approx(
            d["unmodelled_um"] + d["noise_um"])
    assert "unmodelled + noise" in str(v) and "95 % within" in str(v)
    after = np.array([verify_on_twin(machine, plan, correction, seed=k).after
                      for k in range(100, 140)])
    for i, e in enumerate(v.explained):
        got = after[:, i]
        assert abs(got.mean() - e.expected) < 0.15e-6, (got.mean(), e)
        assert np.mean((got >= e.low) & (got <= e.high)) >= 0.85, (got, e)
        assert np.mean(np.abs(got - e.expected) <= 1e-6) >= 0.9, (got, e)
