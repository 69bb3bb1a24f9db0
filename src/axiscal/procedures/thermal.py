"""The ISO 230-3:2020 thermal tests and the ISO 230-2 drift check, planned and simulated.

A :class:`ThermalPlan` says what is done and for how long; :func:`simulate_thermal` runs it on a
:class:`~axiscal.machines.thermal.ThermalTwin` with its simulated instruments and returns the
logged :class:`~axiscal.standards.iso230_3_data.ThermalLog` beside the twin's truth (the figures
the evaluation should find, kept apart from the log: truth appears in simulation reports only).
A procedure measures; it never evaluates.

Defaults (axiscal's where the standard leaves a choice or its text was not available; see
:mod:`axiscal.standards.iso230_3_data` for the minimum durations):

=================  =====================================================================
etve               24 h at rest (one daily cycle), a sample a minute
spindle            4 h at 50 % of the maximum speed, then 1 h stopped; a sample a minute.
                   The speed is the user's choice; 50 % is axiscal's default. A speed
                   programme (steps of a fraction for some minutes, repeated through the
                   run) replaces the constant speed when given
rotary             as the spindle test, the rotary table turning (ISO 230-3:2020 Clause 8);
                   the twin needs a node heated by ``rotary``
linear             4 h cycling between P1 and P2, then 1 h at rest; the axis in motion 80 %
                   of the time (the rest is the measurement dwell at each target); P1 and P2
                   5 % of the travel in from each end; an axis longer than 2 000 mm is tested
                   over a representative 2 000 mm from P1 (ISO 230-3:2020 Scope / Clause 7)
drift-check        the positioning test's duration (default 1 h) at rest at mid-travel; a
                   reading a minute (ISO 230-2:2014 Annex A.5: at least the test's duration)
=================  =====================================================================

Every simulated test starts after a day of the twin at rest in its room, so the slow structure
is in its daily rhythm, not at an artificial equilibrium. Spindle test sensors: X1/Y1 at the
mandrel's reference point near the spindle nose, X2/Y2 a spacing l further (at −l along Z), Z
on the mandrel's end: ``X2 = δX − l·B``, ``Y2 = δY + l·A`` (see :mod:`axiscal.standards.iso230_3`).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from axiscal.errors import InputError, one_line
from axiscal.machines.thermal import ThermalHistory, ThermalTwin
from axiscal.standards.iso230_3 import signed_extreme
from axiscal.standards.iso230_3_data import MAX_INTERVAL, ThermalLog

__all__ = ["ThermalPlan", "ThermalSimulation", "DriftCheck", "plan_thermal", "simulate_thermal",
           "simulate_drift_check", "PLAN_TESTS", "MAX_SAMPLES"]

PLAN_TESTS = ("etve", "spindle", "linear", "rotary", "drift-check")
#: Most samples one simulated test may hold (a week at one a second).
MAX_SAMPLES = 700_000
_SETTLE = 86_400.0
#: Bounds of a plan's start in the room's cycle, s, and of an instrument's drift, m/s.
MAX_START = 1e4 * 3600.0
MAX_INSTRUMENT_DRIFT = 1000e-6 / 3600.0
#: Representative length of a long axis, m (ISO 230-3:2020 Scope / Clause 7).
REPRESENTATIVE_LENGTH = 2.0


@dataclass(frozen=True)
class ThermalPlan:
    """What one thermal test does (SI).

    Attributes
    ----------
    test : {"etve", "spindle", "linear", "rotary", "drift-check"}
    duration : float, s
        Whole test, running and stopped.
    interval : float, s
        Between samples.
    run : float or None, s
        Spindle or linear test: how long the spindle runs or the axis cycles.
    speed : float
        Spindle test: speed as a fraction of the maximum.
    programme : tuple of (float, float)
        Spindle test: steps of (fraction of the maximum speed, seconds), repeated through the
        run; empty for the constant ``speed``.
    axis : str
    targets : tuple of float or None, m
        Linear test: P1 and P2.
    duty : float
        Linear test: the axis's share of time in motion.
    position : float or None, m
        Drift check: where the set-up stands.
    instrument_drift : float, m/s
        Drift check: the instrument's own drift (laser, air compensation) added to the machine's.
    start : float, s
        When the test starts in the twin's room cycle (time after the room's t = 0).
    """

    test: str
    duration: float
    interval: float = 60.0
    run: float | None = None
    speed: float = 0.5
    axis: str = "X"
    targets: tuple[float, float] | None = None
    duty: float = 0.8
    position: float | None = None
    instrument_drift: float = 0.0
    start: float = 8 * 3600.0
    programme: tuple[tuple[float, float], ...] = ()

    @property
    def times(self) -> np.ndarray:
        """Sample times from the start, s."""
        n = int(np.floor(self.duration / self.interval + 1e-9))
        return np.arange(n + 1) * self.interval

    def to_dict(self) -> dict:
        """The plan in the units people read (``axiscal thermal plan --json``)."""
        out = {"test": self.test, "duration_h": self.duration / 3600,
               "interval_s": self.interval, "samples": int(self.times.size),
               "start_h": self.start / 3600}
        if self.test in ("spindle", "rotary"):
            out |= {"run_h": self.run / 3600, "stop_h": (self.duration - self.run) / 3600,
                    "speed_fraction": self.speed,
                    "programme": [{"speed_fraction": f, "minutes": d / 60}
                                  for f, d in self.programme]}
        if self.test == "linear":
            out |= {"axis": self.axis, "run_h": self.run / 3600,
                    "stop_h": (self.duration - self.run) / 3600, "duty": self.duty,
                    "P1_mm": self.targets[0] * 1e3, "P2_mm": self.targets[1] * 1e3}
        if self.test == "drift-check":
            out |= {"axis": self.axis, "position_mm": self.position * 1e3,
                    "instrument_drift_um_per_h": self.instrument_drift * 1e6 * 3600}
        return out


@dataclass(frozen=True)
class ThermalSimulation:
    """A simulated test: the log the instruments wrote, and the twin's truth.

    Attributes
    ----------
    plan : ThermalPlan
    log : ThermalLog
    truth : dict of str to float
        The evaluation's figures as the twin knows them (SI), by figure name: every drift,
        range and rise (a temperature's from its sensor's noiseless readings); not the
        duration.
    history : ThermalHistory
    """

    plan: ThermalPlan
    log: ThermalLog
    truth: dict[str, float]
    history: ThermalHistory


@dataclass(frozen=True)
class DriftCheck:
    """A simulated drift check (ISO 230-2:2014 Annex A.5).

    Attributes
    ----------
    plan : ThermalPlan
    time : ndarray, s
    readings : ndarray, m
        The instrument's readings of the still set-up.
    true_e_ve : float, m
        Range of the noiseless readings (machine and instrument drift).
    """

    plan: ThermalPlan
    time: np.ndarray
    readings: np.ndarray
    true_e_ve: float


def plan_thermal(twin: ThermalTwin, test: str, *, duration: float | None = None,
                 interval: float = 60.0, run: float | None = None, speed: float = 0.5,
                 axis: str = "X", targets: tuple[float, float] | None = None, duty: float = 0.8,
                 position: float | None = None, instrument_drift: float = 0.0,
                 start: float = 8 * 3600.0,
                 programme: tuple[tuple[float, float], ...] = ()) -> ThermalPlan:
    """A checked plan with the defaults of the module docstring (all quantities SI).

    Examples
    --------
    >>> from axiscal.machines.thermal import ThermalAxis, ThermalNode
    >>> twin = ThermalTwin(nodes=(ThermalNode("screw", 2700.0, heat="axis:X", rise=8.0),),
    ...                    axes=(ThermalAxis("X", (0.0, 0.8), "screw"),))
    >>> p = plan_thermal(twin, "linear")
    >>> p.run / 3600, p.duration / 3600, [round(x * 1e3, 3) for x in p.targets]
    (4.0, 5.0, [40.0, 760.0])
    """
    test = test.strip().lower()
    if test not in PLAN_TESTS:
        raise InputError(f"thermal test {one_line(repr(test), 60)}: one of "
                         f"{', '.join(PLAN_TESTS)}")
    if not 0 < interval <= MAX_INTERVAL:
        raise InputError(f"interval {interval:g} s must be more than 0 and at most "
                         f"{MAX_INTERVAL:g} s (5 min)")
    if test == "etve":
        duration = 24 * 3600.0 if duration is None else duration
    elif test in ("spindle", "linear", "rotary"):
        run = 4 * 3600.0 if run is None else run
        duration = run + 3600.0 if duration is None else duration
        if not 0 < run <= duration:
            raise InputError(f"run {run / 3600:g} h must be more than 0 and at most the test's "
                             f"duration {duration / 3600:g} h")
    else:
        duration = 3600.0 if duration is None else duration
    if not duration > 0 or duration / interval > MAX_SAMPLES:
        raise InputError(f"duration {duration / 3600:g} h at {interval:g} s: more than 0 and at "
                         f"most {MAX_SAMPLES} samples")
    if not 0 <= speed <= 1:
        raise InputError(f"speed {speed:g} must be a fraction of the maximum, 0 to 1")
    if test == "rotary" and not twin.heats("rotary"):
        raise InputError("the rotary test (ISO 230-3:2020 Clause 8) needs a twin with a rotary "
                         "table: a [[node]] with heat = \"rotary\" (e.g. "
                         "src/axiscal/data/thermal_rotary_table.toml)")
    for f, d in programme:
        if not (0 <= f <= 1 and 0 < d <= 1e6):
            raise InputError(f"speed programme step ({f:g}, {d / 60:g} min): a fraction 0 to 1 "
                             "for more than 0 min")
    if not 0 <= duty <= 1:
        raise InputError(f"duty {duty:g} must be a share of the time, 0 to 1")
    if not abs(start) <= MAX_START:
        raise InputError(f"start {start / 3600:g} h: at most {MAX_START / 3600:g} h from the "
                         "room's cycle's origin")
    if not abs(instrument_drift) <= MAX_INSTRUMENT_DRIFT:
        raise InputError(f"instrument drift {instrument_drift * 1e6 * 3600:g} µm/h: at most "
                         f"{MAX_INSTRUMENT_DRIFT * 1e6 * 3600:g} µm/h (a laser drifts by µm)")
    if test in ("linear", "drift-check"):
        ax = twin.axis(axis)
        lo, hi = ax.travel
        if test == "linear":
            targets = targets or _default_targets(lo, hi)
            for p in targets:
                if not lo <= p <= hi:
                    raise InputError(f"target {p * 1e3:g} mm is outside the travel "
                                     f"{lo * 1e3:g} to {hi * 1e3:g} mm of axis {ax.name}")
            if targets[0] == targets[1]:
                raise InputError("the targets P1 and P2 must differ")
        else:
            position = (lo + hi) / 2 if position is None else position
            if not lo <= position <= hi:
                raise InputError(f"position {position * 1e3:g} mm is outside the travel of "
                                 f"axis {ax.name}")
        axis = ax.name
    return ThermalPlan(test, float(duration), float(interval), run, speed, axis,
                       None if targets is None else (float(targets[0]), float(targets[1])),
                       duty, position, instrument_drift, start,
                       tuple((float(f), float(d)) for f, d in programme))


def simulate_thermal(twin: ThermalTwin, plan: ThermalPlan,
                     rng: np.random.Generator) -> ThermalSimulation:
    """Run an ISO 230-3 test on the twin with its instruments (see the module docstring)."""
    if plan.test not in ("etve", "spindle", "linear", "rotary"):
        raise InputError(f"simulate_thermal runs etve, spindle, linear or rotary; "
                         f"{one_line(repr(plan.test), 60)} is simulate_drift_check's")
    t = plan.times
    end = plan.run if plan.run is not None else np.inf
    running = t <= end + 1e-9             # the reading at the moment it stops is the run's last
    history = _history(twin, plan, t < end - 1e-9)   # the load held from one sample to the next
    temps = twin.read_temperatures(history, rng)
    quiet = twin.read_temperatures(history, None)      # what each sensor sees, without noise
    noise = twin.displacement_noise
    d = history.displacement

    def read(v):
        return v + (rng.normal(0.0, noise, v.shape) if noise > 0 else 0.0)

    run_end = float(t[running][-1]) if plan.run is not None and not running.all() else None
    if plan.test == "etve":
        channels = {k: read(d[:, i]) for i, k in enumerate("XYZ")}
        log = ThermalLog("etve", t, temps, channels, source="simulation")
        truth = {f"ETVE_{k}": float(np.ptp(d[:, i])) for i, k in enumerate("XYZ")}
    elif plan.test in ("spindle", "rotary"):
        l = float(twin.meta.get("mandrel_spacing", 0.1))
        x, y, z, a, b = d.T
        channels = {"X1": read(x), "X2": read(x - l * b), "Y1": read(y), "Y2": read(y + l * a),
                    "Z": read(z)}
        log = ThermalLog(plan.test, t, temps, channels, run_end=run_end, sensor_spacing=l,
                         source="simulation")
        truth = _drift_truth(dict(zip("XYZAB", d.T)), running)
    else:
        e = twin.positioning_error(history, plan.axis, np.asarray(plan.targets))
        channels = {"P1": read(e[:, 0]), "P2": read(e[:, 1])}
        log = ThermalLog("linear", t, temps, channels, run_end=run_end, targets=plan.targets,
                         axis=plan.axis, source="simulation")
        truth = _drift_truth({"P1": e[:, 0], "P2": e[:, 1], "G": e[:, 1] - e[:, 0]}, running)
        truth["growth_per_length_max_run"] = (truth["delta_G_max_run"]
                                              / abs(plan.targets[1] - plan.targets[0]))
    truth |= _temperature_truth(quiet, running, plan.test)
    return ThermalSimulation(plan, log, truth, history)


def simulate_drift_check(twin: ThermalTwin, plan: ThermalPlan,
                         rng: np.random.Generator) -> DriftCheck:
    """The readings of a still set-up over the positioning test's duration (ISO 230-2:2014
    Annex A.5): the axis's thermal positioning error at the set-up's position, the instrument's
    own drift and its reading noise. E_VE is their range
    (:func:`axiscal.standards.iso230_9_inputs.environmental_variation`)."""
    if plan.test != "drift-check":
        raise InputError(f"simulate_drift_check runs a drift-check plan, not {one_line(repr(plan.test), 60)}")
    t = plan.times
    history = _history(twin, plan, np.zeros(t.size, dtype=bool))
    true = twin.positioning_error(history, plan.axis, plan.position) + plan.instrument_drift * t
    true = true - true[0]
    noise = twin.displacement_noise
    readings = true + (rng.normal(0.0, noise, t.shape) if noise > 0 else 0.0)
    return DriftCheck(plan, t, readings, float(np.ptp(true)))


def _history(twin: ThermalTwin, plan: ThermalPlan, running: np.ndarray) -> ThermalHistory:
    """The twin over a day at rest and then the test (``running``: the load on from each sample
    to the next); the test's part returned, time from 0."""
    t = plan.times
    settle = np.arange(0.0, _SETTLE, 600.0)
    grid = np.concatenate((settle, _SETTLE + t)) + plan.start - _SETTLE
    zeros = np.zeros(settle.size)
    spindle = (np.concatenate((zeros, _speeds(plan) * running)) if plan.test == "spindle"
               else None)
    rotary = (np.concatenate((zeros, _speeds(plan) * running)) if plan.test == "rotary"
              else None)
    axes = ({plan.axis: np.concatenate((zeros, plan.duty * running))}
            if plan.test == "linear" else None)
    h = twin.run(grid, spindle=spindle, axes=axes, rotary=rotary)
    cut = slice(settle.size, None)
    return ThermalHistory(t.copy(), h.room[cut], {k: v[cut] for k, v in h.nodes.items()},
                          h.displacement[cut])


def _speeds(plan: ThermalPlan) -> np.ndarray:
    """The spindle's speed fraction from each sample to the next: constant, or the programme's
    steps repeated from the start."""
    t = plan.times
    if not plan.programme:
        return np.full(t.size, plan.speed)
    ends = np.cumsum([d for _, d in plan.programme])
    phase = np.mod(t, ends[-1])
    step = np.searchsorted(ends, phase, side="right")
    return np.array([f for f, _ in plan.programme])[np.minimum(step, len(ends) - 1)]


def _drift_truth(series: dict[str, np.ndarray], running: np.ndarray) -> dict[str, float]:
    """The drift figures of :mod:`axiscal.standards.iso230_3` from noiseless series."""
    out = {}
    end = int(np.flatnonzero(running)[-1])
    for k, v in series.items():
        d = v - v[0]
        out[f"delta_{k}_max_run"] = signed_extreme(d[running])
        out[f"delta_{k}_end_run"] = float(d[end])
        if end < v.size - 1:
            out[f"delta_{k}_end_stop"] = float(d[-1])
            out[f"delta_{k}_recovery"] = float(d[-1] - d[end])
    return out


def _temperature_truth(quiet: dict[str, np.ndarray], running: np.ndarray,
                       test: str) -> dict[str, float]:
    """The temperature figures of :mod:`axiscal.standards.iso230_3` from each sensor's noiseless
    readings (its node seen through its lag: the temperature where the sensor sits): the range
    over an ETVE log, else the rise by the end of the run."""
    if test == "etve":
        return {f"range_{k}": float(np.ptp(v)) for k, v in quiet.items()}
    end = int(np.flatnonzero(running)[-1])
    return {f"rise_{k}": float(v[end] - v[0]) for k, v in quiet.items()}


def _default_targets(lo: float, hi: float) -> tuple[float, float]:
    p1 = lo + 0.05 * (hi - lo)
    p2 = hi - 0.05 * (hi - lo)
    if p2 - p1 > REPRESENTATIVE_LENGTH:
        p2 = p1 + REPRESENTATIVE_LENGTH
    return p1, p2
