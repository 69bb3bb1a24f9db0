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


def simulate(
    config: Path = typer.Argument(..., help="Machine and test configuration (TOML)."),
    seed: int = typer.Option(1, "--seed", min=0, help="Seed of the simulation's random numbers (a whole number >= 0)."),
    json_out: bool = typer.Option(False, "--json", help="Print the result and the truth as JSON."),
    plot: Optional[Path] = typer.Option(None, "--plot", help="Write the ISO 230-2 plot with the truth (PNG, SVG or PDF by extension)."),
    report: Optional[Path] = typer.Option(None, "--report", help="Write a simulation report (.html, or .pdf with WeasyPrint)."),
    data: Optional[Path] = typer.Option(None, "--data", help="Write the simulated readings (.csv, .json, or Renishaw .rtl/.rta for a linear/rotary axis)."),
) -> None:
    """Simulate an ISO 230-2 positioning test of a configured axis and evaluate it.

    Example: axiscal simulate src/axiscal/data/demo_linear.toml --data x.csv
    """
    from axiscal.io._files import load_toml
    from axiscal.procedures.positioning import simulate_from_config

    if plot is not None:
        plot_path(plot)
    if report is not None:
        report_path(report)
    if data is not None:
        typed_path(data, "data", (".csv", ".json", ".rtl", ".rta"))
    sim = simulate_from_config(load_toml(config), seed=seed)
    write_outputs(sim, plot, report, data)
    if json_out:
        from axiscal.cli.iso230_2 import result_json

        d = result_json(sim.result)
        d.update(truth=sim.truth, seed=seed)
        print_json(d)
    else:
        render_simulation(sim)


def write_outputs(sim, plot=None, report=None, data=None) -> None:
    """Write the plot, the report and the data file of a simulated test, where asked."""
    truth = (sim.plan.targets, 0.5 * (sim.truth_up + sim.truth_down)
             if sim.plan.bidirectional else sim.truth_up)
    if plot is not None:
        from axiscal.report.plots import save_iso230_2_plot

        save_iso230_2_plot(sim.result, sim.dataset, plot, truth=truth)
        note(f"wrote plot {plot}")
    if report is not None:
        from axiscal.report.html import positioning_report

        rep = positioning_report(sim.dataset, sim.result)
        rep.simulation = True
        add_truth_section(rep, sim)
        rep.write(report)
        note(f"wrote report {report}")
    if data is not None:
        from axiscal.io._files import write_text_atomic

        if Path(data).suffix.lower() == ".json":
            from axiscal.io.json import format_positioning_json as fmt
        elif Path(data).suffix.lower() in (".rtl", ".rta"):
            from axiscal.io.renishaw import format_rtl, format_rta

            fmt = format_rtl if Path(data).suffix.lower() == ".rtl" else format_rta
        else:
            from axiscal.io.csv import format_positioning_csv as fmt
        write_text_atomic(data, fmt(sim.dataset))
        note(f"wrote data {data}")


def add_truth_section(rep, sim) -> None:
    """Add 'evaluation beside the truth' to a report."""
    rep.add_heading("Evaluation beside the truth of the simulation")
    rep.add_text("The simulated axis's injected errors imply the figures below without noise; "
                 "the measured figures differ by the repeatability noise of a 5-run test.")
    from axiscal.report.html import _PARAM_LABEL

    rows = [[_PARAM_LABEL[k], sim.result.parameters()[k], v]
            for k, v in sim.truth.items() if k != "R_expected"]
    rows.append(["R (4σ + |b|)", sim.result.R, sim.truth.get("R_expected")])
    rep.add_table(["Parameter", "Measured", "Truth"], rows, digits=2)


def render_simulation(sim) -> None:
    """Print the ISO 230-2 tables and the truth comparison."""
    from rich.markup import escape
    from rich.table import Table

    from axiscal.cli._common import console
    from axiscal.cli.iso230_2 import render_result

    con = console()
    render_result(sim.result, sim.dataset)
    u = {"um": "µm"}.get(sim.dataset.deviation_unit, sim.dataset.deviation_unit)
    t = Table(title=escape(f"Measured beside the simulation's truth [{u}]"), title_justify="left")
    for c in ("parameter", "measured", "truth", "difference"):
        t.add_column(c, justify="right" if c != "parameter" else "left")
    params = sim.result.parameters()
    for k, v in sim.truth.items():
        m = sim.result.R if k == "R_expected" else params.get(k)
        name = "R (expected 4σ+|b|)" if k == "R_expected" else k.replace("_up", "↑").replace("_down", "↓")
        if m is None:
            continue
        t.add_row(name, f"{m:.2f}", f"{v:.2f}", f"{m - v:+.2f}")
    con.print(t)


def register(app: typer.Typer) -> None:
    """Add the ``simulate`` command."""
    app.command("simulate")(simulate)
