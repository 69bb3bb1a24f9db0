"""SINUMERIK machine data that decide how a compensation table is read.

Read from an ``INITIAL.INI`` (``_N_INITIAL_INI`` of a series start-up archive) or any file of
machine-data assignments, through the one line grammar of
:mod:`~axiscal.compensation.controllers.siemens_text`:

=========== ========================================= ===========================================
MD          name                                      used for
=========== ========================================= ===========================================
MD10000     ``$MN_AXCONF_MACHAX_NAME_TAB[i]``         the name of machine axis AX(i+1) (``X1``)
MD10240     ``$MN_SCALING_SYSTEM_IS_METRIC``          basic system: 1 metric, 0 inch
MD30300     ``$MA_IS_ROT_AX[AXn]``                    1: rotary axis (degrees), 0: linear (mm)
MD30310     ``$MA_ROT_IS_MODULO[AXn]``                1: modulo 360°; 0: a swivel axis
MD38000     ``$MA_MM_ENC_COMP_MAX_POINTS[e,AXn]``     interpolation points reserved per table
MD32700     ``$MA_ENC_COMP_ENABLE[e,AXn]``            the table of measuring system e+1 is active
=========== ========================================= ===========================================

Sources: SINUMERIK 840D sl Function Manual *Basic Functions* (MD10000, MD10240, MD30300,
MD30310) and *Extended Functions* K3 "Compensation" (MD32700, MD38000, MD18342); the
SINUMERIK 840D sl/828D List Manual *Machine data and parameters*.

A rotary axis that is not modulo (MD30300 = 1, MD30310 = 0: a swivel head's A or B axis) has an
EEC table in degrees with ``$AA_ENC_COMP_IS_MODULO = 0``; the table alone cannot tell it from a
linear axis, so :func:`parse` is given beside it.
"""

from __future__ import annotations

import re
from dataclasses import dataclass, field

from axiscal.compensation.controllers.siemens_text import statements
from axiscal.errors import DataFormatError

__all__ = ["MachineData", "parse", "EMPTY"]

_TRUE = {"1": True, "TRUE": True, "0": False, "FALSE": False}


@dataclass(frozen=True)
class MachineData:
    """The machine data of :func:`parse` (empty where a file did not say).

    Attributes
    ----------
    names : dict of str to str
        Machine axis ``AXn`` -> its name (MD10000), e.g. ``{"AX4": "A1"}``.
    rotary, modulo : dict of str to bool
        MD30300 and MD30310 by machine axis ``AXn``.
    max_points : dict of (str, int) to int
        MD38000 by (``AXn``, measuring-system index 0 or 1).
    enabled : dict of (str, int) to bool
        MD32700 by (``AXn``, measuring-system index).
    metric : bool or None
        MD10240 (None: not stated).
    source : str
        The file it came from.
    """

    names: dict = field(default_factory=dict)
    rotary: dict = field(default_factory=dict)
    modulo: dict = field(default_factory=dict)
    max_points: dict = field(default_factory=dict)
    enabled: dict = field(default_factory=dict)
    metric: bool | None = None
    source: str = ""

    def machine_axis(self, name: str) -> str:
        """``AXn`` for a machine axis written as ``AXn`` or by its MD10000 name (``C1``)."""
        up = str(name).strip().upper()
        if up in self.rotary or up in self.names or re.fullmatch(r"AX[0-9]{1,3}", up) is not None:
            return up
        return next((ax for ax, n in self.names.items() if n.upper() == up), up)

    def kind(self, name: str) -> tuple[str, bool, str] | None:
        """(``linear`` or ``rotary``, modulo, why) for a machine axis, or None if not stated."""
        ax = self.machine_axis(name)
        if ax not in self.rotary:
            return None
        shown = f"{ax} ({self.names[ax]})" if ax in self.names else ax
        if not self.rotary[ax]:
            return "linear", False, (f"MD30300 $MA_IS_ROT_AX[{ax}] = 0 in {self.source}: "
                                     f"{shown} is linear")
        mod = self.modulo.get(ax, False)
        why = (f"MD30300 $MA_IS_ROT_AX[{ax}] = 1, MD30310 $MA_ROT_IS_MODULO[{ax}] = "
               f"{int(mod)} in {self.source}: {shown} is rotary"
               + (", modulo 360°" if mod else ", not modulo (a swivel axis)"))
        return "rotary", mod, why

    def __bool__(self) -> bool:
        return bool(self.names or self.rotary or self.max_points or self.metric is not None)


EMPTY = MachineData()


def parse(text: str, source: str = "<text>") -> MachineData:
    """The machine data of ``text`` that :class:`MachineData` holds (others are passed over).

    Raises
    ------
    DataFormatError
        A value of one of these machine data that is not what the List Manual allows.
    """
    names, rotary, modulo, points, enabled, metric = {}, {}, {}, {}, {}, None
    for s in statements(text, source):
        if s.kind != "assign" or not s.name.startswith(("MA_", "MN_")):
            continue
        v = s.value.strip().strip('"').strip()
        if s.name == "MN_AXCONF_MACHAX_NAME_TAB" and len(s.index) == 1 and \
                re.fullmatch(r"[0-9]{1,3}", s.index[0]):
            names[f"AX{int(s.index[0]) + 1}"] = v
        elif s.name == "MN_SCALING_SYSTEM_IS_METRIC":
            metric = _flag(v, s, source)
        elif s.name in ("MA_IS_ROT_AX", "MA_ROT_IS_MODULO") and s.index:
            into = rotary if s.name == "MA_IS_ROT_AX" else modulo
            into[s.index[-1].upper()] = _flag(v, s, source)
        elif s.name in ("MA_MM_ENC_COMP_MAX_POINTS", "MA_ENC_COMP_ENABLE") and len(s.index) == 2:
            key = (s.index[1].upper(), _whole(s.index[0], s, source))
            if s.name == "MA_ENC_COMP_ENABLE":
                enabled[key] = _flag(v, s, source)
            else:
                points[key] = _whole(v, s, source)
    md = MachineData(names, rotary, modulo, points, enabled, metric, source)
    # axis data written with the axis's name ([C1]) are keyed by AXn too
    for d in (md.rotary, md.modulo):
        for k in [k for k in d if not k.startswith("AX")]:
            d[md.machine_axis(k)] = d.pop(k)
    return md


def _flag(v: str, s, source: str) -> bool:
    if v.upper() not in _TRUE:
        raise DataFormatError(f"${s.name} = {v[:20]!r}: 0 or 1 expected", source, s.line)
    return _TRUE[v.upper()]


def _whole(v: str, s, source: str) -> int:
    if not re.fullmatch(r"[0-9]{1,9}", v):
        raise DataFormatError(f"${s.name}: {v[:20]!r} is not a whole number", source, s.line)
    return int(v)
