"""``axiscal scale``: the laser scale with an environmental compensator (Renishaw, Laser scale axis referencing).

``scale home CONFIG.toml [--plot FILE] [--json]``
    Referencing of one axis. JSON keys: ``homed``, ``counts_per_period``, ``count_size_nm``,
    ``period_um``, ``direction``, ``virtual_counts``, ``power_up_phase``, ``switch_trip_mm``,
    ``home_position_mm``, ``rephase_periods``, ``events`` (``name``, ``counts_beyond_switch``:
    measured from the simulated motion of the part at 20 °C, ``nominal_counts``: the design
    value, ``uncertainty_counts``: one laser count, ``controller_count``, ``position_mm``,
    ``time_s``), ``alarms``, ``peak_input_frequency_khz`` (over one signal period, from the
    output edges), ``compensation_ppm``, ``laser_count_rate_hz``,
    ``controller_max_speed_m_per_s`` and, when the configuration has moves, ``tracking``
    (``max_count_error`` and ``max_part_error_um``: controller against the true part position,
    ``max_pulse_error``: against the compensator's exact product, ``count_uncertainty``: one
    laser count in output counts, ``end_controller_mm``, ``end_true_mm``, ``end_part_mm``,
    ``end_uncompensated_mm``).
``scale gantry CONFIG.toml [--json] [--plot FILE] [--report FILE]``
    Twin-axis homing. JSON keys: those of the run (``counts_per_period``, ``count_size_nm``,
    ``virtual_1``, ``virtual_2``, ``homing_skew_min``, ``homing_skew_max``, ``skew_before_sync``,
    ``skew_limit``, ``alarm``, ``deskew_move``, ``skew_after_sync``, ``offset``,
    ``homing_skew_bound_um``: (N − 1) counts, just under one signal period), plus
    ``required_skew_limit`` (counts), ``switch_sigma_counts`` and ``worst_case`` (the two
    extreme phase combinations: ``virtual_1``, ``virtual_2``, ``skew_before_sync``, ``alarm``).
``scale compensate [options] [--json]``
    The factor for given conditions and the error of an uncompensated scale. JSON keys:
    ``n``, ``n_standard``, ``growth``, ``ratio``, ``factor``, ``correction_ppm``, ``length_mm``,
    ``raw_error_um``, ``weather_error_um``, ``material_error_um``, ``count_size_in_nm``,
    ``count_size_out_nm``.
"""

from __future__ import annotations

from pathlib import Path
from typing import List, Optional

import typer

from axiscal.cli._common import note, plot_path, print_json, report_path

__all__ = ["register", "scale_app"]

scale_app = typer.Typer(
    name="scale",
    help="Laser scale with an environmental compensator: referencing, gantry homing, "
    "compensation factor (Renishaw, Laser scale axis referencing).",
    no_args_is_help=True,
)


_SEED = typer.Option(None, "--seed", min=0, max=2**63 - 1, help="Random seed of the simulation "
                     "(instead of the configuration's seed; without either, the switch has no "
                     "random error and the power-up phase is the configuration's).")


@scale_app.command("home")
def home(
    config: Path = typer.Argument(..., help="Laser-scale configuration (TOML, see examples/)."),
    plot: Optional[Path] = typer.Option(None, "--plot", help="Write the signals-against-position "
                                        "plot (PNG, SVG or PDF by extension)."),
    json_out: bool = typer.Option(False, "--json", help="Print JSON (stable keys, see the docs)."),
    seed: Optional[int] = _SEED,
    report: Optional[Path] = typer.Option(None, "--report", help="Write a simulation report "
                                          "(signals plot and every figure): HTML or PDF."),
) -> None:
    """Simulate the referencing of one axis: events A, B, Z, C and the signals.

    Example: axiscal scale home examples/scale_single.toml --plot home.png
    """
    from axiscal import api

    if plot is not None:
        plot_path(plot)
    if report is not None:
        report_path(report)
    homing = api.simulate(config, seed, kind="scale-homing")
    sim = homing.test
    run, d, axis, ppm = sim.record, sim.json, sim.parts["axis"], sim.parts["compensation_ppm"]
    if plot is not None:
        from axiscal.report.scale_plot import save_referencing_plot

        save_referencing_plot(run, plot)
    if report is not None:
        homing.report(report)
    if json_out:
        print_json(d)
    else:
        typer.echo(str(run))
        typer.echo(f"  compensation factor {ppm:+.3f} ppm; controller inputs accept up to "
                   f"{axis.controller.max_speed() * 60e3:.0f} mm/min "
                   f"({axis.controller.max_input_frequency / 1e3:g} kHz); the raw fringes "
                   f"({axis.laser.effective_pitch() * 1e6:.3f} µm pitch) would need "
                   f"{axis.laser.fringe_frequency(axis.controller.max_speed()) / 1e6:.1f} MHz "
                   "at that speed")
        if "tracking" in d:
            t = d["tracking"]
            typer.echo(f"  after homing: controller vs the true part position at 20 °C within "
                       f"{t['max_count_error']:.2f} counts ({t['max_part_error_um']:.3f} µm; "
                       f"one laser count is {t['count_uncertainty']:.2f} counts); vs the "
                       f"compensator's exact product within {t['max_pulse_error']:.3f} counts; "
                       f"at the end the controller reads "
                       f"{t['end_controller_mm']:.6f} mm, an uncompensated scale "
                       f"{t['end_uncompensated_mm']:.6f} mm (part {t['end_part_mm']:.6f} mm)")
    for what, path in (("plot", plot), ("report", report)):
        if path is not None:
            note(f"wrote {what} {path}")


@scale_app.command("gantry")
def gantry(
    config: Path = typer.Argument(..., help="Twin-axis configuration (TOML with a gantry "
                                  "table, see examples/scale_gantry.toml)."),
    json_out: bool = typer.Option(False, "--json", help="Print JSON (stable keys, see the docs)."),
    seed: Optional[int] = _SEED,
    plot: Optional[Path] = typer.Option(None, "--plot", help="Write the skew during homing with the skew limits (PNG, SVG or PDF by extension)."),
    report: Optional[Path] = typer.Option(None, "--report", help="Write a simulation report (skew plot and every figure): HTML or PDF."),
) -> None:
    """Simulate twin-axis (gantry) homing: skew, skew-limit alarm, deskew, limit needed.

    Example: axiscal scale gantry examples/scale_gantry.toml
    """
    from axiscal import api

    for p, check in ((plot, plot_path), (report, report_path)):
        if p is not None:
            check(p)
    homing = api.simulate(config, seed, kind="gantry-homing")
    sim = homing.test
    run, d = sim.record, sim.json
    g, worst, spread = sim.parts["gantry"], sim.parts["worst"], sim.parts["spread"]
    if plot is not None:
        from axiscal.report.plots import save_figure

        save_figure(homing.plot(), plot)
    if report is not None:
        homing.report(report)
    if json_out:
        print_json(d)
    else:
        _print_gantry(run, worst, d, g, spread)
    for what, path in (("plot", plot), ("report", report)):
        if path is not None:
            note(f"wrote {what} {path}")


def _print_gantry(run, worst, d, g, spread) -> None:
    typer.echo(str(run))
    for w in worst:
        typer.echo(f"  worst case v1 = {w.virtual_1}, v2 = {w.virtual_2}: skew "
                   f"{w.skew_check.skew} counts -> {'ALARM' if w.alarm else 'within the limit'}")
    typer.echo(f"  set the skew limit to at least {d['required_skew_limit']} counts "
               f"({d['required_skew_limit'] * g.output.count_size * 1e6:.2f} µm)"
               + (f", including 3 sigma of the two switches ({spread} counts)" if spread else ""))


@scale_app.command("compensate")
def compensate(
    temperature: float = typer.Option(20.0, "--temperature", "-t", help="Air temperature, °C."),
    pressure: float = typer.Option(101325.0, "--pressure", "-p", help="Air pressure, Pa."),
    humidity: Optional[float] = typer.Option(None, "--humidity",
                                             help="Relative humidity, %RH (default 50)."),
    dew_point: Optional[float] = typer.Option(None, "--dew-point", help="Dew point, °C."),
    co2: float = typer.Option(450.0, "--co2", help="CO2 content, µmol/mol."),
    equation: str = typer.Option("ciddor", "--equation", "-e",
                                 help="ciddor, edlen or birch-downs."),
    material: Optional[str] = typer.Option(None, "--material",
                                           help="Work-piece material (steel, aluminium ...)."),
    alpha: Optional[float] = typer.Option(None, "--expansion-coefficient",
                                          help="Work-piece expansion coefficient, 1/K."),
    material_temperature: List[float] = typer.Option(
        [], "--material-temperature", help="Work-piece sensor, °C (repeat for several; averaged)."),
    length: float = typer.Option(1000.0, "--length", help="Length of the part (at 20 °C) over which the errors of a scale without this compensation are shown, mm."),
    period: float = typer.Option(20.0, "--period", help="Output period, µm (20, 25, 40, 50, 100)."),
    counts_per_period: int = typer.Option(256, "--counts-per-period",
                                          help="Output counts per period."),
    json_out: bool = typer.Option(False, "--json", help="Print JSON (stable keys, see the docs)."),
) -> None:
    """The compensation factor for given conditions, and the error without compensation.

    Example: axiscal scale compensate -t 22 -p 100500 --humidity 40 --material steel --material-temperature 23
    """
    from axiscal.errors import InputError
    from axiscal.instruments.compensator import Compensator, SineOutput, compensation_summary
    from axiscal.physics.thermal import material as lookup, mean_temperature

    if material is not None and alpha is not None:
        raise InputError("give --material or --expansion-coefficient, not both")
    a = alpha if alpha is not None else (lookup(material).alpha if material else 0.0)
    t_mat = mean_temperature(material_temperature) if material_temperature else 20.0
    comp = Compensator(output=SineOutput(period * 1e-6, counts_per_period), equation=equation,
                       expansion_coefficient=a, co2=co2)
    s = compensation_summary(comp, temperature, pressure, humidity, dew_point=dew_point,
                             material_temperature=t_mat, length=length * 1e-3)
    if json_out:
        print_json(s.to_dict())
    else:
        typer.echo(str(s))


def register(app: typer.Typer) -> None:
    """Add the ``scale`` command group to the application."""
    app.add_typer(scale_app, name="scale")
