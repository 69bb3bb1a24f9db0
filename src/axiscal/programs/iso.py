"""Fanuc and Haas: ISO 6983 G-code as each documents it.

Fanuc (FANUC Series 0i-MODEL F Operator's Manual, B-64604EN, Part II "Programming": "Program
configuration" (``%`` tape start and end, program number ``O`` and four digits, comments between
control-out ``(`` and control-in ``)``), "Decimal point programming" (a number without a decimal
point is read in least input increments, so every position is written with one), "Dwell (G04)"
(``G04 P…`` in milliseconds, no decimal point), G20/G21 inch/metric, G17 plane, G90 absolute,
G94 feed per minute, G02/G03 with I, J, K the centre from the start point, M30 end of program.

Haas (Haas Mill Operator's Manual, "G-codes": G04 Dwell: "P — the dwell time in seconds or
milliseconds ... G04 P10. is a dwell of 10 seconds; G04 P10 is 10 milliseconds"; "Program
numbers": ``O`` and five digits; the same ``%`` framing, comments and G-codes otherwise).

The safe-start block cancels what a previous program may have left: cutter radius compensation
(G40), tool length compensation (G49) and canned cycles (G80). A rotary axis (A, B, C) is
commanded in degrees; the program assumes it does not roll over (its comment says so).
"""

from __future__ import annotations

from axiscal.programs._dialect import Dialect, number
from axiscal.programs._motion import ProgramError

__all__ = ["Fanuc", "Haas"]


class Fanuc(Dialect):
    name = "fanuc"
    manual = ("FANUC Series 0i-MODEL F Operator's Manual B-64604EN: program configuration, "
              "decimal point programming, dwell G04 P (ms)")
    extension = ".nc"
    digits_of_number = 4

    def begin(self) -> None:
        n = 1 if self.number is None else self.number
        top = 10 ** self.digits_of_number - 1
        if not (isinstance(n, int) and 1 <= n <= top):
            raise ProgramError("number", f"number {n!r}: a {self.name} program number is 1 to "
                               f"{top}")
        self.emit("%")
        self.emit(f"O{n:0{self.digits_of_number}d} ({self.program_name})")
        self.emit(f"{'G21' if self.m.metric else 'G20'} G17 G40 G49 G80 G90 G94")

    def end(self) -> None:
        self.emit("M30")
        self.emit("%")

    def rapid(self, b, final=False) -> str:
        return f"G00 {self.words(b.to)}"

    def feed(self, b) -> str:
        return f"G01 {self.words(b.to)} F{number(b.feed, 1)}"

    def arc(self, b) -> str:
        plane = {"XY": "G17", "ZX": "G18", "YZ": "G19"}.get(b.plane, "")
        if not plane:
            raise ProgramError("plane", f"plane {b.plane}: the ISO planes are XY, ZX and YZ")
        g = "G03" if b.ccw else "G02"
        if b.plane != "XY":          # the safe-start block selected G17
            g = f"{plane} {g}"
        return f"{g} {self.words(b.end)} {self.centre_offsets(b)} F{number(b.feed, 1)}"

    def dwell(self, seconds: float) -> list:
        return [f"G04 P{round(seconds * 1000):d}"]


class Haas(Fanuc):
    name = "haas"
    manual = ("Haas Mill Operator's Manual: G04 dwell (P. in seconds), program numbers O and "
              "five digits")
    digits_of_number = 5

    def dwell(self, seconds: float) -> list:
        return [f"G04 P{number(seconds, 3)}"]
