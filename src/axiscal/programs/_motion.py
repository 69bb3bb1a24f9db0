"""The motion of a test plan in no controller's language: blocks a dialect writes out.

A plan (:class:`~axiscal.procedures.positioning.TestPlan`,
:class:`~axiscal.procedures.circular_plan.CircularPlan`,
:class:`~axiscal.procedures.circular_plan.LinePlan`) and the machine's options
(:class:`MachineOptions`) become a :class:`Motion`: the safe start, then every move of the plan
in order, a dwell after each measurement, and the return to the safe start. Every move is checked
against the machine's limits before anything is written: a plan the machine cannot run is refused
by naming the option to change.

Machine coordinates: ``origin + sign × plan position`` for each axis (``sign`` −1 where the
machine counts the axis the other way from the test's positive direction, ``origin`` the machine
position of the plan's zero); limits, the safe start and the origin are given in the plan's unit
(mm, or degrees for a rotary axis), as the plan is; ``units="inch"`` only changes what the
program says (positions ÷ 25.4, feeds in inch/min).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

from axiscal.errors import InputError, ProgramError  # noqa: F401 (ProgramError: raised here, defined with the others)

__all__ = ["ProgramError", "MachineOptions", "Rapid", "Feed", "ArcMove", "Dwell", "Comment",
           "Spindle", "Motion", "build_motion", "DEFAULT_TRIGGER_S"]

#: The stillness a trigger needs at a stop by default, s: a dwell shorter than this is refused.
#: axiscal's reading, not a vendor's figure: ``axiscal capture`` takes a stop of 60 % of the
#: dwell, and a laser's stillness trigger needs its own stable time on top of the settling.
DEFAULT_TRIGGER_S = 0.5
#: Largest number of moves a program may hold (a test of 20,000 readings and their overruns).
MAX_BLOCKS = 200_000


@dataclass(frozen=True)
class MachineOptions:
    """What a part program needs to know of the machine, in the plan's units.

    Attributes
    ----------
    feed : float, plan unit per minute
        Feed of every measuring move (mm/min, deg/min; the circular plan's own feed wins there).
    max_feed : float, optional, plan unit per minute
        The machine's highest feed: a larger ``feed`` is refused.
    limits : dict of str to (float, float)
        Axis letter to (lowest, highest) machine position, plan unit; an axis not named is not
        checked.
    safe : dict of str to float
        Machine position of each axis at the start and the end (default: the plan's first
        approach point).
    sign : dict of str to int
        ±1 per axis (default +1).
    origin : dict of str to float
        Machine position of the plan's zero per axis (default 0).
    units : str
        ``mm`` or ``inch`` (linear axes in the program).
    trigger : float, s
        Stillness the trigger needs at each stop: a shorter dwell is refused.
    spindle : float, optional, rpm
        The spindle's highest speed (an ISO 230-3 spindle test runs at a fraction of it).
    """

    feed: float = 1000.0
    max_feed: float | None = None
    limits: dict = field(default_factory=dict)
    safe: dict = field(default_factory=dict)
    sign: dict = field(default_factory=dict)
    origin: dict = field(default_factory=dict)
    units: str = "mm"
    trigger: float = DEFAULT_TRIGGER_S
    spindle: float | None = None

    def __post_init__(self) -> None:
        if self.units not in ("mm", "inch"):
            raise ProgramError("units", f"units {self.units!r}: give mm or inch")
        if not (isinstance(self.feed, (int, float)) and math.isfinite(self.feed) and self.feed > 0):
            raise ProgramError("feed", f"feed {self.feed!r}: give a feed above 0 (plan unit/min)")
        if self.max_feed is not None:
            if not (math.isfinite(self.max_feed) and self.max_feed > 0):
                raise ProgramError("max-feed", f"max-feed {self.max_feed!r}: give a feed above 0")
        if self.spindle is not None and not (math.isfinite(self.spindle) and self.spindle > 0):
            raise ProgramError("spindle", f"spindle {self.spindle!r} rpm: give the spindle's "
                               "highest speed, above 0")
        if not (math.isfinite(self.trigger) and self.trigger >= 0):
            raise ProgramError("trigger", f"trigger {self.trigger!r} s: give 0 s or more")
        for a, s in self.sign.items():
            if s not in (1, -1):
                raise ProgramError("sign", f"sign {s!r} for {a}: give +1 or -1")
        for a, lim in self.limits.items():
            lo, hi = (float(v) for v in lim)
            if not (math.isfinite(lo) and math.isfinite(hi) and lo < hi):
                raise ProgramError("limits", f"limits {lo:g}:{hi:g} for {a}: give the lowest "
                                   "then the highest position, finite")
        for name in ("safe", "origin"):
            for a, v in getattr(self, name).items():
                if not math.isfinite(float(v)):
                    raise ProgramError(name, f"{name} {v!r} for {a}: give a finite position")

    def machine(self, axis: str, position: float) -> float:
        """Machine coordinate of plan ``position`` on ``axis`` (plan unit)."""
        return self.origin.get(axis, 0.0) + self.sign.get(axis, 1) * position

    def check_feed(self, feed: float, unit: str, option: str = "feed") -> None:
        if not (math.isfinite(feed) and feed > 0):
            raise ProgramError(option, f"{option} {feed:g} {unit}/min: give a feed above 0")
        if self.max_feed is not None and feed > self.max_feed:
            raise ProgramError(option, f"{option} {feed:g} {unit}/min is beyond the machine's "
                               f"max-feed {self.max_feed:g} {unit}/min")


# -- blocks ------------------------------------------------------------------------------------
@dataclass(frozen=True)
class Comment:
    text: str


@dataclass(frozen=True)
class Rapid:
    """Rapid traverse to ``to`` (``((letter, machine position), ...)``, in XYZABC order)."""

    to: tuple

    def __post_init__(self) -> None:
        object.__setattr__(self, "to", tuple(sorted(self.to, key=lambda w: "XYZABC".index(w[0]))))


@dataclass(frozen=True)
class Feed:
    """Straight move at ``feed`` (machine unit per minute) to ``to``."""

    to: tuple
    feed: float


@dataclass(frozen=True)
class ArcMove:
    """Circular move in the plane ``(first, second)`` from ``start`` to ``end`` about ``centre``
    (machine positions), counter-clockwise when ``ccw``, at ``feed``; at most 180°."""

    plane: str
    start: tuple
    end: tuple
    centre: tuple
    ccw: bool
    feed: float


@dataclass(frozen=True)
class Dwell:
    seconds: float


@dataclass(frozen=True)
class Spindle:
    """Spindle on clockwise at ``rpm`` (whole revolutions per minute), or off when 0."""

    rpm: int


@dataclass(frozen=True)
class Motion:
    """A plan's motion in machine coordinates: ``blocks`` in order, the axes, each axis's
    unit (``mm``, ``inch`` or ``deg``), a title and a short kind (``linear`` ...)."""

    kind: str
    title: str
    axes: tuple
    units: dict
    blocks: tuple
    plane: str = ""

    @property
    def metric(self) -> bool:
        return "inch" not in self.units.values()


def build_motion(plan, options: MachineOptions) -> Motion:
    """The motion of ``plan`` on the machine ``options`` describes, checked (module docstring)."""
    from axiscal.procedures.circular_plan import CircularPlan, LinePlan
    from axiscal.procedures.positioning import TestPlan

    if isinstance(plan, CircularPlan):
        return _circular(plan, options)
    if isinstance(plan, LinePlan):
        return _lines(plan, options)
    if isinstance(plan, TestPlan):
        return _positioning(plan, options)
    raise ProgramError("plan", f"no part program for a {type(plan).__name__}")


class _Builder:
    """Collects blocks in machine units and checks every position against the limits."""

    def __init__(self, options: MachineOptions, unit: dict):
        self.o, self.unit = options, unit

    def scale(self, axis: str) -> float:
        return 1 / 25.4 if self.unit[axis] == "inch" else 1.0

    def at(self, axis: str, plan_pos: float, what: str, option: str) -> tuple:
        """(axis, machine position in program units) of plan ``plan_pos``, checked."""
        return self.at_machine(axis, self.o.machine(axis, plan_pos), what, option)

    def at_machine(self, axis: str, m: float, what: str, option: str | None) -> tuple:
        """(axis, program position) of machine position ``m`` (plan unit), checked unless
        ``option`` is None."""
        if option is not None:
            self.check(axis, m, what, option)
        return axis, round(m * self.scale(axis), 9)

    def check(self, axis: str, m: float, what: str, option: str) -> None:
        lim = self.o.limits.get(axis)
        if lim is None:
            return
        lo, hi = (float(v) for v in lim)
        if not lo - 1e-9 <= m <= hi + 1e-9:
            u = "deg" if self.unit[axis] == "deg" else "mm"
            raise ProgramError(option, f"{what} takes {axis} to {m:g} {u}, beyond the limits "
                               f"{lo:g}:{hi:g} {u}: {_ADVICE[option]}")

    def feed(self, axis_feed: float, axis: str) -> float:
        return round(axis_feed * self.scale(axis), 6)


_ADVICE = {"overrun": "give a smaller overrun or wider limits",
           "limits": "move the targets inside (start, length or travel) or widen the limits",
           "safe": "give a safe start inside the limits",
           "radius": "give a smaller radius, another centre or wider limits",
           "set-in": "give a smaller set-in or wider limits",
           "clearance": "give a smaller clearance or wider limits"}


def _header(plan) -> list:
    return [Comment(str(plan)),
            Comment("written by axiscal: check it on the machine before the test")]


def _positioning(plan, options: MachineOptions, fixed=()) -> Motion:
    """A positioning plan's motion (``fixed``: the other axes' positions on a line)."""
    axis = (plan.axis or ("X" if plan.axis_kind.value == "linear" else "C")).upper()
    letters = "XYZUVW" if plan.axis_kind.value == "linear" else "ABC"
    if len(axis) != 1 or axis not in letters:
        raise ProgramError("axis", f"axis {plan.axis!r}: a program commands a "
                           f"{plan.axis_kind.value} axis by one of the letters "
                           f"{', '.join(letters)}")
    unit_name = "deg" if plan.target_unit == "deg" else options.units
    unit = {axis: unit_name, **{a: options.units for a, _ in fixed}}
    b = _Builder(options, unit)
    _check_dwell(plan.dwell, options)
    options.check_feed(options.feed, plan.target_unit)
    steps = plan.steps()
    if len(steps) > MAX_BLOCKS:
        raise ProgramError("targets", f"{len(steps)} moves: a program holds at most {MAX_BLOCKS}")
    blocks = _header(plan)
    if plan.target_unit == "deg":
        blocks.append(Comment(f"{axis} must not roll over (no modulo): the test turns it from "
                              f"{steps[0].position:g} to {max(s.position for s in steps):g} deg"))
    safe = options.safe.get(axis)
    safe_pos = (b.at_machine(axis, float(safe), "the safe start", "safe") if safe is not None
                else b.at(axis, steps[0].position, "the first approach", "overrun"))
    for t in plan.targets:        # the targets first: a target outside is not the overrun's fault
        b.at(axis, float(t), f"target {t:g} {plan.target_unit}", "limits")
    held = [b.at(a, v, f"{a} held at {v:g}", "limits") for a, v in fixed]
    blocks.append(Rapid((safe_pos, *held)))
    f = b.feed(options.feed, axis)
    here = safe_pos
    for s in steps:
        option = "overrun" if s.kind == "overrun" else "limits"
        what = (f"the overrun to {s.position:g} {plan.target_unit}" if s.kind == "overrun"
                else f"target {s.position:g} {plan.target_unit}")
        to = b.at(axis, s.position, what, option)
        if to != here:                 # the safe start may be the first approach already
            blocks.append(Feed((to,), f))
        here = to
        if s.kind == "measure":
            blocks.append(Dwell(plan.dwell))
    back = [b.at_machine(a, float(options.safe[a]), "the safe start", "safe")
            for a, _ in fixed if a in options.safe]
    blocks.append(Rapid((safe_pos, *back)))
    kind = "pilgrim" if plan.cycle == "pilgrim" else (
        "rotary" if plan.target_unit == "deg" else "linear")
    return Motion(kind, str(plan), (axis, *(a for a, _ in fixed)), unit, tuple(blocks))


def _check_dwell(dwell: float, options: MachineOptions) -> None:
    if dwell < options.trigger:
        raise ProgramError("dwell", f"dwell {dwell:g} s is shorter than the {options.trigger:g} s "
                           "of stillness the trigger needs (trigger): give a longer dwell")


def _lines(plan, options: MachineOptions) -> Motion:
    blocks, axes, unit = _header(plan), [], {}
    for k, ln in enumerate(plan.lines):
        sub = _positioning(ln.plan, options, ln.fixed)
        body = [x for x in sub.blocks if not isinstance(x, Comment)]
        blocks.append(Comment(f"line {k + 1}: {ln.plan.axis} from {ln.plan.targets[0]:g} to "
                              f"{ln.plan.targets[-1]:g} mm"))
        blocks += body[:-1] if k < len(plan.lines) - 1 else body
        for a in sub.axes:
            if a not in axes:
                axes.append(a)
        unit.update(sub.units)
    return Motion(plan.kind, str(plan), tuple(axes), unit, tuple(blocks))


def _circular(plan, options: MachineOptions) -> Motion:
    a1, a2 = plan.plane[0], plan.plane[1]
    unit = {a1: options.units, a2: options.units}
    b = _Builder(options, unit)
    options.check_feed(plan.feed, "mm")
    if options.sign.get(a1, 1) * options.sign.get(a2, 1) < 0:
        raise ProgramError("sign", f"sign: {a1} and {a2} counted opposite ways mirror the circle; "
                           "give the same sign to both (the directions would swap)")
    blocks = _header(plan)

    def pt(angle, radius=None, what="the circle", option="radius"):
        x, y = plan.point(angle, radius)
        return (b.at(a1, x, what, option), b.at(a2, y, what, option))

    # every axis's extreme on the circle, whichever arcs pass it
    for ang in range(0, 360, 90):
        pt(ang)
    arcs = plan.arcs()
    first = arcs[0]
    out = plan.radius + plan.set_in
    start = pt(first.start_deg, out, "the set-in start", "set-in")
    safe = (tuple(b.at_machine(a, float(options.safe[a]), "the safe start", "safe")
                  for a in (a1, a2)) if all(a in options.safe for a in (a1, a2)) else start)
    centre = tuple(b.at_machine(a, options.machine(a, v), "", None)
                   for a, v in zip((a1, a2), plan.centre))
    f = b.feed(plan.feed, a1)
    blocks.append(Rapid(safe))
    if safe != start:
        blocks.append(Rapid(start))
    blocks.append(Feed(pt(first.start_deg), f))
    here = first.start_deg
    for arc in arcs:
        blocks.append(Comment(f"{arc.role} arc {arc.direction} from {arc.start_deg % 360:g} deg "
                              f"through {abs(arc.sweep_deg):g} deg"))
        n = max(1, math.ceil(abs(arc.sweep_deg) / 180.0 - 1e-9))
        for k in range(n):
            a0 = arc.start_deg + arc.sweep_deg * k / n
            a_end = arc.start_deg + arc.sweep_deg * (k + 1) / n
            blocks.append(ArcMove(plan.plane, pt(a0), pt(a_end), centre, arc.sweep_deg > 0, f))
        here = arc.end_deg
    end = pt(here, out, "the set-in end", "set-in")
    blocks.append(Feed(end, f))
    blocks.append(Rapid(safe))          # always the last block (HEIDENHAIN puts M30 in it)
    return Motion("circular", str(plan), (a1, a2), unit, tuple(blocks), plane=plan.plane)
