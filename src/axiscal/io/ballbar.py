"""Tidy CSV of a ballbar (circular) test, and of a multi-point diagonal test.

Ballbar format
--------------
One reading per line, header ``angle,direction,deviation``; the leading comment gives the
nominal radius and may give the units (defaults: degrees and µm), the plane and the contouring
feed (``feed_mm_per_min=``, needed for servo mismatch in ms)::

    # radius_mm=150 deviation_unit=um plane=XY
    angle,direction,deviation
    0,ccw,0.12
    1,ccw,0.10
    0,cw,-0.05

``angle`` is the nominal angular position, counter-clockwise from the first axis of the plane
(+X for XY); ``direction`` is ``ccw`` or ``cw`` (the contouring direction); ``deviation`` is the
ballbar reading minus the nominal radius (positive: longer). A full circle or a partial arc of at
least 220° per direction.

Diagonal format
---------------
Header ``diagonal,position,error``; ``diagonal`` is ``D1`` (along −X +Y, from the corner
(+X, −Y)) or ``D2`` (along +X +Y, from (−X, −Y)); ``position`` is the distance from the start of
the diagonal, ``error`` the laser reading minus the programmed displacement. The comment gives the
travels: ``# length_x_mm=800 length_y_mm=600 position_unit=mm error_unit=um``.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from axiscal.errors import DataFormatError
from axiscal.io._tidy import length_factor, number, parse_tidy
from axiscal.standards.iso230_4 import CircularRun

__all__ = ["BallbarData", "DiagonalData", "parse_ballbar", "read_ballbar", "parse_diagonal",
           "read_diagonal", "format_ballbar"]

_KEYS = {"radius_mm", "radius", "radius_unit", "deviation_unit", "plane", "machine", "date",
         "feed_mm_per_min"}
_DKEYS = {"length_x_mm", "length_y_mm", "position_unit", "error_unit", "plane", "machine"}


@dataclass(frozen=True, eq=False)
class BallbarData:
    """A ballbar test: radius (m), runs (rad, m) and the plane's two axes."""

    radius: float
    runs: tuple[CircularRun, ...]
    axes: tuple[str, str] = ("X", "Y")
    source: str = "<text>"
    feed: float | None = None    # contouring feed, m/s (``# feed_mm_per_min=1000``)


@dataclass(frozen=True, eq=False)
class DiagonalData:
    """A multi-point diagonal test in SI: travels and the readings of D1 and D2."""

    length_x: float
    length_y: float
    positions_d1: np.ndarray
    errors_d1: np.ndarray
    positions_d2: np.ndarray
    errors_d2: np.ndarray
    source: str = "<text>"


def read_ballbar(path, **kwargs) -> BallbarData:
    """Read a ballbar CSV file; see :func:`parse_ballbar`."""
    from axiscal.io._files import read_text

    return parse_ballbar(read_text(path), source=str(path), **kwargs)


#: Most samples a ballbar run may hold: a QC20-class ballbar at 1000 Hz records about 113,000 on
#: a 300 mm circle at 1000 mm/min; beyond this the analysis needs gigabytes.
MAX_SAMPLES_PER_RUN = 200_000


def parse_ballbar(text: str, radius_mm: float | None = None, source: str = "<text>"
                  ) -> BallbarData:
    """Parse a ballbar CSV text.

    Raises
    ------
    DataFormatError
        No radius, a bad direction or number (with its line), a bad plane.

    Examples
    --------
    >>> rows = "\\n".join(f"{a},ccw,0.5" for a in range(0, 360, 30))
    >>> d = parse_ballbar("# radius_mm=100\\nangle,direction,deviation\\n" + rows)
    >>> d.radius, len(d.runs), float(d.runs[0].deviations[0])
    (0.1, 1, 5e-07)
    """
    lines = text.count("\n")
    if lines > 2 * MAX_SAMPLES_PER_RUN + 100:   # counted before the rows are built
        raise DataFormatError(f"{lines} lines: a ballbar test holds at most "
                              f"{MAX_SAMPLES_PER_RUN} samples a direction", source)
    meta, rows = parse_tidy(text, ("angle", "direction", "deviation"), _KEYS, source)
    if radius_mm is None:
        if "radius_mm" not in meta:
            raise DataFormatError("no radius: declare '# radius_mm=150' or give it as an option",
                                  source)
        radius_mm = number(meta["radius_mm"], "radius_mm", source, None)
    if not radius_mm > 0:
        raise DataFormatError(f"radius_mm={radius_mm!r}: must be positive", source)
    fd = length_factor(meta.get("deviation_unit", "um"), "deviation_unit", source)
    plane = meta.get("plane", "XY").upper()
    if len(plane) != 2 or plane[0] == plane[1] or any(c not in "XYZ" for c in plane):
        raise DataFormatError(f"plane={plane!r}: must be two of X, Y, Z such as XY", source)
    by: dict[str, list[tuple[float, float]]] = {}
    seen: dict[tuple[str, float], int] = {}
    for n, r in rows:
        d = r["direction"].lower()
        if d not in ("ccw", "cw"):
            raise DataFormatError(f"direction {r['direction']!r} must be ccw or cw", source, n)
        angle = number(r["angle"], "angle", source, n)
        if (d, angle) in seen:
            raise DataFormatError(f"angle {angle:g} deg of the {d} run is given twice (first on "
                                  f"line {seen[d, angle]})", source, n)
        seen[d, angle] = n
        dev = number(r["deviation"], "deviation", source, n) * fd
        if not abs(dev) < radius_mm * 1e-3:
            raise DataFormatError(f"deviation {r['deviation']} {meta.get('deviation_unit', 'um')} "
                                  f"is not smaller than the radius {radius_mm:g} mm; a ballbar "
                                  "reading minus the nominal radius is", source, n)
        by.setdefault(d, []).append((np.radians(angle), dev))
    runs = []
    for d, pairs in by.items():
        a = np.array(pairs)
        try:
            runs.append(CircularRun(a[:, 0], a[:, 1], d))
        except ValueError as exc:
            raise DataFormatError(f"{d} run: {exc}", source) from None
    feed = None
    if "feed_mm_per_min" in meta:
        feed = number(meta["feed_mm_per_min"], "feed_mm_per_min", source, None) / 6e4
        if not feed > 0:
            raise DataFormatError(f"feed_mm_per_min={meta['feed_mm_per_min']}: must be positive",
                                  source)
    return BallbarData(radius_mm * 1e-3, tuple(runs), (plane[0], plane[1]), source, feed)


def format_ballbar(data: BallbarData) -> str:
    """The CSV text of ``data`` (degrees, µm)."""
    feed = "" if data.feed is None else f" feed_mm_per_min={data.feed * 6e4:.9g}"
    lines = [f"# radius_mm={data.radius * 1e3:.9g} deviation_unit=um plane={''.join(data.axes)}"
             + feed, "angle,direction,deviation"]
    for run in data.runs:
        lines += [f"{np.degrees(a):.9g},{run.direction},{d * 1e6:.9g}"
                  for a, d in zip(run.angles, run.deviations)]
    return "\n".join(lines) + "\n"


def read_diagonal(path) -> DiagonalData:
    """Read a multi-point diagonal CSV file; see :func:`parse_diagonal`."""
    from axiscal.io._files import read_text

    return parse_diagonal(read_text(path), source=str(path))


def parse_diagonal(text: str, source: str = "<text>") -> DiagonalData:
    """Parse a multi-point diagonal CSV text (module docstring).

    Examples
    --------
    >>> t = ("# length_x_mm=600 length_y_mm=800\\ndiagonal,position,error\\n"
    ...      "D1,0,0\\nD1,1000,12\\nD2,0,0\\nD2,1000,-12\\n")
    >>> d = parse_diagonal(t)
    >>> d.length_x, d.errors_d1.tolist()
    (0.6, [0.0, 1.2e-05])
    """
    meta, rows = parse_tidy(text, ("diagonal", "position", "error"), _DKEYS, source)
    lengths = []
    for key in ("length_x_mm", "length_y_mm"):
        if key not in meta:
            raise DataFormatError(f"no {key}: declare it in the leading comment", source)
        lengths.append(number(meta[key], key, source, None) * 1e-3)
        if not lengths[-1] > 0:
            raise DataFormatError(f"{key}={meta[key]}: a travel must be positive", source)
    fp = length_factor(meta.get("position_unit", "mm"), "position_unit", source)
    fe = length_factor(meta.get("error_unit", "um"), "error_unit", source)
    data: dict[str, list[tuple[float, float]]] = {"D1": [], "D2": []}
    nominal = float(np.hypot(*lengths))
    for n, r in rows:
        key = r["diagonal"].upper()
        if key not in data:
            raise DataFormatError(f"diagonal {r['diagonal']!r} must be D1 or D2", source, n)
        position = number(r["position"], "position", source, n) * fp
        if not -1e-6 <= position <= nominal + 1e-6:   # 1 µm for rounding in the file
            raise DataFormatError(f"position {r['position']} {meta.get('position_unit', 'mm')} lies "
                                  f"off the diagonal, 0 to {nominal * 1e3:g} mm from its start",
                                  source, n)
        data[key].append((position, number(r["error"], "error", source, n) * fe))
    for key, pairs in data.items():
        if len({p for p, _ in pairs}) < 2:
            raise DataFormatError(f"{key} has {len(pairs)} reading(s); need two positions or more",
                                  source)
    d1, d2 = np.array(data["D1"]), np.array(data["D2"])
    return DiagonalData(lengths[0], lengths[1], d1[:, 0], d1[:, 1], d2[:, 0], d2[:, 1], source)
