"""Volumetric error of a three-axis machine from its 21 geometric errors (rigid-body model).

A serial three-axis machine has, for each linear axis, six error motions that are functions of
that axis's position alone, and three location errors between the axes (ISO 230-1:2012,
clause 3; the notation is ISO 230-1's): for axis X the positioning error ``EXX``, the two
straightness errors ``EYX`` and ``EZX``, and the angular errors ``EAX`` (roll, about X), ``EBX``
(about Y) and ``ECX`` (about Z); the same for Y and Z; and the squareness errors of the pairs
XY, YZ and ZX. This module assembles them into the error of the tool's functional point relative
to the work-piece at any commanded position, the rigid-body model of ISO/TR 16907:2015 and of
Schwenke et al. (2008).

The kinematic chain
-------------------
A chain is written from the work-piece to the tool, with ``|`` for the machine base: ``"X Y | Z"``
is a moving-table machine (the work-piece on X, X on Y, Y on the base, Z on the base carrying the
tool), ``"| X Y Z"`` a gantry (work-piece on the base, X carrying Y carrying Z carrying the tool).
Going round that loop from the work-piece to the tool, each axis's angular error turns everything
that comes after it: the displacements of the later axes and the tool offset. To first order
(Schwenke et al. 2008, eq. 3; ISO/TR 16907:2015, the rigid-body model of a serial machine)::

    E(q) = Σ_i [ δ_i(q_i) + Δε_i(q_i) × ( Σ_{j after i} (q_j − c_j) e_j + (t − t_m) ) ] + S(q)

* ``δ_i = (EX_i, EY_i, EZ_i)`` the translation errors of axis i as measured along its
  measuring line, ``Δε_i = (EA_i, EB_i, EC_i)`` its angular errors, both referred to the
  reference point ``c`` (zero there);
* ``c`` the commanded position through which every measuring line passed (each axis was
  measured with the other two at ``c``) and ``t_m`` the tool offset used while measuring; ``t``
  the tool offset at which the error is wanted, so the angular errors act through their Abbe
  offsets ``(q_j − c_j)`` and ``t − t_m``;
* ``S(q)`` the squareness: with X as the primary direction and XY as the primary plane,
  ``Sx = −θ_xy (y − c_y) − θ_zx (z − c_z)``, ``Sy = −θ_yz (z − c_z)``, each θ positive when the
  angle between the two positive axis directions exceeds 90° (the sign of Chapman, "Calibration of
  machine squareness", Appendix I, eq. 2: ``δx = −y θ0``).

All 21 functions are relative motions of the tool with respect to the work-piece, as a laser
measures them; straightness is taken relative to its least-squares reference line (ISO 230-1
§3.4.9 reference straight line), whose direction is what the squareness describes, so the model
needs no other alignment. The frame is the machine's own: the X motion is its first direction and
the XY motion plane its first plane.

What a table cannot remove
--------------------------
A controller's compensation tables are functions of one axis each. The part of ``E`` that
depends on one axis only (``δ_i`` and ``Δε_i × (t − t_m)`` at the chosen tool offset, and the
squareness as a linear cross-axis table) can be compensated; the Abbe products
``Δε_i(q_i) × (q_j − c_j) e_j`` depend on two axes and stay (:func:`table_part`).

References
----------
ISO 230-1:2012, Test code for machine tools — Part 1: Geometric accuracy of machines operating
under no-load or quasi-static conditions (notation of error motions and squareness).
ISO/TR 16907:2015, Machine tools — Numerical compensation of geometric errors.
ISO 230-6:2002, Test code for machine tools — Part 6: Determination of positioning accuracy on
body and face diagonals (diagonal displacement tests).
H. Schwenke, W. Knapp, H. Haitjema, A. Weckenmann, R. Schmitt, F. Delbressine, "Geometric error
measurement and compensation of machines — An update", CIRP Annals 57 (2008) 660-675.
M.A.V. Chapman, "Calibration of machine squareness" (Renishaw), Appendices I and II.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from axiscal.errors import ConfigError, InputError

__all__ = [
    "AXES", "TRANSLATIONS", "ROTATIONS", "ERROR_NAMES", "PAIRS",
    "KinematicChain", "ErrorFunction", "GeometricErrors",
    "volumetric_error", "table_part", "VolumetricMap", "map_volume",
    "BodyDiagonal", "body_diagonals", "diagonal_corners",
]

AXES = ("X", "Y", "Z")
#: Translation error names of an axis, in the order of the directions X, Y, Z.
TRANSLATIONS = ("EX", "EY", "EZ")
#: Angular error names (about X, Y, Z).
ROTATIONS = ("EA", "EB", "EC")
#: The 18 error motions, ``EXX`` ... ``ECZ`` (ISO 230-1 notation: error, direction, axis).
ERROR_NAMES = tuple(f"{e}{a}" for a in AXES for e in TRANSLATIONS + ROTATIONS)
#: Squareness pairs, positive when the angle between the positive directions exceeds 90°.
PAIRS = ("xy", "yz", "zx")
#: Largest error a first-order model is taken to describe: 1 mm or 1 mrad.
_LIMIT = 1e-3


@dataclass(frozen=True)
class KinematicChain:
    """The order of the axes from the work-piece to the tool (module docstring).

    Attributes
    ----------
    work_side : tuple of str
        Axes carrying the work-piece, from the work-piece to the base (``("X", "Y")``).
    tool_side : tuple of str
        Axes carrying the tool, from the base to the tool (``("Z",)``).

    Examples
    --------
    >>> c = KinematicChain.parse("X Y | Z")
    >>> c.loop, c.after("X"), c.after("Z"), str(c)
    (('X', 'Y', 'Z'), ('Y', 'Z'), (), 'X Y | Z')
    >>> KinematicChain.parse("|XYZ").after("X")
    ('Y', 'Z')
    """

    work_side: tuple[str, ...]
    tool_side: tuple[str, ...]

    @classmethod
    def parse(cls, text: str) -> "KinematicChain":
        """Read ``"X Y | Z"`` (work-piece side, ``|`` for the base, tool side)."""
        if not isinstance(text, str) or text.count("|") != 1:
            raise ConfigError(f"chain = {text!r}: write the axes from the work-piece to the tool "
                              "with one '|' for the machine base, e.g. \"X Y | Z\" or \"| X Y Z\"")
        left, right = (tuple(ch for ch in part.upper() if not ch.isspace())
                       for part in text.split("|"))
        axes = left + right
        if sorted(axes) != sorted(AXES):
            raise ConfigError(f"chain = {text!r}: name each of X, Y and Z once")
        return cls(left, right)

    @property
    def loop(self) -> tuple[str, ...]:
        """The axes in loop order, from the work-piece through the base to the tool."""
        return self.work_side + self.tool_side

    def after(self, axis: str) -> tuple[str, ...]:
        """The axes an angular error of ``axis`` turns (those after it in the loop)."""
        loop = self.loop
        return loop[loop.index(axis) + 1:]

    def __str__(self) -> str:
        return f"{' '.join(self.work_side)} | {' '.join(self.tool_side)}".strip()


@dataclass(frozen=True, eq=False)
class ErrorFunction:
    """One error motion tabulated along its axis, interpolated linearly, held beyond the ends.

    Attributes
    ----------
    positions : numpy.ndarray, m
        Positions of the axis, strictly increasing (at least 2).
    values : numpy.ndarray, m or rad
        The error at each position.
    source : str
        Where it came from (a file name, ``"function"``, ``"simulation"``).
    """

    positions: np.ndarray
    values: np.ndarray
    source: str = ""

    def __post_init__(self) -> None:
        u = np.array(self.positions, dtype=float, ndmin=1)
        v = np.array(self.values, dtype=float, ndmin=1)
        if u.ndim != 1 or u.shape != v.shape or u.size < 2:
            raise InputError(f"{self.source or 'error function'}: needs at least 2 positions and "
                             f"as many values (got {u.size} and {v.size})")
        if not (np.isfinite(u).all() and np.isfinite(v).all()):
            raise InputError(f"{self.source or 'error function'}: positions and values must be "
                             "finite numbers")
        if not np.all(np.diff(u) > 0):
            raise InputError(f"{self.source or 'error function'}: positions must increase strictly")
        if np.abs(v).max() > _LIMIT:
            raise InputError(f"{self.source or 'error function'}: an error of "
                             f"{np.abs(v).max():.3g} (m or rad) is beyond what a first-order "
                             f"model describes (at most {_LIMIT:g})")
        for a in (u, v):
            a.flags.writeable = False
        object.__setattr__(self, "positions", u)
        object.__setattr__(self, "values", v)

    def __call__(self, u) -> np.ndarray:
        return np.interp(np.asarray(u, dtype=float), self.positions, self.values)


@dataclass(frozen=True, eq=False)
class GeometricErrors:
    """The 21 geometric errors of a three-axis machine, measured, with their set-up.

    Attributes
    ----------
    chain : KinematicChain
    functions : dict of str to ErrorFunction
        ``EXX`` ... ``ECZ``; a missing one is taken as zero (and listed by :attr:`missing`).
    squareness : dict of str to float, rad
        ``xy``, ``yz``, ``zx``; positive when the angle exceeds 90°.
    reference : numpy.ndarray, m
        Commanded (x, y, z) through which every measuring line passed.
    measured_tool_offset : numpy.ndarray, m
        Tool offset (x, y, z) used while measuring.
    travel : dict of str to (float, float), m
        Travel of each axis.
    """

    chain: KinematicChain
    functions: dict
    squareness: dict
    reference: np.ndarray
    measured_tool_offset: np.ndarray
    travel: dict
    notes: tuple = field(default=())

    def __post_init__(self) -> None:
        unknown = sorted(set(self.functions) - set(ERROR_NAMES))
        if unknown:
            raise ConfigError(f"unknown error motion(s) {', '.join(unknown)}; "
                              f"known: {' '.join(ERROR_NAMES)}")
        bad = sorted(set(self.squareness) - set(PAIRS))
        if bad:
            raise ConfigError(f"unknown squareness pair(s) {', '.join(bad)}; known: xy yz zx")
        for k, v in self.squareness.items():
            if not (np.isfinite(v) and abs(v) <= _LIMIT):
                raise InputError(f"squareness {k} = {v!r} rad: must be finite and small")
        for a in AXES:
            lo, hi = self.travel.get(a, (np.nan, np.nan))
            if not (np.isfinite(lo) and np.isfinite(hi) and hi > lo):
                raise ConfigError(f"travel of {a} = {self.travel.get(a)!r}: give [low, high] "
                                  "with high > low")
        object.__setattr__(self, "reference", _vector(self.reference, "reference"))
        object.__setattr__(self, "measured_tool_offset",
                           _vector(self.measured_tool_offset, "measured tool offset"))

    @property
    def travel_mm(self) -> dict:
        """:attr:`travel` in mm (what controller tables and files are written in)."""
        return {a: (lo * 1e3, hi * 1e3) for a, (lo, hi) in self.travel.items()}

    @property
    def missing(self) -> tuple[str, ...]:
        """Error motions not given (taken as zero)."""
        return tuple(n for n in ERROR_NAMES if n not in self.functions)

    def value(self, name: str, u) -> np.ndarray:
        """Error ``name`` at positions ``u`` (m) of its axis, zero at the reference point."""
        f = self.functions.get(name)
        u = np.asarray(u, dtype=float)
        if f is None:
            return np.zeros_like(u)
        c = self.reference[AXES.index(name[-1])]
        return f(u) - f(c)


def volumetric_error(errors: GeometricErrors, x, y, z, tool_offset=None, *,
                     part: str = "all") -> np.ndarray:
    """Error of the tool point relative to the work-piece at commanded (x, y, z), metres.

    Parameters
    ----------
    errors : GeometricErrors
    x, y, z : array_like, m
        Commanded positions (broadcast together).
    tool_offset : array_like of 3, m, optional
        Tool offset; default the one used while measuring.
    part : {"all", "table", "cross"}
        ``"table"``: only what single-axis tables can compensate; ``"cross"``: only the Abbe
        products of two axes (``all = table + cross``).

    Returns
    -------
    numpy.ndarray, shape (3, ...)
        (Ex, Ey, Ez) in metres, zero at the reference point.

    Notes
    -----
    The first-order rigid-body model in the module docstring (Schwenke et al. 2008, eq. 3).

    Examples
    --------
    A pure XY squareness of +10 µm/m (angle > 90°) moves X by −10 µm at y = c_y + 1 m
    (Chapman, "Calibration of machine squareness", Appendix I, eq. 2):

    >>> e = GeometricErrors(KinematicChain.parse("X Y | Z"), {}, {"xy": 10e-6},
    ...                     [0, 0, 0], [0, 0, 0], {a: (0.0, 1.0) for a in AXES})
    >>> [round(float(v) * 1e6, 6) for v in volumetric_error(e, 0.0, 1.0, 0.0)]
    [-10.0, 0.0, 0.0]
    """
    if part not in ("all", "table", "cross"):
        raise InputError(f"part = {part!r}; use 'all', 'table' or 'cross'")
    q = np.broadcast_arrays(*(np.asarray(v, dtype=float) for v in (x, y, z)))
    t = errors.measured_tool_offset if tool_offset is None else _vector(tool_offset, "tool offset")
    dt = t - errors.measured_tool_offset
    c = errors.reference
    out = np.zeros((3,) + q[0].shape)
    for a in AXES:
        i = AXES.index(a)
        u = q[i]
        eps = np.stack([errors.value(r + a, u) for r in ROTATIONS])
        if part != "cross":
            out += np.stack([errors.value(d + a, u) for d in TRANSLATIONS])
            out += np.cross(eps, np.broadcast_to(dt.reshape((3,) + (1,) * u.ndim), eps.shape),
                            axis=0)
        if part != "table":
            lever = np.zeros((3,) + u.shape)
            for b in errors.chain.after(a):
                j = AXES.index(b)
                lever[j] = q[j] - c[j]
            out += np.cross(eps, lever, axis=0)
    if part != "cross":
        sq = errors.squareness
        out[0] -= sq.get("xy", 0.0) * (q[1] - c[1]) + sq.get("zx", 0.0) * (q[2] - c[2])
        out[1] -= sq.get("yz", 0.0) * (q[2] - c[2])
    return out


def table_part(errors: GeometricErrors, axis: str, u, tool_offset=None) -> np.ndarray:
    """The error of ``axis`` alone at its positions ``u`` (m): what its tables can remove.

    Returns ``δ_axis(u) + Δε_axis(u) × (t − t_m)``, shape (3, len(u)), metres (the squareness is
    separate: a linear cross-axis table, :func:`axiscal.compensation.volumetric.volumetric_tables`).
    """
    u = np.atleast_1d(np.asarray(u, dtype=float))
    t = errors.measured_tool_offset if tool_offset is None else _vector(tool_offset, "tool offset")
    dt = t - errors.measured_tool_offset
    d = np.stack([errors.value(n + axis, u) for n in TRANSLATIONS])
    eps = np.stack([errors.value(r + axis, u) for r in ROTATIONS])
    return d + np.cross(eps, np.broadcast_to(dt[:, None], eps.shape), axis=0)


@dataclass(frozen=True, eq=False)
class VolumetricMap:
    """The error field on a grid of the working volume.

    Attributes
    ----------
    grid : tuple of 3 numpy.ndarray, m
        Commanded positions of X, Y and Z.
    error : numpy.ndarray, m, shape (3, nx, ny, nz)
        (Ex, Ey, Ez) at every grid point, zero at the reference point.
    tool_offset : numpy.ndarray, m
    """

    grid: tuple
    error: np.ndarray
    tool_offset: np.ndarray

    @property
    def magnitude(self) -> np.ndarray:
        """|E| at every grid point, m."""
        return np.sqrt((self.error ** 2).sum(axis=0))

    @property
    def largest(self) -> float:
        """Largest |E|, m."""
        return float(self.magnitude.max())

    @property
    def largest_at(self) -> tuple[float, float, float]:
        """Commanded position of the largest |E|, m."""
        idx = np.unravel_index(int(np.argmax(self.magnitude)), self.magnitude.shape)
        return tuple(float(g[i]) for g, i in zip(self.grid, idx))

    @property
    def ranges(self) -> dict[str, float]:
        """Range (max − min) of each component over the volume, m."""
        return {a: float(np.ptp(self.error[i])) for i, a in enumerate(AXES)}

    def summary(self) -> dict:
        """The volumetric accuracy figures in µm and mm (for JSON and reports)."""
        return {"largest_um": self.largest * 1e6,
                "largest_at_mm": [v * 1e3 for v in self.largest_at],
                "range_um": {a: v * 1e6 for a, v in self.ranges.items()},
                "grid_points": int(self.magnitude.size)}

    def __str__(self) -> str:
        at = ", ".join(f"{v * 1e3:.0f}" for v in self.largest_at)
        r = ", ".join(f"{a} {v * 1e6:.2f}" for a, v in self.ranges.items())
        return (f"largest volumetric error {self.largest * 1e6:.2f} µm at ({at}) mm; "
                f"ranges {r} µm")


def map_volume(errors: GeometricErrors, n=11, tool_offset=None, field=None) -> VolumetricMap:
    """The error field on an ``n × n × n`` grid (or ``n = (nx, ny, nz)``) of the travel.

    ``field(x, y, z) -> (3, ...)`` replaces the model (a simulated machine's truth is mapped on
    the same grid this way).
    """
    ns = (n, n, n) if np.isscalar(n) else tuple(n)
    if len(ns) != 3 or any(int(k) != k or not 2 <= k <= 1000 for k in ns):
        raise InputError(f"grid = {n!r}: give 2 to 1000 points per axis")
    grid = tuple(np.linspace(*errors.travel[a], int(k)) for a, k in zip(AXES, ns))
    X, Y, Z = np.meshgrid(*grid, indexing="ij")
    t = errors.measured_tool_offset if tool_offset is None else _vector(tool_offset, "tool offset")
    e = (volumetric_error(errors, X, Y, Z, t) if field is None else np.asarray(field(X, Y, Z)))
    return VolumetricMap(grid, e, t)


@dataclass(frozen=True, eq=False)
class BodyDiagonal:
    """Displacement along one body diagonal (ISO 230-6:2002, body diagonal test).

    Attributes
    ----------
    name : str
        ``PPP`` for the diagonal from (low, low, low) to (high, high, high); each letter is the
        end of X, Y, Z where the diagonal starts (``N`` for the high end).
    start, end : numpy.ndarray, m
    distance : numpy.ndarray, m
        Nominal distance from the start.
    deviation : numpy.ndarray, m
        Displacement error along the diagonal, relative to the start.
    """

    name: str
    start: np.ndarray
    end: np.ndarray
    distance: np.ndarray
    deviation: np.ndarray

    @property
    def range(self) -> float:
        """Range of the deviation along the diagonal, m (its systematic positioning error)."""
        return float(np.ptp(self.deviation))


def diagonal_corners(travel: dict) -> dict[str, tuple[np.ndarray, np.ndarray]]:
    """Start and end of the four body diagonals of the travel box, m."""
    lo = np.array([travel[a][0] for a in AXES], float)
    hi = np.array([travel[a][1] for a in AXES], float)
    out = {}
    for name in ("PPP", "NPP", "PNP", "PPN"):
        s = np.where([ch == "P" for ch in name], lo, hi)
        out[name] = (s, lo + hi - s)
    return out


def body_diagonals(errors: GeometricErrors, n: int = 21, tool_offset=None,
                   field=None) -> list[BodyDiagonal]:
    """Predicted displacement errors along the four body diagonals (ISO 230-6:2002).

    The deviation along a diagonal is the projection of the volumetric error on its direction,
    relative to its start: ``(E(p) − E(p0)) · u`` (a laser aligned to the diagonal reads the
    displacement along it; the lateral error is a cosine effect of second order).
    """
    out = []
    for name, (s, e) in diagonal_corners(errors.travel).items():
        f = np.linspace(0.0, 1.0, int(n))
        p = s[:, None] + (e - s)[:, None] * f
        u = (e - s) / np.linalg.norm(e - s)
        err = (volumetric_error(errors, *p, tool_offset) if field is None
               else np.asarray(field(*p)))
        dev = u @ (err - err[:, :1])
        out.append(BodyDiagonal(name, s, e, f * np.linalg.norm(e - s), dev))
    return out


def _vector(v, what: str) -> np.ndarray:
    a = np.array(v, dtype=float, ndmin=1)
    if a.shape != (3,) or not np.isfinite(a).all() or np.abs(a).max() > 100.0:
        raise InputError(f"{what} = {v!r}: give three finite numbers (m)")
    a.flags.writeable = False
    return a
