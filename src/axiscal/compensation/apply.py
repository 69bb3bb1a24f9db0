"""A controller applying a compensation table to a simulated axis.

:class:`CompensatedAxis` wraps a :class:`~axiscal.machines.linear.LinearAxis` or
:class:`~axiscal.machines.rotary.RotaryAxis` the way a CNC applies its table: a commanded position
p becomes the set-point ``p + c(p, d)``, where c is the table's correction interpolated at p for
the direction of approach d (the ``down`` table for d < 0 in a bidirectional table). The axis then
moves to that set-point with its own errors, so the deviation from the commanded position is

    x(p, d) = c(p, d) + e(p + c, d) + noise  ≈  e(p, d) − ê(p, d) + noise,

where ê is the deviation the table was built from (correction = −deviation). It has the same
interface as the axis (``move``, ``check_in_travel``, ``systematic_deviation``, ``name``,
``repeatability_sigma``), so :func:`~axiscal.procedures.positioning.simulate_positioning_test`
re-measures the compensated machine exactly as it measured the bare one (Yüksel et al., Position accuracy and repeatability calibration of turn tables: "after all
corrections, all test procedure shall be repeated").

``sign = −1`` applies every correction with the wrong sign (as a controller that expects
``+deviation`` would, if given corrections): the deviation becomes ≈ 2e, which is what the
sign-pinning test shows.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from axiscal import units
from axiscal.compensation.tables import CompensationTable
from axiscal.errors import InputError
from axiscal.machines.seen_through import AxisSeenThrough

__all__ = ["CompensatedAxis"]


@dataclass(frozen=True)
class CompensatedAxis(AxisSeenThrough):
    """A simulated axis seen through a controller that applies ``table``.

    Attributes
    ----------
    axis : LinearAxis or RotaryAxis
        The machine (SI units inside).
    table : CompensationTable
        Positions in mm or deg, corrections in µm or arcsec (converted here to SI).
    sign : float
        +1 applies ``correction`` as the table states it; −1 applies it with the wrong sign.

    Examples
    --------
    >>> from axiscal.machines.linear import LinearAxis
    >>> from axiscal.machines.error_functions import HarmonicSeries
    >>> from axiscal.compensation.tables import table_from_deviations
    >>> ax = LinearAxis(travel=(0.0, 1.0), error=HarmonicSeries(polynomial=(0.0, 10e-6)))
    >>> t = table_from_deviations([0, 1000], [0.0, 10.0], spacing=100)   # µm at mm
    >>> comp = CompensatedAxis(ax, t)
    >>> round(float(comp.systematic_deviation(0.5, 1)) * 1e9, 3)          # nm left at 500 mm
    -0.05
    """

    axis: object
    table: CompensationTable
    sign: float = 1.0

    def __post_init__(self) -> None:
        dim = "length" if hasattr(self.axis, "systematic_deviation") else "angle"
        if units.dimension(self.table.position_unit) != dim:
            raise InputError(f"table positions in {self.table.position_unit!r} do not suit a "
                             f"{'linear' if dim == 'length' else 'rotary'} axis")
        if self.sign not in (1.0, -1.0):
            raise InputError(f"sign = {self.sign!r}; use +1 or -1")

    def correction(self, position, direction):
        """Correction the controller adds, SI, at commanded positions (SI)."""
        p = np.asarray(position, dtype=float) / units.factor(self.table.position_unit)
        c = self.table.correction_at(p, direction)
        return self.sign * np.asarray(c) * units.factor(self.table.correction_unit)

    def systematic_deviation(self, position, direction, time: float = 0.0):
        """Actual minus commanded position without noise, SI."""
        p = np.asarray(position, dtype=float)
        c = self.correction(p, direction)
        return c + self._axis_systematic(p + c, direction, time)

    def move(self, position, direction, rng: np.random.Generator | None = None, time: float = 0.0):
        """Actual position reached for a commanded position (SI), with the table applied."""
        self.check_in_travel(position)
        p = np.asarray(position, dtype=float)
        c = self.correction(p, direction)
        dev = c + self._axis_systematic(p + c, direction, time)
        if rng is not None and self.axis.repeatability_sigma > 0:
            dev = dev + rng.normal(0.0, self.axis.repeatability_sigma, np.shape(p))
        return p + dev

    def _axis_systematic(self, position, direction, time):
        if hasattr(self.axis, "systematic_deviation"):
            return self.axis.systematic_deviation(position, direction, time)
        return self.axis.systematic_error(position, direction, time)
