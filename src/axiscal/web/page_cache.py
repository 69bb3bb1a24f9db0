"""Whole pages kept by a worker process while what they show is unchanged.

A test's page is the same bytes for every viewer of one kind until someone writes: rendering it
(its results, sign-off form, audit trail and the queries behind them) cost 17 ms of CPU a view,
the largest share of the server's time under 20 people browsing. It is kept here, rendered
once, under a key of everything it depends on:

* the page's address with its query string (``?stored=new``, ``?certificate=N`` change it);
* what of the viewer the templates show: the user's name, role, whether they may write, whether
  the workbench has accounts. The viewer's CSRF token is not in the key: the page is rendered
  with :data:`CSRF_MARK` (a random word of this process, which no stored text can know) in its
  place, and each answer carries the viewer's own token instead, so no viewer ever receives
  another's token;
* the history's generation (:func:`axiscal.store.queries.generation`, read before the page is
  made: what is kept is at least as new as the generation it is kept under), and whatever else
  the caller names (the user configuration a sign-off form starts from).

A part that changes with every upload, where the rest of the page does not (the other tests of
the axis on a test's page), is left out as :data:`PART_MARK` and filled in at each answer from a
part kept under the full generation. At most :data:`MEMORY_BYTES` of pages are kept per
process, the least recently used going first; a page with an error, a refused form or a status
other than 200 is never kept.
"""

from __future__ import annotations

import secrets
import threading
from collections import OrderedDict

from fastapi.responses import HTMLResponse

__all__ = ["CSRF_MARK", "PART_MARK", "viewer", "kept_page", "keep_page", "answer", "forget",
           "MEMORY_BYTES"]

#: Bytes of pages one worker process keeps.
MEMORY_BYTES = 48 * 2**20
#: Stands for the viewer's CSRF token in a kept page (random per process, letters and digits:
#: the same after HTML escaping, unknown to anything stored).
CSRF_MARK = "csrf" + secrets.token_hex(16)
#: Stands for the part of a kept page that is filled in at each answer.
PART_MARK = "part" + secrets.token_hex(16)
_kept: OrderedDict = OrderedDict()       # key -> (body bytes, extra, size)
_size = [0]
_lock = threading.Lock()


def viewer(request) -> tuple:
    """What of the viewer a page shows (name, role, may write, accounts): part of every key."""
    s = getattr(request.state, "session", None) or {}
    return (s.get("name"), s.get("role"),
            bool(request.app.state.users and request.app.state.users.users))


def kept_page(key: tuple):
    """``(body, extra)`` kept under ``key`` (now the most recently used), else None."""
    with _lock:
        hit = _kept.get(key)
        if hit is None:
            return None
        _kept.move_to_end(key)
        return hit[0], hit[1]


def keep_page(key: tuple, response, extra=None) -> bytes | None:
    """Keep the body of ``response`` (a page rendered with :data:`CSRF_MARK` for the token)
    under ``key`` with ``extra`` (what :func:`answer` needs to fill it in); a response that is
    not a plain 200 page is not kept. Returns the body, or None when it was not kept."""
    body = getattr(response, "body", None)
    if response.status_code != 200 or not isinstance(body, bytes):
        return None
    size = len(body) + 200
    if size > MEMORY_BYTES // 8:
        return None
    with _lock:
        old = _kept.pop(key, None)
        _size[0] += size - (old[2] if old else 0)
        _kept[key] = (body, extra, size)
        while _size[0] > MEMORY_BYTES:
            _size[0] -= _kept.popitem(last=False)[1][2]
    return body


def answer(request, body: bytes, part: str = "") -> HTMLResponse:
    """A kept page for this viewer: their CSRF token in place of :data:`CSRF_MARK`, ``part``
    (HTML, escaped already) in place of :data:`PART_MARK`."""
    from markupsafe import escape

    token = str(escape((getattr(request.state, "session", None) or {}).get("csrf") or ""))
    body = body.replace(CSRF_MARK.encode(), token.encode())
    if PART_MARK.encode() in body:
        body = body.replace(PART_MARK.encode(), part.encode("utf-8"))
    return HTMLResponse(body)


def forget() -> None:
    """Empty this process's kept pages (tests)."""
    with _lock:
        _kept.clear()
        _size[0] = 0
