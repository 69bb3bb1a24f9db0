"""The limits of every text field the history stores, enforced at the edge with the field named.

SQLite stores a text of any length in a ``VARCHAR(200)`` column; PostgreSQL refuses it ("value
too long for type character varying(200)", naming no field) or, for a lone surrogate, the
driver fails with a traceback. So the limits are read from the models' own column lengths and
checked before a row is made, the same on both databases (issue 39: a 5,000-character
instrument was stored on SQLite and refused on PostgreSQL).
"""

from __future__ import annotations

import re

from axiscal.errors import InputError

__all__ = ["column_length", "checked_text", "checked_tables", "control_character"]

#: Control characters (C0, DEL, C1) and the bidirectional controls (U+061C, U+200E, U+200F,
#: U+202A-U+202E, U+2066-U+2069, Unicode Standard Annex #9 "Unicode Bidirectional Algorithm",
#: table 4): a name holding one (a line break, an ESC starting a terminal colour, a right-to-left
#: override reversing what follows) breaks or falsifies every listing, report, certificate,
#: controller file and archive line it is written into. A multi-line field (an address, a note,
#: a reason) holds line breaks (``\n``) and nothing else of them.
_CONTROL = re.compile("[\x00-\x1f\x7f-\x9f\u061c\u200e\u200f\u202a-\u202e\u2066-\u2069]")
#: The names of the control characters a person may have typed or pasted.
_NAMES = {0x00: "NUL", 0x07: "BEL", 0x08: "BS", 0x09: "TAB", 0x0A: "a line break",
          0x0D: "a carriage return", 0x1B: "ESC", 0x7F: "DEL",
          0x061C: "ARABIC LETTER MARK", 0x200E: "LEFT-TO-RIGHT MARK",
          0x200F: "RIGHT-TO-LEFT MARK", 0x202A: "LEFT-TO-RIGHT EMBEDDING",
          0x202B: "RIGHT-TO-LEFT EMBEDDING", 0x202C: "POP DIRECTIONAL FORMATTING",
          0x202D: "LEFT-TO-RIGHT OVERRIDE", 0x202E: "RIGHT-TO-LEFT OVERRIDE",
          0x2066: "LEFT-TO-RIGHT ISOLATE", 0x2067: "RIGHT-TO-LEFT ISOLATE",
          0x2068: "FIRST STRONG ISOLATE", 0x2069: "POP DIRECTIONAL ISOLATE"}
#: Keys of a configuration's or job's tables whose text may span lines (one line each).
MULTI_LINE_KEYS = frozenset({"address", "note", "reason", "notes"})


def column_length(model, column: str) -> int | None:
    """The declared length of ``model.column`` (``String(200)`` -> 200; None for ``Text``)."""
    return getattr(model.__table__.c[column].type, "length", None)


def checked_text(value: str, field: str, model=None, column: str | None = None, *,
                 limit: int | None = None, single_line: bool = True) -> str:
    """``value`` if it fits ``model.column`` (or ``limit``), is UTF-8 text and, for a
    ``single_line`` field (a name), holds no control character (C0, DEL, C1) nor a
    bidirectional control, and a multi-line one none but line breaks (``\\r\\n`` made
    ``\\n``); else an :class:`InputError` naming ``field`` and the character.

    Examples
    --------
    >>> from axiscal.store.models import Test
    >>> checked_text("laser XL-80", "instrument", Test, "instrument")
    'laser XL-80'
    >>> checked_text("x" * 5000, "instrument", Test, "instrument")
    Traceback (most recent call last):
    ...
    axiscal.errors.InputError: instrument of 5000 characters; the history keeps at most 200
    >>> checked_text("VMC\\nM30", "machine name")
    Traceback (most recent call last):
    ...
    axiscal.errors.InputError: machine name 'VMC\\nM30' holds a control character U+000A (a line break); give it on one line
    >>> checked_text("Kunde\\u202eGA", "customer name")
    Traceback (most recent call last):
    ...
    axiscal.errors.InputError: customer name 'Kunde\\u202eGA' holds a control character U+202E (RIGHT-TO-LEFT OVERRIDE); type it again without it
    """
    text = "" if value is None else str(value)
    if not single_line:
        text = text.replace("\r\n", "\n")
    if limit is None and model is not None:
        limit = column_length(model, column or field)
    if limit is not None and len(text) > limit:
        raise InputError(f"{field} of {len(text)} characters; the history keeps at most {limit}")
    try:
        text.encode("utf-8")
    except UnicodeEncodeError:
        raise InputError(f"{field} {text[:40].encode('utf-8', 'replace').decode()!r} is not "
                         "UTF-8 text (it holds a lone surrogate)") from None
    bad = control_character(text, single_line)
    if bad:
        raise InputError(f"{field} {text[:60]!r} holds a control character {bad}"
                         + ("; give it on one line" if bad.endswith("line break)") else
                            "; type it again without it"))
    return text


def control_character(text: str, single_line: bool = True) -> str:
    """The first control or bidirectional-control character of ``text`` as ``U+001B (ESC)``
    ('' when none); a line break (``\\n``) is allowed where not ``single_line``.

    Examples
    --------
    >>> control_character("Kunde\\x1b[31mAG")
    'U+001B (ESC)'
    >>> control_character("Werkstr. 5\\nBerlin", single_line=False)
    ''
    """
    for m in _CONTROL.finditer(text):
        if m.group() == "\n" and not single_line:
            continue
        c = ord(m.group())
        return f"U+{c:04X}" + (f" ({_NAMES[c]})" if c in _NAMES else "")
    return ""


def checked_tables(tables, where: str = "", *, limit: int | None = None):
    """``tables`` (a configuration's, a job's or the laboratory's: dicts, lists, texts,
    numbers) if every text in it passes :func:`checked_text`; a text under a key of
    :data:`MULTI_LINE_KEYS` may hold line breaks. Each text is named ``[table] key`` (the
    configuration file's words) after ``where``.

    Examples
    --------
    >>> checked_tables({"customer": {"name": "Kunde\\x1b[31mAG"}}, "job.toml:")
    Traceback (most recent call last):
    ...
    axiscal.errors.InputError: job.toml: [customer] name 'Kunde\\x1b[31mAG' holds a control character U+001B (ESC); type it again without it
    """
    _walk(tables, where, (), limit)
    return tables


def _walk(value, where: str, path: tuple, limit) -> None:
    if isinstance(value, dict):
        for k, v in value.items():
            _walk(str(k), where, (*path, "(a key)"), limit)
            _walk(v, where, (*path, str(k)), limit)
    elif isinstance(value, (list, tuple)):
        for v in value:
            _walk(v, where, path, limit)
    elif isinstance(value, str):
        keys = [p for p in path if p != "(a key)"]
        name = (f"[{keys[0]}] " + " ".join(keys[1:]) if len(keys) > 1 else
                (keys[0] if keys else "text"))
        if path and path[-1] == "(a key)":
            name = f"a key of [{keys[0]}]" if keys else "a table's name"
        checked_text(value, f"{where} {name}".strip(), limit=limit,
                     single_line=not (keys and keys[-1] in MULTI_LINE_KEYS))
