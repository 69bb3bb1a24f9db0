"""Sign-off of a positioning test in the workbench: tolerances, the job, the ISO 14253-1 verdict,
a certificate issued through the history's certificate register.

The form carries what ``axiscal iso230-2 --tolerance NAME=VALUE --job JOB.toml --report`` takes:
tolerances by parameter, and the job's tables (``[customer]``, ``[machine]``, ``[conditions]``,
``[[instrument]]``, ``[operator]``, ``[certificate]``) over the user configuration (axiscal
config). :func:`job_from_form` only parses the fields into that job structure; the verdict is
:func:`axiscal.report.issue.sign_off` and the certificate :func:`axiscal.report.issue.
write_certificate`, the same library calls as the command line, numbered by the register of the
workbench's history (:meth:`axiscal.store.history.Store.issue_certificate`). A certificate whose
mandatory content (ISO/IEC 17025:2017 §7.8.2, §7.8.4) is incomplete is not numbered: the page
names each missing item by the label of the field that gives it, with a link to the field
(:mod:`axiscal.web.signoff_form`).

The laboratory (name, address, code, signatories, E_VE declared, CMC) is kept in the history
(:mod:`axiscal.store.laboratory`; each change an audit entry) and a drift check uploaded on the
form is kept beside the test; the configuration of a sign-off is
:func:`axiscal.store.laboratory.signoff_config`: the stored test's own uncertainty inputs, under its
drift check's E_VE, with the form's job on top, so the budget is the stored test's, made by the
one call (:func:`axiscal.report.issue.budget_for`). The form starts from the laboratory, the
machine's last certificate and the stored test (its date and the instrument typed at upload). A
test with a certificate is amended (a new number with the reason, the old one superseded), never
issued twice; a withdrawn test is never certified (the register refuses both).
"""

from __future__ import annotations

import re

from fastapi import FastAPI, Request
from fastapi.responses import HTMLResponse, RedirectResponse, Response
from starlette.concurrency import run_in_threadpool

from axiscal.errors import AxiscalError, InputError
from axiscal.web.inputs import TestId, checked_form, form_number, require_engineer
from axiscal.web.plot_specs import COLORS, as_list, positioning_plot, unit_text
from axiscal.web.rendering import download, query, render
from axiscal.web.signoff_form import (INSTRUMENT_KEYS, INSTRUMENTS, JOB_FIELDS, LABELS,
                                      checked_fields, lab_defaults, lab_from_form,
                                      missing_fields, plain)

__all__ = ["add_routes", "job_from_form", "signoff_context", "signoff_plot", "INSTRUMENTS"]

_JOB_FIELDS = JOB_FIELDS
_TEMPERATURES = ("air_temperature", "material_temperature")
_INSTRUMENT_KEYS = INSTRUMENT_KEYS
#: The largest drift-check file taken, bytes (a day of readings a second is ~1 MB).
MAX_DRIFT_BYTES = 2 * 2**20
#: Colours of the verdicts (table cells and the tolerance envelope of the plot).
VERDICT_COLORS = {"PASS": "#1e7b34", "FAIL": "#d62728", "ZONE": "#ff7f0e"}


def add_routes(app: FastAPI) -> None:
    """The sign-off routes over the workbench's history (``app.state.store``)."""

    def store(request: Request):
        return request.app.state.store

    @app.post("/tests/{test_id}/signoff", response_class=HTMLResponse)
    async def signoff(request: Request, test_id: TestId):
        form = await checked_form(request)
        require_engineer(request)
        values = {k: str(v).strip() for k, v in form.items() if isinstance(v, str)}
        action = values.get("action") or "verdict"
        drift = form.get("drift_check")
        drift = (await drift.read(MAX_DRIFT_BYTES + 1), drift.filename or "drift-check.csv") \
            if drift is not None and hasattr(drift, "read") and drift.filename else None
        from axiscal.web.workers import heavy     # a certificate: one at a time per worker

        user = request.state.session.get("name") or ""    # signed in: the approver
        ctx = await (heavy if action != "verdict" else run_in_threadpool)(
            _evaluate, store(request), test_id, values, action, user, drift)
        partial = request.headers.get("hx-request") == "true"
        if ctx.get("number"):                  # issued: the test page lists it (POST-redirect-GET)
            url = f"/tests/{test_id}?{query(certificate=ctx['number'])}#signoff"
            return Response(headers={"HX-Redirect": url}) if partial else \
                RedirectResponse(url, 303)
        status = 200 if partial or not ctx.get("error") else 400
        return render(request, "signoff.html" if partial else "signoff_page.html",
                      f"Sign-off of test {test_id}", status, test_id=test_id, signoff=ctx)

    @app.get("/tests/{test_id}/certificate")
    def certificate_document(request: Request, test_id: TestId, number: str):
        """A certificate of this test as the register keeps it (bytes checked by SHA-256)."""
        rec = store(request).certificate(number)
        if rec.test_id != test_id:
            from axiscal.store import NotFoundError

            raise NotFoundError(f"certificate {number} is not one of test {test_id}")
        ext = ".pdf" if rec.media_type == "application/pdf" else ".html"
        return download(rec.document, f"{rec.number}{ext}", rec.media_type)


def signoff_context(st, t, ev, values: dict | None = None, certificate: str = "",
                    cfg: dict | None = None, known: dict | None = None,
                    generation: tuple | None = None) -> dict | None:
    """What the test page's sign-off section shows: the form (filled from ``values``, or from
    the inputs kept with ``certificate`` of this test, whose verdict is then shown, or else
    from the user configuration ``cfg`` (default read now), the laboratory kept in the history,
    the machine's last certificate and the stored test; or, when a sign-off of the test waits
    for approval, the form as its preparer saved it), the certificates of this test in the
    register, its drift checks, the sign-off saved for approval, and whether it may be
    certified; None for a test that is not a
    test of a kind without an uncertainty budget (no form: a statement of conformity needs U,
    :func:`axiscal.report.kind_certificate.require_budget`). A test of another kind with a
    budget (diagonal, ballbar, five-axis, thermal) has the same form without what only a positioning
    test has (E_VE, temperatures, the plot): its figures, U and verdicts are
    :func:`axiscal.report.kind_certificate.certificate_record` of the stored record.

    ``generation``: the history's generation a page read before (without its new tests,
    :data:`axiscal.store.queries.NEW_TESTS`): the reads that are the same for many tests (the
    laboratory, a machine's last certificate, which tests have certificates or drift checks)
    are then kept under it (:func:`kept_read`)."""
    from axiscal.report.issue import load_config
    from axiscal.store.approval import saved_signoff
    from axiscal.store.laboratory import drift_checks

    positioning = ev.kind == "iso230-2"
    e_ve_input = positioning
    if positioning:
        params = [n for n, v in ev.evaluation.parameters().items() if v is not None]
        units = {}
    else:
        from axiscal.report.kind_certificate import certificate_record

        ev = rec = t.record()             # with its budget: what the verdict decides with
        if rec.budget is None:
            return None
        figures = certificate_record(rec).figures
        params = [f.name for f in figures]
        from axiscal.store.laboratory import reads_e_ve

        e_ve_input = reads_e_ve(rec)          # a drift check or the laboratory's E_VE
        units = {f.name: _unit(f.unit) for f in figures}
    tid = t.summary.id
    known = known or {}           # read already by the page: certificates, laboratory, drifts
    records = known.get("certificates")
    if records is None:
        records = st.certificates(test_id=tid) if has_rows(st, generation, "certificate", tid) \
            else []
    checks = known.get("drift_checks")
    if checks is None:
        checks = drift_checks(st, tid) if has_rows(st, generation, "drift_check", tid) else []
    current = next((c for c in records if c.status == "issued"), None)
    ctx = {"test_id": t.summary.id, "parameters": params, "certificates": records,
           "instruments": range(1, INSTRUMENTS + 1), "labels": LABELS,
           "unit": _unit(ev.evaluation.deviation_unit) if positioning else "",
           "units": units, "positioning": positioning, "current": current,
           "e_ve_input": e_ve_input,
           "withdrawn": t.summary.withdrawn,
           "drift_checks": checks,
           "saved": saved_signoff(st, tid)
           if has_rows(st, generation, "signoff_for_approval", tid) else None}
    issued = next((c for c in records if c.number == certificate), None)
    if issued is not None:
        inputs = st.certificate(issued.number, issued.laboratory).inputs
        tolerances = inputs.get("tolerances") or {}
        cfg = inputs["config"]
        ctx["form"] = {**_defaults(cfg, params), **lab_defaults(cfg),
                       **{f"tol_{p}": f"{v:g}" for p, v in tolerances.items()}}
        _verdict(ctx, ev, cfg, tolerances, inputs.get("rule"))
    elif values is not None:
        ctx["form"] = values
    elif ctx["saved"] is not None:            # what the preparer saved for approval
        ctx["form"] = dict(ctx["saved"].values)
    else:
        ctx["form"] = _prefill(st, t, ev, load_config(None) if cfg is None else cfg, params,
                               known.get("laboratory"), generation)
    return ctx


def kept_read(st, generation: tuple | None, key: tuple, make):
    """``make()``, or with the page's ``generation`` (see :func:`signoff_context`) a copy of
    what it gave under that generation in this process (:func:`axiscal.web.memo.memoised`)."""
    if generation is None:
        return make()
    import copy

    from axiscal.web.memo import memoised

    return copy.deepcopy(memoised(st, key, make, generation))


def has_rows(st, generation: tuple | None, table: str, test_id: int) -> bool:
    """May test ``test_id`` have rows in ``table`` (``certificate``, ``drift_check``,
    ``audit``, ``signoff_for_approval``)? Always, without a ``generation``; else whether it is among the tests that have
    (:func:`axiscal.store.queries.tests_with`, kept under the generation)."""
    if generation is None:
        return True
    from axiscal.store.queries import tests_with

    return test_id in kept_read(st, generation, ("tests-with", table),
                                lambda: tests_with(st, table))


def _prefill(st, t, ev, user_cfg: dict, params, lab: dict | None = None,
             generation: tuple | None = None) -> dict:
    """The form of a new sign-off: the user configuration, the laboratory kept in the history,
    the customer, item and instruments of the machine's last certificate (and its conditions
    when it is of this test), the tolerances of the last certificate of this axis and kind of
    test (in this test's units), and the stored test's date and the instrument typed at
    upload (a sign-off is of this test)."""
    from axiscal.io.user_config import merge
    from axiscal.store.laboratory import laboratory, last_certificate_inputs

    cfg = merge(user_cfg, lab if lab is not None else
                kept_read(st, generation, ("laboratory",), lambda: laboratory(st)))
    of_test, last = kept_read(st, generation, ("last-certificate", t.summary.machine_id),
                              lambda: last_certificate_inputs(st, t.summary.machine_id))
    old = last.get("config", {})
    same = ("conditions",) if of_test == t.summary.id else ()     # this test's own conditions
    keep = {k: old[k] for k in ("customer", "instrument", "operator", *same) if k in old}
    keep["machine"] = {k: v for k, v in old.get("machine", {}).items()
                       if k in ("maker", "model", "serial", "location")}
    keep["certificate"] = {k: v for k, v in old.get("certificate", {}).items()
                           if k in ("specification", "rule", "paper")}
    # the last certificate of this axis and kind (none when the machine has none at all)
    _, like = (None, {}) if of_test is None else kept_read(
        st, generation, ("last-certificate", t.summary.machine_id, t.summary.axis,
                         t.summary.kind),
        lambda: last_certificate_inputs(st, t.summary.machine_id, like_test=t.summary.id))
    keep["tolerance"] = {**like.get("config", {}).get("tolerance", {}),     # same axis, kind
                         **(like.get("tolerances") or {})}
    form = {**_defaults(merge(cfg, keep), params), **lab_defaults(cfg)}
    if t.summary.date_known and not getattr(getattr(ev.dataset, "metadata", None), "date",
                                            ev.date):
        form["date"] = t.summary.tested_at.strftime("%Y-%m-%d")
    if t.instrument and not form.get("instrument1_name"):
        form["instrument1_name"] = t.instrument
    elif t.instrument and ev.kind != "iso230-2":
        _test_instrument_first(form, t.instrument)
    return form


def _test_instrument_first(form: dict, name: str) -> None:
    """The instrument rows of a test of another kind (a ballbar, a diagonal ...): the test's
    own instrument, with the details of the row naming it if the laboratory lists it, never
    the laboratory's other instruments (issue 40: a ballbar certificate listed the
    laboratory's laser)."""
    rows = [{k: form.get(f"instrument{i}_{k}", "") for k in _INSTRUMENT_KEYS}
            for i in range(1, INSTRUMENTS + 1)]
    row = next((r for r in rows if r["name"].strip() == name.strip()), {"name": name})
    for i in range(1, INSTRUMENTS + 1):
        for k in _INSTRUMENT_KEYS:
            form[f"instrument{i}_{k}"] = str(row.get(k, "")) if i == 1 else ""


def job_from_form(values: dict, parameters) -> tuple[dict, dict, str | None, str]:
    """(job, tolerances, rule, paper) from the form's text fields.

    ``job`` has the tables of a job file (only the fields given: the user configuration stays
    beneath); ``tolerances`` maps each parameter given (``tol_A`` ...) to its value in the
    deviation unit, as ``--tolerance A=12``. An empty field is not given.

    Raises
    ------
    InputError
        A temperature or tolerance that is not a number; an unknown rule or paper size; a
        field holding a control character (:func:`~axiscal.web.signoff_form.checked_fields`).
    """
    checked_fields(values)
    job: dict = {}
    for field, (table, key) in _JOB_FIELDS.items():
        text = values.get(field, "")
        if not text:
            continue
        value: object = text
        if field in _TEMPERATURES:
            value = form_number(text, field.replace("_", " ") + " [°C]", -50.0, 100.0)
        elif field == "customer_address":
            value = [line.strip() for line in text.splitlines() if line.strip()]
        job.setdefault(table, {})[key] = value
    rows = []
    for i in range(1, INSTRUMENTS + 1):
        row = {k: values.get(f"instrument{i}_{k}", "") for k in _INSTRUMENT_KEYS}
        if any(row.values()) and not row["name"]:
            raise InputError(f"{LABELS[f'instrument{i}_name']}: this instrument row has no "
                             "name; give the instrument's name (or empty the row)")
        if any(row.values()):
            rows.append({k: v for k, v in row.items() if v})
    if rows:
        job["instrument"] = rows
    tolerances = {p: form_number(values[f"tol_{p}"], f"tolerance {p}", 0.0, 1e6)
                  for p in parameters if values.get(f"tol_{p}")}
    rule = values.get("rule") or None
    if rule not in (None, "iso14253-1", "simple"):
        raise InputError(f"decision rule {rule!r}: iso14253-1 or simple")
    paper = values.get("paper") or "A4"
    if paper not in ("A4", "Letter"):
        raise InputError(f"paper {paper!r}: A4 or Letter")
    return job, tolerances, rule, paper


def signoff_plot(ev, so=None, tolerances: dict | None = None) -> dict:
    """uPlot spec of an ISO 230-2 test for the page: the mean lines, x̄ ± 2s of each direction
    (the band of A, ISO 230-2:2014 clause 3; Yüksel et al., eq. 20, 21), every reading, and with
    a sign-off ``so`` the tolerance envelope of A, E and M in the colour of its verdict.

    An envelope is a band as wide as the tolerance, centred on the middle of what the parameter
    spans (x̄ ± 2s for A, the mean lines for E, x̄ for M; eq. 18, 19, 21): the parameter is within
    its tolerance exactly when its curves fit between the two lines. Where to draw a band of that
    width is not said by the standard; the centred position is this page's choice.
    """
    spec = positioning_plot(ev)
    r, ds = ev.evaluation, ev.dataset
    series = spec["series"]
    for arrow, mean, s, arr, color in (("↑", r.mean_up, r.s_up, ds.up, COLORS["up"]),
                                       ("↓", r.mean_down, r.s_down, ds.down, COLORS["down"])):
        if arr.shape[1] == 0:
            continue
        series += [{"label": f"x̄{arrow} + 2s", "values": as_list(mean + 2 * s), "color": color,
                    "dash": True, "thin": True},
                   {"label": f"x̄{arrow} − 2s", "values": as_list(mean - 2 * s), "color": color,
                    "dash": True, "thin": True}]
        runs = arr.shape[1]      # one legend entry for every run's readings of a direction
        series += [{"label": f"readings{arrow} (runs 1–{runs})" if j == 0 else
                    f"readings{arrow} run {j + 1}", "values": as_list(arr[:, j]), "color": color,
                    "points": True, "legend": j == 0} for j in range(runs)]
    if so is not None:
        series += _envelopes(r, so, tolerances or {})
        if so.overall is not None:
            spec["verdict"] = so.overall.short
            spec["title"] += f": {so.overall.value} (ISO 14253-1:2017)"
    return spec


def _envelopes(r, so, tolerances: dict) -> list:
    import numpy as np

    spans = {"A": np.concatenate([r.mean_up + 2 * r.s_up, r.mean_up - 2 * r.s_up,
                                  r.mean_down + 2 * r.s_down, r.mean_down - 2 * r.s_down]),
             "E": np.concatenate([r.mean_up, r.mean_down]), "M": r.mean_bi}
    out = []
    for d in so.decisions:
        values = spans.get(d.parameter)
        if values is None or d.outcome is None or not np.isfinite(values).any():
            continue
        mid = (np.nanmax(values) + np.nanmin(values)) / 2
        color = VERDICT_COLORS[d.outcome.short]
        for sign, edge in ((1, "upper"), (-1, "lower")):
            out.append({"label": f"tolerance {d.parameter} = {d.upper:g} ({d.outcome.short}), "
                                 f"{edge}", "values": [float(mid + sign * d.upper / 2)] *
                        r.targets.size, "color": color, "dash": True})
    return out


def _evaluate(st, test_id: int, values: dict, action: str, user: str = "",
              drift: tuple | None = None) -> dict:
    """The sign-off's verdict; with ``action`` ``save``, the form saved for approval; with
    ``issue`` or ``amend``, the certificate or its amendment (library calls only).

    ``user`` is the signed-in account. Signed in, a certificate is the act of two accounts
    (ISO/IEC 17025:2017 §7.8.2.1 o, §6.2.6; :mod:`axiscal.store.approval`): the preparer saves
    the form for approval, and an authorised signatory, another account, issues exactly what was
    saved: the register keeps the saving account as preparer and the issuing one as approver,
    never a name typed on the form; the signatories are changed only by one of them
    (:func:`axiscal.store.laboratory.check_signatory_change`). Without sign-in (a workbench on
    one's own computer, like the command line's ``--prepared-by/--approved-by``) the form's
    operator prepares and its signatory approves. ``drift`` is (bytes, file name) of a drift
    check uploaded with the form: kept beside the test
    (:func:`axiscal.store.laboratory.add_drift_check`). The laboratory's fields are kept in the
    history when a certificate is issued with them (an audit entry by ``user``, or by the
    certificate's preparer on one's own computer)."""
    from axiscal.report.issue import load_config, signatories
    from axiscal.store.approval import clear_saved, preparer, save_for_approval
    from axiscal.store.laboratory import (add_drift_check, check_signatory_change, laboratory,
                                          set_laboratory, signoff_config, signoff_record)

    t = st.get(test_id)
    ev = t.named(t.evaluate_again())     # the plot's title: the history's machine and axis
    if ev.kind != "iso230-2":
        ev = t.record()                  # the stored record, with its budget
    ctx = signoff_context(st, t, ev, values)
    if ctx is None:
        from axiscal.report.kind_certificate import require_budget

        require_budget(t.record())      # the one line naming why (no budget for the kind)
    if user:             # the approver is the account: the form's signatory fields are not read
        values = {k: v for k, v in values.items() if k not in ("signatory", "signatory_role")}
    try:
        if action in ("issue", "amend"):
            _check_issue(ctx, action, values)
        job, tolerances, rule, paper = job_from_form(values, ctx["parameters"])
        kept = laboratory(st)
        lab = lab_from_form(values, kept, job.get("instrument", []))
        user_cfg = load_config(None)
        if user:
            check_signatory_change(kept, lab, user, user_cfg)
        who = user or values.get("operator", "")
        if drift is not None:       # another kind: refused by the library, in its words
            if len(drift[0]) > MAX_DRIFT_BYTES:
                raise InputError(f"{LABELS['drift_check']}: {drift[1]} is over "
                                 f"{MAX_DRIFT_BYTES // 2**20} MiB")
            if not drift[0].strip():
                raise InputError(f"{LABELS['drift_check']}: {drift[1]} is empty")
            if not who:
                raise InputError(f"{LABELS['operator']}: give your name; the history records "
                                 "who kept the drift check")
            ctx["drift_notice"] = add_drift_check(st, test_id, drift[0], drift[1],
                                                  by=who).notice
            ctx["drift_checks"] = _drift_checks(st, test_id)
        cfg = signoff_config(st, t, user_cfg, job, lab)
        if not ctx["positioning"]:          # E_VE resolved as a positioning test's
            ev = signoff_record(st, t, cfg)
        _verdict(ctx, ev, cfg, tolerances, rule)
        if action == "save":
            ctx.update(saved=save_for_approval(st, test_id, values, by=user), saved_now=True)
        if action in ("issue", "amend"):
            prepared = (preparer(st, test_id, values) or user) if user else ""
            out = _issue(st, t, ev, cfg, tolerances, rule, paper, user, prepared) \
                if action == "issue" else _amend(st, t, ctx["current"].number,
                                                 values["amend_reason"], cfg, user, prepared)
            missing = _approval_items(out.missing, user, signatories(cfg), prepared,
                                      ctx.get("saved")) if user else out.missing
            ctx.update(missing=missing_fields(missing, values, bool(user)), number=out.number)
            if out.number and user:
                clear_saved(st, test_id)
            if out.number and lab != kept:    # issued with it: the laboratory as it was used
                set_laboratory(st, lab, by=who or out.record.prepared_by,
                               reason=f"used for certificate {out.number} of test {test_id}",
                               account=user or None, inherited=user_cfg)
    except AxiscalError as exc:
        ctx["error"] = plain(str(exc)) if "[" in str(exc) else str(exc)
    return ctx


def _approval_items(missing, user: str, allowed: dict, prepared: str, saved) -> tuple:
    """The missing items of a signed-in issue, with the approval said as the page's action:
    an account that is not an authorised signatory is told to save the form for approval (the
    signatory items are not its faults); a signatory issuing a form another account did not
    save (or changed since) is told who prepares it."""
    approval = re.compile(r"^approval by|person authorising|signatory_role|\[certificate\] "
                          r"signatory")
    if user.casefold() not in {n.casefold() for n in allowed}:
        names = ", ".join(allowed) or "none is listed yet"
        return tuple(m for m in missing if not approval.search(m)) + (
            f"approval by an authorised signatory: you ({user}) are not one of the "
            f"laboratory's ({names}); press \"Save for approval\" and one of them approves "
            "and issues it",)
    if prepared.casefold() != user.casefold():
        return tuple(missing)
    if saved is not None and saved.by.casefold() != user.casefold():
        why = (f"the form differs from what {saved.by} saved for approval: whoever changes it "
               "prepares it; press \"Save for approval\" and another signatory issues it (or "
               "reload the test to issue what was saved)")
    else:
        why = ("a certificate is prepared by one account and approved by another: press "
               "\"Save for approval\" and another authorised signatory issues it")
    return tuple(m for m in missing if not m.startswith("approval by a second person")) + (
        f"preparation by another account: {why}",)


def _drift_checks(st, test_id: int):
    from axiscal.store.laboratory import drift_checks

    return drift_checks(st, test_id)


def _check_issue(ctx: dict, action: str, values: dict) -> None:
    """The register's rules in the form's words, before anything is kept: a withdrawn test is
    never certified; a test with a certificate is amended, with a reason, never issued again."""
    if ctx["withdrawn"]:
        raise InputError(f"test {ctx['test_id']} is withdrawn ({ctx['withdrawn']}): a "
                         "withdrawn test is never certified; reinstate it first (Correct this "
                         "test) if the withdrawal was wrong")
    current = ctx["current"]
    if action == "issue" and current is not None:
        raise InputError(f"this test has certificate {current.number}: a second certificate "
                         f"is an amendment; give the {LABELS['amend_reason'].lower()} and "
                         "press \"Issue an amendment\"")
    if action == "amend":
        if current is None:
            raise InputError("this test has no certificate to amend: issue one")
        if not values.get("amend_reason"):
            raise InputError(f"{LABELS['amend_reason']}: say why {current.number} is amended "
                             "(printed on the new certificate)")


def _verdict(ctx: dict, ev, cfg: dict, tolerances: dict, rule) -> None:
    """The sign-off's verdict, verdict table and plot into ``ctx``."""
    from axiscal.report.issue import sign_off

    if not ctx["positioning"]:
        _kind_verdict(ctx, ev, cfg, tolerances, rule)
        return
    so = sign_off(ev.dataset, ev.evaluation, cfg, tolerances, rule)
    ctx.update(result=so, plot=signoff_plot(ev, so, tolerances),
               rows=_rows(ev.evaluation, so, tolerances), budget=so.budget)


def _kind_verdict(ctx: dict, ev, cfg: dict, tolerances: dict, rule) -> None:
    """The verdict of a test of another kind with a budget: its stored record's figures
    decided (:func:`axiscal.report.kind_certificate.certificate_record`, the certificate's own
    call), tolerances of the configuration under the form's."""
    from axiscal.report.kind_certificate import certificate_record

    given = {**cfg.get("tolerance", {}), **tolerances}
    rec = certificate_record(ev, {k: v for k, v in given.items() if k in ev.parameters},
                             rule or cfg.get("certificate", {}).get("rule"))
    ctx.update(result=rec, plot=None, budget=rec, rows=[
        (f"{f.symbol} [{_unit(f.unit)}]", f.value, f.U_text, f.tolerance,
         "the sign-off" if f.name in tolerances else "user configuration", f.verdict,
         next(d.outcome.short for d in rec.decisions if d.parameter == f.name))
        for f in rec.figures if f.verdict is not None])


def _issue(st, t, ev, cfg, tolerances, rule, paper, user: str = "", prepared: str = ""):
    import tempfile
    from pathlib import Path

    from axiscal.report.issue import write_certificate

    with tempfile.TemporaryDirectory() as d:
        if ev.kind != "iso230-2":
            from axiscal.report.kind_certificate import write_kind_certificate

            return write_kind_certificate(Path(d) / "certificate.pdf", ev, cfg, t.raw,
                                          tolerances, rule, store=st,
                                          filename=t.summary.filename, approved_by=user,
                                          prepared_by=prepared, paper=paper,
                                          draft_document=False)
        return write_certificate(Path(d) / "certificate.pdf", ev.dataset, ev.evaluation, cfg,
                                 t.raw, tolerances, rule, paper, store=st,
                                 filename=t.summary.filename, config_note="",
                                 customer_supplied=(), approved_by=user,
                                 prepared_by=prepared, draft_document=False)    # the page lists what is missing


def _amend(st, t, number: str, reason: str, cfg: dict, user: str = "", prepared: str = ""):
    """Amend ``number`` with the form's configuration over the inputs kept with it, the
    machine and the axis named as the history names them now (:func:`axiscal.report.kind_certificate.reissue`,
    any kind: a new number, the reason and the changes printed; a DRAFT refused)."""
    import tempfile
    from pathlib import Path

    from axiscal.report.kind_certificate import reissue as reissue_certificate

    m = st.machine(t.summary.machine_id)
    corrections = {**cfg, "machine": {**cfg.get("machine", {}), "name": m.name,
                                      "axis": st.get(t.summary.id).summary.axis}}
    with tempfile.TemporaryDirectory() as d:
        return reissue_certificate(st, number, reason, Path(d) / "certificate.pdf",
                                   corrections, approved_by=user, prepared_by=prepared)


def _rows(result, so, tolerances: dict) -> list:
    """(parameter, value, U text, tolerance, where the tolerance comes from, outcome, short)."""
    params = result.parameters()
    out = []
    for d in so.decisions:
        source = "the sign-off" if d.parameter in tolerances else "user configuration"
        value = params[d.parameter]
        out.append((d.parameter, value, so.budget.U_text(d.parameter), d.upper, source,
                    d.outcome.value if d.outcome else "does not apply",
                    d.outcome.short if d.outcome else ""))
    return out


def _defaults(cfg: dict, params) -> dict:
    """The form as the user configuration fills it."""
    out = {}
    for field, (table, key) in _JOB_FIELDS.items():
        v = cfg.get(table, {}).get(key, "")
        out[field] = "\n".join(map(str, v)) if isinstance(v, list) else str(v)
    inst = cfg.get("instrument", [])
    for i, row in enumerate(inst if isinstance(inst, list) else [inst], 1):
        if i > INSTRUMENTS:
            break
        for k in _INSTRUMENT_KEYS:
            out[f"instrument{i}_{k}"] = str(row.get(k, ""))
    for p in params:
        tol = cfg.get("tolerance", {}).get(p)
        out[f"tol_{p}"] = "" if tol is None else f"{tol:g}"
    out["rule"] = str(cfg.get("certificate", {}).get("rule", "iso14253-1"))
    out["paper"] = str(cfg.get("certificate", {}).get("paper", "A4"))
    return out


def _unit(unit: str) -> str:
    return unit_text(unit)
