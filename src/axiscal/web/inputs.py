"""What a request brings to the workbench, checked before a page uses it: the POSTed form (its
CSRF token and the bounds of its fields), the role that may change things, the numbers typed in a
form, and the ids in an address (out of range is an error page, never a 500).

It sits below :mod:`axiscal.web.app` and every module of pages, which all use it.
"""

from __future__ import annotations

import secrets
from typing import Annotated

from fastapi import Query, Request
from fastapi import Path as InPath

from axiscal.errors import InputError
from axiscal.web.guards import FORM_OVERHEAD, TooLarge, check_fields
from axiscal.web.rendering import Forbidden

__all__ = ["MAX_ID", "TestId", "QueryId", "Page", "checked_form", "require_engineer",
           "form_number"]

#: Largest id a test can have (SQLite's and PostgreSQL's 64-bit integer keys).
MAX_ID = 2**63 - 1

#: A test's id in a path, a query, and a page number: out of range is an error page, not a 500.
TestId = Annotated[int, InPath(ge=1, le=MAX_ID)]
QueryId = Annotated[int, Query(ge=1, le=MAX_ID)]
Page = Annotated[int, Query(ge=1, le=10**9)]


async def checked_form(request: Request, csrf: bool = True):
    """The POSTed form, after its CSRF token (field ``csrf`` or header ``X-CSRF-Token``) is
    checked against the session's (OWASP synchronizer-token pattern) and its text fields against
    their bound (:func:`~axiscal.web.guards.check_fields`)."""
    try:
        form = await request.form(max_files=4, max_fields=64,
                                  max_part_size=request.app.state.upload_limit + FORM_OVERHEAD)
    except TooLarge:
        raise
    except Exception:                      # a malformed body: say so, never a trace
        raise InputError("the form could not be read") from None
    check_fields(form)
    if not csrf:
        return form
    token = request.headers.get("x-csrf-token") or form.get("csrf")
    if not token or not secrets.compare_digest(str(token), request.state.session["csrf"]):
        raise Forbidden("the form is out of date (CSRF token); reload the page and send it again")
    return form


def require_engineer(request: Request) -> None:
    """Refuse a viewer's attempt to change something."""
    if request.state.session.get("role") != "engineer":
        raise Forbidden("your role is viewer: uploading, storing and writing tables need an "
                        "engineer's account")


def form_number(text, what: str, low: float, high: float, required: bool = False,
                whole: bool = False) -> float:
    """A number typed in a form field, within [low, high] (a whole one if ``whole``); an empty
    field is ``low`` unless ``required``. Errors name the field (``what``) and the range."""
    import math

    if text in (None, ""):
        if required:
            raise InputError(f"{what}: give a number")
        return low
    try:
        v = float(str(text).replace(",", "."))
    except ValueError:
        raise InputError(f"{what} = {text!r}: not a number") from None
    if not math.isfinite(v) or not low <= v <= high or (whole and v != int(v)):
        kind = "a whole number" if whole else "a number"
        raise InputError(f"{what} = {text}: give {kind} from {low:g} to {high:g}")
    if v <= 0 and what == "length or travel":
        raise InputError(f"{what} = {text}: must be positive")
    return v
