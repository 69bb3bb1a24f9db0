"""How every page of the workbench answers: a page from its template with the common context,
the error page (the message in plain words, a way back, never a traceback), a file download with a
safe name, and the query strings of its links.

It sits below :mod:`axiscal.web.app` and every module of pages, which all use it, so that none of
them imports another to render (the application builds the routes; the routes do not reach back
into the application).
"""

from __future__ import annotations

from urllib.parse import urlencode

from fastapi import Request
from fastapi.responses import Response

from axiscal.errors import AxiscalError
from axiscal.web.guards import host_allowed

__all__ = ["Forbidden", "render", "render_error", "download", "query"]


class Forbidden(AxiscalError, PermissionError):
    """The user's role may not do this (or a form's CSRF token is wrong)."""


def render(request: Request, template: str, title: str, status: int = 200, **context):
    """A page with the common context (user, role, CSRF token, may the user write)."""
    s = getattr(request.state, "session", None) or {}
    ctx = {"request": request, "title": title, "csrf": s.get("csrf", ""),
           "user": s.get("name"), "role": s.get("role"),
           "can_write": s.get("role") == "engineer",
           "accounts": bool(request.app.state.users and request.app.state.users.users),
           **context}
    return request.app.state.templates.TemplateResponse(request, template, ctx,
                                                        status_code=status)


def render_error(request: Request, message: str, status: int):
    """The error page: the message in plain words (escaped), never a traceback."""
    if getattr(request.state, "session", None) is None:
        request.state.session = {}
    from http import HTTPStatus

    back = _came_from(request)
    return render(request, "error.html", "Something needs attention", status, error=message,
                  code=status, meaning=HTTPStatus(status).phrase, back=back)


def _came_from(request: Request) -> str | None:
    """The page of this site the user came from (Referer of an allowed host), to go back to."""
    from urllib.parse import urlsplit

    ref = request.headers.get("referer") or ""
    try:
        parts = urlsplit(ref)
    except ValueError:
        return None
    hosts = getattr(request.app.state, "hosts", frozenset())
    if not parts.hostname or parts.hostname.lower() not in hosts or \
            not host_allowed(request.headers.get("host"), hosts):
        return None
    back = parts.path + (f"?{parts.query}" if parts.query else "")
    return back if back.startswith("/") and not back.startswith("//") and \
        back != request.url.path else None


def download(content, filename: str, media_type: str) -> Response:
    """A file download with a safe name (letters, digits, '.', '-', '_' only)."""
    safe = "".join(c if c.isalnum() or c in "._-" else "_" for c in filename) or "download"
    return Response(content, media_type=media_type,
                    headers={"Content-Disposition": f'attachment; filename="{safe}"'})


def query(**params) -> str:
    """A URL query string of the non-empty parameters."""
    return urlencode({k: v for k, v in params.items() if v not in (None, "")})
