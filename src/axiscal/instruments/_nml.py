"""LinuxCNC's Python channels of one session, held in a child process of their own.

The ``linuxcnc`` module's NML library keeps a process-wide list of the buffers it opened: a
status or command channel of one LinuxCNC, once that LinuxCNC has ended, is found again by the
next session's ``linuxcnc.stat()`` in the same process, which then reads unmapped memory. Closing
the channels first made it rarer, not impossible (a segmentation fault in
``linuxcnc.stat()`` ended a test worker on the CI machine; a second five-axis session in one
process lost its MDI moves). Each session therefore opens its ``linuxcnc.stat``,
``linuxcnc.command``, ``linuxcnc.error_channel`` and ``hal.component`` in a fresh child process
(:mod:`axiscal.instruments._nml_server`) that ends with the session: whatever the NML library
keeps, it keeps there. The objects answer as the originals do (attributes, methods, items), one
pipe round trip each (about 0.1 ms); a child that dies becomes a :class:`MeasurementError`.
"""
from __future__ import annotations

import pickle
import select
import subprocess
import sys
import threading
from pathlib import Path

from axiscal.errors import MeasurementError

CALLABLE = "\0callable"

#: Longest wait for one reply, s: every blocking call of the session has a shorter timeout of
#: its own (``wait_complete``); this only turns a child that hangs into an error.
REPLY_TIMEOUT_S = 300.0


class ChannelProcess:
    """The child process; :meth:`new` makes an object there (``"linuxcnc.stat"``, …)."""

    def __init__(self, env: dict | None = None) -> None:
        server = Path(__file__).with_name("_nml_server.py")
        self._p = subprocess.Popen([sys.executable, "-P", str(server)], stdin=subprocess.PIPE,
                                   stdout=subprocess.PIPE, env=env)
        self._lock = threading.Lock()     # one request and its reply at a time, any thread

    def new(self, what: str, *args, **kwargs) -> "Remote":
        return self.request("new", None, what, args, kwargs)

    def request(self, op: str, ref, name: str | None = None, args: tuple = (),
                kwargs: dict | None = None):
        with self._lock:
            return self._request(op, ref, name, args, kwargs)

    def _request(self, op, ref, name, args, kwargs):
        p = self._p
        if p is None:
            raise MeasurementError("LinuxCNC's session has ended")
        try:
            p.stdin.write(pickle.dumps((op, ref, name, args, kwargs or {})))
            p.stdin.flush()
            ready, _, _ = select.select([p.stdout], [], [], REPLY_TIMEOUT_S)
            if not ready:
                self.close()
                raise MeasurementError(f"LinuxCNC's Python interface did not answer {name!r} "
                                       f"within {REPLY_TIMEOUT_S:g} s")
            reply = pickle.load(p.stdout)
        except (EOFError, BrokenPipeError, pickle.UnpicklingError):
            code = p.poll()
            self.close()
            raise MeasurementError(f"LinuxCNC's Python interface ended while asked {name!r} "
                                   f"(exit code {code})") from None
        if reply[0] == "ok":
            return reply[1]
        if reply[0] == "ref":
            return Remote(self, reply[1])
        raise MeasurementError(f"LinuxCNC's Python interface: {name}: {reply[1]}: {reply[2]}")

    def close(self) -> None:
        """End the child (stdin closed; killed if it does not end within 5 s)."""
        p, self._p = self._p, None
        if p is None:
            return
        try:
            p.stdin.close()
        except OSError:
            pass
        try:
            p.wait(5)
        except subprocess.TimeoutExpired:
            p.kill()
            p.wait(5)
        p.stdout.close()


class Remote:
    """An object in the child process: attributes, methods and items go there."""

    __slots__ = ("_proc", "_ref", "_methods")

    def __init__(self, proc: ChannelProcess, ref: int) -> None:
        object.__setattr__(self, "_proc", proc)
        object.__setattr__(self, "_ref", ref)
        object.__setattr__(self, "_methods", set())

    def __getattr__(self, name: str):
        if name.startswith("__"):
            raise AttributeError(name)
        if name not in self._methods:
            value = self._proc.request("get", self._ref, name)
            if value != CALLABLE:
                return value
            self._methods.add(name)
        proc, ref = self._proc, self._ref
        return lambda *args, **kwargs: proc.request("call", ref, name, args, kwargs)

    def __getitem__(self, key):
        return self._proc.request("getitem", self._ref, None, (key,))

    def __setitem__(self, key, value) -> None:
        self._proc.request("setitem", self._ref, None, (key, value))

