"""Reading and writing whole files with errors that name the file."""

from __future__ import annotations

import os
from contextlib import contextmanager
from pathlib import Path

from axiscal.errors import DataFormatError, InputError, MissingFileError

__all__ = ["read_text", "read_controller_text", "read_bytes", "load_toml", "write_text_atomic",
           "write_bytes_atomic", "write_files_atomic", "os_reason"]

#: Every file written through this module by the running process, in order: what an
#: interrupted command says it left (``axiscal: interrupted; wrote ...``).
WRITTEN: list[str] = []

#: Refuse to read text files larger than this (a positioning file is kilobytes).
MAX_TEXT_BYTES = 256 * 1024 * 1024


def read_text(path) -> str:
    """Read a UTF-8 (or UTF-8 with BOM) text file; errors name the file and the problem."""
    p = Path(path)
    with _naming_errors(p):
        data = _read_regular_file(p)
    try:
        return data.decode("utf-8-sig")
    except UnicodeDecodeError as exc:
        raise DataFormatError(_not_utf8(data, exc.start), str(p)) from None


def read_controller_text(path) -> tuple[str, str]:
    """A controller file's text and its encoding: UTF-16 with a BOM, UTF-8, else Windows-1252.

    Controller files come from Windows tools; a comment with ``µ`` in Windows-1252 is common
    (a Siemens ``.INI`` edited on the machine's PC). The numbers are ASCII either way.
    """
    data = read_bytes(path)
    if data.startswith((b"\xff\xfe", b"\xfe\xff")):       # UTF-16 with its BOM (Windows)
        try:
            return data.decode("utf-16"), "utf-16"
        except UnicodeDecodeError:
            raise DataFormatError("not UTF-16 text after its byte-order mark", str(path)) from None
    try:
        return data.decode("utf-8-sig"), "utf-8"
    except UnicodeDecodeError:
        if b"\x00" in data[:4096]:
            raise DataFormatError("not a text file (it holds NUL bytes)", str(path)) from None
        return data.decode("cp1252", errors="replace"), "windows-1252"


def read_bytes(path) -> bytes:
    """Read a regular file's bytes; errors name the file and the problem."""
    p = Path(path)
    with _naming_errors(p):
        return _read_regular_file(p)


@contextmanager
def _naming_errors(p: Path):
    """An operating system's error on ``p`` as a :class:`MissingFileError` naming the file."""
    try:
        yield
    except MissingFileError:
        raise
    except PermissionError:
        raise MissingFileError(p, "permission denied") from None
    except OSError as exc:   # a name too long, a loop of links, an I/O error ...
        raise MissingFileError(p, exc.strerror or str(exc)) from None


def _not_utf8(data: bytes, start: int, offset: int = 0) -> str:
    """Why the bytes are not UTF-8 text: a binary file, or text saved in another encoding.

    A CSV saved by a spreadsheet in Windows-1252 (``µm`` as the byte 0xB5) is the common case on
    the shop floor; saying "binary file" there sends the user looking in the wrong place.
    """
    head = data[:4096]
    at = offset + start
    controls = sum(b < 32 and b not in (9, 10, 13) for b in head)
    if b"\x00" in head or controls > len(head) // 20:
        return f"not UTF-8 text (byte {at}); is this a binary file?"
    return (f"not UTF-8 text (byte {at} is 0x{data[start]:02X}); save the file as UTF-8 "
            "(it looks like text in another encoding, such as Windows-1252)")


def open_regular_file(path):
    """A regular file opened for reading in binary, and its size; errors name the file."""
    p = Path(path)
    with _naming_errors(p):
        _check_regular(p)
        return open(p, "rb"), p.stat().st_size


def _check_regular(p: Path) -> None:
    if not p.exists():
        raise MissingFileError(p)
    if p.is_dir():
        raise MissingFileError(p, "is a folder, not a file")
    if not p.is_file():   # a FIFO or a device would block or never end
        raise MissingFileError(p, "is not a regular file")


def _read_regular_file(p: Path) -> bytes:
    _check_regular(p)
    if p.stat().st_size > MAX_TEXT_BYTES:
        raise DataFormatError(f"file is larger than {MAX_TEXT_BYTES // 2**20} MiB", str(p))
    return p.read_bytes()


def load_toml(path) -> dict:
    """Read a TOML configuration; a syntax error becomes a :class:`ConfigError` naming the file."""
    from axiscal._schema import loads_toml, remember_document

    text = read_text(path)
    return remember_document(loads_toml(text, str(path)), str(path), text)


def write_bytes_atomic(path, data: bytes) -> Path:
    """Write ``data`` to ``path`` through a temporary file so no half-written file is left."""
    import tempfile   # here, not at start-up: most commands write no file

    p = Path(path)
    try:
        fd, tmp = tempfile.mkstemp(prefix=f".{p.name}.", dir=p.parent or ".")
    except OSError as exc:   # a read-only or pseudo file system, a full disk ...
        raise InputError(f"cannot write {p}: {os_reason(exc)}") from None
    try:
        with os.fdopen(fd, "wb") as fh:
            fh.write(data)
            # mkstemp gives 0600; a report or table must get the mode a plain write gives (the
            # umask's), and overwriting keeps the old file's mode
            os.fchmod(fh.fileno(), _mode_for(p))
        os.replace(tmp, p)
        WRITTEN.append(str(p))
    except BaseException as exc:
        try:
            os.unlink(tmp)
        except OSError:
            pass
        if isinstance(exc, OSError):
            raise InputError(f"cannot write {p}: {os_reason(exc)}") from None
        raise
    return p


def os_reason(exc: OSError) -> str:
    """Why a write failed, in words that name the cause: a full disk, the file-size limit of
    the process (``ulimit -f``) or a disk quota, rather than the C library's short text alone.

    Examples
    --------
    >>> import errno
    >>> os_reason(OSError(errno.EFBIG, "File too large"))
    'the file-size limit of this process is reached (ulimit -f; File too large)'
    """
    import errno

    text = exc.strerror or str(exc)
    return {errno.ENOSPC: f"the disk is full ({text})",
            errno.EFBIG: f"the file-size limit of this process is reached (ulimit -f; {text})",
            errno.EDQUOT: f"the disk quota is exhausted ({text})"}.get(exc.errno, text)


def write_files_atomic(folder, files: dict, inputs=()) -> list[str]:
    """Write several files into ``folder``: all of them, or none.

    ``files`` maps a file name to its text or bytes. Each is first written into a hidden
    temporary folder inside ``folder``; only when every one is written (a full disk, a file-size
    limit or an interrupt stops it before) are they renamed into place, one ``rename`` each,
    and the temporary folder removed. So a full disk leaves none of them (issue 39: ``volumetric
    simulate --out`` on a full disk left 7 of 19 files), and an interrupt (SIGINT, or SIGTERM,
    which the command line turns into the same exception) removes the temporary folder.

    A name that would replace one of ``inputs`` (the same file by path, link or inode: a
    measured file the configuration names) is refused before anything is written, as is a name
    given twice.

    Returns
    -------
    list of str
        The names written, in order.
    """
    import shutil
    import tempfile

    out = Path(folder)
    names = list(files)
    _refuse_inputs(out, names, inputs)
    try:
        tmp = Path(tempfile.mkdtemp(prefix=".axiscal-", dir=out))
    except OSError as exc:
        raise InputError(f"cannot write into {out}: {os_reason(exc)}") from None
    try:
        for name in names:
            data = files[name]
            target = tmp / name
            target.write_bytes(data.encode("utf-8") if isinstance(data, str) else data)
            os.chmod(target, _mode_for(out / name))
        for name in names:
            os.replace(tmp / name, out / name)
            WRITTEN.append(str(out / name))
    except OSError as exc:
        raise InputError(f"cannot write {out / name}: {os_reason(exc)}; none of the "
                         f"{len(names)} files was written") from None
    finally:
        shutil.rmtree(tmp, ignore_errors=True)
    return names


def _refuse_inputs(out: Path, names: list, inputs) -> None:
    """Refuse a name of ``names`` in ``out`` that is given twice or is one of ``inputs``."""
    seen = set()
    for name in names:
        if Path(name).name != name or name in ("", ".", ".."):
            raise InputError(f"cannot write {name!r} into {out}: not a plain file name")
        if name.lower() in seen:   # a case-insensitive file system would merge them
            raise InputError(f"two outputs of one run are named {name} in {out}")
        seen.add(name.lower())
    keys = {}
    for given in inputs:
        try:
            real = os.path.realpath(given)
            st = os.stat(given)
            keys[real] = given
            keys[(st.st_dev, st.st_ino)] = given
        except (OSError, ValueError):
            continue
    for name in names:
        target = out / name
        try:
            hit = keys.get(os.path.realpath(target))
            if hit is None and target.exists():
                st = target.stat()
                hit = keys.get((st.st_dev, st.st_ino))
        except (OSError, ValueError):
            continue
        if hit is not None:
            raise InputError(f"{target} would replace the input {hit}: writing it would "
                             "destroy that input; give another folder")


def _mode_for(p: Path) -> int:
    """The permission bits of ``p`` if it exists, else 0666 less the process's umask."""
    try:
        return p.stat().st_mode & 0o7777
    except OSError:
        mask = os.umask(0)
        os.umask(mask)
        return 0o666 & ~mask


def write_text_atomic(path, text: str) -> Path:
    """Write UTF-8 text atomically (see :func:`write_bytes_atomic`)."""
    return write_bytes_atomic(path, text.encode("utf-8"))
