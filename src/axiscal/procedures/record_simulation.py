"""A simulated machine running an exported plan, recorded continuously by a simulated laser.

The truth that :mod:`axiscal.procedures.capture` is checked against: each move follows a
trapezoidal speed profile (speed and acceleration limits), the machine arrives with a damped
ringing (a decaying cosine, its amplitude proportional to the approach speed), a steady
vibration runs all the time, and the laser adds white noise at its sample rate. At rest the axis
sits at its actual position (``axis.move``: systematic error, reversal, repeatability), which is
what a triggered reading at the end of the dwell would see.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from axiscal import units
from axiscal.datasets import PositioningDataset
from axiscal.errors import InputError

__all__ = ["RecordSettings", "simulate_record"]


@dataclass(frozen=True)
class RecordSettings:
    """How the simulated machine moves and how the laser records (SI units).

    speed : m/s (or rad/s); acceleration : m/s²; ringing_hz, ringing_decay_s: the settling
    oscillation and its time constant; ringing_per_speed : ringing amplitude per unit approach
    speed (s); vibration_hz, vibration_amplitude (m); noise (m); sample_rate (Hz).
    """

    sample_rate: float = 1000.0
    speed: float = 0.05
    acceleration: float = 0.5
    ringing_hz: float = 25.0
    ringing_decay_s: float = 0.08
    ringing_per_speed: float = 2e-4
    vibration_hz: float = 120.0
    vibration_amplitude: float = 0.05e-6
    noise: float = 0.05e-6

    def __post_init__(self) -> None:
        if not 1 <= self.sample_rate <= 1e6:
            raise InputError(f"sample rate {self.sample_rate!r} Hz: between 1 Hz and 1 MHz")
        for k in ("speed", "acceleration"):
            if not getattr(self, k) > 0:
                raise InputError(f"{k} must be positive")


def simulate_record(plan, axis, rng: np.random.Generator, settings: RecordSettings = RecordSettings(),
                    datum: float | None = None, max_samples: int = 50_000_000):
    """Run ``plan`` (rows as exported: ``kind``, ``position``, ``direction``, ``run``,
    ``target_index``, ``dwell``, ``target_unit``, ``targets``) on ``axis``.

    Returns
    -------
    times : numpy.ndarray, s
    readings : numpy.ndarray, m
        From the laser's datum (``datum``, default the first target).
    truth : PositioningDataset
        The settled deviations at each measurement (µm).
    """
    f = units.factor(plan.target_unit, "length")
    s = settings
    pos = np.asarray(plan.position, dtype=float) * f
    zero = (float(plan.targets[0]) if datum is None else datum) * f
    segments_t, segments_x = [], []
    t_now, here = 0.0, pos[0]
    dev_here = 0.0
    up = np.full((plan.targets.size, int(plan.run.max())), np.nan)
    down = np.full_like(up, np.nan)
    ring_amp, ring_t0 = 0.0, 0.0
    total = 0.0
    for j in range(pos.size):
        dur = _move_time(abs(pos[j] - here), s.speed, s.acceleration)
        total += dur + float(plan.dwell[j])
    if total * s.sample_rate > max_samples:
        raise InputError(f"the record would hold {total * s.sample_rate:.3g} samples "
                         f"({total:.0f} s at {s.sample_rate:g} Hz); at most {max_samples:g}")
    for j in range(pos.size):
        d = 1 if plan.direction[j] == "+" else -1
        actual = float(axis.move(pos[j], d, rng, time=t_now))
        dev_next = actual - pos[j]
        dist = pos[j] - here
        dur = _move_time(abs(dist), s.speed, s.acceleration)
        tm = _grid(t_now, dur, s.sample_rate)
        frac = _trapezoid(tm - t_now, abs(dist), s.speed, s.acceleration) / max(abs(dist), 1e-30)
        x = here + dist * frac + dev_here + (dev_next - dev_here) * frac
        x = x + _ring(tm, ring_amp, ring_t0, s)
        segments_t.append(tm)
        segments_x.append(x)
        t_now += dur
        peak = min(s.speed, np.sqrt(abs(dist) * s.acceleration))
        ring_amp, ring_t0 = -np.sign(dist) * peak * s.ringing_per_speed, t_now
        dwell = float(plan.dwell[j])
        td = _grid(t_now, dwell, s.sample_rate)
        segments_t.append(td)
        segments_x.append(pos[j] + dev_next + _ring(td, ring_amp, ring_t0, s))
        t_now += dwell
        here, dev_here = pos[j], dev_next
        if plan.kind[j] == "measure":
            arr = up if d > 0 else down
            arr[plan.target_index[j], plan.run[j] - 1] = dev_next / units.UM
    t = np.concatenate(segments_t)
    x = np.concatenate(segments_x)
    x = x + s.vibration_amplitude * np.sin(2 * np.pi * s.vibration_hz * t)
    x = x + rng.normal(0.0, s.noise, t.size) - zero
    has_down = np.any((np.asarray(plan.direction) == "-") & (np.asarray(plan.kind) == "measure"))
    truth = PositioningDataset("linear", plan.targets, up,
                               down if has_down else np.zeros((plan.targets.size, 0)),
                               plan.target_unit, "um")
    return t, x, truth


def _move_time(dist: float, v: float, a: float) -> float:
    if dist <= v * v / a:
        return 2 * np.sqrt(dist / a)
    return dist / v + v / a


def _trapezoid(tau, dist: float, v: float, a: float):
    """Distance travelled at times ``tau`` of a trapezoidal (or triangular) move."""
    if dist == 0:
        return np.zeros_like(tau)
    total = _move_time(dist, v, a)
    vp = min(v, np.sqrt(dist * a))
    ta = vp / a
    out = np.where(tau < ta, 0.5 * a * tau ** 2,
                   np.where(tau < total - ta, 0.5 * a * ta ** 2 + vp * (tau - ta),
                            dist - 0.5 * a * np.clip(total - tau, 0, None) ** 2))
    return np.clip(out, 0, dist)


def _grid(t0: float, dur: float, fs: float) -> np.ndarray:
    k0 = int(np.ceil(t0 * fs - 1e-9))
    k1 = int(np.ceil((t0 + dur) * fs - 1e-9))
    return np.arange(k0, k1) / fs


def _ring(t, amp: float, t0: float, s: RecordSettings):
    if amp == 0:
        return np.zeros_like(t)
    dt = np.clip(t - t0, 0, None)
    return amp * np.exp(-dt / s.ringing_decay_s) * np.cos(2 * np.pi * s.ringing_hz * dt)
