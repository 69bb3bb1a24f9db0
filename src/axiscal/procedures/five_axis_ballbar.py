"""Ballbar tests of a five-axis machine's rotary axes moving with the linear axes (ISO
10791-6:2014 kinematic tests as :mod:`axiscal.standards.iso10791_6` reads them): the path, and
the simulated ballbar's readings on the twin.

A set-up is a ``[[ballbar]]`` table of a five-axis configuration (beside its ``[machine]``,
:mod:`axiscal.machines.five_axis`), lengths in mm, angles in degrees (the LinuxCNC sign)::

    [[ballbar]]
    label = "C radial"
    direction = "radial"            # radial | tangential | axial, to the swept axis (C if both)
    pivot_mm = [150.0, 0.0, 60.0]   # the table ball's centre, table frame
    length_mm = 100.0               # the bar's nominal length (calibrated)
    C_deg = [0, 360]                # a swept axis: [start, end]; a fixed one: one angle
    A_deg = 0                       # B_deg on a B/C machine
    points = 73                     # readings along the path, both ends included (3 ... 20000)
    noise_um = 0.2                  # the ballbar's standard deviation of one reading
    u_gain = 0.001                  # relative calibration uncertainty of its transducer
    drift_K = 0.1                   # change of the bar's temperature during the run
    u_length_um = 0.5               # calibrator length uncertainty (acts on no range)
    calibration_error_um = 0.0      # simulation only: the calibrator's true error

One swept axis is the test of one rotary axis with the linear axes; both swept together (the
five axes moving) is the five-axis test. The controller's path (what the nominal kinematics
command): the spindle ball at ``pivot + length · n`` in the table frame at every point, ``n`` the
bar's direction (:func:`~axiscal.standards.iso10791_6.bar_direction`), so the linear axes move
on :func:`~axiscal.physics.rotary_location.table_to_machine` of that point with no location
error. The twin's ballbar reads the true distance between its balls
(:meth:`axiscal.instruments.ballbar.Ballbar.read_between`); the procedure measures and never
evaluates.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import numpy as np

from axiscal.errors import ConfigError, InputError
from axiscal.instruments.ballbar import Ballbar
from axiscal.machines.config import refuse_unknown_keys
from axiscal.physics.rotary_location import table_to_machine
from axiscal.standards.iso10791_6 import DIRECTIONS, bar_direction
from axiscal.units import DEG, MM, UM

__all__ = ["BallbarSetUp", "BallbarRecord", "ballbar_plan_from_config", "measure_ballbar",
           "MAX_POINTS"]

#: Most readings one set-up may plan.
MAX_POINTS = 20_000

_KEYS = {"label", "direction", "pivot_mm", "length_mm", "C_deg", "points", "noise_um", "u_gain",
         "drift_K", "u_length_um", "calibration_error_um"}


@dataclass(frozen=True, eq=False)
class BallbarSetUp:
    """One planned ballbar set-up and its path (SI units).

    Attributes
    ----------
    label : str
    tilt : str
        The machine's tilting axis (``A`` or ``B``).
    swept : str
        ``"C"``, the tilting axis's letter, or ``"both"``.
    direction : str
    pivot, bar : numpy.ndarray, shape (3,)
        The table ball's centre (m) and the bar's unit direction, table frame.
    length : float, m
    tilt_angle, c_angle : numpy.ndarray, shape (N,), rad
    commanded : numpy.ndarray, shape (N, 3), m
        The linear axes' positions the nominal kinematics give (machine frame).
    ballbar : Ballbar
        The instrument (noise, calibration error; its ``length`` is ``length``).
    u_gain, drift, u_length : float
        Relative, K, m.
    """

    label: str
    tilt: str
    swept: str
    direction: str
    pivot: np.ndarray
    bar: np.ndarray
    length: float
    tilt_angle: np.ndarray
    c_angle: np.ndarray
    commanded: np.ndarray
    ballbar: Ballbar
    u_gain: float = 0.0
    drift: float = 0.0
    u_length: float = 0.0

    @property
    def points(self) -> int:
        return len(self.c_angle)

    @property
    def spindle_ball(self) -> np.ndarray:
        """Where the spindle ball stands in the table frame (m)."""
        return self.pivot + self.length * self.bar

    @property
    def kind(self) -> str:
        """``five-axis`` (both rotary axes move) or ``rotary+linear``."""
        return "five-axis" if self.swept == "both" else "rotary+linear"


@dataclass(frozen=True, eq=False)
class BallbarRecord:
    """The readings of one set-up (SI units): the path's poses and commanded positions and the
    ballbar's deviation (reported − nominal length) at each, with the set-up's statements."""

    label: str
    tilt: str
    swept: str
    direction: str
    pivot: np.ndarray
    bar: np.ndarray
    length: float
    tilt_angle: np.ndarray
    c_angle: np.ndarray
    commanded: np.ndarray
    deviation: np.ndarray
    noise: float
    u_gain: float = 0.0
    drift: float = 0.0
    u_length: float = 0.0
    #: The optional uncertainty settings the file did not state (``u_gain``, ``drift_K``,
    #: ``u_length_um``): their default 0 is assumed, and the report says so beside the number.
    unstated: tuple = ()

    def evaluate(self):
        """The range with its uncertainty
        (:func:`axiscal.standards.iso10791_6.evaluate_ballbar`)."""
        from axiscal.standards.iso10791_6 import evaluate_ballbar

        return evaluate_ballbar(self.deviation, noise=self.noise, u_gain=self.u_gain,
                                length=self.length, drift=self.drift, u_length=self.u_length,
                                label=self.label)

    def result_dict(self, result) -> dict:
        """One set-up of ``axiscal fiveaxis ballbar evaluate --json``: the figure's keys
        (:meth:`~axiscal.standards.iso10791_6.BallbarRange.to_dict`) with the set-up's
        ``direction`` and ``swept``; the history keeps the same object."""
        return result.to_dict() | {"direction": self.direction, "swept": self.swept}


def ballbar_plan_from_config(cfg: dict[str, Any], machine) -> tuple[BallbarSetUp, ...]:
    """Read the ``[[ballbar]]`` tables (module docstring) for ``machine``; every pose is checked
    against the axes' travel (the message names the axis).

    Raises
    ------
    ConfigError
        No set-up, a missing or unknown key, a bad value, no swept axis, a pose outside a travel,
        a spindle-head machine.
    """
    if machine.geometry.head:
        raise ConfigError(f"{machine.name}: the ballbar tests here are for a table-table "
                          "machine (a spindle head's tool turns with the head)")
    tables = cfg.get("ballbar")
    if not isinstance(tables, list) or not tables or not all(isinstance(t, dict) for t in tables):
        raise ConfigError("the configuration needs at least one [[ballbar]] table (README, "
                          "'Five-axis ballbar tests')")
    return tuple(_setup(t, i, machine) for i, t in enumerate(tables, 1))


def measure_ballbar(machine, setups, rng: np.random.Generator | None = None) -> tuple:
    """Run each set-up on the twin: the spindle ball goes where the commanded linear positions
    truly put it (the twin's location and position-dependent errors), the ballbar reads.

    Returns
    -------
    tuple of BallbarRecord, in the set-ups' order.
    """
    out = []
    for s in setups:
        actual = machine.to_table(s.tilt_angle, s.c_angle, s.commanded, rng)
        d = s.ballbar.read_between(actual, s.pivot, rng)
        out.append(BallbarRecord(s.label, s.tilt, s.swept, s.direction, s.pivot, s.bar,
                                 s.length, s.tilt_angle, s.c_angle, s.commanded, d,
                                 s.ballbar.noise, s.u_gain, s.drift, s.u_length))
    return tuple(out)


def _setup(t: dict, i: int, machine) -> BallbarSetUp:
    where = f"[[ballbar]] {i}"
    tilt = machine.tilt
    refuse_unknown_keys(f"[ballbar] {i}", t, _KEYS | {f"{tilt}_deg"})
    direction = t.get("direction", "radial")
    if direction not in DIRECTIONS:
        raise ConfigError(f"{where}: direction = {direction!r}; use one of "
                          f"{', '.join(DIRECTIONS)}")
    points = t.get("points", 73)
    if isinstance(points, bool) or not isinstance(points, int) or not 3 <= points <= MAX_POINTS:
        raise ConfigError(f"{where}: points = {points!r} must be a whole number from 3 to "
                          f"{MAX_POINTS}")
    a, a_swept = _angles(t, f"{tilt}_deg", points, where)
    c, c_swept = _angles(t, "C_deg", points, where)
    if not (a_swept or c_swept):
        raise ConfigError(f"{where}: no rotary axis moves; give C_deg or {tilt}_deg as "
                          "[start, end]")
    swept = "both" if a_swept and c_swept else ("C" if c_swept else tilt)
    try:
        machine.check_pose(a, c)
    except InputError as exc:
        raise ConfigError(f"{where}: {exc}") from None
    pivot = np.array(_triple(t, "pivot_mm", where)) * MM
    length = _num(t, "length_mm", 100.0, where, 1.0) * MM
    label = str(t.get("label", f"ballbar {i} ({swept} {direction})"))[:80]
    try:
        bar = bar_direction(machine.geometry, swept, direction, pivot, a[0], c[0])
    except InputError as exc:
        raise ConfigError(f"{where}: {exc}") from None
    commanded = table_to_machine(machine.geometry, {}, a, c, pivot + length * bar)
    ballbar = Ballbar(length=length, noise=_num(t, "noise_um", 0.2, where, 0.0) * UM,
                      calibration_error=_num(t, "calibration_error_um", 0.0, where, None) * UM)
    return BallbarSetUp(label, tilt, swept, direction, pivot, bar, length, a, c, commanded,
                        ballbar, u_gain=_num(t, "u_gain", 0.0, where, 0.0),
                        drift=_num(t, "drift_K", 0.0, where, 0.0),
                        u_length=_num(t, "u_length_um", 0.0, where, 0.0) * UM)


def _angles(t: dict, key: str, points: int, where: str) -> tuple[np.ndarray, bool]:
    v = t.get(key, 0.0)
    if _finite(v):
        return np.full(points, float(v) * DEG), False
    if isinstance(v, list) and len(v) == 2 and all(_finite(x) for x in v) and v[0] != v[1]:
        return np.linspace(float(v[0]), float(v[1]), points) * DEG, True
    raise ConfigError(f"{where}: {key} = {v!r} must be one angle (fixed) or [start, end] "
                      "(swept), degrees")


def _finite(v) -> bool:
    return isinstance(v, (int, float)) and not isinstance(v, bool) and math.isfinite(v) \
        and abs(v) <= 1e5


def _num(t: dict, key: str, default, where: str, lo) -> float:
    v = t.get(key, default)
    if not _finite(v) or (lo is not None and v < lo):
        rule = "a finite number" if lo is None else f"a finite number >= {lo:g}"
        raise ConfigError(f"{where}: {key} = {v!r} must be {rule}")
    return float(v)


def _triple(t: dict, key: str, where: str) -> list[float]:
    v = t.get(key)
    if v is None:
        raise ConfigError(f"{where}: missing key {key!r} (three numbers, mm)")
    if not isinstance(v, list) or len(v) != 3 or not all(_finite(x) for x in v):
        raise ConfigError(f"{where}: {key} = {v!r} must be three finite numbers (mm)")
    return [float(x) for x in v]
