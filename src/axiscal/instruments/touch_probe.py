"""A touch probe on a precision sphere, as a five-axis kinematics cycle probes it.

The probe sits in the spindle and does not turn with the table: it approaches the sphere along
fixed machine directions (−X, +X, −Y, +Y from the equator and −Z from the top, by default) and
records the machine position of its stylus-ball centre at the trigger. That centre lies at
``R_sphere + r_stylus`` (the effective radius the probe's calibration gives) from the sphere's
centre, along the surface normal at the contact.

The probe's own calibration enters as a constant *offset* of every recorded point (the stylus
ball's X, Y offset from the spindle axis and the tool length's error in Z): it moves every
sphere centre by the same amount in the machine frame, so it is fully correlated with E_Z0A (E_Z0B),
E_X0C and E_Y0C, and belongs in the uncertainty as a calibrated input, not in the fit.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Protocol

import numpy as np

from axiscal.errors import InputError

__all__ = ["SphereProber", "SimulatedTouchProbe", "DIRECTIONS"]

#: Default contact normals (machine frame): the equator's four sides and the top.
DIRECTIONS = np.array([[-1.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, -1.0, 0.0], [0.0, 1.0, 0.0],
                       [0.0, 0.0, 1.0]])


class SphereProber(Protocol):
    """What a real probing driver also provides: the recorded stylus-ball centres (m, machine
    frame, shape (touches, 3)) of one probing of the sphere at a rotary pose (rad)."""

    def probe_sphere(self, machine, tilt_angle: float, c_angle: float, place,
                     rng: np.random.Generator | None = None) -> np.ndarray: ...


@dataclass(frozen=True)
class SimulatedTouchProbe:
    """A simulated touch probe (SI units).

    Attributes
    ----------
    sphere_radius : float, m
    stylus_radius : float, m
        Effective radius of the stylus ball (after pre-travel), from the probe's calibration.
    noise : float, m
        Standard deviation of one touch along its normal (repeatability and sphere form).
    offset : tuple of float, m
        Error of the probe's calibration (stylus offset x, y; length z): added to the truth, not
        known to the evaluation.
    directions : numpy.ndarray, shape (n, 3)
        Contact normals in the machine frame (unit vectors), at least 4, not in one plane.
    """

    sphere_radius: float = 12.5e-3
    stylus_radius: float = 1.5e-3
    noise: float = 0.5e-6
    offset: tuple[float, float, float] = (0.0, 0.0, 0.0)
    directions: np.ndarray = field(default_factory=DIRECTIONS.copy)

    def __post_init__(self) -> None:
        if not (self.sphere_radius > 0 and self.stylus_radius >= 0 and self.noise >= 0):
            raise InputError("probe: sphere radius must be > 0, stylus radius and noise >= 0")
        d = np.asarray(self.directions, float)
        if d.ndim != 2 or d.shape[1] != 3 or d.shape[0] < 4:
            raise InputError("probe: give at least 4 contact directions (x, y, z)")

    @property
    def effective_radius(self) -> float:
        """Distance of a recorded stylus-ball centre from the sphere's centre, m."""
        return self.sphere_radius + self.stylus_radius

    def probe_sphere(self, machine, tilt_angle, c_angle, place, rng=None) -> np.ndarray:
        """Recorded stylus-ball centres of one probing at a pose (machine frame, m).

        Parameters
        ----------
        machine : FiveAxisMachine
        tilt_angle, c_angle : float, rad
        place : array_like, shape (3,), m
            True sphere centre in the table frame.
        rng : numpy.random.Generator, optional
            Draws the touches' noise and the axes' random errors.
        """
        centre = machine.to_machine(np.array([tilt_angle]), np.array([c_angle]),
                                    np.asarray(place, float), rng, readings=False)[0]
        d = np.asarray(self.directions, float)
        d = d / np.linalg.norm(d, axis=1, keepdims=True)
        r = self.effective_radius
        if rng is not None and self.noise > 0:
            r = r + rng.normal(0.0, self.noise, len(d))[:, None]
        return machine.readings(centre + r * d) - np.asarray(self.offset, float)

    def touch_from(self, machine, tilt_angle, c_angle, place, starts, rng=None) -> np.ndarray:
        """Recorded stylus-ball centres when the probe starts at given machine positions and
        moves along the negative of each contact normal until it touches (m, machine frame).

        This is how a controller's probing cycle is measured (issue 43): the controller puts the
        probe at ``starts`` (one per direction of :attr:`directions`, outside the sphere; read
        from its joints) and the probe travels ``-d`` until its stylus-ball centre is the
        effective radius from the true sphere centre: the smaller root ``s`` of
        ``|start − s d − centre| = R``.

        Parameters
        ----------
        machine : FiveAxisMachine
        tilt_angle, c_angle : float, rad
            The angles the rotary drives reached.
        place : array_like, shape (3,), m
            True sphere centre in the table frame.
        starts : array_like, shape (n, 3), m
            Start of each touch in the machine frame, in the order of :attr:`directions`.
        rng : numpy.random.Generator, optional

        Raises
        ------
        InputError
            A start inside the sphere, or whose path misses it.
        """
        centre = machine.to_machine(np.array([tilt_angle]), np.array([c_angle]),
                                    np.asarray(place, float), rng, readings=False)[0]
        d = np.asarray(self.directions, float)
        d = d / np.linalg.norm(d, axis=1, keepdims=True)
        r = np.full(len(d), self.effective_radius)
        if rng is not None and self.noise > 0:
            r = r + rng.normal(0.0, self.noise, len(d))
        true_starts = machine.positions(starts)
        w = true_starts - centre
        b = (w * d).sum(axis=1)
        disc = b * b - (w * w).sum(axis=1) + r * r
        if np.any((w * w).sum(axis=1) < r * r) or np.any(disc < 0) or np.any(b < 0):
            raise InputError("probe: a start point is inside the sphere or its path misses it")
        s = b - np.sqrt(disc)
        return machine.readings(true_starts - s[:, None] * d) - np.asarray(self.offset, float)
