"""The report of a five-axis ballbar test (a rotary axis, or both, moving with the linear axes;
ISO 10791-6:2014 as :mod:`axiscal.standards.iso10791_6` reads it).

:func:`ballbar_report` is the one report of the kind: ``axiscal fiveaxis ballbar evaluate FILE
--report OUT`` writes it for the files given, and the history (``axiscal history show ID
--report``, the workbench's "Report" link, :meth:`axiscal.History.report`) for the stored test,
through :func:`axiscal.report.evaluations.write_evaluation_report`. Per set-up it lays out what
the one evaluation gave (:meth:`~axiscal.procedures.five_axis_ballbar.BallbarRecord.evaluate`,
:class:`~axiscal.standards.iso10791_6.BallbarRange`): the range with U (k) and, with a
tolerance, the ISO 14253-1:2017 decision; the readings along the path
(:func:`~axiscal.report.five_axis_plots.ballbar_path_figure`); the set-up; the budget once, each
contributor with its u, basis and clause; and the inputs, each stated or assumed beside its
number. Nothing is computed here but the decision.
"""

from __future__ import annotations

import math

import numpy as np

from axiscal.errors import InputError

__all__ = ["ballbar_report"]

_SOURCE = ("Kinematic tests of ISO 10791-6:2014 as axiscal reads their public descriptions (the "
           "standard's text was not at hand: its test codes, dimensions and tolerances are not "
           "cited); U (k = 2) by JCGM 100:2008.")


def ballbar_report(tests, *, title: str, tolerance: float | None = None,
                   rule: str | None = None, metadata: dict | None = None):
    """The report (:class:`~axiscal.report.html.Report`) of one or more ballbar set-ups.

    Parameters
    ----------
    tests : sequence of (BallbarRecord, BallbarRange)
        Each set-up's readings and its evaluation (the record's own ``evaluate()``).
    title : str
    tolerance : float, optional, µm
        Upper limit of every set-up's range (one-sided); None: no decision is made.
    rule : str, optional
        ``iso14253-1`` (default) or ``simple`` (:mod:`axiscal.standards.iso14253_1`).
    metadata : dict, optional
        Shown under the title (machine, axis, files ...).

    Raises
    ------
    InputError
        A tolerance that is not a positive finite number.

    Notes
    -----
    The decision is ISO 14253-1:2017 §5.2-5.4 (:func:`~axiscal.standards.iso14253_1.decide`)
    with the U as printed (two significant digits rounded up, JCGM 100:2008 §7.2.6), as the
    certificate decides it.
    """
    from axiscal.report.html import Report

    if tolerance is not None and (isinstance(tolerance, bool) or not math.isfinite(tolerance)
                                  or tolerance <= 0):
        raise InputError(f"--tolerance {tolerance!r}: a positive number of µm")
    tests = list(tests)
    rep = Report(title, _SOURCE, dict(metadata or {}))
    if tolerance is not None:
        from axiscal.standards.iso14253_1 import RULE_TEXT, _rule

        rep.add_text(f"Tolerance: each range ≤ {tolerance:g} µm. "
                     + RULE_TEXT[_rule(rule or "iso14253-1")])
    for rec, r in tests:
        _setup_section(rep, rec, r, tolerance, rule, several=len(tests) > 1)
    return rep


def _setup_section(rep, rec, r, tolerance, rule, several: bool) -> None:
    from axiscal.report.five_axis_plots import ballbar_path_figure

    b = r.budget
    level = 3 if several else 2
    if several:
        rep.add_heading(f"Set-up {r.label}")
    rep.add_heading("The range with its uncertainty", level)
    _range_table(rep, r, tolerance, rule)
    rep.add_figure(ballbar_path_figure(rec, r), "The ballbar's reading − nominal length at each "
                   "point of the path, the largest and smallest dashed; the range is their "
                   "difference.")
    rep.add_heading("The set-up", level)
    rep.add_table(["set-up", "value"], _setup_rows(rec, r), css_class="kv")
    rep.add_heading("The range's uncertainty budget", level)
    unit = "µm" if b.unit == "um" else b.unit
    rows = [[c.name, c.quantity, c.u, c.distribution, c.basis, c.clause]
            for c in b.contributors]
    rows.append(["u_c", "combined (root sum of squares)", b.combined["range"], "", "",
                 "JCGM 100:2008 5.1.2"])
    rows.append(["U", f"expanded, k = {b.k:g}", b.expanded["range"], "", "",
                 "JCGM 100:2008 6.2.1"])
    rep.add_table(["contributor", "quantity", f"u ({unit})", "distribution", "basis", "clause"],
                  rows, digits=3, css_class="budget", formulas=(0,))
    rep.add_heading("The budget's inputs", level + 1)
    rep.add_table(["input", "value", "how it was set"], _input_rows(rec), css_class="kv")
    for note in b.notes:
        rep.add_text(f"Note: {note}.")


def _range_table(rep, r, tolerance, rule) -> None:
    from axiscal.standards.iso14253_1 import decide, unprovable

    b = r.budget
    head = ["figure", "value (µm)", f"U (k = {b.k:g}) (µm)"]
    rows = [["range", r.range * 1e6, r.U * 1e6], ["largest reading", r.maximum * 1e6, None],
            ["smallest reading", r.minimum * 1e6, None],
            ["scatter about the smooth fit (Type A)", r.scatter * 1e6, None]]
    if tolerance is None:
        rep.add_table(head, rows, digits=2)
        return
    d = decide("range", r.range * 1e6, b.stated("range"), float(tolerance),
               rule=rule or "iso14253-1")
    rows[0] += [tolerance, d.outcome.value]
    for row in rows[1:]:
        row += [None, None]
    rep.add_table(head + ["tolerance (µm)", "verdict"], rows, digits=2, css_class="params")
    rep.add_text(f"Decided with U as printed, {b.U_text('range')} µm (JCGM 100:2008 §7.2.6).")
    rep.add_warnings(unprovable([d], "µm"))


def _setup_rows(rec, r) -> list:
    swept = {"both": "both rotary axes (the five axes moving)", "": "not stated"}.get(
        rec.swept, f"{rec.swept} (with the linear axes)")
    ends = np.degrees([[rec.tilt_angle[0], rec.c_angle[0]],
                       [rec.tilt_angle[-1], rec.c_angle[-1]]])
    bar = "not stated" if not np.any(rec.bar) else ", ".join(f"{v:.4f}" for v in rec.bar)
    pivot = ("not stated" if not np.any(rec.pivot)
             else ", ".join(f"{v * 1e3:.3f}" for v in rec.pivot) + " mm")
    return [["rotary axes", f"{rec.tilt} (tilting) and C (rotary), table-table"],
            ["swept", swept], ["bar direction", rec.direction or "not stated"],
            ["bar length (nominal)", f"{rec.length * 1e3:g} mm"],
            ["pivot (table ball, table frame)", pivot], ["bar (unit vector, table frame)", bar],
            ["poses", f"{r.points} readings along the path"],
            ["first pose", f"{rec.tilt} {ends[0][0]:.3f}°, C {ends[0][1]:.3f}°"],
            ["last pose", f"{rec.tilt} {ends[1][0]:.3f}°, C {ends[1][1]:.3f}°"]]


def _input_rows(rec) -> list:
    from axiscal.standards.iso10791_6 import ALPHA_BAR

    def how(key: str) -> str:
        if key in rec.unstated:
            return f"assumed 0: the file does not state it (set it with '# {key} = ...')"
        return "stated in the file"

    return [["noise of one reading", f"{rec.noise * 1e6:g} µm", "stated in the file"],
            ["transducer calibration (relative)", f"{rec.u_gain:g}", how("u_gain")],
            ["bar temperature change during the run", f"{rec.drift:g} K", how("drift_K")],
            ["bar body's expansion coefficient", f"{ALPHA_BAR * 1e6:g} µm/(m·K)",
             "assumed (a steel bar body); a file cannot set it"],
            ["calibrator length uncertainty", f"{rec.u_length * 1e6:g} µm",
             how("u_length_um") + "; acts on no range (sensitivity 0)"]]
