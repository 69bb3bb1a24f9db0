"""The dynamic view of a captured record: position, velocity, acceleration, stops, spectrum."""

from __future__ import annotations

import numpy as np

from axiscal.report._figures import pyplot as _pyplot
from axiscal.units import ARCSEC

__all__ = ["dynamic_figure", "save_dynamic_view", "environment_figure"]

_MAX_POINTS = 200_000


def dynamic_figure(record, result):
    """Four panels: position with the stops, velocity, acceleration, settling and spectrum."""
    plt = _pyplot()

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


def environment_figure(detail, title: str = "Environmental compensation"):
    """Two panels against the time of the test: the air and material temperatures (pressure on
    the right axis), and what the compensation changed at each reading (compensated minus raw
    deviation, µm)."""
    plt = _pyplot()

    c = detail.conditions
    t = detail.times
    fig, (a1, a2) = plt.subplots(2, 1, figsize=(10, 6.4), dpi=110, sharex=True)
    a1.plot(t, c.air_temperature, color="#1f77b4", lw=1.4, label="air temperature")
    if c.material_temperature is not None:
        a1.plot(t, c.material_temperature, color="#8c564b", lw=1.4,
                label="material temperature (mean of the sensors)")
    a1.set_ylabel("temperature [°C]")
    a1.grid(True, color="#e3e7ec", lw=0.7)
    ap = a1.twinx()
    ap.plot(t, np.asarray(c.pressure) / 100.0, color="#7f7f7f", lw=1.0, ls="--",
            label="pressure")
    ap.set_ylabel("pressure [hPa]")
    lines = a1.get_legend_handles_labels()
    more = ap.get_legend_handles_labels()
    a1.legend(lines[0] + more[0], lines[1] + more[1], loc="upper left", fontsize=8.5,
              frameon=False)
    a1.set_title(title, loc="left", fontsize=10.5)
    change = detail.deviation_um - detail.raw_deviation_um
    a2.plot(t, change, "o", ms=3.5, color="#2ca02c")
    a2.axhline(0, color="#888", lw=0.6)
    a2.set_ylabel("compensated − raw [µm]")
    a2.set_xlabel("time [s]")
    a2.grid(True, color="#e3e7ec", lw=0.7)
    a2.set_title("what the compensation changed at each reading", loc="left", fontsize=10.5)
    fig.tight_layout()
    return fig
