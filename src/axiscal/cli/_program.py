"""The part-program options every ``axiscal plan`` command takes (issue 41), and the writing.

``--program FILE --controller NAME`` writes the plan's part program
(:func:`axiscal.programs.write_program`); ``--feed``, ``--max-feed``, ``--limits``, ``--safe``,
``--sign``, ``--origin``, ``--inch``, ``--trigger``, ``--name`` and ``--number`` describe the
machine. Everything is checked, and the program made, before any file is written: a refusal is one
line naming the option, and nothing is written.
"""

from __future__ import annotations

from pathlib import Path
from typing import List, Optional

import typer

from axiscal.errors import InputError

__all__ = ["PROGRAM", "CONTROLLER", "FEED", "MAX_FEED", "LIMITS", "SAFE", "SIGN", "ORIGIN", "INCH",
           "TRIGGER", "NAME", "NUMBER", "make_program", "write_program_file"]

PROGRAM = typer.Option(None, "--program", help="Write the plan's part program to FILE (with --controller).")
CONTROLLER = typer.Option(None, "--controller", help="Language of the program: fanuc, haas, sinumerik, heidenhain or linuxcnc.")
FEED = typer.Option(1000.0, "--feed", help="Feed of the measuring moves, mm/min (deg/min on a rotary axis).")
MAX_FEED = typer.Option(None, "--max-feed", help="The machine's highest feed (the --feed unit): a larger feed is refused.")
LIMITS = typer.Option(None, "--limits", help="Machine limits LO:HI of the axis (AXIS=LO:HI for several, repeatable), mm or deg: a plan beyond them is refused.")
SAFE = typer.Option(None, "--safe", help="Safe start POS (AXIS=POS, repeatable), machine position the program starts and ends at.")
SIGN = typer.Option(None, "--sign", help="-1 (AXIS=-1, repeatable) where the machine counts the axis opposite to the test's positive direction.")
ORIGIN = typer.Option(None, "--origin", help="Machine position of the plan's zero, POS or AXIS=POS (repeatable; default 0).")
INCH = typer.Option(False, "--inch", help="Write linear positions and feeds in inch (G20, G70, INCH).")
TRIGGER = typer.Option(None, "--trigger", help="Stillness the trigger needs at a stop, s (default 0.5): a shorter --dwell is refused.")
NAME = typer.Option("AXISCAL", "--name", help="Program name (letters, digits, _).")
NUMBER = typer.Option(None, "--number", help="Program number (Fanuc 1-9999, Haas 1-99999; default 1).")


def _specs(values, axes: str, option: str, parse) -> dict:
    """``AXIS=VALUE`` (or a bare VALUE for the plan's only axis) items as a dict."""
    out = {}
    for item in values or []:
        text = str(item).strip()
        if "=" in text:
            axis, _, value = text.partition("=")
            axis = axis.strip().upper()
        elif len(axes) == 1:
            axis, value = axes, text
        else:
            raise InputError(f"{option} {text!r}: name the axis, as {axes[0]}=… (the plan moves "
                             f"{', '.join(axes)})")
        if axis not in axes:
            raise InputError(f"{option} {text!r}: the plan moves {', '.join(axes)}, not {axis!r}")
        try:
            out[axis] = parse(value.strip())
        except (ValueError, TypeError):
            raise InputError(f"{option} {text!r}: {_FORMS[option]}") from None
    return out


_FORMS = {"--limits": "give LO:HI (as -10:810), or AXIS=LO:HI",
          "--safe": "give a position, or AXIS=POS", "--origin": "give a position, or AXIS=POS",
          "--sign": "give 1 or -1, or AXIS=-1"}


def _limits(text: str) -> tuple:
    lo, sep, hi = text.rpartition(":")
    if not sep:
        raise ValueError(text)
    return float(lo), float(hi)


def _sign(text: str) -> int:
    v = float(text)
    if v not in (1.0, -1.0):
        raise ValueError(text)
    return int(v)


def make_program(plan, axes: str, program: Optional[Path], controller: Optional[str], *,
                 feed: float, max_feed: Optional[float], limits: Optional[List[str]],
                 safe: Optional[List[str]], sign: Optional[List[str]],
                 origin: Optional[List[str]], inch: bool, trigger: Optional[float], name: str,
                 number: Optional[int], spindle: Optional[float] = None) -> Optional[str]:
    """The program's text (None without ``--program``), every option checked; nothing written."""
    from axiscal.programs import DEFAULT_TRIGGER_S, MachineOptions, ProgramError, write_program
    from axiscal.programs import _dialect_class

    if program is None:
        if controller is not None:
            raise InputError("--controller without --program: give --program FILE to write it to")
        given = [o for o, v in (("--max-feed", max_feed), ("--limits", limits), ("--safe", safe),
                                ("--sign", sign), ("--origin", origin), ("--trigger", trigger),
                                ("--number", number), ("--spindle-max", spindle)) if v]
        if given or inch:
            raise InputError(f"{(given or ['--inch'])[0]} describes the machine for the part "
                             "program: give --program FILE --controller NAME")
        return None
    if controller is None:
        raise InputError("--program needs --controller (fanuc, haas, sinumerik, heidenhain or "
                         "linuxcnc)")
    from axiscal.cli._common import out_path

    try:
        _dialect_class(controller)
        out_path(program, "part program")
        opts = MachineOptions(
            feed=feed, max_feed=max_feed, limits=_specs(limits, axes, "--limits", _limits),
            safe=_specs(safe, axes, "--safe", float), sign=_specs(sign, axes, "--sign", _sign),
            origin=_specs(origin, axes, "--origin", float), units="inch" if inch else "mm",
            trigger=DEFAULT_TRIGGER_S if trigger is None else trigger, spindle=spindle)
        return write_program(plan, controller, opts, name=name, number=number)
    except ProgramError as exc:
        raise InputError(f"{exc} ({_OPTION.get(exc.option, '--' + exc.option)})") from None


#: A ProgramError's option where the command's option (or input) has another name.
_OPTION = {"spindle": "--spindle-max", "programme": "--speed-programme",
           "interval": "--interval-s", "setup": "CONFIG's [[setup]]",
           "poses": "CONFIG's [[setup]]"}


def write_program_file(path: Optional[Path], text: Optional[str], controller: Optional[str]) -> None:
    """Write the program made by :func:`make_program` (atomically) and say so on stderr."""
    if path is None or text is None:
        return
    from axiscal.cli._common import note
    from axiscal.io._files import write_text_atomic

    write_text_atomic(path, text)
    note(f"wrote {controller} program {path} ({text.count(chr(10))} lines)")
