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

The unit of the readings is not publicly documented; the public converter labels linear
readings µm (and angular µrad), so axiscal takes µm by default and lets the user say otherwise
(``--unit``). The readings are memory-mapped, not copied: a one-minute 50 kHz capture (24 MB)
costs no more memory than its pages in use. A file whose data is not a whole number of
readings, lacks its ``EOF::`` end, or holds another number of readings than its header's
``Sample no`` is refused by name.

:func:`format_rtx` writes the same layout (for tests and simulations).
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from axiscal import units
from axiscal.errors import AxiscalError, DataFormatError, MissingFileError

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
    """Read a ``.rtx`` file as a :class:`~axiscal.io.measured.Record` (readings in SI).

    Parameters
    ----------
    path : path
    unit : str, optional
        Unit of the readings: ``um`` (default, as the public converter labels them), ``mm``,
        ``nm``; ``arcsec`` or ``urad`` for an angular capture.
    """
    from axiscal.io.measured import Record

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
    declared = _number(header, "Sample no", src)
    if declared is not None and int(declared) != count:
        raise DataFormatError(f"the header says {int(declared)} samples (Sample no), the file "
                              f"holds {count}", src)
    rate = _number(header, "Actual sample rate", src) or _number(header, "Sample rate", src)
    if not rate or rate <= 0:
        raise DataFormatError("no positive 'Actual sample rate' in the header", src)
    if count < 2:
        raise DataFormatError(f"{count} reading(s): a record needs at least 2", src)
    u = unit or "um"
    try:
        factor = units.factor(u)
    except AxiscalError as exc:
        raise DataFormatError(f"--unit {u!r}: {exc}", src) from None
    raw = np.memmap(p, dtype="<f8", mode="r", offset=start, shape=(count,))
    values = np.multiply(raw, factor)          # SI; one pass over the mapped pages
    if not np.isfinite(values).all():
        raise DataFormatError("the record holds NaN or infinite readings", src)
    times = np.arange(count) / rate
    kind = "rotary" if units.dimension(u) == "angle" else "linear"
    return Record(times, values, kind, None, float(rate), header, u, src)


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


def _number(header: dict, key: str, src: str):
    if key not in header or header[key] == "":
        return None
    try:
        return float(header[key])
    except ValueError:
        raise DataFormatError(f"header {key}: {header[key]!r} is not a number", src) from None
