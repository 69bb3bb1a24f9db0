"""LinuxCNC: the joint compensation file (``COMP_FILE``, ``COMP_FILE_TYPE`` 0 or 1).

Sources: LinuxCNC ``src/emc/motion/usrmotintf.cc``, ``usrmotLoadComp(joint, file, type)``: the
file is read line by line with ``sscanf(buffer, "%lf %lf %lf", &nom, &fwd, &rev)``; a line whose
first three fields are numbers is taken (anything after them, such as ``; home``, is ignored) and
reading stops at the first line that is not (so the file carries no comment lines). With type 0
the numbers are *nominal, forward, reverse* positions and the loader stores the trims
``nominal − forward`` and ``nominal − reverse``; with type 1 they are already *nominal,
forward_trim, reverse_trim*. ``src/emc/motion/motion.h``: ``EMCMOT_COMP_SIZE 256`` entries at
most. The INI documentation (``[JOINT_n] COMP_FILE``, ``COMP_FILE_TYPE``; ``[AXIS_n]`` before
2.8). ``src/emc/motion/control.c`` (``compute_screw_comp``): the trim is added to the commanded
joint position, linearly interpolated between entries whatever their spacing (so irregular
nominal positions, such as an ISO 230-2 test's targets, are as good as equidistant ones); beyond
the first and last entries the end trims hold. Plain backlash compensation is the special case
``fwd_trim = +backlash/2``, ``rev_trim = −backlash/2``. The file is in the machine's
``[TRAJ] LINEAR_UNITS``, often inch: LinuxCNC's own sample ``configs/sim/screwcompX.dat`` is a
type-0 file in inch (its nominal positions run −10 … +10).

Here: trim = correction (= −deviation) in the file's unit (``unit="mm"`` or ``"inch"``; tables
inside axiscal stay in mm); type 0 writes ``forward = nominal − correction_up`` and
``reverse = nominal − correction_down``, the positions the uncompensated axis reaches. A file read
with the wrong type shifts every value by its nominal: :func:`parse` refuses trims larger than a
tenth of the table's span and than half a unit (mm or inch), and says which type the file looks
like.

**Limits checked.** At most 256 lines; nominal positions strictly increasing; range inside the
travel. A continuous rotary joint is compensated only over the table's 0…360° (the joint position
is not wrapped): noted, not refused.
"""

from __future__ import annotations

from dataclasses import replace

import numpy as np

from axiscal.compensation.controllers._common import (
    ControllerFile, check_points, check_travel, correction_factor, decimals, file_unit,
    parse_number)
from axiscal.compensation.tables import CompensationTable
from axiscal.datasets import AxisKind
from axiscal.errors import ControllerLimitError, DataFormatError, InputError

__all__ = ["NAME", "write", "parse", "MAX_POINTS"]

NAME = "linuxcnc"
MAX_POINTS = 256


def write(table: CompensationTable, travel=None, *, file_type: int = 1, joint: int = 0,
          max_points: int = MAX_POINTS, unit: str = "mm") -> ControllerFile:
    """Write ``table`` as a LinuxCNC compensation file of ``file_type`` 0 or 1.

    ``unit``: the machine's ``LINEAR_UNITS`` (``mm`` or ``inch``) for a linear joint. Irregular
    positions (a table built at the measured targets) are written as they are.
    """
    if file_type not in (0, 1):
        raise ControllerLimitError(f"{NAME}: COMP_FILE_TYPE = {file_type!r}; LinuxCNC knows 0 and 1")
    check_points(table.n_points, max_points, NAME, "lines (EMCMOT_COMP_SIZE)")
    check_travel(table, travel, NAME)
    mm = file_unit(unit, table, NAME)
    fu = table.position_unit if mm == 1.0 else "in"
    k = correction_factor(table, fu)
    nd = decimals(table.position_unit) + (1 if mm != 1.0 else 0)
    nom = np.round(table.positions / mm, nd)
    fwd = np.round(table.up * k, nd)
    rev = np.round(table.down * k, nd)
    a, b = (nom - fwd, nom - rev) if file_type == 0 else (fwd, rev)
    text = "".join(f"{n:.{nd}f} {x:.{nd}f} {y:.{nd}f}\n" for n, x, y in zip(nom, a, b))
    name = f"{(table.axis or 'joint').lower()}.comp"
    units_word = "inch" if mm != 1.0 else ("mm" if table.position_unit == "mm" else "degree")
    enable = [f"[JOINT_{joint}] COMP_FILE = {name}", f"[JOINT_{joint}] COMP_FILE_TYPE = {file_type}",
              f"the file is in {units_word}: the machine's [TRAJ] LINEAR_UNITS must be "
              f"{units_word}" if table.position_unit == "mm" else "the file is in degrees",
              f"leave [JOINT_{joint}] BACKLASH unset: the file holds both directions"
              if table.bidirectional else "the same trims serve both directions"]
    notes = ["LinuxCNC holds the first and last trims beyond the table: it should cover the "
             "travel"]
    if table.modulo:
        notes.append("continuous rotary joint: compensated only over the table's range (no wrap)")
    if not table.equidistant:
        notes.append(f"{table.n_points} irregular positions (the measured targets); LinuxCNC "
                     "interpolates between any increasing positions")
    written = replace(table, up=fwd / k, down=rev / k,
                      nodes=None if table.equidistant else nom * mm)
    return ControllerFile(NAME, text, name, written, tuple(enable), notes=tuple(notes))


def parse(text: str, source: str = "<text>", file_type: int = 1,
          axis_kind: "AxisKind | str" = "linear", axis: str = "",
          correction_unit: str | None = None, unit: str = "mm") -> CompensationTable:
    """Read a LinuxCNC compensation file (both types, mm or inch) into a table in mm.

    Lines are read as LinuxCNC reads them (three numbers, anything after them ignored); where
    LinuxCNC would silently stop (a line that is not three numbers before the end of the data),
    this parser refuses the file and names the line, since the rest would be lost.
    """
    if file_type not in (0, 1):
        raise InputError(f"{NAME}: file_type = {file_type!r}; COMP_FILE_TYPE is 0 or 1")
    kind = AxisKind.parse(axis_kind)
    mm = file_unit(unit, None, NAME) if kind is AxisKind.LINEAR else 1.0
    rows = []
    for n, raw in enumerate(text.splitlines(), 1):
        if not raw.strip():
            continue
        cells = raw.split()
        try:
            if len(cells) < 3:
                raise ValueError
            [float(c) for c in cells[:3]]
        except ValueError:
            raise DataFormatError("not three numbers (nominal and two values): LinuxCNC stops "
                                  "reading at this line and ignores the rest of the file",
                                  source, n) from None
        rows.append([parse_number(c, source, n) for c in cells[:3]])
    if len(rows) < 2:
        raise DataFormatError(f"{len(rows)} line(s); a compensation file needs at least 2", source)
    arr = np.array(rows)
    nom = arr[:, 0]
    steps = np.diff(nom)
    if np.any(steps <= 0):
        i = int(np.argmax(steps <= 0))
        raise DataFormatError(f"nominal positions must increase strictly: {nom[i]:g} is "
                              f"followed by {nom[i + 1]:g}", source)
    fwd, rev = (nom - arr[:, 1], nom - arr[:, 2]) if file_type == 0 else (arr[:, 1], arr[:, 2])
    _plausible(nom, fwd, rev, file_type, source)
    pu = "mm" if kind is AxisKind.LINEAR else "deg"
    cu = correction_unit or ("um" if kind is AxisKind.LINEAR else "arcsec")
    modulo = kind is AxisKind.ROTARY and abs(nom[-1] - nom[0] - 360.0) < 1e-6
    regular = not np.any(np.abs(steps - steps[0]) > 1e-6 * max(1.0, abs(steps[0])))
    nodes = None if regular else nom * mm
    t = CompensationTable(axis, kind, pu, cu, float(nom[0] * mm), float(steps[0] * mm), fwd,
                          rev, bidirectional=not np.allclose(fwd, rev), modulo=modulo,
                          nodes=nodes)
    k = correction_factor(t, pu) / mm            # file unit -> correction unit
    return replace(t, up=np.round(fwd / k, 6) + 0.0, down=np.round(rev / k, 6) + 0.0)


def _plausible(nom, fwd, rev, file_type, source) -> None:
    """Trims as large as the positions mean the file was read with the other type."""
    span = float(nom[-1] - nom[0])
    big = float(max(np.abs(fwd).max(), np.abs(rev).max()))
    if big > 0.1 * span and big > 0.5:              # half a millimetre (or inch) of trim
        other = 1 - file_type
        raise DataFormatError(
            f"trims of up to {big:g} on a table spanning {span:g}: read as COMP_FILE_TYPE "
            f"{file_type}, this file looks like type {other} "
            f"({'nominal, forward, reverse positions' if other == 0 else 'nominal and trims'})"
            f"; read it with file_type={other}", source)
