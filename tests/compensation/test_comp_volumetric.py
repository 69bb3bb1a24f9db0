"""Volumetric compensation tables and the measure → compensate → re-measure loop (issue 18)."""

from __future__ import annotations

import numpy as np
import pytest

from axiscal.compensation.volumetric import (VOLUMETRIC_CONTROLLERS, read_back,
                                             volumetric_tables, verify, write_tables)
from axiscal.errors import AxiscalError
from axiscal.machines.three_axis import simulated_machine
from axiscal.procedures.volumetric import MeasurementNoise, measure_errors

TOOL = (0.0, 0.0, -0.1)


def _measured(seed=3, **kw):
    m = simulated_machine(np.random.default_rng(seed), **kw)
    return m, measure_errors(m, np.random.default_rng(seed + 10), tool_offset=TOOL)


@pytest.mark.parametrize("controller", VOLUMETRIC_CONTROLLERS)
def test_tables_read_back_as_written(controller):
    """Every written file parses back to the corrections that were written (to the format's
    rounding of 0.1 µm), up to a constant per axis (the Siemens table is zeroed at the machine
    reference point, a datum shift)."""
    _, e = _measured()
    t = volumetric_tables(e)
    travel = {a: (lo * 1e3, hi * 1e3) for a, (lo, hi) in e.travel.items()}
    files = write_tables(t, controller, travel)
    assert len(files) == 9 and len({f.filename for f in files}) == 9
    back = read_back(files, controller, t.receiving, t.tool_offset)
    x, y, z = np.meshgrid(*(np.linspace(*e.travel[a], 7) for a in "XYZ"), indexing="ij")
    c = e.reference

    def rel(tab):
        return tab.correction(x, y, z) - tab.correction(*c)[:, None, None, None]

    np.testing.assert_allclose(rel(back), rel(t), atol=0.2e-6)


@pytest.mark.parametrize("controller", VOLUMETRIC_CONTROLLERS)
def test_loop_removes_what_tables_can_on_a_machine_without_angular_errors(controller):
    """Without angular errors every error is a function of one axis (or the linear squareness):
    the re-measured volumetric error and every body diagonal fall by at least 80 %."""
    m, e = _measured(angular_scale=0.0)
    r = verify(m, e, volumetric_tables(e), controller, np.random.default_rng(1))
    for name, before, after in r.rows:
        assert after <= 0.2 * before, (name, before, after)
    assert r.residual_predicted < 0.5e-6          # measured angular noise × lever only


def test_loop_leaves_what_the_model_says_tables_cannot_remove():
    """With angular errors, the largest re-measured error falls to the two-axis Abbe products
    the model predicts tables cannot remove (within 1 µm of noise), never more; the diagonals
    fall by at least 60 % here."""
    m, e = _measured()
    t = volumetric_tables(e)
    r = verify(m, e, t, "siemens-840d", np.random.default_rng(2))
    rows = {n: (b, a) for n, b, a in r.rows}
    before, after = rows["largest volumetric error"]
    assert after < before
    assert abs(after - t.uncompensable) < 1.0e-6
    for name, (b, a) in rows.items():
        if name.startswith("body diagonal") and b > 3e-6:
            assert a < 0.4 * b, name


def test_wrong_receiving_axis_tilts_z_away_from_the_spindle():
    """Chapman, "Calibration of machine squareness", Appendix II, Figures 30b-c: correcting the
    ZX squareness on Z (aligned to the spindle) keeps the Z motion parallel to the spindle;
    correcting it on X tilts the compensated Z motion by the squareness itself."""
    m, e = _measured()
    theta = abs(e.squareness["zx"])
    assert theta > 10e-6
    right = verify(m, e, volumetric_tables(e, receiving={"zx": "Z"}), "csv",
                   np.random.default_rng(3))
    wrong = verify(m, e, volumetric_tables(e, receiving={"zx": "X"}), "csv",
                   np.random.default_rng(3))
    assert right.spindle_tilt < 1e-6
    assert wrong.spindle_tilt == pytest.approx(theta, abs=1.5e-6)


def test_receiving_axis_must_belong_to_the_pair():
    _, e = _measured()
    with pytest.raises(AxiscalError, match="must be Z or X"):
        volumetric_tables(e, receiving={"zx": "Y"})
    with pytest.raises(AxiscalError, match="pairs are"):
        volumetric_tables(e, receiving={"xz": "X"})
    with pytest.raises(AxiscalError, match="volumetric tables are written for"):
        write_tables(volumetric_tables(e), "fanuc", {a: (0, 1) for a in "XYZ"})


def test_noise_free_tables_of_a_table_compensable_machine_leave_nothing():
    """Noise-free measurement, no angular errors: the compensated machine's remaining error is
    the tables' 0.1 µm rounding and linear interpolation only."""
    m = simulated_machine(np.random.default_rng(8), angular_scale=0.0)
    e = measure_errors(m, np.random.default_rng(0), tool_offset=TOOL, points=41,
                       noise=MeasurementNoise(0, 0, 0, 0))
    r = verify(m, e, volumetric_tables(e, spacing=10.0), "csv", np.random.default_rng(0),
               noise=MeasurementNoise(0, 0, 0, 0))
    assert dict((n, a) for n, _, a in r.rows)["largest volumetric error"] < 0.6e-6
