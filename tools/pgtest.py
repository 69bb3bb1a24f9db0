"""A throw-away PostgreSQL server for the tests (Debian's PostgreSQL, installed by ``make test``).

``start()`` makes a cluster in a temporary folder (``initdb``, trust authentication, no fsync),
starts it on a Unix socket in that folder only (no TCP port, so parallel test workers never
collide) and returns its SQLAlchemy URL and a ``stop()`` function that stops it and removes the
folder. As root, PostgreSQL refuses to run, so the cluster belongs to the ``postgres`` user.

Command line: ``python tools/pgtest.py`` starts one and prints its URL, until Ctrl+C.
"""

from __future__ import annotations

import glob
import os
import shutil
import subprocess
import tempfile

__all__ = ["bindir", "start"]


def bindir() -> str | None:
    """The newest PostgreSQL server's bin folder, or None."""
    found = sorted(glob.glob("/usr/lib/postgresql/*/bin/initdb"),
                   key=lambda p: int(p.split("/")[4]) if p.split("/")[4].isdigit() else 0)
    return os.path.dirname(found[-1]) if found else None


def start():
    """Start a server; returns ``(url, stop)``."""
    b = bindir()
    if b is None:
        raise RuntimeError("PostgreSQL is not installed (make test installs Debian's "
                           "postgresql package)")
    root = tempfile.mkdtemp(prefix="axpg-", dir="/tmp")
    as_root = os.geteuid() == 0
    if as_root:
        shutil.chown(root, "postgres", "postgres")
    data = os.path.join(root, "data")

    def run(*args):
        cmd = list(args)
        if as_root:
            cmd = ["runuser", "-u", "postgres", "--", *cmd]
        subprocess.run(cmd, check=True, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE,
                       cwd=root)

    run(f"{b}/initdb", "-D", data, "-A", "trust", "-U", "axiscal", "-E", "UTF8", "--no-sync")
    run(f"{b}/pg_ctl", "-D", data, "-l", os.path.join(root, "log"), "-w", "-o",
        f"-k {root} -c listen_addresses='' -F -c max_connections=200", "start")

    def stop():
        try:
            run(f"{b}/pg_ctl", "-D", data, "-m", "immediate", "-w", "stop")
        finally:
            shutil.rmtree(root, ignore_errors=True)

    return f"postgresql+psycopg://axiscal@/postgres?host={root}", stop


if __name__ == "__main__":                      # pragma: no cover
    url, stop = start()
    print(url, flush=True)
    try:
        import time

        while True:
            time.sleep(3600)
    except KeyboardInterrupt:
        stop()
