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

__all__ = ["FiveAxisProgram", "five_axis_motion"]


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
