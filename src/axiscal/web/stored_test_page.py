"""A stored test's page: made from the test's record and the history's reads, kept whole by
:mod:`axiscal.web.page_cache` (issue 40), the other tests of its axis filled in at each answer.

The routes (``GET /tests/{id}``, and a refused drift-check form shown on the page) are in
:mod:`axiscal.web.history_pages`; an upload makes the new test's page parts with
:func:`prepare_view` before it is answered.
"""

from __future__ import annotations

from fastapi import Request
from starlette.concurrency import run_in_threadpool

from axiscal.web.rendering import render

__all__ = ["stored_test_page", "prepare_view"]


async def stored_test_page(request: Request, test_id: int, status: int = 200, **extra):
    """A stored test's page (``extra``: what a refused form says at the form). A plain view is
    kept whole by :mod:`axiscal.web.page_cache` under the history's generation without its new
    tests (an upload elsewhere leaves it as it is; any other write makes it again), the user
    configuration and the viewer; the other tests of its axis, which every upload changes,
    are filled in at each answer (kept under the whole generation)."""
    from axiscal.report.issue import load_config
    from axiscal.store.cache import digest
    from axiscal.store.queries import NEW_TESTS, generation
    from axiscal.web import page_cache

    st = request.app.state.store
    if status != 200 or extra:
        return await _make_test_page(request, test_id, status, extra, None)
    now, cfg = generation(st), load_config(None)
    key = ("test", st.url, test_id, request.url.query, page_cache.viewer(request), digest(cfg),
           now[NEW_TESTS:])
    hit = page_cache.kept_page(key)
    if hit is not None and hit[1]["generation"] in (None, now):
        return page_cache.answer(request, hit[0], _others_html(request, hit[1], now))
    return await _make_test_page(request, test_id, status, extra, (key, now, cfg))


async def _make_test_page(request: Request, test_id: int, status: int, extra: dict, kept):
    """A test's page made (``kept``: (key, generation, configuration) under which
    :func:`stored_test_page` keeps it, or None for a page that is not kept)."""
    from markupsafe import Markup

    from axiscal.compensation.controllers import CONTROLLERS
    from axiscal.store.corrections import audit
    from axiscal.web import page_cache
    from axiscal.web.correction_pages import SHOWN
    from axiscal.web.signoff_pages import has_rows, signoff_context
    from axiscal.web.squareness_pages import made_from, partners

    st, env = request.app.state.store, request.app.state.templates.env
    t = st.get(test_id)
    known = await run_in_threadpool(_known, st, t, kept[0][-1] if kept else None)   # once
    ev, cfg, parts = _test_view(env, t, kept_only=True, st=st, known=known) or \
        await run_in_threadpool(_test_view, env, t, False, st, known)
    if kept is not None:
        cfg = kept[2]
    # a straightness test's page lists the other axes' straightness tests: kept under the
    # whole generation (any new test makes it again)
    summary = {"id": test_id, "machine": t.summary.machine, "axis": t.summary.axis,
               "kind": t.summary.kind, "withdrawn": t.summary.withdrawn,
               "generation": kept[1] if kept and t.summary.kind == "straightness" else None}
    others = _others_html(request, summary, kept[1] if kept else None)
    response = render(request, "test.html", f"Test {test_id}: {t.summary.machine} "
                      f"{t.summary.axis}", status, t=t, ev=ev, **parts,
                      signoff=signoff_context(st, t, ev, None,
                                              request.query_params.get("certificate", ""), cfg,
                                              known, kept[0][-1] if kept else None),
                      controllers=sorted(CONTROLLERS),
                      others_html=Markup(page_cache.PART_MARK) if kept else others,
                      partners=partners(st, t), made_from=made_from(st, ev),
                      audit_entries=audit(st, test_id=test_id, limit=SHOWN) if has_rows(
                          st, kept[0][-1] if kept else None, "audit", test_id) else [],
                      **extra,
                      **({"csrf": page_cache.CSRF_MARK} if kept else {}))
    if kept is None:
        return response
    body = page_cache.keep_page(kept[0], response, summary)
    return page_cache.answer(request, body if body is not None else response.body, others)


def _others_html(request: Request, summary: dict, now: tuple | None):
    """The list of the other tests of a test's axis to compare it with (``_test_others.html``):
    the axis's newest tests read once per generation (:func:`axiscal.web.memo.memoised`)."""
    from markupsafe import Markup

    from axiscal.web.memo import memoised

    st = request.app.state.store
    machine, axis, kind = summary["machine"], summary["axis"], summary["kind"]
    newest = memoised(st, ("others", machine, axis, kind), lambda: st.tests(
        machine=machine, axis=axis, kind=kind, limit=11, parameters=()), now)
    others = [o for o in newest if o.id != summary["id"]]
    if not others:
        return Markup("")
    return Markup(request.app.state.templates.env.get_template("_test_others.html").render(
        others=others, t={"summary": summary}))


def _known(st, t, generation: tuple | None = None) -> dict:
    """What a test's page and its sign-off form both read of the history: the test's
    certificates, the laboratory, the test's drift checks; with the page's ``generation``, the
    laboratory and which tests have certificates or drift checks kept under it
    (:func:`axiscal.web.signoff_pages.kept_read`), so a test without them is not asked."""
    from axiscal.store.laboratory import drift_checks, laboratory
    from axiscal.web.signoff_pages import has_rows, kept_read

    tid = t.summary.id
    return {"certificates": st.certificates(test_id=tid)
            if has_rows(st, generation, "certificate", tid) else [],
            "laboratory": kept_read(st, generation, ("laboratory",), lambda: laboratory(st)),
            "drift_checks": drift_checks(st, tid)
            if has_rows(st, generation, "drift_check", tid) else []}


def _test_view(env, t, kept_only: bool = False, st=None, known: dict | None = None
               ) -> tuple | None:
    """(evaluation, user configuration, page parts) of stored test ``t`` of history ``st``:
    the parts computed once from the evaluation and the configuration (kept by
    :func:`axiscal.store.cache.derived`, on disk), and what the page shows of them rendered
    once (``results_html``, the same for every user: kept on disk too, so another worker
    process reads it; the templates are part of the version the cache is kept under). With
    ``kept_only``, None unless the evaluation and the parts are kept already (nothing is made).

    The U shown is the certificate's (review defect 8): the budget made by the certificate's one
    call from the configuration of the test's certificate (:func:`_certified_config`), so the
    laboratory's CMC and E_VE, the test's drift check and inputs apply on the page as on the
    certificate."""
    from markupsafe import Markup

    from axiscal.report.issue import load_config
    from axiscal.store.cache import derived, digest, lookup

    cfg = load_config(None)
    scfg = _certified_config(st, t, cfg, known)
    # the page names the machine and axis as the history keeps them (a rename makes it again)
    names = [t.summary.machine, t.summary.axis]
    what = f"test-page-{digest([cfg, scfg, t.result.get('uncertainty_inputs'), *names])}"
    if kept_only:
        ev = lookup(t.sha256, "evaluated", t.size)
        parts = lookup(t.sha256, what) if ev is not None else None
        if parts is None:
            return None
        ev, parts = t.named(ev[0]), parts[0]
    else:
        ev = t.named(t.evaluate_again())
        parts = derived(t.sha256, what, lambda: _test_parts(t, ev, scfg, st))   # once, kept
    html = derived(t.sha256, f"{what}-{t.summary.id}.html", lambda: env.get_template(
        "_test_results.html").render(t=t, ev=ev, **parts))
    return ev, cfg, {**parts, "results_html": Markup(html)}


def _certified_config(st, t, user_cfg: dict, known: dict | None = None) -> dict | None:
    """The configuration the test's certificate is made with: the one kept with its issued
    certificate, else the sign-off's without a job (:func:`axiscal.store.laboratory.
    signoff_config`: the test's inputs over the laboratory's, its drift check over both);
    None without a history (the stored inputs alone)."""
    if st is None:
        return None
    known = known or _known(st, t)
    issued = next((c for c in known["certificates"] if c.status == "issued"), None)
    if issued is not None:
        return st.certificate(issued.number, issued.laboratory).inputs["config"]
    from axiscal.store.laboratory import signoff_config

    return signoff_config(st, t, user_cfg, lab=known["laboratory"],
                          checks=known["drift_checks"])



def prepare_view(app, test_id: int) -> None:
    """Make a new test's page parts (its figure, tables, rendering) when it is stored, so its
    first view is a look-up (:func:`axiscal.store.cache.derived` makes a product once). A failure
    here is only logged: the upload is stored; the view makes the parts again and shows its
    error."""
    import logging

    try:
        _test_view(app.state.templates.env, app.state.store.get(test_id), False,
                   app.state.store)
    except Exception:                         # noqa: BLE001 - best effort, the view reports
        logging.getLogger("axiscal.web").warning("test %s: page not made after upload",
                                                 test_id, exc_info=True)


def _test_parts(t, ev, scfg: dict | None = None, st=None) -> dict:
    """The parts of a test's page that are functions of its record and the configuration
    ``scfg`` of its certificate only (kept by :func:`axiscal.store.cache.derived`): the plot,
    the ISO 230-2 Annex A budget the certificate states (its one call,
    :func:`axiscal.report.issue.budget_for`; another kind's record as its certificate makes
    it, :func:`axiscal.store.laboratory.signoff_record`) and the decisions, the other
    standards, the per-target rows, the kind's view."""
    import dataclasses

    from axiscal.store.kinds import with_uncertainty
    from axiscal.web.kind_pages import kind_view
    from axiscal.web.signoff_pages import signoff_plot

    rec = with_uncertainty(ev, t.result.get("uncertainty_inputs"))   # the stored inputs' budget
    if scfg is not None and ev.kind == "iso230-2":
        from axiscal.report.issue import budget_for

        rec = dataclasses.replace(rec, budget=budget_for(ev.dataset, ev.evaluation, scfg))
    elif scfg is not None and rec.budget is not None:
        from axiscal.store.laboratory import signoff_record

        rec = signoff_record(st, t, scfg)
    if ev.kind != "iso230-2":
        return {"plot": None, "budget": None, "decisions": {}, "standards": None,
                "targets": [], "view": kind_view(rec)}
    return {"plot": signoff_plot(ev), "budget": rec.budget, "decisions": _decisions(rec),
            "standards": _other_standards(ev), "targets": _target_rows(ev),
            "view": kind_view(rec)}


def _target_rows(ev) -> list:
    r = ev.evaluation
    return [(float(t), _f(u), _f(d), _f(b), _f(rev), _f(ri)) for t, u, d, b, rev, ri in
            zip(r.targets, r.mean_up, r.mean_down, r.mean_bi, r.reversal, r.R_i)]


def _f(v):
    import math

    return None if v is None or math.isnan(float(v)) else float(v)


def _decisions(rec) -> dict:
    """If the user configuration names tolerances, the ISO 14253-1 decisions (by parameter)
    with the budget of the test's record (the inputs stored with it)."""
    from axiscal.report.issue import decisions_for, load_config

    decisions, _, _ = decisions_for(rec.evaluation.parameters(), rec.budget, {},
                                    load_config(None), None)
    return {d.parameter: d for d in decisions}


def _other_standards(ev) -> dict:
    """The test by every other positioning standard, for the test page: the table kept with
    its evaluation (:func:`axiscal.store.kinds.other_standards`), made again only for an
    evaluation kept without it."""
    if ev.standards is not None:
        return ev.standards
    from axiscal.store.kinds import other_standards

    return other_standards(ev.dataset)[1]
