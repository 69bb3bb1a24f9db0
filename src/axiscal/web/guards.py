"""The checks every request to the workbench passes before a page is made.

* **Host allow-list** (DNS rebinding). A browser that was made to resolve ``evil.example`` to
  127.0.0.1 still sends ``Host: evil.example``; only the names the server was bound under are
  served (:func:`allowed_hosts`), anything else gets a 400 page without a session, a CSRF token or
  a stored upload. This is the defence the OWASP "DNS rebinding" guidance and RFC 9110 §7.2 (the
  Host header names the authority the client means) make possible.
* **Origin check** on every POST (OWASP CSRF Prevention Cheat Sheet, "Verifying origin with
  standard headers"; RFC 6454 §7 for the ``Origin`` header): the ``Origin`` header, or the
  ``Referer`` when the browser sent no Origin, must name this server's origin: the scheme it is
  served by, an allowed host and the same port (RFC 6454 §4: an origin is the triple scheme, host,
  port; ``https://127.0.0.1:PORT`` is another origin than ``http://127.0.0.1:PORT``). A request
  with neither comes from no browser (browsers send Origin on every cross-origin POST), so it is
  not a cross-site request; it still needs the synchronizer CSRF token.
* **Bounded bodies** (:class:`BodyLimit`): a declared ``Content-Length`` over the limit is refused
  before one byte of the body is read, and a body sent without one is counted while it streams and
  stopped at the limit, so nothing is spooled past it (RFC 9110 §15.5.14, 413 Content Too Large).
* **Bounded form fields** (:func:`check_fields`): each text field at most
  :data:`MAX_FIELD_CHARS` characters, named in the refusal.
"""

from __future__ import annotations

import ipaddress
import socket
from urllib.parse import urlsplit

from axiscal.errors import InputError

__all__ = ["TooLarge", "BodyLimit", "allowed_hosts", "host_name", "host_allowed",
           "origin_allowed", "check_fields", "MAX_FIELD_CHARS", "FORM_OVERHEAD"]

#: Longest text field of a form, characters (a note of a few pages; names are much shorter).
MAX_FIELD_CHARS = 10_000
#: Room for the text fields and the multipart framing beside an upload's file, bytes.
FORM_OVERHEAD = 1024 * 1024
_LOOPBACK_NAMES = ("127.0.0.1", "localhost", "::1")


class TooLarge(InputError):
    """A request body or a form field is over its limit (HTTP 413)."""

    status = 413


def allowed_hosts(bind: str, extra=()) -> frozenset:
    """The host names the workbench answers to: the loopback names, the bound address, its names
    when it is every interface (0.0.0.0 or ::) and the ``--allowed-host`` names.

    Parameters
    ----------
    bind : str
        The address given to ``--host``.
    extra : iterable of str
        Further names (``--allowed-host``), e.g. the name a reverse proxy or DNS gives the server.
    """
    names = {*_LOOPBACK_NAMES, _plain(bind)}
    if bind in ("0.0.0.0", "::", ""):
        host = socket.gethostname()
        names |= {host, socket.getfqdn()}
        try:
            names |= {a[4][0] for a in socket.getaddrinfo(host, None)}
        except OSError:
            pass
    names |= {_plain(h) for h in extra}
    return frozenset(n.lower() for n in names if n)


def host_name(header: str | None) -> tuple[str, str] | None:
    """``(name, port)`` of a Host header (``name[:port]`` or ``[v6]:port``), or None if it is not
    one (RFC 9110 §7.2; RFC 3986 §3.2.2 for the bracketed IPv6 form)."""
    if not header or len(header) > 300:
        return None
    try:
        parts = urlsplit(f"//{header}")
        name, port = parts.hostname, parts.port
    except ValueError:
        return None
    if not name or parts.username is not None or parts.password is not None or parts.path:
        return None
    return name.lower(), str(port or "")


def host_allowed(header: str | None, allowed: frozenset) -> bool:
    """True when the Host header names an allowed host."""
    parsed = host_name(header)
    return parsed is not None and parsed[0] in allowed


def origin_allowed(headers, allowed: frozenset, scheme: str = "http") -> bool:
    """True when a POST's Origin (or, without one, its Referer) is this server's origin (RFC 6454
    §4: scheme, host and port): the ``scheme`` the request came by (``http``, or ``https`` behind
    a proxy that says so), an allowed host and the port of the Host header. No header at all is
    allowed (not sent by a browser)."""
    source = headers.get("origin") or headers.get("referer")
    if source is None:
        return True
    here = host_name(headers.get("host"))
    try:
        there = urlsplit(source)
        name, port = there.hostname, there.port
    except ValueError:
        return False
    if here is None or there.scheme not in ("http", "https") or not name \
            or there.scheme != (scheme or "http").lower():
        return False
    default = "443" if there.scheme == "https" else "80"
    return name.lower() in allowed and str(port or default) == (here[1] or default)


def check_fields(form, fields=None, limit: int = MAX_FIELD_CHARS) -> None:
    """Refuse a form whose text field is longer than ``limit`` characters (naming the field)."""
    for key, value in form.multi_items():
        if isinstance(value, str) and len(value) > limit and (fields is None or key in fields):
            raise TooLarge(f"the field {key[:40]!r} has {len(value):,} characters; the workbench "
                           f"takes at most {limit:,}")


class BodyLimit:
    """ASGI middleware: a request body of more than ``limit`` bytes is refused (:class:`TooLarge`
    raised from ``receive``, which the application turns into its 413 page).

    A ``Content-Length`` over the limit is refused on the first ``receive``, before any of the body
    is read; a body without one (chunked) is counted as it arrives and stopped at the limit.
    """

    def __init__(self, app, limit: int):
        self.app, self.limit = app, int(limit)

    async def __call__(self, scope, receive, send):
        if scope["type"] != "http":
            return await self.app(scope, receive, send)
        declared = dict(scope["headers"]).get(b"content-length", b"0")
        declared = int(declared) if declared.isdigit() and len(declared) < 20 else None
        counted = 0
        limit = self.limit

        async def bounded():
            nonlocal counted
            if declared is None or declared > limit:
                raise TooLarge(self._words(declared))
            message = await receive()
            counted += len(message.get("body", b""))
            if counted > limit:
                raise TooLarge(self._words(None))
            return message

        await self.app(scope, bounded, send)

    def _words(self, declared) -> str:
        if declared is None:
            return ("the request has no readable length or is longer than the workbench takes: "
                    f"at most {self.limit / 2**20:.3g} MiB")
        return (f"the request is {declared / 2**20:.3g} MiB; the workbench takes at most "
                f"{self.limit / 2**20:.3g} MiB (RFC 9110 §15.5.14: 413 Content Too Large)")


def _plain(host: str) -> str:
    """A host as it appears in a Host header's name part (IPv6 without brackets, lower case)."""
    h = str(host or "").strip().lower()
    if h.startswith("[") and h.endswith("]"):
        h = h[1:-1]
    try:
        return str(ipaddress.ip_address(h))
    except ValueError:
        return h
