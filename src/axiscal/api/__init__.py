"""The public Python API: the only stable surface of axiscal.

Everything a script or a notebook needs is at the package's top and documented here::

    import axiscal

    ds = axiscal.read("x_axis.csv")     # format told by the content
    ev = axiscal.evaluate(ds)           # ISO 230-2:2014 by default
    ev.to_dict()                        # the keys of ``axiscal iso230-2 --json``
    ev.plot()                           # a matplotlib Figure
    ev.report("x_axis.html")            # the HTML report
    table = axiscal.compensation_table(ev, spacing=10)
    axiscal.write_table(table, "siemens-840d", "x.ini")
    axiscal.plan("linear", length=800).program("fanuc", feed=2000)   # the part program
    with axiscal.History("sqlite:///history.sqlite") as h:
        h.add("x_axis.csv", machine="VMC-1")

The command line and the workbench are built on these same entry points: ``axiscal iso230-2``,
``evaluate`` and ``ballbar analyze`` call :func:`read` and :func:`evaluate` and print
:meth:`Evaluation.to_dict` for ``--json``; ``simulate``, ``rotary simulate``, ``scale
home|gantry``, ``motion simulate`` and ``ballbar simulate`` call :func:`simulate`;
``compensate`` calls :func:`compensation_table` and :func:`write_table`; ``history add`` and
the workbench's upload call :meth:`History.add`; ``compensate-environment``, ``volumetric map``
and ``volumetric compensate`` call :func:`compensate_environment`, :func:`volumetric_map` and
:func:`volumetric_compensation`. Every number comes from the library below
(:func:`axiscal.store.kinds.evaluate_file` is the one evaluation per kind of test,
:mod:`axiscal.standards.positioning_standards` the registry of positioning standards,
:mod:`axiscal.io.results` builds the ``--json`` objects), so a result here equals the command's
``--json`` for the same file. Modules below this one may change between releases; this one
changes only with a note in CHANGELOG.md.

The names are imported on first use (PEP 562), so ``import axiscal.api`` costs next to nothing
and a command's start-up pays only for what it calls. The package's modules: ``_reading``
(:func:`read`, :func:`evaluate`), ``_simulating`` (:func:`simulate`, :func:`volumetric_map`,
:func:`volumetric_compensation`, :func:`compensate_environment`), ``_compensation``
(:func:`compensation_table`, :func:`write_table`), ``_results`` (:class:`Evaluation`,
:class:`Simulation`), ``_history`` (:class:`History`) and ``_config`` (dict configurations
checked by the TOML files' schemas); ``_thermal`` (ISO 230-3 thermal tests:
:func:`simulate_thermal`, :func:`read_thermal`, :func:`evaluate_thermal`,
:func:`fit_thermal_model`, :func:`thermal_compensation`, called by ``axiscal thermal``).
"""

from __future__ import annotations

TYPE_CHECKING = False   # as typing.TYPE_CHECKING, without importing typing (start-up time)

__all__ = ["Evaluation", "Simulation", "History", "read", "evaluate", "simulate",
           "volumetric_map", "volumetric_compensation", "compensate_environment",
           "compensation_table", "write_table", "plan", "Plan", "simulate_thermal", "read_thermal",
           "evaluate_thermal", "fit_thermal_model", "thermal_compensation"]

#: The module of each public name (and of ``PathLike``, the type of a path argument, and
#: ``DEFAULT_STANDARD``, the standard :func:`evaluate` applies when none is named).
_HOME = {"DEFAULT_STANDARD": "_results", "read": "_reading", "evaluate": "_reading",
         "simulate": "_simulating", "volumetric_map": "_simulating",
         "volumetric_compensation": "_simulating", "compensate_environment": "_simulating",
         "compensation_table": "_compensation", "write_table": "_compensation",
         "Evaluation": "_results", "Simulation": "_results", "PathLike": "_results",
         "History": "_history", "plan": "_planning", "Plan": "_planning",
         "simulate_thermal": "_thermal", "read_thermal": "_thermal",
         "evaluate_thermal": "_thermal", "fit_thermal_model": "_thermal",
         "thermal_compensation": "_thermal"}

if TYPE_CHECKING:   # pragma: no cover - for type checkers and IDEs
    from typing import Any

    from axiscal.api._compensation import compensation_table, write_table
    from axiscal.api._history import History
    from axiscal.api._planning import Plan, plan
    from axiscal.api._reading import evaluate, read
    from axiscal.api._results import DEFAULT_STANDARD, Evaluation, PathLike, Simulation
    from axiscal.api._simulating import (compensate_environment, simulate,
                                         volumetric_compensation, volumetric_map)


def __getattr__(name: str) -> Any:
    """A public name, imported from its module when first used (PEP 562)."""
    if name == "fiveaxis":   # a namespace module: axiscal.fiveaxis.plan | simulate | identify
        from importlib import import_module

        return import_module("axiscal.api.fiveaxis")
    home = _HOME.get(name)
    if home is None:
        raise AttributeError(f"module 'axiscal.api' has no attribute {name!r}")
    from importlib import import_module

    value = getattr(import_module(f"axiscal.api.{home}"), name)
    globals()[name] = value
    return value


def __dir__() -> list[str]:
    return sorted(set(globals()) | set(_HOME) | {"fiveaxis"})
