"""LinuxCNC's INI file: which joint's ``COMP_FILE`` a compensation file is, in what unit and type.

Sources: LinuxCNC documentation, "INI Configuration" (docs/src/config/ini-config.adoc):

* "The INI File Components": a comment line starts with ``;`` or ``#`` (inside a value both are
  part of the value); ``[SECTION]`` names are letters, digits and ``_``; a variable line is
  ``NAME = value`` with the white space around the value removed, continued onto the next line
  by a trailing backslash; of two equal variables "the first one encountered will be used".
* ``[TRAJ] LINEAR_UNITS`` ("mm or inch", the machine units of linear axes) and
  ``ANGULAR_UNITS`` (deg, degree, rad, radian, grad, gon); LinuxCNC also takes ``metric``,
  ``in`` and ``imperial`` (src/emc/ini/inifile.cc, ``mapLinearUnits``) and does not start
  without both (src/emc/ini/initraj.cc).
* ``[JOINT_<num>]``: ``TYPE`` (LINEAR or ANGULAR, LINEAR if not given), ``UNITS`` ("overrides
  the related [TRAJ] UNITS setting", LINEAR_UNITS or ANGULAR_UNITS by the joint's type),
  ``COMP_FILE`` ("Compensation file values are in machine units"; a relative name is taken
  from the configuration's directory, where the ``linuxcnc`` script runs) and
  ``COMP_FILE_TYPE`` (0 or 1; "must be specified for each COMP_FILE"; when it is not,
  src/emc/ini/inijoint.cc reads 0). Before LinuxCNC 2.8 the same keys were in ``[AXIS_<num>]``
  sections (LinuxCNC 2.7 "INI Configuration", [AXIS_<num>] Section).

:func:`comp_settings` finds the section naming a file and what the INI says of it;
:func:`read_options` merges that with the options a user gave, refusing one that contradicts the
INI, and says where every value came from (:class:`~axiscal.compensation.controllers._common.FileInput`).
"""

from __future__ import annotations

import re
from dataclasses import dataclass

from axiscal.compensation.controllers._common import FileInput
from axiscal.compensation.controllers.linuxcnc import ANGULAR_UNITS, file_type_by_content
from axiscal.errors import DataFormatError, InputError

__all__ = ["CompSettings", "parse_ini", "comp_sections", "comp_settings", "read_options"]

#: LinuxCNC's linear unit names (src/emc/ini/inifile.cc, mapLinearUnits) -> axiscal's.
LINEAR_UNITS = {"mm": "mm", "metric": "mm", "in": "inch", "inch": "inch", "imperial": "inch"}
_SECTION = re.compile(r"^\[([A-Za-z_][A-Za-z0-9_]*)\]\s*$")
_VARIABLE = re.compile(r"^([A-Za-z_][A-Za-z0-9_]*)\s*=\s*(.*)$")
_COMP_SECTION = re.compile(r"^(JOINT|AXIS)_(\d+)$")


@dataclass(frozen=True)
class CompSettings:
    """What an INI says of one compensation file.

    Attributes
    ----------
    ini : str
        The INI's path (as found or given).
    section : str
        ``JOINT_0`` (or ``AXIS_0`` before LinuxCNC 2.8), whose ``COMP_FILE`` names the file.
    comp_file : str
        The ``COMP_FILE`` value.
    axis_kind, unit, file_type : str, str, int
        ``linear``/``rotary``; the file's unit (``mm``, ``inch``, ``deg``, ``rad`` ...); 0 or 1.
    kind_from, unit_from, type_from : str
        Where each was read (``[TRAJ] LINEAR_UNITS = inch``) or why LinuxCNC's default holds.
    """

    ini: str
    section: str
    comp_file: str
    axis_kind: str
    kind_from: str
    unit: str
    unit_from: str
    file_type: int
    type_from: str

    def items(self) -> tuple[tuple[str, object, str], ...]:
        """``(option, value, where it was read)`` for the unit, the type and the joint kind."""
        return (("unit", self.unit, self.unit_from), ("file_type", self.file_type, self.type_from),
                ("axis_kind", self.axis_kind, self.kind_from))

    def inputs(self) -> tuple[FileInput, ...]:
        """The three as :class:`FileInput` records (source ``ini``)."""
        where = f"in {self.ini}, whose [{self.section}] COMP_FILE names this file"
        return tuple(FileInput(name, value, "", "ini", f"{src} {where}")
                     for name, value, src in self.items())


def parse_ini(text: str, source: str = "<ini>") -> dict[str, dict[str, str]]:
    """Sections -> variables -> values of a LinuxCNC INI (first occurrence wins; see module)."""
    sections: dict[str, dict[str, str]] = {}
    current: dict[str, str] | None = None
    lines = text.splitlines()
    i = 0
    while i < len(lines):
        line = lines[i].strip()
        i += 1
        if not line or line[0] in ";#":
            continue
        m = _SECTION.match(line)
        if m:
            current = sections.setdefault(m.group(1), {})
            continue
        m = _VARIABLE.match(line)
        if m is None or current is None:
            continue                      # LinuxCNC ignores what it cannot read, so does this
        value = m.group(2)
        while value.endswith("\\") and i < len(lines):
            value = value[:-1] + " " + lines[i].strip()
            i += 1
        current.setdefault(m.group(1), value.strip())
    return sections


def comp_sections(sections: dict) -> list[tuple[str, str]]:
    """``(section, COMP_FILE)`` for every joint (or pre-2.8 axis) section naming a file."""
    return [(name, keys["COMP_FILE"]) for name, keys in sections.items()
            if _COMP_SECTION.match(name) and keys.get("COMP_FILE")]


def comp_settings(sections: dict, section: str, ini: str) -> CompSettings:
    """What the INI says of the file ``[section] COMP_FILE`` names."""
    keys = sections[section]
    traj = sections.get("TRAJ", {})
    jtype = keys.get("TYPE", "LINEAR").strip().upper()
    if jtype not in ("LINEAR", "ANGULAR"):
        raise DataFormatError(f"[{section}] TYPE = {keys['TYPE']}; LinuxCNC knows LINEAR and "
                              "ANGULAR", ini)
    kind_from = f"[{section}] TYPE = {keys['TYPE']}" if "TYPE" in keys else \
        f"[{section}] has no TYPE: LinuxCNC takes LINEAR"
    traj_key = "LINEAR_UNITS" if jtype == "LINEAR" else "ANGULAR_UNITS"
    if "UNITS" in keys:
        raw, unit_from = keys["UNITS"], f"[{section}] UNITS = {keys['UNITS']}"
    elif traj_key in traj:
        raw, unit_from = traj[traj_key], f"[TRAJ] {traj_key} = {traj[traj_key]}"
    else:
        raise DataFormatError(f"no [TRAJ] {traj_key}: LinuxCNC does not start without it, and "
                              f"the unit of {keys['COMP_FILE']} cannot be told", ini)
    names = LINEAR_UNITS if jtype == "LINEAR" else {u: u for u in ANGULAR_UNITS}
    unit = names.get(raw.strip().lower())
    if unit is None:
        raise DataFormatError(f"{unit_from}: LinuxCNC's {traj_key} are "
                              f"{', '.join(names)}", ini)
    raw_type = keys.get("COMP_FILE_TYPE")
    if raw_type is None:
        file_type, type_from = 0, f"[{section}] has no COMP_FILE_TYPE: LinuxCNC reads type 0"
    elif raw_type.strip() in ("0", "1"):
        file_type, type_from = int(raw_type), f"[{section}] COMP_FILE_TYPE = {raw_type.strip()}"
    else:
        raise DataFormatError(f"[{section}] COMP_FILE_TYPE = {raw_type}; LinuxCNC knows 0 and 1",
                              ini)
    return CompSettings(ini, section, keys["COMP_FILE"], "linear" if jtype == "LINEAR" else
                        "rotary", kind_from, unit, unit_from, file_type, type_from)


def read_options(settings: CompSettings | None, options: dict, text: str,
                 source: str = "<text>") -> tuple[dict, tuple[FileInput, ...]]:
    """The parser's options with the INI's unit, type and joint kind, and where each came from.

    An option that contradicts the INI is refused in one line naming both. Without an INI the
    unit is assumed (mm, or degrees for a rotary joint), the joint linear, and the type told
    from the content where only one type gives plausible trims (else 1, axiscal's default).
    """
    opts = dict(options)
    if settings is not None:
        for name, value, src in settings.items():
            given = opts.get(name)
            if given is not None and _same(name, given) != _same(name, value):
                raise InputError(f"-o {name}={given} contradicts {src} in {settings.ini}: drop "
                                 f"-o {name}")
            opts[name] = value
        return opts, settings.inputs()
    none = "no INI beside the file names it in a [JOINT_n] COMP_FILE (give --ini)"
    inputs = []
    kind = opts.get("axis_kind")
    inputs.append(FileInput("axis_kind", kind, "", "option", "given") if kind else
                  FileInput("axis_kind", "linear", "", "default", none))
    rotary = str(kind or "linear").lower().startswith("rot")
    unit = opts.get("unit")
    inputs.append(FileInput("unit", unit, "", "option", "given") if unit else
                  FileInput("unit", "deg" if rotary else "mm", "", "default", none))
    if "file_type" in opts:
        inputs.append(FileInput("file_type", opts["file_type"], "", "option", "given"))
    else:
        found = file_type_by_content(text, source)
        opts["file_type"] = 1 if found is None else found
        inputs.append(FileInput("file_type", opts["file_type"], "", "default", none + (
            "; both types give plausible trims" if found is None else
            f"; read as type {found}, the only type whose trims are plausible")))
    return opts, tuple(inputs)


def _same(name: str, value) -> object:
    """A value in one spelling (``in`` and ``inch``, ``Linear`` and ``linear``, ``0`` and 0)."""
    text = str(value).strip().lower()
    if name == "unit":
        return LINEAR_UNITS.get(text, {"degree": "deg", "radian": "rad", "gon": "grad"}.get(
            text, text))
    if name == "axis_kind":
        return "rotary" if text.startswith(("rot", "ang")) else text
    return text
