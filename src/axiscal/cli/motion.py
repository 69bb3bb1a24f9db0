"""``axiscal motion ...``: five motion errors of a rotary axis (Optics Express 2018, Five-DOF motion errors of a rotary axis) and ISO 230-7.

Commands: ``simulate CONFIG`` (one indexing test on the simulation, measured beside the truth),
``stability [CONFIG]`` (60 min every 10 s), ``repeatability CONFIG`` (three runs), ``analyze FILE``
(ISO 230-7 evaluation of a measured data file; format in :mod:`axiscal.io.motion`).

JSON output (``--json``), stable keys. Units are in the key names (``_arcsec``, ``_um``, ``_deg``).

* ``iso230_7`` object (simulate, repeatability, analyze): ``n_runs``, ``angles_deg``, ``motions``
  (list of ``name``, ``unit``, ``total``, ``synchronous``, ``asynchronous`` (null for one run),
  ``fundamental``, ``fundamental_removed``), ``location`` (``x0_um`` (null if δx not measured),
  ``y0_um``, ``a0_arcsec``, ``b0_arcsec``), ``positioning`` (``range_arcsec``,
  ``repeatability_arcsec``, ``mean_arcsec``), ``closure`` (channel -> largest 360°−0° difference,
  arcsec or µm), ``warnings``.
* ``simulate``: ``config``, ``compensated``, ``positions`` (list of ``angle_deg``, ``measured`` and
  ``truth``, each with ``ez_arcsec``, ``ey_arcsec``, ``ex_arcsec``, ``dy_um``, ``dz_um``),
  ``max_abs_error`` (same five keys), ``resolutions`` (``angular_arcsec``, ``tilt_x_arcsec``,
  ``displacement_um``), ``crosstalk`` (``inputs``, ``outputs``, ``matrix``, ``spurious``,
  ``residual``), ``iso230_7``.
* ``stability``: ``readings``, ``duration_min``, ``interval_s``, ``std`` and
  ``std_uncompensated`` (five keys), ``published_std`` (the paper's figures, five keys).
* ``repeatability``: ``runs``, ``repeatability`` (± per channel, five keys), ``published_repeatability``,
  ``iso230_7``.
* ``analyze``: ``file``, ``title``, ``iso230_7``, and the stored record's figures with their U
  (:mod:`axiscal.standards.iso230_7_uncertainty`; inputs: the user configuration's
  ``[motion_uncertainty]``): ``schema_version``, ``quantities`` (per error motion
  ``<motion>_total``, ``<motion>_synchronous`` and, for two runs or more,
  ``<motion>_asynchronous``, ``<motion>`` one of ``radial_Y``, ``radial_X``, ``axial``,
  ``tilt_X``, ``tilt_Y``; e.g. ``radial_Y_total``, ``radial_Y_synchronous``,
  ``radial_Y_asynchronous``, ``radial_X_total``, ``radial_X_synchronous``,
  ``radial_X_asynchronous``, ``axial_total``, ``axial_synchronous``, ``axial_asynchronous``,
  ``tilt_X_total``, ``tilt_X_synchronous``, ``tilt_X_asynchronous``, ``tilt_Y_total``,
  ``tilt_Y_synchronous``, ``tilt_Y_asynchronous``), ``uncertainty_budget`` (``unit``, ``k``,
  ``method``, ``U``, ``U_display``, ``U_stated``, ``U_narrow``, ``cmc``, ``floored``,
  ``contributors``, ``inputs``, ``assumed``, ``missing_inputs``, ``notes``) and
  ``uncertainty_inputs`` (the table's keys as given).
"""

from __future__ import annotations

from pathlib import Path
from typing import Optional

import typer

from axiscal.cli._common import note, plot_path, print_json, report_path, typed_path
from axiscal.io.simulation_results import MOTION_CHANNELS as _KEYS
from axiscal.report.simulation_views import MOUNTING_NOTE as _MOUNTING_NOTE

__all__ = ["register", "iso_json"]

#: The five errors as the terminal heads them (the symbols of Optics Express 2018, Five-DOF
#: motion errors of a rotary axis), not their JSON keys.
_HEADS = {"ez": "εz [″]", "ey": "εy [″]", "ex": "εx [″]", "dy": "δy [µm]", "dz": "δz [µm]"}

app = typer.Typer(help="Five motion errors of a rotary axis at once (Optics Express 2018, Five-DOF motion errors of a rotary axis) and ISO 230-7 "
                  "error motion evaluation.", no_args_is_help=True)

_JSON = typer.Option(False, "--json", help="Print the result as JSON (stable keys, see the docs).")
_REPORT = typer.Option(None, "--report", help="Write a self-contained report: HTML (.html) or PDF (.pdf, WeasyPrint).")
_PLOT = typer.Option(None, "--plot", help="Write the plot (PNG, SVG or PDF by extension).")
_SEED = typer.Option(None, "--seed", min=0, max=2**63 - 1, help="Random seed of the simulation (default: the configuration's seed, 2018).")


def _five(errors, i=None) -> dict:
    from axiscal.io.simulation_results import five_channels

    return five_channels(errors, i)


def iso_json(result) -> dict:
    """The stable JSON object of an ISO 230-7 result (see the module docstring)."""
    from axiscal.io.simulation_results import iso230_7_json

    return iso230_7_json(result)


@app.command("simulate")
def simulate(
    config: Path = typer.Argument(..., help="Configuration TOML (see examples/motion_indexing_table.toml)."),
    json_out: bool = _JSON,
    report: Optional[Path] = _REPORT,
    csv: Optional[Path] = typer.Option(None, "--csv", help="Write the measured errors as a data file "
                                       "(.csv) that 'axiscal motion analyze' reads."),
    no_compensation: bool = typer.Option(False, "--no-compensation", help="Show the errors without "
                                         "the beam-drift compensation (Optics Express 2018, Five-DOF motion errors of a rotary axis eqs. 1-6 only)."),
    plot: Optional[Path] = _PLOT,
    seed: Optional[int] = _SEED,
) -> None:
    """Simulate one indexing test (steps of step_deg, 30° by default; reference counter-rotating).

    Example: axiscal motion simulate examples/motion_indexing_table.toml --csv motion.csv
    """
    from axiscal import api

    paths = _check_outputs(report=report, csv=csv, plot=plot)
    five = api.simulate(config, seed, kind="five-dof", drift_compensation=not no_compensation)
    sim = five.test
    run, measured, result = sim.record, sim.parts["measured"], sim.parts["result"]
    ct, res = sim.parts["crosstalk"], sim.parts["resolutions"]
    if paths.get("csv"):
        five.write_data(csv)
    if paths.get("report"):
        five.report(report)
    if paths.get("plot"):
        from axiscal.report.motion_plots import save_figure

        save_figure(five.plot(), plot)
    if json_out:
        print_json(sim.json)
    else:
        _render_positions(measured, run.truth, sim.parts["machine"] or str(config))
        typer.echo(_MOUNTING_NOTE)
        typer.echo(str(res))
        typer.echo(str(ct))
        typer.echo(str(result))
    _wrote(paths)


@app.command("stability")
def stability(
    config: Optional[Path] = typer.Argument(None, help="Configuration TOML (default: the set-up of Optics Express 2018)."),
    duration_min: Optional[float] = typer.Option(None, "--duration-min", help="Duration in minutes (default: the configuration's stability_duration_min, 60)."),
    interval_s: Optional[float] = typer.Option(None, "--interval-s", help="Sampling interval in seconds (default: the configuration's stability_interval_s, 10)."),
    json_out: bool = _JSON,
    report: Optional[Path] = _REPORT,
    plot: Optional[Path] = _PLOT,
    seed: Optional[int] = _SEED,
) -> None:
    """Run the stability experiment of Optics Express 2018, Five-DOF motion errors of a rotary axis §3.2 on the simulation (still set-up).

    Example: axiscal motion stability --duration-min 10
    """
    import numpy as np

    from axiscal.procedures.motion_errors import stability_test
    from axiscal.report.motion_report import STABILITY_SEED

    from axiscal._schema import check_option
    from axiscal.errors import InputError

    check_option("--duration-min", duration_min, "min", lo=0, lo_open=True, hi=MAX_DURATION_MIN)
    check_option("--interval-s", interval_s, "s", lo=0, lo_open=True, hi=3600)
    paths = _check_outputs(report=report, plot=plot)
    cfg = _config(config)
    duration = cfg.duration if duration_min is None else 60 * duration_min
    interval = cfg.interval if interval_s is None else interval_s
    if duration / interval > MAX_READINGS:
        raise InputError(f"{duration / 60:g} min every {interval:g} s is {duration / interval:.3g} "
                         f"readings; at most {MAX_READINGS:g} are simulated (lengthen --interval-s)")
    run = stability_test(cfg.system, np.random.default_rng(_seed(cfg, seed)), duration, interval,
                         cfg.drift, cfg.drift_window)
    if paths.get("plot"):
        from axiscal.report.motion_plots import save_figure, stability_figure

        save_figure(stability_figure(run), plot)
    std = {k: float(np.std(v)) for k, v in _five(run.measured).items()}
    raw = {k: float(np.std(v)) for k, v in _five(run.uncompensated).items()}
    seed = {_KEYS[c]: v for c, v in STABILITY_SEED.items()}
    if paths.get("report"):
        from axiscal.report.motion_report import motion_report

        motion_report("Stability of the five-DOF measuring system", stability=run,
                      resolutions=cfg.system.resolutions()).write(report)
    if json_out:
        print_json({"readings": int(run.time.size), "duration_min": duration / 60, "interval_s": interval,
                    "std": std, "std_uncompensated": raw, "published_std": seed})
    else:
        typer.echo(f"stability: {run.time.size} readings over {duration / 60:g} min, every {interval:g} s")
        typer.echo(f"{'error':<10}{'σ':>10}{'σ uncomp.':>12}{'published':>11}")
        for c, k in _KEYS.items():
            typer.echo(f"{_HEADS[c]:<10}{std[k]:10.3f}{raw[k]:12.3f}{seed[k]:10.2f}")
    _wrote(paths)


@app.command("repeatability")
def repeatability(
    config: Path = typer.Argument(..., help="Configuration TOML (see examples/motion_indexing_table.toml)."),
    runs: Optional[int] = typer.Option(None, "--runs", max=100, help="Number of runs, at most 100 (default from the config: 3)."),
    json_out: bool = _JSON,
    report: Optional[Path] = _REPORT,
    csv: Optional[Path] = typer.Option(None, "--csv", help="Write all runs as a data file (.csv) for 'analyze'."),
    plot: Optional[Path] = _PLOT,
    seed: Optional[int] = _SEED,
) -> None:
    """Run the indexing test several times (Optics Express 2018, Five-DOF motion errors of a rotary axis §3.3) and report the ± repeatability.

    Example: axiscal motion repeatability examples/motion_indexing_table.toml
    """
    import numpy as np

    from axiscal.io.motion import format_motion_errors, read_motion_config
    from axiscal.procedures.motion_errors import repeatability_test, to_motion_data
    from axiscal.report.motion_report import REPEATABILITY_SEED
    from axiscal.standards.iso230_7 import evaluate, halfrange

    paths = _check_outputs(report=report, csv=csv, plot=plot)
    cfg = read_motion_config(config)
    n = cfg.runs if runs is None else runs
    if runs is not None:
        from axiscal.io.motion import check_simulated_readings

        check_simulated_readings(cfg.step_deg, cfg.samples, n, "--runs with the configuration's ")
    out = repeatability_test(cfg.axis, cfg.system, np.random.default_rng(_seed(cfg, seed)), n,
                             step_deg=cfg.step_deg, reference=cfg.reference, drift=cfg.drift,
                             dwell=cfg.dwell, samples=cfg.samples)
    data = to_motion_data(out, title=cfg.machine)
    result = evaluate(data)
    rep = {c: halfrange(getattr(data, c)) for c in _KEYS}
    if paths.get("plot"):
        from axiscal.report.motion_plots import five_errors_figure, save_figure

        save_figure(five_errors_figure([r.measured for r in out], [r.truth for r in out],
                                       title=f"Repeatability, {n} runs — {cfg.machine or config.name}"),
                    plot)
    if paths.get("csv"):
        from axiscal.io._files import write_text_atomic

        write_text_atomic(csv, format_motion_errors(data))
    if paths.get("report"):
        from axiscal.report.motion_report import motion_report

        motion_report(f"Repeatability — {cfg.machine or config.name}", result=result,
                      runs=[r.measured for r in out], truth=[r.truth for r in out],
                      repeatability=rep, resolutions=cfg.system.resolutions(),
                      notes=[_MOUNTING_NOTE]).write(report)
    if json_out:
        print_json({"runs": n, "repeatability": _five_dict(rep),
                    "published_repeatability": {_KEYS[c]: v for c, v in REPEATABILITY_SEED.items()},
                    "iso230_7": iso_json(result)})
    else:
        typer.echo(f"repeatability over {n} runs (± largest half-range at one angle):")
        for c, k in _KEYS.items():
            typer.echo(f"  {_HEADS[c]:<10} ±{_five_dict(rep)[k]:.2f}   "
                       f"(published: ±{REPEATABILITY_SEED[c]})")
        typer.echo(str(result))
    _wrote(paths)


@app.command("analyze")
def analyze(
    file: Path = typer.Argument(..., help="Five-error data file (CSV; format in the axiscal.io.motion docs)."),
    json_out: bool = _JSON,
    report: Optional[Path] = _REPORT,
    plot: Optional[Path] = _PLOT,
) -> None:
    """Evaluate measured five-error data by ISO 230-7 (error motion values, axis location).

    Example: axiscal motion analyze motion.csv
    """
    from axiscal import api

    paths = _check_outputs(report=report, plot=plot)
    ev = api.evaluate(file)
    data, result = ev.dataset, ev.result
    if paths.get("plot"):
        from axiscal.report.motion_plots import polar_figure, save_figure

        save_figure(polar_figure(result, title=f"ISO 230-7 error motion — {data.title or file.name}"),
                    plot)
    if paths.get("report"):
        from axiscal.instruments.five_dof import FiveErrors
        from axiscal.report.motion_report import motion_report

        runs = [FiveErrors(data.theta, *(getattr(data, c)[j] for c in _KEYS)) for j in range(data.n_runs)]
        motion_report(f"ISO 230-7 evaluation — {data.title or file.name}", result=result, runs=runs,
                      metadata={"File": str(file)}).write(report)
    if json_out:     # the record's quantities with U (standards/iso230_7_uncertainty.py)
        d = ev.to_dict()
        print_json({"file": str(file), "title": data.title, "iso230_7": iso_json(result),
                    **{k: d[k] for k in ("schema_version", "quantities", "uncertainty_budget",
                                         "uncertainty_inputs") if k in d}})
    else:
        typer.echo(str(result))
        _echo_uncertainty(ev)
    _wrote(paths)


def _echo_uncertainty(ev) -> None:
    """Each figure with its U, as the record holds it (inputs: ``[motion_uncertainty]``)."""
    from axiscal.report.labels import name
    from axiscal.standards.uncertainty_reporting import format_uncertainty, format_value
    from axiscal.units import display

    rows = [f"  {name(q.name)} = {format_value(q.value, q.U)} ± {format_uncertainty(q.U)} "
            f"{display(q.unit)} (k = {q.k:g})" for q in ev.quantities.values() if q.U is not None]
    if rows:
        typer.echo("With their expanded uncertainty (ISO/TR 230-9 as axiscal reads it for the "
                   "five-DOF method; inputs in the user configuration's motion uncertainty "
                   "table):")
        typer.echo("\n".join(rows))


#: Longest stability run (one week) and most readings simulated (each holds five channels).
MAX_DURATION_MIN, MAX_READINGS = 10_080, 1_000_000


def _config(path):
    from axiscal.io.motion import parse_motion_config, read_motion_config

    return parse_motion_config("") if path is None else read_motion_config(path)


def _seed(cfg, option: int | None) -> int:
    """The simulation's random seed: ``--seed`` if given, else the configuration's."""
    return cfg.seed if option is None else option


def _check_outputs(report=None, csv=None, plot=None) -> dict:
    """Check the output files before any work (folder exists, .html report, .csv data, plot)."""
    paths = {}
    if plot is not None:
        paths["plot"] = plot_path(plot)
    if report is not None:
        paths["report"] = report_path(report)
    if csv is not None:
        paths["csv"] = typed_path(csv, "csv", (".csv",))
    return paths


def _wrote(paths: dict) -> None:
    for what, p in paths.items():
        note(f"wrote {what} {p}")


def _five_dict(values: dict) -> dict:
    from axiscal.io.simulation_results import channel_dict

    return channel_dict(values)


def _render_positions(measured, truth, title: str) -> None:
    from rich.table import Table

    from axiscal.cli._common import console

    from rich import box

    t = Table(title=f"Five errors per position, measured (truth) — {title}", title_justify="left",
              box=box.SIMPLE_HEAD, show_edge=False, pad_edge=False, padding=(0, 0))
    t.add_column("θ°", justify="right", no_wrap=True)
    for c in _KEYS:
        t.add_column(_HEADS[c], justify="right", no_wrap=True)
    m, tr = _five(measured), _five(truth)
    for i, th in enumerate(measured.theta):
        cells = [f"{float(th) * 57.29577951308232:.0f}"]
        for c, k in _KEYS.items():
            d = 1 if c[0] == "e" else 2
            cells.append(f"{m[k][i]:.{d}f} ({tr[k][i]:.{d}f})")
        t.add_row(*cells)
    console().print(t)


def register(root: typer.Typer) -> None:
    """Add the ``motion`` command group to the application."""
    root.add_typer(app, name="motion")
