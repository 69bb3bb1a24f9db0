"""What a page read from the history, kept in this worker process while the history is unchanged.

A machine's history page is the same for every client until someone writes: its reads (the
machine, a page of its tests with their key parameters, the trend parameters, the audit trail,
the other machines) are kept here under the page's address and the history's *generation*
(:func:`axiscal.store.queries.generation`, one query of counts and largest ids). Every request
reads the generation first; a write committed by any process, through the workbench, the
command line or another worker, changes it, and the page is read again. So a view of an
unchanged page costs that one query and the rendering, and never shows less than was committed
before it began (the generation is read before the page's reads, so what is kept is at least as
new as the generation it is kept under).

The page is rendered for each request (its CSRF token and role are the user's); only the reads
are kept, at most :data:`ENTRIES` pages per process, the least recently used going first.
"""

from __future__ import annotations

import threading
from collections import OrderedDict

__all__ = ["memoised", "forget", "ENTRIES"]

#: Pages whose reads one worker process keeps.
ENTRIES = 64
_kept: OrderedDict = OrderedDict()       # (database URL, page key) -> (generation, value)
_lock = threading.Lock()


def memoised(store, key: tuple, make, now: tuple | None = None):
    """``make()`` (the reads of the page ``key`` of ``store``), or what it gave before if the
    history's generation (``now``, read before, or read here) has not changed since."""
    from axiscal.store.queries import generation

    now = generation(store) if now is None else now
    k = (store.url, key)
    with _lock:
        hit = _kept.get(k)
        if hit is not None and hit[0] == now:
            _kept.move_to_end(k)
            return hit[1]
    value = make()
    with _lock:
        _kept[k] = (now, value)
        _kept.move_to_end(k)
        while len(_kept) > ENTRIES:
            _kept.popitem(last=False)
    return value


def forget() -> None:
    """Empty this process's kept pages (tests)."""
    with _lock:
        _kept.clear()
