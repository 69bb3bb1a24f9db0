"""Calibration certificate of a positioning test: ISO 230-2 result, ISO 230-9 uncertainty,
ISO 14253-1 decisions, with letterhead, customer, machine, test conditions and instruments.

:func:`positioning_certificate` is a pure function of (dataset, result, uncertainty budget,
certificate information, tolerances): it reads no file and no clock, so a calibration history can
store its inputs and regenerate the same certificate. :func:`certificate_info` turns the merged
user configuration and job file (see :mod:`axiscal.io.user_config`) into
:class:`CertificateInfo`. The page is an ordinary :class:`~axiscal.report.html.Report`, so it is
written as HTML or, with a ``.pdf`` name, as a PDF from the same template.

A certificate shows no simulation truth and no internal references: documents are cited by their
title and clause.
"""

from __future__ import annotations

import html as _html
from dataclasses import dataclass, field
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
]

NOT_STATED = "not stated"
_SECTIONS = {
    "company": {"name", "address", "logo", "accreditation"},
    "operator": {"name"},
    "customer": {"name", "address", "reference"},
    "machine": {"maker", "model", "serial", "location"},
    "conditions": {"date", "measuring_line", "feed", "dwell", "cycle", "location"},
    "certificate": {"paper", "rule", "number", "number_prefix", "issued", "approver"},
    "instrument": {"name", "serial", "certificate", "due"},
    "uncertainty": None,  # checked by the budget's own inputs
    "tolerance": None,  # NAME = value, checked against the standard's parameters
    "squareness_uncertainty": None,  # read by the squareness commands
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

    ``logo`` is a ``data:`` URI (read by the I/O layer), ``issued`` the date of issue.
    """

    company: Mapping[str, Any] = field(default_factory=dict)
    operator: str = ""
    customer: Mapping[str, Any] = field(default_factory=dict)
    machine: Mapping[str, Any] = field(default_factory=dict)
    conditions: Mapping[str, Any] = field(default_factory=dict)
    instruments: tuple[Instrument, ...] = ()
    number: str = ""
    issued: str = ""
    approver: str = ""
    paper: str = "A4"
    logo: str = ""


def certificate_info(
    config: Mapping[str, Any], number: str = "", issued: str = "", logo: str = ""
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
        approver=str(cert.get("approver", "")),
        paper=paper,
        logo=logo,
    )


def positioning_certificate(
    dataset, result, budget, info: CertificateInfo, decisions=(), rule_text: str = ""
) -> Report:
    """The certificate of one ISO 230-2 positioning test.

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

    Returns
    -------
    Report
    """
    from axiscal.report.plots import iso230_2_figure
    from axiscal.standards.iso14253_1 import overall

    md = dataset.metadata
    kind = "rotary" if dataset.axis_kind.value == "rotary" else "linear"
    rep = Report(
        f"Calibration certificate — positioning of the {md.axis or kind} axis",
        subtitle="Accuracy and repeatability of positioning by ISO 230-2:2014; measurement "
        "uncertainty by ISO 230-2:2014 Annex A and ISO/TR 230-9",
        reference=f"Certificate {info.number}" if info.number else "",
        letterhead=_letterhead(info),
        paper=info.paper,
    )
    rep.add_html(_verdict_box(overall(decisions), rule_text))
    rep.add_html(
        '<div class="grid2">'
        + _kv(_identification(md, info), "Customer and machine")
        + _kv(_conditions(dataset, result, info), "Test conditions (ISO 230-2:2014 §6)")
        + "</div>"
    )
    _results(rep, result, budget, decisions, rule_text)
    u = unit_label(result.deviation_unit)
    rep.add_figure(
        iso230_2_figure(result, dataset),
        f"Mean deviation per direction with ±2s bands and every run's readings ({u}).",
    )
    rep.add_warnings(result.warnings)
    _instruments(rep, info, md)
    _budget_table(rep, budget)
    _per_target(rep, result)
    rep.add_html(
        '<div class="signatures"><div>Calibrated by'
        + (f": {_esc(info.operator)}" if info.operator else "")
        + "<br>date, signature</div><div>Approved by"
        + (f": {_esc(info.approver)}" if info.approver else "")
        + "<br>date, signature</div></div>"
    )
    return rep


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


def _identification(md, info: CertificateInfo) -> dict[str, Any]:
    c, m = info.customer, info.machine
    return {
        "Certificate number": info.number or NOT_STATED,
        "Date of issue": info.issued or NOT_STATED,
        "Customer": c.get("name") or NOT_STATED,
        "Customer address": _lines(c.get("address"), ", "),
        "Customer reference": c.get("reference"),
        "Machine": " ".join(str(x) for x in (m.get("maker"), m.get("model")) if x)
        or md.machine
        or NOT_STATED,
        "Serial number": m.get("serial") or NOT_STATED,
        "Location": m.get("location") or info.conditions.get("location") or NOT_STATED,
        "Axis": md.axis or NOT_STATED,
    }


def _conditions(dataset, result, info: CertificateInfo) -> dict[str, Any]:
    md, env, cond = dataset.metadata, dataset.metadata.environment, info.conditions
    date = md.date or cond.get("date") or "not stated in the data file"
    tu = unit_label(result.target_unit)
    cycle = cond.get("cycle") or (
        f"{'bidirectional' if result.bidirectional else 'unidirectional'}, {result.n_runs} runs, "
        f"{result.targets.size} targets {target_label(result.targets[0])}…"
        f"{target_label(result.targets[-1])} {tu}"
    )
    mat = ", ".join(f"{t:g}" for t in env.material_temperature) or NOT_STATED
    alpha = env.expansion_coefficient
    alpha = NOT_STATED if alpha is None else f"{alpha * 1e6:g}"
    if dataset.axis_kind.value == "rotary":  # angles do not expand
        alpha = NOT_STATED if env.expansion_coefficient is None else alpha
        alpha = "not applicable (rotary axis)" if alpha == NOT_STATED else alpha
    return {
        "Date of test": date,
        "Location of the measuring line": cond.get("measuring_line") or NOT_STATED,
        "Air temperature [°C]": (
            NOT_STATED if env.air_temperature is None else f"{env.air_temperature:g}"
        ),
        "Material temperature [°C]": mat,
        "Expansion coefficient [µm/(m·K)]": alpha,
        "Air pressure [Pa]": None if env.pressure is None else f"{env.pressure:g}",
        "Humidity [%RH]": None if env.humidity is None else f"{env.humidity:g}",
        "Feed": cond.get("feed") or NOT_STATED,
        "Dwell": cond.get("dwell") or NOT_STATED,
        "Test cycle": cycle,
        "Operator": info.operator or md.operator or NOT_STATED,
    }


def _results(rep: Report, result, budget, decisions, rule_text: str) -> None:
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
        tol = "" if d is None else f"{d.upper:g}"
        verdict = "" if d is None or d.outcome is None else state[d.outcome.short]
        U = budget.U(name)
        rows.append(
            f"<tr><td>{_PARAM_LABEL[name]}</td><td>{_cell(v, 2)}</td>"
            f"<td>{'—' if U is None else f'{U:.2f}'}</td><td>{tol}</td><td>{verdict}</td>"
            f"<td>{_esc(_PARAM_MEANING[name])}</td></tr>"
        )
    for arrow, v in (("↑", result.closure_up), ("↓", result.closure_down)):
        if v is not None:   # a full turn: 0° and 360° stay two targets; their difference
            rows.append(f"<tr><td>Closure {arrow}</td><td>{_cell(v, 2)}</td><td>—</td><td></td>"
                        "<td></td><td>Mean deviation at 360° minus that at 0° (full turn: the "
                        "two stay separate targets)</td></tr>")
    rep.add_heading("Results")
    rep.add_html(
        f'<table class="results"><thead><tr><th>Parameter</th><th>Value [{u}]</th>'
        f"<th>U (k = 2) [{u}]</th><th>Tolerance [{u}]</th><th>Verdict</th><th>Meaning "
        f"(ISO 230-2:2014 clause 3)</th></tr></thead><tbody>{''.join(rows)}</tbody><caption>U: "
        f"expanded uncertainty, coverage factor k = 2 (about 95 % coverage), ISO 230-2:2014 "
        f"Annex A. Verdict: PASS = conformance proven, FAIL = non-conformance proven, ZONE = in "
        f"the uncertainty zone (neither proven).</caption></table>"
    )


def _instruments(rep: Report, info: CertificateInfo, md) -> None:
    rep.add_heading("Instruments")
    rows = [
        [i.name, i.serial or NOT_STATED, i.certificate or NOT_STATED, i.due or NOT_STATED]
        for i in info.instruments
    ]
    if not rows:
        rows = [[md.instrument or NOT_STATED, NOT_STATED, NOT_STATED, NOT_STATED]]
    rep.add_table(
        ["Instrument", "Serial number", "Calibration certificate", "Calibration due"],
        rows,
        css_class="text",
    )


def _budget_table(rep: Report, budget) -> None:
    u = unit_label(budget.unit)
    rep.add_heading("Measurement uncertainty")
    rows = [
        [c.name, c.quantity, c.u, c.distribution, c.basis, c.clause] for c in budget.contributors
    ]
    rep.add_table(
        ["Symbol", "Contribution", f"u [{u}]", "Distribution", "Input", "Source"],
        rows,
        digits=4,
        css_class="budget",
    )
    rep.add_text(
        f"Combined by the law of propagation of uncertainty (JCGM 100:2008, uncorrelated "
        f"inputs) with {budget.method}; U = k·u_c with k = {budget.k:g}. Length-"
        "proportional contributions act on A, E and M; R and B carry the reading "
        "resolution and E_VE."
    )
    rep.add_warnings(budget.notes)


def _per_target(rep: Report, result) -> None:
    u = unit_label(result.deviation_unit)
    rep.add_heading("Deviations per target")
    headers = [
        f"Target [{unit_label(result.target_unit)}]",
        "n↑",
        *(f"{h} [{u}]" for h in ("x̄↑", "s↑")),
        "n↓",
        *(f"{h} [{u}]" for h in ("x̄↓", "s↓", "x̄", "B_i", "R_i")),
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


def _kv(items: dict[str, Any], caption: str) -> str:
    rows = "".join(
        f"<tr><td>{_esc(k)}</td><td>{_esc(v)}</td></tr>"
        for k, v in items.items()
        if v not in (None, "")
    )
    return (
        f'<table class="kv meta"><caption>{_esc(caption)}</caption><thead><tr><th></th><th>'
        f"</th></tr></thead><tbody>{rows}</tbody></table>"
    )


def _lines(v: Any, sep: str = "\n") -> str | None:
    if v is None:
        return None
    return sep.join(str(x) for x in v) if isinstance(v, (list, tuple)) else str(v)


def _esc(v: Any) -> str:
    return _html.escape(str(v))
