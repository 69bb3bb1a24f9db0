"""Small helpers shared by the command modules: output, JSON, units, files.

Nothing here imports rich or matplotlib at module import time.
"""

from __future__ import annotations

import json
import os
import sys
import time
from contextlib import contextmanager
from pathlib import Path
from typing import Any

import typer

from axiscal._json import jsonable
from axiscal.errors import InputError

__all__ = ["console", "print_json", "jsonable", "out_path", "plot_path", "report_path",
           "typed_path", "note", "progress_bar"]


def console():
    """A rich console on stdout (imported on first use) that never cuts a number.

    Piped or redirected output has no terminal width; rich would fall back to 80 columns and cut
    numbers with an ellipsis ("121.6…"), which in a calibration table is a wrong number. So a
    non-terminal gets ``COLUMNS`` if set, else 160 columns; ``COLUMNS`` is clamped to 20 …
    1000 (0 printed nothing). And a table wider than the console is drawn at its own full width
    (the terminal wraps its lines) instead of being squeezed: at 80 columns a cell showed
    ``121.6…``, at 20 cells were empty (issue 39).
    """
    return _whole_console()(highlight=False, width=_width())


def _width() -> int | None:
    """The console width: ``COLUMNS`` clamped to 20 … 1000 (a bad value ignored); for a
    non-terminal without it, 160."""
    import os

    try:
        given = int(os.environ.get("COLUMNS", "").strip() or 0)
    except ValueError:
        given = 0
    if given > 0:
        return min(max(given, 20), 1000)
    return None if sys.stdout.isatty() else 160


def _whole_console():
    """The rich Console class whose tables keep every cell whole (see :func:`console`)."""
    from rich.console import Console
    from rich.table import Table

    class WholeConsole(Console):
        def print(self, *objects, **kw):   # noqa: D102 - rich API
            need = max((self.measure(o, options=self.options.update_width(10**4)).maximum
                        for o in objects if isinstance(o, Table)), default=0)
            if need <= self.width:
                return super().print(*objects, **kw)
            narrow, self.width = self.width, need   # rich's print(width=) cannot widen
            try:
                return super().print(*objects, **kw)
            finally:
                self.width = narrow

        def on_broken_pipe(self) -> None:   # rich exits 1 ("tolerance not met"): say a pipe
            raise BrokenPipeError

    return WholeConsole


def print_json(obj: Any) -> None:
    """Write ``obj`` as indented JSON on stdout."""
    sys.stdout.write(json.dumps(jsonable(obj), indent=2, ensure_ascii=False) + "\n")


def out_path(path: Path, what: str, inputs=None) -> Path:
    """Check that an output file can be written (its folder exists), before any work is done.

    An output that is one of the command's inputs (the same name, a hard link or a symbolic link
    to it) is refused: writing it would destroy the measurement it is made from. The inputs are
    ``inputs`` if given, else every path the running command was given (:func:`_given_paths`).
    """
    path = Path(path)
    _not_an_input(path, what, _given_paths(path) if inputs is None else inputs)
    try:
        if path.exists() and path.is_dir():
            raise InputError(f"{what} {path} is a folder; give a file name")
        if path.exists() and not path.is_file():   # a FIFO or a device: writing would block
            raise InputError(f"{what} {path} is not a regular file; give a file name")
        if path.is_symlink() and not path.exists():
            raise InputError(f"{what} {path} is a symbolic link to nothing (or a loop of links)")
        if not path.parent.exists():
            raise InputError(f"cannot write {what} {path}: folder {path.parent} does not exist")
        import tempfile   # only where an output is written (start-up of the other commands)

        # a read-only or pseudo file system refuses here, before any work is done
        tempfile.TemporaryFile(dir=path.parent).close()
        if path.exists() and not os.access(path, os.W_OK):
            raise InputError(f"cannot write {what} {path}: the file is read-only")
        if len(path.name.encode()) > 255:
            raise InputError(f"cannot write {what}: the file name is longer than 255 bytes")
    except OSError as exc:   # a name too long, a path through a file ...
        raise InputError(f"cannot write {what} {path}: {exc.strerror or exc}") from None
    return path


def _given_paths(output: Path) -> list[tuple[str, str]]:
    """(name, path) of every path parameter of the running command, less ``output`` itself.

    Click keeps the values as given (strings), so the output's own parameter is recognised by its
    value: its last occurrence is dropped (commands declare their inputs first); another one is
    an input of the same name.
    """
    from typer._click.globals import get_current_context

    ctx = get_current_context(silent=True)
    found, databases = [], []
    while ctx is not None:
        for param in ctx.command.params:
            if param.name == "db" and param.param_type_name == "option":
                databases += _database_file(ctx.params.get("db"))
                continue
            if type(param.type).__name__ not in ("TyperPath", "Path"):
                continue
            values = ctx.params.get(param.name)
            for v in values if isinstance(values, (list, tuple)) else [values]:
                if v is not None:
                    found.append((param.opts[0] if param.param_type_name == "option"
                                  else param.name.upper(), str(v)))
        ctx = ctx.parent
    for i, (_, v) in reversed(list(enumerate(found))):
        if v == str(output):
            del found[i]
            break
    return found + databases


def _database_file(url) -> list[tuple[str, str]]:
    """The history database's file as an input, ``("--db", path)`` (none on PostgreSQL).

    ``history show 1 --report r.html --db sqlite:///r.html`` would write the report over the
    history (issue 39); the history a command opens is an input of it like any file it reads,
    and so are SQLite's write-ahead log and shared-memory files beside it.
    """
    try:
        from axiscal.store.database import sqlite_path
        from axiscal.store.history import default_url

        url = url or default_url()
        if url.split(":", 1)[0] not in ("sqlite", "sqlite+pysqlite"):
            return []
        path = sqlite_path(url)
    except Exception:   # noqa: BLE001 - a bad URL is the store's to refuse, with its message
        return []
    if path is None:
        return []
    return [("--db", str(path)), ("--db", f"{path}-wal"), ("--db", f"{path}-shm")]


def _not_an_input(path: Path, what: str, inputs) -> None:
    """Refuse ``path`` if it is one of ``inputs`` (same file by device and inode, or by name)."""
    try:
        out_stat = path.stat() if path.exists() else None
        out_real = os.path.realpath(path)
    except (OSError, ValueError):   # a loop of links or a bad name: out_path says which
        return
    for name, given in inputs:
        try:
            same = os.path.realpath(given) == out_real
            if out_stat is not None and not same and Path(given).exists():
                st = Path(given).stat()
                same = (st.st_dev, st.st_ino) == (out_stat.st_dev, out_stat.st_ino)
        except (OSError, ValueError):
            continue
        if same and name == "--db":
            raise InputError(f"{what} {_short(path)} is the history database (--db "
                             f"{_short(given)}): writing it would destroy the history; give "
                             "another file name")
        if same:
            raise InputError(f"{what} {_short(path)} is the input {name} {_short(given)}: "
                             "writing it would destroy that input; give another file name")


def _short(path) -> str:
    """A path for a message, at most about 120 characters (a hostile name can be 1 MB)."""
    text = str(path)
    return text if len(text) <= 120 else f"{text[:60]}…{text[-40:]}"


PLOT_SUFFIXES = (".png", ".svg", ".pdf")


def plot_path(path: Path) -> Path:
    """Check a plot file before any work: writable folder and a .png, .svg or .pdf name."""
    p = out_path(path, "plot")
    if p.suffix.lower() not in PLOT_SUFFIXES:
        raise InputError(f"plot file {p.name}: use a .png, .svg or .pdf extension")
    return p


def typed_path(path: Path, what: str, suffixes: tuple[str, ...]) -> Path:
    """Check an output file before any work: writable folder and one of ``suffixes``.

    A report named ``r.png`` or a CSV named ``plan.pdf`` is a slip of the keyboard; writing it
    would leave a file no program opens.
    """
    p = out_path(path, what)
    if p.suffix.lower() not in suffixes:
        raise InputError(f"{what} file {p.name}: use a {' or '.join(suffixes)} extension")
    return p


def report_path(path: Path) -> Path:
    """Check a report file before any work: writable folder and a .html, .htm or .pdf name.

    A PDF needs WeasyPrint (the ``report`` extra); that is checked here too, before any work.
    """
    p = typed_path(path, "report", (".html", ".htm", ".pdf"))
    if p.suffix.lower() == ".pdf":
        try:
            import importlib.util

            missing = importlib.util.find_spec("weasyprint") is None
        except (ImportError, ValueError):
            missing = True
        if missing:
            raise InputError(f"report {p.name}: a PDF needs WeasyPrint; pip install "
                             "'axiscal[report]' or write a .html report")
    return p


def note(message: str) -> None:
    """A one-line note on stderr (so --json stdout stays clean)."""
    typer.echo(message, err=True)


class _LazyBar:
    """A progress callback ``(done, total)`` that shows a transient rich bar on stderr once the
    work has taken longer than ``delay`` seconds, and only on a terminal (a pipe, a log file or
    ``--json`` output stays clean)."""

    def __init__(self, description: str, delay: float = 0.5):
        self.description = description
        self.delay = delay
        self.start = time.monotonic()
        self.bar = None
        self.task = None

    def __call__(self, done: float, total: float | None = None) -> None:
        if self.bar is None:
            if time.monotonic() - self.start < self.delay or not sys.stderr.isatty():
                return
            from rich.console import Console
            from rich.progress import Progress

            self.bar = Progress(console=Console(stderr=True), transient=True)
            self.bar.start()
            self.task = self.bar.add_task(self.description, total=total)
        self.bar.update(self.task, completed=done, total=total)

    def close(self) -> None:
        if self.bar is not None:
            self.bar.stop()
            self.bar = None


@contextmanager
def progress_bar(description: str, delay: float = 0.5):
    """Yield a ``(done, total)`` callback for long work; see :class:`_LazyBar`."""
    bar = _LazyBar(description, delay)
    try:
        yield bar
    finally:
        bar.close()
