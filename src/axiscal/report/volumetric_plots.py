"""Plots and the HTML report of a volumetric error map.

* :func:`volumetric_figure` — the working volume's grid distorted by the error field, magnified,
  in 3-D, beside three slices of |E| through the reference point;
* :func:`diagonals_figure` — the four body diagonals' displacement errors (ISO 230-6:2002);
* :func:`volumetric_report` — both, the figures and the tables in one self-contained HTML page.
"""

from __future__ import annotations

import numpy as np

from axiscal.report._figures import pyplot as _pyplot
from axiscal.standards.volumetric import AXES

__all__ = ["volumetric_figure", "diagonals_figure", "volumetric_report"]


def volumetric_figure(vmap, title: str = "", magnification: float | None = None):
    """3-D distorted grid (magnified) and three |E| slices, µm; returns a matplotlib Figure."""
    plt = _pyplot()

    gx, gy, gz = (g * 1e3 for g in vmap.grid)
    e = vmap.error * 1e3                                # mm
    span = max(np.ptp(gx), np.ptp(gy), np.ptp(gz))
    largest = max(float(np.abs(e).max()), 1e-12)
    mag = magnification or _nice(0.1 * span / largest)
    fig = plt.figure(figsize=(11, 8.2))
    ax = fig.add_subplot(2, 2, 1, projection="3d")
    X, Y, Z = np.meshgrid(gx, gy, gz, indexing="ij")
    nominal = (X, Y, Z)
    actual = tuple(n + mag * e[i] for i, n in enumerate(nominal))
    # the nominal grid dashed and darker than the panes' own grid, which hid a light grey one
    for pts, style in ((nominal, dict(color="0.35", lw=0.7, ls="--")),
                       (actual, dict(color="tab:red", lw=0.9))):
        for i in (0, -1):
            for j in (0, -1):
                ax.plot(pts[0][:, i, j], pts[1][:, i, j], pts[2][:, i, j], **style)
                ax.plot(pts[0][i, :, j], pts[1][i, :, j], pts[2][i, :, j], **style)
                ax.plot(pts[0][i, j, :], pts[1][i, j, :], pts[2][i, j, :], **style)
        mid = pts[0].shape[2] // 2
        for i in range(0, pts[0].shape[0], max(1, pts[0].shape[0] // 5)):
            ax.plot(pts[0][i, :, mid], pts[1][i, :, mid], pts[2][i, :, mid], **style)
        for j in range(0, pts[0].shape[1], max(1, pts[0].shape[1] // 5)):
            ax.plot(pts[0][:, j, mid], pts[1][:, j, mid], pts[2][:, j, mid], **style)
    ax.set_xlabel("X [mm]")
    ax.set_ylabel("Y [mm]")
    ax.set_zlabel("Z [mm]")
    ax.set_title(f"grid distorted by the error field, ×{mag:g}\n(grey dashed nominal, red actual)",
                 fontsize=9)
    mags = vmap.magnitude * 1e6
    ix, iy, iz = (int(np.argmin(np.abs(g - c)))
                  for g, c in zip(vmap.grid, _middle(vmap)))
    vmax = float(mags.max())
    slices = ((mags[:, :, iz].T, gx, gy, "X", "Y", f"Z = {gz[iz]:.0f} mm"),
              (mags[:, iy, :].T, gx, gz, "X", "Z", f"Y = {gy[iy]:.0f} mm"),
              (mags[ix, :, :].T, gy, gz, "Y", "Z", f"X = {gx[ix]:.0f} mm"))
    for k, (img, h, v, hl, vl, where) in enumerate(slices, start=2):
        a = fig.add_subplot(2, 2, k)
        im = a.pcolormesh(h, v, img, shading="gouraud", vmin=0, vmax=vmax, cmap="viridis",
                          rasterized=True)   # as vectors: 2 MB of SVG, minutes in WeasyPrint
        a.set_xlabel(f"{hl} [mm]")
        a.set_ylabel(f"{vl} [mm]")
        a.set_title(f"|E| [µm] at {where}", fontsize=9)
        a.set_aspect("equal")
        fig.colorbar(im, ax=a, shrink=0.85)
    fig.suptitle(title or "Volumetric error map (rigid-body model, ISO/TR 16907)", fontsize=11)
    fig.tight_layout()
    return fig


def diagonals_figure(predicted, measured=None, title: str = ""):
    """Displacement error along the four body diagonals, µm: predicted, and measured if given."""
    plt = _pyplot()

    fig, ax = plt.subplots(figsize=(8, 4.2))
    colors = ("tab:blue", "tab:orange", "tab:green", "tab:red")
    for k, (d, c) in enumerate(zip(predicted, colors)):
        ax.plot(d.distance * 1e3, d.deviation * 1e6, color=c, lw=1.5,
                label=f"{d.name} predicted (range {d.range * 1e6:.2f} µm)")
        if measured is not None:
            m = measured[k]
            ax.plot(m.distance * 1e3, m.deviation * 1e6, "o", color=c, ms=3.5,
                    label=f"{m.name} measured (range {m.range * 1e6:.2f} µm)")
    ax.set_xlabel("distance along the diagonal [mm]")
    ax.set_ylabel("displacement error [µm]")
    ax.grid(alpha=0.3)
    ax.legend(fontsize=7, ncol=2)
    ax.set_title(title or "Body diagonal displacement (ISO 230-6:2002)", fontsize=10)
    fig.tight_layout()
    return fig


def volumetric_report(vmap, diagonals, errors, *, name: str, measured=None, truth=None,
                      tables=None, budget=None):
    """The HTML report (:class:`~axiscal.report.html.Report`) of a volumetric map.

    ``truth`` (a map of a simulated machine's true error) is shown only for a simulation, in a
    section headed as such. ``budget``: the record's uncertainty budget
    (:func:`~axiscal.standards.iso230_9_volumetric.volumetric_budget`): each figure's U (k)
    beside it, the budget's inputs and notes.
    """
    from axiscal.report.html import Report

    s = vmap.summary()
    rep = Report(f"Volumetric accuracy — {name}",
                 "Rigid-body model of the 21 geometric errors (ISO 230-1:2012 notation; "
                 "ISO/TR 16907:2015)",
                 {"kinematic chain": str(errors.chain),
                  "reference point [mm]": ", ".join(f"{v * 1e3:g}" for v in errors.reference),
                  "tool offset [mm]": ", ".join(f"{v * 1e3:g}" for v in vmap.tool_offset),
                  "grid points": s["grid_points"]})
    def U(key: str) -> list:
        return [] if budget is None else [budget.U_text(key)]

    u_head = [] if budget is None else [f"U (k = {budget.k:g}) [µm]"]
    rep.add_heading("Volumetric accuracy")
    rep.add_table(["figure", "value [µm]"] + u_head + ["where [mm]"],
                  [["largest |E|", s["largest_um"], *U("largest"),
                    ", ".join(f"{v:.0f}" for v in s["largest_at_mm"])]]
                  + [[f"range of E{a.lower()}", s["range_um"][a], *U(f"range_{a}"), ""]
                     for a in AXES], digits=2)
    rep.add_figure(volumetric_figure(vmap), "Error field: the grid magnified, and |E| slices "
                   "through the reference point.")
    rep.add_heading("Body diagonals (ISO 230-6:2002)")
    rep.add_table(["diagonal", "predicted range [µm]"] + u_head
                  + (["measured range [µm]"] if measured else []),
                  [[d.name, d.range * 1e6, *U(f"diagonal_{d.name}")]
                   + ([m.range * 1e6] if measured else [])
                   for d, m in zip(diagonals, measured or diagonals)], digits=2)
    rep.add_figure(diagonals_figure(diagonals, measured))
    rep.add_heading("Inputs")
    rep.add_table(["squareness", "µm/m"], [[k.upper(), v * 1e6] for k, v in
                                          errors.squareness.items()], digits=2)
    if errors.missing:
        rep.add_warnings([f"not measured, taken as zero: {', '.join(errors.missing)}"])
    if budget is not None:
        rep.add_table(["input", "value", "", "rule or source"],
                      [[i.label, i.value_text, "assumed" if i.assumed else "given", i.rule]
                       for i in budget.inputs], caption=f"Uncertainty budget: {budget.method}")
        for note in budget.notes:
            rep.add_text(note)
    if tables is not None:
        rep.add_heading("Compensation")
        rep.add_text(str(tables))
    if truth is not None:
        rep.add_truth("Simulation: the simulated machine's truth")
        diff = np.abs(vmap.error - truth.error).max() * 1e6
        rep.add_text(f"Largest true |E| {truth.largest * 1e6:.2f} µm; largest |mapped − true| "
                     f"{diff:.3f} µm over the grid.")
    return rep


def _middle(vmap):
    return tuple((g[0] + g[-1]) / 2 for g in vmap.grid)


def _nice(target: float) -> float:
    """The largest 1, 2 or 5 × 10^k not above ``target``."""
    k = 10 ** np.floor(np.log10(target))
    return float(max(m * k for m in (1, 2, 5) if m * k <= target))
