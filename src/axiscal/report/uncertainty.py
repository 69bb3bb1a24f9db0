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

__all__ = ["add_uncertainty"]


def add_uncertainty(rep: Report, budget, decisions=()) -> None:
    """Add the measurement uncertainty section to ``rep``.

    Parameters
    ----------
    rep : Report
    budget : UncertaintyBudget
        With its ``inputs`` (:func:`~axiscal.standards.iso230_9.positioning_budget`).
    decisions : sequence of Decision, optional
        A tolerance not larger than its U is said first (ISO 14253-1:2017 §5.2).
    """
    from axiscal.standards.iso14253_1 import unprovable
    from axiscal.standards.iso230_9 import format_uncertainty

    u = unit_label(budget.unit)
    rep.add_heading("Measurement uncertainty")
    rep.add_warnings(unprovable(decisions, u))
    rep.add_table(
        ["Contribution", f"u [{u}]", "Distribution", "Input", "Source"],
        [[c.quantity, format_uncertainty(c.u), c.distribution, c.basis, c.clause]
         for c in budget.contributors],
        css_class="text",
        caption=f"Standard uncertainties (two significant digits, rounded up), combined by the "
                f"law of propagation of uncertainty (JCGM 100:2008, uncorrelated inputs) with "
                f"{budget.method}; U = k·u_c with k = {budget.k:g}. Length-proportional "
                "contributions act on A, E and M; R and B carry the reading resolution and "
                "E_VE.",
    )
    rep.add_table(
        ["Input", "Value", "From", "Rule or source", "Set with"],
        [[i.label, i.value_text, _source(i, budget), i.rule, i.set_with]
         for i in budget.inputs],
        css_class="text",
        caption="Inputs of the budget: an assumed input is a default chosen by the rule shown; "
                "declare the real value to replace it.",
    )
    for n in budget.notes:
        if not n.startswith("assumed: "):   # those are the inputs table's rows
            rep.add_text(n)


def _source(i, budget) -> str:
    if i.name in budget.missing_inputs:
        return "missing: left out of U"
    if i.assumed:
        return "assumed"
    return "data file" if i.rule.startswith("taken from the data file") else "declared"
