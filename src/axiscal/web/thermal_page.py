"""What a test's page shows of an ISO 230-3:2020 thermal test (ETVE, spindle, linear axis,
rotary table; issue 44), in the generic kind template (``kind.html``).

The view lays out the history's one evaluation of the stored log
(:func:`axiscal.store.kinds.evaluate_file`, kind ``thermal``: the figures of
:func:`axiscal.standards.iso230_3.evaluate_thermal`, as ``axiscal thermal evaluate`` gives
them): the plot of ``thermal evaluate --plot`` (drifts and temperatures over time,
:func:`axiscal.report.thermal_plots.plot_thermal`) and every figure with its U (k = 2), unit and
clause, the numbers of ``thermal evaluate --json``. Nothing is computed here.
"""

from __future__ import annotations

__all__ = ["thermal_view"]


def thermal_view(ev, figure, fmt) -> dict:
    """The page's view (keys of :func:`axiscal.web.kind_pages.kind_view`); ``figure`` and
    ``fmt`` are that module's figure-to-image and number writers, passed in (so this module
    does not import its caller)."""
    from axiscal.report.thermal_plots import plot_thermal

    res, log = ev.result, ev.dataset
    rows = [(f["label"], f["name"], fmt(f["value"]), fmt(f["U"]), f["unit"], f["clause"])
            for f in res["figures"]]
    run = "—" if res["run_end_h"] is None else f"{res['run_end_h']:.3f}"
    lead = (f"{res['test']} test, {res['duration_h']:.3f} h, run ends at {run} h"
            + (f", axis {log.axis}" if log.axis else ""))
    return {"figure": figure(plot_thermal, log),
            "alt": "Drifts (µm, tilts in µrad) and temperatures (°C) over the test's hours, "
                   "the end of the run marked",
            "source": f"{res['clause']} (ISO 230-3:2020, Test code for machine tools — Part 3: "
                      "Determination of thermal effects); U (k = 2) from the sensors' reading "
                      "noise, their calibration not included",
            "lead": lead,
            "tables": [("Figures", "thermal-figures",
                        ["figure", "key", "value", "U (k = 2)", "unit", "clause"], rows),
                       ("Notes", "thermal-notes", ["note"], [(n,) for n in res["notes"]])],
            "statements": [], "warnings": []}
