"""ISO 230-6:2002 diagonal displacement test — squareness from two face diagonals.

Squareness (Chapman, Calibration of machine squareness Method 5, ISO 230-1 §10.3.2.6)::

    squareness = D0 (D1 - D2) / (2 X Y)        (rad; = (D1 - D2) / D0 when X = Y)

with X and Y the programmed travels, ``D0 = sqrt(X² + Y²)`` the nominal diagonal and D1, D2 the
actual lengths of the two diagonals.

Labelling and sign (Chapman, Calibration of machine squareness does not say which diagonal is which; this module fixes it):

* **D1** joins the corner (+X, −Y) to the corner (−X, +Y): the diagonal along (−X, +Y).
* **D2** joins the corner (−X, −Y) to the corner (+X, +Y): the diagonal along (+X, +Y).

With these labels the result is positive when the angle between +X and +Y exceeds 90° (seed
004's convention): opening the angle stretches the (−X, +Y) diagonal and shortens the (+X, +Y)
one. Proof to first order: with ``δx = -θ y``, the (+X, +Y) diagonal becomes
``D0 - θ X Y / D0`` and the other ``D0 + θ X Y / D0``. Equal scale errors on both diagonals (air
refraction, a common linear error) cancel.

Multi-point variant (Chapman, Calibration of machine squareness: "data may be taken at multiple positions along each diagonal"):
a least-squares line is fitted to the displacement error along each diagonal; its slope ``k``
(m/m) times ``D0`` is the diagonal's length error, so ``squareness = D0² (k1 - k2) / (2 X Y)``.

References
----------
ISO 230-6:2002, Test code for machine tools — Part 6: Determination of positioning accuracy on
body and face diagonals. ISO 230-1:2012 §10.3.2.6. Chapman, Calibration of machine squareness, Method 5, Figure 11.
"""

from __future__ import annotations

import math
from dataclasses import dataclass


from axiscal.errors import InputError
from axiscal.standards.iso230_1 import Squareness, least_squares_line

__all__ = ["DiagonalResult", "diagonal_squareness", "diagonal_squareness_multipoint"]


@dataclass(frozen=True)
class DiagonalResult:
    """Squareness from a diagonal displacement test.

    Attributes
    ----------
    squareness : Squareness
        The result in both sign conventions.
    length_x, length_y : float, m
        Programmed travels X and Y.
    nominal : float, m
        D0.
    error_d1, error_d2 : float, m
        Length errors of D1 (along −X +Y) and D2 (along +X +Y): actual minus nominal.
    slope_d1, slope_d2 : float or None, m/m
        Least-squares slopes of the displacement errors (multi-point variant only).
    """

    squareness: Squareness
    length_x: float
    length_y: float
    nominal: float
    error_d1: float
    error_d2: float
    slope_d1: float | None = None
    slope_d2: float | None = None

    def __str__(self) -> str:
        return (f"diagonal test {self.length_x * 1e3:g} × {self.length_y * 1e3:g} mm "
                f"(D0 = {self.nominal * 1e3:.3f} mm): D1 (−X+Y) {self.error_d1 * 1e6:+.3f} µm, "
                f"D2 (+X+Y) {self.error_d2 * 1e6:+.3f} µm\n  {self.squareness}")


def diagonal_squareness(length_x: float, length_y: float, error_d1: float, error_d2: float,
                        *, axes: tuple[str, str] = ("X", "Y"), datum: str = "") -> DiagonalResult:
    """Squareness from the length errors of the two diagonals (ISO 230-6, Chapman, Calibration of machine squareness Method 5).

    Parameters
    ----------
    length_x, length_y : float, m
        Programmed travels X and Y of the test.
    error_d1 : float, m
        Measured minus nominal length of D1, the diagonal along (−X, +Y).
    error_d2 : float, m
        Measured minus nominal length of D2, the diagonal along (+X, +Y).
    axes, datum
        Names for the result (see :class:`~axiscal.standards.iso230_1.Squareness`).

    Returns
    -------
    DiagonalResult

    Examples
    --------
    >>> r = diagonal_squareness(0.8, 0.8, 6e-6, -6e-6)   # (D1 - D2) / D0 when X = Y
    >>> round(r.squareness.um_per_m, 3)
    10.607
    """
    x, y = _positive("length_x", length_x), _positive("length_y", length_y)
    d0 = math.hypot(x, y)
    for key, v in (("error_d1", error_d1), ("error_d2", error_d2)):
        if not math.isfinite(v):
            raise InputError(f"{key}={v!r}: must be finite")
    excess = d0 * (float(error_d1) - float(error_d2)) / (2.0 * x * y)
    return DiagonalResult(Squareness(excess, axes, datum), x, y, d0, float(error_d1),
                          float(error_d2))


def diagonal_squareness_multipoint(length_x: float, length_y: float, positions_d1, errors_d1,
                                   positions_d2, errors_d2, *, axes: tuple[str, str] = ("X", "Y"),
                                   datum: str = "") -> DiagonalResult:
    """Squareness from displacement errors at several positions along each diagonal.

    Parameters
    ----------
    length_x, length_y : float, m
        Programmed travels.
    positions_d1, errors_d1 : array_like, m
        Distance along D1 (−X, +Y) from its start and the displacement error there.
    positions_d2, errors_d2 : array_like, m
        The same for D2 (+X, +Y).

    Returns
    -------
    DiagonalResult
        ``error_d1 = k1 D0`` and ``error_d2 = k2 D0`` from the least-squares slopes.

    Examples
    --------
    >>> import numpy as np
    >>> s = np.linspace(0, 1.0, 11)
    >>> r = diagonal_squareness_multipoint(0.6, 0.8, s, 12e-6 * s, s, -12e-6 * s)
    >>> round(r.squareness.um_per_m, 3)
    25.0
    """
    k1 = least_squares_line(positions_d1, errors_d1).slope
    k2 = least_squares_line(positions_d2, errors_d2).slope
    x, y = _positive("length_x", length_x), _positive("length_y", length_y)
    d0 = math.hypot(x, y)
    r = diagonal_squareness(x, y, k1 * d0, k2 * d0, axes=axes, datum=datum)
    return DiagonalResult(r.squareness, x, y, d0, r.error_d1, r.error_d2, float(k1), float(k2))


def _positive(key: str, v: float) -> float:
    v = float(v)
    if not (math.isfinite(v) and v > 0):
        raise InputError(f"{key}={v!r} m: must be a positive travel")
    return v
