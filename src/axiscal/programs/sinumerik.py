"""SINUMERIK 840D sl: the Siemens programming language (DIN 66025 with Siemens extensions).

SINUMERIK 840D sl Programming Manual "Fundamentals": comments after ``;``, G70/G71 inch/metric,
G17-G19 planes, G90 absolute, G94 feed in mm/min, G0, G1, G2/G3 with I, J, K the centre from the
start point (incremental by default), "Dwell time (G4)": ``G4 F…`` in seconds, "Spindle speed
(S), direction of rotation (M3, M4, M5)", M30 end of program.
The first two lines are the header of the punched-tape (archive) format in which a main program
(``_MPF``) travels to the control: ``%_N_<NAME>_MPF`` and ``;$PATH=/_N_MPF_DIR`` (SINUMERIK
Operate operating manual, "Archiving programs in punched tape format").

A rotary axis is commanded in degrees as a linear-type (not modulo) axis: on a modulo axis the
overrun past 360 would need ``C=DC(…)``/``ACP``/``ACN``; the program's comment says so.
"""

from __future__ import annotations

from axiscal.programs._dialect import number
from axiscal.programs._motion import ProgramError
from axiscal.programs.iso import Fanuc

__all__ = ["Sinumerik"]


class Sinumerik(Fanuc):
    name = "sinumerik"
    manual = "SINUMERIK 840D sl Programming Manual Fundamentals: G4 F (seconds), ; comments, M30"
    extension = ".mpf"

    def begin(self) -> None:
        self.emit(f"%_N_{self.program_name}_MPF")
        self.emit(";$PATH=/_N_MPF_DIR")
        self.emit(f"{'G71' if self.m.metric else 'G70'} G17 G40 G90 G94")

    def end(self) -> None:
        self.emit("M30")

    def comment(self, text: str) -> str:
        return f"; {text}"

    def comment_text(self, text: str) -> str:
        from axiscal.programs._dialect import plain

        return plain(text)

    def rapid(self, b, final=False) -> str:
        return f"G0 {self.words(b.to)}"

    def feed(self, b) -> str:
        return f"G1 {self.words(b.to)} F{number(b.feed, 1)}"

    def arc(self, b) -> str:
        plane = {"XY": "", "ZX": "G18 ", "YZ": "G19 "}.get(b.plane)
        if plane is None:
            raise ProgramError("plane", f"plane {b.plane}: the planes are XY, ZX and YZ")
        return (f"{plane}{'G3' if b.ccw else 'G2'} {self.words(b.end)} {self.centre_offsets(b)} "
                f"F{number(b.feed, 1)}")

    def dwell(self, seconds: float) -> list:
        return [f"G4 F{number(seconds, 3)}"]

    def spindle(self, rpm: int) -> list:
        return [f"S{rpm:d} M3"] if rpm else ["M5"]
