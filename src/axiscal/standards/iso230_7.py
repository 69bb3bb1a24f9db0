"""Error motion of an axis of rotation evaluated by ISO 230-7 (fixed sensitive direction).

Input: the five (or six) errors of a rotary axis measured at equally spaced angles over one full
turn, for one or more runs (revolutions), as :class:`MotionErrorData`. Output: for radial, axial
and tilt error motion the **total**, **synchronous** and **asynchronous** error motion values, the
location errors of the **axis average line** (offsets and tilts), the angular positioning summary
and the data of the polar and linear plots.

Definitions used (ISO 230-7:2015, clause 3 and 5, fixed sensitive direction; linearised because the
error motions are many orders below any plot base radius):

* synchronous error motion: the mean over runs at each angle (the part that repeats each turn);
* asynchronous error motion: each run minus the synchronous curve; its value is the largest width,
  over the angles, of the band the runs span at one angle (max − min across runs);
* total error motion value: the peak-to-valley of every run about the polar-chart (PC) centre;
  synchronous value: peak-to-valley of the synchronous curve;
* the fundamental (once-per-turn) component is removed from **radial** and **tilt** error motion (it
  is the centring/tilt of the target against the axis, not a motion of the axis; its amplitude is
  reported as ``fundamental``); it is kept in **axial** error motion (ISO 230-7 fundamental axial
  error motion is part of it). The fundamental is fitted by least squares to the synchronous curve
  and the same sinusoid removed from every run, which puts the PC centre at the least-squares
  circle centre;
* location errors of the axis average line: the mean over the turn of the synchronous radial
  motions (offsets x0, y0) and tilt motions (tilts a0 about X, b0 about Y). A measurement that
  zeros its readings at the first angle gives them relative to that zero.

All quantities are SI (metres, radians). Pure: no I/O, clock or randomness.

References
----------
ISO 230-7:2015, Test code for machine tools — Part 7: Geometric accuracy of axes of rotation,
clauses 3.1-3.5 (error motion, synchronous/asynchronous, fundamental), 5.4 (polar plots, PC centre)
and 3.3 (axis average line). Optics Express 2018, Five-DOF motion errors of a rotary axis, section 1 and Fig. 1 (the six motion
errors εz, εx, εy, δx, δy, δz of an axis about Z).

Examples
--------
>>> import numpy as np
>>> th = np.radians(np.arange(0, 360, 30.0))
>>> runs = np.vstack([1e-6 * np.cos(2 * th), 1e-6 * np.cos(2 * th) + 0.2e-6])
>>> z = np.zeros((2, th.size))
>>> r = evaluate(MotionErrorData(th, ez=z, ey=z, ex=z, dy=runs, dz=z))
>>> round(r.motion("radial Y").synchronous * 1e6, 3), round(r.motion("radial Y").asynchronous * 1e6, 3)
(2.0, 0.2)
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from axiscal.errors import InputError, InsufficientRunsError
from axiscal.units import ARCSEC, UM

__all__ = ["MotionErrorData", "ErrorMotionValue", "LocationErrors", "PositioningSummary",
           "Iso230_7Result", "evaluate", "fundamental", "polar_coordinates", "halfrange"]

_CHANNELS = ("ez", "ey", "ex", "dy", "dz", "dx")


@dataclass(frozen=True, eq=False)
class MotionErrorData:
    """Five (optionally six) errors of a rotary axis per run and angle (SI).

    Attributes
    ----------
    theta : ndarray, shape (M,), radians
        Commanded angles, strictly increasing, equally spaced over one turn; a last angle of
        ``theta[0] + 2π`` (closing the circle) is allowed.
    ez, ey, ex : ndarray, shape (R, M), radians
        Angular positioning error, tilt error motion about Y and about X.
    dy, dz : ndarray, shape (R, M), metres
        Radial error motion along Y (fixed sensitive direction) and axial error motion.
    dx : ndarray, shape (R, M), metres, optional
        Radial error motion along X, when the instrument measures it (Optics Express 2018, Five-DOF motion errors of a rotary axis's does not).
    title : str
    """

    theta: np.ndarray
    ez: np.ndarray
    ey: np.ndarray
    ex: np.ndarray
    dy: np.ndarray
    dz: np.ndarray
    dx: np.ndarray | None = None
    title: str = ""

    def __post_init__(self) -> None:
        th = np.asarray(self.theta, dtype=float).ravel()
        if th.size < 4 or not np.all(np.isfinite(th)):
            raise InputError(f"{th.size} angle(s); ISO 230-7 evaluation needs at least 4 finite "
                             "angles over one turn")
        if np.any(np.diff(th) <= 0):
            raise InputError("angles must be strictly increasing")
        object.__setattr__(self, "theta", _ro(th))
        for name in _CHANNELS:
            v = getattr(self, name)
            if v is None:
                continue
            a = np.atleast_2d(np.asarray(v, dtype=float))
            if a.shape[1] != th.size:
                raise InputError(f"channel {name} has {a.shape[1]} angles per run; theta has {th.size}")
            if not np.all(np.isfinite(a)):
                raise InputError(f"channel {name} holds NaN or infinite values; ISO 230-7 needs "
                                 "every angle of every run")
            if a.shape[0] != np.atleast_2d(np.asarray(self.ez)).shape[0]:
                raise InputError(f"channel {name} has {a.shape[0]} runs, ez has "
                                 f"{np.atleast_2d(np.asarray(self.ez)).shape[0]}")
            object.__setattr__(self, name, _ro(a))

    @property
    def n_runs(self) -> int:
        """Number of runs (revolutions)."""
        return int(self.ez.shape[0])


@dataclass(frozen=True)
class ErrorMotionValue:
    """ISO 230-7 values of one error motion (metres for radial/axial, radians for tilt).

    Attributes
    ----------
    name : str
        ``"radial Y"``, ``"radial X"``, ``"axial"``, ``"tilt X"`` or ``"tilt Y"``.
    kind : str
        ``"length"`` or ``"angle"``.
    total, synchronous, asynchronous : float
        Error motion values; ``asynchronous`` is NaN for a single run.
    fundamental : float
        Amplitude of the once-per-turn component of the synchronous curve.
    fundamental_removed : bool
        True for radial and tilt error motion.
    synchronous_curve : ndarray, shape (M,)
        Mean over runs, fundamental removed where it is, about the PC centre (mean zero).
    runs : ndarray, shape (R, M)
        Every run treated the same way (for the total and asynchronous plots).
    """

    name: str
    kind: str
    total: float
    synchronous: float
    asynchronous: float
    fundamental: float
    fundamental_removed: bool
    synchronous_curve: np.ndarray
    runs: np.ndarray

    def __str__(self) -> str:
        k, u = (UM, "µm") if self.kind == "length" else (ARCSEC, "arcsec")
        asy = "—" if math.isnan(self.asynchronous) else f"{self.asynchronous / k:.3f}"
        tag = "removed" if self.fundamental_removed else "kept"
        return (f"{self.name:<9} total {self.total / k:8.3f}  synchronous {self.synchronous / k:8.3f}  "
                f"asynchronous {asy:>8} {u}  (fundamental {self.fundamental / k:.3f} {u}, {tag})")


@dataclass(frozen=True)
class LocationErrors:
    """Location of the axis average line (relative to the instrument zero), SI.

    Attributes
    ----------
    x0, y0 : float, metres
        Offsets along X and Y (x0 is NaN when δx was not measured).
    a0, b0 : float, radians
        Tilts about X and about Y.
    """

    x0: float
    y0: float
    a0: float
    b0: float

    def __str__(self) -> str:
        x0 = "—" if math.isnan(self.x0) else f"{self.x0 / UM:.3f}"
        return (f"axis average line: x0 {x0} µm, y0 {self.y0 / UM:.3f} µm, "
                f"a0 {self.a0 / ARCSEC:.3f} arcsec, b0 {self.b0 / ARCSEC:.3f} arcsec")


@dataclass(frozen=True)
class PositioningSummary:
    """Angular positioning error εz per angle over the runs (radians).

    Attributes
    ----------
    mean : ndarray, shape (M,)
        Mean over runs at each angle.
    range : float
        Max − min of ``mean`` (the systematic positioning error over the turn).
    repeatability : float
        Largest half-range across runs at one angle (the paper's "± repeatability deviation"),
        NaN for one run.
    """

    mean: np.ndarray
    range: float
    repeatability: float

    def __str__(self) -> str:
        rep = "—" if math.isnan(self.repeatability) else f"±{self.repeatability / ARCSEC:.2f}"
        return (f"positioning εz: range {self.range / ARCSEC:.2f} arcsec, "
                f"repeatability {rep} arcsec")


@dataclass(frozen=True)
class Iso230_7Result:
    """The ISO 230-7 evaluation of one motion-error measurement.

    Attributes
    ----------
    theta : ndarray, shape (M,), radians
        The angles of one turn (a closing 360° angle removed).
    motions : tuple of ErrorMotionValue
    location : LocationErrors
    positioning : PositioningSummary
    n_runs : int
    closure : dict of str to float
        Largest |value at 360° − value at 0°| per channel over the runs (SI), when the data
        closed the circle; empty otherwise.
    warnings : tuple of str
    """

    theta: np.ndarray
    motions: tuple[ErrorMotionValue, ...]
    location: LocationErrors
    positioning: PositioningSummary
    n_runs: int
    closure: dict
    warnings: tuple[str, ...]

    def motion(self, name: str) -> ErrorMotionValue:
        """The values of the error motion called ``name`` (``"radial Y"``, ``"axial"`` ...)."""
        for m in self.motions:
            if m.name == name:
                return m
        raise InputError(f"no error motion {name!r}; have {[m.name for m in self.motions]}")

    def __str__(self) -> str:
        lines = [f"ISO 230-7 error motion, {self.n_runs} run(s), {self.theta.size} angles per turn"]
        lines += [str(m) for m in self.motions]
        lines += [str(self.location), str(self.positioning)]
        lines += [f"warning: {w}" for w in self.warnings]
        return "\n".join(lines)


def evaluate(data: MotionErrorData) -> Iso230_7Result:
    """Evaluate error motions and location errors by ISO 230-7 (see the module docstring).

    Parameters
    ----------
    data : MotionErrorData

    Returns
    -------
    Iso230_7Result

    Raises
    ------
    InputError
        If the angles are not equally spaced over one full turn.
    """
    theta, closing = _one_turn(data.theta)
    warnings = []
    if data.n_runs < 2:
        warnings.append("one run only: asynchronous error motion and repeatability need at "
                        "least 2 runs (not evaluated)")
    closure = {}
    if closing:
        for name in _CHANNELS:
            a = getattr(data, name)
            if a is not None:
                closure[name] = float(np.max(np.abs(a[:, -1] - a[:, 0])))
    m = theta.size
    cut = {name: (None if getattr(data, name) is None else getattr(data, name)[:, :m])
           for name in _CHANNELS}
    specs = [("radial Y", "dy", "length", True), ("radial X", "dx", "length", True),
             ("axial", "dz", "length", False), ("tilt X", "ex", "angle", True),
             ("tilt Y", "ey", "angle", True)]
    motions = tuple(_error_motion(name, theta, cut[ch], kind, remove)
                    for name, ch, kind, remove in specs if cut[ch] is not None)
    mean = lambda a: float(np.mean(a))  # noqa: E731
    location = LocationErrors(
        x0=mean(cut["dx"]) if cut["dx"] is not None else math.nan,
        y0=mean(cut["dy"]), a0=mean(cut["ex"]), b0=mean(cut["ey"]))
    ez_mean = cut["ez"].mean(axis=0)
    positioning = PositioningSummary(_ro(ez_mean), float(np.ptp(ez_mean)),
                                     halfrange(cut["ez"]) if data.n_runs > 1 else math.nan)
    return Iso230_7Result(_ro(theta), motions, location, positioning, data.n_runs, closure,
                          tuple(warnings))


def fundamental(theta, values):
    """Least-squares once-per-turn sinusoid ``a cos θ + b sin θ`` of ``values`` (mean removed).

    Parameters
    ----------
    theta : array_like, radians (equally spaced over one turn)
    values : array_like, shape (M,)

    Returns
    -------
    ndarray, shape (M,), unit of ``values``
        The fitted fundamental at ``theta``.

    Notes
    -----
    ISO 230-7:2015 §3 (fundamental error motion; the once-per-revolution sinusoid whose removal
    puts the polar-chart centre at the least-squares circle centre): least squares on
    ``[1, cos θ, sin θ]``, the constant dropped.

    Examples
    --------
    >>> th = np.radians(np.arange(0, 360, 45.0))
    >>> np.allclose(fundamental(th, 3 + 2 * np.sin(th) + np.cos(3 * th)), 2 * np.sin(th))
    True
    """
    th = np.asarray(theta, float)
    y = np.asarray(values, float)
    a = np.column_stack([np.ones_like(th), np.cos(th), np.sin(th)])
    coef, *_ = np.linalg.lstsq(a, y, rcond=None)
    return a[:, 1:] @ coef[1:]


def polar_coordinates(theta, values, base_radius: float, gain: float):
    """Cartesian points of a polar error-motion plot: radius ``base + gain·value`` at angle θ.

    Parameters
    ----------
    theta : array_like, radians
    values : array_like (about the PC centre, SI)
    base_radius : float (plot units)
    gain : float (plot units per SI unit)

    Returns
    -------
    x, y : ndarray, plot units

    Notes
    -----
    ISO 230-7:2015 §5.4 polar plot: radius = base circle + gain × error motion, at the angle of
    rotation (the error motions being many orders below the base radius).
    """
    th = np.asarray(theta, float)
    r = base_radius + gain * np.asarray(values, float)
    return r * np.cos(th), r * np.sin(th)


def halfrange(runs) -> float:
    """Largest half-range across runs at one angle: the ± repeatability deviation.

    Parameters
    ----------
    runs : array_like, shape (R, M), any unit

    Returns
    -------
    float, unit of ``runs``
        ``max over angles of (max − min across runs) / 2``.

    Raises
    ------
    InsufficientRunsError
        Fewer than 2 runs.

    Notes
    -----
    Optics Express 2018, Five-DOF motion errors of a rotary axis, section 3, "Repeatability experiments" (the "deviation of repeatability" ± of three
    runs, Fig. 7); the paper does not define it further, half the spread is axiscal's reading.

    Examples
    --------
    >>> halfrange([[0.0, 1.0], [2.0, 1.5], [1.0, 1.2]])
    1.0
    """
    a = np.asarray(runs, float)
    if a.ndim != 2 or a.shape[0] < 2:
        raise InsufficientRunsError(f"{a.shape[0] if a.ndim == 2 else 1} run(s); a repeatability "
                                    "deviation needs at least 2")
    return float(0.5 * np.max(np.ptp(a, axis=0)))


def _error_motion(name, theta, runs, kind, remove) -> ErrorMotionValue:
    sync = runs.mean(axis=0)
    fund = fundamental(theta, sync)
    amp = float(np.sqrt(2.0 * np.mean(fund**2)))
    centre = sync.mean()
    treated = runs - centre - (fund if remove else 0.0)
    sync_t = treated.mean(axis=0)
    asyn = float(np.max(np.ptp(treated, axis=0))) if runs.shape[0] > 1 else math.nan
    return ErrorMotionValue(name, kind, float(np.ptp(treated)), float(np.ptp(sync_t)), asyn, amp,
                            remove, _ro(sync_t), _ro(treated))


def _one_turn(theta):
    th = np.asarray(theta, float)
    closing = math.isclose(th[-1] - th[0], 2 * math.pi, abs_tol=1e-9)
    one = th[:-1] if closing else th
    step = 2 * math.pi / one.size
    if not np.allclose(np.diff(one), step, atol=1e-9) or (
            not closing and not math.isclose(th[-1] - th[0] + step, 2 * math.pi, abs_tol=1e-9)):
        raise InputError(
            f"angles must be equally spaced over one full turn (for {one.size} angles a step of "
            f"{math.degrees(step):g} deg); got {np.round(np.degrees(th), 6).tolist()} deg")
    return one, closing


def _ro(a):
    a = np.array(a, dtype=float)
    a.flags.writeable = False
    return a
