"""Reading numbers out of text files, with errors that name the file, the line and the field.

One function for every reader (positioning CSV, ecmc, tidy files, controller tables), so a bad
value gives the same kind of one-line message wherever it is found.
"""

from __future__ import annotations

import math
import re

from axiscal.errors import DataFormatError

__all__ = ["finite_number", "strict_float", "strict_int", "NUMBER", "csv_cells", "check_run_number", "agreed_unit", "nesting_depth",
           "loads_json", "MAX_NESTING", "comment_tokens"]


#: Largest magnitude a measured value may have, in any unit (a deviation of 1e308 is a typing
#: slip; beyond this, statistics overflow to infinity and print as nonsense).
MAX_MAGNITUDE = 1e100


#: The one grammar of a number in a file axiscal reads: ASCII digits, at most one sign, at most
#: one decimal point, an optional exponent. Python's ``float()`` also takes other scripts' digits
#: (``١٢``, ``１２``), underscores (``1_0``), ``infinity`` and surrounding Unicode spaces; a
#: calibration file holding them was typed or converted wrongly (issue 39: A changed from 14.09
#: to 17.10 with exit 0).
NUMBER = re.compile(r"[+-]?(?:[0-9]+(?:\.[0-9]*)?|\.[0-9]+)(?:[eE][+-]?[0-9]+)?")
_NOT_FINITE = re.compile(r"[+-]?(?:nan|inf|infinity)", re.IGNORECASE)


def strict_float(text: str) -> float:
    """``float(text)`` by the one grammar :data:`NUMBER` (surrounding ASCII blanks allowed);
    ``nan`` and ``inf`` pass as such, so the caller says they are not finite. ValueError else.

    Examples
    --------
    >>> strict_float(" -1.5e3 "), strict_float(".5")
    (-1500.0, 0.5)
    >>> for bad in ("1_0", "١٢", "１２", "1.2.3", "--1", "0x10", "", "1e"):
    ...     try:
    ...         strict_float(bad)
    ...     except ValueError:
    ...         pass
    ...     else:
    ...         print("accepted", bad)
    """
    t = text.strip(" \t\r\n")
    if NUMBER.fullmatch(t) or _NOT_FINITE.fullmatch(t):
        return float(t)
    raise ValueError(f"not a number: {text!r}")


def strict_int(text: str) -> int:
    """``int(text)`` for ASCII digits with at most one sign (at most 18 digits); ValueError else.

    Examples
    --------
    >>> strict_int(" 12 "), strict_int("-3")
    (12, -3)
    >>> strict_int("1_0")
    Traceback (most recent call last):
    ...
    ValueError: not a whole number: '1_0'
    """
    t = text.strip(" \t\r\n")
    if not re.fullmatch(r"[+-]?[0-9]{1,18}", t):
        raise ValueError(f"not a whole number: {text!r}")
    return int(t)


def finite_number(text: str, what: str, source: str | None = None, line: int | None = None,
                  limit: float = MAX_MAGNITUDE) -> float:
    """A finite float within ±``limit`` from ``text``, or a :class:`DataFormatError` naming
    ``what`` and the line.

    Examples
    --------
    >>> finite_number(" 2.5 ", "deviation")
    2.5
    >>> finite_number("x", "deviation", "f.csv", 3)
    Traceback (most recent call last):
    ...
    axiscal.errors.DataFormatError: f.csv:3: deviation 'x' is not a number
    """
    stripped = text.strip()
    try:
        v = strict_float(stripped)
    except ValueError:
        raise DataFormatError(f"{what} {stripped!r} is not a number", source, line) from None
    if not math.isfinite(v):
        raise DataFormatError(f"{what} {stripped!r} is not a finite number", source, line)
    if abs(v) > limit:
        raise DataFormatError(f"{what} {stripped} is out of range (beyond ±{limit:g})", source,
                              line)
    return v


def csv_cells(line: str, source: str | None = None, lineno: int | None = None) -> list[str]:
    """The cells of one CSV line; the csv module's own errors (a field over its size limit)
    become a :class:`DataFormatError` naming the line.

    Examples
    --------
    >>> csv_cells('0,"+",1')
    ['0', '+', '1']
    >>> csv_cells("1," + "2" * 200000, "f.csv", 4)
    Traceback (most recent call last):
    ...
    axiscal.errors.DataFormatError: f.csv:4: not a CSV line: field larger than field limit (131072)
    """
    import csv

    try:
        return next(csv.reader([line]), [])
    except csv.Error as exc:
        raise DataFormatError(f"not a CSV line: {exc}", source, lineno) from None


def check_run_number(run: float, n_readings: int, source: str | None = None,
                     line: int | None = None, text: str | None = None, what: str = "run") -> int:
    """A run number as an int: whole, at least 1 and not more than the readings the file holds.

    Runs are numbered 1, 2, 3 ... in each direction; a run numbered beyond the count of readings
    would stand for whole runs of missing readings (and make the table of runs as wide as the
    number), so it is a typing error.

    Examples
    --------
    >>> check_run_number(3.0, 10)
    3
    >>> check_run_number(1e9, 10, "f.csv", 7)
    Traceback (most recent call last):
    ...
    axiscal.errors.DataFormatError: f.csv:7: run 1e+09 is beyond the 10 readings in the file; runs are numbered 1, 2, 3 ... in each direction
    """
    if text is not None:
        shown = repr(text.strip())
    else:
        shown = str(run) if isinstance(run, int) else f"{run:g}"
    if run != int(run) or run < 1:
        raise DataFormatError(f"{what} {shown} is not a whole number >= 1", source, line)
    if run > n_readings:
        raise DataFormatError(f"{what} {shown} is beyond the {n_readings} readings in the file; "
                              "runs are numbered 1, 2, 3 ... in each direction", source, line)
    return int(run)


def agreed_unit(option: str | None, declared: str | None, key: str,
                source: str | None = None) -> str | None:
    """The unit an option gives or the file declares; both given, they must be the same unit.

    A file that says ``deviation_unit=um`` read with ``--deviation-unit mm`` would give numbers a
    thousand times too large that look right: the disagreement is refused, not resolved.

    Examples
    --------
    >>> agreed_unit("µm", "um", "deviation_unit"), agreed_unit(None, "deg", "target_unit")
    ('µm', 'deg')
    >>> agreed_unit("mm", "um", "deviation_unit", "f.csv")
    Traceback (most recent call last):
    ...
    axiscal.errors.DataFormatError: f.csv: the file declares deviation_unit=um but the option gives mm; drop the option or correct the file
    """
    from axiscal import units

    if option and declared and units.canonical(option) != units.canonical(declared):
        raise DataFormatError(f"the file declares {key}={declared} but the option gives {option}; "
                              "drop the option or correct the file", source)
    return option or declared


#: Deepest nesting of brackets a JSON or TOML input may have. axiscal's own files nest 4 deep
#: (a dataset's ``up`` runs); Python's parsers recurse once per level and stop with a
#: RecursionError near 1,000 (JSON) or print thousands of lines of traceback (TOML).
MAX_NESTING = 64


def nesting_depth(text: str, limit: int = MAX_NESTING) -> int:
    """How deep ``[`` and ``{`` nest in ``text`` (strings left out; unclosed brackets counted as
    nesting), counting no further than ``limit + 1``.

    Each pass removes the innermost bracket pairs, so the cost is ``limit`` passes over the text
    at most, and nothing recurses however deep the input nests.

    Examples
    --------
    >>> nesting_depth('{"a": [[1, 2], [3]], "b": "[[[["}')
    3
    >>> nesting_depth("[" * 100000 + "]" * 100000)
    65
    """
    import re

    text = re.sub(r'"""[\s\S]*?"""|\'\'\'[\s\S]*?\'\'\'|"(?:[^"\\\n]|\\.)*"|\'[^\'\n]*\'', "",
                  text)
    text = re.sub(r"[^\[\]{}]+", "", text)
    inner = re.compile(r"\[\]|\{\}")
    depth = 0
    while depth <= limit:
        text, n = inner.subn("", text)
        if not n:   # what is left never closes ("]]][[["): its openers nest on top
            return min(depth + text.count("[") + text.count("{"), limit + 1)
        depth += 1
    return depth


def loads_json(text: str, source: str | None = None):
    """``json.loads(text)`` with its nesting bounded first (:data:`MAX_NESTING`); a syntax error
    or too deep a nesting is a :class:`DataFormatError` naming the source and line.

    Examples
    --------
    >>> loads_json('{"a": [1, 2]}')
    {'a': [1, 2]}
    >>> loads_json("[" * 5000, "f.json")
    Traceback (most recent call last):
    ...
    axiscal.errors.DataFormatError: f.json: brackets nest more than 64 deep; no axiscal file nests so deep
    """
    import json

    if nesting_depth(text) > MAX_NESTING:
        raise DataFormatError(f"brackets nest more than {MAX_NESTING} deep; no axiscal file "
                              "nests so deep", source)
    try:
        return json.loads(text, parse_int=_json_int)
    except _JsonNumberError as exc:
        raise DataFormatError(str(exc), source) from None
    except json.JSONDecodeError as exc:
        raise DataFormatError(f"not valid JSON: {exc.msg}", source, exc.lineno) from None
    except RecursionError:   # pragma: no cover - the depth check comes first
        raise DataFormatError("brackets nest too deep", source) from None


class _JsonNumberError(ValueError):
    pass


def _json_int(text: str) -> int:
    """A JSON integer that a float can hold (``10**400`` written out cannot: OverflowError)."""
    if len(text.lstrip("-")) > 300:
        raise _JsonNumberError(f"a number of {len(text.lstrip('-'))} digits "
                               f"({text[:12]}…) is out of range; no measured value has so many")
    return int(text)


#: Longest ``# key=value ...`` line read for declarations, characters. shlex takes time growing
#: with the square of a token's length (a 1 MB line: minutes); a metadata line is a few hundred.
MAX_COMMENT = 8192


def comment_tokens(text: str, source: str | None = None, line: int | None = None) -> list[str]:
    """The shell-like tokens of a comment line's text (``key=value`` and ``key="a b"``); a line
    without ``=`` declares nothing and is not split; a line of declarations longer than
    :data:`MAX_COMMENT` is a :class:`DataFormatError`.

    Examples
    --------
    >>> comment_tokens(' machine="VMC 800" axis=X')
    ['machine=VMC 800', 'axis=X']
    >>> comment_tokens(" " + "x" * 10**6)
    []
    """
    import shlex

    if "=" not in text:
        return []
    if len(text) > MAX_COMMENT:
        raise DataFormatError(f"a comment line of {len(text)} characters holding '=': "
                              f"declarations (key=value) fit in {MAX_COMMENT}", source, line)
    try:
        return shlex.split(text)
    except ValueError:
        return []
