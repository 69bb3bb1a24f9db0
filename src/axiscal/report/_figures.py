"""What every figure module of the reports shares: matplotlib on the Agg backend (no display
needed), saving a figure atomically by its file's extension, and the frame of a ballbar polar plot.

The squareness, ballbar, positioning and motion plots all save through :func:`save_figure`, so a
plot file is refused in one line for an extension other than png, svg or pdf and is never left
half-written (:func:`axiscal.io._files.write_bytes_atomic`).
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

__all__ = ["pyplot", "save_figure", "nice_step", "polar_rings", "polar_frame"]

#: The formats a plot file may have, by extension.
FORMATS = ("png", "svg", "pdf")


def pyplot():
    """``matplotlib.pyplot`` on the Agg backend (imported on first use: it costs start-up time)."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    return plt


def save_figure(fig, path, *, dpi: float = 150, tight: bool = True) -> Path:
    """Save a figure by the file's extension (png, svg, pdf) atomically and close it.

    Parameters
    ----------
    fig : matplotlib.figure.Figure
    path : path
    dpi : float
        Resolution of a PNG, dots per inch (a vector format ignores it).
    tight : bool
        Crop the figure to its content (``bbox_inches="tight"``).

    Raises
    ------
    InputError
        For an extension other than ``.png``, ``.svg`` or ``.pdf`` (the figure is closed).
    """
    import io

    from axiscal.errors import InputError
    from axiscal.io._files import write_bytes_atomic

    plt = pyplot()
    p = Path(path)
    fmt = p.suffix.lower().lstrip(".") or "png"
    if fmt not in FORMATS:
        plt.close(fig)
        raise InputError(f"plot file {p.name}: use a .png, .svg or .pdf extension")
    buf = io.BytesIO()
    fig.savefig(buf, format=fmt, bbox_inches="tight" if tight else None,
                dpi=dpi if fmt == "png" else None)
    plt.close(fig)
    return write_bytes_atomic(p, buf.getvalue())


def nice_step(v: float) -> float:
    """The smallest 1, 2, 5 or 10 × 10^k not below ``v`` (> 0): a round ring or grid spacing.

    Examples
    --------
    >>> nice_step(3.2e-6), nice_step(0.7), nice_step(5.0)
    (5e-06, 1.0, 5.0)
    """
    step = 10 ** np.floor(np.log10(v))
    for m in (1, 2, 5, 10):
        if m * step >= v:
            return float(m * step)
    return float(10 * step)  # pragma: no cover


def polar_rings(ax, ring: float, labelled: bool = False):
    """Draw the nominal circle (radius 1) and dotted rings at ± ``ring`` of deviation about it
    (each named at 62° when ``labelled``); return ``(base, k, t)``: the nominal radius, the
    magnification (plot units per metre of deviation, a ring at 0.45) and 361 angles over a
    turn, for the caller's traces."""
    base, k = 1.0, 0.45 / ring
    t = np.linspace(0, 2 * np.pi, 361)
    c, sn = np.cos(np.radians(62)), np.sin(np.radians(62))
    for v, style in ((-ring, ":"), (0.0, "-"), (ring, ":")):
        ax.plot((base + k * v) * np.cos(t), (base + k * v) * np.sin(t), color="0.6", ls=style,
                lw=0.8)
        if labelled:
            ax.annotate(f"{v * 1e6:+.3g} µm" if v else "nominal", ((base + k * v) * c,
                        (base + k * v) * sn), fontsize=8, color="0.35", xytext=(4, 0),
                        textcoords="offset points", va="center")
    return base, k, t


def polar_frame(ax, axes, xlim, ylim, scale_note: str) -> None:
    """The frame of a ballbar polar plot: equal aspect, the limits, the two axes' directions as
    labels (``scale_note`` after the first) and no ticks (the rings give the scale)."""
    ax.set_aspect("equal")
    ax.set_xlim(*xlim)
    ax.set_ylim(*ylim)
    ax.axhline(0, color="0.85", lw=0.6)
    ax.axvline(0, color="0.85", lw=0.6)
    a0, a1 = axes
    ax.set_xlabel(f"+{a0} →   {scale_note}")
    ax.set_ylabel(f"+{a1} →")
    ax.set_xticks([])
    ax.set_yticks([])
