"""Plots of the five-DOF motion-error measurement (matplotlib, Agg backend).

* :func:`five_errors_figure`: the five errors against angle, every run, with the truth if known;
* :func:`stability_figure`: the five stability traces against time, with and without the drift
  compensation;
* :func:`polar_figure`: ISO 230-7 polar plots of radial, axial and tilt error motion.

Each returns a matplotlib figure; :func:`save_figure` writes one atomically by extension.
"""

from __future__ import annotations

import numpy as np

from axiscal.report._figures import pyplot as _pyplot
from axiscal.report._figures import save_figure
from axiscal.units import ARCSEC, UM

__all__ = ["five_errors_figure", "stability_figure", "polar_figure", "save_figure", "LABELS"]

#: Channel -> (axis label, SI factor of its display unit).
LABELS = {
    "ez": ("εz angular positioning [arcsec]", ARCSEC),
    "ey": ("εy tilt about Y [arcsec]", ARCSEC),
    "ex": ("εx tilt about X [arcsec]", ARCSEC),
    "dy": ("δy radial [µm]", UM),
    "dz": ("δz axial [µm]", UM),
}
_COLOURS = ["#1f5fa8", "#d1601f", "#2f8f46", "#8a3ea8", "#a82f3e"]


def _name_panel(ax, label: str) -> None:
    """Symbol and unit as the y label (``εz [arcsec]``), the error's name above the panel: the
    whole name beside five short panels ran into its neighbours' labels."""
    symbol, _, rest = label.partition(" ")
    name, _, unit = rest.rpartition(" ")
    ax.set_ylabel(f"{symbol} {unit}", fontsize=8.5)
    ax.set_title(name, loc="left", fontsize=8, pad=2)


def five_errors_figure(runs, truth=None, title: str = "Five motion errors against angle"):
    """One panel per error against angle (degrees) for each run; the truth dashed if given.

    Parameters
    ----------
    runs : sequence of FiveErrors (or objects with theta, ez, ey, ex, dy, dz in SI)
    truth : sequence of FiveErrors, optional
    title : str
    """
    plt = _pyplot()
    fig, axes = plt.subplots(5, 1, figsize=(10.0, 8.0), sharex=True)   # wider than tall:
    # a print fits a figure in 118 mm of height; 7.5 × 10.5 in left it a third of the page wide
    for k, (ch, (label, unit)) in enumerate(LABELS.items()):
        ax = axes[k]
        for j, run in enumerate(runs):
            ax.plot(np.degrees(run.theta), getattr(run, ch) / unit, "o-", ms=3.5, lw=1.2,
                    color=_COLOURS[j % len(_COLOURS)], label=f"run {j + 1} (measured)")
        for j, t in enumerate(truth or ()):
            ax.plot(np.degrees(t.theta), getattr(t, ch) / unit, "--", lw=1.0, color="0.35",
                    label=f"truth, run {j + 1} (simulation)")
        _name_panel(ax, label)
        ax.grid(True, alpha=0.3)
    axes[-1].set_xlabel("commanded angle θ [°]")
    axes[-1].set_xticks(np.arange(0, 361, 30))
    # above the first panel, never over the data
    axes[0].legend(fontsize=7.5, ncol=2, loc="lower right", bbox_to_anchor=(1.0, 1.0),
                   frameon=False)
    fig.suptitle(title, fontsize=11)
    fig.tight_layout()
    return fig


def stability_figure(run, title: str = "Stability: five errors of a still set-up"):
    """The five errors against time (minutes) with (solid) and without (grey) drift compensation.

    Parameters
    ----------
    run : MotionRun
        From :func:`axiscal.procedures.motion_errors.stability_test`.
    """
    plt = _pyplot()
    fig, axes = plt.subplots(5, 1, figsize=(10.0, 8.0), sharex=True)   # wider than tall:
    # a print fits a figure in 118 mm of height; 7.5 × 10.5 in left it a third of the page wide
    minutes = run.time / 60.0
    for k, (ch, (label, unit)) in enumerate(LABELS.items()):
        ax = axes[k]
        raw = getattr(run.uncompensated, ch) / unit
        meas = getattr(run.measured, ch) / unit
        ax.plot(minutes, raw, lw=0.8, color="0.65", label="without drift compensation")
        ax.plot(minutes, meas, lw=0.9, color=_COLOURS[k],
                label=f"compensated (σ = {np.std(meas):.3f})")
        _name_panel(ax, label)
        ax.grid(True, alpha=0.3)
        # beside the panel: inside, it hid the first minutes of the traces
        ax.legend(fontsize=7, loc="upper left", bbox_to_anchor=(1.01, 1.0), frameon=False)
    axes[-1].set_xlabel("time [min]")
    fig.suptitle(title, fontsize=11)
    fig.tight_layout()
    return fig


def polar_figure(result, title: str = "ISO 230-7 error motion (polar plots)"):
    """Polar plots of every error motion in ``result`` (an ISO 230-7 result).

    Each panel draws every run (thin) and the synchronous curve (thick) as
    ``base + value`` around a dotted zero circle of radius ``base`` (2 × the largest |value|),
    with labelled rings at a round step in the panel's unit so the error can be read off the
    plot; the fundamental is removed where ISO 230-7 removes it.
    """
    plt = _pyplot()
    motions = result.motions
    cols = 2
    rows = (len(motions) + 1) // 2
    fig, axes = plt.subplots(rows, cols, figsize=(8.0, 4.2 * rows), subplot_kw={"projection": "polar"})
    axes = np.atleast_1d(axes).ravel()
    th = np.append(result.theta, result.theta[0])
    for ax, m in zip(axes, motions):
        unit, sym = (UM, "µm") if m.kind == "length" else (ARCSEC, "arcsec")
        runs = m.runs / unit
        peak = max(float(np.max(np.abs(runs))), 1e-9)
        base = 2.0 * peak
        for r in runs:
            ax.plot(th, base + np.append(r, r[0]), lw=0.7, color="0.55")
        sync = m.synchronous_curve / unit
        ax.plot(th, base + np.append(sync, sync[0]), lw=2.0, color="#1f5fa8")
        ax.plot(np.linspace(0, 2 * np.pi, 200), np.full(200, base), lw=0.6, ls=":", color="k")
        step = ring_step(peak)
        ax.set_rmin(0.0)
        ax.set_rmax(base + 1.1 * peak)
        rings = step * np.arange(-np.floor(peak / step), np.floor(1.1 * peak / step) + 1)
        ax.set_rticks(base + rings, [f"{v:+g}" if v else "0" for v in rings], fontsize=7,
                      color="0.3")
        ax.set_rlabel_position(67.5)
        asy = "—" if np.isnan(m.asynchronous) else f"{m.asynchronous / unit:.2f}"
        ax.set_title(f"{m.name}: total {m.total / unit:.2f}, sync {m.synchronous / unit:.2f}, "
                     f"async {asy} {sym}\n(dotted circle = zero; rings every {step:g} {sym})",
                     fontsize=8.5)
    for ax in axes[len(motions):]:
        ax.set_visible(False)
    fig.suptitle(title, fontsize=11)
    fig.tight_layout(h_pad=2.0)   # keep a panel's title clear of the 270° label above it
    return fig


def ring_step(peak: float) -> float:
    """A round ring spacing (1, 2 or 5 × 10^k) giving one to two rings over ``peak``."""
    k = 10.0 ** np.floor(np.log10(peak))
    for m in (1.0, 2.0, 5.0, 10.0):
        if peak / (m * k) <= 2.0:
            return float(m * k)
    return float(10.0 * k)
