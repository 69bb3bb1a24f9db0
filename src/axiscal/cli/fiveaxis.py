"""``axiscal fiveaxis plan|simulate|identify|compensate``: the location errors of the rotary axes of a
five-axis machine (table-table A/C or B/C, or a spindle head over a C table), from spheres probed
at many rotary poses and R-tests.

Without a configuration the shipped example is used (``--machine ac``, ``bc`` or ``head``); the format is in
the README, 'Five-axis configuration', and the files' in 'Five-axis files'.

JSON output (``--json``), stable keys, µm and µrad:

* ``plan``: ``machine``, ``tilt_axis``, ``kind`` (``table-table`` or ``head-table``), ``poses``, ``observations``, ``rank``, ``columns``,
  ``condition``, ``identifiable`` (names), ``unidentified`` (``name``, ``reason``: why and the test
  that would see it), ``convention``, ``setups`` (``label``, ``kind``, ``poses``, ``place_mm``,
  ``angles_deg`` as [tilt, C] pairs).
* ``identify``: ``plan`` (as above, without ``machine`` and ``setups``), ``errors`` (``name``,
  ``value``, ``U``, ``k``, ``unit``, ``u_components``: standard uncertainty by input),
  ``unidentified``, ``correlation`` (matrix in the order of ``errors``), ``places_mm`` (fitted
  sphere/nest place of each file, table frame), ``residual_rms_um``, ``residual_max_um``,
  ``residual_by_setup_um``, ``chi2_per_dof``, ``dof``, ``unmodelled`` (what the residual
  suggests).
* ``compensate``: ``component`` (``xyzac-trt-kins`` or ``xyzbc-trt-kins``), ``pins_mm`` (pin ->
  ``before``, ``after``), ``home_offset_change_deg`` (tilting axis -> change of HOME_OFFSET),
  ``not_held_urad`` (orientation errors no pin holds), ``sources`` (pin -> the location errors
  it takes), ``external_offsets`` (null, or what ``axiscal_trtcomp.py`` reads: ``tilt``,
  ``unit``, ``nominal`` and ``actual`` axis lines, each ``tilt`` and ``c`` as [point mm, unit
  direction, zero deg]), ``verify`` (null, or ``setups``: ``label``, ``before_um``, ``after_um``,
  ``reduction``, ``after_unmodelled_um`` (after, without noise: what the errors the correction
  cannot hold leave), ``explained`` (what ``after_um`` is expected to be: ``unmodelled_um``,
  ``noise_um`` (what the instruments' noise adds on average), ``expected_um`` (their sum),
  ``interval_95_um`` ([2.5 %, 97.5 %] of the range with noise), ``unexplained_um`` (after −
  expected), ``within_95``, ``explained`` (true when within 1 µm of expected), ``draws``):
  deviation range of each set-up on the twin, or with ``--on-controller`` of each
  probing and R-test set-up run through LinuxCNC), ``on_controller``, ``sinumerik`` (null, or
  the SINUMERIK 840D swivel data of :mod:`axiscal.compensation.five_axis_sinumerik`:
  ``carrier``, ``values`` (``$TC_CARRn`` -> mm, unit-vector component, deg or letter),
  ``meaning``, ``manuals``).
* ``ballbar plan``: ``machine``, ``tilt_axis``, ``units`` (error -> ``µm/µm`` or ``µm/µrad``),
  ``setups`` (``label``, ``kind`` (``rotary+linear`` or ``five-axis``), ``swept``,
  ``direction``, ``points``, ``pivot_mm``, ``bar``, ``length_mm``, ``spindle_ball_mm``,
  ``start_deg``, ``end_deg`` ([tilt, C]), ``sensitivity`` (error -> range per unit error),
  ``blind`` (names)).
* ``ballbar evaluate``: ``setups`` (``label``, ``range_um``, ``U_um``, ``k``, ``max_um``,
  ``min_um``, ``scatter_um``, ``points``, ``budget``, ``direction``, ``swept``), ``files``;
  ``ballbar simulate`` adds ``true_range_um`` and ``deviation_um`` per set-up.
* ``simulate``: the keys of ``identify``, and ``truth`` (the ten true location errors), per error
  ``true`` (the truth in the result's convention: sums added, on a spindle head the head's zero
  counted in the positions across) and ``deviation`` (identified − true), ``files`` (written, or empty).
"""

from __future__ import annotations

from pathlib import Path
from typing import List, Optional

import typer

from axiscal.cli._common import print_json

__all__ = ["register"]

app = typer.Typer(help="Five-axis machines: the location errors of both rotary axes (ISO 230-1, "
                  "ISO 230-7) identified from probed spheres and R-tests, with their "
                  "uncertainty.", no_args_is_help=True)

_JSON = typer.Option(False, "--json", help="Print the result as JSON (stable keys, module docs).")
_MACHINE = typer.Option("ac", "--machine", help="The shipped example used without CONFIG: 'ac' "
                        "(A/C table-table), 'bc' (B/C) or 'head' (B spindle head over C).")
_SQUARENESS = typer.Option(False, "--squareness", help="Also identify the linear axes' three "
                           "squareness errors (E_C(0X)Y, E_B(0X)Z, E_A(0Y)Z, ISO 230-1).")
_CONFIG = typer.Argument(None, help="Five-axis configuration (TOML); default: the shipped "
                         "example (--machine).")


def config_for(config: Optional[Path], machine: str):
    """``--config`` when given, else the shipped example of ``--machine`` (ac, bc, head); the
    one reading of these two options, also for ``axiscal plan fiveaxis``."""
    if config is not None:
        return config
    from importlib import resources

    from axiscal.api.fiveaxis import EXAMPLES
    from axiscal.errors import InputError

    key = {"ac": "A/C", "bc": "B/C", "head": "head B/C"}.get(machine.lower())
    if key is None:
        raise InputError(f"--machine {machine[:20]!r}: use 'ac', 'bc' or 'head'")
    from axiscal.io._files import load_toml

    return load_toml(resources.files("axiscal.data").joinpath(EXAMPLES[key]))


@app.command("plan")
def plan(config: Optional[Path] = _CONFIG, machine: str = _MACHINE,
         squareness: bool = _SQUARENESS, as_json: bool = _JSON):
    """What the planned set-ups can separate before measuring: rank, condition, the unseen.

    Example: axiscal fiveaxis plan --machine bc
    """
    from axiscal.api import fiveaxis

    _show(fiveaxis.plan(config_for(config, machine), squareness), as_json)


@app.command("simulate")
def simulate(
    config: Optional[Path] = _CONFIG,
    machine: str = _MACHINE,
    seed: int = typer.Option(1, "--seed", min=0, help="Random seed of the measurement noise."),
    out: Optional[Path] = typer.Option(None, "--out", help="Folder for the measured files "
                                       "(one CSV per set-up; created if missing)."),
    report: Optional[Path] = typer.Option(None, "--report", help="Write the report with the "
                                          "twin's truth beside: HTML (.html) or PDF (.pdf)."),
    squareness: bool = _SQUARENESS,
    on_controller: bool = typer.Option(False, "--on-controller", help="Run the probing and "
                                       "R-test set-ups through a live LinuxCNC "
                                       "(xyzac/xyzbc-trt-kins, nominal pins); the twin "
                                       "measures from its joints."),
    as_json: bool = _JSON,
):
    """Measure the twin with its simulated probe and R-test, identify, compare with the truth.

    Example: axiscal fiveaxis simulate --out run && axiscal fiveaxis identify run/*.csv
    """
    from axiscal.api import fiveaxis
    from axiscal.cli._common import report_path

    if report is not None:
        report_path(report)
    cfg = config_for(config, machine)
    sim = fiveaxis.simulate(cfg, seed=seed, out=out, squareness=squareness,
                            on_controller=on_controller)
    if report is not None:
        fiveaxis.report(cfg, sim.result, report, files=sim.files, truth=sim.truth())
    _show(sim, as_json, sim.files)


@app.command("identify")
def identify(
    files: List[Path] = typer.Argument(..., help="Probing and R-test CSV files (README, "
                                       "'Five-axis files')."),
    config: Optional[Path] = typer.Option(None, "--config", help="The machine's configuration "
                                          "(its \\[machine] table); default: the shipped example "
                                          "(--machine)."),
    machine: str = _MACHINE,
    plot: Optional[Path] = typer.Option(None, "--plot", help="Write the axis lines in 3-D "
                                        "(magnified) and the values with U (.png, .svg, .pdf)."),
    report: Optional[Path] = typer.Option(None, "--report", help="Write the report (values, "
                                          "budget, unseen, correlations, residual, figure): "
                                          "HTML (.html) or PDF (.pdf, WeasyPrint)."),
    squareness: bool = _SQUARENESS,
    as_json: bool = _JSON,
):
    """Identify the location errors from measured files, with U (k = 2) and correlations.

    Example: axiscal fiveaxis identify run/1_probing.csv run/3_r-test.csv --plot lines.png
    """
    from axiscal.api import fiveaxis
    from axiscal.cli._common import plot_path, report_path

    if plot is not None:
        plot_path(plot)
    if report is not None:
        report_path(report)
    cfg = config_for(config, machine)
    result = fiveaxis.identify(cfg, files, squareness=squareness)
    if plot is not None:
        fiveaxis.figure(cfg, result).savefig(plot, dpi=110)
    if report is not None:
        fiveaxis.report(cfg, result, report, files=files)
    _show(result, as_json)


@app.command("compensate")
def compensate(
    files: List[Path] = typer.Argument(..., help="Probing and R-test CSV files."),
    config: Optional[Path] = typer.Option(None, "--config", help="The machine's configuration; "
                                          "default: the shipped example (--machine)."),
    machine: str = _MACHINE,
    z_rot_point: float = typer.Option(0.0, "--z-rot-point", min=-1e5, max=1e5,
                                      help="The z-rot-point pin as set now, mm (kept)."),
    out: Optional[Path] = typer.Option(None, "--out", help="Write the halcmd 'setp' lines "
                                       "(.hal)."),
    table: Optional[Path] = typer.Option(None, "--table", help="Write the neutral table (CSV: "
                                         "parameter, before, after, unit, what it takes)."),
    offsets: Optional[Path] = typer.Option(None, "--offsets", help="Write the external-offset "
                                           "correction of the orientation errors no pin holds "
                                           "(trtcomp.json, read by axiscal_trtcomp.py)."),
    sinumerik: Optional[Path] = typer.Option(None, "--sinumerik", help="Write the SINUMERIK "
                                             "840D swivel data ($TC_CARR of toolholder 1, "
                                             "kinematics type P) as a part-program fragment."),
    verify: bool = typer.Option(False, "--verify", help="Re-measure the configuration's twin "
                                "before and after the correction (simulated configurations)."),
    on_controller: bool = typer.Option(False, "--on-controller", help="With --verify: run the "
                                       "probing and R-test set-ups through a live LinuxCNC "
                                       "(xyzac/xyzbc-trt-kins, external offsets) before and "
                                       "after."),
    as_json: bool = _JSON,
):
    """The correction as LinuxCNC trt pins, HOME_OFFSET, external offsets and SINUMERIK $TC_CARR.

    The sign conventions of each are printed with the values.

    Example: axiscal fiveaxis compensate run/*.csv --out trt.hal --verify --on-controller
    """
    from axiscal.api import fiveaxis
    from axiscal.cli._common import out_path

    for path, what in ((out, "the HAL file"), (table, "the neutral table"),
                       (offsets, "the external-offset file"),
                       (sinumerik, "the SINUMERIK swivel data")):
        if path is not None:
            out_path(path, what)
    comp = fiveaxis.compensate(config_for(config, machine), files, z_rot_point, verify,
                               on_controller=on_controller)
    from axiscal.io._files import write_bytes_atomic

    eo = comp.correction.external_offsets
    if offsets is not None and eo is None:
        from axiscal.errors import InputError

        raise InputError("--offsets: no orientation error was identified, so there is no "
                         "external-offset correction to write")
    if out is not None:
        write_bytes_atomic(out, comp.correction.hal().encode("utf-8"))
    if table is not None:
        write_bytes_atomic(table, comp.correction.table_csv().encode("utf-8"))
    if sinumerik is not None:
        write_bytes_atomic(sinumerik, comp.sinumerik.program().encode("utf-8"))
    if offsets is not None:
        import json

        write_bytes_atomic(offsets, (json.dumps(eo, indent=1) + "\n").encode("utf-8"))
    _show(comp, as_json, [p for p in (out, table, offsets, sinumerik) if p is not None])


ballbar_app = typer.Typer(help="Ballbar tests of the rotary axes moving with the linear axes "
                          "(ISO 10791-6:2014 kinematic tests as axiscal reads them): what each "
                          "set-up sees, the twin's readings, the range with U.",
                          no_args_is_help=True)
app.add_typer(ballbar_app, name="ballbar")


@ballbar_app.command("plan")
def ballbar_plan(config: Optional[Path] = _CONFIG, machine: str = _MACHINE,
                 as_json: bool = _JSON):
    """The \\[\\[ballbar]] set-ups, their paths, and which location errors each can see.

    Example: axiscal fiveaxis ballbar plan --machine bc
    """
    from axiscal.api import fiveaxis

    _show(fiveaxis.ballbar.plan(config_for(config, machine)), as_json)


@ballbar_app.command("simulate")
def ballbar_simulate(
    config: Optional[Path] = _CONFIG,
    machine: str = _MACHINE,
    seed: int = typer.Option(1, "--seed", min=0, help="Random seed of the ballbar's noise."),
    out: Optional[Path] = typer.Option(None, "--out", help="Folder for the readings (one CSV "
                                       "per set-up; created if missing)."),
    as_json: bool = _JSON,
):
    """Run the ballbar set-ups on the twin, evaluate each range, compare with the truth.

    Example: axiscal fiveaxis ballbar simulate --out bb && axiscal fiveaxis ballbar evaluate bb/*.csv
    """
    from axiscal.api import fiveaxis

    sim = fiveaxis.ballbar.simulate(config_for(config, machine), seed=seed, out=out)
    _show(sim, as_json, sim.files)


@ballbar_app.command("evaluate")
def ballbar_evaluate(
    files: List[Path] = typer.Argument(..., help="Ballbar CSV files (README, 'Five-axis "
                                       "ballbar tests')."),
    report: Optional[Path] = typer.Option(None, "--report", help="Write the report (set-up, "
                                          "readings, range with U, budget, inputs): HTML "
                                          "(.html) or PDF (.pdf); the history's report of a "
                                          "stored test."),
    tolerance: Optional[float] = typer.Option(None, "--tolerance", help="Upper limit of each "
                                              "range, µm: the report decides it by ISO "
                                              "14253-1:2017 (with --report)."),
    as_json: bool = _JSON,
):
    """The range of each ballbar file's readings with its uncertainty budget (k = 2).

    Example: axiscal fiveaxis ballbar evaluate bb/1_ballbar.csv --report bb.pdf --tolerance 20
    """
    from axiscal.api import fiveaxis
    from axiscal.cli._common import report_path

    if tolerance is not None and report is None:
        from axiscal.errors import InputError

        raise InputError("--tolerance is decided in the report: give --report too")
    if report is not None:
        report_path(report)
    done = fiveaxis.ballbar.evaluate(files)
    if report is not None:
        fiveaxis.ballbar.report(done, report, tolerance)
    _show(done, as_json)


def _show(result, as_json: bool, wrote=()) -> None:
    """The end of every command here: the result's ``--json`` object (``to_dict()``), or its
    text and a line for each file written."""
    if as_json:
        print_json(result.to_dict())
        return
    typer.echo(str(result))
    for path in wrote:
        typer.echo(f"wrote {path}")


def register(root: typer.Typer) -> None:
    """Add the ``fiveaxis`` command group to the application."""
    root.add_typer(app, name="fiveaxis")
