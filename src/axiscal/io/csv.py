"""Tidy CSV for positioning tests.

Format
------
One reading per line with the header ``target,direction,run,deviation``; ``actual`` may stand
instead of ``deviation``, in which case deviation = actual − target (ISO 230-2 §3.1; seed 001
eq. 1) and ``actual`` is in the target unit. ``direction`` is ``+``/``-`` (also ``up``/``down``,
``fwd``/``bwd``). Comment lines start with ``#``; a leading comment may declare the units and the
metadata as ``key=value`` pairs::

    # target_unit=mm deviation_unit=um axis=X machine=VMC-800
    target,direction,run,deviation
    0,+,1,0.8
    0,-,1,-1.2

Units given as options stand in for units the file does not declare; an option that disagrees
with the file's declaration is refused, and missing units are an error (a rotary file read as
millimetres, or µm read as mm, would give numbers that look right and are not).
"""

from __future__ import annotations

import io
import math
import shlex

from axiscal import units
from axiscal._parse import agreed_unit, check_run_number, csv_cells, finite_number
from axiscal.datasets import AxisKind, Metadata, PositioningDataset
from axiscal.errors import AxiscalError, DataFormatError, InputError

__all__ = ["parse_positioning_csv", "read_positioning_csv", "format_positioning_csv"]

_META_KEYS = {"machine", "axis", "operator", "date", "instrument", "notes"}


def read_positioning_csv(path, **kwargs) -> PositioningDataset:
    """Read a tidy positioning CSV file; see :func:`parse_positioning_csv`."""
    from axiscal.io._files import read_text

    return parse_positioning_csv(read_text(path), source=str(path), **kwargs)


def parse_positioning_csv(
    text: str,
    target_unit: str | None = None,
    deviation_unit: str | None = None,
    axis_kind: str | None = None,
    source: str = "<text>",
) -> PositioningDataset:
    """Parse a tidy positioning CSV text into a :class:`PositioningDataset`.

    Raises
    ------
    DataFormatError
        Wrong header, a non-numeric value (with its line number), a bad direction, no data.
    UnitError
        An unknown unit, or units of the wrong dimension.

    Examples
    --------
    >>> ds = parse_positioning_csv('''# target_unit=deg deviation_unit=arcsec
    ... target,direction,run,deviation
    ... 0,+,1,1.0
    ... 0,+,2,1.5
    ... 90,+,1,-0.5
    ... 90,+,2,0.0
    ... ''')
    >>> ds.axis_kind.value, ds.n_targets, ds.bidirectional
    ('rotary', 2, False)
    """
    header_meta: dict[str, str] = {}
    data_lines: list[tuple[int, str]] = []
    for lineno, line in enumerate(text.splitlines(), start=1):
        s = line.strip()
        if not s:
            continue
        if s.startswith("#"):
            for key, value in _parse_comment(s[1:], source, lineno).items():
                if header_meta.get(key, value) != value:   # two files pasted together?
                    raise DataFormatError(f"{key}={value} contradicts {key}={header_meta[key]} "
                                          "declared above", source, lineno)
                if not data_lines:
                    header_meta[key] = value
            continue
        data_lines.append((lineno, line))
    if not data_lines:
        raise DataFormatError("no header and no readings (empty file?)", source)

    tu = agreed_unit(target_unit, header_meta.pop("target_unit", None), "target_unit", source)
    du = agreed_unit(deviation_unit, header_meta.pop("deviation_unit", None), "deviation_unit",
                     source)
    declared_kind = header_meta.pop("axis_kind", None)
    if (axis_kind and declared_kind
            and AxisKind.parse(axis_kind) is not AxisKind.parse(declared_kind)):
        raise DataFormatError(f"the file declares axis_kind={declared_kind} but the option gives "
                              f"{axis_kind}", source)
    kind_text = axis_kind or declared_kind

    header_lineno, header_line = data_lines[0]
    columns = [c.strip().lower() for c in csv_cells(header_line, source, header_lineno)]
    value_col = "deviation" if "deviation" in columns else "actual" if "actual" in columns else None
    needed = ["target", "direction", "run"]
    if value_col is None or any(c not in columns for c in needed):
        raise DataFormatError(
            f"header {header_line.strip()!r} must name the columns target,direction,run,deviation "
            "(or actual instead of deviation)",
            source,
            header_lineno,
        )
    if tu is None:
        raise DataFormatError(
            "no target unit: give --target-unit (mm or deg) or a leading comment "
            "'# target_unit=mm deviation_unit=um'",
            source,
        )
    tu = units.canonical(tu)
    if value_col == "deviation" and du is None:
        raise DataFormatError(
            "no deviation unit: give --deviation-unit (um, mm or arcsec) or a leading comment "
            "'# target_unit=mm deviation_unit=um'",
            source,
        )
    du = units.canonical(du) if du is not None else ("um" if units.dimension(tu) == "length" else "arcsec")
    kind = AxisKind.parse(kind_text) if kind_text else (
        AxisKind.LINEAR if units.dimension(tu) == "length" else AxisKind.ROTARY
    )
    to_dev = units.convert(1.0, tu, du) if value_col == "actual" else None
    records = _records(data_lines[1:], columns, value_col, to_dev, source)
    if not records:
        raise DataFormatError("the header is there but no readings follow", source)
    meta = Metadata(**{k: v for k, v in header_meta.items() if k in _META_KEYS})
    try:
        return PositioningDataset.from_records(kind, records, tu, du, meta, source=source)
    except DataFormatError:
        raise
    except AxiscalError as exc:
        raise DataFormatError(str(exc), source) from None


def _records(lines, columns: list[str], value_col: str, to_dev: float | None, source: str):
    """``(target, direction, run, deviation)`` of every reading line; missing readings left out."""
    idx = {c: columns.index(c) for c in ("target", "direction", "run", value_col)}
    records = []
    for lineno, line in lines:
        row = csv_cells(line, source, lineno)
        if len(row) < len(columns):
            raise DataFormatError(f"{len(row)} fields where the header has {len(columns)}",
                                  source, lineno)
        target = finite_number(row[idx["target"]], "target", source, lineno)
        try:
            direction = _direction(row[idx["direction"]])
        except InputError as exc:
            raise DataFormatError(str(exc), source, lineno) from None
        run = check_run_number(finite_number(row[idx["run"]], "run", source, lineno,
                                                 limit=math.inf),
                               len(lines), source, lineno, row[idx["run"]])
        raw = row[idx[value_col]].strip()
        if raw == "" or raw.lower() in {"nan", "na", "missing"}:
            continue  # a missing reading: counted by the dataset as NaN
        value = finite_number(raw, value_col, source, lineno)
        records.append((target, direction, run,
                        (value - target) * to_dev if to_dev is not None else value))
    return records


def format_positioning_csv(ds: PositioningDataset) -> str:
    """Write a dataset as tidy CSV with a units comment (missing readings are left out)."""
    buf = io.StringIO()
    meta = {k: getattr(ds.metadata, k) for k in sorted(_META_KEYS) if getattr(ds.metadata, k)}
    head = f"target_unit={ds.target_unit} deviation_unit={ds.deviation_unit} axis_kind={ds.axis_kind.value}"
    for k, v in meta.items():
        head += f" {k}={shlex.quote(v)}"
    buf.write(f"# {head}\n")
    buf.write("target,direction,run,deviation\n")
    for t, d, run, dev in ds.records():
        buf.write(f"{t:.12g},{d},{run},{dev:.12g}\n")
    return buf.getvalue()


def _parse_comment(text: str, source: str, lineno: int) -> dict[str, str]:
    out = {}
    try:
        tokens = shlex.split(text)
    except ValueError:
        return out
    for tok in tokens:
        if "=" in tok:
            k, v = tok.split("=", 1)
            k = k.strip().lower()
            if k in _META_KEYS or k in {"target_unit", "deviation_unit", "axis_kind"}:
                out[k] = v.strip()
    return out




def _direction(text: str) -> str:
    from axiscal.datasets import Direction

    return Direction.parse(text).value
