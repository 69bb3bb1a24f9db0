"""SINUMERIK NC text as a series start-up archive and a builder's loader program hold it.

One reader of lines for every SINUMERIK file axiscal reads (``AX_EEC.INI``, ``NC_CEC.INI``,
``INITIAL.INI`` and ``.MPF`` loader programs), so that the tables and the machine data are read
from the same grammar:

* **Headers the NCK writes.** ``%_N_AX_EEC_INI`` (or ``;$PATH=…``), ``METRIC`` or ``INCH`` (the
  unit system the values were written in) and ``CHANDATA(n)``; blank lines; CRLF line ends.
  SINUMERIK 840D/810D Start-Up Guide (IADC) 03/2006 §11.12 "Line checksums and MD numbers in
  MD files": a machine data number may precede an assignment as a block number
  (``N38000 $MA_MM_ENC_COMP_MAX_POINTS[0,AX1]=25``), separated by a blank.
* **Assignments** ``$NAME[i,j,AXk]=value`` with a comment after ``;``; the value is a number, a
  name in parentheses ``(AX2)`` or a quoted string ``"X1"``.
* **Program ends** ``M17``, ``M30``, ``M02``, ``M2``, ``RET``.
* **Control statements of a loader program** (SINUMERIK 840D sl Programming Manual Job
  Planning: ``NEWCONF`` takes over machine data of effect NEW_CONFIG, ``STOPRE`` stops the
  preprocessor, ``MSG("…")`` shows a message, ``G4 F…`` dwells): recognised, reported with
  their line, and left out of the tables. Any other statement (``IF``, ``GOTO``, an R parameter,
  a motion block) is refused naming it: axiscal does not execute part programs.

:func:`statements` gives the lines as :class:`Statement` records.
"""

from __future__ import annotations

import re
from dataclasses import dataclass

from axiscal.errors import DataFormatError

__all__ = ["Statement", "statements", "CONTROL", "SWITCHES", "said", "fmt"]

#: Program statements a loader program uses around its tables, and what each does.
CONTROL = {
    "NEWCONF": "takes over machine data of effect NEW_CONFIG",
    "STOPRE": "stops the preprocessor until the blocks before it are executed",
    "MSG": "shows a message on the operator panel",
    "G4": "dwells",
}

#: Data a loader program sets around its tables to switch the compensation off and on again
#: (SINUMERIK 840D sl Function Manual K3: tables load only while MD32700 / MD32710 = 0; SD41300
#: enables a CEC table).
SWITCHES = {"MA_ENC_COMP_ENABLE": "MD32700", "MA_CEC_ENABLE": "MD32710",
            "SN_CEC_TABLE_ENABLE": "SD41300"}

_SAID = {"NEWCONF": "takes over NEW_CONFIG machine data", "STOPRE": "preprocessing stop",
         "MSG": "operator message", "G4": "dwell"}

_BLOCK = re.compile(r"^N\d{1,9}\s+", re.IGNORECASE)
_ASSIGN = re.compile(r"^\$([A-Z]{1,4})_([A-Z0-9_]+)\s*(?:\[([^\]]*)\])?\s*=\s*(.*)$", re.IGNORECASE)
#: a user variable (GUD) without ``$``, as an ``INITIAL.INI`` holds them (``_ZSD[0]=-1``)
_USER = re.compile(r"^([A-Z_][A-Z0-9_]*)\s*(?:\[([^\]]*)\])?\s*=\s*(.*)$", re.IGNORECASE)
_CHAN = re.compile(r"^CHANDATA\s*\(\s*\d{1,3}\s*\)$", re.IGNORECASE)
_END = {"M17", "M30", "M02", "M2", "RET"}
_UNIT = {"METRIC": "mm", "INCH": "inch"}


@dataclass(frozen=True)
class Statement:
    """One meaningful line of a SINUMERIK file.

    Attributes
    ----------
    line : int
        1-based line number.
    kind : str
        ``assign`` (a system variable or machine data, ``$`` and one to four letters:
        ``$MA_``, ``$MNS_``, ``$P_``), ``user`` (a user variable without ``$``, as the GUD
        blocks of an ``INITIAL.INI`` hold them: ``_ZSD[0]=-1``), ``unit`` (``METRIC``/``INCH``),
        ``control`` (a loader program's statement, :data:`CONTROL`), ``end`` (``M17`` …).
    name : str
        ``AA_ENC_COMP``, ``MA_IS_ROT_AX`` … (without the ``$``, upper case); for ``unit`` the
        unit (``mm``/``inch``), for ``control`` the statement (``NEWCONF``).
    index : tuple of str
        The bracket's entries (``("0", "3", "AX1")``).
    value : str
        The assigned value as written (comment removed), or the control statement's text.
    block : str
        The block number written before it (``N38000``), or ``""``.
    """

    line: int
    kind: str
    name: str = ""
    index: tuple = ()
    value: str = ""
    block: str = ""


def statements(text: str, source: str = "<text>") -> list[Statement]:
    """The file's statements; comments, blank lines and headers left out, others refused.

    Raises
    ------
    DataFormatError
        A line that is none of the above, naming the line and the statement.
    """
    out = []
    for n, raw in enumerate(text.splitlines(), 1):
        line = _code(raw)
        if not line or line.startswith("%") or _CHAN.match(line):
            continue
        block = ""
        m = _BLOCK.match(line)
        if m:
            block, line = m.group(0).strip().upper(), line[m.end():].strip()
            if not line:
                continue
        up = line.upper()
        if up in _UNIT:
            out.append(Statement(n, "unit", _UNIT[up], block=block))
            continue
        if up in _END:
            out.append(Statement(n, "end", up, block=block))
            continue
        m = _ASSIGN.match(line)
        if m:
            name = f"{m.group(1)}_{m.group(2)}".upper()
            index = tuple(s.strip() for s in m.group(3).split(",")) if m.group(3) else ()
            out.append(Statement(n, "assign", name, index, m.group(4).strip(), block))
            continue
        m = _USER.match(line)
        if m:
            index = tuple(s.strip() for s in m.group(2).split(",")) if m.group(2) else ()
            out.append(Statement(n, "user", m.group(1).upper(), index, m.group(3).strip(), block))
            continue
        word = _control(up)
        if word:
            out.append(Statement(n, "control", word, value=line, block=block))
            continue
        raise DataFormatError(f"{line[:60]!r} is a statement axiscal does not read in a SINUMERIK "
                              "table or loader program (it reads system-variable assignments, "
                              f"{', '.join(CONTROL)}, M17/M30 and comments)", source, n)
    return out


def said(s: Statement) -> str:
    """What a reader says of a loader program's statement it leaves out, or ``""``: a control
    statement (:data:`CONTROL`) or a switch of the compensation (:data:`SWITCHES`)."""
    if s.kind == "control":
        return f"line {s.line}: {s.name} left out ({_SAID[s.name]})"
    if s.kind == "assign" and s.name in SWITCHES:
        return (f"line {s.line}: {SWITCHES[s.name]} ${s.name}[{','.join(s.index)}] = {s.value} "
                "(the program switches the compensation; not a table value)")
    return ""


def _code(raw: str) -> str:
    """The line without its comment (``;`` outside a quoted string) and blanks."""
    quoted = False
    for i, c in enumerate(raw):
        if c == '"':
            quoted = not quoted
        elif c == ";" and not quoted:
            return raw[:i].strip()
    return raw.strip()


def _control(up: str) -> str:
    """The control statement ``up`` begins with (``MSG``, ``G4`` …), or ``""``."""
    if up in ("NEWCONF", "STOPRE"):
        return up
    if re.fullmatch(r'MSG\s*\(\s*("[^"]*")?\s*\)', up):
        return "MSG"
    if re.fullmatch(r"G0?4\s*F\s*[0-9.]+", up):
        return "G4"
    return ""


def fmt(v: float, nd: int = 9) -> str:
    """A number as a SINUMERIK file writes it: at most ``nd`` decimals, no trailing zeros."""
    s = f"{v:.{nd}f}".rstrip("0")
    return s + "0" if s.endswith(".") else s
