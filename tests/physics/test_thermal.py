"""Thermal normalisation to 20 °C (ISO 1): material table, sensor averaging, dataset correction."""

from __future__ import annotations

import numpy as np
import pytest

from axiscal.datasets import Environment, Metadata, PositioningDataset
from axiscal.errors import InputError
from axiscal.machines.error_functions import HarmonicSeries
from axiscal.machines.linear import LinearAxis
from axiscal.physics import thermal


def test_material_table_has_values_and_sources():
    for key in ("steel", "cast iron", "aluminium", "granite", "invar", "glass ceramic", "brass"):
        m = thermal.material(key)
        lo, hi = m.alpha_range
        assert lo <= m.alpha <= hi
        assert m.source
        assert abs(m.alpha) < 30e-6
    assert thermal.material("Aluminum") is thermal.MATERIALS["aluminium"]
    assert thermal.material("ZERODUR").name == "glass ceramic"
    # ISO 3650: steel gauge blocks (11.5 ± 1.0) × 10⁻⁶/K
    assert thermal.material("steel").alpha == pytest.approx(11.5e-6)
    with pytest.raises(InputError, match="known materials"):
        thermal.material("unobtainium")


def test_mean_temperature_of_several_sensors():
    assert thermal.mean_temperature([20.0, 21.0, 22.0]) == pytest.approx(21.0)
    assert thermal.mean_temperature(19.5) == 19.5
    assert thermal.mean_temperature([20.0, 22.0], weights=[1, 3]) == pytest.approx(21.5)
    with pytest.raises(InputError, match="sensor 2"):
        thermal.mean_temperature([20.0, np.nan])
    with pytest.raises(InputError):
        thermal.mean_temperature([])
    with pytest.raises(InputError, match="weights"):
        thermal.mean_temperature([20.0, 21.0], weights=[1.0])


def test_normalise_length_inverts_length_at():
    L = np.array([0.0, 250.0, 1000.0])
    for t in (10.0, 20.0, 27.3):
        back = thermal.normalise_length(thermal.length_at(L, t, 23.1e-6), t, 23.1e-6)
        np.testing.assert_allclose(back, L, rtol=1e-15, atol=1e-12)
    assert thermal.expansion(1000.0, 20.0, 11.5e-6) == 0.0
    # 1 m of aluminium 1 K warm is 23.1 µm long
    assert thermal.expansion(1e6, 21.0, 23.1e-6) == pytest.approx(23.1)


def test_truth_normalisation_recovers_the_machine_error():
    """Truth test: a steel-scale axis at 25.3 °C with a known error curve; the laser sees the error
    plus the scale's expansion; normalisation leaves the known error (within 1 nm)."""
    alpha, t_mat = 11.5e-6, 25.3
    ax = LinearAxis(travel=(0.0, 1.0), error=HarmonicSeries(polynomial=(0.0, 4e-6)), backlash=2e-6)
    targets = np.linspace(0.0, 1.0, 11)
    runs = 3

    def measured(direction):
        true_pos = ax.move(np.repeat(targets[:, None], runs, 1), direction)  # actual, at 20 °C
        laser = true_pos * (1 + alpha * (t_mat - 20.0))  # the warm axis is stretched
        return (laser - targets[:, None]) * 1e6  # deviations, µm

    md = Metadata(environment=Environment(material_temperature=(25.1, 25.3, 25.5),
                                          expansion_coefficient=alpha))
    ds = PositioningDataset.from_arrays("linear", targets * 1e3, measured(+1), measured(-1),
                                        "mm", "um", md)
    assert ds.up[-1, 0] > 60  # the raw data hold 61 µm of expansion at 1 m
    out = thermal.normalise_dataset(ds)
    want_up = ax.systematic_deviation(targets, +1)[:, None] * 1e6
    want_down = ax.systematic_deviation(targets, -1)[:, None] * 1e6
    np.testing.assert_allclose(out.up, np.broadcast_to(want_up, out.up.shape), atol=1e-3)
    np.testing.assert_allclose(out.down, np.broadcast_to(want_down, out.down.shape), atol=1e-3)
    assert "normalised to 20 °C" in out.metadata.notes
    assert ds.up[-1, 0] > 60  # the input is unchanged (frozen)


def test_normalise_dataset_sign_and_options():
    md = Metadata(environment=Environment(material_temperature=(25.0,)))
    ds = PositioningDataset.from_arrays("linear", [0.0, 1000.0], [[0.0, 0.0], [0.0, 0.0]],
                                        metadata=md)
    # a perfect reading of a warm steel axis means the axis is short at 20 °C: positive growth
    # removed, so the deviation at 1 m becomes -57.5 µm·(1/(1+αΔt)) ≈ -57.497 µm
    out = thermal.normalise_dataset(ds, material_name="steel")
    assert out.up[1, 0] == pytest.approx(-1e6 * 11.5e-6 * 5 / (1 + 11.5e-6 * 5), rel=1e-12)
    # explicit alpha and temperature override; the datum is the fixed point
    out2 = thermal.normalise_dataset(ds, alpha=23.1e-6, temperature=21.0, datum=1000.0)
    assert out2.up[1, 0] == 0.0 and out2.up[0, 0] > 0
    with pytest.raises(InputError, match="expansion coefficient"):
        thermal.normalise_dataset(ds)
    with pytest.raises(InputError, match="material temperature"):
        thermal.normalise_dataset(PositioningDataset.from_arrays("linear", [0, 1], [[0], [0]]),
                                  alpha=11.5e-6)
    rot = PositioningDataset.from_arrays("rotary", [0, 90], [[0], [0]])
    with pytest.raises(InputError, match="linear axes"):
        thermal.normalise_dataset(rot, alpha=11.5e-6, temperature=25.0)


def test_normalise_dataset_mm_deviations_and_nan_kept():
    md = Metadata(environment=Environment(material_temperature=(30.0,),
                                          expansion_coefficient=10e-6))
    ds = PositioningDataset.from_arrays("linear", [0.0, 500.0], [[0.0, np.nan], [0.05, 0.05]],
                                        target_unit="mm", deviation_unit="mm", metadata=md)
    out = thermal.normalise_dataset(ds)
    assert np.isnan(out.up[0, 1])
    assert out.up[1, 0] == pytest.approx((500.05) / (1 + 1e-4) - 500.0, rel=1e-12)
