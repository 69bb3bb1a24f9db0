"""A plain CSV compensation table for any other controller.

Format (written and read here; every column and unit named so nothing is implied)::

    # axiscal compensation table: correction = -deviation (add to the commanded position)
    # axis=X axis_kind=linear position_unit=mm correction_unit=um bidirectional=true modulo=false reference_index=0 resolution=0.1 extrapolation=hold
    position_mm,correction_up_um,correction_down_um
    0,-1.2,0.3
    ...

No limits beyond a table's own (at least 2 equidistant points). The axis name in the header and
the file name keeps to the POSIX portable characters (any other becomes ``_``, see
:func:`~axiscal.compensation.controllers._common.safe_axis_name`); a name changed so is kept in a
``# axis name in the source data: …`` comment line.
"""

from __future__ import annotations

from dataclasses import replace

import numpy as np

from axiscal.compensation.controllers._common import (
    SOURCE_COMMENT, ControllerFile, check_travel, parse_number, safe_axis_name)
from axiscal.compensation.tables import CompensationTable
from axiscal.errors import DataFormatError

__all__ = ["NAME", "write", "parse"]

NAME = "csv"
_KEYS = ("axis", "axis_kind", "position_unit", "correction_unit", "bidirectional", "modulo",
         "reference_index", "resolution", "extrapolation")


def write(table: CompensationTable, travel=None) -> ControllerFile:
    """Write ``table`` as CSV with a two-line header of metadata."""
    check_travel(table, travel, NAME)
    names = safe_axis_name(table.axis, NAME)
    table = replace(table, axis=names.name)
    pu, cu = table.position_unit, table.correction_unit
    meta = dict(axis=table.axis or "-", axis_kind=table.axis_kind.value, position_unit=pu,
                correction_unit=cu, bidirectional=str(table.bidirectional).lower(),
                modulo=str(table.modulo).lower(), reference_index=table.reference_index,
                resolution=f"{table.resolution:g}", extrapolation=table.extrapolation)
    lines = ["# axiscal compensation table: correction = -deviation (add to the commanded position)",
             "# " + " ".join(f"{k}={v}" for k, v in meta.items()), *names.comment("# "),
             f"position_{pu},correction_up_{cu},correction_down_{cu}"]
    lines += [f"{p:.10g},{u:.10g},{d:.10g}" for p, u, d in zip(table.positions, table.up, table.down)]
    enable = ["load the columns into the controller's table in its own sign convention "
              "(these are corrections to add to the commanded position)"]
    return ControllerFile(NAME, "\n".join(lines) + "\n", f"{table.axis or 'axis'}_compensation.csv",
                          table, tuple(enable))


def parse(text: str, source: str = "<text>") -> CompensationTable:
    """Read a CSV written by :func:`write`."""
    meta: dict[str, str] = {}
    rows = []
    header_seen = False
    for n, raw in enumerate(text.splitlines(), 1):
        line = raw.strip()
        if not line:
            continue
        if line.startswith(f"# {SOURCE_COMMENT}"):
            continue
        if line.startswith("#"):
            for tok in line[1:].split():
                if "=" in tok:
                    k, v = tok.split("=", 1)
                    meta[k] = v
            continue
        if not header_seen:
            if not line.startswith("position_"):
                raise DataFormatError("header 'position_<unit>,correction_up_<unit>,"
                                      "correction_down_<unit>' expected", source, n)
            header_seen = True
            continue
        cells = line.split(",")
        if len(cells) != 3:
            raise DataFormatError(f"{len(cells)} columns; expected 3", source, n)
        rows.append([parse_number(c, source, n) for c in cells])
    missing = [k for k in _KEYS if k not in meta]
    if missing:
        raise DataFormatError(f"header is missing {', '.join(missing)}", source)
    if len(rows) < 2:
        raise DataFormatError(f"{len(rows)} row(s); a table needs at least 2", source)
    arr = np.array(rows)
    steps = np.diff(arr[:, 0])
    if np.any(steps <= 0):
        raise DataFormatError("positions must increase strictly", source)
    regular = not np.any(np.abs(steps - steps[0]) > 1e-6 * max(1.0, abs(steps[0])))
    try:
        return CompensationTable(
            "" if meta["axis"] == "-" else meta["axis"], meta["axis_kind"], meta["position_unit"],
            meta["correction_unit"], float(arr[0, 0]), float(steps[0]), arr[:, 1], arr[:, 2],
            bidirectional=meta["bidirectional"] == "true", modulo=meta["modulo"] == "true",
            resolution=float(meta["resolution"]), reference_index=int(meta["reference_index"]),
            extrapolation=meta["extrapolation"], nodes=None if regular else arr[:, 0])
    except (ValueError, TypeError) as exc:
        raise DataFormatError(f"bad header value: {exc}", source) from None
