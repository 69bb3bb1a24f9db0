"""Plans of the contouring and line tests: the ISO 230-4 circular test and the squareness and
straightness lines, as data a part program (:mod:`axiscal.programs`) or a simulation executes.

Circular test (ISO 230-4:2005)
------------------------------
The machine contours a circle of radius ``R`` about the ballbar's pivot at the feed given, in both
directions (ISO 230-4:2005 §5: "the test should be carried out ... counter-clockwise and
clockwise"). The data arc is contoured at the steady feed: it is preceded by a feed-in arc and
followed by a feed-out arc (the overshoot arcs) on the same circle, so the acceleration and the
deceleration of the axes fall outside it. The standard does not give the overshoot's length; axiscal
takes 180° by default (a half turn lets the servo settle at the feed at any feed a ballbar test
uses) and accepts 0° to 360°. The counter-clockwise run ends with its feed-out arc where the
clockwise run's feed-in arc starts, so the machine reverses on the circle and contours the same
data arc back. The start point lies ``set_in`` outside the circle on the feed-in arc's radius;
a radial move at the feed puts the machine on the circle (and takes it off at the end).

Lines (ISO 230-1:2012 §8 straightness, §10.3 squareness)
---------------------------------------------------------
A line is a :class:`~axiscal.procedures.positioning.TestPlan` on the axis that moves (its points,
runs, direction of approach and overrun: the same cycle as a positioning test, so a reading is
taken at each point after the dwell) with the other axes held at fixed positions. A squareness
test by the straightness of two axes (ISO 230-1:2012 §10.3.2, Chapman, Calibration of machine
squareness, Method 1) is two lines from a common corner: along the first axis at the corner's
position of the second, then along the second at the corner's position of the first.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from axiscal.errors import InputError
from axiscal.procedures.positioning import TestPlan

__all__ = ["CircularPlan", "Line", "LinePlan", "plan_circular", "plan_lines", "plan_squareness",
           "plan_straightness", "Arc"]

DIRECTIONS = ("ccw", "cw")


@dataclass(frozen=True)
class Arc:
    """One arc of a circular plan: from ``start_deg`` through ``sweep_deg`` (+ CCW, − CW).

    ``role`` is ``feed-in``, ``data`` or ``feed-out``; ``direction`` ``ccw`` or ``cw``.
    """

    role: str
    direction: str
    start_deg: float
    sweep_deg: float

    @property
    def end_deg(self) -> float:
        return self.start_deg + self.sweep_deg


@dataclass(frozen=True, eq=False)
class CircularPlan:
    """An ISO 230-4 circular test plan (module docstring), lengths in mm, angles in degrees.

    Attributes
    ----------
    radius : float, mm
        Nominal radius (the ballbar's length).
    centre : (float, float), mm
        The pivot's position on the plane's two axes.
    plane : str
        Two axis letters, first then second (``XY``, ``YZ``, ``ZX``): angles count from the
        first axis towards the second.
    feed : float, mm/min
        Contouring feed.
    start_deg, arc_deg, overshoot_deg : float, degrees
        Start of the data arc, its length (0 < arc ≤ 360) and the overshoot arcs' length.
    directions : tuple of str
        ``("ccw", "cw")`` (both, the default), or one of them.
    set_in : float, mm
        Radial distance outside the circle of the start and end points.
    """

    radius: float
    centre: tuple = (0.0, 0.0)
    plane: str = "XY"
    feed: float = 1000.0
    start_deg: float = 0.0
    arc_deg: float = 360.0
    overshoot_deg: float = 180.0
    directions: tuple = DIRECTIONS
    set_in: float = 1.0

    def __post_init__(self) -> None:
        if not (math.isfinite(self.radius) and self.radius > 0):
            raise InputError(f"radius {self.radius!r} mm: give a radius above 0")
        c = tuple(float(v) for v in self.centre)
        if len(c) != 2 or not all(math.isfinite(v) for v in c):
            raise InputError(f"centre {self.centre!r}: give two finite positions in mm")
        object.__setattr__(self, "centre", c)
        p = str(self.plane).upper()
        if len(p) != 2 or p[0] == p[1] or any(a not in "XYZ" for a in p):
            raise InputError(f"plane {self.plane!r}: give two of X, Y, Z (XY, YZ or ZX)")
        object.__setattr__(self, "plane", p)
        if not (math.isfinite(self.feed) and self.feed > 0):
            raise InputError(f"feed {self.feed!r} mm/min: give a feed above 0")
        if not (math.isfinite(self.arc_deg) and 0 < self.arc_deg <= 360):
            raise InputError(f"arc {self.arc_deg!r} deg: give a data arc above 0 and at most 360")
        if not (math.isfinite(self.overshoot_deg) and 0 <= self.overshoot_deg <= 360):
            raise InputError(f"overshoot {self.overshoot_deg!r} deg: give 0 to 360")
        if not math.isfinite(self.start_deg):
            raise InputError(f"start {self.start_deg!r} deg: give a finite angle")
        d = tuple(self.directions)
        if not d or len(set(d)) != len(d) or any(x not in DIRECTIONS for x in d):
            raise InputError(f"directions {self.directions!r}: give ccw, cw or both")
        object.__setattr__(self, "directions", d)
        if not (math.isfinite(self.set_in) and 0 <= self.set_in < self.radius):
            raise InputError(f"set-in {self.set_in!r} mm: give 0 or more, less than the radius")

    def arcs(self) -> tuple[Arc, ...]:
        """The arcs in the order contoured: per direction feed-in, data, feed-out."""
        out = []
        o, a, s = self.overshoot_deg, self.arc_deg, self.start_deg
        for d in self.directions:
            if d == "ccw":
                seq = [("feed-in", s - o, o), ("data", s, a), ("feed-out", s + a, o)]
            else:
                seq = [("feed-in", s + a + o, -o), ("data", s + a, -a), ("feed-out", s, -o)]
            out += [Arc(role, d, st, sw) for role, st, sw in seq if sw != 0]
        return tuple(out)

    def point(self, angle_deg: float, radius: float | None = None) -> tuple[float, float]:
        """The point at ``angle_deg`` on the circle (or at ``radius``), mm."""
        r = self.radius if radius is None else radius
        t = math.radians(angle_deg)
        return (self.centre[0] + r * math.cos(t), self.centre[1] + r * math.sin(t))

    def __str__(self) -> str:
        return (f"ISO 230-4 circular test in {self.plane}: radius {self.radius:g} mm about "
                f"({self.centre[0]:g}, {self.centre[1]:g}) mm, feed {self.feed:g} mm/min, data arc "
                f"{self.arc_deg:g} deg from {self.start_deg:g} deg, overshoot "
                f"{self.overshoot_deg:g} deg, {' then '.join(self.directions)}")


def plan_circular(radius: float, centre=(0.0, 0.0), *, plane: str = "XY", feed: float = 1000.0,
                  start_deg: float = 0.0, arc_deg: float = 360.0, overshoot_deg: float = 180.0,
                  directions=DIRECTIONS, set_in: float = 1.0) -> CircularPlan:
    """An ISO 230-4:2005 circular test plan (see :class:`CircularPlan`; mm, mm/min, degrees).

    Examples
    --------
    >>> for a in plan_circular(100).arcs()[:3]:
    ...     print(a.role, a.direction, a.start_deg, a.sweep_deg)
    feed-in ccw -180.0 180.0
    data ccw 0.0 360.0
    feed-out ccw 360.0 180.0
    """
    return CircularPlan(radius, tuple(centre), plane, feed, start_deg, arc_deg, overshoot_deg,
                        tuple(directions), set_in)


@dataclass(frozen=True, eq=False)
class Line:
    """One measured line: the moving axis's plan and the positions the other axes hold (mm)."""

    plan: TestPlan
    fixed: tuple        # ((letter, position mm), ...)


@dataclass(frozen=True, eq=False)
class LinePlan:
    """Lines measured one after the other (straightness, squareness); ``kind`` names the test."""

    lines: tuple
    kind: str = "straightness"

    def __post_init__(self) -> None:
        if not self.lines:
            raise InputError("a line plan needs at least one line")
        for ln in self.lines:
            if ln.plan.axis_kind.value != "linear":
                raise InputError("lines move linear axes")

    @property
    def dwell(self) -> float:
        return min(ln.plan.dwell for ln in self.lines)

    def __str__(self) -> str:
        parts = []
        for ln in self.lines:
            held = ", ".join(f"{a}={v:g}" for a, v in ln.fixed)
            parts.append(f"{ln.plan.axis} {ln.plan.targets[0]:g} to {ln.plan.targets[-1]:g} mm, "
                         f"{ln.plan.targets.size} points" + (f" at {held}" if held else ""))
        return f"{self.kind} lines (ISO 230-1): " + "; ".join(parts)


def plan_lines(lines, *, kind: str = "straightness") -> LinePlan:
    """A plan of lines: ``lines`` is a sequence of ``(TestPlan, {letter: position mm})``."""
    out = []
    for plan, fixed in lines:
        held = tuple((str(a).upper(), float(v)) for a, v in dict(fixed).items())
        if any(a == plan.axis.upper() for a, _ in held):
            raise InputError(f"line along {plan.axis} cannot also hold {plan.axis} fixed")
        out.append(Line(plan, held))
    return LinePlan(tuple(out), kind)


def plan_squareness(axes: str = "XY", length: float = 400.0, corner=(0.0, 0.0), *,
                    points: int = 5, runs: int = 1, dwell: float = 4.0, overrun: float = 5.0,
                    bidirectional: bool = True) -> LinePlan:
    """Two straightness lines from ``corner`` (mm) along the plane's axes, each ``length`` mm with
    ``points`` evenly spaced reading points (ISO 230-1:2012 §10.3.2; module docstring).

    Examples
    --------
    >>> print(plan_squareness("XY", 400, points=5, dwell=2))
    squareness lines (ISO 230-1): X 0 to 400 mm, 5 points at Y=0; Y 0 to 400 mm, 5 points at X=0
    """
    from axiscal.datasets import AxisKind

    a = str(axes).upper()
    if len(a) != 2 or a[0] == a[1] or any(x not in "XYZ" for x in a):
        raise InputError(f"axes {axes!r}: give two of X, Y, Z (XY, YZ or ZX)")
    if not (math.isfinite(length) and length > 0):
        raise InputError(f"length {length!r} mm: give a length above 0")
    if not isinstance(points, int) or points < 2:
        raise InputError(f"points {points!r}: give at least 2")
    c = [float(v) for v in corner]
    lines = []
    for k in (0, 1):
        targets = np.round(c[k] + np.linspace(0.0, length, points), 6)
        plan = TestPlan(AxisKind.LINEAR, targets, "mm", runs, "linear", bidirectional, overrun,
                        dwell, a[k])
        lines.append((plan, {a[1 - k]: c[1 - k]}))
    return plan_lines(lines, kind="squareness")


def plan_straightness(axis: str = "X", length: float = 400.0, start: float = 0.0, *,
                      at: dict | None = None, points: int = 5, runs: int = 1, dwell: float = 4.0,
                      overrun: float = 5.0, bidirectional: bool = True) -> LinePlan:
    """One straightness line along ``axis`` from ``start`` over ``length`` mm, ``points`` evenly
    spaced reading points, the other axes held ``at`` (mm) (ISO 230-1:2012 §8.2).

    Examples
    --------
    >>> print(plan_straightness("Y", 300, at={"X": 100}, points=4, dwell=2))
    straightness lines (ISO 230-1): Y 0 to 300 mm, 4 points at X=100
    """
    from axiscal.datasets import AxisKind

    a = str(axis).upper()
    if len(a) != 1 or a not in "XYZ":
        raise InputError(f"axis {axis!r}: give X, Y or Z")
    if not (math.isfinite(length) and length > 0):
        raise InputError(f"length {length!r} mm: give a length above 0")
    if not math.isfinite(start):
        raise InputError(f"start {start!r} mm: give a finite position")
    if not isinstance(points, int) or points < 2:
        raise InputError(f"points {points!r}: give at least 2")
    targets = np.round(start + np.linspace(0.0, length, points), 6)
    plan = TestPlan(AxisKind.LINEAR, targets, "mm", runs, "linear", bidirectional, overrun,
                    dwell, a)
    return plan_lines([(plan, at or {})], kind="straightness")
