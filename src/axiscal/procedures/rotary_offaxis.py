"""Off-axis rotary calibration: three-point alignment, the synchronised part program, yaw removal.

When the calibrator cannot sit on the axis under test it is mounted on a bracket at a radius R;
as the axis turns, the reflector moves on a circle and a linear axis carries the interferometer
sideways to keep the beams on the reflector (Renishaw, Interferometric calibration of rotary axes, Figures 25-27). This module:

* fits the circle from a **three-point alignment** (the linear-axis position that centres the beam
  at three rotary angles): ``y(θ) = y₀ + a·sin θ + b·cos θ``, so ``R = √(a² + b²)``;
* writes the **part program** (G-code), one synchronised rotary + linear move per step of the ISO
  230-2 test plan, with the dwell at each target;
* removes the **angular error of the linear axis** (yaw or pitch) measured separately over the
  short travel used, after checking the sign convention of the two measurements explicitly.

The sign check. The laser reads the angle of the reflector *relative to* the interferometer. In
the off-axis capture the interferometer rides on the linear axis, so its yaw ε enters the reading
as −ε. In the separate yaw measurement the moving optic may be the interferometer (reading −ε) or
the reflector (reading +ε), and the laser's direction setting may be reversed (×−1). The sign with
which the separately measured profile must be *subtracted* follows from those two records; a user
who states a sign that contradicts them gets a :class:`~axiscal.errors.SignConventionError`,
because Renishaw, Interferometric calibration of rotary axes warns that with the wrong sign "the subtraction process will double them".
The data alone cannot reveal the sign (the rotary error is unknown), so the records must carry it.

References
----------
Renishaw, Interferometric calibration of rotary axes, "Off axis rotary calibration" and its "Error analysis".
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Literal

import numpy as np

from axiscal.errors import InputError, SignConventionError
from axiscal.units import ARCSEC, DEG, MM

__all__ = [
    "OffAxisAlignment",
    "three_point_alignment",
    "part_program",
    "YawProfile",
    "yaw_subtraction_sign",
    "subtract_linear_yaw",
    "OFFAXIS_EXTRA_ERROR",
]

#: Extra measurement error to add to the budget off axis (Renishaw, Interferometric calibration of rotary axes: "an additional measurement
#: error of ±0.5 arcseconds"), radians.
OFFAXIS_EXTRA_ERROR = 0.5 * ARCSEC

MovingOptic = Literal["interferometer", "reflector"]


@dataclass(frozen=True)
class OffAxisAlignment:
    """Circle of the reflector as seen by the linear axis, from the three-point alignment.

    Attributes
    ----------
    y0 : float, metres
        Linear-axis position that centres the beam on the axis of rotation's line.
    a, b : float, metres
        ``y(θ) = y0 + a·sin θ + b·cos θ``.
    angles : tuple of float, radians
        Rotary angles of the three alignment points.
    positions : tuple of float, metres
        Linear-axis positions found at them.
    """

    y0: float
    a: float
    b: float
    angles: tuple[float, float, float]
    positions: tuple[float, float, float]

    @property
    def radius(self) -> float:
        """Estimated offset between the calibrator's axis and the axis under test, metres."""
        return math.hypot(self.a, self.b)

    @property
    def phase(self) -> float:
        """Angle γ of the offset, radians: ``y = y0 + R·sin(θ + γ)``."""
        return math.atan2(self.b, self.a)

    def position(self, theta):
        """Linear-axis position (metres) that keeps the beams aligned at rotary angle θ (rad)."""
        th = np.asarray(theta, dtype=float)
        return self.y0 + self.a * np.sin(th) + self.b * np.cos(th)

    def __str__(self) -> str:
        return (f"three-point alignment: offset R = {self.radius / MM:.3f} mm at "
                f"{math.degrees(self.phase):.2f}°, centre y0 = {self.y0 / MM:.3f} mm")


def three_point_alignment(angles, positions) -> OffAxisAlignment:
    """Fit ``y(θ) = y0 + a·sin θ + b·cos θ`` through three alignment points.

    Parameters
    ----------
    angles : sequence of 3 float, radians
        Distinct rotary angles (spread them: 60° or more apart).
    positions : sequence of 3 float, metres
        Linear-axis positions that centred the returned beams.

    Examples
    --------
    >>> th = np.radians([-60.0, 0.0, 60.0])
    >>> al = three_point_alignment(th, 0.01 + 0.15 * np.sin(th + 0.3))
    >>> round(al.radius, 9), round(al.phase, 9), round(al.y0, 9)
    (0.15, 0.3, 0.01)
    """
    th = np.asarray(angles, dtype=float)
    y = np.asarray(positions, dtype=float)
    if th.shape != (3,) or y.shape != (3,):
        raise InputError(f"three-point alignment needs 3 angles and 3 positions, got {th.size} and {y.size}")
    m = np.column_stack([np.ones(3), np.sin(th), np.cos(th)])
    if abs(np.linalg.det(m)) < 1e-3:
        raise InputError(
            f"alignment angles {np.degrees(th).round(1).tolist()} deg are too close together to fit "
            "the offset; spread them 60° or more apart")
    y0, a, b = np.linalg.solve(m, y)
    return OffAxisAlignment(float(y0), float(a), float(b), tuple(float(v) for v in th),  # type: ignore[arg-type]
                            tuple(float(v) for v in y))  # type: ignore[arg-type]


def part_program(plan, alignment: OffAxisAlignment, rotary_axis: str = "C",
                 linear_axis: str = "Y", feed: float = 1000.0) -> str:
    """G-code for an off-axis test: one synchronised rotary + linear move per plan step.

    Parameters
    ----------
    plan : axiscal.procedures.positioning.TestPlan
        The ISO 230-2 test plan (rotary, degrees).
    alignment : OffAxisAlignment
    rotary_axis, linear_axis : str
        Axis letters of the controller.
    feed : float, mm/min (or deg/min for the rotary part; ``G94``)

    Returns
    -------
    str
        ``G90 G94`` absolute programming, ``G01`` moves with the linear position in mm to 4
        decimals, ``G04 X<s>`` dwell (seconds) after each move to a target, comments naming the
        run, direction and target, ``M30`` at the end.

    Examples
    --------
    >>> from axiscal.procedures.positioning import plan_rotary
    >>> al = three_point_alignment(np.radians([-60, 0, 60]), [0.0, 0.05, 0.1])
    >>> prog = part_program(plan_rotary(360, runs=1), al)
    >>> prog.splitlines()[3]
    'G01 C-5.0000 Y44.9681 F1000'
    """
    for name, letter in (("rotary_axis", rotary_axis), ("linear_axis", linear_axis)):
        if not (isinstance(letter, str) and len(letter) == 1 and letter.isalpha()):
            raise InputError(f"{name}={letter!r} must be one axis letter")
    if not feed > 0:
        raise InputError(f"feed={feed!r} must be positive")
    if plan.target_unit != "deg":
        raise InputError("part_program needs a rotary plan in degrees")
    lines = [f"(axiscal off-axis rotary calibration: {plan.targets.size} targets, {plan.runs} runs)",
             f"(offset {alignment.radius / MM:.3f} mm at {math.degrees(alignment.phase):.3f} deg)",
             "G90 G94"]
    for s in plan.steps():
        y = float(alignment.position(s.position * DEG)) / MM
        line = f"G01 {rotary_axis.upper()}{s.position:.4f} {linear_axis.upper()}{y:.4f} F{feed:g}"
        if s.kind == "measure":
            lines.append(f"{line} (run {s.run} {s.direction} target {s.position:g})")
            lines.append(f"G04 X{plan.dwell:g}")
        else:
            lines.append(line)
    lines.append("M30")
    return "\n".join(lines) + "\n"


@dataclass(frozen=True, eq=False)
class YawProfile:
    """Angular error of the linear axis measured separately, with its sign convention.

    Attributes
    ----------
    positions : ndarray, metres
        Linear-axis positions, strictly increasing.
    readings : ndarray, radians
        Laser readings at them (relative to the first).
    moving_optic : {"interferometer", "reflector"}
        Which optic the linear axis carried during this measurement.
    direction_sign : int, +1 or -1
        The laser's angular direction setting during this measurement.
    """

    positions: np.ndarray
    readings: np.ndarray
    moving_optic: MovingOptic = "interferometer"
    direction_sign: int = 1

    def __post_init__(self) -> None:
        p = np.asarray(self.positions, dtype=float)
        r = np.asarray(self.readings, dtype=float)
        if p.ndim != 1 or p.shape != r.shape or p.size < 2:
            raise InputError("yaw profile needs matching 1-D positions and readings (at least 2)")
        if np.any(np.diff(p) <= 0):
            raise InputError("yaw profile positions must increase strictly")
        if self.moving_optic not in ("interferometer", "reflector"):
            raise InputError(f"moving_optic={self.moving_optic!r} is not 'interferometer' or 'reflector'")
        if self.direction_sign not in (1, -1):
            raise InputError(f"direction_sign={self.direction_sign!r} must be +1 or -1")
        object.__setattr__(self, "positions", p)
        object.__setattr__(self, "readings", r)

    def at(self, y):
        """Reading interpolated at linear positions ``y`` (metres); outside the range refused."""
        yy = np.asarray(y, dtype=float)
        lo, hi = self.positions[0], self.positions[-1]
        tol = 1e-9
        if np.any(yy < lo - tol) or np.any(yy > hi + tol):
            raise InputError(
                f"linear positions {yy.min() / MM:.3f} to {yy.max() / MM:.3f} mm leave the yaw "
                f"profile's range {lo / MM:.3f} to {hi / MM:.3f} mm; measure it over the travel used")
        return np.interp(yy, self.positions, self.readings)


def yaw_subtraction_sign(profile: YawProfile, capture_moving_optic: MovingOptic = "interferometer",
                         capture_direction_sign: int = 1, stated_sign: int | None = None) -> int:
    """The sign with which the profile's readings are subtracted from the capture's, checked.

    Returns +1 when the profile reads the linear axis's error exactly as the capture does
    (subtract it), −1 when it reads it with the opposite sign (add it).

    Raises
    ------
    SignConventionError
        If ``stated_sign`` is given and contradicts the two records' conventions.

    Examples
    --------
    >>> p = YawProfile(np.array([0.0, 0.1]), np.array([0.0, 1e-6]), "reflector")
    >>> yaw_subtraction_sign(p)
    -1
    """
    def sense(optic: str, direction: int) -> int:
        # reading = sense * yaw of the linear axis
        return (-1 if optic == "interferometer" else 1) * direction

    if capture_moving_optic not in ("interferometer", "reflector"):
        raise InputError(f"capture_moving_optic={capture_moving_optic!r} is not valid")
    sign = sense(capture_moving_optic, capture_direction_sign) * sense(
        profile.moving_optic, profile.direction_sign)
    if stated_sign is not None and stated_sign != sign:
        raise SignConventionError(
            f"yaw sign {stated_sign:+d} contradicts the records: the capture moved the "
            f"{capture_moving_optic} (laser direction {capture_direction_sign:+d}) and the yaw "
            f"profile the {profile.moving_optic} (laser direction {profile.direction_sign:+d}), "
            f"which needs sign {sign:+d}; subtracting with the wrong sign doubles the linear "
            "axis's angular error (Renishaw, Interferometric calibration of rotary axes, off-axis calibration)")
    return sign


def subtract_linear_yaw(deviations, linear_positions, datum_position: float, profile: YawProfile,
                        sign: int):
    """Remove the linear axis's angular error from off-axis deviations (radians).

    ``corrected = deviation − sign·(profile(y) − profile(y_datum))``: the capture's laser was zeroed
    with the linear axis at ``datum_position``.

    Parameters
    ----------
    deviations : array_like, radians
    linear_positions : array_like, metres (same shape)
    datum_position : float, metres
    profile : YawProfile
    sign : int
        From :func:`yaw_subtraction_sign`.
    """
    if sign not in (1, -1):
        raise InputError(f"sign={sign!r} must be +1 or -1")
    d = np.asarray(deviations, dtype=float)
    return d - sign * (profile.at(linear_positions) - float(profile.at(datum_position)))
