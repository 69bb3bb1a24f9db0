"""``axiscal.plan``: a test plan and the part program that runs it (issue 41).

::

    p = axiscal.plan("linear", length=800)              # ISO 230-2, axiscal plan linear
    p.program("fanuc", feed=2000, limits={"X": (-10, 810)})
    p.write_program("x.nc", "fanuc")
    axiscal.plan("circular", radius=150, feed=1000).program("heidenhain")

The plan kinds and their arguments are those of :func:`axiscal.procedures.positioning.plan_linear`
(``linear``), :func:`~axiscal.procedures.positioning.plan_rotary` (``rotary``),
:func:`axiscal.procedures.circular_plan.plan_circular` (``circular``),
:func:`~axiscal.procedures.circular_plan.plan_squareness` (``squareness``) and
:func:`~axiscal.procedures.circular_plan.plan_straightness` (``straightness``); ``cycle="pilgrim"``
makes a pilgrim-step positioning plan; ``thermal`` takes the arguments of
:func:`axiscal.api._thermal.plan_thermal` (an ISO 230-3 test on the thermal twin, as ``axiscal
thermal plan``) and ``fiveaxis`` a five-axis configuration (``config``, default the shipped A/C
example; ``dwell``, s, and ``clearance``, mm, of its R-test program). :meth:`Plan.program` takes the options of
:class:`axiscal.programs.MachineOptions` and calls :func:`axiscal.programs.write_program`, the
one writer ``axiscal plan … --program`` and the workbench also call.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

from axiscal.errors import InputError

__all__ = ["plan", "Plan"]

_KINDS = {"linear": ("axiscal.procedures.positioning", "plan_linear"),
          "rotary": ("axiscal.procedures.positioning", "plan_rotary"),
          "circular": ("axiscal.procedures.circular_plan", "plan_circular"),
          "squareness": ("axiscal.procedures.circular_plan", "plan_squareness"),
          "straightness": ("axiscal.procedures.circular_plan", "plan_straightness"),
          "thermal": ("axiscal.api._thermal", "plan_thermal"),
          "fiveaxis": ("axiscal.api._planning", "_fiveaxis")}


@dataclass(frozen=True, eq=False)
class Plan:
    """A test plan (``plan``: the procedures' object) and what can be made of it."""

    kind: str
    plan: Any

    def program(self, controller: str, *, name: str = "AXISCAL", number: int | None = None,
                **machine) -> str:
        """The part program in ``controller``'s language (text).

        ``machine``: the fields of :class:`axiscal.programs.MachineOptions` (``feed``,
        ``max_feed``, ``limits``, ``safe``, ``sign``, ``origin``, ``units``, ``trigger``).
        """
        from axiscal.programs import MachineOptions, write_program

        opts = dict(machine)
        if self.kind == "circular":
            opts.setdefault("feed", self.plan.feed)
        try:
            options = MachineOptions(**opts)
        except TypeError as exc:
            raise InputError(f"program options: {exc}") from None
        return write_program(self.plan, controller, options, name=name, number=number)

    def write_program(self, path, controller: str, **options) -> str:
        """Write :meth:`program` to ``path`` (atomically); the text."""
        from axiscal.io._files import write_text_atomic

        text = self.program(controller, **options)
        write_text_atomic(path, text)
        return text

    def to_csv(self) -> str:
        """The move sequence as CSV (positioning plans; ``axiscal plan … --csv``)."""
        if not hasattr(self.plan, "to_csv"):
            raise InputError(f"a {self.kind} plan has no CSV of moves: write its program")
        return self.plan.to_csv()

    def __str__(self) -> str:
        return str(self.plan)


def plan(kind: str = "linear", **arguments) -> Plan:
    """Make a test plan of ``kind`` (``linear``, ``rotary``, ``circular``, ``squareness``,
    ``straightness``, ``thermal``, ``fiveaxis``).

    Examples
    --------
    >>> import axiscal
    >>> p = axiscal.plan("linear", length=100, irregularity=0, runs=1, dwell=1)
    >>> [line for line in p.program("linuxcnc").splitlines() if line.startswith("G")][:4]
    ['G21 G17 G40 G49 G80 G90 G94', 'G0 X-5.000', 'G1 X0.000 F1000.0', 'G4 P1.000']
    """
    from importlib import import_module

    if kind not in _KINDS:
        raise InputError(f"plan kind {kind!r}: give one of {', '.join(_KINDS)}")
    module, function = _KINDS[kind]
    try:
        made = getattr(import_module(module), function)(**arguments)
    except TypeError as exc:
        raise InputError(f"plan {kind}: {exc}") from None
    return Plan(kind, made)



def _fiveaxis(config=None, dwell: float = 1.0, clearance: float = 10.0):
    """A five-axis plan with its machine (:class:`axiscal.programs.FiveAxisProgram`): ``config``
    a path or a parsed configuration, default the shipped A/C example."""
    from axiscal.api import fiveaxis
    from axiscal.programs import FiveAxisProgram

    if config is None:
        from importlib import resources

        from axiscal.io._files import load_toml

        config = load_toml(resources.files("axiscal.data").joinpath(fiveaxis.EXAMPLES["A/C"]))
    planned = fiveaxis.plan(config)
    return FiveAxisProgram(planned.plan, planned.machine, dwell=dwell, clearance=clearance)
