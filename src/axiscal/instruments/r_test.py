"""An R-test: three displacement sensors in a nest on the table, a precision sphere in the spindle.

The machine moves its rotary and linear axes together so that, by its nominal kinematics, the
tool sphere stays at the nest's place on the table. The nest turns with the table, so its three
sensors measure the sphere's displacement relative to the nest in the *table-fixed* frame: sensor
``i`` reads ``s_i = g_i (n_i · Δ)`` with ``n_i`` its measuring direction, ``g_i`` its gain and
``Δ`` the sphere centre's displacement from its place at zero; the instrument gives
``Δ = N⁻¹ s`` with the nominal directions and unit gains (IBS Precision Engineering, R-test
principle, after Weikert, "R-Test, a New Device for Accuracy Measurements on Five Axis Machine
Tools", CIRP Annals 53 (2004) 429-432). The gains' calibration error is the instrument's
systematic input; the sensors' noise and the sphere's form its random one.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Protocol

import numpy as np

from axiscal.errors import InputError

__all__ = ["RTestInstrument", "SimulatedRTest", "SENSOR_DIRECTIONS"]

#: Nominal measuring directions of the three sensors in the nest (table frame): three mutually
#: orthogonal directions each 35.26° above the table plane, as a tripod nest has them.
SENSOR_DIRECTIONS = np.array([
    [np.sqrt(2 / 3), 0.0, np.sqrt(1 / 3)],
    [-np.sqrt(1 / 6), np.sqrt(1 / 2), np.sqrt(1 / 3)],
    [-np.sqrt(1 / 6), -np.sqrt(1 / 2), np.sqrt(1 / 3)],
])


class RTestInstrument(Protocol):
    """What a real R-test driver also provides: displacements (m, table frame, shape (N, 3)) of
    the tool sphere relative to the nest at N poses (rad) and commanded positions (m)."""

    def measure(self, machine, tilt_angle, c_angle, commanded, place,
                rng: np.random.Generator | None = None) -> np.ndarray: ...


@dataclass(frozen=True)
class SimulatedRTest:
    """A simulated R-test (SI units).

    Attributes
    ----------
    noise : float, m
        Standard deviation of one sensor reading (noise and sphere form).
    gain_errors : tuple of float
        True relative gain error of each sensor (unknown to the evaluation).
    directions : numpy.ndarray, shape (3, 3)
        Nominal measuring directions (rows, table frame).
    range : float, m
        Measuring range of a sensor: a reading beyond it is refused.
    """

    noise: float = 0.5e-6
    gain_errors: tuple[float, float, float] = (0.0, 0.0, 0.0)
    directions: np.ndarray = field(default_factory=SENSOR_DIRECTIONS.copy)
    range: float = 1e-3

    def __post_init__(self) -> None:
        d = np.asarray(self.directions, float)
        if d.shape != (3, 3) or abs(np.linalg.det(d)) < 1e-3:
            raise InputError("R-test: three measuring directions not in one plane are needed")
        if self.noise < 0 or not self.range > 0:
            raise InputError("R-test: noise must be >= 0 and range > 0")

    def measure(self, machine, tilt_angle, c_angle, commanded, place, rng=None) -> np.ndarray:
        """Displacement of the tool sphere from the nest, table frame (m), at each pose.

        Parameters
        ----------
        machine : FiveAxisMachine
        tilt_angle, c_angle : array_like, shape (N,), rad
        commanded : array_like, shape (N, 3), m
            Machine positions of the tool sphere's centre.
        place : array_like, shape (3,), m
            True place of the nest's zero in the table frame.
        """
        actual = machine.to_table(tilt_angle, c_angle, commanded, rng)
        delta = actual - np.asarray(place, float)
        d = np.asarray(self.directions, float)
        s = (delta @ d.T) * (1.0 + np.asarray(self.gain_errors, float))
        if rng is not None and self.noise > 0:
            s = s + rng.normal(0.0, self.noise, s.shape)
        if np.abs(s).max() > self.range:
            raise InputError(f"R-test: a sensor reads {np.abs(s).max() * 1e3:.3f} mm, beyond its "
                             f"range {self.range * 1e3:g} mm; centre the nest better")
        return np.linalg.solve(d, s.T).T
