"""The XY plane of a machine with squareness, straightness and associated yaw (Chapman, Calibration of machine squareness Appendix I).

Coordinates are centred: a plane of lengths ``Lx × Ly`` spans ``x ∈ [-Lx/2, Lx/2]``,
``y ∈ [-Ly/2, Ly/2]`` (metres), so the quadratic bend of Appendix I, ``δy = 4 S x² / L²``
(Equation 1, x measured from the middle of the axis), is zero in the middle and ``S`` at both ends.

A machine commanded to ``(x, y)`` reaches ``(x + δx, y + δy)`` with (Appendix I, generalised)::

    δx = -y (θ0 + [yaw_x] f'(x)) + g(y) + e_x x + (b_x / 2) sign(v_x)
    δy =  f(x) - [yaw_y] x g'(y) + e_y y + (b_y / 2) sign(v_y)

* ``θ0`` — global squareness, rad, positive when the angle between +X and +Y exceeds 90° (seed
  004's convention; Equation 2's ``δx = -y θ0``).
* ``f`` — straightness of X (deviation along Y as a function of x), Equation 1 or any profile.
* ``g`` — straightness of Y (deviation along X as a function of y), the same forms.
* ``[yaw_x]`` — X carries the work-holder, so the yaw ``θ = f'(x)`` of the X carriage turns the
  Y axis above it (Equation 2, ``δx = -y(θ0 + 8Sx/L²)``); without it Equation 4.
* ``[yaw_y]`` — the same for Y: the yaw ``-g'(y)`` of the Y carriage (counter-clockwise positive)
  turns the X axis it carries, ``δy = -x g'(y)``. Appendix I says this is "derived in a similar
  way" and gives no equation; this sign is the one for which a rigid body keeps the local
  squareness uniform (Chapman, Calibration of machine squareness, Machine 5: "uniform local and global squareness").
* ``e_x``, ``e_y`` — linear (scale) errors, for scale mismatch; ``b_x``, ``b_y`` — reversal
  values (backlash) with the convention of :class:`~axiscal.machines.linear.LinearAxis`
  (a positive approach lands ``b/2`` further on).

The local squareness (angle between the local X and Y directions minus 90°) is then
``θ0 + [yaw_x] f' - g' - f' + [yaw_y] g'``: uniform where every bend carries its yaw (Machines 3
and 5), varying with location where none does (Machines 2 and 4).

References
----------
Chapman, Calibration of machine squareness, Appendix I, Equations 1-4 and Figures 28-29; "Simulation of machine errors" (Figure 12)
and "Testing global squareness errors on machines with unequal aspect ratios" (Machines 6 and 7).
"""

from __future__ import annotations

from dataclasses import dataclass, replace
from typing import Protocol

import numpy as np

from axiscal.errors import InputError

__all__ = [
    "StraightnessProfile",
    "QuadraticBend",
    "TabulatedProfile",
    "airy_points_bend",
    "XYPlaneMachine",
    "seed004_machine",
    "SEED004_STRAIGHTNESS",
]

#: Straightness values chosen for Chapman, Calibration of machine squareness's machines, metres (the paper gives only some; see
#: :func:`seed004_machine`).
SEED004_STRAIGHTNESS = {"x": 10e-6, "y": 5e-6}


class StraightnessProfile(Protocol):
    """A straightness deviation along an axis, as a function of the centred position (metres)."""

    def __call__(self, u: np.ndarray) -> np.ndarray: ...  # pragma: no cover

    def slope(self, u: np.ndarray) -> np.ndarray: ...  # pragma: no cover


@dataclass(frozen=True)
class QuadraticBend:
    """The simple bend of Chapman, Calibration of machine squareness Equation 1: ``δ = 4 S u² / L²``, slope ``8 S u / L²``.

    Attributes
    ----------
    straightness : float, m
        S: the deviation at both ends relative to the middle (the straightness deviation).
    length : float, m
        L: the length of the axis.

    Examples
    --------
    >>> b = QuadraticBend(10e-6, 0.8)
    >>> float(b(0.4)) * 1e6, round(float(b.slope(0.4)) * 1e6, 6)   # 10 µm, 50 µm/m at the end
    (10.0, 50.0)
    """

    straightness: float
    length: float

    def __post_init__(self):
        if not self.length > 0:
            raise InputError(f"length={self.length!r} m: must be positive")

    def __call__(self, u):
        return 4.0 * self.straightness * np.asarray(u, dtype=float) ** 2 / self.length**2

    def slope(self, u):
        return 8.0 * self.straightness * np.asarray(u, dtype=float) / self.length**2


@dataclass(frozen=True, eq=False)
class TabulatedProfile:
    """Any user-given straightness profile, interpolated by a cubic spline (not-a-knot ends).

    Attributes
    ----------
    positions : numpy.ndarray, m
        Centred positions along the axis, strictly increasing (at least 4).
    deviations : numpy.ndarray, m
        Straightness deviation at each position.

    Examples
    --------
    >>> u = np.linspace(-0.4, 0.4, 9)
    >>> p = TabulatedProfile(u, 4 * 10e-6 * u**2 / 0.64)
    >>> round(float(p.slope(0.2)) * 1e6, 3)
    25.0
    """

    positions: np.ndarray
    deviations: np.ndarray

    def __post_init__(self):
        u = np.asarray(self.positions, dtype=float)
        d = np.asarray(self.deviations, dtype=float)
        if u.ndim != 1 or u.shape != d.shape or u.size < 4:
            raise InputError(f"profile needs at least 4 positions and as many deviations "
                             f"(got {u.size} and {d.size})")
        if not (np.all(np.diff(u) > 0) and np.isfinite(d).all()):
            raise InputError("profile positions must increase strictly and deviations be finite")
        from scipy.interpolate import CubicSpline

        object.__setattr__(self, "positions", u)
        object.__setattr__(self, "deviations", d)
        object.__setattr__(self, "_spline", CubicSpline(u, d))

    def __call__(self, u):
        return self._spline(np.asarray(u, dtype=float))

    def slope(self, u):
        return self._spline(np.asarray(u, dtype=float), 1)


def airy_points_bend(length: float, straightness: float, n: int = 401) -> TabulatedProfile:
    """Self-weight bend of an axis resting on its Airy points (Chapman, Calibration of machine squareness, Machine 7).

    A uniform beam of length L on two supports ``L/√3`` apart (the Airy points, where the end
    slopes are zero) sags between them and droops beyond them; the elastic line is integrated
    from the bending moment and scaled so that its peak-to-valley is ``straightness``.

    Parameters
    ----------
    length : float, m
        Axis length L.
    straightness : float, m
        Peak-to-valley of the profile (its minimum-zone straightness). Positive: the physical
        shape under gravity, the middle sagging lowest and the ends (whose slope is zero) highest,
        like a positive :class:`QuadraticBend`.
    n : int
        Number of tabulated points.

    Returns
    -------
    TabulatedProfile
        Symmetric about the middle of the axis.

    Notes
    -----
    Chapman, Calibration of machine squareness says only that Machine 7's X axis has "a more complex form of straightness error,
    such as might be shown by an axis supported at its airy points"; the shape is the classical
    beam solution, ``EI w'' = M(u)`` with ``M = -q (L/2 - |u|)² / 2 + R (c - |u|)`` inside the
    supports at ``±c = ±L/(2√3)``, ``R = qL/2`` (sagging moment positive, ``w'' = M/EI``).

    Examples
    --------
    >>> p = airy_points_bend(0.75, 10e-6)
    >>> round(float(np.ptp(p(np.linspace(-0.375, 0.375, 1001)))) * 1e6, 3)
    10.0
    >>> bool(abs(p.slope(0.375)) < 0.01 * np.abs(p.slope(np.linspace(0, 0.375, 50))).max())
    True
    """
    if not length > 0:
        raise InputError(f"length={length!r} m: must be positive")
    u = np.linspace(-length / 2, length / 2, int(n))
    half, c = length / 2, length / (2 * np.sqrt(3.0))
    a = np.abs(u)
    moment = -0.5 * (half - a) ** 2 + half * np.clip(c - a, 0.0, None)  # q = 1, R = L/2
    from scipy.integrate import cumulative_trapezoid

    slope = cumulative_trapezoid(moment, u, initial=0.0)
    slope -= np.interp(0.0, u, slope)  # symmetric: zero slope in the middle
    w = cumulative_trapezoid(slope, u, initial=0.0)
    w -= np.interp(c, u, w)  # supports at zero
    return TabulatedProfile(u, w * (float(straightness) / np.ptp(w)))


@dataclass(frozen=True)
class XYPlaneMachine:
    """A simulated XY plane with the errors of Chapman, Calibration of machine squareness Appendix I (module docstring).

    Attributes
    ----------
    length_x, length_y : float, m
        Axis lengths; the plane is centred on (0, 0).
    squareness : float, rad
        θ0, positive when the angle between +X and +Y exceeds 90°.
    x_straightness, y_straightness : StraightnessProfile or None
        f(x) (deviation along Y) and g(y) (deviation along X), metres.
    x_yaw, y_yaw : bool
        Whether the axis carries the work-holder, so its associated yaw distorts the plane.
    scale_x, scale_y : float, m/m
        Linear positioning errors.
    backlash_x, backlash_y : float, m
        Reversal values.
    name : str
        A label.

    Examples
    --------
    >>> m = seed004_machine(3)
    >>> dx, dy = m.deviation(0.4, 0.4)
    >>> round(float(dx) * 1e6, 3), round(float(dy) * 1e6, 3)   # -0.4 (15 + 50) µm/m, 10 µm
    (-26.0, 10.0)
    """

    length_x: float = 0.8
    length_y: float = 0.8
    squareness: float = 0.0
    x_straightness: StraightnessProfile | None = None
    y_straightness: StraightnessProfile | None = None
    x_yaw: bool = False
    y_yaw: bool = False
    scale_x: float = 0.0
    scale_y: float = 0.0
    backlash_x: float = 0.0
    backlash_y: float = 0.0
    name: str = ""

    def __post_init__(self):
        for key in ("length_x", "length_y"):
            v = getattr(self, key)
            if not (np.isfinite(v) and v > 0):
                raise InputError(f"{key}={v!r} m: must be positive")
        for key in ("squareness", "scale_x", "scale_y", "backlash_x", "backlash_y"):
            v = getattr(self, key)
            if not np.isfinite(v) or abs(v) > 0.01:
                raise InputError(f"{key}={v!r}: must be finite and small (|value| <= 0.01); "
                                 "the model is first order")

    @property
    def x_range(self) -> tuple[float, float]:
        """Travel of X, metres."""
        return (-self.length_x / 2, self.length_x / 2)

    @property
    def y_range(self) -> tuple[float, float]:
        """Travel of Y, metres."""
        return (-self.length_y / 2, self.length_y / 2)

    def deviation(self, x, y, vx=0.0, vy=0.0) -> tuple[np.ndarray, np.ndarray]:
        """Positioning deviations (δx, δy), metres, at commanded (x, y) moving with (vx, vy).

        Only the signs of ``vx`` and ``vy`` matter (backlash); 0 means at rest (no reversal term).
        """
        x, y = np.broadcast_arrays(np.asarray(x, float), np.asarray(y, float))
        f, fs = _profile(self.x_straightness, x)
        g, gs = _profile(self.y_straightness, y)
        yaw_x = fs if self.x_yaw else 0.0
        yaw_y = gs if self.y_yaw else 0.0
        dx = -y * (self.squareness + yaw_x) + g + self.scale_x * x
        dy = f - x * yaw_y + self.scale_y * y
        dx = dx + 0.5 * self.backlash_x * np.sign(vx)
        dy = dy + 0.5 * self.backlash_y * np.sign(vy)
        return dx, dy

    def actual(self, x, y, vx=0.0, vy=0.0) -> tuple[np.ndarray, np.ndarray]:
        """Actual position reached for commanded (x, y), metres (see :meth:`deviation`)."""
        dx, dy = self.deviation(x, y, vx, vy)
        return np.asarray(x, float) + dx, np.asarray(y, float) + dy

    def local_squareness(self, x, y) -> np.ndarray:
        """True local squareness at (x, y), rad (angle between local +X and +Y minus 90°)."""
        _, fs = _profile(self.x_straightness, np.asarray(x, float))
        _, gs = _profile(self.y_straightness, np.asarray(y, float))
        tilt_y = self.squareness + (fs if self.x_yaw else 0.0) - gs  # +Y turned towards -X
        tilt_x = fs - (gs if self.y_yaw else 0.0)  # +X turned towards +Y
        return np.asarray(tilt_y - tilt_x, dtype=float)

    def with_(self, **changes) -> XYPlaneMachine:
        """A copy with some attributes changed."""
        return replace(self, **changes)

    def __str__(self) -> str:
        parts = [f"{self.name or 'XY plane'}: {self.length_x * 1e3:g} × {self.length_y * 1e3:g} mm",
                 f"squareness {self.squareness * 1e6:+.2f} µm/m"]
        for ax, prof, yaw in (("X", self.x_straightness, self.x_yaw),
                              ("Y", self.y_straightness, self.y_yaw)):
            if prof is not None:
                parts.append(f"{ax} straightness {_describe(prof)}"
                             f" {'with' if yaw else 'without'} associated yaw")
        return ", ".join(parts)


def seed004_machine(number: int, *, x_yaw: bool | None = None,
                    y_yaw: bool | None = None) -> XYPlaneMachine:
    """Machines 1-7 of Chapman, Calibration of machine squareness (Figure 12, Figures 24-25), global squareness +15 µm/m.

    ======  ==============  =========================================  ========================
    number  plane (mm)      straightness                               associated yaw
    ======  ==============  =========================================  ========================
    1       800 × 800       none                                       —
    2       800 × 800       X 10 µm (Equation 1)                       no
    3       800 × 800       X 10 µm                                    X
    4       800 × 800       X 10 µm, Y 5 µm                            no
    5       800 × 800       X 10 µm, Y 5 µm                            X and Y
    6       750 × 250       X 10 µm, Y 5 µm (seed values)              no
    7       750 × 250       X 10 µm Airy-point bend, Y 5 µm            no
    ======  ==============  =========================================  ========================

    Parameters
    ----------
    number : int
        1 to 7.
    x_yaw, y_yaw : bool, optional
        Override the associated yaw (Chapman, Calibration of machine squareness also reports Machine 7 with both yaws added).

    Notes
    -----
    The paper gives the straightness values of Machines 6 and 7 only. Machine 3's angle running
    from -35 to +65 µm/m along X (seed, Figure 16) fixes X's bend: ``4S/L = 50 µm/m`` gives
    S = 10 µm on 800 mm, the value of Machine 6 too. Y's 5 µm for Machines 4 and 5 is taken from
    Machine 6 (a choice; any value gives the same qualitative findings). Bends are positive
    (ends high), as Machine 3's -35 at the left and +65 at the right require.

    Examples
    --------
    >>> print(seed004_machine(6))
    Machine 6: 750 × 250 mm, squareness +15.00 µm/m, X straightness quadratic 10 µm without associated yaw, Y straightness quadratic 5 µm without associated yaw
    """
    if number not in range(1, 8):
        raise InputError(f"machine={number!r}: Chapman, Calibration of machine squareness defines machines 1 to 7")
    lx, ly = (0.8, 0.8) if number <= 5 else (0.75, 0.25)
    sx, sy = SEED004_STRAIGHTNESS["x"], SEED004_STRAIGHTNESS["y"]
    xs = None if number == 1 else QuadraticBend(sx, lx)
    if number == 7:
        xs = airy_points_bend(lx, sx)
    ys = QuadraticBend(sy, ly) if number in (4, 5, 6, 7) else None
    yaw = {3: (True, False), 5: (True, True)}.get(number, (False, False))
    return XYPlaneMachine(
        length_x=lx, length_y=ly, squareness=15e-6, x_straightness=xs, y_straightness=ys,
        x_yaw=yaw[0] if x_yaw is None else bool(x_yaw),
        y_yaw=yaw[1] if y_yaw is None else bool(y_yaw), name=f"Machine {number}")


def _profile(profile, u):
    if profile is None:
        z = np.zeros_like(np.asarray(u, dtype=float))
        return z, z
    return np.asarray(profile(u), dtype=float), np.asarray(profile.slope(u), dtype=float)


def _describe(profile) -> str:
    if isinstance(profile, QuadraticBend):
        return f"quadratic {profile.straightness * 1e6:g} µm"
    if isinstance(profile, TabulatedProfile):
        return f"tabulated {np.ptp(profile.deviations) * 1e6:.3g} µm ({profile.positions.size} points)"
    return type(profile).__name__
