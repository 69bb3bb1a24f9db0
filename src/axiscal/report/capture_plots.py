"""The dynamic view of a captured record: position, velocity, acceleration, stops, spectrum."""

from __future__ import annotations

import numpy as np

from axiscal.units import ARCSEC

__all__ = ["dynamic_figure", "save_dynamic_view"]

_MAX_POINTS = 200_000


def dynamic_figure(record, result):
    """Four panels: position with the stops, velocity, acceleration, settling and spectrum."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    lin = record.kind == "linear"
    scale, unit = (1e3, "mm") if lin else (180 / np.pi, "deg")
    step = max(1, record.times.size // _MAX_POINTS)
    t = record.times[::step]
    fig, ax = plt.subplots(2, 2, figsize=(12, 7.5))
    a = ax[0, 0]
    a.plot(t, result.smoothed[::step] * scale, lw=0.7, color="0.3")
    for k, _ in result.assigned:
        s = result.stops[k]
        a.axvspan(s.t_start, s.t_end, color="tab:green", alpha=0.25, lw=0)
    a.set(xlabel="time [s]", ylabel=f"reading [{unit}]",
          title=f"{len(result.assigned)} stops matched to the plan (green)")
    a = ax[0, 1]
    a.plot(t, result.velocity[::step] * scale, lw=0.7, color="tab:blue", label="velocity")
    a.set(xlabel="time [s]", ylabel=f"velocity [{unit}/s]", title="Velocity and acceleration")
    b = a.twinx()
    b.plot(t, result.acceleration[::step] * scale, lw=0.5, color="tab:orange", alpha=0.6)
    b.set_ylabel(f"acceleration [{unit}/s²]", color="tab:orange")
    a = ax[1, 0]
    a.bar(np.arange(1, result.settling.size + 1), result.settling, color="tab:purple")
    a.set(xlabel="measurement (in time order)", ylabel="settling time [s]",
          title="Settling: from the end of the move to the stable band")
    a = ax[1, 1]
    f, amp = result.spectrum
    su, un = (1e6, "µm") if lin else (1 / ARCSEC, "arcsec")
    if f.size:
        a.semilogy(f, np.maximum(amp * su, 1e-6), lw=0.8, color="tab:red")
    a.set(xlabel="frequency [Hz]", ylabel=f"amplitude [{un}]",
          title="Vibration at the stops (Hann-windowed FFT)")
    for x in ax.flat:
        x.grid(alpha=0.3)
    fig.tight_layout()
    return fig


def save_dynamic_view(record, result, path) -> None:
    """Write :func:`dynamic_figure` to ``path``."""
    dynamic_figure(record, result).savefig(path, dpi=100)
