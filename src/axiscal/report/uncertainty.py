"""The uncertainty section of a report: U per parameter, the contributors, every input with where
it came from (assumed ones with the rule of their default), what U leaves out, and a tolerance
that can never be proven.

One section for every report that shows an ISO 230-2:2014 Annex A budget
(:class:`~axiscal.standards.iso230_9.UncertaintyBudget`); U is shown by
:func:`~axiscal.standards.iso230_9.format_uncertainty` (two significant digits rounded up,
JCGM 100:2008 §7.2.6), like the terminal and ``--json``'s display fields.
"""

from __future__ import annotations

from axiscal.report.html import Report, unit_label
from axiscal.report.labels import symbol_html

__all__ = ["add_uncertainty"]


def add_uncertainty(rep: Report, budget, decisions=(), parameters=None) -> None:
    """Add the measurement uncertainty section to ``rep``.

    Parameters
    ----------
    rep : Report
    budget : UncertaintyBudget
        With its ``inputs`` (:func:`~axiscal.standards.iso230_9.positioning_budget`).
    decisions : sequence of Decision, optional
        A tolerance not larger than its U is said first (ISO 14253-1:2017 §5.2).
    parameters : sequence of str, optional
        The parameters whose U is listed (default: every one the budget covers).

    Notes
    -----
    Symbols are written with their subscripts (E<sub>VE</sub>) and the inputs by their names in
    words: a customer's page carries no configuration keys (they are in ``--json``).
    """
    from axiscal.standards.iso14253_1 import unprovable
    from axiscal.standards.iso230_9 import format_uncertainty

    from axiscal.standards.positioning_standards import parameter_label

    u = unit_label(budget.unit)
    rep.add_heading("Measurement uncertainty")
    rep.add_warnings(unprovable(decisions, u))
    names = [p for p in (parameters or budget.expanded) if budget.U(p) is not None]
    rep.add_html(_table(
        ["Parameter", *(parameter_label(p) for p in names)],
        [[f"U (k = {budget.k:g}) [{u}]", *(budget.U_text(p) for p in names)]],
        "Expanded uncertainty per parameter, ISO 230-2:2014 Annex A: two significant digits, "
        "rounded up (JCGM 100:2008 §7.2.6)."))
    rep.add_html(_table(
        ["Contribution", f"u [{u}]", "Distribution", "Input", "Source"],
        [[c.quantity, format_uncertainty(c.u), c.distribution, c.basis, c.clause]
         for c in budget.contributors],
        f"Standard uncertainties (two significant digits, rounded up), combined by the law of "
        f"propagation of uncertainty (JCGM 100:2008, uncorrelated inputs) with {budget.method}; "
        f"U = k·u_c with k = {budget.k:g}. Length-proportional contributions act on A, E and M; "
        "R and B carry the reading resolution and E_VE."))
    rep.add_html(_table(
        ["Input", "Value", "From", "Rule or source"],
        [[i.label, i.value_text, _source(i, budget), i.rule] for i in budget.inputs],
        "Inputs of the budget. An assumed input is a default chosen by the rule shown: declare "
        "the real value in the job file's uncertainty table or with the command's --uncertainty "
        "option to replace it."))
    for n in budget.notes:
        if not n.startswith("assumed: "):   # those are the inputs table's rows
            rep.add_html(f"<p>{symbol_html(n.split(' with [uncertainty]')[0])}</p>")


def _table(headers, rows, caption: str) -> str:
    head = "".join(f"<th>{symbol_html(h)}</th>" for h in headers)
    body = "".join("<tr>" + "".join(f"<td>{symbol_html(str(c))}</td>" for c in row) + "</tr>"
                   for row in rows)
    return (f'<table class="text"><caption>{symbol_html(caption)}</caption><thead><tr>{head}'
            f"</tr></thead><tbody>{body}</tbody></table>")


def _source(i, budget) -> str:
    if i.name in budget.missing_inputs:
        return "missing: left out of U"
    if i.assumed:
        return "assumed"
    return "data file" if i.rule.startswith("taken from the data file") else "declared"
