"""Files in and out. Every format has ``parse_<fmt>(text)`` and ``read_<fmt>(path)``.

:func:`read_positioning` picks the reader by the file's extension and content.
"""

from __future__ import annotations

from pathlib import Path

from axiscal.io._files import read_text
from axiscal.errors import DataFormatError

__all__ = ["read_positioning", "parse_positioning", "read_text"]


def read_positioning(path, target_unit: str | None = None, deviation_unit: str | None = None,
                     axis_kind: str | None = None):
    """Read a positioning test from a CSV, JSON or EPICS ecmc file (see :func:`parse_positioning`).

    Parameters
    ----------
    path : str or Path
    target_unit, deviation_unit : str, optional
        Units for CSV/ecmc files that do not declare them.
    axis_kind : {"linear", "rotary"}, optional
        Overrides the kind a CSV file would be given from its units.
    """
    return parse_positioning(read_text(path), str(path), target_unit, deviation_unit, axis_kind)


def parse_positioning(text: str, source: str = "<text>", target_unit: str | None = None,
                      deviation_unit: str | None = None, axis_kind: str | None = None):
    """Parse positioning data already read, choosing the format by ``source``'s extension and content.

    JSON (``.json`` or text starting with ``{``), EPICS ecmc (``TGT_DATA[`` keys) or tidy CSV.
    """
    from axiscal.io import csv as _csv
    from axiscal.io import ecmc as _ecmc
    from axiscal.io import json as _json

    if Path(source).suffix.lower() == ".json" or text.lstrip().startswith("{"):
        if target_unit or deviation_unit:
            raise DataFormatError("a JSON dataset carries its own units; drop the unit options",
                                  source)
        return _json.parse_positioning_json(text, source=source)
    if _ecmc.looks_like_ecmc(text):
        return _ecmc.parse_ecmc(text, target_unit=target_unit, deviation_unit=deviation_unit,
                                axis_kind=axis_kind, source=source)
    return _csv.parse_positioning_csv(text, target_unit=target_unit, deviation_unit=deviation_unit,
                                      axis_kind=axis_kind, source=source)
