"""Plot of a laser-scale referencing run against position, like Figure 4 of Renishaw, Laser scale axis referencing.

Panels, sharing the position axis (real output counts of motion beyond the switch, and µm):
the laser head's digital A/B quadrature, the reference switch, the synthesised sine and cosine
(with the stage-1 phase continued as a faint line, to show the virtual movement of stage 2), and
the reference mark; the events A, B, Z, C and the stages 1, 2, 3 are marked.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from axiscal.report._figures import pyplot as _pyplot

__all__ = ["referencing_figure", "save_referencing_plot"]


def referencing_figure(run, before_counts: float | None = None, after_counts: float | None = None):
    """A matplotlib Figure of a :class:`~axiscal.procedures.referencing.ReferencingRun`."""
    plt = _pyplot()
    lo, hi, sl, xk = _window(run, before_counts, after_counts)
    fig, axes = plt.subplots(4, 1, sharex=True, figsize=(10, 7.5),
                             gridspec_kw={"height_ratios": [1.0, 0.6, 2.0, 0.8]})
    _signal_panels(axes, run, sl, xk)
    _events_and_stages(axes, run, lo, hi)
    ev = {e.name: e for e in run.events}
    z = (f"Z measured {ev['Z'].counts_beyond_switch:.1f} ± {ev['Z'].uncertainty_counts:.1f} "
         f"output counts beyond the switch, design {ev['Z'].nominal_counts}") if "Z" in ev \
        else "no home found"
    fig.suptitle(f"Single-axis referencing with a compensated laser scale ({z})", fontsize=11)
    fig.tight_layout()
    return fig


def _window(run, before_counts, after_counts):
    """The part of the run drawn: (lo, hi) in output counts beyond the switch, the slice of the
    samples and their abscissa (true position beyond the switch's trip point, output counts)."""
    out = run.axis.output
    n = out.counts_per_period
    d = run.axis.direction
    if run.events:
        o_a = int(run.output_counts[run.event("A").index])
    else:
        o_a = int(run.output_counts[0])
    u = d * (run.output_counts - o_a)  # real output counts beyond the switch
    lo = -(1.5 * n if before_counts is None else before_counts)
    hi = 2.0 * n if after_counts is None else after_counts
    first = int(np.argmax(u >= lo)) if np.any(u >= lo) else 0
    beyond = np.flatnonzero(u > hi)
    last = int(beyond[0]) if beyond.size else u.size
    sl = slice(first, max(last, first + 2))
    # abscissa: the true position beyond the switch's trip point, in output-count lengths
    xk = d * (run.position[sl] - run.switch_trip) / out.count_size
    return lo, hi, sl, xk


def _signal_panels(axes, run, sl, xk) -> None:
    """The four signals: laser quadrature, switch, synthesised sine/cosine, reference mark."""
    out = run.axis.output
    n = out.counts_per_period
    a, b = run.axis.laser.quadrature(run.laser_counts[sl])
    axes[0].step(xk, a + 1.6, where="post", lw=0.9, color="tab:blue", label="A")
    axes[0].step(xk, b + 0.0, where="post", lw=0.9, color="tab:orange", label="B")
    axes[0].set_yticks([0.5, 2.1], ["B", "A"])
    axes[0].set_title(f"laser head quadrature ({run.axis.laser.count_size * 1e6:.3f} µm, "
                      "uncompensated)", fontsize=9, loc="left")
    axes[1].step(xk, run.switch[sl].astype(float), where="post", color="k", lw=1.0)
    axes[1].set_yticks([0, 1], ["off", "on"])
    axes[1].set_title("reference switch (into the compensator)", fontsize=9, loc="left")
    axes[2].plot(xk, run.sine[sl], lw=1.2, color="tab:red", label="sine")
    axes[2].plot(xk, run.cosine[sl], lw=1.2, color="tab:green", label="cosine")
    unphased = 2 * np.pi * (run.output_counts[sl] + run.power_up_phase) / n
    axes[2].plot(xk, np.sin(unphased), lw=0.6, color="tab:red", alpha=0.25,
                 label="sine if not rephased")
    axes[2].set_ylim(-1.25, 1.25)
    # outside the panel, at the right of its title: inside it the legend hid the stage-1 trough
    axes[2].legend(loc="lower right", bbox_to_anchor=(1.0, 1.0), fontsize=8, ncol=3,
                   frameon=False, borderaxespad=0.1)
    axes[2].set_title(f"synthesised outputs to the controller ({n} counts per "
                      f"{out.period * 1e6:g} µm period)", fontsize=9, loc="left")
    axes[3].step(xk, run.reference[sl].astype(float), where="post", color="tab:purple", lw=1.2)
    axes[3].set_yticks([0, 1], ["off", "on"])
    axes[3].set_title("reference mark (to the controller)", fontsize=9, loc="left")
    axes[3].set_xlabel("true position beyond the switch's trip point [lengths of one output "
                       f"count, {out.count_size * 1e9:.3f} nm]")


def _events_and_stages(axes, run, lo, hi) -> None:
    """Events A, B, Z, C as dashed lines, the three stages, and the µm scale below."""
    out = run.axis.output
    d = run.axis.direction
    marks = {e.name: d * (e.position - run.switch_trip) / out.count_size for e in run.events}
    for name, k in marks.items():
        for ax in axes:
            ax.axvline(k, color="0.3", lw=0.8, ls="--")
        axes[0].annotate(name, (k, 1.0), xycoords=("data", "axes fraction"),
                         xytext=(0, 3), textcoords="offset points", ha="center", fontsize=10,
                         fontweight="bold")
    stages = [("Stage 1", lo, 0.0), ("Stage 2", 0.0, float(run.stage2_counts)),
              ("Stage 3", float(run.stage2_counts), hi)]
    for label, s0, s1 in stages:
        axes[2].axvspan(s0, s1, color={"Stage 2": "0.85"}.get(label, "1.0"), zorder=-1)
        axes[2].text((s0 + s1) / 2, 1.12, label, ha="center", fontsize=9)
    axes[2].text(run.stage2_counts / 2, -1.17, f"+{run.virtual} virtual counts", ha="center",
                 fontsize=8, color="0.3")
    axes[3].set_xlim(lo, hi)
    sec = axes[3].secondary_xaxis(
        "bottom", functions=(lambda c: c * out.count_size * 1e6,
                             lambda m: m / (out.count_size * 1e6)))
    sec.spines["bottom"].set_position(("outward", 38))
    sec.set_xlabel("µm beyond the switch")


def save_referencing_plot(run, path) -> Path:
    """Write the referencing plot to ``path`` (PNG, SVG or PDF by extension), atomically; any
    other extension is refused with :class:`~axiscal.errors.InputError` and nothing is written."""
    from axiscal.report.plots import save_figure

    return save_figure(referencing_figure(run), path)


def gantry_figure(run, required_limit: int | None = None):
    """The real skew X1 − X2 of a twin-axis homing, step by step (Renishaw, Laser scale axis
    referencing: the twin-axis sequence), with the controller's skew limit and the limit this
    configuration needs (``required_limit``, counts). ``run`` is a
    :class:`~axiscal.procedures.twin_axis.TwinHomingResult`."""
    plt = _pyplot()

    g = run.gantry
    q = g.output.count_size * 1e6
    skew = run.real_skew * q
    steps = np.arange(skew.size)
    fig, ax = plt.subplots(figsize=(10, 4.2), dpi=110)
    names = {1: "X1 homes (master)", 2: "X2 homes (master)", 3: "deskew, X2 alone"}
    for ph, colour in ((1, "#1f77b4"), (2, "#d62728"), (3, "#2ca02c")):
        m = run.phase == ph
        if m.any():
            ax.plot(*_envelope(steps[m], skew[m]), ".", ms=2.5, color=colour, label=names[ph])
    lim = run.skew_check.limit * q
    ax.axhline(lim, color="#c0392b", lw=1.0, ls="--", label=f"skew limit ±{lim:.2f} µm")
    ax.axhline(-lim, color="#c0392b", lw=1.0, ls="--")
    if required_limit is not None:
        need = required_limit * q
        ax.axhline(need, color="#7f8c8d", lw=0.9, ls=":",
                   label=f"limit needed ±{need:.2f} µm")
        ax.axhline(-need, color="#7f8c8d", lw=0.9, ls=":")
    ax.axhline(0, color="#888", lw=0.6)
    ax.set_xlabel("Command step")
    ax.set_ylabel("Real skew X1 − X2 [µm]")
    ax.grid(True, color="#e3e7ec", lw=0.7)
    ax.set_title(f"Twin-axis homing: skew before synchronisation {run.skew_check.skew} counts "
                 f"({run.skew_check.skew * q:.2f} µm)" + (", ALARM" if run.alarm else ""),
                 loc="left", fontsize=11)
    ax.legend(loc="upper left", bbox_to_anchor=(1.01, 1.0), fontsize=8.5, frameon=False)
    fig.tight_layout()
    return fig


def _envelope(x: np.ndarray, y: np.ndarray, bins: int = 2000):
    """At most 2·``bins`` points that keep every extreme: the lowest and highest y of each run
    of consecutive samples (a homing from far away has a million steps; drawn whole, its report
    would be tens of megabytes for the same picture)."""
    if x.size <= 2 * bins:
        return x, y
    edges = np.linspace(0, x.size, bins + 1).astype(np.int64)[:-1]
    lo, hi = np.minimum.reduceat(y, edges), np.maximum.reduceat(y, edges)
    xb = x[edges]
    return np.repeat(xb, 2), np.column_stack([lo, hi]).ravel()
