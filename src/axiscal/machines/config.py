"""Simulated axes from configuration tables (TOML), in the units people write.

A linear axis (``kind = "linear"``)::

    [axis]
    name = "X"
    kind = "linear"
    travel_mm = [0, 800]
    scale_error_ppm = 12          # slope of the deviation, µm per m = ppm
    bend_um = 0.0                 # quadratic bow: deviation at mid-travel relative to the ends
    backlash_um = 3.0             # reversal value b: B_i = x↑ - x↓ = b
    repeatability_um = 0.5        # standard deviation of one approach
    thermal_ppm_per_hour = 0.0    # scale growth during the test
    periodic = [{ amplitude_um = 1.5, period_mm = 20, phase_deg = 0 }]
    irregular = { rms_um = 0.8, seed = 7 }

A rotary axis (``kind = "rotary"``), angles in arcseconds and degrees, displacements in µm::

    [axis]
    name = "C"
    kind = "rotary"
    travel_deg = [-120, 120]      # omit for a continuous axis
    backlash_arcsec = 2.0
    repeatability_arcsec = 0.4
    drift_arcsec_per_hour = 0.0
    harmonics = [{ order = 1, amplitude_arcsec = 3.0, phase_deg = 20 }]
    irregular = { rms_arcsec = 0.5, seed = 3 }

    [axis.error_motions.radial_x]  # also radial_y, axial (µm) and tilt_x, tilt_y (arcsec)
    offset_um = 0.0
    asynchronous_um = 0.05
    harmonics = [{ order = 2, amplitude_um = 0.8, phase_deg = 0 }]

Unknown keys are refused with a :class:`~axiscal.errors.ConfigError` that names them, so a typo
never silently becomes a perfect machine.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from axiscal.errors import ConfigError, InputError
from axiscal.machines.error_functions import ZERO, Harmonic, HarmonicSeries, random_profile
from axiscal.machines.linear import LinearAxis
from axiscal.machines.rotary import TWO_PI, ErrorMotion, RotaryAxis
from axiscal.units import ARCSEC, DEG, MM, UM

__all__ = ["refuse_unknown_keys", "axis_from_config", "linear_axis_from_config",
           "rotary_axis_from_config", "check_test_types"]

_LINEAR_KEYS = {"name", "kind", "travel_mm", "scale_error_ppm", "bend_um", "backlash_um",
                "repeatability_um", "thermal_ppm_per_hour", "periodic", "irregular"}
_ROTARY_KEYS = {"name", "kind", "travel_deg", "backlash_arcsec", "repeatability_arcsec",
                "drift_arcsec_per_hour", "harmonics", "irregular", "error_motions"}
_MOTIONS = {"radial_x": ("um", UM), "radial_y": ("um", UM), "axial": ("um", UM),
            "tilt_x": ("arcsec", ARCSEC), "tilt_y": ("arcsec", ARCSEC)}


#: The value type of each ``[test]`` key a positioning plan reads (see
#: :func:`axiscal.procedures.positioning.plan_from_config`); the plan refuses unknown keys.
_TEST_TYPES = {
    "runs": "count", "n_targets": "count", "seed": "seed", "cycle": "text",
    "bidirectional": "bool", "overrun": "number", "dwell_s": "number", "length_mm": "number",
    "start_mm": "number", "irregularity": "number", "travel_deg": "number", "start_deg": "number",
    "step_deg": "number", "measurement_sigma": "number", "speed_deg_s": "number",
}


#: Bounds beyond which a plan would only exhaust memory (the command line uses the same).
MAX_TEST = {"runs": 100, "n_targets": 10_000, "length_mm": 1e6, "travel_deg": 36_000.0}


def check_test_types(test: Any) -> None:
    """Refuse a ``[test]`` value of the wrong TOML type before the plan converts it.

    ``runs = "five"`` would end in ``int()``'s ValueError, ``runs = 2.7`` would silently become 2
    and ``bidirectional = "no"`` would be true; each is named here instead, and so are counts and
    travels beyond :data:`MAX_TEST` (a billion targets is a typing slip that exhausts memory).

    Examples
    --------
    >>> check_test_types({"runs": 5, "step_deg": 45.0, "bidirectional": True})
    >>> check_test_types({"runs": 2.7})
    Traceback (most recent call last):
    ...
    axiscal.errors.ConfigError: [test] runs = 2.7 must be a whole number >= 1
    """
    if not isinstance(test, dict):
        raise ConfigError(f"[test] must be a table, got {test!r}")
    for key, v in test.items():
        kind = _TEST_TYPES.get(key)
        is_int = isinstance(v, int) and not isinstance(v, bool)
        if kind == "count" and not (is_int and v >= 1):
            raise ConfigError(f"[test] {key} = {v!r} must be a whole number >= 1")
        if kind == "seed" and not (is_int and v >= 0):
            raise ConfigError(f"[test] {key} = {v!r} must be a whole number >= 0")
        if kind == "number":
            _num(test, key, None, "[test] ")
        if kind == "text" and not isinstance(v, str):
            raise ConfigError(f"[test] {key} = {v!r} must be text")
        if kind == "bool" and not isinstance(v, bool):
            raise ConfigError(f"[test] {key} = {v!r} must be true or false")
        if key in MAX_TEST and abs(v) > MAX_TEST[key]:
            raise ConfigError(f"[test] {key} = {v!r} is more than {MAX_TEST[key]:g}")
    step, travel = test.get("step_deg"), test.get("travel_deg", 360.0)
    if step is not None and step > 0 and travel / step > MAX_TEST["n_targets"]:
        raise ConfigError(f"[test] step_deg = {step!r} over {travel!r} deg gives more than "
                          f"{MAX_TEST['n_targets']} targets")


def axis_from_config(table: dict[str, Any]) -> LinearAxis | RotaryAxis:
    """Build a simulated axis from an ``[axis]`` table (``kind`` decides which)."""
    if not isinstance(table, dict):
        raise ConfigError(f"[axis] must be a table, got {table!r}")
    kind = str(table.get("kind", "")).lower()
    if kind == "linear":
        return linear_axis_from_config(table)
    if kind == "rotary":
        return rotary_axis_from_config(table)
    raise ConfigError(f"[axis] kind = {table.get('kind')!r}; use 'linear' or 'rotary'")


def linear_axis_from_config(t: dict[str, Any]) -> LinearAxis:
    """Build a :class:`LinearAxis` from a table in mm/µm/ppm (see the module docstring).

    Examples
    --------
    >>> ax = linear_axis_from_config({"travel_mm": [0, 1000], "scale_error_ppm": 10})
    >>> round(float(ax.systematic_deviation(1.0, +1)) / UM, 6)
    10.0
    """
    refuse_unknown_keys("[axis]", t, _LINEAR_KEYS)
    lo, hi = _pair(t.get("travel_mm", [0.0, 1000.0]), "travel_mm")
    length = (hi - lo) * MM
    poly = [0.0, _num(t, "scale_error_ppm", 0.0) * 1e-6]
    bend = _num(t, "bend_um", 0.0) * UM
    if bend:
        # e(x) = 4 bend (x - lo)(hi - x) / L²: zero at the ends, ``bend`` at mid-travel.
        a, b = lo * MM, hi * MM
        k = 4.0 * bend / length**2
        poly = [poly[0] - k * a * b, poly[1] + k * (a + b), -k]
    harmonics = []
    for i, h in enumerate(_list(t, "periodic")):
        refuse_unknown_keys(f"[axis] periodic[{i}]", h, {"amplitude_um", "period_mm", "phase_deg"})
        harmonics.append(Harmonic(_num(h, "amplitude_um", None) * UM, _num(h, "period_mm", None) * MM,
                                  _num(h, "phase_deg", 0.0) * DEG))
    error = HarmonicSeries(tuple(harmonics), tuple(poly))
    irr = t.get("irregular")
    if irr:
        refuse_unknown_keys("[axis] irregular", irr, {"rms_um", "seed"})
        error = error + random_profile(_nonnegative(irr, "rms_um") * UM, length, range(3, 60),
                                       np.random.default_rng(_seed(irr, "[axis] irregular")))
    try:
        return LinearAxis(
            name=_name(t, "X"),
            travel=(lo * MM, hi * MM),
            error=error,
            backlash=_num(t, "backlash_um", 0.0) * UM,
            repeatability_sigma=_num(t, "repeatability_um", 0.0) * UM,
            thermal_scale_rate=_num(t, "thermal_ppm_per_hour", 0.0) * 1e-6 / 3600.0,
        )
    except ConfigError:
        raise
    except InputError as exc:  # the axis's own validation: say it is the config
        raise ConfigError(f"[axis]: {exc}") from None


def rotary_axis_from_config(t: dict[str, Any]) -> RotaryAxis:
    """Build a :class:`RotaryAxis` from a table in arcsec/deg/µm (see the module docstring).

    Examples
    --------
    >>> ax = rotary_axis_from_config({"harmonics": [{"order": 1, "amplitude_arcsec": 3.0}]})
    >>> round(float(ax.systematic_error(math.pi / 2, 1)) / ARCSEC, 6)
    3.0
    """
    refuse_unknown_keys("[axis]", t, _ROTARY_KEYS)
    positioning = _orders(t.get("harmonics", []), "arcsec", ARCSEC, "[axis] harmonics")
    irr = t.get("irregular")
    if irr:
        refuse_unknown_keys("[axis] irregular", irr, {"rms_arcsec", "seed", "orders"})
        lo, hi = _orders_range(irr.get("orders", [5, 40]))
        positioning = positioning + random_profile(
            _nonnegative(irr, "rms_arcsec") * ARCSEC, TWO_PI, range(lo, hi + 1),
            np.random.default_rng(_seed(irr, "[axis] irregular")))
    travel = None
    if "travel_deg" in t:
        lo, hi = _pair(t["travel_deg"], "travel_deg")
        travel = (lo * DEG, hi * DEG)
    motions = {}
    em = t.get("error_motions", {}) or {}
    refuse_unknown_keys("[axis.error_motions]", em, set(_MOTIONS))
    for name, (unit, k) in _MOTIONS.items():
        if name in em:
            motions[name] = _error_motion(em[name], unit, k, f"[axis.error_motions.{name}]")
    try:
        return RotaryAxis(
            name=_name(t, "C"),
            positioning=positioning,
            backlash=_num(t, "backlash_arcsec", 0.0) * ARCSEC,
            repeatability_sigma=_num(t, "repeatability_arcsec", 0.0) * ARCSEC,
            drift_rate=_num(t, "drift_arcsec_per_hour", 0.0) * ARCSEC / 3600.0,
            travel=travel,
            **motions,
        )
    except ConfigError:
        raise
    except InputError as exc:
        raise ConfigError(f"[axis]: {exc}") from None


def _error_motion(t: dict[str, Any], unit: str, k: float, where: str) -> ErrorMotion:
    refuse_unknown_keys(where, t, {f"offset_{unit}", f"asynchronous_{unit}", "harmonics"})
    return ErrorMotion(
        synchronous=_orders(t.get("harmonics", []), unit, k, f"{where} harmonics"),
        asynchronous_sigma=_num(t, f"asynchronous_{unit}", 0.0) * k,
        offset=_num(t, f"offset_{unit}", 0.0) * k,
    )


def _orders(items, unit: str, k: float, where: str) -> HarmonicSeries:
    if not isinstance(items, list):
        raise ConfigError(f"{where} must be a list of tables")
    out = []
    for i, h in enumerate(items):
        if not isinstance(h, dict):
            raise ConfigError(f"{where}[{i}] must be a table")
        refuse_unknown_keys(f"{where}[{i}]", h, {"order", f"amplitude_{unit}", "phase_deg"})
        order = h.get("order")
        if isinstance(order, bool) or not isinstance(order, int) or order < 1:
            raise ConfigError(f"{where}[{i}] order = {order!r} must be a whole number >= 1 per turn")
        out.append(Harmonic(_num(h, f"amplitude_{unit}", None) * k, TWO_PI / order,
                            _num(h, "phase_deg", 0.0) * DEG))
    return HarmonicSeries(tuple(out)) if out else ZERO


def refuse_unknown_keys(where: str, t: Any, allowed: set[str]) -> None:
    """Raise :class:`ConfigError` if ``t`` is not a table or has keys outside ``allowed``
    (the message style of :func:`axiscal._schema.refuse_unknown`, with the file and line)."""
    from axiscal._schema import refuse_unknown

    refuse_unknown(t, allowed, where)


def _num(t: dict[str, Any], key: str, default: float | None, where: str = "") -> float:
    if key not in t:
        if default is None:
            raise ConfigError(f"missing key {key!r}")
        return default
    v = t[key]
    if isinstance(v, bool) or not isinstance(v, (int, float)) or not math.isfinite(v):
        raise ConfigError(f"{where}{key} = {v!r} must be a finite number")
    return float(v)


def _nonnegative(t: dict[str, Any], key: str) -> float:
    """A required number >= 0 (an rms or a standard deviation)."""
    v = _num(t, key, None)
    if v < 0:
        raise ConfigError(f"{key} = {t[key]!r} must be >= 0 (it is a root mean square)")
    return v


def _seed(t: dict[str, Any], where: str) -> int:
    """A random seed: a whole number >= 0 (numpy refuses negative seeds)."""
    v = t.get("seed", 0)
    if isinstance(v, bool) or not isinstance(v, int) or v < 0:
        raise ConfigError(f"{where} seed = {v!r} must be a whole number >= 0")
    return v


def _name(t: dict[str, Any], default: str) -> str:
    v = t.get("name", default)
    if not isinstance(v, str) or not v.strip():
        raise ConfigError(f"[axis] name = {v!r} must be the axis name as text, e.g. \"{default}\"")
    return v


#: Highest order of a rotary axis's irregular profile: one harmonic per 0.1 degree.
MAX_IRREGULAR_ORDER = 3600


def _orders_range(v: Any) -> tuple[int, int]:
    lo, hi = _pair(v, "irregular.orders")
    if lo != int(lo) or hi != int(hi) or lo < 1 or hi > MAX_IRREGULAR_ORDER:
        raise ConfigError(f"irregular.orders = {v!r} must be whole orders per turn, 1 <= low < "
                          f"high <= {MAX_IRREGULAR_ORDER}")
    return int(lo), int(hi)


def _pair(v: Any, key: str) -> tuple[float, float]:
    if (not isinstance(v, list) or len(v) != 2
            or not all(isinstance(x, (int, float)) and not isinstance(x, bool) and math.isfinite(x)
                       for x in v)):
        raise ConfigError(f"{key} = {v!r} must be a pair of finite numbers [low, high]")
    lo, hi = float(v[0]), float(v[1])
    if not hi > lo:
        raise ConfigError(f"{key} = {v!r}: the second number must be larger than the first")
    return lo, hi


def _list(t: dict[str, Any], key: str) -> list:
    v = t.get(key, [])
    if not isinstance(v, list):
        raise ConfigError(f"{key} must be a list of tables")
    return v
