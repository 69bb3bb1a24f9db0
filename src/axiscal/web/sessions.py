"""Server-side login sessions and the back-off of wrong passwords.

Sessions (OWASP Session Management Cheat Sheet: "Session expiration", "Manual session
expiration"): the cookie carries only a random identifier (256 bits from :mod:`secrets`); the
session itself (user, role, CSRF token, times) is kept by the server, so logging out ends it for
every copy of the cookie, and it ends by itself after ``idle`` seconds without a request or
``absolute`` seconds after the login, whichever comes first.

Where they are kept: in the memory of the one server process (``axiscal serve`` runs one
uvicorn process). A restart logs everyone out, which is the safe direction. When the workbench is
served by several worker processes the store must move to a table of the history database; it is
one class with three calls (:meth:`Sessions.issue`, :meth:`Sessions.read`,
:meth:`Sessions.revoke`) for that reason.

Back-off (OWASP Authentication Cheat Sheet, "Login throttling"; NIST SP 800-63B §5.2.2, rate
limiting): after :data:`FREE_FAILURES` wrong passwords for one account, or from one address,
further attempts are refused without checking the password for ``base · 2^(n − FREE_FAILURES)``
seconds (n the failures so far), at most :data:`MAX_LOCK` seconds; the page says how long. A
right password ends the count of that account and address.
"""

from __future__ import annotations

import hashlib
import secrets
import threading
import time
from collections import OrderedDict
from dataclasses import dataclass

__all__ = ["Sessions", "LoginThrottle", "IDLE_SECONDS", "ABSOLUTE_SECONDS", "FREE_FAILURES",
           "MAX_LOCK"]

#: A session ends after this long without a request, seconds (OWASP: 15–30 min for most apps).
IDLE_SECONDS = 30 * 60
#: A session ends this long after its login whatever happens, seconds (a working day and more).
ABSOLUTE_SECONDS = 12 * 3600
#: Wrong passwords allowed for an account or an address before the back-off starts.
FREE_FAILURES = 5
#: Longest lock-out, seconds.
MAX_LOCK = 15 * 60
#: Most accounts/addresses remembered by the throttle (oldest forgotten first).
_REMEMBERED = 10_000


@dataclass
class _Session:
    name: str
    role: str
    csrf: str
    created: float
    seen: float


class Sessions:
    """Sessions kept by the server, found by the cookie's random identifier.

    Parameters
    ----------
    idle, absolute : float, seconds
        Idle and absolute lifetimes (default :data:`IDLE_SECONDS`, :data:`ABSOLUTE_SECONDS`).
    clock : callable
        Time source (``time.monotonic``; tests pass their own).
    """

    def __init__(self, idle: float = IDLE_SECONDS, absolute: float = ABSOLUTE_SECONDS,
                 clock=time.monotonic):
        self.idle, self.absolute, self.clock = float(idle), float(absolute), clock
        self.key = secrets.token_bytes(32)        # binds the no-login CSRF tokens (localhost)
        self._live: dict[str, _Session] = {}
        self._lock = threading.Lock()

    def issue(self, name: str, role: str) -> str:
        """Start a session; returns the cookie value (only its hash is kept)."""
        token = secrets.token_urlsafe(32)
        now = self.clock()
        with self._lock:
            self._sweep(now)
            self._live[_digest(token)] = _Session(name, role, secrets.token_urlsafe(24), now, now)
        return token

    def read(self, cookie: str | None) -> dict | None:
        """The live session of a cookie (``name``, ``role``, ``csrf``), else None; a read counts
        as activity (restarts the idle time)."""
        if not cookie or len(cookie) > 100:
            return None
        now = self.clock()
        with self._lock:
            key = _digest(cookie)
            s = self._live.get(key)
            if s is None:
                return None
            if now - s.seen > self.idle or now - s.created > self.absolute:
                del self._live[key]
                return None
            s.seen = now
            return {"name": s.name, "role": s.role, "csrf": s.csrf}

    def revoke(self, cookie: str | None) -> bool:
        """End the session of a cookie (log-out); True if there was one."""
        with self._lock:
            return self._live.pop(_digest(cookie or ""), None) is not None

    def csrf_for(self, anonymous_id: str) -> str:
        """The CSRF token of a session without login (localhost): bound to a random cookie."""
        import hmac

        return hmac.new(self.key, f"csrf|{anonymous_id}".encode(), hashlib.sha256).hexdigest()[:32]

    def __len__(self) -> int:
        return len(self._live)

    def _sweep(self, now: float) -> None:
        dead = [k for k, s in self._live.items()
                if now - s.seen > self.idle or now - s.created > self.absolute]
        for k in dead:
            del self._live[k]


class LoginThrottle:
    """Failures per account and per address, and the lock-out they earn.

    Parameters
    ----------
    base : float, seconds
        First lock-out after :data:`FREE_FAILURES` failures; each further failure doubles it.
    free : int
        Failures allowed before the lock-out starts.
    clock : callable
    """

    def __init__(self, base: float = 30.0, free: int = FREE_FAILURES, clock=time.monotonic):
        self.base, self.free, self.clock = float(base), int(free), clock
        self._failures: OrderedDict = OrderedDict()     # key -> (count, last failure time)
        self._lock = threading.Lock()

    def wait(self, account: str, address: str) -> float:
        """Seconds before ``account`` may be tried again from ``address`` (0: now)."""
        now = self.clock()
        with self._lock:
            return max(self._left(("account", account), now), self._left(("address", address),
                                                                         now))

    def failed(self, account: str, address: str) -> None:
        """Count one wrong password."""
        now = self.clock()
        with self._lock:
            for key in (("account", account), ("address", address)):
                count, _ = self._failures.pop(key, (0, now))
                self._failures[key] = (count + 1, now)
            while len(self._failures) > _REMEMBERED:
                self._failures.popitem(last=False)

    def succeeded(self, account: str, address: str) -> None:
        """A right password: forget the failures of this account and address."""
        with self._lock:
            self._failures.pop(("account", account), None)
            self._failures.pop(("address", address), None)

    def _left(self, key, now: float) -> float:
        count, last = self._failures.get(key, (0, now))
        lock = min(self.base * 2 ** (count - self.free), MAX_LOCK) if count >= self.free else 0.0
        if now - last > MAX_LOCK + lock:                 # a long quiet: start afresh
            self._failures.pop(key, None)
            return 0.0
        return max(0.0, last + lock - now)


def _digest(token: str) -> str:
    return hashlib.sha256(token.encode("utf-8", "surrogatepass")).hexdigest()
