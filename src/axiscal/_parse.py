"""Reading numbers out of text files, with errors that name the file, the line and the field.

One function for every reader (positioning CSV, ecmc, tidy files, controller tables), so a bad
value gives the same kind of one-line message wherever it is found.
"""

from __future__ import annotations

import math

from axiscal.errors import DataFormatError

__all__ = ["finite_number"]


def finite_number(text: str, what: str, source: str | None = None, line: int | None = None) -> float:
    """A finite float from ``text``, or a :class:`DataFormatError` naming ``what`` and the line.

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
        v = float(stripped)
    except ValueError:
        raise DataFormatError(f"{what} {stripped!r} is not a number", source, line) from None
    if not math.isfinite(v):
        raise DataFormatError(f"{what} {stripped!r} is not a finite number", source, line)
    return v
