"""Measuring the five motion errors of a rotary axis with the system of Optics Express 2018, Five-DOF motion errors of a rotary axis.

Three experiments of Optics Express 2018, Five-DOF motion errors of a rotary axis section 3 on the simulation, and the crosstalk study it leaves open:

* :func:`indexing_test`: the target axis (an indexing table) steps through 0-360° (30° steps),
  the reference rotary axis counter-rotates by the same nominal angle and the five errors are
  read at each stop (section 2.1, 3.3);
* :func:`stability_test`: the system stands still for 60 min, read every 10 s (section 3.2);
* :func:`repeatability_test`: the indexing test three times (section 3.3);
* :func:`crosstalk`: how each of the six true errors leaks into the five measured ones for given
  mounting errors, and the spurious motion the mounting alone shows on a perfect axis.

A procedure measures; evaluation is :mod:`axiscal.standards.iso230_7`'s business.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field, replace

import numpy as np

from axiscal.errors import InputError
from axiscal.instruments.five_dof import FiveDofSystem, FiveErrors, Readings, motion_at_unit, reconstruct
from axiscal.machines.error_functions import ZERO, HarmonicSeries
from axiscal.machines.rotary import Pose, RotaryAxis
from axiscal.standards.iso230_7 import MotionErrorData, fundamental
from axiscal.units import ARCSEC, UM

__all__ = ["ReferenceAxis", "BeamDrift", "MotionRun", "indexing_test", "stability_test",
           "repeatability_test", "to_motion_data", "Crosstalk", "crosstalk", "INPUTS", "SYMBOLS"]

#: The six true errors of the crosstalk study, in the order of its matrix columns.
INPUTS = ("ez", "ey", "ex", "dx", "dy", "dz")
#: How each error is written for people (Optics Express 2018, Five-DOF motion errors of a rotary
#: axis: ε for an angular error, δ for a linear one).
SYMBOLS = {"ez": "εz", "ey": "εy", "ex": "εx", "dx": "δx", "dy": "δy", "dz": "δz"}


@dataclass(frozen=True)
class ReferenceAxis:
    """The counter-rotating reference axis (step table with an angle encoder), radians.

    Attributes
    ----------
    step : float, radians
        Resolution of the step table (BOCI MRS201: 0.33 arcsec): it lands on a whole step.
    encoder_error : HarmonicSeries
        Encoder reading minus actual angle, as a function of angle (RON886: within ±1 arcsec).
    encoder_noise : float, radians
        Standard deviation of one encoder reading.
    """

    step: float = 0.33 * ARCSEC
    encoder_error: HarmonicSeries = ZERO
    encoder_noise: float = 0.05 * ARCSEC

    def turn_back(self, theta, rng: np.random.Generator | None):
        """Actual angle turned back and the encoder reading for nominal ``theta`` (radians)."""
        th = np.asarray(theta, float)
        actual = np.round(th / self.step) * self.step if self.step > 0 else th.copy()
        read = actual + self.encoder_error(actual)
        if rng is not None and self.encoder_noise > 0:
            read = read + rng.normal(0.0, self.encoder_noise, th.shape)
        return actual, read


@dataclass(frozen=True)
class BeamDrift:
    """Angular drift of the collimated beam over time (Δβ towards Y, Δγ towards Z), radians.

    ``Δβ(t) = rate[0]·t + wander·sin(2πt/period)``, ``Δγ(t) = rate[1]·t + wander·cos(2πt/period) − wander``
    (slow mechanical deformation and air, Optics Express 2018, Five-DOF motion errors of a rotary axis section 2.4); zero at t = 0.
    """

    rate: tuple[float, float] = (0.0, 0.0)
    wander: float = 0.0
    period: float = 1200.0

    def __call__(self, t):
        t = np.asarray(t, float)
        w = 2 * math.pi * t / self.period
        return (self.rate[0] * t + self.wander * np.sin(w),
                self.rate[1] * t + self.wander * (np.cos(w) - 1.0))


#: A drift of the paper's kind: 1 µrad/h plus 0.5 µrad wander (20 min), visible uncompensated.
TYPICAL_DRIFT = BeamDrift(rate=(1e-6 / 3600, -0.7e-6 / 3600), wander=0.5e-6)


@dataclass(frozen=True)
class MotionRun:
    """One measurement: readings and the errors reconstructed from them, with the truth (SI).

    Attributes
    ----------
    time : ndarray, seconds
    readings : Readings
    measured : FiveErrors
        Eqs. 1-9 with the drift compensation, zeroed at the first reading.
    uncompensated : FiveErrors
        Eqs. 1-6 without it.
    truth : FiveErrors
        The true errors at the sensitive unit, zeroed at the first reading.
    drift_measured, drift_true : ndarray, shape (N, 2), radians
    """

    time: np.ndarray
    readings: Readings
    measured: FiveErrors
    uncompensated: FiveErrors
    truth: FiveErrors
    drift_measured: np.ndarray
    drift_true: np.ndarray

    def __str__(self) -> str:
        return f"five-DOF measurement, {len(self.readings)} readings\n{self.measured}"


def indexing_test(axis: RotaryAxis, system: FiveDofSystem, rng: np.random.Generator,
                  step_deg: float = 30.0, reference: ReferenceAxis = ReferenceAxis(),
                  drift: BeamDrift = TYPICAL_DRIFT, dwell: float = 30.0, start_time: float = 0.0,
                  drift_window: int = 1, samples: int = 10) -> MotionRun:
    """Step the target axis over 0-360° and read the five errors at every stop.

    Parameters
    ----------
    axis : RotaryAxis
        The target axis (the truth).
    system : FiveDofSystem
    rng : numpy.random.Generator
    step_deg : float, degrees
        Indexing step; 360 must be a whole multiple (30° for the paper's HSD-200RT).
    reference : ReferenceAxis
    drift : BeamDrift
    dwell : float, seconds
        Time per stop (the drift and the axis's thermal drift grow with it).
    start_time : float, seconds
    drift_window : int
        Passed to :func:`axiscal.instruments.five_dof.reconstruct`.
    samples : int
        Readings taken 1 s apart at each stop and averaged (the axis stands still: one pose per
        stop, fresh detector noise and beam jitter per reading).

    Returns
    -------
    MotionRun
        13 stops for 30° (0° and 360° both read).
    """
    n = 360.0 / step_deg if step_deg > 0 else math.nan
    if not (math.isfinite(n) and abs(n - round(n)) < 1e-9 and round(n) >= 4):
        raise InputError(f"step_deg = {step_deg!r}: 360 deg must be a whole multiple of the step, "
                         "with at least 4 steps")
    theta = np.radians(np.arange(int(round(n)) + 1) * step_deg)
    t = start_time + dwell * np.arange(theta.size)
    if not (isinstance(samples, int) and samples >= 1):
        raise InputError(f"samples = {samples!r} must be a whole number >= 1")
    pose = axis.pose(theta, +1, rng, t)
    _, read = reference.turn_back(theta, rng)
    actual, _ = reference.turn_back(theta, None)
    return _measure(system, pose, actual, read, drift, t, rng, drift_window, samples)


def stability_test(system: FiveDofSystem, rng: np.random.Generator, duration: float = 3600.0,
                   interval: float = 10.0, drift: BeamDrift = TYPICAL_DRIFT,
                   drift_window: int = 7) -> MotionRun:
    """The system standing still, read every ``interval`` s for ``duration`` s (Optics Express 2018, Five-DOF motion errors of a rotary axis §3.2).

    The sensitive unit does not move (truth zero): what the measured errors show is the
    instrument's noise and the residue of the drift compensation. ``drift_window`` = 7 readings
    (70 s at 10 s) averages PSD2 for the slow drift.
    """
    if not (duration > 0 and interval > 0 and duration / interval >= 2):
        raise InputError(f"duration {duration!r} s and interval {interval!r} s must give at least "
                         "2 readings")
    t = np.arange(0.0, duration + 1e-9, interval)
    z = np.zeros_like(t)
    pose = Pose(theta=z, ez=z, ex=z, ey=z, dx=z, dy=z, dz=z)
    return _measure(system, pose, z, z, drift, t, rng, drift_window)


def repeatability_test(axis: RotaryAxis, system: FiveDofSystem, rng: np.random.Generator,
                       runs: int = 3, pause: float = 600.0, **kwargs) -> tuple[MotionRun, ...]:
    """The indexing test ``runs`` times, ``pause`` s apart (Optics Express 2018, Five-DOF motion errors of a rotary axis §3.3: three runs).

    Extra keyword arguments go to :func:`indexing_test`.
    """
    if not (isinstance(runs, int) and runs >= 2):
        raise InputError(f"runs = {runs!r}: a repeatability test needs at least 2 runs")
    out, t0 = [], 0.0
    for _ in range(runs):
        run = indexing_test(axis, system, rng, start_time=t0, **kwargs)
        out.append(run)
        t0 = float(run.time[-1]) + pause
    return tuple(out)


def to_motion_data(runs, which: str = "measured", title: str = "") -> MotionErrorData:
    """Stack the ``measured`` (or ``truth``, ``uncompensated``) errors of runs for ISO 230-7."""
    if which not in ("measured", "truth", "uncompensated"):
        raise InputError(f"which = {which!r} must be 'measured', 'truth' or 'uncompensated'")
    errs = [getattr(r, which) for r in runs]
    stack = {c: np.vstack([getattr(e, c) for e in errs]) for c in FiveErrors.CHANNELS}
    return MotionErrorData(errs[0].theta, title=title, **stack)


def _measure(system, pose, theta_ref_actual, theta_ref_read, drift, t, rng, drift_window,
             samples=1):
    beta, gamma = drift(t)
    rep = lambda a: np.repeat(np.broadcast_to(np.asarray(a, float), t.shape), samples)  # noqa: E731
    many = Pose(*(rep(getattr(pose, f)) for f in ("theta", "ez", "ex", "ey", "dx", "dy", "dz")))
    tt = rep(t) + np.tile(np.arange(samples, dtype=float), t.size)
    raw = system.read(many, rep(theta_ref_actual), drift(tt), rng)
    mean = lambda a: a.reshape(t.size, samples, *a.shape[1:]).mean(axis=1)  # noqa: E731
    readings = Readings(np.asarray(pose.theta, float).copy(), np.asarray(theta_ref_read, float),
                        *(mean(getattr(raw, f)) for f in ("psd1", "psd2", "qd1", "qd2")))
    measured, d = reconstruct(readings, system, True, 0, drift_window)
    plain, _ = reconstruct(readings, system, False, 0, drift_window)
    truth = motion_at_unit(pose, system.height).relative(0)
    return MotionRun(np.asarray(t, float), readings, measured, plain, truth, d,
                     np.column_stack([beta, gamma]))


@dataclass(frozen=True)
class Crosstalk:
    """How true errors leak into measured ones for a set-up (noise-free, SI ratios).

    Attributes
    ----------
    matrix : ndarray, shape (5, 6)
        Row: measured error (εz, εy, εx, δy, δz); column: true error (:data:`INPUTS`).
        Entry: largest |measured − true at the unit| per unit of the true error over the angles of
        a turn (radian/radian, metre/metre, metre/radian or radian/metre; 0 for a perfect set-up).
    spurious : dict of str to float
        Peak-to-valley over a turn that each measured error shows on a perfect axis (radians or
        metres): the mounting errors alone.
    residual : dict of str to float
        The same after removing the once-per-turn component (what an ISO 230-7 radial or tilt
        evaluation keeps of it).
    """

    matrix: np.ndarray
    spurious: dict = field(default_factory=dict)
    residual: dict = field(default_factory=dict)

    def table(self) -> list[list[float]]:
        """The matrix in display units: arcsec or µm of output per arcsec or µm of input."""
        scale = {"e": ARCSEC, "d": UM}
        return [[float(self.matrix[i, j]) * scale[inp[0]] / scale[out[0]]
                 for j, inp in enumerate(INPUTS)] for i, out in enumerate(FiveErrors.CHANNELS)]

    def __str__(self) -> str:
        head = "leak [out/in]" + "".join(f"{SYMBOLS[c]:>10}" for c in INPUTS)
        rows = [f"{SYMBOLS[out]:<13}" + "".join(f"{v:10.4f}" for v in row)
                for out, row in zip(FiveErrors.CHANNELS, self.table())]

        def shown(values: dict) -> str:
            return ", ".join(f"{SYMBOLS[k]} {v / (ARCSEC if k[0] == 'e' else UM):.3f}"
                             f"{' arcsec' if k[0] == 'e' else ' µm'}" for k, v in values.items())

        sp, rs = shown(self.spurious), shown(self.residual)
        return "\n".join([head, *rows, f"spurious motion on a perfect axis (p-v): {sp}",
                          f"  after removing the once-per-turn component: {rs}"])


def crosstalk(system: FiveDofSystem, angle_step: float = 30 * math.pi / 180,
              step_angle: float = 20 * ARCSEC, step_length: float = 5 * UM) -> Crosstalk:
    """Leak of each true error into the five measured ones, for ``system``'s mounting.

    Each of the six errors is injected alone (``step_angle`` or ``step_length``) at every angle
    of a turn, the system (noise-free) read and reconstructed against the reading with no error
    at the same angle; the leak is the largest |measured − true at the unit| per unit injected.
    """
    quiet = system.noiseless()
    theta = np.arange(0.0, 2 * math.pi - 1e-9, angle_step)
    zero = np.zeros_like(theta)
    base = Pose(theta=theta, ez=zero, ex=zero, ey=zero, dx=zero, dy=zero, dz=zero)
    base_read = quiet.read(base, theta)
    matrix = np.zeros((len(FiveErrors.CHANNELS), len(INPUTS)))
    for j, name in enumerate(INPUTS):
        step = step_angle if name[0] == "e" else step_length
        pose = replace(base, **{name: zero + step})
        read = quiet.read(pose, theta)
        true = motion_at_unit(pose, quiet.height)
        for i, ch in enumerate(FiveErrors.CHANNELS):
            leaks = [_pair(quiet, base_read, read, k, ch) - getattr(true, ch)[k]
                     for k in range(theta.size)]
            matrix[i, j] = np.max(np.abs(leaks)) / step
    full = np.append(theta, 2 * math.pi)
    z = np.zeros_like(full)
    perfect = Pose(theta=full, ez=z, ex=z, ey=z, dx=z, dy=z, dz=z)
    measured, _ = reconstruct(quiet.read(perfect, full), quiet)
    spurious = {ch: float(np.ptp(getattr(measured, ch))) for ch in FiveErrors.CHANNELS}
    residual = {ch: float(np.ptp(getattr(measured, ch)[:-1] - fundamental(theta, getattr(measured, ch)[:-1])))
                for ch in FiveErrors.CHANNELS}
    return Crosstalk(matrix, spurious, residual)


def _pair(system, base, read, k, channel):
    """Reconstruct one channel from the zero reading ``base[k]`` and the reading ``read[k]``."""
    two = Readings(*(np.stack([getattr(base, f)[k], getattr(read, f)[k]])
                     for f in ("theta", "theta_ref", "psd1", "psd2", "qd1", "qd2")))
    errs, _ = reconstruct(two, system)
    return float(getattr(errs, channel)[1])
