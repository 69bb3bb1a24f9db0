"""ISO 230-4:2005 circular test — G, H, F, and squareness from the elliptical component.

A run is the radial deviation ``Δr(φ)`` of the actual path from the nominal circle of radius R
(a telescoping ballbar's reading), at the nominal angular positions φ (rad, counter-clockwise from
+X), contoured counter-clockwise (``"ccw"``) or clockwise (``"cw"``).

ISO 230-4 definitions (§3, evaluated here on the sampled path):

* **F, radial deviation** — deviation of the actual path from the nominal path about the nominal
  centre (the ballbar's pivot): ``F_max = max Δr``, ``F_min = min Δr`` over all runs.
* **G, circular deviation** — the minimum radial separation of two concentric circles
  enveloping the actual path of one direction (minimum-zone centre), ``G_ccw``, ``G_cw``. Solved
  exactly as a linear programme on the first-order model ``Δr - (a cos φ + b sin φ)`` (valid while
  the deviations are small against R, as they are on a machine). The value about the
  least-squares centre, which ISO 230-4 also allows and which is never smaller, is in
  ``G_lsc_ccw``, ``G_lsc_cw``.
* **H, circular hysteresis** — largest radial difference between the CW and CCW paths at the same
  angle, both referred to their common least-squares centre.

Diagnosis (Chapman, Calibration of machine squareness Method 4: squareness "isolated from backlash, scale mismatch ..."): to first
order the errors enter ``Δr`` as

====================  ============================================  ===========================
error                 model                                        ``Δr(φ)`` term
====================  ============================================  ===========================
squareness θ          δx = -θ y (Chapman, Calibration of machine squareness Eq. 2)                    ``-(θR/2) sin 2φ``
scale mismatch        δx = e_x x, δy = e_y y                        ``R(e_x - e_y)/2 cos 2φ``
                                                                    (+ a radius change)
backlash b_x, b_y     δx = (b_x/2) sign(v_x) (``LinearAxis``)        ``±(b_x/2) sign(sin φ) cos φ``,
                                                                    ``∓(b_y/2) sign(cos φ) sin φ``
centre offset         —                                            ``c_x cos φ + c_y sin φ``
====================  ============================================  ===========================

The backlash terms change sign with the direction (upper sign CW), so the **mean** of the CCW and
CW runs holds squareness and scale mismatch free of backlash: a least-squares fit of
``[1, cos φ, sin φ, cos 2φ, sin 2φ]`` to the mean gives them. Half the difference of the runs holds
the backlash (with any centre and radius shift between runs): a fit of
``[1, cos φ, sin φ, B_x(φ), B_y(φ)]`` gives b_x and b_y. Least squares (not Fourier sums) keeps
this valid on partial arcs, accepted down to 220° (Chapman, Calibration of machine squareness). With one direction only, all terms
are fitted together and the result carries a warning.

References
----------
ISO 230-4:2005, Test code for machine tools — Part 4: Circular tests for numerically controlled
machine tools, §3. Chapman, Calibration of machine squareness, Method 4 (Figure 9) and "Testing global squareness errors on
machines with unequal aspect ratios".
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from axiscal.errors import InputError
from axiscal.standards.iso230_1 import Squareness

__all__ = ["CircularRun", "CircularResult", "evaluate_circular", "MIN_ARC_DEG", "arc_coverage"]

#: Smallest arc accepted for squareness, degrees (Chapman, Calibration of machine squareness: "partial arc tests (down to 220°)").
MIN_ARC_DEG = 220.0


@dataclass(frozen=True, eq=False)
class CircularRun:
    """One circular run (one direction).

    Attributes
    ----------
    angles : numpy.ndarray, rad
        Nominal angular positions, counter-clockwise from +X.
    deviations : numpy.ndarray, m
        Radial deviation from the nominal radius at each angle.
    direction : str
        ``"ccw"`` or ``"cw"``.
    """

    angles: np.ndarray
    deviations: np.ndarray
    direction: str = "ccw"

    def __post_init__(self):
        a = np.asarray(self.angles, dtype=float).ravel()
        d = np.asarray(self.deviations, dtype=float).ravel()
        if a.shape != d.shape or a.size < 8:
            raise InputError(f"circular run needs at least 8 angles and as many deviations "
                             f"(got {a.size} and {d.size})")
        if not (np.isfinite(a).all() and np.isfinite(d).all()):
            raise InputError("circular run holds NaN or infinite values")
        direction = str(self.direction).lower()
        if direction not in ("ccw", "cw"):
            raise InputError(f"direction={self.direction!r}: must be 'ccw' or 'cw'")
        object.__setattr__(self, "angles", _frozen(a))
        object.__setattr__(self, "deviations", _frozen(d))
        object.__setattr__(self, "direction", direction)


@dataclass(frozen=True)
class CircularResult:
    """ISO 230-4 circular test evaluation with the squareness diagnosis.

    Attributes
    ----------
    radius : float, m
        Nominal radius R.
    squareness : Squareness
        From the sin 2φ (elliptical) term.
    scale_mismatch : float, m/m
        ``e_x - e_y`` from the cos 2φ term.
    backlash_x, backlash_y : float or None, m
        Reversal values (None with one direction).
    G_ccw, G_cw : float or None, m
        Circular deviation of each direction (minimum-zone centre).
    H : float or None, m
        Circular hysteresis (both directions needed).
    F_max, F_min : float, m
        Radial deviation extremes about the nominal centre.
    arc_deg : float
        Angular coverage of the runs, degrees.
    fit_rms : float, m
        RMS residual of the diagnosis model.
    warnings : tuple of str
    G_lsc_ccw, G_lsc_cw : float or None, m
        Circular deviation about the least-squares centre.
    """

    radius: float
    squareness: Squareness
    scale_mismatch: float
    backlash_x: float | None
    backlash_y: float | None
    G_ccw: float | None
    G_cw: float | None
    H: float | None
    F_max: float
    F_min: float
    arc_deg: float
    fit_rms: float
    warnings: tuple[str, ...] = ()
    G_lsc_ccw: float | None = None
    G_lsc_cw: float | None = None

    def as_dict(self) -> dict:
        """Numbers for JSON: lengths in µm, ratios in µm/m."""
        um = (lambda v: None if v is None else v * 1e6)
        return {"radius_mm": self.radius * 1e3, "squareness": self.squareness.as_dict(),
                "scale_mismatch_um_per_m": self.scale_mismatch * 1e6,
                "backlash_x_um": um(self.backlash_x), "backlash_y_um": um(self.backlash_y),
                "G_ccw_um": um(self.G_ccw), "G_cw_um": um(self.G_cw), "H_um": um(self.H),
                "G_lsc_ccw_um": um(self.G_lsc_ccw), "G_lsc_cw_um": um(self.G_lsc_cw),
                "F_max_um": um(self.F_max), "F_min_um": um(self.F_min), "arc_deg": self.arc_deg,
                "fit_rms_um": um(self.fit_rms), "warnings": list(self.warnings)}

    def __str__(self) -> str:
        f = (lambda v: "—" if v is None else f"{v * 1e6:.3f} µm")
        lines = [f"circular test R = {self.radius * 1e3:g} mm over {self.arc_deg:.0f}°",
                 f"  {self.squareness}",
                 f"  scale mismatch X−Y {self.scale_mismatch * 1e6:+.2f} µm/m, "
                 f"backlash X {f(self.backlash_x)}, Y {f(self.backlash_y)}",
                 f"  G ccw {f(self.G_ccw)}, G cw {f(self.G_cw)}, H {f(self.H)}, "
                 f"F max {f(self.F_max)}, F min {f(self.F_min)}"]
        lines += [f"  warning: {w}" for w in self.warnings]
        return "\n".join(lines)


def arc_coverage(angles) -> float:
    """Angular coverage of a set of angles, degrees (360 minus the largest empty gap, one sample
    step added back so that an evenly sampled full circle gives 360).

    Parameters
    ----------
    angles : array_like, radians
        Nominal angular positions of one run (at least two).

    Returns
    -------
    float, degrees
        At most 360. The arc a partial-arc test covers (Chapman, Calibration of machine squareness: down to 220°).

    Examples
    --------
    >>> arc_coverage(np.radians(np.arange(0, 360, 10)))
    360.0
    >>> round(arc_coverage(np.radians(np.arange(0, 221, 5))), 6)
    225.0
    """
    a = np.sort(np.mod(np.asarray(angles, dtype=float).ravel(), 2 * np.pi))
    if a.size < 2 or not np.all(np.isfinite(a)):
        raise InputError(f"arc coverage needs at least 2 finite angles, got {a.size}")
    gaps = np.diff(np.r_[a, a[0] + 2 * np.pi])
    step = float(np.median(gaps))
    return float(np.degrees(min(2 * np.pi, 2 * np.pi - gaps.max() + step)))


def evaluate_circular(runs, radius: float, *, axes: tuple[str, str] = ("X", "Y"),
                      datum: str = "") -> CircularResult:
    """Evaluate a circular (ballbar) test by ISO 230-4 with the squareness diagnosis.

    Parameters
    ----------
    runs : sequence of CircularRun
        One CCW and/or one CW run.
    radius : float, m
        Nominal radius.
    axes, datum
        Naming of the plane for the result's :class:`~axiscal.standards.iso230_1.Squareness`.

    Returns
    -------
    CircularResult

    Raises
    ------
    InputError
        No run, two runs of one direction, an arc under 220°, a bad radius.

    Examples
    --------
    >>> phi = np.radians(np.arange(0, 360, 1.0))
    >>> dr = -(15e-6 * 0.1 / 2) * np.sin(2 * phi)          # 15 µm/m on R = 100 mm
    >>> r = evaluate_circular([CircularRun(phi, dr, "ccw"), CircularRun(phi, dr, "cw")], 0.1)
    >>> round(r.squareness.um_per_m, 6), round(r.backlash_x * 1e6, 6)
    (15.0, 0.0)
    """
    runs = list(runs)
    if not runs or len(runs) > 2 or len({r.direction for r in runs}) != len(runs):
        raise InputError(f"{len(runs)} run(s) given: need one CCW and/or one CW run")
    if not (math.isfinite(radius) and radius > 0):
        raise InputError(f"radius={radius!r} m: must be positive")
    arc = min(arc_coverage(r.angles) for r in runs)
    if arc < MIN_ARC_DEG - 1e-6:
        raise InputError(f"arc of {arc:.1f}°: squareness needs at least {MIN_ARC_DEG:.0f}° "
                         "(Chapman, Calibration of machine squareness, partial arcs down to 220°)")
    by = {r.direction: r for r in runs}
    warnings: list[str] = []
    g, g_lsc = {}, {}
    for d, r in by.items():
        g[d], g_lsc[d] = _circular_deviations(r)
    devs = np.concatenate([r.deviations for r in runs])
    if len(by) == 2:
        q, m, bx, by_, rms, h = _diagnose_both(by["ccw"], by["cw"], arc)
    else:
        (d, run), = by.items()
        cols = np.column_stack([_harmonics(run.angles), _backlash_basis(run.angles, d)])
        c, rms = _lstsq(cols, run.deviations)
        q, m, bx, by_, h = float(c[4]), float(c[3]), None, None, None
        warnings.append(f"one direction ({d}) only: backlash is not separated from squareness; "
                        "measure both directions")
    return CircularResult(
        radius=float(radius), squareness=Squareness(-2.0 * q / radius, axes, datum),
        scale_mismatch=2.0 * m / radius, backlash_x=bx, backlash_y=by_,
        G_ccw=g.get("ccw"), G_cw=g.get("cw"), H=h, F_max=float(devs.max()),
        F_min=float(devs.min()), arc_deg=arc, fit_rms=float(rms), warnings=tuple(warnings),
        G_lsc_ccw=g_lsc.get("ccw"), G_lsc_cw=g_lsc.get("cw"))


# --- helpers -------------------------------------------------------------------------------------

def _diagnose_both(ccw_run: CircularRun, cw_run: CircularRun, arc: float):
    """Squareness, scale mismatch and backlash from one least-squares fit of both runs.

    Rows: the CCW then the CW run on common angles. Columns: the common harmonics
    ``[1, cos φ, sin φ, cos 2φ, sin 2φ]``, a centre and radius shift between the runs
    (``±[1, cos φ, sin φ]/2``) and the backlash basis of each run's direction. Away from the
    reversal points this is the fit of the mean (squareness, scale) and of the half difference
    (backlash); at a sample exactly on a reversal point both runs carry the approach side's
    backlash (:func:`_backlash_basis`), which the mean/half-difference split would lose.
    """
    phi, ccw, cw = _common(ccw_run, cw_run, arc)
    h = _harmonics(phi)
    n = phi.size
    cols = np.empty((2 * n, 10), order="F")
    for k, sense in enumerate((1.0, -1.0)):          # CCW rows, then CW rows
        blk = cols[k * n:(k + 1) * n]
        sx, sy = velocity_signs(h[:, 2], h[:, 1], sense)
        blk[:, :5] = h
        blk[:, 5:8] = sense * 0.5 * h[:, :3]
        blk[:, 8], blk[:, 9] = 0.5 * sx * h[:, 1], 0.5 * sy * h[:, 2]   # = _backlash_basis
    c, rms = _lstsq(cols, np.concatenate([ccw, cw]))
    return (float(c[4]), float(c[3]), float(c[8]), float(c[9]), rms, _hysteresis(phi, ccw, cw))


def _harmonics(phi: np.ndarray) -> np.ndarray:
    return np.column_stack([np.ones_like(phi), np.cos(phi), np.sin(phi), np.cos(2 * phi),
                            np.sin(2 * phi)])


#: |sin φ| (|cos φ|) below this: the sample sits on the reversal point of X (Y), radians.
REVERSAL_TOL = 1e-9


def _backlash_basis(phi: np.ndarray, direction: str = "ccw") -> np.ndarray:
    """Δr per unit reversal value of X and Y in a run, columns B_x, B_y.

    The axis sits on the side of its last motion (lost motion, ``LinearAxis``):
    ``δx = (b_x/2) s_x`` with ``s_x`` the sign of X's velocity, ``v_x = -sin φ`` CCW and
    ``+sin φ`` CW, so ``B_x = -(1/2) sign(sin φ) cos φ`` CCW and the opposite CW. On a reversal
    point itself (φ = 0° or 180° for X, 90° or 270° for Y, within :data:`REVERSAL_TOL`) the
    velocity is zero but the axis still carries the backlash of the side it approached from,
    the same in both directions: X at +R was reached moving +X, so ``s_x = sign(cos φ)`` and
    ``B_x = +1/2`` (ISO 230-4:2005 Annex, reversal at the quadrant points; issue 21).
    """
    s, c = np.sin(phi), np.cos(phi)
    sx, sy = velocity_signs(s, c, 1.0 if direction == "ccw" else -1.0)
    return np.column_stack([0.5 * sx * c, 0.5 * sy * s])


def velocity_signs(s: np.ndarray, c: np.ndarray, sense: float) -> tuple[np.ndarray, np.ndarray]:
    """Signs of the X and Y velocities at ``sin φ = s``, ``cos φ = c`` of a run contoured
    counter-clockwise (``sense = +1``) or clockwise (``-1``): ``v_x ∝ -sense·sin φ``,
    ``v_y ∝ sense·cos φ``; on a reversal point the side it was approached from (as
    :func:`_backlash_basis`)."""
    sx = np.where(np.abs(s) < REVERSAL_TOL, np.sign(c), -sense * np.sign(s))
    sy = np.where(np.abs(c) < REVERSAL_TOL, np.sign(s), sense * np.sign(c))
    return sx, sy


def _lstsq(a: np.ndarray, b: np.ndarray) -> tuple[np.ndarray, float]:
    """Least squares by the normal equations (a handful of columns of order one, well
    conditioned: a 10-column product instead of an SVD of every reading)."""
    g, r = normal_equations(a, b)
    c = np.linalg.lstsq(g, r, rcond=None)[0]
    res = b - block_product(a, c)
    return c, float(np.sqrt(np.mean(res**2)))


#: Rows per block of :func:`normal_equations` and :func:`block_product`: 256 rows of the
#: diagnosis's 33 columns keep OpenBLAS on the calling thread; 512 woke its threads (measured).
_BLOCK_ROWS = 256


def normal_equations(a: np.ndarray, b: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """``AᵀA`` and ``Aᵀb``, summed over blocks of :data:`_BLOCK_ROWS` rows.

    A block is below the size at which OpenBLAS splits a product over threads: on a machine
    whose cores are busy, the split product of 20,000 × 33 readings waited 20–400 ms for its
    threads instead of 1.4 ms (axiscal's benchmarks, 2026-11-24), and threads once woken spin on
    for a while, taking a busy core from what follows; by blocks it takes 1.4 ms loaded or not.
    Every product over the readings in this module and the ballbar diagnosis is kept below that
    size (this, :func:`block_product`, ``einsum`` for sums of products)."""
    n = a.shape[0]
    g = np.zeros((a.shape[1], a.shape[1]))
    r = np.zeros((a.shape[1],) + b.shape[1:])
    for i in range(0, n, _BLOCK_ROWS):
        blk = a[i:i + _BLOCK_ROWS]
        g += blk.T @ blk
        r += blk.T @ b[i:i + _BLOCK_ROWS]
    return g, r


def block_product(a: np.ndarray, c: np.ndarray) -> np.ndarray:
    """``A c`` by blocks of :data:`_BLOCK_ROWS` rows (as :func:`normal_equations`, and for the
    same reason: a 20,000 × 17 product kept two OpenBLAS threads spinning for 19 ms)."""
    out = np.empty((a.shape[0],) + c.shape[1:])
    for i in range(0, a.shape[0], _BLOCK_ROWS):
        out[i:i + _BLOCK_ROWS] = a[i:i + _BLOCK_ROWS] @ c
    return out


def _circular_deviations(run: CircularRun) -> tuple[float, float]:
    """G about the minimum-zone centre and about the least-squares centre.

    Minimum zone: min over (a, b) of max - min of Δr - a cos φ - b sin φ (an LP), started from
    the least-squares centre: the LP then solves for a small correction on data of unit spread,
    whatever the radius offset (a constant moves both envelope circles alike)."""
    cos, sin = np.cos(run.angles), np.sin(run.angles)
    h3 = np.column_stack([np.ones_like(cos), cos, sin])
    c0, _ = _lstsq(h3, run.deviations)
    d = run.deviations - h3 @ c0
    g_lsc = float(d.max() - d.min())
    scale = float(np.ptp(d))
    if not scale > 0:
        return 0.0, g_lsc
    dn = d / scale
    # constraint generation: the LP on the extreme readings, then add any reading outside the
    # zone found and solve again; the zone of the subset enclosing every reading is the exact one
    k = min(d.size // 2, 100)
    part = np.argpartition(dn, (k, d.size - k - 1)) if d.size > 2 * k + 1 else np.arange(d.size)
    active = np.zeros(d.size, bool)
    active[part[:k + 1]] = active[part[-k - 1:]] = True
    while True:
        x = _zone_lp(cos[active], sin[active], dn[active])
        if x is None:  # pragma: no cover - a bounded LP with a feasible start always solves
            return g_lsc, g_lsc
        r = dn - x[0] * cos - x[1] * sin
        out = (r > x[2] + 1e-12) | (r < x[3] - 1e-12)
        if not out[~active].any():
            break
        active |= out
    r = d - (x[0] * scale) * cos - (x[1] * scale) * sin
    return float(r.max() - r.min()), g_lsc


def _zone_lp(cos, sin, dn):
    """Variables a, b, u, l: minimise u - l with l <= dn - a cos - b sin <= u (HiGHS)."""
    from scipy.optimize import linprog

    ones, zeros = np.ones_like(dn), np.zeros_like(dn)
    a_ub = np.vstack([np.column_stack([-cos, -sin, -ones, zeros]),
                      np.column_stack([cos, sin, zeros, ones])])
    res = linprog([0, 0, 1, -1], A_ub=a_ub, b_ub=np.concatenate([-dn, dn]),
                  bounds=[(None, None)] * 4, method="highs")
    return res.x if res.success else None


def _common(ccw: CircularRun, cw: CircularRun, arc: float):
    """Both runs on the CCW run's angles (the CW run interpolated, periodically on full circles)."""
    phi = ccw.angles
    a, d = np.mod(cw.angles, 2 * np.pi), cw.deviations
    order = np.argsort(a)
    a, d = a[order], d[order]
    if arc >= 360.0 - 1e-9:
        cw_on = np.interp(np.mod(phi, 2 * np.pi), a, d, period=2 * np.pi)
        return phi, ccw.deviations, cw_on
    p = np.mod(phi - a[0], 2 * np.pi) + a[0]  # partial arcs: the overlap only
    inside = (p >= a[0]) & (p <= a[-1])
    if inside.sum() < 8:
        raise InputError("the CCW and CW runs overlap on fewer than 8 angles")
    return phi[inside], ccw.deviations[inside], np.interp(p[inside], a, d)


def _hysteresis(phi, ccw, cw) -> float:
    """Both runs referred to the same centre, so the centre cancels in their difference."""
    return float(np.max(np.abs(ccw - cw)))


def _frozen(a: np.ndarray) -> np.ndarray:
    a = np.array(a, dtype=float)
    a.setflags(write=False)
    return a
