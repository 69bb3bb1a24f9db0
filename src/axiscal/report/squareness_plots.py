"""Plots for squareness and straightness: the distorted XY plane with each test and its result
(Chapman, Calibration of machine squareness Figures 13-26), the ballbar polar plot, and a straightness trace with its line.

Every ``save_*`` function writes atomically (PNG, SVG or PDF by extension); every ``*_figure``
function returns the matplotlib figure for a report. Agg backend, no display needed.
"""

from __future__ import annotations

from dataclasses import replace
from pathlib import Path

import numpy as np

from axiscal.report._figures import nice_step, polar_frame, polar_rings, pyplot, save_figure
from axiscal.report.labels import fmt

__all__ = ["comparison_figure", "save_comparison_plot", "ballbar_figure", "save_ballbar_plot",
           "straightness_figure", "save_straightness_plot", "magnification",
           "write_biaxial_report"]

_PANELS = (("a", "ballbar", "Circular test (ballbar)"), ("b", "diagonal", "Laser diagonal test"),
           ("c", "+", "Bi-axial straightness, “+”"), ("d", "T", "Bi-axial straightness, “T”"),
           ("e", "L", "Bi-axial straightness, “L”"))


def magnification(machine, target: float = 0.04) -> float:
    """A round magnification that makes the largest deviation about ``target`` of the plane."""
    x = np.linspace(*machine.x_range, 41)
    y = np.linspace(*machine.y_range, 41)
    gx, gy = np.meshgrid(x, y)
    dx, dy = machine.deviation(gx, gy)
    biggest = float(np.max(np.hypot(dx, dy)))
    if biggest == 0:
        return 1.0
    raw = target * max(machine.length_x, machine.length_y) / biggest
    step = 10 ** np.floor(np.log10(raw))
    return float(step * np.floor(raw / step))


def comparison_figure(machine, comparison):
    """Chapman, Calibration of machine squareness Figure 13-26 style: one panel per method, distorted plane, paths, results."""
    plt = pyplot()
    mag = magnification(machine)
    aspect = machine.length_y / machine.length_x
    fig, axes = plt.subplots(2, 3, figsize=(15, 2 + 8.6 * max(aspect, 0.45)))
    for ax, (letter, kind, title) in zip(axes.flat, _PANELS):
        _draw_plane(ax, machine, mag)
        rows = [r for r in comparison.results if _kind(r.method) == kind]
        for r in rows:
            _draw_test(ax, machine, r, mag, first=r.method == "+" or r.method.endswith(" 0"))
        ax.set_title(f"{letter}) {title}", fontsize=11)
    _summary_panel(axes.flat[5], machine, comparison, mag)
    fig.suptitle(f"{machine.name or 'XY plane'} — {comparison.scope} squareness in µm/m "
                 "(positive when the angle between +X and +Y exceeds 90°)", fontsize=13)
    fig.tight_layout()
    return fig


def save_comparison_plot(machine, comparison, path) -> Path:
    """Write :func:`comparison_figure` to ``path``."""
    return save_figure(comparison_figure(machine, comparison), path, dpi=110, tight=False)


def ballbar_figure(runs, result, title: str = "Ballbar test"):
    """Polar plot of a ballbar test: deviations magnified about the nominal circle."""
    plt = pyplot()
    fig, ax = plt.subplots(figsize=(8, 8.4))
    devs = np.concatenate([r.deviations for r in runs])
    span = max(float(np.max(np.abs(devs))), 1e-9)
    ring = nice_step(span)  # µm-scale rings at ±ring around the nominal circle
    base, k, _t = polar_rings(ax, ring, labelled=True)
    colours = {"ccw": "tab:blue", "cw": "tab:red"}
    for r in runs:
        order = np.argsort(r.angles)
        a, d = r.angles[order], r.deviations[order]
        if result.arc_deg >= 359.0:  # close the loop of a full circle
            a, d = np.r_[a, a[:1] + 2 * np.pi], np.r_[d, d[:1]]
        ax.plot((base + k * d) * np.cos(a), (base + k * d) * np.sin(a), color=colours[r.direction],
                lw=1.4, label=r.direction.upper())
    polar_frame(ax, result.squareness.axes, (-1.75, 1.75), (-2.25, 1.6),
                f"(radial scale: {ring * 1e6:.3g} µm per dotted ring)")
    ax.legend(loc="upper right")
    ax.text(-1.7, -2.2, _ballbar_text(result), fontsize=9, family="monospace", va="bottom",
            bbox=dict(boxstyle="round", fc="white", ec="0.7"))
    ax.set_title(f"{title}, R = {result.radius * 1e3:g} mm, {result.arc_deg:.0f}°")
    fig.tight_layout()
    return fig


def save_ballbar_plot(runs, result, path, title: str = "Ballbar test") -> Path:
    """Write :func:`ballbar_figure` to ``path``."""
    return save_figure(ballbar_figure(runs, result, title), path, dpi=110, tight=False)


def straightness_figure(data, result):
    """Readings, reference line and the band of a straightness measurement."""
    plt = pyplot()
    fig, ax = plt.subplots(figsize=(9, 4.8))
    x, y = data.positions * 1e3, data.deviations * 1e6
    line = result.line
    ax.plot(x, y, "o-", color="tab:red", ms=3, lw=1, label="readings")
    fit = line(data.positions) * 1e6
    ax.plot(x, fit, "--", color="tab:blue", label=f"{line.method.replace('_', ' ')} line")
    lo, hi = result.residuals.min() * 1e6, result.residuals.max() * 1e6
    ax.fill_between(x, fit + lo, fit + hi, color="tab:blue", alpha=0.08,
                    label=f"band {fmt(result.deviation * 1e6, 'µm')} µm")
    ax.set_xlabel(f"position along {data.axis or 'the axis'} [mm]")
    ax.set_ylabel(f"deviation along {data.direction or 'the normal'} [µm]")
    ax.set_title(f"Straightness {fmt(result.deviation * 1e6, 'µm')} µm, slope "
                 f"{fmt(line.slope * 1e6, 'µm/m', True)} µm/m ({result.n} readings)")
    ax.grid(alpha=0.3)
    ax.legend()
    fig.tight_layout()
    return fig


def biaxial_figure(one, two, r, title: str = "Bi-axial squareness"):
    """The two trajectories of a bi-axial test, each with its reference line, and the
    squareness in the title (ISO 230-1 §3.6.7)."""
    plt = pyplot()
    fig, axes = plt.subplots(1, 2, figsize=(11, 4.4))
    for ax, data, res in ((axes[0], one, r.first), (axes[1], two, r.second)):
        x, y = data.positions * 1e3, data.deviations * 1e6
        ax.plot(x, y, "o-", color="tab:red", ms=3, lw=1, label="readings")
        ax.plot(x, res.line(data.positions) * 1e6, "--", color="tab:blue",
                label=f"{res.line.method.replace('_', ' ')} line, slope "
                      f"{fmt(res.line.slope * 1e6, 'µm/m', True)} µm/m")
        ax.set_xlabel(f"position along {data.axis or 'the axis'} [mm]")
        ax.set_ylabel(f"deviation along {data.direction or 'the normal'} [µm]")
        ax.grid(alpha=0.3)
        ax.legend(fontsize=8)
    sq = r.squareness
    fig.suptitle(f"{title}: squareness {_sq(sq)}, "
                 f"{sq.angle_note}", fontsize=10.5)
    fig.tight_layout()
    return fig


def write_biaxial_report(path, one, two, b, sources: str, config: str = "L",
                         orientation: int = 0) -> Path:
    """The report of a bi-axial squareness (:func:`axiscal.standards.squareness_biaxial.
    evaluate_biaxial`'s ``b``), as ``axiscal squareness biaxial --report`` and the workbench
    write it: both trajectories with their reference lines, then every figure of its JSON.
    ``sources`` names the two trajectories (files, or stored tests with their machine)."""
    from axiscal.report.html import write_result_report

    title = f"Bi-axial {config.upper()} {orientation}°"
    return write_result_report(
        path, f"Squareness, bi-axial {config.upper()} {orientation}° — {sources}", b.summary,
        figure=biaxial_figure(one, two, b.result, title),
        method="Squareness from the slopes of the reference straight lines of two "
               "trajectories, ISO 230-1:2012 §3.6.7 (Chapman, Calibration of machine "
               "squareness, Methods 1-3), with the reference square's angle error corrected "
               "for its orientation; U by ISO/TR 230-9.")


def diagonal_figure(d, r, title: str = "Diagonal squareness"):
    """The length errors along the two diagonals of a multi-point diagonal test (ISO 230-6)."""
    plt = pyplot()
    fig, ax = plt.subplots(figsize=(9, 4.4))
    ax.plot(d.positions_d1 * 1e3, d.errors_d1 * 1e6, "o-", color="tab:red", ms=3,
            label="D1 (along -X +Y, from corner +X -Y)")
    ax.plot(d.positions_d2 * 1e3, d.errors_d2 * 1e6, "s-", color="tab:blue", ms=3,
            label="D2 (along +X +Y, from corner -X -Y)")
    ax.set_xlabel("position along the diagonal [mm]")
    ax.set_ylabel("length error [µm]")
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8)
    sq = r.squareness
    ax.set_title(f"{title}: squareness {_sq(sq)}")
    fig.tight_layout()
    return fig


def save_straightness_plot(data, result, path) -> Path:
    """Write :func:`straightness_figure` to ``path``."""
    return save_figure(straightness_figure(data, result), path, dpi=110, tight=False)


# --- helpers -------------------------------------------------------------------------------------

def _kind(method: str) -> str:
    return method.split()[0] if method[0] in "TL" else method


def _warp(machine, x, y, mag):
    dx, dy = machine.deviation(x, y)
    return (x + mag * dx) * 1e3, (y + mag * dy) * 1e3


def _draw_plane(ax, machine, mag) -> None:
    (x0, x1), (y0, y1) = machine.x_range, machine.y_range
    # grid of (nearly) 100 mm squares that always includes the edges of the plane
    xs = np.linspace(x0, x1, max(2, round(machine.length_x / 0.1)) + 1)
    ys = np.linspace(y0, y1, max(2, round(machine.length_y / 0.1)) + 1)
    fine_x, fine_y = np.linspace(x0, x1, 81), np.linspace(y0, y1, 81)
    for xv in xs:
        ax.plot([xv * 1e3] * 2, [y0 * 1e3, y1 * 1e3], color="0.88", lw=0.7)
        ax.plot(*_warp(machine, np.full_like(fine_y, xv), fine_y, mag), color="tab:blue", lw=0.8)
    for yv in ys:
        ax.plot([x0 * 1e3, x1 * 1e3], [yv * 1e3] * 2, color="0.88", lw=0.7)
        ax.plot(*_warp(machine, fine_x, np.full_like(fine_x, yv), mag), color="tab:blue", lw=0.8)
    pad = 0.09 * max(machine.length_x, machine.length_y) * 1e3
    ax.set_xlim(x0 * 1e3 - pad, x1 * 1e3 + pad)
    ax.set_ylim(y0 * 1e3 - pad, y1 * 1e3 + pad)
    ax.set_aspect("equal")
    ax.set_xlabel(f"X [mm] (distortion × {mag:g})", fontsize=9)
    ax.set_ylabel("Y [mm]", fontsize=9)
    ax.tick_params(labelsize=8)


def _draw_test(ax, machine, r, mag, first: bool) -> None:
    from axiscal.procedures.squareness import BiaxialTest, biaxial_lines

    (xc, yc), (sx, sy) = r.centre, r.size
    red = dict(color="tab:red", lw=1.6)
    if r.method == "ballbar":
        overlapping = "overlapping" in r.group
        _draw_ballbar_trace(ax, machine, r, dict(color="tab:orange", lw=1.0, ls="--")
                            if overlapping else red)
        if overlapping:  # the second row's results below the first row's
            r = replace(r, label_at=(r.centre[0], r.centre[1] - 0.55 * r.size[0] / 2))
    elif r.method == "diagonal":
        for (xa, ya), (xb, yb) in (((xc - sx / 2, yc - sy / 2), (xc + sx / 2, yc + sy / 2)),
                                   ((xc + sx / 2, yc - sy / 2), (xc - sx / 2, yc + sy / 2))):
            s = np.linspace(0, 1, 41)
            ax.plot(*_warp(machine, xa + s * (xb - xa), ya + s * (yb - ya), mag), **red)
    elif first:  # only one path of the four orientations, as in the paper's figures
        cfg, orient = (r.method.split() + ["0"])[:2]
        y_line, x_line = biaxial_lines(BiaxialTest(cfg, int(orient), r.centre, r.size))
        xs = np.linspace(xc - sx / 2, xc + sx / 2, 41)
        ys = np.linspace(yc - sy / 2, yc + sy / 2, 41)
        ax.plot(*_warp(machine, xs, np.full_like(xs, y_line), mag), **red)
        ax.plot(*_warp(machine, np.full_like(ys, x_line), ys, mag), **red)
    lx, ly = r.label_at
    # pull the box a little towards the test's centre so it stays inside the plane
    bx = lx + 0.18 * (xc - lx) if r.method[0] in "TL" else lx
    by = ly + 0.18 * (yc - ly) if r.method[0] in "TL" else ly
    ax.text(bx * 1e3, by * 1e3, fmt(r.squareness.um_per_m, "µm/m"), ha="center", va="center",
            fontsize=8, bbox=dict(boxstyle="square,pad=0.2", fc="white", ec="0.3", lw=0.6))


def _draw_ballbar_trace(ax, machine, r, style) -> None:
    """The mean CCW/CW ballbar trace, auto-scaled to ±12 % of the radius (Chapman, Calibration of machine squareness Figure 13)."""
    from axiscal.procedures.squareness import BallbarTest, measure_ballbar

    rad = r.size[0] / 2
    test = BallbarTest(r.centre, rad, n_points=180)
    ccw, cw = measure_ballbar(machine, test)
    d = 0.5 * (ccw.deviations + cw.deviations)
    d = d - d.mean()
    scale = 0.12 * rad / max(float(np.max(np.abs(d))), 1e-12)
    a = np.r_[ccw.angles, ccw.angles[:1]]
    rr = rad + scale * np.r_[d, d[:1]]
    ax.plot((r.centre[0] + rr * np.cos(a)) * 1e3, (r.centre[1] + rr * np.sin(a)) * 1e3, **style)


def _summary_panel(ax, machine, comparison, mag) -> None:
    ax.axis("off")
    lines = [str(machine).replace(", ", "\n"), "",
             f"truth θ0 = {fmt(comparison.truth, 'µm/m', True)} µm/m",
             f"plane distortion × {mag:g}",
             "red: test path (one orientation of T / L shown;", "     ballbar trace auto-scaled;",
             "     orange dashed: overlapping ballbar row)",
             "", "averages (µm/m):"]
    groups: dict = {}
    for name, centre, v in comparison.averages:
        groups.setdefault(centre, []).append((name, v))
    for centre, items in groups.items():
        if comparison.scope == "local":
            lines.append(f" at ({centre[0] * 1e3:+.0f}, {centre[1] * 1e3:+.0f}) mm:")
        pairs = [f"{n.replace(' + ', '+')} {fmt(v, 'µm/m', True)}" for n, v in items]
        for i in range(0, len(pairs), 2):
            lines.append("   " + "   ".join(pairs[i:i + 2]))
    ax.text(0.0, 1.0, "\n".join(lines), va="top", family="monospace", fontsize=8,
            transform=ax.transAxes)


def _ballbar_text(result) -> str:
    f = (lambda v: "—" if v is None else f"{fmt(v * 1e6, 'µm', True)} µm")
    s = result.squareness
    return "\n".join([
        f"squareness  {_sq(s)}",
        f"            {s.angle_note}",
        f"scale mismatch {fmt(result.scale_mismatch * 1e6, 'µm/m', True)} µm/m",
        f"backlash {s.axes[0]} {f(result.backlash_x)}, {s.axes[1]} {f(result.backlash_y)}",
        f"G ccw {f(result.G_ccw)}  G cw {f(result.G_cw)}  H {f(result.H)}",
    ])


def _sq(sq) -> str:
    """A squareness as the plots' titles and boxes show it, with the tables' decimals."""
    return f"{fmt(sq.um_per_m, 'µm/m', True)} µm/m ({fmt(sq.arcsec, 'arcsec', True)}″)"
