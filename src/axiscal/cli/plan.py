"""``axiscal plan linear|rotary``: ISO 230-2 test plans, printed or exported as CSV.

The CSV (``--csv FILE``) has the columns ``seq,kind,position,direction,run,target_index,dwell_s``
after one comment line; ``kind`` is ``measure`` (take a reading after the dwell) or ``overrun``
(a reversing move). ``--json`` prints ``targets``, ``target_unit``, ``runs``, ``cycle``,
``bidirectional``, ``overrun``, ``dwell``, ``n_measurements`` and ``steps`` (one object per move:
``seq``, ``kind``, ``position``, ``direction``, ``run``, ``target_index``; the dwell is ``dwell``).
"""

from __future__ import annotations

from pathlib import Path
from typing import Optional

import typer

from axiscal.cli._common import note, print_json, typed_path

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

plan_app = typer.Typer(help="Make ISO 230-2 test plans (targets, runs, cycle) for a real or simulated axis.",
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
) -> None:
    """Plan a linear-axis positioning test (irregular target spacing, ISO 230-2 §5.2).

    Example: axiscal plan linear --length 800 --csv plan.csv
    """
    from axiscal.procedures.positioning import plan_linear

    _check_csv(csv)
    p = plan_linear(length, start, n_targets, irregularity, seed, runs, cycle, not unidirectional,  # type: ignore[arg-type]
                    overrun, dwell, axis)
    _emit(p, csv, json_out)


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
    _emit(p, csv, json_out)


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
