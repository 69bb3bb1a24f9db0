"""A laser scale (HS20-like, Renishaw, Laser scale axis referencing): the laser head and its reference switch.

The head counts interference fringes between the beam returned by a reflector on the moving axis
and its reference beam. The reflector doubles the sensitivity: one fringe is λ/2 of motion, the
*effective scale pitch* 0.316 µm for the 0.633 µm HeNe light (Renishaw, Laser scale axis referencing). The head's digital A/B
quadrature output used with the compensator has a resolution of 0.633 µm (one count per λ of
motion, chosen "to minimise the signal bandwidth between HS20 laser and RCU10 compensator").

The head counts optical path: with the reflector at ``x`` and ``L = D + x`` the beam length
(``D``, the dead path, is the beam length at x = 0),

.. math::
    c = \\left\\lfloor \\frac{n L k}{\\lambda_{vac}} + \\varphi \\right\\rfloor
        - \\left\\lfloor \\frac{n_0 L_0 k}{\\lambda_{vac}} + \\varphi \\right\\rfloor

counted from power-up (subscript 0), k counts per wavelength, φ the fringe phase at power-up
(the fringes are not registered to anything mechanical). The *uncompensated* position,
``c λ_vac / k``, is too long by the refractivity (about 271 ppm) and drifts with the weather;
the compensator (:mod:`axiscal.instruments.compensator`) removes both.

The reference switch is separate (mechanical or optical) and is not registered to the fringes;
it trips at its nominal position plus a random repeatability error.

Examples
--------
>>> head = LaserHead()
>>> round(head.count_size * 1e6, 3), round(head.effective_pitch() * 1e6, 3)
(0.633, 0.316)
>>> a, b = head.quadrature([0, 1, 2, 3, 4])
>>> a.astype(int).tolist(), b.astype(int).tolist()
([0, 1, 1, 0, 0], [0, 0, 1, 1, 0])
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Protocol, runtime_checkable

import numpy as np

from axiscal.errors import InputError
from axiscal.physics.air import HENE_VACUUM_WAVELENGTH

__all__ = ["LaserHead", "ReferenceSwitch", "LaserScale", "HomeSwitch", "SimulatedLaserScale",
           "SimulatedHomeSwitch"]


@runtime_checkable
class LaserScale(Protocol):
    """What a laser scale's head does for a procedure (real driver or simulator): it counts.

    The simulator :class:`SimulatedLaserScale` implements it on :class:`LaserHead`;
    :mod:`axiscal.procedures.referencing` calls the same physics in vectorised form
    (:meth:`LaserHead.counts` over a whole trajectory) for speed.
    """

    def read_counts(self) -> int:
        """Quadrature counts since power-up (uncompensated, one per λ_vac/k of optical path)."""
        ...


@runtime_checkable
class HomeSwitch(Protocol):
    """What a reference (home) switch does for a procedure: it is on or off."""

    def is_on(self) -> bool:
        """True while the switch is activated."""
        ...


@dataclass(frozen=True)
class LaserHead:
    """The laser head of a laser scale.

    Attributes
    ----------
    vacuum_wavelength : float, metres
        632.991 nm for the stabilised HeNe laser.
    counts_per_wavelength : int
        Quadrature counts per wavelength of motion: 1 gives the paper's 0.633 µm resolution,
        2 one count per fringe (0.316 µm).
    dead_path : float, metres
        Beam length from the head to the reflector with the axis at x = 0.
    """

    vacuum_wavelength: float = HENE_VACUUM_WAVELENGTH
    counts_per_wavelength: int = 1
    dead_path: float = 0.0

    def __post_init__(self) -> None:
        if not 300e-9 <= self.vacuum_wavelength <= 1700e-9:
            raise InputError(f"vacuum_wavelength = {self.vacuum_wavelength * 1e9:g} nm is not a "
                             "laser wavelength between 300 and 1700 nm")
        k = self.counts_per_wavelength
        if isinstance(k, bool) or not isinstance(k, (int, np.integer)) or not 1 <= k <= 1024:
            raise InputError(f"counts_per_wavelength = {k!r} must be a whole number 1 to 1024")
        if not np.isfinite(self.dead_path) or self.dead_path < 0:
            raise InputError(f"dead_path = {self.dead_path!r} m must be >= 0")

    @property
    def count_size(self) -> float:
        """Uncompensated size of one count, metres: λ_vac / k (0.633 µm in the paper)."""
        return self.vacuum_wavelength / self.counts_per_wavelength

    def effective_pitch(self, n: float = 1.0) -> float:
        """Motion per fringe, λ/(2n), metres: the 0.316 µm "effective scale pitch" of Renishaw, Laser scale axis referencing."""
        return self.vacuum_wavelength / (2.0 * n)

    def counts(self, position, n, power_up_position: float, power_up_n: float,
               phase: float = 0.0) -> np.ndarray:
        """Laser counts since power-up for reflector positions and air refractive indices.

        Parameters
        ----------
        position : array_like, metres
            Reflector position x per sample.
        n : array_like
            Refractive index of the air in the beam per sample.
        power_up_position : float, metres
        power_up_n : float
        phase : float, in [0, 1)
            Fringe phase at power-up, in counts.

        Returns
        -------
        ndarray of int64
        """
        x = np.asarray(position, dtype=float)
        path = np.asarray(n, dtype=float) * (self.dead_path + x) / self.count_size
        path0 = power_up_n * (self.dead_path + power_up_position) / self.count_size
        return (np.floor(path + phase) - np.floor(path0 + phase)).astype(np.int64)

    def uncompensated_position(self, counts) -> np.ndarray:
        """Position the raw count stands for if the light were in vacuum, metres."""
        return np.asarray(counts, dtype=float) * self.count_size

    def quadrature(self, counts):
        """Digital A and B quadrature (Gray code; A leads B in the positive direction).

        Returns
        -------
        a, b : ndarray of bool
        """
        state = np.mod(np.asarray(counts, dtype=np.int64), 4)
        return (state == 1) | (state == 2), (state == 2) | (state == 3)

    def analogue(self, position, n: float = 1.0):
        """Analogue sine and cosine of the fringes, effective pitch λ/(2n), unit amplitude."""
        x = np.asarray(position, dtype=float)
        phase = 2.0 * np.pi * (self.dead_path + x) / self.effective_pitch(n)
        return np.sin(phase), np.cos(phase)

    def count_rate(self, speed: float, n: float = 1.0) -> float:
        """Quadrature count rate at a speed (m/s), counts per second."""
        return abs(float(speed)) * n / self.count_size

    def fringe_frequency(self, speed: float, n: float = 1.0) -> float:
        """Frequency of the raw fringe signal (0.316 µm pitch) at a speed (m/s), Hz."""
        return abs(float(speed)) / self.effective_pitch(n)


@dataclass(frozen=True)
class ReferenceSwitch:
    """A reference (home) switch, not registered to the fringes.

    Attributes
    ----------
    position : float, metres
        Nominal trip point.
    repeatability : float, metres
        Standard deviation of the trip point from one activation to the next.
    active_above : bool
        True if the switch is on for positions at or beyond the trip point (homing in the
        positive direction), False if on at or below it.
    """

    position: float
    repeatability: float = 0.0
    active_above: bool = True

    def __post_init__(self) -> None:
        if not np.isfinite(self.position):
            raise InputError(f"switch position {self.position!r} must be finite")
        if not np.isfinite(self.repeatability) or self.repeatability < 0:
            raise InputError(f"switch repeatability {self.repeatability!r} m must be >= 0")

    def trip_point(self, rng: np.random.Generator | None = None) -> float:
        """Where the switch trips this time: nominal plus a normal repeatability error, metres."""
        if rng is None or self.repeatability == 0:
            return float(self.position)
        return float(self.position + rng.normal(0.0, self.repeatability))

    def state(self, position, trip_point: float | None = None) -> np.ndarray:
        """Switch state (True = activated) at each position, for a given trip point."""
        x = np.asarray(position, dtype=float)
        trip = self.position if trip_point is None else trip_point
        return x >= trip if self.active_above else x <= trip


class SimulatedLaserScale:
    """The :class:`LaserScale` interface on a :class:`LaserHead` (a small stateful adapter).

    Powered up with the reflector at ``position`` in air of refractive index ``n`` and a fringe
    phase ``phase`` (counts, in [0, 1)); the simulated world moves the reflector
    (:meth:`move_to`) and the head counts.

    Examples
    --------
    >>> scale = SimulatedLaserScale(LaserHead(), position=0.0, n=1.0)
    >>> isinstance(scale, LaserScale)
    True
    >>> scale.move_to(6.33e-6); scale.read_counts()
    10
    """

    def __init__(self, head: LaserHead, position: float = 0.0, n: float = 1.0,
                 phase: float = 0.0) -> None:
        if not 0.0 <= phase < 1.0:
            raise InputError(f"phase = {phase!r} counts must lie in [0, 1)")
        self.head = head
        self._power_up = (float(position), float(n), float(phase))
        self._state = (float(position), float(n))

    def move_to(self, position: float, n: float | None = None) -> None:
        """The simulated world: the reflector at ``position`` (metres) in air of index ``n``
        (unchanged if None)."""
        self._state = (float(position), self._state[1] if n is None else float(n))

    def read_counts(self) -> int:
        x0, n0, phase = self._power_up
        x, n = self._state
        return int(self.head.counts([x], [n], x0, n0, phase)[0])


class SimulatedHomeSwitch:
    """The :class:`HomeSwitch` interface on a :class:`ReferenceSwitch`.

    The trip point is drawn once per activation (:meth:`arm`, called at construction) from the
    switch's repeatability with ``rng`` (None: the nominal trip point).
    """

    def __init__(self, switch: ReferenceSwitch, rng: np.random.Generator | None = None) -> None:
        self.switch = switch
        self.rng = rng
        self.position = float("nan")
        self.arm()

    def arm(self) -> float:
        """Draw the trip point of the next activation; return it, metres."""
        self.trip = self.switch.trip_point(self.rng)
        return self.trip

    def move_to(self, position: float) -> None:
        """The simulated world: the axis at ``position``, metres."""
        self.position = float(position)

    def is_on(self) -> bool:
        if not np.isfinite(self.position):
            raise InputError("simulated home switch: the axis position is not set; call move_to()")
        return bool(self.switch.state(self.position, self.trip))
