"""LinuxCNC: the joint compensation file (``COMP_FILE``, ``COMP_FILE_TYPE`` 0 or 1).

Sources: LinuxCNC ``src/emc/motion/usrmotintf.cc``, ``usrmotLoadComp(joint, file, type)``: the
file is read line by line with ``sscanf(buffer, "%lf %lf %lf", &nom, &fwd, &rev)``; a line whose
first three fields are numbers is taken (anything after them, such as ``; home``, is ignored) and
reading stops at the first line that is not (so the file carries no comment lines). With type 0
the numbers are *nominal, forward, reverse* positions and the loader stores the trims
``nominal − forward`` and ``nominal − reverse``; with type 1 they are already *nominal,
forward_trim, reverse_trim*. ``src/emc/motion/motion.h``: ``EMCMOT_COMP_SIZE 256`` entries at
most. The INI documentation (``[JOINT_n] COMP_FILE``, ``COMP_FILE_TYPE``; ``[AXIS_n]`` before
2.8). ``src/emc/motion/control.c`` (``compute_screw_comp``): the trim is added to the commanded
joint position, linearly interpolated between entries whatever their spacing (so irregular
nominal positions, such as an ISO 230-2 test's targets, are as good as equidistant ones); beyond
the first and last entries the end trims hold. Plain backlash compensation is the special case
``fwd_trim = +backlash/2``, ``rev_trim = −backlash/2``. The file is in the machine's
``[TRAJ] LINEAR_UNITS``, often inch: LinuxCNC's own sample ``configs/sim/screwcompX.dat`` is a
type-0 file in inch (its nominal positions run −10 … +10).

Here: trim = correction (= −deviation) in the file's unit (``unit="mm"`` or ``"inch"``; tables
inside axiscal stay in mm); type 0 writes ``forward = nominal − correction_up`` and
``reverse = nominal − correction_down``, the positions the uncompensated axis reaches. A file read
with the wrong type shifts every value by its nominal: :func:`parse` refuses trims larger than a
tenth of the table's span and than half a unit (mm or inch), and says which type the file looks
like.

**Limits checked.** At most 256 lines; nominal positions strictly increasing; range inside the
travel. A continuous rotary joint is compensated only over the table's 0…360° (the joint position
is not wrapped): noted, not refused.

**Names and comments.** The file name keeps to letters, digits, ``_`` and ``-`` (LinuxCNC,
"INI Configuration", [JOINT_n] ``COMP_FILE``: "File names are case sensitive and can contain
letters and/or numbers"; an ecmc PV name's ``:`` becomes ``_``). The axis name follows the data
as a trailing comment line (``# axiscal: axis X``, and the source name when it was changed):
LinuxCNC stops reading at the first line that is not three numbers, so lines after the data are
never read, and :func:`parse` reads them back (a line that is not three numbers *before* data
is refused, since LinuxCNC would drop the data after it).

**Implausible trims** (:func:`trim_jumps`). A trim that jumps away from its neighbours by far more
than the table's usual step is flagged, not refused: LinuxCNC would apply it as a jump of the
axis. The rule (axiscal's; LinuxCNC checks nothing): an interval between neighbouring entries of
one direction jumps when its trim change exceeds both ``JUMP_FACTOR`` (10) × the median absolute
change between neighbours (both directions pooled) and ``JUMP_SLOPE`` (1 %) of the distance
between the two nominal positions, a slope of 10 mm/m, hundreds of times a ground lead screw's
error (Steinmeyer, "Lead error over 300 mm": 12 µm per 300 mm for accuracy class P3). Two jumping
intervals of opposite sign around one entry make that entry a *spike* (LinuxCNC's sample
``screwcompX.dat`` has one: ``-4 -4.2 -3.998``, a forward trim of 0.2 inch between neighbours of
0.002 and 0.003 inch); a single jumping interval is a *step*.
"""

from __future__ import annotations

import re
from dataclasses import dataclass, replace

import numpy as np

from axiscal.compensation.controllers._common import (
    ControllerFile, check_points, check_travel, correction_factor, decimals, file_unit,
    parse_number, safe_axis_name, COUNT, whole, check_fields)
from axiscal.compensation.tables import CompensationTable, TableOrigin
from axiscal.datasets import AxisKind
from axiscal.errors import ControllerLimitError, DataFormatError, InputError

__all__ = ["NAME", "write", "parse", "MAX_POINTS", "TrimJump", "trim_jumps", "file_type_by_content",
           "trailing_lines", "looks_like", "ANGULAR_UNITS"]

NAME = "linuxcnc"
MAX_POINTS = 256
#: A trim change larger than this many median changes between neighbours may be a jump ...
JUMP_FACTOR = 10.0
#: ... if it is also larger than this share of the distance between the two nominal positions.
JUMP_SLOPE = 0.01
#: Degrees per unit of LinuxCNC's ``[TRAJ] ANGULAR_UNITS`` (src/emc/ini/inifile.cc,
#: ``mapAngularUnits``): a rotary joint's file is in these units.
ANGULAR_UNITS = {"deg": 1.0, "degree": 1.0, "grad": 0.9, "gon": 0.9, "rad": 180.0 / np.pi,
                 "radian": 180.0 / np.pi}
_STOPS = ("not three numbers (nominal and two values): LinuxCNC stops reading at this line and "
          "ignores the rest of the file")
_AXIS_COMMENT = re.compile(r"^#\s*axiscal: axis (\S+)\s*$")


#: The grammar of the options :func:`write` writes into the INI lines: LinuxCNC has at most 16
#: joints (``[JOINT_0]`` … ``[JOINT_15]``, EMCMOT_MAX_JOINTS).
FIELDS = {"joint": whole(0, 15, "joints"), "max_points": COUNT}


def write(table: CompensationTable, travel=None, *, file_type: int = 1, joint: int = 0,
          max_points: int = MAX_POINTS, unit: str = "mm") -> ControllerFile:
    """Write ``table`` as a LinuxCNC compensation file of ``file_type`` 0 or 1.

    ``unit``: the machine's ``LINEAR_UNITS`` (``mm`` or ``inch``) for a linear joint. Irregular
    positions (a table built at the measured targets) are written as they are. The axis name
    follows the data as a comment LinuxCNC never reads (see the module's notes).
    """
    check_fields(NAME, FIELDS, joint=joint, max_points=max_points)
    if file_type not in (0, 1):
        raise ControllerLimitError(f"{NAME}: COMP_FILE_TYPE = {file_type!r}; LinuxCNC knows 0 and 1")
    check_points(table.n_points, max_points, NAME, "lines (EMCMOT_COMP_SIZE)")
    check_travel(table, travel, NAME)
    names = safe_axis_name(table.axis, NAME)
    mm = file_unit(unit, table, NAME)
    fu = table.position_unit if mm == 1.0 else "in"
    k = correction_factor(table, fu)
    nd = decimals(table.position_unit) + (1 if mm != 1.0 else 0)
    nom = np.round(table.positions / mm, nd)
    fwd = np.round(table.up * k, nd)
    rev = np.round(table.down * k, nd)
    a, b = (nom - fwd, nom - rev) if file_type == 0 else (fwd, rev)
    text = "".join(f"{n:.{nd}f} {x:.{nd}f} {y:.{nd}f}\n" for n, x, y in zip(nom, a, b))
    if names.name:
        text += "\n".join([f"# axiscal: axis {names.name}", *names.comment("# ")]) + "\n"
    name = f"{(names.name or 'joint').lower()}.comp"
    units_word = "inch" if mm != 1.0 else ("mm" if table.position_unit == "mm" else "degree")
    enable = [f"[JOINT_{joint}] COMP_FILE = {name}", f"[JOINT_{joint}] COMP_FILE_TYPE = {file_type}",
              f"the file is in {units_word}: the machine's [TRAJ] LINEAR_UNITS must be "
              f"{units_word}" if table.position_unit == "mm" else "the file is in degrees",
              f"leave [JOINT_{joint}] BACKLASH unset: the file holds both directions"
              if table.bidirectional else "the same trims serve both directions"]
    notes = ["LinuxCNC holds the first and last trims beyond the table: it should cover the "
             "travel"]
    if table.modulo:
        notes.append("continuous rotary joint: compensated only over the table's range (no wrap)")
    if not table.equidistant:
        notes.append(f"{table.n_points} irregular positions (the measured targets); LinuxCNC "
                     "interpolates between any increasing positions")
    written = replace(table, axis=names.name, up=fwd / k, down=rev / k,
                      bidirectional=not np.allclose(fwd, rev),   # as parse tells it
                      nodes=None if table.equidistant else nom * mm)
    return ControllerFile(NAME, text, name, written, tuple(enable), notes=tuple(notes))


def parse(text: str, source: str = "<text>", file_type: int = 1,
          axis_kind: "AxisKind | str" = "linear", axis: str = "",
          correction_unit: str | None = None, unit: str = "mm") -> CompensationTable:
    """Read a LinuxCNC compensation file (both types; mm or inch, or a rotary joint's angular
    unit) into a table in mm (deg).

    Lines are read as LinuxCNC reads them (three numbers, anything after them ignored); where
    LinuxCNC would silently stop (a line that is not three numbers before the end of the data),
    this parser refuses the file and names the line, since the rest would be lost. Lines after
    the data (comments) are never read by LinuxCNC and are skipped here; axiscal's own
    ``# axiscal: axis X`` gives the axis name back when ``axis`` is not given.
    """
    if file_type not in (0, 1):
        raise InputError(f"{NAME}: file_type = {file_type!r}; COMP_FILE_TYPE is 0 or 1")
    kind = AxisKind.parse(axis_kind)
    mm = _scale(unit, kind)
    rows, tail = _data_rows(text, source)
    arr = np.array(rows)
    nom = arr[:, 0]
    steps = np.diff(nom)
    if np.any(steps <= 0):
        i = int(np.argmax(steps <= 0))
        raise DataFormatError(f"nominal positions must increase strictly: {nom[i]:g} is "
                              f"followed by {nom[i + 1]:g}", source)
    fwd, rev = (nom - arr[:, 1], nom - arr[:, 2]) if file_type == 0 else (arr[:, 1], arr[:, 2])
    _plausible(nom, fwd, rev, file_type, source)
    if not axis:
        found = [m.group(1) for m in map(_AXIS_COMMENT.match, tail) if m]
        axis = found[0] if found else ""
    pu = "mm" if kind is AxisKind.LINEAR else "deg"
    cu = correction_unit or ("um" if kind is AxisKind.LINEAR else "arcsec")
    modulo = kind is AxisKind.ROTARY and abs((nom[-1] - nom[0]) * mm - 360.0) < 1e-6
    regular = not np.any(np.abs(steps - steps[0]) > 1e-6 * max(1.0, abs(steps[0])))
    nodes = None if regular else nom * mm
    t = CompensationTable(axis, kind, pu, cu, float(nom[0] * mm), float(steps[0] * mm), fwd,
                          rev, bidirectional=not np.allclose(fwd, rev), modulo=modulo,
                          nodes=nodes)
    k = correction_factor(t, pu) / mm            # file unit -> correction unit
    origin = TableOrigin(NAME, "", None, "deg" if kind is not AxisKind.LINEAR else
                         ("inch" if mm != 1.0 else "mm"), "option")
    return replace(t, up=np.round(fwd / k, 6) + 0.0, down=np.round(rev / k, 6) + 0.0,
                   origin=origin)


def looks_like(text: str) -> bool:
    """True if ``text`` is at least two lines of three numbers, with only comments after them."""
    try:
        _data_rows(text, "<text>")
    except DataFormatError:
        return False
    return True


def trailing_lines(text: str) -> int:
    """How many non-empty lines follow the data (comments LinuxCNC never reads)."""
    return len(_data_rows(text, "<text>")[1])


def file_type_by_content(text: str, source: str = "<text>") -> int | None:
    """0 or 1 where only one type gives plausible trims (see :func:`parse`), else None."""
    rows, _ = _data_rows(text, source)
    arr = np.array(rows)
    nom = arr[:, 0]
    fits = []
    for file_type in (0, 1):
        fwd, rev = (nom - arr[:, 1], nom - arr[:, 2]) if file_type == 0 else (arr[:, 1], arr[:, 2])
        try:
            _plausible(nom, fwd, rev, file_type, source)
            fits.append(file_type)
        except DataFormatError:
            pass
    return fits[0] if len(fits) == 1 else None


@dataclass(frozen=True)
class TrimJump:
    """A trim that jumps from its neighbour(s) by more than the table's plausible step.

    Attributes
    ----------
    direction : str
        ``forward`` (the file's second column as a trim) or ``reverse``.
    kind : str
        ``spike`` (one entry away from both neighbours) or ``step`` (one interval).
    position : float, table position unit
        The entry's nominal (a spike) or the interval's start (a step).
    trim, before, after : float, table correction unit
        The trim there and its neighbours' (``before``/``after`` NaN at an end).
    jump : float, table correction unit
        The largest change to a neighbour.
    threshold : float, table correction unit
        The change the rule allows there.
    """

    direction: str
    kind: str
    position: float
    trim: float
    before: float
    after: float
    jump: float
    threshold: float

    def describe(self, table, file_unit_name: str | None = None) -> str:
        """One line: where, how large, the rule, in the table's units and the file's."""
        pu, cu = table.position_unit, table.correction_unit
        f = correction_factor(table, pu)
        where = (f"at {self.position:g} {pu}" if self.kind == "spike"
                 else f"after {self.position:g} {pu}")
        extra = ""
        if file_unit_name and file_unit_name not in ("mm", "deg", "degree"):
            per = FILE_SCALE.get(file_unit_name, 1.0)
            extra = f" ({self.jump * f / per:.4g} {file_unit_name} in the file)"
        return (f"{self.direction} trim {self.kind} {where}: {self.trim:+.4g} {cu} beside "
                f"{self.before:+.4g} and {self.after:+.4g} {cu}, a jump of {self.jump:.4g} "
                f"{cu}{extra} that LinuxCNC would apply as a move of the axis (plausible at most "
                f"{self.threshold:.4g} {cu} there: the larger of {JUMP_FACTOR:g} × the median change "
                f"between neighbours and {100 * JUMP_SLOPE:g} % of the spacing)")

    def to_dict(self) -> dict:
        return {k: (None if isinstance(v, float) and not np.isfinite(v) else v)
                for k, v in self.__dict__.items()}


#: Table position unit per file unit, for :meth:`TrimJump.describe`.
FILE_SCALE = {"inch": 25.4, "in": 25.4, "mm": 1.0, **ANGULAR_UNITS}


def trim_jumps(table: CompensationTable) -> tuple[TrimJump, ...]:
    """The trims of ``table`` that jump by more than the table's plausible step (module notes).

    Examples
    --------
    >>> from axiscal.compensation.tables import CompensationTable
    >>> t = CompensationTable("X", "linear", "mm", "um", 0.0, 10.0, [1., 2., 900., 3., 2.],
    ...                       [0., 0., 0., 0., 0.])
    >>> [(j.kind, j.position, j.trim) for j in trim_jumps(t)]
    [('spike', 20.0, 900.0)]
    """
    pos = table.positions
    f = correction_factor(table, table.position_unit)       # correction unit -> position unit
    curves = {"forward": np.asarray(table.up, float), "reverse": np.asarray(table.down, float)}
    changes = np.concatenate([np.diff(c) for c in curves.values()])
    allowed = np.maximum(JUMP_FACTOR * float(np.median(np.abs(changes))),
                         JUMP_SLOPE * np.diff(pos) / f)
    out = []
    for name, c in curves.items():
        d = np.diff(c)
        big = np.abs(d) > allowed
        i = 0
        while i < len(d):
            if not big[i]:
                i += 1
                continue
            spike = i + 1 < len(d) and big[i + 1] and np.sign(d[i + 1]) != np.sign(d[i])
            at = i + 1 if spike else i
            before = c[at - 1] if at > 0 else np.nan
            after = c[at + 1] if at + 1 < len(c) else np.nan
            jump = max(abs(d[i]), abs(d[i + 1])) if spike else abs(d[i])
            out.append(TrimJump(name, "spike" if spike else "step", float(pos[at]), float(c[at]),
                                float(before), float(after), float(jump), float(allowed[i])))
            i += 2 if spike else 1
    return tuple(out)


def _scale(unit: str, kind: AxisKind) -> float:
    """Table position unit (mm or deg) per unit of the file."""
    if kind is AxisKind.LINEAR:
        return file_unit(unit, None, NAME)
    u = str(unit).strip().lower()
    if u in ("mm", ""):                        # the parameter's default: a rotary file in degrees
        return 1.0
    if u not in ANGULAR_UNITS:
        raise InputError(f"{NAME}: unit {unit!r} for a rotary joint; LinuxCNC's ANGULAR_UNITS "
                         f"are {', '.join(ANGULAR_UNITS)}")
    return ANGULAR_UNITS[u]


def _is_number(token: str) -> bool:
    try:
        float(token)
    except ValueError:
        return False
    return True


def _data_rows(text: str, source: str) -> tuple[list, list[str]]:
    """The triplets, and the non-empty lines after them (which LinuxCNC never reads).

    A line after the data is a comment only if it does not begin with a number: a last data
    line cut short (``200.0 -0.005``) is refused, as a line that is not three numbers before
    more data is.
    """
    rows: list = []
    tail: list[str] = []
    for n, raw in enumerate(text.splitlines(), 1):
        if not raw.strip():
            continue
        cells = raw.split()
        try:
            if len(cells) < 3:
                raise ValueError
            [float(c) for c in cells[:3]]
        except ValueError:
            if not rows or _is_number(cells[0]):      # a data line cut short loses a point
                raise DataFormatError(_STOPS, source, n) from None
            tail.append((n, raw.strip()))
            continue
        if tail:
            raise DataFormatError(_STOPS, source, tail[0][0])
        rows.append([parse_number(c, source, n) for c in cells[:3]])
    if len(rows) < 2:
        raise DataFormatError(f"{len(rows)} line(s); a compensation file needs at least 2", source)
    return rows, [t for _, t in tail]


def _plausible(nom, fwd, rev, file_type, source) -> None:
    """Trims as large as the positions mean the file was read with the other type."""
    span = float(nom[-1] - nom[0])
    big = float(max(np.abs(fwd).max(), np.abs(rev).max()))
    if big > 0.1 * span and big > 0.5:              # half a millimetre (or inch) of trim
        other = 1 - file_type
        raise DataFormatError(
            f"trims of up to {big:g} on a table spanning {span:g}: read as COMP_FILE_TYPE "
            f"{file_type}, this file looks like type {other} "
            f"({'nominal, forward, reverse positions' if other == 0 else 'nominal and trims'})"
            f"; read it with file_type={other}", source)
