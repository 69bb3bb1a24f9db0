"""CSV files of a five-axis ballbar test (a rotary axis, or both, moving with the linear axes;
:mod:`axiscal.procedures.five_axis_ballbar`).

No open format exists (a ballbar's own software writes its own), so axiscal defines a tidy one,
in the manner of the probing and R-test files (:mod:`axiscal.io.five_axis`): comment lines
``# key = value`` before the header give the set-up; one row per reading, in path order; angles
in degrees with the LinuxCNC sign, ``A_deg`` on an A/C machine and ``B_deg`` on a B/C one; the
commanded linear positions (machine frame, mm) and the ballbar's deviation (reported length −
nominal length, µm)::

    # length_mm = 100                (required: the bar's nominal length)
    # noise_um = 0.2                 (required: one reading's standard deviation)
    # u_gain = 0.001                 (relative transducer calibration uncertainty; default 0)
    # drift_K = 0.1                  (the bar's temperature change during the run; default 0)
    # u_length_um = 0.5              (calibrator length uncertainty; default 0)
    # direction = radial             (radial, tangential or axial; optional)
    # swept = C                      (C, A, B or both; optional)
    # pivot_mm = 150, 0, 60          (the table ball, table frame; optional)
    # bar = 1, 0, 0                  (the bar's unit direction, table frame; optional)
    # label = C radial
    pose,A_deg,C_deg,X_mm,Y_mm,Z_mm,deviation_um
    1,0.000000,0.000000,250.0000000,0.0000000,60.0000000,0.1200

Poses are numbered 1, 2, ... with no gap. A missing pose, an empty cell, a value that is not a
finite number or a rotary axis named twice is refused with one line naming the line of the file.
"""

from __future__ import annotations

import numpy as np

from axiscal.errors import DataFormatError
from axiscal.io.five_axis import _check_poses, _setting, _split, _table, _vector
from axiscal.procedures.five_axis_ballbar import BallbarRecord
from axiscal.standards.iso10791_6 import DIRECTIONS
from axiscal.units import DEG, MM, UM

__all__ = ["read_ballbar", "parse_ballbar", "format_ballbar", "BALLBAR_COLUMNS"]

BALLBAR_COLUMNS = ("X_mm", "Y_mm", "Z_mm", "deviation_um")
#: The optional settings of the range's uncertainty (default 0 when the file does not state them).
UNCERTAINTY_SETTINGS = ("u_gain", "drift_K", "u_length_um")
_SETTINGS = {"length_mm", "noise_um", "u_gain", "drift_K", "u_length_um", "direction", "swept",
             "pivot_mm", "bar", "label"}


def read_ballbar(path) -> BallbarRecord:
    """Read a five-axis ballbar CSV (module docstring); errors name the file."""
    from axiscal.io._files import read_text

    return parse_ballbar(read_text(path), source=str(path))


def parse_ballbar(text: str, source: str = "<text>") -> BallbarRecord:
    """Parse a five-axis ballbar CSV text (module docstring).

    Raises
    ------
    DataFormatError
        A malformed file (the message names the line).
    """
    settings, (hn, header), rows = _split(text, source, _SETTINGS)
    tilt = _tilt(header, hn, source)
    names = ("pose", f"{tilt}_deg", "C_deg", *BALLBAR_COLUMNS)
    poses, vals = _table(rows, names, source)
    _check_poses(poses, rows, source, one_row=True)
    for key in ("length_mm", "noise_um"):
        if key not in settings:
            raise DataFormatError(f"{source}: missing '# {key} = ...' before the header")
    length = _setting(settings, "length_mm", None, source, 1.0) * MM
    direction = settings.get("direction", (0, ""))[1]
    if direction and direction not in DIRECTIONS:
        raise DataFormatError(f"{source}:{settings['direction'][0]}: direction = "
                              f"{direction[:20]!r}; use one of {', '.join(DIRECTIONS)}")
    swept = settings.get("swept", (0, ""))[1]
    if swept and swept not in ("C", tilt, "both"):
        raise DataFormatError(f"{source}:{settings['swept'][0]}: swept = {swept[:20]!r}; use C, "
                              f"{tilt} or both")
    pivot = np.array(_vector(settings, "pivot_mm", (0.0, 0.0, 0.0), source)) * MM
    bar = np.array(_vector(settings, "bar", (0.0, 0.0, 0.0), source))
    return BallbarRecord(
        settings["label"][1][:80] if "label" in settings else "ballbar", tilt, swept,
        direction, pivot, bar, length, vals[:, 0] * DEG, vals[:, 1] * DEG, vals[:, 2:5] * MM,
        vals[:, 5] * UM, _setting(settings, "noise_um", None, source, 0.0) * UM,
        u_gain=_setting(settings, "u_gain", 0.0, source, 0.0),
        drift=_setting(settings, "drift_K", 0.0, source, 0.0),
        u_length=_setting(settings, "u_length_um", 0.0, source, 0.0) * UM,
        unstated=tuple(k for k in UNCERTAINTY_SETTINGS if k not in settings))


def format_ballbar(record: BallbarRecord) -> str:
    """The CSV text of a record (module docstring), which :func:`parse_ballbar` reads back."""
    lines = [f"# length_mm = {record.length / MM:.6f}", f"# noise_um = {record.noise / UM:g}",
             f"# u_gain = {record.u_gain:g}", f"# drift_K = {record.drift:g}",
             f"# u_length_um = {record.u_length / UM:g}"]
    if record.direction:
        lines.append(f"# direction = {record.direction}")
    if record.swept:
        lines.append(f"# swept = {record.swept}")
    lines += [f"# pivot_mm = {', '.join(f'{v / MM:.6f}' for v in record.pivot)}",
              f"# bar = {', '.join(f'{v:.9f}' for v in record.bar)}",
              f"# label = {record.label}",
              f"pose,{record.tilt}_deg,C_deg," + ",".join(BALLBAR_COLUMNS)]
    for i, (a, c, x, d) in enumerate(zip(record.tilt_angle, record.c_angle, record.commanded,
                                         record.deviation), 1):
        lines.append(f"{i},{a / DEG:.6f},{c / DEG:.6f},"
                     + ",".join(f"{v / MM:.7f}" for v in x) + f",{d / UM:.4f}")
    return "\n".join(lines) + "\n"


def _tilt(cells, n: int, source: str) -> str:
    seen = set()
    for c in cells:
        if c in seen:
            what = f"rotary axis {c[0]} named twice" if c.endswith("_deg") else f"{c} twice"
            raise DataFormatError(f"{source}:{n}: {what} in the header")
        seen.add(c)
    for tilt in "AB":
        if cells == ["pose", f"{tilt}_deg", "C_deg", *BALLBAR_COLUMNS]:
            return tilt
    raise DataFormatError(f"{source}:{n}: header {','.join(cells)[:120]!r}; expected "
                          f"pose,A_deg,C_deg,{','.join(BALLBAR_COLUMNS)} (B_deg on a B/C "
                          "machine)")
