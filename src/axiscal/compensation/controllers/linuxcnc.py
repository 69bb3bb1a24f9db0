"""LinuxCNC: the joint compensation file (``COMP_FILE``, ``COMP_FILE_TYPE`` 0 or 1).

Sources: LinuxCNC ``src/emc/motion/usrmotintf.cc``, ``usrmotLoadComp(joint, file, type)``: the
file is read line by line as three numbers ``nominal a b``; reading stops at the first line that
is not three numbers (so the file carries no comments); with type 0 the numbers are
*nominal, forward, reverse* positions and the loader stores the trims ``nominal − forward`` and
``nominal − reverse``; with type 1 they are already *nominal, forward_trim, reverse_trim*.
``src/emc/motion/motion.h``: ``EMCMOT_COMP_SIZE 256`` entries at most. The LinuxCNC INI
documentation names the keys ``COMP_FILE`` and ``COMP_FILE_TYPE`` of the ``[JOINT_n]`` section
(``[AXIS_n]`` before 2.8). ``src/emc/motion/control.c`` (``compute_screw_comp``): the trim is
added to the commanded joint position (``backlash_corr = fwd_trim + fwd_slope·dpos`` while
``vel_cmd > 0``, the reverse trim while ``vel_cmd < 0``, the last value while at rest), linearly
interpolated between entries; plain backlash compensation is the special case
``fwd_trim = +backlash/2``, ``rev_trim = −backlash/2``. The table is bracketed by sentinel
entries with zero trim, so it should cover the whole travel. The file is in machine units.

Here: trim = correction (= −deviation) converted to the machine unit (mm or deg); type 0 writes
``forward = nominal − correction_up`` and ``reverse = nominal − correction_down``, i.e. the
position the uncompensated axis reaches. Nominal positions must increase strictly.

**Limits checked.** At most 256 lines; range inside the travel. A continuous rotary joint is
compensated only over the table's 0…360° (the joint position is not wrapped): noted, not refused.
"""

from __future__ import annotations

from dataclasses import replace

import numpy as np

from axiscal.compensation.controllers._common import (
    ControllerFile, check_points, check_travel, correction_factor, decimals, parse_number)
from axiscal.compensation.tables import CompensationTable
from axiscal.datasets import AxisKind
from axiscal.errors import ControllerLimitError, DataFormatError, InputError

__all__ = ["NAME", "write", "parse", "MAX_POINTS"]

NAME = "linuxcnc"
MAX_POINTS = 256


def write(table: CompensationTable, travel=None, *, file_type: int = 1, joint: int = 0,
          max_points: int = MAX_POINTS) -> ControllerFile:
    """Write ``table`` as a LinuxCNC compensation file of ``file_type`` 0 or 1."""
    if file_type not in (0, 1):
        raise ControllerLimitError(f"{NAME}: COMP_FILE_TYPE = {file_type!r}; LinuxCNC knows 0 and 1")
    check_points(table.n_points, max_points, NAME, "lines (EMCMOT_COMP_SIZE)")
    check_travel(table, travel, NAME)
    k = correction_factor(table, table.position_unit)
    nd = decimals(table.position_unit)
    nom = table.positions
    fwd = np.round(table.up * k, nd)
    rev = np.round(table.down * k, nd)
    if file_type == 0:
        a, b = nom - fwd, nom - rev
    else:
        a, b = fwd, rev
    text = "".join(f"{n:.{nd}f} {x:.{nd}f} {y:.{nd}f}\n" for n, x, y in zip(nom, a, b))
    name = f"{(table.axis or 'joint').lower()}.comp"
    enable = [f"[JOINT_{joint}] COMP_FILE = {name}", f"[JOINT_{joint}] COMP_FILE_TYPE = {file_type}",
              f"leave [JOINT_{joint}] BACKLASH unset: the file holds both directions"
              if table.bidirectional else "the same trims serve both directions"]
    notes = ("continuous rotary joint: compensated only over the table's range (no wrap)",) \
        if table.modulo else ()
    written = replace(table, up=fwd / k, down=rev / k)
    return ControllerFile(NAME, text, name, written, tuple(enable), notes=notes)


def parse(text: str, source: str = "<text>", file_type: int = 1,
          axis_kind: "AxisKind | str" = "linear", axis: str = "",
          correction_unit: str | None = None) -> CompensationTable:
    """Read a LinuxCNC compensation file (both types) into a table.

    Unlike LinuxCNC, which silently stops at the first bad line, this parser refuses it.
    """
    if file_type not in (0, 1):
        raise InputError(f"{NAME}: file_type = {file_type!r}; COMP_FILE_TYPE is 0 or 1")
    rows = []
    for n, raw in enumerate(text.splitlines(), 1):
        if not raw.strip():
            continue
        cells = raw.split()
        if len(cells) != 3:
            raise DataFormatError(f"{len(cells)} numbers; a line holds nominal and two values "
                                  "(LinuxCNC stops reading here)", source, n)
        rows.append([parse_number(c, source, n) for c in cells])
    if len(rows) < 2:
        raise DataFormatError(f"{len(rows)} line(s); a compensation file needs at least 2", source)
    arr = np.array(rows)
    nom = arr[:, 0]
    steps = np.diff(nom)
    if np.any(steps <= 0):
        raise DataFormatError("nominal positions must increase strictly", source)
    if np.any(np.abs(steps - steps[0]) > 1e-6 * max(1.0, abs(steps[0]))):
        raise DataFormatError("nominal positions are not equidistant; axiscal tables are", source)
    fwd, rev = (nom - arr[:, 1], nom - arr[:, 2]) if file_type == 0 else (arr[:, 1], arr[:, 2])
    kind = AxisKind.parse(axis_kind)
    pu = "mm" if kind is AxisKind.LINEAR else "deg"
    cu = correction_unit or ("um" if kind is AxisKind.LINEAR else "arcsec")
    modulo = kind is AxisKind.ROTARY and abs(nom[-1] - nom[0] - 360.0) < 1e-6
    t = CompensationTable(axis, kind, pu, cu, float(nom[0]), float(steps[0]), fwd, rev,
                          bidirectional=not np.allclose(fwd, rev), modulo=modulo)
    k = correction_factor(t, pu)
    return replace(t, up=np.round(fwd / k, 6) + 0.0, down=np.round(rev / k, 6) + 0.0)
