"""What a stored test gives (its evaluation, reports, certificates) computed once and kept.

An evaluation of a stored test is a function of two things only: the test's stored bytes and the
version of axiscal that evaluates them (``StoredTest.evaluate_again`` is
:func:`axiscal.store.kinds.evaluate_file` on the stored bytes). So it is kept under the key
``(SHA-256 of the stored bytes, axiscal version, what)`` (the version with a fingerprint of
the installed source files, so an edited development checkout counts as another version) and a
second view is a look-up, not a second evaluation (after one 19.6 MB upload a view of its page took 2.85 s and its report 14.5 s
and 116 MB, every time). A new version of axiscal reads and writes another folder, so it never
serves what an older version computed (invalidation by version); a product that also depends on
other inputs (a certificate on the user configuration, the paper) carries their digest in
``what``.

Where: files under ``AXISCAL_CACHE``, else the user's cache folder (platformdirs
``user_cache_dir("axiscal")``), ``artifacts/<version>/<sha[:2]>/<sha>.<what>``. Every file is
written whole to a temporary name in the same folder and renamed over the final one
(``os.replace``, atomic on POSIX and Windows), so a reader sees the old file, the new one or
none, never half of one, whichever process of a multi-worker server wrote it. A cache that cannot
be written (a read-only home) is not an error: the product is returned uncached.

The evaluation itself (an :class:`~axiscal.store.kinds.Evaluated` with its dataset and result
objects) is kept as a pickle in that same folder, which only this user writes (the trust of a
pickle is that of the folder, as for the user's own virtual environment), and, in each process,
the most recently used ones in memory, bounded by :data:`MEMORY_BYTES` of stored bytes.
"""

from __future__ import annotations

import hashlib
import os
import pickle
import tempfile
import threading
from collections import OrderedDict
from pathlib import Path

__all__ = ["cache_folder", "read", "write", "kept", "kept_file", "evaluated", "derived", "lookup",
           "remember",
           "MEMORY_BYTES", "MEMORY_ENTRIES"]

#: Stored bytes whose evaluations one process keeps in memory, with the pickled size of the page
#: parts derived from them (the rest are read from disk).
MEMORY_BYTES = 32 * 2**20
#: Evaluations one process keeps in memory at most.
MEMORY_ENTRIES = 256
_memory: OrderedDict = OrderedDict()        # (sha, version, what) -> (value, size)
_memory_size = [0]                          # the sizes in _memory, summed
_memory_lock = threading.Lock()
_key_locks: dict = {}
_key_locks_lock = threading.Lock()


_VERSION: list = []


def _version() -> str:
    """The axiscal version, with a fingerprint of its source files and the workbench's templates
    (names, sizes, modification times) so that an edited checkout of one version never reads
    what its older code kept."""
    if not _VERSION:
        from axiscal import __version__

        root = Path(__file__).resolve().parents[1]
        h = hashlib.sha256()
        # the page parts kept are drawn by the templates too: an edited template is new code
        for p in sorted([*root.rglob("*.py"), *(root / "web" / "templates").rglob("*.html")]):
            st = p.stat()
            h.update(f"{p.relative_to(root)}|{st.st_size}|{st.st_mtime_ns}\n".encode())
        _VERSION.append(f"{__version__}-{h.hexdigest()[:12]}")
    return _VERSION[0]


def cache_folder() -> Path:
    """``AXISCAL_CACHE``, else ``artifacts`` in the user's cache folder; one sub-folder per
    axiscal version."""
    env = os.environ.get("AXISCAL_CACHE")
    if env:
        base = Path(env)
    else:
        from platformdirs import user_cache_dir

        base = Path(user_cache_dir("axiscal")) / "artifacts"
    return base / _safe(_version())


def _path(sha: str, what: str) -> Path:
    if len(sha) != 64 or not all(c in "0123456789abcdef" for c in sha):
        raise ValueError(f"not a SHA-256: {sha[:70]!r}")
    return cache_folder() / sha[:2] / f"{sha}.{_safe(what)}"


def _safe(text: str) -> str:
    return "".join(c if c.isalnum() or c in "._-" else "_" for c in text)[:120]


def read(sha: str, what: str) -> bytes | None:
    """The kept bytes of ``what`` for the test with stored-bytes digest ``sha``, else None."""
    try:
        return _path(sha, what).read_bytes()
    except OSError:
        return None


def write(sha: str, what: str, data: bytes) -> bool:
    """Keep ``data`` (atomically: a temporary file renamed over the final name); False if the
    cache folder cannot be written."""
    path = _path(sha, what)
    try:
        path.parent.mkdir(parents=True, exist_ok=True)
        fd, tmp = tempfile.mkstemp(dir=path.parent, prefix=".tmp-")
        try:
            with os.fdopen(fd, "wb") as f:
                f.write(data)
            os.replace(tmp, path)
        except BaseException:
            Path(tmp).unlink(missing_ok=True)
            raise
    except OSError:
        return False
    return True


def _lock_for(key) -> threading.Lock:
    with _key_locks_lock:
        if len(_key_locks) > 4096:
            _key_locks.clear()
        return _key_locks.setdefault(key, threading.Lock())


def kept(sha: str, what: str, make) -> bytes:
    """The kept bytes of ``what``, else ``make()`` (bytes or str) computed, kept and returned.

    Concurrent requests for the same product wait for the one computing it (and then read it),
    in this process (a lock) and in the other worker processes (an exclusive ``flock`` on a lock
    file beside it, POSIX), so six requests for one report compute it once."""
    data = read(sha, what)
    if data is not None:
        return data
    with _lock_for((sha, what)), _file_lock(_path(sha, what)):
        data = read(sha, what)
        if data is None:
            data = make()
            data = data.encode("utf-8") if isinstance(data, str) else bytes(data)
            write(sha, what, data)
    return data


def kept_file(sha: str, what: str) -> Path | None:
    """The file holding the kept ``what`` (to be sent as it is, never read whole), else None."""
    path = _path(sha, what)
    return path if path.is_file() else None


class _file_lock:
    """An exclusive lock on ``path + '.lock'`` across processes (no lock where there is no
    ``fcntl`` or the folder cannot be written: then only the in-process lock holds)."""

    def __init__(self, path: Path):
        self.path, self.fd = path.with_name(path.name + ".lock"), None

    def __enter__(self):
        try:
            import fcntl

            self.path.parent.mkdir(parents=True, exist_ok=True)
            self.fd = os.open(self.path, os.O_RDWR | os.O_CREAT, 0o600)
            fcntl.flock(self.fd, fcntl.LOCK_EX)
        except (ImportError, OSError):
            self.fd = None
        return self

    def __exit__(self, *exc):
        if self.fd is not None:
            os.close(self.fd)                 # closing releases the flock


def digest(*parts) -> str:
    """A short digest of further inputs a product depends on (for ``what``)."""
    return hashlib.sha256(repr(parts).encode("utf-8", "surrogatepass")).hexdigest()[:16]


def evaluated(raw, sha: str, filename: str, kind: str | None, size: int | None = None):
    """The evaluation of stored bytes ``raw`` (digest ``sha``): from memory, else the disk, else
    :func:`~axiscal.store.kinds.evaluate_file` once (then kept).

    ``raw`` may be a callable that reads the bytes: it is called only when the evaluation must
    be made (then ``size``, the bytes' length, counts them in memory without reading them)."""
    def make():
        from axiscal.store.kinds import evaluate_file

        return evaluate_file(raw() if callable(raw) else raw, filename, kind)

    return derived(sha, "evaluated", make, size=len(raw) if size is None else size)


def derived(sha: str, what: str, make, size: int | None = None, disk: bool = True):
    """A value computed from a stored test (its evaluation; a page's plot, tables, figures):
    kept in memory and as a pickle on disk under ``what``, made by ``make()`` once. In memory it
    counts ``size`` bytes (default: its pickle's size) against :data:`MEMORY_BYTES`.

    With ``disk`` False it is kept in this process's memory only, counting its length (a page's
    rendered HTML, whose templates are not part of the version the disk is keyed by)."""
    key = (sha, _version(), what)
    if not disk:
        found = _in_memory(key)
        if found is None:
            found = (make(),)
            _hold(key, found[0], len(found[0]) if size is None else size)
        return found[0]
    found = _in_memory(key)
    if found is not None:
        return found[0]
    with _lock_for(key):
        found = _kept(key, size)           # in memory, made by another thread meanwhile, or on disk
        if found is not None:
            return found[0]
        value = make()
        data = _keep_on_disk(sha, value, f"{what}.pickle")
        _hold(key, value, len(data or b"") if size is None else size)
    return value


def lookup(sha: str, what: str, size: int | None = None) -> tuple | None:
    """``(value,)`` of :func:`derived` ``what`` if it is kept (in memory, or on disk: then read
    into memory), else None; never makes it. A caller on an event loop looks first, and hands
    the making (seconds for a figure) to a thread only when nothing is kept."""
    key = (sha, _version(), what)
    return _in_memory(key) or _kept(key, size)


def _kept(key, size: int | None) -> tuple | None:
    """``(value,)`` under ``key`` in memory, else from its pickle on disk (then held in memory,
    counting ``size`` bytes, default the pickle's), else None."""
    found = _in_memory(key)
    if found is not None:
        return found
    sha, _, what = key
    data = read(sha, f"{what}.pickle")
    if data is None:
        return None
    try:
        value = pickle.loads(data)
    except Exception:                         # noqa: BLE001 - a damaged entry: make it again
        return None
    _hold(key, value, len(data) if size is None else size)
    return (value,)


def _in_memory(key) -> tuple | None:
    """``(value,)`` kept in this process's memory under ``key`` (now the most recently used),
    else None."""
    with _memory_lock:
        hit = _memory.get(key)
        if hit is None:
            return None
        _memory.move_to_end(key)
        return (hit[0],)


def remember(raw: bytes, sha: str, ev) -> None:
    """Keep an evaluation just made (at upload), so the first view is already a look-up."""
    _keep_on_disk(sha, ev, "evaluated.pickle")
    _hold((sha, _version(), "evaluated"), ev, len(raw))


def _keep_on_disk(sha: str, value, what: str) -> bytes | None:
    try:
        data = pickle.dumps(value, protocol=pickle.HIGHEST_PROTOCOL)
    except Exception:                         # noqa: BLE001 - not picklable: memory only
        return None
    write(sha, what, data)
    return data


def _hold(key, ev, size: int) -> None:
    if size > MEMORY_BYTES:
        return
    with _memory_lock:
        old = _memory.pop(key, None)
        _memory_size[0] += size - (old[1] if old else 0)
        _memory[key] = (ev, size)
        while len(_memory) > MEMORY_ENTRIES or _memory_size[0] > MEMORY_BYTES:
            _memory_size[0] -= _memory.popitem(last=False)[1][1]


def forget_memory() -> None:
    """Empty this process's in-memory evaluations (tests; the disk keeps them)."""
    with _memory_lock:
        _memory.clear()
        _memory_size[0] = 0
