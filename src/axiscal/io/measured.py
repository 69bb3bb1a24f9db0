"""Files of a real measurement: raw laser readings, an environment log, a test plan, a record.

Raw laser readings (CSV)
------------------------
One reading per line, as the laser gave it before any compensation, with its time::

    # reading_unit=mm target_unit=mm machine="VMC 800" axis=X dead_path_mm=120 index=1
    time_s,target,direction,run,reading
    12.0,0,+,1,0.000000
    17.5,100,+,1,100.027089

``reading`` is the displacement from the laser's datum (zeroed at the first target unless
``datum`` says otherwise) computed with the vacuum wavelength (``index=1``, the default) or with a
fixed index (``index=1.000271``); ``dead_path_mm`` the distance between the interferometer and the
reflector at the datum.

Environment log (CSV or JSON)
-----------------------------
::

    # expansion_coefficient_ppm=11.5
    time_s,air_temperature_c,pressure_pa,humidity_pct,material_temperature_c,material_temperature_c
    0,20.10,101320,45.0,20.40,20.52
    60,20.14,101318,45.2,20.41,20.55

Any number of ``material_temperature_c`` columns (one per sensor, averaged); JSON holds the same
as ``{"expansion_coefficient_ppm": ..., "samples": [{"time_s": ..., "air_temperature_c": ...,
"material_temperature_c": [...]}, ...]}``.

Test plan (CSV)
---------------
What ``axiscal plan ... --csv`` writes: ``seq,kind,position,direction,run,target_index,dwell_s``.

Continuous record (CSV)
-----------------------
``time_s,reading_mm[,commanded_mm]`` (or ``reading_deg`` for a rotary axis); a Renishaw ``.rtx``
dynamic capture is read by :mod:`axiscal.io.rtx`.
"""

from __future__ import annotations

import numpy as np

from axiscal import units
from axiscal._parse import csv_cells, finite_number
from axiscal.errors import AxiscalError, DataFormatError
from axiscal.procedures.capture import PlanRows, Record
from axiscal.procedures.environment import EnvironmentLog, RawReadings

__all__ = ["RawReadings", "EnvironmentLog", "PlanRows", "Record", "parse_raw_readings",
           "read_raw_readings", "parse_environment_log", "read_environment_log",
           "parse_plan_csv", "read_plan_csv", "parse_record_csv", "read_record"]


def read_raw_readings(path) -> RawReadings:
    """Read a raw readings CSV (module docstring), streaming it: memory grows with the readings
    (five numbers each), not with the text."""
    from axiscal.io.csv import iter_file_lines

    return _raw_readings(iter_file_lines(path), str(path))


def parse_raw_readings(text: str, source: str = "<text>") -> RawReadings:
    """Parse raw laser readings; errors name the line."""
    from axiscal.io.csv import _numbered_lines

    return _raw_readings(_numbered_lines(text), source)


_RAW_COLUMNS = ("time_s", "target", "direction", "run", "reading")
_RAW_KEYS = {"reading_unit", "target_unit", "machine", "axis", "dead_path_mm", "index", "datum",
             "operator", "date", "instrument"}
_SIGN = {"+": 1, "up": 1, "fwd": 1, "forward": 1, "positive": 1,
         "-": -1, "down": -1, "bwd": -1, "backward": -1, "negative": -1}


def _raw_readings(lines, source: str) -> RawReadings:
    """The readings of numbered lines, kept in compact arrays as they are read; a line of plain
    cells is converted directly, anything else through the checked cells (same messages)."""
    from array import array

    from axiscal._parse import MAX_MAGNITUDE
    from axiscal.io._tidy import data_lines, no_data

    meta: dict[str, str] = {}
    cols: dict = {c: array("d") for c in ("time_s", "target", "run", "reading")}
    signs, where = array("b"), array("q")
    idx: list[int] = []
    for lineno, stripped, header in data_lines(lines, _RAW_COLUMNS, _RAW_KEYS, source, meta):
        idx = idx or [header.index(c) for c in _RAW_COLUMNS]
        cells = stripped.split(",")
        row = None
        if len(cells) >= len(header) and '"' not in stripped and stripped.isascii() \
                and "_" not in stripped:
            try:
                row = (float(cells[idx[0]]), float(cells[idx[1]]),
                       _SIGN[cells[idx[2]].strip().lower()], float(cells[idx[3]]),
                       float(cells[idx[4]]))
            except (ValueError, KeyError):
                row = None
            if row is not None and not all(-MAX_MAGNITUDE <= v <= MAX_MAGNITUDE
                                           for v in (row[0], row[1], row[3], row[4])):
                row = None
        if row is None:   # the checked path: the one-line error naming the cell and the line
            row = _checked_row(stripped, len(header), idx, source, lineno)
        cols["time_s"].append(row[0])
        cols["target"].append(row[1])
        signs.append(row[2])
        cols["run"].append(row[3])
        cols["reading"].append(row[4])
        where.append(lineno)
    if not where:
        raise no_data(_RAW_COLUMNS, source)
    ru, tu = meta.get("reading_unit", "mm"), meta.get("target_unit", "mm")
    try:
        fr = units.factor(ru, "length")
        units.factor(tu, "length")
    except AxiscalError as exc:
        raise DataFormatError(str(exc), source) from None
    t = np.frombuffer(cols["time_s"], dtype=float).copy()
    tg = np.frombuffer(cols["target"], dtype=float).copy()
    d = np.where(np.frombuffer(signs, dtype=np.int8) > 0, "+", "-")
    run = np.frombuffer(cols["run"], dtype=float).astype(int)
    x = np.frombuffer(cols["reading"], dtype=float) * fr
    if np.any(np.diff(t) < 0):
        i = int(np.argmax(np.diff(t) < 0))
        raise DataFormatError(f"time_s goes back from {t[i]:g} to {t[i + 1]:g} s",
                              source, int(where[i + 1]))
    _inch_slip(tg * units.factor(tu), x, tu, ru, source)
    dead = _meta_number(meta, "dead_path_mm", 0.0, 0.0, 1e5, source) * 1e-3
    index = _meta_number(meta, "index", 1.0, 0.99, 1.01, source)
    datum = _meta_number(meta, "datum", float(tg[0]), -1e9, 1e9, source)
    return RawReadings(t, tg, d, run, x, tu, dead, index, datum, meta, source)


def _checked_row(stripped: str, n_header: int, idx: list, source: str, lineno: int) -> tuple:
    """One line of raw readings read cell by cell (quoted cells, a bad number or direction):
    (time_s, target, ±1, run, reading), or the one-line error naming the cell and the line."""
    cells = [c.strip() for c in csv_cells(stripped, source, lineno)]
    if len(cells) < n_header:
        raise DataFormatError(f"{len(cells)} cells where the header has {n_header}", source,
                              lineno)
    c = [cells[i] for i in idx]
    return (finite_number(c[0], "time_s", source, lineno),
            finite_number(c[1], "target", source, lineno),
            1 if _direction(c[2], source, lineno) == "+" else -1,
            finite_number(c[3], "run", source, lineno),
            finite_number(c[4], "reading", source, lineno))


def format_raw_readings(raw: RawReadings, header: str = "") -> str:
    """Raw readings as the CSV :func:`parse_raw_readings` reads (readings in mm; ``header`` is
    extra ``key=value`` metadata for the leading comment)."""
    head = f"# reading_unit=mm target_unit={raw.target_unit} dead_path_mm={raw.dead_path * 1e3:g}"
    lines = [head + (f" {header}" if header else ""), "time_s,target,direction,run,reading"]
    lines += [f"{t:.3f},{g:g},{d},{r},{x * 1e3:.9f}" for t, g, d, r, x in
              zip(raw.times, raw.targets, raw.directions, raw.runs, raw.readings)]
    return "\n".join(lines) + "\n"


def format_environment_log(log: EnvironmentLog) -> str:
    """An environment log as the CSV :func:`parse_environment_log` reads (one column per
    material sensor)."""
    mat = np.asarray(log.material_temperature).reshape(len(log.times), -1)
    head = ([f"# expansion_coefficient_ppm={log.expansion_coefficient * 1e6:g}"]
            if log.expansion_coefficient is not None else [])
    cols = "time_s,air_temperature_c,pressure_pa,humidity_pct" + ",material_temperature_c" * mat.shape[1]
    rows = [",".join([f"{t:g}", f"{a:.4f}", f"{p:.1f}", f"{h:.2f}", *(f"{m:.4f}" for m in ms)])
            for t, a, p, h, ms in zip(log.times, log.air_temperature, log.pressure,
                                      log.humidity, mat)]
    return "\n".join(head + [cols] + rows) + "\n"


def read_environment_log(path) -> EnvironmentLog:
    """Read an environment log (CSV, or JSON by extension or content)."""
    from axiscal.io._files import read_text

    return parse_environment_log(read_text(path), str(path))


def parse_environment_log(text: str, source: str = "<text>") -> EnvironmentLog:
    """Parse an environment log (module docstring)."""
    if text.lstrip().startswith("{"):
        return _environment_json(text, source)
    lines = [(n, ln.strip()) for n, ln in enumerate(text.splitlines(), 1) if ln.strip()]
    alpha = None
    header, rows = None, []
    for n, ln in lines:
        if ln.startswith("#"):
            for tok in ln[1:].split():
                if tok.startswith("expansion_coefficient_ppm="):
                    alpha = finite_number(tok.split("=", 1)[1], "expansion_coefficient_ppm",
                                          source, n) * 1e-6
            continue
        cells = [c.strip().lower() for c in csv_cells(ln, source, n)]
        if header is None:
            header = cells
            need = ("time_s", "air_temperature_c", "pressure_pa", "humidity_pct")
            missing = [c for c in need if c not in header]
            if missing:
                raise DataFormatError(f"environment log header lacks {', '.join(missing)}",
                                      source, n)
            continue
        if len(cells) != len(header):
            raise DataFormatError(f"{len(cells)} cells where the header has {len(header)}",
                                  source, n)
        rows.append((n, [finite_number(c, header[i], source, n) for i, c in enumerate(cells)]))
    if header is None or not rows:
        raise DataFormatError("no samples: expected a header time_s,air_temperature_c,"
                              "pressure_pa,humidity_pct[,material_temperature_c...]", source)
    a = np.array([r for _, r in rows])
    col = {c: i for i, c in enumerate(header)}
    mats = [i for i, c in enumerate(header) if c.startswith("material_temperature")]
    return _log(a[:, col["time_s"]], a[:, col["air_temperature_c"]], a[:, col["pressure_pa"]],
                a[:, col["humidity_pct"]], a[:, mats] if mats else np.zeros((len(rows), 0)),
                alpha, source, [n for n, _ in rows])


def read_plan_csv(path) -> PlanRows:
    """Read a plan exported by ``axiscal plan ... --csv``."""
    from axiscal.io._files import read_text

    return parse_plan_csv(read_text(path), str(path))


def parse_plan_csv(text: str, source: str = "<text>") -> PlanRows:
    """Parse a plan CSV (``seq,kind,position,direction,run,target_index,dwell_s``)."""
    from axiscal.io._tidy import parse_tidy

    meta, rows = parse_tidy(text, ("seq", "kind", "position", "direction", "run",
                                   "target_index", "dwell_s"),
                            {"axis", "axis_kind", "target_unit", "runs", "cycle",
                             "bidirectional", "overrun"}, source)
    kind = np.array([r["kind"].strip().lower() for _, r in rows])
    bad = [n for (n, _), k in zip(rows, kind) if k not in ("measure", "overrun")]
    if bad:
        raise DataFormatError("kind must be measure or overrun", source, bad[0])
    pos = np.array([finite_number(r["position"], "position", source, n) for n, r in rows])
    d = np.array([_direction(r["direction"], source, n) for n, r in rows])
    run = np.array([int(finite_number(r["run"], "run", source, n)) for n, r in rows])
    ti = np.array([int(finite_number(r["target_index"], "target_index", source, n))
                   if k == "measure" else -1 for (n, r), k in zip(rows, kind)])
    dw = np.array([finite_number(r["dwell_s"], "dwell_s", source, n) for n, r in rows])
    if not np.any(kind == "measure"):
        raise DataFormatError("the plan has no measure step", source)
    tu = meta.get("target_unit", "mm")
    ak = meta.get("axis_kind", "rotary" if tu in ("deg", "°") else "linear")
    return PlanRows(kind, pos, d, run, ti, dw, tu, meta.get("axis", ""), ak, source)


def read_record(path, unit: str | None = None) -> Record:
    """Read a continuous record: ``.rtx`` (:mod:`axiscal.io.rtx`) or CSV."""
    from pathlib import Path

    if Path(path).suffix.lower() == ".rtx":
        from axiscal.io.rtx import read_rtx

        return read_rtx(path, unit=unit)
    from axiscal.io._files import read_text

    return parse_record_csv(read_text(path), str(path))


def parse_record_csv(text: str, source: str = "<text>") -> Record:
    """Parse ``time_s,reading_mm[,commanded_mm]`` (or ``_deg``) with NumPy (fast for long
    records); errors name the line."""
    import io

    header_line, start = None, 0   # the header and its 0-based line, found without splitting
    for start, line in enumerate(io.StringIO(text, newline=None)):   # the record into lines
        if line.strip() and not line.lstrip().startswith("#"):
            header_line = line.rstrip("\r\n")
            break
    if header_line is None:
        raise DataFormatError("no data: expected a header time_s,reading_mm", source)
    header = [c.strip().lower() for c in header_line.split(",")]
    unit_col = next((c for c in header if c.startswith("reading_")), None)
    if "time_s" not in header or unit_col is None:
        raise DataFormatError(f"header {header_line!r}: expected time_s,reading_mm"
                              "[,commanded_mm] (or reading_deg)", source, start + 1)
    unit = unit_col.split("_", 1)[1]
    try:
        factor = units.factor(unit)
    except AxiscalError as exc:
        raise DataFormatError(f"{unit_col}: {exc}", source, start + 1) from None
    try:
        a = np.loadtxt(io.StringIO(text, newline=None), delimiter=",", ndmin=2, comments="#",
                       skiprows=start + 1)
    except ValueError as exc:
        raise DataFormatError(f"not a number in the record ({exc})", source) from None
    if a.shape[0] < 2 or a.shape[1] != len(header):
        raise DataFormatError(f"{a.shape[0]} rows of {a.shape[1]} columns; expected at least "
                              f"2 rows of {len(header)}", source)
    if not np.isfinite(a).all():
        raise DataFormatError("the record holds a NaN or infinite value", source)
    t = a[:, header.index("time_s")]
    if np.any(np.diff(t) <= 0):
        i = int(np.argmax(np.diff(t) <= 0))
        raise DataFormatError(f"time_s must increase: {t[i]:g} then {t[i + 1]:g}",
                              source, start + 3 + i)
    cmd = next((c for c in header if c.startswith("commanded_")), None)
    kind = "rotary" if units.dimension(unit) == "angle" else "linear"
    return Record(t, a[:, header.index(unit_col)] * factor, kind,
                  None if cmd is None else a[:, header.index(cmd)] * factor,
                  float((t.size - 1) / (t[-1] - t[0])), {}, unit, source)


# -- helpers ---------------------------------------------------------------------------------
def _inch_slip(targets, readings, tu: str, ru: str, source: str) -> None:
    """Refuse laser readings that travel 25.4 × or 1/25.4 of the targets: an inch read as a mm
    (:func:`axiscal.datasets.inch_signature` for the rule and its physical grounds), naming the
    declaration of the leading comment that reads the file right."""
    from axiscal.datasets import inch_reading, inch_signature

    k = inch_signature(targets, readings)
    if k is None:
        return
    text, which, unit = inch_reading(k, tu, ru, "laser readings")
    key = "target_unit" if which == "target" else "reading_unit"
    fix = f"give {key}={unit}" if unit else f"declare the {key} the file was written in"
    raise DataFormatError(f"{text} (a machine axis follows its targets to parts per million, "
                          f"ISO 230-2:2014 §3.1): {fix}", source)


def _direction(text: str, source: str, n: int) -> str:
    t = text.strip().lower()
    if t in ("+", "up", "fwd", "forward", "positive"):
        return "+"
    if t in ("-", "down", "bwd", "backward", "negative"):
        return "-"
    raise DataFormatError(f"direction {text!r}: use + or -", source, n)


def _meta_number(meta, key, default, lo, hi, source) -> float:
    if key not in meta:
        return default
    v = finite_number(meta[key], key, source)
    if not lo <= v <= hi:
        raise DataFormatError(f"{key}={meta[key]}: outside {lo:g} … {hi:g}", source)
    return v


def _environment_json(text: str, source: str) -> EnvironmentLog:
    from axiscal._parse import loads_json

    d = loads_json(text, source)
    try:
        samples = d["samples"]
        rows = [(s["time_s"], s["air_temperature_c"], s["pressure_pa"], s["humidity_pct"],
                 s.get("material_temperature_c", [])) for s in samples]
    except (ValueError, KeyError, TypeError) as exc:
        raise DataFormatError(f"environment log JSON: {exc}", source) from None
    if not rows:
        raise DataFormatError("environment log JSON has no samples", source)
    mats = [r[4] if isinstance(r[4], list) else [r[4]] for r in rows]
    if len({len(m) for m in mats}) != 1:
        raise DataFormatError("every sample needs the same number of material sensors", source)
    try:
        a = np.array([r[:4] for r in rows], dtype=float)
        m = np.array(mats, dtype=float).reshape(len(rows), -1)
    except (TypeError, ValueError) as exc:
        raise DataFormatError(f"environment log JSON: {exc}", source) from None
    alpha = d.get("expansion_coefficient_ppm")
    return _log(a[:, 0], a[:, 1], a[:, 2], a[:, 3], m,
                None if alpha is None else float(alpha) * 1e-6, source,
                list(range(1, len(rows) + 1)))


def _log(t, air, p, h, mat, alpha, source, lines) -> EnvironmentLog:
    if not (np.isfinite(t).all() and np.isfinite(air).all() and np.isfinite(p).all()
            and np.isfinite(h).all() and np.isfinite(mat).all()):
        raise DataFormatError("the environment log holds a NaN or infinite value", source)
    if np.any(np.diff(t) <= 0):
        i = int(np.argmax(np.diff(t) <= 0))
        raise DataFormatError(f"time_s must increase: {t[i]:g} then {t[i + 1]:g}", source,
                              lines[i + 1])
    if alpha is not None and not abs(alpha) <= 1e-4:
        raise DataFormatError(f"expansion_coefficient_ppm = {alpha * 1e6:g}: at most 100 ppm/K",
                              source)
    _unit_slips(air, p, mat, source)
    return EnvironmentLog(t, air, p, h, mat, alpha, source)


#: The band in which the refractive-index equations were tested against measurements (Stone and
#: Zimmerman, NIST "Engineering metrology toolbox", index of refraction of air: 0-40 °C,
#: 60-120 kPa; see axiscal.physics.air.VALIDITY): a log outside it that falls inside it in a
#: unit often mistaken for the column's is a slip of unit, and refused with the reading named.
_AIR_C, _AIR_KPA = (0.0, 40.0), (60.0, 120.0)


def _unit_slips(air, p, mat, source) -> None:
    """Refuse a temperature column in °F and a pressure column in kPa or hPa (module docstring
    of :mod:`axiscal.physics.air` for the band)."""
    lo, hi = _AIR_C
    for name, col in (("air_temperature_c", air), ("material_temperature_c", mat)):
        col = np.asarray(col, dtype=float)
        if col.size and col.max() > hi:
            as_c = (col - 32.0) * 5.0 / 9.0
            if lo <= as_c.min() and as_c.max() <= hi:
                raise DataFormatError(
                    f"{name} {col.min():g} … {col.max():g} °C is hotter than any calibration "
                    f"(the air equations are tested from {lo:g} to {hi:g} °C); read as °F it is "
                    f"{as_c.min():.1f} … {as_c.max():.1f} °C: convert the column to °C", source)
    lo, hi = _AIR_KPA
    for factor, unit in ((1e3, "kPa"), (1e2, "hPa (mbar)")):
        if p.size and lo * 1e3 <= p.min() * factor and p.max() * factor <= hi * 1e3:
            raise DataFormatError(
                f"pressure_pa {p.min():g} … {p.max():g} Pa is far below any air a machine "
                f"stands in; read as {unit} it is {p.min() * factor:g} … {p.max() * factor:g} "
                "Pa: convert the column to Pa", source)
