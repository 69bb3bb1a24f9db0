"""Rephasing of the compensator's outputs at the reference switch (Renishaw, Laser scale axis referencing, Figure 4).

A laser scale's reference switch is not registered to the fringes, so at the moment the switch
trips the phase of the synthesised sine/cosine relative to the axis home is unknown (anything in
one period). The compensator holds the reference back, adjusts the phase of its outputs over the
next N counts of real motion (the "virtual movement", 0 to N-1 counts, seen by the controller but
not made by the axis), and only then sends a reference mark, correctly phased, so that the
controller's home Z is always the same place: 5N/4 counts (320 for N = 256) beyond the switch.

The pulse model of the reference mark
-------------------------------------
Renishaw, Laser scale axis referencing places B 256 output counts of real motion beyond the switch A, Z 64 counts beyond B
(320 beyond A), says the reference mark is active at Z, and then says the pulse ends at C
"64 output counts beyond point B", i.e. at Z itself, which contradicts "active at Z". The
physically consistent model used here: the reference pulse is **half a period wide and centred
on Z**. With N counts per period it starts at B (N real counts beyond A, phase -45°), Z is N/4
further (phase 45°, where sine = cosine and both are positive, as a conventional scale's mark is
phased) and it ends at C, another N/4 beyond Z (phase 135°). Over the pulse sin + cos > 0. For
N = 256: A = 0, B = 256, **Z = 320**, C = 384 output counts beyond the switch. The paper's
"64 output counts beyond point B" for C is read as "beyond point Z".
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from axiscal.errors import InputError

__all__ = ["RephaseResult", "rephase", "reference_virtual", "reference_window", "synthesise"]


@dataclass(frozen=True)
class RephaseResult:
    """What the rephasing did over one trajectory.

    Attributes
    ----------
    m : ndarray of int64
        Controller-side count per sample: the real output count plus the power-up phase and
        the virtual movement.
    reference : ndarray of bool
        The reference mark output per sample.
    index_a : int or None
        Sample at which the compensator saw the switch (A); None if it never did.
    count_a : int or None
        Real output count at A.
    virtual : int
        Virtual movement v added in stage 2, 0 to N-1 counts.
    m_b, m_z, m_c : int or None
        Controller-side counts of B (pulse starts), Z (sine = cosine, pulse active) and C
        (pulse ends).
    direction : int
        +1 or -1, the direction of homing.
    counts_per_period : int
    """

    m: np.ndarray
    reference: np.ndarray
    index_a: int | None
    count_a: int | None
    virtual: int
    m_b: int | None
    m_z: int | None
    m_c: int | None
    direction: int
    counts_per_period: int

    @property
    def rephased(self) -> bool:
        """True if the trajectory reached B, where the stage-2 adjustment is complete."""
        if self.m_b is None:
            return False
        return bool(np.any(self.direction * self.m >= self.direction * self.m_b))


def rephase(output_counts, switch, counts_per_period: int = 256, direction: int = 1,
            power_up_phase: int = 0, stage2_periods: int = 1) -> RephaseResult:
    """Rephase the synthesised signals at the reference switch (Renishaw, Laser scale axis referencing, Figure 4).

    Parameters
    ----------
    output_counts : array_like of int
        Real output counts o per sample (the result of :func:`multiply`).
    switch : array_like of bool
        Reference switch state per sample as the compensator sees it.
    counts_per_period : int
        N (256 in the paper).
    direction : {+1, -1}
        Direction of the homing move in output counts.
    power_up_phase : int
        Phase of the synthesised outputs at power-up, in counts (0 to N-1): the controller
        count is ``m = o + power_up_phase`` before the switch.
    stage2_periods : int
        k: the virtual movement is spread over k·N counts of real motion (1 in the paper). With
        k > 1 the controller sees at most (kN + N − 1)/(kN) times the real count rate during
        stage 2 instead of nearly twice it, and B, Z, C lie (k − 1)·N counts further on (a fixed
        setting, so the home stays repeatable): see
        :func:`axiscal.instruments.compensator.rephase_periods_for`.

    Returns
    -------
    RephaseResult

    Notes
    -----
    Stage 1: ``m = o + φ``. At A (the first sample with the switch on) the compensator holds the
    reference back and chooses the virtual movement

    .. math::
        v = \\left(\\tfrac{N}{8} - d\\,(m_A + \\tfrac{5N}{4}\\,d)\\right) \\bmod N \\quad (d = +1),

    (generally the v in 0..N-1 that puts m_Z = m_A + d(5N/4 + v) on phase 45°, m_Z ≡ N/8 mod N).
    Stage 2: over the next N counts of real motion it adds ``floor(v (u - u_A) / N)`` counts
    (u = d·o), an exact integer spread, so the controller sees N + v counts (N to 2N - 1: the
    the paper's "256 to 512"). At B (u = u_A + N) the adjustment is complete and latched: from then
    on ``m = o + φ + d v`` for ever (stage 3, the phase is preserved). The reference pulse is
    active while the controller count lies in the half period from B to C centred on Z; it is
    registered to position like a conventional scale's mark. The spread is a function of the
    real position until it completes, so a reversal during stage 2 takes back what was added.
    """
    o = np.asarray(output_counts, dtype=np.int64)
    sw = np.asarray(switch, dtype=bool)
    if o.shape != sw.shape or o.ndim != 1:
        raise InputError(f"output counts {o.shape} and switch states {sw.shape} must be 1-D "
                         "arrays of the same length")
    n = int(counts_per_period)
    if n < 8 or n % 8:
        raise InputError(f"counts_per_period = {n} must be a multiple of 8")
    d = _direction(direction)
    k2 = int(stage2_periods)
    if k2 < 1:
        raise InputError(f"stage2_periods = {stage2_periods!r} must be a whole number >= 1")
    span = k2 * n
    phi = int(power_up_phase) % n
    m = o + phi
    ref = np.zeros(o.shape, dtype=bool)
    if not sw.any():
        return RephaseResult(m, ref, None, None, 0, None, None, None, d, n)
    ka = int(np.argmax(sw))
    o_a = int(o[ka])
    m_a = o_a + phi
    v = reference_virtual(m_a, n, d)
    u = d * o[ka:]
    u_a = d * o_a
    progress = np.clip(u - u_a, 0, span)
    done = np.maximum.accumulate(u) >= u_a + span
    extra = np.where(done, v, (v * progress) // span)
    m[ka:] = o[ka:] + phi + d * extra
    m_b = m_a + d * (span + v)
    m_z = m_b + d * (n // 4)
    m_c = m_b + d * (n // 2)
    lo, hi = reference_window(m_b, n, d)
    seg = m[ka:]
    ref[ka:] = done & (seg >= lo) & (seg < hi)
    return RephaseResult(m, ref, ka, o_a, v, m_b, m_z, m_c, d, n)


def reference_virtual(m_a: int, counts_per_period: int, direction: int = 1) -> int:
    """Virtual movement v (0..N-1) that puts Z on phase 45° for a switch seen at count m_A."""
    n = int(counts_per_period)
    d = _direction(direction)
    # m_Z = m_A + d (5N/4 + v) ≡ N/8 (mod N)  ->  d v ≡ N/8 - m_A - d 5N/4
    return int((d * (n // 8 - m_a) - (5 * n) // 4) % n)


def reference_window(m_b: int, counts_per_period: int, direction: int = 1) -> tuple[int, int]:
    """Controller counts [lo, hi) where the reference pulse is active (B to C, centred on Z)."""
    n = int(counts_per_period)
    if _direction(direction) > 0:
        return m_b, m_b + n // 2
    return m_b - n // 2 + 1, m_b + 1


def synthesise(m, counts_per_period: int = 256, amplitude: float = 1.0):
    """The sine and cosine outputs for controller counts m: ``A sin(2π m/N)``, ``A cos(2π m/N)``.

    A DAC staircase of N steps per period; sine = cosine > 0 at m ≡ N/8 (mod N).

    Examples
    --------
    >>> s, c = synthesise([32], 256)
    >>> bool(abs(s[0] - c[0]) < 1e-12 and s[0] > 0)
    True
    """
    n = int(counts_per_period)
    k = np.mod(np.asarray(m, dtype=np.int64), n)
    table = 2.0 * np.pi * np.arange(n) / n
    return amplitude * np.sin(table)[k], amplitude * np.cos(table)[k]


def _direction(direction) -> int:
    if direction in (1, "+", "+1", "up", "positive"):
        return 1
    if direction in (-1, "-", "-1", "down", "negative"):
        return -1
    raise InputError(f"direction {direction!r} must be +1 or -1")
