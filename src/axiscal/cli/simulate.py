"""``axiscal simulate CONFIG.toml``: a positioning test of a simulated axis, evaluated by ISO 230-2.

The configuration has ``[axis]`` (see :mod:`axiscal.machines.config`), ``[test]`` (see
:func:`axiscal.procedures.positioning.plan_from_config`) and an optional ``[meta]``. The output
sets the evaluation beside the truth the simulation knew. ``--json`` prints the ISO 230-2 object of
``axiscal iso230-2 --json`` (keys in :mod:`axiscal.cli.iso230_2`) plus ``truth`` (``E``,
``E_up``, ``E_down``, ``M``, ``B``, ``B_mean`` implied by the injected errors, and
``R_expected`` = 4σ + |b|; ``E_up`` and ``R_expected`` only for a unidirectional test) and
``seed``. ``--data FILE`` writes the simulated readings (CSV or JSON by
extension) so they can be evaluated again with ``axiscal iso230-2``.
"""

from __future__ import annotations

from pathlib import Path
from typing import Optional

import typer

from axiscal.cli._common import note, plot_path, print_json, report_path, typed_path
from axiscal.cli._encoding import WRITE_ENCODING


def simulate(
    config: Path = typer.Argument(..., help="Machine and test configuration (TOML)."),
    seed: int = typer.Option(1, "--seed", min=0, help="Seed of the simulation's random numbers (a whole number >= 0)."),
    json_out: bool = typer.Option(False, "--json", help="Print the result and the truth as JSON."),
    plot: Optional[Path] = typer.Option(None, "--plot", help="Write the ISO 230-2 plot with the truth (PNG, SVG or PDF by extension)."),
    report: Optional[Path] = typer.Option(None, "--report", help="Write a simulation report (.html, or .pdf with WeasyPrint)."),
    data: Optional[Path] = typer.Option(None, "--data", help="Write the simulated readings (.csv, .json, or Renishaw .rtl/.rta for a linear/rotary axis)."),
    encoding: Optional[str] = WRITE_ENCODING,
) -> None:
    """Simulate an ISO 230-2 positioning test of a configured axis and evaluate it.

    Example: axiscal simulate src/axiscal/data/demo_linear.toml --data x.csv
    """
    from axiscal import api

    if plot is not None:
        plot_path(plot)
    if report is not None:
        report_path(report)
    if data is not None:
        typed_path(data, "data", (".csv", ".json", ".rtl", ".rta"))
    if encoding is not None:
        from axiscal.errors import InputError
        from axiscal.io.renishaw import encode

        if data is None or data.suffix.lower() not in (".rtl", ".rta"):
            raise InputError(f"--encoding {encoding} is the code page of the Renishaw export "
                             "written with --data x.rtl/.rta; "
                             + ("no --data is given" if data is None else
                                f"{data.name} is written as UTF-8") + ": drop --encoding")
        encode("", encoding)                 # an unknown name refused before simulating
    sim = api.simulate(config, seed, kind="positioning")
    write_outputs(sim, plot, report, data, encoding)
    if json_out:
        print_json(sim.to_dict())
    else:
        render_simulation(sim.test)


def write_outputs(sim, plot=None, report=None, data=None, encoding=None) -> None:
    """Write the plot, the report and the data file of a simulated test (an
    :class:`axiscal.api.Simulation`), where asked."""
    if plot is not None:
        from axiscal.report.plots import save_figure

        save_figure(sim.plot(), plot)
        note(f"wrote plot {plot}")
    if report is not None:
        sim.report(report)
        note(f"wrote report {report}")
    if data is not None:
        sim.write_data(data, encoding)
        note(f"wrote data {data}")


def render_simulation(sim) -> None:
    """Print the ISO 230-2 tables and the truth comparison."""
    from rich.markup import escape
    from rich.table import Table

    from axiscal.cli._common import console
    from axiscal.cli.iso230_2 import render_result
    from axiscal.standards.positioning_standards import parameter_label

    con = console()
    render_result(sim.result, sim.dataset)
    u = {"um": "µm"}.get(sim.dataset.deviation_unit, sim.dataset.deviation_unit)
    t = Table(title=escape(f"Measured beside the simulation's truth [{u}]"), title_justify="left")
    for c in ("parameter", "measured", "truth", "difference"):
        t.add_column(c, justify="right" if c != "parameter" else "left")
    params = sim.result.parameters()
    for k, v in sim.truth.items():
        m = sim.result.R if k == "R_expected" else params.get(k)
        name = "R (expected 4σ+|b|)" if k == "R_expected" else parameter_label(k)
        if m is None:
            continue
        t.add_row(name, f"{m:.2f}", f"{v:.2f}", f"{m - v:+.2f}")
    con.print(t)


def register(app: typer.Typer) -> None:
    """Add the ``simulate`` command."""
    app.command("simulate")(simulate)
