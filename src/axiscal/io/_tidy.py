"""Shared parser of the tidy CSV files of axiscal (one reading per line, ``#`` comments).

A comment line may declare metadata as ``key=value`` pairs (shell quoting allowed); the first
non-comment line is the header. Used by :mod:`axiscal.io.straightness`,
:mod:`axiscal.io.ballbar` and the raw readings of :mod:`axiscal.io.measured` (streamed line by
line through :func:`data_lines`).
"""

from __future__ import annotations


from axiscal import units
from axiscal._parse import csv_cells, finite_number
from axiscal.errors import AxiscalError, DataFormatError

__all__ = ["parse_tidy", "data_lines", "no_data", "header_of", "take_comment", "number",
           "length_factor"]


def parse_tidy(text: str, columns: tuple[str, ...], meta_keys: set[str], source: str):
    """Split a tidy CSV into its metadata and its rows.

    Returns
    -------
    meta : dict of str
        The declared ``key=value`` pairs whose key is in ``meta_keys`` (lower-case keys).
    rows : list of (int, dict)
        Line number and the row's cells by column name (only ``columns``).

    Raises
    ------
    DataFormatError
        No header, a missing column, a short row, or no data.
    """
    meta: dict[str, str] = {}
    rows: list[tuple[int, dict[str, str]]] = []
    for lineno, stripped, header in data_lines(enumerate(text.splitlines(), start=1), columns,
                                               meta_keys, source, meta):
        cells = [c.strip() for c in csv_cells(stripped, source, lineno)]
        if len(cells) < len(header):
            raise DataFormatError(f"{len(cells)} cells where the header has {len(header)}",
                                  source, lineno)
        rows.append((lineno, {c: cells[header.index(c)] for c in columns}))
    if not rows:
        raise no_data(columns, source)
    return meta, rows


def data_lines(numbered_lines, columns: tuple[str, ...], meta_keys: set[str], source: str,
               meta: dict):
    """The data lines of a tidy CSV as ``(lineno, stripped line, header)``, read one at a time
    from ``(lineno, line)`` pairs: blank lines skipped, each comment's ``key=value`` declarations
    added to ``meta`` (:func:`take_comment`), the first other line taken as the header
    (:func:`header_of`)."""
    header: list[str] | None = None
    for lineno, line in numbered_lines:
        stripped = line.strip()
        if not stripped:
            continue
        if stripped.startswith("#"):
            take_comment(meta, stripped, meta_keys, source, lineno)
            continue
        if header is None:
            header = header_of(stripped, columns, source, lineno)
            continue
        yield lineno, stripped, header


def no_data(columns: tuple[str, ...], source: str) -> DataFormatError:
    """The error of a file with no header or no data line."""
    return DataFormatError(f"no data: expected a header {','.join(columns)} and readings", source)


def header_of(stripped: str, columns: tuple[str, ...], source: str, lineno: int) -> list[str]:
    """The lower-case column names of a header line; a missing column is refused by name."""
    cells = [c.strip() for c in csv_cells(stripped, source, lineno)]
    header = [c.lower() for c in cells]
    missing = [c for c in columns if c not in header]
    if missing:
        raise DataFormatError(f"header {','.join(cells)!r} lacks column(s) {', '.join(missing)}; "
                              f"expected {','.join(columns)}", source, lineno)
    return header


def take_comment(meta: dict, stripped: str, keys: set[str], source: str, lineno: int) -> None:
    """Add a ``# key=value ...`` line's declarations to ``meta``; a key declared twice with two
    values (two files pasted together?) is refused naming the line."""
    for key, value in _comment(stripped[1:], keys, source, lineno).items():
        if meta.get(key, value) != value:
            raise DataFormatError(f"{key}={value} contradicts {key}={meta[key]} declared above",
                                  source, lineno)
        meta[key] = value


def number(text: str, column: str, source: str, lineno: int) -> float:
    """A finite number, or a DataFormatError naming the column and the line."""
    return finite_number(text, column, source, lineno)


def length_factor(unit: str, key: str, source: str) -> float:
    """Metres per ``unit`` (a length unit), or a DataFormatError naming the key."""
    try:
        return units.factor(unit, "length")
    except AxiscalError as exc:
        raise DataFormatError(f"{key}={unit!r}: {exc}", source) from None


def _comment(text: str, keys: set[str], source=None, lineno=None) -> dict[str, str]:
    from axiscal._parse import comment_tokens

    out = {}
    for tok in comment_tokens(text, source, lineno):
        if "=" in tok:
            k, v = tok.split("=", 1)
            if k.strip().lower() in keys:
                out[k.strip().lower()] = v.strip()
    return out
