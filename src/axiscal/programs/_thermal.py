"""The motion of an ISO 230-3 thermal test's plan (:class:`~axiscal.procedures.thermal.ThermalPlan`).

What each test's program does (the plan's durations, speeds and targets, as
:func:`~axiscal.procedures.thermal.simulate_thermal` runs them on the twin; the spindle test is
ISO 230-3:2020 Clause 6, the linear-axis test Clause 7):

=============  =================================================================================
spindle        ``S`` at the plan's speed (its fraction of ``MachineOptions.spindle``, the highest
               speed) for the run, or the plan's speed programme's steps repeated through it; then
               the spindle off (``M5``) and a dwell for the stop (the sensors keep reading)
linear         one cycle per sampling interval for the run: at P1 a dwell, to P2 at the feed that
               keeps the axis moving the plan's ``duty`` of the time (2 |P2 − P1| in
               ``duty × interval``), a dwell at P2, back to P1; each dwell
               ``(1 − duty) × interval / 2`` (the measurement at each end, checked against the
               trigger); then at P1 for the stop
drift-check    to the set-up's position, then a dwell for the check's duration (ISO 230-2:2014
               Annex A.5: the machine at rest where the test stands)
etve           none: the ETVE test (ISO 230-3:2020 Clause 5) keeps the machine at rest, with no
               program running; refused with that reason
=============  =================================================================================

A dwell longer than an hour is written as several of at most an hour (HEIDENHAIN's Cycle 9 takes
0 to 3600 s; the others are given the same pieces so that every program reads alike).
"""

from __future__ import annotations

import math

from axiscal.programs._motion import (MAX_BLOCKS, Comment, Dwell, Feed, MachineOptions, Motion,
                                      ProgramError, Rapid, Spindle, _Builder, _check_dwell)

__all__ = ["thermal_motion"]

#: Longest single dwell written, s (HEIDENHAIN Cycle 9's input range).
MAX_DWELL_PIECE_S = 3600.0


def thermal_motion(plan, options: MachineOptions) -> Motion:
    """The checked motion of a thermal test plan (module docstring)."""
    what = ("ISO 230-2:2014 Annex A.5 drift check" if plan.test == "drift-check"
            else f"ISO 230-3:2020 {plan.test} test")
    head = [Comment(f"{what}: {_span(plan.duration)}, a reading every {plan.interval:g} s"),
            Comment("written by axiscal: check it on the machine before the test")]
    if plan.test == "etve":
        raise ProgramError("test", "an ETVE test (ISO 230-3:2020 Clause 5) keeps the machine at "
                           "rest with no program running: there is no part program to write")
    if plan.test == "spindle":
        return _spindle(plan, options, head)
    if plan.test == "linear":
        return _linear(plan, options, head)
    return _drift_check(plan, options, head)


def _span(seconds: float) -> str:
    """A duration as people write it: minutes below two hours, else hours (3 digits)."""
    return f"{seconds / 60:.3g} min" if seconds < 7200 else f"{seconds / 3600:.3g} h"


def _dwells(seconds: float) -> list:
    n = max(1, math.ceil(seconds / MAX_DWELL_PIECE_S - 1e-9))
    return [Dwell(seconds / n)] * n


def _spindle(plan, options: MachineOptions, head: list) -> Motion:
    if options.spindle is None:
        raise ProgramError("spindle", "the spindle test runs at a fraction of the spindle's "
                           "highest speed: give it (spindle, rpm)")
    steps = plan.programme or ((plan.speed, plan.run),)
    blocks = head + [Comment(f"spindle run {_span(plan.run)}, then stopped "
                             f"{_span(plan.duration - plan.run)}")]
    left, k = plan.run, 0
    while left > 1e-9:
        fraction, seconds = steps[k % len(steps)]
        seconds = min(seconds, left)
        rpm = round(fraction * options.spindle)
        blocks += [Spindle(rpm) if rpm else Spindle(0)] + _dwells(seconds)
        left -= seconds
        k += 1
        if len(blocks) > MAX_BLOCKS:
            raise ProgramError("programme", f"the speed programme makes more than {MAX_BLOCKS} "
                               "blocks over the run: give longer steps")
    blocks.append(Spindle(0))
    if plan.duration - plan.run > 1e-9:
        blocks += _dwells(plan.duration - plan.run)
    return Motion("thermal-spindle", head[0].text, (), {}, tuple(blocks))


def _linear(plan, options: MachineOptions, head: list) -> Motion:
    axis = plan.axis.upper()
    b = _Builder(options, {axis: options.units})
    p1, p2 = (b.at(axis, t * 1e3, f"P{k} {t * 1e3:g} mm", "limits")
              for k, t in enumerate(plan.targets, 1))
    length = abs(plan.targets[1] - plan.targets[0]) * 1e3
    moving = plan.duty * plan.interval
    if moving <= 0:
        raise ProgramError("duty", f"duty {plan.duty:g}: the axis must move part of each "
                           "interval (give a duty above 0)")
    feed = 2 * length / moving * 60.0
    options.check_feed(feed, "mm", "duty")
    dwell = (plan.interval - moving) / 2
    _check_dwell(dwell, options)
    cycles = round(plan.run / plan.interval)
    if 4 * cycles > MAX_BLOCKS:
        raise ProgramError("interval", f"{cycles} cycles: a program holds at most "
                           f"{MAX_BLOCKS // 4}")
    f = b.feed(feed, axis)
    blocks = head + [Comment(f"{cycles} cycles P1-P2-P1 at {feed:.1f} mm/min, a dwell of "
                             f"{dwell:g} s at each end, then at P1 for "
                             f"{_span(plan.duration - cycles * plan.interval)}"),
                     Rapid((p1,))]
    for _ in range(cycles):
        blocks += [Dwell(dwell), Feed((p2,), f), Dwell(dwell), Feed((p1,), f)]
    rest = plan.duration - cycles * plan.interval
    if rest > 1e-9:
        blocks += _dwells(rest)
    blocks.append(Rapid((p1,)))
    return Motion("thermal-linear", head[0].text, (axis,), {axis: options.units}, tuple(blocks))


def _drift_check(plan, options: MachineOptions, head: list) -> Motion:
    axis = plan.axis.upper()
    b = _Builder(options, {axis: options.units})
    at = b.at(axis, plan.position * 1e3, f"the position {plan.position * 1e3:g} mm", "limits")
    blocks = head + [Rapid((at,))] + _dwells(plan.duration) + [Rapid((at,))]
    return Motion("thermal-drift-check", head[0].text, (axis,), {axis: options.units},
                  tuple(blocks))
