"""ISO 230-2 test plans and the simulated positioning test, checked against the injected truth."""

import math

import numpy as np
import pytest

from axiscal.errors import ConfigError, InputError
from axiscal.machines.error_functions import Harmonic, HarmonicSeries
from axiscal.machines.linear import LinearAxis
from axiscal.machines.rotary import TWO_PI, RotaryAxis
from axiscal.procedures.positioning import (
    plan_from_config,
    plan_linear,
    plan_rotary,
    simulate_from_config,
    simulate_positioning_test,
)
from axiscal.datasets import AxisKind
from axiscal.standards.iso230_2 import evaluate
from axiscal.units import ARCSEC, UM


def test_linear_plan_meets_the_standard_and_is_irregular():
    """ISO 230-2 §5.2: at least 5 targets per metre and 5 in all; P_i = (i-1)p + r_i."""
    p = plan_linear(1200, seed=4)
    assert p.targets.size == 6
    assert p.targets[0] == 0 and p.targets[-1] == 1200
    spacing = np.diff(p.targets)
    assert np.ptp(spacing) > 10, "targets should not be evenly spaced"
    nominal = 1200 / 5
    assert np.all(np.abs(p.targets - nominal * np.arange(6)) <= 0.25 * nominal + 1e-9)
    assert plan_linear(1200, seed=4).targets.tolist() == p.targets.tolist()  # reproducible
    with pytest.raises(InputError, match="at least 6"):
        plan_linear(1200, n_targets=5)


def test_rotary_plan_table_1_and_main_positions():
    """Seed 001 Table 1: 3 / 5 / 8 targets; Table 3: 0..315 plus 0/360 for a full turn."""
    assert plan_rotary(360).targets.tolist() == [0, 45, 90, 135, 180, 225, 270, 315, 360]
    assert set([0.0, 90.0, 180.0, 270.0]) <= set(plan_rotary(360, step=40).targets.tolist())
    assert plan_rotary(90, step=45).targets.tolist() == [0, 45, 90]
    with pytest.raises(InputError, match="at least 8"):
        plan_rotary(360, step=90)  # 0, 90, 180, 270, 360 are 4 distinct positions
    with pytest.raises(InputError, match="at least 5"):
        plan_rotary(180, step=90)


def test_linear_cycle_sequence():
    p = plan_rotary(90, step=45, runs=2, overrun=5)
    steps = p.steps()
    measures = [s for s in steps if s.kind == "measure"]
    assert len(measures) == p.n_measurements == 3 * 2 * 2
    # run 1: approach 0 from -5, up 0,45,90, overrun to 95, down 90,45,0
    assert [(s.kind, s.position, s.direction) for s in steps[:9]] == [
        ("overrun", -5, "-"), ("measure", 0, "+"), ("measure", 45, "+"), ("measure", 90, "+"),
        ("overrun", 95, "+"), ("measure", 90, "-"), ("measure", 45, "-"), ("measure", 0, "-"),
        ("overrun", -5, "-")]
    csv = p.to_csv().splitlines()
    assert csv[1] == "seq,kind,position,direction,run,target_index,dwell_s"
    assert len(csv) == 2 + len(steps)


def test_pilgrim_cycle_visits_each_target_runs_times_from_both_sides():
    p = plan_linear(200, n_targets=5, irregularity=0, runs=3, cycle="pilgrim")
    steps = p.steps()
    first = [s for s in steps if s.kind == "measure"][:6]
    assert {s.target_index for s in first} == {0}
    assert [s.direction for s in first] == ["+", "-"] * 3
    assert sum(s.kind == "measure" for s in steps) == 5 * 3 * 2


def _linear_axis(sigma):
    return LinearAxis(
        name="X", travel=(-0.01, 0.81),
        error=HarmonicSeries((Harmonic(1.5e-6, 0.02, 0.3), Harmonic(2e-6, 0.4, 1.0)), (0.0, 9e-6)),
        backlash=3e-6, repeatability_sigma=sigma)


def test_noise_free_chain_reproduces_the_truth_exactly():
    """With no noise the evaluation must equal the injected systematic errors to rounding."""
    p = plan_linear(800, n_targets=21, seed=2)
    ax = _linear_axis(0.0)
    ds = simulate_positioning_test(p, ax, np.random.default_rng(0))
    r = evaluate(ds)
    x = p.targets * 1e-3
    up = ax.systematic_deviation(x, 1) / UM
    down = ax.systematic_deviation(x, -1) / UM
    np.testing.assert_allclose(r.mean_up, up, atol=1e-9)
    np.testing.assert_allclose(r.mean_down, down, atol=1e-9)
    assert r.B == pytest.approx(3.0, abs=1e-9) and r.B_mean == pytest.approx(3.0, abs=1e-9)
    assert r.E == pytest.approx(max(up.max(), down.max()) - min(up.min(), down.min()), abs=1e-9)
    assert r.R == pytest.approx(3.0, abs=1e-9)  # 2s + 2s + |B| with s = 0


@pytest.mark.parametrize("seed", [1, 2, 3])
def test_truth_linear_axis_with_noise(seed):
    """CONVENTIONS habit 8: known error curve, backlash 3 µm, repeatability σ = 0.5 µm, 5 runs.

    Budget: each mean is off by σ/√n = 0.22 µm (1 s.d.); E and M are differences of two extreme
    means, so within 2 × 3σ/√n = 1.34 µm; B_i scatters by σ√(2/n) = 0.32 µm, so B (a maximum of
    21 of them) lies within [b, b + 4σ√(2/n)] and B̄ (a mean) within 3σ√(2/n)/√m of b; R_i's
    expectation is about 4σ + b = 5 µm and R, the largest of 21, stays below b + 8σ = 7 µm.
    """
    sigma, n, m, b = 0.5, 5, 21, 3.0
    p = plan_linear(800, n_targets=m, seed=seed)
    ax = _linear_axis(sigma * UM)
    ds = simulate_positioning_test(p, ax, np.random.default_rng(seed))
    r = evaluate(ds)
    x = p.targets * 1e-3
    up, down = ax.systematic_deviation(x, 1) / UM, ax.systematic_deviation(x, -1) / UM
    e_true = max(up.max(), down.max()) - min(up.min(), down.min())
    assert abs(r.E - e_true) < 2 * 3 * sigma / math.sqrt(n)
    assert abs(r.M - np.ptp((up + down) / 2)) < 2 * 3 * sigma / math.sqrt(n)
    assert b - 0.1 < r.B < b + 4 * sigma * math.sqrt(2 / n)
    assert abs(r.B_mean - b) < 3 * sigma * math.sqrt(2 / n) / math.sqrt(m)
    assert b + 2 * sigma < r.R < b + 8 * sigma
    assert np.all(np.abs(r.mean_up - up) < 4 * sigma / math.sqrt(n))


def test_truth_rotary_full_turn_and_thermal_drift_shows_as_closure():
    """A turntable with 1st/2nd-order errors; a drift during the test appears as a closure error
    between 0° and 360° (the same position measured at the start and the end of each run) of the
    size the drift rate and the elapsed time predict."""
    err = HarmonicSeries((Harmonic(3 * ARCSEC, TWO_PI, 0.5), Harmonic(1 * ARCSEC, TWO_PI / 2)))
    p = plan_rotary(360, step=30, dwell=10)
    still = RotaryAxis(positioning=err, backlash=1.5 * ARCSEC, repeatability_sigma=0.2 * ARCSEC)
    r = evaluate(simulate_positioning_test(p, still, np.random.default_rng(5)))
    assert abs(r.closure_up) < 0.5 and r.B == pytest.approx(1.5, abs=0.5)
    truth = err(np.radians(p.targets)) / ARCSEC
    assert np.all(np.abs(r.mean_bi - truth) < 0.4)
    drifting = RotaryAxis(positioning=err, repeatability_sigma=0.2 * ARCSEC,
                          drift_rate=20 * ARCSEC / 3600)
    rd = evaluate(simulate_positioning_test(p, drifting, np.random.default_rng(5)))
    # one positive pass of 13 targets: 36 s moving + 130 s dwell = 166 s -> about 0.92 arcsec
    assert rd.closure_up == pytest.approx(20 / 3600 * (360 / 10 + 13 * 10), abs=0.5)
    # the drift also grows from run to run (about 1.8 arcsec per bidirectional run), so it shows
    # above all as a loss of repeatability: that is what an engineer would see first
    assert rd.R > 3 * r.R


def test_overrun_outside_travel_is_refused_before_moving():
    ax = RotaryAxis(name="A", travel=(math.radians(-90), math.radians(90)))
    p = plan_rotary(180, start=-90, step=45)
    with pytest.raises(InputError, match="outside the travel"):
        simulate_positioning_test(p, ax, np.random.default_rng(0))


def test_config_errors_name_the_key():
    with pytest.raises(ConfigError, match="unknown key.*lenght_mm"):
        plan_from_config({"lenght_mm": 800}, AxisKind.LINEAR)
    with pytest.raises(ConfigError, match="length_mm"):
        plan_from_config({}, AxisKind.LINEAR)
    with pytest.raises(ConfigError, match="backlash_mu"):
        simulate_from_config({"axis": {"kind": "linear", "backlash_mu": 3}, "test": {"length_mm": 100}})
    with pytest.raises(ConfigError, match="no \\[axis\\]"):
        simulate_from_config({"test": {}})


def test_demo_configurations_recover_their_truth():
    import tomllib
    from importlib import resources

    for name in ("demo_linear.toml", "demo_rotary.toml"):
        cfg = tomllib.loads(resources.files("axiscal.data").joinpath(name).read_text("utf-8"))
        sim = simulate_from_config(cfg, seed=7)
        assert abs(sim.result.E - sim.truth["E"]) < 1.5
        assert abs(sim.result.B_mean - sim.truth["B_mean"]) < 0.5


# -- Wrong TOML types in a positioning [test] table are named, never coerced (review finding). ----------

AXIS = {"kind": "linear", "travel_mm": [0, 800]}


@pytest.mark.parametrize("test, message", [
    ({"length_mm": 800, "runs": "five"}, "runs = 'five' must be a whole number"),
    ({"length_mm": 800, "runs": 2.7}, "runs = 2.7 must be a whole number"),
    ({"length_mm": 800, "bidirectional": "no"}, "bidirectional = 'no' must be true or false"),
    ({"length_mm": "800"}, "length_mm"),
    ({"length_mm": 800, "dwell_s": []}, "dwell_s"),
    ({"length_mm": 800, "measurement_sigma": "x"}, "measurement_sigma"),
    ({"length_mm": 800, "measurement_sigma": -0.1}, "measurement_sigma = -0.1 must be zero or positive"),
])
def test_wrong_types_are_named(test, message):
    with pytest.raises(ConfigError, match=message):
        simulate_from_config({"axis": AXIS, "test": test})
