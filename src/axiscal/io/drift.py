"""Drift-check files: the readings of a still set-up, from which E_VE is measured.

ISO 230-2:2014 Annex A.5 takes the environmental variation error E_VE from a drift check: the
instrument reads a target with the machine at rest, reflector and interferometer fixed, for at
least the duration of the positioning test; E_VE is the range of those readings
(:func:`axiscal.standards.iso230_9_inputs.environmental_variation`).

Format
------
CSV text; ``#`` starts a comment line. Either one column of numbers (no header), or a header
naming a ``reading`` or ``deviation`` column (others, such as ``time_s``, are ignored)::

    # drift check, X axis at 400 mm, 30 min
    time_s,reading
    0,0.00
    60,0.12

The readings are in the positioning test's deviation unit (µm for a linear axis, arcsec for a
rotary one).
"""

from __future__ import annotations

import re

import numpy as np

from axiscal._parse import csv_cells, finite_number
from axiscal.errors import DataFormatError

__all__ = ["parse_drift_check", "read_drift_check"]

_COLUMNS = ("reading", "deviation")


def read_drift_check(path) -> np.ndarray:
    """Read a drift-check file; see :func:`parse_drift_check`."""
    from axiscal.io._files import read_text

    return parse_drift_check(read_text(path), source=str(path))


def parse_drift_check(text: str, source: str = "<text>") -> np.ndarray:
    """The readings of a drift check, in file order.

    Examples
    --------
    >>> parse_drift_check("time_s,reading\\n0,0.1\\n60,0.4\\n120,-0.2\\n").tolist()
    [0.1, 0.4, -0.2]
    >>> parse_drift_check("0.3\\n0.5\\n").tolist()
    [0.3, 0.5]
    """
    rows = [(n, line) for n, line in enumerate(text.splitlines(), 1)
            if line.strip() and not line.lstrip().startswith("#")]
    if not rows:
        raise DataFormatError("no readings: a drift check needs at least 2", source)
    col, start = 0, 0
    head = [c.strip().lower() for c in csv_cells(rows[0][1], source, rows[0][0])]
    found = [c for c in _COLUMNS if c in head]
    if found:
        col, start = head.index(found[0]), 1
    elif not re.fullmatch(r"[-+]?(\d+\.?\d*|\.\d+)([eE][-+]?\d+)?|[-+]?(nan|inf)", head[0]):
        raise DataFormatError(f"no 'reading' or 'deviation' column in the header "
                              f"{rows[0][1].strip()!r}", source, rows[0][0])
    out = []
    for n, line in rows[start:]:
        cells = csv_cells(line, source, n)
        if col >= len(cells):
            raise DataFormatError(f"{len(cells)} cells; the reading is column {col + 1}", source, n)
        out.append(finite_number(cells[col], "reading", source, n))
    if len(out) < 2:
        raise DataFormatError(f"{len(out)} reading: a drift check needs at least 2", source)
    return np.asarray(out, dtype=float)

