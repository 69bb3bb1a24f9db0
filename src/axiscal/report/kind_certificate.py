"""Calibration certificate of a stored test of any kind that has an uncertainty budget.

A statement of conformity is made only with the expanded uncertainty U of each figure
(ISO 14253-1:2017 §5; ILAC-P14:09/2020 §5), so a kind of test gets a certificate only when
axiscal makes a budget for it: :func:`axiscal.store.kinds.budget_of` (the one call behind
:func:`axiscal.store.kinds.with_uncertainty`; :data:`axiscal.store.kinds.UNCERTAINTY_TABLE`).
Today that is a positioning test (ISO 230-2:2014 Annex A, which keeps its own, fuller
certificate: :mod:`axiscal.report.certificate`), a diagonal squareness test (ISO/TR 230-9), a
squareness from two straightness profiles (ISO/TR 230-9), a
ballbar test's G and H (:mod:`axiscal.standards.iso230_9_ballbar`), a straightness test's
figures (:mod:`axiscal.standards.iso230_9_straightness`), a five-motion-error
test's ISO 230-7 values (:mod:`axiscal.standards.iso230_7_uncertainty`), a five-axis identification (JCGM 100:2008 §5.1.3 over the least-squares fit) and an ISO 230-3:2020
thermal test, and a volumetric test (:mod:`axiscal.standards.iso230_9_volumetric`). Any other
kind is refused in one line naming why.

The path is one for every kind, keyed by nothing but the stored record
(:class:`~axiscal.store.kinds.Evaluated`: its parameters, its budget, its inputs):

- :func:`certificate_record` — the figures as the certificate states them (value rounded to
  the last digit of U, ILAC-P14:09/2020 §5.3, :func:`~axiscal.standards.uncertainty_reporting.
  format_value`; U to two significant digits rounded up, JCGM 100:2008 §7.2.6; k), each decided
  by :func:`~axiscal.standards.iso14253_1.decide_all` against the tolerance the user gives,
  with the U as printed, and the budget's inputs listed. Pure: no file, no clock.
- :func:`kind_certificate` — that record on a page (:class:`~axiscal.report.html.Report`).
- :func:`write_kind_certificate` — the mandatory content checked, the issue authorised and
  numbered by the history's certificate register, as :func:`axiscal.report.issue.
  write_certificate` does for a positioning test.
"""

from __future__ import annotations

import dataclasses
import math
import re
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from axiscal.errors import InputError

__all__ = ["CertifiedFigure", "KindCertificate", "KIND_NAMES", "require_budget",
           "certificate_record", "kind_certificate", "write_kind_certificate",
           "certify_stored", "kind_changes", "reissue"]

#: Each kind of test in words, with the document that evaluates it.
KIND_NAMES = {
    "iso230-2": "positioning (ISO 230-2:2014)",
    "straightness": "straightness (ISO 230-1:2012)",
    "ballbar": "ballbar (ISO 230-4:2005)",
    "diagonal": "diagonal squareness (ISO 230-6:2002)",
    "motion": "five-motion-error (ISO 230-7:2015)",
    "fiveaxis": "five-axis location error (ISO 230-1:2012, ISO 230-7:2015)",
    "thermal": "thermal (ISO 230-3:2020)",
    "volumetric": "volumetric (ISO/TR 16907:2015)",
    "fiveaxis-ballbar": "five-axis ballbar (ISO 10791-6:2014)",     # main's kind (issue 43)
    "squareness": "squareness from two straightness profiles (ISO 230-1:2012)",
}


@dataclass(frozen=True)
class CertifiedFigure:
    """One figure as a certificate states it.

    Attributes
    ----------
    name, symbol : str
        The key (as stored) and the document's symbol.
    value, U : float, ``unit``
        As stored in the record (U: expanded uncertainty, JCGM 100:2008 §6.2.1).
    k : float
        Coverage factor of U.
    unit : str
    value_text, U_text : str
        As printed: U to two significant digits rounded up, the value to U's last digit
        (ILAC-P14:09/2020 §5.3).
    tolerance : float or None, ``unit``
    verdict : str or None
        ISO 14253-1:2017 outcome (None: no tolerance for this figure).
    """

    name: str
    symbol: str
    value: float
    U: float
    k: float
    unit: str
    value_text: str
    U_text: str
    tolerance: float | None = None
    verdict: str | None = None


@dataclass(frozen=True)
class KindCertificate:
    """What a certificate of one stored test states: its figures, decisions and budget."""

    kind: str
    figures: tuple[CertifiedFigure, ...]
    decisions: tuple
    overall: Any
    rule_text: str
    warnings: tuple[str, ...]
    method: str
    #: (input, value, how it was set) of the budget, in the budget's order.
    inputs: tuple[tuple[str, str, str], ...]
    notes: tuple[str, ...]

    def __str__(self) -> str:
        lines = [f"{f.symbol} = {f.value_text} ± {f.U_text} {f.unit} (k = {f.k:g})"
                 + (f", {f.verdict} (≤ {f.tolerance:g})" if f.verdict else "")
                 for f in self.figures]
        verdict = self.overall.value if self.overall else "no tolerance given"
        return "\n".join([f"overall: {verdict}", *lines, *self.warnings])


def require_budget(ev) -> None:
    """Refuse, in one line, a record without an uncertainty budget (a conformity statement
    without U is one an assessor must refuse: ILAC-P14:09/2020 §5, ISO 14253-1:2017 §5).

    Raises
    ------
    InputError
        ``no uncertainty budget for ballbar tests in axiscal ...``
    """
    if ev.budget is None:
        name = KIND_NAMES.get(ev.kind, ev.kind).split(" (")[0]
        raise InputError(f"no uncertainty budget for {name} tests in axiscal: a certificate "
                         "states each result with its expanded uncertainty U (ILAC-P14:09/2020 "
                         "§5; ISO 14253-1:2017 §5), so this test gets none")


def certificate_record(ev, tolerances: dict | None = None,
                       rule: str | None = None) -> KindCertificate:
    """The certificate's content of a stored test's record ``ev`` (with its budget,
    :func:`axiscal.store.kinds.with_uncertainty`).

    Parameters
    ----------
    ev : axiscal.store.kinds.Evaluated
    tolerances : dict of str to float, each figure's unit
        Upper limits by figure key (one-sided, as the ISO 230 parts state tolerances).
    rule : str, optional
        ``iso14253-1`` (default) or ``simple``.

    Returns
    -------
    KindCertificate
        The figures the budget covers (a figure without U is not stated: it could not be
        decided), in the record's order.

    Raises
    ------
    InputError
        The kind has no budget; a tolerance names no figure with U, or is not a positive number.

    Notes
    -----
    The decision uses the U as printed (two significant digits rounded up, JCGM 100:2008
    §7.2.6), so the verdict follows from the numbers on the page, as for a positioning test.
    """
    from axiscal.standards.iso14253_1 import RULE_TEXT, _rule, decide_all, overall, unprovable
    from axiscal.units import display
    from axiscal.standards.uncertainty_reporting import (format_uncertainty, format_value,
                                                         round_up)

    require_budget(ev)
    tolerances = dict(tolerances or {})
    for name, tol in tolerances.items():
        if isinstance(tol, bool) or not isinstance(tol, (int, float)) or not math.isfinite(tol) \
                or tol <= 0:
            raise InputError(f"tolerance {name} = {tol!r}: a positive number")
    quantities = {n: q for n, q in ev.quantities.items()
                  if q.U is not None and q.value is not None}
    r = _rule(rule or "iso14253-1")
    stated = _Stated({n: round_up(q.U) for n, q in quantities.items()})
    decisions = decide_all({n: q.value for n, q in quantities.items()}, stated, tolerances, r) \
        if tolerances else ()
    by = {d.parameter: d for d in decisions}
    figures = tuple(CertifiedFigure(
        n, q.symbol or n, q.value, q.U, q.k, q.unit, format_value(q.value, q.U),
        format_uncertainty(q.U), None if n not in by else by[n].upper,
        None if n not in by or by[n].outcome is None else by[n].outcome.value)
        for n, q in quantities.items())
    units = {q.unit for q in quantities.values()}
    budget = ev.budget.to_json()
    return KindCertificate(ev.kind, figures, tuple(decisions), overall(decisions),
                           RULE_TEXT[r] if decisions else "",
                           tuple(unprovable(decisions, display(units.pop())
                                            if len(units) == 1 else "")),
                           str(budget.get("method", "")), _inputs(budget, ev.inputs),
                           tuple(budget.get("notes", ())))


def kind_certificate(ev, record: KindCertificate, info) -> Any:
    """The certificate page of ``record`` (a DRAFT when ``info.draft``): verdict, customer and
    item, results with U and k, the budget's inputs, statements, signatures.

    Parameters
    ----------
    ev : axiscal.store.kinds.Evaluated
        The stored record (its item's names as the history keeps them).
    record : KindCertificate
    info : axiscal.report.certificate.CertificateInfo

    Returns
    -------
    Report
    """
    from axiscal import units
    from axiscal.report import certificate as c
    from axiscal.report.html import Report

    what = KIND_NAMES.get(ev.kind, ev.kind)
    rep = Report(f"DRAFT — not a certificate: {what} test" if info.draft
                 else f"Calibration certificate — {what} test",
                 subtitle=f"Evaluation by {what.split('(', 1)[-1].rstrip(')')}; measurement "
                 f"uncertainty: {record.method}", reference=c._reference(info),
                 letterhead=c._letterhead(info), paper=info.paper)
    rep.add_html(f"<style>{c._CSS}</style>")
    if info.draft:
        rep.add_html(c._draft_box(info))
    elif info.replaces:
        rep.add_html(f'<div class="amend">This certificate replaces certificate '
                     f"{c._esc(info.replaces)}. Reason: {c._esc(info.reason)}"
                     + c._changes(info.changes) + "</div>")
    rep.add_html(c._verdict_box(record.overall, record.rule_text))
    m = info.machine
    rep.add_html(c._pairs({
        "Customer": info.customer.get("name"), "Customer address": c._lines(
            info.customer.get("address"), ", "),
        "Machine": m.get("name") or ev.machine,
        "Maker, model, serial": " ".join(str(m.get(k)) for k in ("maker", "model", "serial")
                                         if m.get(k)),
        "Axis": m.get("axis") or ev.axis, "Location": m.get("location"),
        "Date of test": ev.date or info.conditions.get("date"),
        "Instrument": ev.instrument, "Date of issue": info.issued},
        "Customer and item calibrated"))
    c._instruments(rep, info, None)
    rep.add_table(["Input", "Value", "How it was set"], record.inputs,
                  caption=f"Uncertainty budget: {record.method}")
    for note in record.notes:      # an assumed input is a row of the table above
        if not note.startswith("assumed:"):
            rep.add_text(c.customer_words(note))
    rep.add_html(c._statements(info, record.decisions, record.rule_text))
    rows = [(_label(ev, f), f.value_text, f.U_text, f"{f.k:g}", units.display(f.unit),
             "—" if f.tolerance is None else f"{f.tolerance:g}", f.verdict or "—")
            for f in record.figures]
    head = "".join(f"<th>{h}</th>" for h in ("Result", "Value", "U", "k", "Unit",
                                             "Tolerance", "Verdict"))
    body = "".join("<tr>" + "".join(f"<td>{c._esc(v)}</td>" for v in r) + "</tr>" for r in rows)
    warn = "".join(f"<p>{c._esc(w)}</p>" for w in record.warnings)
    rep.add_html('<div class="closing"><h2>Results</h2><table class="results"><thead><tr>'
                 f"{head}</tr></thead><tbody>{body}</tbody></table><p>Each value is rounded "
                 "to the last digit of its expanded uncertainty U (ILAC-P14:09/2020 §5.3); U "
                 "is stated with its coverage factor k (about 95 % coverage).</p>" + warn
                 + c._signatures(info, info.operator or ev.operator) + "</div>")
    return rep


def write_kind_certificate(path, ev, cfg: dict, data_bytes: bytes,
                           tolerances: dict | None = None, rule: str | None = None, *,
                           store=None, filename: str = "data.csv", today: str | None = None,
                           prepared_by: str = "", approved_by: str = "",
                           paper: str | None = None, draft_document: bool = True,
                           replaces: str = "", reason: str = "", changes=()):
    """The certificate of a stored test's record ``ev`` written to ``path`` (.html or .pdf):
    issued and numbered through ``store``'s register when every mandatory item is there (ISO/IEC
    17025:2017 §7.8.2, §7.8.4), else a DRAFT naming what is missing (not written with
    ``draft_document`` False).

    Parameters
    ----------
    ev : axiscal.store.kinds.Evaluated
        With its budget (:meth:`axiscal.store.history.StoredTest.record`).
    cfg : dict
        The configuration (laboratory, customer, item, instruments, signatory).
    tolerances : dict of str to float
        Over the configuration's ``[tolerance]``, keyed by figure.
    replaces, reason, changes
        An amendment's (:func:`reissue`).

    Returns
    -------
    axiscal.report.issue.CertificateOutcome

    Raises
    ------
    InputError
        No budget for the kind; a bad tolerance; a date of test after the date of issue.
    """
    from axiscal.io._files import write_bytes_atomic
    from axiscal.report.certificate_content import (_identity, _instruments, check_dates)
    from axiscal.report.issue import (CertificateOutcome, _info, _register, _with_history_item,
                                      _with_paper, authorisation)

    require_budget(ev)
    if store is not None and not callable(store):
        cfg = _with_history_item(cfg, store, data_bytes)
    # the configuration's tolerances that name this test's results (it may hold a positioning
    # test's A, E ...), under those given for this test (an unknown name among them refused)
    tol = {**{k: v for k, v in cfg.get("tolerance", {}).items() if k in ev.parameters},
           **(tolerances or {})}
    record = certificate_record(ev, tol, rule or cfg.get("certificate", {}).get("rule"))
    cfg = _with_paper(cfg, paper)
    info = _info(cfg, today, "", ())
    tested = str(ev.date or info.conditions.get("date") or "")
    check_dates(tested, info.issued)
    info, refusals = authorisation(cfg, info, prepared_by or info.operator or ev.operator,
                                   approved_by)
    missing = _identity(info, "")
    if not tested:
        missing.append("date of calibration (not in the data file; give [conditions] date)")
    missing += _instruments(info, tested)
    missing += [f"expanded uncertainty of {f.symbol} (zero: never a defensible statement, "
                "JCGM 100:2008 §7.2.6)" for f in record.figures if not f.U > 0]
    if not record.figures:
        missing.append("a result with its expanded uncertainty")
    missing += _unmeasured_e_ve(ev)
    if record.decisions and not info.specification:
        missing.append("source of the specification the verdict is given against "
                       "([certificate] specification)")
    missing = tuple(missing + list(refusals))
    if store is None and not missing:
        missing = ("certificate number: a certificate is numbered only by the certificate "
                   "register (a calibration history, --db)",)
    info = dataclasses.replace(info, missing=missing, replaces=replaces, reason=reason,
                               changes=tuple(changes))

    def render(number: str) -> bytes:
        return kind_certificate(ev, record, dataclasses.replace(info, number=number)
                                ).document(path)

    if missing:
        if draft_document:
            write_bytes_atomic(Path(path), render(""))
        return CertificateOutcome(Path(path), record.decisions, missing)
    inputs = {"config": cfg, "tolerances": tol, "rule": rule, "paper": info.paper,
              "logo": "", "customer_supplied": [], "kind": ev.kind}
    store = store() if callable(store) else store
    rec = _register(store, ev.dataset, info, data_bytes, filename, render, inputs, path)
    write_bytes_atomic(Path(path), rec.document)
    return CertificateOutcome(Path(path), record.decisions, (), rec.number, rec)


def certify_stored(store, test_id: int, path, cfg: dict, tolerances: dict | None = None,
                   rule: str | None = None, *, paper: str | None = None,
                   today: str | None = None, prepared_by: str = "", approved_by: str = "",
                   draft_document: bool = True):
    """The certificate of stored test ``test_id``, whatever its kind: the one entry of
    ``axiscal certificate issue`` and the workbench's sign-off of a test that is not a
    positioning test.

    The configuration is the sign-off's (:func:`axiscal.store.laboratory.signoff_config`: the
    laboratory kept in the history under ``cfg``); the figures and their U are the stored
    record's (:meth:`axiscal.store.history.StoredTest.record`, the budget made from the inputs
    kept with the test). A positioning test takes its own certificate
    (:func:`axiscal.report.issue.write_certificate`: per-target table, figure, conditions of
    ISO 230-2:2014 §6); every other kind :func:`write_kind_certificate`.

    Raises
    ------
    InputError
        The kind has no uncertainty budget (one line naming it); a bad tolerance.
    """
    from axiscal.store.laboratory import signoff_config, signoff_record

    t = store.get(test_id)
    ev = t.record()
    require_budget(ev)
    cfg = signoff_config(store, t, cfg)
    if ev.kind != "iso230-2":        # E_VE as a positioning test's: the laboratory's, a drift check
        ev = signoff_record(store, t, cfg)
    if ev.kind == "iso230-2":
        from axiscal.report.issue import write_certificate

        return write_certificate(path, ev.dataset, ev.evaluation, cfg, t.raw, tolerances, rule,
                                 paper, store=store, filename=t.summary.filename, today=today,
                                 customer_supplied=(), prepared_by=prepared_by,
                                 approved_by=approved_by, draft_document=draft_document)
    return write_kind_certificate(path, ev, cfg, t.raw, tolerances, rule, store=store,
                                  filename=t.summary.filename, today=today,
                                  prepared_by=prepared_by, approved_by=approved_by, paper=paper,
                                  draft_document=draft_document)


def _unmeasured_e_ve(ev) -> list[str]:
    """E_VE as a missing item where the budget reads it and nobody gave it (ISO 230-2:2014
    Annex A.5: measured by a drift check or declared; ISO/IEC 17025:2017 §7.8.4.1 b): a
    certificate never states a U that took it as 0."""
    return ["E_VE, the environmental variation (ISO 230-2:2014 Annex A.5): neither measured "
            "by a drift check kept with the test nor declared by the laboratory (--uncertainty "
            "e_ve=VALUE); a certificate never takes it as 0"
            for i in getattr(ev.budget, "inputs", None) or ()
            if getattr(i, "name", None) == "e_ve" and getattr(i, "assumed", False)]


def kind_changes(ev, before, after) -> list[dict]:
    """What an amendment of a certificate of ``ev`` changes (ISO/IEC 17025:2017 §7.8.8.3), as
    :func:`axiscal.report.issue.amendment_changes` says it for a positioning test: each field
    of the inputs whose text changed, each figure whose tolerance or verdict changed.
    ``before``, ``after``: ``(config, tolerances, rule)``."""
    from axiscal.report.issue import _flat

    old, new = _flat(before[0]), _flat(after[0])
    out = [{"what": k, "old": old.get(k, "—"), "new": new.get(k, "—")}
           for k in sorted(set(old) | set(new)) if old.get(k) != new.get(k)]
    states = []
    for cfg, tol, rule in (before, after):
        tol = {k: v for k, v in {**cfg.get("tolerance", {}), **(tol or {})}.items()
               if k in ev.parameters}
        rec = certificate_record(ev, tol, rule or cfg.get("certificate", {}).get("rule"))
        row = {}
        for f in rec.figures:
            row[f"tolerance {f.name}"] = "—" if f.tolerance is None else f"{f.tolerance:g}"
            row[f"verdict {f.name}"] = f.verdict or "—"
        row["overall verdict"] = rec.overall.value if rec.overall else "no tolerance"
        states.append(row)
    return out + [{"what": k, "old": states[0][k], "new": states[1][k]} for k in states[0]
                  if states[0][k] != states[1].get(k)]


def _label(ev, f: CertifiedFigure) -> str:
    """A figure in words with its symbol: a thermal test's own label (ISO 230-3:2020), else the
    label of :func:`axiscal.report.labels.quantity` where it knows the key."""
    from axiscal.report.labels import QUANTITIES, quantity

    words = next((g.get("label") for g in ev.result.get("figures", ())
                  if isinstance(g, dict) and g.get("name") == f.name), None)
    if words is None and f.name in QUANTITIES:
        words = quantity(f.name)[0]
    elif words is None and ev.kind == "motion":      # ISO 230-7:2015 §3 error motion values
        from axiscal.report.labels import name

        words = name(f.name)
    return f.symbol if not words or words.casefold() == f.symbol.casefold() \
        else f"{words} ({f.symbol})"


def reissue(store, number: str, reason: str, path, corrections: dict | None = None,
            today: str | None = None, laboratory: str | None = None, prepared_by: str = "",
            approved_by: str = ""):
    """Amend certificate ``number`` (ISO/IEC 17025:2017 §7.8.8), whatever its test's kind: a
    positioning test's by :func:`axiscal.report.issue.reissue_certificate`, another kind's by
    :func:`write_kind_certificate` of the stored record with the inputs kept with the old one
    and ``corrections`` on top (:func:`axiscal.report.issue.amendment_inputs`), the changes
    listed (:func:`kind_changes`); a reissue that would be a DRAFT is refused. The one call
    of ``axiscal certificate reissue`` and the workbench's amendment."""
    from axiscal.report.issue import _draft_refused, amendment_inputs, reissue_certificate

    _, stored, inputs, cfg = amendment_inputs(store, number, reason, path, corrections,
                                              laboratory)
    if stored.summary.kind == "iso230-2":
        return reissue_certificate(store, number, reason, path, corrections, today, laboratory,
                                   prepared_by, approved_by)
    from axiscal.store.laboratory import signoff_record

    rec = signoff_record(store, stored, cfg)      # E_VE as it was certified (kept in cfg)
    kept = (inputs["config"], inputs["tolerances"], inputs["rule"])
    changes = kind_changes(rec, kept, (cfg, inputs["tolerances"], inputs["rule"]))
    return _draft_refused(path, lambda p: write_kind_certificate(
        p, rec, cfg, stored.raw, inputs["tolerances"], inputs["rule"], store=store,
        filename=stored.summary.filename, today=today, prepared_by=prepared_by,
        approved_by=approved_by, paper=inputs["paper"], replaces=number,
        reason=reason.strip(), changes=changes), number)


class _Stated:
    """The U as printed, for :func:`~axiscal.standards.iso14253_1.decide_all`."""

    def __init__(self, U: dict):
        self._U = U

    def U(self, name: str) -> float | None:
        return self._U.get(name)


def _inputs(budget: dict, given: dict) -> tuple[tuple[str, str, str], ...]:
    """(input, value, how) of a budget's JSON: its declared inputs where it lists them (ISO/TR
    230-9 budgets), else the standard uncertainties by figure and input (a five-axis
    identification), else its contributors (a five-axis ballbar range: each u with its basis),
    else the inputs given to it."""
    rows = []
    for name, i in (budget.get("inputs") or {}).items():
        rule = re.sub(r"^(assumed|given):\s*", "", str(i.get("rule", "")))  # said once
        how = "assumed" if i.get("assumed") else "measured" if rule.startswith("measured") \
            else "given"                          # a measured input's rule says so itself
        rows.append((str(i.get("label") or name), f"{i.get('value'):g} {i.get('unit', '')}"
                     .strip(), rule if how == "measured" else f"{how}: {rule}".rstrip(": ")))
    for fig, comps in (budget.get("u_components") or {}).items():
        for comp, u in comps.items():
            rows.append((f"u({fig}) from {comp}", f"{u:.3g}", "standard uncertainty, µm or µrad"))
    if not rows:
        unit = str(budget.get("unit", "")).replace("um", "µm")
        rows = [(f"{c.get('name')}: {c.get('quantity')}", f"u = {c.get('u', 0.0):.3g} {unit}",
                 f"{c.get('basis', '')} ({c.get('clause', '')})")
                for c in budget.get("contributors") or ()]
    if not rows:
        rows = [(str(k), str(v), "given") for k, v in (given or {}).items()]
    return tuple(rows)
