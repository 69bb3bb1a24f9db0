"""A simulated linear axis with a known positioning error.

The truth a linear positioning test measures against: a systematic error curve (scale error,
bend, periodic ball-screw pitch error, irregular residue), a reversal value (backlash), a random
repeatability component and an optional thermal drift that grows during the test.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from axiscal.errors import InputError
from axiscal.machines.error_functions import ZERO, HarmonicSeries

__all__ = ["LinearAxis"]


@dataclass(frozen=True)
class LinearAxis:
    """A numerically controlled linear axis (all quantities SI).

    Attributes
    ----------
    name : str
        Axis name (``"X"``).
    travel : tuple of float, metres
        Lower and upper limit of travel.
    error : HarmonicSeries
        Systematic positioning deviation e(x), metres, as a function of position in metres:
        actual = commanded + e(x) + reversal term + noise.
    backlash : float, metres
        Reversal value b. An approach in the positive direction lands at ``e(x) + b/2``, in the
        negative direction at ``e(x) - b/2``, so the ISO 230-2 reversal value
        B_i = x↑ - x↓ equals ``b``.
    repeatability_sigma : float, metres
        Standard deviation of the random positioning component of one approach.
    thermal_scale_rate : float, 1/s
        Growth of a scale error with time (thermal drift): adds ``rate * t * x`` at time t.

    Examples
    --------
    >>> ax = LinearAxis(travel=(0.0, 1.0), error=HarmonicSeries(polynomial=(0.0, 10e-6)),
    ...                 backlash=2e-6)
    >>> round(float(ax.systematic_deviation(0.5, +1)) * 1e6, 3)   # 5 µm scale + 1 µm half backlash
    6.0
    """

    name: str = "X"
    travel: tuple[float, float] = (0.0, 1.0)
    error: HarmonicSeries = ZERO
    backlash: float = 0.0
    repeatability_sigma: float = 0.0
    thermal_scale_rate: float = 0.0

    def __post_init__(self) -> None:
        lo, hi = self.travel
        if not hi > lo:
            raise InputError(f"axis {self.name}: travel {self.travel} must have upper > lower")
        if self.repeatability_sigma < 0:
            raise InputError(f"axis {self.name}: repeatability_sigma must be >= 0")

    def check_in_travel(self, position) -> None:
        """Raise :class:`InputError` if a commanded position lies outside the travel."""
        p = np.asarray(position, dtype=float)
        lo, hi = self.travel
        tol = 1e-12 * max(1.0, abs(hi - lo))
        if np.any(p < lo - tol) or np.any(p > hi + tol):
            bad = p[(p < lo - tol) | (p > hi + tol)].ravel()[0]
            raise InputError(
                f"axis {self.name}: position {bad * 1e3:g} mm is outside the travel "
                f"{lo * 1e3:g} to {hi * 1e3:g} mm"
            )

    def systematic_deviation(self, position, direction, time: float = 0.0):
        """Deviation without the random part, metres.

        Parameters
        ----------
        position : array_like, metres
        direction : int or array_like
            +1 for an approach in the positive direction, -1 for the negative one.
        time : float, seconds since the start of the test (for thermal drift).
        """
        x = np.asarray(position, dtype=float)
        d = np.asarray(direction, dtype=float)
        return self.error(x) + 0.5 * self.backlash * np.sign(d) + self.thermal_scale_rate * time * x

    def move(self, position, direction, rng: np.random.Generator | None = None, time: float = 0.0):
        """Actual position reached for a commanded position (metres), with repeatability noise."""
        self.check_in_travel(position)
        x = np.asarray(position, dtype=float)
        dev = self.systematic_deviation(x, direction, time)
        if rng is not None and self.repeatability_sigma > 0:
            dev = dev + rng.normal(0.0, self.repeatability_sigma, np.shape(x))
        return x + dev
