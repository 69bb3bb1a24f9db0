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

__all__ = ["column_length", "checked_text"]

#: Control characters (C0, DEL, C1): a name holding one (a line break) breaks every listing,
#: report and archive line it is written into.
_CONTROL = re.compile(r"[\x00-\x1f\x7f-\x9f]")


def column_length(model, column: str) -> int | None:
    """The declared length of ``model.column`` (``String(200)`` -> 200; None for ``Text``)."""
    return getattr(model.__table__.c[column].type, "length", None)


def checked_text(value: str, field: str, model=None, column: str | None = None, *,
                 limit: int | None = None, single_line: bool = True) -> str:
    """``value`` if it fits ``model.column`` (or ``limit``), is UTF-8 text and, for a
    ``single_line`` field (a name), holds no control character; else an :class:`InputError`
    naming ``field``.

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
    axiscal.errors.InputError: machine name 'VMC\\nM30' holds a control character (a line break or the like); give it on one line
    """
    text = "" if value is None else str(value)
    if limit is None and model is not None:
        limit = column_length(model, column or field)
    if limit is not None and len(text) > limit:
        raise InputError(f"{field} of {len(text)} characters; the history keeps at most {limit}")
    try:
        text.encode("utf-8")
    except UnicodeEncodeError:
        raise InputError(f"{field} {text[:40].encode('utf-8', 'replace').decode()!r} is not "
                         "UTF-8 text (it holds a lone surrogate)") from None
    if single_line and _CONTROL.search(text):
        raise InputError(f"{field} {text[:60]!r} holds a control character (a line break or "
                         "the like); give it on one line")
    return text
