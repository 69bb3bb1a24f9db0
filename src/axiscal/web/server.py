"""Serving the workbench with uvicorn, with the limits a server reachable by others needs.

uvicorn closes an idle keep-alive connection (``timeout_keep_alive``) and answers 503 past
``limit_concurrency``, but it waits for a request's headers, and for its body, as long as the
client likes: 1,100 clients that each sent half a header held 1,100 connections open, and with
1,024 file descriptors the server stopped accepting ("slowloris"). :class:`TimedH11Protocol`
closes a connection whose request headers are not complete ``header_timeout`` seconds after the
first byte of them (or after the connection opened), and one that sends no byte of a request
body for ``body_timeout`` seconds; h11's own limit bounds the size of the headers
(``h11_max_incomplete_event_size``). The defaults (:data:`LIMITS`) are shown by
``axiscal serve`` when it starts.

With several worker processes on one listening socket, the kernel hands each new connection to
whichever process accepts it first, and asyncio accepts every waiting connection in one go: 20
clients connecting at once were 18 on one worker and 2 on the other, and kept so for as long as
their keep-alive connections lived (one core busy, the other idle). So a connection answers
``requests_per_connection`` requests and then says ``Connection: close`` with the last (RFC 9112
§9.6: the sender of "close" closes after that response); the client connects again and the new
connection goes to the worker that is free to accept it, which spreads the clients by load (the
same limit as nginx's ``keepalive_requests``, with a smaller number so that it rebalances within
a second under load).
"""

from __future__ import annotations

import asyncio

import h11
from uvicorn.protocols.http.flow_control import CLOSE_HEADER
from uvicorn.protocols.http.h11_impl import H11Protocol

__all__ = ["LIMITS", "TimedH11Protocol", "app_from_env", "protocol", "run"]

#: Defaults: seconds to send the request headers; seconds of silence within a body; connections
#: served at once (more get 503); seconds an idle keep-alive connection is kept; header bytes;
#: requests answered on one connection before it is closed (see the module docstring).
LIMITS = {"header_timeout": 10.0, "body_timeout": 30.0, "max_connections": 100,
          "keep_alive": 5, "max_header_bytes": 16 * 1024, "requests_per_connection": 20}


#: Seconds a thread holds the GIL while another waits for it, in a serving process.
SWITCH_INTERVAL = 0.001


class TimedH11Protocol(H11Protocol):
    """uvicorn's h11 protocol with a deadline for the headers, a silence limit in the body and
    at most :attr:`requests_per_connection` requests on one connection."""

    header_timeout = LIMITS["header_timeout"]
    body_timeout = LIMITS["body_timeout"]
    requests_per_connection = LIMITS["requests_per_connection"]

    def connection_made(self, transport: asyncio.Transport) -> None:
        super().connection_made(transport)
        _no_delay(transport)
        self._timer: asyncio.TimerHandle | None = None
        self._served = 0
        self._arm(self.header_timeout)

    def handle_events(self) -> None:
        cycle = self.cycle
        super().handle_events()
        if self.cycle is not cycle:                          # a request began
            self._served += 1
            if self._served >= self.requests_per_connection and CLOSE_HEADER not in self.headers:
                self.headers.append(CLOSE_HEADER)            # uvicorn answers "close" and closes

    def data_received(self, data: bytes) -> None:
        super().data_received(data)
        state = self.conn.their_state
        if state is h11.IDLE and self._timer is None:      # a new request's headers begin
            self._arm(self.header_timeout)
        elif state is h11.SEND_BODY:                        # silence in a body: from now
            self._arm(self.body_timeout)
        elif state is not h11.IDLE:
            self._disarm()

    def connection_lost(self, exc: Exception | None) -> None:
        self._disarm()
        super().connection_lost(exc)

    def _arm(self, seconds: float) -> None:
        self._disarm()
        self._timer = self.loop.call_later(seconds, self._too_slow)

    def _disarm(self) -> None:
        if getattr(self, "_timer", None) is not None:
            self._timer.cancel()
            self._timer = None

    def _too_slow(self) -> None:
        self._timer = None
        if not self.transport.is_closing():
            self.logger.warning("closed a connection from %s: request too slow",
                                self.client[0] if self.client else "?")
            self.transport.close()


def _no_delay(transport) -> None:
    """Send small answers at once (TCP_NODELAY). asyncio sets it only on a socket whose ``proto``
    is IPPROTO_TCP; the listening socket uvicorn hands to its worker processes reports 0, so
    without this every answer of a worker waited for the client's delayed ACK (Nagle's
    algorithm, RFC 896; RFC 1122 §4.2.3.2): a static file took 44 ms instead of 2 ms."""
    import socket

    sock = transport.get_extra_info("socket")
    if sock is not None and sock.family in (socket.AF_INET, socket.AF_INET6):
        try:
            sock.setsockopt(socket.IPPROTO_TCP, socket.TCP_NODELAY, 1)
        except OSError:
            pass


def protocol(header_timeout: float, body_timeout: float) -> type:
    """:class:`TimedH11Protocol` with these timeouts, seconds."""
    return type("TimedH11Protocol", (TimedH11Protocol,), {
        "header_timeout": float(header_timeout), "body_timeout": float(body_timeout)})


def run(app, host: str, port: int, header_timeout: float, body_timeout: float,
        max_connections: int, workers: int = 1, settings: dict | None = None) -> None:
    """Serve ``app`` with uvicorn under the limits above.

    With ``workers`` > 1, uvicorn starts that many processes on one listening socket, each
    building the application from ``settings`` (the keyword arguments of
    :func:`~axiscal.web.app.create_app`, handed over in the environment, :func:`app_from_env`);
    ``max_connections`` is shared out among them.
    """
    import uvicorn

    _switch_often()
    _freeze_what_was_loaded()
    common = dict(host=host, port=port, log_level="warning",
                  timeout_keep_alive=LIMITS["keep_alive"],
                  h11_max_incomplete_event_size=LIMITS["max_header_bytes"])
    if workers <= 1:
        uvicorn.run(app, http=protocol(header_timeout, body_timeout),
                    limit_concurrency=max_connections, **common)
        return
    import json
    import os

    from axiscal.web.workers import ENV

    os.environ[ENV] = json.dumps({"app": settings or {}, "header_timeout": header_timeout,
                                  "body_timeout": body_timeout})
    uvicorn.run("axiscal.web.server:app_from_env", factory=True, workers=workers,
                http=TimedH11Protocol, limit_concurrency=max(1, -(-max_connections // workers)),
                **common)


def _switch_often() -> None:
    """Hand the GIL over every :data:`SWITCH_INTERVAL` seconds in a serving process (Python's
    default: 5 ms). Pages are served on the event loop; an upload or a report runs in a thread,
    and every SQLite step or file write of that thread lets the GIL go and waits for it back,
    while the busy event loop keeps it a whole interval: the "convoy effect" of the GIL
    (D. Beazley, "Understanding the Python GIL", PyCon 2010; CPython bpo-7946)."""
    import sys

    sys.setswitchinterval(SWITCH_INTERVAL)


def app_from_env():
    """The application of one worker process of ``axiscal serve --workers N`` (a uvicorn
    factory): :func:`~axiscal.web.app.create_app` with the settings the server handed over."""
    from axiscal.web.app import create_app
    from axiscal.web.workers import settings_from_env

    s = settings_from_env()
    _switch_often()
    TimedH11Protocol.header_timeout = float(s["header_timeout"])
    TimedH11Protocol.body_timeout = float(s["body_timeout"])
    app = create_app(**s["app"])
    _freeze_what_was_loaded()
    return app


def _freeze_what_was_loaded() -> None:
    """Leave out of every later garbage collection what the serving process holds once its
    application is built (modules, classes, templates: ~137,000 objects, which live as long as the
    process): ``gc.freeze`` (Python Library Reference, "gc — Garbage Collector interface"; the
    practice of I. Kim et al., Instagram Engineering, "Dismissing Python Garbage Collection at
    Instagram", 2017). Every collection of the oldest generation walked them: under 20 clients a
    worker collected it every ~7 s for 120-280 ms, the event loop and every thread stopped."""
    import gc

    gc.collect()
    gc.freeze()
