"""LinuxCNC: RS274/NGC as LinuxCNC's G-code reference documents it.

LinuxCNC documentation, "G-Code Overview" (``%`` file demarcation: a file that starts with
``%`` runs to the next ``%``; comments in parentheses; numbers with a decimal point), "G Codes"
(G0, G1, G2/G3 with I, J, K the centre from the start point, G4 "P — seconds to dwell", G17-G19,
G20/G21, G40, G49, G80, G90, G94), "M Codes" (M2 program end). LinuxCNC reads the same safe-start
block as the ISO controllers.
"""

from __future__ import annotations

from axiscal.programs._dialect import number
from axiscal.programs.iso import Fanuc

__all__ = ["LinuxCNC"]


class LinuxCNC(Fanuc):
    name = "linuxcnc"
    manual = "LinuxCNC G-code reference: % demarcation, G4 P (seconds), M2"
    extension = ".ngc"

    def begin(self) -> None:
        self.emit("%")
        self.emit(f"({self.program_name})")
        self.emit(f"{'G21' if self.m.metric else 'G20'} G17 G40 G49 G80 G90 G94")

    def end(self) -> None:
        self.emit("M2")
        self.emit("%")

    def rapid(self, b, final=False) -> str:
        return f"G0 {self.words(b.to)}"

    def feed(self, b) -> str:
        return f"G1 {self.words(b.to)} F{number(b.feed, 1)}"

    def arc(self, b) -> str:
        return super().arc(b).replace("G03 ", "G3 ").replace("G02 ", "G2 ")

    def dwell(self, seconds: float) -> list:
        return [f"G4 P{number(seconds, 3)}"]

    def spindle(self, rpm: int) -> list:
        return [f"S{rpm:d} M3"] if rpm else ["M5"]
