"""Error functions of a machine axis: smooth, periodic and random components.

These are the building blocks of the simulated axes in :mod:`axiscal.machines.linear` and
:mod:`axiscal.machines.rotary`: a sum of sinusoids (:class:`HarmonicSeries`) for periodic errors
(ball-screw pitch, encoder graduation, the once- and twice-per-revolution errors of a rotary table),
a polynomial for scale and bend, and a seeded random profile for the irregular residue.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from axiscal.errors import InputError

__all__ = ["Harmonic", "HarmonicSeries", "random_profile"]


@dataclass(frozen=True)
class Harmonic:
    """One sinusoid ``amplitude * sin(2*pi*x/period + phase)``.

    Attributes
    ----------
    amplitude : float
        In the unit of the error (metres or radians).
    period : float
        In the unit of the position (metres, or radians for a rotary axis: 2*pi/k is the k-th
        order per revolution).
    phase : float, radians
    """

    amplitude: float
    period: float
    phase: float = 0.0

    def __post_init__(self) -> None:
        if not np.isfinite(self.period) or self.period <= 0:
            raise InputError(f"harmonic period must be positive, got {self.period!r}")
        if not np.isfinite(self.amplitude):
            raise InputError(f"harmonic amplitude must be finite, got {self.amplitude!r}")


@dataclass(frozen=True)
class HarmonicSeries:
    """A sum of sinusoids plus a polynomial in position.

    ``value(x) = sum_k a_k sin(2 pi x / p_k + phi_k) + sum_n c_n x**n``

    Attributes
    ----------
    harmonics : tuple of Harmonic
    polynomial : tuple of float
        Coefficients c_0, c_1, ... of increasing power (c_1 is a scale error, c_2 a bend).

    Examples
    --------
    >>> s = HarmonicSeries((Harmonic(1.0, 4.0),), polynomial=(0.0, 0.5))
    >>> float(s(1.0))
    1.5
    """

    harmonics: tuple[Harmonic, ...] = ()
    polynomial: tuple[float, ...] = ()

    def __call__(self, x):
        x = np.asarray(x, dtype=float)
        out = np.zeros_like(x)
        for h in self.harmonics:
            out = out + h.amplitude * np.sin(2.0 * np.pi * x / h.period + h.phase)
        for n, c in enumerate(self.polynomial):
            if c:
                out = out + c * x**n
        return out

    def derivative(self, x):
        """First derivative with respect to position."""
        x = np.asarray(x, dtype=float)
        out = np.zeros_like(x)
        for h in self.harmonics:
            w = 2.0 * np.pi / h.period
            out = out + h.amplitude * w * np.cos(w * x + h.phase)
        for n, c in enumerate(self.polynomial):
            if n and c:
                out = out + n * c * x ** (n - 1)
        return out

    def __add__(self, other: "HarmonicSeries") -> "HarmonicSeries":
        n = max(len(self.polynomial), len(other.polynomial))
        p1 = list(self.polynomial) + [0.0] * (n - len(self.polynomial))
        p2 = list(other.polynomial) + [0.0] * (n - len(other.polynomial))
        return HarmonicSeries(self.harmonics + other.harmonics, tuple(a + b for a, b in zip(p1, p2)))


ZERO = HarmonicSeries()


def random_profile(
    rms: float, base_period: float, orders: range, rng: np.random.Generator, slope: float = 1.0
) -> HarmonicSeries:
    """A reproducible irregular error: harmonics of ``base_period`` with random phases.

    The amplitude of order k falls as ``k**-slope`` and the whole series is scaled so that its
    root-mean-square over one base period is ``rms``. With ``base_period`` = one revolution the
    profile closes on itself, as a rotary axis's must.

    Parameters
    ----------
    rms : float
        Root-mean-square value of the profile (unit of the error).
    base_period : float
        Period of order 1 (unit of position).
    orders : range
        Orders k to include (for example ``range(3, 40)``).
    rng : numpy.random.Generator
    slope : float
        Spectral slope of the amplitudes.
    """
    ks = np.array(list(orders), dtype=float)
    if ks.size == 0 or rms == 0:
        return ZERO
    amp = ks**-slope
    amp *= rms / np.sqrt(0.5 * np.sum(amp**2))
    phases = rng.uniform(0, 2 * np.pi, ks.size)
    return HarmonicSeries(
        tuple(Harmonic(float(a), base_period / k, float(p)) for a, k, p in zip(amp, ks, phases))
    )
