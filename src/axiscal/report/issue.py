"""Issuing a calibration certificate: configuration, budget, decisions, the mandatory content, a
number from the certificate register, the document kept with the test.

This is the library work behind ``axiscal iso230-2 --report``, ``axiscal certificate`` and the
workbench's certificate: the front ends parse and render, they call :func:`write_certificate`
and :func:`reissue_certificate`.

A certificate is *issued* only when every mandatory item of ISO/IEC 17025:2017 §7.8.2 and §7.8.4
is there (:func:`axiscal.report.certificate_content.missing_items`) and a register (a calibration
history, :mod:`axiscal.store`) numbers it; otherwise the page is written as a DRAFT that names
each missing item and takes no number. An issued certificate's number comes from the laboratory's
pattern (``[certificate] number_pattern``, default ``{lab}-{year}-{counter:05d}``: ``{lab}`` the
``[company] code``, ``{year}`` the year of issue, ``{counter}`` the register's next counter for
the laboratory and year), never from the data alone; the issued bytes and their SHA-256 are kept
with the stored test. An amendment (§7.8.8) is a new number that replaces the old one, with a
reason; the old one is kept and marked superseded.
"""

from __future__ import annotations

import dataclasses
import datetime as _dt
import json
from pathlib import Path
from typing import Any

from axiscal.errors import ConfigError, InputError

__all__ = ["load_config", "budget_for", "decisions_for", "write_certificate",
           "reissue_certificate", "CertificateOutcome", "number_format", "SignOff", "sign_off",
           "signatories", "authorisation", "amendment_changes", "write_as_found_as_left",
           "amendment_inputs"]


@dataclasses.dataclass(frozen=True)
class CertificateOutcome:
    """What :func:`write_certificate` wrote: an issued certificate (``record`` from the register)
    or a DRAFT (``missing`` names each mandatory item not given)."""

    path: Path
    decisions: tuple
    missing: tuple[str, ...]
    number: str = ""
    record: Any = None

    @property
    def draft(self) -> bool:
        return self.record is None


def load_config(job: Path | None) -> dict[str, Any]:
    """The user configuration with the job file on top."""
    from axiscal.io.user_config import load_job, load_user_config, merge

    cfg = load_user_config()
    return merge(cfg, load_job(job)) if job is not None else cfg


def budget_for(dataset, result, cfg: dict):
    """The ISO 230-2:2014 Annex A budget with the configuration's inputs, resolved as every
    path resolves them (:func:`axiscal.store.kinds.inputs_from_config`: a material temperature
    the job's ``[conditions]`` states is the budget's too) and made by the one budget call
    (:func:`axiscal.store.kinds.budget_of`)."""
    from axiscal.store.kinds import budget_of, inputs_from_config

    return budget_of("iso230-2", dataset, result, inputs_from_config("iso230-2", cfg, dataset))


def decisions_for(values, budget, tolerances: dict, cfg: dict, rule: str | None):
    """Tolerances of the command line over those of the configuration, decided by the rule."""
    from axiscal.standards.iso14253_1 import RULE_TEXT, _rule, decide_all

    tol = {**cfg.get("tolerance", {}), **tolerances}
    r = _rule(rule or cfg.get("certificate", {}).get("rule", "iso14253-1"))
    return (decide_all(values, budget, tol, r) if tol else ()), r, RULE_TEXT[r]


@dataclasses.dataclass(frozen=True)
class SignOff:
    """The ISO 14253-1 verdict of one positioning test against its tolerances.

    Attributes
    ----------
    budget : UncertaintyBudget
        ISO 230-2:2014 Annex A budget with the configuration's (and job's) inputs.
    decisions : tuple of Decision
        One per toleranced parameter, in the result's order.
    overall : Outcome or None
        :func:`axiscal.standards.iso14253_1.overall` of the decisions (None: no tolerance).
    rule_text : str
        How the rule is stated on a certificate.
    warnings : tuple of str
        Tolerances whose conformance can never be proven (ISO 14253-1:2017 §5.2,
        :func:`axiscal.standards.iso14253_1.unprovable`).
    """

    budget: Any
    decisions: tuple
    overall: Any
    rule_text: str
    warnings: tuple[str, ...]

    def __str__(self) -> str:
        lines = [str(d) for d in self.decisions] + list(self.warnings)
        verdict = self.overall.value if self.overall else "no tolerance given"
        return "\n".join([f"overall: {verdict} ({self.rule_text})", *lines])


def sign_off(dataset, result, cfg: dict, tolerances: dict | None = None,
             rule: str | None = None) -> SignOff:
    """Budget and ISO 14253-1 decisions of a positioning test, as ``axiscal iso230-2
    --tolerance`` prints them and :func:`write_certificate` states them.

    Parameters
    ----------
    dataset, result : PositioningDataset, Iso230_2Result
    cfg : dict
        The configuration with the job on top (its ``[tolerance]`` and ``[conditions]``).
    tolerances : dict of str to float, deviation unit
        Over the configuration's ``[tolerance]`` (as ``--tolerance NAME=VALUE``).
    rule : str, optional
        ``iso14253-1`` (default, or the configuration's ``[certificate] rule``) or ``simple``.

    Raises
    ------
    InputError
        A tolerance names no parameter of the result, or is not a positive number.

    Examples
    --------
    >>> from axiscal.datasets import PositioningDataset
    >>> from axiscal.standards.iso230_2 import evaluate
    >>> ds = PositioningDataset.from_arrays("linear", [0, 100, 200], [[1, 2], [0, 1], [2, 2]],
    ...                                     [[3, 3], [2, 1], [4, 5]], "mm", "um")
    >>> so = sign_off(ds, evaluate(ds), {"uncertainty": {"e_ve": 0.3}}, {"E": 10})
    >>> so.overall.value, str(so.decisions[0])
    ('conformance proven', 'E: 4 ± 1.2 (≤ 10) conformance proven')
    """
    from axiscal.standards.iso230_2 import check_tolerances
    from axiscal.standards.iso14253_1 import overall, unprovable

    check_tolerances(result, {**cfg.get("tolerance", {}), **(tolerances or {})})
    budget = budget_for(dataset, result, cfg)
    decisions, _, text = decisions_for(result.parameters(), budget, tolerances or {}, cfg, rule)
    unit = {"um": "µm"}.get(result.deviation_unit, result.deviation_unit)
    return SignOff(budget, tuple(decisions), overall(decisions), text,
                   tuple(unprovable(decisions, unit)))


def number_format(cfg: dict, issued: str):
    """(laboratory code, series, counter -> number) of the configuration's numbering.

    The register is keyed by the laboratory's code (``[company] code``, else the initials of its
    name), never by the name: the same laboratory written another way keeps one counter.
    A ``[certificate] number`` is used as it is (the register refuses it a second time); else
    ``number_pattern`` (``number_prefix`` of earlier versions means ``PREFIX{year}-{counter:05d}``).
    """
    from axiscal.io.user_config import DEFAULT_NUMBER_PATTERN

    company, cert = cfg.get("company", {}), cfg.get("certificate", {})
    lab = str(company.get("name", "")).strip()
    code = str(company.get("code") or "".join(w[0] for w in lab.split() if w[:1].isalnum())
               or "LAB").upper()
    year = issued[:4]
    if cert.get("number"):
        fixed = str(cert["number"])
        return code, f"{code}|fixed", lambda counter: fixed
    pattern = str(cert.get("number_pattern") or (
        f"{cert['number_prefix']}{{year}}-{{counter:05d}}" if cert.get("number_prefix")
        else DEFAULT_NUMBER_PATTERN))
    try:
        pattern.format(lab=code, year=year, counter=1)
    except (KeyError, ValueError, IndexError) as exc:
        raise ConfigError(f"[certificate] number_pattern {pattern!r}: {exc}; use {{lab}}, "
                          "{year} and {counter}") from None
    if "{counter" not in pattern:
        raise ConfigError(f"[certificate] number_pattern {pattern!r} has no {{counter}}: every "
                          "number would be the same")
    series = f"{code}|{year}" if "{year" in pattern else code
    return code, series, lambda counter: pattern.format(lab=code, year=year, counter=counter)


def write_certificate(path, dataset, result, cfg: dict, data_bytes: bytes, tolerances=None,
                      rule: str | None = None, paper: str | None = None, job: Path | None = None,
                      *, store=None, filename: str = "data.csv", today: str | None = None,
                      config_note: str = "", customer_supplied=None, logo: str | None = None,
                      replaces: str = "", reason: str = "", prepared_by: str = "",
                      approved_by: str = "", changes=(), as_found=None,
                      draft_document: bool = True, preview: bool = False
                      ) -> CertificateOutcome:
    """Budget, decisions and certificate of one positioning test, written to ``path``
    (.html or .pdf): issued through ``store``'s register when complete, else a DRAFT.

    Parameters
    ----------
    cfg : dict
        The configuration (user file merged with the job, or the demo's own).
    data_bytes, filename : bytes, str
        The data file as it came: stored with the certificate in the history.
    job : Path, optional
        The job file: its tolerances are marked as supplied by the customer, its logo path is
        relative to it.
    store : Store or callable returning one, optional
        The calibration history whose register numbers the certificate (a callable is called
        only when the certificate is complete); without one the page is a DRAFT (a number is
        issued only by the register).
    today : str, optional
        Date of issue (``YYYY-MM-DD``), default today; ``[certificate] issued`` overrides.
    config_note : str
        Why the user configuration identifies no laboratory (:func:`~axiscal.io.user_config.
        config_problem`), named among the missing items.
    as_found : tuple, optional
        ``(dataset, result, test_id)`` of the stored test before adjustment: the certificate
        reports both (ISO/IEC 17025:2017 §7.8.4.1 d), this test "as left"
        (:func:`write_as_found_as_left`).
    prepared_by, approved_by : str
        Who prepared the certificate (default ``[operator] name``) and the authorised signatory
        who approves its issue (default ``[certificate] signatory``; the workbench passes the
        signed-in user). :func:`authorisation` checks them; both are printed and kept in the
        register.
    draft_document : bool
        Write the DRAFT to ``path`` when an item is missing (default). The workbench, which
        shows the missing items on its page and keeps no DRAFT, says False: nothing is
        rendered (a PDF takes seconds).
    preview : bool
        A DRAFT whatever is given, never numbered: the workbench's preview of a sign-off, with
        the item as ``store`` names it (the same call as the issue, one item more missing).

    Raises
    ------
    InputError
        The date of test is after the date of issue; a name no font can print.
    """
    from axiscal.report.certificate_content import (calibration_date, check_dates,
                                                    missing_items)

    if store is not None and not callable(store):      # the test as the history names it
        cfg = _with_history_item(cfg, store, data_bytes)
    budget = budget_for(dataset, result, cfg)
    decisions, _, rule_text = decisions_for(result.parameters(), budget, tolerances or {}, cfg,
                                            rule)
    cfg = _with_paper(cfg, paper)
    if customer_supplied is None:
        customer_supplied = _job_tolerances(job)
    if logo is None:
        logo = _logo(cfg, job)
    info = _info(cfg, today, logo, customer_supplied)
    check_dates(calibration_date(dataset, info), info.issued)
    info, refusals = authorisation(cfg, info, prepared_by or info.operator
                                   or dataset.metadata.operator, approved_by)
    missing = tuple(missing_items(dataset, result, budget, info, decisions, config_note)
                    + refusals)
    if store is None and not missing:
        missing = ("certificate number: a certificate is numbered only by the certificate "
                   "register (a calibration history, --db)",)
    if preview and not missing:
        missing = ("certificate number: this is the preview; the certificate is numbered when "
                   "it is issued",)
    info = dataclasses.replace(info, missing=missing, replaces=replaces, reason=reason,
                               changes=tuple(changes))

    found = None
    if as_found is not None:
        f_ds, f_res, _ = as_found
        f_budget = budget_for(f_ds, f_res, cfg)
        f_dec, _, _ = decisions_for(f_res.parameters(), f_budget, tolerances or {}, cfg, rule)
        found = (f_ds, f_res, f_budget, tuple(f_dec))

    def render(number: str) -> bytes:
        from axiscal.report.certificate import positioning_certificate

        rep = positioning_certificate(dataset, result, budget,
                                      dataclasses.replace(info, number=number), decisions,
                                      rule_text, as_found=found)
        return rep.document(path)

    from axiscal.io._files import write_bytes_atomic

    if missing:
        if draft_document:
            write_bytes_atomic(Path(path), render(""))
        return CertificateOutcome(Path(path), tuple(decisions), missing)
    inputs = {"config": cfg, "tolerances": dict(tolerances or {}), "rule": rule, "paper": paper,
              "logo": logo, "customer_supplied": list(customer_supplied)}
    store = store() if callable(store) else store        # opened only to issue
    record = _register(store, dataset, info, data_bytes, filename, render, inputs, path,
                       None if as_found is None else as_found[2])
    write_bytes_atomic(Path(path), record.document)
    return CertificateOutcome(Path(path), tuple(decisions), (), record.number, record)


def reissue_certificate(store, number: str, reason: str, path, corrections: dict | None = None,
                        today: str | None = None, laboratory: str | None = None,
                        prepared_by: str = "", approved_by: str = "") -> CertificateOutcome:
    """Amend certificate ``number``: a new certificate with a new number that replaces it, for
    ``reason``, rebuilt from the stored test and the inputs kept with the old one, with
    ``corrections`` (job-file tables) on top; the old one is marked superseded. A reissue that
    would be a DRAFT is refused and changes nothing."""
    old, stored, inputs, cfg = amendment_inputs(store, number, reason, path, corrections,
                                                laboratory)
    ev = stored.evaluate_again()
    if ev.kind != "iso230-2":
        raise InputError(f"certificate {number} is of a {ev.kind} test: amend it by "
                         "axiscal.report.kind_certificate.reissue")
    changes = amendment_changes(ev.dataset, ev.evaluation, (inputs["config"], inputs["tolerances"],
                                                            inputs["rule"]),
                                (cfg, inputs["tolerances"], inputs["rule"]))
    out = _draft_refused(path, lambda p: write_certificate(
        p, ev.dataset, ev.evaluation, cfg, stored.raw, inputs["tolerances"], inputs["rule"],
        inputs["paper"], store=store, filename=stored.summary.filename, today=today,
        customer_supplied=inputs["customer_supplied"], logo=inputs["logo"], replaces=number,
        reason=reason.strip(), prepared_by=prepared_by, approved_by=approved_by,
        changes=changes), number)
    return out


def amendment_inputs(store, number: str, reason: str, path, corrections: dict | None = None,
                     laboratory: str | None = None):
    """(old record, stored test, inputs kept with it, amended configuration) of an amendment of
    certificate ``number``: the checks every amendment makes (a reason; a PDF stays a PDF) and
    the configuration kept with the old one with ``corrections`` on top (no number, date of
    issue only when corrected). The one preamble of :func:`reissue_certificate` and
    :func:`axiscal.report.kind_certificate.reissue`."""
    from axiscal.io.user_config import merge

    if not reason.strip():
        raise InputError("a reissue states its reason (--reason)")
    old = store.certificate(number, laboratory)
    stored = store.get(old.test_id)
    inputs = old.inputs
    cfg = merge(inputs["config"], corrections or {})
    cfg["certificate"] = {k: v for k, v in cfg.get("certificate", {}).items()
                          if k not in ("number", "issued")}
    if (corrections or {}).get("certificate", {}).get("issued"):
        cfg["certificate"]["issued"] = corrections["certificate"]["issued"]
    if Path(path).suffix.lower() != ".pdf" and old.media_type == "application/pdf":
        raise InputError(f"--out {path}: certificate {number} was issued as a PDF; write .pdf")
    return old, stored, inputs, cfg


def signatories(cfg: dict) -> dict[str, str]:
    """The laboratory's authorised signatories, name -> role: the configuration's
    ``[[signatory]]`` tables (``name``, ``role``), else the one ``[certificate] signatory``
    with its ``signatory_role``."""
    listed = cfg.get("signatory") or []
    listed = listed if isinstance(listed, list) else [listed]
    out = {str(t.get("name", "")).strip(): str(t.get("role", "")).strip()
           for t in listed if isinstance(t, dict) and str(t.get("name", "")).strip()}
    cert = cfg.get("certificate", {})
    if not out and str(cert.get("signatory") or "").strip():
        out[str(cert["signatory"]).strip()] = str(cert.get("signatory_role", "")).strip()
    return out


def authorisation(cfg: dict, info, prepared_by: str, approved_by: str = ""):
    """(info with the preparer and the approving signatory, what withholds the issue).

    A certificate is prepared by one person and issued only when an authorised signatory
    of the laboratory approves it (ISO/IEC 17025:2017 §7.8.2.1 o: the identification of the
    person authorising it; §6.2.6 c: authorised personnel): the approver must be one of
    :func:`signatories`, and another person than the one who prepared it. The approver's role
    comes from the list. Each unmet condition is an item of the DRAFT's list.
    """
    approver = (approved_by or info.signatory or "").strip()
    allowed = signatories(cfg)
    info = dataclasses.replace(info, prepared_by=(prepared_by or "").strip())
    out = []
    if approver and allowed and approver not in allowed:
        out.append(f"approval by an authorised signatory: {approver!r} is not one of the "
                   f"laboratory's ({', '.join(allowed)}; [[signatory]] name and role)")
    elif approver:
        info = dataclasses.replace(info, signatory=approver,
                                   signatory_role=allowed.get(approver) or info.signatory_role)
    if approver and info.prepared_by and approver.casefold() == info.prepared_by.casefold():
        out.append(f"approval by a second person: {approver} prepared the certificate and "
                   "cannot also approve it")
    if not info.prepared_by:
        out.append("name of the person who prepared the certificate ([operator] name)")
    return info, out


def write_as_found_as_left(path, store, found_id: int, left_id: int, cfg: dict,
                           tolerances=None, rule: str | None = None, paper: str | None = None,
                           job: Path | None = None, **kw) -> CertificateOutcome:
    """The certificate of a compensated (or repaired) axis from two stored tests: ``found_id``
    before the adjustment, ``left_id`` after it, each with its U and verdict against the same
    tolerances (ISO/IEC 17025:2017 §7.8.4.1 d). Numbered as the certificate of the as-left test,
    the as-found test named beside it in the register.

    Raises
    ------
    InputError
        The two are the same test, not both ISO 230-2 tests, not of the same machine and axis,
        or the as-found test is dated after the as-left one.
    """
    if found_id == left_id:
        raise InputError(f"as found and as left are both test {left_id}: give the test before "
                         "the adjustment and the test after it")
    found, left = store.get(found_id), store.get(left_id)
    evs = [t.evaluate_again() for t in (found, left)]
    if any(e.kind != "iso230-2" for e in evs):
        raise InputError("an as found / as left certificate reports two ISO 230-2 positioning "
                         f"tests; test {found_id} is {evs[0].kind}, test {left_id} {evs[1].kind}")
    a, b = found.summary, left.summary
    if (a.machine, a.axis) != (b.machine, b.axis):
        raise InputError(f"test {found_id} is of {a.machine} axis {a.axis}, test {left_id} of "
                         f"{b.machine} axis {b.axis}: as found and as left are one axis")
    if a.tested_at > b.tested_at:
        raise InputError(f"test {found_id} (as found, {a.tested_at:%Y-%m-%d}) is after test "
                         f"{left_id} (as left, {b.tested_at:%Y-%m-%d})")
    return write_certificate(path, evs[1].dataset, evs[1].evaluation, cfg, left.raw, tolerances,
                             rule, paper, job, store=store, filename=b.filename,
                             as_found=(evs[0].dataset, evs[0].evaluation, found_id), **kw)


def amendment_changes(dataset, result, before, after) -> list[dict]:
    """What an amendment changes (ISO/IEC 17025:2017 §7.8.8.3: the change identified): every
    field of the certificate's inputs whose text changed, and every result whose printed U or
    verdict changed, as ``{"what", "old", "new"}``.

    ``before`` and ``after`` are ``(config, tolerances, rule)``: the inputs kept with the old
    certificate and the amended ones. The results of both come from the same library calls
    (:func:`budget_for`, :func:`decisions_for`) on the same stored test.
    """
    from axiscal.standards.iso14253_1 import overall

    old, new = _flat(before[0]), _flat(after[0])
    out = [{"what": k, "old": old.get(k, "—"), "new": new.get(k, "—")}
           for k in sorted(set(old) | set(new)) if old.get(k) != new.get(k)]
    states = []
    for cfg, tol, rule in (before, after):
        budget = budget_for(dataset, result, cfg)
        decisions, _, _ = decisions_for(result.parameters(), budget, tol or {}, cfg, rule)
        by = {d.parameter: d for d in decisions}
        row = {}
        for p, v in result.parameters().items():
            if v is None:
                continue
            d = by.get(p)
            row[f"U({p})"] = budget.U_text(p)
            row[f"tolerance {p}"] = "—" if d is None else f"{d.upper:g}"
            row[f"verdict {p}"] = "—" if d is None or d.outcome is None else d.outcome.value
        o = overall(decisions)
        row["overall verdict"] = o.value if o else "no tolerance"
        states.append(row)
    out += [{"what": k, "old": states[0][k], "new": states[1][k]} for k in states[0]
            if states[0][k] != states[1].get(k)]
    return out


def _flat(cfg: dict) -> dict[str, str]:
    """Each printed field of a configuration as ``[table] key`` -> text (the logo and the
    number and date of issue, which an amendment always changes, left out)."""
    out = {}
    for table, v in cfg.items():
        rows = v if isinstance(v, list) else [v]
        for n, t in enumerate(rows, 1):
            if not isinstance(t, dict):
                continue
            where = f"[[{table}]] {n}" if isinstance(v, list) else f"[{table}]"
            for k, x in t.items():
                if k in ("logo",) or (table == "certificate" and k in ("number", "issued")):
                    continue
                out[f"{where} {k}"] = ("; ".join(map(str, x)) if isinstance(x, list)
                                       else json.dumps(x, sort_keys=True)
                                       if isinstance(x, dict) else str(x))
    return out


def _draft_refused(path, write, number: str) -> CertificateOutcome:
    """Run ``write`` into a scratch file; a DRAFT is refused, an issued one moved to ``path``."""
    import tempfile

    from axiscal.io._files import write_bytes_atomic

    with tempfile.TemporaryDirectory() as d:
        scratch = Path(d) / Path(path).name
        out = write(scratch)
        if out.draft:
            raise InputError(f"certificate {number} cannot be reissued: missing "
                             + "; ".join(out.missing))
        write_bytes_atomic(Path(path), scratch.read_bytes())
    return dataclasses.replace(out, path=Path(path))


def _register(store, dataset, info, data_bytes: bytes, filename: str, render, inputs, path,
              as_found_test_id: int | None = None):
    """Keep the test in the history and issue the next number of the laboratory (a date of
    issue in the future refused before the test is kept)."""
    from axiscal.store.register import check_issue_date

    check_issue_date(info.issued)
    named = getattr(getattr(dataset, "metadata", None), "machine", "")  # a file naming it
    m = info.machine
    machine = None if named else " ".join(
        str(m.get(k)) for k in ("maker", "model", "serial") if m.get(k)) or None
    test = store.add(data_bytes, Path(filename).name, machine=machine)
    lab, series, number_for = number_format(inputs["config"], info.issued)
    pdf = Path(path).suffix.lower() == ".pdf"
    return store.issue_certificate(
        test_id=test.id, laboratory=lab, series=series,
        laboratory_name=str(info.company.get("name", "")).strip(), number_for=number_for, render=render,
        customer=str(info.customer.get("name", "")), issued=info.issued,
        media_type="application/pdf" if pdf else "text/html",
        inputs=json.loads(json.dumps(inputs, default=str)), replaces=info.replaces,
        reason=info.reason, prepared_by=info.prepared_by, approved_by=info.signatory,
        approved_role=info.signatory_role, changes=info.changes,
        as_found_test_id=as_found_test_id)


def _with_history_item(cfg: dict, store, data_bytes: bytes) -> dict:
    """``cfg`` with the item's identity from the history where the job leaves it out: the
    machine's name, maker, model, serial and location and the axis, as corrected there
    (renamed, merged: :mod:`axiscal.store.corrections`), for a test the history holds."""
    import hashlib

    sha = hashlib.sha256(data_bytes).hexdigest()
    hit = store.stored([sha]).get(sha)
    if hit is None:
        return cfg
    t = store.get(hit.id).summary
    m = store.machine(t.machine_id)
    machine = dict(cfg.get("machine", {}))
    for key, value in (("name", m.name), ("maker", m.maker), ("model", m.model),
                       ("serial", m.serial), ("location", m.location), ("axis", t.axis)):
        if value and not str(machine.get(key) or "").strip():
            machine[key] = value
    return {**cfg, "machine": machine}


def _info(cfg: dict, today: str | None, logo: str, customer_supplied):
    from axiscal.report.certificate import certificate_info
    from axiscal.report.certificate_content import parse_date, refuse_unrenderable

    issued = str(cfg.get("certificate", {}).get("issued") or today
                 or _dt.date.today().isoformat())
    parse_date(issued, "date of issue")
    info = certificate_info(cfg, issued=issued, logo=logo, customer_supplied=customer_supplied)
    refuse_unrenderable(_texts(cfg))
    return dataclasses.replace(info, number="")


def _texts(cfg: dict) -> dict[str, Any]:
    """Every text of the configuration a certificate prints, by where it comes from."""
    out: dict[str, Any] = {}
    for table in ("company", "operator", "customer", "machine", "conditions", "certificate"):
        for k, v in cfg.get(table, {}).items():
            if k != "logo":
                out[f"[{table}] {k}"] = " ".join(map(str, v)) if isinstance(v, list) else v
    inst = cfg.get("instrument", [])
    for n, t in enumerate(inst if isinstance(inst, list) else [inst], 1):
        for k, v in t.items():
            out[f"[[instrument]] {n} {k}"] = v
    return out


def _with_paper(cfg: dict, paper: str | None) -> dict:
    if paper is None:
        return cfg
    return {**cfg, "certificate": {**cfg.get("certificate", {}), "paper": paper}}


def _job_tolerances(job: Path | None) -> tuple[str, ...]:
    """The tolerances a job file gives: supplied by the customer (ISO/IEC 17025:2017
    §7.8.2.1, information supplied by the customer identified)."""
    if job is None:
        return ()
    from axiscal.io.user_config import load_job

    return tuple(load_job(job).get("tolerance", {}))


def _logo(cfg: dict, job: Path | None) -> str:
    from axiscal.io.user_config import config_path, logo_data_uri

    where = job if job is not None and cfg.get("company", {}).get("logo") else config_path()
    return logo_data_uri(cfg, where)
