"""Misalignment error of a counter-rotating rotary calibration (Renishaw, Interferometric calibration of rotary axes equation 1).

With the reference calibrator's axis tilted by α from the axis under test, the laser's line of
sight tilted by β from the plane of rotation and the reflector's centre-line twisted by ω from
perpendicular to the calibrator's axis, the angle measured at axis angle θ is wrong by::

    E(θ) = sin(2(θ+η))·α²/4 + sin(θ+η)·α·β + cos(θ+η)·α·ω        (Renishaw, Interferometric calibration of rotary axes, eq. 1)

where η is the direction of α (the paper's note under eq. 1). This module gives E and each of its
terms, the peak and the half range over a turn, a trade-off table of expected accuracy over α and
β in the manner of Renishaw, Interferometric calibration of rotary axes's Figure 22, and the exact 3-D pose of the reflector
(:func:`reflector_pose`) from which the simulated instruments compute the laser's reading, so
that equation 1 is a *result* of the simulation, not an input to it.

Sign conventions (those of :func:`reflector_pose`): the axis under test turns about +Z; the
laser looks along −X (its beams return along +X) and β tilts the beams towards +Z; α tilts the
calibrator's axis about the direction ``η + 90°`` so that at θ = 0 it leans towards +X (the laser)
when η = 0; ω tilts the reflector's +Y end towards −Z. With these, the exact geometry reproduces
equation 1 with its printed signs (checked in the tests to second order in the angles).

References
----------
Renishaw, Interferometric calibration of rotary axes, "Errors due to angular misalignment of axes", eq. 1, Figures 7-14
and Figure 22.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from axiscal.errors import InputError
from axiscal.units import ARCSEC

__all__ = [
    "misalignment_error",
    "MisalignmentTerms",
    "misalignment_terms",
    "peak_error",
    "half_range",
    "TradeoffTable",
    "tradeoff_table",
    "SEED000_FIGURE22",
    "reflector_pose",
    "max_alpha",
    "FIGURE22_FIT",
    "figure22_model",
    "AccuracyEstimate",
    "expected_accuracy",
]

TWO_PI = 2.0 * math.pi
_TURN = np.linspace(0.0, TWO_PI, 7201)

#: Renishaw, Interferometric calibration of rotary axes Figure 22: estimated accuracy (arcsec) for α (columns, mrad) and β (rows, mrad).
SEED000_FIGURE22 = {
    "alpha_mrad": (0.4, 1.0, 2.0, 3.0, 4.0, 5.0),
    "beta_mrad": (1.0, 2.0, 3.0, 4.0, 5.0),
    "accuracy_arcsec": (
        (1.0, 1.3, 2.2, 3.6, 5.4, 7.6),
        (1.1, 1.5, 2.4, 3.8, 5.6, 7.8),
        (1.2, 1.6, 2.7, 4.1, 5.9, 8.2),
        (1.3, 1.8, 3.0, 4.5, 6.4, 8.7),
        (1.4, 2.0, 3.3, 5.0, 6.9, 9.3),
    ),
}

#: Least-squares fit of ``c0 + RSS(a·α²/4, b·α·β, c·α·ω)`` to :data:`SEED000_FIGURE22` at
#: ω = 2.5 mrad (c0 in arcsec; a, b, c scale equation 1's three amplitudes). Reproduces the 30
#: published values within 0.10 arcsec (the table's rounding is 0.05); tests refit it.
FIGURE22_FIT = {"c0_arcsec": 0.8572, "a": 4.8875, "b": 1.0116, "c": 0.8454}


def misalignment_error(theta, alpha: float, beta: float, omega: float, eta: float = 0.0):
    """Measurement error of Renishaw, Interferometric calibration of rotary axes equation 1, radians.

    Parameters
    ----------
    theta : array_like, radians
        Angle of the axis under test.
    alpha, beta, omega : float, radians
        Misalignments (axes, laser line of sight, reflector twist).
    eta : float, radians
        Direction of α (phase of the error).

    Returns
    -------
    float or ndarray, radians
        ``E(θ)`` of Renishaw, Interferometric calibration of rotary axes eq. 1 (module docstring).

    Examples
    --------
    >>> e = misalignment_error(math.radians(45), 5e-3, 0.0, 0.0)
    >>> round(e / ARCSEC, 3)         # α²/4 at 2θ = 90°
    1.289
    """
    return misalignment_terms(theta, alpha, beta, omega, eta).total_at()


@dataclass(frozen=True, eq=False)
class MisalignmentTerms:
    """The three terms of Renishaw, Interferometric calibration of rotary axes equation 1 over a set of angles (radians).

    Attributes
    ----------
    theta : ndarray, radians
    quadratic : ndarray, radians
        ``sin(2(θ+η))·α²/4``: reflector wobble (pitch × roll, α²/2) less the yaw of the
        counter-rotation (α²/4).
    alpha_beta : ndarray, radians
        ``sin(θ+η)·α·β``.
    alpha_omega : ndarray, radians
        ``cos(θ+η)·α·ω``.
    """

    theta: np.ndarray
    quadratic: np.ndarray
    alpha_beta: np.ndarray
    alpha_omega: np.ndarray

    def total_at(self):
        """The sum E(θ), radians (a float for a scalar θ)."""
        out = self.quadratic + self.alpha_beta + self.alpha_omega
        return float(out) if np.ndim(out) == 0 else out

    @property
    def total(self) -> np.ndarray:
        """The sum E(θ) as an array, radians."""
        return np.asarray(self.quadratic + self.alpha_beta + self.alpha_omega)

    def __str__(self) -> str:
        def pk(a):
            return float(np.max(np.abs(a))) / ARCSEC if np.size(a) else 0.0
        return (f"eq. 1 terms over {np.size(self.theta)} angles: α²/4 ±{pk(self.quadratic):.3f}, "
                f"αβ ±{pk(self.alpha_beta):.3f}, αω ±{pk(self.alpha_omega):.3f}, total peak "
                f"{pk(self.total):.3f} arcsec")


def misalignment_terms(theta, alpha: float, beta: float, omega: float,
                       eta: float = 0.0) -> MisalignmentTerms:
    """Each term of Renishaw, Interferometric calibration of rotary axes equation 1 separately (radians); see :class:`MisalignmentTerms`.

    Parameters
    ----------
    theta : array_like, radians
    alpha, beta, omega, eta : float, radians
        As in :func:`misalignment_error`; |α|, |β|, |ω| <= 0.1 rad (a small-angle result).

    Returns
    -------
    MisalignmentTerms
        The three terms of Renishaw, Interferometric calibration of rotary axes eq. 1, radians.
    """
    for name, v in (("alpha", alpha), ("beta", beta), ("omega", omega), ("eta", eta)):
        if not math.isfinite(v):
            raise InputError(f"{name}={v!r} must be a finite angle in radians")
    for name, v in (("alpha", alpha), ("beta", beta), ("omega", omega)):
        if abs(v) > 0.1:
            raise InputError(f"{name}={v!r} rad is not a small misalignment (|{name}| <= 0.1 rad); "
                             "equation 1 is a small-angle result")
    t = np.asarray(theta, dtype=float) + eta
    return MisalignmentTerms(theta=np.asarray(theta, dtype=float),
                             quadratic=np.sin(2 * t) * alpha * alpha / 4,
                             alpha_beta=np.sin(t) * alpha * beta,
                             alpha_omega=np.cos(t) * alpha * omega)


def peak_error(alpha: float, beta: float, omega: float) -> float:
    """Largest |E(θ)| over a full turn, radians (independent of η).

    Parameters
    ----------
    alpha, beta, omega : float, radians

    Returns
    -------
    float, radians
        max |E(θ)| of Renishaw, Interferometric calibration of rotary axes eq. 1, sampled every 0.05° (the sampling misses the true peak by
        less than 4e-7 of it).

    Examples
    --------
    >>> round(peak_error(0.62e-3, 1.23e-3, 2.26e-3) / ARCSEC, 3)   # Renishaw, Interferometric calibration of rotary axes Figure 14 case
    0.346
    """
    return float(np.max(np.abs(misalignment_terms(_TURN, alpha, beta, omega).total)))


def half_range(alpha: float, beta: float, omega: float) -> float:
    """Half of (max − min) of E(θ) over a full turn, radians: the ± an offset-free reading sees.

    A reading zeroed at a datum carries ``E(θ) − E(θ_datum)``; a constant does not change any
    ISO 230-2 parameter, so the half range is the ± that matters for the result.

    Parameters
    ----------
    alpha, beta, omega : float, radians

    Returns
    -------
    float, radians
        ``(max E − min E)/2`` of Renishaw, Interferometric calibration of rotary axes eq. 1 over a turn.
    """
    e = misalignment_terms(_TURN, alpha, beta, omega).total
    return float(0.5 * (e.max() - e.min()))


@dataclass(frozen=True, eq=False)
class TradeoffTable:
    """Expected measurement accuracy over grids of α and β (Renishaw, Interferometric calibration of rotary axes Figure 22 style).

    Attributes
    ----------
    alpha, beta : ndarray, radians
        Column (α) and row (β) values.
    accuracy : ndarray, shape (len(beta), len(alpha)), radians
        ``base + peak|E|`` with the reflector twist ω at its tolerance.
    omega : float, radians
        ω used (Renishaw, Interferometric calibration of rotary axes: reflector alignment within ±2.5 mrad).
    base : float, radians
        The system's accuracy with perfect alignment (encoder, laser, error map residuals).
    """

    alpha: np.ndarray
    beta: np.ndarray
    accuracy: np.ndarray
    omega: float
    base: float

    def rows(self) -> list[list[float]]:
        """The table in arcsec, one list per β."""
        return [[float(v) / ARCSEC for v in row] for row in self.accuracy]

    def __str__(self) -> str:
        head = "β\\α [mrad] " + "".join(f"{a * 1e3:7.2f}" for a in self.alpha)
        lines = [f"expected accuracy ± arcsec (ω = {self.omega * 1e3:g} mrad, base "
                 f"{self.base / ARCSEC:g} arcsec)", head]
        for b, row in zip(self.beta, self.rows()):
            lines.append(f"{b * 1e3:10.2f} " + "".join(f"{v:7.2f}" for v in row))
        return "\n".join(lines)


def tradeoff_table(alphas, betas, omega: float = 2.5e-3, base: float = 0.8 * ARCSEC) -> TradeoffTable:
    """Expected accuracy for every (α, β): ``base + peak|E(θ)|`` of equation 1, radians.

    Parameters
    ----------
    alphas, betas : array_like, radians
    omega : float, radians
        Reflector twist at its worst (Renishaw, Interferometric calibration of rotary axes: set within ±2.5 mrad in manufacture).
    base : float, radians
        Accuracy of the system at perfect alignment. The default 0.8 arcsec is the excess of seed
        000's Figure 22 over equation 1 at its smallest α (0.4 mrad), where equation 1 adds only
        0.2-0.5 arcsec.

    Returns
    -------
    TradeoffTable
        Accuracies in radians, one row per β.

    Notes
    -----
    How the numbers are formed, and why they differ from Figure 22: this table is equation 1's
    peak (the three terms added with their phases, which is less than the sum of their amplitudes)
    plus a constant base. Figure 22 agrees within about 0.3 arcsec for α <= 2 mrad but grows
    faster with α (7.6 against 4.7 arcsec at α = 5, β = 1 mrad): its excess over equation 1 rises
    roughly as 0.11 arcsec/mrad²·α², a contribution the paper does not list (for instance the error
    map's loss of validity and the cosine-type errors of a tilted calibrator). We do not invent
    that term; the comparison is printed in the report and checked in the tests.
    """
    a = np.atleast_1d(np.array(alphas, dtype=float))  # copies: the caller's arrays stay writeable
    b = np.atleast_1d(np.array(betas, dtype=float))
    acc = np.array([[base + peak_error(ai, bi, omega) for ai in a] for bi in b])
    for arr in (a, b, acc):
        arr.flags.writeable = False
    return TradeoffTable(alpha=a, beta=b, accuracy=acc, omega=float(omega), base=float(base))


def reflector_pose(theta, phi, alpha: float, eta: float, omega: float, height: float = 0.0,
                   offset=(0.0, 0.0)) -> tuple[np.ndarray, np.ndarray]:
    """Direction of the reflector's centre-line and position of its centre, fixed frame.

    Parameters
    ----------
    theta : array_like, radians
        Actual angle of the axis under test (about +Z).
    phi : array_like, radians
        Actual angle of the calibrator's shaft about its own axis (about −θ when
        counter-rotating).
    alpha, eta : float, radians
        Tilt of the calibrator's axis and its direction, in the frame of the turning table.
    omega : float, radians
        Twist of the reflector's centre-line out of the calibrator's plane of rotation.
    height : float, metres
        Height of the reflector centre above the mounting face, along the calibrator's axis.
    offset : (float, float), metres
        Position of the calibrator's axis on the table (from the axis under test), in the table's
        frame: a lateral offset on axis, the bracket radius off axis.

    Returns
    -------
    u : ndarray, shape (n, 3)
        Unit vector from retro-reflector 2 to retro-reflector 1.
    centre : ndarray, shape (n, 3), metres

    Notes
    -----
    ``u = R_z(θ)·T·R_z(φ)·u₀`` with ``T = R_z(η)·R_y(α)·R_z(−η)`` and
    ``u₀ = (0, cos ω, −sin ω)``; ``centre = R_z(θ)·(offset + T·(0, 0, height))``.
    """
    th = np.atleast_1d(np.asarray(theta, dtype=float))
    ph = np.broadcast_to(np.atleast_1d(np.asarray(phi, dtype=float)), th.shape)
    tilt = _rz(eta) @ _ry(alpha) @ _rz(-eta)
    u0 = np.array([0.0, math.cos(omega), -math.sin(omega)])
    cp, sp = np.cos(ph), np.sin(ph)
    v = np.stack([cp * u0[0] - sp * u0[1], sp * u0[0] + cp * u0[1], np.full_like(cp, u0[2])], -1)
    v = v @ tilt.T
    c_local = np.array([offset[0], offset[1], 0.0]) + tilt @ np.array([0.0, 0.0, height])
    ct, st = np.cos(th), np.sin(th)
    u = np.stack([ct * v[:, 0] - st * v[:, 1], st * v[:, 0] + ct * v[:, 1], v[:, 2]], -1)
    centre = np.stack([ct * c_local[0] - st * c_local[1], st * c_local[0] + ct * c_local[1],
                       np.full_like(ct, c_local[2])], -1)
    return u, centre


def _rz(t: float) -> np.ndarray:
    c, s = math.cos(t), math.sin(t)
    return np.array([[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]])


def _ry(t: float) -> np.ndarray:
    c, s = math.cos(t), math.sin(t)
    return np.array([[c, 0.0, s], [0.0, 1.0, 0.0], [-s, 0.0, c]])


def figure22_model(alpha: float, beta: float, omega: float = 2.5e-3) -> float:
    """Accuracy the published trade-off table gives, as a model fitted to it, radians.

    Parameters
    ----------
    alpha, beta, omega : float, radians

    Returns
    -------
    float, radians
        ``c0 + sqrt((a·α²/4)² + (b·α·β)² + (c·α·ω)²)`` with :data:`FIGURE22_FIT`.

    Notes
    -----
    Renishaw, Interferometric calibration of rotary axes Figure 22 tabulates the estimated accuracy over α = 0.4…5 mrad and β = 1…5 mrad.
    It grows faster with α than equation 1 does (7.6 against 0.8 + 3.9 arcsec at α = 5,
    β = 1 mrad), by an excess that shrinks with β, so it is not a pure α² term. The form above,
    equation 1's three amplitudes added in quadrature and scaled, fitted by least squares,
    reproduces the table within 0.10 arcsec. It is a fit, not physics: ω enters only through
    the form (the table is for ω at its 2.5 mrad tolerance), and outside the table's range it
    extrapolates.

    Examples
    --------
    >>> round(figure22_model(5e-3, 1e-3) / ARCSEC, 2)   # Figure 22: 7.6
    7.61
    """
    f = FIGURE22_FIT
    rss = math.sqrt((f["a"] * alpha**2 / 4) ** 2 + (f["b"] * alpha * beta) ** 2
                    + (f["c"] * alpha * omega) ** 2)
    return f["c0_arcsec"] * ARCSEC + rss


@dataclass(frozen=True)
class AccuracyEstimate:
    """Expected accuracy of a set-up by equation 1 and by the published table (radians).

    Attributes
    ----------
    peak : float
        Peak |E(θ)| of equation 1 over a turn: the error of a reading against the axis's true
        angle, up to a constant (ISO 230-2 A, E, M, R, B do not change with a constant).
    datum_relative : float
        max E − min E: the largest error of a reading relative to the 0° datum (E(θ) − E(0)) over
        every direction η of α; up to twice the peak.
    equation1 : float
        ``base + peak``.
    figure22 : float
        :func:`figure22_model`.
    """

    peak: float
    datum_relative: float
    equation1: float
    figure22: float

    @property
    def value(self) -> float:
        """The more cautious of the two, radians: what the budget states."""
        return max(self.equation1, self.figure22)

    @property
    def source(self) -> str:
        """Which estimate :attr:`value` is: ``"figure22_model"`` or ``"equation1"``."""
        return "figure22_model" if self.figure22 > self.equation1 else "equation1"


def expected_accuracy(alpha: float, beta: float, omega: float = 2.5e-3,
                      base: float = 0.8 * ARCSEC) -> AccuracyEstimate:
    """Expected ± accuracy of a set-up: equation 1's and the published table's, radians.

    Parameters
    ----------
    alpha, beta, omega, base : float, radians
        As in :func:`tradeoff_table`.

    Returns
    -------
    AccuracyEstimate
        ``value`` is the more cautious of ``base + peak`` (equation 1) and the model fitted to
        Figure 22 (:func:`figure22_model`); ``source`` says which.

    Examples
    --------
    >>> e = expected_accuracy(5e-3, 1e-3)
    >>> round(e.equation1 / ARCSEC, 2), round(e.value / ARCSEC, 2), e.source
    (4.72, 7.61, 'figure22_model')
    """
    peak = peak_error(alpha, beta, omega)
    return AccuracyEstimate(peak, 2.0 * half_range(alpha, beta, omega), base + peak,
                            figure22_model(alpha, beta, omega))


def max_alpha(accuracy: float, beta: float, omega: float = 2.5e-3,
              base: float = 0.8 * ARCSEC) -> float:
    """Largest α for which the expected accuracy stays within ``accuracy``, radians.

    Answers the set-up question "how well must I align the axes for this accuracy?" for a given
    laser alignment β and reflector twist ω. The expected accuracy is the more cautious of
    ``base + peak|E|`` (equation 1) and the model fitted to Figure 22
    (:func:`expected_accuracy`); both grow monotonically with α.

    Parameters
    ----------
    accuracy : float, radians
        The ± accuracy wanted.
    beta, omega, base : float, radians
        As in :func:`tradeoff_table`.

    Returns
    -------
    float, radians
        0.0 if even perfect axes cannot reach ``accuracy`` (``accuracy <= base`` or below the
        fitted table's constant, 0.857 arcsec).

    Notes
    -----
    Bisection (60 halvings of 0.1 rad) on :func:`expected_accuracy`; the peak of Renishaw, Interferometric calibration of rotary axes eq. 1
    is ``α·max|α sin 2t/4 + β sin t + ω cos t|`` and the fitted model is increasing in α too.

    Examples
    --------
    >>> a = max_alpha(2.0 * ARCSEC, 1e-3)
    >>> e = expected_accuracy(a, 1e-3)
    >>> round(a * 1e3, 2), round(e.value / ARCSEC, 6), e.source
    (1.75, 2.0, 'figure22_model')
    """
    if not accuracy > 0:
        raise InputError(f"accuracy={accuracy!r} rad must be positive")
    if accuracy <= max(base, FIGURE22_FIT["c0_arcsec"] * ARCSEC):
        return 0.0
    lo, hi = 0.0, 0.1
    if expected_accuracy(hi, beta, omega, base).value <= accuracy:
        return hi
    for _ in range(60):
        mid = 0.5 * (lo + hi)
        if expected_accuracy(mid, beta, omega, base).value <= accuracy:
            lo = mid
        else:
            hi = mid
    return lo
