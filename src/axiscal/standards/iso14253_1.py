"""Decision rules for proving conformance or non-conformance with specifications (ISO 14253-1).

Any parameter with a measured value y, an expanded uncertainty U and a tolerance zone (an upper
limit, optionally a lower one) gets one of three outcomes:

* **conformance proven** — the whole interval y ± U lies in the tolerance zone
  (ISO 14253-1:2017 §5.2: the specification zone reduced by U, the acceptance zone);
* **non-conformance proven** — the whole interval y ± U lies outside it (§5.3: the zone
  enlarged by U, the rejection zone);
* **uncertainty zone** — neither can be proven (§5.4): the interval straddles a limit.

The *simple acceptance* rule (ISO 14253-5 / ILAC-G8:2019 §4.2.1, "shared risk", no guard band)
compares y with the limits alone; it is selectable, and every report states which rule was used.

Nothing here knows about ISO 230-2: the rules apply to a parameter of any standard
(VDI 3441, ASME B5.54 ...) that has a value and a U in the same unit.

References
----------
ISO 14253-1:2017, Geometrical product specifications (GPS) — Inspection by measurement of
workpieces and measuring equipment — Part 1: Decision rules for verifying conformity or
nonconformity with specifications.
ILAC-G8:09/2019, Guidelines on Decision Rules and Statements of Conformity, §4.2.1.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from enum import Enum

from axiscal.errors import InputError

__all__ = ["Outcome", "Rule", "Decision", "decide", "decide_all", "overall", "unprovable",
           "RULE_TEXT"]


class Outcome(str, Enum):
    """What the measurement proves about one parameter."""

    CONFORMS = "conformance proven"
    NONCONFORMS = "non-conformance proven"
    ZONE = "uncertainty zone"

    @property
    def short(self) -> str:
        """PASS, FAIL or ZONE, for a table cell."""
        return {"conformance proven": "PASS", "non-conformance proven": "FAIL"}.get(
            self.value, "ZONE"
        )


class Rule(str, Enum):
    """Which decision rule applies."""

    ISO_14253_1 = "iso14253-1"
    SIMPLE = "simple"


#: How each rule is stated on a report.
RULE_TEXT = {
    Rule.ISO_14253_1: "Decision rule ISO 14253-1:2017 §5: conformance is proven when the measured "
    "value plus and minus its expanded uncertainty U (k = 2) lies inside the "
    "tolerance, non-conformance when it lies wholly outside; otherwise the "
    "result is in the uncertainty zone and neither is proven.",
    Rule.SIMPLE: "Decision rule: simple acceptance (ILAC-G8:2019 §4.2.1, no guard band): the "
    "measured value is compared with the tolerance, the measurement uncertainty "
    "is stated but not taken into account (risk shared by supplier and customer).",
}


@dataclass(frozen=True)
class Decision:
    """The outcome for one parameter.

    Attributes
    ----------
    parameter : str
    value : float or None
        Measured value (None: the parameter does not apply; outcome None).
    U : float
        Expanded uncertainty, same unit.
    upper : float
        Upper tolerance limit.
    lower : float or None
        Lower tolerance limit (None: one-sided, e.g. E ≤ 10 µm).
    rule : Rule
    outcome : Outcome or None
    """

    parameter: str
    value: float | None
    U: float
    upper: float
    lower: float | None
    rule: Rule
    outcome: Outcome | None

    @property
    def passed(self) -> bool | None:
        """True when conformance is proven, False when non-conformance is, None otherwise."""
        return {Outcome.CONFORMS: True, Outcome.NONCONFORMS: False}.get(self.outcome)

    def __str__(self) -> str:
        v = "n/a" if self.value is None else f"{self.value:.4g} ± {self.U:.2g}"
        lim = f"≤ {self.upper:g}" if self.lower is None else f"in [{self.lower:g}, {self.upper:g}]"
        return f"{self.parameter}: {v} ({lim}) {self.outcome.value if self.outcome else 'n/a'}"


def decide(
    parameter: str,
    value: float | None,
    U: float,
    upper: float,
    lower: float | None = None,
    rule: Rule | str = Rule.ISO_14253_1,
) -> Decision:
    """Apply a decision rule to one parameter.

    Parameters
    ----------
    parameter : str
    value : float or None
        Measured value; None when it does not apply (e.g. A↓ of a unidirectional test).
    U : float
        Expanded uncertainty (k = 2), same unit, >= 0.
    upper : float
        Upper limit of the tolerance zone.
    lower : float, optional
        Lower limit; for a one-sided tolerance (the usual case for A, E, R ...) leave it None.
    rule : Rule or str
        ``iso14253-1`` (default) or ``simple``.

    Returns
    -------
    Decision

    Notes
    -----
    ISO 14253-1:2017 §5.2-5.4. With a lower limit L and upper limit T:
    conforms ⇔ L + U ≤ y ≤ T − U; non-conforms ⇔ y > T + U or y < L − U; the uncertainty zone
    otherwise. A value exactly at T − U conforms and exactly at T + U is still in the zone (the
    standard proves non-conformance only outside the enlarged zone). Simple acceptance:
    conforms ⇔ L ≤ y ≤ T.

    Examples
    --------
    >>> decide("E", 8.0, 1.5, 10.0).outcome.value
    'conformance proven'
    >>> decide("E", 9.0, 1.5, 10.0).outcome.value
    'uncertainty zone'
    >>> decide("E", 9.0, 1.5, 10.0, rule="simple").outcome.short
    'PASS'
    """
    rule = _rule(rule)
    for name, v in (("U", U), ("upper limit", upper), ("lower limit", lower)):
        if v is not None and (isinstance(v, bool) or not math.isfinite(v)):
            raise InputError(f"{parameter}: {name} = {v!r} must be a finite number")
    if U < 0:
        raise InputError(f"{parameter}: expanded uncertainty U = {U!r} must be >= 0")
    if lower is not None and lower > upper:
        raise InputError(f"{parameter}: lower limit {lower:g} is above the upper limit {upper:g}")
    if value is None or (isinstance(value, float) and math.isnan(value)):
        return Decision(parameter, None, float(U), float(upper), lower, rule, None)
    y = float(value)
    lo = -math.inf if lower is None else float(lower)
    g = 0.0 if rule is Rule.SIMPLE else float(U)
    if lo + g <= y <= upper - g:
        outcome = Outcome.CONFORMS
    elif rule is Rule.SIMPLE or y > upper + g or y < lo - g:
        outcome = Outcome.NONCONFORMS
    else:
        outcome = Outcome.ZONE
    return Decision(parameter, y, float(U), float(upper), lower, rule, outcome)


def overall(decisions) -> Outcome | None:
    """The outcome of a whole test: non-conformance if any parameter's is proven, conformance
    if every applicable parameter's is proven, the uncertainty zone otherwise (None if nothing
    applies)."""
    outcomes = [d.outcome for d in decisions if d.outcome is not None]
    if not outcomes:
        return None
    if Outcome.NONCONFORMS in outcomes:
        return Outcome.NONCONFORMS
    return Outcome.CONFORMS if all(o is Outcome.CONFORMS for o in outcomes) else Outcome.ZONE


def unprovable(decisions, unit: str = "") -> list[str]:
    """One warning line per tolerance whose conformance can never be proven.

    Under ISO 14253-1:2017 §5.2 conformance is proven only inside the acceptance zone, the
    tolerance zone reduced by U on each limited side: for an upper limit T alone the zone is
    y ≤ T − U, empty for a parameter that cannot be negative once U ≥ T (and for a two-sided
    zone once 2U ≥ T − L). Simple acceptance has no guard band, so nothing is said there.

    Parameters
    ----------
    decisions : sequence of Decision
    unit : str
        Display unit of the values (``µm`` ...).

    Returns
    -------
    list of str

    Examples
    --------
    >>> unprovable([decide("A", 0.09, 3.52, 1.0)], "µm")[0][:60]
    'tolerance A = 1 µm is not larger than its expanded uncertain'
    """
    from axiscal.standards.iso230_9 import format_uncertainty

    out = []
    for d in decisions:
        if d.rule is not Rule.ISO_14253_1 or math.isnan(d.U):
            continue
        width = d.upper if d.lower is None else (d.upper - d.lower) / 2
        if d.U >= width:
            u = f" {unit}" if unit else ""
            out.append(
                f"tolerance {d.parameter} = {d.upper:g}{u} is not larger than its expanded "
                f"uncertainty U = {format_uncertainty(d.U)}{u}: conformance can never be proven "
                "(ISO 14253-1:2017 §5.2: the tolerance reduced by U leaves no acceptance zone); "
                "declare the assumed uncertainty inputs or use a better set-up to lower U"
            )
    return out


def decide_all(
    values, budget, tolerances, rule: Rule | str = Rule.ISO_14253_1, signed=("B_mean",)
) -> tuple[Decision, ...]:
    """Decide every toleranced parameter of a result.

    Parameters
    ----------
    values : mapping of str to float or None
        Parameter values (e.g. ``Iso230_2Result.parameters()``).
    budget : UncertaintyBudget or mapping with ``U(name)``
        Supplies U per parameter (a parameter it does not cover is refused); an
        :class:`~axiscal.standards.iso230_9.UncertaintyBudget` supplies the U it prints
        (``stated``: two significant digits, rounded up), so a verdict never rests on a U
        smaller than the one on the certificate.
    tolerances : mapping of str to float
        Upper limit per parameter (one-sided, as ISO 230-2 acceptance tests state them).
    rule : Rule or str
    signed : sequence of str
        Parameters whose magnitude is toleranced (the signed mean reversal B̄).
    """
    for name in tolerances:
        if name not in values:
            raise InputError(
                f"tolerance for {name!r}: not a parameter of this result; use one of "
                f"{', '.join(values)}"
            )
    out = []
    for name in (n for n in values if n in tolerances):  # in the result's order
        tol = tolerances[name]
        # the U printed (rounded up to two digits) where the budget states one: the verdict
        # follows from the numbers on the page (issue 38: E = 74.77 ± 0.66 against 75.428)
        U = budget.stated(name) if hasattr(budget, "stated") else budget.U(name)
        if U is None:
            raise InputError(f"tolerance for {name!r}: the uncertainty budget does not cover it")
        v = values[name]
        out.append(
            decide(
                name,
                None if v is None else (abs(v) if name in signed else v),
                U,
                float(tol),
                None,
                rule,
            )
        )
    return tuple(out)


def _rule(rule: Rule | str) -> Rule:
    try:
        return Rule(rule)
    except ValueError:
        raise InputError(f"decision rule {rule!r}: use iso14253-1 or simple") from None
