"""Rotary encoder physics: graduation period, interpolation, read-heads, error map.

The reference calibrator of Renishaw, Interferometric calibration of rotary axes (XR20-like) reads a 50 mm disk with 7,850 graduations at
20 µm through two diametrically opposed read-heads. This module holds the geometry and the error
mechanisms as pure functions:

* :class:`EncoderGeometry`: graduation pitch, angular period (165 arcsec), resolution after
  interpolation (about 0.08 arcsec at 2000×);
* :func:`readhead_displacement_error`: a lateral shift ``t`` of the disk against a read-head reads
  as a rotation ``t/(d/2)`` (Renishaw, Interferometric calibration of rotary axes Figure 20); two heads 180° apart read it with opposite
  signs and their average cancels it (Figure 21), as it cancels a mounting eccentricity;
* :func:`graduation_error_at_heads`: the graduation errors each head sees, and their average (odd
  harmonics of the graduation error cancel between two opposed heads);
* :class:`ErrorMap`: the factory error map, "actual position = average read-head position ± error
  map correction" (Renishaw, Interferometric calibration of rotary axes): the map holds the error of the averaged reading, ``e(ψ) = reading −
  actual``, and :meth:`ErrorMap.correct` returns ``reading − e(reading)`` (the paper's ± is this
  minus sign with this definition of e).

References
----------
Renishaw, Interferometric calibration of rotary axes, "Sub-divisional errors", "Bearing wander and encoder mounting
eccentricity", "Graduation Errors".
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from axiscal.errors import InputError
from axiscal.units import ARCSEC

__all__ = [
    "EncoderGeometry",
    "readhead_displacement_error",
    "eccentricity_displacement",
    "average_readheads",
    "graduation_error_at_heads",
    "ErrorMap",
]

TWO_PI = 2.0 * math.pi


@dataclass(frozen=True)
class EncoderGeometry:
    """Geometry of a graduated rotary encoder disk.

    Attributes
    ----------
    graduations : int
        Graduations (signal periods) per revolution.
    diameter : float, metres
        Diameter of the graduated circle.
    interpolation : int
        Interpolation factor: counts per signal period.

    Examples
    --------
    >>> g = EncoderGeometry(7850, 50e-3, 2000)
    >>> round(g.pitch * 1e6, 2), round(g.period / ARCSEC, 1), round(g.resolution / ARCSEC, 3)
    (20.01, 165.1, 0.083)
    """

    graduations: int = 7850
    diameter: float = 50e-3
    interpolation: int = 2000

    def __post_init__(self) -> None:
        if int(self.graduations) != self.graduations or self.graduations < 4:
            raise InputError(f"graduations={self.graduations!r} must be a whole number >= 4")
        if not (math.isfinite(self.diameter) and self.diameter > 0):
            raise InputError(f"diameter={self.diameter!r} m must be positive")
        if int(self.interpolation) != self.interpolation or self.interpolation < 1:
            raise InputError(f"interpolation={self.interpolation!r} must be a whole number >= 1")

    @property
    def radius(self) -> float:
        """Radius of the graduated circle, metres."""
        return 0.5 * self.diameter

    @property
    def pitch(self) -> float:
        """Graduation pitch along the circumference, metres: ``π·d/N``."""
        return math.pi * self.diameter / self.graduations

    @property
    def period(self) -> float:
        """Angular interval between graduations, radians: ``2π/N`` (Renishaw, Interferometric calibration of rotary axes: 165 arcsec)."""
        return TWO_PI / self.graduations

    @property
    def resolution(self) -> float:
        """Angular resolution after interpolation, radians (Renishaw, Interferometric calibration of rotary axes: ~0.08 arcsec at 2000×)."""
        return self.period / self.interpolation

    def quantize(self, angle):
        """Round angles (radians) to the encoder's resolution."""
        r = self.resolution
        return np.rint(np.asarray(angle, dtype=float) / r) * r

    def phase_to_angle(self, phase):
        """Convert a signal phase (radians) to a disk angle (radians): ``φ·period/2π``."""
        return np.asarray(phase, dtype=float) * (self.period / TWO_PI)

    def __str__(self) -> str:
        return (f"encoder: {self.graduations} graduations on {self.diameter * 1e3:g} mm "
                f"(pitch {self.pitch * 1e6:.2f} µm, period {self.period / ARCSEC:.1f} arcsec), "
                f"×{self.interpolation} -> resolution {self.resolution / ARCSEC:.3f} arcsec")


def readhead_displacement_error(dx, dy, head_angle, radius: float):
    """Apparent rotation read by a head when the disk shifts sideways by (dx, dy), radians.

    Parameters
    ----------
    dx, dy : array_like, metres
        Lateral displacement of the disk centre against the read-heads (bearing wander,
        eccentricity).
    head_angle : float or array_like, radians
        Position of the read-head around the disk.
    radius : float, metres

    Returns
    -------
    ndarray or float, radians
        ``(−dx·sin ψ + dy·cos ψ)/r``: the tangential part of the shift at the head, over the radius
        (Renishaw, Interferometric calibration of rotary axes: "a counter-clockwise movement of t/(d/2) radians").

    Examples
    --------
    >>> e1 = readhead_displacement_error(0.0, 1e-6, 0.0, 25e-3)         # ±1 µm on a 50 mm disk
    >>> e2 = readhead_displacement_error(0.0, 1e-6, math.pi, 25e-3)
    >>> round(e1 / ARCSEC, 2), round((e1 + e2) / 2 / ARCSEC, 12)
    (8.25, 0.0)
    """
    if not radius > 0:
        raise InputError(f"radius={radius!r} m must be positive")
    psi = np.asarray(head_angle, dtype=float)
    out = (-np.asarray(dx, dtype=float) * np.sin(psi) + np.asarray(dy, dtype=float) * np.cos(psi)) / radius
    return float(out) if out.ndim == 0 else out


def eccentricity_displacement(angle, eccentricity: float, phase: float = 0.0):
    """Displacement (dx, dy) of an eccentric disk's centre at shaft angle ``angle``, metres.

    The centre of the graduated circle sits ``eccentricity`` from the axis of rotation at angle
    ``angle + phase``; it turns with the shaft.

    Parameters
    ----------
    angle : array_like, radians
        Shaft angle.
    eccentricity : float, metres
    phase : float, radians

    Returns
    -------
    dx, dy : ndarray, metres
        ``e·cos(angle + phase)``, ``e·sin(angle + phase)``; fed to
        :func:`readhead_displacement_error` (Renishaw, Interferometric calibration of rotary axes, "Bearing wander and encoder mounting
        eccentricity").
    """
    th = np.asarray(angle, dtype=float) + phase
    return eccentricity * np.cos(th), eccentricity * np.sin(th)


def average_readheads(*readings):
    """Average the angles read by several read-heads (Renishaw, Interferometric calibration of rotary axes: "the average of the angular
    positions indicated by each read-head"), radians.

    Parameters
    ----------
    *readings : array_like, radians
        One angle (or array of angles) per head, all of one shape.

    Returns
    -------
    ndarray, radians
        The arithmetic mean over the heads (Renishaw, Interferometric calibration of rotary axes Figure 21).
    """
    if not readings:
        raise InputError("average_readheads needs at least one reading")
    return np.mean(np.stack([np.asarray(r, dtype=float) for r in readings]), axis=0)


def graduation_error_at_heads(angle, graduation_error, head_angles=(0.0, math.pi)):
    """Graduation error read by each head and by their average, radians.

    Parameters
    ----------
    angle : array_like, radians
        Shaft angle.
    graduation_error : callable
        ``g(χ)`` radians: position error of the graduation at disk coordinate χ (radians).
    head_angles : sequence of float, radians
        Read-head positions around the disk.

    Returns
    -------
    per_head : ndarray, shape (heads, ...), radians
        Head k reads the graduation at disk coordinate ``angle − ψ_k``.
    average : ndarray, radians

    Notes
    -----
    With two heads 180° apart the odd harmonics of g cancel in the average and the even ones
    remain; the error map removes what remains (Renishaw, Interferometric calibration of rotary axes, "Graduation Errors").
    """
    th = np.asarray(angle, dtype=float)
    per = np.stack([np.asarray(graduation_error(np.mod(th - psi, TWO_PI)), dtype=float)
                    for psi in head_angles])
    return per, per.mean(axis=0)


@dataclass(frozen=True, eq=False)
class ErrorMap:
    """A periodic error map of an encoder reading, interpolated linearly between points.

    Attributes
    ----------
    angles : ndarray, radians
        Strictly increasing map points within one revolution [0, 2π).
    errors : ndarray, radians
        Error of the reading at each point, ``e = reading − actual``.

    Examples
    --------
    >>> m = ErrorMap.from_function(lambda a: 1e-5 * np.sin(2 * a), 360)
    >>> round(float(m.correct(math.pi / 4 + 1e-5)) - math.pi / 4, 9)
    0.0
    """

    angles: np.ndarray
    errors: np.ndarray

    def __post_init__(self) -> None:
        a = np.array(self.angles, dtype=float)  # copies: freezing must not touch the caller's
        e = np.array(self.errors, dtype=float)
        if a.ndim != 1 or a.shape != e.shape or a.size < 2:
            raise InputError("error map needs matching 1-D angles and errors with at least 2 points")
        if np.any(np.diff(a) <= 0) or a[0] < 0 or a[-1] >= TWO_PI:
            raise InputError("error map angles must increase strictly within [0, 2π) rad")
        if not np.all(np.isfinite(e)):
            raise InputError("error map holds NaN or infinite errors")
        for arr in (a, e):
            arr.flags.writeable = False
        object.__setattr__(self, "angles", a)
        object.__setattr__(self, "errors", e)

    @classmethod
    def from_function(cls, error, points: int) -> "ErrorMap":
        """Sample ``error(angle)`` (radians) at ``points`` equally spaced angles."""
        a = np.arange(points) * (TWO_PI / points)
        return cls(a, np.asarray(error(a), dtype=float))

    def __call__(self, angle):
        """Error of the reading at ``angle`` (radians), periodic linear interpolation."""
        return np.interp(np.mod(np.asarray(angle, dtype=float), TWO_PI), self.angles, self.errors,
                         period=TWO_PI)

    def correct(self, reading):
        """Actual angle from an averaged reading: ``reading − e(reading)``, radians."""
        r = np.asarray(reading, dtype=float)
        out = r - self(r)
        return float(out) if out.ndim == 0 else out

    def __str__(self) -> str:
        return (f"error map: {self.angles.size} points, errors {self.errors.min() / ARCSEC:+.2f} to "
                f"{self.errors.max() / ARCSEC:+.2f} arcsec")
