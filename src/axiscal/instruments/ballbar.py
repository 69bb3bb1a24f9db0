"""A telescoping ballbar: length, calibration against a reference length, thermal expansion,
noise and sample rate.

The bar's transducer is zeroed on a calibrator of reference length ``L_ref``; the length it reports
is ``L_ref + Δ`` with Δ the transducer travel. A calibration error ``e_cal`` (the calibrator's
length minus its stated value) makes the bar read ``d + e_cal`` for a true centre distance
``d``. The bar body expands by ``α ΔT L`` with its
temperature ``ΔT`` above 20 °C (ISO 1:2016 reference temperature), which shortens the readings by
that much if not compensated. Readings come at the sample rate with Gaussian noise (a simulation
takes a numpy Generator).

References
----------
ISO 230-4:2005 §5 (test equipment), Annex A. ISO 1:2016 (20 °C reference temperature).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from axiscal.errors import InputError

__all__ = ["Ballbar"]


@dataclass(frozen=True)
class Ballbar:
    """A ballbar (SI units).

    Attributes
    ----------
    length : float, m
        Nominal length (the test radius).
    calibration_error : float, m
        Calibrator length minus its stated value.
    alpha : float, 1/K
        Expansion coefficient of the bar body.
    temperature_delta : float, K
        Bar temperature minus 20 °C.
    noise : float, m
        Standard deviation of a reading.
    sample_rate : float, Hz
    """

    length: float = 0.1
    calibration_error: float = 0.0
    alpha: float = 11.5e-6
    temperature_delta: float = 0.0
    noise: float = 0.0
    sample_rate: float = 250.0

    def __post_init__(self):
        if not (math.isfinite(self.length) and self.length > 0):
            raise InputError(f"ballbar length={self.length!r} m: must be positive")
        if not (math.isfinite(self.sample_rate) and self.sample_rate > 0):
            raise InputError(f"sample_rate={self.sample_rate!r} Hz: must be positive")
        if not (math.isfinite(self.noise) and self.noise >= 0):
            raise InputError(f"noise={self.noise!r} m: must be zero or positive")
        for key in ("calibration_error", "alpha", "temperature_delta"):
            if not math.isfinite(getattr(self, key)):
                raise InputError(f"ballbar {key}={getattr(self, key)!r}: must be finite")

    def offset(self) -> float:
        """Constant reading offset, m: calibration error minus the bar's own expansion."""
        return self.calibration_error - self.alpha * self.temperature_delta * self.length

    def read(self, x, y, centre, rng: np.random.Generator | None = None) -> np.ndarray:
        """Deviation readings (reported length minus nominal), m, for tool positions (x, y)."""
        d = np.hypot(np.asarray(x) - centre[0], np.asarray(y) - centre[1])
        return self._noisy(d - self.length + self.offset(), rng)

    def _noisy(self, r: np.ndarray, rng) -> np.ndarray:
        if self.noise > 0:
            if rng is None:
                raise InputError("ballbar noise needs a random generator (seed)")
            r = r + rng.normal(0.0, self.noise, r.shape)
        return r

    def read_between(self, points, centre, rng: np.random.Generator | None = None) -> np.ndarray:
        """Deviation readings (reported length minus nominal), m, with the spindle ball at 3-D
        ``points`` (N, 3), m, and the table ball at ``centre`` (3,), m, in one frame: the bar
        of a five-axis test (:mod:`axiscal.procedures.five_axis_ballbar`)."""
        d = np.linalg.norm(np.atleast_2d(np.asarray(points, float))
                           - np.asarray(centre, float), axis=1)
        return self._noisy(d - self.length + self.offset(), rng)

