"""``/laboratory``: the laboratory as the history keeps it (:mod:`axiscal.store.laboratory`),
shown to everyone and edited by an engineer, each change an entry of the audit trail with its
reason (ISO/IEC 17025:2017 §7.5.2). The same fields as the sign-off form's laboratory
(:mod:`axiscal.web.signoff_form`), which keeps them when a certificate is issued with them."""

from __future__ import annotations

from fastapi import FastAPI, Request
from fastapi.responses import HTMLResponse, RedirectResponse
from starlette.concurrency import run_in_threadpool

from axiscal.errors import AxiscalError, InputError
from axiscal.web.inputs import checked_form, require_engineer
from axiscal.web.rendering import render
from axiscal.web.signoff_form import (INSTRUMENT_KEYS, INSTRUMENTS, LAB_FIELDS, LABELS,
                                      lab_defaults, lab_from_form)

__all__ = ["add_routes"]

_FIELDS = (*LAB_FIELDS, *(f"instrument{i}_{k}" for i in range(1, INSTRUMENTS + 1)
                          for k in INSTRUMENT_KEYS), "reason", "by")


def add_routes(app: FastAPI) -> None:
    """Add ``GET`` and ``POST /laboratory``."""

    @app.get("/laboratory", response_class=HTMLResponse)
    def laboratory_page(request: Request):
        st = request.app.state.store
        return render(request, "laboratory.html", "Laboratory", **_view(st, None))

    @app.post("/laboratory", response_class=HTMLResponse)
    async def laboratory_save(request: Request):
        form = await checked_form(request)
        require_engineer(request)
        values = {k: str(form.get(k, "") or "").strip() for k in _FIELDS}
        st = request.app.state.store
        account = request.state.session.get("name")      # None: one's own computer
        by = account or values["by"]
        try:
            await run_in_threadpool(_save, st, values, by, account)
        except AxiscalError as exc:
            return render(request, "laboratory.html", "Laboratory", getattr(exc, "status", 400),
                          error=str(exc), **_view(st, values))
        return RedirectResponse("/laboratory?saved=1", 303)


def _view(st, values: dict | None) -> dict:
    from axiscal.io.user_config import merge
    from axiscal.report.issue import load_config
    from axiscal.store.corrections import audit
    from axiscal.store.laboratory import laboratory

    kept = laboratory(st)
    if values is None:
        lab = merge(load_config(None), kept)
        values = lab_defaults(lab)
        inst = lab.get("instrument", [])
        for i, row in enumerate(inst if isinstance(inst, list) else [inst], 1):
            if i <= INSTRUMENTS:
                values.update({f"instrument{i}_{k}": str(row.get(k, "")) for k in
                               INSTRUMENT_KEYS})
    entries = [a for a in audit(st, limit=500) if a.action == "laboratory"][:20]
    return {"form": values, "labels": LABELS, "instruments": range(1, INSTRUMENTS + 1),
            "kept": bool(kept), "audit_entries": entries}


def _save(st, values: dict, by: str, account: str | None = None) -> None:
    """The form's laboratory over what the history keeps: the fields shown replace theirs (an
    emptied field removes its value), other uncertainty inputs stay. Signed in (``account``),
    the signatories are changed only by one of them (:func:`axiscal.store.laboratory.
    set_laboratory`)."""
    from axiscal.report.issue import load_config
    from axiscal.store.laboratory import laboratory, set_laboratory
    from axiscal.web.signoff_pages import job_from_form

    kept = laboratory(st)
    base = {k: v for k, v in kept.items() if k not in ("company", "signatory", "instrument",
                                                       "uncertainty")}
    unc = {k: v for k, v in (kept.get("uncertainty") or {}).items()
           if k not in ("e_ve", "e_ve_source", "linear")}
    linear = {k: v for k, v in ((kept.get("uncertainty") or {}).get("linear") or {}).items()
              if k != "cmc"}
    if linear:
        unc["linear"] = linear
    if unc:
        base["uncertainty"] = unc
    if not values.get("reason"):
        raise InputError("Reason: say why the laboratory changes; the audit trail records it")
    job, _, _, _ = job_from_form(values, ())
    set_laboratory(st, lab_from_form(values, base, job.get("instrument", [])), by=by,
                   reason=values["reason"], account=account, inherited=load_config(None))
