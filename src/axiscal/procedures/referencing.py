"""Referencing (homing) of an axis fed by a compensated laser scale (Renishaw, Laser scale axis referencing, Figure 4).

:func:`simulate_referencing` runs the whole chain on one axis, sample by sample and vectorised:

    true motion x(t) and air n(t)
      -> laser head: uncompensated quadrature count c (0.633 µm)
      -> compensator: factor P from its sensors (sample and hold), output count o = ⌊cP/2^B⌋,
         rephasing at the switch, synthesised sine/cosine and reference mark (count m)
      -> controller: arctangent decoding, frequency monitor, home latch at Z

and reports the events A (switch), B (reference pulse starts), Z (home) and C (pulse ends): where
each happened, measured from the simulated motion (the true position of the part referred to
20 °C, in output counts beyond the switch, to within one laser count: the compensator's count
changes only when the laser's does), beside the design value. After the homing move the axis can
make further moves (``moves``) under changing air, for the truth tests of the compensation.

The axis moves at constant real speed while homing (the servo is not modelled; the controller
sees (N + v)/N times that speed during stage 2). Positions are sampled uniformly in distance, at
most ``max_step_counts`` output counts apart, so the decoding condition (less than half a period
between samples) holds; times follow from a trapezoidal speed profile.

Twin axes (gantry) are in :mod:`axiscal.procedures.twin_axis`.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

import numpy as np

from axiscal.errors import InputError
from axiscal.instruments.compensator import (Compensator, SineOutput, multiply, rephase,
                                             synthesise)
from axiscal.instruments.controller import Controller, ControllerAlarm
from axiscal.instruments.laser_scale import LaserHead, ReferenceSwitch
from axiscal.physics.air import refractive_index
from axiscal.physics.thermal import REFERENCE_TEMPERATURE

__all__ = [
    "AirHistory",
    "ScaleAxis",
    "Move",
    "HomingEvent",
    "ReferencingRun",
    "simulate_referencing",
]


@dataclass(frozen=True)
class AirHistory:
    """True air and work-piece conditions, each linear in time from t = 0.

    Attributes
    ----------
    temperature : float, °C
    pressure : float, Pa
    humidity : float, %RH
    material_temperature : float, °C
    temperature_rate : float, K/s
    pressure_rate : float, Pa/s
    humidity_rate : float, %RH/s
    material_rate : float, K/s
    """

    temperature: float = 20.0
    pressure: float = 101325.0
    humidity: float = 50.0
    material_temperature: float = REFERENCE_TEMPERATURE
    temperature_rate: float = 0.0
    pressure_rate: float = 0.0
    humidity_rate: float = 0.0
    material_rate: float = 0.0

    def at(self, t):
        """(temperature, pressure, humidity, material temperature) at times t (arrays)."""
        t = np.asarray(t, dtype=float)
        return (self.temperature + self.temperature_rate * t,
                self.pressure + self.pressure_rate * t,
                np.clip(self.humidity + self.humidity_rate * t, 0.0, 100.0),
                self.material_temperature + self.material_rate * t)


@dataclass(frozen=True)
class ScaleAxis:
    """One axis fed by a compensated laser scale: the whole configuration of a referencing run.

    Attributes
    ----------
    laser : LaserHead
    compensator : Compensator
    switch : ReferenceSwitch
    controller : Controller
    air : AirHistory
        The true conditions.
    sensor_error : tuple of 4 floats
        Errors of the compensator's sensors (air temperature K, pressure Pa, humidity %RH,
        material temperature K); zero for ideal sensors.
    """

    laser: LaserHead = field(default_factory=LaserHead)
    compensator: Compensator = field(default_factory=Compensator)
    switch: ReferenceSwitch = field(default_factory=lambda: ReferenceSwitch(position=0.1))
    controller: Controller = field(default_factory=Controller)
    air: AirHistory = field(default_factory=AirHistory)
    sensor_error: tuple[float, float, float, float] = (0.0, 0.0, 0.0, 0.0)

    def __post_init__(self) -> None:
        out = self.compensator.output
        if self.controller.counts_per_period != out.counts_per_period:
            raise InputError(f"the controller counts {self.controller.counts_per_period} per "
                             f"period but the compensator synthesises {out.counts_per_period}")
        if abs(self.controller.count_size - out.count_size) > 1e-15:
            raise InputError("the controller's count size differs from the compensator's output "
                             f"count ({self.controller.count_size * 1e9:g} vs "
                             f"{out.count_size * 1e9:g} nm)")
        if self.compensator.laser != self.laser:
            raise InputError("the compensator is set up for another laser head than the axis has")

    @property
    def direction(self) -> int:
        """+1 if homing runs in the positive direction (switch active above its trip point)."""
        return 1 if self.switch.active_above else -1

    @property
    def output(self) -> SineOutput:
        """The compensator's sine/cosine output format."""
        return self.compensator.output


@dataclass(frozen=True)
class Move:
    """A move after homing: to ``target`` (metres) at ``speed`` (m/s) with ``acceleration``."""

    target: float
    speed: float = 0.1
    acceleration: float = 1.0


@dataclass(frozen=True)
class HomingEvent:
    """One event of the referencing sequence.

    Attributes
    ----------
    name : str
        ``"A"`` switch hit, ``"B"`` reference pulse starts, ``"Z"`` home, ``"C"`` pulse ends.
    index : int
        First sample at or after the event.
    counts_beyond_switch : float
        Measured: the true motion of the part (referred to 20 °C) from the switch trip point to
        the event's sample, in output counts. Uncertain by one laser count
        (``uncertainty_counts``) plus the sample spacing.
    nominal_counts : int
        The design value: 0, kN, kN + N/4, kN + N/2 (0, 256, 320, 384 for N = 256, k = 1).
    uncertainty_counts : float
        One laser count in output counts (8.1 for 0.633 µm and 78.125 nm).
    controller_count : int
        The controller-side count m at the event (includes the virtual movement).
    position : float, metres
        True axis position at the sample.
    time : float, seconds
    """

    name: str
    index: int
    counts_beyond_switch: float
    nominal_counts: int
    uncertainty_counts: float
    controller_count: int
    position: float
    time: float


@dataclass(frozen=True, eq=False)
class ReferencingRun:
    """Everything a referencing simulation produced.

    Attributes
    ----------
    axis : ScaleAxis
    events : tuple of HomingEvent
        A, B, Z, C in that order (those reached).
    virtual : int
        Virtual movement v added during stage 2, counts (0 to N-1).
    switch_trip : float, metres
        Where the switch tripped this time.
    home_count : int or None
        Controller count latched as home (position 0).
    alarms : tuple of ControllerAlarm
    time, position, n, laser_counts, factor, output_counts, controller_side, reference, switch,
    sine, cosine, decoded : ndarray
        The trace, one value per sample (seconds, metres, refractive index, laser counts, factor
        P, output counts o, compensator count m, reference mark, switch, outputs, controller
        counts).
    power_up_phase : int
        Phase of the synthesised outputs at power-up, counts.
    """

    axis: ScaleAxis
    events: tuple[HomingEvent, ...]
    virtual: int
    switch_trip: float
    home_count: int | None
    alarms: tuple[ControllerAlarm, ...]
    time: np.ndarray
    position: np.ndarray
    n: np.ndarray
    laser_counts: np.ndarray
    factor: np.ndarray
    output_counts: np.ndarray
    controller_side: np.ndarray
    reference: np.ndarray
    switch: np.ndarray
    sine: np.ndarray
    cosine: np.ndarray
    decoded: np.ndarray
    power_up_phase: int

    @property
    def homed(self) -> bool:
        """True if the controller found the home position."""
        return self.home_count is not None

    def event(self, name: str) -> HomingEvent:
        """The event called ``name`` (A, B, Z or C); InputError if it was not reached."""
        for e in self.events:
            if e.name == name:
                return e
        raise InputError(f"event {name} was not reached in this run")

    @property
    def home_position(self) -> float:
        """True position where the controller zeroed the axis, metres."""
        return self.event("Z").position

    def controller_position(self) -> np.ndarray:
        """The controller's position per sample in counts from home (NaN-free; before homing it
        is relative to the home found later)."""
        if self.home_count is None:
            raise InputError("the axis was not homed")
        return self.decoded - self.home_count

    @property
    def home_output_count(self) -> int:
        """Real output count o at which the controller zeroed (o_A ± 5N/4)."""
        k = self.event("Z").index
        return int(self.home_count - (int(self.decoded[k]) - int(self.output_counts[k])))

    def exact_compensated_counts(self, index=slice(None)) -> list:
        """The compensated position as exact rationals, output counts from home:
        ``c P / 2**B - o_Z`` per sample (:class:`fractions.Fraction`), the real number the pulse
        multiplication rounds down."""
        from fractions import Fraction

        o_z = self.home_output_count
        den = 1 << self.axis.compensator.bits
        return [Fraction(int(c) * int(p), den) - o_z
                for c, p in zip(self.laser_counts[index].tolist(), self.factor[index].tolist())]

    @property
    def peak_input_frequency(self) -> float | None:
        """Highest signal frequency over one signal period, from the output edges, Hz (None if
        the record holds less than a period of motion): the true peak, not a gated average."""
        f = self.axis.controller.edge_frequency(self.controller_side, self.time)
        return float(np.nanmax(f)) if np.isfinite(f).any() else None

    @property
    def stage2_counts(self) -> int:
        """Real output counts over which the virtual movement is spread: k·N."""
        return self.axis.compensator.rephase_periods * self.axis.output.counts_per_period

    @property
    def laser_count_in_output_counts(self) -> float:
        """One laser count (λ_vac/k of optical path in air) in output counts, at the start."""
        return float(self.axis.laser.uncompensated_position(1) / self.n[0]
                     / self.axis.output.count_size)

    def tracking(self) -> dict[str, float]:
        """After homing, the controller's position against the truth of the simulation.

        ``max_count_error`` (counts) and ``max_part_error_um``: the controller's position from
        home against the true position of the part referred to 20 °C, from the home sample (its
        true position) on. They hold the quantisation of one laser count
        (``count_uncertainty``, output counts), the dead-path error and the sensors' lag.
        ``max_pulse_error`` (counts): the controller against the compensator's own exact product
        ``c P / 2^B`` (the exactness of the pulse multiplication, not an accuracy).
        """
        kz = self.event("Z").index
        k = slice(kz, None)
        q = self.axis.output.count_size
        p = self.controller_position()[k].astype(float)
        exact = (self.laser_counts[k].astype(float) * self.factor[k].astype(float)
                 / float(1 << self.axis.compensator.bits) - self.home_output_count)
        _, _, _, tmat = self.axis.air.at(self.time[k])
        growth = 1.0 + self.axis.compensator.expansion_coefficient * (
            np.asarray(tmat) - REFERENCE_TEMPERATURE)
        part = (self.position[k] - self.position[kz]) / growth
        raw = self.axis.laser.uncompensated_position(self.laser_counts[k] - self.laser_counts[kz])
        err = (p - p[0]) - part / q
        return {
            "max_count_error": float(np.max(np.abs(err))),
            "max_part_error_um": float(np.max(np.abs(err)) * q * 1e6),
            "max_pulse_error": float(np.max(np.abs(p - exact))),
            "count_uncertainty": self.laser_count_in_output_counts,
            "end_controller_mm": float(p[-1] * q * 1e3),
            "end_true_mm": float((self.position[-1] - self.position[kz]) * 1e3),
            "end_part_mm": float(part[-1] * 1e3),
            "end_uncompensated_mm": float(raw[-1] * 1e3),
        }

    def to_dict(self) -> dict[str, Any]:
        """Plain-data summary (the ``axiscal scale home --json`` object)."""
        out = self.axis.output
        return {
            "homed": self.homed,
            "counts_per_period": out.counts_per_period,
            "count_size_nm": out.count_size * 1e9,
            "period_um": out.period * 1e6,
            "direction": self.axis.direction,
            "virtual_counts": self.virtual,
            "power_up_phase": self.power_up_phase,
            "switch_trip_mm": self.switch_trip * 1e3,
            "home_position_mm": self.home_position * 1e3 if self.homed else None,
            "rephase_periods": self.axis.compensator.rephase_periods,
            "events": [
                {"name": e.name, "counts_beyond_switch": round(e.counts_beyond_switch, 3),
                 "nominal_counts": e.nominal_counts,
                 "uncertainty_counts": round(e.uncertainty_counts, 3),
                 "controller_count": e.controller_count, "position_mm": e.position * 1e3,
                 "time_s": e.time}
                for e in self.events
            ],
            "alarms": [str(a) for a in self.alarms],
            "peak_input_frequency_khz": None if (f := self.peak_input_frequency) is None
            else f / 1e3,
        }

    def __str__(self) -> str:
        out = self.axis.output
        lines = [
            f"Referencing with a compensated laser scale: {out.counts_per_period} counts of "
            f"{out.count_size * 1e9:.3f} nm per {out.period * 1e6:g} µm period, homing "
            f"{'+' if self.axis.direction > 0 else '-'}",
            f"  switch tripped at {self.switch_trip * 1e3:.6f} mm; virtual movement "
            f"{self.virtual} counts in stage 2",
            "  event  counts beyond switch (measured ± 1 laser count, design)  controller count"
            "   position [mm]   time [s]",
        ]
        for e in self.events:
            meas = (f"{e.counts_beyond_switch:8.1f} ± {e.uncertainty_counts:.1f}  "
                    f"({e.nominal_counts})")
            lines.append(f"  {e.name:<5}  {meas:>52}  {e.controller_count:>16d}"
                         f"  {e.position * 1e3:>14.6f}  {e.time:>9.7f}")
        if self.homed:
            lines.append(f"  home (Z) at {self.home_position * 1e3:.6f} mm")
        else:
            lines.append("  NOT HOMED")
        f = self.peak_input_frequency
        if f is not None:
            lines.append(f"  peak input frequency {f / 1e3:.2f} kHz over one signal period "
                         f"(controller limit {self.axis.controller.max_input_frequency / 1e3:g} "
                         f"kHz; stage 2 spread over {self.stage2_counts} counts)")
        lines += [f"  {a}" for a in self.alarms]
        return "\n".join(lines)


def simulate_referencing(
    axis: ScaleAxis,
    start: float,
    homing_speed: float = 0.005,
    *,
    moves: tuple[Move, ...] = (),
    rng: np.random.Generator | None = None,
    power_up_phase: int | None = None,
    fringe_phase: float | None = None,
    power_up_position: float | None = None,
    overtravel_counts: int | None = None,
    max_step_counts: float = 0.5,
    move_step_counts: float | None = None,
) -> ReferencingRun:
    """Simulate the referencing of one axis, then optional moves.

    Parameters
    ----------
    axis : ScaleAxis
    start : float, metres
        Where the homing move starts; before the switch in the homing direction.
    homing_speed : float, m/s
        Constant real speed of the homing move.
    moves : tuple of Move
        Moves after the homing move (they start where it stops).
    rng : numpy.random.Generator, optional
        Source of the switch's repeatability error and, where not given, of the power-up phase
        (uniform 0..N-1) and the fringe phase (uniform 0..1). Without it: no switch error, phases 0.
    power_up_phase : int, optional
        Phase of the synthesised outputs at power-up, counts.
    fringe_phase : float, optional
        Fringe phase at power-up, in laser counts (0..1).
    power_up_position : float, metres, optional
        Where the laser was powered up (default: ``start``).
    overtravel_counts : int, optional
        How far the homing move runs beyond the switch, output counts (default (k + 1)·N, past
        C; k = the compensator's ``rephase_periods``).
    max_step_counts : float
        Sample spacing of the homing move in output counts.
    move_step_counts : float, optional
        Sample spacing of the moves (default N/8 counts).

    Returns
    -------
    ReferencingRun
    """
    out = axis.output
    n_per = out.counts_per_period
    q = out.count_size
    d = axis.direction
    trip = axis.switch.trip_point(rng)
    if d * (trip - start) <= 0:
        raise InputError(f"the homing move starts at {start * 1e3:g} mm, which is not before the "
                         f"switch at {trip * 1e3:g} mm in the homing direction")
    if not homing_speed > 0:
        raise InputError(f"homing speed {homing_speed!r} m/s must be positive")
    x, t = _motion(axis, start, trip, homing_speed, moves, overtravel_counts, max_step_counts,
                   move_step_counts)
    if rng is not None:
        phi = int(rng.integers(n_per)) if power_up_phase is None else int(power_up_phase)
        fphase = float(rng.random()) if fringe_phase is None else float(fringe_phase)
    else:
        phi = int(power_up_phase or 0)
        fphase = float(fringe_phase or 0.0)

    temp, pres, hum, tmat = axis.air.at(t)
    n_true = np.asarray(refractive_index(temp, pres, hum, co2=axis.compensator.co2,
                                         vacuum_wavelength=axis.laser.vacuum_wavelength,
                                         equation="ciddor"))
    x0 = start if power_up_position is None else float(power_up_position)
    counts = axis.laser.counts(x, n_true, x0, float(n_true[0]), fphase)
    e = axis.sensor_error
    factor = axis.compensator.factor_schedule(t, temp + e[0], pres + e[1],
                                              np.clip(hum + e[2], 0, 100), tmat + e[3])
    o = multiply(counts, factor, axis.compensator.bits)
    sw = axis.switch.state(x, trip)
    rep = rephase(o, sw, n_per, d, phi, axis.compensator.rephase_periods)
    sine, cosine = synthesise(rep.m, n_per)
    decoded = axis.controller.decode(sine, cosine)
    # the frequency monitor measures the signal itself (the compensator-side count)
    alarms = axis.controller.frequency_alarms(rep.m, t) + _step_alarms(rep.m, n_per)
    latch = axis.controller.find_home(decoded, rep.reference, d)
    part = _part_counts(axis, x, t, trip)
    events = _events(rep, latch, decoded, part, x, t, out, axis.compensator.rephase_periods,
                     axis.laser.uncompensated_position(1) / float(n_true[0]) / q)
    return ReferencingRun(
        axis=axis, events=tuple(events), virtual=rep.virtual, switch_trip=trip,
        home_count=None if latch is None else latch.count, alarms=tuple(alarms), time=t,
        position=x, n=n_true, laser_counts=counts, factor=factor, output_counts=o,
        controller_side=rep.m, reference=rep.reference, switch=sw, sine=sine, cosine=cosine,
        decoded=decoded, power_up_phase=phi)


# -- helpers ------------------------------------------------------------------------------
def _motion(axis, start, trip, homing_speed, moves, overtravel_counts, max_step_counts,
            move_step_counts):
    """Positions (m) and times (s) of the homing move (``overtravel_counts`` output counts past
    the switch at ``trip``, default (k + 1)·N) and of the ``moves`` after it (trapezoids)."""
    n_per = axis.output.counts_per_period
    q = axis.output.count_size
    k2 = axis.compensator.rephase_periods
    over = (k2 + 1) * n_per if overtravel_counts is None else int(overtravel_counts)
    # enough real motion for `over` output counts, whatever the air and the work-piece
    end = trip + axis.direction * over * q * 1.001 * _max_growth(axis)
    x, t = _homing_path(start, end, homing_speed, max_step_counts * q)
    step_moves = (n_per / 8 if move_step_counts is None else move_step_counts) * q
    for mv in moves:
        xm, tm = _trapezoid(float(x[-1]), mv.target, mv.speed, mv.acceleration, step_moves)
        x = np.concatenate((x, xm[1:]))
        t = np.concatenate((t, t[-1] + tm[1:]))
    return x, t


def _max_growth(axis: ScaleAxis) -> float:
    """Upper bound of true length per compensated length (air and work-piece), >= 1."""
    alpha = abs(axis.compensator.expansion_coefficient)
    return (1.0 + 1e-3) * (1.0 + alpha * 200.0)


def _part_counts(axis: ScaleAxis, x, t, trip: float) -> np.ndarray:
    """True motion of the part from the switch trip point, referred to 20 °C, output counts."""
    _, _, _, tmat = axis.air.at(t)
    growth = 1.0 + axis.compensator.expansion_coefficient * (
        np.asarray(tmat) - REFERENCE_TEMPERATURE)
    return axis.direction * (x - trip) / growth / axis.output.count_size


def _events(rep, latch, decoded, part, x, t, out: SineOutput, periods: int,
            laser_count: float) -> list[HomingEvent]:
    """A, B, Z, C: where each happened (``part`` at its first sample), beside the design value.

    ``part`` is the true motion of the part beyond the switch in output counts; ``laser_count``
    one laser count in output counts, the uncertainty of every event's position.
    """
    if rep.index_a is None:
        return []
    ka = rep.index_a
    n2 = periods * out.counts_per_period

    def ev(name, k, nominal, m_exact):
        return HomingEvent(name, int(k), float(part[k]), int(nominal), float(laser_count),
                           int(m_exact), float(x[k]), float(t[k]))

    events = [ev("A", ka, 0, rep.m[ka])]
    if rep.reference.any():
        events.append(ev("B", int(np.argmax(rep.reference)), n2, rep.m_b))
    if latch is not None:
        # the compensator-side count at Z: the latched controller count less the decoder's
        # offset, a multiple of N
        k = latch.index
        m_z = latch.count - (int(decoded[k]) - int(rep.m[k]))
        events.append(ev("Z", k, n2 + out.counts_per_period // 4, m_z))
    if rep.reference.any():
        m = rep.m[ka:]
        past_c = np.flatnonzero(rep.direction * m >= rep.direction * rep.m_c)
        if past_c.size:
            events.append(ev("C", ka + int(past_c[0]), n2 + out.pulse_counts, rep.m_c))
    return events


def _step_alarms(m: np.ndarray, n_per: int) -> list[ControllerAlarm]:
    """A jump of half a period or more between two samples cannot be decoded: say so."""
    steps = np.abs(np.diff(m))
    if steps.size == 0 or steps.max() < n_per // 2:
        return []
    k = int(np.argmax(steps >= n_per // 2)) + 1
    return [ControllerAlarm(
        "signal step", f"the outputs jumped {int(steps.max())} counts between two samples (half "
        f"a period is {n_per // 2}); the controller cannot follow such a jump and may miscount",
        k, float(steps.max()), float(n_per // 2))]


def _homing_path(start: float, end: float, speed: float, step: float):
    n = max(2, int(np.ceil(abs(end - start) / step)) + 1)
    x = np.linspace(start, end, n)
    return x, np.abs(x - start) / speed


def _trapezoid(x0: float, x1: float, vmax: float, acc: float, step: float):
    """Positions sampled uniformly in distance and their times for a trapezoidal move."""
    if not vmax > 0 or not acc > 0:
        raise InputError(f"move speed {vmax!r} m/s and acceleration {acc!r} m/s² must be positive")
    dist = abs(x1 - x0)
    n = max(2, int(np.ceil(dist / step)) + 1)
    s = np.linspace(0.0, dist, n)
    s_acc = min(vmax * vmax / (2 * acc), dist / 2)
    v_peak = np.sqrt(2 * acc * s_acc)
    t_acc = v_peak / acc
    t_cruise = (dist - 2 * s_acc) / v_peak if v_peak > 0 else 0.0
    t = np.where(
        s < s_acc, np.sqrt(2 * np.maximum(s, 0) / acc),
        np.where(s <= dist - s_acc, t_acc + (s - s_acc) / max(v_peak, 1e-300),
                 t_acc + t_cruise + t_acc - np.sqrt(2 * np.maximum(dist - s, 0) / acc)))
    return x0 + np.sign(x1 - x0) * s, t
