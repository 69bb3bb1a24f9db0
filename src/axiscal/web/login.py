"""``/login`` and ``/logout``: the password checked in a worker thread (an Argon2id verification
takes tens of milliseconds of CPU and must not stop other users' pages), wrong passwords backed
off per account and per address (:class:`~axiscal.web.sessions.LoginThrottle`), the session kept
by the server and ended at log-out (:class:`~axiscal.web.sessions.Sessions`)."""

from __future__ import annotations

import math

from fastapi import FastAPI, Request
from fastapi.responses import HTMLResponse, RedirectResponse
from starlette.concurrency import run_in_threadpool

from axiscal.web.inputs import checked_form
from axiscal.web.rendering import render

__all__ = ["login_routes", "COOKIE"]

COOKIE = "axiscal_session"


def login_routes(app: FastAPI) -> None:
    """Add ``/login`` and ``/logout`` to ``app``."""
    @app.get("/login", response_class=HTMLResponse)
    async def login_form(request: Request, next: str = "/", expired: str = ""):
        request.state.session = request.state.session or {}
        return render(request, "login.html", "Log in", next=_local(next),
                      expired=bool(expired))

    @app.post("/login")
    async def login(request: Request):
        request.state.session = request.state.session or {}
        form = await checked_form(request, csrf=False)
        users, throttle = request.app.state.users, request.app.state.throttle
        name, password = str(form.get("username", "")), str(form.get("password", ""))
        address = request.client.host if request.client else "?"
        wait = throttle.wait(name, address)
        if wait > 0:                       # 429 Too Many Requests, Retry-After (RFC 6585 §4)
            resp = render(request, "login.html", "Log in", 429, next=_local(form.get("next")),
                          error=f"too many wrong passwords for this account or from this "
                          f"address: try again in {math.ceil(wait)} s")
            resp.headers["Retry-After"] = str(math.ceil(wait))
            return resp
        user = await run_in_threadpool(users.check, name, password) if users else None
        if user is None:
            throttle.failed(name, address)
            return render(request, "login.html", "Log in", 401, next=_local(form.get("next")),
                          error="wrong user name or password")
        throttle.succeeded(name, address)
        resp = RedirectResponse(_local(form.get("next")), 303)
        resp.set_cookie(COOKIE, request.app.state.sessions.issue(user.name, user.role),
                        httponly=True, samesite="strict")
        return resp

    @app.post("/logout")
    async def logout(request: Request):
        request.app.state.sessions.revoke(request.cookies.get(COOKIE))
        resp = RedirectResponse("/login", 303)
        resp.delete_cookie(COOKIE)
        return resp


def _local(path) -> str:
    """Only a path on this site is a place to go back to (no open redirect)."""
    p = str(path or "/")
    return p if p.startswith("/") and not p.startswith("//") else "/"
