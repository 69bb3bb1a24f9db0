"""A simulated five-axis machine, table-table (A/C or B/C) or spindle head over a C table
(``kind = "head-table"``): the twin whose rotary axes carry the
location errors of ISO 230-1:2012 / ISO 230-7:2015 Clause 3 and the position-dependent errors of
the five-DOF rotary-axis model.

The kinematics (frames, reference points, the LinuxCNC sign of the rotary angles) are those of
:mod:`axiscal.physics.rotary_location`; each rotary axis is a
:class:`~axiscal.machines.rotary.RotaryAxis` for its travel and its angular positioning error and
error motions (radial, axial, tilt; ISO 230-7), applied in the axis's own frame.

Configuration (TOML), lengths in mm, location errors in µm and µrad::

    [machine]
    name = "table-table A/C"
    kind = "table-table"
    rotary = ["A", "C"]              # the tilting axis (A or B), then C, which it carries
    tilt_position_mm = [0.0, -50.0]  # A: Y, Z of the A axis (LinuxCNC y-rot-point + y-offset,
                                     # z-rot-point + z-offset); B: X, Z of the B axis
    c_position_mm = [0.0, 0.0]       # X, Y of the C axis at A = 0 (x-rot-point, y-rot-point)

    [machine.A]                      # the keys of a rotary [axis] (README), without name/kind
    travel_deg = [-120, 30]
    harmonics = [{ order = 1, amplitude_arcsec = 2.0 }]
    [machine.A.error_motions.radial_x]
    harmonics = [{ order = 2, amplitude_um = 0.5 }]

    [machine.C]                      # no travel_deg: a continuous table

    # a spindle head instead: kind = "head-table", rotary = ["B", "C"], pivot_length_mm = 150
    # (the tool tip below the head's axis at B = 0), no tilt_position_mm

    [location_errors]                # the twin's truth, shown only in simulation reports
    E_Y0A = 12.0                     # µm
    E_B0A = 25.0                     # µrad
    "E_C(0X)Y" = 20.0                # µrad: squareness of the linear axes (ISO 230-1), optional
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from axiscal.errors import ConfigError, InputError
from axiscal.machines.config import refuse_unknown_keys, rotary_axis_from_config
from axiscal.machines.rotary import RotaryAxis
from axiscal.physics.rotary_location import (SQUARENESS, AxisMotion, Geometry, is_angle,
                                              linear_to_true, machine_to_table,
                                              table_to_machine, true_to_linear)
from axiscal.units import MM

__all__ = ["FiveAxisMachine", "five_axis_from_config", "MACHINE_KEYS"]

MACHINE_KEYS = {"name", "kind", "rotary", "tilt_position_mm", "c_position_mm", "pivot_length_mm"}


@dataclass(frozen=True, eq=False)
class FiveAxisMachine:
    """A table-table five-axis machine (SI units).

    Attributes
    ----------
    geometry : Geometry
        Nominal kinematics (what the controller holds).
    errors : dict of str to float
        True location errors by ISO 230 name, m or rad (missing ones are zero).
    tilt_axis, c_axis : RotaryAxis
        Travel and position-dependent errors of each rotary axis.
    name : str
    """

    geometry: Geometry
    errors: dict = field(default_factory=dict)
    tilt_axis: RotaryAxis = field(default_factory=lambda: RotaryAxis(name="A",
                                                                      travel=(-2.1, 2.1)))
    c_axis: RotaryAxis = field(default_factory=lambda: RotaryAxis(name="C"))
    name: str = "simulated five-axis machine"

    def __post_init__(self) -> None:
        unknown = set(self.errors) - set(self.geometry.names) - set(SQUARENESS)
        if unknown:
            raise InputError(f"location errors {sorted(unknown)} are not those of a "
                             f"{self.geometry.tilt}/C machine: {', '.join(self.geometry.names)}")
        if self.tilt_axis.name != self.geometry.tilt or self.c_axis.name != "C":
            raise InputError(f"axes {self.tilt_axis.name}/{self.c_axis.name} do not match the "
                             f"{self.geometry.tilt}/C geometry")

    @property
    def tilt(self) -> str:
        return self.geometry.tilt

    def check_pose(self, tilt_angle, c_angle) -> None:
        """Refuse a pose outside an axis's travel, naming the axis (radians in)."""
        self.tilt_axis.check_in_travel(tilt_angle)
        self.c_axis.check_in_travel(c_angle)

    def motions(self, tilt_angle, c_angle, rng: np.random.Generator | None = None):
        """Position-dependent errors of both axes at the poses (``None`` for a perfect axis)."""
        return _motion(self.tilt_axis, tilt_angle, rng), _motion(self.c_axis, c_angle, rng)

    def to_machine(self, tilt_angle, c_angle, points, rng: np.random.Generator | None = None,
                   readings: bool = True):
        """The linear axes' readings (m) that put the tool on table points at commanded angles
        (rad); with ``readings`` False, where those points truly are (m, orthogonal machine
        frame: the two differ by the linear axes' squareness,
        :func:`~axiscal.physics.rotary_location.squareness_matrix`)."""
        self.check_pose(tilt_angle, c_angle)
        mt, mc = self.motions(tilt_angle, c_angle, rng)
        p = table_to_machine(self.geometry, self.errors, tilt_angle, c_angle, points, mt, mc)
        return self.readings(p) if readings else p

    def to_table(self, tilt_angle, c_angle, points, rng: np.random.Generator | None = None):
        """True table-frame position (m) of the tool at readings ``points`` of the linear axes
        (m) and commanded angles (rad)."""
        self.check_pose(tilt_angle, c_angle)
        mt, mc = self.motions(tilt_angle, c_angle, rng)
        return machine_to_table(self.geometry, self.errors, tilt_angle, c_angle,
                                self.positions(points), mt, mc)

    def readings(self, points) -> np.ndarray:
        """The linear axes' readings (m) with the tool at true positions ``points`` (m)."""
        return true_to_linear(points, self.errors) if self._square else \
            np.atleast_2d(np.asarray(points, float))

    def positions(self, points) -> np.ndarray:
        """Where the tool truly is (m) at readings ``points`` of the linear axes (m)."""
        return linear_to_true(points, self.errors) if self._square else \
            np.atleast_2d(np.asarray(points, float))

    @property
    def _square(self) -> bool:
        return any(self.errors.get(n, 0.0) for n in SQUARENESS)

    def truth_display(self) -> dict[str, float]:
        """The true location errors in µm and µrad, every one of the ten named, and the linear
        axes' squareness errors (µrad) where the twin has them."""
        out = {n: round(float(self.errors.get(n, 0.0)) * 1e6, 9) for n in self.geometry.names}
        out.update({n: round(float(self.errors[n]) * 1e6, 9) for n in SQUARENESS
                    if n in self.errors})
        return out


def _motion(axis: RotaryAxis, theta, rng) -> AxisMotion | None:
    if _perfect(axis):
        return None
    th = np.atleast_1d(np.asarray(theta, float))
    p = axis.pose(th, 1, rng)
    return AxisMotion(ez=p.ez, ex=p.ex, ey=p.ey, dx=p.dx, dy=p.dy, dz=p.dz)


def _perfect(axis: RotaryAxis) -> bool:
    from axiscal.machines.error_functions import ZERO
    from axiscal.machines.rotary import ErrorMotion

    none = ErrorMotion()
    return (axis.positioning == ZERO and axis.backlash == 0 and axis.repeatability_sigma == 0
            and axis.drift_rate == 0 and all(getattr(axis, m) == none for m in
                                             ("radial_x", "radial_y", "axial", "tilt_x", "tilt_y")))


def five_axis_from_config(cfg: dict[str, Any]) -> FiveAxisMachine:
    """Build the twin from a configuration table (module docstring).

    Raises
    ------
    ConfigError
        A missing or unknown key, an impossible value, a rotary axis named twice.

    Examples
    --------
    >>> m = five_axis_from_config({"machine": {"rotary": ["A", "C"],
    ...     "tilt_position_mm": [0, -50], "c_position_mm": [0, 0]},
    ...     "location_errors": {"E_X0C": 20.0}})
    >>> p = m.to_machine(0.0, math.pi, [[0.1, 0.0, 0.0]])     # half a turn of C
    >>> round(float(p[0, 0] + 0.1) * 1e6, 3)                  # 2 × E_X0C
    40.0
    """
    if not isinstance(cfg, dict) or not isinstance(cfg.get("machine"), dict):
        raise ConfigError("the configuration needs a [machine] table")
    m = cfg["machine"]
    tilt = _rotary(m.get("rotary"))
    refuse_unknown_keys("[machine]", m, MACHINE_KEYS | {tilt, "C"})
    kind = m.get("kind", "table-table")
    if kind not in ("table-table", "head-table"):
        raise ConfigError(f"[machine] kind = {kind!r}: 'table-table' (a tilting table carrying "
                          "the C table) or 'head-table' (a spindle head over a C table)")
    if kind == "head-table":
        if "tilt_position_mm" in m:
            raise ConfigError("[machine] tilt_position_mm: a spindle head's axis passes through "
                              "the spindle's pivot point; give pivot_length_mm")
        pivot = m.get("pivot_length_mm")
        if isinstance(pivot, bool) or not isinstance(pivot, (int, float)) \
                or not math.isfinite(pivot) or not 0 <= pivot <= 1e4:
            raise ConfigError(f"[machine] pivot_length_mm = {pivot!r} must be a number of mm "
                              "from 0 to 10000 (the tool tip below the head's axis)")
        geometry = Geometry(tilt, (0.0, 0.0), _pair_mm(m, "c_position_mm"), kind,
                            float(pivot) * MM)
    else:
        if "pivot_length_mm" in m:
            raise ConfigError("[machine] pivot_length_mm belongs to a spindle head "
                              "(kind = \"head-table\")")
        geometry = Geometry(tilt, _pair_mm(m, "tilt_position_mm"), _pair_mm(m, "c_position_mm"))
    axes = {}
    for axis in (tilt, "C"):
        t = m.get(axis, {})
        if not isinstance(t, dict):
            raise ConfigError(f"[machine.{axis}] must be a table")
        if "name" in t or "kind" in t:
            raise ConfigError(f"[machine.{axis}]: the axis is named by its table; leave out "
                              "'name' and 'kind'")
        axes[axis] = rotary_axis_from_config({**t, "name": axis, "kind": "rotary"})
    return FiveAxisMachine(geometry=geometry, errors=_location_errors(cfg, geometry),
                           tilt_axis=axes[tilt], c_axis=axes["C"],
                           name=str(m.get("name", f"simulated {kind} {tilt}/C machine"))[:80])


def _rotary(v: Any) -> str:
    if (not isinstance(v, list) or len(v) != 2
            or not all(isinstance(x, str) for x in v)):
        raise ConfigError(f"[machine] rotary = {v!r}: name the tilting axis and the table, "
                          "e.g. [\"A\", \"C\"]")
    names = [x.strip().upper() for x in v]
    if names[0] == names[1]:
        raise ConfigError(f"[machine] rotary = {v!r}: rotary axis {names[0]} named twice")
    if names[0] not in ("A", "B") or names[1] != "C":
        raise ConfigError(f"[machine] rotary = {v!r}: the machine is [\"A\", \"C\"] or "
                          "[\"B\", \"C\"] (the tilting axis, then the C table)")
    return names[0]


def _pair_mm(m: dict, key: str) -> tuple[float, float]:
    v = m.get(key, [0.0, 0.0])
    if (not isinstance(v, list) or len(v) != 2
            or not all(isinstance(x, (int, float)) and not isinstance(x, bool)
                       and math.isfinite(x) and abs(x) <= 1e5 for x in v)):
        raise ConfigError(f"[machine] {key} = {v!r} must be two finite numbers (mm)")
    return float(v[0]) * MM, float(v[1]) * MM


def _location_errors(cfg: dict, geometry: Geometry) -> dict[str, float]:
    t = cfg.get("location_errors", {})
    refuse_unknown_keys("[location_errors]", t, set(geometry.names) | set(SQUARENESS))
    out = {}
    for name, v in t.items():
        if isinstance(v, bool) or not isinstance(v, (int, float)) or not math.isfinite(v) \
                or abs(v) > 1e4:
            raise ConfigError(f"[location_errors] {name} = {v!r} must be a finite number of "
                              f"{'µrad' if is_angle(name) else 'µm'}, at most 10000")
        out[name] = float(v) * 1e-6
    return out

