"""Raw laser readings compensated for the air and the material (issue 12): truth tests."""

from __future__ import annotations

import numpy as np
import pytest

from axiscal.errors import AxiscalError
from axiscal.machines.config import axis_from_config
from axiscal.physics.air import refractive_index
from axiscal.procedures.environment import (EnvironmentLog, compensate_raw_readings,
                                            simulate_raw_test)
from axiscal.procedures.positioning import plan_linear
from axiscal.standards.iso230_2 import evaluate

AXIS = {"name": "X", "kind": "linear", "travel_mm": [-10, 810], "scale_error_ppm": 5.0,
        "backlash_um": 2.0, "repeatability_um": 0.2}


def _drift(t):
    """Air warming 2 K over the test, pressure swinging ±200 Pa, material warming 1.5 K."""
    return (20.0 + 2.0 * t / 600, 101325 + 200 * np.sin(t / 100), 45 + 5 * t / 600,
            20.5 + 1.5 * t / 600)


@pytest.fixture(scope="module")
def measured():
    plan = plan_linear(800, runs=5, dwell=2.0)
    return simulate_raw_test(plan, axis_from_config(AXIS), np.random.default_rng(1), _drift,
                             dead_path=0.2)


def test_compensated_readings_equal_the_truth_within_the_laser_accuracy(measured):
    """Truth test: the simulated machine's deviations at 20 °C (the truth) are recovered from raw
    readings in drifting air on an expanding axis within the laser's noise (0.02 µm) plus its
    stated accuracy over 800 mm (XL-80: ±0.5 ppm → 0.4 µm)."""
    raw, log, truth = measured
    ds = compensate_raw_readings(raw, log)
    diff = np.abs(ds.up - truth.up)
    assert np.nanmax(diff) < 0.05                  # µm: noise only, the physics is exact
    r, rt = evaluate(ds), evaluate(truth)
    for k in ("E", "M", "R", "B"):
        assert getattr(r, k) == pytest.approx(getattr(rt, k), abs=0.4)
    assert "Ciddor (1996)" in ds.metadata.notes and "ISO 1" in ds.metadata.notes
    assert ds.metadata.environment.expansion_coefficient == 11.5e-6


def test_without_the_log_the_error_is_what_the_air_and_thermal_physics_predict(measured):
    """Compensated with the conditions at the start only, each reading is off by the change of
    the index (L·Δn/n, about −0.95 ppm per K of air, NIST/Edlén sensitivity) and of the material
    (L·αΔT): the error per target equals that prediction."""
    raw, log, truth = measured
    start = _drift(0.0)
    ds = compensate_raw_readings(raw, None, air_temperature=start[0], pressure=start[1],
                                 humidity=start[2], material_temperature=start[3],
                                 expansion_coefficient=11.5e-6)
    up = raw.directions == "+"
    t, L = raw.times[up], (raw.targets[up] - raw.datum) * 1e-3
    env = np.array([_drift(x) for x in t])
    n_true = refractive_index(env[:, 0], env[:, 1], env[:, 2])
    n_fix = refractive_index(*start[:3])
    n0 = refractive_index(*_drift(raw.times[0])[:3])
    predicted = np.full(ds.up.shape, np.nan)
    idx = np.searchsorted(ds.targets, raw.targets[up])
    predicted[idx, raw.runs[up] - 1] = (
        ((n_true - n_fix) * (L + 0.2) - (n0 - n_fix) * 0.2) / n_fix
        + L * 11.5e-6 * (env[:, 3] - start[3])) * 1e6                   # µm
    err = ds.up - truth.up
    assert np.nanmax(np.abs(err)) > 1.0                    # the drift matters here
    np.testing.assert_allclose(err, predicted, atol=0.08)  # laser noise and second order


def test_one_kelvin_of_air_is_about_one_ppm():
    """A reading compensated with an air temperature 1 K too low is about 0.95 µm per metre too
    short (the assumed index is too high; dn/dT ≈ −0.95 ppm/K near 20 °C, 101 kPa: NIST
    Engineering Metrology Toolbox, refractive index of air)."""
    plan = plan_linear(1000, runs=2, dwell=1.0, irregularity=0)
    raw, log, truth = simulate_raw_test(
        plan, axis_from_config({**AXIS, "travel_mm": [-10, 1010], "repeatability_um": 0.0}),
        np.random.default_rng(2), lambda t: (21.0, 101325.0, 50.0, 20.0), laser_noise=0.0)
    ok = compensate_raw_readings(raw, log)
    cold = compensate_raw_readings(raw, log, air_temperature=20.0)
    slope = np.polyfit(ok.targets, (cold.up - ok.up).mean(axis=1), 1)[0] * 1e3   # µm per m
    assert slope == pytest.approx(-0.95, abs=0.03)


def test_edlen_selectable_and_close(measured):
    raw, log, truth = measured
    a = compensate_raw_readings(raw, log, equation="edlen")
    assert "Edlén (1966)" in a.metadata.notes
    assert np.nanmax(np.abs(a.up - truth.up)) < 0.2


def test_a_log_that_cannot_give_the_air_is_refused(measured):
    raw, log, _ = measured
    keep = (log.times < 100) | (log.times > 500)
    gappy = EnvironmentLog(log.times[keep], log.air_temperature[keep], log.pressure[keep],
                           log.humidity[keep], log.material_temperature[keep],
                           log.expansion_coefficient)
    with pytest.raises(AxiscalError, match="gap from"):
        compensate_raw_readings(raw, gappy)
    short = EnvironmentLog(log.times[:5], log.air_temperature[:5], log.pressure[:5],
                           log.humidity[:5], log.material_temperature[:5], 11.5e-6)
    with pytest.raises(AxiscalError, match="outside the environment log"):
        compensate_raw_readings(raw, short)
    hot = EnvironmentLog(log.times, log.air_temperature + 200, log.pressure, log.humidity,
                         log.material_temperature, 11.5e-6)
    with pytest.raises(AxiscalError, match="outside the ciddor equation's validity"):
        compensate_raw_readings(raw, hot)
    with pytest.raises(AxiscalError, match="material temperature"):
        compensate_raw_readings(raw, None, air_temperature=20, pressure=101325, humidity=50)
