"""Renishaw XL-80 dynamic capture files (``.rtx``, written by CARTO Capture's dynamic mode).

Layout, as a public converter reads it (T. Pani, "rtx2csv", github.com/TanmayPani/rtx2csv,
``rtx_to_csv.py``, which converts CARTO-Dynamic ``.rtx`` files to CSV)::

    HEADER::\\r\\n
    Owner: CARTO-Dynamic\\r\\n
    Version no: 4.13.9237.28405\\r\\n
    File Type: ...\\r\\n
    Velocity: 0\\r\\n
    Sample rate: 50000\\r\\n
    Sample no: 1000001\\r\\n
    Actual sample rate: 50000\\r\\n
    Trigger point: 0\\r\\n
    Trigger interval: 2e-05\\r\\n
    Flags: 0 1 2 0 2\\r\\n
    Machine: ...\\r\\n  Serial No: ...\\r\\n  Date: 10/02/2025 12:58:22\\r\\n  By: User\\r\\n
    Axis: ...\\r\\n  Location: ...\\r\\n
    Data:\\r\\n
    <Sample no little-endian float64 readings>
    EOF::\\r\\n

What the public converter establishes, and what axiscal assumes
---------------------------------------------------------------
Established by ``rtx_to_csv.py`` and its published output (``test/outputs/
MagOuterDynamic1Pitch2Cyc/header.json``, commit ``105a6fc``): the header's keys and their
form (``Sample rate: 50000``, ``Sample no: 1000001``, ``Actual sample rate: 50000``,
``Trigger interval: 2e-05``, ``Date: 10/02/2025 12:58:22``); the readings are 8-byte floats
between ``Data:\r\n`` and ``EOF::\r\n``; the converter reads *every* reading it finds there
(it never compares their number with ``Sample no``) and times reading ``i`` at
``i / Actual sample rate``. A real header's ``Sample no`` of 1 000 001 at 50 000 Hz counts
both ends of a 20 s capture.

Not established by any public source: whether CARTO ever writes fewer or more readings than
``Sample no``, what a padding would hold, and the unit of the readings (the converter labels
linear readings µm and angular µrad, so axiscal takes µm by default and lets the user say
otherwise, ``--unit``). axiscal therefore reads a count that differs from ``Sample no`` this
way, and says so in the record's ``notes`` (carried into the capture's result):

* fewer readings than ``Sample no`` (a capture stopped early): the readings there are read at
  the header's rate, as the converter reads them, and the shortfall is stated;
* more readings than ``Sample no``, all the readings beyond it one and the same value (0, NaN
  or any filler): that tail is padding, dropped and stated;
* more readings, and the tail beyond ``Sample no`` varies: which readings are the capture is
  ambiguous (a header from another capture, or readings appended), and the file is refused.

A header value that is not a finite positive number (``Sample no`` not a whole number from 2 to
10¹², a sample rate that is NaN, negative, zero or above 10 MHz) is refused in one line. The
readings are memory-mapped, not copied: a one-minute 50 kHz capture (24 MB) costs no more
memory than its pages in use. A file whose data is not a whole number of readings, or lacks its
``EOF::`` end, is refused by name.

:func:`format_rtx` writes the same layout (for tests and simulations).
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from axiscal import units
from axiscal.errors import AxiscalError, DataFormatError, MissingFileError
from axiscal.procedures.capture import Record

__all__ = ["read_rtx", "format_rtx", "parse_rtx_header"]

_HEAD, _DATA, _EOF = b"HEADER::", b"Data:\r\n", b"EOF::\r\n"
_MAX_HEADER = 65536


def parse_rtx_header(head: bytes, source: str = "<rtx>") -> tuple[dict, int]:
    """The header's ``Key: value`` pairs and the offset of the first reading."""
    if not head.startswith(_HEAD):
        raise DataFormatError("not a Renishaw .rtx file: it does not start with 'HEADER::'",
                              source)
    end = head.find(_DATA)
    if end < 0:
        raise DataFormatError("no 'Data:' line in the first 64 KiB: the header is damaged",
                              source)
    header = {}
    for line in head[len(_HEAD):end].split(b"\r\n"):
        text = line.decode("latin-1").strip()
        if not text or text.endswith("::"):
            continue
        key, sep, value = text.partition(":")
        if sep:
            header[key.strip()] = value.strip()
    return header, end + len(_DATA)


def read_rtx(path, unit: str | None = None):
    """Read a ``.rtx`` file as a :class:`~axiscal.procedures.capture.Record` (readings in SI).

    Parameters
    ----------
    path : path
    unit : str, optional
        Unit of the readings: ``um`` (default, as the public converter labels them), ``mm``,
        ``nm``; ``arcsec`` or ``urad`` for an angular capture.
    """
    p = Path(path)
    if not p.is_file():
        raise MissingFileError(p)
    src = str(p)
    size = p.stat().st_size
    with open(p, "rb") as fh:
        head = fh.read(_MAX_HEADER)
        fh.seek(max(0, size - len(_EOF)))
        tail = fh.read()
    header, start = parse_rtx_header(head, src)
    if tail != _EOF:
        raise DataFormatError("the file does not end with 'EOF::': it is truncated", src)
    nbytes = size - start - len(_EOF)
    if nbytes < 0 or nbytes % 8:
        raise DataFormatError(f"{nbytes} bytes of data are not a whole number of 8-byte "
                              "readings: the file is truncated or damaged", src)
    count = nbytes // 8
    declared = _sample_no(header, src)
    rate = _rate(header, src)
    raw = np.memmap(p, dtype="<f8", mode="r", offset=start, shape=(count,)) if count else \
        np.zeros(0)
    count, notes = _reconcile(raw, count, declared, src)
    if count < 2:
        raise DataFormatError(f"{count} reading(s): a record needs at least 2", src)
    u = unit or "um"
    try:
        factor = units.factor(u)
    except AxiscalError as exc:
        raise DataFormatError(f"--unit {u!r}: {exc}", src) from None
    values = np.multiply(raw[:count], factor)  # SI; one pass over the mapped pages
    if not np.isfinite(values).all():
        raise DataFormatError("the record holds NaN or infinite readings", src)
    times = np.arange(count) / rate
    kind = "rotary" if units.dimension(u) == "angle" else "linear"
    return Record(times, values, kind, None, float(rate), header, u, src, notes)


def format_rtx(readings, sample_rate: float, **fields) -> bytes:
    """The bytes of a ``.rtx`` file holding ``readings`` (in the file's unit)."""
    v = np.asarray(readings, dtype="<f8")
    keys = {"Owner": "CARTO-Dynamic", "Version no": "4.13.0.0", "File Type": "",
            "Velocity": "0", "Sample rate": f"{sample_rate:g}", "Sample no": str(v.size),
            "Actual sample rate": f"{sample_rate:g}", "Trigger point": "0",
            "Trigger interval": f"{1 / sample_rate:g}", "Flags": "0 1 2 0 2", "Machine": "",
            "Serial No": "", "Date": "", "By": "axiscal", "Axis": "", "Location": ""}
    keys.update({k.replace("_", " "): str(x) for k, x in fields.items()})
    head = b"HEADER::\r\n" + b"".join(f"{k}: {x}\r\n".encode("latin-1")
                                        for k, x in keys.items()) + _DATA
    return head + v.tobytes() + _EOF


#: Largest sample rate a header may give, Hz (the XL-80 samples at up to 50 kHz).
MAX_RATE = 1e7


def _sample_no(header: dict, src: str):
    """The header's ``Sample no`` as a whole number, or None if absent."""
    n = _number(header, "Sample no", src)
    if n is not None and not (n == int(n) and 2 <= n <= 1e12):
        raise DataFormatError(f"header Sample no: {header['Sample no']!r} is not a whole number "
                              "of samples from 2 to 10^12", src)
    return None if n is None else int(n)


def _rate(header: dict, src: str) -> float:
    """``Actual sample rate`` (what the converter times readings by), else ``Sample rate``."""
    for key in ("Actual sample rate", "Sample rate"):
        r = _number(header, key, src)
        if r is not None:
            if not 0 < r <= MAX_RATE:
                raise DataFormatError(f"header {key}: {header[key]!r} is not a sample rate "
                                      f"(above 0, at most {MAX_RATE:g} Hz)", src)
            return r
    raise DataFormatError("no 'Actual sample rate' or 'Sample rate' in the header", src)


def _reconcile(raw, count: int, declared, src: str) -> tuple[int, tuple]:
    """The number of readings to keep and what was noted (module docstring)."""
    if declared is None or declared == count:
        return count, ()
    if count < declared:
        return count, (f"the file holds {count} readings, its header's Sample no {declared}: "
                       f"the capture stopped early ({declared - count} readings short); the "
                       "readings present are read at the header's rate",)
    tail = np.asarray(raw[declared:])
    first = tail[0]
    filler = np.isnan(tail).all() if np.isnan(first) else bool((tail == first).all())
    if not filler:
        raise DataFormatError(f"the file holds {count} readings, its header's Sample no "
                              f"{declared}, and the {count - declared} beyond it vary: which "
                              "readings are the capture is ambiguous", src)
    return declared, (f"{count - declared} readings of {first:g} after the header's Sample no "
                      f"{declared} dropped as padding",)


def _number(header: dict, key: str, src: str):
    if key not in header or header[key] == "":
        return None
    try:
        v = float(header[key])
    except ValueError:
        raise DataFormatError(f"header {key}: {header[key]!r} is not a number", src) from None
    if not np.isfinite(v):
        raise DataFormatError(f"header {key}: {header[key]!r} is not a finite number", src)
    return v
