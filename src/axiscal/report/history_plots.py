"""Plots of the calibration history: a comparison of two tests and a parameter's trend."""

from __future__ import annotations

from axiscal.report._figures import pyplot as _pyplot

__all__ = ["comparison_figure", "trend_figure"]


def comparison_figure(c):
    """Per-target change of the mean bidirectional deviation (second − first test)."""
    from axiscal.errors import InputError

    plt = _pyplot()

    if c.targets is None:
        raise InputError("a per-target comparison needs two ISO 230-2 tests with common targets")
    fig, ax = plt.subplots(figsize=(8, 4))
    ax.axhline(0, color="0.6", lw=0.8)
    ax.plot(c.targets, c.difference, "o-", color="tab:blue",
            label=f"test {c.second} − test {c.first}")
    ax.set_xlabel(f"target [{c.target_unit}]")
    ax.set_ylabel(f"change of x̄ [{'µm' if c.unit == 'um' else c.unit}]")
    ax.grid(alpha=0.3)
    ax.legend()
    ax.set_title(f"Change of the mean bidirectional deviation (ISO 230-2:2014), "
                 f"tests {c.first} → {c.second}", fontsize=10)
    fig.tight_layout()
    return fig


def trend_figure(tr, title: str = ""):
    """The parameter over time, the fitted line and the tolerance with its predicted crossing."""
    import matplotlib.dates as mdates

    plt = _pyplot()

    fig, ax = plt.subplots(figsize=(8, 4))
    ax.plot(tr.dates, tr.values, "o", color="tab:blue", label=tr.parameter)
    if tr.drift is not None:
        ends = [tr.dates[0], tr.crossing or tr.dates[-1]]
        t0 = tr.dates[-1]
        y = [tr.level + tr.drift * (d - t0).total_seconds() / (365.25 * 86400) for d in ends]
        ax.plot(ends, y, "-", color="tab:blue", alpha=0.6,
                label=f"drift {tr.drift:+.3g} {tr.unit}/year")
    if tr.tolerance is not None:
        ax.axhline(tr.tolerance, color="tab:red", ls="--", label=f"tolerance {tr.tolerance:g}")
    if tr.crossing is not None:
        ax.plot([tr.crossing], [tr.tolerance], "D", color="tab:red", ms=7,
                label=f"predicted crossing {tr.crossing:%Y-%m-%d}")
    if tr.recalibrate_by is not None:
        ax.axvline(tr.recalibrate_by, color="tab:orange", ls=":",
                   label=f"recalibrate by {tr.recalibrate_by:%Y-%m-%d}")
    ax.xaxis.set_major_formatter(mdates.DateFormatter("%Y-%m-%d"))
    ax.set_xlabel("date of the test")
    ax.set_ylabel(f"{tr.parameter} [{'µm' if tr.unit == 'um' else tr.unit}]")
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8)
    ax.set_title(title or f"Trend of {tr.parameter}", fontsize=10)
    fig.autofmt_xdate()
    fig.tight_layout()
    return fig
