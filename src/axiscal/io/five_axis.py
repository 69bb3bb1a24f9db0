"""CSV files of five-axis kinematics tests: a sphere probed at many rotary poses, and an R-test.

No open format exists for either (KinematicsOpt, CYCLE996 and the R-test's own software write
proprietary protocols), so axiscal defines two tidy ones. Comment lines ``# key = value`` before
the header give the set-up; the header names the columns; angles are in degrees with the
LinuxCNC sign (the table turns right-handed: :mod:`axiscal.physics.rotary_location`); ``A_deg``
on an A/C machine, ``B_deg`` on a B/C one.

Probing (one row per touch: the stylus-ball centre at the trigger, machine frame, mm)::

    # sphere_radius_mm = 12.5        (required)
    # stylus_radius_mm = 1.5         (effective radius, from the probe's calibration; default 0)
    # noise_um = 0.5                 (one touch's standard deviation; default 0.5)
    # u_offset_um = 0.3, 0.3, 0.3    (stylus offset x, y and length z calibration; default 0)
    # radius_tolerance_mm = 0.02     (default 0.02)
    # place_mm = 150, 20, 60         (nominal sphere centre on the table, optional)
    # label = sphere 1
    pose,A_deg,C_deg,x_mm,y_mm,z_mm
    1,0,0,136.0001,20.0000,60.0000

R-test (one row per pose: commanded tool-sphere centre, machine frame, mm, and the sphere's
displacement from the nest, table-fixed frame, µm)::

    # noise_um = 0.5                 (one sensor's standard deviation; default 0.5)
    # u_gain = 0.001                 (relative gain calibration uncertainty; default 0)
    # u_direction_mrad = 1.0         (sensor direction calibration uncertainty; default 0)

The gain and direction uncertainties act through the sensors' measuring directions of axiscal's
tripod nest (:data:`axiscal.instruments.r_test.SENSOR_DIRECTIONS`), as the instrument turned its
three readings into X, Y, Z.
    pose,A_deg,C_deg,X_mm,Y_mm,Z_mm,dx_um,dy_um,dz_um
    1,0,0,-60.0,-40.0,80.0,0.12,-0.30,0.05

Either file may also state the machine's nominal geometry (what its controller holds; mm, as in
the machine's configuration), which the history needs to evaluate the file alone::

    # tilt_position_mm = 0, -60      (A: Y, Z of the A axis; B: X, Z of the B axis)
    # c_position_mm = 0, 0           (X, Y of the C axis at tilt 0)

Poses are numbered 1, 2, ... with no gap; a probing pose's rows are together and share their
angles, and each needs at least 4 touches; every sphere fit is checked against
``sphere_radius_mm + stylus_radius_mm`` when the file is read. A missing pose, an empty cell, a
value that is not a finite number, a rotary axis named twice or a radius that contradicts the
touches is refused with one line naming the line of the file.
"""

from __future__ import annotations

import math

import numpy as np

from axiscal.errors import DataFormatError, InputError
from axiscal.procedures.five_axis import ProbingRecord, RTestRecord
from axiscal.standards.sphere_fit import RADIUS_TOLERANCE
from axiscal.units import DEG, MM, UM

__all__ = ["read_five_axis", "parse_five_axis", "parse_five_axis_geometry", "format_five_axis",
           "write_five_axis", "PROBING_COLUMNS", "RTEST_COLUMNS"]

PROBING_COLUMNS = ("x_mm", "y_mm", "z_mm")
RTEST_COLUMNS = ("X_mm", "Y_mm", "Z_mm", "dx_um", "dy_um", "dz_um")
_SETTINGS = {"sphere_radius_mm", "stylus_radius_mm", "noise_um", "u_offset_um",
             "radius_tolerance_mm", "place_mm", "label", "u_gain", "u_direction_mrad",
             "tilt_position_mm", "c_position_mm"}
#: Most rows a file may hold (a probing of 20 000 poses with 10 touches each).
MAX_ROWS = 200_000


def read_five_axis(path) -> ProbingRecord | RTestRecord:
    """Read a probing or R-test CSV (module docstring); errors name the file."""
    from axiscal.io._files import read_text

    return parse_five_axis(read_text(path), source=str(path))


def parse_five_axis(text: str, source: str = "<text>") -> ProbingRecord | RTestRecord:
    """Parse a probing or R-test CSV text (module docstring).

    Raises
    ------
    DataFormatError
        A malformed file (the message names the line).
    InputError
        A sphere fit that contradicts the radius.
    """
    settings, header, rows = _split(text, source)
    tilt, kind = _columns(header, source)
    if kind == "probing":
        return _probing(settings, rows, tilt, source)
    return _rtest(settings, rows, tilt, source)


def parse_five_axis_geometry(text: str, source: str = "<text>"):
    """The nominal geometry a probing or R-test CSV states (``# tilt_position_mm``, ``#
    c_position_mm``), or None where it states neither.

    Returns
    -------
    Geometry or None
        Table-table, the file's tilting axis, positions in m.

    Raises
    ------
    DataFormatError
        One of the two lines without the other, or not two finite numbers.
    """
    from axiscal.physics.rotary_location import Geometry

    settings, header, _ = _split(text, source)
    tilt, _ = _columns(header, source)
    given = [k for k in ("tilt_position_mm", "c_position_mm") if k in settings]
    if not given:
        return None
    if len(given) == 1:
        other = ({"tilt_position_mm", "c_position_mm"} - set(given)).pop()
        raise DataFormatError(f"{source}:{settings[given[0]][0]}: {given[0]} without {other}; "
                              "the machine's nominal geometry needs both")
    pos = [_pair(settings, k, source) for k in ("tilt_position_mm", "c_position_mm")]
    return Geometry(tilt, tuple(v * MM for v in pos[0]), tuple(v * MM for v in pos[1]))


def format_five_axis(record: ProbingRecord | RTestRecord, geometry=None) -> str:
    """The CSV text of a record (module docstring), which :func:`parse_five_axis` reads back;
    with a table-table ``geometry``, its nominal positions too."""
    t = record.tilt
    lines = []
    if geometry is not None and not geometry.head:
        for key, pos in (("tilt_position_mm", geometry.tilt_position),
                         ("c_position_mm", geometry.c_position)):
            lines.append(f"# {key} = {', '.join(f'{v / MM:.6f}' for v in pos)}")
    if isinstance(record, ProbingRecord):
        lines += [f"# sphere_radius_mm = {record.sphere_radius / MM:.6f}",
                  f"# stylus_radius_mm = {record.stylus_radius / MM:.6f}",
                  f"# noise_um = {record.noise / UM:g}",
                  f"# u_offset_um = {', '.join(f'{v / UM:g}' for v in record.u_offset)}",
                  f"# radius_tolerance_mm = {record.tolerance / MM:g}"]
    else:
        lines += [f"# noise_um = {record.noise / UM:g}", f"# u_gain = {record.u_gain:g}",
                  f"# u_direction_mrad = {record.u_direction * 1e3:g}"]
    if record.place is not None:
        lines.append(f"# place_mm = {', '.join(f'{v / MM:.6f}' for v in record.place)}")
    lines.append(f"# label = {record.label}")
    if isinstance(record, ProbingRecord):
        lines.append(f"pose,{t}_deg,C_deg," + ",".join(PROBING_COLUMNS))
        for i, (a, c, touches) in enumerate(zip(record.tilt_angle, record.c_angle,
                                                record.touches), 1):
            for p in touches:
                lines.append(f"{i},{a / DEG:.6f},{c / DEG:.6f},"
                             + ",".join(f"{v / MM:.7f}" for v in p))
    else:
        lines.append(f"pose,{t}_deg,C_deg," + ",".join(RTEST_COLUMNS))
        for i, (a, c, x, d) in enumerate(zip(record.tilt_angle, record.c_angle,
                                             record.commanded, record.displacement), 1):
            lines.append(f"{i},{a / DEG:.6f},{c / DEG:.6f},"
                         + ",".join(f"{v / MM:.7f}" for v in x) + ","
                         + ",".join(f"{v / UM:.4f}" for v in d))
    return "\n".join(lines) + "\n"


def write_five_axis(record, path):
    """Write a record's CSV atomically (nothing half-written); returns the path."""
    from axiscal.io._files import write_bytes_atomic

    return write_bytes_atomic(path, format_five_axis(record).encode("utf-8"))


# -- the pieces -------------------------------------------------------------------------------

def _split(text: str, source: str, known=None):
    known = _SETTINGS if known is None else known
    settings: dict[str, tuple[int, str]] = {}
    header = None
    rows = []
    for n, raw in enumerate(text.splitlines(), 1):
        line = raw.strip()
        if not line:
            continue
        if line.startswith("#"):
            if header is None and "=" in line:
                key, _, value = line[1:].partition("=")
                key = key.strip()
                if key not in known:
                    raise DataFormatError(f"{source}:{n}: unknown setting {key!r}; known: "
                                          f"{', '.join(sorted(known))}")
                if key in settings:
                    raise DataFormatError(f"{source}:{n}: {key} given twice")
                settings[key] = (n, value.strip())
            continue
        cells = [c.strip() for c in line.split(",")]
        if header is None:
            header = (n, cells)
        else:
            rows.append((n, cells))
            if len(rows) > MAX_ROWS:
                raise DataFormatError(f"{source}: more than {MAX_ROWS} rows")
    if header is None:
        raise DataFormatError(f"{source}: no header line (pose,A_deg,C_deg,...); see "
                              "'axiscal formats' or the README, 'Five-axis files'")
    if not rows:
        raise DataFormatError(f"{source}: no data rows after the header")
    return settings, header, rows


def _columns(header, source: str) -> tuple[str, str]:
    n, cells = header
    seen = set()
    for c in cells:
        if c in seen:
            what = f"rotary axis {c[0]} named twice" if c.endswith("_deg") else f"{c} twice"
            raise DataFormatError(f"{source}:{n}: {what} in the header")
        seen.add(c)
    tilts = [t for t in "AB" if f"{t}_deg" in seen]
    if len(tilts) != 1:
        raise DataFormatError(f"{source}:{n}: the header names "
                              f"{' and '.join(tilts) or 'no'} tilting axis; a table-table "
                              "machine has one: A_deg (A/C) or B_deg (B/C)")
    tilt = tilts[0]
    for kind, data in (("probing", PROBING_COLUMNS), ("r-test", RTEST_COLUMNS)):
        if cells == ["pose", f"{tilt}_deg", "C_deg", *data]:
            return tilt, kind
    raise DataFormatError(f"{source}:{n}: header {','.join(cells)!r}; expected "
                          f"pose,{tilt}_deg,C_deg,{','.join(PROBING_COLUMNS)} (probing) or "
                          f"pose,{tilt}_deg,C_deg,{','.join(RTEST_COLUMNS)} (R-test)")


def _table(rows, names: tuple[str, ...], source: str) -> tuple[np.ndarray, np.ndarray]:
    """Pose numbers and values of every row, each cell checked."""
    poses = np.empty(len(rows), dtype=np.int64)
    vals = np.empty((len(rows), len(names) - 1))
    for i, (n, cells) in enumerate(rows):
        if len(cells) != len(names):
            raise DataFormatError(f"{source}:{n}: {len(cells)} cells; the header has "
                                  f"{len(names)}")
        for j, (name, cell) in enumerate(zip(names, cells)):
            if cell == "":
                raise DataFormatError(f"{source}:{n}: {name} is empty")
            try:
                v = float(cell)
            except ValueError:
                raise DataFormatError(f"{source}:{n}: {name} = {cell[:40]!r} is not a number") \
                    from None
            if not math.isfinite(v) or abs(v) > 1e9:
                raise DataFormatError(f"{source}:{n}: {name} = {cell[:40]} is not a finite "
                                      "number of a machine's size")
            if j == 0:
                if v != int(v) or v < 1:
                    raise DataFormatError(f"{source}:{n}: pose = {cell} must be a whole number "
                                          ">= 1")
                poses[i] = int(v)
            else:
                vals[i, j - 1] = v
    return poses, vals


def _check_poses(poses, rows, source: str, one_row: bool) -> list[int]:
    """Start index of each pose; poses 1..N in order with no gap (and one row each for an
    R-test)."""
    starts = []
    expected = 1
    for i, p in enumerate(poses):
        if i and p == poses[i - 1]:
            if one_row:
                raise DataFormatError(f"{source}:{rows[i][0]}: pose {p} given twice (an R-test "
                                      "has one row per pose)")
            continue
        if p != expected:
            what = (f"pose {expected} is missing" if p > expected
                    else f"pose {p} comes again after pose {expected - 1}")
            raise DataFormatError(f"{source}:{rows[i][0]}: {what} (poses are numbered 1, 2, ... "
                                  "in order)")
        starts.append(i)
        expected += 1
    return starts


def _probing(settings, rows, tilt, source) -> ProbingRecord:
    names = ("pose", f"{tilt}_deg", "C_deg", *PROBING_COLUMNS)
    poses, vals = _table(rows, names, source)
    starts = _check_poses(poses, rows, source, one_row=False)
    ends = starts[1:] + [len(rows)]
    tilt_angle, c_angle, touches = [], [], []
    for k, (s, e) in enumerate(zip(starts, ends), 1):
        block = vals[s:e]
        if np.ptp(block[:, 0]) > 1e-9 or np.ptp(block[:, 1]) > 1e-9:
            raise DataFormatError(f"{source}:{rows[s][0]}: the rows of pose {k} give different "
                                  "angles")
        if e - s < 4:
            raise DataFormatError(f"{source}:{rows[s][0]}: pose {k} has {e - s} touches; a "
                                  "sphere needs at least 4")
        tilt_angle.append(block[0, 0] * DEG)
        c_angle.append(block[0, 1] * DEG)
        touches.append(block[:, 2:] * MM)
    if "sphere_radius_mm" not in settings:
        raise DataFormatError(f"{source}: no '# sphere_radius_mm = ...' line; the sphere fits are "
                              "checked against the calibrated sphere's radius")
    rec = ProbingRecord(
        tilt, np.array(tilt_angle), np.array(c_angle), tuple(touches),
        sphere_radius=_setting(settings, "sphere_radius_mm", None, source, lo=1e-3) * MM,
        stylus_radius=_setting(settings, "stylus_radius_mm", 0.0, source, lo=0.0) * MM,
        noise=_setting(settings, "noise_um", 0.5, source, lo=0.0) * UM,
        u_offset=tuple(v * UM for v in _vector(settings, "u_offset_um", (0, 0, 0), source)),
        tolerance=_setting(settings, "radius_tolerance_mm", RADIUS_TOLERANCE / MM, source,
                           lo=1e-6) * MM,
        place=_place(settings, source), label=_label(settings, "probing"))
    try:
        rec.fits()
    except InputError as exc:
        raise InputError(f"{source}: {exc}") from None
    return rec


def _rtest(settings, rows, tilt, source) -> RTestRecord:
    names = ("pose", f"{tilt}_deg", "C_deg", *RTEST_COLUMNS)
    poses, vals = _table(rows, names, source)
    _check_poses(poses, rows, source, one_row=True)
    for key in ("sphere_radius_mm", "stylus_radius_mm", "u_offset_um", "radius_tolerance_mm"):
        if key in settings:
            raise DataFormatError(f"{source}:{settings[key][0]}: {key} belongs to a probing "
                                  "file, not an R-test")
    return RTestRecord(tilt, vals[:, 0] * DEG, vals[:, 1] * DEG, vals[:, 2:5] * MM,
                       vals[:, 5:8] * UM,
                       noise=_setting(settings, "noise_um", 0.5, source, lo=0.0) * UM,
                       u_gain=_setting(settings, "u_gain", 0.0, source, lo=0.0),
                       place=_place(settings, source), label=_label(settings, "r-test"),
                       u_direction=_setting(settings, "u_direction_mrad", 0.0, source,
                                            lo=0.0) * 1e-3)


def _setting(settings, key, default, source, lo: float) -> float:
    if key not in settings:
        return default
    n, text = settings[key]
    try:
        v = float(text)
    except ValueError:
        raise DataFormatError(f"{source}:{n}: {key} = {text[:40]!r} is not a number") from None
    if not math.isfinite(v) or v < lo or v > 1e6:
        raise DataFormatError(f"{source}:{n}: {key} = {text[:40]} must be a finite number "
                              f">= {lo:g}")
    return v


def _vector(settings, key, default, source) -> tuple[float, float, float]:
    if key not in settings:
        return tuple(float(v) for v in default)
    n, text = settings[key]
    parts = [p.strip() for p in text.split(",")]
    try:
        v = [float(p) for p in parts]
    except ValueError:
        v = []
    if len(v) != 3 or not all(math.isfinite(x) and abs(x) <= 1e6 for x in v):
        raise DataFormatError(f"{source}:{n}: {key} = {text[:60]!r} must be three finite numbers "
                              "separated by commas")
    return tuple(v)


def _pair(settings, key, source) -> tuple[float, float]:
    n, text = settings[key]
    try:
        v = [float(p) for p in text.split(",")]
    except ValueError:
        v = []
    if len(v) != 2 or not all(math.isfinite(x) and abs(x) <= 1e6 for x in v):
        raise DataFormatError(f"{source}:{n}: {key} = {text[:60]!r} must be two finite numbers "
                              "separated by a comma")
    return v[0], v[1]


def _place(settings, source):
    if "place_mm" not in settings:
        return None
    return np.array(_vector(settings, "place_mm", None, source)) * MM


def _label(settings, default: str) -> str:
    return settings["label"][1][:80] if "label" in settings else default
