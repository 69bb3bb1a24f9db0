"""``axiscal volumetric ...``: the 21 geometric errors of a three-axis machine, mapped,
compensated and verified on the body diagonals.

Commands: ``simulate [--out DIR]`` (a simulated machine with all 21 errors, measured by the
simulated laser tests; ``--out`` writes the measured files and a configuration), ``map CONFIG``
(the volumetric error field, its figures and the body diagonals; ``--inline FILE`` writes the
configuration with every error inline, the one file ``history add`` keeps), ``compensate CONFIG
--controller C`` (positioning and cross-axis tables; ``--verify`` re-measures a simulated
machine with them applied). The configuration format is in :mod:`axiscal.io.volumetric`.

JSON output (``--json``), stable keys, units in the key names:

* ``map``: ``machine``, ``chain``, ``tool_offset_mm``, ``largest_um``, ``largest_at_mm``,
  ``range_um`` (``X``, ``Y``, ``Z``), ``grid_points``, ``diagonals`` (list of ``name``,
  ``start_mm``, ``end_mm``, ``range_um``), ``missing`` (error motions taken as zero); for a
  simulated configuration also ``truth`` (``largest_um``, ``range_um``) and
  ``mapped_minus_true_um`` (largest |mapped − true| over the grid).
  ``quantities`` (schema 1: ``largest``, ``range_X`` …, ``diagonal_PPP`` … with ``U`` and
  ``k``), ``uncertainty_inputs`` and ``uncertainty_budget``: the budget of
  :mod:`axiscal.standards.iso230_9_volumetric` from the user configuration's
  ``[volumetric_uncertainty]`` (and an inline error's own ``U``), as the history stores it.
* ``compensate``: ``controller``, ``receiving``, ``files`` (names written), ``left_by_tables_um``;
  with ``--verify`` also ``verify``: ``figures`` (name -> ``before_um``, ``after_um``,
  ``reduction``), ``spindle_tilt_um_per_m``, ``left_by_tables_um``. With ``--controller
  linuxcnc --on-controller`` (measured through LinuxCNC) each figure has also ``tables_um`` and
  ``tables_reduction`` (tables alone; ``after_um`` is with the 3-D correction), and ``verify``
  has ``moves``, ``largest_applied_difference_um`` and ``on_controller`` (settings); the files
  are the COMP_FILEs, ``volcomp.json`` and the HAL component (``grid_spacing_mm``).
* ``simulate``: ``seed``, ``chain``, ``squareness_um_per_m`` (true ``xy``, ``yz``, ``zx``),
  ``measured_squareness_um_per_m``, ``largest_um`` (true), ``mapped_minus_true_um``, ``config``
  (the written configuration, or null).
"""

from __future__ import annotations

from pathlib import Path
from typing import Optional

import typer

from axiscal.cli._common import note, plot_path, print_json, report_path
from axiscal.io.simulation_results import TRUE_SQUARENESS_UM_PER_M

__all__ = ["register"]

app = typer.Typer(help="Volumetric accuracy of a three-axis machine: the 21 geometric errors "
                  "(ISO 230-1) mapped by the rigid-body model (ISO/TR 16907), compensated by "
                  "tables, verified on the body diagonals (ISO 230-6). Format: README, "
                  "'Volumetric configuration'.", no_args_is_help=True)

_JSON = typer.Option(False, "--json", help="Print the result as JSON (stable keys).")
_TRUE_SQUARENESS = TRUE_SQUARENESS_UM_PER_M


@app.command("simulate")
def simulate(
    out: Optional[Path] = typer.Option(None, "--out", help="Folder for the measured files and "
                                       "volumetric.toml (created if missing)."),
    seed: int = typer.Option(1, "--seed", min=0, help="Random seed of the machine and the "
                             "measurement noise."),
    chain: str = typer.Option("X Y | Z", "--chain", help="Kinematic chain, work-piece side | "
                              "tool side, e.g. 'X Y | Z' or '| X Y Z'."),
    points: int = typer.Option(21, "--points", min=2, max=1000, help="Targets per axis."),
    as_json: bool = _JSON,
):
    """A simulated machine with all 21 errors, measured by the simulated laser tests.

    Example: axiscal volumetric simulate --out vol && axiscal volumetric map vol/volumetric.toml
    """
    import numpy as np

    from axiscal.machines.three_axis import simulated_machine
    from axiscal.procedures.volumetric import MeasurementNoise, measure_tests, true_field
    from axiscal.standards.volumetric import KinematicChain, map_volume

    KinematicChain.parse(chain)
    if out is not None:
        _folder(out)
    rng = np.random.default_rng(seed)
    machine = simulated_machine(rng, chain=chain, squareness_um_per_m=_TRUE_SQUARENESS)
    errors, tests = measure_tests(machine, rng, points=points, tool_offset=(0, 0, -0.1))
    exact = measure_tests(machine, np.random.default_rng(0), points=points,
                          tool_offset=(0, 0, -0.1), noise=MeasurementNoise(0, 0, 0, 0))[0]
    mapped = map_volume(errors, 11)
    truth = map_volume(errors, 11, field=true_field(machine, tool_offset=(0, 0, -0.1)))
    cfg = None
    if out is not None:
        from axiscal.io.volumetric import write_simulation

        cfg = write_simulation(out, machine, errors, tests, seed, _TRUE_SQUARENESS, points)
    diff = float(np.abs(mapped.error - truth.error).max())
    if as_json:
        print_json({"seed": seed, "chain": str(machine.chain),
                    "squareness_um_per_m": {k: v * 1e6 for k, v in exact.squareness.items()},
                    "measured_squareness_um_per_m": {k: v * 1e6 for k, v in
                                                     errors.squareness.items()},
                    "largest_um": truth.largest * 1e6, "mapped_minus_true_um": diff * 1e6,
                    "config": str(cfg) if cfg else None})
        return
    typer.echo(f"{machine.name}, chain {machine.chain}, seed {seed}: 21 errors measured "
               f"({points} targets per axis)")
    sq = ", ".join(f"{k.upper()} {v * 1e6:+.2f} (true {exact.squareness[k] * 1e6:+.2f})"
                   for k, v in errors.squareness.items())
    typer.echo(f"  squareness measured µm/m: {sq}")
    typer.echo(f"  true volumetric error: {truth}")
    typer.echo(f"  mapped from the measured errors: {mapped}")
    typer.echo(f"  largest |mapped − true| over the 11³ grid: {diff * 1e6:.3f} µm")
    if cfg:
        typer.echo(f"  wrote {cfg} and the 18 measured files beside it")


@app.command("map")
def map_(
    config: Path = typer.Argument(..., help="Volumetric configuration (TOML)."),
    grid: int = typer.Option(11, "--grid", min=2, max=100, help="Grid points per axis (at most 100: 10^6 points, about 0.6 GB)."),
    plot: Optional[Path] = typer.Option(None, "--plot", help="Write the 3-D grid and slices "
                                        "(.png, .svg, .pdf)."),
    report: Optional[Path] = typer.Option(None, "--report", help="Write the map's report (error field, body diagonals, inputs): HTML (.html) or PDF (.pdf, WeasyPrint)."),
    inline: Optional[Path] = typer.Option(None, "--inline", help="Write the configuration with every measured file's error inline (.toml): one self-contained file, the one 'axiscal history add' keeps as a volumetric test."),
    as_json: bool = _JSON,
):
    """The volumetric error at every point of the working volume, and the body diagonals.

    Example: axiscal volumetric map vol/volumetric.toml --plot vol.png --report vol.html
    """
    from axiscal import api

    plot = plot_path(plot) if plot else None
    report = report_path(report) if report else None
    if inline:
        from axiscal.cli._common import typed_path

        inline = typed_path(inline, "--inline", (".toml",))
    mapped = api.volumetric_map(config, grid)
    sim = mapped.test
    cfg = sim.parts["config"]
    from axiscal.report.simulation_views import volumetric_map_record

    rec = volumetric_map_record(sim)      # its U: a bad [volumetric_uncertainty] writes nothing
    if inline:
        _write_inline(config, inline, cfg)
    e = cfg.errors
    vmap, diags, truth, out = sim.record, sim.parts["diagonals"], sim.parts["truth"], sim.json
    if plot:
        mapped.plot().savefig(plot, dpi=110)
    if report:
        mapped.report(report)
    if as_json:
        print_json(rec.stored_result())     # = mapped.to_dict(): the same record
        return
    typer.echo(f"volumetric map of {cfg.name} (chain {e.chain}), {grid}³ grid, tool offset "
               f"{', '.join(f'{v * 1e3:g}' for v in cfg.tool_offset)} mm")
    typer.echo(f"  {vmap}")
    for d in diags:
        typer.echo(f"  body diagonal {d.name}: range {d.range * 1e6:.2f} µm")
    if e.missing:
        note(f"not measured, taken as zero: {', '.join(e.missing)}")
    if truth is not None:
        typer.echo(f"  simulation truth: {truth}; largest |mapped − true| "
                   f"{out['mapped_minus_true_um']:.3f} µm")
    from axiscal.standards.uncertainty_reporting import format_uncertainty, format_value

    typer.echo(f"  with their expanded uncertainty (k = {rec.budget.k:g}; {rec.budget.method}; "
               "inputs in the user configuration's [volumetric_uncertainty]): " + "; ".join(
                   f"{q.name} {format_value(q.value, q.U)} ± {format_uncertainty(q.U)} µm"
                   for q in rec.quantities.values() if q.U is not None))



@app.command("compensate")
def compensate(
    config: Path = typer.Argument(..., help="Volumetric configuration (TOML)."),
    controller: str = typer.Option(..., "--controller", help="siemens-840d, heidenhain, csv, "
                                   "or linuxcnc (a COMP_FILE per joint and the 3-D correction "
                                   "through external offsets, docs/linuxcnc.md)."),
    out: Optional[Path] = typer.Option(None, "--out", help="Folder for the tables (created if "
                                       "missing)."),
    receiving: list[str] = typer.Option([], "--receiving", help="Axis receiving a squareness "
                                        "correction, e.g. zx=Z (repeatable; default xy=Y yz=Z "
                                        "zx=Z: the axis aligned to the spindle)."),
    spacing: float = typer.Option(20.0, "--spacing", min=0.001, max=10000.0,
                                  help="Table spacing, mm."),
    verify: bool = typer.Option(False, "--verify", help="Apply the tables to the simulated "
                                "machine and re-measure (a simulated configuration only)."),
    on_controller: bool = typer.Option(False, "--on-controller", help="With --controller "
                                       "linuxcnc --verify: measure through a real LinuxCNC "
                                       "(headless simulation): bare, tables alone, tables + "
                                       "the 3-D correction, in one run."),
    as_json: bool = _JSON,
):
    """Positioning and cross-axis tables that remove what tables can (Chapman's Appendix II).

    In the order of Chapman, "Calibration of machine squareness", Appendix II.

    Example: axiscal volumetric compensate vol/volumetric.toml --controller siemens-840d --verify
    """
    from axiscal import api
    from axiscal.errors import InputError

    rec = {}
    for item in receiving:
        if "=" not in item:
            raise InputError(f"--receiving {item!r}: write PAIR=AXIS, e.g. zx=Z")
        k, v = item.split("=", 1)
        rec[k.strip().lower()] = v.strip()
    if on_controller and controller != "linuxcnc":
        raise InputError(f"--on-controller runs LinuxCNC; the controller is {controller!r}: "
                         "give --controller linuxcnc")
    if controller == "linuxcnc" and verify != on_controller:
        raise InputError("--controller linuxcnc verifies through LinuxCNC itself: give both "
                         "--verify and --on-controller, or neither")
    sim = api.volumetric_compensation(config, controller, out=out, receiving=rec,
                                      spacing=spacing, verify=verify)
    if as_json:
        print_json(sim.to_dict())
        return
    run, tables = sim.test, sim.result
    name, written, result = run.parts["config"].name, run.json["files"], run.parts["verify"]
    comp = run.parts.get("linuxcnc")
    if comp is None:
        files = run.parts["files"]
        typer.echo(f"{controller} volumetric compensation of {name}: "
                   f"{len(files)} tables (3 positioning, {len(files) - 3} cross-axis)")
    else:
        typer.echo(f"linuxcnc volumetric compensation of {name}: a COMP_FILE per joint, "
                   f"{len(comp.cross)} cross-axis tables and the 3-D grid (every ≤ "
                   f"{comp.spacing:g} mm) for axiscal_volcomp.py through external offsets")
    typer.echo(str(tables))
    for n in tables.notes if comp is None else ():
        note(n)
    if written:
        where = "" if comp is None else " (docs/linuxcnc.md: INI and HAL lines)"
        typer.echo(f"wrote {', '.join(written)} in {out}{where}")
    if result is not None:
        typer.echo(str(result))


def _write_inline(config: Path, out: Path, cfg) -> None:
    """``--inline``: the configuration with its errors inline
    (:func:`axiscal.io.volumetric.format_volumetric_inline`), never over one of its inputs."""
    from axiscal.errors import InputError
    from axiscal.io._files import read_text, write_text_atomic
    from axiscal.io.volumetric import format_volumetric_inline

    if any(out.resolve() == Path(p).resolve() for p in cfg.inputs):
        raise InputError(f"--inline {out}: it is one of the files the configuration is read "
                         "from; write it elsewhere")
    write_text_atomic(out, format_volumetric_inline(read_text(config), cfg))
    note(f"wrote {out} (every error inline)")


def _folder(out: Path) -> None:
    from axiscal.errors import InputError

    try:
        out.mkdir(parents=True, exist_ok=True)
    except OSError as exc:
        raise InputError(f"cannot create folder {out}: {exc.strerror or exc}") from None


def register(root: typer.Typer) -> None:
    """Add the ``volumetric`` command group to the application."""
    root.add_typer(app, name="volumetric")
