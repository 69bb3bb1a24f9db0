"""Two servo axes contouring a circle on the squareness simulator's plane (ballbar tests).

Each axis is a position loop of gain ``K_v`` (1/s) driving its motor: ``ṁ = K_v (c - p)``, with
``c`` the command and ``p`` the table position measured by the loop (fully closed). Between motor
and table a transmission gap ``g`` (lost motion): the table follows the motor only when the motor
pushes on one side of the gap (play operator). In steady contouring the axis lags its command by
``τ = 1/K_v`` (first-order loop), so two gains give the servo mismatch ``Δτ = 1/K_x - 1/K_y``; at a
reversal the table stands still while the motor crosses the gap and the loop catches up with time
constant ``1/K_v``: the reversal spike comes from the dynamics, not from a formula. The geometric
errors of :class:`~axiscal.machines.xy_plane.XYPlaneMachine` (squareness, scale, straightness,
semi-closed backlash) are added at the table position, with lateral play
(``δy = (l_x/2) sign v_x``) and a cyclic error per axis (``δx = A sin(2π x / p)``) on top.

References
----------
ISO 230-4:2005 Annex A (servo mismatch, reversal spikes, lateral play, cyclic error). Renishaw
(M.A.V. Chapman), Calibration of machine squareness, Method 4 (Chapman, Calibration of machine squareness).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from axiscal.errors import InputError
from axiscal.machines.xy_plane import XYPlaneMachine

__all__ = ["ServoPlane", "contour_circle"]


@dataclass(frozen=True)
class ServoPlane:
    """The plane's geometry plus the servo of each axis (SI units).

    Attributes
    ----------
    machine : XYPlaneMachine
    kv_x, kv_y : float, 1/s
        Position-loop gains.
    gap_x, gap_y : float, m
        Transmission lost motion inside the fully closed loop (reversal spikes).
    lateral_x, lateral_y : float, m
        Lateral play: the other axis shifts by ``±l/2`` with the sign of this axis's velocity.
    cyclic_x, cyclic_y : (float, float), (m, m)
        Amplitude and pitch of a cyclic positioning error.
    """

    machine: XYPlaneMachine = field(default_factory=XYPlaneMachine)
    kv_x: float = 40.0
    kv_y: float = 40.0
    gap_x: float = 0.0
    gap_y: float = 0.0
    lateral_x: float = 0.0
    lateral_y: float = 0.0
    cyclic_x: tuple[float, float] = (0.0, 0.005)
    cyclic_y: tuple[float, float] = (0.0, 0.005)

    def __post_init__(self):
        for key in ("kv_x", "kv_y"):
            if not (math.isfinite(getattr(self, key)) and getattr(self, key) > 0):
                raise InputError(f"{key}={getattr(self, key)!r} 1/s: must be positive")
        for key in ("gap_x", "gap_y", "lateral_x", "lateral_y"):
            if not (math.isfinite(getattr(self, key)) and abs(getattr(self, key)) < 1e-3):
                raise InputError(f"{key}={getattr(self, key)!r} m: must be finite, under 1 mm")
        for key in ("cyclic_x", "cyclic_y"):
            amp, pitch = getattr(self, key)
            if not (math.isfinite(amp) and abs(amp) < 1e-3 and pitch > 0):
                raise InputError(f"{key}={getattr(self, key)!r}: amplitude under 1 mm, pitch > 0")


def contour_circle(plane: ServoPlane, radius: float, feed: float, direction: str, times,
                   *, centre=(0.0, 0.0), start_deg: float = 0.0, lead_in_deg: float = 45.0,
                   substeps: int = 8):
    """Actual tool positions at ``times`` while contouring a circle (module docstring).

    Parameters
    ----------
    plane : ServoPlane
    radius : float, m
    feed : float, m/s
    direction : str
        ``"ccw"`` or ``"cw"``.
    times : array_like, s
        Sample instants after the start angle is commanded (increasing, >= 0).
    centre : (float, float), m
    start_deg, lead_in_deg : float, degrees
        Start of the measured arc, and the arc run before it so the loops reach steady state.
    substeps : int
        Integration steps per sample interval (exact first-order update per step).

    Returns
    -------
    (x, y, phi) : numpy.ndarray, m, m, rad
        Actual positions and the commanded angle at each sample.
    """
    sense = 1.0 if direction == "ccw" else -1.0
    t = np.asarray(times, float)
    w = sense * feed / radius
    t0 = math.radians(lead_in_deg) * radius / feed
    dt_s = float(np.min(np.diff(t))) if t.size > 1 else 1e-3
    dt = min(dt_s, 0.1 / max(plane.kv_x, plane.kv_y)) / substeps
    grid = np.arange(-t0, t[-1] + dt, dt)
    ang = math.radians(start_deg) + w * grid
    cx, cy = centre[0] + radius * np.cos(ang), centre[1] + radius * np.sin(ang)
    px, vx = _axis(cx, plane.kv_x, plane.gap_x, dt)
    py, vy = _axis(cy, plane.kv_y, plane.gap_y, dt)
    x, y = np.interp(t, grid, px), np.interp(t, grid, py)
    sx, sy = np.interp(t, grid, vx), np.interp(t, grid, vy)
    dx, dy = plane.machine.deviation(x, y, sx, sy)
    ax, px_ = plane.cyclic_x
    ay, py_ = plane.cyclic_y
    dx = dx + ax * np.sin(2 * np.pi * x / px_) + 0.5 * plane.lateral_y * np.sign(sy)
    dy = dy + ay * np.sin(2 * np.pi * y / py_) + 0.5 * plane.lateral_x * np.sign(sx)
    return x + dx, y + dy, math.radians(start_deg) + w * t


def _axis(cmd: np.ndarray, kv: float, gap: float, dt: float):
    """Loop ṁ = K_v (c - p) with the table p following the motor m through a play of ``gap``;
    returns the table position and the sign of its last motion (the approach side)."""
    decay = math.exp(-kv * dt)
    m = p = float(cmd[0])
    last = 0.0
    out, sgn = np.empty_like(cmd), np.empty_like(cmd)
    half = 0.5 * gap
    for i, c in enumerate(cmd):
        # exact update of ṁ = K_v (c - p) over dt with p held (p moves with m when in contact)
        step = (c - p) * (1.0 - decay)
        m += step
        q = min(max(p, m - half), m + half) if gap > 0 else m
        if q != p:
            last = 1.0 if q > p else -1.0
        p = q
        out[i], sgn[i] = p, last
    return out, sgn
