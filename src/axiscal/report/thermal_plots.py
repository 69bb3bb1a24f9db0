"""The plot over time of an ISO 230-3 thermal test: the drifts above, the temperatures below."""

from __future__ import annotations

from pathlib import Path

from axiscal.standards.iso230_3 import drift_series
from axiscal.standards.iso230_3_data import TESTS, ThermalLog

__all__ = ["plot_thermal", "save_thermal_plot", "thermal_report"]


def plot_thermal(log: ThermalLog, title: str | None = None):
    """A matplotlib Figure: each drift quantity relative to its start (µm, tilts in µrad on a
    second axis) and each temperature (°C) against time in hours; the end of the run marked."""
    from axiscal.report._figures import pyplot

    plt = pyplot()
    fig, (top, bottom) = plt.subplots(2, 1, sharex=True, figsize=(9, 6.5))
    hours = log.time / 3600.0
    tilt_ax = None
    for name, v in drift_series(log).items():
        d = (v - v[0]) * 1e6
        if name in ("A", "B"):
            tilt_ax = tilt_ax or top.twinx()
            tilt_ax.plot(hours, d, "--", lw=0.8, label=f"tilt {name}",
                         color={"A": "tab:purple", "B": "tab:brown"}[name])
        else:
            top.plot(hours, d, lw=1.2, label=f"δ{name}")
    top.set_ylabel("drift / µm")
    top.grid(True, alpha=0.3)
    lines, labels = top.get_legend_handles_labels()
    if tilt_ax is not None:
        tilt_ax.set_ylabel("tilt / µrad")
        more = tilt_ax.get_legend_handles_labels()
        lines, labels = lines + more[0], labels + more[1]
    top.legend(lines, labels, loc="best", fontsize=8)
    for name, v in log.temperatures.items():
        bottom.plot(hours, v, lw=1.2, label=name)
    bottom.set_ylabel("temperature / °C")
    bottom.set_xlabel("time / h")
    bottom.grid(True, alpha=0.3)
    bottom.legend(loc="best", fontsize=8)
    if log.run_end is not None:
        for ax in (top, bottom):
            ax.axvline(log.run_end / 3600.0, color="grey", lw=0.8, ls=":")
        top.annotate("stop", (log.run_end / 3600.0, 0), xytext=(3, 3),
                     textcoords="offset points", fontsize=8, color="grey")
    fig.suptitle(title or f"{TESTS[log.test]}: {log.test} test ({log.source})", fontsize=10)
    return fig


def save_thermal_plot(log: ThermalLog, path) -> Path:
    """Write :func:`plot_thermal` to ``path`` (.png, .svg or .pdf), atomically."""
    from axiscal.report._figures import save_figure

    return save_figure(plot_thermal(log), path)




def thermal_report(log: ThermalLog, result, truth: dict | None = None):
    """An HTML :class:`~axiscal.report.html.Report` of one ISO 230-3 test: its figures with U
    and clause, the plot over time, and (a simulation only) the twin's truth beside each
    figure, under the simulation banner."""
    from axiscal.report.html import Report

    rep = Report(title=f"{result.clause}: {log.test} test",
                 subtitle="Test code for machine tools — Part 3: Determination of thermal effects",
                 metadata={"Source": log.source, "Duration": f"{log.duration / 3600:.3g} h",
                           "Run ends": "—" if log.run_end is None else f"{log.run_end / 3600:.3g} h",
                           "Axis": log.axis or None})
    rows = []
    for f in result.figures:
        v, u = f.shown()
        rows.append([f.label, v, u, f.unit, f.clause])
    rep.add_heading("Figures")
    rep.add_table(["Figure", "Value", "U", "Unit", "Clause"], rows, digits=3)
    for n in result.notes:
        rep.add_text(n)
    rep.add_figure(plot_thermal(log), "Drift and temperatures over time")
    if truth:
        from axiscal.standards.iso230_3 import _UNITS

        rep.add_truth("Simulation truth")
        rep.add_table(["Figure", "Evaluated", "Truth", "U", "Unit"],
                      [[f.label, f.shown()[0], truth[f.name] * _UNITS[f.kind][1], f.shown()[1],
                        f.unit] for f in result.figures if f.name in truth], digits=3)
    return rep
