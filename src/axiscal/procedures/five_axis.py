"""Five-axis kinematics tests: a sphere on the table probed at many rotary poses, and an R-test.

A plan is read from the ``[[setup]]`` tables of a five-axis configuration (beside the
``[machine]`` of :mod:`axiscal.machines.five_axis`), lengths in mm, noise in µm::

    [[setup]]
    kind = "probing"                 # a precision sphere on the table, touch probe in the spindle
    place_mm = [100.0, 0.0, 50.0]    # nominal sphere centre in the table frame
    A_deg = [0, -30, -60, -90]       # the tilting axis's angles (B_deg on a B/C machine)
    C_deg = [0, 45, 90, 135, 180, 225, 270, 315]   # every A angle with every C angle
    sphere_radius_mm = 12.5
    stylus_radius_mm = 1.5           # effective, from the probe's calibration
    noise_um = 0.5                   # one touch's standard deviation
    u_offset_um = [1.0, 1.0, 1.0]    # calibration uncertainty of stylus offset x, y and length z
    radius_tolerance_mm = 0.02       # a sphere fit farther from the radius is refused
    offset_um = [0, 0, 0]            # simulation only: the probe calibration's true error

    [[setup]]
    kind = "r-test"                  # nest on the table, sphere in the spindle
    place_mm = [0.0, 0.0, 80.0]      # nominal nest place in the table frame
    poses_deg = [[0, 0], [-45, 90], [-90, 180]]   # or A_deg and C_deg as above
    noise_um = 0.5                   # one sensor reading's standard deviation
    u_gain = 0.001                   # relative calibration uncertainty of each sensor's gain
    u_direction_mrad = 1.0           # calibration uncertainty of each sensor's direction
    gain_errors = [0, 0, 0]          # simulation only: the gains' true errors

The procedure measures; it never evaluates: it returns one record per set-up (the touches, or the
R-test's displacements with the commanded positions), which
:mod:`axiscal.standards.location_errors` turns into location errors.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import numpy as np

from axiscal.errors import ConfigError, InputError
from axiscal.instruments.r_test import SENSOR_DIRECTIONS, SimulatedRTest
from axiscal.instruments.touch_probe import SimulatedTouchProbe
from axiscal.machines.config import refuse_unknown_keys
from axiscal.physics.rotary_location import table_to_machine
from axiscal.standards.location_errors import PROBING, R_TEST, SetUp
from axiscal.standards.sphere_fit import RADIUS_TOLERANCE, SphereFit, fit_sphere
from axiscal.units import DEG, MM, UM

__all__ = ["PlannedSetUp", "FiveAxisPlan", "ProbingRecord", "RTestRecord", "plan_from_config",
           "measure", "MAX_POSES"]

#: Most poses one set-up may plan (a typing slip in a step would otherwise exhaust memory).
MAX_POSES = 20_000

_COMMON = {"kind", "place_mm", "poses_deg", "C_deg", "noise_um", "label"}
_KEYS = {PROBING: _COMMON | {"sphere_radius_mm", "stylus_radius_mm", "u_offset_um",
                             "radius_tolerance_mm", "offset_um"},
         R_TEST: _COMMON | {"u_gain", "u_direction_mrad", "gain_errors", "range_mm"}}


@dataclass(frozen=True, eq=False)
class PlannedSetUp:
    """One planned set-up (SI units): its kind, poses, nominal place and instrument."""

    kind: str
    tilt: str
    tilt_angle: np.ndarray
    c_angle: np.ndarray
    place: np.ndarray
    instrument: Any
    u_offset: tuple[float, float, float] = (0.0, 0.0, 0.0)
    u_gain: float = 0.0
    tolerance: float = RADIUS_TOLERANCE
    label: str = ""
    u_direction: float = 0.0

    @property
    def poses(self) -> int:
        return len(self.tilt_angle)

    def nominal_setup(self) -> SetUp:
        """The set-up as :func:`~axiscal.standards.location_errors.check_plan` needs it."""
        directions = getattr(self.instrument, "directions", None) if self.kind == R_TEST \
            else None
        return SetUp(self.kind, self.tilt_angle, self.c_angle, nominal=tuple(self.place),
                     u_reading=_u_reading(self), u_offset=self.u_offset, u_gain=self.u_gain,
                     u_direction=self.u_direction, directions=directions, label=self.label)


@dataclass(frozen=True, eq=False)
class FiveAxisPlan:
    """The planned set-ups of a five-axis test."""

    setups: tuple[PlannedSetUp, ...]

    @property
    def poses(self) -> int:
        return sum(s.poses for s in self.setups)


@dataclass(frozen=True, eq=False)
class ProbingRecord:
    """A sphere probed at N poses: the recorded stylus-ball centres of each (SI units).

    Attributes
    ----------
    tilt : str
    tilt_angle, c_angle : numpy.ndarray, shape (N,), rad
    touches : tuple of numpy.ndarray, each (n, 3), m, machine frame
    sphere_radius, stylus_radius : float, m
    noise : float, m
        One touch's standard deviation (the probe's statement).
    u_offset : tuple of float, m
    tolerance : float, m
    place : numpy.ndarray or None, m
        Nominal sphere place in the table frame, when known.
    label : str
    """

    tilt: str
    tilt_angle: np.ndarray
    c_angle: np.ndarray
    touches: tuple
    sphere_radius: float
    stylus_radius: float
    noise: float = 0.5e-6
    u_offset: tuple[float, float, float] = (0.0, 0.0, 0.0)
    tolerance: float = RADIUS_TOLERANCE
    place: np.ndarray | None = None
    label: str = "probing"

    kind = PROBING

    def fits(self) -> tuple[SphereFit, ...]:
        """One sphere fit per pose, each checked against the radius (pose numbers from 1)."""
        r = self.sphere_radius + self.stylus_radius
        return tuple(fit_sphere(t, r, self.tolerance, f"{self.label} pose {i + 1}")
                     for i, t in enumerate(self.touches))

    def setup(self) -> SetUp:
        centres = np.array([f.center for f in self.fits()])
        u = self.noise * _centre_factor(self.touches[0], centres[0])
        return SetUp(PROBING, self.tilt_angle, self.c_angle, centres,
                     nominal=tuple(self.place) if self.place is not None else (0.0, 0.0, 0.0),
                     u_reading=max(u, 1e-9), u_offset=self.u_offset, label=self.label)


@dataclass(frozen=True, eq=False)
class RTestRecord:
    """An R-test at N poses (SI units): commanded tool-sphere positions (machine frame) and the
    sphere's displacement from the nest (table frame)."""

    tilt: str
    tilt_angle: np.ndarray
    c_angle: np.ndarray
    commanded: np.ndarray
    displacement: np.ndarray
    noise: float = 0.5e-6
    u_gain: float = 0.0
    place: np.ndarray | None = None
    label: str = "r-test"
    u_direction: float = 0.0
    directions: np.ndarray | None = None

    kind = R_TEST

    def setup(self) -> SetUp:
        return SetUp(R_TEST, self.tilt_angle, self.c_angle, self.displacement, self.commanded,
                     nominal=tuple(self.place) if self.place is not None else (0.0, 0.0, 0.0),
                     u_reading=max(self.noise, 1e-9), u_gain=self.u_gain,
                     u_direction=self.u_direction,
                     directions=SENSOR_DIRECTIONS if self.directions is None else self.directions,
                     label=self.label)


def plan_from_config(cfg: dict[str, Any], machine) -> FiveAxisPlan:
    """Read the ``[[setup]]`` tables (module docstring) and check every pose against the axes'
    travel (the message names the axis).

    Raises
    ------
    ConfigError
        A missing or unknown key, a bad value, no set-up, a pose outside an axis's travel.
    """
    tables = cfg.get("setup")
    if not isinstance(tables, list) or not tables or not all(isinstance(t, dict) for t in tables):
        raise ConfigError("the configuration needs at least one [[setup]] table (kind = "
                          "\"probing\" or \"r-test\")")
    out = []
    for i, t in enumerate(tables, 1):
        where = f"[[setup]] {i}"
        kind = t.get("kind")
        if kind not in _KEYS:
            raise ConfigError(f"{where}: kind = {kind!r}; use \"probing\" or \"r-test\"")
        tilt_key = f"{machine.tilt}_deg"
        refuse_unknown_keys(f"[setup] {i}", t, _KEYS[kind] | {tilt_key})
        a, c = _poses(t, machine.tilt, where)
        try:
            machine.check_pose(a, c)
        except InputError as exc:
            raise ConfigError(f"{where}: {exc}") from None
        place = np.array(_triple(t, "place_mm", None, where)) * MM
        label = str(t.get("label", f"{kind} {i}"))[:80]
        noise = _num(t, "noise_um", 0.5, where, lo=0.0) * UM
        if kind == PROBING:
            inst = SimulatedTouchProbe(
                sphere_radius=_num(t, "sphere_radius_mm", 12.5, where, lo=0.1) * MM,
                stylus_radius=_num(t, "stylus_radius_mm", 1.5, where, lo=0.0) * MM,
                noise=noise, offset=tuple(np.array(_triple(t, "offset_um", [0, 0, 0], where)) * UM))
            out.append(PlannedSetUp(
                PROBING, machine.tilt, a, c, place, inst,
                u_offset=tuple(np.array(_triple(t, "u_offset_um", [0, 0, 0], where)) * UM),
                tolerance=_num(t, "radius_tolerance_mm", RADIUS_TOLERANCE / MM, where,
                               lo=1e-6) * MM, label=label))
        else:
            inst = SimulatedRTest(noise=noise,
                                  gain_errors=tuple(_triple(t, "gain_errors", [0, 0, 0], where)),
                                  range=_num(t, "range_mm", 1.0, where, lo=1e-3) * MM)
            out.append(PlannedSetUp(
                R_TEST, machine.tilt, a, c, place, inst,
                u_gain=_num(t, "u_gain", 0.0, where, lo=0.0), label=label,
                u_direction=_num(t, "u_direction_mrad", 0.0, where, lo=0.0) * 1e-3))
    return FiveAxisPlan(tuple(out))


def measure(machine, plan: FiveAxisPlan, rng: np.random.Generator | None = None) -> tuple:
    """Run every planned set-up on ``machine`` (the twin, or a driver with its interface).

    Returns
    -------
    tuple of ProbingRecord and RTestRecord, one per set-up, in the plan's order.
    """
    out = []
    for s in plan.setups:
        if s.kind == PROBING:
            touches = tuple(s.instrument.probe_sphere(machine, a, c, s.place, rng)
                            for a, c in zip(s.tilt_angle, s.c_angle))
            out.append(ProbingRecord(s.tilt, s.tilt_angle, s.c_angle, touches,
                                     s.instrument.sphere_radius, s.instrument.stylus_radius,
                                     s.instrument.noise, s.u_offset, s.tolerance, s.place, s.label))
        else:
            commanded = table_to_machine(machine.geometry, {}, s.tilt_angle, s.c_angle, s.place)
            d = s.instrument.measure(machine, s.tilt_angle, s.c_angle, commanded, s.place, rng)
            out.append(RTestRecord(s.tilt, s.tilt_angle, s.c_angle, commanded, d,
                                   s.instrument.noise, s.u_gain, s.place, s.label,
                                   s.u_direction, np.asarray(s.instrument.directions, float)))
    return tuple(out)


def _u_reading(s: PlannedSetUp) -> float:
    if s.kind == PROBING:
        d = np.asarray(s.instrument.directions, float)
        return max(s.instrument.noise * _centre_factor(d, np.zeros(3)), 1e-9)
    return max(s.instrument.noise, 1e-9)


def _centre_factor(points, centre) -> float:
    """Largest standard deviation of a fitted centre coordinate per unit touch noise:
    ``sqrt(max diag(G Gᵀ))`` = ``sqrt(max diag((DᵀD)⁻¹))`` with rows ``[n_i, 1]`` (n_i the contact
    normals; :func:`~axiscal.standards.sphere_fit.centre_sensitivity`; JCGM 100, F.2)."""
    from axiscal.standards.sphere_fit import centre_sensitivity

    g = centre_sensitivity(np.asarray(points, float) - centre)
    return float(np.sqrt(np.max((g * g).sum(axis=1))))


def _poses(t: dict, tilt: str, where: str) -> tuple[np.ndarray, np.ndarray]:
    key = f"{tilt}_deg"
    if "poses_deg" in t:
        if key in t or "C_deg" in t:
            raise ConfigError(f"{where}: give poses_deg or {key} with C_deg, not both")
        p = t["poses_deg"]
        if (not isinstance(p, list) or not p or not all(
                isinstance(x, list) and len(x) == 2 and all(_finite(v) for v in x) for x in p)):
            raise ConfigError(f"{where}: poses_deg must be a list of [{tilt}, C] pairs in degrees")
        arr = np.array(p, float)
        a, c = arr[:, 0], arr[:, 1]
    else:
        lists = []
        for k in (key, "C_deg"):
            v = t.get(k)
            if not isinstance(v, list) or not v or not all(_finite(x) for x in v):
                raise ConfigError(f"{where}: {k} must be a list of angles in degrees (or give "
                                  "poses_deg)")
            lists.append(np.array(v, float))
        a, c = (x.ravel() for x in np.meshgrid(*lists, indexing="ij"))
    if len(a) > MAX_POSES:
        raise ConfigError(f"{where}: {len(a)} poses; at most {MAX_POSES}")
    return a * DEG, c * DEG


def _finite(v) -> bool:
    return isinstance(v, (int, float)) and not isinstance(v, bool) and math.isfinite(v) \
        and abs(v) <= 1e6


def _num(t: dict, key: str, default, where: str, lo: float) -> float:
    v = t.get(key, default)
    if not _finite(v) or v < lo:
        raise ConfigError(f"{where}: {key} = {v!r} must be a finite number >= {lo:g}")
    return float(v)


def _triple(t: dict, key: str, default, where: str) -> list[float]:
    v = t.get(key, default)
    if v is None:
        raise ConfigError(f"{where}: missing key {key!r} (three numbers)")
    if not isinstance(v, list) or len(v) != 3 or not all(_finite(x) for x in v):
        raise ConfigError(f"{where}: {key} = {v!r} must be three finite numbers")
    return [float(x) for x in v]

