"""Cross-axis compensation of a squareness error, by the advice of Chapman, Calibration of machine squareness Appendix II.

A squareness measurement alone cannot tell which of the two axes is out of line (Chapman, Calibration of machine squareness
Figure 30a). The compensation must keep the axis that is aligned to the machine's other
references — the spindle's axis of rotation, the table — where it is, and tilt the *other* axis's
motion: the corrections are therefore applied **on the aligned axis, driven by the position of the
other axis** (Figure 30b: Z parallel to the spindle, δz corrections during X motion). Applying
them on the other axis (Figure 30c) also makes the axes look square but tilts the aligned axis
off the spindle.

The correction, with θ the squareness in Chapman, Calibration of machine squareness's convention (angle between the positive
directions minus 90°), is, for both choices of aligned axis::

    δ(aligned) = +θ · (p(driving) − p_ref)

Proof (first order): if the second axis B is aligned, the first axis A moves along (1, −θ) in
(A, B) and adding θ·a to B makes it (1, 0); if A is aligned, B moves along (−θ, 1) and adding θ·b
to A makes it (0, 1).

Appendix II also advises: measure and compensate straightness, pitch and yaw first (they make
the squareness depend on method and location), and remove a large squareness mechanically before
compensating the remainder. Both are returned as advice with every result.

References
----------
Chapman, Calibration of machine squareness, Appendix II, Figures 30a-c.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from axiscal.compensation.tables import check_point_count
from axiscal.errors import InputError
from axiscal.standards.iso230_1 import Squareness

__all__ = ["CrossAxisCompensation", "squareness_compensation", "LARGE_SQUARENESS"]

#: Above this |squareness| (rad, 50 µm/m) the advice is a mechanical adjustment first. Chapman, Calibration of machine squareness
#: names no figure ("large XZ or YZ squareness errors"); 50 µm/m is this module's choice.
LARGE_SQUARENESS = 50e-6


@dataclass(frozen=True)
class CrossAxisCompensation:
    """How to compensate a squareness error (Chapman, Calibration of machine squareness Appendix II).

    Attributes
    ----------
    squareness : Squareness
        The measured squareness.
    aligned_axis : str
        The axis aligned to the spindle (or other reference); it receives the corrections.
    driving_axis : str
        The axis whose position drives the corrections.
    factor : float, m/m
        Correction of the aligned axis per unit travel of the driving axis (θ, seed sign).
    reference_position : float, m
        Position of the driving axis where the correction is zero.
    advice : tuple of str
        Appendix II's points that apply.
    """

    squareness: Squareness
    aligned_axis: str
    driving_axis: str
    factor: float
    reference_position: float
    advice: tuple[str, ...]

    @property
    def compensated_axis(self) -> str:
        """The axis that receives the cross-axis corrections (the aligned axis)."""
        return self.aligned_axis

    @property
    def factor_um_per_m(self) -> float:
        """``factor`` in µm/m."""
        return self.factor * 1e6

    def correction(self, driving_positions) -> np.ndarray:
        """Corrections to add to the aligned axis's command, m, at driving-axis positions (m)."""
        p = np.asarray(driving_positions, dtype=float)
        return self.factor * (p - self.reference_position)

    def table(self, start: float, stop: float, step: float) -> tuple[np.ndarray, np.ndarray]:
        """A correction table: driving positions from ``start`` to ``stop`` (m) and corrections (m).

        Examples
        --------
        >>> c = squareness_compensation(Squareness(40e-6, ("X", "Z")), aligned_axis="Z")
        >>> p, d = c.table(0.0, 0.5, 0.25)
        >>> (p * 1e3).tolist(), np.round(d * 1e6, 6).tolist()
        ([0.0, 250.0, 500.0], [0.0, 10.0, 20.0])
        """
        if not step > 0 or not stop > start:
            raise InputError(f"table from {start!r} to {stop!r} by {step!r} m: need stop > start "
                             "and a positive step")
        check_point_count((stop - start) / step + 1, step, f"{start:g} … {stop:g} m")
        n = int(np.floor((stop - start) / step + 1e-9)) + 1
        positions = start + step * np.arange(n)
        return positions, self.correction(positions)

    def __str__(self) -> str:
        lines = [f"compensate {self.squareness}",
                 f"  apply δ{self.aligned_axis.lower()} = {self.factor_um_per_m:+.3f} µm/m × "
                 f"({self.driving_axis} − {self.reference_position * 1e3:g} mm) on axis "
                 f"{self.aligned_axis} (aligned to the spindle) during {self.driving_axis} motion"]
        lines += [f"  advice: {a}" for a in self.advice]
        return "\n".join(lines)


def squareness_compensation(squareness: Squareness, aligned_axis: str | None,
                            reference_position: float = 0.0, *,
                            large: float = LARGE_SQUARENESS) -> CrossAxisCompensation:
    """Which axis receives the squareness compensation, and by how much (Chapman, Calibration of machine squareness Appendix II).

    Parameters
    ----------
    squareness : Squareness
        Measured squareness between two axes.
    aligned_axis : str
        The axis known to be aligned to the spindle's axis of rotation (or to the reference that
        must be kept). ``None`` is refused: Appendix II warns that the squareness alone cannot
        tell, and a wrong choice misaligns the machine (Figure 30c).
    reference_position : float, m
        Driving-axis position at which the correction is zero.
    large : float, rad
        Above this magnitude the advice is a mechanical adjustment first.

    Returns
    -------
    CrossAxisCompensation

    Examples
    --------
    >>> c = squareness_compensation(Squareness(40e-6, ("X", "Z")), aligned_axis="Z")
    >>> c.compensated_axis, c.driving_axis, round(c.factor_um_per_m, 6)
    ('Z', 'X', 40.0)
    """
    if aligned_axis is None or str(aligned_axis).upper() not in squareness.axes:
        raise InputError(
            f"aligned_axis={aligned_axis!r}: name the axis of {'/'.join(squareness.axes)} that is "
            "aligned to the spindle (Chapman, Calibration of machine squareness, Appendix II: the squareness alone cannot tell, and "
            "compensating the wrong axis tilts it off the spindle)")
    aligned = str(aligned_axis).upper()
    driving = squareness.axes[1] if aligned == squareness.axes[0] else squareness.axes[0]
    advice = ["measure and compensate straightness, pitch and yaw first: they make squareness "
              "results depend on the test method, location and orientation",
              f"check that {driving} motion, once compensated, stays parallel or perpendicular "
              "to the table and to the reference points of rotary axes"]
    if abs(squareness.excess) > large:
        advice.insert(0, f"|{squareness.um_per_m:.1f}| µm/m is large (> {large * 1e6:g} µm/m): "
                         "adjust mechanically first and compensate only the remainder")
    return CrossAxisCompensation(squareness, aligned, driving, squareness.excess,
                                 float(reference_position), tuple(advice))
