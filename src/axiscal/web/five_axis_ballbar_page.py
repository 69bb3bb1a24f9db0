"""What a test's page shows of a five-axis ballbar test (a rotary axis, or both, moving with the
linear axes; ISO 10791-6:2014 as :mod:`axiscal.standards.iso10791_6` reads it; issue 43), in the
generic kind template (``kind.html``).

The view lays out the history's one evaluation of the stored file
(:func:`axiscal.store.kinds.evaluate_file`, kind ``fiveaxis-ballbar``: the range with U of
``axiscal fiveaxis ballbar evaluate``): the readings along the path
(:func:`axiscal.report.five_axis_plots.ballbar_path_figure`), the figures of the set-up and the
range's uncertainty budget. Nothing is computed here.
"""

from __future__ import annotations

__all__ = ["five_axis_ballbar_view"]


def five_axis_ballbar_view(ev, figure, fmt) -> dict:
    """The page's view (keys of :func:`axiscal.web.kind_pages.kind_view`); ``figure`` and
    ``fmt`` are that module's figure-to-image and number writers, passed in (so this module
    does not import its caller)."""
    from axiscal.report.five_axis_plots import ballbar_path_figure

    rec, r, d = ev.dataset, ev.evaluation, ev.result
    figures = [("range", fmt(d["range_um"]), fmt(d["U_um"]), "µm"),
               ("largest reading", fmt(d["max_um"]), "", "µm"),
               ("smallest reading", fmt(d["min_um"]), "", "µm"),
               ("scatter about the smooth fit (Type A)", fmt(d["scatter_um"]), "", "µm"),
               ("points", str(d["points"]), "", "")]
    b = d["budget"]
    contributors = [(c["name"], c["quantity"], c["basis"], fmt(c["u"]), "µm", c["clause"])
                    for c in b["contributors"]]
    setup = [("swept", d["swept"] or "—"), ("bar direction", d["direction"] or "—"),
             ("nominal length", f"{rec.length * 1e3:g} mm"),
             ("pivot (table frame)", ", ".join(f"{v * 1e3:.3f}" for v in rec.pivot) + " mm"),
             ("noise of one reading (stated)", f"{rec.noise * 1e6:g} µm")]
    return {"figure": figure(ballbar_path_figure, rec, r),
            "alt": "The ballbar's readings along the path, with the largest and smallest "
                   "and the range with U",
            "source": "Kinematic tests of ISO 10791-6:2014 as axiscal reads their public "
                      "descriptions (the standard's text was not at hand: its test codes, "
                      "dimensions and tolerances are not cited); U (k = 2) by JCGM 100:2008",
            "lead": f"{d['label']}: {'all five axes' if d['swept'] == 'both' else 'a rotary axis'}"
                    f" moving with the linear axes ({d['swept'] or 'swept axis not stated'}), "
                    f"{rec.tilt}/C table-table",
            "tables": [("The range", "ballbar-range", ["figure", "value", "U (k = 2)", "unit"],
                        figures),
                       ("Its uncertainty budget", "ballbar-budget",
                        ["contributor", "quantity", "basis", "u", "unit", "clause"],
                        contributors),
                       ("The set-up", "ballbar-setup", ["quantity", "value"], setup)],
            "statements": [], "warnings": []}
