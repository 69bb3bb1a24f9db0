"""What every controller language shares: the walk over a :class:`~axiscal.programs._motion.Motion`
and the number words. A dialect is a :class:`Dialect` subclass that says how each block is
written; :meth:`Dialect.write` gives the program's text."""

from __future__ import annotations

import re

from axiscal.programs._motion import (ArcMove, Comment, Dwell, Feed, Motion, ProgramError,
                                      Rapid, Spindle)

__all__ = ["Dialect", "number", "plain"]

#: Digits after the decimal point: a micrometre (mm), a tenth of a thou (inch), a millidegree,
#: the least input increment IS-B of the ISO controllers (Fanuc, Haas) and the display
#: resolution of the others.
DIGITS = {"mm": 3, "inch": 4, "deg": 3}


def number(value: float, digits: int, plus: bool = False) -> str:
    """``value`` with ``digits`` decimals and always a decimal point (no ``-0``); ``plus`` writes
    the sign of a positive number too (HEIDENHAIN)."""
    text = f"{value:.{digits}f}"
    if float(text) == 0:
        text = text.lstrip("-")
    if plus and not text.startswith("-"):
        text = "+" + text
    return text


def plain(text: str, allowed: str = r"A-Za-z0-9 .,:=+\-/_") -> str:
    """``text`` with only the characters a comment may hold (others become spaces)."""
    text = text.replace("°", " deg").replace("µ", "u").replace("×", "x").replace(";", ",")
    text = text.replace("(", "").replace(")", "")
    return re.sub(r"\s+", " ", re.sub(f"[^{allowed}]", " ", text)).strip()


def wrap(text: str, width: int = 60) -> list:
    """``text`` cut into comment lines of at most ``width`` characters, at spaces."""
    out, line = [], ""
    for w in text.split(" "):
        if line and len(line) + 1 + len(w) > width:
            out.append(line)
            line = w
        else:
            line = f"{line} {w}".strip()
    return out + ([line] if line else [])


class Dialect:
    """One controller language. Subclasses set :attr:`name`, :attr:`manual`,
    :attr:`extension` and write the blocks."""

    name = ""
    manual = ""
    extension = ".nc"

    def __init__(self, motion: Motion, program_name: str = "AXISCAL", number_: int | None = None):
        self.m = motion
        self.program_name = self.check_name(program_name)
        self.number = number_
        self.lines: list[str] = []

    # -- the walk ----------------------------------------------------------------------------
    def write(self) -> str:
        self.begin()
        last = len(self.m.blocks) - 1
        for k, b in enumerate(self.m.blocks):
            if isinstance(b, Comment):
                for part in wrap(self.comment_text(b.text)):
                    self.emit(self.comment(part))
            elif isinstance(b, Rapid):
                self.emit(self.rapid(b, final=k == last))
            elif isinstance(b, Feed):
                self.emit(self.feed(b))
            elif isinstance(b, ArcMove):
                self.emit(self.arc(b))
            elif isinstance(b, Dwell):
                for line in self.dwell(b.seconds):
                    self.emit(line)
            elif isinstance(b, Spindle):
                for line in self.spindle(b.rpm):
                    self.emit(line)
        self.end()
        return "\n".join(self.lines) + "\n"

    def emit(self, line: str) -> None:
        self.lines.append(line)

    def word(self, axis: str, value: float, plus: bool = False) -> str:
        return f"{axis}{number(value, DIGITS[self.m.units[axis]], plus)}"

    def words(self, to, plus: bool = False) -> str:
        return " ".join(self.word(a, v, plus) for a, v in to)

    def check_name(self, name: str) -> str:
        if not re.fullmatch(r"[A-Za-z][A-Za-z0-9_]{0,23}", name or ""):
            raise ProgramError("name", f"name {name!r}: give a letter then letters, digits or _, "
                               "at most 24 characters")
        return name.upper()

    def comment_text(self, text: str) -> str:
        return plain(text).upper()

    # -- what each dialect says ---------------------------------------------------------------
    def begin(self) -> None:
        raise NotImplementedError

    def end(self) -> None:
        raise NotImplementedError

    def comment(self, text: str) -> str:
        return f"({text})"

    def rapid(self, b: Rapid, final: bool = False) -> str:
        raise NotImplementedError

    def feed(self, b: Feed) -> str:
        raise NotImplementedError

    def arc(self, b: ArcMove) -> str:
        raise NotImplementedError

    def dwell(self, seconds: float) -> list:
        raise NotImplementedError

    def spindle(self, rpm: int) -> list:
        """Spindle on clockwise at ``rpm`` (``S… M3``), or off (``M5``) when 0: the ISO 6983
        words every G-code dialect here shares."""
        return [f"S{rpm:d} M03"] if rpm else ["M05"]

    def centre_offsets(self, b: ArcMove) -> str:
        """``I… J…`` (``J… K…``, ``K… I…``): the centre from the start, incremental."""
        letters = {"X": "I", "Y": "J", "Z": "K"}
        return " ".join(f"{letters[a]}{number(c - s, DIGITS[self.m.units[a]])}"
                        for (a, s), (_, c) in zip(b.start, b.centre))
