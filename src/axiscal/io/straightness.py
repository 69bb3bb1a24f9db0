"""Tidy CSV of a straightness measurement (one trajectory).

Format
------
A leading comment declares the units and what was measured; the header is
``position,deviation``::

    # position_unit=mm deviation_unit=um axis=X direction=Y
    position,deviation
    0,0.00
    100,1.35

``axis`` is the moving axis, ``direction`` the axis along which the deviation is read, positive
in its + direction (the machine's axis directions, whatever the instrument's orientation; convert
an instrument's sign before writing the file). A straightness file is linear by nature, so
when neither the file nor the caller names the units, mm and µm are taken (the result records
the units it used); options given by the caller override the file.

:func:`read_straightness` wraps :func:`parse_straightness`; :func:`format_straightness` writes
the same format.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from axiscal.errors import DataFormatError
from axiscal.io._tidy import length_factor, number, parse_tidy

__all__ = ["StraightnessData", "parse_straightness", "read_straightness", "format_straightness"]

_KEYS = {"position_unit", "deviation_unit", "axis", "direction", "machine", "date", "notes"}


@dataclass(frozen=True, eq=False)
class StraightnessData:
    """One straightness trajectory, in SI.

    Attributes
    ----------
    positions : numpy.ndarray, m
    deviations : numpy.ndarray, m
    axis : str
        Moving axis (``"X"``), or ``""`` if the file does not say.
    direction : str
        Axis of the deviation (``"Y"``), or ``""``.
    position_unit, deviation_unit : str
        Units the file was written in (for display).
    source : str
    """

    positions: np.ndarray
    deviations: np.ndarray
    axis: str = ""
    direction: str = ""
    position_unit: str = "mm"
    deviation_unit: str = "um"
    source: str = "<text>"


def read_straightness(path, **kwargs) -> StraightnessData:
    """Read a straightness CSV file; see :func:`parse_straightness`."""
    from axiscal.io._files import read_text

    return parse_straightness(read_text(path), source=str(path), **kwargs)


def parse_straightness(text: str, position_unit: str | None = None,
                       deviation_unit: str | None = None, source: str = "<text>"
                       ) -> StraightnessData:
    """Parse a straightness CSV text.

    Raises
    ------
    DataFormatError
        Wrong header, a non-number (with its line), an unknown unit, repeated positions only.

    Examples
    --------
    >>> d = parse_straightness("# axis=X direction=Y\\nposition,deviation\\n0,1\\n500,2\\n")
    >>> d.positions.tolist(), d.deviations.tolist(), d.axis
    ([0.0, 0.5], [1e-06, 2e-06], 'X')
    """
    meta, rows = parse_tidy(text, ("position", "deviation"), _KEYS, source)
    pu = position_unit or meta.get("position_unit", "mm")
    du = deviation_unit or meta.get("deviation_unit", "um")
    fp, fd = length_factor(pu, "position_unit", source), length_factor(du, "deviation_unit", source)
    pos = np.array([number(r["position"], "position", source, n) for n, r in rows]) * fp
    dev = np.array([number(r["deviation"], "deviation", source, n) for n, r in rows]) * fd
    if np.ptp(pos) == 0:
        raise DataFormatError(f"all {pos.size} readings are at one position; a straightness "
                              "needs at least two", source)
    return StraightnessData(pos, dev, meta.get("axis", "").upper(),
                            meta.get("direction", "").upper(), pu, du, source)


def format_straightness(data: StraightnessData) -> str:
    """The CSV text of ``data`` (mm and µm).

    Examples
    --------
    >>> d = parse_straightness("position,deviation\\n0,1\\n500,2\\n")
    >>> parse_straightness(format_straightness(d)).deviations.tolist()
    [1e-06, 2e-06]
    """
    head = "# position_unit=mm deviation_unit=um"
    if data.axis:
        head += f" axis={data.axis}"
    if data.direction:
        head += f" direction={data.direction}"
    lines = [head, "position,deviation"]
    lines += [f"{p * 1e3:.9g},{d * 1e6:.9g}" for p, d in zip(data.positions, data.deviations)]
    return "\n".join(lines) + "\n"
