"""Renishaw ``.ren`` compensation export (spacing, start, end and a value per point).

Source
------
The one public program found that reads the format is a Python converter from ``.REN`` to a
Siemens ``CHANDATA(1)`` / ``$AA_ENC_COMP`` table (in the public code index as file id
48250776003; its repository could not be resolved through the index, licence not seen; read for
the layout, no code copied). It establishes:

* three lines naming ``Compensation spacing``, ``Compensation start`` and ``Compensation end``,
  each followed by its number (the first number on the line), which it writes as
  ``$AA_ENC_COMP_STEP``, ``$AA_ENC_COMP_MIN`` and ``$AA_ENC_COMP_MAX``;
* a table after the header line ``No.     Axis position        Combined``, one row a point with
  three numbers, the third (``Combined``) copied verbatim into ``$AA_ENC_COMP[1,i,AXIS]`` for
  i = 0, 1, 2 … in row order, with ``$AA_ENC_COMP_IS_MODULO`` = 0.

Readings chosen
---------------
* **Unit and sign.** The converter copies the Combined value unchanged into the Siemens table,
  whose values are the axis *error* in mm (deg for a rotary axis): a positive value moves the axis
  the negative way (SINUMERIK 808D Function Manual, "Leadscrew error compensation"; see
  :mod:`~axiscal.compensation.controllers.siemens_840d`). So a ``.ren`` value is read as the
  deviation in mm (deg), correction = −value, the same as a Siemens file's value. No public
  source states this directly.
* **One table.** ``Combined`` is one value per point: a bidirectional table is written as its
  mean, and its mean reversal B̄ (ISO 230-2:2014 eq. 7, as a controller's backlash value) on a
  line ``Mean reversal : … mm`` before the table, which the converter ignores (it is not a
  Renishaw field) and :func:`parse` reads back as ``up = mean − B̄/2``, ``down = mean + B̄/2``.
  A rotary table needs ``axis_kind="rotary"`` to be read (the file does not say).
* **Layout written.** A title line, the axis, the three lines, a blank line, the header and the
  rows ``No.  position  value`` (numbered from 0, as the converter counts), CRLF line ends as a
  Windows tool writes them. Anything else in a file read (a further line of text after the table,
  a row that is not three numbers, counts or positions that contradict spacing, start and end) is
  refused, naming the line.
"""

from __future__ import annotations

import re
from dataclasses import replace

import numpy as np

from axiscal.compensation.controllers._common import (
    ControllerFile, check_points, check_travel, correction_factor, decimals, parse_number,
    require_equidistant, safe_axis_name, COUNT, SOURCE_COMMENT, check_fields)
from axiscal.compensation.tables import CompensationTable
from axiscal.datasets import AxisKind
from axiscal.errors import DataFormatError

__all__ = ["NAME", "write", "parse", "looks_like_ren", "MAX_POINTS"]

NAME = "renishaw-ren"
#: No limit is stated by the source; this bounds a file to a size any real table stays under.
MAX_POINTS = 100000
HEADER = "No.     Axis position        Combined"
_HEADER = re.compile(r"^No\.\s+Axis position\s+Combined\s*$", re.IGNORECASE)
_PARAM = re.compile(r"^\s*Compensation (spacing|start|end)\b[^-+\d.]*"
                    r"([-+]?\d*\.?\d+(?:[eE][-+]?\d+)?)", re.IGNORECASE)
_AXIS = re.compile(r"^\s*Axis\s*:\s*(\S*)\s*$", re.IGNORECASE)
_REVERSAL = re.compile(r"^\s*Mean reversal\s*:\s*(\S+)", re.IGNORECASE)


def looks_like_ren(text: str) -> bool:
    """True if the text has the ``Compensation spacing`` line and the table header of a .ren."""
    return bool(re.search(r"^\s*Compensation spacing", text, re.IGNORECASE | re.MULTILINE)) and \
        any(_HEADER.match(line.strip()) for line in text.splitlines())


#: The grammar of the options :func:`write` writes (:func:`~axiscal.compensation.controllers.
#: _common.check_fields`).
FIELDS = {"max_points": COUNT}


def write(table: CompensationTable, travel=None, *, max_points: int = MAX_POINTS) -> ControllerFile:
    """Write ``table`` as a ``.ren`` export: value = deviation (−correction) in mm (deg).

    Parameters
    ----------
    table : CompensationTable
        Equidistant points, positions in mm (linear) or deg (rotary).
    travel : (float, float), optional, ``table.position_unit``
        Axis travel; the table must lie inside it.
    max_points : int
        Largest number of points written.
    """
    check_fields(NAME, FIELDS, max_points=max_points)
    names = safe_axis_name(table.axis, NAME)    # the Axis line ends at a space or line break
    table = replace(table, axis=names.name)
    require_equidistant(table, NAME)
    check_points(table.n_points, max_points, NAME)
    check_travel(table, travel, NAME)
    k = correction_factor(table, table.position_unit)     # correction unit -> mm or deg
    nd = decimals(table.position_unit)
    values = np.round(-table.mean * k, nd) + 0.0
    pu = table.position_unit
    lines = ["Renishaw compensation table (written by axiscal)", f"Axis : {table.axis or '-'}",
             f"Compensation spacing : {table.spacing:.{nd}f} {pu}",
             f"Compensation start : {table.start:.{nd}f} {pu}",
             f"Compensation end : {table.end:.{nd}f} {pu}"]
    b = np.round(table.backlash * k, nd) + 0.0 if table.bidirectional else None
    if b is not None:
        lines.append(f"Mean reversal : {b:.{nd}f} {pu} (axiscal: B of ISO 230-2, down - up)")
    lines += ["", HEADER]
    lines += [f"{i:<8d}{p:<21.{nd}f}{v:.{nd}f}" for i, (p, v) in
              enumerate(zip(table.positions, values))]
    text = "\r\n".join(lines) + "\r\n"
    as_file = np.round(-values / k, 6) + 0.0
    written = _with_reversal(replace(table, up=as_file, down=as_file, bidirectional=False),
                             None if b is None else b / k)
    notes = [f"values are the axis error (−correction) in {pu}, as a Siemens $AA_ENC_COMP table "
             "holds them (the public .REN converter copies them there unchanged)"]
    if table.bidirectional:
        notes.append(f"the table holds the mean of both directions; the mean reversal "
                     f"{table.backlash:+.4g} {table.correction_unit} is on a 'Mean reversal' line "
                     "that Renishaw's software and the converter do not read")
    if names.changed:   # a .ren has no comment line: the source name goes into the notes
        notes.append(f"axis {names.name or '-'}; {SOURCE_COMMENT} {names.source!r}")
    name = f"{(table.axis or 'axis').upper()}.REN"
    enable = ["load it in Renishaw's software, or convert it to a controller's table: axiscal "
              "compensate --read FILE.REN --to NAME --out FILE"]
    return ControllerFile(NAME, text, name, written, tuple(enable), notes=tuple(notes))


def parse(text: str, source: str = "<text>", axis_kind: "AxisKind | str" = "linear",
          axis: str = "", correction_unit: str | None = None) -> CompensationTable:
    """Read a ``.ren`` export back into a table (corrections = −values, in µm or arcsec).

    ``axis_kind``: the file does not say; ``rotary`` reads positions in deg and values in deg.
    ``axis``: overrides the file's ``Axis :`` line.
    """
    kind = AxisKind.parse(axis_kind)
    params, named, rows, reversal = _scan(text, source)
    for key in ("spacing", "start", "end"):
        if key not in params:
            raise DataFormatError(f"no 'Compensation {key}' line", source)
    spacing, start, end = params["spacing"], params["start"], params["end"]
    if not spacing > 0 or end <= start:
        raise DataFormatError(f"spacing {spacing:g} from {start:g} to {end:g}: a table needs a "
                              "positive spacing and end beyond start", source)
    n = int(round((end - start) / spacing)) + 1
    if abs(start + (n - 1) * spacing - end) > 1e-6 * spacing or len(rows) != n:
        raise DataFormatError(f"spacing {spacing:g} from {start:g} to {end:g} makes "
                              f"{(end - start) / spacing + 1:g} points but the table has "
                              f"{len(rows)} rows", source)
    for i, (line, pos, _v) in enumerate(rows):
        if abs(pos - (start + i * spacing)) > 1e-6 * spacing:
            raise DataFormatError(f"row {i} at {pos:g}, not at start + {i} × spacing = "
                                  f"{start + i * spacing:g}", source, line)
    pu = "mm" if kind is AxisKind.LINEAR else "deg"
    cu = correction_unit or ("um" if kind is AxisKind.LINEAR else "arcsec")
    values = np.array([v for _n, _p, v in rows])
    modulo = kind is AxisKind.ROTARY and abs(end - start - 360.0) < 1e-6
    t = CompensationTable(axis or named, kind, pu, cu, start, spacing, values, values,
                          modulo=modulo)
    k = correction_factor(t, pu)
    c = np.round(-values / k, 6) + 0.0
    return _with_reversal(replace(t, up=c, down=c), None if reversal is None else reversal / k)


def _with_reversal(table: CompensationTable, b: float | None) -> CompensationTable:
    """Mean table and mean reversal B̄ (correction unit) -> up/down tables."""
    if b is None:
        return table
    return replace(table, up=np.round(table.mean - b / 2, 6) + 0.0,
                   down=np.round(table.mean + b / 2, 6) + 0.0, bidirectional=True)


def _scan(text: str, source: str):
    """The three parameters, the axis name and the table rows (line, position, value)."""
    params: dict[str, float] = {}
    named = ""
    reversal = None
    rows: list[tuple[int, float, float]] = []
    in_table = False
    for n, raw in enumerate(text.lstrip("\ufeff").splitlines(), 1):
        line = raw.strip()
        if not line:
            continue
        if in_table:
            cells = line.split()
            if len(cells) != 3:
                raise DataFormatError(f"{line[:50]!r}: a table row is No., position and value",
                                      source, n)
            parse_number(cells[0], source, n)
            rows.append((n, parse_number(cells[1], source, n), parse_number(cells[2], source, n)))
            continue
        m = _PARAM.match(line)
        if m:
            key = m.group(1).lower()
            if key in params:
                raise DataFormatError(f"'Compensation {key}' is given twice", source, n)
            params[key] = parse_number(m.group(2), source, n)
        elif _REVERSAL.match(line):
            reversal = parse_number(_REVERSAL.match(line).group(1), source, n)
        elif _AXIS.match(line):
            named = _AXIS.match(line).group(1).strip("-")
        elif _HEADER.match(line):
            in_table = True
    if not in_table:
        raise DataFormatError(f"no table header {HEADER!r}", source)
    if len(rows) < 2:
        raise DataFormatError(f"{len(rows)} table row(s); a table needs at least 2", source)
    return params, named, rows, reversal
