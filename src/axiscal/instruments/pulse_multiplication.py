"""Exact pulse multiplication: the integer arithmetic of a laser scale's environmental compensator.

The laser's uncompensated count ``c`` becomes the output count ``o = floor(c P / 2^B)``, with P
the multiplication factor held to ``B = 32`` fractional bits (Renishaw, Laser scale axis
referencing, "Compensated laser scale system": compensation by exact pulse multiplication and
addition). Every output count is computed from the *total* laser count with integer arithmetic,
so nothing is rounded twice and no error accumulates however long the move; the streaming
:class:`PulseMultiplier` does the same incrementally with a remainder accumulator (Bresenham) and
gives identical counts. The factor itself (air, material) is
:class:`~axiscal.instruments.compensator.Compensator`'s; every name here is also importable from
:mod:`axiscal.instruments.compensator`.

Examples
--------
>>> mult = PulseMultiplier(factor_to_integer(8.1))
>>> mult.feed([1, 1, 1, 1]).tolist()   # 8.1 output counts per input count, spread exactly
[8, 8, 8, 8]
>>> mult.output
32
"""

from __future__ import annotations

from dataclasses import dataclass, field
from fractions import Fraction

import numpy as np

from axiscal.errors import InputError

__all__ = ["FACTOR_BITS", "factor_to_integer", "multiply", "PulseMultiplier", "expand_counts"]

#: Fractional bits of the multiplication factor (P / 2**FACTOR_BITS).
FACTOR_BITS = 32

_INT64_MAX = np.iinfo(np.int64).max


def factor_to_integer(ratio: float, bits: int = FACTOR_BITS) -> int:
    """The multiplication factor as the integer P of P / 2**bits (rounded to nearest).

    Parameters
    ----------
    ratio : float
        Output counts per laser count (positive).
    bits : int
        Fractional bits.

    Examples
    --------
    >>> factor_to_integer(0.5, bits=4)
    8
    """
    r = float(ratio)
    if not np.isfinite(r) or r <= 0:
        raise InputError(f"multiplication factor {ratio!r} must be a positive number")
    return int(round(r * (1 << bits)))


def multiply(counts, factors, bits: int = FACTOR_BITS) -> np.ndarray:
    """Output counts from laser counts: ``floor(c * P / 2**bits)``, exactly.

    Parameters
    ----------
    counts : array_like of int
        Laser counts since power-up, one per sample.
    factors : int or array_like of int
        The integer factor P in force at each sample (broadcast).
    bits : int

    Returns
    -------
    ndarray of int64
        Output counts.

    Raises
    ------
    InputError
        If a product would not fit in 64 bits (a move of more than about 160 m at 78 nm).

    Notes
    -----
    ``(c * P) >> bits`` is the floor of the exact rational c P / 2^bits for either sign of c
    (arithmetic shift), so each output count is exact and independent of every earlier one.
    """
    c = np.asarray(counts, dtype=np.int64)
    p = np.asarray(factors, dtype=np.int64)
    if c.size and p.size:
        worst = int(np.max(np.abs(c))) * int(np.max(np.abs(p)))
        if worst > _INT64_MAX:
            raise InputError(f"laser count {int(np.max(np.abs(c)))} times factor "
                             f"{int(np.max(p))} overflows 64 bits; the move is too long for "
                             "this factor resolution")
    return (c * p) >> bits


@dataclass
class PulseMultiplier:
    """Streaming pulse multiplier with a remainder accumulator (Bresenham-like), exact.

    Feed it laser count increments; it returns output count increments. The state is the integer
    accumulator ``acc = c * P`` (kept in Python integers, so it never overflows) and the output
    emitted so far; the output always equals ``floor(c * P / 2**bits)``. A new factor
    (:meth:`set_factor`) re-scales the whole count: the pulses it adds or removes are returned.

    Attributes
    ----------
    factor : int
        P, output counts per laser count times 2**bits.
    bits : int
    count : int
        Laser counts received (net).
    output : int
        Output counts emitted (net).
    """

    factor: int
    bits: int = FACTOR_BITS
    count: int = 0
    output: int = 0
    _acc: int = field(default=0, repr=False)

    def feed(self, increments) -> np.ndarray:
        """Process laser count increments (one per sample); return the output increments."""
        inc = np.asarray(increments, dtype=np.int64)
        c = self.count + np.cumsum(inc, dtype=np.int64)
        out = multiply(c, self.factor, self.bits)
        prev = np.concatenate(([self.output], out[:-1])) if out.size else out
        if out.size:
            self.count = int(c[-1])
            self.output = int(out[-1])
            self._acc = self.count * self.factor
        return out - prev

    def set_factor(self, factor: int) -> int:
        """Change P; return the output counts added (+) or removed (-) to re-scale the position."""
        self.factor = int(factor)
        self._acc = self.count * self.factor
        new = self._acc >> self.bits
        added = new - self.output
        self.output = new
        return int(added)

    @property
    def remainder(self) -> Fraction:
        """Fraction of an output count not yet emitted, in [0, 1)."""
        return Fraction(self._acc - (self.output << self.bits), 1 << self.bits)


def expand_counts(output_counts) -> np.ndarray:
    """Every output count the compensator emits between samples, in order (the pulse train).

    Between two samples whose output counts differ by k, the compensator emits k pulses; this
    returns the count after each pulse, so consecutive values differ by exactly one (what the
    digital A/B or the DAC staircase of the outputs steps through).

    Examples
    --------
    >>> expand_counts([0, 3, 3, 1]).tolist()
    [0, 1, 2, 3, 2, 1]
    """
    o = np.asarray(output_counts, dtype=np.int64)
    if o.size == 0:
        return o
    steps = np.diff(o)
    lengths = np.abs(steps)
    total = int(lengths.sum())
    starts = np.repeat(o[:-1], lengths)
    sign = np.repeat(np.sign(steps), lengths)
    within = np.arange(total, dtype=np.int64) - np.repeat(np.cumsum(lengths) - lengths, lengths)
    return np.concatenate((o[:1], starts + sign * (within + 1)))
