"""axiscal: calibration of machine-tool and turntable axes.

Laser interferometry, reference rotary calibrators, laser scales, ballbars and multi-DOF optical
sensors, evaluated by the ISO 230 family of standards, with faithful simulations of every
instrument and machine.

The package is layered (see the README): ``errors``, ``units``, ``datasets`` -> ``physics`` ->
``standards`` -> ``machines`` -> ``instruments`` -> ``procedures`` -> ``compensation`` ->
``io``/``report``/``store`` -> ``api`` -> ``cli``/``web``. A layer imports only from the layers
before it.

The public API (:mod:`axiscal.api`, the only stable surface) is at the top: ``axiscal.read``,
``axiscal.evaluate``, ``axiscal.simulate``, ``axiscal.volumetric_map``,
``axiscal.volumetric_compensation``,
``axiscal.compensate_environment``, ``axiscal.compensation_table``,
``axiscal.write_table``, ``axiscal.History``. Its names are imported on first use, so
``import axiscal`` (and the command line's start-up) stays light. Every exception the library
raises on purpose is at the top too (``axiscal.DataFormatError``, ``axiscal.InputError`` ...,
all deriving from ``axiscal.AxiscalError`` and a builtin: :mod:`axiscal.errors`).
"""

from __future__ import annotations

TYPE_CHECKING = False   # as typing.TYPE_CHECKING, without importing typing (start-up time)

__version__ = "0.1.0"

__all__ = ["__version__", "read", "evaluate", "simulate", "volumetric_map",
           "volumetric_compensation", "compensate_environment", "compensation_table",
           "write_table", "History", "Evaluation", "Simulation", "plan", "Plan",
           "simulate_thermal", "read_thermal", "evaluate_thermal", "fit_thermal_model",
           "thermal_compensation"]

from axiscal.errors import (  # noqa: E402  (the exceptions: light, and at the top by name)
    ERRORS,
    AxiscalError,
    ConfigError,
    ControllerLimitError,
    DataFormatError,
    InputError,
    InsufficientRunsError,
    MeasurementError,
    MissingExtraError,
    MissingFileError,
    NotAvailableError,
    NotAuthorisedError,
    NotFoundError,
    ProgramError,
    SignalLossError,
    SignConventionError,
    StoreError,
    UnitError,
)

_API = tuple(__all__[1:])
__all__ += list(ERRORS)

if TYPE_CHECKING:   # pragma: no cover - for type checkers and IDEs
    from typing import Any

    from axiscal.api import (Evaluation, History, Simulation, compensate_environment,
                             compensation_table, evaluate, read, simulate,
                             volumetric_compensation, volumetric_map, write_table, plan, Plan)


def __getattr__(name: str) -> Any:
    """The public API's names, imported from :mod:`axiscal.api` when first used (PEP 562)."""
    if name in _API or name == "fiveaxis":
        from axiscal import api

        return getattr(api, name)
    raise AttributeError(f"module 'axiscal' has no attribute {name!r}")


def __dir__() -> list[str]:
    return sorted(set(globals()) | set(__all__) | {"fiveaxis"})
