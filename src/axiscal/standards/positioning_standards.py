"""Registry of the positioning standards a contract may name, and one result shape for all of them.

Each entry says what axiscal can evaluate for that standard *from a public definition*. Where no
public text of a standard's definitions was available to this project, the entry is kept (so
``--standard`` names it and the user learns why) but it has no evaluation: asking for it is an
:class:`~axiscal.errors.InputError` that says so. No formula is written here from memory.

==================  ===================================================  =========================
key                 standard                                             status
==================  ===================================================  =========================
iso230-2:2014       ISO 230-2:2014                                       evaluated (Yüksel et al.,
                                                                         eqs 1-21, :mod:`.iso230_2`)
iso230-2:2006       ISO 230-2:2006                                       R↑, R↓ (4s; AMT),
                                                                         :mod:`.iso230_2_editions`
iso230-2:1997       ISO 230-2:1997                                       not available publicly
iso230-2:1988       ISO 230-2:1988                                       R↑, R↓ (6s; WIT 1999),
                                                                         :mod:`.iso230_2_editions`
gb-t17421.2         GB/T 17421.2 (Chinese adoption of an ISO 230-2       not available publicly
                    edition)
jis-b6192           JIS B 6192 / JIS B 0182-1993 vocabulary              R and B only (terms 342,
                                                                         346, :mod:`.jis_b6192`)
vdi3441             VDI/DGQ 3441                                         Pa, U, Ū (Rexroth
                                                                         R310DE), :mod:`.vdi3441`
asme-b5.54          ASME B5.54                                           not available publicly
bs3800              BS 3800                                              not available publicly
nmtba               NMTBA                                                not available publicly
==================  ===================================================  =========================

A standard evaluated in part names the parameters it does not evaluate, with the reason
(:attr:`StandardResult.not_evaluated`); a tolerance on one of them is refused.

Every evaluated standard gives a :class:`StandardResult`; its :meth:`StandardResult.parameters`
maps name -> (value, unit, description), the same shape for every standard, so results can be
stored and judged generically (:func:`check_tolerances`).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Callable

from axiscal.datasets import PositioningDataset
from axiscal.errors import InputError, NotAvailableError
from axiscal.standards._parameters import described_parameters, parameter_label

__all__ = ["Standard", "StandardResult", "STANDARDS", "evaluate", "evaluate_all",
           "check_tolerances", "NotAvailableError", "described_parameters", "parameter_label",
           "table_rows"]


def table_rows(std: "Standard", result: "StandardResult") -> list[tuple]:
    """One standard's rows of a results table, as the terminal, the report and the workbench
    show them: (the standard's title on its first row only, parameter label, value, meaning,
    evaluated), the parameters axiscal does not evaluate last, with value None and the reason."""
    rows = [(parameter_label(n), v, d, True) for n, (v, _u, d) in result.parameters().items()]
    rows += [(parameter_label(n), None, why, False) for n, why in result.not_evaluated]
    return [(std.title if i == 0 else "", *r) for i, r in enumerate(rows)]


@dataclass(frozen=True)
class StandardResult:
    """Axis parameters of one test by one standard.

    Attributes
    ----------
    key, title : str
        Registry key (``jis-b6192``) and the standard's title.
    rows : tuple of (name, value, unit, description)
        The standard's own parameter names and symbols, in its order; value None where it does
        not apply to this test.
    warnings : tuple of str
    not_evaluated : tuple of (name, reason)
        The standard's other parameters, which axiscal does not evaluate, and why.
    """

    key: str
    title: str
    rows: tuple[tuple[str, float | None, str, str], ...]
    warnings: tuple[str, ...] = field(default_factory=tuple)
    not_evaluated: tuple[tuple[str, str], ...] = field(default_factory=tuple)

    def parameters(self) -> dict[str, tuple[float | None, str, str]]:
        """name -> (value, unit, description)."""
        return {name: (value, unit, desc) for name, value, unit, desc in self.rows}


@dataclass(frozen=True)
class Standard:
    """One registry entry: what the standard is, and how (or whether) axiscal evaluates it."""

    key: str
    title: str
    source: str
    run: Callable[[PositioningDataset], StandardResult] | None = None
    #: The ±k·s band its definitions draw around each direction's mean (None: not public).
    band: float | None = None

    @property
    def available(self) -> bool:
        return self.run is not None


_ISO_2014_MEANINGS = {
    "A": "bidirectional accuracy of positioning (±2s)", "A_up": "unidirectional accuracy ↑",
    "A_down": "unidirectional accuracy ↓", "E": "bidirectional systematic positioning error",
    "E_up": "unidirectional systematic error ↑", "E_down": "unidirectional systematic error ↓",
    "M": "range of mean bidirectional positioning error",
    "R": "bidirectional repeatability, max[2s↑ + 2s↓ + |B_i|; 4s↑; 4s↓]",
    "R_up": "unidirectional repeatability ↑ (4s)", "R_down": "unidirectional repeatability ↓ (4s)",
    "B": "reversal value, max |B_i|", "B_mean": "mean reversal value (signed, B_i = x̄↑ − x̄↓)",
}


def _iso230_2_2014(ds: PositioningDataset) -> StandardResult:
    from axiscal.standards import iso230_2

    r = iso230_2.evaluate(ds)
    rows = tuple((name, value, ds.deviation_unit, _ISO_2014_MEANINGS[name])
                 for name, value in r.parameters().items())
    return StandardResult("iso230-2:2014", STANDARDS["iso230-2:2014"].title, rows, r.warnings)


def _described(key: str, r, not_evaluated: dict | None = None) -> StandardResult:
    """A module's result (whose ``parameters()`` gives name -> (value, unit, description)) as
    the registry's :class:`StandardResult`."""
    rows = tuple((name, v, u, d) for name, (v, u, d) in r.parameters().items())
    return StandardResult(key, STANDARDS[key].title, rows, r.warnings,
                          tuple((not_evaluated or {}).items()))


def _jis_b6192(ds: PositioningDataset) -> StandardResult:
    from axiscal.standards import jis_b6192

    return _described("jis-b6192", jis_b6192.evaluate(ds))


def _vdi3441(ds: PositioningDataset) -> StandardResult:
    from axiscal.standards import vdi3441

    return _described("vdi3441", vdi3441.evaluate(ds), vdi3441.NOT_EVALUATED)


def _iso_edition(edition: str) -> Callable[[PositioningDataset], StandardResult]:
    def run(ds: PositioningDataset) -> StandardResult:
        from axiscal.standards import iso230_2_editions as ed

        return _described(f"iso230-2:{edition}", getattr(ed, f"evaluate_{edition}")(ds),
                          ed.NOT_EVALUATED)
    return run


_NONE = "no public text of its definitions was available to axiscal"

STANDARDS: dict[str, Standard] = {s.key: s for s in (
    Standard("iso230-2:2014", "ISO 230-2:2014",
             "ISO 230-2:2014 clause 3 (Yüksel et al., eqs. 1-21)", _iso230_2_2014, 2.0),
    Standard("iso230-2:2006", "ISO 230-2:2006",
             "AMT announcement of ISO 230-2:2006 (2 standard uncertainties)", _iso_edition("2006"),
             2.0),
    Standard("iso230-2:1997", "ISO 230-2:1997", _NONE),
    Standard("iso230-2:1988", "ISO 230-2:1988",
             "WIT Trans. Eng. Sci. 23 (1999): a six standard deviation spread",
             _iso_edition("1988"), 3.0),
    Standard("gb-t17421.2", "GB/T 17421.2", _NONE + " (nor which ISO 230-2 edition it adopts)"),
    Standard("jis-b6192", "JIS B 6192 / B 0182",
             "JIS B 0182-1993 terms 342, 346", _jis_b6192, 3.0),
    Standard("vdi3441", "VDI/DGQ 3441", "Bosch Rexroth, Linearmodule R310DE 2402, p. 151",
             _vdi3441),
    Standard("asme-b5.54", "ASME B5.54", _NONE),
    Standard("bs3800", "BS 3800", _NONE),
    Standard("nmtba", "NMTBA", _NONE),
)}


def _entry(key: str) -> Standard:
    if key not in STANDARDS:
        raise InputError(f"standard {key!r} is not known; use one of {', '.join(STANDARDS)} "
                         "or 'all'")
    return STANDARDS[key]


def evaluate(key: str, dataset: PositioningDataset) -> StandardResult:
    """Evaluate ``dataset`` by the standard ``key`` (see :data:`STANDARDS`).

    Raises
    ------
    NotAvailableError
        If the standard's definitions were not publicly available (the message says so).
    InputError
        If ``key`` is unknown, or the standard cannot form its parameters from this test.
    """
    std = _entry(key)
    if std.run is None:
        raise NotAvailableError(f"{std.title}: not evaluated, {std.source}; axiscal does not "
                                "invent a standard's formulas (see docs/standards.md)")
    return std.run(dataset)


def evaluate_all(dataset: PositioningDataset) -> tuple[tuple[Standard, StandardResult | str], ...]:
    """Every registered standard: its result, or the one-line reason it was not evaluated."""
    out: list[tuple[Standard, StandardResult | str]] = []
    for std in STANDARDS.values():
        try:
            out.append((std, evaluate(std.key, dataset)))
        except InputError as exc:
            out.append((std, str(exc)))
    return tuple(out)


def check_tolerances(key: str, dataset: PositioningDataset, result: StandardResult,
                     tolerances: dict[str, float], rule: str | None = None, uncertainty=None,
                     budget=None):
    """Decide acceptance tolerances of any standard's parameters (ISO 14253-1:2017 decisions).

    Parameters
    ----------
    key : str
        Registry key of ``result``.
    dataset : PositioningDataset
        The test ``result`` was evaluated from (for the uncertainty budget).
    result : StandardResult
    tolerances : dict of str to float
        Upper limit per parameter name of that standard, in the deviation unit.
    rule : {"iso14253-1", "simple"}, optional
        For ``iso230-2:2014`` the default is ISO 14253-1 with U from the ISO 230-9 budget of
        :func:`axiscal.standards.iso230_9.positioning_budget`. No published budget gives U for the
        other standards' parameters, so for them the rule is simple acceptance (ILAC-G8 §4.2.1)
        and U is reported as not estimated (NaN); asking for ``iso14253-1`` there is refused.
    uncertainty : mapping, optional
        The ``[uncertainty]`` inputs of that budget (absent ones are assumed and shown so).
    budget : UncertaintyBudget, optional
        That budget already made (the test's record): used as it is, ``uncertainty`` ignored.

    Returns
    -------
    tuple of :class:`axiscal.standards.iso14253_1.Decision`, in the standard's parameter order.
    """
    from dataclasses import replace

    from axiscal.standards import iso230_2, iso230_9
    from axiscal.standards.iso14253_1 import Rule, _rule, decide_all

    values = {name: v for name, (v, _u, _d) in result.parameters().items()}
    skipped = dict(result.not_evaluated)
    for name, tol in tolerances.items():
        if name in skipped:
            raise InputError(f"tolerance for {name!r}: {result.title} {name}, "
                             f"{skipped[name]}; use one of {', '.join(values)}")
        if name not in values:
            raise InputError(f"tolerance for {name!r}: not a {result.title} parameter; use one "
                             f"of {', '.join(values)}")
        if not (isinstance(tol, (int, float)) and math.isfinite(tol) and tol >= 0):
            raise InputError(f"tolerance {name} = {tol!r} must be a number >= 0")
    if key == "iso230-2:2014":
        if budget is None:
            budget = iso230_9.positioning_budget(dataset, iso230_2.evaluate(dataset),
                                                 uncertainty)
        return decide_all(values, budget, tolerances, _rule(rule or "iso14253-1"))
    r = _rule(rule or "simple")
    if r is not Rule.SIMPLE:
        raise InputError(f"{result.title}: the ISO 14253-1 rule needs the expanded uncertainty of "
                         "each parameter, and ISO 230-9 gives it for ISO 230-2:2014 parameters "
                         "only; use --rule simple")
    decisions = decide_all(values, _NotEstimated(), tolerances, r)
    return tuple(replace(d, U=math.nan) for d in decisions)


class _NotEstimated:
    """A budget for simple acceptance: U is not taken into account (and not estimated)."""

    def U(self, name: str) -> float:  # noqa: N802 - the budget interface
        return 0.0
