"""Calibration certificate of a positioning test: ISO 230-2 result, ISO 230-9 uncertainty,
ISO 14253-1 decisions, with letterhead, customer, machine, test conditions and instruments.

:func:`positioning_certificate` is a pure function of (dataset, result, uncertainty budget,
certificate information, tolerances): it reads no file and no clock, so a calibration history can
store its inputs and regenerate the same certificate. :func:`certificate_info` turns the merged
user configuration and job file (see :mod:`axiscal.io.user_config`) into
:class:`CertificateInfo`. The page is an ordinary :class:`~axiscal.report.html.Report`, so it is
written as HTML or, with a ``.pdf`` name, as a PDF from the same template.

A certificate shows no simulation truth and no internal references: documents are cited by their
title and clause. It carries the statements of ISO/IEC 17025:2017 §7.8 (traceability through the
instruments' certificates, results relating only to the item, reproduction only in full, the
customer-supplied information marked, the decision rule and specification, assumptions and
deviations in plain words, the authorising signatory, an end mark). A certificate that lacks a
mandatory item (:mod:`axiscal.report.certificate_content`) is built as a DRAFT: "not a
certificate" in its title, a watermark on every page and the missing items listed.
"""

from __future__ import annotations

import html as _html
import json
import re
from dataclasses import dataclass, field
from importlib import resources
from typing import Any, Mapping

from axiscal.errors import ConfigError
from axiscal.report.html import (
    Report,
    _PARAM_LABEL,
    _PARAM_MEANING,
    _cell,
    target_label,
    unit_label,
)

__all__ = [
    "Instrument",
    "CertificateInfo",
    "certificate_info",
    "positioning_certificate",
    "NOT_STATED",
    "item_identity",
    "data_origin",
]

NOT_STATED = "not stated"
_SECTIONS = {
    "company": {"name", "address", "logo", "accreditation", "code"},
    "operator": {"name"},
    "customer": {"name", "address", "reference"},
    "machine": {"maker", "model", "serial", "location", "axis", "name"},
    "conditions": {"date", "measuring_line", "feed", "dwell", "cycle", "location",
                   "air_temperature", "material_temperature", "air_pressure", "humidity",
                   "material_sensors", "referred_to_20", "data_origin"},
    "certificate": {"paper", "rule", "number", "number_prefix", "number_pattern", "issued",
                    "approver", "signatory", "signatory_role", "specification"},
    "instrument": {"name", "serial", "certificate", "due"},
    "signatory": {"name", "role"},
    "uncertainty": None,  # checked by the budget's own inputs
    "tolerance": None,  # NAME = value, checked against the standard's parameters
    "squareness_uncertainty": None,  # read by the squareness commands
    "ballbar_uncertainty": None,  # a ballbar test's budget (standards/iso230_9_ballbar.py)
    "motion_uncertainty": None,  # an ISO 230-7 test's budget (standards/iso230_7_uncertainty.py)
    "volumetric_uncertainty": None,  # a volumetric map's budget (iso230_9_volumetric.py)
    "straightness_uncertainty": None,  # standards/iso230_9_straightness.py
}


@dataclass(frozen=True)
class Instrument:
    """A measuring instrument used, with its calibration certificate."""

    name: str
    serial: str = ""
    certificate: str = ""
    due: str = ""


@dataclass(frozen=True)
class CertificateInfo:
    """Everything on a certificate that is not the measurement (all text, as the user wrote it).

    ``logo`` is a ``data:`` URI (read by the I/O layer), ``issued`` the date of issue,
    ``customer_supplied`` the tolerances the customer gave (the job file), ``missing`` the
    mandatory items not given (a DRAFT when any), ``replaces`` and ``reason`` an amendment's.
    """

    company: Mapping[str, Any] = field(default_factory=dict)
    operator: str = ""
    customer: Mapping[str, Any] = field(default_factory=dict)
    machine: Mapping[str, Any] = field(default_factory=dict)
    conditions: Mapping[str, Any] = field(default_factory=dict)
    instruments: tuple[Instrument, ...] = ()
    number: str = ""
    issued: str = ""
    signatory: str = ""
    signatory_role: str = ""
    specification: str = ""
    paper: str = "A4"
    logo: str = ""
    customer_supplied: tuple[str, ...] = ()
    missing: tuple[str, ...] = ()
    replaces: str = ""
    reason: str = ""
    prepared_by: str = ""
    changes: tuple = ()

    @property
    def draft(self) -> bool:
        """Not a certificate: a mandatory item is missing, or no number was issued."""
        return bool(self.missing) or not self.number


def certificate_info(
    config: Mapping[str, Any], number: str = "", issued: str = "", logo: str = "",
    customer_supplied=(),
) -> CertificateInfo:
    """Build :class:`CertificateInfo` from a configuration mapping (user file merged with a job).

    Parameters
    ----------
    config : mapping
        Tables ``[company]``, ``[operator]``, ``[customer]``, ``[machine]``, ``[conditions]``,
        ``[certificate]``, ``[[instrument]]`` (and ``[uncertainty]``, ``[tolerance]``, read
        elsewhere). Unknown tables or keys are a :class:`ConfigError`.
    number : str
        Report number to use when the configuration gives none.
    issued : str
        Date of issue.
    logo : str
        The company logo as a ``data:`` URI.
    customer_supplied : sequence of str
        Names of the tolerances the customer supplied (marked on the certificate).
    """
    from axiscal._schema import refuse_unknown

    refuse_unknown(config, set(_SECTIONS))
    for name, value in config.items():
        keys = _SECTIONS[name]
        for table in (value if isinstance(value, list) else [value]):
            if not isinstance(table, dict):
                raise ConfigError(f"configuration: [{name}] must be a table")
            if keys is not None:
                refuse_unknown(table, keys, f"[{name}]")
    _check_conditions(config.get("conditions", {}))
    cert = config.get("certificate", {})
    paper = str(cert.get("paper", "A4"))
    if paper.lower() not in ("a4", "letter"):
        raise ConfigError(f"configuration [certificate] paper = {paper!r}: use A4 or Letter")
    inst = config.get("instrument", [])
    inst = inst if isinstance(inst, list) else [inst]
    return CertificateInfo(
        company=dict(config.get("company", {})),
        operator=str(config.get("operator", {}).get("name", "")),
        customer=dict(config.get("customer", {})),
        machine=dict(config.get("machine", {})),
        conditions=dict(config.get("conditions", {})),
        instruments=tuple(Instrument(**{k: str(v) for k, v in t.items()}) for t in inst),
        number=str(cert.get("number") or number),
        issued=str(cert.get("issued") or issued),
        signatory=str(cert.get("signatory") or cert.get("approver") or ""),
        signatory_role=str(cert.get("signatory_role", "")),
        specification=str(cert.get("specification", "")),
        paper=paper,
        logo=logo,
        customer_supplied=tuple(customer_supplied),
    )


#: ``[conditions] data_origin``: who took the readings (ISO/IEC 17025:2017 §7.8.2.2).
DATA_ORIGINS = ("laboratory", "customer")


def _check_conditions(cond: Mapping[str, Any]) -> None:
    """The laser user's stated conditions: numbers in range, a yes/no, an origin by name."""
    for key, lo, hi, unit in (("air_pressure", 1e3, 2e5, "Pa"), ("humidity", 0.0, 100.0, "%RH")):
        v = cond.get(key)
        if v is not None and (isinstance(v, bool) or not isinstance(v, (int, float))
                              or not lo <= v <= hi):
            raise ConfigError(f"[conditions] {key} = {v!r}: a number from {lo:g} to {hi:g} "
                              f"{unit}")
    if "referred_to_20" in cond and not isinstance(cond["referred_to_20"], bool):
        raise ConfigError(f"[conditions] referred_to_20 = {cond['referred_to_20']!r}: true "
                          "(deviations referred to 20 °C, ISO 1) or false")
    if cond.get("data_origin") not in (None, *DATA_ORIGINS):
        raise ConfigError(f"[conditions] data_origin = {cond['data_origin']!r}: laboratory "
                          "(the laboratory's instrument) or customer (the customer's own system)")


def data_origin(dataset, info: CertificateInfo) -> tuple[str, str]:
    """(``laboratory`` or ``customer``, why): ``[conditions] data_origin`` as stated, else a
    reference the data file names as the machine's own encoder read by its control system (an
    EPICS ecmc ``…-Enc<NN>-PosAct``) is the customer's, else the laboratory's instrument."""
    stated = info.conditions.get("data_origin")
    if stated:
        return stated, "stated ([conditions] data_origin)"
    if re.search(r"-Enc\d*-PosAct\b", dataset.metadata.instrument or "", re.IGNORECASE):
        return "customer", (f"the data file's reference {dataset.metadata.instrument} is the "
                            "machine's encoder read by its own control system (EPICS ecmc)")
    return "laboratory", "not stated: the laboratory's instrument assumed"


def positioning_certificate(
    dataset, result, budget, info: CertificateInfo, decisions=(), rule_text: str = "",
    as_found=None,
) -> Report:
    """The certificate of one ISO 230-2 positioning test (a DRAFT when ``info.draft``).

    Parameters
    ----------
    dataset : PositioningDataset
    result : Iso230_2Result
    budget : UncertaintyBudget
        In the result's deviation unit (:mod:`axiscal.standards.iso230_9`).
    info : CertificateInfo
    decisions : sequence of Decision
        From :func:`axiscal.standards.iso14253_1.decide`, one per toleranced parameter.
    rule_text : str
        The decision rule as stated on the certificate.
    as_found : tuple, optional
        ``(dataset, result, budget, decisions)`` of the test before adjustment: its results,
        U and verdicts are reported beside these, the results "as left" (ISO/IEC 17025:2017
        §7.8.4.1 d).

    Returns
    -------
    Report

    Notes
    -----
    Order of the page: verdict, identification, conditions, instruments, uncertainty budget,
    figure, deviations per target, assumptions and deviations, statements, then one block that
    is never split across pages: the results with U and k, the signatory and the end mark (the
    signature always stands with the results it signs). The block is kept under half a page,
    so the page before it is never left more than half empty.
    """
    from axiscal.report.plots import iso230_2_figure
    from axiscal.standards.iso14253_1 import overall

    md = dataset.metadata
    kind = "rotary" if dataset.axis_kind.value == "rotary" else "linear"
    item = item_identity(dataset, info)
    what = f"positioning of the {item['Axis'] if item['Axis'] != NOT_STATED else kind} axis"
    if as_found is not None:
        what += ", as found and as left"
    rep = Report(
        f"DRAFT — not a certificate: calibration of the {what}" if info.draft
        else f"Calibration certificate — {what}",
        subtitle="Accuracy and repeatability of positioning by ISO 230-2:2014; measurement "
        "uncertainty by ISO 230-2:2014 Annex A and ISO/TR 230-9",
        reference=_reference(info),
        letterhead=_letterhead(info),
        paper=info.paper,
    )
    rep.add_html(f"<style>{_CSS}</style>")
    if info.draft:
        rep.add_html(_draft_box(info))
    elif info.replaces:
        rep.add_html(f'<div class="amend">This certificate replaces certificate '
                     f"{_esc(info.replaces)}. Reason: {_esc(info.reason)}"
                     + _changes(info.changes) + "</div>")
    rep.add_html(_verdict_box(overall(decisions), rule_text))
    rep.add_html(_pairs(_identification(md, info, item), "Customer and item calibrated"))
    rep.add_html(_pairs(_conditions(dataset, result, info, budget),
                        "Test conditions (ISO 230-2:2014 §6)"))
    _instruments(rep, info, md)
    _budget_table(rep, budget)
    u = unit_label(result.deviation_unit)
    rep.add_figure(
        iso230_2_figure(result, dataset, _figure_title(item)),
        f"Mean deviation per direction with ±2s bands and every run's readings ({u}).",
    )
    _per_target(rep, result)
    _assumptions(rep, dataset, result, budget, info)
    if as_found is not None:
        f_ds, f_res, f_budget, f_dec = as_found
        rep.add_html(_results(f_res, f_budget, f_dec, info, heading=(
            f"Results as found, before adjustment (test of "
            f"{f_ds.metadata.date or 'date not stated'})")))
        rep.add_html(f'<p class="overall">As found: {_esc(_overall_words(f_dec))}; as left: '
                     f"{_esc(_overall_words(decisions))}.</p>")
    rep.add_html(_statements(info, decisions, rule_text, data_origin(dataset, info)[0]))
    rep.add_html('<div class="closing">' + _results(
        result, budget, decisions, info,
        heading="Results as left, after adjustment" if as_found is not None else "Results")
                 + _signatures(info, info.operator or md.operator) + "</div>")
    return rep


def _reference(info: CertificateInfo) -> str:
    if info.draft:
        return "DRAFT — not a certificate"
    return f"Certificate {info.number}"


def _changes(changes) -> str:
    """Every change an amendment makes, old → new (ISO/IEC 17025:2017 §7.8.8.3)."""
    if not changes:
        return " No field or result changed."
    from axiscal.report.field_labels import field_label, value_text

    def said(v) -> str:                    # a table kept as JSON: its keys and values in words
        if isinstance(v, str) and v.startswith("{"):
            try:
                return value_text(json.loads(v))
            except ValueError:
                pass
        return str(v)

    # each field by the label this certificate prints for it, never a configuration key
    rows = "".join(f"<li>{_esc(field_label(c['what']))}: {_esc(said(c['old']))} → "
                   f"{_esc(said(c['new']))}</li>" for c in changes)
    return f"<br>Changed from the replaced certificate:<ul>{rows}</ul>"


def _draft_box(info: CertificateInfo) -> str:
    items = "".join(f"<li>{_plain(_HINT.sub('', m))}</li>" for m in info.missing) or (
        "<li>certificate number: a certificate is numbered only when the certificate register "
        "issues it</li>")
    return ('<div class="watermark">DRAFT</div><div class="draftbox"><strong>DRAFT — not a '
            "certificate.</strong> It lacks what ISO/IEC 17025:2017 §7.8.2 and §7.8.4 require "
            f"a certificate to carry:<ul>{items}</ul></div>")


def _signatures(info: CertificateInfo, operator: str) -> str:
    """Who calibrated, who prepared the certificate and the authorised signatory who approved
    its issue (ISO/IEC 17025:2017 §7.8.2.1 o)."""
    who = ", ".join(x for x in (info.signatory, info.signatory_role) if x) or NOT_STATED
    prepared = (f"<br>Prepared by: {_esc(info.prepared_by)}" if info.prepared_by
                and info.prepared_by != operator else "")
    return (
        '<div class="signatures"><div>Calibrated by'
        + (f": {_esc(operator)}" if operator else "")
        + f"{prepared}<br>date, signature</div><div>Authorised by: {_esc(who)}"
        + f"<br>{_esc(info.issued or 'date')}, signature</div></div>"
        + (f'<p class="prepared">Prepared by {_esc(info.prepared_by)}; issue approved by '
           f"{_esc(info.signatory)}.</p>" if info.prepared_by and info.signatory
           and not info.draft else "")
        + '<p class="endmark">— End of certificate —</p>'
    )


def _verdict_box(outcome, rule_text: str) -> str:
    if outcome is None:
        return (
            '<div class="verdict zone">No tolerance given: values and uncertainties are '
            "reported without a statement of conformity.</div>"
        )
    cls = {"conformance proven": "ok", "non-conformance proven": "bad"}.get(outcome.value, "zone")
    words = {
        "ok": "CONFORMS — conformance proven for every toleranced parameter",
        "bad": "DOES NOT CONFORM — non-conformance proven for at least one parameter",
        "zone": "NOT PROVEN — at least one parameter lies in the uncertainty zone",
    }[cls]
    return f'<div class="verdict {cls}">Overall verdict: {words}</div><p>{_esc(rule_text)}</p>'


def item_identity(dataset, info: CertificateInfo) -> dict[str, str]:
    """The one identity of the item calibrated (ISO/IEC 17025:2017 §7.8.2.1 c, g): machine
    (maker and model with the name the shop gives it in brackets, else that name or the data
    file's), serial number, axis (the
    job's ``[machine] axis``, else the history's as corrected there, else the data file's) and
    location; the certificate's identification,
    its title and its figure all print these."""
    m, md = info.machine, dataset.metadata
    made = " ".join(str(x) for x in (m.get("maker"), m.get("model")) if x)
    name = str(m.get("name") or "").strip()
    if made and name and name not in made:       # the shop's own name of it, as in the history
        made = f"{made} ({name})"
    return {
        "Machine": made or name or md.machine or NOT_STATED,
        "Serial number": str(m.get("serial") or NOT_STATED),
        "Location": str(m.get("location") or info.conditions.get("location") or NOT_STATED),
        "Axis": str(m.get("axis") or md.axis or NOT_STATED),
    }


def _figure_title(item: dict[str, str]) -> str:
    who = ", ".join(x for x in (
        item["Machine"], item["Serial number"] != NOT_STATED and f"serial {item['Serial number']}",
        item["Axis"] != NOT_STATED and f"axis {item['Axis']}") if x and x != NOT_STATED)
    return "Positioning deviation, ISO 230-2:2014" + (f" — {who}" if who else "")


def _identification(md, info: CertificateInfo, item: dict[str, str] | None = None
                    ) -> dict[str, Any]:
    c = info.customer
    item = item or {"Machine": md.machine or NOT_STATED, "Serial number": NOT_STATED,
                    "Location": NOT_STATED, "Axis": md.axis or NOT_STATED}
    return {
        "Certificate number": info.number or ("none: a draft is not numbered" if info.draft
                                              else NOT_STATED),
        "Date of issue": info.issued or NOT_STATED,
        "Customer": c.get("name") or NOT_STATED,
        "Customer address": _lines(c.get("address"), ", "),
        "Customer reference": c.get("reference"),
        **item,
    }


def _conditions(dataset, result, info: CertificateInfo, budget=None) -> dict[str, Any]:
    from axiscal.report.certificate_content import calibration_date, measured_temperatures

    md, env, cond = dataset.metadata, dataset.metadata.environment, info.conditions
    tu = unit_label(result.target_unit)
    cycle = cond.get("cycle") or (
        f"{'bidirectional' if result.bidirectional else 'unidirectional'}, {result.n_runs} runs, "
        f"{result.targets.size} targets from {target_label(result.targets[0])} to "
        f"{target_label(result.targets[-1])}{'' if tu == '°' else ' '}{tu}"   # 360°, 800 mm
    )
    air, mat = measured_temperatures(dataset, info)
    if env.material_temperature:
        mat = ", ".join(f"{t:g}" for t in env.material_temperature)
    alpha = env.expansion_coefficient
    alpha = NOT_STATED if alpha is None else f"{alpha * 1e6:g}"
    used = {i.name: i for i in getattr(budget, "inputs", ())}.get("expansion_coefficient")
    if alpha == NOT_STATED and used is not None:       # the α the budget used, and whence
        alpha = f"{used.value * 1e6:g} ({'assumed: ' if used.assumed else ''}{used.rule})"
    if dataset.axis_kind.value == "rotary" and alpha == NOT_STATED:  # angles do not expand
        alpha = "not applicable (rotary axis)"
    pressure = env.pressure if env.pressure is not None else cond.get("air_pressure")
    humidity = env.humidity if env.humidity is not None else cond.get("humidity")
    ref20 = cond.get("referred_to_20")
    origin, why = data_origin(dataset, info)
    linear = dataset.axis_kind.value != "rotary"
    return {
        "Date of test": calibration_date(dataset, info) or "not stated in the data file",
        "Location of the measuring line": cond.get("measuring_line") or NOT_STATED,
        "Air temperature (°C)": NOT_STATED if air is None else f"{air:g}",
        "Material temperature (°C)": NOT_STATED if mat is None else (
            mat if isinstance(mat, str) else f"{mat:g}"),
        "Expansion coefficient (µm/(m·K))": alpha,
        "Air pressure (Pa)": NOT_STATED if pressure is None else f"{pressure:g}",
        "Humidity (%RH)": NOT_STATED if humidity is None else f"{humidity:g}",
        "Material temperature sensors": (cond.get("material_sensors") or NOT_STATED)
        if linear else None,
        "Deviations referred to 20 °C (ISO 1)": (
            NOT_STATED if ref20 is None else "yes" if ref20 else
            "no: at the material temperature of the test") if linear else None,
        "Readings taken by": ("the laboratory's instrument" if origin == "laboratory" else
                              "the customer's own system (data supplied by the customer)")
        + ("" if why.startswith("stated") else f"; {why}"),
        "Feed": cond.get("feed") or NOT_STATED,
        "Dwell": cond.get("dwell") or NOT_STATED,
        "Test cycle": cycle,
        "Operator": info.operator or md.operator or NOT_STATED,
    }


def _overall_words(decisions) -> str:
    from axiscal.standards.iso14253_1 import overall

    o = overall(decisions)
    return o.value if o else "no tolerance given"


def _results(result, budget, decisions, info: CertificateInfo, heading: str = "Results") -> str:
    """The results table with U and k: the first part of the block the signature closes. U is
    never printed as zero: two significant digits, rounded up (JCGM 100:2008 §7.2.6); each value
    to the last digit of its U (ILAC-P14:09/2020 §5.3); the verdicts were decided with the U
    printed (:meth:`~axiscal.standards.iso230_9.UncertaintyBudget.stated`)."""
    from axiscal.standards.iso230_9 import format_uncertainty

    u = unit_label(result.deviation_unit)
    by = {d.parameter: d for d in decisions}
    state = {
        "PASS": '<span class="ok">PASS</span>',
        "FAIL": '<span class="bad">FAIL</span>',
        "ZONE": '<span class="zone">ZONE</span>',
    }
    rows = []
    for name, v in result.parameters().items():
        if v is None:
            continue
        d = by.get(name)
        mark = " *" if name in info.customer_supplied else ""
        tol = "" if d is None else f"{d.upper:g}{mark}"
        verdict = "" if d is None or d.outcome is None else state[d.outcome.short]
        rows.append(
            f"<tr><td>{_PARAM_LABEL[name]}</td><td>{budget.value_text(name, v)}</td>"
            f"<td>{format_uncertainty(budget.U(name))}</td><td>{tol}</td><td>{verdict}</td>"
            f"<td>{_plain(_PARAM_MEANING[name])}</td></tr>"
        )
    for arrow, v in (("↑", result.closure_up), ("↓", result.closure_down)):
        if v is not None:   # a full turn: 0° and 360° stay two targets; their difference
            rows.append(f"<tr><td>Closure {arrow}</td><td>{_cell(v, 2)}</td><td>—</td><td></td>"
                        "<td></td><td>Mean deviation at 360° minus that at 0° (full turn: the "
                        "two stay separate targets)</td></tr>")
    supplied = " * Supplied by the customer (job file)." if info.customer_supplied else ""
    return (
        f'<h2>{_esc(heading)}</h2><table class="results"><thead><tr><th>Parameter</th><th>Value '
        f"({u})</th><th>U, k = {budget.k:g} ({u})</th><th>Tolerance ({u})</th><th>Verdict</th>"
        f"<th>Meaning (ISO 230-2:2014 clause 3)</th></tr></thead><tbody>{''.join(rows)}"
        f"</tbody><caption>U: expanded uncertainty, coverage factor k = {budget.k:g} (about "
        f"95 % coverage), ISO 230-2:2014 Annex A. Verdict: PASS = conformance proven, FAIL = "
        f"non-conformance proven, ZONE = in the uncertainty zone (neither proven).{supplied}"
        "</caption></table>"
    )


def _statements(info: CertificateInfo, decisions, rule_text: str,
                origin: str = "laboratory") -> str:
    """The statements ISO/IEC 17025:2017 §7.8.2.1 and §7.8.4.1 ask a certificate to make."""
    certs = [f"{i.name} (certificate {i.certificate}, due {i.due})" for i in info.instruments
             if i.certificate]
    trace = ("The measurements are metrologically traceable to the SI through the calibration "
             "certificates of the instruments used: " + "; ".join(certs) + "."
             if certs else "Metrological traceability: not stated (no instrument certificates).")
    items = [
        trace,
        "The results relate only to the item calibrated.",
        "This certificate shall not be reproduced except in full without the written approval "
        "of the laboratory.",
    ]
    if origin == "customer":
        items.append("The readings were taken by the customer's own control system and supplied "
                     "by the customer (ISO/IEC 17025:2017 §7.8.2.2): the laboratory evaluated "
                     "them and is not responsible for their measurement.")
    if decisions:
        spec = info.specification or NOT_STATED
        items.append(f"Statement of conformity against the specification: {spec}"
                     + (" (supplied by the customer)" if info.customer_supplied else "")
                     + f". {rule_text}")
    lis = "".join(f"<li>{_esc(t)}</li>" for t in items)
    return f'<h2>Statements</h2><ul class="statements">{lis}</ul>'


def _assumptions(rep: Report, dataset, result, budget, info: CertificateInfo) -> None:
    """What the evaluation assumed or could not follow, in plain words (not tool warnings):
    each assumed input of the budget with its rule, the budget's other statements (runs behind
    R and B, E_VE declared ...), the result's warnings and the test conditions not stated."""
    notes = [f"{i.label}: {i.value_text} assumed, not given ({i.rule})"
             for i in getattr(budget, "assumed", ()) if i.value is not None]
    missing = set(getattr(budget, "missing_inputs", ()))
    notes += [customer_words(n) for n in budget.notes
              if not n.startswith("assumed:") and not (missing and "not given" in n)]
    notes += list(result.warnings)
    from axiscal.io.epics import NOTES_START

    if dataset.metadata.notes.startswith(NOTES_START):    # what the raw log's reader assumed
        notes.append(dataset.metadata.notes)
    cond = info.conditions
    for key, what in (("measuring_line", "The location of the measuring line"),
                      ("feed", "The feed"), ("dwell", "The dwell time")):
        if not cond.get(key):
            notes.append(f"{what} was not stated (ISO 230-2:2014 §6).")
    rep.add_heading("Assumptions and deviations")
    if not notes:
        rep.add_text("None: the test followed ISO 230-2:2014 and every input of the "
                     "uncertainty budget was measured or declared.")
        return
    lis = "".join(f"<li>{_plain(_sentence(n))}</li>" for n in notes)
    rep.add_html(f'<ul class="assumptions">{lis}</ul>')


#: Where a missing item is set ("([customer] address)"): said in the terminal, not on the page.
_HINT = re.compile(r"\s*\([^()]*\[[^()]*\)|;\s*give \[[^;)]*")
#: How a tool sets an input ("; set with [uncertainty] beam_offset"): not for a customer.
_SET_WITH = re.compile(r";?\s*(?:set|declare it) with [^;)]*")
#: ... said in words where it names the input: "set with [squareness_uncertainty] e_ve in the
#: user configuration (axiscal config)".
_SET_WITH_KEY = re.compile(r"(;?\s*)(set|declare it) with \[(\w+)\] (\w+)"
                           r"(?:[^;()]|\([^()]*\))*")


def customer_words(note: str) -> str:
    """A budget's note for a customer's certificate: how an input is set said in words (the
    laboratory's uncertainty input, by its label), never a configuration file's table, key or
    a command's option.

    >>> customer_words("assumed: E_VE 0 µm; set with [squareness_uncertainty] e_ve in the "
    ...                "user configuration (axiscal config)")
    "assumed: E_VE 0 µm; set as the laboratory's uncertainty input E_VE (environmental variation)"
    >>> customer_words("E_VE not given (measure it by a drift check or declare it with "
    ...                "[uncertainty] e_ve in the job or configuration file, or --uncertainty "
    ...                "e_ve=VALUE)")
    "E_VE not given (measure it by a drift check or declare it as the laboratory's uncertainty input E_VE (environmental variation))"
    """
    from axiscal.report.field_labels import field_label

    def words(m) -> str:
        label = field_label(f"[{m.group(3)}] {m.group(4)}").removeprefix("Uncertainty input: ")
        return (f"{m.group(1)}{'set' if m.group(2) == 'set' else 'declare it'} as the "
                f"laboratory's uncertainty input {label}")

    return _SET_WITH.sub("", _SET_WITH_KEY.sub(words, str(note)))


def _sentence(text: str) -> str:
    t = str(text).strip()
    return (t[:1].upper() + t[1:] + ("" if t.endswith(".") else ".")) if t else t


def _instruments(rep: Report, info: CertificateInfo, md) -> None:
    rep.add_heading("Instruments")
    rows = [
        [i.name, i.serial or NOT_STATED, i.certificate or NOT_STATED, i.due or NOT_STATED]
        for i in info.instruments
    ]
    if not rows:
        rows = [[getattr(md, "instrument", "") or NOT_STATED, NOT_STATED, NOT_STATED,
                 NOT_STATED]]
    rep.add_table(
        ["Instrument", "Serial number", "Calibration certificate", "Calibration due"],
        rows,
        css_class="text",
    )


def _budget_table(rep: Report, budget) -> None:
    u = unit_label(budget.unit)
    rep.add_heading("Measurement uncertainty")
    rows = "".join(
        f"<tr><td>{_plain(c.name)}</td><td>{_plain(c.quantity)}</td><td>{_cell(c.u, 4)}</td>"
        f"<td>{_esc(c.distribution)}</td><td>{_plain(c.basis)}</td><td>{_plain(c.clause)}</td>"
        "</tr>" for c in budget.contributors)
    rep.add_html(
        f'<table class="budget"><thead><tr><th>Symbol</th><th>Contribution</th><th>u ({u})'
        "</th><th>Distribution</th><th>Input</th><th>Source</th></tr></thead><tbody>"
        f"{rows}</tbody></table>")
    rep.add_html(_plain(
        f"<p>Combined by the law of propagation of uncertainty (JCGM 100:2008, uncorrelated "
        f"inputs) with {_esc(budget.method)}; U = k·u_c with k = {budget.k:g}. Length-"
        "proportional contributions act on A, E and M; R and B carry the reading "
        "resolution, E_VE and the sampling uncertainty of the runs they are formed from "
        "(JCGM 100:2008 Annex E.4.3). U is never stated below the laboratory's CMC "
        "(ILAC-P14:09/2020 §5.4).</p>", escaped=True))


def _per_target(rep: Report, result) -> None:
    u = unit_label(result.deviation_unit)
    rep.add_heading("Deviations per target")
    headers = [
        f"Target ({unit_label(result.target_unit)})",
        "n↑",
        *(f"{h} ({u})" for h in ("x̄↑", "s↑")),
        "n↓",
        *(f"{h} ({u})" for h in ("x̄↓", "s↓", "x̄", "Bᵢ", "Rᵢ")),
    ]
    rows = [
        [
            target_label(r["target"]),
            r["n_up"],
            r["mean_up"],
            r["s_up"],
            r["n_down"],
            r["mean_down"],
            r["s_down"],
            r["mean_bi"],
            r["reversal"],
            r["R_i"],
        ]
        for r in result.target_table()
    ]
    rep.add_table(
        headers,
        rows,
        caption=f"Deviation = actual − target in {u}; n = readings used "
        "(ISO 230-2:2014 clause 3).",
        digits=2,
        css_class="targets",
    )


def _letterhead(info: CertificateInfo) -> str:
    c = info.company
    if not (c or info.logo):
        return ""
    logo = f'<img src="{_esc(info.logo)}" alt="logo">' if info.logo else ""
    acc = f'<div class="address">{_esc(c["accreditation"])}</div>' if c.get("accreditation") else ""
    return (
        f'<div class="letterhead"><div><div class="company">{_esc(c.get("name", ""))}</div>'
        f'<div class="address">{_esc(_lines(c.get("address")) or "")}</div>{acc}</div>'
        f"{logo}</div>"
    )


def _pairs(items: dict[str, Any], caption: str) -> str:
    """A two-column block of labelled values (two label-value pairs a row; long text wraps
    inside its cell)."""
    cells = [(k, v) for k, v in items.items() if v not in (None, "")]
    rows = []
    for i in range(0, len(cells), 2):
        pair = cells[i:i + 2] + ([("", "")] if i + 1 >= len(cells) else [])
        rows.append("<tr>" + "".join(f'<td class="k">{_esc(k)}</td><td>{_esc(v)}</td>'
                                     for k, v in pair) + "</tr>")
    return (f'<table class="pairs"><caption>{_esc(caption)}</caption><colgroup><col class="k">'
            '<col class="v"><col class="k"><col class="v"></colgroup><tbody>'
            f"{''.join(rows)}</tbody></table>")


def _plain(text: Any, escaped: bool = False) -> str:
    """Escaped text with a symbol's subscript written as one (u_DEVICE -> u<sub>DEVICE</sub>):
    a certificate shows no code identifiers."""
    t = str(text) if escaped else _esc(text)
    return _SUBSCRIPT.sub(r"\1<sub>\2</sub>", t)


_SUBSCRIPT = re.compile(r"(?<![A-Za-z0-9])([A-Za-zα])_([A-Za-z0-9,]+)")
_CSS = resources.files("axiscal.report").joinpath("templates/certificate.css").read_text("utf-8")


def _lines(v: Any, sep: str = "\n") -> str | None:
    if v is None:
        return None
    return sep.join(str(x) for x in v) if isinstance(v, (list, tuple)) else str(v)


def _esc(v: Any) -> str:
    return _html.escape(str(v))
