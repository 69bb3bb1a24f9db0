"""One way to check configuration files (TOML) and numeric options: type, unit, bounds.

Every key a configuration may hold is declared once, with the unit the user writes and the range a
physical set-up can have (and a size bound on anything that allocates: counts, durations over
intervals, reaches). The checks give one message style, naming what the user WROTE, in the unit
the user wrote it, with the file and line::

    scale.toml:9: [compensator] counts_per_period = 1000000000 must be at most 65536
    scale.toml:14: unknown key [air] temprature; known: humidity, pressure, temperature ...
    scale.toml: unknown table [foo]; known: air, compensator, laser ...
    scale.toml: the file is empty; it needs a [gantry] table (see examples/scale_gantry.toml)
    --duration-min = -5 min must be more than 0 min

How to adopt it in a reader (a new command's configuration)::

    from axiscal._schema import Num, Text, Flag, Schema

    SCHEMA = Schema({
        "probe": {"radius_mm": Num("mm", lo=1, hi=2000, required=True),
                  "samples": Num("", lo=2, hi=100_000, integer=True, default=360),
                  "name": Text(default="")},
    }, required=("probe",), example="examples/probe.toml")
    cfg = SCHEMA.parse(read_text(path), str(path))   # read_text from axiscal.io._files
    # -> {"probe": {"radius_mm": 150.0, "samples": 360, "name": ""}}

and for an option: ``check_option("--radius", radius, "mm", lo=0, lo_open=True, hi=2000)``.

Why not pydantic (or another validation library): importing pydantic costs about 45 ms of the
CLI's start-up budget (ISO 230-2 ``--json`` in under twice ``python -c "import numpy"``), and its
messages name the internal model fields, not the TOML line the user wrote. This module is stdlib
only (``tomllib``, ``re``) and costs well under a millisecond to import.
"""

from __future__ import annotations

import math
import re
from dataclasses import dataclass, field
from typing import Any

from axiscal.errors import ConfigError, InputError

__all__ = ["SchemaError", "Free", "Num", "Text", "Flag", "Schema", "check_option", "show", "MAX_MAGNITUDE",
           "remember_document", "refuse_unknown", "document_sources", "loads_toml",
           "MAX_TOML_BYTES"]

#: No length, angle, time, temperature or rate a machine-tool set-up has comes near this; a value
#: beyond it is a typing slip (and squaring it overflows a float).
MAX_MAGNITUDE = 1e12


def show(v: Any) -> str:
    """A value as the user would have typed it (``1e+308`` as ``1e308``, text quoted)."""
    if isinstance(v, bool):
        return "true" if v else "false"
    if isinstance(v, float):
        s = repr(v)
        return s.replace("e+", "e")
    if isinstance(v, int):
        return str(v)
    if isinstance(v, str):
        return repr(v)
    return type(v).__name__ if isinstance(v, (dict, list)) and len(repr(v)) > 60 else repr(v)


def _g(x: float, unit: str) -> str:
    text = f"{x:g}".replace("e+0", "e").replace("e+", "e")
    return f"{text} {unit}" if unit else text


@dataclass(frozen=True)
class Num:
    """A number in ``unit`` (what the user writes), within ``[lo, hi]``; ``integer`` for counts."""

    unit: str = ""
    lo: float | None = None
    hi: float | None = None
    lo_open: bool = False
    integer: bool = False
    default: Any = None
    required: bool = False

    def check(self, v: Any, name: str) -> float | int:
        """The value, or an error message (raised by the caller as it knows the file/line).

        Text with a unit (``"0.1 m"``, ``"293.15 K"``) is read in ``unit`` by pint, where the
        unit is one pint knows (:func:`axiscal.units.quantity`; a unit of K is a difference)."""
        shown = f"{name} = {show(v)}{' ' + self.unit if self.unit and _is_num(v) else ''}"
        if isinstance(v, str) and not self.integer and self.unit not in _NOT_PINT:
            v = _from_text(v, self.unit, name)
        if self.integer:
            if not (_is_num(v) and isinstance(v, int)):
                raise _Bad(f"{shown} must be a whole number")
        elif not _is_num(v):
            raise _Bad(f"{shown} must be a number{' in ' + self.unit if self.unit else ''}")
        if not math.isfinite(v):
            raise _Bad(f"{shown} must be a finite number")
        lo, hi = self.lo, self.hi
        if hi is None and not self.integer:
            hi = MAX_MAGNITUDE
        if lo is None and not self.integer:
            lo = -MAX_MAGNITUDE
        if lo is not None and (v <= lo if self.lo_open else v < lo):
            rule = "more than" if self.lo_open else "at least"
            raise _Bad(f"{shown} must be {rule} {_g(lo, self.unit)}")
        if hi is not None and v > hi:
            raise _Bad(f"{shown} must be at most {_g(hi, self.unit)}")
        return int(v) if self.integer else float(v)


#: Units of :class:`Num` that pint does not read (a count, a relative humidity, no unit).
_NOT_PINT = ("", "counts", "%RH", "%RH/s")
#: A :class:`Num`'s unit as pint writes it, where the two differ.
_PINT = {"°C": "degC", "m/s²": "m/s**2", "µm": "um", "µm/m": "um/m", "µs": "us",
         "µmol/mol": "umol/mol"}
_LEADING_NUMBER = re.compile(r"\s*[-+]?(?:\d|\.\d)")


def _from_text(v: str, unit: str, name: str) -> Any:
    """``v``, text, as a number in ``unit``; text without a leading number is left for
    :meth:`Num.check` to refuse as before (``must be a number in mm``)."""
    if not _LEADING_NUMBER.match(v):
        return v
    from axiscal.units import quantity

    try:
        return quantity(v, _PINT.get(unit, unit), difference=unit in ("K", "K/s"))
    except InputError as exc:
        raise _Bad(f"{name} = {show(v)}: {str(exc).split(': ', 1)[-1]}") from None


@dataclass(frozen=True)
class Text:
    """A text value, optionally one of ``choices`` (compared case-insensitively)."""

    choices: tuple[str, ...] = ()
    default: Any = None
    required: bool = False

    def check(self, v: Any, name: str) -> str:
        if not isinstance(v, str):
            raise _Bad(f"{name} = {show(v)} must be text in quotes")
        if self.choices and v.strip().lower() not in [c.lower() for c in self.choices]:
            raise _Bad(f"{name} = {show(v)} must be one of {', '.join(self.choices)}")
        return v


@dataclass(frozen=True)
class Flag:
    """``true`` or ``false``."""

    default: Any = None
    required: bool = False

    def check(self, v: Any, name: str) -> bool:
        if not isinstance(v, bool):
            raise _Bad(f"{name} = {show(v)} must be true or false")
        return v


@dataclass(frozen=True)
class Free:
    """A key whose value the reader checks itself (one of several types, e.g. 3 or "auto")."""

    default: Any = None
    required: bool = False

    def check(self, v: Any, name: str) -> Any:
        return v


class SchemaError(Exception):
    """A value breaks its declared rule (the caller adds the file and line)."""


_Bad = SchemaError


#: Largest configuration file read, bytes: axiscal's configurations are a few kilobytes; a larger
#: one holds something else (a 200 MB string would become a 200 MB report).
MAX_TOML_BYTES = 1024 * 1024
#: Most parts a dotted key (``a.b.c``) may have: tomllib's time grows with the square of it
#: (20,000 parts: 9 s; 200,000 would take hours).
MAX_KEY_PARTS = 32
_DOTTED = re.compile(r"""(?:(?:[A-Za-z0-9_-]+|"[^"\n]*"|'[^'\n]*')[ \t]*\.[ \t]*){%d,}"""
                     % MAX_KEY_PARTS)


def loads_toml(text: str, source: str = "<text>") -> dict:
    """``tomllib.loads(text)`` once the text is bounded: its size (:data:`MAX_TOML_BYTES`), the
    nesting of its arrays and tables (``axiscal._parse.MAX_NESTING``) and the parts of a dotted
    key (:data:`MAX_KEY_PARTS`), so no input makes the parser recurse or run for minutes; a
    syntax error is a :class:`ConfigError` naming the file.

    Examples
    --------
    >>> loads_toml("a = [[1], [2]]")
    {'a': [[1], [2]]}
    >>> loads_toml("x = " + "[" * 3000 + "]" * 3000, "job.toml")
    Traceback (most recent call last):
    ...
    axiscal.errors.ConfigError: job.toml: arrays or tables nest more than 64 deep; no axiscal configuration nests so deep
    """
    import tomllib

    from axiscal._parse import MAX_NESTING, nesting_depth

    if len(text) > MAX_TOML_BYTES:
        raise ConfigError(f"{source}: {len(text.encode()) / 2**20:.1f} MiB is too large for a "
                          f"configuration (at most {MAX_TOML_BYTES // 2**20} MiB)")
    if nesting_depth(text) > MAX_NESTING:
        raise ConfigError(f"{source}: arrays or tables nest more than {MAX_NESTING} deep; no "
                          "axiscal configuration nests so deep")
    if _DOTTED.search(text):
        raise ConfigError(f"{source}: a dotted key has more than {MAX_KEY_PARTS} parts; no "
                          "axiscal configuration has such a key")
    try:
        return tomllib.loads(text)
    except tomllib.TOMLDecodeError as exc:
        raise ConfigError(f"{source}: not valid TOML: {exc}") from None
    except RecursionError:   # pragma: no cover - the nesting is bounded first
        raise ConfigError(f"{source}: arrays or tables nest too deep") from None


def _is_num(v: Any) -> bool:
    return isinstance(v, (int, float)) and not isinstance(v, bool)


@dataclass(frozen=True)
class Schema:
    """The tables of a configuration file and the keys of each (see the module docstring).

    ``arrays`` names tables written ``[[name]]`` (an array of tables); ``required`` names tables
    that must be present and not empty; ``example`` is a file the messages point to.
    """

    tables: dict[str, dict[str, Any]]
    required: tuple[str, ...] = ()
    arrays: tuple[str, ...] = ()
    example: str = ""
    extra_top: tuple[str, ...] = field(default=())

    def parse(self, text: str, source: str = "<text>") -> dict[str, Any]:
        """Check ``text``; return each table with its values (defaults filled in)."""
        doc = loads_toml(text, source)
        lines = _Lines(text, source)
        see = f" (see {self.example})" if self.example else ""
        if not doc and (self.required or self.tables):
            need = (f"it needs a [{'], ['.join(self.required)}] table" if self.required
                    else f"give at least one of [{'], ['.join(self.tables)}]")
            raise ConfigError(f"{source}: the file is empty; {need}{see}")
        for name in doc:
            if name not in self.tables:
                raise ConfigError(f"{lines.where(name, None)}: unknown table [{name}]; known: "
                                  f"{', '.join(sorted(self.tables))}")
        for name in self.required:
            if not doc.get(name):
                raise ConfigError(f"{source}: [{name}] is missing or empty; it is required{see}")
        out: dict[str, Any] = {}
        for name, keys in self.tables.items():
            value = doc.get(name, [] if name in self.arrays else {})
            if name in self.arrays:
                if not isinstance(value, list):
                    raise ConfigError(f"{lines.where(name, None)}: write [[{name}]] (an array of "
                                      "tables), not [{name}]")
                out[name] = [self._table(name, t, keys, lines) for t in value]
            else:
                out[name] = self._table(name, value, keys, lines)
        return out

    @staticmethod
    def _table(name, t, keys, lines) -> dict[str, Any]:
        if not isinstance(t, dict):
            raise ConfigError(f"{lines.where(name, None)}: [{name}] must be a table, "
                              f"got {show(t)}")
        for key in t:
            if key not in keys:
                raise ConfigError(f"{lines.where(name, key)}: unknown key [{name}] {key}; known: "
                                  f"{', '.join(sorted(keys))}")
        out = {}
        for key, spec in keys.items():
            if key not in t:
                if spec.required:
                    raise ConfigError(f"{lines.where(name, None)}: [{name}] needs {key}")
                out[key] = spec.default
                continue
            try:
                out[key] = spec.check(t[key], f"[{name}] {key}")
            except _Bad as exc:
                message = str(exc)
                written = lines.written(name, key)
                if written is not None:   # the value as typed: 1e12, not 1000000000000.0
                    message = message.replace(f"= {show(t[key])}", f"= {written}", 1)
                raise ConfigError(f"{lines.where(name, key)}: {message}") from None
        return out


class _Lines:
    """Where a table header or a key is in the TOML text: ``file:line`` (``file`` if not found)."""

    _HEADER = re.compile(r"^\s*\[\[?\s*([^\]]+?)\s*\]\]?")
    _KEY = re.compile(r"^\s*([A-Za-z0-9_\-\"']+)\s*=")

    def __init__(self, text: str, source: str):
        self.text, self.source = text, source

    def written(self, table: str, key: str) -> str | None:
        """The text of ``key``'s value as written on its line (no comment), if simple."""
        line = self._find(table, key)
        if line is None:
            return None
        value = self.text.splitlines()[line - 1].split("=", 1)[1].split("#", 1)[0].strip()
        return value if value and value[0] not in "[{\"'" else None

    def where(self, table: str, key: str | None) -> str:
        line = self._find(table, key)
        return self.source if line is None else f"{self.source}:{line}"

    def _find(self, table: str, key: str | None) -> int | None:
        current = ""
        for i, line in enumerate(self.text.splitlines(), 1):
            h = self._HEADER.match(line)
            if h:
                current = h.group(1).strip().strip('"')
                if key is None and current == table:
                    return i
                continue
            k = self._KEY.match(line)
            if k and current == table and key is not None and k.group(1).strip("\"'") == key:
                return i
        return None


def check_option(name: str, value, unit: str = "", lo: float | None = None,
                 hi: float | None = None, lo_open: bool = False, integer: bool = False):
    """Check a command-line number in the unit the user typed it; ``None`` passes through.

    Examples
    --------
    >>> check_option("--duration-min", 60.0, "min", lo=0, lo_open=True, hi=10_080)
    60.0
    >>> check_option("--duration-min", -5.0, "min", lo=0, lo_open=True)
    Traceback (most recent call last):
    ...
    axiscal.errors.InputError: --duration-min = -5 min must be more than 0 min
    """
    if value is None:
        return None
    shown = value
    if isinstance(value, float) and value.is_integer() and abs(value) < 1e15:
        shown = int(value)   # the user typed "-5", click made it -5.0
    try:
        Num(unit, lo, hi, lo_open, integer).check(shown if integer else value, name)
    except _Bad as exc:
        raise InputError(str(exc).replace(f"= {show(value)}", f"= {show(shown)}", 1)) from None
    return value


# -- unknown tables and keys in readers that do not declare a Schema -------------------------------
#: The TOML documents read lately (the parsed dict, its file name and its text), newest last, so a
#: reader handed only a table can still say where the table is: ``file:line``.
_DOCUMENTS: list[tuple[dict, str, str]] = []


def remember_document(doc: dict, source: str, text: str) -> dict:
    """Note where ``doc`` (parsed from ``text``) came from; :func:`refuse_unknown` finds it."""
    _DOCUMENTS.append((doc, source, text))
    del _DOCUMENTS[:-8]
    return doc


def forget_documents() -> None:
    """Start afresh (each command invocation reads its own files)."""
    _DOCUMENTS.clear()


def document_sources() -> list[str]:
    """The files of the TOML documents read so far (each once, oldest first)."""
    return list(dict.fromkeys(source for _, source, _ in _DOCUMENTS))


def _path_to(node: Any, target: Any, path: tuple, same) -> tuple | None:
    if same(node, target):
        return path
    if isinstance(node, dict):
        for k, v in node.items():
            if isinstance(v, (dict, list)):
                found = _path_to(v, target, path + (k,), same)
                if found is not None:
                    return found
    elif isinstance(node, list):
        for v in node:
            if isinstance(v, (dict, list)):
                found = _path_to(v, target, path, same)
                if found is not None:
                    return found
    return None


def _locate(table: dict, key: str | None) -> tuple[str, str | None]:
    """``(file:line or file or "", the table's dotted name or None)`` for a key of ``table``:
    the document holding this very table, else one holding an equal table (a reader's copy)."""
    for same in ((lambda a, b: a is b), (lambda a, b: isinstance(a, dict) and a == b)):
        for doc, source, text in reversed(_DOCUMENTS):
            path = _path_to(doc, table, (), same)
            if path is not None:
                name = ".".join(path)
                lines = _Lines(text, source)
                if not name and key is not None and isinstance(table.get(key), (dict, list)):
                    return lines.where(key, None), None     # a table: its [header] line
                return lines.where(name, key), name or None
    return "", None


def refuse_unknown(table: Any, known, where: str = "") -> None:
    """Refuse a key of ``table`` outside ``known`` (or ``table`` not being a table) in the one
    message style of :class:`Schema`: ``file:line: unknown key [axis] typo; known: a, b``, and
    ``file:line: unknown table [foo]; known: ...`` for the top level of a document.

    ``where`` names the table (``"[axis] periodic[1]"``) when it is not found in a document read
    through :func:`axiscal.io._files.load_toml`; the top level is ``""``.
    """
    if not isinstance(table, dict):
        raise ConfigError(f"{where or 'the configuration'} must be a table, got {show(table)}")
    unknown = [k for k in table if k not in known]
    if not unknown:
        return
    key = unknown[0]
    loc, name = _locate(table, key)
    if name is None and where not in ("", "top level") and not loc:
        name = where.strip("[]") if where.startswith("[") and where.endswith("]") else None
        label = f"[{name}]" if name else where
    else:
        label = f"[{name}]" if name else ""
    value = table[key]
    if label:
        what = f"unknown key {label} {key}"
    elif isinstance(value, dict) or (isinstance(value, list) and value
                                     and all(isinstance(v, dict) for v in value)):
        what = f"unknown table [{key}]"
    else:
        what = f"unknown key {key}"
    message = f"{what}; known: {', '.join(sorted(known))}"
    raise ConfigError(f"{loc}: {message}" if loc else message)
