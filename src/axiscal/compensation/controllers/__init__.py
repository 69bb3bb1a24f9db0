"""Writers and parsers of controller compensation formats, one module per controller.

Each module has ``NAME``, ``write(table, travel=None, **options) -> ControllerFile`` and
``parse(text, ...) -> CompensationTable``, documents its format with the source it was checked
against, and refuses what the controller would refuse with a
:class:`~axiscal.errors.ControllerLimitError` (too many points, a spacing that is not a whole
number of the controller's position unit, a range outside the axis travel, a rotary table whose
increments do not sum to zero ...).

============== =================================================== ===========================
name           module                                              file
============== =================================================== ===========================
siemens-840d   :mod:`~axiscal.compensation.controllers.siemens_840d`  ``%_N_AX_EEC_INI``
fanuc          :mod:`~axiscal.compensation.controllers.fanuc`         parameters 3620-3627 + data
heidenhain     :mod:`~axiscal.compensation.controllers.heidenhain`    ``.COM`` table + ``.CMA``
linuxcnc       :mod:`~axiscal.compensation.controllers.linuxcnc`      ``COMP_FILE`` (type 0 or 1)
csv            :mod:`~axiscal.compensation.controllers.csv`           plain CSV with a header
renishaw-ren   :mod:`~axiscal.compensation.controllers.renishaw_ren`  Renishaw ``.ren`` export
============== =================================================== ===========================
"""

from __future__ import annotations

import importlib

from axiscal.compensation.controllers._common import ControllerFile
from axiscal.errors import InputError

__all__ = ["CONTROLLERS", "controller", "ControllerFile", "check_options", "detect",
           "HOLDS_REFERENCE", "reference_note"]

#: Controller name -> module name.
CONTROLLERS = {
    "siemens-840d": "siemens_840d",
    "fanuc": "fanuc",
    "heidenhain": "heidenhain",
    "linuxcnc": "linuxcnc",
    "csv": "csv",
    "renishaw-ren": "renishaw_ren",
}


#: Formats whose file holds the reference (home) position: the 840D table is shifted to zero
#: there, Fanuc's parameter 3620 numbers it, the CSV records ``reference_index``. A Heidenhain
#: ``.COM``, a LinuxCNC file and a Renishaw ``.ren`` hold the values as measured.
HOLDS_REFERENCE = frozenset({"siemens-840d", "fanuc", "csv"})


def reference_note(name: str, home: float, unit: str) -> str:
    """What a writer's output says of a reference position given (``--home``) that its format
    does not hold; ``""`` where it does (:data:`HOLDS_REFERENCE`)."""
    if controller(name).NAME in HOLDS_REFERENCE:
        return ""
    return (f"--home {home:g} {unit}: a {controller(name).NAME} file holds no reference position; "
            "its values are written as measured, not shifted to zero there")


def controller(name: str):
    """The module for a controller name (``siemens-840d``, ``fanuc``, ``heidenhain``, ...)."""
    key = str(name).strip().lower().replace("_", "-")
    if key not in CONTROLLERS:
        raise InputError(f"controller {name!r} is not one of {', '.join(CONTROLLERS)}")
    return importlib.import_module(f"axiscal.compensation.controllers.{CONTROLLERS[key]}")


def check_options(function, options: dict, what: str) -> dict:
    """Refuse options a writer or parser does not take, naming them and the allowed ones."""
    import inspect

    params = inspect.signature(function).parameters
    allowed = sorted(k for k, p in params.items() if p.kind is p.KEYWORD_ONLY or
                     (p.default is not p.empty and k not in ("travel", "source")))
    unknown = sorted(set(options) - set(allowed))
    if unknown:
        raise InputError(f"{what}: unknown option(s) {', '.join(unknown)}; allowed: "
                         f"{', '.join(allowed) or 'none'}")
    return options


def detect(text: str) -> str | None:
    """The controller whose file ``text`` is, from its content (None if it cannot be told).

    Siemens files begin ``%_N_AX_EEC_INI`` (or ``%_N_NC_CEC_INI``), Heidenhain tables
    ``BEGIN <name>.COM``, Fanuc tapes hold ``N3620``…``N3624`` parameter lines, an axiscal CSV
    its ``position_<unit>`` header, and a LinuxCNC file is lines of three numbers (comment lines
    may follow them, never precede them: LinuxCNC stops reading at the first other line).
    """
    import re

    body = text.lstrip("\ufeff \t\r\n")
    if body.startswith(("%_N_AX_EEC_INI", "%_N_NC_CEC_INI")) or \
            re.search(r"\$(AA_ENC_COMP|AN_CEC)\s*\[", body, re.IGNORECASE):   # `$AN_CEC [0,0]` too
        return "siemens-840d"
    if re.match(r"BEGIN\s+\S+\.COM\b", body, re.IGNORECASE):
        return "heidenhain"
    if re.search(r"^N0*362[0-4]\s*(A\d+)?\s*P", body, re.MULTILINE):
        return "fanuc"
    from axiscal.compensation.controllers.renishaw_ren import looks_like_ren

    if looks_like_ren(body):        # 'Compensation spacing' and 'No. Axis position Combined'
        return "renishaw-ren"
    if re.search(r"^position_\w+,correction_up_", body, re.MULTILINE):
        return "csv"
    from axiscal.compensation.controllers.linuxcnc import looks_like

    return "linuxcnc" if looks_like(body) else None
