"""A simulated ballbar test: the servo plane contours CCW then CW, the ballbar samples both.

The ballbar software places each sample at an angle from its instant (start angle plus
feed × time / R), the clock started when the bar sees the machine move: the common lag of the two
axes ``(1/K_x + 1/K_y)/2`` falls out of the angle that way, and what lag differs between the
axes (servo mismatch) shows in the reading.
"""

from __future__ import annotations

import math

import numpy as np

from axiscal.errors import InputError
from axiscal.instruments.ballbar import Ballbar
from axiscal.machines.servo_plane import ServoPlane, contour_circle
from axiscal.standards.iso230_4 import CircularRun

__all__ = ["simulate_ballbar"]


def simulate_ballbar(plane: ServoPlane, bar: Ballbar, feed: float, *, arc_deg: float = 360.0,
                     start_deg: float = 0.0, rng: np.random.Generator | None = None
                     ) -> tuple[CircularRun, CircularRun]:
    """CCW and CW runs of a circular test of radius ``bar.length`` at ``feed`` (m/s).

    The CCW run covers ``start_deg`` to ``start_deg + arc_deg``; the CW run the same arc back.
    """
    if not (math.isfinite(feed) and feed > 0):
        raise InputError(f"feed={feed!r} m/s: must be positive")
    if not 0 < arc_deg <= 360:
        raise InputError(f"arc_deg={arc_deg!r}: must lie in (0, 360]")
    radius = bar.length
    duration = math.radians(arc_deg) * radius / feed
    n = int(duration * bar.sample_rate)
    if n < 8:
        raise InputError(f"{n} samples: raise the sample rate or lower the feed")
    full = arc_deg >= 360.0
    t = np.arange(n) / bar.sample_rate if full else np.linspace(0, duration, n)
    runs = []
    for direction, start in (("ccw", start_deg), ("cw", start_deg + arc_deg)):
        x, y, phi = contour_circle(plane, radius, feed, direction, t, start_deg=start)
        # the pivot sits where the machine put the tool when commanded to the centre
        cx, cy = plane.machine.actual(0.0, 0.0)
        dev = bar.read(x, y, (float(cx), float(cy)), rng)
        sense = 1.0 if direction == "ccw" else -1.0
        lag = 0.5 * (1.0 / plane.kv_x + 1.0 / plane.kv_y) * feed / radius   # rad
        runs.append(CircularRun(np.mod(phi - sense * lag, 2 * np.pi), dev, direction))
    return runs[0], runs[1]
