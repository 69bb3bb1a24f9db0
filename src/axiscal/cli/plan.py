"""``axiscal plan linear|rotary|circular|squareness|straightness|thermal|fiveaxis``: test plans,
printed, exported as CSV, or written as part programs (``--program FILE --controller NAME``,
:mod:`axiscal.cli._program`). ``plan thermal`` takes ``axiscal thermal plan``'s options and prints
its plan; ``plan fiveaxis`` takes ``axiscal fiveaxis plan``'s and writes the R-test set-ups'
program (:mod:`axiscal.programs._five_axis`).

The CSV (``--csv FILE``) has the columns ``seq,kind,position,direction,run,target_index,dwell_s``
after one comment line; ``kind`` is ``measure`` (take a reading after the dwell) or ``overrun``
(a reversing move). ``--json`` prints ``targets``, ``target_unit``, ``runs``, ``cycle``,
``bidirectional``, ``overrun``, ``dwell``, ``n_measurements`` and ``steps`` (one object per move:
``seq``, ``kind``, ``position``, ``direction``, ``run``, ``target_index``; the dwell is ``dwell``).
``plan circular --json`` prints ``radius``, ``centre``, ``plane``, ``feed``, ``arc``,
``overshoot``, ``directions``, ``set_in`` and ``arcs`` (``role``, ``direction``, ``start_deg``,
``sweep_deg``); ``plan squareness --json`` (and ``plan straightness --json``) prints ``kind`` and ``lines`` (``axis``, ``points``,
``fixed``, ``steps``).

``--program FILE --controller NAME`` writes the part program (fanuc, haas, sinumerik, heidenhain,
linuxcnc; :mod:`axiscal.programs`), checked against ``--limits``, ``--feed``/``--max-feed`` and
``--trigger`` before anything is written.
"""

from __future__ import annotations

from pathlib import Path
from typing import List, Optional

import typer

from axiscal.cli import _program as P
from axiscal.cli._common import note, print_json, typed_path
from axiscal.cli.thermal import PLAN_OPTIONS as _T

#: Bounds of the counts a plan is asked for: beyond them a typing slip would only exhaust memory.
MAX_TARGETS, MAX_RUNS = 10_000, 100
MAX_LENGTH_MM, MAX_TRAVEL_DEG = 1e6, 36_000.0

# The options both plans take, the same for a linear and a rotary axis.
_RUNS = typer.Option(5, "--runs", min=1, max=MAX_RUNS, help="Runs per direction (ISO 230-2: 5).")
_CYCLE = typer.Option("linear", "--cycle", help="'linear' or 'pilgrim' (pilgrim step).")
_UNIDIRECTIONAL = typer.Option(False, "--unidirectional", help="Approach in the positive direction only.")
_DWELL = typer.Option(4.0, "--dwell", min=0.0, max=3600.0,
                      help="Dwell at each target before the reading, s (at most an hour).")
_CSV = typer.Option(None, "--csv", help="Export the move sequence as CSV (.csv).")
_JSON = typer.Option(False, "--json", help="Print the plan as JSON.")

plan_app = typer.Typer(help="Make test plans (ISO 230-2, 230-4 circular, squareness lines) and their part programs.",
                       no_args_is_help=True)


@plan_app.command("linear")
def plan_linear_cmd(
    length: float = typer.Option(..., "--length", max=MAX_LENGTH_MM, help="Measurement travel in mm (at most 1 km)."),
    start: float = typer.Option(0.0, "--start", help="First target in mm."),
    n_targets: Optional[int] = typer.Option(None, "--targets", min=2, max=MAX_TARGETS, help="Number of targets (default: the ISO 230-2 minimum, 5 per metre and 5 at least)."),
    irregularity: float = typer.Option(0.25, "--irregularity", help="Random offset of each target as a fraction of the interval (0 = even spacing)."),
    seed: int = typer.Option(0, "--seed", min=0, help="Seed of the random offsets, a whole number >= 0 (plans are reproducible)."),
    runs: int = _RUNS,
    cycle: str = _CYCLE,
    unidirectional: bool = _UNIDIRECTIONAL,
    overrun: float = typer.Option(5.0, "--overrun", min=0.0, max=1000.0, help="Overrun for the reversal, mm (at most 1 m)."),
    dwell: float = _DWELL,
    axis: str = typer.Option("X", "--axis", help="Axis name."),
    csv: Optional[Path] = _CSV,
    json_out: bool = _JSON,
    program: Optional[Path] = P.PROGRAM,
    controller: Optional[str] = P.CONTROLLER,
    feed: float = P.FEED,
    max_feed: Optional[float] = P.MAX_FEED,
    limits: Optional[List[str]] = P.LIMITS,
    safe: Optional[List[str]] = P.SAFE,
    sign: Optional[List[str]] = P.SIGN,
    origin: Optional[List[str]] = P.ORIGIN,
    inch: bool = P.INCH,
    trigger: Optional[float] = P.TRIGGER,
    name: str = P.NAME,
    number: Optional[int] = P.NUMBER,
) -> None:
    """Plan a linear-axis positioning test (irregular target spacing, ISO 230-2 §5.2).

    Example: axiscal plan linear --length 800 --csv plan.csv --program x.nc --controller fanuc
    """
    from axiscal.procedures.positioning import plan_linear

    _check_csv(csv)
    p = plan_linear(length, start, n_targets, irregularity, seed, runs, cycle, not unidirectional,  # type: ignore[arg-type]
                    overrun, dwell, axis)
    text = P.make_program(p, axis.upper(), program, controller, **_machine(locals()))
    _emit(p, csv, json_out)
    P.write_program_file(program, text, controller)


@plan_app.command("rotary")
def plan_rotary_cmd(
    travel: float = typer.Option(360.0, "--travel", max=MAX_TRAVEL_DEG, help="Measurement travel in degrees (at most 100 turns)."),
    start: float = typer.Option(0.0, "--start", help="First target in degrees."),
    step: Optional[float] = typer.Option(None, "--step", help="Interval between targets in degrees (default 45)."),
    n_targets: Optional[int] = typer.Option(None, "--targets", min=2, max=MAX_TARGETS, help="Number of evenly spaced targets (instead of --step)."),
    runs: int = _RUNS,
    cycle: str = _CYCLE,
    unidirectional: bool = _UNIDIRECTIONAL,
    overrun: float = typer.Option(5.0, "--overrun", min=0.0, max=360.0, help="Overrun for the reversal, degrees, at most one turn (Yüksel et al., Position accuracy and repeatability calibration of turn tables: 5)."),
    dwell: float = _DWELL,
    axis: str = typer.Option("C", "--axis", help="Axis name."),
    csv: Optional[Path] = _CSV,
    json_out: bool = _JSON,
    program: Optional[Path] = P.PROGRAM,
    controller: Optional[str] = P.CONTROLLER,
    feed: float = P.FEED,
    max_feed: Optional[float] = P.MAX_FEED,
    limits: Optional[List[str]] = P.LIMITS,
    safe: Optional[List[str]] = P.SAFE,
    sign: Optional[List[str]] = P.SIGN,
    origin: Optional[List[str]] = P.ORIGIN,
    inch: bool = P.INCH,
    trigger: Optional[float] = P.TRIGGER,
    name: str = P.NAME,
    number: Optional[int] = P.NUMBER,
) -> None:
    """Plan a rotary-axis positioning test (ISO 230-2 Table 1; 0/90/180/270 deg included).

    Example: axiscal plan rotary --travel 360 --step 45
    """
    from axiscal.errors import InputError
    from axiscal.procedures.positioning import plan_rotary

    _check_csv(csv)
    if step is not None and step > 0 and travel / step > MAX_TARGETS:
        raise InputError(f"--step {step:g} deg over {travel:g} deg gives more than {MAX_TARGETS} "
                         "targets")
    p = plan_rotary(travel, start, step, n_targets, runs, cycle, not unidirectional, overrun,  # type: ignore[arg-type]
                    dwell, axis)
    text = P.make_program(p, axis.upper(), program, controller, **_machine(locals()))
    _emit(p, csv, json_out)
    P.write_program_file(program, text, controller)


@plan_app.command("circular")
def plan_circular_cmd(
    radius: float = typer.Option(..., "--radius", max=MAX_LENGTH_MM, help="Radius of the circle (the ballbar's length), mm."),
    centre: str = typer.Option("0,0", "--centre", help="The pivot's position on the plane's two axes, mm: 'A,B'."),
    plane: str = typer.Option("XY", "--plane", help="XY, YZ or ZX (angles count from the first axis to the second)."),
    feed: float = typer.Option(1000.0, "--feed", help="Contouring feed, mm/min."),
    start_angle: float = typer.Option(0.0, "--start-angle", help="Start of the data arc, degrees."),
    arc: float = typer.Option(360.0, "--arc", help="Data arc, degrees (at most 360)."),
    overshoot: float = typer.Option(180.0, "--overshoot", help="Feed-in and feed-out arcs, degrees (0 to 360)."),
    direction: str = typer.Option("both", "--direction", help="both (CCW then CW), ccw or cw."),
    set_in: float = typer.Option(1.0, "--set-in", help="Radial distance of the start and end points outside the circle, mm."),
    json_out: bool = _JSON,
    program: Optional[Path] = P.PROGRAM,
    controller: Optional[str] = P.CONTROLLER,
    max_feed: Optional[float] = P.MAX_FEED,
    limits: Optional[List[str]] = P.LIMITS,
    safe: Optional[List[str]] = P.SAFE,
    sign: Optional[List[str]] = P.SIGN,
    origin: Optional[List[str]] = P.ORIGIN,
    inch: bool = P.INCH,
    trigger: Optional[float] = P.TRIGGER,
    name: str = P.NAME,
    number: Optional[int] = P.NUMBER,
) -> None:
    """Plan an ISO 230-4 circular (ballbar) test: overshoot arcs, both directions, at the feed.

    Example: axiscal plan circular --radius 150 --feed 1000 --program bb.nc --controller fanuc
    """
    from axiscal.errors import InputError
    from axiscal.procedures.circular_plan import plan_circular

    try:
        c = tuple(float(v) for v in centre.split(","))
    except ValueError:
        c = ()
    if len(c) != 2:
        raise InputError(f"--centre {centre!r}: give two positions in mm, as 0,0")
    dirs = {"both": ("ccw", "cw"), "ccw": ("ccw",), "cw": ("cw",)}.get(direction.strip().lower())
    if dirs is None:
        raise InputError(f"--direction {direction!r}: give both, ccw or cw")
    p = plan_circular(radius, c, plane=plane, feed=feed, start_deg=start_angle, arc_deg=arc,
                      overshoot_deg=overshoot, directions=dirs, set_in=set_in)
    text = P.make_program(p, p.plane, program, controller, **_machine(locals()))
    if json_out:
        print_json({"radius": p.radius, "centre": list(p.centre), "plane": p.plane,
                    "feed": p.feed, "arc": p.arc_deg, "overshoot": p.overshoot_deg,
                    "directions": list(p.directions), "set_in": p.set_in,
                    "arcs": [a.__dict__ for a in p.arcs()]})
    else:
        typer.echo(str(p))
    P.write_program_file(program, text, controller)


@plan_app.command("squareness")
def plan_squareness_cmd(
    axes: str = typer.Option("XY", "--axes", help="The two axes (XY, YZ or ZX)."),
    length: float = typer.Option(..., "--length", max=MAX_LENGTH_MM, help="Length of each line, mm."),
    corner: str = typer.Option("0,0", "--corner", help="The lines' common corner on the two axes, mm: 'A,B'."),
    points: int = typer.Option(5, "--points", min=2, max=MAX_TARGETS, help="Reading points on each line."),
    runs: int = typer.Option(1, "--runs", min=1, max=MAX_RUNS, help="Runs per direction on each line."),
    unidirectional: bool = _UNIDIRECTIONAL,
    overrun: float = typer.Option(5.0, "--overrun", help="Overrun for the reversal, mm."),
    dwell: float = _DWELL,
    json_out: bool = _JSON,
    feed: float = P.FEED,
    program: Optional[Path] = P.PROGRAM,
    controller: Optional[str] = P.CONTROLLER,
    max_feed: Optional[float] = P.MAX_FEED,
    limits: Optional[List[str]] = P.LIMITS,
    safe: Optional[List[str]] = P.SAFE,
    sign: Optional[List[str]] = P.SIGN,
    origin: Optional[List[str]] = P.ORIGIN,
    inch: bool = P.INCH,
    trigger: Optional[float] = P.TRIGGER,
    name: str = P.NAME,
    number: Optional[int] = P.NUMBER,
) -> None:
    """Plan a squareness test by two straightness lines from a corner (ISO 230-1 §10.3.2).

    Example: axiscal plan squareness --length 400 --program sq.h --controller heidenhain
    """
    from axiscal.errors import InputError
    from axiscal.procedures.circular_plan import plan_squareness

    try:
        c = tuple(float(v) for v in corner.split(","))
    except ValueError:
        c = ()
    if len(c) != 2:
        raise InputError(f"--corner {corner!r}: give two positions in mm, as 0,0")
    p = plan_squareness(axes, length, c, points=points, runs=runs, dwell=dwell, overrun=overrun,
                        bidirectional=not unidirectional)
    text = P.make_program(p, axes.upper(), program, controller, **_machine(locals()))
    if json_out:
        print_json({"kind": p.kind, "lines": [
            {"axis": ln.plan.axis, "points": ln.plan.targets, "fixed": dict(ln.fixed),
             "steps": [s.__dict__ for s in ln.plan.steps()]} for ln in p.lines]})
    else:
        typer.echo(str(p))
    P.write_program_file(program, text, controller)


@plan_app.command("straightness")
def plan_straightness_cmd(
    axis: str = typer.Option("X", "--axis", help="The axis that moves (X, Y or Z)."),
    length: float = typer.Option(..., "--length", max=MAX_LENGTH_MM, help="Length of the line, mm."),
    start: float = typer.Option(0.0, "--start", help="First point, mm."),
    at: Optional[List[str]] = typer.Option(None, "--at", help="Position an other axis holds, AXIS=POS mm (repeatable)."),
    points: int = typer.Option(5, "--points", min=2, max=MAX_TARGETS, help="Reading points on the line."),
    runs: int = typer.Option(1, "--runs", min=1, max=MAX_RUNS, help="Runs per direction."),
    unidirectional: bool = _UNIDIRECTIONAL,
    overrun: float = typer.Option(5.0, "--overrun", help="Overrun for the reversal, mm."),
    dwell: float = _DWELL,
    json_out: bool = _JSON,
    feed: float = P.FEED,
    program: Optional[Path] = P.PROGRAM,
    controller: Optional[str] = P.CONTROLLER,
    max_feed: Optional[float] = P.MAX_FEED,
    limits: Optional[List[str]] = P.LIMITS,
    safe: Optional[List[str]] = P.SAFE,
    sign: Optional[List[str]] = P.SIGN,
    origin: Optional[List[str]] = P.ORIGIN,
    inch: bool = P.INCH,
    trigger: Optional[float] = P.TRIGGER,
    name: str = P.NAME,
    number: Optional[int] = P.NUMBER,
) -> None:
    """Plan a straightness line: points along one axis, the others held (ISO 230-1 §8.2).

    Example: axiscal plan straightness --axis Y --length 300 --at X=100 --program y.mpf --controller sinumerik
    """
    from axiscal.errors import InputError
    from axiscal.procedures.circular_plan import plan_straightness

    import math

    held = {}
    for item in at or []:
        a, sep, v = str(item).partition("=")
        a = a.strip().upper()
        try:
            pos = float(v)
        except ValueError:
            pos = float("nan")
        if not sep or len(a) != 1 or a not in "XYZ" or not math.isfinite(pos):
            raise InputError(f"--at {item!r}: give AXIS=POS, as Y=100 (mm)")
        held[a] = pos
    p = plan_straightness(axis, length, start, at=held, points=points, runs=runs, dwell=dwell,
                          overrun=overrun, bidirectional=not unidirectional)
    axes = "".join(dict.fromkeys(axis.upper() + "".join(held)))
    text = P.make_program(p, axes, program, controller, **_machine(locals()))
    if json_out:
        print_json({"kind": p.kind, "lines": [
            {"axis": ln.plan.axis, "points": ln.plan.targets, "fixed": dict(ln.fixed),
             "steps": [s.__dict__ for s in ln.plan.steps()]} for ln in p.lines]})
    else:
        typer.echo(str(p))
    P.write_program_file(program, text, controller)


def _machine(given: dict) -> dict:
    """The machine options among a command's arguments (for :func:`P.make_program`)."""
    keys = ("feed", "max_feed", "limits", "safe", "sign", "origin", "inch", "trigger", "name",
            "number")
    return {k: given[k] for k in keys}


def _check_csv(csv: Optional[Path]) -> None:
    if csv is not None:
        typed_path(csv, "plan CSV", (".csv",))


def _emit(p, csv: Optional[Path], json_out: bool) -> None:
    if csv is not None:
        from axiscal.io._files import write_text_atomic

        write_text_atomic(csv, p.to_csv())
    if json_out:
        print_json({
            "targets": p.targets, "target_unit": p.target_unit, "runs": p.runs, "cycle": p.cycle,
            "bidirectional": p.bidirectional, "overrun": p.overrun, "dwell": p.dwell,
            "n_measurements": p.n_measurements,
            "steps": [s.__dict__ for s in p.steps()],
        })
    else:
        typer.echo(str(p))
    if csv is not None:
        note(f"wrote plan {csv} ({len(p.steps())} moves)")


def register(app: typer.Typer) -> None:
    """Add the ``plan`` command group."""
    app.add_typer(plan_app, name="plan")


@plan_app.command("thermal")
def plan_thermal_cmd(
    test: str = _T["test"], config: Optional[Path] = _T["config"],
    duration_h: Optional[float] = _T["duration_h"], run_h: Optional[float] = _T["run_h"],
    interval_s: float = _T["interval_s"], speed: float = _T["speed"], axis: str = _T["axis"],
    p1_mm: Optional[float] = _T["p1_mm"], p2_mm: Optional[float] = _T["p2_mm"],
    duty: float = _T["duty"], position_mm: Optional[float] = _T["position_mm"],
    start_h: float = _T["start_h"], programme: Optional[str] = _T["programme"],
    spindle_max: Optional[float] = typer.Option(None, "--spindle-max", help="Spindle test: the spindle's highest speed, rpm (the plan's --speed is a fraction of it)."),
    json_out: bool = _JSON,
    program: Optional[Path] = P.PROGRAM,
    controller: Optional[str] = P.CONTROLLER,
    max_feed: Optional[float] = P.MAX_FEED,
    limits: Optional[List[str]] = P.LIMITS,
    sign: Optional[List[str]] = P.SIGN,
    origin: Optional[List[str]] = P.ORIGIN,
    inch: bool = P.INCH,
    trigger: Optional[float] = P.TRIGGER,
    name: str = P.NAME,
    number: Optional[int] = P.NUMBER,
) -> None:
    """Plan an ISO 230-3 thermal test's cycle (spindle, linear axis) or a drift check.

    The linear test's feed follows from the plan (P1 to P2 and back in --duty of each
    --interval-s); an ETVE test has no program (the machine stands still).

    Example: axiscal plan thermal --test linear --run-h 4 --program heat.nc --controller fanuc
    """
    from axiscal.api._thermal import plan_thermal
    from axiscal.cli.thermal import plan_options

    p = plan_thermal(**plan_options(test, config, duration_h, run_h, interval_s, speed, axis,
                                     p1_mm, p2_mm, duty, position_mm, 0.0, start_h, programme))
    machine = _machine(dict(locals(), feed=1000.0, safe=None))
    text = P.make_program(p, p.axis.upper(), program, controller, spindle=spindle_max, **machine)
    d = p.to_dict()
    if json_out:
        print_json(d)
    else:
        typer.echo("\n".join(f"{k}: {v:g}" if isinstance(v, float) else f"{k}: {v}"
                             for k, v in d.items()))
    P.write_program_file(program, text, controller)


@plan_app.command("fiveaxis")
def plan_fiveaxis_cmd(
    config: Optional[Path] = typer.Argument(None, help="Five-axis configuration (TOML); default: the shipped example (--machine)."),
    machine_: str = typer.Option("ac", "--machine", help="The shipped example used without CONFIG: 'ac' or 'bc' (table-table)."),
    dwell: float = typer.Option(1.0, "--dwell", min=0.0, max=3600.0, help="Dwell at each pose for the R-test's reading, s."),
    clearance: float = typer.Option(10.0, "--clearance", help="How far the sphere leaves the nest between poses, along the nest's axis, mm."),
    ballbar: bool = typer.Option(False, "--ballbar", help="Write the \\[\\[ballbar]] set-ups' paths instead (axiscal fiveaxis ballbar)."),
    tolerance: float = typer.Option(1.0, "--tolerance", help="With --ballbar: how far, µm, the spindle ball may leave its place on the table between two programmed points."),
    json_out: bool = _JSON,
    program: Optional[Path] = P.PROGRAM,
    controller: Optional[str] = P.CONTROLLER,
    feed: float = P.FEED,
    max_feed: Optional[float] = P.MAX_FEED,
    limits: Optional[List[str]] = P.LIMITS,
    safe: Optional[List[str]] = P.SAFE,
    origin: Optional[List[str]] = P.ORIGIN,
    inch: bool = P.INCH,
    trigger: Optional[float] = P.TRIGGER,
    name: str = P.NAME,
    number: Optional[int] = P.NUMBER,
) -> None:
    """Plan a five-axis test and write its R-test set-ups' part program (pose by pose).

    With --ballbar, the ballbar set-ups' paths instead: the spindle ball held on the table by
    the nominal kinematics, points within --tolerance, a dwell at each path's ends.

    Each pose: out of the nest, up to the safe Z (--safe Z=...), the rotary axes to the pose, down
    and into the nest at --feed, a dwell for the reading; nominal kinematics, no TCP needed.

    Example: axiscal plan fiveaxis --machine ac --program rtest.ngc --controller linuxcnc --safe Z=200
    """
    from axiscal.api import fiveaxis
    from axiscal.cli.fiveaxis import config_for
    from axiscal.programs import BallbarProgram, FiveAxisProgram

    if ballbar:
        bb = fiveaxis.ballbar.plan(config_for(config, machine_))
        job = BallbarProgram(bb.setups, bb.machine, dwell=dwell, tolerance=tolerance)
        text = P.make_program(job, f"XYZ{bb.machine.tilt}C", program, controller,
                              **_machine(dict(locals(), sign=None)))
        if json_out:
            print_json(bb.to_dict())
        else:
            typer.echo(str(bb))
        P.write_program_file(program, text, controller)
        return
    planned = fiveaxis.plan(config_for(config, machine_))
    tilt = planned.machine.tilt
    job = FiveAxisProgram(planned.plan, planned.machine, dwell=dwell, clearance=clearance)
    text = P.make_program(job, f"XYZ{tilt}C", program, controller,
                          **_machine(dict(locals(), sign=None)))
    if json_out:
        print_json(planned.to_dict())
    else:
        typer.echo(str(planned))
    P.write_program_file(program, text, controller)
