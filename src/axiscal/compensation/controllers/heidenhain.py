"""HEIDENHAIN TNC: nonlinear axis error compensation, ``.COM`` table and ``.CMA`` assignment.

Sources: HEIDENHAIN Technical Manual MANUALplus 620, "Nonlinear axis error compensation"
(``*.COM``: column AXISPOS holds the compensation points relative to the machine datum, a column
named after the compensated axis holds the values, an optional BACKLASH column the values for the
negative direction of traverse; ``*.CMA``: one column per compensated axis holding the ``.COM``
name, the line marked ``*`` in column ACTIVE is active); HEIDENHAIN TNC 407/415/425 Technical
Manual (each axis gets a ``.COM`` table in the ``.CMA`` file; the function needs MP730 and a valid
``.CMA``; PLC module 9095 refuses a ``.COM`` with more than 256 entries; a rotary axis is
compensated over 0…360°; the old entry form had power-of-two point spacings).

Written here (the usual TNC table layout, ``BEGIN`` line, a header row, ``[END]``)::

    BEGIN X.COM MM
    NR   AXISPOS    X         BACKLASH
    0    +0.0000    +0.00120  +0.00000
    ...
    [END]

Values in mm (deg for a rotary axis), or inch for an inch machine (``BEGIN X.COM INCH``, written
with ``unit="inch"``; read back in mm, and a unit the caller names that contradicts the file's
is refused). Sign: the value is the correction (added to the nominal
position): correction = −deviation. BACKLASH (bidirectional tables only) is written as the
*additional* correction for the negative direction, ``down − up``. Neither the sign nor the
meaning of BACKLASH was confirmed against a Heidenhain source beyond the sentence quoted above.

**Limits checked.** At most ``max_points`` points (256, module 9095); spacing a whole number of
0.0001 mm (or deg); with ``power_of_two=True`` (older TNC 4xx) the spacing must be 2^k µm;
range inside the travel.
"""

from __future__ import annotations

import math
import re
from dataclasses import replace

import numpy as np

from axiscal.compensation.controllers._common import (
    SOURCE_COMMENT, ControllerFile, check_modulo, check_points, check_spacing, check_travel, correction_factor,
    decimals, file_unit, parse_number, require_equidistant, safe_axis_name, LETTER_FIELD, COUNT,
    check_fields)
from axiscal.compensation.tables import CompensationTable, TableOrigin
from axiscal.datasets import AxisKind
from axiscal.errors import ControllerLimitError, DataFormatError

__all__ = ["NAME", "write", "parse", "write_cma", "MAX_POINTS"]

NAME = "heidenhain"
MAX_POINTS = 256
#: The value column and the file names are an axis letter (``is_axis_letter``; MANUALplus 620,
#: "Entering compensation values"): a front end asks for one where the data's axis is not one.
AXIS_LETTER = True

_BEGIN = re.compile(r"^BEGIN\s+(\S+?)(?:\.COM)?\s+(MM|INCH)?\s*$", re.IGNORECASE)


#: The grammar of the options :func:`write` writes into the table and file names.
FIELDS = {"driving_axis": LETTER_FIELD, "max_points": COUNT}


def write(table: CompensationTable, travel=None, *, max_points: int = MAX_POINTS,
          position_resolution: float = 0.0001, power_of_two: bool = False,
          driving_axis: str | None = None, unit: str = "mm", axis: str = "") -> ControllerFile:
    """Write ``table`` as ``<AXIS>.COM`` with its ``.CMA`` assignment (in ``extra_files``).

    Parameters
    ----------
    table : CompensationTable
    travel : (float, float), optional, ``table.position_unit``
    max_points : int
        Largest number of points in one ``.COM`` table.
    position_resolution : float, mm or deg
        The spacing must be a whole multiple of this.
    power_of_two : bool
        Require a spacing of 2^k µm (TNC 4xx).
    driving_axis : str, optional
        For a cross-axis table ``table.axis = F(driving_axis)``: AXISPOS holds positions of the
        driving axis and the ``.CMA`` enters the table in the driving axis's column (MANUALplus
        620: "[axis in column from *.com] = F(axis in column from *.cma ...)").
    unit : {"mm", "inch"}
        Unit of the file (``BEGIN <name>.COM INCH``) for a linear axis.
    axis : str, optional
        The axis letter of the value column and of the file names, where the table's own axis
        name is not one (an ecmc PV name): the column is named after the axis key of
        CfgAxes/axisList (MANUALplus 620, "Entering compensation values"), and a TNC file name
        keeps to the POSIX portable characters (TNC 640 User's Manual, File names). A .COM
        table has no documented comment line, so the source name goes into the notes.
    """
    check_fields(NAME, FIELDS, driving_axis=driving_axis, max_points=max_points)
    require_equidistant(table, NAME)
    mm = file_unit(unit, table, NAME)
    check_points(table.n_points, max_points, NAME)
    check_spacing(table.spacing, position_resolution, table.position_unit, NAME)
    if power_of_two:
        um = table.spacing * 1000.0
        k = math.log2(um) if um > 0 else -1
        if abs(k - round(k)) > 1e-9:
            raise ControllerLimitError(f"{NAME}: spacing {table.spacing:g} {table.position_unit} "
                                       "is not a power of two micrometres (2^k µm), as this TNC needs")
    check_travel(table, travel, NAME)
    check_modulo(table, NAME)
    names = safe_axis_name(table.axis, NAME, letter=True, given=axis)
    ax = names.name
    word = "INCH" if mm != 1.0 else "MM"
    k = correction_factor(table, table.position_unit if mm == 1.0 else "in")
    nd = decimals(table.position_unit) + (1 if mm != 1.0 else 0)
    up = np.round(table.up * k, nd)
    extra = np.round((table.down - table.up) * k, nd)
    head = ["NR", "AXISPOS", ax] + (["BACKLASH"] if table.bidirectional else [])
    lines = [f"BEGIN {ax}.COM {word}",
             "  ".join(f"{h:<12}" for h in head).rstrip()]
    for i, (p, v, b) in enumerate(zip(table.positions / mm, up, extra)):
        row = [str(i), f"{p:+.{4 if mm == 1.0 else 5}f}", f"{v:+.{nd}f}"]
        if table.bidirectional:
            row.append(f"{b:+.{nd}f}")
        lines.append("  ".join(f"{c:<12}" for c in row).rstrip())
    lines.append("[END]")
    drv = (driving_axis or ax).upper()
    name = f"{ax}.COM" if drv == ax else f"{ax}{drv}.COM"
    lines[0] = f"BEGIN {name} {word}"
    enable = [f"copy {name} and {drv}.CMA to the control (PLC partition / TNC:\\)",
              f"in {drv}.CMA the line with {name} in column {drv} is marked active (*)",
              "activate nonlinear axis error compensation in the machine parameters "
              "(MP730 on TNC 4xx; CfgAxisComp on newer controls: not confirmed)"]
    if mm != 1.0:
        enable.append("the table is in inch (BEGIN … INCH): the control must run in inch")
    notes = [f"axis {ax} (the data named no axis: give -o axis=)" if not names.source else
             f"axis {ax}; {SOURCE_COMMENT} {names.source}" if names.changed else ""]
    return ControllerFile(NAME, "\n".join(lines) + "\n", name,
                          replace(_as_written(table, up, extra, k), axis=ax), tuple(enable),
                          extra_files={f"{drv}.CMA": write_cma({drv: name})},
                          notes=tuple(n for n in notes if n))


def write_cma(assignments: dict[str, str]) -> str:
    """The ``.CMA`` assignment table: one column per axis, one active line (``*``)."""
    axes = list(assignments)
    lines = ["BEGIN CONFIG.CMA", "  ".join(f"{h:<12}" for h in ["NR", *axes, "ACTIVE"]).rstrip(),
             "  ".join(f"{c:<12}" for c in ["0", *assignments.values(), "*"]).rstrip(), "[END]"]
    return "\n".join(lines) + "\n"


def parse(text: str, source: str = "<text>", axis_kind: "AxisKind | str" = "linear",
          correction_unit: str | None = None, unit: str | None = None) -> CompensationTable:
    """Read a ``.COM`` table (equidistant AXISPOS required) into a table in mm (or deg).

    The file's ``BEGIN … MM|INCH`` gives its unit; ``unit``, if given, must agree with it.
    """
    rows = [r.strip() for r in text.splitlines()]
    rows = [(n, r) for n, r in enumerate(rows, 1) if r]
    begin = _BEGIN.match(rows[0][1]) if rows else None
    if not begin:
        raise DataFormatError("a .COM table starts with 'BEGIN <name>.COM MM'", source, 1)
    declared = (begin.group(2) or "MM").lower()
    declared = "inch" if declared == "inch" else "mm"
    if unit is not None and file_unit(unit, None, NAME) != file_unit(declared, None, NAME):
        raise DataFormatError(f"the table says {declared.upper()} (BEGIN line), not {unit}",
                              source, rows[0][0])
    mm = file_unit(declared, None, NAME)
    if rows[-1][1].upper() != "[END]":
        raise DataFormatError("a .COM table ends with [END]", source, rows[-1][0])
    header = rows[1][1].split() if len(rows) > 2 else []
    if len(header) < 3 or header[0].upper() != "NR" or header[1].upper() != "AXISPOS":
        raise DataFormatError("header must be 'NR AXISPOS <axis> [BACKLASH]'", source, rows[1][0] if len(rows) > 1 else 1)
    if len(header) > 4 or (len(header) == 4 and header[3].upper() != "BACKLASH"):
        raise DataFormatError(f"header {' '.join(header)!r} has columns this reader would drop; "
                              "a .COM table holds NR, AXISPOS, one axis and optionally BACKLASH",
                              source, rows[1][0])
    ax = header[2]
    data = []
    for n, r in rows[2:-1]:
        cells = r.split()
        if len(cells) != len(header):
            raise DataFormatError(f"{len(cells)} columns; the header has {len(header)}", source, n)
        data.append([parse_number(c, source, n) for c in cells[1:]])
    if len(data) < 2:
        raise DataFormatError(f"{len(data)} compensation point(s); a table needs at least 2", source)
    arr = np.array(data)
    if mm != 1.0:
        if AxisKind.parse(axis_kind) is not AxisKind.LINEAR:
            raise DataFormatError("an INCH table holds a linear axis", source)
        arr = arr * mm                                     # inch -> mm, positions and values
    pos = arr[:, 0]
    steps = np.diff(pos)
    tol = 1e-6 * max(1.0, abs(steps[0])) if mm == 1.0 else 2e-4 * mm   # inch rounding in mm
    if np.any(np.abs(steps - steps[0]) > tol) or steps[0] <= 0:
        raise DataFormatError("AXISPOS must be equidistant and increasing", source)
    kind = AxisKind.parse(axis_kind)
    pu = "mm" if kind is AxisKind.LINEAR else "deg"
    cu = correction_unit or ("um" if kind is AxisKind.LINEAR else "arcsec")
    modulo = kind is AxisKind.ROTARY and abs(pos[-1] - pos[0] - 360.0) < 1e-6
    bidi = arr.shape[1] == 3
    t = CompensationTable(ax, kind, pu, cu, float(pos[0]), float(steps.mean()), arr[:, 1],
                          arr[:, 1] + (arr[:, 2] if bidi else 0.0), bidirectional=bidi,
                          modulo=modulo)
    k = correction_factor(t, pu)
    t = replace(t, origin=TableOrigin(NAME, ax, None, declared if kind is AxisKind.LINEAR
                                      else "deg", "option"))
    return _as_written(t, arr[:, 1], arr[:, 2] if bidi else 0 * arr[:, 1], k)


def _as_written(table, up_file, extra_file, k) -> CompensationTable:
    up = np.round(np.asarray(up_file) / k, 6) + 0.0
    down = np.round((np.asarray(up_file) + np.asarray(extra_file)) / k, 6) + 0.0
    return replace(table, up=up, down=down if table.bidirectional else up)
