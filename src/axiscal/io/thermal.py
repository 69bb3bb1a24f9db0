"""Logs of ISO 230-3 thermal tests as CSV: read strictly, written by the simulations.

Format
------
UTF-8 text. Header lines ``# key = value`` first (other ``#`` lines are comments), then a header
row and one row per sample::

    # axiscal thermal log
    # test = spindle               etve | spindle | linear
    # temperature_unit = C         C (default), or F or K: read only when declared
    # displacement_unit = um       um (default) or mm
    # sensor_spacing_mm = 100      spindle test: X1/X2 and Y1/Y2 apart along the mandrel
    # run_end_s = 14400            spindle/linear: when the spindle or axis stopped
    # axis = X                     linear test
    # P1_mm = 40                   linear test: the two targets
    # P2_mm = 760
    time_s,T_room,T_spindle,X1,X2,Y1,Y2,Z
    0,20.012,20.104,0.03,-0.02,0.11,0.05,-0.08

Columns: ``time_s`` first; temperatures are the columns named ``T_...``; the displacement
columns are the test's (``X``, ``Y``, ``Z`` for the ETVE test, any of them; ``X1 X2 Y1 Y2 Z`` for
the spindle test; ``P1 P2``, the positioning errors at the targets, for the linear test).

Strict: an unknown header key or column, a cell that is not a finite number, a row of the wrong
length, time not increasing, a gap, a stuck or jumping sensor, a test shorter than its minimum
(:func:`axiscal.standards.iso230_3_data.check_log`) are each refused with one line naming the
place. Temperatures that do not look like °C (outside −10 to 60) are refused unless the header
declares their unit: a 20 °C shop reads 68 in °F and 293 in K, both refused undeclared.
"""

from __future__ import annotations

import numpy as np

from axiscal._parse import csv_cells, finite_number
from axiscal.errors import DataFormatError, one_line
from axiscal.standards.iso230_3_data import CHANNELS, TESTS, ThermalLog, check_log

__all__ = ["parse_thermal_log", "read_thermal_log", "format_thermal_log", "write_thermal_log",
           "format_drift_check", "CELSIUS_RANGE"]

#: Temperatures (°C) a machine tool's sensors show; outside, an undeclared unit is refused.
CELSIUS_RANGE = (-10.0, 60.0)
_KEYS = ("test", "temperature_unit", "displacement_unit", "sensor_spacing_mm", "run_end_s",
         "axis", "P1_mm", "P2_mm")
_T_UNITS = {"c": "C", "°c": "C", "degc": "C", "f": "F", "°f": "F", "degf": "F", "k": "K"}
_D_UNITS = {"um": 1e-6, "µm": 1e-6, "mm": 1e-3}
MAX_ROWS = 2_000_000


def read_thermal_log(path) -> ThermalLog:
    """Read a thermal log file; see :func:`parse_thermal_log`."""
    from axiscal.io._files import read_text

    return parse_thermal_log(read_text(path), source=str(path))


def parse_thermal_log(text: str, source: str = "<text>") -> ThermalLog:
    """A checked :class:`~axiscal.standards.iso230_3_data.ThermalLog` from the CSV text.

    Examples
    --------
    >>> rows = "\\n".join(f"{60 * i},{20 + 0.001 * (i % 7):.3f},{0.01 * (i % 5):.2f}"
    ...                   for i in range(60 * 13 + 1))
    >>> log = parse_thermal_log("# test = etve\\ntime_s,T_room,X\\n" + rows)
    >>> log.test, log.time.size, sorted(log.displacements)
    ('etve', 781, ['X'])
    """
    meta, header, rows = _split(text, source)
    test = meta.get("test", "").lower()
    if test not in TESTS:
        raise DataFormatError(f"the header must say '# test = ' one of {', '.join(TESTS)}", source)
    names = [c.strip() for c in csv_cells(header[1], source, header[0])]
    if not names or names[0] != "time_s":
        raise DataFormatError(f"the first column must be time_s, got {names[:1]}", source,
                              header[0])
    if len(set(names)) != len(names):
        raise DataFormatError("a column name appears twice", source, header[0])
    temp_cols = [n for n in names[1:] if n.startswith("T_")]
    disp_cols = [n for n in names[1:] if not n.startswith("T_")]
    bad = [n for n in disp_cols if n not in CHANNELS[test]]
    if bad:
        raise DataFormatError(f"column {one_line(repr(bad[0]), 60)} is neither a temperature (T_...) nor a "
                              f"displacement of the {test} test ({', '.join(CHANNELS[test])})",
                              source, header[0])
    data = _numbers(rows, len(names), source)
    t_unit = _unit(meta, "temperature_unit", _T_UNITS, "C", source)
    d_unit = _unit(meta, "displacement_unit", _D_UNITS, "um", source)
    temps = {n: _to_celsius(data[:, names.index(n)], t_unit, n, "temperature_unit" in meta, source)
             for n in temp_cols}
    disps = {n: data[:, names.index(n)] * _D_UNITS[d_unit] for n in disp_cols}
    log = ThermalLog(test=test, time=data[:, 0], temperatures=temps, displacements=disps,
                     run_end=_opt(meta, "run_end_s", 1.0, source),
                     sensor_spacing=_opt(meta, "sensor_spacing_mm", 1e-3, source),
                     targets=_targets(meta, source), axis=meta.get("axis", ""), source=source)
    return check_log(log)


def format_thermal_log(log: ThermalLog) -> str:
    """The CSV text of a log (temperatures in °C, displacements in µm)."""
    head = ["# axiscal thermal log", f"# test = {log.test}", "# temperature_unit = C",
            "# displacement_unit = um"]
    if log.sensor_spacing is not None:
        head.append(f"# sensor_spacing_mm = {log.sensor_spacing * 1e3:.6g}")
    if log.run_end is not None:
        head.append(f"# run_end_s = {log.run_end:.6g}")
    if log.axis:
        head.append(f"# axis = {log.axis}")
    if log.targets is not None:
        head += [f"# P1_mm = {log.targets[0] * 1e3:.9g}", f"# P2_mm = {log.targets[1] * 1e3:.9g}"]
    tn, dn = list(log.temperatures), [c for c in CHANNELS[log.test] if c in log.displacements]
    head.append(",".join(["time_s", *tn, *dn]))
    cols = [log.time] + [log.temperatures[n] for n in tn] + [log.displacements[n] * 1e6 for n in dn]
    fmt = ["%.3f"] + ["%.4f"] * len(tn) + ["%.4f"] * len(dn)
    body = np.column_stack(cols)
    lines = [",".join(f % v for f, v in zip(fmt, row)) for row in body]
    return "\n".join(head + lines) + "\n"


def write_thermal_log(path, log: ThermalLog):
    """Write :func:`format_thermal_log` atomically (no half-written file is left)."""
    from axiscal.io._files import write_text_atomic

    return write_text_atomic(path, format_thermal_log(log))


def format_drift_check(time, readings) -> str:
    """A drift check (s, m) as the CSV ``axiscal iso230-2 --drift-check`` reads (µm)."""
    lines = ["# drift check (ISO 230-2:2014 Annex A.5), readings in um", "time_s,reading"]
    lines += [f"{t:.3f},{r * 1e6:.4f}" for t, r in zip(time, readings)]
    return "\n".join(lines) + "\n"


def _split(text: str, source: str):
    meta: dict[str, str] = {}
    header = None
    rows = []
    for n, line in enumerate(text.splitlines(), 1):
        s = line.strip()
        if not s:
            continue
        if s.startswith("#"):
            if header is None and "=" in s:
                key, _, value = s[1:].partition("=")
                key = key.strip()
                if key not in _KEYS:
                    raise DataFormatError(f"unknown header key {one_line(repr(key), 60)}; known: "
                                          f"{', '.join(_KEYS)}", source, n)
                meta[key] = value.strip()
            continue
        if header is None:
            header = (n, s)
        else:
            rows.append((n, s))
            if len(rows) > MAX_ROWS:
                raise DataFormatError(f"more than {MAX_ROWS} rows; a thermal log at one sample a "
                                      "second for a week has 604,800", source)
    if header is None or not rows:
        raise DataFormatError("no data: a header row (time_s, ...) and rows are needed", source)
    return meta, header, rows


def _numbers(rows, width: int, source: str) -> np.ndarray:
    out = np.empty((len(rows), width))
    for i, (n, line) in enumerate(rows):
        cells = csv_cells(line, source, n)
        if len(cells) != width:
            raise DataFormatError(f"{len(cells)} cells; the header has {width}", source, n)
        for j, c in enumerate(cells):
            out[i, j] = finite_number(c, "value", source, n)
    return out


def _unit(meta, key, known, default, source):
    v = meta.get(key, default).strip().lower()
    if v not in known:
        raise DataFormatError(f"{key} = {one_line(repr(meta.get(key)), 60)}; one of "
                              f"{', '.join(sorted(set(k for k in known if k.isascii())))}", source)
    return known[v] if key == "temperature_unit" else v


def _to_celsius(v: np.ndarray, unit: str, name: str, declared: bool, source: str) -> np.ndarray:
    c = {"C": v, "F": (v - 32.0) * 5.0 / 9.0, "K": v - 273.15}[unit]
    lo, hi = CELSIUS_RANGE
    if not declared and (c.min() < lo or c.max() > hi):
        m = float(np.median(v))
        guess = ("they look like kelvin: declare '# temperature_unit = K'" if 250 <= m <= 350
                 else "they look like °F: declare '# temperature_unit = F'" if 40 <= m <= 140
                 else "declare their unit ('# temperature_unit = C, F or K')")
        raise DataFormatError(f"{name}: temperatures from {v.min():g} to {v.max():g} are not a "
                              f"machine's °C ({lo:g} to {hi:g}); {guess}", source)
    if c.min() < -273.15:
        raise DataFormatError(f"{name}: below absolute zero in {unit}", source)
    return c


def _opt(meta, key, scale, source):
    if key not in meta:
        return None
    return finite_number(meta[key], key, source) * scale


def _targets(meta, source):
    p1, p2 = _opt(meta, "P1_mm", 1e-3, source), _opt(meta, "P2_mm", 1e-3, source)
    if p1 is None and p2 is None:
        return None
    if p1 is None or p2 is None:
        raise DataFormatError("the header gives one of P1_mm and P2_mm; both are needed", source)
    return (p1, p2)
