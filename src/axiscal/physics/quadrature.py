"""Encoder and interferometer signals: digital A/B quadrature and analogue sine/cosine.

* Digital quadrature (:func:`encode_quadrature`, :func:`decode_quadrature`): two square waves A and
  B a quarter period apart; every edge is one count (×4 counting). A transition that changes both
  A and B at once is *illegal*: the direction (±2 counts) cannot be known. It is reported (its
  sample indices and number), never silently dropped; the counter holds its value there.
* Analogue sine/cosine (:func:`interpolate_sincos`): the phase within a signal period is
  ``φ = arctan(sin/cos)`` (Renishaw, Interferometric calibration of rotary axes, "Sub-divisional errors") and whole periods are counted by
  unwrapping the phase from sample to sample. A jump of more than a quarter period between two
  samples is counted as a *tracking warning* (the signal was sampled too slowly to be sure).
* Imperfect signals (:class:`SignalImperfections`, :func:`synthesize_sincos`): DC offsets, amplitude
  mismatch, phase error from 90° and noise distort the Lissajous circle (Renishaw, Interferometric calibration of rotary axes Figures 17-19)
  into an ellipse and cause a sub-divisional error (SDE) that repeats every signal period.
* The Heydemann correction (:func:`heydemann_fit`, :func:`heydemann_correct`) fits that ellipse and
  maps it back to a circle (Heydemann 1981), removing most of the SDE.

All functions are vectorised NumPy; none loops over samples in Python. For large records the
sine/cosine interpolation uses compiled kernels when numba is installed (the ``fast`` extra,
:mod:`axiscal.physics._sincos_numba`, loaded lazily on the first large array): a branch-free
rational arctangent fused with the period count, about 3x a copy of the array against 20x or
more with ``numpy.arctan2`` (scalar libm); the NumPy path stays the fallback and the reference.

References
----------
Renishaw, Interferometric calibration of rotary axes, "Sub-divisional errors" and Figures 15-19.
P. L. M. Heydemann, "Determination and correction of quadrature fringe measurement errors in
interferometers", Applied Optics 20(19), 3382-3384 (1981).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from axiscal.errors import InputError

__all__ = [
    "QuadratureDecoding",
    "encode_quadrature",
    "decode_quadrature",
    "Interpolation",
    "interpolate_sincos",
    "SignalImperfections",
    "synthesize_sincos",
    "interpolation_error",
    "subdivisional_error",
    "HeydemannCorrection",
    "heydemann_fit",
    "heydemann_correct",
]

TWO_PI = 2.0 * math.pi
#: Smallest record for which :func:`interpolate_sincos` uses the numba kernels when available.
ACCELERATE_MIN_SAMPLES = 1 << 16
_ACCEL: object = None   # None: not tried yet; False: numba unavailable; else the kernel module
# (phase now - phase before) mod 4 -> count step; 2 is illegal (both signals changed).
_STEP = np.array([0, 1, 0, -1], dtype=np.int64)
_BLOCK = 1 << 15


# --------------------------------------------------------------------------------------------
# digital quadrature
# --------------------------------------------------------------------------------------------
@dataclass(frozen=True, eq=False)
class QuadratureDecoding:
    """Result of decoding A/B quadrature.

    Attributes
    ----------
    counts : ndarray of int64, counts (quarter periods)
        Position after each sample; ``counts[0]`` is the initial count.
    illegal : ndarray of int64
        Indices ``i`` of the samples reached by an illegal transition from sample ``i - 1`` (both
        A and B changed). The count is held at those samples.
    """

    counts: np.ndarray
    illegal: np.ndarray

    @property
    def n_illegal(self) -> int:
        """Number of illegal transitions."""
        return int(self.illegal.size)

    def __str__(self) -> str:
        return (f"quadrature decoding: {self.counts.size} samples, final count "
                f"{int(self.counts[-1]) if self.counts.size else 0}, "
                f"{self.n_illegal} illegal transition(s)")


def encode_quadrature(counts) -> tuple[np.ndarray, np.ndarray]:
    """A and B square-wave states for integer positions in counts (×4 counting).

    Parameters
    ----------
    counts : array_like of int, counts (quarter periods)

    Returns
    -------
    a, b : ndarray of bool
        The phase ``counts mod 4`` = 0, 1, 2, 3 gives (A, B) = (0,0), (1,0), (1,1), (0,1): A leads B
        for a positive motion.

    Notes
    -----
    The Gray-code cycle of ×4 quadrature counting (issue 3; Renishaw, Laser scale axis referencing, "digital A/B quadrature" of
    the laser head): consecutive states differ in one signal only.

    Examples
    --------
    >>> a, b = encode_quadrature([0, 1, 2, 3, 4, -1])
    >>> a.astype(int).tolist(), b.astype(int).tolist()
    ([0, 1, 1, 0, 0, 0], [0, 0, 1, 1, 0, 1])
    """
    c = np.asarray(counts)
    if not np.issubdtype(c.dtype, np.integer):
        raise InputError(f"counts must be integers, got dtype {c.dtype}")
    phase = (c & 3).astype(np.uint8)
    bit1 = phase >> 1
    return (phase & 1) ^ bit1 == 1, bit1 == 1


def decode_quadrature(a, b, initial_count: int = 0) -> QuadratureDecoding:
    """Count the edges of A/B quadrature signals (×4), flagging illegal transitions.

    Parameters
    ----------
    a, b : array_like of bool (or 0/1), same shape (n,)
        Sampled signal states.
    initial_count : int
        Count assigned to the first sample.

    Returns
    -------
    QuadratureDecoding

    Notes
    -----
    The phase index is ``2·B + (A xor B)`` (0, 1, 2, 3 around the cycle); the step between two
    samples is ``(phase_i − phase_{i−1}) mod 4``: 0 → no count, 1 → +1, 3 → −1, 2 → illegal.

    Examples
    --------
    >>> a, b = encode_quadrature(np.array([0, 1, 2, 3, 2, 1]))
    >>> decode_quadrature(a, b).counts.tolist()
    [0, 1, 2, 3, 2, 1]
    >>> a, b = encode_quadrature(np.array([0, 1, 3, 4]))   # 1 -> 3 skips a state
    >>> decode_quadrature(a, b).illegal.tolist()
    [2]
    """
    a = np.asarray(a)
    b = np.asarray(b)
    if a.shape != b.shape or a.ndim != 1:
        raise InputError(f"a and b must be 1-D arrays of the same length, got shapes {a.shape} "
                         f"and {b.shape}")
    n = a.size
    if n == 0:
        return QuadratureDecoding(_frozen(np.zeros(0, np.int64)), _frozen(np.zeros(0, np.int64)))
    if a.dtype != bool or b.dtype != bool:
        if not (np.isin(a, (0, 1)).all() and np.isin(b, (0, 1)).all()):
            raise InputError("a and b must hold only 0/1 (or booleans)")
        a, b = a.astype(bool), b.astype(bool)
    au, bu = a.view(np.uint8), b.view(np.uint8)
    phase = np.bitwise_xor(au, bu)
    phase |= bu << 1
    delta = np.subtract(phase[1:], phase[:-1])
    delta &= 3
    illegal = np.flatnonzero(delta == 2) + 1
    counts = np.empty(n, dtype=np.int64)
    counts[0] = initial_count
    acc = np.int64(initial_count)
    for i in range(0, n - 1, _BLOCK):          # blocks that stay in cache; no per-sample loop
        d = delta[i:i + _BLOCK]
        out = counts[i + 1:i + 1 + d.size]
        np.take(_STEP, d, out=out)
        np.cumsum(out, out=out)
        out += acc
        acc = out[-1]
    return QuadratureDecoding(_frozen(counts), _frozen(illegal.astype(np.int64)))


# --------------------------------------------------------------------------------------------
# analogue sine / cosine
# --------------------------------------------------------------------------------------------
@dataclass(frozen=True, eq=False)
class Interpolation:
    """Result of sine/cosine interpolation.

    Attributes
    ----------
    position : ndarray, signal periods
        Whole periods counted plus the fraction ``φ/2π``.
    phase : ndarray, radians in (−π, π]
        Interpolated phase ``arctan2(sin, cos)`` within the period.
    tracking_warnings : ndarray of int64
        Indices of samples whose phase moved by more than a quarter period from the previous
        sample (the count may be wrong there: the signal was sampled too slowly).
    """

    position: np.ndarray
    phase: np.ndarray
    tracking_warnings: np.ndarray

    @property
    def n_tracking_warnings(self) -> int:
        """Number of samples with an uncertain period count."""
        return int(self.tracking_warnings.size)

    def __str__(self) -> str:
        end = float(self.position[-1]) if self.position.size else 0.0
        return (f"sine/cosine interpolation: {self.position.size} samples, final position "
                f"{end:.4f} periods, {self.n_tracking_warnings} tracking warning(s)")


def interpolate_sincos(sin, cos, initial_period: int = 0, *,
                       accelerate: bool | None = None) -> Interpolation:
    """Position in signal periods from sampled sine and cosine, by arctangent and unwrapping.

    Parameters
    ----------
    sin, cos : array_like, shape (n,), any consistent unit (volts)
    initial_period : int
        Whole periods assigned to the first sample.
    accelerate : bool, optional
        None (default): the numba kernels for records of at least
        :data:`ACCELERATE_MIN_SAMPLES` samples when numba is installed, else NumPy. False: NumPy
        always. True: the kernels, :class:`~axiscal.errors.InputError` if numba is missing. Both
        give the same periods and phases within 5e-16 rad.

    Returns
    -------
    Interpolation

    Notes
    -----
    Renishaw, Interferometric calibration of rotary axes: "digitally calculating the phase angle, φ, by computing φ = arctan(sin/cos)" and
    counting the cycles for the coarse position; here the quadrant-correct ``arctan2`` is used and
    a change of phase of more than π between samples is taken as a wrap to the next period.

    Examples
    --------
    >>> x = np.linspace(-0.3, 2.7, 50)
    >>> r = interpolate_sincos(np.sin(TWO_PI * x), np.cos(TWO_PI * x))
    >>> bool(np.allclose(r.position - r.position[0], x - x[0]))
    True
    """
    s = np.asarray(sin, dtype=float)
    c = np.asarray(cos, dtype=float)
    if s.shape != c.shape or s.ndim != 1:
        raise InputError(f"sin and cos must be 1-D arrays of the same length, got {s.shape} and "
                         f"{c.shape}")
    n = s.size
    phase = np.empty(n)
    position = np.empty(n)
    warn: list[np.ndarray] = []
    if n == 0:
        empty = np.zeros(0, np.int64)
        return Interpolation(_frozen(position), _frozen(phase), _frozen(empty))
    kernels = _kernels(n, accelerate)
    if kernels is not None:
        s, c = np.ascontiguousarray(s), np.ascontiguousarray(c)
        bad = kernels.interpolate(s, c, int(initial_period), phase, position)
        if bad < 0:                            # a NaN or an infinity: say where
            _refuse_non_finite(s, c)
        w = kernels.warnings(phase, bad) if bad else np.zeros(0, np.int64)
        return Interpolation(_frozen(position), _frozen(phase), _frozen(w))
    _refuse_non_finite(s, c)
    np.arctan2(s[:1], c[:1], out=phase[:1])
    position[0] = phase[0] / TWO_PI + initial_period
    turns = float(initial_period)
    for i in range(1, n, _BLOCK):              # blocks that stay in cache; no per-sample loop
        j = min(i + _BLOCK, n)
        ph = np.arctan2(s[i:j], c[i:j], out=phase[i:j])
        d = ph - phase[i - 1:j - 1]
        out = position[i:j]
        np.less(d, -math.pi, out=out)          # phase fell through -pi: one more period
        out -= d > math.pi                     # rose through +pi: one fewer
        ad = np.abs(d, out=d)
        bad = (ad > 0.5 * math.pi) & (ad < 1.5 * math.pi)
        if bad.any():
            warn.append(np.flatnonzero(bad) + i)
        np.cumsum(out, out=out)
        out += turns
        turns = float(out[-1])
        out += ph * (1.0 / TWO_PI)
    w = np.concatenate(warn) if warn else np.zeros(0, np.int64)
    return Interpolation(_frozen(position), _frozen(phase), _frozen(w.astype(np.int64)))


@dataclass(frozen=True)
class SignalImperfections:
    """Departures of a sine/cosine pair from the ideal (unit circle) Lissajous figure.

    The signals are ``sin = amplitude_sin·sin(φ + phase_error) + offset_sin + noise`` and
    ``cos = amplitude_cos·cos(φ) + offset_cos + noise``.

    Attributes
    ----------
    offset_sin, offset_cos : float, signal units
        DC offsets (Renishaw, Interferometric calibration of rotary axes Figure 19).
    amplitude_sin, amplitude_cos : float, signal units
        Amplitudes (Renishaw, Interferometric calibration of rotary axes Figure 18: a mismatch makes an ellipse).
    phase_error : float, radians
        Departure of the phase difference from 90° (Renishaw, Interferometric calibration of rotary axes Figure 17).
    noise : float, signal units
        Standard deviation of additive white noise on each signal.
    """

    offset_sin: float = 0.0
    offset_cos: float = 0.0
    amplitude_sin: float = 1.0
    amplitude_cos: float = 1.0
    phase_error: float = 0.0
    noise: float = 0.0

    def __post_init__(self) -> None:
        for name in ("amplitude_sin", "amplitude_cos"):
            v = getattr(self, name)
            if not (math.isfinite(v) and v > 0):
                raise InputError(f"{name}={v!r} must be positive")
        if not abs(self.phase_error) < math.pi / 4:
            raise InputError(f"phase_error={self.phase_error!r} rad must be within ±45°")
        if self.noise < 0:
            raise InputError(f"noise={self.noise!r} must be >= 0")


def synthesize_sincos(position, imperfections: SignalImperfections = SignalImperfections(),
                      rng: np.random.Generator | None = None) -> tuple[np.ndarray, np.ndarray]:
    """Sine and cosine signals for positions in signal periods, with imperfections.

    Parameters
    ----------
    position : array_like, signal periods
    imperfections : SignalImperfections
    rng : numpy.random.Generator, optional
        Needed only if ``imperfections.noise > 0``.

    Returns
    -------
    sin, cos : ndarray, signal units

    Notes
    -----
    The signal model of :class:`SignalImperfections` (Renishaw, Interferometric calibration of rotary axes Figures 17-19: phase error,
    amplitude mismatch, DC offset; Heydemann 1981 eq. 1).
    """
    p = imperfections
    phi = TWO_PI * np.asarray(position, dtype=float)
    s = p.amplitude_sin * np.sin(phi + p.phase_error) + p.offset_sin
    c = p.amplitude_cos * np.cos(phi) + p.offset_cos
    if p.noise > 0:
        if rng is None:
            raise InputError("imperfections.noise > 0 needs a numpy.random.Generator (rng)")
        s = s + rng.normal(0.0, p.noise, s.shape)
        c = c + rng.normal(0.0, p.noise, c.shape)
    return s, c


def interpolation_error(phase, imperfections: SignalImperfections):
    """Phase error of arctangent interpolation on imperfect, noise-free signals, radians.

    Parameters
    ----------
    phase : array_like, radians
        True phase within the signal period.
    imperfections : SignalImperfections (its noise is ignored)

    Returns
    -------
    ndarray, radians in (−π, π]
        Interpolated minus true phase: the sub-divisional error as a function of phase.

    Notes
    -----
    ``arctan2(sin, cos) − φ`` on the signals of :func:`synthesize_sincos` (Renishaw, Interferometric calibration of rotary axes,
    "Sub-divisional errors": φ = arctan(sin/cos) on imperfect signals).

    Examples
    --------
    >>> e = interpolation_error(np.linspace(0, TWO_PI, 721), SignalImperfections(amplitude_sin=1.05))
    >>> round(float(np.max(np.abs(e))), 4)   # about half the 5 % mismatch, radians
    0.0244
    """
    ph = np.asarray(phase, dtype=float)
    s, c = synthesize_sincos(ph / TWO_PI, SignalImperfections(
        imperfections.offset_sin, imperfections.offset_cos, imperfections.amplitude_sin,
        imperfections.amplitude_cos, imperfections.phase_error, 0.0))
    return _wrap(np.arctan2(s, c) - ph)


def subdivisional_error(phase_error, phase, bins: int = 64) -> float:
    """Amplitude of the sub-divisional error: largest |mean phase error| over phase bins, radians.

    The phase error is averaged in ``bins`` equal bins of the true phase so that random noise
    averages out and what remains is the error that repeats every period (the SDE of Renishaw, Interferometric calibration of rotary axes).

    Parameters
    ----------
    phase_error : array_like, radians
        Interpolated minus true phase, per sample.
    phase : array_like, radians
        True phase per sample.
    bins : int

    Returns
    -------
    float, radians
    """
    err = _wrap(np.asarray(phase_error, dtype=float))
    if not (np.all(np.isfinite(err)) and np.all(np.isfinite(phase))):
        raise InputError("phase_error and phase must be finite (a NaN has no bin)")
    idx = (np.mod(np.asarray(phase, dtype=float), TWO_PI) * (bins / TWO_PI)).astype(np.int64)
    idx = np.minimum(idx, bins - 1)
    n = np.bincount(idx, minlength=bins)
    if np.any(n == 0):
        raise InputError(f"phase does not cover all {bins} bins of the period; use more samples")
    return float(np.max(np.abs(np.bincount(idx, err, minlength=bins) / n)))


@dataclass(frozen=True)
class HeydemannCorrection:
    """Ellipse parameters fitted to a sine/cosine Lissajous figure (Heydemann 1981).

    Attributes
    ----------
    offset_sin, offset_cos : float, signal units
    amplitude_sin, amplitude_cos : float, signal units
    phase_error : float, radians
        Same meaning as in :class:`SignalImperfections`.
    """

    offset_sin: float
    offset_cos: float
    amplitude_sin: float
    amplitude_cos: float
    phase_error: float

    def __str__(self) -> str:
        return (f"Heydemann fit: offsets sin {self.offset_sin:+.4g}, cos {self.offset_cos:+.4g}; "
                f"amplitudes sin {self.amplitude_sin:.4g}, cos {self.amplitude_cos:.4g}; "
                f"phase error {math.degrees(self.phase_error):+.3f}°")


def heydemann_fit(sin, cos) -> HeydemannCorrection:
    """Fit the ellipse ``sin = a_s·sin(φ+δ) + p_s``, ``cos = a_c·cos φ + p_c`` to the samples.

    Parameters
    ----------
    sin, cos : array_like, shape (n,), n >= 5, signal units
        Samples spread around the Lissajous figure (a fraction of a period is not enough).

    Returns
    -------
    HeydemannCorrection

    Raises
    ------
    InputError
        Too few samples, or the points do not lie on an ellipse.

    Notes
    -----
    A general conic ``A x² + B xy + C y² + D x + E y + F = 0`` (x = cos, y = sin, normalised
    first) is fitted by least squares (the singular vector of the smallest singular value). Its
    centre is the offsets; about the centre it reads ``A u² + B uv + C v² = G`` with
    ``G = A p_c² + B p_c p_s + C p_s² − F``, and comparing with the ellipse's own equation
    ``u²/a_c² − 2uv·sin δ/(a_c a_s) + v²/a_s² = cos² δ`` gives ``sin δ = −B/(2√(AC))``,
    ``a_c = √(G/A)/cos δ`` and ``a_s = √(G/C)/cos δ`` (Heydemann 1981, eq. 2-6, rewritten).

    Examples
    --------
    >>> imp = SignalImperfections(0.02, -0.01, 1.05, 1.0, math.radians(3))
    >>> s, c = synthesize_sincos(np.linspace(0, 1, 400, endpoint=False), imp)
    >>> h = heydemann_fit(s, c)
    >>> round(h.amplitude_sin, 6), round(math.degrees(h.phase_error), 6), round(h.offset_sin, 6)
    (1.05, 3.0, 0.02)
    """
    y = np.asarray(sin, dtype=float).ravel()
    x = np.asarray(cos, dtype=float).ravel()
    if x.size != y.size or x.size < 5:
        raise InputError(f"heydemann_fit needs at least 5 (sin, cos) pairs, got {min(x.size, y.size)}")
    _refuse_non_finite(y, x)
    mx, my = float(x.mean()), float(y.mean())
    sx, sy = float(x.std()), float(y.std())
    if not (sx > 0 and sy > 0):
        raise InputError("sin and cos must vary: the samples do not span the Lissajous figure")
    xn, yn = (x - mx) / sx, (y - my) / sy
    design = np.column_stack([xn * xn, xn * yn, yn * yn, xn, yn, np.ones_like(xn)])
    _, _, vt = np.linalg.svd(design.T @ design)
    A, B, C, D, E, F = vt[-1]
    det = 4 * A * C - B * B
    if not det > 0:
        raise InputError("the sin/cos samples do not lie on an ellipse (conic discriminant >= 0)")
    pc = (-2 * C * D + B * E) / det
    ps = (-2 * A * E + B * D) / det
    G = A * pc * pc + B * pc * ps + C * ps * ps - F
    sin_d = -B / (2.0 * math.sqrt(A * C)) * (1.0 if A > 0 else -1.0)
    cos_d = math.sqrt(max(1.0 - sin_d * sin_d, 1e-12))
    ac = math.sqrt(G / A) / cos_d
    as_ = math.sqrt(G / C) / cos_d
    return HeydemannCorrection(offset_sin=float(my + sy * ps), offset_cos=float(mx + sx * pc),
                               amplitude_sin=float(sy * as_), amplitude_cos=float(sx * ac),
                               phase_error=float(math.asin(sin_d)))


def heydemann_correct(sin, cos, fit: HeydemannCorrection) -> tuple[np.ndarray, np.ndarray]:
    """Map imperfect signals back onto the unit circle with a fitted correction.

    Parameters
    ----------
    sin, cos : array_like, signal units
        Measured signals.
    fit : HeydemannCorrection
        From :func:`heydemann_fit` (offsets and amplitudes in signal units, phase in radians).

    Notes
    -----
    Heydemann (1981): the inverse of the signal model of :func:`synthesize_sincos`, with the
    ellipse parameters of :func:`heydemann_fit` (its Notes hold the algebra).

    Returns
    -------
    sin, cos : ndarray, dimensionless
        ``cos' = (cos − p_c)/a_c``, ``sin' = ((sin − p_s)/a_s − cos'·sin δ)/cos δ``.
    """
    c = (np.asarray(cos, dtype=float) - fit.offset_cos) / fit.amplitude_cos
    s = (np.asarray(sin, dtype=float) - fit.offset_sin) / fit.amplitude_sin
    s = (s - c * math.sin(fit.phase_error)) / math.cos(fit.phase_error)
    return s, c


def _kernels(n: int, accelerate: bool | None):
    """The numba kernel module to use for ``n`` samples, or None for the NumPy path."""
    global _ACCEL
    if accelerate is False or (accelerate is None and n < ACCELERATE_MIN_SAMPLES):
        return None
    if _ACCEL is None:
        import importlib

        try:
            _ACCEL = importlib.import_module("axiscal.physics._sincos_numba")
        except ImportError:
            _ACCEL = False
    if _ACCEL is False:
        if accelerate:
            raise InputError("accelerate=True needs numba (pip install 'axiscal[fast]')")
        return None
    return _ACCEL


def _refuse_non_finite(s: np.ndarray, c: np.ndarray) -> None:
    """A NaN or infinite sample has no phase: refuse it rather than lose a period count there
    (a wrap across a NaN sample is not seen, and arctan2 of an infinity is a finite angle).

    Fast path: a dot product is finite whenever every sample is (barring |values| > 1e150), and a
    NaN or infinity in either array makes it NaN or infinite; only then are the samples scanned."""
    with np.errstate(all="ignore"):
        if np.isfinite(np.dot(s, c)):
            return
    for name, arr in (("sin", s), ("cos", c)):
        ok = np.isfinite(arr)
        if not ok.all():
            i = int(np.argmin(ok))
            raise InputError(f"{name}[{i}] = {arr[i]!r}: every sample must be finite; a missing "
                             "sample cannot be interpolated (split the record there or fill it)")


def _wrap(x):
    return np.mod(np.asarray(x) + math.pi, TWO_PI) - math.pi


def _frozen(a: np.ndarray) -> np.ndarray:
    a.flags.writeable = False
    return a
