"""What the controller writers share: the written file and the limit checks."""

from __future__ import annotations

import math
import re
from dataclasses import dataclass, field

import numpy as np

from axiscal import units
from axiscal._parse import finite_number
from axiscal.errors import ControllerLimitError, DataFormatError, InputError

__all__ = ["ControllerFile", "FileInput", "resolve_input", "check_points", "check_spacing",
           "check_travel", "check_modulo", "correction_factor", "parse_number", "decimals",
           "SafeName", "safe_axis_name", "is_axis_letter", "SOURCE_COMMENT", "Field",
           "check_fields", "WORD", "LETTER_FIELD", "whole", "COUNT"]


@dataclass(frozen=True, eq=False)
class ControllerFile:
    """A compensation table written for one controller.

    Attributes
    ----------
    controller : str
        Controller name (``siemens-840d`` ...).
    text : str
        The main file's content.
    filename : str
        The name the controller expects or a good default (``X.COM``, ``AX_EEC.INI`` ...).
    table : CompensationTable
        The table as written (after the format's rounding or re-referencing), which is what
        :func:`parse` gives back.
    enable : tuple of str
        What the controller must be told to use the table (machine data, parameters, INI keys).
    extra_files : dict of str to str
        Further files that belong to it (Heidenhain's ``.CMA``), name -> content.
    notes : tuple of str
        What a user should know (shifts applied, limits approached, conventions).
    """

    controller: str
    text: str
    filename: str
    table: object
    enable: tuple[str, ...] = ()
    extra_files: dict = field(default_factory=dict)
    notes: tuple[str, ...] = ()

    def written_as(self, name: str) -> "ControllerFile":
        """The same file saved as ``name``: an enabling step that names the file (LinuxCNC's
        ``COMP_FILE = x.comp``) names ``name`` instead (issue 42)."""
        from dataclasses import replace

        if not name or name == self.filename:
            return self
        return replace(self, filename=name, enable=tuple(
            e.replace(f"= {self.filename}", f"= {name}") for e in self.enable))

    def summary(self) -> list[str]:
        """What ``axiscal compensate`` prints about the file before its text, line by line, and
        the workbench shows beside its download: the table's points, spacing, range, reference
        point and largest correction, the mean reversal of a bidirectional table, then every
        step to enable it (``enable: …``) and every note (``note: …``: the shift to zero at the
        reference point, the backlash machine datum's value ...)."""
        from axiscal.units import display

        t = self.table
        pu, cu = t.position_unit, display(t.correction_unit)   # µm, as every output writes
        lines = [f"{self.controller} compensation table for axis {t.axis or '-'} "
                 f"({'bidirectional' if t.bidirectional else 'one table for both directions'})",
                 f"  points           {t.n_points}",
                 f"  spacing          {t.spacing:g} {pu}",
                 f"  range            {t.start:g} … {t.end:g} {pu}"
                 f"{' (modulo 360)' if t.modulo else ''}",
                 f"  reference point  {t.reference_index} at {t.reference_position:g} {pu}",
                 f"  largest corr.    {t.largest:.4g} {cu} (correction = −deviation)"]
        if t.bidirectional:
            lines.append(f"  mean reversal    {t.backlash:+.4g} {cu}")
        lines += [f"  enable: {e}" for e in self.enable]
        lines += [f"  note: {n}" for n in self.notes]
        return lines

    def __str__(self) -> str:
        lines = [f"{self.controller}: {self.filename} ({len(self.text.splitlines())} lines)"]
        lines += [f"  enable: {e}" for e in self.enable]
        lines += [f"  note: {n}" for n in self.notes]
        return "\n".join(lines)


def check_points(n: int, maximum: int, fmt: str, what: str = "points") -> None:
    """Refuse a table with more than ``maximum`` points."""
    if n > maximum:
        raise ControllerLimitError(
            f"{fmt}: {n} compensation {what}; the format allows at most {maximum} "
            "(use a larger --spacing or a shorter range)")


def check_spacing(spacing: float, resolution: float, unit: str, fmt: str,
                  name: str = "position_resolution") -> int:
    """Refuse a spacing that is not a whole number of ``resolution``; return that number.

    ``name`` is the writer's option that gave ``resolution``; a resolution that is not a
    positive number is refused naming it.
    """
    try:
        ok = math.isfinite(float(resolution)) and float(resolution) > 0
    except (TypeError, ValueError):
        ok = False
    if not ok:
        raise ControllerLimitError(f"{fmt}: {name} = {resolution!r} {unit} must be a positive "
                                   "number (the controller's position unit)")
    k = spacing / resolution
    if not math.isfinite(k) or k < 1 or abs(k - round(k)) > 1e-6:
        raise ControllerLimitError(
            f"{fmt}: spacing {spacing:.10g} {unit} is not a whole multiple of the controller's "
            f"position unit {resolution:g} {unit}")
    return int(round(k))


def check_travel(table, travel, fmt: str) -> None:
    """Refuse a table reaching outside ``travel`` = (low, high) in the table's position unit."""
    if travel is None:
        return
    lo, hi = float(travel[0]), float(travel[1])
    tol = 1e-9 * max(1.0, abs(hi - lo))
    if table.start < lo - tol or table.end > hi + tol:
        u = table.position_unit
        raise ControllerLimitError(
            f"{fmt}: table range {table.start:g} … {table.end:g} {u} lies outside the axis travel "
            f"{lo:g} … {hi:g} {u}")


def check_modulo(table, fmt: str) -> None:
    """A modulo table must close: the value at 360° equals the value at 0° (each direction)."""
    if not table.modulo:
        return
    for name in ("up", "down"):
        c = getattr(table, name)
        if abs(c[-1] - c[0]) > 1e-9 * max(1.0, float(np.max(np.abs(c)))):
            raise ControllerLimitError(
                f"{fmt}: rotary table ({name}) does not close on itself: {c[0]:g} at "
                f"{table.start:g} deg but {c[-1]:g} at {table.end:g} deg {table.correction_unit}; "
                "the increments over one revolution must sum to zero")


def correction_factor(table, to_unit: str) -> float:
    """Multiply a correction in ``table.correction_unit`` by this to get ``to_unit``."""
    return units.factor(table.correction_unit) / units.factor(to_unit)


#: Largest magnitude a number in a controller file may have (mm, deg, µm or arcsec): far beyond
#: any real table, small enough that the unit conversions cannot overflow.
LARGEST_VALUE = 1e9


def parse_number(token: str, source: str, line: int) -> float:
    """A float from a file, or a :class:`DataFormatError` naming the line."""
    v = finite_number(token, "value", source, line)
    if abs(v) > LARGEST_VALUE:
        raise DataFormatError(f"value {v:g} is out of range (at most {LARGEST_VALUE:g} in "
                              "magnitude)", source, line)
    return v


def decimals(position_unit: str) -> int:
    """Decimals written for a correction in ``position_unit``: 1 nm in mm, 1e-9 deg (4 µarcsec)."""
    return 6 if position_unit == "mm" else 9


#: Length units a controller file may be written in: name -> mm per file unit.
FILE_UNITS = {"mm": 1.0, "inch": 25.4}


def file_unit(unit: str, table, fmt: str) -> float:
    """mm per unit of the file (``mm`` or ``inch``; a rotary table is always in degrees)."""
    u = {"in": "inch", "inches": "inch", "millimetre": "mm"}.get(str(unit).lower(), str(unit).lower())
    if u not in FILE_UNITS:
        raise InputError(f"{fmt}: unit {unit!r}; the file is in mm or inch")
    if u == "inch" and table is not None and table.position_unit != "mm":
        raise ControllerLimitError(f"{fmt}: an inch file holds a linear axis (the table is in "
                                   f"{table.position_unit})")
    return FILE_UNITS[u]


def require_equidistant(table, fmt: str) -> None:
    """Refuse a table with irregular positions for a format whose points are equidistant."""
    if not table.equidistant:
        raise ControllerLimitError(f"{fmt}: the table has irregular positions (at the measured "
                                   "targets); this controller takes equidistant points: give a "
                                   "spacing")


@dataclass(frozen=True)
class FileInput:
    """A number a parser needs that a controller file may not carry, and where it came from.

    Attributes
    ----------
    name : str
        The parser's option that sets it (``reference_position``, ``unit`` ...).
    value : object
        The value used.
    unit : str
        Its unit (``mm``, ``deg``, ``""``).
    source : str
        ``"option"`` (given), ``"file"`` (stated in the file) or ``"default"`` (assumed).
    why : str
        What the file says, or why the value had to be assumed.
    needed_to_compare : bool
        A comparison with measured data is meaningless on an assumed value (refused then).
    """

    name: str
    value: object
    unit: str
    source: str
    why: str
    needed_to_compare: bool = False

    @property
    def assumed(self) -> bool:
        """True when neither the file nor the caller gave the value."""
        return self.source == "default"

    def to_dict(self) -> dict:
        return dict(name=self.name, value=self.value, unit=self.unit, assumed=self.assumed,
                    source=self.source, why=self.why, set_with=f"-o {self.name}=…")

    def __str__(self) -> str:
        u = f" {self.unit}" if self.unit else ""
        if self.assumed:
            return (f"assumed: {self.name} = {_shown(self.value)}{u} ({self.why}; set with "
                    f"-o {self.name}=…)")
        return (f"{self.name} = {_shown(self.value)}{u} "
                f"({'given' if self.source == 'option' else self.why})")


def resolve_input(name: str, given, stated, default, *, said: str, why: str, unit: str = "",
                  source: str = "<text>", needed_to_compare: bool = False) -> FileInput:
    """The caller's value (refused where it contradicts the file's), the file's, or the default.

    ``stated`` is what the file says (None: silent), ``said`` how it says it (the ``why`` of a
    value from the file), ``why`` the reason a default had to be assumed.
    """
    if given is not None:
        if stated is not None and not _same(given, stated):
            u = f" {unit}" if unit else ""
            raise DataFormatError(f"{name} = {_shown(given)}{u} contradicts the file ({said}: "
                                  f"{_shown(stated)}{u})", source)
        return FileInput(name, given, unit, "option", "given", needed_to_compare)
    if stated is not None:
        return FileInput(name, stated, unit, "file", said, needed_to_compare)
    return FileInput(name, default, unit, "default", why, needed_to_compare)


def _same(a, b) -> bool:
    if isinstance(a, (int, float)) and isinstance(b, (int, float)):
        return math.isclose(a, b, rel_tol=1e-9, abs_tol=1e-9)
    return a == b


def _shown(v) -> str:
    return f"{v:g}" if isinstance(v, float) else str(v)


# -- names written into controller files ------------------------------------------------------
#: Axis letters of DIN 66025 / ISO 6983-1 (linear X, Y, Z; rotary A, B, C; secondary U, V, W).
AXIS_LETTERS = "XYZABCUVW"
#: The POSIX portable filename character set (The Open Group Base Specifications Issue 6,
#: IEEE Std 1003.1-2004, §3.276), which HEIDENHAIN's TNC file names must keep to (TNC 640
#: User's Manual, "File management: fundamentals", File names). It holds none of the characters
#: Windows reserves (``< > : " / \\ | ? *`` and 0-31; Microsoft, "Naming Files, Paths, and
#: Namespaces"), and LinuxCNC's COMP_FILE names are letters and numbers ("INI Configuration",
#: [JOINT_n] COMP_FILE).
_NOT_PORTABLE = re.compile(r"[^A-Za-z0-9_-]+")
#: Device names Windows reserves whatever the extension (the same Microsoft page).
_RESERVED = {"CON", "PRN", "AUX", "NUL", *(f"COM{i}" for i in range(1, 10)),
             *(f"LPT{i}" for i in range(1, 10))}
#: Longest name written: well inside the 255 characters of path and name a TNC 640 takes (User's
#: Manual, File names) and Windows' 260 (MAX_PATH).
NAME_LENGTH = 64
#: How the comment that keeps a sanitised name's source begins.
SOURCE_COMMENT = "axis name in the source data:"


@dataclass(frozen=True)
class SafeName:
    """An axis name as a controller file may hold it, and the name it came from.

    Attributes
    ----------
    name : str
        What is written into the file and its file name: an axis letter where the controller
        wants one, else the source's characters outside the portable set replaced by ``_``.
    source : str
        The name as the data gave it (``""`` when the data named no axis).
    """

    name: str
    source: str

    @property
    def changed(self) -> bool:
        """The file holds another name than the data gave."""
        return bool(self.source) and self.name != self.source

    def comment(self, begin: str, end: str = "", upper: bool = False) -> list[str]:
        """The comment line keeping the source name (none when the name is unchanged).

        ``begin``/``end`` are the format's comment delimiters; they, and control characters
        (C0, C1, the bidirectional controls such as U+202E), are taken out of the name so the
        comment cannot end early nor show reversed.
        """
        if not self.changed:
            return []
        text = "".join("?" if not c.isprintable() or c in begin + end else c
                       for c in self.source)     # C0, C1 and bidi controls are not printable
        line = f"{SOURCE_COMMENT} {text}"
        return [f"{begin}{line.upper() if upper else line}{end}"]


def is_axis_letter(name: str) -> bool:
    """``name`` is one of :data:`AXIS_LETTERS` (either case), optionally followed by one digit.

    Examples
    --------
    >>> [is_axis_letter(n) for n in ("X", "c", "X2", "Q", "IOC:m1", "")]
    [True, True, True, False, False, False]
    """
    return bool(re.fullmatch(f"[{AXIS_LETTERS}][0-9]?", str(name), re.IGNORECASE))


def safe_axis_name(axis: str, fmt: str, *, letter: bool = False,
                   given: str | None = None) -> SafeName:
    """The axis name ``fmt`` may write, from the table's ``axis`` (or ``given``, the writer's
    ``axis=`` option, which wins).

    With ``letter=True`` (a controller whose axis column is an axis letter, HEIDENHAIN's
    ``.COM``) the name must be one of :data:`AXIS_LETTERS`, optionally followed by one digit
    (``X``, ``x2``): an ecmc PV name such as ``SLS-SIOC-ECAT01:M1-PosSet`` is refused, naming
    ``-o axis=``. Otherwise characters outside the POSIX portable set become ``_``, a Windows
    device name gets a trailing ``_``, and the name is cut to :data:`NAME_LENGTH` characters.
    """
    source = str(axis or "").strip()
    wanted = str(given).strip() if given else source
    if letter:
        if not wanted:
            return SafeName("X", "")
        if not is_axis_letter(wanted):
            what = "-o axis=" if given else "the data's axis"
            raise ControllerLimitError(
                f"{fmt}: the axis column takes an axis letter ({', '.join(AXIS_LETTERS)}); "
                f"{what} {wanted[:60]!r} is not one: give -o axis=X (or --axis X)")
        return SafeName(wanted.upper(), source)
    name = _NOT_PORTABLE.sub("_", wanted).strip("_-")[:NAME_LENGTH].rstrip("_-")
    if name.upper() in _RESERVED:
        name += "_"
    return SafeName(name, source)


# -- the grammar of every field a writer puts into its file ----------------------------------
@dataclass(frozen=True)
class Field:
    """The grammar of one value a writer writes into a controller file.

    A writer declares its fields in a module-level ``FIELDS`` dict (option name -> Field) and
    calls :func:`check_fields` first: every value is checked against its format's grammar and
    refused naming the option, the value and the rule, before a line is written. So a name with
    a line break cannot add a line to the file (``machine_axis=X1]=0\\nM30``), and a number too
    large for the word it goes into cannot be written (``N3620A99999999999999999999``).

    Attributes
    ----------
    pattern : str
        For a name: the regular expression the whole value must match ("" for a number).
    lo, hi : int
        For a whole number: the inclusive range.
    rule : str
        The rule in words, for the message.
    """

    pattern: str = ""
    lo: int = 0
    hi: int = 0
    rule: str = ""

    def check(self, fmt: str, name: str, value) -> None:
        """Refuse ``value`` unless it keeps to this field's grammar (ControllerLimitError)."""
        if value is None:
            return
        if self.pattern:
            text = value if isinstance(value, str) else None
            if text is None or len(text) > 64 or not re.fullmatch(self.pattern, text):
                raise ControllerLimitError(f"{fmt}: {name} = {_quoted(value)} is not {self.rule}")
            return
        if isinstance(value, bool) or not isinstance(value, (int, np.integer)) or \
                not self.lo <= int(value) <= self.hi:
            raise ControllerLimitError(f"{fmt}: {name} = {_quoted(value)} is not {self.rule} "
                                       f"({self.lo} … {self.hi})")


def whole(lo: int, hi: int, what: str) -> Field:
    """A whole-number field from ``lo`` to ``hi`` (``what`` names it in the message)."""
    return Field(lo=lo, hi=hi, rule=f"a whole number of {what}")


#: A machine-data name (SINUMERIK machine axis names ``AX1``, ``X1``, ``SP1``, or a number):
#: letters, digits or ``_``, at most 32 characters. No space, bracket, ``=``, ``;`` or line
#: break, any of which would end the ``$AA_ENC_COMP[0,i,AX1]`` word it is written into.
WORD = Field(pattern=r"[A-Za-z0-9_]{1,32}",
             rule="a machine axis name (letters, digits or _, at most 32)")
#: An axis letter of DIN 66025 / ISO 6983-1, optionally followed by one digit.
LETTER_FIELD = Field(pattern=f"[{AXIS_LETTERS}{AXIS_LETTERS.lower()}][0-9]?",
                    rule=f"an axis letter ({', '.join(AXIS_LETTERS)}, optionally one digit)")
#: A count of table points a control may hold: far beyond any controller's table (a Siemens
#: MD38000 of 840D sl allows 125 000 points), small enough that no loop runs away.
COUNT = whole(1, 10**6, "points")


def check_fields(fmt: str, fields: dict, **values) -> None:
    """Check every value against its :class:`Field` in ``fields`` (names not there are left).

    Examples
    --------
    >>> check_fields("siemens-840d", {"machine_axis": WORD}, machine_axis="X1")
    >>> check_fields("siemens-840d", {"machine_axis": WORD}, machine_axis="X1]=0\\nM30")
    Traceback (most recent call last):
    ...
    axiscal.errors.ControllerLimitError: siemens-840d: machine_axis = 'X1]=0\\nM30' is not a machine axis name (letters, digits or _, at most 32)
    >>> check_fields("fanuc", {"axis_number": whole(1, 32, "axes")}, axis_number=10**20)
    Traceback (most recent call last):
    ...
    axiscal.errors.ControllerLimitError: fanuc: axis_number = 100000000000000000000 is not a whole number of axes (1 … 32)
    """
    for name, value in values.items():
        if name in fields:
            fields[name].check(fmt, name, value)


def _quoted(value) -> str:
    """A value for a message: its repr, at most about 60 characters."""
    text = repr(value) if isinstance(value, str) else str(value)
    return text if len(text) <= 60 else f"{text[:40]}…{text[-12:]}"
