"""Kinematics of a table-table five-axis machine with the location errors of its rotary axes.

A table-table machine carries the work-piece on a rotary table (C, about Z) that a tilting axis
(A about X, or B about Y) carries. The linear axes move the tool; the table turns the work-piece.
Each rotary axis's *average line* is placed by five location errors (ISO 230-1:2012, 3.4.x and
ISO 230-7:2015, Clause 3): two positions of the line, two orientations (tilts) and the zero
position of the axis. For an A/C machine::

    A axis: E_Y0A, E_Z0A (position), E_B0A, E_C0A (orientation), E_A0A (zero position)
    C axis: E_X0C, E_Y0C (position), E_A0C, E_B0C (orientation), E_C0C (zero position)

and for a B/C machine ``E_X0B, E_Z0B, E_A0B, E_C0B, E_B0B`` and the same five of C.

Frames and reference points (the reading chosen here; the standards name the errors, a machine
builder chooses where a line's position is taken):

* the *machine frame* is that of the linear axes (X, Y, Z joint positions of the tool point);
* the *table frame* is fixed to the C table and coincides with the machine frame when both rotary
  axes are at zero on a machine without errors;
* the tilting axis's position (E_Y0A, E_Z0A for A; E_X0B, E_Z0B for B) is that of its line where it
  crosses the plane through the nominal C axis normal to the tilting axis; the C axis's position
  (E_X0C, E_Y0C) is that of its line, at A = 0 (B = 0), where it crosses the plane Z = height of
  the nominal tilting axis. With these reference points the zero position of the tilting axis and
  the tilt of C about the same direction (E_A0A and E_A0C; E_B0B and E_B0C) move a point on the
  table in the same way to first order, so a set-up whose sphere place is unknown sees their sum.
* orientation errors are small rotations of the nominal direction (X for A, Y for B, Z for C)
  about the named axes, right-handed: the A line's direction is ``Rz(E_C0A) Ry(E_B0A) x̂``, the
  C line's ``Ry(E_B0C) Rx(E_A0C) ẑ``; the zero-position error adds to the commanded angle.

Sign of the rotary motion (LinuxCNC convention)
-----------------------------------------------
A commanded angle ``θ`` turns the *table* right-handed about its axis's positive direction by
``θ``: a point ``p`` fixed on the table is at ``R_T(a) R_C(c) p`` in the machine frame. This is the
convention of LinuxCNC's table-rotary-tilting kinematics (``xyzac-trt-kins`` and
``xyzbc-trt-kins``, functions ``xyzacKinematicsForward`` and ``xyzbcKinematicsForward`` of
``src/emc/kinematics/trtfuncs.c``, whose forward transform is, in matrix form,
``world = Rz(−c) [Rx(−a) (joint − p_A) + p_A − p_C] + p_C``), and the source's header note 5 of
``xyzac-trt-kins.c`` says so: "The directions of the rotational axes are the opposite of the
conventional axis directions". ISO 841:2001 takes positive rotation of the *tool relative to the
work-piece* right-handed, so a table (primed axis C') turns the other way: an ISO 841 angle is
the negative of the angle used here.

Spindle head (``kind = "head-table"``)
--------------------------------------
A spindle head turns the *tool* about its tilting axis (B about Y, or A about X) over a C table.
The joints X, Y, Z are the machine position of the spindle's pivot point; at tilt 0 the tool tip
is ``pivot`` below it, and the head turns it right-handed by the commanded angle about its actual
line, which passes through the pivot point offset by its position errors (E_X0B, E_Z0B for B;
E_Y0A, E_Z0A for A) with the same orientation and zero errors. :func:`table_to_machine` then gives
the joints that put the tool tip on a table point, ``T_C(c) p − tip(b)``, and
:func:`machine_to_table` the table point the tip reaches from given joints. The tool length
(``pivot``) is fully correlated with the head's Z position error and is taken as calibrated.

Position-dependent errors (error motions of ISO 230-7 and the angular positioning error) come from
:class:`axiscal.machines.rotary.RotaryAxis` (the five-DOF model), applied in each axis's own frame
(its axis of rotation is the frame's +z): ``p → q + F·(Rxy(εx, εy)·Fᵀ·R(θ + εz)(p − q) + δ)``.

All lengths in metres, angles in radians. Rotations are exact (Rodrigues), so the model holds the
second-order terms; the location errors are small but not linearised.

References
----------
ISO 230-1:2012, Test code for machine tools, Part 1: Geometric accuracy of machines operating
under no-load or quasi-static conditions, 3.4 (location errors) and Annex A.
ISO 230-7:2015, Test code for machine tools, Part 7: Geometric accuracy of axes of rotation,
Clause 3.
LinuxCNC 2.9, src/emc/kinematics/trtfuncs.c and xyzac-trt-kins.c (GPL-2.0), github.com/LinuxCNC/
linuxcnc, read at commit 135b0ce5220bef8f8a34b6825723108b8b9740f1.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from axiscal.errors import InputError

__all__ = ["KINDS", "TABLE_TABLE", "HEAD_TABLE", "TILT_AXES", "parameter_names", "Geometry", "AxisMotion", "table_to_machine",
           "machine_to_table", "rotate_about_line", "is_angle", "transform_many", "SQUARENESS",
           "squareness_matrix", "linear_to_true", "true_to_linear"]

TABLE_TABLE = "table-table"
HEAD_TABLE = "head-table"
#: The machine kinds modelled: a tilting table carrying C, or a spindle head tilting the tool
#: over a C table.
KINDS = (TABLE_TABLE, HEAD_TABLE)

#: The tilting axes a table-table machine may have, with their nominal direction.
TILT_AXES = {"A": np.array([1.0, 0.0, 0.0]), "B": np.array([0.0, 1.0, 0.0])}

#: Frame of each rotary axis: columns are the machine-frame directions of the axis frame's
#: x', y', z' (z' along the axis), right-handed.
_FRAMES = {"A": np.array([[0.0, 0.0, 1.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]]),
           "B": np.array([[0.0, 1.0, 0.0], [0.0, 0.0, 1.0], [1.0, 0.0, 0.0]]),
           "C": np.eye(3)}


def parameter_names(tilt: str) -> tuple[str, ...]:
    """The ten location errors of a table-table ``tilt``/C machine, tilting axis first.

    Examples
    --------
    >>> parameter_names("A")
    ('E_Y0A', 'E_Z0A', 'E_B0A', 'E_C0A', 'E_A0A', 'E_X0C', 'E_Y0C', 'E_A0C', 'E_B0C', 'E_C0C')
    """
    if tilt == "A":
        head = ("E_Y0A", "E_Z0A", "E_B0A", "E_C0A", "E_A0A")
    elif tilt == "B":
        head = ("E_X0B", "E_Z0B", "E_A0B", "E_C0B", "E_B0B")
    else:
        raise InputError(f"tilting axis {tilt!r}: a table-table machine tilts about A or B")
    return head + ("E_X0C", "E_Y0C", "E_A0C", "E_B0C", "E_C0C")


#: The squareness errors of the linear axes (ISO 230-1:2012 names): Y to X (about Z), Z to X
#: (about Y), Z to Y (about X).
SQUARENESS = ("E_C(0X)Y", "E_B(0X)Z", "E_A(0Y)Z")


def squareness_matrix(errors) -> np.ndarray:
    """``I + S``: where the tool is (machine frame, orthogonal) for unit readings of X, Y, Z.

    The reading chosen (ISO 230-1:2012 names the errors; the reference is the machine builder's):
    X is the reference line, Y lies in the XY plane; each error is the right-handed rotation of
    the later axis's line about the named axis, small (first order): the Y axis moves along
    ``(−E_C(0X)Y, 1, 0)`` and the Z axis along ``(E_B(0X)Z, −E_A(0Y)Z, 1)``.
    """
    e = errors or {}
    c, b, a = (float(e.get(n, 0.0)) for n in SQUARENESS)
    return np.array([[1.0, -c, b], [0.0, 1.0, -a], [0.0, 0.0, 1.0]])


def linear_to_true(points, errors) -> np.ndarray:
    """Where the tool is (m) for readings of the linear axes ``points`` (N, 3), m."""
    return np.atleast_2d(np.asarray(points, float)) @ squareness_matrix(errors).T


def true_to_linear(points, errors) -> np.ndarray:
    """The linear axes' readings (m) that put the tool at ``points`` (N, 3), m: the exact
    inverse of :func:`linear_to_true`."""
    m = squareness_matrix(errors)
    return np.linalg.solve(m, np.atleast_2d(np.asarray(points, float)).T).T


def is_angle(name: str) -> bool:
    """True for an orientation or zero-position error (radians), False for a position (m)."""
    return name[2] in "ABC"


@dataclass(frozen=True)
class Geometry:
    """Nominal geometry of a table-table machine (metres).

    Attributes
    ----------
    tilt : str
        ``"A"`` or ``"B"``.
    tilt_position : tuple of float, m
        For A: ``(y, z)`` of the nominal A axis (LinuxCNC ``y-rot-point + y-offset``,
        ``z-rot-point + z-offset``); for B: ``(x, z)`` (``x-rot-point + x-offset``,
        ``z-rot-point + z-offset``).
    c_position : tuple of float, m
        ``(x, y)`` of the nominal C axis at tilt 0 (LinuxCNC ``x-rot-point``, ``y-rot-point``).
    kind : str
        ``"table-table"`` or ``"head-table"`` (module docstring, 'Spindle head').
    pivot : float, m
        Head only: the tool tip's distance below the head's axis at tilt 0 (pivot length).
    """

    tilt: str = "A"
    tilt_position: tuple[float, float] = (0.0, 0.0)
    c_position: tuple[float, float] = (0.0, 0.0)
    kind: str = "table-table"
    pivot: float = 0.0

    def __post_init__(self) -> None:
        parameter_names(self.tilt)
        if self.kind not in KINDS:
            raise InputError(f"machine kind {self.kind!r}: use one of {', '.join(KINDS)}")
        if self.kind == HEAD_TABLE and not (np.isfinite(self.pivot) and self.pivot >= 0):
            raise InputError(f"pivot length {self.pivot!r} m must be a finite number >= 0")

    @property
    def head(self) -> bool:
        """True for a spindle head (the tilting axis turns the tool, C the table)."""
        return self.kind == HEAD_TABLE

    @property
    def names(self) -> tuple[str, ...]:
        return parameter_names(self.tilt)

    def reference_points(self) -> tuple[np.ndarray, np.ndarray]:
        """Nominal reference points of the tilting axis and of C (module docstring), m."""
        cx, cy = self.c_position
        t1, tz = self.tilt_position
        if self.head:     # the head's line, relative to the spindle's pivot point (the joints)
            return np.zeros(3), np.array([cx, cy, 0.0])
        if self.tilt == "A":
            return np.array([cx, t1, tz]), np.array([cx, cy, tz])
        return np.array([t1, cy, tz]), np.array([cx, cy, tz])

    def lines(self, errors: dict[str, float] | None = None):
        """Actual lines ``(point, unit direction, zero error)`` of the tilting axis and of C."""
        e = errors or {}
        g = lambda k: float(e.get(k, 0.0))  # noqa: E731 - a short reader
        q_t, q_c = self.reference_points()
        if self.tilt == "A":
            q_t = q_t + np.array([0.0, g("E_Y0A"), g("E_Z0A")])
            u_t = _rz(g("E_C0A")) @ _ry(g("E_B0A")) @ TILT_AXES["A"]
            z_t = g("E_A0A")
        else:
            q_t = q_t + np.array([g("E_X0B"), 0.0, g("E_Z0B")])
            u_t = _rz(g("E_C0B")) @ _rx(g("E_A0B")) @ TILT_AXES["B"]
            z_t = g("E_B0B")
        q_c = q_c + np.array([g("E_X0C"), g("E_Y0C"), 0.0])
        u_c = _ry(g("E_B0C")) @ _rx(g("E_A0C")) @ np.array([0.0, 0.0, 1.0])
        return (q_t, u_t, z_t), (q_c, u_c, g("E_C0C"))


@dataclass(frozen=True)
class AxisMotion:
    """Position-dependent errors of one rotary axis at each pose (arrays, SI): angular
    positioning ``ez`` and the error motions ``ex``, ``ey`` (rad), ``dx``, ``dy``, ``dz`` (m) in
    the axis's own frame (``+z`` along the axis), as :meth:`RotaryAxis.pose` gives them."""

    ez: np.ndarray
    ex: np.ndarray
    ey: np.ndarray
    dx: np.ndarray
    dy: np.ndarray
    dz: np.ndarray


def rotate_about_line(p, q, u, theta):
    """Rotate points ``p`` (N, 3) about the line through ``q`` along unit ``u`` by ``theta`` (N,),
    right-handed (Rodrigues' formula), metres and radians; ``q`` and ``u`` may be one (3,) or one
    per point (N, 3)."""
    v = np.asarray(p, float) - q
    th = np.asarray(theta, float)[:, None]
    cos, sin = np.cos(th), np.sin(th)
    return q + v * cos + _cross(u, v) * sin + (v * u).sum(-1)[:, None] * u * (1.0 - cos)


def _cross(u, v):
    u0, u1, u2 = u[..., 0], u[..., 1], u[..., 2]
    v0, v1, v2 = v[..., 0], v[..., 1], v[..., 2]
    return np.stack([u1 * v2 - u2 * v1, u2 * v0 - u0 * v2, u0 * v1 - u1 * v0], axis=-1)


def _tip(geometry: Geometry, q, u, theta, motion: AxisMotion | None):
    """Tool tip relative to the spindle's pivot point (the joints), head turned by ``theta``:
    ``(0, 0, −pivot)`` at zero, turned about the head's actual line (point ``q`` relative to
    the pivot, direction ``u``), then the head's error motion."""
    th = np.atleast_1d(np.asarray(theta, float))
    tip0 = np.broadcast_to(np.array([0.0, 0.0, -geometry.pivot]), (len(th), 3))
    return _motion_forward(rotate_about_line(tip0, q, u, th), q, geometry.tilt, motion)


def _motion_forward(p, q, axis, m: AxisMotion | None):
    """Apply the error motion of ``axis`` (about reference point ``q``) to rotated points."""
    if m is None:
        return p
    F = _FRAMES[axis]
    w = (p - q) @ F                                 # axis-frame coordinates
    w = _small_rotation(w, m.ex, m.ey, +1) + np.stack([m.dx, m.dy, m.dz], axis=-1)
    return q + w @ F.T


def _motion_inverse(p, q, axis, m: AxisMotion | None):
    if m is None:
        return p
    F = _FRAMES[axis]
    w = (p - q) @ F - np.stack([m.dx, m.dy, m.dz], axis=-1)
    return q + _small_rotation(w, m.ex, m.ey, -1) @ F.T


def _small_rotation(w, ex, ey, sign):
    """``Ry(ey) Rx(ex) w`` (sign +1) or its inverse (sign −1), exact, row-wise."""
    ex, ey = np.broadcast_to(ex, w.shape[:1]), np.broadcast_to(ey, w.shape[:1])
    if sign < 0:
        w = _rot_rows(w, -ey, 1)
        return _rot_rows(w, -ex, 0)
    return _rot_rows(_rot_rows(w, ex, 0), ey, 1)


def _rot_rows(w, ang, axis):
    c, s = np.cos(ang), np.sin(ang)
    x, y, z = w[:, 0], w[:, 1], w[:, 2]
    if axis == 0:
        return np.stack([x, c * y - s * z, s * y + c * z], axis=-1)
    return np.stack([c * x + s * z, y, -s * x + c * z], axis=-1)


def _angles(a, c, n):
    a = np.broadcast_to(np.asarray(a, float), (n,))
    c = np.broadcast_to(np.asarray(c, float), (n,))
    return a, c


def table_to_machine(geometry: Geometry, errors, tilt_angle, c_angle, points,
                     tilt_motion: AxisMotion | None = None, c_motion: AxisMotion | None = None):
    """Machine-frame position of table-fixed points at commanded rotary angles.

    Parameters
    ----------
    geometry : Geometry
    errors : dict of str to float
        Location errors by ISO 230 name (m, rad); missing ones are zero.
    tilt_angle, c_angle : array_like, radians
        Commanded angles of the tilting axis and of C (LinuxCNC sign, module docstring).
    points : array_like, shape (N, 3) or (3,), m
        Points in the table frame.
    tilt_motion, c_motion : AxisMotion, optional
        Position-dependent errors of each axis at each pose.

    Returns
    -------
    numpy.ndarray, shape (N, 3), m

    Examples
    --------
    >>> g = Geometry("A", (0.0, 0.0), (0.0, 0.0))
    >>> p = table_to_machine(g, {}, 0.0, np.pi / 2, [[0.1, 0.0, 0.0]])
    >>> np.round(p, 12).tolist()   # the table turned +90° about +Z: +X goes to +Y
    [[0.0, 0.1, 0.0]]
    """
    p = np.atleast_2d(np.asarray(points, float))
    n = max(p.shape[0], np.size(tilt_angle), np.size(c_angle))
    p = np.broadcast_to(p, (n, 3))
    a, c = _angles(tilt_angle, c_angle, n)
    (q_t, u_t, z_t), (q_c, u_c, z_c) = geometry.lines(errors)
    ec = 0.0 if c_motion is None else c_motion.ez
    et = 0.0 if tilt_motion is None else tilt_motion.ez
    p = _motion_forward(rotate_about_line(p, q_c, u_c, c + z_c + ec), q_c, "C", c_motion)
    if geometry.head:
        return p - _tip(geometry, q_t, u_t, a + z_t + et, tilt_motion)
    return _motion_forward(rotate_about_line(p, q_t, u_t, a + z_t + et), q_t, geometry.tilt,
                           tilt_motion)


def machine_to_table(geometry: Geometry, errors, tilt_angle, c_angle, points,
                     tilt_motion: AxisMotion | None = None, c_motion: AxisMotion | None = None):
    """Table-frame position of machine-frame points: the exact inverse of
    :func:`table_to_machine` (same parameters and units)."""
    p = np.atleast_2d(np.asarray(points, float))
    n = max(p.shape[0], np.size(tilt_angle), np.size(c_angle))
    p = np.broadcast_to(p, (n, 3))
    a, c = _angles(tilt_angle, c_angle, n)
    (q_t, u_t, z_t), (q_c, u_c, z_c) = geometry.lines(errors)
    ec = 0.0 if c_motion is None else c_motion.ez
    et = 0.0 if tilt_motion is None else tilt_motion.ez
    if geometry.head:
        p = p + _tip(geometry, q_t, u_t, a + z_t + et, tilt_motion)
    else:
        p = rotate_about_line(_motion_inverse(p, q_t, geometry.tilt, tilt_motion), q_t, u_t,
                              -(a + z_t + et))
    return rotate_about_line(_motion_inverse(p, q_c, "C", c_motion), q_c, u_c, -(c + z_c + ec))


def transform_many(geometry: Geometry, error_sets, tilt_angle, c_angle, points,
                   inverse: bool = False) -> np.ndarray:
    """:func:`table_to_machine` (or, with ``inverse``, :func:`machine_to_table`) for several sets
    of location errors at once, without position-dependent errors: one vectorised pass.

    Parameters
    ----------
    geometry : Geometry
    error_sets : sequence of dict
        P sets of location errors (m, rad).
    tilt_angle, c_angle : array_like, shape (N,), rad
    points : array_like, shape (P, N, 3), (N, 3) or (3,), m

    Returns
    -------
    numpy.ndarray, shape (P, N, 3), m
    """
    a = np.atleast_1d(np.asarray(tilt_angle, float))
    c = np.atleast_1d(np.asarray(c_angle, float))
    n, P = len(a), len(error_sets)
    pts = np.broadcast_to(np.asarray(points, float), (P, n, 3)).reshape(P * n, 3)
    lines = [geometry.lines(e) for e in error_sets]
    rep = lambda k, i: np.repeat(np.array([ln[k][i] for ln in lines]), n, axis=0)  # noqa: E731
    q_t, u_t, z_t, q_c, u_c, z_c = (rep(0, 0), rep(0, 1), rep(0, 2), rep(1, 0), rep(1, 1),
                                    rep(1, 2))
    a, c = np.tile(a, P), np.tile(c, P)
    if geometry.head:
        tip = _tip(geometry, q_t, u_t, a + z_t, None)
        if inverse:
            out = rotate_about_line(pts + tip, q_c, u_c, -(c + z_c))
        else:
            out = rotate_about_line(pts, q_c, u_c, c + z_c) - tip
        return out.reshape(P, n, 3)
    if inverse:
        out = rotate_about_line(rotate_about_line(pts, q_t, u_t, -(a + z_t)), q_c, u_c,
                                -(c + z_c))
    else:
        out = rotate_about_line(rotate_about_line(pts, q_c, u_c, c + z_c), q_t, u_t, a + z_t)
    return out.reshape(P, n, 3)


def _rx(t):
    c, s = np.cos(t), np.sin(t)
    return np.array([[1.0, 0.0, 0.0], [0.0, c, -s], [0.0, s, c]])


def _ry(t):
    c, s = np.cos(t), np.sin(t)
    return np.array([[c, 0.0, s], [0.0, 1.0, 0.0], [-s, 0.0, c]])


def _rz(t):
    c, s = np.cos(t), np.sin(t)
    return np.array([[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]])
