"""The motion of a five-axis R-test plan (:class:`~axiscal.procedures.five_axis.FiveAxisPlan`).

An R-test (ISO 10791-6:2014 Annex K, the test ISO 230-1 and ISO 230-7 use for the location errors
of rotary axes) holds a precision sphere in the spindle inside a nest of three displacement
sensors on the table and reads the sphere's displacement at each rotary pose. The program below
does it pose by pose ("discrete" measurement) with the machine's nominal kinematics written out, so
that no tool-centre-point function (G43.4, TRAORI, M128, LinuxCNC's TCP kinematics) is needed:

for each pose, the sphere leaves the nest along the nest's axis (the table's +Z at that pose) to a
clearance, the spindle rises to the safe Z, the rotary axes turn to the next pose while X, Y go
over its approach point, Z comes down to it, the sphere enters the nest at the feed, and a dwell
lets the sensors read. Positions: the nominal nest place turned by the pose
(:func:`axiscal.physics.rotary_location.table_to_machine` with no location error: what the
controller's kinematics hold), in the machine frame of the configuration's ``[machine]`` (origin
at its reference; ``MachineOptions.origin`` moves it), rotary angles as LinuxCNC's trt kinematics
count them.

Probing set-ups are not programmed (their touches are the controller's sphere-probing cycle, which
axiscal does not write): the program names each one it leaves out. A spindle-head machine is
refused (its tool axis turns with the head: the approach needs the controller's TCP).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from axiscal.programs._motion import (MAX_BLOCKS, Comment, Dwell, Feed, MachineOptions, Motion,
                                      ProgramError, Rapid, _Builder, _check_dwell)

__all__ = ["FiveAxisProgram", "five_axis_motion", "BallbarProgram", "ballbar_motion", "path_points"]


@dataclass(frozen=True, eq=False)
class FiveAxisProgram:
    """A five-axis plan with its machine and what the program adds.

    Attributes
    ----------
    plan : FiveAxisPlan
    machine : FiveAxisMachine
    dwell : float, s
        At each pose, for the sensors' reading.
    clearance : float, mm
        How far the sphere leaves the nest, along the nest's axis, between poses.
    """

    plan: object
    machine: object
    dwell: float = 1.0
    clearance: float = 10.0


def five_axis_motion(plan, machine, options: MachineOptions, dwell: float = 1.0,
                     clearance: float = 10.0) -> Motion:
    """The checked motion of the R-test set-ups of ``plan`` on ``machine`` (module docstring)."""
    from axiscal.physics.rotary_location import table_to_machine
    from axiscal.standards.location_errors import R_TEST

    g = machine.geometry
    if g.head:
        raise ProgramError("machine", f"{machine.name} has a spindle head: its R-test program "
                           "needs the controller's tool centre point control, which axiscal "
                           "does not write (table-table machines only)")
    if not (np.isfinite(clearance) and clearance > 0):
        raise ProgramError("clearance", f"clearance {clearance!r} mm: give a distance above 0")
    _check_dwell(dwell, options)
    options.check_feed(options.feed, "mm")
    if "Z" not in options.safe:
        raise ProgramError("safe", "give the safe Z (safe Z=…), the machine position the "
                           "spindle rises to between poses")
    tilt = g.tilt
    letters = ("X", "Y", "Z", tilt, "C")
    unit = {a: options.units for a in "XYZ"} | {tilt: "deg", "C": "deg"}
    b = _Builder(options, unit)
    z_safe = b.at_machine("Z", float(options.safe["Z"]), "the safe Z", "safe")
    blocks = [Comment(f"R-test of {machine.name}: the nominal place of the nest turned by "
                      "each pose, no TCP needed"),
              Comment("written by axiscal: check it on the machine before the test")]
    rtests = [s for s in plan.setups if s.kind == R_TEST]
    for s in plan.setups:
        if s.kind != R_TEST:
            blocks.append(Comment(f"set-up {s.label or s.kind} ({s.kind}) is not programmed: "
                                  "its touches are a probing cycle of the controller"))
    if not rtests:
        raise ProgramError("setup", "the plan has no R-test set-up: probing set-ups are the "
                           "controller's probing cycle, which axiscal does not write")
    if sum(s.poses for s in rtests) * 6 > MAX_BLOCKS:
        raise ProgramError("poses", f"a program holds at most {MAX_BLOCKS // 6} poses")
    f = b.feed(options.feed, "X")
    blocks.append(Rapid((z_safe,)))
    for s in rtests:
        place = np.asarray(s.place, float)
        blocks.append(Comment(f"set-up {s.label or s.kind}: nest at "
                              f"{', '.join(f'{v * 1e3:g}' for v in place)} mm on the table, "
                              f"{s.poses} poses"))
        lift = place + np.array([0.0, 0.0, clearance * 1e-3])
        at = table_to_machine(g, {}, s.tilt_angle, s.c_angle, place) * 1e3
        out = table_to_machine(g, {}, s.tilt_angle, s.c_angle, lift) * 1e3
        angles = np.degrees(np.column_stack([s.tilt_angle, s.c_angle]))
        for k in range(s.poses):
            what = f"pose {tilt} {angles[k, 0]:g}, C {angles[k, 1]:g} deg"
            rot = tuple(b.at(a, float(v), what, "limits") for a, v in zip((tilt, "C"), angles[k]))
            nest = tuple(b.at(a, float(v), f"the nest at {what}", "limits")
                         for a, v in zip("XYZ", at[k]))
            approach = tuple(b.at(a, float(v), f"the approach at {what}", "clearance")
                             for a, v in zip("XYZ", out[k]))
            blocks += [Rapid((*approach[:2], *rot)), Rapid((approach[2],)), Feed(nest, f),
                       Dwell(dwell), Feed(approach, f), Rapid((z_safe,))]
    back = [b.at_machine(a, float(options.safe[a]), "the safe start", "safe")
            for a in letters if a in options.safe and a != "Z"]
    blocks[-1] = Rapid((z_safe, *back))         # the last pose's rise, with the way back
    return Motion("five-axis", str(blocks[0].text), letters, unit, tuple(blocks))


@dataclass(frozen=True, eq=False)
class BallbarProgram:
    """The ballbar set-ups of a five-axis configuration with their machine
    (:mod:`axiscal.procedures.five_axis_ballbar`) and what the program adds.

    Attributes
    ----------
    setups : tuple of BallbarSetUp
    machine : FiveAxisMachine
    dwell : float, s
        At the start and the end of each set-up's path (the ballbar's reading starts and ends).
    tolerance : float, µm
        Largest distance, in the table frame, of the spindle ball from its place between two
        programmed points (the chord of the joint-space straight move).
    """

    setups: tuple
    machine: object
    dwell: float = 1.0
    tolerance: float = 1.0


def ballbar_motion(job: BallbarProgram, options: MachineOptions) -> Motion:
    """The checked motion of the ballbar set-ups of ``job`` (joint space, no TCP).

    For each set-up: up to the safe Z, the rotary axes and X, Y to the path's start, Z down to
    it, a dwell (the bar is mounted before the program starts; the ballbar starts reading), the
    path at the feed through points dense enough that the spindle ball stays within
    ``tolerance`` of its place on the table between them (each segment's chord is measured with
    the nominal kinematics at its middle and the segment split until it is within), a dwell, and
    up to the safe Z. Every position is the nominal kinematics' (what the controller holds),
    angles as LinuxCNC's trt kinematics count them. axiscal writes no program stop: move the bar
    to the next set-up's balls during the controller's own stop (single block) or with one
    program per set-up.
    """
    machine = job.machine
    g = machine.geometry
    if g.head:
        raise ProgramError("machine", f"{machine.name} has a spindle head: its ballbar path "
                           "needs the controller's tool centre point control (table-table "
                           "machines only)")
    if not (np.isfinite(job.tolerance) and job.tolerance > 0):
        raise ProgramError("tolerance", f"tolerance {job.tolerance!r} µm: give a distance "
                           "above 0")
    _check_dwell(job.dwell, options)
    options.check_feed(options.feed, "mm")
    if "Z" not in options.safe:
        raise ProgramError("safe", "give the safe Z (safe Z=…), the machine position the "
                           "spindle rises to between set-ups")
    tilt = g.tilt
    letters = ("X", "Y", "Z", tilt, "C")
    unit = {a: options.units for a in "XYZ"} | {tilt: "deg", "C": "deg"}
    b = _Builder(options, unit)
    z_safe = b.at_machine("Z", float(options.safe["Z"]), "the safe Z", "safe")
    f = b.feed(options.feed, "X")
    blocks = [Comment(f"ballbar tests of {machine.name}: the spindle ball held on the table by "
                      "the nominal kinematics, no TCP needed"),
              Comment("written by axiscal: check it on the machine before the test"),
              Rapid((z_safe,))]
    for s in job.setups:
        a, c, xyz = path_points(machine, s, job.tolerance * 1e-6, resolution=1e-3)
        if len(blocks) + len(a) + 8 > MAX_BLOCKS:
            raise ProgramError("tolerance", f"a program holds at most {MAX_BLOCKS} moves: give "
                               "a larger tolerance or fewer set-ups")
        blocks.append(Comment(f"set-up {s.label}: {s.direction} bar {s.length * 1e3:g} mm from "
                              f"the table ball at {', '.join(f'{v * 1e3:g}' for v in s.pivot)} "
                              f"mm, {len(a)} points"))
        pts = [tuple(b.at(ax, float(v), f"{s.label} point {k + 1}", "limits")
                     for ax, v in zip(letters, (*(xyz[k] * 1e3), np.degrees(a[k]),
                                                np.degrees(c[k]))))
               for k in range(len(a))]
        blocks += [Rapid((*pts[0][:2], *pts[0][3:])), Rapid((pts[0][2],)), Dwell(job.dwell)]
        blocks += [Feed(p, f) for p in pts[1:]]
        blocks += [Dwell(job.dwell), Rapid((z_safe,))]
    back = [b.at_machine(ax, float(options.safe[ax]), "the safe start", "safe")
            for ax in letters if ax in options.safe and ax != "Z"]
    if back:
        blocks.append(Rapid(tuple(back)))
    return Motion("five-axis ballbar", str(blocks[0].text), letters, unit, tuple(blocks))


def path_points(machine, setup, tolerance: float, resolution: float | None = None):
    """The set-up's path densified so that a straight joint-space move between two points keeps
    the spindle ball within ``tolerance`` (m) of its place on the table (nominal kinematics):
    ``(tilt_angle, c_angle, commanded)``, rad, rad, (N, 3) m. With ``resolution`` (degrees, the
    program's least increment of an angle) the angles are rounded to it first and the linear
    positions computed for the rounded angles, so that the program's rounding of an angle moves
    no point (0.001° is 4.4 µm at 250 mm); the linear positions' own rounding (0.001 mm) stays."""
    from axiscal.physics.rotary_location import machine_to_table, table_to_machine

    g = machine.geometry
    place = setup.spindle_ball
    a, c = np.asarray(setup.tilt_angle, float), np.asarray(setup.c_angle, float)
    for _ in range(12):
        q = table_to_machine(g, {}, a, c, place)
        mid = machine_to_table(g, {}, (a[1:] + a[:-1]) / 2, (c[1:] + c[:-1]) / 2,
                               (q[1:] + q[:-1]) / 2)
        err = np.linalg.norm(mid - place, axis=1)
        if err.max() <= tolerance:
            if resolution is None:
                return a, c, q
            a, c = (np.radians(np.round(np.degrees(x) / resolution) * resolution) for x in (a, c))
            keep = np.r_[True, (np.diff(a) != 0) | (np.diff(c) != 0)]
            a, c = a[keep], c[keep]
            return a, c, table_to_machine(g, {}, a, c, place)
        split = np.maximum(1, np.ceil(np.sqrt(err / tolerance) * 1.05)).astype(int)
        frac = [np.arange(k) / k for k in split]
        a = np.concatenate([a[i] + (a[i + 1] - a[i]) * t for i, t in enumerate(frac)] + [a[-1:]])
        c = np.concatenate([c[i] + (c[i + 1] - c[i]) * t for i, t in enumerate(frac)] + [c[-1:]])
    raise ProgramError("tolerance", f"the path of {setup.label} does not reach the tolerance "
                       f"{tolerance * 1e6:g} µm")
