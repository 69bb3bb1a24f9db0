"""The temperature compensation applied by LinuxCNC, proven through a real LinuxCNC (issue 44).

From the compensation fitted to ISO 230-3:2020 linear-axis tests
(:class:`~axiscal.compensation.thermal_model.SinumerikTemperatureCompensation`: K0(T), tanβ(T)
and P0, each temperature through its lag), :func:`linuxcnc_thermcomp` writes what axiscal's
userspace HAL component ``axiscal_thermcomp.py`` (package data) reads; the component drives the
axis's external offset with −ΔK = −(K0 + tanβ (P − P0)) at the commanded position (LinuxCNC
documentation, "External Axis Offsets"; :mod:`axiscal.instruments.linuxcnc_thermal`).

:func:`verify_thermal_on_linuxcnc` runs the linear-axis test (ISO 230-3:2020 Clause 7) on the
thermal twin with the positioning measured through LinuxCNC, twice in one session on one
simulated thermal history (one seed: the same temperatures, the same reading noise): the
component active, then inactive, each run starting its filters afresh (``reset``). At every sample of the plan the simulated sensors' readings go
to LinuxCNC through HAL (``feed``: the temperature pins, then the sensors' clock); at every
``every``-th sample the axis moves to P1 and P2 (a LinuxCNC move each, MDI), and the simulated
laser reads the position the machine reaches: ``motor-pos-cmd`` (command + external offset)
plus the twin's thermal positioning error there and its noise, minus the target.

**Time compression.** LinuxCNC runs in real time, the thermal test takes hours: the sensors'
clock is the ``time`` pin (``"clock": "pin"`` in ``thermcomp.json``), advanced by the plan's
interval at each feed, so the component's lags run on the simulated clock while a simulated
hour passes in a few seconds of LinuxCNC's (the ratio is measured and reported). The twin's
heat comes from the plan's duty (the axis's share of time in motion), not from the LinuxCNC
moves, which are the measurement's: at 60 s between samples a real axis would be moving
between them; the compressed run moves only to measure.
"""

from __future__ import annotations

import json
import time
from dataclasses import dataclass

import numpy as np

from axiscal.compensation.thermal_model import (CompensationCheck,
                                                SinumerikTemperatureCompensation, lagged)
from axiscal.errors import InputError, MeasurementError

__all__ = ["linuxcnc_thermcomp", "thermal_linuxcnc_outputs", "ThermalOnController",
           "verify_thermal_on_linuxcnc"]

#: The simulated X axis's limits, mm/s and mm/s² (the simulated drive follows any command;
#: high, so the 2 × 2 × 49 moves of a 4 h test take about 15 s), and the share of them left to
#: the external offset, ``[AXIS_X] OFFSET_AV_RATIO``: small, so the offset planner's dead band,
#: 0.001 × OFFSET_AV_RATIO × acceleration × servo period² (LinuxCNC ``simple_tp.c``,
#: ``tiny_dp``), stays 20 nm (at 0.2 it was 200 nm and a settled offset stood 0.12 µm from its
#: request, beyond the 50 nm the reading waits for).
VELOCITY, ACCELERATION, AV_RATIO = 50_000.0, 1.0e6, 0.02


def linuxcnc_thermcomp(comp: SinumerikTemperatureCompensation, *, clock: str = "wall",
                       interval: float = 60.0) -> dict:
    """The parameters ``axiscal_thermcomp.py`` reads (``thermcomp.json``; mm, 1/K, s).

    ``clock``: ``"wall"`` (a machine: a reading every ``interval`` s of the computer's clock)
    or ``"pin"`` (the ``time`` pin's, as the time-compressed test feeds it).
    """
    if clock not in ("wall", "pin"):
        raise InputError(f"clock {clock!r}: wall or pin")
    if not interval > 0:
        raise InputError(f"interval {interval!r} s must be > 0")
    return {"axis": comp.axis, "sensors": list(comp.sensors), "lags_s": list(comp.lags),
            "k0_mm_per_K": [k * 1e3 for k in comp.k0], "slope_per_K": list(comp.slope),
            "p0_mm": round(comp.p0 * 1e3, 9), "reference_C": 20.0, "clock": clock,
            "interval_s": float(interval),
            "model": "dK = K0 + tan(beta) (P - P0), K0 = sum k0_i (L_i - 20 C), tan(beta) = "
                     "sum s_i (L_i - 20 C); the external offset is -dK"}


def thermal_linuxcnc_outputs(comp: SinumerikTemperatureCompensation) -> dict:
    """The files a LinuxCNC machine is given (name -> text): ``thermcomp.json``, the component
    ``axiscal_thermcomp.py`` and its HAL file ``axiscal_thermcomp.hal`` (axis X; net the
    component's ``temp-N`` pins from the temperature inputs, one per term of ``sensors``)."""
    from importlib import resources

    data = resources.files("axiscal.data") / "linuxcnc"
    out = {"thermcomp.json": json.dumps(linuxcnc_thermcomp(comp), indent=1) + "\n"}
    for name in ("axiscal_thermcomp.py", "axiscal_thermcomp.hal"):
        out[name] = (data / name).read_text()
    return out


@dataclass(frozen=True)
class ThermalOnController:
    """The linear-axis test measured through LinuxCNC without and with the compensation.

    Attributes
    ----------
    check : CompensationCheck
        The largest drift while running at P1 and P2 (ISO 230-3:2020 Clause 7), before and
        after, and the fall.
    moves : int
        LinuxCNC moves per run.
    applied : float, m
        Largest |(motor − commanded) + ΔK| over the compensated run's readings: what LinuxCNC
        applied beside what axiscal's model asks at that reading.
    compression : float
        Simulated seconds per second of LinuxCNC's clock over both runs.
    settings : dict
    """

    check: CompensationCheck
    moves: int
    applied: float
    compression: float
    settings: dict

    def to_dict(self) -> dict:
        return {**self.check.to_dict(), "moves_per_run": self.moves,
                "largest_applied_difference_um": round(self.applied * 1e6, 6),
                "time_compression": round(self.compression, 1),
                "on_controller": dict(self.settings)}

    def __str__(self) -> str:
        return (str(self.check).replace("verified on the twin", "measured through LinuxCNC")
                + f"\n{self.moves} LinuxCNC moves per run; the sensors' clock ran "
                f"{self.compression:.0f}× faster than LinuxCNC's; largest |applied − asked| "
                f"offset {self.applied * 1e6:.3f} µm")


def verify_thermal_on_linuxcnc(twin, plan, comp: SinumerikTemperatureCompensation, seed: int,
                               *, every: int = 5, progress=None) -> ThermalOnController:
    """Measure ``plan`` (a linear test) through LinuxCNC without and with ``comp`` (module
    docstring); the positioning error read at every ``every``-th sample of the plan (at most
    :data:`~axiscal.standards.iso230_3_data.MAX_INTERVAL` apart). ``progress(done, total)``,
    if given, is called after each sample of both runs."""
    from axiscal.instruments.linuxcnc_controller import unavailable_reason
    from axiscal.instruments.linuxcnc_thermal import LinuxCNCThermal
    from axiscal.procedures.thermal import simulate_thermal
    from axiscal.standards.iso230_3 import evaluate_linear
    from axiscal.standards.iso230_3_data import MAX_INTERVAL, ThermalLog

    if plan.test != "linear" or plan.axis.upper() != comp.axis.upper() or comp.axis.upper() != "X":
        raise InputError(f"the LinuxCNC verification runs a linear test of axis X (the "
                         f"component drives X); got a {plan.test} test of axis {plan.axis} and "
                         f"a compensation of axis {comp.axis}")
    if not (isinstance(every, int) and every >= 1 and every * plan.interval <= MAX_INTERVAL):
        raise InputError(f"every = {every!r}: a whole number ≥ 1 with every × interval ≤ "
                         f"{MAX_INTERVAL:g} s")
    why = unavailable_reason()
    if why:
        raise MeasurementError(f"LinuxCNC cannot run here: {why}")
    sim = simulate_thermal(twin, plan, np.random.default_rng(seed))
    log, history = sim.log, sim.history
    t = log.time
    temps = np.column_stack([log.temperatures[s] for s in comp.sensors])
    lag = np.column_stack([lagged(log.temperatures[s], t, tau)
                           for s, tau in zip(comp.sensors, comp.lags)])
    measured = np.arange(0, t.size, every)
    targets_mm = [round(p * 1e3, 9) for p in plan.targets]
    noise = np.random.default_rng([seed, 44]).normal(0.0, twin.displacement_noise,
                                                     (measured.size, 2))
    lo, hi = (v * 1e3 for v in twin.axis(plan.axis).travel)
    travel = {"X": (lo, hi), "Y": (0.0, 10.0), "Z": (0.0, 10.0)}
    params = linuxcnc_thermcomp(comp, clock="pin", interval=plan.interval)
    readings, applied = {}, 0.0
    with LinuxCNCThermal(travel=travel, thermcomp=params, velocity=VELOCITY,
                         acceleration=ACCELERATION, av_ratio=AV_RATIO) as cnc:
        start = time.monotonic()             # once LinuxCNC runs (not the wait for its lock)
        for active in (True, False):         # the compensated run first: from a fresh start
            cnc.set_active(active)
            e = np.empty((measured.size, 2))
            for k in range(t.size):
                (cnc.start if k == 0 else cnc.feed)(float(t[k]), temps[k])
                if progress is not None:
                    progress(k + 1 + (0 if active else t.size), 2 * t.size)
                if k % every:
                    continue
                m = k // every
                for j, p in enumerate(targets_mm):
                    motor = float(cnc.move_to((p, 0.0, 0.0))[0])
                    true = twin.positioning_error(history, plan.axis, motor * 1e-3)[k]
                    e[m, j] = (motor - p) * 1e-3 + true + noise[m, j]
                    if active:
                        asked = comp.error(p * 1e-3, lag[k])
                        applied = max(applied, abs((motor - p) * 1e-3 + asked))
            readings[active] = e
        wall = time.monotonic() - start
    tm = t[measured]
    run_end = None if log.run_end is None else float(tm[tm <= log.run_end + 1e-9][-1])

    def as_log(e, what):
        return ThermalLog("linear", tm, {s: v[measured] for s, v in log.temperatures.items()},
                          {"P1": e[:, 0], "P2": e[:, 1]}, run_end=run_end,
                          targets=plan.targets, axis=plan.axis,
                          source=f"LinuxCNC, {what}")

    before = evaluate_linear(as_log(readings[False], "without compensation"))
    after = evaluate_linear(as_log(readings[True], "with axiscal-thermcomp"))
    b = {k: before[f"delta_{k}_max_run"].value for k in ("P1", "P2")}
    a = {k: after[f"delta_{k}_max_run"].value for k in ("P1", "P2")}
    check = CompensationCheck(b, a, {k: 1 - abs(a[k]) / abs(b[k]) if b[k] else 0.0 for k in b})
    settings = {"controller": "LinuxCNC (linuxcnc-uspace), headless simulation",
                "component": "axiscal_thermcomp.py (external offsets of X)",
                "sensors_clock": "pin (time-compressed)", "feed_interval_s": plan.interval,
                "measure_interval_s": plan.interval * every, "seed": int(seed),
                "eoffset_scale_mm": 1e-6, "offset_av_ratio": AV_RATIO,
                "velocity_mm_per_s": VELOCITY, "acceleration_mm_per_s2": ACCELERATION}
    return ThermalOnController(check, int(measured.size * 2), applied,
                               2 * plan.duration / wall, settings)
