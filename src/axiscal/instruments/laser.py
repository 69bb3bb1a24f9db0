"""Angular laser interferometer: the interface and a simulator built on the optics' geometry.

The simulator computes the two arms' path difference from the 3-D positions of the two
retro-reflectors (:func:`axiscal.physics.misalignment.reflector_pose`) and the directions of the
two beams, then converts it like the laser's software: ``θ = arcsin(ΔL/(K·S))`` (Renishaw, Interferometric calibration of rotary axes). What
it models:

* the true retro-reflector spacing against the nominal one the software uses (K corrects it);
* beams that are not quite parallel (≤ 15 arcsec, Renishaw, Interferometric calibration of rotary axes): lateral motion of the reflector
  then reads as an angle (0.5 arcsec per mm at 15 arcsec and S = 30 mm);
* the laser's line of sight tilted by β out of the plane of rotation;
* a yaw of the interferometer itself (an off-axis set-up carries it on a linear axis);
* the periscope's temperature sensitivity (13.8 µrad/°C, Renishaw, Interferometric calibration of rotary axes) over a temperature change;
* noise and the resolution of the reading;
* loss of signal when the reflector turns more than about ±10° from the beams: a
  :class:`~axiscal.errors.SignalLossError` naming the angle, never a silent zero.

Frame: the axis under test turns about +Z; the beams return to the interferometer along +X.
Angles radians, lengths metres.

References
----------
Renishaw, Interferometric calibration of rotary axes, "Interferometric angular measurement", "Inaccuracies in the laser
interferometer reading".
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Protocol, runtime_checkable

import numpy as np

from axiscal.errors import InputError, SignalLossError
from axiscal.physics.interferometry import angle_from_path_difference
from axiscal.units import ARCSEC

__all__ = ["AngularLaser", "SimulatedAngularInterferometer", "SimulatedAngularLaser",
           "PERISCOPE_SENSITIVITY"]

#: Temperature sensitivity of the angular periscope, rad/K (Renishaw, Interferometric calibration of rotary axes: 13.8 µrad/°C).
PERISCOPE_SENSITIVITY = 13.8e-6


@runtime_checkable
class AngularLaser(Protocol):
    """What an angular laser does for a procedure (real driver or simulator).

    A real driver datums the reading where the optics stand (``zero``), takes the correction
    factor K of the optics self-calibration (``set_correction``) and reads the angle. The simulator
    :class:`SimulatedAngularLaser` implements it on :class:`SimulatedAngularInterferometer`; the
    simulated rotary calibration (:mod:`axiscal.procedures._rotary_chain`) calls the same
    physics in vectorised form (:meth:`SimulatedAngularInterferometer.path_difference`,
    :meth:`~SimulatedAngularInterferometer.check_signal`,
    :meth:`~SimulatedAngularInterferometer.read`) for speed; a test checks that both give the
    same reading.
    """

    def zero(self) -> None:
        """Datum the reading where the reflector stands now."""
        ...

    def set_correction(self, k: float) -> None:
        """Apply the correction factor K of the optics self-calibration (1 for none)."""
        ...

    def read_angle(self) -> float:
        """The current angular reading relative to the datum, radians.

        Raises :class:`~axiscal.errors.SignalLossError` when the beams are lost.
        """
        ...


@dataclass(frozen=True)
class SimulatedAngularInterferometer:
    """A simulated laser with angular optics.

    Attributes
    ----------
    spacing : float, metres
        True centre-to-centre spacing of the retro-reflectors.
    nominal_spacing : float, metres
        Spacing the software uses (30 mm in Renishaw, Interferometric calibration of rotary axes's example).
    beam_tilt : float, radians
        β: tilt of the line of sight out of the plane of rotation.
    nonparallelism : float, radians
        Angle between the two beams (Renishaw, Interferometric calibration of rotary axes: within ±15 arcsec).
    noise : float, radians
        Standard deviation of the angular reading noise.
    resolution : float, radians
        Reading resolution (0 for none).
    max_angle : float, radians
        Largest angle of the reflector to the beams with enough returned signal (about 10°).
    """

    spacing: float = 30.0e-3
    nominal_spacing: float = 30.0e-3
    beam_tilt: float = 0.0
    nonparallelism: float = 0.0
    noise: float = 0.0
    resolution: float = 0.0
    max_angle: float = math.radians(10.0)

    def __post_init__(self) -> None:
        for name in ("spacing", "nominal_spacing"):
            v = getattr(self, name)
            if not (math.isfinite(v) and 5e-3 <= v <= 0.2):
                raise InputError(f"{name}={v!r} m must be between 5 mm and 200 mm")
        if abs(self.nonparallelism) > 60 * ARCSEC:
            raise InputError(f"nonparallelism={self.nonparallelism / ARCSEC:g} arcsec is beyond "
                             "60 arcsec; the optics are specified within ±15 arcsec")
        if abs(self.beam_tilt) > 0.05:
            raise InputError(f"beam_tilt={self.beam_tilt!r} rad is not a small misalignment")
        if self.noise < 0 or self.resolution < 0:
            raise InputError("noise and resolution must be >= 0")

    def beams(self, interferometer_yaw=0.0) -> tuple[np.ndarray, np.ndarray]:
        """Unit directions (n, 3) of beam 1 and beam 2, reflector to interferometer."""
        yaw = np.atleast_1d(np.asarray(interferometer_yaw, dtype=float))
        cb, sb = math.cos(self.beam_tilt), math.sin(self.beam_tilt)

        def beam(extra):
            return np.stack([cb * np.cos(yaw + extra), cb * np.sin(yaw + extra),
                             np.full_like(yaw, sb)], -1)
        return beam(0.0), beam(self.nonparallelism)

    def path_difference(self, u, centre, interferometer=(0.0, 0.0, 0.0),
                        interferometer_yaw=0.0) -> np.ndarray:
        """Arm 1 minus arm 2 path length (displacement), metres, for reflector poses.

        Parameters
        ----------
        u : array_like, shape (n, 3)
            Unit vector from retro-reflector 2 to 1.
        centre : array_like, shape (n, 3), metres
        interferometer : array_like, shape (3,) or (n, 3), metres
        interferometer_yaw : float or array_like, radians

        Notes
        -----
        ``ΔL = (I − p₁)·b₁ − (I − p₂)·b₂`` with ``p = centre ± (S/2)·u``, which is
        ``−(S/2)·u·(b₁ + b₂) + (centre − I)·(b₂ − b₁)``: the first term is the angle, the second the
        non-parallel beams' response to lateral motion.
        """
        u = np.atleast_2d(np.asarray(u, dtype=float))
        rel = np.atleast_2d(np.asarray(centre, dtype=float)) - np.asarray(interferometer, dtype=float)
        b1, b2 = self.beams(interferometer_yaw)
        return (-0.5 * self.spacing * np.einsum("ij,ij->i", u, b1 + b2)
                + np.einsum("ij,ij->i", rel, b2 - b1))

    def turn(self, u, interferometer_yaw=0.0) -> np.ndarray:
        """The reflector's turn from facing the beams, radians, for reflector directions ``u``.

        The centre-line's component along the beam is the sine of the turn (Renishaw, Interferometric calibration of rotary axes: beyond
        about ±10° the returned beams are lost).
        """
        b1, _ = self.beams(interferometer_yaw)
        u = np.atleast_2d(np.asarray(u, dtype=float))
        return np.arcsin(np.clip(-np.einsum("ij,ij->i", u, b1), -1.0, 1.0))

    def check_signal(self, u, interferometer_yaw=0.0) -> None:
        """Raise :class:`SignalLossError` where the reflector faces the beams beyond max_angle."""
        turn = self.turn(u, interferometer_yaw)
        bad = np.abs(turn) > self.max_angle
        if np.any(bad):
            worst = float(turn[np.argmax(np.abs(turn))])
            raise SignalLossError(
                f"laser signal lost: the reflector is turned {math.degrees(worst):+.1f}° from the "
                f"beams (limit ±{math.degrees(self.max_angle):g}°) at reading {int(np.argmax(bad))}; "
                "counter-rotate the calibrator to keep the reflector facing the laser"
            )

    def read(self, delta_l, k: float = 1.0, temperature_change=0.0,
             rng: np.random.Generator | None = None) -> np.ndarray:
        """Angular reading(s) from path differences relative to the datum, radians.

        Parameters
        ----------
        delta_l : array_like, metres
            Path difference minus its value at the datum.
        k : float
            Correction factor from the optics self-calibration.
        temperature_change : float or array_like, kelvin
            Periscope temperature change since the datum (adds 13.8 µrad/K).
        rng : numpy.random.Generator, optional
            Needed for noise.
        """
        theta = np.atleast_1d(angle_from_path_difference(delta_l, self.nominal_spacing, k))
        theta = theta + PERISCOPE_SENSITIVITY * np.asarray(temperature_change, dtype=float)
        if rng is not None and self.noise > 0:
            theta = theta + rng.normal(0.0, self.noise, theta.shape)
        if self.resolution > 0:
            theta = np.rint(theta / self.resolution) * self.resolution
        return theta

    def __str__(self) -> str:
        return (f"simulated angular interferometer: S = {self.spacing * 1e3:.3f} mm (nominal "
                f"{self.nominal_spacing * 1e3:.3f}), β = {self.beam_tilt * 1e3:.2f} mrad, beams "
                f"parallel within {self.nonparallelism / ARCSEC:.1f} arcsec")


class SimulatedAngularLaser:
    """The :class:`AngularLaser` interface on a :class:`SimulatedAngularInterferometer`.

    A small stateful adapter: the simulated world puts the reflector somewhere (:meth:`place`),
    the procedure zeroes, corrects and reads as it would with a real laser. Radians, metres.

    Parameters
    ----------
    optics : SimulatedAngularInterferometer
    rng : numpy.random.Generator, optional
        Noise source of the readings (None: noise-free).

    Examples
    --------
    >>> from axiscal.physics.misalignment import reflector_pose
    >>> laser = SimulatedAngularLaser(SimulatedAngularInterferometer())
    >>> isinstance(laser, AngularLaser)
    True
    >>> laser.place(*reflector_pose(0.0, 0.0, 0.0, 0.0, 0.0)); laser.zero()
    >>> laser.place(*reflector_pose(math.radians(2.0), 0.0, 0.0, 0.0, 0.0))
    >>> round(math.degrees(laser.read_angle()), 9)
    2.0
    """

    def __init__(self, optics: SimulatedAngularInterferometer,
                 rng: np.random.Generator | None = None) -> None:
        self.optics = optics
        self.rng = rng
        self.k = 1.0
        self.temperature_change = 0.0
        self._pose: tuple | None = None
        self._datum = 0.0

    def place(self, u, centre, interferometer=(0.0, 0.0, 0.0), interferometer_yaw: float = 0.0,
              temperature_change: float = 0.0) -> None:
        """The simulated world: the reflector's direction ``u`` and centre (metres), where the
        interferometer stands and its yaw (radians), and the periscope's temperature change (K)."""
        self._pose = (np.atleast_2d(np.asarray(u, dtype=float))[:1],
                      np.atleast_2d(np.asarray(centre, dtype=float))[:1],
                      np.asarray(interferometer, dtype=float), float(interferometer_yaw))
        self.temperature_change = float(temperature_change)

    def _path(self) -> float:
        if self._pose is None:
            raise InputError("simulated laser: no reflector placed; call place(u, centre) first")
        u, c, i, yaw = self._pose
        self.optics.check_signal(u, yaw)
        return float(self.optics.path_difference(u, c, i, yaw)[0])

    def zero(self) -> None:
        """Datum the reading at the reflector's present pose."""
        self._datum = self._path()

    def set_correction(self, k: float) -> None:
        """Set K (Renishaw, Interferometric calibration of rotary axes optics self-calibration); must be positive and finite."""
        if not (math.isfinite(k) and k > 0):
            raise InputError(f"k={k!r} must be a positive correction factor")
        self.k = float(k)

    def read_angle(self) -> float:
        """The reading relative to the datum, radians (noise, resolution, periscope drift)."""
        dl = self._path() - self._datum
        return float(self.optics.read(dl, self.k, self.temperature_change, self.rng)[0])
