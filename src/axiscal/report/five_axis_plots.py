"""Figure of the identified location errors of a table-table five-axis machine.

:func:`location_figure`: the two rotary axes' average lines in 3-D, nominal (dashed) and as
identified (solid, the location errors magnified so that they can be seen), beside the
identified values with their expanded uncertainty (bars: µm for positions, µrad for orientations
and the zero sum). Location errors that were not identified are drawn as zero and said in the
title.
"""

from __future__ import annotations

import numpy as np

from axiscal.physics.rotary_location import Geometry
from axiscal.report._figures import pyplot as _pyplot

__all__ = ["location_figure", "location_report", "ballbar_path_figure"]


def location_figure(geometry: Geometry, result, magnification: float | None = None,
                    reach: float = 0.15):
    """3-D axis lines (magnified) and the identified values with U; a matplotlib Figure.

    Parameters
    ----------
    geometry : Geometry
    result : LocationIdentification
    magnification : float, optional
        Scale of the location errors in the 3-D view (default: the largest displacement at the
        lines' ends becomes a tenth of ``reach``).
    reach : float, m
        Half length of the lines drawn.
    """
    plt = _pyplot()
    errors = {}
    for e in result.errors:
        errors[e.name.split("+")[0]] = e.value
    s = np.linspace(-reach, reach, 2)
    nominal = geometry.lines({})
    actual = geometry.lines(errors)
    largest = max(float(np.abs(_ends(a, s) - _ends(n, s)).max()) for a, n in zip(actual, nominal))
    mag = magnification or (0.1 * reach / largest if largest > 0 else 1.0)
    fig = plt.figure(figsize=(11, 4.8))
    ax = fig.add_subplot(1, 2, 1, projection="3d")
    names = (geometry.tilt, "C")
    for (n, a, name, colour) in zip(nominal, actual, names, ("tab:blue", "tab:red")):
        pn = _ends(n, s) * 1e3
        pa = (_ends(n, s) + mag * (_ends(a, s) - _ends(n, s))) * 1e3
        ax.plot(*pn.T, color="0.4", ls="--", lw=0.8)
        ax.plot(*pa.T, color=colour, lw=1.6, label=f"{name} axis (errors × {mag:.3g})")
    centre = np.mean([n[0] for n in nominal], axis=0) * 1e3
    for setter, c in zip((ax.set_xlim, ax.set_ylim, ax.set_zlim), centre):
        setter(c - reach * 1e3, c + reach * 1e3)
    ax.set_box_aspect((1, 1, 1))
    ax.set_xlabel("X [mm]")
    ax.set_ylabel("Y [mm]")
    ax.set_zlabel("Z [mm]")
    ax.legend(loc="upper left", fontsize=8)
    unseen = ", ".join(u.name for u in result.unidentified)
    ax.set_title(f"{geometry.tilt}/C axis lines, nominal dashed" + (f"\n(not identified, drawn 0: "
                 f"{unseen})" if unseen else ""), fontsize=9)
    bx = fig.add_subplot(1, 2, 2)
    labels = [f"{e.name} [{e.unit}]" for e in result.errors]
    y = np.arange(len(labels))
    bx.barh(y, [e.value_display for e in result.errors],
            xerr=[e.U_display for e in result.errors], color=["tab:blue" if e.unit == "µm"
                                                              else "tab:orange"
                                                              for e in result.errors],
            capsize=3)
    bx.set_yticks(y, labels, fontsize=8)
    bx.invert_yaxis()
    bx.axvline(0.0, color="0.3", lw=0.6)
    bx.set_xlabel("identified value, bars U (k = 2)")
    bx.set_title(f"residual {result.residual_rms * 1e6:.2f} µm rms", fontsize=9)
    fig.tight_layout()
    return fig


def _ends(line, s):
    q, u, _ = line
    return q + np.outer(s, u)


def location_report(geometry: Geometry, result, *, name: str, truth: dict | None = None,
                    files=()):
    """The HTML report (:class:`~axiscal.report.html.Report`) of an identification: the values
    with U and their budget, the unseen with the test that would see them, the convention, the
    correlations, the residual and the figure. ``truth`` (name -> µm or µrad, a simulation's) is
    shown only in a section headed as the simulation's truth."""
    from axiscal.report.html import Report

    kind = "spindle head" if geometry.head else "table-table"
    plan = result.plan
    rep = Report(f"Five-axis location errors — {name}",
                 f"{geometry.tilt}/C {kind}: ISO 230-1:2012 / ISO 230-7:2015 location errors by "
                 "least squares, U after JCGM 100",
                 {"files": ", ".join(str(f) for f in files), "poses": plan.poses,
                  "sensitivity rank": f"{plan.rank} of {plan.columns}",
                  "condition": f"{plan.condition:.3g}"})
    rep.add_heading("Location errors")
    inputs = sorted({k for e in result.errors for k in e.components})
    rep.add_table(["error", "value", "U (k = 2)", "unit"] + [f"u: {k}" for k in inputs],
                  [[e.name, e.value_display, e.U_display, e.unit]
                   + [e.components.get(k, 0.0) * 1e6 for k in inputs] for e in result.errors],
                  digits=2, formulas=(0,))
    rep.add_warnings([str(u) for u in result.unidentified])
    rep.add_text(f"Convention: {plan.convention}.")
    rep.add_figure(location_figure(geometry, result), "The rotary axes' lines, nominal (dashed) "
                   "and identified (magnified), and the values with U.")
    rep.add_heading("Correlations")
    names = [e.name for e in result.errors]
    rep.add_table([""] + names, [[n] + list(row) for n, row in zip(names, result.correlation)],
                  digits=2, formulas=(0,))
    rep.add_heading("Residual")
    rep.add_text(f"{result.residual_rms * 1e6:.2f} µm rms, largest {result.residual_max * 1e6:.2f}"
                 f" µm, χ²/ν = {result.chi2_per_dof:.2f} (ν = {result.dof}); "
                 f"{result.unmodelled}.")
    if truth is not None:
        rep.add_truth("Simulation: the twin's truth")
        rep.add_table(["error", "identified", "true", "identified − true", "unit"],
                      [[e.name, e.value_display, truth[e.name], e.value_display - truth[e.name],
                        e.unit] for e in result.errors], digits=2, formulas=(0,))
    return rep


def ballbar_path_figure(record, result):
    """A five-axis ballbar set-up's readings along its path (µm against the swept angles, the
    path's points in order), with the largest and smallest reading and the range with U
    (:class:`~axiscal.standards.iso10791_6.BallbarRange`): the figure of a stored
    ``fiveaxis-ballbar`` test (history, workbench, report)."""
    plt = _pyplot()
    fig, ax = plt.subplots(figsize=(7.0, 3.6))
    swept = record.c_angle if record.swept in ("C", "both", "") else record.tilt_angle
    x = np.degrees(np.asarray(swept, float))
    if np.ptp(x) == 0:
        x = np.arange(1, len(record.deviation) + 1, dtype=float)
        ax.set_xlabel("point along the path")
    else:
        ax.set_xlabel(f"{'C' if record.swept in ('C', 'both', '') else record.tilt} (deg, "
                      "LinuxCNC sign)")
    d = np.asarray(record.deviation, float) * 1e6
    ax.plot(x, d, ".-", lw=1.0, ms=3, label="reading − nominal length")
    for v, what in ((result.maximum, "largest"), (result.minimum, "smallest")):
        ax.axhline(v * 1e6, ls="--", lw=0.8, color="0.4")
        ax.annotate(what, (x[0], v * 1e6), fontsize=7, va="bottom", color="0.3")
    ax.set_ylabel("deviation (µm)")
    ax.set_title(f"{result.label}: range {result.range * 1e6:.2f} µm, U = "
                 f"{result.U * 1e6:.2f} µm (k = {result.budget.k:g})", fontsize=9)
    ax.grid(True, lw=0.3)
    fig.tight_layout()
    return fig
