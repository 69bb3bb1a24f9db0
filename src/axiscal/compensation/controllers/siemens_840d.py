"""SINUMERIK 840D: leadscrew / measuring-system error compensation (LEC, "EEC") file.

Format (Siemens SINUMERIK 840D sl Function Manual *Extended Functions*, K3 "Compensation",
section "Interpolatory compensation", example for axis X1; and SINUMERIK 808D Function Manual,
"Leadscrew error compensation")::

    %_N_AX_EEC_INI
    CHANDATA(1)
    $AA_ENC_COMP[0,0,AX1]=0.003        ; value at interpolation point 0, mm (deg for rotary)
    $AA_ENC_COMP[0,1,AX1]=0.01
    ...
    $AA_ENC_COMP_STEP[0,AX1]=1.0       ; distance between interpolation points
    $AA_ENC_COMP_MIN[0,AX1]=-200.0     ; position of point 0
    $AA_ENC_COMP_MAX[0,AX1]=600.0      ; position of the last point
    $AA_ENC_COMP_IS_MODULO[0,AX1]=0    ; 1: the table repeats (rotary axis, 0 to 360 deg)
    M17

The first index is the measuring system (0 = encoder 1). Linear interpolation between points.

**Sign.** The 808D manual: "A positive compensation value causes the corresponding machine axis
to move in the negative direction." The controller therefore expects the *error* (deviation):
file value = −correction = +deviation, in mm (deg for a rotary axis).

**Enabling.** MD38000 ``$MA_MM_ENC_COMP_MAX_POINTS[0,AX1]`` ≥ number of points (memory is
re-formatted at the next power-on); the table loads only while MD32700
``$MA_ENC_COMP_ENABLE[0,AX1] = 0``; then MD32700 = 1 and reference the axis (compensation acts
only on a referenced axis). The compensation value at the reference point should be zero to avoid
a jump when it becomes active (808D manual): :func:`write` zeroes the table there by default.

**Direction.** This file holds one table; a bidirectional result is written as its mean table
plus a backlash value for MD32450 ``$MA_BACKLASH[0,AX1]`` (given in the enable list and as a
comment the parser reads back). The backlash sign used: positive for the normal case of play
(an approach in the positive direction stops short, ISO 230-2 B̄ < 0), i.e. MD32450 = −B̄; not
confirmed against a Siemens source. Direction-dependent LEC through the CEC tables
(``$AN_CEC_DIRECTION``) is not written.

**Limits checked.** Number of points ≤ ``max_points`` (MD38000; the 840D sl manuals show tables
of several thousand points, the default 5000 here is not confirmed; the 808D allows 200);
spacing a whole number of ``position_resolution`` in the file's unit (0.001 mm, inch or deg by
default); modulo tables
run 0…360° and close on themselves; the range lies inside the axis travel when given.

**Several axes.** A control's EEC file commonly holds the tables of several machine axes, each
line naming its axis (``$AA_ENC_COMP[0,i,AX1]``, ``[0,i,X1]``): :func:`parse_axes` reads every
axis, :func:`parse` one (``machine_axis=``, needed when the file holds more than one), and
:func:`write_axes` writes several into one file. Comments may be in Windows-1252 (a ``µ`` in a
comment, from a Windows tool): the callers decode the file (:func:`axiscal.io._files.
read_controller_text`); the numbers are ASCII.

**Inch machines.** MD10240 ``$MN_SCALING_SYSTEM_IS_METRIC`` = 0 makes the control's basic
system inch: data loaded from a file (part program or download) is scaled in inch, so the
values, STEP, MIN and MAX of a linear axis's table are in inch (SINUMERIK 808D ADVANCED
Parameter Manual 08/2013 §2.2, MD10240; SINUMERIK 840D sl Function Manual Basic Functions
01/2015, G2 §7.3 "Metric/inch measuring system": compensation values follow the system of
units; 1 inch = 25.4 mm, MD10250 ``$MN_SCALING_VALUE_INCH``). An EEC file does not hold
MD10240 itself: :func:`write` (``unit="inch"``) states it in a comment
(``; MD10240 $MN_SCALING_SYSTEM_IS_METRIC = 0: …``, ``= 1`` for mm) and in the enable list,
:func:`parse` reads it back (also a ``$MN_SCALING_SYSTEM_IS_METRIC=0`` line of an archive), a
``unit`` contradicting it is refused, and a file that says nothing is read in mm (assumed:
:func:`inputs` says so). Rotary axes are in degrees in either system.

**Ends** (``zero_ends=True``): outside MIN…MAX the controller keeps applying the end values
(not confirmed against the manual); ``zero_ends`` forces the first and last values to zero so
the table fades out instead, at the cost of the correction in the last interval.
"""

from __future__ import annotations

import re
from dataclasses import replace

import numpy as np

from axiscal.compensation.controllers._common import (
    ControllerFile, check_modulo, check_points, check_spacing, check_travel,
    correction_factor, decimals, file_unit, parse_number, require_equidistant, resolve_input,
    safe_axis_name, WORD, COUNT, whole, check_fields)
from axiscal.compensation.tables import CompensationTable
from axiscal.datasets import AxisKind
from axiscal.errors import ControllerLimitError, DataFormatError, InputError
from axiscal.units import display

__all__ = ["NAME", "write", "write_axes", "parse", "parse_axes", "inputs", "MAX_POINTS"]

NAME = "siemens-840d"
#: Default MD38000 limit (not confirmed; the machine's MD38000 value is the real limit).
MAX_POINTS = 5000

_VALUE = re.compile(r"^\$AA_ENC_COMP\[\s*(\d{1,9})\s*,\s*(\d{1,9})\s*,\s*([A-Za-z0-9_]+)\s*\]\s*=\s*(\S+)")
_PARAM = re.compile(r"^\$AA_ENC_COMP_(STEP|MIN|MAX|IS_MODULO)\[\s*(\d{1,9})\s*,\s*([A-Za-z0-9_]+)\s*\]"
                    r"\s*=\s*(\S+)")
_BACKLASH = re.compile(r"MD32450\s+\$MA_BACKLASH\[[^\]]*\]\s*=\s*(\S+)")
_NAME = re.compile(r"^;\s*axiscal: axis (\S+),")
_MD10240 = re.compile(r"^(?:;\s*MD10240\s+)?\$MN_SCALING_SYSTEM_IS_METRIC\s*=\s*(\S+?)(?::|\s|$)")


#: The grammar of every option :func:`write`, :func:`write_axes` and :func:`write_cross_axis`
#: write into the file (:func:`~axiscal.compensation.controllers._common.check_fields`).
FIELDS = {"machine_axis": WORD, "input_axis": WORD, "output_axis": WORD, "max_points": COUNT,
          "table_index": whole(0, 999, "CEC tables")}


def write(table: CompensationTable, travel=None, *, machine_axis: str = "AX1",
          max_points: int = MAX_POINTS, position_resolution: float = 0.001,
          zero_at_reference: bool = True, zero_ends: bool = False,
          unit: str = "mm") -> ControllerFile:
    """Write ``table`` as a ``%_N_AX_EEC_INI`` file for ``machine_axis``.

    Parameters
    ----------
    table : CompensationTable
        Positions in mm (linear) or deg (rotary).
    travel : (float, float), optional, ``table.position_unit``
        Axis travel; the table must lie inside it.
    machine_axis : str
        Machine axis name in the file (``AX1``, ``X1`` ...).
    max_points : int
        MD38000 ``$MA_MM_ENC_COMP_MAX_POINTS``.
    position_resolution : float, mm, inch or deg
        The spacing must be a whole multiple of this, in the file's unit.
    zero_at_reference : bool
        Shift the table so the value at its reference point is 0 (Siemens' advice).
    zero_ends : bool
        Set the first and last values to 0 (see the module docstring).
    unit : str
        ``mm`` or ``inch``: the machine's basic system (MD10240 = 1 or 0) for a linear axis.

    Returns
    -------
    ControllerFile
    """
    check_fields(NAME, FIELDS, machine_axis=machine_axis, max_points=max_points)
    per = file_unit(unit, table, NAME)
    _check(table, travel, max_points, position_resolution, per)
    body, enable, written, notes = _axis_block(table, machine_axis, zero_at_reference, zero_ends,
                                               per)
    text = "\n".join(["%_N_AX_EEC_INI", "CHANDATA(1)", *body, "M17"]) + "\n"
    return ControllerFile(NAME, text, "AX_EEC.INI", written, tuple(enable), notes=tuple(notes))


def write_axes(tables: dict, travel=None, **options) -> ControllerFile:
    """One ``%_N_AX_EEC_INI`` file with a table per machine axis (``{"AX1": table, ...}``).

    ``travel`` may be a dict by machine axis; ``options`` as :func:`write`.
    """
    if not tables:
        raise InputError(f"{NAME}: no table to write")
    body, enable, notes = [], [], []
    mp = options.pop("max_points", MAX_POINTS)
    res = options.pop("position_resolution", 0.001)
    unit = options.pop("unit", "mm")
    for ax, table in tables.items():
        check_fields(NAME, FIELDS, machine_axis=ax, max_points=mp)
        tr = travel.get(ax) if isinstance(travel, dict) else travel
        _check(table, tr, mp, res, file_unit(unit, table, NAME))
        b, e, _, n = _axis_block(table, ax, options.get("zero_at_reference", True),
                                 options.get("zero_ends", False), file_unit(unit, table, NAME))
        body += b
        enable += e
        notes += n
    text = "\n".join(["%_N_AX_EEC_INI", "CHANDATA(1)", *body, "M17"]) + "\n"
    first = next(iter(tables.values()))
    return ControllerFile(NAME, text, "AX_EEC.INI", first, tuple(enable), notes=tuple(notes))


def _axis_block(table, machine_axis, zero_at_reference, zero_ends, per=1.0):
    """The lines of one axis's table, its enabling steps, the table as written, notes.

    ``per``: mm per unit of the file (25.4 on an inch machine, MD10240 = 0).
    """
    notes = []
    if zero_at_reference and table.mean[table.reference_index] != 0:
        notes.append(f"table shifted by {-table.mean[table.reference_index]:+.4g} "
                     f"{display(table.correction_unit)} so it is zero at the reference point "
                     f"{table.reference_position:g} {display(table.position_unit)}")
        table = table.zeroed_at_reference(on="mean")
    k = correction_factor(table, table.position_unit) / per  # correction unit -> file unit
    nd = decimals(table.position_unit) + (1 if per != 1.0 else 0)
    fu = table.position_unit if per == 1.0 else "inch"
    mean = table.mean
    if zero_ends:
        mean = mean.copy()
        mean[[0, -1]] = 0.0
    values = np.round(-mean * k, nd) + 0.0      # file value = deviation = −correction
    ax = machine_axis
    names = safe_axis_name(table.axis, NAME)         # portable characters; the source kept
    table = replace(table, axis=names.name)
    lines = [f"; axiscal: axis {table.axis or '-'}, {table.n_points} points, values = deviation "
             f"(-correction) in {fu}", *names.comment("; ")]
    metric = []
    if table.position_unit == "mm":
        metric = [f"MD10240 $MN_SCALING_SYSTEM_IS_METRIC = {1 if per == 1.0 else 0}"]
        lines.append(f"; {metric[0]}: values, STEP, MIN and MAX in {fu}")
    lines += [f"$AA_ENC_COMP[0,{i},{ax}]={_fmt(v)}" for i, v in enumerate(values)]
    nd_pos = 9 if per == 1.0 else 12
    lines += [f"$AA_ENC_COMP_STEP[0,{ax}]={_fmt(table.spacing / per, nd_pos)}",
              f"$AA_ENC_COMP_MIN[0,{ax}]={_fmt(table.start / per, nd_pos)}",
              f"$AA_ENC_COMP_MAX[0,{ax}]={_fmt(table.end / per, nd_pos)}",
              f"$AA_ENC_COMP_IS_MODULO[0,{ax}]={1 if table.modulo else 0}"]
    enable = [f"MD38000 $MA_MM_ENC_COMP_MAX_POINTS[0,{ax}] >= {table.n_points} "
              "(memory is re-formatted at the next power-on)",
              f"load the file while MD32700 $MA_ENC_COMP_ENABLE[0,{ax}] = 0",
              f"then MD32700 $MA_ENC_COMP_ENABLE[0,{ax}] = 1 and reference the axis"]
    enable += [f"{m} on the machine (the file's values, STEP, MIN and MAX are in {fu})"
               for m in metric]
    if table.bidirectional:
        b = np.round(-table.backlash * k, nd) + 0.0
        lines.append(f"; MD32450 $MA_BACKLASH[0,{ax}]={_fmt(b)}")
        enable.append(f"MD32450 $MA_BACKLASH[0,{ax}] = {_fmt(b)} {fu} "
                      "(mean reversal; the table holds the mean of both directions)")
    as_file = np.round(-values / k, 6) + 0.0          # what the file holds, back in the table's unit
    written = replace(table, up=as_file, down=as_file, bidirectional=False)
    if table.bidirectional:
        written = _with_backlash(written, b / k)
    return lines, enable, written, notes


def parse(text: str, source: str = "<text>", axis_kind: "AxisKind | str | None" = None,
          axis: str = "", correction_unit: str | None = None,
          machine_axis: str | None = None, unit: str | None = None) -> CompensationTable:
    """Read one axis of a ``%_N_AX_EEC_INI`` file back into a table (corrections = −file values).

    ``machine_axis`` chooses the axis of a file holding several (it must then be given).
    ``axis_kind`` defaults to rotary if the table is modulo, else linear. Corrections come back
    in ``correction_unit`` (default µm or arcsec). A ``; MD32450`` comment written by
    :func:`write` makes the table bidirectional again (mean ± backlash/2); a ``; axiscal: axis X``
    comment gives the axis name back. ``unit`` (``mm`` or ``inch``) is the machine's basic system
    (MD10240); the file's own statement of it wins, and a ``unit`` contradicting it is refused.
    """
    tables = parse_axes(text, source, axis_kind=axis_kind, correction_unit=correction_unit,
                        unit=unit)
    if machine_axis is None:
        if len(tables) > 1:
            raise DataFormatError(f"the file holds the tables of {len(tables)} machine axes "
                                  f"({', '.join(tables)}): choose one with machine_axis=",
                                  source)
        machine_axis = next(iter(tables))
    key = next((k for k in tables if k.upper() == str(machine_axis).upper()), None)
    if key is None:
        raise DataFormatError(f"no table for machine axis {machine_axis!r}; the file holds "
                              f"{', '.join(tables)}", source)
    t = tables[key]
    return replace(t, axis=axis) if axis else t


def parse_axes(text: str, source: str = "<text>", axis_kind=None,
               correction_unit: str | None = None, unit: str | None = None) -> dict:
    """Every machine axis's table of a ``%_N_AX_EEC_INI`` file, by machine axis name.

    Positions come back in mm (deg), whatever the file's unit (see :func:`inputs`).
    """
    per = file_unit(inputs(text, source, unit=unit)[0].value, None, NAME)
    values: dict[str, dict[int, float]] = {}
    params: dict[str, dict[str, float]] = {}
    backlash: dict[str, float] = {}
    names: dict[str, str] = {}
    pending_name = ""
    for n, raw in enumerate(text.splitlines(), 1):
        line = raw.strip()
        m = _BACKLASH.search(line)
        if m:
            ax = re.search(r"\[\s*\d+\s*,\s*([A-Za-z0-9_]+)\s*\]", line)
            backlash[ax.group(1) if ax else ""] = parse_number(m.group(1), source, n)
        m = _NAME.match(line)
        if m:
            pending_name = "" if m.group(1) == "-" else m.group(1)
        if not line or line.startswith((";", "%", "CHANDATA", "M17", "M30")) or \
                _MD10240.match(line):
            continue
        m = _VALUE.match(line)
        if m:
            ax, i = m.group(3), int(m.group(2))
            _once(values.setdefault(ax, {}), i, f"{ax}: $AA_ENC_COMP point {i}", source, n)
            values[ax][i] = parse_number(m.group(4).split(";")[0], source, n)
            if pending_name and ax not in names:
                names[ax] = pending_name
            continue
        m = _PARAM.match(line)
        if m:
            ax = m.group(3)
            _once(params.setdefault(ax, {}), m.group(1), f"{ax}: $AA_ENC_COMP_{m.group(1)}",
                  source, n)
            params[ax][m.group(1)] = parse_number(m.group(4).split(";")[0], source, n)
            continue
        raise DataFormatError(f"not a $AA_ENC_COMP line: {raw[:60]!r}", source, n)
    if not values:
        raise DataFormatError("no $AA_ENC_COMP values: not an EEC table", source)
    out = {}
    for ax in values:
        b = backlash.get(ax, backlash.get("") if len(values) == 1 else None)
        out[ax] = _one_axis(values[ax], params.get(ax, {}), b, ax, names.get(ax, ""), axis_kind,
                            correction_unit, source, per)
    return out


def inputs(text: str, source: str = "<text>", unit: str | None = None, **_) -> tuple:
    """The file's length unit (MD10240): stated in the file, given as ``unit``, or mm assumed.

    A ``unit`` that contradicts the file's statement, or a file stating MD10240 twice
    differently, is refused (:class:`DataFormatError`).
    """
    stated = None
    for n, raw in enumerate(text.splitlines(), 1):
        m = _MD10240.match(raw.strip())
        if not m:
            continue
        v = {"0": "inch", "false": "inch", "1": "mm", "true": "mm"}.get(m.group(1).lower())
        if v is None or stated not in (None, v):
            raise DataFormatError(f"MD10240 $MN_SCALING_SYSTEM_IS_METRIC = {m.group(1)[:20]!r}"
                                  + ("" if v is None else " contradicts an earlier line")
                                  + " (1: metric, 0: inch)", source, n)
        stated = v
    given = None if unit is None else ("inch" if file_unit(unit, None, NAME) != 1.0 else "mm")
    said = f"the file states MD10240 $MN_SCALING_SYSTEM_IS_METRIC = {0 if stated == 'inch' else 1}"
    return (resolve_input("unit", given, stated, "mm", said=said, source=source,
                          why="the file does not state MD10240 (a metric machine, MD10240 = 1, "
                              "assumed)"),)


def _one_axis(values, params, backlash, machine_axis, name, axis_kind, correction_unit, source,
              per=1.0):
    for key in ("STEP", "MIN", "MAX"):
        if key not in params:
            raise DataFormatError(f"$AA_ENC_COMP_{key} of {machine_axis} is missing", source)
    if sorted(values) != list(range(len(values))):
        raise DataFormatError(f"interpolation points of {machine_axis} must be numbered 0, 1, 2 "
                              "… without gaps", source)
    modulo = bool(params.get("IS_MODULO", 0))
    kind = AxisKind.parse(axis_kind or ("rotary" if modulo else "linear"))
    pu = "mm" if kind is AxisKind.LINEAR else "deg"
    cu = correction_unit or ("um" if kind is AxisKind.LINEAR else "arcsec")
    per = per if kind is AxisKind.LINEAR else 1.0     # degrees in either basic system
    dev = np.array([values[i] for i in range(len(values))]) * per
    span = (len(dev) - 1) * params["STEP"]
    if abs(params["MIN"] + span - params["MAX"]) > 1e-6 * max(1.0, abs(span)):
        raise DataFormatError(f"{machine_axis}: MIN {params['MIN']:g} + {len(dev) - 1} x STEP "
                              f"{params['STEP']:g} does not reach MAX {params['MAX']:g}", source)
    try:
        t = CompensationTable(name or machine_axis, kind, pu, cu, _mm(params["MIN"], per),
                              _mm(params["STEP"], per), dev, dev, modulo=modulo)
    except ControllerLimitError:
        raise
    except InputError as exc:  # the table's own validation of what the file declared
        raise DataFormatError(str(exc), source) from None
    t = replace(t, up=np.round(-dev / correction_factor(t, pu), 6) + 0.0,
                down=np.round(-dev / correction_factor(t, pu), 6) + 0.0)
    return t if backlash is None else _with_backlash(t, backlash * per / correction_factor(t, pu))


def _mm(v: float, per: float) -> float:
    """A position of the file in mm: inch x 25.4, rounded to 1e-9 mm (the 12 decimals of inch
    :func:`write` gives a position leave a few 1e-11 mm)."""
    return v if per == 1.0 else float(np.round(v * per, 9))


def _once(seen: dict, key, what: str, source: str, line: int) -> None:
    """Refuse a value given twice (a second axis or a repeated line would overwrite silently)."""
    if key in seen:
        raise DataFormatError(f"{what} is given twice", source, line)


def _with_backlash(table: CompensationTable, md32450: float) -> CompensationTable:
    """Mean table plus a backlash value (correction unit) -> up/down tables (B̄ = −MD32450)."""
    half = 0.5 * md32450
    return replace(table, up=np.round(table.mean + half, 6) + 0.0,
                   down=np.round(table.mean - half, 6) + 0.0, bidirectional=True)


def _check(table, travel, max_points, position_resolution, per=1.0) -> None:
    require_equidistant(table, NAME)
    check_points(table.n_points, max_points, NAME, "points (MD38000)")
    check_spacing(table.spacing / per, position_resolution,
                  table.position_unit if per == 1.0 else "inch", NAME)
    check_travel(table, travel, NAME)
    check_modulo(table, NAME)
    if table.modulo and abs(table.start) > 1e-9:
        raise ControllerLimitError(f"{NAME}: a modulo table must start at 0 deg, not "
                                   f"{table.start:g} deg")


def _fmt(v: float, nd: int = 9) -> str:
    s = f"{v:.{nd}f}".rstrip("0")
    return s + "0" if s.endswith(".") else s


# -- cross-axis (sag / angularity) compensation: the CEC table -------------------------------
_CEC_VALUE = re.compile(r"^\$AN_CEC\[\s*(\d{1,9})\s*,\s*(\d{1,9})\s*\]\s*=\s*(\S+)")
_CEC_PARAM = re.compile(r"^\$AN_CEC_([A-Z_]+)\[\s*(\d{1,9})\s*\]\s*=\s*(\S+)")


def write_cross_axis(table: CompensationTable, travel=None, *, input_axis: str = "AX1",
                     output_axis: str = "AX2", table_index: int = 0, max_points: int = MAX_POINTS,
                     position_resolution: float = 0.001) -> ControllerFile:
    """Write a cross-axis table (positions of the base axis, corrections of the compensation axis)
    as a sag/angularity compensation file ``%_N_NC_CEC_INI``.

    Format (SINUMERIK 802D sl / 840D sl Function Manual K3, "Compensation of sag and angularity
    errors", table example for axis Y1)::

        %_N_NC_CEC_INI
        CHANDATA(1)
        $AN_CEC[0,0]=0              ; value at interpolation point 0, mm
        ...
        $AN_CEC_INPUT_AXIS[0]=(AX2)  ; base axis (drives the table)
        $AN_CEC_OUTPUT_AXIS[0]=(AX1) ; compensation axis (receives the values)
        $AN_CEC_STEP[0]=6.73
        $AN_CEC_MIN[0]=-400.0
        $AN_CEC_MAX[0]=400.0
        $AN_CEC_DIRECTION[0]=0       ; both directions of the base axis
        $AN_CEC_MULT_BY_TABLE[0]=0
        $AN_CEC_IS_MODULO[0]=0
        M17

    Enabling: MD18342 ``$MN_MM_CEC_MAX_POINTS[t]`` ≥ points, MD32710 ``$MA_CEC_ENABLE[AXi]`` = 1
    for the compensation axis, SD41300 ``$SN_CEC_TABLE_ENABLE[t]`` = 1. Sign: written like the
    EEC table, file value = −correction; that the CEC uses the same sign as the EEC is not
    confirmed.
    """
    check_fields(NAME, FIELDS, input_axis=input_axis, output_axis=output_axis,
                 table_index=table_index, max_points=max_points)
    check_points(table.n_points, max_points, NAME, "points (MD18342)")
    check_spacing(table.spacing, position_resolution, table.position_unit, NAME)
    check_travel(table, travel, NAME)
    k = correction_factor(table, table.position_unit)
    nd = decimals(table.position_unit)
    values = np.round(-table.mean * k, nd) + 0.0
    t = int(table_index)
    lines = ["%_N_NC_CEC_INI", "CHANDATA(1)",
             f"; axiscal cross-axis table: {output_axis} corrected as a function of {input_axis}, "
             f"values = -correction in {table.position_unit}"]
    lines += [f"$AN_CEC[{t},{i}]={_fmt(v)}" for i, v in enumerate(values)]
    lines += [f"$AN_CEC_INPUT_AXIS[{t}]=({input_axis})", f"$AN_CEC_OUTPUT_AXIS[{t}]=({output_axis})",
              f"$AN_CEC_STEP[{t}]={_fmt(table.spacing)}", f"$AN_CEC_MIN[{t}]={_fmt(table.start)}",
              f"$AN_CEC_MAX[{t}]={_fmt(table.end)}", f"$AN_CEC_DIRECTION[{t}]=0",
              f"$AN_CEC_MULT_BY_TABLE[{t}]=0", f"$AN_CEC_IS_MODULO[{t}]=0", "M17"]
    enable = [f"MD18342 $MN_MM_CEC_MAX_POINTS[{t}] >= {table.n_points} (power-on re-formats memory)",
              f"MD32710 $MA_CEC_ENABLE[{output_axis}] = 1 (load the table while it is 0)",
              f"SD41300 $SN_CEC_TABLE_ENABLE[{t}] = 1"]
    as_file = np.round(-values / k, 6) + 0.0
    written = replace(table, up=as_file, down=as_file, bidirectional=False)
    return ControllerFile(NAME, "\n".join(lines) + "\n", "NC_CEC.INI", written, tuple(enable))


def parse_cross_axis(text: str, source: str = "<text>", correction_unit: str = "um"):
    """Read a ``%_N_NC_CEC_INI`` table: (table, input axis, output axis) of its first table."""
    values: dict[int, float] = {}
    params: dict[str, str] = {}
    for n, raw in enumerate(text.splitlines(), 1):
        line = raw.split(";")[0].strip()
        if not line or line.startswith(("%", "CHANDATA", "M17", "M30")):
            continue
        m = _CEC_VALUE.match(line)
        if m:
            values[int(m.group(2))] = parse_number(m.group(3), source, n)
            continue
        m = _CEC_PARAM.match(line)
        if m:
            params[m.group(1)] = m.group(3).strip("()")
            continue
        raise DataFormatError(f"not a $AN_CEC line: {raw[:60]!r}", source, n)
    for key in ("INPUT_AXIS", "OUTPUT_AXIS", "STEP", "MIN", "MAX"):
        if key not in params:
            raise DataFormatError(f"$AN_CEC_{key} is missing", source)
    if len(values) < 2 or sorted(values) != list(range(len(values))):
        raise DataFormatError("interpolation points must be numbered 0, 1, 2 … without gaps", source)
    dev = np.array([values[i] for i in range(len(values))])
    try:
        step, lo = float(params["STEP"]), float(params["MIN"])
        t = CompensationTable("", AxisKind.LINEAR, "mm", correction_unit, lo, step, dev, dev)
    except ValueError as exc:
        raise DataFormatError(str(exc), source) from None
    c = np.round(-dev / correction_factor(t, "mm"), 6) + 0.0
    return replace(t, up=c, down=c), params["INPUT_AXIS"], params["OUTPUT_AXIS"]
