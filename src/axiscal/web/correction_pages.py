"""Corrections in the workbench: rename and merge machines and axes, edit a test's metadata,
withdraw and reinstate a test, and the audit trail (:mod:`axiscal.store.corrections`, the same
calls as ``axiscal history rename-machine ... audit``; ISO/IEC 17025:2017 §7.5.2, §8.4.2).

Every change is a POST with the session's CSRF token, by an engineer, with a reason; who made it
is the logged-in account, or (in the no-login local mode) the name typed in the form. The pages
of a machine and of a test hand their templates the newest :data:`SHOWN` entries of the trail
(``audit_entries``). Machines are addressed by id, so any name, "/" included, reaches its page.
"""

from __future__ import annotations

from typing import Annotated

from fastapi import FastAPI, Request
from fastapi import Path as InPath
from fastapi.responses import HTMLResponse, RedirectResponse
from starlette.concurrency import run_in_threadpool

from axiscal.errors import InputError
from axiscal.web.inputs import MAX_ID, checked_form, require_engineer
from axiscal.web.rendering import render

__all__ = ["add_routes"]

Id = Annotated[int, InPath(ge=1, le=MAX_ID)]
#: Entries of the trail shown on a machine's or a test's page (the whole trail: /audit).
SHOWN = 50


def add_routes(app: FastAPI) -> None:
    """Add the correction routes and the audit trail page."""
    _machine_routes(app)
    _test_routes(app)


def _store(request: Request):
    return request.app.state.store


async def _change(request: Request, fn, *args, fields=(), back: str, **kw):
    """Read the form, check the token and the role, make the change, go back."""
    form = await checked_form(request)
    require_engineer(request)
    values = {k: str(form.get(k, "") or "").strip() for k in fields}
    by = request.state.session.get("name") or str(form.get("by", "") or "").strip()
    await run_in_threadpool(fn, _store(request), *args, *values.values(), by=by,
                            reason=str(form.get("reason", "") or ""), **kw)
    return RedirectResponse(back, 303)


def _machine_routes(app: FastAPI) -> None:
    from axiscal.store import corrections as c

    @app.post("/machine/{machine_id}/rename")
    async def rename_machine(request: Request, machine_id: Id):
        return await _change(request, c.rename_machine, machine_id, fields=("name",),
                            back=f"/machine/{machine_id}")

    @app.post("/machine/{machine_id}/rename-axis")
    async def rename_axis(request: Request, machine_id: Id):
        return await _change(request, c.rename_axis, machine_id, fields=("axis", "name"),
                            back=f"/machine/{machine_id}")

    @app.post("/machine/{machine_id}/merge")
    async def merge_machine(request: Request, machine_id: Id):
        form = await checked_form(request)
        into = _id(form.get("into"), "the machine to merge into")
        return await _change(request, c.merge_machines, machine_id, into,
                            back=f"/machine/{into}")

    @app.post("/machine/{machine_id}/merge-axes")
    async def merge_axes(request: Request, machine_id: Id):
        return await _change(request, c.merge_axes, machine_id, fields=("axis", "into"),
                            back=f"/machine/{machine_id}")



def _test_routes(app: FastAPI) -> None:
    from axiscal.store import corrections as c

    @app.post("/tests/{test_id}/edit")
    async def edit(request: Request, test_id: Id):
        form = await checked_form(request)
        changes = {k: str(form.get(k)).strip() for k in c.EDITABLE if form.get(k) is not None}
        old = _store(request).get(test_id)
        shown = {"date": old.summary.tested_at.strftime("%Y-%m-%d"), "operator": old.operator,
                 "instrument": old.instrument, "note": old.summary.note}
        changes = {k: v for k, v in changes.items()        # the fields changed (a date left
                   if v != shown[k] and (v or k != "date")}  # empty by the browser: unchanged
        return await _change(request, c.edit_test, test_id, back=f"/tests/{test_id}",
                            **changes)

    @app.post("/tests/{test_id}/withdraw")
    async def withdraw(request: Request, test_id: Id):
        return await _change(request, c.withdraw, test_id, back=f"/tests/{test_id}")

    @app.post("/tests/{test_id}/reinstate")
    async def reinstate(request: Request, test_id: Id):
        return await _change(request, c.reinstate, test_id, back=f"/tests/{test_id}")

    @app.get("/audit", response_class=HTMLResponse)
    def audit_page(request: Request):
        return render(request, "audit.html", "Audit trail: every change to the history",
                      entries=c.audit(_store(request), limit=1000))


def _id(text, what: str) -> int:
    try:
        n = int(str(text))
    except ValueError:
        raise InputError(f"choose {what}") from None
    if not 0 < n <= MAX_ID:
        raise InputError(f"choose {what}")
    return n
