"""A simulated rotary axis (turntable, indexing table, trunnion) with known errors.

The truth that a rotary calibration or a five-DOF motion-error measurement measures against:

* the angular positioning error εz(θ): harmonics of several orders plus an irregular component,
  a reversal value (backlash), repeatability noise, and an optional thermal drift over the test;
* the error motions of ISO 230-7: radial δx(θ), δy(θ), axial δz(θ) and tilt εx(θ), εy(θ), each a
  synchronous (repeating every revolution) function of angle plus an asynchronous random part;
* the location errors of the axis average line: offsets x0, y0 and tilts a0 (about X), b0 (about Y).

Angles are radians and displacements metres, positive by the right-hand rule about the axis
(ISO 841). The axis direction is +Z of the axis frame, whatever the machine calls it (C, A, B).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from axiscal.errors import InputError
from axiscal.machines.error_functions import ZERO, Harmonic, HarmonicSeries

__all__ = ["ErrorMotion", "RotaryAxis", "Pose", "TWO_PI"]

TWO_PI = 2.0 * math.pi


@dataclass(frozen=True)
class ErrorMotion:
    """One component of error motion as a function of the axis angle.

    Attributes
    ----------
    synchronous : HarmonicSeries
        Repeats every revolution: use harmonics with period ``2*pi/k`` (k integer) so it closes.
    asynchronous_sigma : float
        Standard deviation of the part that does not repeat (same unit as the series).
    offset : float
        Constant location error (the average line's offset or tilt).
    """

    synchronous: HarmonicSeries = ZERO
    asynchronous_sigma: float = 0.0
    offset: float = 0.0

    def __call__(self, theta, rng: np.random.Generator | None = None):
        th = np.asarray(theta, dtype=float)
        val = self.offset + self.synchronous(th)
        if rng is not None and self.asynchronous_sigma > 0:
            val = val + rng.normal(0.0, self.asynchronous_sigma, np.shape(th))
        return val

    @classmethod
    def of_orders(cls, amplitudes: dict[int, float], phases: dict[int, float] | None = None,
                  asynchronous_sigma: float = 0.0, offset: float = 0.0) -> "ErrorMotion":
        """Build from ``{order: amplitude}`` (orders per revolution) and optional phases."""
        phases = phases or {}
        hs = []
        for k, a in amplitudes.items():
            if int(k) != k or k < 1:
                raise InputError(f"harmonic order {k!r} must be a whole number of cycles per turn")
            hs.append(Harmonic(float(a), TWO_PI / k, float(phases.get(k, 0.0))))
        return cls(HarmonicSeries(tuple(hs)), asynchronous_sigma, offset)


@dataclass(frozen=True)
class Pose:
    """Six-DOF pose error of the rotating part at one angle (SI units).

    ``ez`` is the angular positioning error (actual minus commanded angle); ``ex``, ``ey`` are tilt
    error motions, ``dx``, ``dy`` radial and ``dz`` axial error motions, all of the rotating frame's
    origin measured in the fixed frame.
    """

    theta: np.ndarray
    ez: np.ndarray
    ex: np.ndarray
    ey: np.ndarray
    dx: np.ndarray
    dy: np.ndarray
    dz: np.ndarray


@dataclass(frozen=True)
class RotaryAxis:
    """A numerically controlled rotary axis (all quantities SI).

    Attributes
    ----------
    name : str
        ``"C"`` for a turntable, ``"A"`` or ``"B"`` for a trunnion.
    positioning : HarmonicSeries
        Systematic angular positioning error εz(θ), radians, θ in radians. For a continuous
        axis use whole orders per revolution so the error closes on itself.
    backlash : float, radians
        Reversal value b: positive approach lands at ``εz + b/2``, negative at ``εz - b/2`` so the
        ISO 230-2 reversal value B_i = x↑ - x↓ is ``b``.
    repeatability_sigma : float, radians
        Standard deviation of the random part of one approach.
    drift_rate : float, rad/s
        Thermal drift: a uniform angular offset growing linearly with time over the test.
    travel : tuple of float or None, radians
        Limits for a trunnion (for example ``(-2.1, 2.1)``); None for a continuous axis.
    radial_x, radial_y, axial, tilt_x, tilt_y : ErrorMotion
        Error motions δx, δy, δz (metres) and εx, εy (radians) of ISO 230-7.

    Examples
    --------
    >>> ax = RotaryAxis(positioning=HarmonicSeries((Harmonic(1e-5, TWO_PI),)))
    >>> round(float(ax.systematic_error(math.pi / 2, +1)), 8)
    1e-05
    """

    name: str = "C"
    positioning: HarmonicSeries = ZERO
    backlash: float = 0.0
    repeatability_sigma: float = 0.0
    drift_rate: float = 0.0
    travel: tuple[float, float] | None = None
    radial_x: ErrorMotion = field(default_factory=ErrorMotion)
    radial_y: ErrorMotion = field(default_factory=ErrorMotion)
    axial: ErrorMotion = field(default_factory=ErrorMotion)
    tilt_x: ErrorMotion = field(default_factory=ErrorMotion)
    tilt_y: ErrorMotion = field(default_factory=ErrorMotion)

    def __post_init__(self) -> None:
        if self.repeatability_sigma < 0:
            raise InputError(f"axis {self.name}: repeatability_sigma must be >= 0")
        if self.travel is not None and not self.travel[1] > self.travel[0]:
            raise InputError(f"axis {self.name}: travel {self.travel} must have upper > lower")

    @property
    def continuous(self) -> bool:
        """True for an axis that turns without limit (a turntable)."""
        return self.travel is None

    def check_in_travel(self, theta) -> None:
        """Raise :class:`InputError` for a commanded angle outside a limited axis's travel."""
        if self.travel is None:
            return
        th = np.asarray(theta, dtype=float)
        lo, hi = self.travel
        if np.any(th < lo - 1e-12) or np.any(th > hi + 1e-12):
            bad = th[(th < lo - 1e-12) | (th > hi + 1e-12)].ravel()[0]
            raise InputError(
                f"axis {self.name}: angle {math.degrees(bad):g} deg is outside the travel "
                f"{math.degrees(lo):g} to {math.degrees(hi):g} deg"
            )

    def systematic_error(self, theta, direction, time: float = 0.0):
        """Angular positioning error without the random part, radians.

        Parameters
        ----------
        theta : array_like, radians (commanded angle; may exceed one turn)
        direction : int or array_like, +1 or -1 (direction of approach)
        time : float, seconds since the start of the test
        """
        th = np.asarray(theta, dtype=float)
        d = np.asarray(direction, dtype=float)
        return self.positioning(th) + 0.5 * self.backlash * np.sign(d) + self.drift_rate * time

    def move(self, theta, direction, rng: np.random.Generator | None = None, time: float = 0.0):
        """Actual angle reached (radians) for a commanded angle, with repeatability noise."""
        self.check_in_travel(theta)
        th = np.asarray(theta, dtype=float)
        err = self.systematic_error(th, direction, time)
        if rng is not None and self.repeatability_sigma > 0:
            err = err + rng.normal(0.0, self.repeatability_sigma, np.shape(th))
        return th + err

    def pose(self, theta, direction=1, rng: np.random.Generator | None = None,
             time: float = 0.0) -> Pose:
        """Full six-DOF pose error at commanded angle(s) ``theta`` (radians)."""
        th = np.asarray(theta, dtype=float)
        ez = self.move(th, direction, rng, time) - th
        return Pose(
            theta=th,
            ez=ez,
            ex=self.tilt_x(th, rng),
            ey=self.tilt_y(th, rng),
            dx=self.radial_x(th, rng),
            dy=self.radial_y(th, rng),
            dz=self.axial(th, rng),
        )
