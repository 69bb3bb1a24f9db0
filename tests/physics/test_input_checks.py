"""Review: inputs a user naturally passes are accepted, or refused with an InputError."""

from __future__ import annotations

import numpy as np
import pytest

from axiscal.errors import InputError
from axiscal.physics import air, interferometry


def test_sensitivities_of_dry_air():
    """humidity=None means dry air everywhere else in air.py; sensitivities raised TypeError."""
    dry = air.sensitivities(20.0, 101325.0, None)
    assert dry == air.sensitivities(20.0, 101325.0, 0.0)
    assert dry.dn_dT_ppm_per_K == pytest.approx(-0.95, abs=0.03)
    with pytest.raises(InputError, match="humidity"):
        air.sensitivities(20.0, 101325.0, float("nan"))


def test_interferometry_accepts_numpy_scalars():
    """A wavelength or spacing taken from a NumPy array (np.float32, np.int64) is a number."""
    assert interferometry.effective_pitch(np.float32(633e-9)) == pytest.approx(316.5e-9)
    assert interferometry.path_difference(0.01, np.int64(1)) == pytest.approx(np.sin(0.01))
    for bad in (True, "30e-3", np.float64("nan"), -1.0):
        with pytest.raises(InputError, match="spacing"):
            interferometry.path_difference(0.01, bad)
