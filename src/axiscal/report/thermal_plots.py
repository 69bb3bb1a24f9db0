"""The plot over time of an ISO 230-3 thermal test: the drifts above, the temperatures below."""

from __future__ import annotations

from pathlib import Path

from axiscal.standards.iso230_3 import drift_series
from axiscal.standards.iso230_3_data import TESTS, ThermalLog

__all__ = ["plot_thermal", "save_thermal_plot"]


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


