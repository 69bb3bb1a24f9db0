"""Part programs that drive a machine through an axiscal test plan, in the controller's language.

:func:`write_program` turns a plan (an ISO 230-2 positioning plan, linear or rotary, linear or
pilgrim cycle; an ISO 230-4 circular plan; squareness or straightness lines; an ISO 230-3 thermal
test's cycle, :mod:`axiscal.programs._thermal`; a five-axis R-test, :class:`FiveAxisProgram`,
and a five-axis ballbar path, :class:`BallbarProgram`, :mod:`axiscal.programs._five_axis`) and
the machine's
options (:class:`MachineOptions`: feed, limits, safe start, sign convention, units, the trigger's
stillness) into the program a controller runs: a safe-start block, every move of the plan in
order at the feed, a dwell after each measurement, the return to the safe start and the end of
program. Nothing is written for a plan the machine cannot run: a move beyond the limits, a feed
of 0 or beyond the machine's, a dwell shorter than the trigger needs are refused with a
:class:`ProgramError` that names the option (``option``).

One module per controller language, each citing the manual it follows:

==============  ===========================  ========================================
controller      module                       dwell, framing
==============  ===========================  ========================================
``fanuc``       :mod:`axiscal.programs.iso`  ``G04 P<ms>``, ``%``, ``O0001``, ``M30``
``haas``        :mod:`axiscal.programs.iso`  ``G04 P<s>.``, ``%``, ``O00001``, ``M30``
``sinumerik``   :mod:`~.sinumerik`           ``G4 F<s>``, ``%_N_…_MPF``, ``;``, ``M30``
``heidenhain``  :mod:`~.heidenhain`          ``CYCL DEF 9.0/9.1``, ``BEGIN PGM``, numbered
``linuxcnc``    :mod:`~.linuxcnc`            ``G4 P<s>``, ``%``, ``M2``
==============  ===========================  ========================================
"""

from __future__ import annotations

from axiscal.programs._five_axis import BallbarProgram, FiveAxisProgram
from axiscal.programs._motion import (DEFAULT_TRIGGER_S, MachineOptions, Motion, ProgramError,
                                      build_motion)

__all__ = ["write_program", "program_motion", "MachineOptions", "ProgramError", "CONTROLLERS",
           "DEFAULT_TRIGGER_S", "FiveAxisProgram", "BallbarProgram", "extension", "manual"]

#: Controller name -> (module, class) of its dialect.
_DIALECTS = {"fanuc": ("iso", "Fanuc"), "haas": ("iso", "Haas"),
             "sinumerik": ("sinumerik", "Sinumerik"), "heidenhain": ("heidenhain", "Heidenhain"),
             "linuxcnc": ("linuxcnc", "LinuxCNC")}
#: The controllers a program can be written for.
CONTROLLERS = tuple(_DIALECTS)


def _dialect_class(controller: str):
    import importlib

    key = str(controller).strip().lower()
    if key not in _DIALECTS:
        raise ProgramError("controller", f"controller {controller!r}: give one of "
                           f"{', '.join(CONTROLLERS)}")
    module, cls = _DIALECTS[key]
    return getattr(importlib.import_module(f"axiscal.programs.{module}"), cls)


def program_motion(plan, options: MachineOptions | None = None) -> Motion:
    """The checked motion of ``plan`` (what every dialect writes)."""
    from axiscal.procedures.five_axis import FiveAxisPlan
    from axiscal.procedures.thermal import ThermalPlan

    options = options or MachineOptions()
    if isinstance(plan, ThermalPlan):
        from axiscal.programs._thermal import thermal_motion

        return thermal_motion(plan, options)
    if isinstance(plan, BallbarProgram):
        from axiscal.programs._five_axis import ballbar_motion

        return ballbar_motion(plan, options)
    if isinstance(getattr(plan, "plan", None), FiveAxisPlan):     # a plan with its machine
        from axiscal.programs._five_axis import five_axis_motion

        return five_axis_motion(plan.plan, plan.machine, options, getattr(plan, "dwell", 1.0),
                                getattr(plan, "clearance", 10.0))
    return build_motion(plan, options)


def write_program(plan, controller: str, options: MachineOptions | None = None, *,
                  name: str = "AXISCAL", number: int | None = None) -> str:
    """The part program of ``plan`` in ``controller``'s language (text).

    Parameters
    ----------
    plan : TestPlan, CircularPlan, LinePlan, ThermalPlan or FiveAxisProgram
    controller : str
        One of :data:`CONTROLLERS`.
    options : MachineOptions, optional
        Feed, limits, safe start, sign, units, trigger (defaults: 1000 per minute, no limits).
    name : str
        Program name (letters, digits, ``_``).
    number : int, optional
        Program number where the controller has one (Fanuc 1-9999, Haas 1-99999; default 1).

    Raises
    ------
    ProgramError
        The plan cannot run as asked; ``option`` names what to change.

    Examples
    --------
    >>> from axiscal.procedures.positioning import plan_linear
    >>> p = plan_linear(100, irregularity=0, runs=1, bidirectional=False, dwell=1)
    >>> text = write_program(p, "fanuc", MachineOptions(feed=2000, limits={"X": (-10, 110)}))
    >>> [line for line in text.splitlines() if line.startswith("G")][1:5]
    ['G00 X-5.000', 'G01 X0.000 F2000.0', 'G04 P1000', 'G01 X25.000 F2000.0']
    """
    cls = _dialect_class(controller)
    motion = program_motion(plan, options)
    return cls(motion, name, number).write()


def extension(controller: str) -> str:
    """The usual file extension of ``controller``'s programs (``.nc``, ``.mpf``, ``.h``,
    ``.ngc``)."""
    return _dialect_class(controller).extension


def manual(controller: str) -> str:
    """The manual (and its sections) ``controller``'s dialect follows."""
    return _dialect_class(controller).manual
