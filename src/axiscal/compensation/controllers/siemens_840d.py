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
from dataclasses import dataclass, replace

import numpy as np

from axiscal.compensation.controllers._common import (
    ControllerFile, check_modulo, check_points, check_spacing, check_travel,
    correction_factor, decimals, file_unit, parse_number, require_equidistant, resolve_input,
    safe_axis_name, WORD, COUNT, check_fields)
from axiscal.compensation.controllers.siemens_text import fmt as _fmt
from axiscal.compensation.controllers.siemens_cec import (  # noqa: F401 - the CEC tables
    CECTable, parse_cross_axis, read_cross_axis, write_cross_axis)
from axiscal.compensation.controllers.siemens_cec import FIELDS as _cec_fields
from axiscal.compensation.tables import CompensationTable, TableOrigin
from axiscal.datasets import AxisKind
from axiscal.errors import ControllerLimitError, DataFormatError, InputError
from axiscal.units import display

__all__ = ["NAME", "write", "write_axes", "parse", "parse_axes", "read_tables", "EECFile",
           "inputs", "MAX_POINTS", "read_cross_axis", "write_cross_axis", "parse_cross_axis"]

NAME = "siemens-840d"
#: Default MD38000 limit (not confirmed; the machine's MD38000 value is the real limit).
MAX_POINTS = 5000

_VALUE = re.compile(r"^\$AA_ENC_COMP\[\s*(\d{1,9})\s*,\s*(\d{1,9})\s*,\s*([A-Za-z0-9_]+)\s*\]\s*=\s*(\S+)")
_BACKLASH = re.compile(r"MD32450\s+\$MA_BACKLASH\[[^\]]*\]\s*=\s*(\S+)")
_NAME = re.compile(r"^;\s*axiscal: axis (\S+),")
_MD10240 = re.compile(r"^(?:;\s*MD10240\s+)?\$MN_SCALING_SYSTEM_IS_METRIC\s*=\s*(\S+?)(?::|\s|$)")


#: The grammar of every option :func:`write`, :func:`write_axes` and the cross-axis writer
#: (:data:`axiscal.compensation.controllers.siemens_cec.FIELDS`) write into the file
#: (:func:`~axiscal.compensation.controllers._common.check_fields`).
FIELDS = {"machine_axis": WORD, "max_points": COUNT, **_cec_fields}


def write(table: CompensationTable, travel=None, *, machine_axis: str | None = None,
          max_points: int = MAX_POINTS, position_resolution: float = 0.001,
          zero_at_reference: bool = True, zero_ends: bool = False,
          unit: str | None = None, measuring_system: int | None = None) -> ControllerFile:
    """Write ``table`` as a ``%_N_AX_EEC_INI`` file for ``machine_axis``.

    Parameters
    ----------
    table : CompensationTable
        Positions in mm (linear) or deg (rotary).
    travel : (float, float), optional, ``table.position_unit``
        Axis travel; the table must lie inside it.
    machine_axis : str, optional
        Machine axis name in the file (``AX1``, ``X1`` ...); default: the axis the table was
        read from (:attr:`CompensationTable.origin` of an 840D table), else ``AX1``.
    max_points : int
        MD38000 ``$MA_MM_ENC_COMP_MAX_POINTS``.
    position_resolution : float, mm, inch or deg
        The spacing must be a whole multiple of this, in the file's unit.
    zero_at_reference : bool
        Shift the table so the value at its reference point is 0 (Siemens' advice).
    zero_ends : bool
        Set the first and last values to 0 (see the module docstring).
    unit : str, optional
        ``mm`` or ``inch``: the machine's basic system (MD10240 = 1 or 0) for a linear axis;
        default: the unit of the 840D file the table was read from, else mm.
    measuring_system : int, optional
        1 or 2 (the first index 0 or 1, MD32700 per measuring system); default: the one the
        table was read from, else 1.

    Returns
    -------
    ControllerFile
    """
    machine_axis, measuring_system, unit = _own(table, machine_axis, measuring_system, unit)
    check_fields(NAME, FIELDS, machine_axis=machine_axis, max_points=max_points)
    per = file_unit(unit, table, NAME)
    _check(table, travel, max_points, position_resolution, per)
    body, enable, written, notes = _axis_block(table, machine_axis, zero_at_reference, zero_ends,
                                               per, measuring_system)
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
    for ax, table in tables.items():
        check_fields(NAME, FIELDS, machine_axis=ax, max_points=mp)
        tr = travel.get(ax) if isinstance(travel, dict) else travel
        _, ms, unit = _own(table, ax, options.get("measuring_system"), options.get("unit"))
        _check(table, tr, mp, res, file_unit(unit, table, NAME))
        b, e, _, n = _axis_block(table, ax, options.get("zero_at_reference", True),
                                 options.get("zero_ends", False), file_unit(unit, table, NAME), ms)
        body += b
        enable += e
        notes += n
    text = "\n".join(["%_N_AX_EEC_INI", "CHANDATA(1)", *body, "M17"]) + "\n"
    first = next(iter(tables.values()))
    return ControllerFile(NAME, text, "AX_EEC.INI", first, tuple(enable), notes=tuple(notes))


def _own(table, machine_axis, measuring_system, unit):
    """Machine axis, measuring system and unit: given, else those of the 840D file the table was
    read from (so a converted table lands on its own axis), else AX1, 1 and mm."""
    o = table.origin if getattr(table.origin, "controller", "") == NAME else None
    if machine_axis is None:
        machine_axis = o.machine_axis if o and o.machine_axis else "AX1"
    if measuring_system is None:
        measuring_system = o.measuring_system if o and o.measuring_system else 1
    if str(measuring_system) not in ("1", "2"):
        raise InputError(f"{NAME}: measuring_system = {measuring_system!r}; 1 or 2")
    if unit is None:
        unit = o.unit if o and o.unit == "inch" else "mm"
    return str(machine_axis), int(measuring_system), unit


def _axis_block(table, machine_axis, zero_at_reference, zero_ends, per=1.0, ms=1):
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
    e = ms - 1                                       # measuring system 1 -> index 0
    lines += [f"$AA_ENC_COMP[{e},{i},{ax}]={_fmt(v)}" for i, v in enumerate(values)]
    nd_pos = 9 if per == 1.0 else 12
    lines += [f"$AA_ENC_COMP_STEP[{e},{ax}]={_fmt(table.spacing / per, nd_pos)}",
              f"$AA_ENC_COMP_MIN[{e},{ax}]={_fmt(table.start / per, nd_pos)}",
              f"$AA_ENC_COMP_MAX[{e},{ax}]={_fmt(table.end / per, nd_pos)}",
              f"$AA_ENC_COMP_IS_MODULO[{e},{ax}]={1 if table.modulo else 0}"]
    enable = [f"MD38000 $MA_MM_ENC_COMP_MAX_POINTS[{e},{ax}] >= {table.n_points} "
              "(memory is re-formatted at the next power-on)",
              f"load the file while MD32700 $MA_ENC_COMP_ENABLE[{e},{ax}] = 0",
              f"then MD32700 $MA_ENC_COMP_ENABLE[{e},{ax}] = 1 and reference the axis"]
    enable += [f"{m} on the machine (the file's values, STEP, MIN and MAX are in {fu})"
               for m in metric]
    if table.bidirectional:
        b = np.round(-table.backlash * k, nd) + 0.0
        lines.append(f"; MD32450 $MA_BACKLASH[{e},{ax}]={_fmt(b)}")
        enable.append(f"MD32450 $MA_BACKLASH[{e},{ax}] = {_fmt(b)} {fu} "
                      "(mean reversal; the table holds the mean of both directions)")
    as_file = np.round(-values / k, 6) + 0.0          # what the file holds, back in the table's unit
    kind_from = table.origin.kind_from if table.origin is not None else ""
    written = replace(table, up=as_file, down=as_file, bidirectional=False,
                      origin=TableOrigin(NAME, ax, ms, fu, kind_from))
    if table.bidirectional:
        written = _with_backlash(written, b / k)
    return lines, enable, written, notes


def parse(text: str, source: str = "<text>", axis_kind: "AxisKind | str | None" = None,
          axis: str = "", correction_unit: str | None = None,
          machine_axis: str | None = None, unit: str | None = None,
          measuring_system: int | None = None, machine_data: str = "") -> CompensationTable:
    """Read one table of an EEC file back (corrections = −file values).

    ``machine_axis`` (``AX4`` or its name ``C1``) and ``measuring_system`` (1 or 2) choose the
    table of a file holding several (they must then be given); another table that cannot be
    read does not stop this one. ``axis_kind`` defaults to the machine data's (MD30300,
    ``machine_data`` = the text of an ``INITIAL.INI``), else rotary if the table is modulo,
    else linear (said by :func:`read_tables` as an assumption). Corrections come back in
    ``correction_unit`` (default µm or arcsec). A ``; MD32450`` comment written by :func:`write`
    makes the table bidirectional again (mean ± backlash/2); a ``; axiscal: axis X`` comment
    gives the axis name back. ``unit`` (``mm`` or ``inch``) is the machine's basic system
    (MD10240); the file's own statement of it (``METRIC``/``INCH`` or MD10240) wins, and a
    ``unit`` contradicting it is refused.
    """
    r = read_tables(text, source, axis_kind=axis_kind, correction_unit=correction_unit,
                    unit=unit, machine_data=machine_data)
    keys = list(r.tables) + list(r.refused)
    if machine_axis is None and measuring_system is None and len(keys) > 1:
        axes = len({k[0] for k in keys})
        what = (f"{len(keys)} tables of {axes} machine axes" if axes < len(keys)
                else f"the tables of {axes} machine axes")
        raise DataFormatError(f"the file holds {what} ({', '.join(map(_key, keys))}): choose one "
                              "with machine_axis= (AX1/2: measuring system 2 of AX1)", source)
    want = [k for k in keys if _matches(k, machine_axis, measuring_system, r.md)]
    if not want:
        raise DataFormatError(f"no table for {_wanted(machine_axis, measuring_system)}; the file "
                              f"holds {', '.join(map(_key, keys))}", source)
    if len(want) > 1:
        raise DataFormatError(f"{machine_axis} has a table for each measuring system: give "
                              "measuring_system=1 or 2", source)
    if want[0] in r.refused:
        raise DataFormatError(r.refused[want[0]], source)
    t = r.tables[want[0]]
    return replace(t, axis=axis) if axis else t


def parse_axes(text: str, source: str = "<text>", axis_kind=None,
               correction_unit: str | None = None, unit: str | None = None,
               machine_data: str = "") -> dict:
    """Every table of an EEC file by machine axis (``AX1``; ``AX1/2`` for measuring system 2).

    Positions come back in mm (deg), whatever the file's unit (see :func:`inputs`). A table that
    cannot be read is refused naming it; :func:`read_tables` reads the others regardless.
    """
    r = read_tables(text, source, axis_kind=axis_kind, correction_unit=correction_unit,
                    unit=unit, machine_data=machine_data)
    if r.refused:
        raise DataFormatError("; ".join(r.refused.values()), source)
    return {_key(k): t for k, t in r.tables.items()}


@dataclass(frozen=True)
class EECFile:
    """What :func:`read_tables` found in an EEC file or loader program.

    Attributes
    ----------
    tables : dict of (str, int) to CompensationTable
        By (machine axis as written, measuring system 1 or 2).
    refused : dict of (str, int) to str
        The tables that cannot be read, each with its reason (the others are read regardless).
    notes : tuple of str
        What was read, assumed or left out (control statements of a loader program, points
        reserved but unused, where each axis kind came from).
    md : MachineData
        The machine data used (given beside, or held in the file itself).
    """

    tables: dict
    refused: dict
    notes: tuple
    md: object

    @staticmethod
    def key(k) -> str:
        """``AX1`` (measuring system 1) or ``AX1/2`` (measuring system 2)."""
        return _key(k)


def read_tables(text: str, source: str = "<text>", axis_kind=None,
                correction_unit: str | None = None, unit: str | None = None,
                machine_data: str = "", machine_data_source: str = "the machine data") -> EECFile:
    """Every ``$AA_ENC_COMP`` table of a file as the control writes it, one bad table not
    blocking the others.

    Reads the NCK's headers (``%_N_…``, ``METRIC``/``INCH``, ``CHANDATA``), ``M17``/``M30``,
    comments and CRLF (:mod:`~axiscal.compensation.controllers.siemens_text`); a loader
    program's ``NEWCONF``, ``STOPRE``, ``MSG``, ``G4`` and machine-data assignments are named in
    the notes and left out. Each table is keyed by machine axis and measuring system (the first
    index: 0 = measuring system 1, 1 = measuring system 2, MD32700 per measuring system; SINUMERIK
    840D sl Function Manual K3, "Measuring system-specific parameters of the compensation
    table"), so the values of one are never combined with STEP/MIN/MAX of the other.

    Notes
    -----
    K3: ``$AA_ENC_COMP_MAX`` is the end position, interpolation point *k* with
    k = (MAX − MIN)/STEP; the control applies point k's value beyond it. MD38000 reserves
    points 0 … MD38000−1 and a series start-up file lists them all: points after *k* are not
    used (said in the notes, and named if they are not 0). A range that is not a whole number
    of steps, or a *k* beyond the points given, refuses that table only.
    """
    from axiscal.compensation.controllers import siemens_machine_data as smd
    from axiscal.compensation.controllers.siemens_text import said as left_out
    from axiscal.compensation.controllers.siemens_text import statements

    own = smd.parse(text, source)
    md = smd.parse(machine_data, machine_data_source) if machine_data else own
    notes: list[str] = []
    said = inputs(text, source, unit=unit)[0]
    if said.assumed and md.metric is not None:      # the machine data's MD10240 decides
        said = inputs(text, source, unit="mm" if md.metric else "inch")[0]
        notes.append(f"unit {said.value}: MD10240 $MN_SCALING_SYSTEM_IS_METRIC = "
                     f"{int(md.metric)} in {md.source}")
    per = file_unit(said.value, None, NAME)
    values: dict = {}
    params: dict = {}
    for s in statements(text, source):
        if left_out(s):
            notes.append(left_out(s))
        elif s.kind == "assign" and s.name == "AA_ENC_COMP" and len(s.index) == 3:
            key = (s.index[2], _ms(s.index[0], source, s.line))
            i = _index(s.index[1], source, s.line)
            _once(values.setdefault(key, {}), i, f"{_key(key)}: $AA_ENC_COMP point {i}", source,
                  s.line)
            values[key][i] = parse_number(s.value, source, s.line)
        elif s.kind == "assign" and s.name.startswith("AA_ENC_COMP_") and len(s.index) == 2:
            what = s.name[len("AA_ENC_COMP_"):]
            if what not in ("STEP", "MIN", "MAX", "IS_MODULO"):
                raise DataFormatError(f"${s.name} is not a parameter of the EEC table", source,
                                      s.line)
            key = (s.index[1], _ms(s.index[0], source, s.line))
            _once(params.setdefault(key, {}), what, f"{_key(key)}: $AA_ENC_COMP_{what}", source,
                  s.line)
            params[key][what] = parse_number(s.value, source, s.line)
        elif s.kind == "assign" and s.name.startswith(("MA_", "MN_", "MC_", "SN_", "SA_")):
            continue                           # other machine and setting data: passed over
        elif s.kind == "assign" and s.name.startswith("AN_CEC"):
            continue                           # cross-axis tables: read_cross_axis reads them
        elif s.kind in ("assign", "user"):
            what = f"${s.name}" if s.kind == "assign" else f"{s.name} (a user variable)"
            raise DataFormatError(f"{what} is not a compensation table variable axiscal reads "
                                  "($AA_ENC_COMP…, $AN_CEC…, machine data)", source, s.line)
    if not values:
        raise DataFormatError("no $AA_ENC_COMP values: not an EEC table", source)
    extra = _comments(text, source)
    tables, refused = {}, {}
    for key in values:
        try:
            t, n = _one_axis(values[key], params.get(key, {}), extra, key, axis_kind, md,
                             correction_unit, source, per)
        except DataFormatError as exc:
            refused[key] = f"{_key(key)}: {exc.message if hasattr(exc, 'message') else exc}"
            continue
        tables[key] = t
        notes += n
    refused.update(_without_values(values, params, tables))
    return EECFile(tables, refused, tuple(notes), md)


def _without_values(values: dict, params: dict, read: dict) -> dict:
    """The reason of each table whose STEP/MIN/MAX come without values; a loader writing one
    measuring system's values with the other's STEP/MIN/MAX (a real builder's ``.MPF``) has
    both halves named so, never combined (K3: the table is kept per measuring system)."""
    refused = {key: f"{_key(key)}: STEP/MIN/MAX given but no $AA_ENC_COMP values"
               for key in params if key not in values}
    for (ax, ms) in values:
        other = (ax, 3 - ms)
        if other in refused and (ax, ms) not in params and (ax, ms) not in read:
            why = (f"the values are for measuring system {ms} ([{ms - 1},…]), STEP/MIN/MAX "
                   f"for measuring system {3 - ms} ([{2 - ms},…]); axiscal does not combine them "
                   "(MD32700 and the table are kept per measuring system, K3)")
            refused[(ax, ms)], refused[other] = f"{_key((ax, ms))}: {why}", f"{_key(other)}: {why}"
    return refused


def _key(k) -> str:
    ax, ms = k
    return ax if ms == 1 else f"{ax}/{ms}"


def _matches(k, machine_axis, measuring_system, md) -> bool:
    ax, ms = k
    if measuring_system is not None and int(measuring_system) != ms:
        return False
    if machine_axis is None:
        return True
    want = str(machine_axis).strip().upper()
    if "/" in want:
        want, _, m = want.partition("/")
        if m.strip() != str(ms):
            return False
    return ax.upper() == want or md.machine_axis(ax) == md.machine_axis(want)


def _wanted(machine_axis, measuring_system) -> str:
    ms = f", measuring system {measuring_system}" if measuring_system is not None else ""
    if machine_axis is None:
        return f"measuring system {measuring_system}"
    return f"machine axis {machine_axis!r}{ms}"


def _ms(token: str, source: str, line: int) -> int:
    """Measuring system 1 or 2 from the first index (0 or 1)."""
    if token not in ("0", "1"):
        raise DataFormatError(f"measuring-system index {token[:10]!r}: 0 (measuring system 1) or "
                              "1 (measuring system 2)", source, line)
    return int(token) + 1


def _index(token: str, source: str, line: int) -> int:
    if not re.fullmatch(r"[0-9]{1,9}", token):
        raise DataFormatError(f"interpolation point {token[:12]!r} is not a whole number", source,
                              line)
    return int(token)


def _comments(text: str, source: str) -> dict:
    """What :func:`write` says in comments: MD32450 backlash and the axis name, by axis."""
    backlash, names, pending = {}, {}, ""
    for n, raw in enumerate(text.splitlines(), 1):
        line = raw.strip()
        m = _BACKLASH.search(line)
        if m:
            ax = re.search(r"\[\s*\d+\s*,\s*([A-Za-z0-9_]+)\s*\]", line)
            backlash[ax.group(1) if ax else ""] = parse_number(m.group(1), source, n)
        m = _NAME.match(line)
        if m:
            pending = "" if m.group(1) == "-" else m.group(1)
        m = _VALUE.match(line)
        if m and pending and m.group(3) not in names:
            names[m.group(3)] = pending
    return dict(backlash=backlash, names=names)


def inputs(text: str, source: str = "<text>", unit: str | None = None, *,
           metric: bool | None = None, metric_source: str = "the machine data", **_) -> tuple:
    """The file's length unit: stated in the file (``METRIC``/``INCH`` header or MD10240),
    given as ``unit``, stated by the machine data given beside it (``metric``: MD10240 of the
    ``INITIAL.INI``, from ``metric_source``), or mm assumed.

    A ``unit`` that contradicts the file's statement, or a file stating it twice differently,
    is refused (:class:`DataFormatError`).
    """
    stated, said = None, ""
    for n, raw in enumerate(text.splitlines(), 1):
        line = re.sub(r"^N\d+\s+", "", raw.strip(), flags=re.IGNORECASE)
        m = _MD10240.match(line)
        head = line.split(";")[0].strip().upper()
        if m:
            v = {"0": "inch", "false": "inch", "1": "mm", "true": "mm"}.get(m.group(1).lower())
            what = f"MD10240 $MN_SCALING_SYSTEM_IS_METRIC = {m.group(1)[:20]}"
            if v is None:
                raise DataFormatError(f"MD10240 $MN_SCALING_SYSTEM_IS_METRIC = {m.group(1)[:20]!r}"
                                      " (1: metric, 0: inch)", source, n)
        elif head in ("METRIC", "INCH"):
            v, what = ("mm" if head == "METRIC" else "inch"), f"the header line {head}"
        else:
            continue
        if stated not in (None, v):
            raise DataFormatError(f"{what} contradicts an earlier line ({said})", source, n)
        stated, said = v, what
    from_md = stated is None and metric is not None
    if from_md:
        stated = "mm" if metric else "inch"
        said = f"MD10240 $MN_SCALING_SYSTEM_IS_METRIC = {int(metric)} in {metric_source}"
    given = None if unit is None else ("inch" if file_unit(unit, None, NAME) != 1.0 else "mm")
    return (resolve_input("unit", given, stated, "mm",
                          said=said if from_md else f"the file states {said}",
                          source=source,
                          why="the file does not state its unit (no METRIC/INCH header, no "
                              "MD10240): a metric machine, MD10240 = 1, assumed"),)


def _one_axis(values, params, extra, key, axis_kind, md, correction_unit, source, per=1.0):
    """One table (and its notes) from its values and STEP/MIN/MAX/IS_MODULO."""
    machine_axis, ms = key
    name = _key(key)
    notes = []
    for p in ("STEP", "MIN", "MAX"):
        if p not in params:
            raise DataFormatError(f"$AA_ENC_COMP_{p} is missing", source)
    if sorted(values) != list(range(len(values))):
        raise DataFormatError("interpolation points must be numbered 0, 1, 2 … without gaps",
                              source)
    step, lo, hi = params["STEP"], params["MIN"], params["MAX"]
    if not step > 0:
        raise DataFormatError(f"$AA_ENC_COMP_STEP = {step:g} must be positive", source)
    k = (hi - lo) / step
    if abs(k - round(k)) > 1e-6 * max(1.0, abs(k)) or round(k) < 1:
        raise DataFormatError(f"(MAX {hi:g} − MIN {lo:g}) / STEP {step:g} = {k:.6g} is not a "
                              "whole number of steps of at least 1 (K3: MAX is interpolation "
                              "point k)", source)
    k = int(round(k))
    n = len(values)
    if k >= n:
        raise DataFormatError(f"MAX {hi:g} is interpolation point {k}, but the file gives points "
                              f"0 … {n - 1} only", source)
    unused = [values[i] for i in range(k + 1, n)]
    if unused:
        nonzero = sum(v != 0 for v in unused)
        notes.append(f"{name}: {_points(k + 1, n - 1)} ({n - k - 1} of {n}, reserved by MD38000) "
                     f"{'is' if k + 2 == n else 'are'} not used: the table ends at point {k} = "
                     f"MAX {hi:g}"
                     + (f"; {nonzero} of them hold values the control does not apply"
                        if nonzero else ""))
    reserved = md.max_points.get((md.machine_axis(machine_axis), ms - 1))
    if reserved is not None and n > reserved:
        raise DataFormatError(f"{n} points but MD38000 $MA_MM_ENC_COMP_MAX_POINTS[{ms - 1},"
                              f"{machine_axis}] = {reserved}", source)
    modulo = bool(params.get("IS_MODULO", 0))
    kind, kind_from = _kind(machine_axis, axis_kind, modulo, md, name, notes)
    pu = "mm" if kind is AxisKind.LINEAR else "deg"
    cu = correction_unit or ("um" if kind is AxisKind.LINEAR else "arcsec")
    per = per if kind is AxisKind.LINEAR else 1.0     # degrees in either basic system
    dev = np.array([values[i] for i in range(k + 1)]) * per
    label = extra["names"].get(machine_axis) or md.names.get(md.machine_axis(machine_axis)) \
        or machine_axis
    origin = TableOrigin(NAME, machine_axis, ms, "inch" if per != 1.0 else pu, kind_from)
    try:
        t = CompensationTable(label, kind, pu, cu, _mm(lo, per), _mm(step, per), dev, dev,
                              modulo=modulo, origin=origin)
    except ControllerLimitError:
        raise
    except InputError as exc:  # the table's own validation of what the file declared
        raise DataFormatError(str(exc), source) from None
    c = np.round(-dev / correction_factor(t, pu), 6) + 0.0
    t = replace(t, up=c, down=c)
    bl = extra["backlash"]
    b = bl.get(machine_axis, bl.get("") if len(bl) == 1 else None)
    return (t if b is None else _with_backlash(t, b * per / correction_factor(t, pu))), notes


def _points(a: int, b: int) -> str:
    return f"point {a}" if a == b else f"points {a} … {b}"


def _kind(machine_axis, axis_kind, modulo, md, name, notes):
    """The axis kind: given, from the machine data, modulo → rotary, or linear assumed."""
    if axis_kind is not None:
        return AxisKind.parse(axis_kind), "option"
    said = md.kind(machine_axis)
    if said is not None:
        kind, md_modulo, why = said
        notes.append(f"{name}: {why}")
        if md_modulo != modulo and kind == "rotary":
            notes.append(f"{name}: $AA_ENC_COMP_IS_MODULO = {int(modulo)} while MD30310 = "
                         f"{int(md_modulo)}: the table is read as the file says")
        return AxisKind.parse(kind), "machine data"
    if modulo:
        notes.append(f"{name}: rotary (the table is modulo, $AA_ENC_COMP_IS_MODULO = 1)")
        return AxisKind.ROTARY, "file"
    notes.append(f"assumed: {name} is linear (mm): the table is not modulo and no machine data "
                 "(MD30300 $MA_IS_ROT_AX) was given; a swivel axis is rotary without being "
                 "modulo: give the INITIAL.INI (--ini) or -o axis_kind=rotary")
    return AxisKind.LINEAR, "assumed"


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




