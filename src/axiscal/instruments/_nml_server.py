"""The child process that holds one LinuxCNC session's Python channels (``linuxcnc``, ``hal``).

Run by :class:`axiscal.instruments._nml.ChannelProcess` as ``python -P _nml_server.py``; it
imports nothing of axiscal. Requests and replies are pickles on the pipe the parent gave it as
stdout (fd 1 is pointed at stderr at once, so nothing LinuxCNC's libraries print can corrupt the
stream): ``(op, ref, name, args, kwargs)`` in, ``("ok", value)``, ``("ref", id)`` (a value that
does not pickle, kept here) or ``("err", type, message)`` out. The process ends when its stdin
closes.
"""
import importlib
import os
import pickle
import sys

CALLABLE = "\0callable"


def serve() -> None:
    out = os.fdopen(os.dup(1), "wb")
    os.dup2(2, 1)
    inp = sys.stdin.buffer
    objects: dict = {}
    while True:
        try:
            op, ref, name, args, kwargs = pickle.load(inp)
        except EOFError:
            break
        try:
            if op == "new":
                module, _, attr = name.rpartition(".")
                value = getattr(importlib.import_module(module), attr)(*args, **kwargs)
            elif op == "call":
                value = getattr(objects[ref], name)(*args, **kwargs)
            elif op == "get":
                value = getattr(objects[ref], name)
                if callable(value):
                    value = CALLABLE
            elif op == "getitem":
                value = objects[ref][args[0]]
            elif op == "setitem":
                objects[ref][args[0]] = args[1]
                value = None
            elif op == "drop":
                objects.pop(ref, None)
                value = None
            else:
                raise ValueError(f"unknown request {op!r}")
            try:
                if op == "new":             # always kept here
                    raise TypeError
                data = pickle.dumps(("ok", value))
            except Exception:
                key = len(objects) + 1
                while key in objects:
                    key += 1
                objects[key] = value
                data = pickle.dumps(("ref", key))
        except Exception as exc:            # sent back, raised there
            data = pickle.dumps(("err", type(exc).__name__, str(exc)))
        out.write(data)
        out.flush()


if __name__ == "__main__":
    serve()
