"""FANUC pitch error compensation: parameters 3620-3627 and incremental values per point.

Sources: FANUC Series 0i-PB Parameter Manual (B-63980EN/01) §4, parameters 3620-3625 with
Example 2 (rotary axis); FANUC technical report A-77810E "Bidirectional pitch error compensation"
(Series 16i/18i-MA/TA), table (a) of parameters 3605#0, 3620-3627; cnc.wiki "Setup guide for
Fanuc pitch error compensation parameters" (values entered incrementally as seen from the
negative direction; power off/on and a reference return after a change).

Parameters (per axis):

====== =====================================================================================
3605#0 1: bidirectional pitch error compensation enabled
3620   number of the compensation point at the reference position
3621   number of the most distant point on the − side (positive-direction table)
3622   number of the most distant point on the + side (positive-direction table)
3623   compensation magnification (the values are multiplied by it)
3624   interval between compensation points, in detection units
3625   rotary axis: travel per revolution, in detection units
3626   bidirectional: number of the most distant − point of the negative-direction table
3627   bidirectional: compensation at the reference position for travel in the negative
       direction (absolute value, detection units)
====== =====================================================================================

**Values.** The value at point N is the *increment* of the correction over the interval that
ends at point N (from N−1 to N), in detection units, multiplied by 3623. The correction at the
reference position is 0 by construction, so :func:`write` shifts the table to zero there
(:meth:`~axiscal.compensation.tables.CompensationTable.zeroed_at_reference`). Sign: the values
are corrections (added to the motion): correction = −deviation. (That the value belongs to the
interval *ending* at N, and the sign, are this module's reading of the sources above.)

**Bidirectional.** The negative-direction table takes the point numbers after the positive one
(3626 = 3622 + 1 by default) and 3627 holds its absolute correction at the reference position;
the reference return is assumed to be made in the positive direction (so the positive table is
the one that is zero there).

**Rotary axis** (0i-PB Example 2): 3621 = 3620, 3622 = 3620 + 360°/interval; the increments from
3620+1 to 3622 must sum to zero (else the error accumulates every revolution: refused here) and
point 3620 holds the same value as point 3622.

**File.** An ISO parameter-tape text: ``%``, parameter lines ``N3620A1P40`` (A1 = first axis),
the data as ``N1xxxxPv`` (data number 10000 + point number), ``%``.

**Limits checked.** Point numbers 0…1023 (``max_number``); each value within −128…127 after the
magnification (the range of the 16i/18i/0i series; later series allow more, not confirmed);
interval a whole number of detection units (0.001 mm or 0.001 deg by default); range inside the
travel; rotary sum zero.
"""

from __future__ import annotations

import math
import re
from dataclasses import replace

import numpy as np

from axiscal.compensation.controllers._common import (
    ControllerFile, check_points, check_spacing, check_travel, correction_factor,
    require_equidistant)
from axiscal.compensation.tables import CompensationTable
from axiscal.datasets import AxisKind
from axiscal.errors import ControllerLimitError, DataFormatError, InputError

__all__ = ["NAME", "write", "parse", "VALUE_RANGE"]

NAME = "fanuc"
VALUE_RANGE = (-128, 127)
MAX_NUMBER = 1023

_LINE = re.compile(r"^N0*(\d{1,9})\s*(?:A(\d{1,3})\s*)?P\s*([-+]?\d+)\s*;?$")


def write(table: CompensationTable, travel=None, *, axis_number: int = 1, reference_number: int | None = None,
          detection_unit: float = 0.001, magnification: int | None = None,
          max_number: int = MAX_NUMBER) -> ControllerFile:
    """Write ``table`` as FANUC pitch error compensation parameters and data.

    Parameters
    ----------
    table : CompensationTable
        Positions in mm or deg; its ``reference_index`` is the reference position (for a rotary
        axis it must be point 0).
    travel : (float, float), optional, ``table.position_unit``
    axis_number : int
        Axis number in the parameter lines (``A1``).
    reference_number : int, optional
        Parameter 3620; default so the table's first point gets number 0 (rotary: 0).
    detection_unit : float, mm or deg
        One count of the values and of parameter 3624.
    magnification : int, optional
        Parameter 3623 (1…100); default the smallest that keeps every value within −128…127.
    max_number : int
        Highest point number the control has (1023 for 16i/18i/0i).
    """
    require_equidistant(table, NAME)
    table, mag = _prepare(table, travel, detection_unit, magnification)
    r = table.reference_index
    ref = (r if not table.modulo else 0) if reference_number is None else int(reference_number)
    n = table.n_points
    first = ref - r
    last = first + n - 1
    unit = correction_factor(table, table.position_unit) / detection_unit  # corr -> counts
    inc_up = _increments(table.up, unit, mag)
    params = [(3620, ref), (3621, first), (3622, last), (3623, mag),
              (3624, check_spacing(table.spacing, detection_unit, table.position_unit, NAME,
                                  "detection_unit"))]
    data = list(zip(range(first, last + 1), inc_up))
    if table.modulo:
        params.append((3625, int(round(360.0 / detection_unit))))
        data[0] = (first, inc_up[-1])        # point 3620 repeats the value of point 3622
    if table.bidirectional:
        neg_first = last + 1
        inc_down = _increments(table.down, unit, mag)
        if table.modulo:
            inc_down[0] = inc_down[-1]
        params += [(3626, neg_first), (3627, int(round(table.down[r] * unit)))]
        data += list(zip(range(neg_first, neg_first + n), inc_down))
    _check_numbers(data, max_number)
    a = int(axis_number)
    lines = ["%", f"(AXISCAL PITCH ERROR COMPENSATION AXIS {table.axis or '-'}, CORRECTION = "
             f"-DEVIATION, 1 COUNT = {detection_unit:g} {table.position_unit.upper()})"]
    if table.bidirectional:      # a bit parameter: the tape would overwrite all eight bits
        lines.append(f"(SET 3605#0 = 1 FOR AXIS {a} BY HAND, KEEPING BITS 1-7)")
    lines += [f"N{p}A{a}P{v}" for p, v in params]
    lines += [f"N{10000 + k}P{v}" for k, v in data]
    lines.append("%")
    enable = [f"parameters {', '.join(str(p) for p, _ in params)} as written (axis {a})",
              "set bit 0 of parameter 3605 to 1 (bidirectional pitch error compensation) on "
              "the parameter screen, keeping its other seven bits as the machine has them: a "
              "tape line N3605 would overwrite the whole byte" if table.bidirectional
              else "parameter 3605 bit 0 must be 0 (one table for both directions); leave its "
              "other bits as they are",
              "power the control off and on, then return to the reference position (G28)"]
    step = mag * detection_unit / correction_factor(table, table.position_unit)
    notes = (f"magnification 3623 = {mag}; point {ref} is the reference position "
             f"{table.reference_position:g} {table.position_unit}",
             f"corrections rounded to one count x magnification = {step:g} {table.correction_unit}")
    if table.axis_kind is AxisKind.ROTARY and step >= 1.0:
        notes += (f"a detection unit of {detection_unit:g}° limits the compensation: corrections "
                  f"move in steps of {step:g} {table.correction_unit}, so errors smaller than "
                  "that are not removed (a 0.0001° detection unit, where the machine has it, "
                  "does better)",)
    return ControllerFile(NAME, "\n".join(lines) + "\n", f"PITCH_{table.axis or 'AXIS'}.TXT",
                          table, tuple(enable), notes=notes)


def parse(text: str, source: str = "<text>", axis_kind: "AxisKind | str" = "linear",
          axis: str = "", axis_number: int = 1, detection_unit: float = 0.001,
          reference_position: float = 0.0, correction_unit: str | None = None,
          max_number: int = MAX_NUMBER) -> CompensationTable:
    """Read parameters and data written by :func:`write` back into a table.

    The file does not say where the reference position is in machine coordinates nor the
    detection unit: give them (``reference_position`` in mm or deg). Point numbers must lie in
    0 … ``max_number`` (as :func:`write` checks); a missing parameter or data line, a repeated
    one, or parameters that describe no table raise :class:`DataFormatError` naming it.
    """
    if not (math.isfinite(detection_unit) and detection_unit > 0):
        raise InputError(f"{NAME}: detection_unit = {detection_unit!r} must be a positive number "
                         "(mm or deg per count)")
    params, data = _read_lines(text, source, axis_number)
    if not axis:                  # the axis name axiscal's tape comment carries
        m = re.search(r"\(AXISCAL PITCH ERROR COMPENSATION AXIS (\S+?),", text)
        axis = "" if m is None or m.group(1) == "-" else m.group(1)
    # 3605#0 is set by hand (not on the tape): 3626 or 3627 mark a bidirectional table too
    bidirectional = bool(params.get(3605, 0) % 2) or 3626 in params or 3627 in params
    for p in (3620, 3621, 3622, 3624) + ((3626,) if bidirectional else ()):
        if p not in params:
            raise DataFormatError(f"parameter {p} is missing" + (
                " (3605#0 = 1 makes the table bidirectional; 3626 numbers its negative-direction "
                "points)" if p == 3626 else ""), source)
    kind = AxisKind.parse(axis_kind)
    pu = "mm" if kind is AxisKind.LINEAR else "deg"
    cu = correction_unit or ("um" if kind is AxisKind.LINEAR else "arcsec")
    ref, first, last = params[3620], params[3621], params[3622]
    mag = params.get(3623, 1)
    _check_read_params(params, first, last, ref, mag, max_number, source)
    spacing = params[3624] * detection_unit
    modulo = 3625 in params
    up = _absolute(data, first, last, ref, 0, mag, source)
    down = up
    if bidirectional:
        nf = params[3626]
        if not 0 <= nf <= max_number - (last - first):
            raise DataFormatError(f"parameter 3626 = {nf}: the negative-direction points "
                                  f"{nf} … {nf + last - first} fall outside 0 … {max_number}", source)
        down = _absolute(data, nf, nf + last - first, nf + ref - first, params.get(3627, 0), mag,
                         source)
    t = CompensationTable(axis, kind, pu, cu, reference_position - (ref - first) * spacing,
                          spacing, up, down, bidirectional=bidirectional, modulo=modulo,
                          reference_index=ref - first)
    k = detection_unit / correction_factor(t, pu)   # counts -> correction unit
    return replace(t, up=np.round(up * k, 9) + 0.0, down=np.round(down * k, 9) + 0.0,
                   resolution=k * mag)


# -- helpers ---------------------------------------------------------------------------------
def _prepare(table, travel, detection_unit, magnification):
    check_spacing(table.spacing, detection_unit, table.position_unit, NAME, "detection_unit")
    check_travel(table, travel, NAME)
    if table.modulo and table.reference_index != 0:
        raise ControllerLimitError(f"{NAME}: a rotary table must start at its reference position "
                                   f"(reference point {table.reference_index}, not 0)")
    table = table.zeroed_at_reference()
    counts = correction_factor(table, table.position_unit) / detection_unit
    if table.modulo:
        for name in ("up", "down"):
            c = getattr(table, name)
            if round(c[-1] * counts) != round(c[0] * counts):
                raise ControllerLimitError(
                    f"{NAME}: rotary table ({name}) increments over one revolution sum to "
                    f"{round((c[-1] - c[0]) * counts)} counts, not zero; the error would "
                    "accumulate every revolution")
    if magnification is None:
        steps = np.abs(np.diff(np.round(np.concatenate([table.up, table.down]) * counts)))
        magnification = max(1, math.ceil(float(np.max(steps, initial=0)) / VALUE_RANGE[1]))
    mag = int(magnification)
    if not 1 <= mag <= 100:
        raise ControllerLimitError(f"{NAME}: magnification 3623 = {mag}; allowed 1 … 100")
    step = mag / counts       # one value count in the correction unit
    table = replace(table, up=np.round(table.up / step) * step, down=np.round(table.down / step) * step)
    return table, mag


def _increments(c, counts_per_unit, mag):
    absolute = np.round(c * counts_per_unit / mag).astype(int)
    inc = np.concatenate([[0], np.diff(absolute)])
    bad = (inc < VALUE_RANGE[0]) | (inc > VALUE_RANGE[1])
    if np.any(bad):
        raise ControllerLimitError(
            f"{NAME}: increment {int(inc[bad][0])} at point {int(np.argmax(bad))} is outside "
            f"{VALUE_RANGE[0]} … {VALUE_RANGE[1]} even with magnification {mag}")
    return [int(v) for v in inc]


def _check_numbers(data, max_number):
    nums = [k for k, _ in data]
    check_points(len(nums), max_number + 1, NAME, "point numbers")
    if min(nums) < 0 or max(nums) > max_number:
        raise ControllerLimitError(f"{NAME}: point numbers {min(nums)} … {max(nums)} fall outside "
                                   f"0 … {max_number}; choose another reference_number")


def _check_read_params(params, first, last, ref, mag, max_number, source):
    """Refuse parameters that do not describe a table (before any array is built from them)."""
    if not 0 <= first < last <= max_number:
        raise DataFormatError(f"parameters 3621 = {first} and 3622 = {last} must satisfy "
                              f"0 <= 3621 < 3622 <= {max_number}", source)
    if not first <= ref <= last:
        raise DataFormatError(f"parameter 3620 = {ref} (reference point) lies outside the points "
                              f"{first} … {last} of 3621 … 3622", source)
    if not 1 <= mag <= 100:
        raise DataFormatError(f"parameter 3623 = {mag} (magnification); allowed 1 … 100", source)
    if params[3624] <= 0:
        raise DataFormatError(f"parameter 3624 = {params[3624]} (interval between points) must "
                              "be a positive number of detection units", source)


def _read_lines(text, source, axis_number):
    params: dict[int, int] = {}
    data: dict[int, int] = {}
    for n, raw in enumerate(text.splitlines(), 1):
        line = raw.strip().replace(" ", "")
        if not line or line == "%" or line.startswith("("):
            continue
        m = _LINE.match(line)
        if not m:
            raise DataFormatError(f"not a parameter or data line: {raw[:60]!r}", source, n)
        num, ax, val = int(m.group(1)), m.group(2), m.group(3)
        if num >= 10000:
            target, key = data, num - 10000
        elif ax is None or int(ax) == axis_number:
            target, key = params, num
            if num == 3605 and not re.fullmatch(r"[01]{1,8}", val):
                raise DataFormatError(f"parameter 3605 = {val!r} is not a bit pattern (8 digits "
                                      "0 or 1)", source, n)
        else:
            continue
        if len(val.lstrip("+-").lstrip("0")) > 9:
            raise DataFormatError(f"value {val[:20]} of N{num} is out of range (at most "
                                  "9 digits)", source, n)
        if key in target:
            what = f"pitch error data N{num}" if target is data else f"parameter {num}"
            raise DataFormatError(f"{what} is given twice", source, n)
        target[key] = int(val, 2) if target is params and num == 3605 else int(val)
    return params, data


def _absolute(data, first, last, ref, at_ref, mag, source):
    missing = [k for k in range(first, last + 1) if k not in data]
    if missing:
        raise DataFormatError(f"pitch error data for point {missing[0]} is missing", source)
    inc = np.array([data[k] for k in range(first, last + 1)], dtype=float) * mag
    inc[0] = 0.0                          # the interval before the first point is outside
    cum = np.cumsum(inc)
    return cum - cum[ref - first] + at_ref * 1.0
