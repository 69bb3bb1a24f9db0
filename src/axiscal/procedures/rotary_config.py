"""A simulated rotary calibration from a configuration (TOML tables), in the units people write.

::

    seed = 1                       # random stream of the simulation

    [axis]                         # the machine under test: see axiscal.machines.config
    name = "C"
    kind = "rotary"
    harmonics = [{ order = 1, amplitude_arcsec = 4.0, phase_deg = 30 }]
    backlash_arcsec = 1.5
    repeatability_arcsec = 0.3

    [test]                         # the ISO 230-2 plan: see axiscal.procedures.positioning
    travel_deg = 360
    step_deg = 45
    runs = 5
    overrun = 5.0                  # degrees
    dwell_s = 2.0
    speed_deg_s = 10.0             # read here, not by the plan

    [setup]                        # the true set-up (angles mrad/deg, lengths mm, m)
    mount_tilt_mrad = 0.2          # tilt of the mounting face (the TIR shows 2·r·tilt)
    mount_tilt_direction_deg = 0
    calibrator_tilt_mrad = 0.2     # the calibrator's own axis to its base (±0.025° = 0.44 mrad)
    calibrator_tilt_direction_deg = 60
    beam_tilt_mrad = 0.3           # β
    target_misalignment_mrad = 0.15
    reflector_twist_mrad = 1.5     # ω
    lateral_offset_mm = [0.2, 0.1]
    reflector_height_mm = 80
    datum_misalignment_deg = 0.1
    tir_radius_mm = 50
    laser_distance_m = 1.0
    counter_rotation = true
    self_calibration = true
    periscope_drift_K_per_hour = 0.0

    [laser]
    spacing_mm = 30.1              # true retro-reflector spacing
    nominal_spacing_mm = 30.0      # what the software assumes
    nonparallelism_arcsec = 10
    noise_arcsec = 0.05
    resolution_arcsec = 0.01

    [calibrator]
    graduation_error_rms_arcsec = 2.0
    bearing_wander_um = 0.5
    eccentricity_um = 3.0
    read_heads = 2
    error_map = true
    signal_imperfection = 0.003
    servo_arcsec = 0.5
    seed = 11                      # the calibrator's own (factory) errors

    [offaxis]                      # optional: calibrator on a bracket, interferometer on a linear axis
    radius_mm = 150
    phase_deg = 20
    interferometer_distance_mm = 500
    alignment_angles_deg = [-60, 0, 60]
    alignment_noise_mm = 0.02
    beam_yaw_mrad = 2
    yaw_arcsec_per_100mm = 2.0     # the linear axis's yaw: a slope ...
    yaw_amplitude_arcsec = 1.0     # ... and a periodic part
    yaw_period_mm = 120
    yaw_profile_moving_optic = "interferometer"
    yaw_profile_direction_sign = 1
    yaw_sign = "auto"              # or +1 / -1 as the user states it (checked against the records)
    linear_axis = "Y"
    feed_mm_min = 1000

    [meta]                         # optional text: machine, operator, date, notes
    machine = "Turntable T1"

Unknown keys and tables are refused with a :class:`~axiscal.errors.ConfigError` naming them.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import numpy as np

from axiscal.datasets import AxisKind, Metadata
from axiscal.errors import ConfigError, InputError
from axiscal.instruments.laser import SimulatedAngularInterferometer
from axiscal.instruments.rotary_calibrator import SimulatedRotaryCalibrator
from axiscal.machines.config import check_test_types, refuse_unknown_keys
from axiscal.machines.error_functions import Harmonic, HarmonicSeries
from axiscal.machines.rotary import RotaryAxis
from axiscal.procedures.positioning import TestPlan
from axiscal.procedures.rotary_calibration import OffAxisSetup, RotarySetup
from axiscal.units import ARCSEC, DEG, MM, UM

__all__ = ["RotaryCalibrationConfig", "rotary_config_from_dict", "run_rotary_config"]

_TABLES = {"seed", "axis", "test", "setup", "laser", "calibrator", "offaxis", "meta"}
# key -> (field name, factor to SI)
_SETUP = {
    "mount_tilt_mrad": ("mount_tilt", 1e-3), "mount_tilt_direction_deg": ("mount_tilt_direction", DEG),
    "calibrator_tilt_mrad": ("calibrator_tilt", 1e-3),
    "calibrator_tilt_direction_deg": ("calibrator_tilt_direction", DEG),
    "beam_tilt_mrad": ("beam_tilt", 1e-3), "target_misalignment_mrad": ("target_misalignment", 1e-3),
    "reflector_twist_mrad": ("reflector_twist", 1e-3), "reflector_height_mm": ("reflector_height", MM),
    "datum_misalignment_deg": ("datum_misalignment", DEG), "tir_radius_mm": ("tir_radius", MM),
    "laser_distance_m": ("laser_distance", 1.0), "dial_noise_mm": ("dial_noise", MM),
    "shutter_noise_mm": ("shutter_noise", MM), "centring_noise_mm": ("centring_noise", MM),
    "periscope_drift_K_per_hour": ("periscope_drift", 1 / 3600.0),
}
_LASER = {"spacing_mm": ("spacing", MM), "nominal_spacing_mm": ("nominal_spacing", MM),
          "nonparallelism_arcsec": ("nonparallelism", ARCSEC), "noise_arcsec": ("noise", ARCSEC),
          "resolution_arcsec": ("resolution", ARCSEC), "max_angle_deg": ("max_angle", DEG)}
_CALIB = {"graduation_error_rms_arcsec": ("graduation_error_rms", ARCSEC),
          "bearing_wander_um": ("bearing_wander", UM), "eccentricity_um": ("eccentricity", UM),
          "signal_imperfection": ("signal_imperfection", 1.0),
          "map_uncertainty_arcsec": ("map_uncertainty", ARCSEC)}
_OFFAXIS = {"radius_mm": ("radius", MM), "phase_deg": ("phase", DEG),
            "interferometer_distance_mm": ("interferometer_distance", MM),
            "alignment_noise_mm": ("alignment_noise", MM), "beam_yaw_mrad": ("beam_yaw", 1e-3),
            "profile_noise_arcsec": ("profile_noise", ARCSEC), "feed_mm_min": ("feed", 1.0)}
_OFFAXIS_OTHER = {"alignment_angles_deg", "yaw_arcsec_per_100mm", "yaw_amplitude_arcsec",
                  "yaw_period_mm", "yaw_profile_moving_optic", "yaw_profile_direction_sign",
                  "yaw_sign", "linear_axis"}


@dataclass(frozen=True, eq=False)
class RotaryCalibrationConfig:
    """Everything a simulated rotary calibration needs, built from a configuration."""

    axis: RotaryAxis
    plan: TestPlan
    setup: RotarySetup
    laser: SimulatedAngularInterferometer
    calibrator: SimulatedRotaryCalibrator
    offaxis: OffAxisSetup | None
    speed: float
    seed: int
    metadata: Metadata


def rotary_config_from_dict(config: dict[str, Any]) -> RotaryCalibrationConfig:
    """Validate a configuration (a parsed TOML document) and build the simulation's parts.

    Raises
    ------
    ConfigError
        Naming the table and key of any unknown key or impossible value.
    """
    from axiscal.machines.config import axis_from_config
    from axiscal.procedures.positioning import plan_from_config

    if not isinstance(config, dict):
        raise ConfigError("the configuration must be a TOML table")
    refuse_unknown_keys("top level", config, _TABLES)
    seed = _int(config, "seed", 1, "top level", lo=0)
    if "axis" not in config:
        raise ConfigError("the configuration has no [axis] table: say what is calibrated (an empty "
                          "file would simulate a perfect axis)")
    axis_t = dict(_table(config, "axis"))
    axis_t.setdefault("kind", "rotary")
    if str(axis_t["kind"]).lower() != "rotary":
        raise ConfigError(f"[axis] kind = {axis_t['kind']!r}; a rotary calibration needs 'rotary'")
    axis = axis_from_config(axis_t)
    test = dict(_table(config, "test"))
    check_test_types(test)
    speed = _num(test.pop("speed_deg_s", 10.0), "[test] speed_deg_s", positive=True)
    plan = plan_from_config(test, AxisKind.ROTARY, axis.name)
    meta_t = config.get("meta", {}) or {}
    refuse_unknown_keys("[meta]", meta_t, {"machine", "operator", "date", "instrument", "notes"})
    meta = Metadata(axis=axis.name, instrument="angular interferometer + rotary calibrator (simulated)",
                    **{k: str(v) for k, v in meta_t.items()})
    offaxis = None
    if "offaxis" in config:
        from dataclasses import replace

        offaxis = _offaxis(config["offaxis"])
        if len(axis.name) == 1 and axis.name.isalpha():   # the program drives the axis under test
            offaxis = replace(offaxis, rotary_letter=axis.name.upper())
    return RotaryCalibrationConfig(
        axis=axis, plan=plan, setup=_setup(config.get("setup", {}) or {}),
        laser=_build("[laser]", SimulatedAngularInterferometer, config.get("laser", {}) or {}, _LASER),
        calibrator=_calibrator(config.get("calibrator", {}) or {}),
        offaxis=offaxis, speed=speed, seed=seed, metadata=meta)


def run_rotary_config(config: dict[str, Any], seed: int | None = None):
    """Build from a configuration and run :func:`simulate_rotary_calibration` with its seed
    (``seed``, if given, instead of the configuration's)."""
    from axiscal.procedures.rotary_calibration import simulate_rotary_calibration

    c = rotary_config_from_dict(config)
    return simulate_rotary_calibration(c.axis, c.plan, c.setup, c.laser, c.calibrator,
                                       np.random.default_rng(c.seed if seed is None else seed),
                                       c.speed, c.offaxis, c.metadata)


def _setup(t: dict[str, Any]) -> RotarySetup:
    extra = {"lateral_offset_mm", "counter_rotation", "self_calibration"}
    kw = _convert("[setup]", t, _SETUP, extra)
    if "lateral_offset_mm" in t:
        kw["lateral_offset"] = _numbers("[setup]", t, "lateral_offset_mm", 2, "be [x, y] in mm", MM)
    for key in ("counter_rotation", "self_calibration"):
        if key in t:
            kw[key] = _bool(t[key], f"[setup] {key}")
    return _make("[setup]", RotarySetup, kw)


def _calibrator(t: dict[str, Any]) -> SimulatedRotaryCalibrator:
    from dataclasses import replace

    extra = {"read_heads", "error_map", "servo_arcsec", "seed", "map_points"}
    kw = _convert("[calibrator]", t, _CALIB, extra)
    kw["heads_used"] = _int(t, "read_heads", 2, "[calibrator]")
    kw["error_map"] = _bool(t.get("error_map", True), "[calibrator] error_map")
    kw["map_points"] = _int(t, "map_points", 720, "[calibrator]", lo=2)
    rng = np.random.default_rng(_int(t, "seed", 11, "[calibrator]", lo=0))
    cal = _make("[calibrator]", SimulatedRotaryCalibrator.xr20_like, dict(rng=rng, **kw))
    servo = _num(t.get("servo_arcsec", 0.5), "[calibrator] servo_arcsec") * ARCSEC
    return _make("[calibrator]", lambda **k: replace(cal, **k), dict(servo_sigma=servo))


def _offaxis(t: dict[str, Any]) -> OffAxisSetup:
    if not isinstance(t, dict):
        raise ConfigError("[offaxis] must be a table")
    kw = _convert("[offaxis]", t, _OFFAXIS, _OFFAXIS_OTHER)
    if "alignment_angles_deg" in t:
        kw["alignment_angles"] = _numbers("[offaxis]", t, "alignment_angles_deg", 3,
                                          "list 3 angles", DEG)
    slope = _num(t.get("yaw_arcsec_per_100mm", 0.0), "[offaxis] yaw_arcsec_per_100mm") * ARCSEC / 0.1
    amp = _num(t.get("yaw_amplitude_arcsec", 0.0), "[offaxis] yaw_amplitude_arcsec") * ARCSEC
    period = _num(t.get("yaw_period_mm", 100.0), "[offaxis] yaw_period_mm", positive=True) * MM
    kw["linear_yaw"] = HarmonicSeries((Harmonic(amp, period),) if amp else (), (0.0, slope))
    kw["profile_moving_optic"] = str(t.get("yaw_profile_moving_optic", "interferometer"))
    kw["profile_direction_sign"] = _int(t, "yaw_profile_direction_sign", 1, "[offaxis]")
    sign = t.get("yaw_sign", "auto")
    if sign != "auto" and (isinstance(sign, bool) or sign not in (1, -1)):
        raise ConfigError(f"[offaxis] yaw_sign = {sign!r} must be \"auto\", 1 or -1")
    kw["stated_sign"] = None if sign == "auto" else int(sign)
    letter = str(t.get("linear_axis", "Y"))
    if not (len(letter) == 1 and letter.isalpha()):
        raise ConfigError(f"[offaxis] linear_axis = {letter!r} must be one axis letter")
    kw["linear_letter"] = letter.upper()
    if kw["profile_moving_optic"] not in ("interferometer", "reflector"):
        raise ConfigError(f"[offaxis] yaw_profile_moving_optic = {kw['profile_moving_optic']!r}: "
                          "use \"interferometer\" or \"reflector\"")
    return _make("[offaxis]", OffAxisSetup, kw)


def _table(config: dict[str, Any], name: str) -> dict[str, Any]:
    t = config.get(name, {})
    if not isinstance(t, dict):
        raise ConfigError(f"[{name}] must be a table, got {t!r}")
    return t


def _build(where: str, cls, t: dict[str, Any], table: dict[str, tuple[str, float]]):
    return _make(where, cls, _convert(where, t, table, set()))


#: Keys that are a noise, an rms or an error size (>= 0) or a distance or speed (> 0).
_NONNEGATIVE = {"dial_noise_mm", "shutter_noise_mm", "centring_noise_mm", "noise_arcsec",
                "resolution_arcsec", "graduation_error_rms_arcsec", "bearing_wander_um",
                "eccentricity_um", "map_uncertainty_arcsec", "alignment_noise_mm",
                "profile_noise_arcsec"}
_POSITIVE = {"tir_radius_mm", "laser_distance_m", "spacing_mm", "nominal_spacing_mm",
             "radius_mm", "interferometer_distance_mm", "feed_mm_min"}


def _convert(where: str, t: Any, table: dict[str, tuple[str, float]], extra: set[str]) -> dict:
    refuse_unknown_keys(where, t, set(table) | extra)
    out = {}
    for key, (name, k) in table.items():
        if key in t:
            v = _num(t[key], f"{where} {key}", positive=key in _POSITIVE)
            if key in _NONNEGATIVE and v < 0:
                raise ConfigError(f"{where} {key} = {t[key]!r} must be >= 0")
            out[name] = v * k
    return out


def _make(where: str, fn, kw: dict):
    try:
        return fn(**kw)
    except ConfigError:
        raise
    except (InputError, TypeError, ValueError) as exc:
        raise ConfigError(f"{where}: {exc}") from None



def _numbers(where: str, t: dict, key: str, n: int, shape: str, scale: float) -> tuple:
    """``t[key]``, a list of ``n`` finite numbers, each times ``scale`` (to SI)."""
    v = t[key]
    if not (isinstance(v, list) and len(v) == n):
        raise ConfigError(f"{where} {key} = {v!r} must {shape}")
    return tuple(_num(x, f"{where} {key}") * scale for x in v)


def _num(v: Any, where: str, positive: bool = False) -> float:
    from axiscal._schema import MAX_MAGNITUDE

    if isinstance(v, bool) or not isinstance(v, (int, float)) or not math.isfinite(v):
        raise ConfigError(f"{where} = {v!r} must be a finite number")
    if abs(v) > MAX_MAGNITUDE:   # no set-up comes near it; squaring it would overflow
        raise ConfigError(f"{where} = {v!r} is out of range (beyond ±{MAX_MAGNITUDE:g})")
    if positive and not v > 0:
        raise ConfigError(f"{where} = {v!r} must be positive")
    return float(v)


def _int(t: dict, key: str, default: int, where: str, lo: int | None = None) -> int:
    v = t.get(key, default)
    if isinstance(v, bool) or not isinstance(v, int) or (lo is not None and v < lo):
        raise ConfigError(f"{where} {key} = {v!r} must be a whole number"
                          + (f" >= {lo}" if lo is not None else ""))
    return v


def _bool(v: Any, where: str) -> bool:
    if not isinstance(v, bool):
        raise ConfigError(f"{where} = {v!r} must be true or false")
    return v
