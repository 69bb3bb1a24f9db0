"""Which reader a positioning file needs, told from its first lines alone.

:func:`axiscal.io.parse_positioning` asks these questions before it imports a reader, so a run
over a tidy CSV (the common case) never loads the Renishaw, ecmc or EPICS readers (start-up,
issue 30). Each test follows the layout its reader's module docstring documents with its public
source:

* an EPICS ``camonitor`` log (:mod:`axiscal.io.epics`: EPICS Base, ``modules/ca/src/tools/
  tool_lib.c``, ``print_time_val_sts``, and the ``camonitor`` manual page, "Timestamps"): a PV
  name, then a time stamp;
* a Renishaw ``.rtl``/``.rta`` export (:mod:`axiscal.io.renishaw`): a ``HEADER::`` line first;
* an ecmc ISO 230-2 input file (:mod:`axiscal.io.ecmc`): ``TGT_DATA[`` keys.

The readers re-export their test (``axiscal.io.epics.looks_like_camonitor`` ...), which stays the
name to use.
"""

from __future__ import annotations

import re

__all__ = ["looks_like_camonitor", "looks_like_ecmc", "looks_like_renishaw", "NOTES_START"]

#: How the notes of a dataset read from a camonitor log begin.
NOTES_START = "EPICS camonitor log"

# camonitor's time stamps (tool_lib.c, print_time_val_sts): server ``-ts`` (the default),
# client ``-tc``, and the signed offsets of ``-tr``/``-ti``/``-tI``
DATE = r"\d{4}-\d{2}-\d{2}[ T]\d{2}:\d{2}:\d{2}(?:\.\d+)?"
CLOCK = r"\d{1,2}:\d{2}:\d{2}(?:\.\d+)?"
OFFSET = r"[+-]\d+\.\d+"
_FIRST = re.compile(rf"^\S+\s+(?:{DATE}|{CLOCK}|<undefined>|\({DATE}\))\s")


def looks_like_camonitor(text: str) -> bool:
    """True if the first line that is not blank, a ``#`` comment or a lost channel's
    ``PV *** ...`` reads ``PV <time stamp> value``."""
    for line in text[:4096].splitlines():
        line = line.strip()
        if line and not line.startswith("#") and "***" not in line:
            return bool(_FIRST.match(line + " "))
    return False


def looks_like_ecmc(text: str) -> bool:
    """True if the text has ``TGT_DATA[`` keys outside comments."""
    return any(line.strip().startswith("TGT_DATA[") for line in text.splitlines())


def looks_like_renishaw(text: str) -> bool:
    """True if the text opens with a ``HEADER::`` line (then a truncated file is named as one)."""
    return text.lstrip("\ufeff \t\r\n").startswith("HEADER::")
