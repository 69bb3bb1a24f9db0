"""JSON form of a positioning dataset (``"format": "axiscal.positioning/1"``).

The dataset itself, round-tripping exactly: ``parse_positioning_json(format_positioning_json(ds))``
equals ``ds`` field for field (floats are written with ``repr`` precision, missing readings as
``null``).

Keys: ``format``, ``axis_kind`` (``linear``/``rotary``), ``target_unit``, ``deviation_unit``,
``targets`` (list of m numbers), ``up`` and ``down`` (m lists of runs each; ``down`` holds empty
lists for a unidirectional test), ``metadata`` (``machine``, ``axis``, ``operator``, ``date``,
``instrument``, ``notes``, ``environment`` with ``air_temperature`` °C, ``material_temperature``
list of °C, ``pressure`` Pa, ``humidity`` %RH, ``expansion_coefficient`` 1/K).
"""

from __future__ import annotations

import json

import numpy as np

from axiscal.datasets import Metadata, PositioningDataset
from axiscal.errors import AxiscalError, DataFormatError

__all__ = ["FORMAT", "parse_positioning_json", "read_positioning_json", "format_positioning_json"]

FORMAT = "axiscal.positioning/1"


def format_positioning_json(ds: PositioningDataset) -> str:
    """Serialise a dataset to JSON text."""
    return json.dumps(ds.to_dict(), indent=1) + "\n"


def read_positioning_json(path) -> PositioningDataset:
    """Read a dataset written by :func:`format_positioning_json`."""
    from axiscal.io._files import read_text

    return parse_positioning_json(read_text(path), source=str(path))


def parse_positioning_json(text: str, source: str = "<text>") -> PositioningDataset:
    """Parse the JSON form of a dataset; any defect is a :class:`DataFormatError`."""
    from axiscal._parse import loads_json

    d = loads_json(text, source)
    if not isinstance(d, dict):
        raise DataFormatError("a dataset must be a JSON object", source)
    if d.get("format") != FORMAT:
        raise DataFormatError(f"'format' is {d.get('format')!r}, expected {FORMAT!r}", source)
    missing = [k for k in ("axis_kind", "target_unit", "deviation_unit", "targets", "up", "down")
               if k not in d]
    if missing:
        raise DataFormatError(f"missing key(s): {', '.join(missing)}", source)
    if not isinstance(d.get("metadata", {}), (dict, type(None))):
        raise DataFormatError(f"'metadata' must be a JSON object, not {d['metadata']!r}", source)
    try:
        targets = _array(d["targets"], "targets")
        up = _array(d["up"], "up", rows=len(targets))
        down = _array(d["down"], "down", rows=len(targets))
        return PositioningDataset(
            axis_kind=d["axis_kind"],
            targets=targets,
            up=up,
            down=down,
            target_unit=d["target_unit"],
            deviation_unit=d["deviation_unit"],
            metadata=Metadata.from_dict(d.get("metadata")),
        )
    except DataFormatError:
        raise
    except (AxiscalError, TypeError, ValueError) as exc:
        raise DataFormatError(str(exc), source) from None


def _array(value, name: str, rows: int | None = None) -> np.ndarray:
    if not isinstance(value, list):
        raise DataFormatError(f"{name!r} must be a list")
    if rows is None:
        for v in value:
            if not isinstance(v, (int, float)) or isinstance(v, bool):
                raise DataFormatError(f"{name!r} holds {v!r}, not a number")
        return np.array(value, dtype=float)
    if len(value) != rows:
        raise DataFormatError(f"{name!r} has {len(value)} rows for {rows} targets")
    widths = {len(r) if isinstance(r, list) else -1 for r in value}
    if -1 in widths or len(widths) > 1:
        raise DataFormatError(f"{name!r} must be {rows} lists of equal length")
    out = []
    for r in value:
        row = []
        for v in r:
            if v is None:
                row.append(np.nan)
            elif isinstance(v, (int, float)) and not isinstance(v, bool):
                row.append(float(v))
            else:
                raise DataFormatError(f"{name!r} holds {v!r}, not a number or null")
        out.append(row)
    width = widths.pop() if widths else 0
    return np.array(out, dtype=float).reshape(rows, width)
