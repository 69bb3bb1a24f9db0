"""Least-squares sphere through probed points, with the radius check a probing cycle makes.

A touch probe records the centre of its stylus ball where it triggers on a precision sphere; the
points lie on a sphere of radius ``R_sphere + r_stylus`` (the effective radius, after the probe's
own calibration) about the sphere's centre. The centre is found by minimising the sum of squared
*geometric* distances ``Σ (|p_i − c| − R)²`` (ISO 10360-6:2001 calls this the Gaussian,
least-squares, element), started from the linear (algebraic) fit ``|p|² = 2 c·p + (R² − |c|²)``
and refined by Gauss–Newton.

A fitted radius that departs from the expected one by more than a tolerance means a wrong sphere,
a wrong stylus calibration, a bad touch or chips: the fit is refused, as Heidenhain's
KinematicsOpt (cycle 451) refuses a calibration sphere whose measured diameter departs from the
entered one by more than its tolerance (0.02 mm in its default settings, the reading chosen here).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from axiscal.errors import InputError

__all__ = ["SphereFit", "fit_sphere", "centre_sensitivity", "RADIUS_TOLERANCE"]

#: Default largest |fitted − expected| radius, m (0.02 mm as KinematicsOpt's check).
RADIUS_TOLERANCE = 0.02e-3


@dataclass(frozen=True)
class SphereFit:
    """A fitted sphere (SI units).

    Attributes
    ----------
    center : numpy.ndarray, shape (3,), m
    radius : float, m
    rms : float, m
        Root mean square of the geometric residuals.
    n : int
        Number of points.
    """

    center: np.ndarray
    radius: float
    rms: float
    n: int

    def __str__(self) -> str:
        c = ", ".join(f"{v * 1e3:.4f}" for v in self.center)
        return (f"sphere centre ({c}) mm, radius {self.radius * 1e3:.4f} mm, "
                f"rms {self.rms * 1e6:.2f} µm of {self.n} points")


def fit_sphere(points, expected_radius: float | None = None,
               tolerance: float = RADIUS_TOLERANCE, label: str = "sphere") -> SphereFit:
    """Fit a sphere to probed points and check its radius.

    Parameters
    ----------
    points : array_like, shape (N, 3), m
        Stylus-ball centres at the triggers, N >= 4, not all in one plane.
    expected_radius : float, m, optional
        Sphere radius plus effective stylus radius; when given, a fitted radius farther from it
        than ``tolerance`` is refused.
    tolerance : float, m
    label : str
        Names the fit in a message (for example ``"pose 7"``).

    Returns
    -------
    SphereFit

    Raises
    ------
    InputError
        Fewer than 4 points, a non-finite value, or points that fix no sphere.
    InputError
        The fitted radius contradicts ``expected_radius``.

    Examples
    --------
    >>> d = np.array([[1, 0, 0], [-1, 0, 0], [0, 1, 0], [0, -1, 0], [0, 0, 1.0]])
    >>> f = fit_sphere(0.0125 * d + [0.1, 0.2, 0.3], expected_radius=0.0125)
    >>> np.round(f.center * 1e3, 6).tolist(), round(f.radius * 1e3, 6)
    ([100.0, 200.0, 300.0], 12.5)
    """
    p = np.asarray(points, dtype=float)
    if p.ndim != 2 or p.shape[1] != 3 or p.shape[0] < 4:
        raise InputError(f"{label}: a sphere needs at least 4 probed points (x, y, z), "
                         f"got {p.shape[0] if p.ndim == 2 else p.size}")
    if not np.all(np.isfinite(p)):
        raise InputError(f"{label}: a probed point is not a finite number")
    mean = p.mean(axis=0)
    q = p - mean
    A = np.column_stack([2.0 * q, np.ones(len(q))])
    sol, *_, sv = np.linalg.lstsq(A, (q * q).sum(axis=1), rcond=None)
    if sv[-1] < 1e-9 * sv[0]:
        raise InputError(f"{label}: the {len(p)} probed points fix no sphere (all in one plane "
                         "or one circle); probe the sphere's top too")
    c = sol[:3]
    r = float(np.sqrt(max(sol[3] + c @ c, 0.0)))
    for _ in range(10):
        d = q - c
        dist = np.linalg.norm(d, axis=1)
        res = dist - r
        J = np.column_stack([-d / dist[:, None], -np.ones(len(q))])
        step = np.linalg.lstsq(J, -res, rcond=None)[0]
        c, r = c + step[:3], r + step[3]
        if np.abs(step).max() < 1e-13:
            break
    res = np.linalg.norm(q - c, axis=1) - r
    fit = SphereFit(center=c + mean, radius=float(r), rms=float(np.sqrt(np.mean(res ** 2))),
                    n=len(p))
    if expected_radius is not None and abs(fit.radius - expected_radius) > tolerance:
        raise InputError(
            f"{label}: fitted radius {fit.radius * 1e3:.4f} mm differs from the expected "
            f"{expected_radius * 1e3:.4f} mm (sphere + stylus) by "
            f"{(fit.radius - expected_radius) * 1e3:+.4f} mm, beyond the tolerance "
            f"{tolerance * 1e3:g} mm; check the sphere, the stylus calibration and the touches")
    return fit


def centre_sensitivity(normals) -> np.ndarray:
    """How the fitted centre moves with each point's error along its contact normal.

    Parameters
    ----------
    normals : array_like, shape (N, 3)
        Directions from the sphere's centre to the probed points (normalised here), N >= 4.

    Returns
    -------
    numpy.ndarray, shape (3, N), m per m
        ``G`` with ``δc = G ε`` to first order, ``ε_i`` the error of point ``i`` along its
        normal (a touch probe's noise is along its travel).

    Notes
    -----
    At the solution the geometric residuals ``|p_i − c| − r`` of :func:`fit_sphere` change by
    ``ε_i − n_i·δc − δr``; least squares over ``(δc, δr)`` gives
    ``(δc, δr) = (DᵀD)⁻¹ Dᵀ ε`` with the rows of ``D`` equal to ``[n_i, 1]``, and ``G`` is the
    first three rows (the linear propagation of JCGM 100:2008, 5.1.2, sensitivity coefficients
    ``∂c/∂ε_i``). With independent errors of standard deviation ``σ`` the centre's covariance is
    ``σ² G Gᵀ``, the top-left 3 × 3 block of ``σ² (DᵀD)⁻¹``.

    Examples
    --------
    >>> d = np.array([[1, 0, 0], [-1, 0, 0], [0, 1, 0], [0, -1, 0], [0, 0, 1.0]])
    >>> np.round(centre_sensitivity(d), 3).tolist()[0]
    [0.5, -0.5, 0.0, 0.0, 0.0]
    """
    n = np.asarray(normals, float)
    n = n / np.linalg.norm(n, axis=1, keepdims=True)
    D = np.column_stack([n, np.ones(len(n))])
    return (np.linalg.inv(D.T @ D) @ D.T)[:3]
