"""Finding the LinuxCNC INI that names a compensation file (the file side of
:mod:`axiscal.compensation.controllers.linuxcnc_ini`).

LinuxCNC runs in its configuration's directory (``scripts/linuxcnc.in``: ``cd "$INI_DIR"``), so
a relative ``COMP_FILE`` is a file beside the INI: :func:`find_comp_settings` reads the ``*.ini``
files beside a compensation file and takes the one whose ``[JOINT_n]`` (or pre-2.8
``[AXIS_n]``) ``COMP_FILE`` is that file, or reads the INI it is given.
"""

from __future__ import annotations

from pathlib import Path

from axiscal.compensation.controllers.linuxcnc_ini import (
    CompSettings, comp_sections, comp_settings, parse_ini)
from axiscal.errors import AxiscalError, InputError

__all__ = ["find_comp_settings"]

#: At most this many INIs beside a file are read (a configuration directory holds a few).
MAX_INIS = 50
#: An INI larger than this is not a LinuxCNC configuration.
MAX_INI_BYTES = 1024 * 1024


def find_comp_settings(comp_path, ini=None) -> CompSettings | None:
    """What the INI naming ``comp_path`` says of it (None if no INI beside it names it).

    With ``ini`` (``--ini``) that INI is read and must name the file (by path or, for a copy
    kept elsewhere, by name); beside the file, INIs that name it by path count, and two that
    disagree on its unit, type or joint kind are refused, naming both.
    """
    from axiscal.io._files import read_controller_text

    comp = Path(comp_path)
    if ini is not None:
        sections = parse_ini(read_controller_text(ini)[0], str(ini))
        named = comp_sections(sections)
        hits = [s for s, f in named if _same_file(Path(ini), f, comp)] or \
               [s for s, f in named if Path(f).name == comp.name]
        if not hits:
            listed = ", ".join(f"{f} in [{s}]" for s, f in named) or "no file"
            raise InputError(f"{ini}: no [JOINT_n] COMP_FILE names {comp.name} (it names "
                             f"{listed})")
        return comp_settings(sections, hits[0], str(ini))
    found = []
    for path in _inis_beside(comp):
        try:
            text = read_controller_text(path)[0]
        except AxiscalError:
            continue                      # unreadable: it cannot be the machine's INI
        sections = parse_ini(text, str(path))
        found += [comp_settings(sections, s, str(path)) for s, f in comp_sections(sections)
                  if _same_file(path, f, comp)]
    kinds = {(s.unit, s.file_type, s.axis_kind) for s in found}
    if len(kinds) > 1:
        a, b = found[0], next(s for s in found if (s.unit, s.file_type, s.axis_kind) != (
            found[0].unit, found[0].file_type, found[0].axis_kind))
        raise InputError(f"{comp.name} is named by {a.ini} [{a.section}] ({a.unit}, type "
                         f"{a.file_type}) and {b.ini} [{b.section}] ({b.unit}, type "
                         f"{b.file_type}): give --ini")
    return found[0] if found else None


def _inis_beside(comp: Path) -> list[Path]:
    try:
        entries = sorted(p for p in comp.parent.iterdir() if p.suffix.lower() == ".ini")
    except OSError:
        return []
    return [p for p in entries[:MAX_INIS] if p.is_file() and p.stat().st_size <= MAX_INI_BYTES]


def _same_file(ini: Path, comp_file: str, comp: Path) -> bool:
    """``COMP_FILE`` (relative to the INI's directory) is ``comp``."""
    try:
        return (ini.parent / comp_file).resolve() == comp.resolve()
    except (OSError, RuntimeError, ValueError):
        return False
