"""``axiscal thermal``: the ISO 230-3:2020 thermal tests, their model and SINUMERIK's
temperature compensation.

Each command parses, calls one function of :mod:`axiscal.api._thermal` and renders; ``--json``
prints the result's ``to_dict()``. The twin is ``axiscal/data/thermal_vmc.toml`` unless
``--config`` names another (format: :mod:`axiscal.machines.thermal_config`).

JSON (``--json``), units in the key names (µm, µrad, K, h as each figure's ``unit`` says):

* ``plan``: ``test``, ``duration_h``, ``interval_s``, ``samples``, ``start_h``; the spindle and
  linear tests ``run_h``, ``stop_h``; spindle ``speed_fraction``; linear ``axis``, ``duty``,
  ``P1_mm``, ``P2_mm``; drift check ``position_mm``, ``instrument_drift_um_per_h``.
* ``evaluate``: ``test``, ``clause``, ``duration_h``, ``run_end_h``, ``notes`` and ``figures``,
  each with ``name``, ``label``, ``value``, ``U``, ``unit``, ``clause``; with ``--e-ve`` also
  ``e_ve`` (``channel``, ``start_h``, ``duration_h``, ``value_um``, ``source``, ``what``).
* ``simulate``: ``plan``, ``evaluation`` (as evaluate), ``truth`` (figure name to value, in the
  figure's unit) and ``out``; a drift check ``plan``, ``e_ve_um``, ``e_ve_source``, ``truth``
  (``e_ve_um``), ``out``.
* ``model``: ``test``, ``axis``, ``targets_mm``, ``sensors`` and ``lags_min`` (one per term),
  ``reference_C``, ``coefficients`` (per channel ``unit``, ``values``, ``u``) and ``scores``
  (per run ``role``, ``source``, ``rms``, ``max_error``, ``drift_range``,
  ``max_error_share_of_range``).
* ``compensate``: ``sinumerik`` (``controller``, ``axis``, the machine and setting data by
  name, each with its ``value`` or ``formula`` and ``unit``, ``k0_mm_per_K`` and ``s_per_K``
  (lists, one per term), ``sensors`` and ``lags_min`` (one per term: a sensor may give two
  terms), ``lag``, ``sign``, ``outside``), ``model`` (as model), ``verify`` (null, or
  ``before_um``, ``after_um``, ``reduction`` per target; with ``--on-controller`` also
  ``moves_per_run``, ``largest_applied_difference_um``, ``time_compression``,
  ``on_controller``) and ``files`` (what ``--sinumerik-out`` and ``--linuxcnc-out`` wrote).
"""

from __future__ import annotations

from pathlib import Path
from typing import List, Optional

import typer

from axiscal.cli._common import note, out_path, plot_path, print_json, report_path

__all__ = ["register", "thermal_app"]

HELP = ("Thermal effects by ISO 230-3:2020: ETVE, spindle, linear-axis and rotary-table tests "
        "planned, simulated on a thermal twin and evaluated; a thermal model; SINUMERIK and "
        "LinuxCNC temperature compensation.")

thermal_app = typer.Typer(help=HELP, no_args_is_help=True)

_TESTS = ("etve, spindle, linear, rotary (a rotary table turning: a twin with one, e.g. "
          "src/axiscal/data/thermal_rotary_table.toml) or drift-check (ISO 230-2 Annex A.5)")


def plan_options(test, config, duration_h, run_h, interval_s, speed, axis, p1_mm, p2_mm, duty,
                  position_mm, instrument_drift, start_h, programme=None) -> dict:
    """The keyword arguments of ``plan_thermal`` from the plan's options (:data:`PLAN_OPTIONS`),
    for ``axiscal thermal plan`` and ``axiscal plan thermal`` alike."""
    return dict(test=test, config=config, duration_h=duration_h, run_h=run_h,
                interval_s=interval_s, speed=speed, axis=axis, p1_mm=p1_mm, p2_mm=p2_mm,
                duty=duty, position_mm=position_mm, instrument_drift_um_per_h=instrument_drift,
                start_h=start_h, programme=_programme(programme))


def _programme(text):
    """``--speed-programme 0.25:30,0.5:30,1:30`` -> ((0.25, 30.0), ...) (fraction, minutes)."""
    if text is None:
        return ()
    from axiscal.errors import InputError, one_line

    steps = []
    for part in text.split(","):
        try:
            f, m = (float(x) for x in part.split(":"))
        except ValueError:
            raise InputError(f"--speed-programme {one_line(repr(text), 60)}: give steps "
                             "FRACTION:MINUTES separated by commas, e.g. 0.25:30,0.5:30,1:30"
                             ) from None
        if not (0 <= f <= 1 and 0 < m <= 1e4):
            raise InputError(f"--speed-programme step {one_line(part, 40)}: a fraction 0 to 1 "
                             "and more than 0, at most 10000 min")
        steps.append((f, m))
    if len(steps) > 1000:
        raise InputError("--speed-programme: at most 1000 steps")
    return tuple(steps)


# The options every planned test shares (plan and simulate), declared once.
#: The plan's options, shared with ``axiscal plan thermal`` (one definition, one help text).
PLAN_OPTIONS = dict(
    test=typer.Option(..., "--test", help=f"The test: {_TESTS}."),
    config=typer.Option(None, "--config", help="Thermal twin (TOML); default the shipped VMC."),
    duration_h=typer.Option(None, "--duration-h", min=0.0, help="Whole test, h (default: etve "
                            "24, spindle/linear/rotary the run + 1, drift-check 1)."),
    run_h=typer.Option(None, "--run-h", min=0.0, help="Spindle running / axis cycling / "
                       "table turning, h (default 4)."),
    interval_s=typer.Option(60.0, "--interval-s", help="Between samples, s (at most 300)."),
    speed=typer.Option(0.5, "--speed", help="Spindle (or rotary table) speed, "
                      "fraction of the maximum (0.5)."),
    axis=typer.Option("X", "--axis", help="Axis of the linear test or drift check."),
    p1_mm=typer.Option(None, "--p1-mm", help="Linear test: target P1, mm."),
    p2_mm=typer.Option(None, "--p2-mm", help="Linear test: target P2, mm."),
    duty=typer.Option(0.8, "--duty", help="Linear test: the axis's share of time in motion."),
    position_mm=typer.Option(None, "--position-mm", help="Drift check: where the set-up "
                             "stands, mm (default mid-travel)."),
    instrument_drift=typer.Option(0.0, "--instrument-drift-um-per-h", help="Drift check: the "
                                  "instrument's own drift, µm/h."),
    start_h=typer.Option(8.0, "--start-h", help="When the test starts in the room's day, h."),
    programme=typer.Option(None, "--speed-programme", help="Spindle test: speed steps "
                           "FRACTION:MINUTES,... repeated through the run (replaces --speed)."),
)


def plan(test: str = PLAN_OPTIONS["test"], config: Optional[Path] = PLAN_OPTIONS["config"],
         duration_h: Optional[float] = PLAN_OPTIONS["duration_h"], run_h: Optional[float] = PLAN_OPTIONS["run_h"],
         interval_s: float = PLAN_OPTIONS["interval_s"], speed: float = PLAN_OPTIONS["speed"],
         axis: str = PLAN_OPTIONS["axis"], p1_mm: Optional[float] = PLAN_OPTIONS["p1_mm"],
         p2_mm: Optional[float] = PLAN_OPTIONS["p2_mm"], duty: float = PLAN_OPTIONS["duty"],
         position_mm: Optional[float] = PLAN_OPTIONS["position_mm"],
         instrument_drift: float = PLAN_OPTIONS["instrument_drift"], start_h: float = PLAN_OPTIONS["start_h"],
         programme: Optional[str] = PLAN_OPTIONS["programme"],
         json_out: bool = typer.Option(False, "--json", help="Print the plan as JSON.")) -> None:
    """Plan an ISO 230-3 thermal test or an ISO 230-2 drift check: durations, samples, targets.

    Example: axiscal thermal plan --test spindle --speed 0.5 --run-h 4
    """
    from axiscal.api._thermal import plan_thermal

    p = plan_thermal(**plan_options(test, config, duration_h, run_h, interval_s, speed, axis,
                                     p1_mm, p2_mm, duty, position_mm, instrument_drift, start_h,
                                     programme))
    d = p.to_dict()
    if json_out:
        print_json(d)
        return
    typer.echo("\n".join(f"{k}: {v:g}" if isinstance(v, float) else f"{k}: {v}"
                         for k, v in d.items()))


def simulate(test: str = PLAN_OPTIONS["test"], config: Optional[Path] = PLAN_OPTIONS["config"],
             duration_h: Optional[float] = PLAN_OPTIONS["duration_h"],
             run_h: Optional[float] = PLAN_OPTIONS["run_h"], interval_s: float = PLAN_OPTIONS["interval_s"],
             speed: float = PLAN_OPTIONS["speed"], axis: str = PLAN_OPTIONS["axis"],
             p1_mm: Optional[float] = PLAN_OPTIONS["p1_mm"], p2_mm: Optional[float] = PLAN_OPTIONS["p2_mm"],
             duty: float = PLAN_OPTIONS["duty"], position_mm: Optional[float] = PLAN_OPTIONS["position_mm"],
             instrument_drift: float = PLAN_OPTIONS["instrument_drift"],
             start_h: float = PLAN_OPTIONS["start_h"], programme: Optional[str] = PLAN_OPTIONS["programme"],
             seed: int = typer.Option(0, "--seed", min=0, help="Seed of the sensors' noise."),
             out: Optional[Path] = typer.Option(None, "--out", help="Write the log CSV (a drift "
                                                "check: the file iso230-2 --drift-check reads)."),
             plot: Optional[Path] = typer.Option(None, "--plot", help="Plot over time (.png, "
                                                 ".svg, .pdf)."),
             report: Optional[Path] = typer.Option(None, "--report", help="HTML (or PDF) "
                                                   "report with the truth, as a simulation."),
             json_out: bool = typer.Option(False, "--json", help="Print figures and truth as "
                                           "JSON.")) -> None:
    """Simulate a thermal test on the twin with its sensors; evaluate it beside the truth.

    The truth appears only here (the log holds what the sensors read). Example:
    axiscal thermal simulate --test linear --out x_linear.csv --seed 1
    """
    from axiscal.api._thermal import simulate_thermal

    if out is not None:
        out_path(out, "log")
    if plot is not None:
        plot_path(plot)
    if report is not None:
        report_path(report)
    opts = plan_options(test, config, duration_h, run_h, interval_s, speed, axis, p1_mm, p2_mm,
                         duty, position_mm, instrument_drift, start_h, programme)
    sim = simulate_thermal(opts.pop("test"), opts.pop("config"), seed, **opts)
    if sim.plan.test == "drift-check":
        _drift_check(sim, out, plot or report, json_out)
        return
    from axiscal.api._thermal import evaluate_thermal

    result = evaluate_thermal(sim.log)
    if out is not None:
        from axiscal.io.thermal import write_thermal_log

        write_thermal_log(out, sim.log)
    if plot is not None:
        from axiscal.report.thermal_plots import save_thermal_plot

        save_thermal_plot(sim.log, plot)
    if report is not None:
        from axiscal.report.thermal_plots import thermal_report

        thermal_report(sim.log, result, sim.truth).write(report)
    truth = {k: _shown(result, k, v) for k, v in sim.truth.items()}
    if json_out:
        print_json({"plan": sim.plan.to_dict(), "evaluation": result.to_dict(),
                    "truth": truth, "out": None if out is None else str(out)})
        return
    typer.echo(str(result))
    typer.echo("simulation truth: " + ", ".join(f"{k} {v:.4g}" for k, v in truth.items()))
    if out is not None:
        note(f"wrote {out} ({sim.log.time.size} samples)")


def evaluate(log: Path = typer.Argument(..., help="Thermal log CSV (format: axiscal formats)."),
             plot: Optional[Path] = typer.Option(None, "--plot", help="Plot over time (.png, "
                                                 ".svg, .pdf)."),
             report: Optional[Path] = typer.Option(None, "--report", help="HTML (or PDF) "
                                                   "report: figures, clauses, plot."),
             e_ve: Optional[str] = typer.Option(None, "--e-ve", help="ETVE log: E_VE of "
                                                "ISO 230-2 Annex A.5 from one direction over a "
                                                "window, CHANNEL,START_H,DURATION_H (e.g. "
                                                "X,1,2): the machine's response to the room "
                                                "only, to be declared."),
             json_out: bool = typer.Option(False, "--json", help="Print the figures as JSON.")
             ) -> None:
    """Evaluate a logged thermal test by ISO 230-3:2020 (ETVE, spindle, linear axis, rotary).

    Example: axiscal thermal evaluate x_linear.csv --plot x_linear.png
    """
    from axiscal.api._thermal import evaluate_thermal, read_thermal

    if plot is not None:
        plot_path(plot)
    if report is not None:
        report_path(report)
    data = read_thermal(log)
    result = evaluate_thermal(data)
    derived = None if e_ve is None else _e_ve_from_etve(data, e_ve)
    if plot is not None:
        from axiscal.report.thermal_plots import save_thermal_plot

        save_thermal_plot(data, plot)
    if report is not None:
        from axiscal.report.thermal_plots import thermal_report

        thermal_report(data, result).write(report)
    if json_out:
        print_json({**result.to_dict(), **({} if derived is None else {"e_ve": derived})})
        return
    typer.echo(str(result))
    if derived is not None:
        typer.echo(f"E_VE from the ETVE record, {derived['channel']} over "
                   f"{derived['start_h']:g} h + {derived['duration_h']:g} h: "
                   f"{derived['value_um']:.3f} µm; {derived['what']}")


def model(fit: List[Path] = typer.Argument(..., help="Log(s) to fit (runs of one test)."),
          validate: Path = typer.Option(..., "--validate", help="A run not fitted: the terms "
                                        "are chosen on it."),
          test_run: Optional[Path] = typer.Option(None, "--test", help="A run used for neither: "
                                                  "the model is judged on it."),
          sensors: Optional[str] = typer.Option(None, "--sensors", help="Temperatures to use, "
                                                "comma-separated (default: all)."),
          channels: Optional[str] = typer.Option(None, "--channels", help="Drifts to model, "
                                                 "comma-separated (default: all of the test)."),
          json_out: bool = typer.Option(False, "--json", help="Print the model as JSON.")) -> None:
    """Fit a thermal model: drift as a linear function of lagged temperatures, validated.

    Example: axiscal thermal model a.csv b.csv --validate c.csv --test d.csv
    """
    from axiscal.api._thermal import fit_thermal_model

    m = fit_thermal_model(list(fit), validate, test_run, sensors=_names(sensors),
                          channels=_names(channels))
    if json_out:
        print_json(m.to_dict())
        return
    typer.echo(str(m))


def compensate(fit: List[Path] = typer.Argument(..., help="Linear-axis log(s) to fit."),
               validate: Path = typer.Option(..., "--validate", help="A run not fitted: the "
                                             "terms are chosen on it."),
               test_run: Optional[Path] = typer.Option(None, "--test", help="A run used for "
                                                       "neither: the model is judged on it."),
               sensors: Optional[str] = typer.Option(None, "--sensors", help="Temperatures to "
                                                     "use, comma-separated (default: all)."),
               verify: bool = typer.Option(False, "--verify", help="Run a linear test on the "
                                           "twin twice, one thermal history, without and with "
                                           "the compensation: the drift at P1 and P2 before "
                                           "and after."),
               on_controller: bool = typer.Option(False, "--on-controller", help="With "
                                                  "--verify: measure through a real LinuxCNC "
                                                  "(headless, Debian linuxcnc-uspace) with "
                                                  "axiscal's HAL component driving X's external "
                                                  "offset, fed by the simulated sensors "
                                                  "through HAL on a time-compressed clock."),
               linuxcnc_out: Optional[Path] = typer.Option(None, "--linuxcnc-out", help="Write "
                                                           "LinuxCNC's files into this folder: "
                                                           "thermcomp.json, "
                                                           "axiscal_thermcomp.py and .hal."),
               sinumerik_out: Optional[Path] = typer.Option(None, "--sinumerik-out",
                                                            help="Write SINUMERIK's machine "
                                                            "and setting data (MD32750, "
                                                            "SD43920, SD43900, SD43910) with "
                                                            "the PLC's formulas as comments."),
               config: Optional[Path] = PLAN_OPTIONS["config"],
               seed: int = typer.Option(0, "--seed", min=0, help="--verify: seed of the run."),
               duty: float = PLAN_OPTIONS["duty"], start_h: float = PLAN_OPTIONS["start_h"],
               json_out: bool = typer.Option(False, "--json", help="Print the parameters and "
                                             "the model as JSON.")) -> None:
    """SINUMERIK temperature compensation from linear-axis runs (ISO 230-3:2020 Clause 7).

    K3 function manual: MD32750, SD43900 K0(T), SD43910 tanβ(T), SD43920 P0.

    With --verify, the compensation is applied on the twin to a new linear test (same thermal
    history with and without it); with --on-controller too, through a real LinuxCNC. Example:
    axiscal thermal compensate a.csv --validate b.csv --test c.csv --verify --json
    """
    from axiscal.api._thermal import fit_thermal_model, thermal_compensation
    from axiscal.errors import InputError

    if on_controller and not verify:
        raise InputError("--on-controller measures the --verify run through LinuxCNC: give "
                         "--verify too")
    if sinumerik_out is not None:
        out_path(sinumerik_out, "SINUMERIK data")
    if linuxcnc_out is not None and linuxcnc_out.exists() and not linuxcnc_out.is_dir():
        raise InputError(f"--linuxcnc-out {str(linuxcnc_out)[:200]}: not a folder")
    m = fit_thermal_model(list(fit), validate, test_run, sensors=_names(sensors),
                          channels=("P1", "P2"))
    comp = thermal_compensation(m)
    check = None
    if verify:
        from axiscal.api._thermal import verify_thermal_compensation
        from axiscal.cli._common import progress_bar

        with progress_bar("through LinuxCNC: without, then with the compensation") as bar:
            check = verify_thermal_compensation(comp, config, seed, duty=duty,
                                                start_h=start_h, p1_mm=m.targets[0] * 1e3,
                                                p2_mm=m.targets[1] * 1e3,
                                                on_controller=on_controller,
                                                progress=bar if on_controller else None)
    written = []
    if linuxcnc_out is not None:            # all three files or none (write_files_atomic)
        from axiscal.compensation.on_controller_thermal import thermal_linuxcnc_outputs
        from axiscal.io._files import write_files_atomic

        try:
            linuxcnc_out.mkdir(parents=True, exist_ok=True)
        except OSError as exc:
            raise InputError(f"cannot create folder {str(linuxcnc_out)[:200]}: "
                             f"{exc.strerror or exc}") from None
        names = write_files_atomic(linuxcnc_out, thermal_linuxcnc_outputs(comp),
                                   inputs=[*fit, validate, *([test_run] if test_run else [])])
        written += [str(linuxcnc_out / n) for n in names]
    if sinumerik_out is not None:           # checked writable before the fit (out_path)
        from axiscal.io._files import write_text_atomic

        write_text_atomic(sinumerik_out, comp.to_text())
        written.append(str(sinumerik_out))
    if json_out:
        print_json({"sinumerik": comp.to_dict(), "model": m.to_dict(),
                    "verify": None if check is None else check.to_dict(),
                    "files": written})
        return
    typer.echo(str(comp))
    typer.echo(str(m))
    if check is not None:
        typer.echo(str(check))
    if written:
        note(f"wrote {', '.join(written)}")


def _drift_check(dc, out, plot, json_out) -> None:
    from axiscal.io.drift import parse_drift_check
    from axiscal.io.thermal import format_drift_check
    from axiscal.standards.iso230_9_inputs import environmental_variation

    text = format_drift_check(dc.time, dc.readings)
    # from the file's own readings: the number iso230-2 --drift-check will find in it
    e_ve = environmental_variation(parse_drift_check(text))
    if out is not None:
        from axiscal.io._files import write_text_atomic

        write_text_atomic(out, text)
    if plot is not None:
        note("a drift check has no thermal plot or report; --plot and --report ignored")
    d = {"plan": dc.plan.to_dict(), "e_ve_um": round(e_ve, 6),
         "e_ve_source": "drift check (ISO 230-2:2014 Annex A.5)",
         "truth": {"e_ve_um": round(dc.true_e_ve * 1e6, 6)},
         "out": None if out is None else str(out)}
    if json_out:
        print_json(d)
        return
    typer.echo(f"drift check at {dc.plan.position * 1e3:g} mm on axis {dc.plan.axis} over "
               f"{dc.plan.duration / 3600:g} h: E_VE = {e_ve:.3f} µm (ISO 230-2:2014 Annex A.5); "
               f"simulation truth {dc.true_e_ve * 1e6:.3f} µm")
    if out is not None:
        note(f"wrote {out}: give it to 'axiscal iso230-2 TEST --drift-check {out}'")


def _e_ve_from_etve(log, text: str) -> dict:
    """``--e-ve CHANNEL,START_H,DURATION_H`` (:func:`axiscal.standards.iso230_3.e_ve_from_etve`)."""
    from axiscal.errors import InputError, one_line
    from axiscal.standards.iso230_3 import e_ve_from_etve

    parts = [p.strip() for p in text.split(",")]
    try:
        channel, start, duration = parts[0], float(parts[1]), float(parts[2])
        ok = len(parts) == 3 and all(map(lambda v: v == v and abs(v) < 1e6, (start, duration)))
    except (IndexError, ValueError):
        ok = False
    if not ok:
        raise InputError(f"--e-ve {one_line(repr(text), 60)}: give CHANNEL,START_H,DURATION_H, "
                         "e.g. X,1,2")
    v = e_ve_from_etve(log, channel, start * 3600, duration * 3600)
    return {"channel": channel, "start_h": start, "duration_h": duration,
            "value_um": round(v * 1e6, 6), "source": "declared",
            "what": ("the machine's response to the room in that direction at the ETVE set-up's "
                     "place over that time, without the positioning test's instrument drift; "
                     "declare it (--uncertainty e_ve=VALUE, e_ve_source = 'declared'), a drift "
                     "check measures the set-up itself")}


def _shown(result, name: str, value: float) -> float:
    try:
        f = result[name]
    except KeyError:
        return value
    from axiscal.standards.iso230_3 import _UNITS

    return round(value * _UNITS[f.kind][1], 6)


def _names(text: Optional[str]):
    if text is None:
        return None
    names = [n.strip() for n in text.split(",") if n.strip()]
    if not names:
        from axiscal.errors import InputError

        from axiscal.errors import one_line

        raise InputError(f"{one_line(repr(text), 60)}: give names separated by commas")
    return names


def register(app: typer.Typer) -> None:
    """Add the ``thermal`` group to the application."""
    thermal_app.command("plan")(plan)
    thermal_app.command("simulate")(simulate)
    thermal_app.command("evaluate")(evaluate)
    thermal_app.command("model")(model)
    thermal_app.command("compensate")(compensate)
    app.add_typer(thermal_app, name="thermal")
