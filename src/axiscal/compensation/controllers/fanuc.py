"""FANUC pitch error compensation: parameters 3620-3627 and incremental values per point.

Sources: FANUC Series 0i-PB Parameter Manual (B-63980EN/01) §4 "Description of parameters",
parameters 3620-3625 with Example 1 (linear axis, reference position at machine coordinate 0)
and Example 2 (rotary axis); FANUC technical report A-77810E "Bidirectional pitch error
compensation" (Series 16i/18i-MA/TA) §2 table (a) of parameters 3605#0, 3620-3627; FANUC Series
15i/150i-MODEL A Parameter Manual (B-63330EN/03) §3 "Inputting and outputting parameters using
external input/output devices" (tape formats: an axis-type parameter is one line
``N***** A* P****** A* P****** … ;`` holding every axis, a bit parameter's eight digits count
bit 0 from the right; a record begins and ends with ``%``); FANUC Series 30i/31i-MODEL A
Parameter Manual (B-63950EN/02) §3.3 (the same lines with ``Q1`` after the number); cnc.wiki
"Setup guide for Fanuc pitch error compensation parameters" (values entered incrementally as
seen from the negative direction; power off/on and a reference return after a change).

Parameters (per axis):

====== =====================================================================================
3605#0 1: bidirectional pitch error compensation enabled (0: one table, 3626/3627 unused)
3620   number of the compensation point at the reference position
3621   number of the most distant point on the − side (positive-direction table)
3622   number of the most distant point on the + side (positive-direction table)
3623   compensation magnification (the values are multiplied by it)
3624   interval between compensation points, in detection units
3625   rotary axis: travel per revolution, in detection units (0 on a linear axis)
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
the one that is zero there). Reading: where the listing holds 3605, its bit 0 decides (a full
listing with 3605#0 = 0 and 3625-3627 at zero is one table for both directions, as the control
reads it); where it does not (axiscal's tapes leave 3605 to the parameter screen), a non-zero
3626 or 3627 marks a bidirectional table.

**Rotary axis** (0i-PB Example 2): 3621 = 3620, 3622 = 3620 + 360°/interval; the increments from
3620+1 to 3622 must sum to zero (else the error accumulates every revolution: refused here) and
point 3620 holds the same value as point 3622. A non-zero 3625 marks a rotary axis.

**What the tape does not carry.** The tape holds counts and point numbers only: where the
reference position lies in the coordinates of the measurement (the control puts point 3620
where the reference return ends; 0i-PB Example 1 draws it at machine coordinate 0), the
detection unit (0.001 mm on an IS-B machine, 0.0001 mm on IS-C; inch on an inch machine,
parameter 1001#0 INM = 1) and whether the axis is linear. :func:`write` states all three in
comments (``(REFERENCE POSITION 15 MM AT POINT 0)``) and :func:`parse` takes them from there; on
a tape without them they are the caller's options or assumed (reference position 0, detection
unit 0.001, linear), and :func:`inputs` says which. A comparison with measured positions on an
assumed reference position is refused by ``axiscal compensate --read`` (it shifts every point).

**File.** An ISO parameter tape: ``%``, parameter lines ``N3620A1P40`` (A1 = first axis; a
machine's punched listing holds every axis on one line, ``N03620A1P2A2P40A3P80``, and may
carry ``Q1`` after the number), the data as ``N1xxxxPv`` (data number 10000 + point number),
``%``. Lines of other parameters in a full listing are skipped; a listing with pitch error
parameters for several axes is read for the axis ``axis_number`` names.

**Limits checked.** Point numbers 0…1023 (``max_number``); each value within −128…127 after the
magnification (the range of the 16i/18i/0i series; later series allow more, not confirmed);
interval a whole number of detection units (0.001 mm or 0.001 deg by default); range inside the
travel; rotary sum zero; on reading, a negative-direction table (3626) whose point numbers
overlap the positive one's (3621 … 3622) is refused (one point cannot hold two values; this
module's reading, not a rule found in the sources).
"""

from __future__ import annotations

import math
import re
from dataclasses import replace

import numpy as np

from axiscal.compensation.controllers._common import (
    ControllerFile, FileInput, check_points, check_spacing, check_travel, correction_factor,
    file_unit, parse_number, require_equidistant, resolve_input, safe_axis_name, whole,
    check_fields)
from axiscal.compensation.tables import CompensationTable, TableOrigin
from axiscal.datasets import AxisKind
from axiscal.errors import ControllerLimitError, DataFormatError, InputError

__all__ = ["NAME", "write", "parse", "inputs", "VALUE_RANGE"]

NAME = "fanuc"
VALUE_RANGE = (-128, 127)
MAX_NUMBER = 1023
#: The pitch error compensation parameters (A-77810E table (a)); a listing's others are skipped.
PARAMETERS = (3605, 3620, 3621, 3622, 3623, 3624, 3625, 3626, 3627)

_LINE = re.compile(r"^N0*(\d{1,9})(?:Q[01])?((?:A\d{1,3}P[-+]?\d+)+|P[-+]?\d+);?$")
_PAIR = re.compile(r"(?:A(\d{1,3}))?P([-+]?\d+)")
_OTHER = re.compile(r"^N0*(\d{1,9})[A-Z0-9.+\-]*;?$")
_HEAD = re.compile(r"\(AXISCAL PITCH ERROR COMPENSATION AXIS (\S+?),.*?1 COUNT = "
                   r"([0-9.eE+\-]{1,30}) (MM|DEG|INCH)\)")
_REF = re.compile(r"\(REFERENCE POSITION ([0-9.eE+\-]{1,30}) (MM|DEG|INCH) AT POINT \d+\)")
_WORD = {"mm": "MM", "deg": "DEG", "inch": "INCH"}


#: The grammar of every number :func:`write` puts into a tape word: ``A`` (axis) numbers a
#: FANUC control's axes from 1 (a Series 30i path has at most 32); a data line is
#: ``N(10000 + point)`` and a tape's N word holds 5 digits, so no point number passes 89999.
FIELDS = {"axis_number": whole(1, 32, "axes"), "reference_number": whole(0, 89999, "points"),
          "max_number": whole(1, 89999, "points"), "magnification": whole(1, 100, "steps")}


def write(table: CompensationTable, travel=None, *, axis_number: int = 1,
          reference_number: int | None = None, detection_unit: float = 0.001,
          magnification: int | None = None, max_number: int = MAX_NUMBER,
          unit: str = "mm") -> ControllerFile:
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
    detection_unit : float, mm, inch or deg
        One count of the values and of parameter 3624, in ``unit`` (deg on a rotary axis).
    magnification : int, optional
        Parameter 3623 (1…100); default the smallest that keeps every value within −128…127.
    max_number : int
        Highest point number the control has (1023 for 16i/18i/0i).
    unit : str
        ``mm`` or ``inch`` (an inch machine, parameter 1001#0 INM = 1): the unit of
        ``detection_unit`` on a linear axis.
    """
    check_fields(NAME, FIELDS, axis_number=axis_number, reference_number=reference_number,
                 max_number=max_number, magnification=magnification)
    require_equidistant(table, NAME)
    names = safe_axis_name(table.axis, NAME)             # portable: the comment and file name
    table = replace(table, axis=names.name)
    per = file_unit(unit, table, NAME)                  # mm per file unit (1 on a rotary axis)
    count = detection_unit * per                         # one count in the table's position unit
    table, mag = _prepare(table, travel, count, magnification)
    r = table.reference_index
    ref = (r if not table.modulo else 0) if reference_number is None else int(reference_number)
    n = table.n_points
    first = ref - r
    last = first + n - 1
    counts = correction_factor(table, table.position_unit) / count   # corr -> counts
    inc_up = _increments(table.up, counts, mag)
    params = [(3620, ref), (3621, first), (3622, last), (3623, mag),
              (3624, check_spacing(table.spacing, count, table.position_unit, NAME,
                                  "detection_unit"))]
    data = list(zip(range(first, last + 1), inc_up))
    if table.modulo:
        params.append((3625, int(round(360.0 / count))))
        data[0] = (first, inc_up[-1])        # point 3620 repeats the value of point 3622
    if table.bidirectional:
        neg_first = last + 1
        inc_down = _increments(table.down, counts, mag)
        if table.modulo:
            inc_down[0] = inc_down[-1]
        params += [(3626, neg_first), (3627, int(round(table.down[r] * counts)))]
        data += list(zip(range(neg_first, neg_first + n), inc_down))
    _check_numbers(data, max_number)
    a = int(axis_number)
    word = _WORD[table.position_unit if per == 1.0 else "inch"]
    lines = ["%", f"(AXISCAL PITCH ERROR COMPENSATION AXIS {table.axis or '-'}, CORRECTION = "
             f"-DEVIATION, 1 COUNT = {detection_unit:.12g} {word})",
             f"(REFERENCE POSITION {table.reference_position / per:.12g} {word} AT POINT {ref})",
             *names.comment("(", ")", upper=True), *_tape(params, data, a, table.bidirectional)]
    return ControllerFile(NAME, "\n".join(lines) + "\n", f"PITCH_{table.axis or 'AXIS'}.TXT",
                          table, _enable(params, a, table.bidirectional),
                          notes=_notes(table, ref, mag, detection_unit, count, per, word))


def parse(text: str, source: str = "<text>", axis_kind: "AxisKind | str | None" = None,
          axis: str = "", axis_number: int | None = None, detection_unit: float | None = None,
          reference_position: float | None = None, correction_unit: str | None = None,
          max_number: int = MAX_NUMBER, unit: str | None = None) -> CompensationTable:
    """Read a FANUC pitch error compensation tape or punched parameter listing into a table.

    Parameters
    ----------
    text : str
        The tape: ``%``, parameter lines (one axis or every axis per line), ``N1xxxxP`` data.
    axis_number : int, optional
        The axis to read from a listing that holds several (refused without it, naming them).
    detection_unit : float, optional, mm, inch or deg
        One count; default from axiscal's tape comment, else 0.001 (assumed, see :func:`inputs`).
    reference_position : float, optional, mm or deg
        Where point 3620 lies in the coordinates of the measurement (the reference position);
        default from axiscal's tape comment, else 0 (assumed).
    axis_kind : str, optional
        Default from the tape comment's unit, else rotary if 3625 is non-zero, else linear.
    unit : str, optional
        ``mm`` or ``inch``: the unit of ``detection_unit`` on a linear axis (default from the
        tape comment, else mm). A unit or detection unit contradicting the comment is refused.

    Point numbers must lie in 0 … ``max_number``; a missing parameter or data line, a repeated
    one, or parameters that describe no table raise :class:`DataFormatError` naming it. The
    positions come back in mm (deg), the corrections in ``correction_unit`` (µm or arcsec).
    """
    params = _axis_params(_read_lines(text, source), axis_number, source)
    got = {i.name: i for i in _inputs(text, params, source, axis_kind, detection_unit,
                                      reference_position, unit)}
    kind = AxisKind.parse(got["axis_kind"].value)
    per = 1.0 if kind is AxisKind.ROTARY else file_unit(got["unit"].value, None, NAME)
    if not axis:                  # the axis name axiscal's tape comment carries
        m = _HEAD.search(text)
        axis = "" if m is None or m.group(1) == "-" else m.group(1)
    bidirectional = _bidirectional(params)
    for p in (3620, 3621, 3622, 3624) + ((3626,) if bidirectional else ()):
        if p not in params:
            raise DataFormatError(f"parameter {p} is missing" + (
                " (3605#0 = 1 makes the table bidirectional; 3626 numbers its negative-direction "
                "points)" if p == 3626 else ""), source)
    pu = "mm" if kind is AxisKind.LINEAR else "deg"
    cu = correction_unit or ("um" if kind is AxisKind.LINEAR else "arcsec")
    ref, first, last = params[3620], params[3621], params[3622]
    mag = params.get(3623, 1)
    _check_read_params(params, first, last, ref, mag, max_number, source)
    count = got["detection_unit"].value * per            # one count in mm or deg
    spacing = params[3624] * count
    data = params["data"]
    up = _absolute(data, first, last, ref, 0, mag, source)
    down = _negative(params, first, last, ref, mag, max_number, source) if bidirectional else up
    t = CompensationTable(axis, kind, pu, cu,
                          got["reference_position"].value - (ref - first) * spacing,
                          spacing, up, down, bidirectional=bidirectional,
                          modulo=params.get(3625, 0) != 0, reference_index=ref - first)
    k = count / correction_factor(t, pu)   # counts -> correction unit
    origin = TableOrigin(NAME, str(axis_number) if axis_number else "", None,
                         got["unit"].value if kind is AxisKind.LINEAR else "deg",
                         got["axis_kind"].source)
    return replace(t, up=np.round(up * k, 9) + 0.0, down=np.round(down * k, 9) + 0.0,
                   resolution=k * mag, origin=origin)


def inputs(text: str, source: str = "<text>", axis_kind=None, axis_number: int | None = None,
           detection_unit: float | None = None, reference_position: float | None = None,
           unit: str | None = None, **_) -> tuple[FileInput, ...]:
    """What :func:`parse` takes from the tape's comments, from the caller, or assumes.

    ``reference_position`` (needed to compare with measured positions), ``detection_unit``,
    ``unit`` and ``axis_kind``; see the module docstring ("What the tape does not carry").
    """
    params = _axis_params(_read_lines(text, source), axis_number, source)
    return _inputs(text, params, source, axis_kind, detection_unit, reference_position, unit)


# -- what the tape says and what is assumed ------------------------------------------------
def _inputs(text, params, source, axis_kind, detection_unit, reference_position, unit):
    head, ref = _HEAD.search(text), _REF.search(text)
    if head and ref and head.group(3) != ref.group(2):
        raise DataFormatError(f"the tape's comments disagree: counts in {head.group(3)}, the "
                              f"reference position in {ref.group(2)}", source)
    stated = (head.group(3).lower() if head else None) or (ref.group(2).lower() if ref else None)
    said = "from the tape's comment"
    k_stated, k_said = (None, said) if stated is None else (
        "rotary" if stated == "deg" else "linear", said)
    if stated is None and params.get(3625, 0) != 0:
        k_stated, k_said = "rotary", "parameter 3625 (travel per revolution) is set"
    kind = resolve_input("axis_kind", None if axis_kind is None else AxisKind.parse(axis_kind).value,
                         k_stated, "linear", said=k_said, source=source,
                         why="3625 is not set and the tape does not say")
    rotary = kind.value == AxisKind.ROTARY.value
    u = FileInput("unit", "deg", "", "file", "a rotary axis counts in degrees") if rotary else \
        resolve_input("unit", None if unit is None else _unit_name(unit),
                      None if stated == "deg" else stated, "mm", said=said, source=source,
                      why="a metric machine (1001#0 INM = 0) assumed")
    du = resolve_input("detection_unit", _number("detection_unit", detection_unit),
                       None if head is None else parse_number(head.group(2), source, None),
                       0.001, said=said, unit="deg" if rotary else u.value, source=source,
                       why="the tape does not record the detection unit (0.001 on an IS-B "
                           "machine)")
    if not du.value > 0:
        raise InputError(f"{NAME}: detection_unit = {du.value!r} must be a positive number "
                         "(mm, inch or deg per count)")
    per = 1.0 if rotary else file_unit(u.value, None, NAME)
    rp = resolve_input("reference_position", _number("reference_position", reference_position),
                       None if ref is None else parse_number(ref.group(1), source, None) * per,
                       0.0, said=said, unit="deg" if rotary else "mm", source=source,
                       needed_to_compare=True,
                       why="a Fanuc tape does not record where the reference position (point "
                           "3620) lies in the coordinates of the measurement")
    return (rp, du, u, kind)


def _number(name, given):
    """An option as a finite float (None stays None), or an :class:`InputError` naming it."""
    if given is None:
        return None
    try:
        value = float(given)
    except (TypeError, ValueError):
        raise InputError(f"{NAME}: {name} = {given!r} must be a number") from None
    if not math.isfinite(value):
        raise InputError(f"{NAME}: {name} = {given!r} must be a finite number")
    return value


def _unit_name(unit) -> str:
    return "inch" if file_unit(unit, None, NAME) != 1.0 else "mm"


def _bidirectional(params) -> bool:
    """3605#0 decides where the listing holds it; else a non-zero 3626 or 3627 (A-77810E)."""
    if 3605 in params:
        return bool(params[3605] % 2)
    return bool(params.get(3626, 0) or params.get(3627, 0))


# -- writing helpers -------------------------------------------------------------------------
def _tape(params, data, a, bidirectional) -> list[str]:
    """The parameter and data lines of axis ``a`` (ISO tape, 0i-PB §4), closed by ``%``."""
    lines = [f"(SET 3605#0 = 1 FOR AXIS {a} BY HAND, KEEPING BITS 1-7)"] if bidirectional else []
    lines += [f"N{p}A{a}P{v}" for p, v in params]            # 3605 is a bit parameter: a tape
    lines += [f"N{10000 + k}P{v}" for k, v in data]          # line would overwrite all 8 bits
    return lines + ["%"]


def _enable(params, a, bidirectional) -> tuple[str, ...]:
    return (f"parameters {', '.join(str(p) for p, _ in params)} as written (axis {a})",
            "set bit 0 of parameter 3605 to 1 (bidirectional pitch error compensation) on "
            "the parameter screen, keeping its other seven bits as the machine has them: a "
            "tape line N3605 would overwrite the whole byte" if bidirectional
            else "parameter 3605 bit 0 must be 0 (one table for both directions); leave its "
            "other bits as they are",
            "power the control off and on, then return to the reference position (G28)")


def _notes(table, ref, mag, detection_unit, count, per, word) -> tuple[str, ...]:
    step = mag * count / correction_factor(table, table.position_unit)
    u = word.lower()
    notes = (f"magnification 3623 = {mag}; point {ref} is the reference position "
             f"{table.reference_position / per:g} {u} (stated in a comment only: the control "
             "puts point 3620 where the reference return ends)",
             f"1 count = {detection_unit:g} {u}; corrections rounded to one count x "
             f"magnification = {step:g} {table.correction_unit}")
    if table.axis_kind is AxisKind.ROTARY and step >= 1.0:
        notes += (f"a detection unit of {detection_unit:g}° limits the compensation: corrections "
                  f"move in steps of {step:g} {table.correction_unit}, so errors smaller than "
                  "that are not removed (a 0.0001° detection unit, where the machine has it, "
                  "does better)",)
    return notes


def _prepare(table, travel, count, magnification):
    check_spacing(table.spacing, count, table.position_unit, NAME, "detection_unit")
    check_travel(table, travel, NAME)
    if table.modulo and table.reference_index != 0:
        raise ControllerLimitError(f"{NAME}: a rotary table must start at its reference position "
                                   f"(reference point {table.reference_index}, not 0)")
    table = table.zeroed_at_reference()
    counts = correction_factor(table, table.position_unit) / count
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


# -- reading helpers -------------------------------------------------------------------------
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


def _read_lines(text, source):
    """Pitch error parameters by number and axis (None: a line without ``A``) and the data."""
    params: dict[int, dict] = {}
    data: dict[int, int] = {}
    for n, raw in enumerate(text.splitlines(), 1):
        line = raw.strip().replace(" ", "")
        if not line or line in ("%", "%;") or line.startswith("("):
            continue
        m = _LINE.match(line)
        other = None if m else _OTHER.match(line)
        if other and int(other.group(1)) not in PARAMETERS and int(other.group(1)) < 10000:
            continue                              # another parameter of a full listing
        if not m:
            raise DataFormatError(f"not a parameter or data line: {raw[:60]!r}", source, n)
        num = int(m.group(1))
        if num < 10000 and num not in PARAMETERS:
            continue
        for ax, val in _PAIR.findall(m.group(2)):
            _store(params, data, num, int(ax) if ax else None, val, source, n)
    return params, data


def _store(params, data, num, ax, val, source, n):
    if len(val.lstrip("+-").lstrip("0")) > 9:
        raise DataFormatError(f"value {val[:20]} of N{num} is out of range (at most "
                              "9 digits)", source, n)
    if num >= 10000:
        target, key, what = data, num - 10000, f"pitch error data N{num}"
    else:
        target, key = params.setdefault(num, {}), ax
        what = f"parameter {num}" + (f" for axis {ax}" if ax is not None else "")
        if num == 3605 and not re.fullmatch(r"[01]{1,8}", val):
            raise DataFormatError(f"parameter 3605 = {val!r} is not a bit pattern (8 digits "
                                  "0 or 1)", source, n)
    if key in target:
        raise DataFormatError(f"{what} is given twice", source, n)
    target[key] = int(val, 2) if target is not data and num == 3605 else int(val)


def _axis_params(lines, axis_number, source) -> dict:
    """The parameters of one axis (plus ``"data"``), chosen by number where there are several."""
    params, data = lines
    axes = sorted({a for p in (3620, 3621, 3622, 3624) for a in params.get(p, {}) if a is not None})
    if axis_number is None:
        if len(axes) > 1:
            raise DataFormatError(f"the listing holds pitch error parameters for axes "
                                  f"{', '.join(map(str, axes))}: choose one with axis_number=N",
                                  source)
        axis_number = axes[0] if axes else 1
    try:
        a = int(axis_number)
    except (TypeError, ValueError):
        raise InputError(f"{NAME}: axis_number = {axis_number!r} must be a whole number") from None
    if axes and a not in axes:
        raise DataFormatError(f"no pitch error parameters for axis {a}; the listing holds axes "
                              f"{', '.join(map(str, axes))}", source)
    out: dict = {p: v[a] if a in v else v[None] for p, v in params.items() if a in v or None in v}
    out["data"] = data
    return out


def _negative(params, first, last, ref, mag, max_number, source):
    """The negative-direction table: points from 3626 on, 3627 at the reference (A-77810E)."""
    nf = params[3626]
    if not 0 <= nf <= max_number - (last - first):
        raise DataFormatError(f"parameter 3626 = {nf}: the negative-direction points "
                              f"{nf} … {nf + last - first} fall outside 0 … {max_number}", source)
    if nf <= last and first <= nf + last - first:      # one point would hold two values
        raise DataFormatError(f"parameter 3626 = {nf}: the negative-direction points "
                              f"{nf} … {nf + last - first} overlap the positive-direction "
                              f"points {first} … {last} (3621 … 3622)", source)
    return _absolute(params["data"], nf, nf + last - first, nf + ref - first,
                     params.get(3627, 0), mag, source)


def _absolute(data, first, last, ref, at_ref, mag, source):
    missing = [k for k in range(first, last + 1) if k not in data]
    if missing:
        raise DataFormatError(f"pitch error data for point {missing[0]} is missing", source)
    inc = np.array([data[k] for k in range(first, last + 1)], dtype=float) * mag
    inc[0] = 0.0                          # the interval before the first point is outside
    cum = np.cumsum(inc)
    return cum - cum[ref - first] + at_ref * 1.0
