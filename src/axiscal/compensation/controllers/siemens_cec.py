"""SINUMERIK 840D: sag and angularity (cross-axis) compensation, the ``NC_CEC.INI`` tables.

Format (SINUMERIK 802D sl / 840D sl Function Manual *Extended Functions*, K3 "Compensation",
"Compensation of sag and angularity errors", table parameters; 03/2013 edition §4.4.4)::

    %_N_NC_CEC_INI
    CHANDATA(1)
    $AN_CEC[0,0]=0              ; value at interpolation point 0 of table 0, mm
    ...
    $AN_CEC_INPUT_AXIS[0]=(AX2)  ; base axis: its setpoint drives the table
    $AN_CEC_OUTPUT_AXIS[0]=(AX1) ; compensation axis: receives the values
    $AN_CEC_STEP[0]=6.73
    $AN_CEC_MIN[0]=-400.0        ; interpolation point 0
    $AN_CEC_MAX[0]=400.0         ; interpolation point k
    $AN_CEC_DIRECTION[0]=0       ; 0 both directions of the base axis, 1 / -1 one only
    $AN_CEC_MULT_BY_TABLE[0]=0   ; 0 or the number (index + 1) of a table to multiply by
    $AN_CEC_IS_MODULO[0]=0
    M17

A series start-up archive's ``NC_CEC.INI`` also holds, per table, ``$AN_CEC_INPUT_NCU`` and
``$AN_CEC_OUTPUT_NCU`` (the NCU that computes the base and the compensation axis, for an NCU
link) and ``$AN_CEC_TYPE`` (0 no special table type, 1 cylinder error compensation), as the
control's own description of these variables (``CECDescr``) names them: read, a type other than
0 and an NCU other than 1 said in the notes. A table the machine reserves but does not use
(STEP 0, every value 0, as the NCK lists it) is named as not in use, not read.

A file holds several tables (MD18342 ``$MN_MM_CEC_MAX_POINTS[t]`` reserves the points of table
t); each is its own relation (input axis, output axis, direction), so :func:`read_cross_axis`
reads them as separate tables, never merged.

**Range not a whole number of steps.** K3 names MAX the position of interpolation point k and
says the value of point k is used for all positions beyond it. Where (MAX − MIN)/STEP is not a
whole number no point lies at MAX; axiscal reads such a table with its points at MIN + i·STEP,
as the control spaces them, up to the last point k = ⌊(MAX − MIN)/STEP⌋ the file's range
reaches, and says so (the note gives MAX and the last point's position). This reading is
axiscal's: the manual does not say what the control does between point k and MAX.

Sign: written like the EEC table, file value = −correction; that the CEC uses the same sign as
the EEC is not confirmed.
"""

from __future__ import annotations

import math
import re
from dataclasses import dataclass, replace

import numpy as np

from axiscal.compensation.controllers._common import (
    COUNT, WORD, ControllerFile, check_fields, check_points, check_spacing, check_travel,
    correction_factor, decimals, parse_number, whole)
from axiscal.compensation.controllers.siemens_text import fmt as _fmt
from axiscal.compensation.tables import CompensationTable, TableOrigin
from axiscal.datasets import AxisKind
from axiscal.errors import DataFormatError, InputError
from axiscal.units import display

__all__ = ["CECTable", "read_cross_axis", "write_cross_axis", "parse_cross_axis", "NOT_IN_USE",
           "in_error", "loader_notes"]

NAME = "siemens-840d"
MAX_POINTS = 5000
_PARAMS = ("INPUT_AXIS", "OUTPUT_AXIS", "STEP", "MIN", "MAX", "DIRECTION", "MULT_BY_TABLE",
           "IS_MODULO", "INPUT_NCU", "OUTPUT_NCU", "TYPE")
#: How the reason of a reserved table that is not in use begins (after ``CEC table t: ``).
NOT_IN_USE = "not in use"
#: ``$AN_CEC_TYPE`` (the control's description of its system variables, ``CECDescr``)
_TYPES = {0: "no special table type", 1: "a cylinder error compensation table"}


@dataclass(frozen=True)
class CECTable:
    """One cross-axis table of an ``NC_CEC.INI``.

    Attributes
    ----------
    index : int
        The table index t of ``$AN_CEC[t,N]``.
    input_axis, output_axis : str
        Base axis (drives the table) and compensation axis (receives its values).
    table : CompensationTable
        Positions of the input axis (mm), corrections of the output axis (µm).
    direction : int
        ``$AN_CEC_DIRECTION``: 0 both directions, 1 positive only, −1 negative only.
    mult_by_table : int
        ``$AN_CEC_MULT_BY_TABLE``: 0, or the number of the table this one is multiplied by.
    notes : tuple of str
        Points reserved but unused, a range that is not a whole number of steps.
    """

    index: int
    input_axis: str
    output_axis: str
    table: CompensationTable
    direction: int = 0
    mult_by_table: int = 0
    notes: tuple = ()

    def to_dict(self) -> dict:
        return dict(index=self.index, input_axis=self.input_axis, output_axis=self.output_axis,
                    direction=self.direction, mult_by_table=self.mult_by_table,
                    notes=list(self.notes), table=self.table.to_dict())

    def __str__(self) -> str:
        t = self.table
        d = {0: "both directions", 1: "positive direction only", -1: "negative direction only"}
        return (f"CEC table {self.index}: {self.output_axis} corrected as a function of "
                f"{self.input_axis} ({d.get(self.direction, self.direction)}), {t.n_points} "
                f"points every {t.spacing:g} {display(t.position_unit)} from {t.start:g} to "
                f"{t.end:g} {display(t.position_unit)}, largest correction {t.largest:.4g} "
                f"{display(t.correction_unit)}")


def read_cross_axis(text: str, source: str = "<text>", correction_unit: str | None = None,
                    machine_data: str = "") -> tuple:
    """Every cross-axis table of a file, each with its axes: (tables, refused).

    ``tables`` is a list of :class:`CECTable` by index; ``refused`` maps the index of a table that
    cannot be read to its reason (the others are read regardless); a table reserved but not in
    use is there too, its reason beginning ``CEC table t: not in use`` (:func:`in_error` leaves
    it out). With ``machine_data`` (an
    ``INITIAL.INI``'s text; else the file's own machine data), a rotary input axis (MD30300) has
    its positions in degrees and a rotary output axis its values in degrees, read in arcsec;
    otherwise both are taken as linear (mm, µm), as the file does not say.
    """
    from axiscal.compensation.controllers import siemens_machine_data as smd

    md = smd.parse(machine_data, "the machine data") if machine_data else smd.parse(text, source)
    from axiscal.compensation.controllers.siemens_text import statements

    values: dict = {}
    params: dict = {}
    for s in statements(text, source):
        if s.kind == "user":
            raise DataFormatError(f"{s.name} (a user variable) is not a CEC table variable "
                                  "axiscal reads ($AN_CEC…, machine and setting data)", source,
                                  s.line)
        if s.kind == "assign" and not s.name.startswith(("AN_CEC", "MA_", "MN_", "MC_", "SN_",
                                                           "SA_", "SC_")):
            raise DataFormatError(f"${s.name} is not a CEC table variable axiscal reads "
                                  "($AN_CEC…, machine and setting data)", source, s.line)
        if s.kind != "assign" or not s.name.startswith("AN_CEC"):
            continue
        if s.name == "AN_CEC" and len(s.index) == 2:
            t, i = _whole(s.index[0], source, s.line), _whole(s.index[1], source, s.line)
            if i in values.setdefault(t, {}):
                raise DataFormatError(f"$AN_CEC[{t},{i}] is given twice", source, s.line)
            values[t][i] = parse_number(s.value, source, s.line)
        elif s.name[len("AN_CEC_"):] in _PARAMS and len(s.index) == 1:
            t = _whole(s.index[0], source, s.line)
            params.setdefault(t, {})[s.name[len("AN_CEC_"):]] = s.value.strip().strip("()")
        else:
            raise DataFormatError(f"${s.name}[{','.join(s.index)}] is not a CEC table variable",
                                  source, s.line)
    if not values:
        raise DataFormatError("no $AN_CEC values: not a cross-axis (CEC) table", source)
    tables, refused = [], {}
    for t in sorted(set(values) | set(params)):
        try:
            tables.append(_one_table(t, values.get(t, {}), params.get(t, {}), source, md,
                                     correction_unit))
        except DataFormatError as exc:
            refused[t] = f"CEC table {t}: {exc.message}"
    return tables, refused


def loader_notes(text: str, source: str = "<text>") -> tuple:
    """What a loader program does around its CEC tables, said and left out (``NEWCONF``,
    MD32710 ``$MA_CEC_ENABLE``, SD41300 ``$SN_CEC_TABLE_ENABLE`` …), one note per line."""
    from axiscal.compensation.controllers.siemens_text import said, statements

    return tuple(said(s) for s in statements(text, source) if said(s))


def in_error(refused: dict) -> dict:
    """The tables of ``refused`` that could not be read (a table not in use is not an error)."""
    return {t: r for t, r in refused.items() if not r.startswith(f"CEC table {t}: {NOT_IN_USE}")}


def _one_table(t, values, params, source, md, correction_unit) -> CECTable:
    for key in ("INPUT_AXIS", "OUTPUT_AXIS", "STEP", "MIN", "MAX"):
        if key not in params:
            raise DataFormatError(f"$AN_CEC_{key}[{t}] is missing", source)
    if not values or sorted(values) != list(range(len(values))):
        raise DataFormatError("interpolation points must be numbered 0, 1, 2 … without gaps",
                              source)
    try:
        step, lo, hi = (float(params[k]) for k in ("STEP", "MIN", "MAX"))
        direction, mult, modulo, ttype, in_ncu, out_ncu = (
            int(float(params.get(k, d))) for k, d in (
                ("DIRECTION", "0"), ("MULT_BY_TABLE", "0"), ("IS_MODULO", "0"), ("TYPE", "0"),
                ("INPUT_NCU", "1"), ("OUTPUT_NCU", "1")))
    except (ValueError, OverflowError):
        raise DataFormatError("STEP, MIN, MAX, DIRECTION, MULT_BY_TABLE, IS_MODULO, TYPE and the "
                              "NCUs must be numbers", source) from None
    modulo = bool(modulo)
    if step == 0 and lo == hi and not any(values.values()):
        raise DataFormatError(f"{NOT_IN_USE} (STEP 0, MIN = MAX = {lo:g}, every value 0; input "
                              f"axis {params['INPUT_AXIS']}, output axis "
                              f"{params['OUTPUT_AXIS']})", source)
    if not (math.isfinite(step) and step > 0 and math.isfinite(lo) and math.isfinite(hi)):
        raise DataFormatError(f"STEP {step:g} must be positive, MIN and MAX finite", source)
    span = (hi - lo) / step
    k = int(math.floor(span + 1e-6))
    notes = _type_and_ncu(ttype, in_ncu, out_ncu)
    if abs(span - round(span)) > 1e-6 * max(1.0, abs(span)):
        notes.append(f"(MAX {hi:g} − MIN {lo:g}) / STEP {step:g} = {span:.6g} is not a whole "
                     f"number of steps: read up to point {k} at {lo + k * step:g}, the last "
                     "point the range reaches (axiscal's reading; K3 does not say)")
    if modulo:
        notes.append("IS_MODULO = 1: the table repeats, point k followed by point 0 (K3 §4.4.4)")
    if k < 1:
        raise DataFormatError(f"MIN {lo:g} … MAX {hi:g} holds less than one STEP {step:g}",
                              source)
    n = len(values)
    if k >= n:
        raise DataFormatError(f"the range needs points 0 … {k}, the file gives 0 … {n - 1}",
                              source)
    if k + 1 < n:
        nonzero = sum(values[i] != 0 for i in range(k + 1, n))
        notes.append((f"point {n - 1} is" if k + 2 == n else f"points {k + 1} … {n - 1} are")
                     + " reserved by MD18342 but not used"
                     + (f"; {nonzero} of them hold values the control does not apply"
                        if nonzero else ""))
    dev = np.array([values[i] for i in range(k + 1)])
    out_axis = params["OUTPUT_AXIS"]
    rot_in = (md.kind(params["INPUT_AXIS"]) or ("linear",))[0] == "rotary"
    rot_out = (md.kind(out_axis) or ("linear",))[0] == "rotary"
    kind, pu = (AxisKind.ROTARY, "deg") if rot_in else (AxisKind.LINEAR, "mm")
    vu = "deg" if rot_out else "mm"                       # the file's values
    cu = correction_unit or ("arcsec" if rot_out else "um")
    try:
        tab = CompensationTable(out_axis, kind, pu, cu, lo, step, dev,
                                dev, origin=TableOrigin(NAME, out_axis, None, pu, "file"))
    except InputError as exc:
        raise DataFormatError(str(exc), source) from None
    c = np.round(-dev / correction_factor(tab, vu), 6) + 0.0
    return CECTable(t, params["INPUT_AXIS"], out_axis, replace(tab, up=c, down=c), direction,
                    mult, tuple(notes))


def _type_and_ncu(ttype: int, in_ncu: int, out_ncu: int) -> list:
    """Notes for a table type other than 0 and an NCU other than 1 (an NCU link)."""
    notes = []
    if ttype != 0:
        notes.append(f"$AN_CEC_TYPE = {ttype}: {_TYPES.get(ttype, 'a type axiscal does not know')}"
                     " (read as a table of values; axiscal does not model the type)")
    if (in_ncu, out_ncu) != (1, 1):
        notes.append(f"$AN_CEC_INPUT_NCU = {in_ncu}, $AN_CEC_OUTPUT_NCU = {out_ncu} (NCU link)")
    return notes


def _whole(token: str, source: str, line: int) -> int:
    if not re.fullmatch(r"[0-9]{1,9}", token):
        raise DataFormatError(f"table index {token[:12]!r} is not a whole number", source, line)
    return int(token)


#: The grammar of every option :func:`write_cross_axis` writes into the file
#: (:func:`~axiscal.compensation.controllers._common.check_fields`).
FIELDS = {"input_axis": WORD, "output_axis": WORD, "max_points": COUNT,
          "table_index": whole(0, 999, "CEC tables")}


def write_cross_axis(table: CompensationTable, travel=None, *, input_axis: str = "AX1",
                     output_axis: str = "AX2", table_index: int = 0, max_points: int = MAX_POINTS,
                     position_resolution: float = 0.001) -> ControllerFile:
    """Write a cross-axis table (positions of the base axis, corrections of the compensation
    axis) as a sag/angularity compensation file ``%_N_NC_CEC_INI`` (format in the module
    docstring).

    Enabling: MD18342 ``$MN_MM_CEC_MAX_POINTS[t]`` ≥ points, MD32710 ``$MA_CEC_ENABLE[AXi]`` = 1
    for the compensation axis, SD41300 ``$SN_CEC_TABLE_ENABLE[t]`` = 1.
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
    """The one table of a ``%_N_NC_CEC_INI`` file: (table, input axis, output axis).

    A file of several tables is refused naming them (:func:`read_cross_axis` reads them all).
    """
    tables, refused = read_cross_axis(text, source, correction_unit)
    if len(tables) + len(refused) > 1:
        raise DataFormatError(f"the file holds {len(tables) + len(refused)} CEC tables; read them "
                              "with read_cross_axis (each with its axes)", source)
    if refused:
        raise DataFormatError(next(iter(refused.values())), source)
    c = tables[0]
    return replace(c.table, axis=""), c.input_axis, c.output_axis
