"""HEIDENHAIN Klartext (conversational) programs, TNC 640 / TNC 620.

HEIDENHAIN TNC 640 User's Manual for Klartext Programming: "Program structure" (``0 BEGIN PGM
<name> MM`` … ``END PGM <name> MM``, blocks numbered from 0, ``INCH`` programs), "Path
functions" (``L`` straight line, ``FMAX`` rapid traverse, ``R0`` no radius compensation, ``F`` in
mm/min, in an inch program in 0.1 inch/min; ``CC`` circle centre, ``C`` circular path with
``DR+`` counter-clockwise and ``DR−`` clockwise; coordinates with their sign), "Comments" (``;``);
Cycle Programming manual, "DWELL TIME (Cycle 9)": ``CYCL DEF 9.0 DWELL TIME`` then
``CYCL DEF 9.1 DWELL <s>`` (0 to 3600 s: a longer dwell is written as several); "Tool call"
(``TOOL CALL Z S<rpm>``: a tool call without a tool number changes the spindle speed) and
"Miscellaneous functions" (``L M3`` spindle on clockwise, ``L M5`` off: an ``L`` block with only an
M function); M30 (end of program) in the last move, or ``L M30`` after a last block that is not one.

The circle is in the working plane, which the TOOL CALL's tool axis sets (Z: the XY plane): a
test in YZ or ZX needs a tool call with the X or Y axis before it (the program's comment says so).
"""

from __future__ import annotations

from axiscal.programs._dialect import Dialect, number, plain

__all__ = ["Heidenhain"]

#: Cycle 9's input range ends at an hour, s.
MAX_DWELL_S = 3600.0


class Heidenhain(Dialect):
    name = "heidenhain"
    manual = ("HEIDENHAIN TNC 640 User's Manual Klartext: BEGIN PGM/END PGM, L ... FMAX, CC/C DR+, "
              "Cycle 9 DWELL TIME")
    extension = ".h"

    def unit_word(self) -> str:
        return "MM" if self.m.metric else "INCH"

    def begin(self) -> None:
        self.emit(f"BEGIN PGM {self.program_name} {self.unit_word()}")
        if self.m.plane and self.m.plane != "XY":
            self.emit(self.comment(f"THE {self.m.plane} PLANE NEEDS A TOOL CALL WITH THE "
                                   f"{'X' if self.m.plane == 'YZ' else 'Y'} TOOL AXIS BEFORE THIS"))

    def end(self) -> None:
        if not self.lines[-1].endswith(" M30"):
            self.emit("L M30")
        self.emit(f"END PGM {self.program_name} {self.unit_word()}")

    def emit(self, line: str) -> None:
        self.lines.append(f"{len(self.lines)} {line}")

    def comment(self, text: str) -> str:
        return f"; {text}"

    def comment_text(self, text: str) -> str:
        return plain(text)

    def f(self, feed: float) -> str:
        return f"F{round(feed if self.m.metric else feed * 10)}"

    def rapid(self, b, final=False) -> str:
        return f"L {self.words(b.to, True)} R0 FMAX" + (" M30" if final else "")

    def feed(self, b) -> str:
        return f"L {self.words(b.to, True)} R0 {self.f(b.feed)}"

    def arc(self, b) -> str:
        cc = f"CC {self.words(b.centre, True)}"
        if getattr(self, "_cc", None) != cc:      # CC is modal: written when it changes
            self.emit(cc)
            self._cc = cc
        return f"C {self.words(b.end, True)} DR{'+' if b.ccw else '-'} R0 {self.f(b.feed)}"

    def dwell(self, seconds: float) -> list:
        out = []
        while seconds > 1e-9:
            piece = min(seconds, MAX_DWELL_S)
            out += ["CYCL DEF 9.0 DWELL TIME", f"CYCL DEF 9.1 DWELL {number(piece, 3)}"]
            seconds -= piece
        return out

    def spindle(self, rpm: int) -> list:
        return [f"TOOL CALL Z S{rpm:d}", "L M3"] if rpm else ["L M5"]
