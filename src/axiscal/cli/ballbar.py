"""``axiscal ballbar analyze|simulate|volumetric``: the circular-test diagnosis.

JSON output (``--json``), stable keys:

* ``ballbar analyze``: ``file``, ``plane``, every term with its unit in the key
  (``squareness_um_per_m``, ``scale_mismatch_um_per_m``, ``servo_mismatch_ms`` (null without a
  feed), ``servo_term_um``, ``backlash_x_um``, ``backlash_y_um``, ``lateral_play_x_um``,
  ``lateral_play_y_um``, ``straightness_x_um``, ``straightness_y_um``, ``reversal_spike_x_um``,
  ``reversal_spike_x_decay_mm`` (and y), ``cyclic_x_um``, ``cyclic_x_pitch_mm`` (and y),
  ``stick_slip_um``, ``vibration_um``, ``vibration_hz``), ``residual_rms_um``,
  ``residual_ptp_um``, ``feed_mm_per_min``, ``iso230_4`` (the ``squareness circular`` object),
  ``ranking`` (``term``, ``value``, ``unit``, ``effect_um``, ``share_percent``, ``advice``, largest
  effect first), ``warnings``. ``iso230_4.folded`` lists, for squareness, scale mismatch and each
  backlash, what the ISO 230-4 fit folds in: ``quantity``, ``unit``, ``iso230_4``, ``diagnosis``,
  ``difference``, ``folded`` (term -> amount), ``material``, ``statement``. The history stores
  this same object (with ``plane``) for a two-direction ballbar file
  (:func:`axiscal.store.kinds.evaluate_ballbar`). ``x``/``y`` are the plane's first and second axis.
  ``quantities`` (schema 1): H, G_ccw and G_cw carry ``U`` and ``k`` from the budget of
  :mod:`axiscal.standards.iso230_9_ballbar` (inputs: the user configuration's
  ``[ballbar_uncertainty]``), and ``uncertainty_budget`` holds it (contributors, inputs, notes).
* ``ballbar volumetric``: ``planes`` (per file: ``plane``, ``squareness_um_per_m``,
  ``scale_mismatch_um_per_m``, ``backlash_x_um``, ``backlash_y_um``), ``squareness_um_per_m``
  (object by plane), ``scale_mismatch_um_per_m`` (object by plane).
"""

from __future__ import annotations

from pathlib import Path
from typing import Optional

import typer

from axiscal.cli._common import note, plot_path, print_json, report_path

__all__ = ["register"]

ballbar_app = typer.Typer(
    help="Ballbar (circular test) diagnosis after ISO 230-4:2005 and Renishaw, Calibration of "
    "machine squareness, Method 4: every separable machine error, ranked, with advice.",
    no_args_is_help=True,
)


def analyze(
    file: Path = typer.Argument(..., help="Ballbar CSV (angle,direction,deviation; "
                                "'# radius_mm=150 feed_mm_per_min=1000 plane=XY')."),
    plane: Optional[str] = typer.Option(None, "--plane", help="XY, YZ or ZX (overrides the file)."),
    feed: Optional[float] = typer.Option(None, "--feed", help="Feed, mm/min (overrides the file)."),
    json_out: bool = typer.Option(False, "--json", help="Print JSON (stable keys, module docs)."),
    plot: Optional[Path] = typer.Option(None, "--plot", help="Polar plot and diagnostic bar chart "
                                        "(PNG/SVG/PDF)."),
    report: Optional[Path] = typer.Option(None, "--report", help="Write the diagnosis report (plot, ranked terms, ISO 230-4 values): HTML (.html) or PDF (.pdf, WeasyPrint)."),
) -> None:
    """Diagnose a CW + CCW circular test: each error, its share of the circularity, advice.

    Example: axiscal ballbar analyze examples/squareness_ballbar_150mm.csv --feed 1000
    """
    from axiscal import api

    if plot is not None:
        plot_path(plot)
    if report is not None:
        report_path(report)
    data = api.read(file, kind="ballbar")
    _two_directions(file, data)
    ev = api.evaluate(data, feed=feed, plane=plane)
    result, axes = ev.result, tuple(ev.to_dict()["plane"])
    if plot is not None:
        from axiscal.report.ballbar_plots import save_diagnosis_plot

        save_diagnosis_plot(data.runs, result, plot, title=f"Ballbar {''.join(axes)} — {file.name}")
    if report is not None:
        ev.report(report, title=f"Ballbar diagnosis {file.name}")
    if json_out:
        print_json({"file": str(file), **ev.to_dict()})
        return
    from axiscal.report.labels import quantity

    typer.echo(result.text(lambda key, ax: quantity(key, axes=ax)[0]))
    from axiscal.standards.uncertainty_reporting import format_uncertainty, format_value
    from axiscal.units import display

    with_u = [f"{quantity(q.name, axes=axes)[0]} = {format_value(q.value, q.U)} ± "
              f"{format_uncertainty(q.U)} {display(q.unit)} (k = {q.k:g})"
              for q in ev.quantities.values() if q.U is not None]
    if with_u:            # the budget of G and H (standards/iso230_9_ballbar.py)
        typer.echo("With their expanded uncertainty (ISO/TR 230-9; inputs in the user "
                   "configuration's ballbar uncertainty table): " + "; ".join(with_u))
    for path in (plot, report):
        if path is not None:
            note(f"wrote {path}")


def volumetric(
    files: list[Path] = typer.Argument(..., help="Ballbar CSV of each plane (XY, YZ, ZX)."),
    json_out: bool = typer.Option(False, "--json", help="Print JSON (stable keys, module docs)."),
) -> None:
    """Volumetric summary of three planes: the three squareness values and scale mismatches.

    Example: axiscal ballbar volumetric xy.csv yz.csv zx.csv
    """
    from axiscal import api
    from axiscal.errors import InputError

    rows = []
    for file in files:
        data = api.read(file, kind="ballbar")
        _two_directions(file, data)
        v = api.evaluate(data).result.values
        rows.append({"plane": "".join(data.axes), "file": str(file),
                     "squareness_um_per_m": v["squareness_um_per_m"],
                     "scale_mismatch_um_per_m": v["scale_mismatch_um_per_m"],
                     "backlash_x_um": v["backlash_x_um"], "backlash_y_um": v["backlash_y_um"]})
    planes = [r["plane"] for r in rows]
    if len(set(planes)) != len(planes):
        raise InputError(f"planes {', '.join(planes)}: give each plane once (plane= in the file)")
    out = {"planes": rows,
           "squareness_um_per_m": {r["plane"]: r["squareness_um_per_m"] for r in rows},
           "scale_mismatch_um_per_m": {r["plane"]: r["scale_mismatch_um_per_m"] for r in rows}}
    if json_out:
        print_json(out)
        return
    typer.echo("volumetric summary (ISO 230-4:2005 circular tests in each plane)")
    for r in rows:
        typer.echo(f"  {r['plane']}: squareness {r['squareness_um_per_m']:+8.2f} µm/m, scale "
                   f"mismatch {r['scale_mismatch_um_per_m']:+8.2f} µm/m, backlash "
                   f"{r['backlash_x_um']:+.2f} / {r['backlash_y_um']:+.2f} µm")


def _two_directions(file, data) -> None:
    """Only the diagnosis is shown here: a one-direction test is refused in one line."""
    from axiscal.errors import InputError

    if len(data.runs) != 2:
        raise InputError(f"{file}: one direction ({data.runs[0].direction}) only; the diagnosis "
                         "needs one CCW and one CW run ('axiscal squareness circular' evaluates "
                         "one direction by ISO 230-4)")


def register(app: typer.Typer) -> None:
    """Add the ``ballbar`` group to the application."""
    ballbar_app.command("analyze")(analyze)
    ballbar_app.command("volumetric")(volumetric)
    try:
        from axiscal.cli.ballbar_simulate import simulate
    except ImportError:  # pragma: no cover - the simulator lands in a later commit
        pass
    else:
        ballbar_app.command("simulate")(simulate)
    app.add_typer(ballbar_app, name="ballbar")
