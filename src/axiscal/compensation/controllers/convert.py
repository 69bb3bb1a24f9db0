"""A table read from one controller's file, written for another, on the same axis.

:func:`convert` is the one path of ``axiscal compensate --read FILE --to NAME``, of the API's
:func:`axiscal.api.write_table` and of the workbench's table download: it carries what a table
read from a controller file knows of its place on the machine (its
:class:`~axiscal.compensation.tables.TableOrigin`: machine axis, measuring system, unit, and the
axis kind the table itself holds) to the writer's options, and refuses a conversion that would
lose one, naming it (issue 42: the C axis's table read from an 840D file was written as
``$AA_ENC_COMP[0,i,AX1]``, the X axis).

Rules
-----
* **Same controller**: the writer takes machine axis, measuring system and unit from the table
  (the 840D writer does so itself; Fanuc's axis number is carried as ``axis_number``).
* **Unit**: a table read in inch is written in inch where the writer has a ``unit`` option;
  a writer without one (CSV, Renishaw ``.ren``) writes mm, and a note says so (the lengths are
  the same; the machine's unit is not in the file).
* **Measuring system 2** (an 840D table of ``[1,…]``) has no place in a format without measuring
  systems: refused, naming it.
* **Machine axis**: a table that came from a named axis of another controller is refused by a
  writer that names its axis by a number or a machine-axis name (840D ``machine_axis``, Fanuc
  ``axis_number``, LinuxCNC ``joint``) unless that option is given: the default (AX1, axis 1,
  joint 0) would put the correction on another axis. Heidenhain, CSV and ``.ren`` write the
  table's axis name itself.
* **Axis kind**: a rotary axis whose file does not record it (a swivel axis in an 840D file,
  a LinuxCNC or ``.ren`` file) gets a note: read it back as rotary.
"""

from __future__ import annotations

import inspect
import re
from dataclasses import replace

from axiscal.errors import ControllerLimitError

__all__ = ["convert", "writer_options", "AXIS_OPTION"]

#: The writer option that names the axis on the machine, by controller.
AXIS_OPTION = {"siemens-840d": "machine_axis", "fanuc": "axis_number", "linuxcnc": "joint"}
#: Formats whose file records that an axis is rotary (840D only for a modulo table).
_RECORDS_KIND = {"fanuc", "csv"}


def writer_options(table, controller: str, options: dict | None = None) -> tuple[dict, list]:
    """The options for ``controller``'s writer that keep ``table`` on its axis, and notes.

    Raises
    ------
    ControllerLimitError
        The conversion would lose the table's measuring system or machine axis (named).
    """
    from axiscal.compensation.controllers import controller as get_controller

    mod = get_controller(controller)
    opts = dict(options or {})
    notes: list[str] = []
    o = getattr(table, "origin", None)
    if o is None:
        return opts, notes
    params = inspect.signature(mod.write).parameters
    where = f"{o.controller} {o.machine_axis or table.axis or 'axis'}"
    if o.unit == "inch":
        if "unit" in params:
            opts.setdefault("unit", "inch")
        else:
            notes.append(f"written in mm: the table was read from an inch file ({where}); "
                         f"a {mod.NAME} file holds mm")
    if o.measuring_system == 2 and "measuring_system" not in params:
        raise ControllerLimitError(
            f"{o.controller} → {mod.NAME}: the table is measuring system 2 of {o.machine_axis} "
            f"(MD32700[1]); a {mod.NAME} file has no measuring system to hold it")
    slot = AXIS_OPTION.get(mod.NAME)
    if o.controller == mod.NAME:
        if slot == "axis_number" and re.fullmatch(r"[0-9]{1,4}", o.machine_axis):
            opts.setdefault(slot, int(o.machine_axis))
    elif slot and o.machine_axis and slot not in opts:
        raise ControllerLimitError(
            f"{o.controller} → {mod.NAME}: the table is {o.controller}'s axis {o.machine_axis}"
            f"{f' ({table.axis})' if table.axis and table.axis != o.machine_axis else ''}; a "
            f"{mod.NAME} file names its axis by {slot}: give -o {slot}=… (the default would put "
            "the correction on another axis)")
    kind = getattr(table.axis_kind, "value", str(table.axis_kind))
    if kind == "rotary" and mod.NAME not in _RECORDS_KIND and not table.modulo:
        notes.append(f"the {mod.NAME} file does not record that {table.axis or 'the axis'} is "
                     "rotary: read it back as rotary (-o axis_kind=rotary"
                     + (", or the INITIAL.INI with --ini)" if mod.NAME == "siemens-840d" else ")"))
    return opts, notes


def convert(table, controller: str, travel=None, **options):
    """Write ``table`` for ``controller`` on the axis it was read from (see the module's rules).

    Parameters
    ----------
    table : CompensationTable
        A table read from a controller file (or made from measurements: then as ``write``).
    controller : str
        The controller to write for.
    travel : (float, float), optional, ``table.position_unit``
        The axis travel.
    **options
        The writer's options; given ones win over what the table carries.

    Returns
    -------
    ControllerFile
        With a note for each thing the target file cannot say.
    """
    from axiscal.compensation.controllers import check_options
    from axiscal.compensation.controllers import controller as get_controller

    mod = get_controller(controller)
    opts, notes = writer_options(table, mod.NAME, options)
    cf = mod.write(table, travel, **check_options(mod.write, opts, f"option for {mod.NAME}"))
    return replace(cf, notes=tuple(cf.notes) + tuple(notes)) if notes else cf
