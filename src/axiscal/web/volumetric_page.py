"""What a test's page shows of a volumetric test (the 21 geometric errors of a three-axis
machine, ISO 230-1:2012 notation, combined by the rigid-body model of ISO/TR 16907:2015; the
body diagonals of ISO 230-6:2002), in the generic kind template (``kind.html``).

The view lays out the history's one evaluation of the stored configuration
(:func:`axiscal.store.kinds.evaluate_file`, kind ``volumetric``: ``axiscal volumetric map``'s
run on its 11³ grid): the figure of ``volumetric map --plot`` (the grid magnified and the |E|
slices, :func:`axiscal.report.volumetric_plots.volumetric_figure`), the figures of its
``--json`` (largest |E| and where, each axis's range, each body diagonal's range), the
squareness it was given and the error motions not measured; beside each figure its U from the
record's budget (:mod:`axiscal.standards.iso230_9_volumetric`, the inputs stored with the
test), and the budget's inputs and notes. Nothing is computed here.
"""

from __future__ import annotations

__all__ = ["volumetric_view"]


def volumetric_view(ev, figure, fmt) -> dict:
    """The page's view (keys of :func:`axiscal.web.kind_pages.kind_view`); ``figure`` and
    ``fmt`` are that module's figure-to-image and number writers, passed in (so this module
    does not import its caller)."""
    from axiscal.report.evaluations import FIGURES
    from axiscal.report.labels import name

    d, run = ev.result, ev.dataset
    errors = run.parts["config"].errors
    budget = ev.budget

    def U(key: str) -> str:       # the record's U (iso230_9_volumetric), as the certificate's
        return "—" if budget is None else budget.U_text(key)

    k = "" if budget is None else f" (k = {budget.k:g})"
    where = ", ".join(f"{v:.0f}" for v in d["largest_at_mm"])
    rows = [(name("largest"), "largest", fmt(d["largest_um"]), U("largest"), "µm",
             f"at ({where}) mm")]
    rows += [(name(f"range_{a}"), f"range_{a}", fmt(v), U(f"range_{a}"), "µm", "")
             for a, v in d["range_um"].items()]
    diagonals = [(g["name"], f"diagonal_{g['name']}",
                  ", ".join(f"{v:g}" for v in g["start_mm"]),
                  ", ".join(f"{v:g}" for v in g["end_mm"]), fmt(g["range_um"]),
                  U(f"diagonal_{g['name']}"))
                 for g in d["diagonals"]]
    tables = [("Volumetric accuracy", "volumetric-figures",
               ["figure", "key", "value", f"U{k}", "unit", "where"], rows),
              ("Body diagonals (ISO 230-6:2002), predicted", "volumetric-diagonals",
               ["diagonal", "key", "start [mm]", "end [mm]", "range [µm]", f"U{k} [µm]"],
               diagonals),
              ("Squareness given", "volumetric-squareness", ["pair", "squareness [µm/m]"],
               [(k.upper(), fmt(v * 1e6)) for k, v in errors.squareness.items()])]
    if "truth" in d:
        tables.append(("Simulation: the simulated machine's truth", "volumetric-truth",
                       ["figure", "value [µm]"],
                       [(name("largest"), fmt(d["truth"]["largest_um"])),
                        ("Largest |mapped − true| over the grid",
                         fmt(d["mapped_minus_true_um"]))]))
    if budget is not None:
        tables.append((f"Inputs of the uncertainty budget ({budget.method})",
                       "volumetric-budget-inputs", ["input", "value", "", "rule or source",
                                                    "set with"],
                       [(i.label, i.value_text, "assumed" if i.assumed else "given", i.rule,
                         i.set_with) for i in budget.inputs]))
    return {"figure": figure(FIGURES["volumetric"], run, ev.evaluation),
            "alt": "The working volume's grid with the volumetric error magnified, and |E| "
                   "slices through the reference point",
            "source": "ISO/TR 16907:2015 (rigid-body model of the 21 geometric errors, ISO "
                      "230-1:2012 notation); body diagonals by ISO 230-6:2002",
            "lead": (f"{d['machine']}, chain {d['chain']}, {d['grid_points']} grid points, tool "
                     f"offset {', '.join(f'{v:g}' for v in d['tool_offset_mm'])} mm"),
            "tables": tables, "statements": [],
            "notes": [] if budget is None else list(budget.notes),
            "warnings": ([f"not measured, taken as zero: {', '.join(d['missing'])}"]
                         if d["missing"] else [])}
