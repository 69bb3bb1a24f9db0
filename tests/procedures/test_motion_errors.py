"""Seed 003 experiments on the simulation: indexing truth test, stability, repeatability, crosstalk."""

import math

import numpy as np
import pytest

from axiscal.errors import InputError
from axiscal.instruments.five_dof import FiveDofSystem, FiveErrors
from axiscal.machines.error_functions import Harmonic, HarmonicSeries
from axiscal.machines.rotary import TWO_PI, ErrorMotion, RotaryAxis
from axiscal.procedures.motion_errors import (BeamDrift, ReferenceAxis, crosstalk, indexing_test,
                                              repeatability_test, stability_test, to_motion_data)
from axiscal.standards.iso230_7 import evaluate, halfrange
from axiscal.units import ARCSEC, UM

TABLE = RotaryAxis(
    positioning=HarmonicSeries((Harmonic(18 * ARCSEC, TWO_PI, 0.5), Harmonic(6 * ARCSEC, TWO_PI / 3, 1.0))),
    repeatability_sigma=1.5 * ARCSEC,
    tilt_x=ErrorMotion.of_orders({1: 4 * ARCSEC, 2: 6 * ARCSEC}, {2: 0.3}, 1.2 * ARCSEC),
    tilt_y=ErrorMotion.of_orders({1: 5 * ARCSEC, 3: 4 * ARCSEC}, {3: 1.3}, 1.7 * ARCSEC),
    radial_y=ErrorMotion.of_orders({1: 3 * UM, 2: 2 * UM}, {2: 0.7}, 0.9 * UM),
    radial_x=ErrorMotion.of_orders({2: 2 * UM}, {2: 2.0}, 0.9 * UM),
    axial=ErrorMotion.of_orders({1: 1.5 * UM, 4: 1.0 * UM}, {}, 0.8 * UM),
)

#: Budget of an indexing stop (10 averaged readings): 5 x the single-reading stability σ of the
#: seed (0.05-0.19 arcsec, 0.03-0.04 µm), plus the reference encoder noise for εz.
BUDGET = {"ez": 0.35 * ARCSEC, "ey": 0.3 * ARCSEC, "ex": 0.6 * ARCSEC, "dy": 0.2 * UM, "dz": 0.2 * UM}


def _max_err(run, which="measured"):
    e = getattr(run, which) - run.truth
    return {c: float(np.max(np.abs(getattr(e, c)))) for c in FiveErrors.CHANNELS}


def test_indexing_table_errors_recovered_within_noise():
    """Truth test: an indexing table with 40 arcsec positioning error and arcsec/µm error motions,
    30° steps over 360° with the reference axis counter-rotating, a drifting beam: every measured
    error is within BUDGET of the truth at all 13 stops."""
    run = indexing_test(TABLE, FiveDofSystem(), np.random.default_rng(11))
    assert run.measured.theta.size == 13
    assert np.ptp(run.truth.ez) > 20 * ARCSEC  # the injected error is far above the budget
    err = _max_err(run)
    for c, b in BUDGET.items():
        assert err[c] < b, (c, err[c], b)


def test_drift_shows_without_compensation_in_indexing():
    """A strong drift (40 µrad/h, 30 µrad/h) over the 6.5 min test: uncompensated δy, δz leave
    the budget by l·Δβ ≈ 1.1 µm, compensated they stay in it."""
    drift = BeamDrift(rate=(40e-6 / 3600, 30e-6 / 3600))
    run = indexing_test(TABLE, FiveDofSystem(), np.random.default_rng(2), drift=drift)
    good, bad = _max_err(run), _max_err(run, "uncompensated")
    assert good["dy"] < BUDGET["dy"] and good["ez"] < BUDGET["ez"]
    assert bad["dy"] > 2 * BUDGET["dy"] and bad["dz"] > 2 * BUDGET["dz"]
    assert run.drift_measured[-1, 0] == pytest.approx(run.drift_true[-1, 0], abs=0.2e-6)


def test_stability_of_the_seed_order():
    """Seed 003 §3.2: 60 min every 10 s, standard deviations 0.05, 0.06 arcsec (εz, εy),
    0.04, 0.03 µm (δy, δz), 0.19 arcsec (εx). The simulation (noise σ = resolution/6, beam jitter
    0.07 µrad, drift averaged over 70 s) gives each within a factor 1.6 of the seed."""
    run = stability_test(FiveDofSystem(), np.random.default_rng(4))
    assert run.time.size == 361
    seed = {"ez": 0.05 * ARCSEC, "ey": 0.06 * ARCSEC, "ex": 0.19 * ARCSEC, "dy": 0.04 * UM, "dz": 0.03 * UM}
    for c, s in seed.items():
        sd = float(np.std(getattr(run.measured, c)))
        assert s / 1.6 < sd < s * 1.6, (c, sd / s)
    # the drift (1 µrad/h plus 0.5 µrad wander, l·Δβ up to 0.3 µm) shows in the uncompensated
    # δy: it follows −l·Δβ, and its spread is well above the compensated one
    unc = run.uncompensated.dy
    assert np.std(unc) > 1.5 * np.std(run.measured.dy)
    assert np.std(unc + 0.25 * run.drift_true[:, 0]) < 0.5 * np.std(unc)


def test_repeatability_three_runs():
    """Seed 003 §3.3: three runs; the ± deviation is of the table's own repeatability order
    (1.5 arcsec σ positioning: ± a few arcsec) and the measurement tracks the truth's."""
    runs = repeatability_test(TABLE, FiveDofSystem(), np.random.default_rng(8))
    meas, truth = to_motion_data(runs), to_motion_data(runs, "truth")
    for c in FiveErrors.CHANNELS:
        unit = ARCSEC if c[0] == "e" else UM
        m, t = halfrange(getattr(meas, c)) / unit, halfrange(getattr(truth, c)) / unit
        assert 0.3 < m < 8.0, c
        assert abs(m - t) < 2 * BUDGET[c] / unit, c
    res = evaluate(meas)
    ref = evaluate(truth)
    for a, b in zip(res.motions, ref.motions):
        tol = 2 * (BUDGET["ex"] if a.kind == "angle" else BUDGET["dy"])
        assert abs(a.synchronous - b.synchronous) < tol, a.name


def test_crosstalk_zero_for_perfect_and_quantified_for_realistic_mounting():
    """Perfect set-up: no leak at all. Realistic mounting (0.5° detector rotation, 1 arcmin beam,
    10 µm/10 arcsec reference axis): εy↔εz leak ≈ sin 0.5° = 0.0087; δy into εx through the QD
    rotations, (sin 0.5° + sin 0.3°)/h = 0.096 arcsec/µm; the reference-axis eccentricity and tilt
    show as once-per-turn spurious motion that ISO 230-7 removes as the fundamental."""
    perfect = crosstalk(FiveDofSystem())
    assert np.max(np.abs(perfect.table())) < 1e-4  # second-order residue only
    real = crosstalk(FiveDofSystem().with_realistic_mounting())
    t = real.table()
    assert t[1][0] == pytest.approx(math.sin(math.radians(0.5)), rel=0.05)
    assert t[2][4] == pytest.approx((math.sin(math.radians(0.5)) + math.sin(math.radians(0.3)))
                                    / 0.03 * UM / ARCSEC, rel=0.05)
    assert real.spurious["dy"] / UM == pytest.approx(2 * math.hypot(10, 6), rel=0.05)
    assert real.residual["dy"] < 0.05 * UM and real.residual["ex"] < 0.1 * ARCSEC
    assert "spurious" in str(real)


def test_reference_axis_and_bad_inputs():
    ref = ReferenceAxis(encoder_noise=0.0)
    actual, read = ref.turn_back(np.radians([30.0]), None)
    assert abs(actual[0] - math.radians(30)) <= 0.5 * ref.step
    assert read[0] == actual[0]
    with pytest.raises(InputError):
        indexing_test(TABLE, FiveDofSystem(), np.random.default_rng(0), step_deg=35)
    with pytest.raises(InputError):
        stability_test(FiveDofSystem(), np.random.default_rng(0), duration=5)
    with pytest.raises(InputError):
        repeatability_test(TABLE, FiveDofSystem(), np.random.default_rng(0), runs=1)
    with pytest.raises(InputError):
        to_motion_data([], "nonsense")


def test_iso230_7_values_survive_realistic_mounting():
    """Truth test with the realistic mounting (spurious once-per-turn motion of 25 arcsec and 23 µm
    p-v): after the ISO 230-7 fundamental removal the synchronous and total values agree with the
    truth's within 0.1/0.2 µm (radial, axial), 0.4/0.6 arcsec (tilt) and the εz range within
    0.4 arcsec (0.9 % εy leak of the 0.5° turned PSD1 plus noise)."""
    runs = repeatability_test(TABLE, FiveDofSystem().with_realistic_mounting(), np.random.default_rng(21))
    a, b = evaluate(to_motion_data(runs)), evaluate(to_motion_data(runs, "truth"))
    for m, t in zip(a.motions, b.motions):
        sync, total = (0.1 * UM, 0.2 * UM) if m.kind == "length" else (0.4 * ARCSEC, 0.6 * ARCSEC)
        assert abs(m.synchronous - t.synchronous) < sync, m.name
        assert abs(m.total - t.total) < total, m.name
    assert abs(a.positioning.range - b.positioning.range) < 0.4 * ARCSEC
    assert abs(a.motion("radial Y").fundamental - b.motion("radial Y").fundamental) > 5 * UM
