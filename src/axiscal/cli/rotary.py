"""``axiscal rotary``: simulated rotary-axis calibration and the alignment budget.

``axiscal rotary simulate CONFIG.toml [--json] [--report FILE]`` runs a complete simulated
calibration (set-up checks, optics self-calibration, counter-rotating capture, ISO 230-2
evaluation) and compares it with the truth. ``--json`` keys (stable): ``axis``, ``n_targets``,
``n_runs``, ``n_readings``, ``measured`` and ``truth`` (ISO 230-2 parameters in arcsec: ``A``,
``A_up``, ``A_down``, ``E``, ``E_up``, ``E_down``, ``M``, ``R``, ``R_up``, ``R_down``, ``B``,
``B_mean``), ``max_mean_error_arcsec``, ``max_reading_error_arcsec``, ``within_budget``, ``setup``
(``tir_mm``, ``return_offset_mm``, ``centring_mm``, ``alpha_bound_mrad``, ``beta_bound_mrad``,
``passed``, ``warnings``), ``optics`` (``k``, ``datum_misalignment_arcsec``, or null),
``budget`` (``items``: list of ``name``/``arcsec``/``source``; ``worst_case_arcsec``,
``rss_arcsec``), ``true_misalignment_mrad`` (``alpha``, ``beta``, ``omega``, ``eta_deg``),
``max_laser_angle_arcsec``, ``offaxis`` (``radius_mm``, ``phase_deg``, ``yaw_sign``,
``yaw_removed_arcsec``, ``program_lines``, or null) and ``warnings``.

``axiscal rotary budget --alpha A --beta B [--omega W] [--accuracy X] [--json] [--plot FILE]
[--report FILE]`` answers "how
well must I align for this accuracy?" from Renishaw, Interferometric calibration of rotary axes, equation 1 and its Figure 22 table, taking
the more cautious (:func:`axiscal.physics.misalignment.expected_accuracy`). ``--json`` keys
(stable): ``alpha_mrad``, ``beta_mrad``, ``omega_mrad``, ``terms_arcsec`` (``quadratic``,
``alpha_beta``, ``alpha_omega``: amplitudes), ``peak_arcsec``, ``half_range_arcsec``,
``datum_relative_arcsec`` (max E − min E: the largest error relative to the 0° datum),
``base_arcsec``, ``equation1_accuracy_arcsec`` (base + peak), ``figure22_model_arcsec`` (the
model fitted to Figure 22), ``expected_accuracy_arcsec`` (the larger of the two),
``accuracy_source`` (``"equation1"`` or ``"figure22_model"``), ``bounds`` (what the estimate
bounds, in words), ``accuracy_arcsec`` and ``max_alpha_mrad`` (null without ``--accuracy``; 0.0
when the accuracy is out of reach even at perfect alignment), ``table`` (``alpha_mrad``,
``beta_mrad``, ``accuracy_arcsec``, ``published_figure22_arcsec``).
"""

from __future__ import annotations

from pathlib import Path
from typing import Optional

import typer

from axiscal.cli._common import note, plot_path, print_json, report_path

__all__ = ["register"]

_DOC = "Renishaw, Interferometric calibration of rotary axes"
_BOUNDS = ("the error of each reading against the axis's true angle up to a constant offset "
           "(peak |E| of eq. 1), which is what ISO 230-2 A, E, M, R and B see; a deviation "
           "relative to the 0° datum can carry up to max E − min E (datum_relative_arcsec)")


def simulate(
    config: Path = typer.Argument(..., help="Rotary calibration configuration (TOML); see examples/rotary_*.toml."),
    json_out: bool = typer.Option(False, "--json", help="Print the result as JSON (stable keys, see the module docs)."),
    report: Optional[Path] = typer.Option(None, "--report", help="Write a self-contained report: HTML (.html) or PDF (.pdf, WeasyPrint)."),
    plot: Optional[Path] = typer.Option(None, "--plot", help="Write the error plot (PNG, SVG or PDF by extension)."),
    seed: Optional[int] = typer.Option(None, "--seed", min=0, max=2**63 - 1, help="Random seed of the simulation (default: the configuration's seed)."),
) -> None:
    """Simulate a complete rotary-axis calibration and compare it with the truth.

    Example: axiscal rotary simulate examples/rotary_turntable.toml --report turntable.html
    """
    from axiscal import api

    if report is not None:
        report_path(report)
    if plot is not None:
        plot_path(plot)
    sim = api.simulate(config, seed, kind="rotary-calibration")
    result = sim.test
    if plot is not None:
        from axiscal.report.plots import save_figure

        save_figure(sim.plot(), plot)
    if report is not None:
        sim.report(report)
    if json_out:
        print_json(sim.to_dict())
    else:
        render_rotary(result, str(config))
    for what, path in (("plot", plot), ("report", report)):
        if path is not None:
            note(f"wrote {what} {path}")


def budget(
    alpha: float = typer.Option(..., "--alpha", help="Misalignment α between the axes, mrad."),
    beta: float = typer.Option(..., "--beta", help="Misalignment β of the laser's line of sight, mrad."),
    omega: float = typer.Option(2.5, "--omega", help="Twist ω of the reflector, mrad (manufacturing tolerance 2.5)."),
    accuracy: Optional[float] = typer.Option(None, "--accuracy", help="Wanted ± accuracy, arcsec: print the largest α that reaches it."),
    base: float = typer.Option(0.8, "--base", help="Accuracy of the system at perfect alignment, arcsec."),
    json_out: bool = typer.Option(False, "--json", help="Print the result as JSON (stable keys, see the module docs)."),
    plot: Optional[Path] = typer.Option(None, "--plot", help="Write the error over a turn, each term of eq. 1 and their sum (PNG, SVG or PDF by extension)."),
    report: Optional[Path] = typer.Option(None, "--report", help="Write the budget as a report: HTML (.html) or PDF (.pdf)."),
) -> None:
    """Misalignment error for α, β, ω, and the alignment a wanted accuracy needs.

    Uses eq. 1 or Figure 22 (a model fitted to it), whichever is more cautious.

    Source: Renishaw, Interferometric calibration of rotary axes.

    Example: axiscal rotary budget --alpha 0.62 --beta 1.23 --omega 2.26 --accuracy 1
    """
    for p, check in ((plot, plot_path), (report, report_path)):
        if p is not None:
            check(p)
    data = _budget_data(alpha, beta, omega, accuracy, base)
    if plot is not None or report is not None:
        _budget_outputs(data, plot, report)
    if json_out:
        print_json(data)
        return
    from rich.markup import escape
    from rich.table import Table

    from axiscal.cli._common import console

    con = console()
    con.print(f"α = {alpha:g} mrad, β = {beta:g} mrad, ω = {omega:g} mrad ({_DOC}, eq. 1)")
    from axiscal.report.labels import quantity

    for k, v in data["terms_arcsec"].items():   # named as the report names them
        con.print(f"  {quantity(k)[0]:<22} ±{v:.3f} arcsec")
    con.print(f"  peak |E| over a turn   {data['peak_arcsec']:.3f} arcsec (half range "
              f"{data['half_range_arcsec']:.3f})")
    con.print(f"  relative to the 0° datum {data['datum_relative_arcsec']:.3f} arcsec at most "
              "(max E − min E, worst direction of α)")
    con.print(f"  equation 1             ±{data['equation1_accuracy_arcsec']:.2f} arcsec "
              f"(base {base:g} + peak)")
    con.print(f"  Figure 22 (fitted)     ±{data['figure22_model_arcsec']:.2f} arcsec "
              "(model fitted to the published table, within 0.1 arcsec of it)")
    used = "Figure 22 fitted model" if data["accuracy_source"] == "figure22_model" else "equation 1"
    con.print(f"  expected accuracy      ±{data['expected_accuracy_arcsec']:.2f} arcsec "
              f"(the more cautious: {used})")
    con.print("  it bounds each reading's error against the true angle up to a constant (peak |E|; "
              "ISO 230-2 parameters ignore the constant), not the deviation from the 0° datum")
    if accuracy is not None and data["max_alpha_mrad"] == 0.0:
        from axiscal.physics.misalignment import FIGURE22_FIT

        floor = max(base, FIGURE22_FIT["c0_arcsec"])
        con.print(f"  ±{accuracy:g} arcsec cannot be reached at any alignment: the system alone "
                  f"gives ±{floor:.3g} arcsec (--base, or the fitted Figure 22 at α = 0)")
    elif accuracy is not None:
        ma = data["max_alpha_mrad"]
        con.print(f"  for ±{accuracy:g} arcsec at this β, ω: align α within {ma:.3f} mrad "
                  f"(TIR < {2 * 50 * ma * 1e-3:.3f} mm at 50 mm, before the calibrator's own 0.44 mrad)")
    tab = data["table"]
    for title, rows in (("Model: base + eq. 1 peak [± arcsec]", tab["accuracy_arcsec"]),
                        (f"{_DOC}, Figure 22 [± arcsec]", tab["published_figure22_arcsec"])):
        t = Table(title=title, title_justify="left")
        t.add_column(escape("β \\ α [mrad]"))   # Rich would take [mrad] for markup
        for a in tab["alpha_mrad"]:
            t.add_column(f"{a:g}", justify="right")
        for b, row in zip(tab["beta_mrad"], rows):
            t.add_row(f"{b:g}", *[f"{v:.1f}" for v in row])
        con.print(t)


def _budget_outputs(data: dict, plot, report) -> None:
    from axiscal.report.plots import save_figure
    from axiscal.report.rotary import budget_figure

    if plot is not None:
        save_figure(budget_figure(data), plot)
        note(f"wrote plot {plot}")
    if report is not None:
        from axiscal.report.html import write_result_report

        tab = data["table"]
        heads = ["β \\ α [mrad]", *(f"{a:g}" for a in tab["alpha_mrad"])]
        tables = [(title, heads, [[f"{b:g}", *row] for b, row in zip(tab["beta_mrad"], rows)])
                  for title, rows in (
                      ("Model: base + eq. 1 peak [± arcsec]", tab["accuracy_arcsec"]),
                      (f"{_DOC}, Figure 22 [± arcsec]", tab["published_figure22_arcsec"]))]
        write_result_report(
            report, "Rotary calibration: misalignment budget",
            {k: v for k, v in data.items() if k != "table"}, tables=tables,
            figure=budget_figure(data),
            caption="The terms of eq. 1 over a turn and their sum; the band is the expected "
                    "accuracy (the more cautious of eq. 1 + the base accuracy and the model "
                    "fitted to Figure 22).",
            method=f"Misalignment error of an angular interferometer and reference rotary "
                   f"calibrator set-up: {_DOC}, eq. 1 (E = α²/4 sin 2θ + αβ sin θ + αω cos θ) "
                   "and Figure 22 (the published accuracy table, fitted). It bounds each "
                   "reading's error against the true angle up to a constant, which no ISO 230-2 "
                   "parameter depends on.")
        note(f"wrote report {report}")


def _budget_data(alpha, beta, omega, accuracy, base) -> dict:
    import numpy as np

    from axiscal.errors import InputError
    from axiscal.physics import misalignment as mis
    from axiscal.units import ARCSEC

    for name, v in (("--alpha", alpha), ("--beta", beta), ("--omega", omega)):
        if not (abs(v) <= 100):
            raise InputError(f"{name} {v!r} mrad is not a small misalignment (at most 100 mrad)")
    if not 0 <= base <= 3600:
        raise InputError(f"--base {base!r} arcsec: the accuracy of the system at perfect "
                         "alignment must be between 0 and 3600 arcsec (1°)")
    a, b, w = alpha * 1e-3, beta * 1e-3, omega * 1e-3
    turn = np.linspace(0, 2 * np.pi, 3601)
    terms = mis.misalignment_terms(turn, a, b, w)
    peak = mis.peak_error(a, b, w) / ARCSEC
    fig = mis.SEED000_FIGURE22
    table = mis.tradeoff_table(np.array(fig["alpha_mrad"]) * 1e-3, np.array(fig["beta_mrad"]) * 1e-3,
                               w, base * ARCSEC)
    est = mis.expected_accuracy(a, b, w, base * ARCSEC)
    max_a = None
    if accuracy is not None:
        max_a = mis.max_alpha(accuracy * ARCSEC, b, w, base * ARCSEC) * 1e3
    return {
        "alpha_mrad": alpha, "beta_mrad": beta, "omega_mrad": omega,
        "terms_arcsec": {k: float(np.max(np.abs(getattr(terms, k)))) / ARCSEC
                         for k in ("quadratic", "alpha_beta", "alpha_omega")},
        "peak_arcsec": peak, "half_range_arcsec": mis.half_range(a, b, w) / ARCSEC,
        "datum_relative_arcsec": est.datum_relative / ARCSEC,
        "base_arcsec": base, "equation1_accuracy_arcsec": est.equation1 / ARCSEC,
        "figure22_model_arcsec": est.figure22 / ARCSEC,
        "expected_accuracy_arcsec": est.value / ARCSEC, "accuracy_source": est.source,
        "bounds": _BOUNDS,
        "accuracy_arcsec": accuracy, "max_alpha_mrad": max_a,
        "table": {"alpha_mrad": list(fig["alpha_mrad"]), "beta_mrad": list(fig["beta_mrad"]),
                  "accuracy_arcsec": table.rows(),
                  "published_figure22_arcsec": [list(r) for r in fig["accuracy_arcsec"]]},
    }


def render_rotary(result, title: str) -> None:
    from rich.markup import escape
    from rich.table import Table

    from axiscal.cli._common import console
    from axiscal.cli.iso230_2 import render_result
    from axiscal.standards.positioning_standards import parameter_label

    con = console()
    render_result(result.result, result.capture.dataset, title=title, console=con)
    s = result.summary()
    t = Table(title=escape("Measured beside the truth [arcsec]"), title_justify="left")
    for c in ("parameter", "measured", "true", "difference"):
        t.add_column(c, justify="right" if c != "parameter" else "left")
    for k, m in s["measured"].items():
        tv = s["truth"][k]
        if m is not None and tv is not None:
            t.add_row(parameter_label(k), f"{m:.2f}", f"{tv:.2f}", f"{m - tv:+.2f}")
    con.print(t)
    con.print(str(result.setup))
    if result.optics is not None:
        con.print(str(result.optics))
    con.print(str(result.budget))
    con.print(f"largest per-target error against the truth: {s['max_mean_error_arcsec']:.3f} arcsec "
              f"({'within' if s['within_budget'] else 'OUTSIDE'} the budget)")


def register(app: typer.Typer) -> None:
    """Add the ``rotary`` command group (``simulate``, ``budget``)."""
    group = typer.Typer(help="Rotary-axis calibration with an angular interferometer and a "
                             "counter-rotating reference calibrator (Renishaw, Interferometric "
                             "calibration of rotary axes).",
                        no_args_is_help=True)
    group.command("simulate")(simulate)
    group.command("budget")(budget)
    app.add_typer(group, name="rotary")
