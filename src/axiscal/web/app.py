"""The workbench application: FastAPI routes over the same library the command line calls.

:func:`create_app` builds it; ``axiscal serve`` runs it with uvicorn. Pages are Jinja2 templates
(autoescaped) with htmx and uPlot served from ``static/`` (vendored; nothing is fetched at run
time). A library error (:class:`~axiscal.errors.AxiscalError`) is shown on the page in the same
words the command line prints; anything else is an "internal error" page, its traceback only in
the server's log. Who may do what is in :mod:`axiscal.web.security`; the checks every request
passes (Host allow-list, Origin of a POST, bounded bodies and fields) in :mod:`axiscal.web.guards`;
sessions and the back-off of wrong passwords in :mod:`axiscal.web.sessions`.

Every error is a page of the workbench with a way back, never FastAPI's JSON: a path that names
nothing (``/tests/abc``, an id beyond the database's 64-bit integers) is 404, a query parameter
out of its range (``?page=99999999999999999999``) or missing (compare with one test) is 400.
"""

from __future__ import annotations

import logging
import secrets
from pathlib import Path
from urllib.parse import quote

from fastapi import FastAPI, Request
from fastapi.exceptions import RequestValidationError
from fastapi.responses import RedirectResponse
from fastapi.staticfiles import StaticFiles
from fastapi.templating import Jinja2Templates

from axiscal.errors import AxiscalError, InputError
from axiscal.report.labels import name as quantity_name
from axiscal.report.labels import unit_text
from axiscal.web.guards import FORM_OVERHEAD, BodyLimit, allowed_hosts, host_allowed, origin_allowed
from axiscal.web.inputs import MAX_ID
from axiscal.web.login import COOKIE
from axiscal.web.rendering import Forbidden, query, render_error
from axiscal.web.rendering import download  # noqa: F401  (callers import it from here too)
from axiscal.web.security import MAX_UPLOAD_BYTES, UserFile
from axiscal.web.sessions import ABSOLUTE_SECONDS, IDLE_SECONDS, LoginThrottle, Sessions
from axiscal.web.workers import WORKER_ID

__all__ = ["create_app", "Forbidden", "MAX_ID"]

HERE = Path(__file__).parent
LOG = logging.getLogger("axiscal.web")
ANON = "axiscal_anon"


def create_app(db_url: str | None = None, users_file=None, require_login: bool = False,
               upload_limit: int = MAX_UPLOAD_BYTES, hosts=None,
               session_idle: float = IDLE_SECONDS, session_max: float = ABSOLUTE_SECONDS,
               sessions_folder=None) -> FastAPI:
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
    hosts : iterable of str, optional
        Host names served (default: the loopback names, :func:`~axiscal.web.guards.allowed_hosts`
        of 127.0.0.1); a request naming another host gets a 400 page.
    session_idle, session_max : float, seconds
        A login ends after this long without a request, and this long after the login.
    sessions_folder : path, optional
        Keep the sessions there, shared by several worker processes
        (:class:`~axiscal.web.workers.SharedSessions`); default: in this process's memory.
    """
    from axiscal.web import correction_pages, pages

    users = UserFile.load(users_file) if users_file else None
    if require_login and (users is None or not users.users):
        raise InputError("serving beyond this computer needs accounts: add one with "
                         "'axiscal serve --add-user NAME --role engineer' (and --users FILE)")
    app = FastAPI(title="axiscal workbench", docs_url=None, redoc_url=None, openapi_url=None)
    if sessions_folder:
        from axiscal.web.workers import SharedSessions, SharedThrottle

        app.state.sessions = SharedSessions(sessions_folder, session_idle, session_max)
        app.state.throttle = SharedThrottle(app.state.sessions)
    else:
        app.state.sessions = Sessions(session_idle, session_max)
        app.state.throttle = LoginThrottle()
    app.state.hosts = frozenset(h.lower() for h in hosts) if hosts else allowed_hosts("127.0.0.1")
    app.state.users = users
    app.state.require_login = require_login
    app.state.upload_limit = int(upload_limit)
    app.state.db_url = db_url
    app.state.templates = Jinja2Templates(directory=str(HERE / "templates"))
    # templates are read once: not looked up on disk (a stat of each file) at every rendering
    app.state.templates.env.auto_reload = False
    app.state.templates.env.globals.update(zip=zip, query=query)
    app.state.templates.env.filters["unit"] = unit_text
    # a parameter as the interface names it: its symbol in ISO 230-2:2014 clause 3 (A↑, B̄),
    # else its label (Reversal spike X decay length); the key goes in a title attribute
    app.state.templates.env.filters["symbol"] = lambda k, axes="XY": quantity_name(k, axes)
    from axiscal.report.field_labels import key_label, value_text
    from axiscal.report.labels import fixed

    # an audit entry's values as a person reads them (not a Python list or dict)
    app.state.templates.env.filters.update(key_label=key_label, readable=value_text,
                                           fixed=fixed)     # fixed(3): no "-0.000"
    app.mount("/static", StaticFiles(directory=str(HERE / "static")), name="static")
    app.add_middleware(BodyLimit, limit=app.state.upload_limit + FORM_OVERHEAD)
    _add_guard(app)
    _add_error_pages(app)
    _add_favicon(app)
    pages.add_routes(app)
    correction_pages.add_routes(app)       # rename, merge, edit, withdraw; the audit trail
    return app


def _add_guard(app: FastAPI) -> None:
    """The middleware every request passes: Host, Origin of a POST, session, and the protective
    headers of every answer (:class:`_Guard`)."""
    app.add_middleware(_Guard)


class _Guard:
    """ASGI middleware of :func:`_add_guard`: a refusal is answered here; any other request goes
    on to the application, whose answer gets the headers as it starts.

    A plain ASGI middleware, not Starlette's ``BaseHTTPMiddleware`` (``@app.middleware``): that
    one runs the application in a second task and hands every message of the request and of the
    answer across a memory stream, so each request waited for the event loop a few more times;
    with 20 clients on a busy loop each wait was a round of every ready callback (an upload, a
    POST and the GET it is sent on to, passed it four times)."""

    def __init__(self, app):
        self.app = app

    async def __call__(self, scope, receive, send):
        if scope["type"] != "http":
            return await self.app(scope, receive, send)
        from starlette.datastructures import MutableHeaders

        request = Request(scope)
        public_asset = _public_asset(request.url.path)
        refusal = _refusal(request)
        session = None if refusal is not None else request.state.session
        cookie = _anon_cookie(session["anon"]) if session and session.get("new_anon") else None

        async def headed(message):
            if message["type"] == "http.response.start":
                headers = MutableHeaders(scope=message)
                if refusal is None:
                    if cookie:
                        headers.append("set-cookie", cookie)
                    for name, value in _PROTECTIVE:
                        headers.setdefault(name, value)
                    if not public_asset:        # a page of a session: never kept, so Back
                        headers.setdefault("Cache-Control", "no-store")  # after log-out asks
                headers["X-Axiscal-Worker"] = WORKER_ID     # which process answered (opaque)
            await send(message)

        await (refusal or self.app)(scope, receive, headed)


#: Headers of every answer the application gives (unless it set them itself).
_PROTECTIVE = (("X-Content-Type-Options", "nosniff"), ("X-Frame-Options", "DENY"),
               ("Content-Security-Policy", "default-src 'self'; img-src 'self' data:; "
                "style-src 'self' 'unsafe-inline'; object-src 'none'"))


def _refusal(request: Request):
    """The answer to a request refused here (wrong Host, a POST from another site, no session),
    else None (then ``request.state.session`` is set)."""
    if not host_allowed(request.headers.get("host"), request.app.state.hosts):
        return render_error(request, "this server does not answer to that host name "
                            "(Host header); open it by the address it was started on", 400)
    if request.method == "POST" and not origin_allowed(request.headers, request.app.state.hosts,
                                                       request.url.scheme):
        return render_error(request, "the form was sent from another site (Origin "
                            "header); open the workbench and send it from there", 403)
    session = _session(request)
    request.state.session = session
    public = _public_asset(request.url.path) or request.url.path == "/login"
    if session is None and not public:
        if request.method == "GET":
            return RedirectResponse(f"/login?next={quote(request.url.path)}", 303)
        return render_error(request, "not logged in, or the session has ended: log in "
                            "first (nothing was done)", 401)
    return None


def _public_asset(path: str) -> bool:
    """The files every page loads, the same for everyone (served without a session, cacheable):
    ``/static/`` and ``/favicon.ico``. Every other answer is a page of a session and carries
    ``Cache-Control: no-store`` (RFC 9111 §5.2.2.5; OWASP Session Management Cheat Sheet, "Web
    content caching"): after log-out, Back asks the server again and gets the login."""
    return path.startswith("/static/") or path == "/favicon.ico"


def _add_favicon(app: FastAPI) -> None:
    """``/favicon.ico``, which every browser asks for on every page (a 404 each time before)."""
    from fastapi.responses import FileResponse

    @app.get("/favicon.ico", include_in_schema=False)
    def favicon():
        return FileResponse(HERE / "static" / "favicon.ico", media_type="image/x-icon",
                            headers={"Cache-Control": "public, max-age=86400"})


def _anon_cookie(anon: str) -> str:
    """The Set-Cookie value of a new anonymous visitor's cookie."""
    from starlette.responses import Response

    r = Response()
    r.set_cookie(ANON, anon, httponly=True, samesite="strict")
    return r.headers["set-cookie"]


def _add_error_pages(app: FastAPI) -> None:
    """Every error as a page of the workbench (library errors in their own words, an address
    FastAPI cannot read, HTTP errors, and anything else as "internal error")."""

    @app.exception_handler(AxiscalError)
    async def library_error(request: Request, exc: AxiscalError):
        status = 403 if isinstance(exc, Forbidden) else 404 if isinstance(exc, LookupError) \
            else getattr(exc, "status", 400)
        return render_error(request, str(exc), status)

    @app.exception_handler(RequestValidationError)
    async def invalid_address(request: Request, exc: RequestValidationError):
        return render_error(request, *_validation_words(request, exc.errors()))

    from starlette.exceptions import HTTPException

    @app.exception_handler(HTTPException)
    async def http_error(request: Request, exc: HTTPException):
        words = {404: "no such page", 405: "this page does not take that request"}
        return render_error(request, words.get(exc.status_code, str(exc.detail)), exc.status_code)

    @app.exception_handler(Exception)
    async def internal_error(request: Request, exc: Exception):
        LOG.exception("internal error on %s %s", request.method, request.url.path)
        return render_error(request, "internal error: the server's log has the details", 500)


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


def _validation_words(request: Request, errors) -> tuple[str, int]:
    """The error page's words and status for an address FastAPI could not read: a path part that
    names nothing is 404; a query parameter missing or out of its range is 400, named."""
    err = errors[0] if errors else {}
    where, name = (list(err.get("loc", ())) + ["", ""])[:2]
    if where == "path":
        return f"no such page: {request.url.path[:80]!r} names nothing here", 404
    if request.url.path == "/compare":
        return "choose two tests to compare: a first and a second in a machine's list", 400
    value = str(err.get("input", ""))[:40]
    if err.get("type") == "missing":
        return f"the address lacks {name!r}", 400
    return f"{name} = {value!r} in the address: {err.get('msg', 'not accepted')}", 400
