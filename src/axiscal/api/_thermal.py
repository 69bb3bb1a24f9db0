"""Thermal effects by ISO 230-3:2020 in the public API: twin, plan, simulate, read, evaluate,
model, SINUMERIK compensation.

``axiscal thermal plan | simulate | evaluate | model | compensate`` call these functions::

    import axiscal

    sim = axiscal.simulate_thermal("spindle", seed=1)          # the shipped twin
    sim.log, sim.truth                                         # what was logged; the truth
    res = axiscal.evaluate_thermal(sim.log)                    # ISO 230-3 figures
    res.to_dict()                                              # as ``thermal evaluate --json``
    model = axiscal.fit_thermal_model(["a.csv", "b.csv"], "c.csv", test="d.csv")
    comp = axiscal.thermal_compensation(model)                 # SINUMERIK K0(T), tanβ(T), P0

Options are in the units people write (hours, minutes, mm); the library below is SI.
"""

from __future__ import annotations

from pathlib import Path
from typing import Any, Sequence

__all__ = ["thermal_twin", "plan_thermal", "simulate_thermal", "read_thermal",
           "evaluate_thermal", "fit_thermal_model", "thermal_compensation",
           "verify_thermal_compensation", "DEFAULT_TWIN"]

#: The shipped twin of a vertical machining centre.
DEFAULT_TWIN = Path(__file__).resolve().parent.parent / "data" / "thermal_vmc.toml"


def thermal_twin(config: Any = None):
    """The thermal twin from a TOML file (default: :data:`DEFAULT_TWIN`)."""
    from axiscal.io._files import read_text
    from axiscal.machines.thermal_config import parse_thermal_config

    path = DEFAULT_TWIN if config is None else Path(config)
    return parse_thermal_config(read_text(path), str(path))


def plan_thermal(test: str, config: Any = None, *, duration_h: float | None = None,
                 run_h: float | None = None, interval_s: float = 60.0, speed: float = 0.5,
                 axis: str = "X", p1_mm: float | None = None, p2_mm: float | None = None,
                 duty: float = 0.8, position_mm: float | None = None,
                 instrument_drift_um_per_h: float = 0.0, start_h: float = 8.0,
                 programme: Sequence[tuple[float, float]] = ()):
    """A plan of an ISO 230-3 test (``etve``, ``spindle``, ``linear``) or of the ISO 230-2
    drift check (``drift-check``) on the twin; defaults in
    :mod:`axiscal.procedures.thermal`. ``programme``: spindle speed steps (fraction of the
    maximum, minutes), repeated through the run."""
    from axiscal.errors import InputError
    from axiscal.procedures.thermal import plan_thermal as plan

    targets = None
    if p1_mm is not None and p2_mm is not None:
        targets = (p1_mm * 1e-3, p2_mm * 1e-3)
    elif (p1_mm is None) != (p2_mm is None):
        raise InputError("give both targets, P1 and P2, or neither")
    return plan(thermal_twin(config), test,
                duration=None if duration_h is None else duration_h * 3600,
                run=None if run_h is None else run_h * 3600, interval=interval_s, speed=speed,
                axis=axis, targets=targets, duty=duty,
                position=None if position_mm is None else position_mm * 1e-3,
                instrument_drift=instrument_drift_um_per_h * 1e-6 / 3600, start=start_h * 3600,
                programme=tuple((f, m * 60) for f, m in programme))


def simulate_thermal(test: str, config: Any = None, seed: int = 0, **options):
    """Simulate a planned test on the twin: a :class:`~axiscal.procedures.thermal.ThermalSimulation`
    (log and truth) or, for ``drift-check``, a :class:`~axiscal.procedures.thermal.DriftCheck`.
    ``options`` as :func:`plan_thermal`."""
    import numpy as np

    from axiscal.procedures.thermal import simulate_drift_check
    from axiscal.procedures.thermal import simulate_thermal as simulate

    twin = thermal_twin(config)
    plan = plan_thermal(test, config, **options)
    rng = np.random.default_rng(seed)
    if plan.test == "drift-check":
        return simulate_drift_check(twin, plan, rng)
    return simulate(twin, plan, rng)


def read_thermal(path: Any):
    """A thermal log file (:mod:`axiscal.io.thermal`), checked."""
    from axiscal.io.thermal import read_thermal_log

    return read_thermal_log(path)


def evaluate_thermal(data: Any):
    """The ISO 230-3:2020 figures of a log (a :class:`ThermalLog` or a path)."""
    from axiscal.standards.iso230_3 import evaluate_thermal as evaluate

    return evaluate(_log(data))


def fit_thermal_model(fit: Any, validation: Any, test: Any = None, *,
                      sensors: Sequence[str] | None = None,
                      channels: Sequence[str] | None = None):
    """A thermal model (:mod:`axiscal.compensation.thermal_model`) fitted on ``fit`` (one log or
    path, or several), chosen on ``validation``, judged on ``test``."""
    from axiscal.compensation.thermal_model import fit_thermal_model as fit_model

    fits = [_log(f) for f in (fit if isinstance(fit, (list, tuple)) else [fit])]
    return fit_model(fits, _log(validation), None if test is None else _log(test),
                     sensors=tuple(sensors) if sensors else None,
                     channels=tuple(channels) if channels else None)


def thermal_compensation(model: Any):
    """SINUMERIK's temperature compensation (K0(T), tanβ(T), P0) from a linear-axis model."""
    from axiscal.compensation.thermal_model import sinumerik_compensation

    return sinumerik_compensation(model)


def verify_thermal_compensation(comp: Any, config: Any = None, seed: int = 0, *,
                                on_controller: bool = False, progress: Any = None, **options):
    """A linear test of ``comp``'s axis on the twin, run without and with the compensation on
    one thermal history (:func:`axiscal.compensation.thermal_model.verify_on_twin`); with
    ``on_controller``, measured through a real LinuxCNC with axiscal's HAL component
    (:func:`axiscal.compensation.on_controller_thermal.verify_thermal_on_linuxcnc`).
    ``options`` as :func:`plan_thermal`; ``progress(done, total)`` follows the LinuxCNC run."""
    plan = plan_thermal("linear", config, axis=comp.axis, **options)
    if on_controller:
        from axiscal.compensation.on_controller_thermal import verify_thermal_on_linuxcnc

        return verify_thermal_on_linuxcnc(thermal_twin(config), plan, comp, seed,
                                          progress=progress)
    from axiscal.compensation.thermal_model import verify_on_twin

    return verify_on_twin(thermal_twin(config), plan, comp, seed)


def _log(data: Any):
    from axiscal.standards.iso230_3_data import ThermalLog

    return data if isinstance(data, ThermalLog) else read_thermal(data)
