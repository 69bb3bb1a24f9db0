"""Plot of a compensation loop: the deviations before, the table, and the deviations after.

Top panel: the mean deviations x̄↑, x̄↓ of the first test and the table's *expected deviation*
(−correction, per direction) drawn between its points, so a reader sees that the table follows
the error. Bottom panel: the re-measured mean deviations with their ±2s bands, on their own
scale, with E before and after and the budget that explains what remains.
"""

from __future__ import annotations

import numpy as np

from axiscal.report.plots import DOWN_COLOR, UP_COLOR, _pyplot, save_figure

__all__ = ["compensation_figure", "save_compensation_plot"]


def compensation_figure(loop, title: str | None = None):
    """The before/table/after figure of a :class:`~axiscal.compensation.loop.CompensationLoopResult`."""
    plt = _pyplot()
    b, a, t = loop.before, loop.after, loop.table
    u = {"um": "µm"}.get(loop.unit, loop.unit)
    tu = {"deg": "°"}.get(b.target_unit, b.target_unit)
    fig, (ax0, ax1) = plt.subplots(2, 1, figsize=(10, 7.2), dpi=110, sharex=True,
                                   gridspec_kw=dict(height_ratios=[1.25, 1.0]))
    x = np.linspace(t.start, t.end, 20 * (t.n_points - 1) + 1)
    # A writer may re-reference the table (zero at the reference point): a constant that the
    # reference absorbs. Shift the drawn table by it so it lies on the measured means.
    shift = float(np.median(b.mean_bi + 0.5 * (t.correction_at(b.targets, 1)
                                               + t.correction_at(b.targets, -1))))
    shifted = f" {shift:+.2f} {u}" if abs(shift) > 1e-9 else ""
    for mean, color, name, d in ((b.mean_up, UP_COLOR, "↑", 1), (b.mean_down, DOWN_COLOR, "↓", -1)):
        ax0.plot(b.targets, mean, "o", color=color, ms=3.5, label=f"measured mean x̄{name}")
        ax0.plot(x, shift - np.asarray(t.correction_at(x, d)), "-", color=color, lw=1.1, alpha=0.8,
                 label=f"−(table correction) {name}" + (f", shifted{shifted}" if shifted else ""))
    ax0.plot(t.positions, shift - t.up, "|", color="#2d3436", ms=7, label="table points")
    if shifted:
        ax0.text(1.015, 0.0, f"The table is re-referenced\n(zero at its reference point);\n"
                 f"drawn shifted by{shifted}.\nThe offset after compensation\nis that constant.",
                 transform=ax0.transAxes, fontsize=8, va="bottom", ha="left", color="#555")
    ax0.set_ylabel(f"Deviation before [{u}]")
    ax0.set_title(title or f"Compensation loop: {loop.controller_file.controller} table, "
                  f"{t.n_points} points every {t.spacing:g}{'' if tu == '°' else ' '}{tu}",
                  loc="left", fontsize=12)
    for mean, s, color, name in ((a.mean_up, a.s_up, UP_COLOR, "↑"), (a.mean_down, a.s_down, DOWN_COLOR, "↓")):
        ax1.fill_between(a.targets, mean - 2 * s, mean + 2 * s, color=color, alpha=0.13, lw=0)
        ax1.plot(a.targets, mean, "-o", color=color, ms=3, lw=1.3, label=f"re-measured x̄{name} ± 2s")
    ax1.set_ylabel(f"Deviation after [{u}]")
    ax1.set_xlabel(f"Target position [{tu}]")
    text = (f"E before {b.E:.2f} {u}\nE after  {a.E:.2f} {u}  (−{100 * loop.reduction:.0f} %)\n"
            f"budget   {loop.budget_E:.2f} {u}")
    ax1.text(1.015, 0.0, text, transform=ax1.transAxes, fontsize=9, family="monospace",
             va="bottom", ha="left", bbox=dict(boxstyle="round,pad=0.5", fc="#f5f7fa", ec="#c9d1db"))
    for ax in (ax0, ax1):
        ax.axhline(0, color="#888", lw=0.6)
        ax.grid(True, color="#e3e7ec", lw=0.7)
        ax.legend(loc="upper left", bbox_to_anchor=(1.01, 1.0), fontsize=8.5, frameon=False)
    if b.axis_kind.value == "rotary" and b.target_unit == "deg":
        # ticks every 45° over the tested range only: fixed 0-360 ticks squeezed a shorter
        # (or negative) travel into a corner of the plot
        lo, hi = float(b.targets[0]), float(b.targets[-1])
        if hi - lo >= 90:
            ax1.set_xticks(np.arange(np.ceil(lo / 45) * 45, hi + 1e-9, 45 if hi - lo <= 720 else 90))
        ax1.set_xlim(lo - 0.02 * (hi - lo), hi + 0.02 * (hi - lo))
    fig.tight_layout()
    return fig


def save_compensation_plot(loop, path, title: str | None = None):
    """Write the loop's figure (PNG, SVG or PDF by extension)."""
    return save_figure(compensation_figure(loop, title), path)
