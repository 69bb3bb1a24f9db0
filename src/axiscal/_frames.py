"""The readings of a positioning test in a table in memory, for
:meth:`axiscal.datasets.PositioningDataset.from_dataframe`.

The table is the tidy layout of axiscal's CSV (one reading per row: target, direction, run,
deviation), as a pandas ``DataFrame`` or any mapping of column name to a sequence. pandas is not
imported here: the table is read through ``table[column]``, so a dict of lists works too.

Units, first found wins: the arguments ``target_unit``/``deviation_unit``; ``attrs["units"]``
of the table (``{"target": "mm", "deviation": "um"}``, as the API's data frames carry them); a
unit in the column's name, ``target [mm]``, ``target (mm)`` or ``target_mm``. A unit found
nowhere is refused by name: a deviation typed in µm and read as mm is a factor 1000.
"""

from __future__ import annotations

import re
from typing import Any, Callable, Mapping

import numpy as np

from axiscal.errors import DataFormatError, InputError

__all__ = ["table_readings", "COLUMNS", "SOURCE"]

#: The columns of a tidy positioning table (the ISO 230-2:2014 vocabulary of the CSV).
COLUMNS = ("target", "direction", "run", "deviation")
#: The source errors name.
SOURCE = "<DataFrame>"
_UNIT_IN_NAME = re.compile(r"^\s*(target|direction|run|deviation)\s*(?:\[(.+)\]|\((.+)\)|_(\w+))?"
                           r"\s*$", re.IGNORECASE)


def table_readings(table: Any, parse_direction: Callable[[Any], Any], *,
                   target_unit: str | None = None, deviation_unit: str | None = None,
                   axis_kind: str | None = None, columns: Mapping[str, str] | None = None,
                   source: str = SOURCE) -> tuple[str, list, str, str]:
    """The readings of a tidy table, for
    :meth:`~axiscal.datasets.PositioningDataset.from_dataframe` (which builds the dataset).

    Parameters
    ----------
    table : pandas.DataFrame or mapping of str to sequence
        One reading per row: target, direction (``+``/``-``, ``up``/``down`` ...), run (from
        1), deviation (actual − target; NaN: a missing reading).
    parse_direction : callable
        ``Direction.parse``: a direction's word to the direction, InputError if none.
    target_unit, deviation_unit : str, optional
        ``mm``/``um`` (linear), ``deg``/``arcsec`` (rotary) ...; else from ``table.attrs["units"]``
        or the column names (``target [mm]``).
    axis_kind : {"linear", "rotary"}, optional
        Default: told by the target unit (an angle: rotary).
    columns : mapping, optional
        Your column of each of :data:`COLUMNS` (``{"target": "pos", "deviation": "err_um"}``).
    source : str
        Named in errors.

    Returns
    -------
    (axis_kind, records, target_unit, deviation_unit)
        ``records``: ``(target, direction, run, deviation)`` tuples, as
        :meth:`~axiscal.datasets.PositioningDataset.from_records` takes them.

    Raises
    ------
    DataFormatError
        A column missing, a cell that is not a number or a direction (its row named).
    InputError
        A unit given nowhere, or not a unit of length or angle.

    Examples
    --------
    >>> t = {"target [mm]": [0, 100], "direction": ["+", "+"], "run": [1, 1],
    ...      "deviation [um]": [0.5, 1.5]}
    >>> kind, records, tu, du = table_readings(t, str)
    >>> kind, records, tu, du
    ('linear', [(0.0, '+', 1, 0.5), (100.0, '+', 1, 1.5)], 'mm', 'um')
    """
    from axiscal import units

    names = _columns(table, columns or {}, source)
    found = _units(table, names)
    tu = target_unit or found.get("target")
    du = deviation_unit or found.get("deviation")
    for what, unit in (("target", tu), ("deviation", du)):
        if not unit:
            raise InputError(f"{source}: no {what} unit: give {what}_unit=, "
                             f"attrs['units'] = {{'{what}': ...}} or a column named "
                             f"'{what} [unit]'")
    kind = axis_kind or ("rotary" if units.dimension(tu) == "angle" else "linear")
    cells = {c: _values(table, names[c]) for c in COLUMNS}
    n = {len(v) for v in cells.values()}
    if len(n) != 1:
        raise DataFormatError(f"columns of different lengths {sorted(n)}", source)
    records = []
    for row in range(n.pop()):
        try:
            target = _number(cells["target"][row], "target")
            direction = parse_direction(cells["direction"][row])
            run = _number(cells["run"][row], "run")
            if run != int(run):
                raise InputError(f"run {run:g} is not a whole number")
            deviation = _number(cells["deviation"][row], "deviation", missing_ok=True)
        except InputError as e:
            raise DataFormatError(f"row {row}: {e}", source) from None
        records.append((target, direction, int(run), deviation))
    return kind, records, tu, du


def _columns(table, given: Mapping[str, str], source: str) -> dict[str, str]:
    """The table's column of each of :data:`COLUMNS`: given, else the one named so (a unit in
    the name allowed, any case)."""
    try:
        present = [str(c) for c in table.keys()]
    except AttributeError:
        raise InputError(f"{source}: a table is a pandas DataFrame or a mapping of column "
                         f"name to values, not {type(table).__name__}") from None
    out = {}
    for col in COLUMNS:
        if col in given:
            if given[col] not in present:
                raise DataFormatError(f"no column {given[col]!r} (given for {col}); the columns "
                                      f"are {', '.join(present)}", source)
            out[col] = given[col]
            continue
        match = [c for c in present if (m := _UNIT_IN_NAME.match(c)) and m[1].lower() == col]
        if len(match) != 1:
            what = "no" if not match else f"{len(match)} columns for the"
            raise DataFormatError(f"{what} {col!r} column; the columns are "
                                  f"{', '.join(present) or 'none'} (name them "
                                  f"{', '.join(COLUMNS)} or give columns=)", source)
        out[col] = match[0]
    return out


def _units(table, names: dict[str, str]) -> dict[str, str]:
    """Units of target and deviation from ``attrs["units"]``, else from the column names."""
    attrs = getattr(table, "attrs", None) or {}
    declared = attrs.get("units", {}) if isinstance(attrs, Mapping) else {}
    out = {}
    for col in ("target", "deviation"):
        unit = declared.get(col) or declared.get(names[col])
        if not unit:
            m = _UNIT_IN_NAME.match(names[col])
            unit = m and (m[2] or m[3] or m[4])
        if unit:
            out[col] = str(unit).strip()
    return out


def _values(table, column: str) -> list:
    v = table[column]
    return list(v.tolist() if hasattr(v, "tolist") else v)


def _number(value, what: str, missing_ok: bool = False) -> float:
    if isinstance(value, bool) or value is None:
        if value is None and missing_ok:
            return float("nan")
        raise InputError(f"{what} {value!r} is not a number")
    try:
        x = float(value)
    except (TypeError, ValueError):
        raise InputError(f"{what} {value!r} is not a number") from None
    if not np.isfinite(x) and not (missing_ok and np.isnan(x)):
        raise InputError(f"{what} {value!r} is not a finite number")
    return x
