"""Plots of positioning tests (matplotlib, Agg backend, no display needed).

The ISO 230-2 plot follows the layout of the standard's figures and of the reports calibration
engineers are used to: the mean positioning deviation per direction (x̄↑, x̄↓) against the target,
the ±2s bands around each, every run's readings as points, and a box with A, E, M, R, B.
"""

from __future__ import annotations

import unicodedata
from pathlib import Path

import numpy as np

from axiscal.report._figures import pyplot as _pyplot
from axiscal.report._figures import save_figure
from axiscal.report.labels import fmt, unit_text

__all__ = ["iso230_2_figure", "save_iso230_2_plot", "save_figure", "UP_COLOR", "DOWN_COLOR"]

UP_COLOR = "#0b5fa5"
DOWN_COLOR = "#c0392b"
BI_COLOR = "#2d3436"


def iso230_2_figure(result, dataset=None, title: str | None = None, truth=None, *,
                    band: float | None = 2.0, box: str | None = None):
    """The standard ISO 230-2 plot of one positioning test.

    Parameters
    ----------
    result : Iso230_2Result
    dataset : PositioningDataset, optional
        If given, every run's readings are drawn as points.
    title : str, optional
    truth : tuple of (ndarray, ndarray), optional
        ``(positions, systematic deviation)`` a simulation knew, drawn as a dashed line.
    band : float or None
        The ±k·s band drawn around each direction's mean (2 for ISO 230-2:2014 eqs. 20, 21);
        None draws none. :func:`standard_figure` passes another standard's band.
    box : str, optional
        The parameter box beside the plot (default: the ISO 230-2:2014 parameters).

    Returns
    -------
    matplotlib.figure.Figure
    """
    plt = _pyplot()
    u = {"um": "µm", "arcsec": "arcsec"}.get(result.deviation_unit, result.deviation_unit)
    tu = {"deg": "°"}.get(result.target_unit, result.target_unit)
    fig, ax = plt.subplots(figsize=(10, 5.2), dpi=110)
    t = result.targets
    for name, mean, s, color, arr in (
        ("positive ↑", result.mean_up, result.s_up, UP_COLOR, None if dataset is None else dataset.up),
        ("negative ↓", result.mean_down, result.s_down, DOWN_COLOR,
         None if dataset is None else dataset.down),
    ):
        if np.all(np.isnan(mean)):
            continue
        if band is not None:
            ax.fill_between(t, mean - band * s, mean + band * s, color=color, alpha=0.13,
                            linewidth=0, label=f"x̄ ± {band:g}s, {name.split()[0]}")
        ax.plot(t, mean, "-", color=color, lw=1.8, marker="o", ms=3.5, label=f"mean x̄, {name}")
        if arr is not None and arr.shape[1]:
            jitter = 0.004 * (t[-1] - t[0]) * (1 if color == UP_COLOR else -1)
            for j in range(arr.shape[1]):
                ax.plot(t + jitter, arr[:, j], ".", color=color, ms=3, alpha=0.55,
                        label="readings" if j == 0 and color == UP_COLOR else None)
    if result.bidirectional:
        ax.plot(t, result.mean_bi, ":", color=BI_COLOR, lw=1.2, label="mean bidirectional x̄")
    if truth is not None:
        ax.plot(truth[0], truth[1], "--", color="#27ae60", lw=1.2, label="truth (simulation)")
    ax.axhline(0, color="#888", lw=0.6)
    ax.set_xlabel(f"Target position [{tu}]")
    ax.set_ylabel(f"Positioning deviation [{u}]")
    ax.grid(True, color="#e3e7ec", lw=0.7)
    ax.set_xlim(t[0] - 0.02 * (t[-1] - t[0]), t[-1] + 0.02 * (t[-1] - t[0]))
    if result.axis_kind.value == "rotary" and result.target_unit == "deg":
        span = t[-1] - t[0]
        if span >= 90:
            ax.set_xticks(np.arange(np.ceil(t[0] / 45) * 45, t[-1] + 1e-9, 45 if span <= 720 else 90))
    ax.set_title(title or default_title(dataset), loc="left", fontsize=12)
    ax.legend(loc="upper left", bbox_to_anchor=(1.01, 1.0), fontsize=8.5, frameon=False)
    ax.text(1.015, 0.0, box or _parameter_box(result, u), transform=ax.transAxes, fontsize=9,
            family="monospace", va="bottom", ha="left",
            bbox=dict(boxstyle="round,pad=0.5", fc="#f5f7fa", ec="#c9d1db"))
    fig.tight_layout()
    return fig


def per_target(dataset):
    """Each direction's mean and standard deviation at every target, for a figure: NaN-aware, an
    s of NaN (no band) where a direction has fewer than 2 readings, so a test another standard
    evaluates but ISO 230-2:2014 refuses still has its picture. The fields
    :func:`iso230_2_figure` reads from an :class:`~axiscal.standards.iso230_2.Iso230_2Result`."""
    from types import SimpleNamespace

    def stats(a):
        if a.shape[1] == 0:
            return (np.full(dataset.targets.size, np.nan),) * 2
        n = np.sum(~np.isnan(a), axis=1)
        with np.errstate(invalid="ignore", divide="ignore"):
            mean = np.nansum(a, axis=1) / n
            dev = np.where(np.isnan(a), 0.0, a - mean[:, None])
            s = np.sqrt(np.sum(dev ** 2, axis=1) / (n - 1))
        return mean, np.where(n >= 2, s, np.nan)

    up, s_up = stats(dataset.up)
    down, s_down = stats(dataset.down)
    both = dataset.up.shape[1] > 0 and dataset.down.shape[1] > 0
    return SimpleNamespace(
        targets=dataset.targets, mean_up=up, mean_down=down, s_up=s_up, s_down=s_down,
        mean_bi=0.5 * (up + down), bidirectional=both, axis_kind=dataset.axis_kind,
        target_unit=dataset.target_unit, deviation_unit=dataset.deviation_unit,
        n_runs=int(max(dataset.up.shape[1], dataset.down.shape[1])))


def standard_figure(dataset, standard, result):
    """The per-target plot of one test by another positioning standard: each direction's mean and
    every run's readings, the band that standard's definitions use (``standard.band``: ±3s for
    JIS B 0182 and ISO 230-2:1988, none where it is not public) and its own parameters beside.

    ``standard`` is a :class:`~axiscal.standards.positioning_standards.Standard` and ``result``
    its :class:`~axiscal.standards.positioning_standards.StandardResult` for ``dataset``.
    """
    from axiscal.standards.positioning_standards import parameter_label

    u = unit_text(dataset.deviation_unit)
    lines = [f"{standard.title} [{u}]"]
    for name, (v, _unit, _d) in result.parameters().items():
        label = parameter_label(name)
        lines.append(f"{label:<7}" + ("      —" if v is None else f"{fmt(v, u):>9}"))
    lines += [f"{name:<7}      —" for name, _ in result.not_evaluated]
    base = per_target(dataset)
    lines.append(f"runs {base.n_runs}, targets {base.targets.size}")
    title = default_title(dataset).replace("ISO 230-2:2014", standard.title)
    return iso230_2_figure(base, dataset, title, band=standard.band, box="\n".join(lines))


def standards_figure(dataset, results):
    """The figure of ``evaluate --standard all``: ISO 230-2:2014's when it evaluates the test,
    else the first standard's that does (``results`` as
    :func:`~axiscal.standards.positioning_standards.evaluate_all` gives them); None if none does."""
    from axiscal.standards import iso230_2

    done = [(std, r) for std, r in results if not isinstance(r, str)]
    if not done:
        return None
    if done[0][0].key == "iso230-2:2014":
        return iso230_2_figure(iso230_2.evaluate(dataset), dataset)
    return standard_figure(dataset, *done[0])


def default_title(dataset=None) -> str:
    """"Positioning deviation, ISO 230-2:2014", followed by the machine and axis when the
    dataset's metadata names them (a plot file leaves the report that named them)."""
    base = "Positioning deviation, ISO 230-2:2014"
    if dataset is None:
        return base
    md = dataset.metadata
    who = " ".join(str(v) for v in (md.machine, md.axis and f"axis {md.axis}") if v)
    return f"{base} — {who}" if who else base


def _parameter_box(result, u: str) -> str:
    from axiscal.standards.iso230_2 import PARAMETER_SYMBOLS

    labels = [(k, PARAMETER_SYMBOLS[k]) for k in ("A", "A_up", "A_down", "E", "M", "R", "R_up",
                                                  "R_down", "B", "B_mean")]
    lines = [f"ISO 230-2 [{u}]"]
    for key, label in labels:
        v = getattr(result, key)
        if v is not None:
            pad = 3 - sum(not unicodedata.combining(c) for c in label)  # B̄ is one column wide
            lines.append(f"{label}{' ' * pad}{fmt(v, u):>9}")   # the tables' decimals
    lines.append(f"runs {result.n_runs}, targets {result.targets.size}")
    return "\n".join(lines)


def save_iso230_2_plot(result, dataset, path, title: str | None = None, truth=None) -> Path:
    """Write the ISO 230-2 plot (PNG, SVG or PDF by the file's extension)."""
    return save_figure(iso230_2_figure(result, dataset, title, truth), path)
