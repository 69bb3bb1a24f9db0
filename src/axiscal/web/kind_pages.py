"""What a test's page shows of the kinds of test other than ISO 230-2 positioning.

Each view takes the library's one evaluation of the stored file
(:func:`axiscal.store.kinds.evaluate_file`, the numbers of the command a user runs on the file)
and lays it out: a figure drawn by :mod:`axiscal.report` (as an SVG image) and tables of labelled
quantities, every value with three decimals as the command line and the page's parameter table
write them (a share in % with one). Nothing is computed here.

- ballbar: the polar plot and ranked bars of ``ballbar analyze --plot``, the ISO 230-4:2005 §3
  figures, the ranked diagnosis with its advice (Renishaw, "Calibration of machine squareness",
  Method 4), what the ISO 230-4 fit folds together; one direction: the ISO 230-4 evaluation;
- straightness: both ISO 230-1:2012 reference lines (§3.4.8 least squares, §3.4.9 minimum zone),
  each figure with its U and the budget's contributors and inputs
  (:func:`axiscal.standards.iso230_9_straightness.straightness_budget`, the stored record's);
- diagonal: squareness from two diagonals (ISO 230-6:2002; Chapman, Method 5) with its U (k = 2),
  the budget ``squareness diagonal`` prints
  (:func:`axiscal.standards.iso230_9_geometry.diagonal_budget`, ISO/TR 230-9; the user
  configuration's ``[squareness_uncertainty]`` inputs), its contributors, its inputs and each
  assumed one in words;
- motion: the ISO 230-7:2015 error motion values with their U (the record's budget,
  :mod:`axiscal.standards.iso230_7_uncertainty`, its contributors and inputs) and their polar
  plots;
- squareness (from two straightness profiles): ``squareness biaxial``'s figure, figures, options
  and budget (ISO 230-1:2012 §3.6.7; ISO/TR 230-9), from the stored record;
- fiveaxis, fiveaxis-ballbar, thermal and volumetric: their own modules
  (:mod:`axiscal.web.five_axis_page`, :mod:`axiscal.web.five_axis_ballbar_page`,
  :mod:`axiscal.web.thermal_page`, :mod:`axiscal.web.volumetric_page`).
"""

from __future__ import annotations

import threading

__all__ = ["kind_view"]

#: matplotlib's pyplot is not thread-safe; the pages are served from a thread pool.
_PLOT_LOCK = threading.Lock()


def kind_view(ev) -> dict | None:
    """The page's view of an evaluated test (None for ISO 230-2, which has its own page):
    ``figure`` (a ``data:`` URI), ``alt``, ``tables`` (caption, id, headers, rows of text),
    ``statements`` and ``warnings`` (lines of text) and ``source`` (the standard and clause)."""
    if ev.kind == "fiveaxis":              # its own module (issue 43)
        from axiscal.web.five_axis_page import five_axis_view

        return five_axis_view(ev, _figure, fmt)
    if ev.kind == "fiveaxis-ballbar":      # its own module (issue 43)
        from axiscal.web.five_axis_ballbar_page import five_axis_ballbar_view

        return five_axis_ballbar_view(ev, _figure, fmt)
    if ev.kind == "thermal":               # its own module (issue 44)
        from axiscal.web.thermal_page import thermal_view

        return thermal_view(ev, _figure, fmt)
    if ev.kind == "volumetric":            # its own module (issue 40)
        from axiscal.web.volumetric_page import volumetric_view

        return volumetric_view(ev, _figure, fmt)
    view = _VIEWS.get(ev.kind)
    return None if view is None else view(ev)


def _figure(draw, *args, **kw) -> str:
    """A figure of :mod:`axiscal.report` as a ``data:image/svg+xml`` URI (an image: the SVG's
    text is never part of the page's markup)."""
    import base64

    from axiscal.report.html import figure_svg

    with _PLOT_LOCK:
        svg = figure_svg(draw(*args, **kw))
    return "data:image/svg+xml;base64," + base64.b64encode(svg.encode()).decode()


def fmt(value, unit: str = "") -> str:
    """A number as the page writes it: three decimals (a share in % one), None or NaN a dash."""
    import math

    if value is None or math.isnan(value):
        return "—"
    return f"{value:.1f}" if unit == "%" else f"{value:.3f}"


def _um(v):
    return None if v is None else v * 1e6


def _ballbar(ev) -> dict:
    r, d = ev.evaluation, ev.dataset
    plane = "".join(d.axes)
    if not hasattr(r, "circular"):
        return _ballbar_one_direction(ev)
    from axiscal.report.ballbar_plots import (RANKING_CAPTION, RANKING_HEADERS,
                                              diagnosis_figure, ranking_rows)

    c = r.circular
    figures = [("G ccw", _um(c.G_ccw)), ("G cw", _um(c.G_cw)), ("H", _um(c.H)),
               ("F max", _um(c.F_max)), ("F min", _um(c.F_min)),
               ("residual after the model, rms", r.residual_rms * 1e6),
               ("residual after the model, peak-to-valley", r.residual_ptp * 1e6)]
    feed = "not given" if r.feed is None else f"{r.feed * 6e4:g} mm/min"
    return {
        "figure": _figure(diagnosis_figure, d.runs, r, title=f"Ballbar {plane}"),
        "alt": f"Polar plot of the {plane} circular test and the diagnosis bars",
        "source": "ISO 230-4:2005 circular test; diagnosis after Renishaw, \"Calibration of "
                  "machine squareness\", Method 4",
        "lead": f"R = {c.radius * 1e3:g} mm over {c.arc_deg:.0f}°, feed {feed}",
        "tables": [("ISO 230-4:2005 §3 figures", "iso230-4", ["quantity", "value [µm]"],
                    [(n, fmt(v, "µm")) for n, v in figures]),
                   (RANKING_CAPTION, "diagnosis", RANKING_HEADERS, ranking_rows(r, fmt)),
                   _iso_fit_table(c)],
        "statements": [f.strip() for f in r.folded_lines()],
        "warnings": list(r.warnings)}


def _iso_fit_table(c) -> tuple:
    """The ISO 230-4 fit's own squareness, scale mismatch and backlash (``squareness
    circular``)."""
    a0, a1 = c.squareness.axes
    rows = [("squareness", fmt(c.squareness.um_per_m, "µm/m"), "µm/m"),
            ("scale mismatch", fmt(c.scale_mismatch * 1e6, "µm/m"), "µm/m"),
            (f"backlash {a0}", fmt(_um(c.backlash_x), "µm"), "µm"),
            (f"backlash {a1}", fmt(_um(c.backlash_y), "µm"), "µm")]
    return ("The ISO 230-4:2005 fit (squareness circular)", "iso230-4-fit",
            ["quantity", "value", "unit"], rows)


def _ballbar_one_direction(ev) -> dict:
    from axiscal.report.squareness_plots import ballbar_figure

    c, d = ev.evaluation, ev.dataset
    plane = "".join(d.axes)
    rows = [("G ccw", fmt(_um(c.G_ccw), "µm"), "µm"), ("G cw", fmt(_um(c.G_cw), "µm"), "µm"),
            ("H", fmt(_um(c.H), "µm"), "µm")]
    _, _, _, fit = _iso_fit_table(c)
    return {"figure": _figure(ballbar_figure, d.runs, c, title=f"Ballbar {plane}"),
            "alt": f"Polar plot of the {plane} circular test",
            "source": "ISO 230-4:2005 circular test, one direction: the diagnosis needs both",
            "lead": f"R = {c.radius * 1e3:g} mm over {c.arc_deg:.0f}°",
            "tables": [("ISO 230-4:2005 §3 figures and fit", "iso230-4", ["quantity", "value",
                                                                          "unit"], rows + fit)],
            "statements": [], "warnings": list(c.warnings)}


def _straightness(ev) -> dict:
    from axiscal.report.squareness_plots import straightness_figure

    res, d = ev.result, ev.dataset
    names = {"least_squares": "least squares (ISO 230-1:2012 §3.4.8)",
             "minimum_zone": "minimum zone (ISO 230-1:2012 §3.4.9)"}
    rows = [(names[m], fmt(res[m]["straightness_um"], "µm"),
             fmt(res[m]["slope_um_per_m"], "µm/m")) for m in names]
    b = ev.budget                   # the record's (iso230_9_straightness): U beside each figure
    heads = ["reference line", "straightness [µm]", "slope [µm/m]"]
    if b is not None:
        heads = ["reference line", "straightness [µm]", "U (k = 2) [µm]", "slope [µm/m]",
                 "U (k = 2) [µm/m]"]
        rows = [(rows[0][0], rows[0][1], b.U_text("straightness"), rows[0][2],
                 b.U_text("slope")),
                (rows[1][0], rows[1][1], b.U_text("straightness_min_zone"), rows[1][2], "—")]
    return {"figure": _figure(straightness_figure, d, ev.evaluation),
            "alt": "Straightness readings, the least-squares line and its band",
            "source": "ISO 230-1:2012 §3.4.8 and §3.4.9, reference straight lines",
            "lead": f"{res['n']} readings along {d.axis or 'the axis'}, deviation along "
                    f"{d.direction or 'the normal'}",
            "tables": [("Straightness about each reference line", "straightness", heads, rows),
                       *(_budget_tables(b, "µm; the slope's µm/m") if b is not None else ())],
            "notes": list(b.notes) if b is not None else [], "statements": [], "warnings": []}


def _diagonal(ev) -> dict:
    from axiscal.report.squareness_plots import diagonal_figure
    from axiscal.standards.iso230_9_geometry import diagonal_budget

    r, sq = ev.evaluation, ev.evaluation.squareness
    rows = [("squareness", fmt(sq.um_per_m, "µm/m"), "µm/m"),
            ("squareness", fmt(sq.arcsec, "arcsec"), "arcsec"),
            ("X travel", fmt(r.length_x * 1e3, "mm"), "mm"),
            ("Y travel", fmt(r.length_y * 1e3, "mm"), "mm"),
            ("diagonal nominal D0", fmt(r.nominal * 1e3, "mm"), "mm"),
            ("length error of D1 (along -X +Y)", fmt(r.error_d1 * 1e6, "µm"), "µm"),
            ("length error of D2 (along +X +Y)", fmt(r.error_d2 * 1e6, "µm"), "µm")]
    budget = ev.budget if ev.budget is not None else diagonal_budget(r, _squareness_table())
    rows.insert(2, ("U (k = 2) of the squareness", budget.U_text("squareness"), "µm/m"))
    return {"figure": _figure(diagonal_figure, ev.dataset, r),
            "alt": "Length errors along the two diagonals",
            "source": "ISO 230-6:2002 diagonal displacement; Chapman, \"Calibration of machine "
                      "squareness\", Method 5: squareness = D0 (D1 − D2) / (2XY)",
            "lead": sq.angle_note,
            "tables": [("Squareness from two diagonals", "diagonal", ["quantity", "value",
                                                                       "unit"], rows),
                       *_budget_tables(budget, "µm/m")],
            "notes": list(budget.notes), "statements": [], "warnings": []}


def _squareness(ev) -> dict:
    """A squareness from two straightness profiles (kind ``squareness``): the figure, table
    and budget of ``squareness biaxial`` (its ``--json``, the stored record's result)."""
    from axiscal.report.evaluations import FIGURES

    d, t, b = ev.result, ev.dataset, ev.evaluation
    sq = d["squareness"]
    a0, a1 = sq["axes"]
    rows = [("squareness", fmt(sq["um_per_m"], "µm/m"), "µm/m"),
            ("squareness", fmt(sq["arcsec"], "arcsec"), "arcsec"),
            ("U (k = 2) of the squareness", ev.budget.U_text("squareness"), "µm/m"),
            (f"ISO 230-1: {sq['iso_referred']} referred to datum {sq['iso_datum']}",
             fmt(sq["iso_um_per_m"], "µm/m"), "µm/m"),
            (f"slope of the {a0} trajectory", fmt(d["slope_first_um_per_m"], "µm/m"), "µm/m"),
            (f"slope of the {a1} trajectory", fmt(d["slope_second_um_per_m"], "µm/m"),
             "µm/m"),
            (f"straightness of the {a0} trajectory", fmt(d["straightness_first_um"], "µm"),
             "µm"),
            (f"straightness of the {a1} trajectory", fmt(d["straightness_second_um"], "µm"),
             "µm"),
            ("correction for the square's angle error", fmt(d["correction_um_per_m"], "µm/m"),
             "µm/m")]
    options = [("set-up (Chapman, Methods 1-3)", d["config"]),
               ("orientation [°, clockwise]", str(d["orientation"])),
               ("square's angle error [arcsec]", fmt(d["prism_error_arcsec"], "arcsec")),
               ("reference line (ISO 230-1:2012 §3.4)", d["reference"].replace("_", " ")),
               ("reference square (budget)", t.square),
               (f"{a0} trajectory", f"{t.one.source}: {t.one.positions.size} readings"),
               (f"{a1} trajectory", f"{t.two.source}: {t.two.positions.size} readings")]
    return {"figure": _figure(FIGURES["squareness"], t, b),
            "alt": "Both trajectories with their reference lines",
            "source": "ISO 230-1:2012 §3.6.7, squareness from two straightness trajectories "
                      "(Chapman, \"Calibration of machine squareness\", Methods 1-3); U by "
                      "ISO/TR 230-9, as axiscal squareness biaxial",
            "lead": f"{t.title}; {sq['angle_note']}",
            "tables": [("Squareness from two straightness profiles", "biaxial",
                        ["quantity", "value", "unit"], rows),
                       ("Set-up and options", "biaxial-options", ["option", "value"], options),
                       *_budget_tables(ev.budget, "µm/m")],
            "notes": list(ev.budget.notes), "statements": [], "warnings": []}


def _squareness_table() -> dict:
    """The user configuration's ``[squareness_uncertainty]`` table, as the squareness commands
    read it."""
    from axiscal.io.user_config import load_user_config

    return dict(load_user_config().get("squareness_uncertainty", {}))


def _budget_tables(budget, unit: str) -> list:
    """An uncertainty budget as two tables: its contributors (ISO/TR 230-9 form; u with three
    significant digits, a small one is not a zero) and every input with where it came from
    (measured, given, assumed with its rule)."""
    contributors = [(c.name, c.quantity, f"{c.u:.3g}", c.distribution, c.basis, c.clause)
                    for c in budget.contributors]
    inputs = [(i.label, i.value_text, "assumed" if i.assumed else "measured"
               if i.rule.startswith("measured") else "given", i.rule, i.set_with)
              for i in budget.inputs]
    return [(f"Uncertainty budget ({budget.method}, k = {budget.k:g})", "budget",
             ["contributor", "quantity", f"u [{unit}]", "distribution", "basis", "clause"],
             contributors),
            ("Inputs of the budget", "budget-inputs",
             ["input", "value", "", "rule or source", "set with"], inputs)]


def _motion(ev) -> dict:
    from axiscal.report.motion_plots import polar_figure
    from axiscal.report.motion_report import iso230_7_rows

    r, d, b = ev.evaluation, ev.dataset, ev.budget

    def U(name, fig):       # the record's U of a figure (iso230_7_uncertainty), "—" if none
        return "—" if b is None else b.U_text(f"{name.replace(' ', '_')}_{fig}")

    rows = [(name, fmt(t), U(name, "total"), fmt(s), U(name, "synchronous"), fmt(a),
             U(name, "asynchronous"), fmt(f), fund, u)
            for name, t, s, a, f, fund, u in iso230_7_rows(r)]
    k = "" if b is None else f" (k = {b.k:g})"
    return {"figure": _figure(polar_figure, r, title="ISO 230-7 error motion"
                              + (f" — {d.title}" if d.title else "")),
            "alt": "Polar plots of the five error motions",
            "source": "ISO 230-7:2015, error motion of an axis of rotation",
            "lead": f"{r.n_runs} run{'s' if r.n_runs != 1 else ''}",
            "tables": [("ISO 230-7 error motion values with their expanded uncertainty U"
                        + k, "motion",
                        ["motion", "total", "U", "synchronous", "U", "asynchronous", "U",
                         "fundamental", "fundamental in the values", "unit"], rows),
                       *(_budget_tables(b, "µm or arcsec") if b is not None else ())],
            "notes": [] if b is None else list(b.notes), "statements": [], "warnings": []}


_VIEWS = {"ballbar": _ballbar, "straightness": _straightness, "diagonal": _diagonal,
          "motion": _motion, "squareness": _squareness}
