"""ISO 230-1:2012 — reference straight lines, straightness, and squareness between two linear axes.

Reference straight lines (ISO 230-1:2012 §3.4.8, Chapman, Calibration of machine squareness "Squareness ... definitions" a-c):

* :func:`least_squares_line` — minimises the sum of squared deviations from the line.
* :func:`end_point_line` — joins the first and the last reading.
* :func:`minimum_zone_line` — the *mean minimum zone* line: the middle of the two parallel lines
  that enclose every reading with the smallest separation. Exact, not iterative: the optimal band
  touches an edge of the convex hull of the readings, so the hull is built (O(n log n)) and every
  hull edge slope is tried with a rotating-calipers search (a binary search on the monotone edge
  slopes of the opposite chain), which gives the global minimum of the convex, piecewise-linear
  band width ``w(m) = max(y - m x) - min(y - m x)``.

Straightness deviation (§3.4.9) is the band width about the chosen line, :func:`straightness`.

Squareness (§3.6.7, Chapman, Calibration of machine squareness Figure 2) is the difference of the inclinations of the reference
lines of two trajectories, :func:`squareness_from_trajectories`. A trajectory of the first axis
records deviations along the second axis and vice versa, both in the machine's positive axis
directions. With ``a`` the slope of the first trajectory (its deviation along the second axis per
unit travel) and ``b`` the slope of the second (deviation along the first axis per unit travel),
the angle between the positive directions of the two trajectories is ``90° - (a + b)``.

Sign conventions (both always available, see :class:`Squareness`):

* *Chapman, Calibration of machine squareness / Renishaw*: positive when the angle between the positive directions of the two
  axes exceeds 90°: ``excess = -(a + b)``.
* *ISO 230-1 datum / referred axis*: the rotation of the referred axis relative to the datum axis
  by the right-hand rule about the third axis, stated together with the note whether the angle
  is larger or smaller than 90° (Chapman, Calibration of machine squareness Note 1). For X datum / Y referred it equals the paper's
  value, for Y datum / X referred it is its negative; for planes taken against the cyclic order
  X→Y→Z→X (for example datum X, referred Z) the sign flips again.

Errors of the reference square itself: :func:`correct_reference_angle` adds the angle error of an
optical square (the *prism error*, Chapman, Calibration of machine squareness Method 3) or a mechanical square, and :func:`reversal`
removes an unknown square error from two measurements with the square reversed (Chapman, Calibration of machine squareness Note 2).

References
----------
ISO 230-1:2012, Test code for machine tools — Part 1: Geometric accuracy of machines operating
under no-load or quasi-static conditions, §3.4.8, §3.4.9, §3.6.7, §10.3.2.
Chapman, Calibration of machine squareness: M.A.V. Chapman, "Calibration of machine squareness", Figures 1 and 2, Notes 1-3.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Literal

import numpy as np

from axiscal.errors import InputError, InsufficientRunsError
from axiscal.standards._convex_hull import band_widths as _band_widths
from axiscal.standards._convex_hull import edge_slopes as _edge_slopes
from axiscal.standards._convex_hull import hull_chains as _hull_chains
from axiscal.units import ARCSEC

__all__ = [
    "ReferenceLine",
    "StraightnessResult",
    "Squareness",
    "TrajectorySquareness",
    "REFERENCE_METHODS",
    "reference_line",
    "least_squares_line",
    "end_point_line",
    "minimum_zone_line",
    "straightness",
    "squareness_from_trajectories",
    "correct_reference_angle",
    "orientation_sign",
    "reversal",
]

Method = Literal["least_squares", "end_point", "minimum_zone"]
REFERENCE_METHODS: tuple[str, ...] = ("least_squares", "end_point", "minimum_zone")
_CYCLIC = {("X", "Y"), ("Y", "Z"), ("Z", "X")}


@dataclass(frozen=True)
class ReferenceLine:
    """A reference straight line ``deviation = slope * position + intercept``.

    Attributes
    ----------
    method : str
        ``"least_squares"``, ``"end_point"`` or ``"minimum_zone"``.
    slope : float, deviation unit per position unit
        Inclination of the line (for mm and µm: µm/mm = mm/m; for m and m: rad).
    intercept : float, deviation unit
        Value of the line at position 0.
    """

    method: str
    slope: float
    intercept: float

    def __call__(self, position):
        """The line's value at ``position`` (same units as the fit)."""
        return self.slope * np.asarray(position, dtype=float) + self.intercept

    def __str__(self) -> str:
        return f"{self.method} line: slope {self.slope:.6g}, intercept {self.intercept:.6g}"


@dataclass(frozen=True)
class StraightnessResult:
    """Straightness deviation of one trajectory about its reference line (ISO 230-1 §3.4.9).

    Attributes
    ----------
    line : ReferenceLine
        The reference straight line.
    deviation : float, deviation unit
        Straightness deviation: largest minus smallest residual about the line.
    residuals : numpy.ndarray, deviation unit
        Reading minus line at each position.
    n : int
        Number of readings.
    """

    line: ReferenceLine
    deviation: float
    residuals: np.ndarray
    n: int

    def __str__(self) -> str:
        return (f"straightness {self.deviation:.4g} about the {self.line.method.replace('_', ' ')}"
                f" line (slope {self.line.slope:.6g}, {self.n} readings)")


@dataclass(frozen=True)
class Squareness:
    """A squareness error between two linear axes, in both sign conventions.

    Attributes
    ----------
    excess : float, rad
        Angle between the positive directions of ``axes[0]`` and ``axes[1]`` minus 90° (the paper
        004 / Renishaw value: positive when the angle exceeds 90°).
    axes : tuple of str
        The two axes, for example ``("X", "Y")``.
    datum : str
        The datum axis for the ISO 230-1 value (one of ``axes``; default the first).

    Examples
    --------
    >>> s = Squareness(15e-6, ("X", "Y"))
    >>> round(s.um_per_m, 3), round(s.arcsec, 3), round(s.iso_um_per_m, 3)
    (15.0, 3.094, 15.0)
    >>> round(Squareness(15e-6, ("X", "Y"), datum="Y").iso_um_per_m, 3)
    -15.0
    """

    excess: float
    axes: tuple[str, str] = ("X", "Y")
    datum: str = ""

    def __post_init__(self):
        axes = tuple(str(a).upper() for a in self.axes)
        if len(axes) != 2 or axes[0] == axes[1] or any(a not in "XYZ" for a in axes):
            raise InputError(f"axes={self.axes!r}: need two different linear axes of X, Y, Z")
        datum = (self.datum or axes[0]).upper()
        if datum not in axes:
            raise InputError(f"datum={self.datum!r}: must be one of the axes {axes}")
        object.__setattr__(self, "axes", axes)
        object.__setattr__(self, "datum", datum)
        object.__setattr__(self, "excess", float(self.excess))

    @property
    def referred(self) -> str:
        """The referred axis (the one that is not the datum)."""
        return self.axes[1] if self.datum == self.axes[0] else self.axes[0]

    @property
    def um_per_m(self) -> float:
        """Chapman, Calibration of machine squareness convention, µm/m (positive when the angle exceeds 90°)."""
        return self.excess * 1e6

    @property
    def arcsec(self) -> float:
        """Chapman, Calibration of machine squareness convention, arcseconds."""
        return self.excess / ARCSEC

    @property
    def iso(self) -> float:
        """ISO 230-1 value, rad: rotation of the referred axis relative to the datum axis by the
        right-hand rule about the third axis."""
        return self.excess if (self.datum, self.referred) in _CYCLIC else -self.excess

    @property
    def iso_um_per_m(self) -> float:
        """ISO 230-1 value, µm/m."""
        return self.iso * 1e6

    @property
    def iso_arcsec(self) -> float:
        """ISO 230-1 value, arcseconds."""
        return self.iso / ARCSEC

    @property
    def angle_note(self) -> str:
        """The note ISO 230-1 asks for: is the angle larger or smaller than 90°?"""
        a, b = self.axes
        if self.excess == 0.0:
            return f"angle between +{a} and +{b} is 90°"
        word = "larger" if self.excess > 0 else "smaller"
        return f"angle between +{a} and +{b} is {word} than 90°"

    def as_dict(self) -> dict:
        """Plain numbers for JSON: both conventions, units in the key names."""
        return {
            "axes": list(self.axes),
            "um_per_m": self.um_per_m,
            "arcsec": self.arcsec,
            "convention": "positive when the angle between the positive axis directions exceeds 90°",
            "iso_datum": self.datum,
            "iso_referred": self.referred,
            "iso_um_per_m": self.iso_um_per_m,
            "iso_arcsec": self.iso_arcsec,
            "angle_note": self.angle_note,
        }

    def __str__(self) -> str:
        return (f"squareness {self.axes[0]}{self.axes[1]}: {self.um_per_m:+.2f} µm/m "
                f"({self.arcsec:+.2f}″), positive when the angle exceeds 90°; ISO 230-1 "
                f"{self.referred} referred to datum {self.datum}: {self.iso_um_per_m:+.2f} µm/m; "
                f"{self.angle_note}")


@dataclass(frozen=True)
class TrajectorySquareness:
    """Squareness from the reference lines of two trajectories (ISO 230-1 §3.6.7).

    Attributes
    ----------
    squareness : Squareness
        The result, reference-square error included.
    first, second : StraightnessResult
        Straightness of each trajectory about its reference line (slopes in the input units).
    slope_first, slope_second : float, rad
        Inclinations ``a`` and ``b`` (dimensionless, deviation per travel).
    reference_excess : float, rad
        Angle error of the reference square that was added (0 if none).
    """

    squareness: Squareness
    first: StraightnessResult
    second: StraightnessResult
    slope_first: float
    slope_second: float
    reference_excess: float = 0.0

    def __str__(self) -> str:
        a, b = self.squareness.axes
        method = self.first.line.method.replace("_", " ")
        return (f"{self.squareness}\n"
                f"  {a} trajectory: straightness {self.first.deviation * 1e6:.3f} µm, slope "
                f"{self.slope_first * 1e6:+.3f} µm/m towards +{b} ({method} line)\n"
                f"  {b} trajectory: straightness {self.second.deviation * 1e6:.3f} µm, slope "
                f"{self.slope_second * 1e6:+.3f} µm/m towards +{a} ({method} line)\n"
                f"  reference square correction: {self.reference_excess * 1e6:+.3f} µm/m")


def reference_line(positions, deviations, method: Method = "least_squares") -> ReferenceLine:
    """Fit a reference straight line by the named method.

    Parameters
    ----------
    positions : array_like, any length unit
        Positions along the axis (need not be sorted; at least two distinct).
    deviations : array_like, any length unit
        Straightness readings at the positions.
    method : {"least_squares", "end_point", "minimum_zone"}
        The ISO 230-1 reference line.

    Returns
    -------
    ReferenceLine

    Raises
    ------
    InputError
        For an unknown method, NaN readings or mismatched lengths.
    InsufficientRunsError
        For fewer than two distinct positions.
    """
    fits = {"least_squares": least_squares_line, "end_point": end_point_line,
            "minimum_zone": minimum_zone_line}
    if method not in fits:
        raise InputError(f"method={method!r}: choose one of {', '.join(REFERENCE_METHODS)}")
    return fits[method](positions, deviations)


def least_squares_line(positions, deviations) -> ReferenceLine:
    """Least-squares reference straight line (ISO 230-1 §3.4.8, Chapman, Calibration of machine squareness Figure 1).

    Parameters
    ----------
    positions, deviations : array_like
        As for :func:`reference_line` (any length units).

    Returns
    -------
    ReferenceLine
        Slope in deviation unit per position unit.

    Notes
    -----
    Minimises :math:`\\sum (y_i - m x_i - c)^2`: :math:`m = \\sum (x_i - \\bar x)(y_i - \\bar y)
    / \\sum (x_i - \\bar x)^2`, :math:`c = \\bar y - m \\bar x`, computed on centred, scaled
    positions so that neither tiny nor huge position ranges lose digits.

    Examples
    --------
    >>> least_squares_line([0, 1, 2, 3], [0.0, 1.1, 1.9, 3.0]).slope
    0.98
    """
    x, y = _xy(positions, deviations)
    xm, ym, span = x.mean(), y.mean(), np.ptp(x)
    u = (x - xm) / span  # scaled so that tiny or huge position ranges neither under- nor overflow
    slope = float(np.dot(u, y - ym) / np.dot(u, u) / span)
    return ReferenceLine("least_squares", slope, float(ym - slope * xm))


def end_point_line(positions, deviations) -> ReferenceLine:
    """End-point reference straight line: through the first and last readings in position order.

    Parameters
    ----------
    positions, deviations : array_like
        As for :func:`reference_line` (any length units).

    Returns
    -------
    ReferenceLine

    Notes
    -----
    ISO 230-1 §3.4.8 (Chapman, Calibration of machine squareness, reference line (b)): the line joining the readings at the
    smallest and the largest position.

    Examples
    --------
    >>> end_point_line([0, 1, 2], [1.0, 5.0, 3.0]).slope
    1.0
    """
    x, y = _xy(positions, deviations)
    i, j = int(np.argmin(x)), int(np.argmax(x))
    slope = float((y[j] - y[i]) / (x[j] - x[i]))
    return ReferenceLine("end_point", slope, float(y[i] - slope * x[i]))


def minimum_zone_line(positions, deviations) -> ReferenceLine:
    """Mean minimum-zone reference straight line, exact (convex hull + rotating calipers).

    The zone is measured along the deviation direction (the band ``max(y - m x) - min(y - m x)``),
    as straightness readings are taken perpendicular to a nominally straight axis. The function
    ``w(m)`` is convex and piecewise linear with breakpoints at the slopes of the hull edges, so
    its minimum is at one of them; the mean line lies half-way across the band. Where the minimum
    is flat over a range of slopes the middle of that range is taken.

    Parameters
    ----------
    positions, deviations : array_like
        As for :func:`reference_line`.

    Returns
    -------
    ReferenceLine

    Notes
    -----
    Cost O(n log n) for the hull (scipy's Qhull on scaled coordinates, with an exact monotone
    chain as fall-back for degenerate sets), then O(h log h) for h hull vertices.

    Examples
    --------
    >>> line = minimum_zone_line([0, 1, 2, 3, 4], [0.0, 1.0, 0.0, 1.0, 0.0])
    >>> line.slope, line.intercept
    (0.0, 0.5)
    """
    x, y = _xy(positions, deviations)
    upper, lower = _hull_chains(x, y)
    slopes = np.concatenate([_edge_slopes(*upper), _edge_slopes(*lower)])
    # an edge between two positions a subnormal apart has an infinite slope: never the minimum
    slopes = slopes[np.isfinite(slopes)]
    widths = _band_widths(upper, lower, slopes) if slopes.size else slopes
    finite = np.isfinite(widths)
    if not finite.any():  # all readings on one line through two hull points
        line = end_point_line(x, y)
        return ReferenceLine("minimum_zone", line.slope, line.intercept)
    best = widths[finite].min()
    tol = 1e-12 * max(best, float(np.ptp(y)), 1e-300)
    tied = slopes[finite & (widths <= best + tol)]
    m = 0.5 * (float(tied.min()) + float(tied.max()))
    r = y - m * x
    return ReferenceLine("minimum_zone", m, 0.5 * (float(r.max()) + float(r.min())))


def straightness(positions, deviations, method: Method = "least_squares") -> StraightnessResult:
    """Straightness deviation about a reference line (ISO 230-1 §3.4.9).

    Parameters
    ----------
    positions : array_like, mm (or any length unit)
        Positions along the axis.
    deviations : array_like, µm (or any length unit)
        Readings perpendicular to the axis.
    method : {"least_squares", "end_point", "minimum_zone"}
        Reference line.

    Returns
    -------
    StraightnessResult
        Band width in the unit of ``deviations``; the line's slope is deviation unit per
        position unit (µm/mm = mm/m for mm and µm).

    Examples
    --------
    >>> r = straightness([0, 100, 200, 300, 400], [0.0, 3.0, 4.0, 3.0, 0.0], "end_point")
    >>> r.deviation
    4.0
    """
    x, y = _xy(positions, deviations)
    line = reference_line(x, y, method)
    res = y - line(x)
    return StraightnessResult(line, float(res.max() - res.min()), _frozen(res), int(x.size))


def squareness_from_trajectories(
    first_positions, first_deviations, second_positions, second_deviations, *,
    axes: tuple[str, str] = ("X", "Y"), method: Method = "least_squares", datum: str = "",
    reference_excess: float = 0.0,
) -> TrajectorySquareness:
    """Squareness from the reference lines of two trajectories (ISO 230-1 §3.6.7).

    Parameters
    ----------
    first_positions : array_like, m
        Positions along the first axis (``axes[0]``).
    first_deviations : array_like, m
        Deviations of the first trajectory along the *second* axis, positive in its + direction.
    second_positions : array_like, m
        Positions along the second axis.
    second_deviations : array_like, m
        Deviations of the second trajectory along the *first* axis, positive in its + direction.
    axes : tuple of str
        Names of the two axes.
    method : {"least_squares", "end_point", "minimum_zone"}
        Reference line for both trajectories (Chapman, Calibration of machine squareness advises the same method for both).
    datum : str
        Datum axis of the ISO 230-1 value (default the first axis).
    reference_excess : float, rad
        Angle between the references of the + directions of the two axes minus 90° (see
        :func:`correct_reference_angle`); added to the result.

    Returns
    -------
    TrajectorySquareness

    Notes
    -----
    Positions and deviations must be in the same unit (both m, or both mm) so the slopes are
    in rad; with mm positions and µm deviations divide the deviations by 1000 first.
    ``excess = -(a + b) + reference_excess`` (module docstring).

    Examples
    --------
    >>> x = np.linspace(0, 0.8, 9)
    >>> r = squareness_from_trajectories(x, 0 * x, x, -15e-6 * x)
    >>> round(r.squareness.um_per_m, 6)
    15.0
    """
    one = straightness(first_positions, first_deviations, method)
    two = straightness(second_positions, second_deviations, method)
    a, b = one.line.slope, two.line.slope
    excess = -(a + b) + float(reference_excess)
    return TrajectorySquareness(Squareness(excess, axes, datum), one, two, a, b,
                                float(reference_excess))


def orientation_sign(orientation: int) -> int:
    """Sign with which a square's angle error enters in one of the four orientations.

    Turning the square by 90° makes its arms point along (+first, -second) or (-first, +second),
    so the angle between the references of the + directions becomes 90° − ε instead of 90° + ε;
    turning by 180° keeps it (Chapman, Calibration of machine squareness Method 3 and Figure 14).

    Parameters
    ----------
    orientation : {0, 90, 180, 270}, degrees

    Returns
    -------
    int
        +1 for 0° and 180°, −1 for 90° and 270°.

    Examples
    --------
    >>> [orientation_sign(o) for o in (0, 90, 180, 270)]
    [1, -1, 1, -1]
    """
    if orientation not in (0, 90, 180, 270):
        raise InputError(f"orientation={orientation!r}: must be 0, 90, 180 or 270 degrees")
    return 1 if orientation in (0, 180) else -1


def correct_reference_angle(square_error: float, orientation: int = 0) -> float:
    """Angle excess of the references for a square (optical or mechanical) with an angle error.

    Parameters
    ----------
    square_error : float, rad
        The square's angle minus 90° as set up in orientation 0 (arms along the + directions of
        both axes). For an optical square this is the *prism error* (Chapman, Calibration of machine squareness Method 3).
    orientation : {0, 90, 180, 270}
        The equipment's orientation, degrees clockwise (Chapman, Calibration of machine squareness Figure 14).

    Returns
    -------
    float, rad
        The ``reference_excess`` to pass to :func:`squareness_from_trajectories`: measured
        squareness + this = squareness of the machine.

    Examples
    --------
    >>> correct_reference_angle(2e-6, 90)
    -2e-06
    """
    return orientation_sign(orientation) * float(square_error)


def reversal(first: float, reversed_: float) -> tuple[float, float]:
    """Reversal technique: remove an unknown square error (Chapman, Calibration of machine squareness Note 2, Method 1 "T").

    A square with angle error ε gives ``m1 = s - ε`` and, mirrored, ``m2 = s + ε``.

    Parameters
    ----------
    first, reversed_ : float, any unit
        Squareness measured with the square in its first and in its mirrored position (same
        sign convention, no prism correction applied).

    Returns
    -------
    (squareness, square_error) : tuple of float, same unit
        ``(m1 + m2) / 2`` and ``(m2 - m1) / 2``.

    Examples
    --------
    >>> reversal(13.0, 17.0)
    (15.0, 2.0)
    """
    m1, m2 = float(first), float(reversed_)
    return 0.5 * (m1 + m2), 0.5 * (m2 - m1)


# --- helpers -------------------------------------------------------------------------------------

def _xy(positions, deviations) -> tuple[np.ndarray, np.ndarray]:
    x = np.asarray(positions, dtype=float).ravel()
    y = np.asarray(deviations, dtype=float).ravel()
    if x.shape != y.shape:
        raise InputError(f"positions ({x.size}) and deviations ({y.size}) differ in length")
    if not (np.isfinite(x).all() and np.isfinite(y).all()):
        raise InputError("positions/deviations hold NaN or infinite values; remove them first")
    if x.size < 2 or np.ptp(x) == 0:
        raise InsufficientRunsError(
            f"{x.size} reading(s) at {np.unique(x).size} distinct position(s); a reference line "
            "needs at least 2 distinct positions")
    span = float(np.ptp(x))
    if span < 1e-100 or span <= 1e-12 * float(np.abs(x).max()):
        # the slope of any line through the data would overflow or be pure rounding noise
        raise InputError(
            f"positions span only {span:.3g} (largest |position| {float(np.abs(x).max()):.3g}); "
            "too narrow to fit a reference line")
    return x, y


def _frozen(a: np.ndarray) -> np.ndarray:
    a = np.array(a, dtype=float)
    a.setflags(write=False)
    return a
