"""HTML report of a five-DOF motion-error measurement (built with :class:`axiscal.report.html.Report`).

Sections, each present when its data is given: resolutions from the parts, the five errors against
angle (with the truth of a simulation), the ISO 230-7 values and polar plots, the stability traces
and their standard deviations, the repeatability, and the crosstalk of the mounting errors.
"""

from __future__ import annotations

import math

import numpy as np

from axiscal.procedures.motion_errors import SYMBOLS
from axiscal.report.html import Report
from axiscal.units import ARCSEC, UM

__all__ = ["motion_report", "iso230_7_rows", "STABILITY_SEED"]

#: Optics Express 2018, Five-DOF motion errors of a rotary axis §3.2 standard deviations of the 60 min stability experiment (arcsec, µm).
STABILITY_SEED = {"ez": 0.05, "ey": 0.06, "ex": 0.19, "dy": 0.04, "dz": 0.03}
#: Optics Express 2018, Five-DOF motion errors of a rotary axis §3.3 repeatability deviations (±, arcsec and µm).
REPEATABILITY_SEED = {"ez": 3.4, "ey": 4.6, "ex": 3.2, "dy": 2.6, "dz": 2.3}
_SYMBOL = SYMBOLS
_NAMES = {"ez": "εz angular positioning", "ey": "εy tilt about Y", "ex": "εx tilt about X",
          "dy": "δy radial", "dz": "δz axial"}


#: The five errors' caption when a simulation's truth is drawn (a measured file has none).
_TRUTH_CAPTION = ("Measured errors per run (zeroed at 0°); dashed: the simulation's truth of run "
                  "1 at the sensitive unit. Where the two differ by a once-per-turn wave (a "
                  "tilted or eccentric reference axis shows in εy, εx and δy), the gap is the "
                  "mounting's crosstalk, quantified in the crosstalk table when it is given; "
                  "ISO 230-7 removes it as the fundamental.")


def _unit(ch):
    return (ARCSEC, "arcsec") if ch[0] == "e" else (UM, "µm")


def iso230_7_rows(result) -> list[list]:
    """Rows (name, total, synchronous, asynchronous, fundamental, unit) of an ISO 230-7 result."""
    rows = []
    for m in result.motions:
        k, u = (UM, "µm") if m.kind == "length" else (ARCSEC, "arcsec")
        rows.append([m.name, m.total / k, m.synchronous / k,
                     None if math.isnan(m.asynchronous) else m.asynchronous / k,
                     m.fundamental / k, "removed" if m.fundamental_removed else "kept", u])
    return rows


def motion_report(title: str, *, metadata=None, result=None, runs=None, truth=None,
                  stability=None, repeatability=None, crosstalk=None, resolutions=None,
                  notes=()) -> Report:
    """Build the report; every keyword is optional.

    Parameters
    ----------
    title : str
    metadata : dict, optional
    result : Iso230_7Result, optional
    runs : sequence of FiveErrors, optional
        Measured errors per run (plotted against angle).
    truth : sequence of FiveErrors, optional
        The simulation's truth for the same runs.
    stability : MotionRun, optional
    repeatability : dict of str to float, optional
        ± deviation per channel (SI).
    crosstalk : Crosstalk, optional
    resolutions : Resolutions, optional
    notes : sequence of str
    """
    from axiscal.report import motion_plots as mp

    rep = Report(title, subtitle="Five motion errors of a rotary axis measured at once "
                 "(Method for simultaneous measurement of five DOF motion errors of a rotary axis "
                 "using a single-mode fiber-coupled laser, Optics Express 2018); "
                 "error motion by ISO 230-7", metadata=metadata or {})
    for n in notes:
        rep.add_text(n)
    if truth:
        rep.add_truth()
    if runs:
        rep.add_heading("Five errors against angle")
        rep.add_figure(mp.five_errors_figure(runs, truth[:1] if truth else None),
                       _TRUTH_CAPTION if truth else "Measured errors per run (zeroed at 0°).")
    if resolutions is not None:
        _resolution_section(rep, resolutions)
    if result is not None:
        _iso_section(rep, result)
    if repeatability:
        rep.add_heading("Repeatability")
        rep.add_table(["Error", "± deviation", "Optics Express 2018 §3.3", "unit"],
                      [[_NAMES[c], v / _unit(c)[0], REPEATABILITY_SEED[c], _unit(c)[1]]
                       for c, v in repeatability.items()], digits=2,
                      caption="Largest half-range across the runs at one angle.")
    if stability is not None:
        _stability_section(rep, stability)
    if crosstalk is not None:
        _crosstalk_section(rep, crosstalk)
    return rep


def _resolution_section(rep: Report, resolutions) -> None:
    """The resolution each error has from the parts, with the decimals of its unit."""
    from axiscal.report.labels import fmt

    rep.add_heading("Resolution from the parts")
    rep.add_text("r_PSD/(2 f_1), r_QD/(2h) and r_QD/2 (Optics Express 2018, five-DOF rotary axis, "
                 "eqs. 1-6, §3).")
    rep.add_key_values({"εz, εy [arcsec]": fmt(resolutions.angular / ARCSEC, "arcsec"),
                        "εx [arcsec]": fmt(resolutions.tilt_x / ARCSEC, "arcsec"),
                        "δy, δz [µm]": fmt(resolutions.displacement / UM, "µm")})


def _iso_section(rep, result):
    rep.add_heading("ISO 230-7 error motion (fixed sensitive direction)")
    rep.add_table(["Error motion", "Total", "Synchronous", "Asynchronous", "Once-per-turn amplitude",
                   "Once-per-turn", "Unit"], iso230_7_rows(result), digits=3)
    loc = result.location
    rep.add_key_values({
        "x0 offset [µm]": None if math.isnan(loc.x0) else loc.x0 / UM, "y0 offset [µm]": loc.y0 / UM,
        "a0 tilt about X [arcsec]": loc.a0 / ARCSEC, "b0 tilt about Y [arcsec]": loc.b0 / ARCSEC,
        "εz range [arcsec]": result.positioning.range / ARCSEC,
        "εz ± repeatability [arcsec]": (None if math.isnan(result.positioning.repeatability)
                                        else result.positioning.repeatability / ARCSEC),
    }, caption="Location of the axis average line (relative to the zero at the first angle) and "
               "angular positioning", digits=3)
    rep.add_warnings(result.warnings)
    from axiscal.report.motion_plots import polar_figure

    rep.add_figure(polar_figure(result), "Runs (grey) and synchronous error motion (blue) about the "
                   "PC centre; fundamental removed for radial and tilt.")


def _stability_section(rep, run):
    from axiscal.report.motion_plots import stability_figure

    rep.add_heading("Stability")
    minutes = (run.time[-1] - run.time[0]) / 60
    rows = []
    for ch in _NAMES:
        k, u = _unit(ch)
        rows.append([_NAMES[ch], float(np.std(getattr(run.measured, ch))) / k,
                     float(np.std(getattr(run.uncompensated, ch))) / k, STABILITY_SEED[ch], u])
    rep.add_table(["Error", "σ compensated", "σ without compensation", "Optics Express 2018 §3.2", "unit"], rows,
                  caption=f"{run.time.size} readings over {minutes:.0f} min.", digits=3)
    rep.add_figure(stability_figure(run), "The still set-up, with and without the common-path drift "
                   "compensation (Optics Express 2018, eqs. 7-9).")


def _crosstalk_section(rep, ct):
    from axiscal.procedures.motion_errors import INPUTS

    rep.add_heading("Crosstalk of the mounting errors")
    rows = [[_NAMES[out], *row] for out, row in zip(_NAMES, ct.table())]
    rep.add_table(["measured ↓ / true →", *(_SYMBOL[c] for c in INPUTS)], rows, digits=4,
                  caption="Largest leak over a turn per unit of true error (arcsec or µm per arcsec "
                          "or µm); 0 for a perfect set-up.")
    rep.add_table(["Error", "spurious p-v on a perfect axis", "after removing once-per-turn", "unit"],
                  [[_NAMES[c], ct.spurious[c] / _unit(c)[0], ct.residual[c] / _unit(c)[0], _unit(c)[1]]
                   for c in _NAMES], digits=3)
