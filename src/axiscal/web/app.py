"""The workbench application: FastAPI routes over the same library the command line calls.

:func:`create_app` builds it; ``axiscal serve`` runs it with uvicorn. Pages are Jinja2 templates
(autoescaped) with htmx and uPlot served from ``static/`` (vendored; nothing is fetched at run
time). A library error (:class:`~axiscal.errors.AxiscalError`) is shown on the page in the same
words the command line prints; anything else is an "internal error" page, its traceback only in
the server's log. Who may do what is in :mod:`axiscal.web.security`.
"""

from __future__ import annotations

import logging
import secrets
from pathlib import Path
from urllib.parse import quote, urlencode

from fastapi import FastAPI, Request
from fastapi.responses import HTMLResponse, RedirectResponse, Response
from fastapi.staticfiles import StaticFiles
from fastapi.templating import Jinja2Templates

from axiscal.errors import AxiscalError, InputError
from axiscal.web.security import MAX_UPLOAD_BYTES, Sessions, UserFile

__all__ = ["create_app", "Forbidden"]

HERE = Path(__file__).parent
LOG = logging.getLogger("axiscal.web")
COOKIE, ANON = "axiscal_session", "axiscal_anon"


class Forbidden(AxiscalError, PermissionError):
    """The user's role may not do this (or a form's CSRF token is wrong)."""


def create_app(db_url: str | None = None, users_file=None, require_login: bool = False,
               upload_limit: int = MAX_UPLOAD_BYTES) -> FastAPI:
    """The workbench over the history database ``db_url`` (default: the user's database).

    Parameters
    ----------
    db_url : str, optional
        SQLAlchemy URL of the history (``sqlite:///...`` or ``postgresql+psycopg://...``).
    users_file : path, optional
        Accounts (:class:`~axiscal.web.security.UserFile`); with ``require_login`` every page
        needs a login.
    require_login : bool
        True when served on a non-loopback address (``axiscal serve`` decides).
    upload_limit : int, bytes
    """
    from axiscal.web import pages

    users = UserFile.load(users_file) if users_file else None
    if require_login and (users is None or not users.users):
        raise InputError("serving beyond this computer needs accounts: add one with "
                         "'axiscal serve --add-user NAME --role engineer' (and --users FILE)")
    app = FastAPI(title="axiscal workbench", docs_url=None, redoc_url=None, openapi_url=None)
    app.state.sessions = Sessions()
    app.state.users = users
    app.state.require_login = require_login
    app.state.upload_limit = int(upload_limit)
    app.state.db_url = db_url
    app.state.templates = Jinja2Templates(directory=str(HERE / "templates"))
    app.state.templates.env.globals.update(zip=zip, query=query)
    app.state.templates.env.filters["unit"] = lambda u: {"um": "µm", "um/m": "µm/m"}.get(u, u)
    app.mount("/static", StaticFiles(directory=str(HERE / "static")), name="static")

    @app.middleware("http")
    async def guard(request: Request, call_next):
        session = _session(request)
        request.state.session = session
        public = request.url.path.startswith("/static/") or request.url.path == "/login"
        if session is None and not public:
            if request.method == "GET":
                return RedirectResponse(f"/login?next={quote(request.url.path)}", 303)
            return render_error(request, "log in first", 401)
        response = await call_next(request)
        if session and session.get("new_anon"):
            response.set_cookie(ANON, session["anon"], httponly=True, samesite="strict")
        response.headers.setdefault("X-Content-Type-Options", "nosniff")
        response.headers.setdefault("X-Frame-Options", "DENY")
        response.headers.setdefault("Content-Security-Policy",
                                    "default-src 'self'; img-src 'self' data:; "
                                    "style-src 'self' 'unsafe-inline'; object-src 'none'")
        return response

    @app.exception_handler(AxiscalError)
    async def library_error(request: Request, exc: AxiscalError):
        status = 403 if isinstance(exc, Forbidden) else 404 if isinstance(exc, LookupError) \
            else 400
        return render_error(request, str(exc), status)

    from starlette.exceptions import HTTPException

    @app.exception_handler(HTTPException)
    async def http_error(request: Request, exc: HTTPException):
        words = {404: "no such page", 405: "this page does not take that request"}
        return render_error(request, words.get(exc.status_code, str(exc.detail)), exc.status_code)

    @app.exception_handler(Exception)
    async def internal_error(request: Request, exc: Exception):
        LOG.exception("internal error on %s %s", request.method, request.url.path)
        return render_error(request, "internal error: the server's log has the details", 500)

    pages.add_routes(app)
    return app


def render(request: Request, template: str, title: str, status: int = 200, **context):
    """A page with the common context (user, role, CSRF token, may the user write)."""
    s = getattr(request.state, "session", None) or {}
    ctx = {"request": request, "title": title, "csrf": s.get("csrf", ""),
           "user": s.get("name"), "role": s.get("role"),
           "can_write": s.get("role") == "engineer", **context}
    return request.app.state.templates.TemplateResponse(request, template, ctx,
                                                        status_code=status)


def render_error(request: Request, message: str, status: int):
    """The error page: the message in plain words (escaped), never a traceback."""
    if getattr(request.state, "session", None) is None:
        request.state.session = {}
    return render(request, "error.html", "Something needs attention", status, error=message)


async def checked_form(request: Request):
    """The POSTed form, after its CSRF token (field ``csrf`` or header ``X-CSRF-Token``) is
    checked against the session's (OWASP synchronizer-token pattern)."""
    try:
        form = await request.form(max_part_size=request.app.state.upload_limit + 1)
    except Exception:                      # a malformed body: say so, never a trace
        raise InputError("the form could not be read") from None
    token = request.headers.get("x-csrf-token") or form.get("csrf")
    if not token or not secrets.compare_digest(str(token), request.state.session["csrf"]):
        raise Forbidden("the form is out of date (CSRF token); reload the page and send it again")
    return form


def require_engineer(request: Request) -> None:
    """Refuse a viewer's attempt to change something."""
    if request.state.session.get("role") != "engineer":
        raise Forbidden("your role is viewer: uploading, storing and writing tables need an "
                        "engineer's account")


def download(content, filename: str, media_type: str) -> Response:
    """A file download with a safe name (letters, digits, '.', '-', '_' only)."""
    safe = "".join(c if c.isalnum() or c in "._-" else "_" for c in filename) or "download"
    return Response(content, media_type=media_type,
                    headers={"Content-Disposition": f'attachment; filename="{safe}"'})


def _session(request: Request) -> dict | None:
    app = request.app
    sessions: Sessions = app.state.sessions
    if app.state.users is not None and app.state.users.users:
        return sessions.read(request.cookies.get(COOKIE))
    anon = request.cookies.get(ANON)
    new = not anon or len(anon) != 32 or not anon.isalnum()
    if new:
        anon = secrets.token_hex(16)
    return {"name": None, "role": "engineer", "csrf": sessions.csrf_for(anon), "anon": anon,
            "new_anon": new}


def query(**params) -> str:
    """A URL query string of the non-empty parameters."""
    return urlencode({k: v for k, v in params.items() if v not in (None, "")})


def login_routes(app: FastAPI) -> None:
    """``/login`` and ``/logout``."""

    @app.get("/login", response_class=HTMLResponse)
    async def login_form(request: Request, next: str = "/"):
        request.state.session = request.state.session or {}
        return render(request, "login.html", "Log in", next=_local(next))

    @app.post("/login")
    async def login(request: Request):
        form = await request.form()
        users = request.app.state.users
        request.state.session = request.state.session or {}
        user = users.check(str(form.get("username", "")), str(form.get("password", ""))) \
            if users else None
        if user is None:
            return render(request, "login.html", "Log in", 401, next=_local(form.get("next")),
                          error="wrong user name or password")
        resp = RedirectResponse(_local(form.get("next")), 303)
        resp.set_cookie(COOKIE, request.app.state.sessions.issue(user.name, user.role),
                        httponly=True, samesite="strict")
        return resp

    @app.post("/logout")
    async def logout(request: Request):
        resp = RedirectResponse("/login", 303)
        resp.delete_cookie(COOKIE)
        return resp


def _local(path) -> str:
    """Only a path on this site is a place to go back to (no open redirect)."""
    p = str(path or "/")
    return p if p.startswith("/") and not p.startswith("//") else "/"
