"""Reference rotary calibrator (XR20-like): a servo-driven axis read by a two-head encoder.

:class:`RotaryCalibrator` is the interface a real driver implements (rotate, read). The
simulator :class:`SimulatedRotaryCalibrator` builds its reading from the encoder physics of seed
000 (:mod:`axiscal.physics.encoder`, :mod:`axiscal.physics.quadrature`):

* graduation errors of the disk (about ±4 arcsec, smooth), read by each head at its own place;
* the sub-divisional error of each head's sine/cosine after automatic gain and offset control
  (small residual imperfections; Renishaw, Interferometric calibration of rotary axes: kept below ±0.25 arcsec);
* bearing wander (random lateral shifts) and a mounting eccentricity of the disk, read with
  opposite signs by two diametrically opposed heads;
* the average of the heads (or one head only, to show what the second one is for);
* the factory error map, measured at manufacture with a small uncertainty and applied as
  "actual position = average read-head position ± error map correction";
* quantisation to the interpolated resolution, and a servo positioning noise of the shaft (the
  reading is of the actual shaft angle, so servo noise does not enter the measurement).

All angles are radians, lengths metres. The calibrator's angle is positive about its own axis;
counter-rotation means commanding about minus the angle of the axis under test.

References
----------
Renishaw, Interferometric calibration of rotary axes, "The XR20 - A closer look", "Inaccuracies in the rotary encoder
reading".
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field, replace
from typing import Protocol, runtime_checkable

import numpy as np

from axiscal.errors import InputError
from axiscal.machines.error_functions import ZERO, HarmonicSeries, random_profile
from axiscal.physics.encoder import EncoderGeometry, ErrorMap, readhead_displacement_error
from axiscal.physics.quadrature import SignalImperfections, interpolation_error
from axiscal.units import ARCSEC

__all__ = ["RotaryCalibrator", "SimulatedRotaryCalibrator"]

TWO_PI = 2.0 * math.pi


@runtime_checkable
class RotaryCalibrator(Protocol):
    """What a reference rotary calibrator does for a procedure (real driver or simulator).

    :class:`SimulatedRotaryCalibrator` implements it (:meth:`~SimulatedRotaryCalibrator.rotate_to`);
    the simulated rotary calibration calls the same physics in vectorised form
    (:meth:`~SimulatedRotaryCalibrator.move` then :meth:`~SimulatedRotaryCalibrator.read`, with
    servo noise and bearing wander) for speed.
    """

    def rotate_to(self, angle: float) -> float:
        """Servo to ``angle`` (radians, own axis) and return the encoder reading (radians)."""
        ...


@dataclass(frozen=True)
class SimulatedRotaryCalibrator:
    """A simulated XR20-like calibrator.

    Attributes
    ----------
    encoder : EncoderGeometry
        Renishaw, Interferometric calibration of rotary axes: 7,850 graduations on 50 mm, interpolated 2000×.
    graduation_error : HarmonicSeries
        Position error g(χ) of the graduation at disk coordinate χ (radians), radians.
    head_angles : tuple of float, radians
        Read-head positions (two heads 180° apart; a small departure leaves a second-order
        residual, as Renishaw, Interferometric calibration of rotary axes says).
    heads_used : int
        1 (first head only) or 2 (average of both).
    head_signals : tuple of SignalImperfections
        Residual signal imperfections of each head after gain/offset control.
    bearing_wander : float, metres
        Standard deviation of the random lateral shift of the disk at each reading.
    eccentricity : float, metres
        Distance of the graduated circle's centre from the axis of rotation.
    eccentricity_phase : float, radians
    error_map : ErrorMap or None
        Factory map of the averaged reading; None if not applied.
    servo_sigma : float, radians
        Positioning noise of the shaft (not a measurement error).
    """

    encoder: EncoderGeometry = field(default_factory=EncoderGeometry)
    graduation_error: HarmonicSeries = ZERO
    head_angles: tuple[float, float] = (0.0, math.pi)
    heads_used: int = 2
    head_signals: tuple[SignalImperfections, SignalImperfections] = (
        SignalImperfections(), SignalImperfections())
    bearing_wander: float = 0.0
    eccentricity: float = 0.0
    eccentricity_phase: float = 0.0
    error_map: ErrorMap | None = None
    servo_sigma: float = 0.0

    def __post_init__(self) -> None:
        if self.heads_used not in (1, 2):
            raise InputError(f"heads_used={self.heads_used!r} must be 1 or 2")
        for name in ("bearing_wander", "eccentricity", "servo_sigma"):
            if getattr(self, name) < 0:
                raise InputError(f"{name}={getattr(self, name)!r} must be >= 0")

    # -- construction ------------------------------------------------------------------
    @classmethod
    def xr20_like(cls, rng: np.random.Generator, graduation_error_rms: float = 2.0 * ARCSEC,
                  bearing_wander: float = 0.5e-6, eccentricity: float = 3e-6,
                  signal_imperfection: float = 0.003, map_points: int = 720,
                  map_uncertainty: float = 0.05 * ARCSEC, heads_used: int = 2,
                  error_map: bool = True) -> "SimulatedRotaryCalibrator":
        """A calibrator with seed-000-like errors drawn from ``rng``, and its factory error map.

        Parameters
        ----------
        rng : numpy.random.Generator
        graduation_error_rms : float, radians
            RMS of the smooth graduation error (orders 1-40; ±4 arcsec peak ≈ 2 arcsec RMS).
        bearing_wander, eccentricity : float, metres
        signal_imperfection : float
            Residual relative offset/amplitude mismatch and phase error (radians) of each head's
            signals after automatic gain and offset control.
        map_points : int
            Points of the factory error map over a turn.
        map_uncertainty : float, radians
            Standard deviation of the factory's measurement of each map point.
        heads_used : int
        error_map : bool
            Apply the factory map.
        """
        grad = random_profile(graduation_error_rms, TWO_PI, range(1, 41), rng, slope=1.0)
        heads = tuple(SignalImperfections(
            offset_sin=rng.uniform(-1, 1) * signal_imperfection,
            offset_cos=rng.uniform(-1, 1) * signal_imperfection,
            amplitude_sin=1.0 + rng.uniform(-1, 1) * signal_imperfection,
            phase_error=rng.uniform(-1, 1) * signal_imperfection) for _ in range(2))
        cal = cls(graduation_error=grad, heads_used=heads_used, head_signals=heads,  # type: ignore[arg-type]
                  bearing_wander=bearing_wander, eccentricity=eccentricity,
                  eccentricity_phase=float(rng.uniform(0, TWO_PI)))
        if not error_map:
            return cal
        grid = np.arange(map_points) * (TWO_PI / map_points)
        measured = cal.systematic_error(grid) + rng.normal(0.0, map_uncertainty, grid.size)
        return replace(cal, error_map=ErrorMap(grid, measured))

    # -- the reading -------------------------------------------------------------------
    def head_errors(self, shaft_angle, wander_x=0.0, wander_y=0.0) -> np.ndarray:
        """Reading error of each head (rows), radians, at actual shaft angle(s)."""
        th = np.atleast_1d(np.asarray(shaft_angle, dtype=float))
        ex, ey = self._eccentric_offset(th)
        rows = []
        for psi, imp in zip(self.head_angles, self.head_signals):
            chi = np.mod(th - psi, TWO_PI)
            sde = self.encoder.phase_to_angle(
                interpolation_error(np.mod(chi, self.encoder.period) * (TWO_PI / self.encoder.period), imp))
            lateral = readhead_displacement_error(ex + wander_x, ey + wander_y, psi,
                                                  self.encoder.radius)
            rows.append(self.graduation_error(chi) + sde + lateral)
        return np.stack(rows)

    def systematic_error(self, shaft_angle) -> np.ndarray:
        """Error of the head average (or head 1) without wander, map or quantisation, radians."""
        e = self.head_errors(shaft_angle)
        return e[0] if self.heads_used == 1 else e.mean(axis=0)

    def read(self, shaft_angle, rng: np.random.Generator | None = None) -> np.ndarray:
        """Encoder output (radians) at actual shaft angle(s): heads, map, quantisation."""
        th = np.atleast_1d(np.asarray(shaft_angle, dtype=float))
        wx = wy = 0.0
        if rng is not None and self.bearing_wander > 0:
            wx = rng.normal(0.0, self.bearing_wander, th.shape)
            wy = rng.normal(0.0, self.bearing_wander, th.shape)
        e = self.head_errors(th, wx, wy)
        reading = th + (e[0] if self.heads_used == 1 else e.mean(axis=0))
        if self.error_map is not None:
            reading = self.error_map.correct(reading)
        return self.encoder.quantize(reading)

    def move(self, commanded, rng: np.random.Generator | None = None) -> np.ndarray:
        """Actual shaft angle reached for commanded angle(s), radians (servo noise)."""
        c = np.atleast_1d(np.asarray(commanded, dtype=float))
        if rng is not None and self.servo_sigma > 0:
            return c + rng.normal(0.0, self.servo_sigma, c.shape)
        return c.copy()

    def rotate_to(self, angle: float) -> float:
        """Protocol method: servo (without noise) to ``angle`` and read, radians."""
        return float(self.read(self.move(angle))[0])

    def _eccentric_offset(self, th: np.ndarray):
        if self.eccentricity == 0:
            return 0.0, 0.0
        a = th + self.eccentricity_phase
        return self.eccentricity * np.cos(a), self.eccentricity * np.sin(a)

    def __str__(self) -> str:
        return (f"simulated rotary calibrator: {self.encoder}; {self.heads_used} read-head(s), "
                f"error map {'on' if self.error_map is not None else 'off'}")
