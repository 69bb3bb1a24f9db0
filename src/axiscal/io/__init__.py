"""Files in and out. Every format has ``parse_<fmt>(text)`` and ``read_<fmt>(path)``.

:func:`read_positioning` picks the reader by the file's extension and content.
"""

from __future__ import annotations

from pathlib import Path

from axiscal.io._files import read_text
from axiscal.errors import DataFormatError

__all__ = ["read_positioning", "parse_positioning", "read_text"]


#: A positioning file larger than this is streamed when it is a CSV (the other formats are read
#: whole; they hold kilobytes).
STREAM_ABOVE_BYTES = 1 << 20


def read_positioning(path, target_unit: str | None = None, deviation_unit: str | None = None,
                     axis_kind: str | None = None, progress=None, epics: dict | None = None,
                     encoding: str | None = None):
    """Read a positioning test from a CSV, JSON, Renishaw .rtl/.rta or EPICS ecmc file (see
    :func:`parse_positioning`).

    Parameters
    ----------
    path : str or Path
    target_unit, deviation_unit : str, optional
        Units for CSV/ecmc files that do not declare them.
    axis_kind : {"linear", "rotary"}, optional
        Overrides the kind a CSV file would be given from its units.
    progress : callable, optional
        Called with ``(bytes read, file size)`` while a large CSV file is streamed.
    epics : dict, optional
        Options of an EPICS camonitor log (:func:`axiscal.io.epics.parse_epics`: ``setpoint_pv``,
        ``reference_pv``, ``targets``, ``plan`` ...); refused for any other file.
    encoding : str, optional
        The code page of a Renishaw ``.rtl``/``.rta`` export (``cp1250`` …, one of
        :data:`axiscal.io.renishaw.CODE_PAGES`, or ``utf-8``/``utf-16``; the command's
        ``--encoding``); by default UTF-8, UTF-16 with a BOM, else Windows-1252. An unknown
        encoding, or one given for a file that is not a Renishaw export, is refused.

    A CSV file over :data:`STREAM_ABOVE_BYTES` is read a line at a time into compact arrays, so
    memory grows with the readings, not with the file's text.
    """
    if encoding is not None:
        return _read_renishaw_in(path, encoding, target_unit, deviation_unit, axis_kind, epics)
    from axiscal.io._files import open_regular_file

    fh, size = open_regular_file(path)
    with fh:
        head = fh.read(STREAM_ABOVE_BYTES + 1)
    if len(head) > STREAM_ABOVE_BYTES:
        text = head.decode("utf-8", errors="replace")
        if not _whole_file_format(text, str(path)):
            from axiscal.io import csv as _csv

            return _csv.read_positioning_csv(path, target_unit, deviation_unit, axis_kind,
                                             progress=progress)
    text, used = _text(path)
    if used != "utf-8":                      # a Renishaw export in UTF-16 or a code page
        return _renishaw_text(text, used, path, target_unit, deviation_unit, axis_kind, epics)
    return parse_positioning(text, str(path), target_unit, deviation_unit, axis_kind,
                             epics=epics)


def _read_renishaw_in(path, encoding, target_unit, deviation_unit, axis_kind, epics):
    """A Renishaw export read in the code page given (``encoding``); any other file refused."""
    from axiscal.errors import InputError
    from axiscal.io import detect
    from axiscal.io import renishaw as _renishaw
    from axiscal.io._files import read_bytes

    text, used = _renishaw.decode(read_bytes(path), encoding, str(path))
    if not detect.looks_like_renishaw(text):
        raise InputError(f"--encoding {encoding} is the code page of a Renishaw .rtl/.rta export; "
                         f"{path} is not one (axiscal reads its other files as UTF-8): drop "
                         "--encoding")
    return _renishaw_text(text, used, path, target_unit, deviation_unit, axis_kind, epics)


def _renishaw_text(text, used, path, target_unit, deviation_unit, axis_kind, epics):
    """A Renishaw export's decoded ``text`` (code page ``used``) parsed; EPICS options refused."""
    from axiscal.io import renishaw as _renishaw

    if epics:
        raise DataFormatError(f"--{next(iter(epics)).replace('_', '-')} applies to an EPICS "
                              "camonitor log; this file is a Renishaw export", str(path))
    return _renishaw.parse_renishaw(text, source=str(path), target_unit=target_unit,
                                    deviation_unit=deviation_unit, axis_kind=axis_kind,
                                    encoding=used)


def _text(path) -> tuple[str, str]:
    """The file's text and encoding: UTF-8; a Renishaw export may also be UTF-16 (BOM) or in a
    Windows code page (:func:`axiscal.io.renishaw.decode`). Anything else not UTF-8 is refused
    as :func:`read_text` refuses it."""
    from axiscal.io._files import read_bytes

    data = read_bytes(path)
    if not data.startswith((b"\xff\xfe", b"\xfe\xff")):
        try:
            return data.decode("utf-8-sig"), "utf-8"
        except UnicodeDecodeError:
            pass
    from axiscal.io import detect
    from axiscal.io.renishaw import decode

    try:
        text, used = decode(data, None, str(path))
    except DataFormatError:
        return read_text(path), "utf-8"      # not text: the UTF-8 error names the byte
    if detect.looks_like_renishaw(text):
        return text, used
    return read_text(path), "utf-8"          # raises the UTF-8 error, naming the byte


def _whole_file_format(text: str, source: str) -> bool:
    """True for a JSON, Renishaw or ecmc positioning file (told by the name or the content)."""
    from axiscal.io import detect

    return (Path(source).suffix.lower() == ".json" or text.lstrip("\ufeff \t\r\n").startswith("{")
            or detect.looks_like_ecmc(text) or detect.looks_like_renishaw(text)
            or detect.looks_like_camonitor(text))


def parse_positioning(text: str, source: str = "<text>", target_unit: str | None = None,
                      deviation_unit: str | None = None, axis_kind: str | None = None,
                      epics: dict | None = None):
    """Parse positioning data already read, choosing the format by ``source``'s extension and content.

    JSON (``.json`` or text starting with ``{``), Renishaw ``.rtl``/``.rta`` (a ``HEADER::``
    line first), EPICS ecmc (``TGT_DATA[`` keys), an EPICS camonitor log (``PV time stamp
    value`` lines; ``epics`` holds its options) or tidy CSV. Only the reader the file needs is
    imported (:mod:`axiscal.io.detect` tells which).
    """
    from axiscal.io import detect

    if detect.looks_like_camonitor(text):
        from axiscal.io import epics as _epics

        return _epics.parse_epics(text, target_unit=target_unit, deviation_unit=deviation_unit,
                                  axis_kind=axis_kind, source=source, **(epics or {}))
    if epics:
        raise DataFormatError(f"--{next(iter(epics)).replace('_', '-')} applies to an EPICS "
                              "camonitor log; this file is not one", source)
    if Path(source).suffix.lower() == ".json" or text.lstrip().startswith("{"):
        if target_unit or deviation_unit:
            raise DataFormatError("a JSON dataset carries its own units; drop the unit options",
                                  source)
        from axiscal.io import json as _json

        return _json.parse_positioning_json(text, source=source)
    if detect.looks_like_renishaw(text):
        from axiscal.io import renishaw as _renishaw

        return _renishaw.parse_renishaw(text, source=source, target_unit=target_unit,
                                        deviation_unit=deviation_unit, axis_kind=axis_kind)
    if detect.looks_like_ecmc(text):
        from axiscal.io import ecmc as _ecmc

        return _ecmc.parse_ecmc(text, target_unit=target_unit, deviation_unit=deviation_unit,
                                axis_kind=axis_kind, source=source)
    from axiscal.io import csv as _csv

    return _csv.parse_positioning_csv(text, target_unit=target_unit, deviation_unit=deviation_unit,
                                      axis_kind=axis_kind, source=source)
