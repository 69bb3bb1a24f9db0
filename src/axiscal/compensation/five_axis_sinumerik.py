"""The identified axis lines of a table-table machine as SINUMERIK 840D swivel data: the
orientable toolholder's system variables ``$TC_CARR`` that CYCLE800 (swivel plane) reads, for
kinematics of type P (only the part rotates).

Where the values come from (SINUMERIK 840D sl, Function Manual "Tools" / W1 Tool offset,
"Toolholder with orientation capability", list of ``$TC_CARRn[m]``; SINUMERIK Operate
Commissioning Manual 10/2015, 6FC5397-3DP40-5BA3, 7.7 "Swiveling", kinematics with a
rotary table)::

    l2  $TC_CARR4..6    from the machine's reference point to the centre of rotation of
                        rotary axis 1 (the tilting axis, which carries C)
    v1  $TC_CARR7..9    direction of rotary axis 1
    v2  $TC_CARR10..12  direction of rotary axis 2 (C)
    l3  $TC_CARR15..17  from the centre of rotation of rotary axis 1 to that of rotary axis 2
    l4  $TC_CARR18..20  closure of the chain, l4 = −(l2 + l3)
    $TC_CARR21, 22      axis identifiers of rotary axes 1 and 2
    $TC_CARR23          kinematic type "P"
    $TC_CARR24, 25      offset of rotary axes 1 and 2 (degrees): the axis position at which the
                        chain's vectors hold (the initial setting)

Reading chosen where the manuals leave it to the machine (stated with every value):

* the *centre of rotation* of each axis is the reference point of its line in
  :mod:`axiscal.physics.rotary_location` (for A: where the A line crosses the plane through the
  C axis normal to X; for C: its line at A = 0 at the height of the A axis), moved by the
  identified position errors; any point on the line gives the same chain, since each vector
  only places a line;
* ``v1``, ``v2`` are the identified lines' unit directions, oriented so that a positive axis
  position turns the table right-handed about them (axiscal's and LinuxCNC's trt sign): on a
  machine whose table turns the ISO 841 way (opposite), both vectors change sign;
* the zero error of the tilting axis (identified as E_A0A+E_A0C, E_B0B+E_B0C for B/C, the
  convention of :mod:`axiscal.standards.location_errors`) goes to ``$TC_CARR24`` as the axis
  position at which the table is at the chain's zero: ``−(E_A0A+E_A0C)`` in degrees (a
  commanded ``a`` reaches ``a + E``); ``$TC_CARR25`` is 0, since E_C0C is not seen (the C zero is
  the set-up's);
* lengths in mm in the machine frame, the machine's reference point the origin of its X, Y, Z.

These values were not loaded into an 840D (none was available): they are the manual's parameters
filled from the identified lines, with the reading above; a machine's own CYCLE996/CYCLE9960
measuring cycle writes the same quantities.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from axiscal.errors import InputError
from axiscal.physics.rotary_location import Geometry

__all__ = ["SwivelData", "swivel_data", "MANUALS"]

#: The manuals the parameters' meaning comes from.
MANUALS = ("SINUMERIK 840D sl, Function Manual Tools (W1 Tool offset), 'Toolholder with "
           "orientation capability', system variables $TC_CARR1...$TC_CARR33",
           "SINUMERIK Operate, Commissioning Manual 10/2015 (6FC5397-3DP40-5BA3), 7.7 "
           "'Swiveling': offset vectors I2, I3, I4 = -(I2 + I3), rotary axis vectors V1, V2")


@dataclass(frozen=True)
class SwivelData:
    """The toolholder's ``$TC_CARR`` values (mm, unit vectors, degrees).

    Attributes
    ----------
    carrier : int
        The toolholder number ``m``.
    values : dict of str to float or str
        ``"$TC_CARR4"`` ... -> value, in the manual's numbering.
    meaning : dict of str to str
        Each variable -> what it is and which identified errors it takes.
    """

    carrier: int
    values: dict
    meaning: dict

    def program(self) -> str:
        """A part-program fragment that writes the values (one ``$TC_CARRn[m]=`` a line, with
        its meaning as a comment), preceded by the reading it rests on."""
        lines = [f"; toolholder {self.carrier}: axis lines identified by axiscal (ISO 230-1 "
                 "names), kinematics type P",
                 "; v1, v2 turn the table right-handed for a positive axis position (LinuxCNC "
                 "trt sign); reverse both for an ISO 841 table"]
        for k, v in self.values.items():
            text = f'"{v}"' if isinstance(v, str) and k.endswith("23") else \
                (v if isinstance(v, str) else f"{v:.6f}")
            lines.append(f"{k}[{self.carrier}]={text} ; {self.meaning[k]}")
        return "\n".join(lines) + "\nM17\n"

    def to_dict(self) -> dict:
        return {"carrier": self.carrier, "values": dict(self.values),
                "meaning": dict(self.meaning), "manuals": list(MANUALS)}


def swivel_data(geometry: Geometry, result, carrier: int = 1) -> SwivelData:
    """The ``$TC_CARR`` values of toolholder ``carrier`` from the identified location errors
    (module docstring).

    Parameters
    ----------
    geometry : Geometry
        The nominal geometry (m).
    result : LocationIdentification
    carrier : int
        Toolholder number, 1 or more.

    Raises
    ------
    InputError
        A spindle head (type T/M, not written here), a position or orientation error not
        identified, or a carrier number below 1.
    """
    if geometry.head:
        raise InputError("a spindle head: the swivel data written here are for table-table "
                         "machines (kinematics type P)")
    if int(carrier) != carrier or carrier < 1:
        raise InputError(f"toolholder number {carrier!r}: give a whole number >= 1")
    got = {e.name: e.value for e in result.errors}
    t = geometry.tilt
    zero = f"E_{t}0{t}+E_{t}0C"
    names = [n for n in geometry.names if n not in (f"E_{t}0{t}", f"E_{t}0C", "E_C0C")]
    missing = [n for n in names + [zero] if n not in got]
    if missing:
        raise InputError(f"{', '.join(missing)} not identified: no swivel data can be given; "
                         "measure with a plan that sees them (axiscal fiveaxis plan)")
    errors = {n: got[n] for n in names}
    errors[f"E_{t}0{t}"] = got[zero]
    (q_t, u_t, _), (q_c, u_c, _) = geometry.lines(errors)
    mm = 1e3
    l2, l3 = q_t * mm, (q_c - q_t) * mm
    l4 = -(l2 + l3)
    values, meaning = {}, {}
    pos = "E_Y0A, E_Z0A" if t == "A" else "E_X0B, E_Z0B"
    tilts = "E_B0A, E_C0A" if t == "A" else "E_A0B, E_C0B"
    ctilt = "E_B0C" if t == "A" else "E_A0C"
    for first, vec, what in ((4, l2, f"l2 {{}}: machine reference point to axis {t} ({pos}), mm"),
                             (7, u_t, f"v1 {{}}: direction of {t} ({tilts})"),
                             (10, u_c, f"v2 {{}}: direction of C ({ctilt})"),
                             (15, l3, f"l3 {{}}: axis {t} to axis C (E_X0C, E_Y0C), mm"),
                             (18, l4, "l4 {}: closure -(l2 + l3), mm")):
        for i, comp in enumerate("xyz"):
            key = f"$TC_CARR{first + i}"
            values[key] = float(np.round(vec[i], 12))
            meaning[key] = what.format(comp)
    values["$TC_CARR21"], meaning["$TC_CARR21"] = t, "rotary axis 1"
    values["$TC_CARR22"], meaning["$TC_CARR22"] = "C", "rotary axis 2"
    values["$TC_CARR23"], meaning["$TC_CARR23"] = "P", "kinematics type: the part rotates"
    values["$TC_CARR24"] = float(-np.degrees(got[zero]))
    meaning["$TC_CARR24"] = f"offset of {t}, deg: -({zero})"
    values["$TC_CARR25"] = 0.0
    meaning["$TC_CARR25"] = "offset of C, deg: E_C0C not seen (the set-up's zero)"
    return SwivelData(int(carrier), values, meaning)
