"""Laser-scale configurations in TOML (``examples/scale_*.toml``).

:func:`parse_scale_config` reads the text into plain sections and refuses unknown sections or
keys (a misspelt key never silently falls back to a default); :func:`axis_from_config` and
:func:`twin_axis_from_config` build the simulation objects. Units are in the key names
(``_mm``, ``_um``, ``_khz`` ...). Sections and keys, all optional:

``[laser]``
    ``vacuum_wavelength_nm`` (632.991), ``counts_per_wavelength`` (1: 0.633 µm counts),
    ``dead_path_mm`` (0).
``[compensator]``
    ``period_um`` (20), ``counts_per_period`` (256), ``equation`` ("ciddor"), ``material``
    (a name from :data:`axiscal.physics.thermal.MATERIALS`, or "none") or
    ``expansion_coefficient`` (1/K), ``update_interval_s`` (1), ``co2`` (450 µmol/mol).
``[compensator] rephase_periods``
    Signal periods of real motion over which the rephasing spreads its virtual movement: 1 (the
    default, as Renishaw's application note describes), a whole number, or ``"auto"``: the
    fewest that keep the controller's inputs within their limit at the homing speed.
``[air]``
    The true conditions: ``temperature`` (°C), ``pressure`` (Pa), ``humidity`` (%RH),
    ``material_temperature`` (°C) and their rates per second ``temperature_rate``,
    ``pressure_rate``, ``humidity_rate``, ``material_rate``.
``[sensors]``
    Errors of the compensator's sensors: ``temperature_error`` (K), ``pressure_error`` (Pa),
    ``humidity_error`` (%RH), ``material_error`` (K).
``[switch]``
    ``position_mm`` (100), ``repeatability_um`` (0), ``direction`` ("+" or "-").
``[controller]``
    ``max_input_frequency_khz`` (100), ``frequency_gate_us`` (100), ``skew_limit_counts`` (300),
    ``offset_counts`` (0).
``[homing]``
    ``start_mm`` (40 µm before the switch), ``speed_mm_per_min`` (300), ``seed`` (random switch
    error and power-up phases; omit for none), ``power_up_phase`` (counts).
``[[move]]``
    Moves after homing: ``target_mm``, ``speed_mm_per_min`` (6000), ``acceleration`` (1 m/s²).
``[gantry]``
    Twin axis: ``switch_1_mm``, ``switch_2_mm``, ``start_1_mm``, ``start_2_mm``,
    ``switch_repeatability_um`` (0), ``direction``, ``seed``, ``power_up_phase_1``,
    ``power_up_phase_2``.
"""

from __future__ import annotations

from typing import Any

import numpy as np

from axiscal._schema import Free, Num, Schema, Text
from axiscal.errors import ConfigError
from axiscal.io._files import read_text

__all__ = ["parse_scale_config", "read_scale_config", "axis_from_config",
           "homing_from_config", "twin_axis_from_config", "compensator_from_config"]

#: Largest output counts per period taken: the simulation samples every count of the homing
#: (a billion counts per period would need 60 GiB; a gantry with millions never finishes).
MAX_COUNTS_PER_PERIOD = 4096
_MM = Num("mm", -1e6, 1e6)          # a machine coordinate: within 1 km
_SPEED = Num("mm/min", 0, 1e6, lo_open=True)
_DIRECTION = Text(("+", "-", "+1", "-1", "1", "positive", "negative"))
_SEED = Num("", 0, 2**63 - 1, integer=True)
_PHASE = Num("counts", 0, MAX_COUNTS_PER_PERIOD, integer=True)

#: Every table and key of a laser-scale configuration, with the unit written and its bounds.
SCHEMA = Schema({
    "laser": {"vacuum_wavelength_nm": Num("nm", 200, 2000),
              "counts_per_wavelength": Num("", 1, 64, integer=True),
              "dead_path_mm": Num("mm", 0, 100_000)},
    "compensator": {"period_um": Num("µm", 0, 1000, lo_open=True),
                    "counts_per_period": Num("", 1, MAX_COUNTS_PER_PERIOD, integer=True),
                    "equation": Text(("ciddor", "edlen", "birch-downs")), "material": Text(),
                    "expansion_coefficient": Num("1/K", -1e-3, 1e-3),
                    "update_interval_s": Num("s", 0, 3600, lo_open=True),
                    "co2": Num("µmol/mol", 0, 100_000),
                    "rephase_periods": Free()},   # a whole number or "auto": read below
    "air": {"temperature": Num("°C", -50, 100), "pressure": Num("Pa", 1000, 200_000),
            "humidity": Num("%RH", 0, 100), "material_temperature": Num("°C", -50, 200),
            "temperature_rate": Num("K/s", -1, 1), "pressure_rate": Num("Pa/s", -1000, 1000),
            "humidity_rate": Num("%RH/s", -10, 10), "material_rate": Num("K/s", -1, 1)},
    "sensors": {"temperature_error": Num("K", -10, 10), "pressure_error": Num("Pa", -10_000, 10_000),
                "humidity_error": Num("%RH", -100, 100), "material_error": Num("K", -10, 10)},
    "switch": {"position_mm": _MM, "repeatability_um": Num("µm", 0, 1000),
               "direction": _DIRECTION},
    "controller": {"max_input_frequency_khz": Num("kHz", 0, 1e6, lo_open=True),
                   "frequency_gate_us": Num("µs", 0, 1e6, lo_open=True),
                   "skew_limit_counts": Num("counts", 0, 10**9, integer=True),
                   "offset_counts": Num("counts", -10**9, 10**9, integer=True)},
    "homing": {"start_mm": _MM, "speed_mm_per_min": _SPEED, "seed": _SEED,
               "power_up_phase": _PHASE},
    "move": {"target_mm": Num("mm", -1e6, 1e6, required=True), "speed_mm_per_min": _SPEED,
             "acceleration": Num("m/s²", 0, 1000, lo_open=True)},
    "gantry": {"switch_1_mm": _MM, "switch_2_mm": _MM, "start_1_mm": _MM, "start_2_mm": _MM,
               "switch_repeatability_um": Num("µm", 0, 1000), "direction": _DIRECTION,
               "seed": _SEED, "power_up_phase_1": _PHASE, "power_up_phase_2": _PHASE},
}, arrays=("move",), example="examples/scale_single.toml")
_SCHEMA = {name: set(keys) for name, keys in SCHEMA.tables.items()}
#: The twin-axis command needs its [gantry] table.
GANTRY_SCHEMA = Schema(SCHEMA.tables, required=("gantry",), arrays=("move",),
                       example="examples/scale_gantry.toml")


def parse_scale_config(text: str, source: str = "<text>", schema: Schema = SCHEMA) -> dict[str, Any]:
    """Parse TOML text into sections: unknown tables and keys, values of the wrong type or beyond
    a physical set-up, and an empty file are refused by name (:class:`axiscal._schema.Schema`)."""
    data = schema.parse(text, source)
    data = {name: ([{k: v for k, v in t.items() if v is not None} for t in value]
                   if isinstance(value, list) else {k: v for k, v in value.items() if v is not None})
            for name, value in data.items()}
    data["_source"] = source
    return data


def read_scale_config(path, gantry: bool = False) -> dict[str, Any]:
    """Read a laser-scale configuration file (TOML); ``gantry`` requires the [gantry] table."""
    return parse_scale_config(read_text(path), str(path), GANTRY_SCHEMA if gantry else SCHEMA)


def compensator_from_config(cfg: dict[str, Any]):
    """The :class:`~axiscal.instruments.compensator.Compensator` of a configuration."""
    from axiscal.instruments.compensator import Compensator, SineOutput
    from axiscal.instruments.laser_scale import LaserHead
    from axiscal.physics.thermal import material

    las = cfg.get("laser", {})
    com = cfg.get("compensator", {})
    laser = LaserHead(
        vacuum_wavelength=_num(cfg, "laser", "vacuum_wavelength_nm", las, 632.991) * 1e-9,
        counts_per_wavelength=_int(cfg, "laser", "counts_per_wavelength", las, 1),
        dead_path=_num(cfg, "laser", "dead_path_mm", las, 0.0) * 1e-3)
    output = SineOutput(period=_num(cfg, "compensator", "period_um", com, 20.0) * 1e-6,
                        counts_per_period=_int(cfg, "compensator", "counts_per_period", com, 256))
    if "material" in com and "expansion_coefficient" in com:
        raise ConfigError(f"{cfg['_source']}: [compensator] gives both material and "
                          "expansion_coefficient; give one")
    alpha = 0.0
    if "expansion_coefficient" in com:
        alpha = _num(cfg, "compensator", "expansion_coefficient", com, 0.0)
    elif str(com.get("material", "none")).strip().lower() != "none":
        alpha = material(str(com["material"])).alpha
    return Compensator(
        laser=laser, output=output, equation=str(com.get("equation", "ciddor")),
        expansion_coefficient=alpha,
        update_interval=_num(cfg, "compensator", "update_interval_s", com, 1.0),
        co2=_num(cfg, "compensator", "co2", com, 450.0))


def axis_from_config(cfg: dict[str, Any]):
    """The :class:`~axiscal.procedures.referencing.ScaleAxis` of a configuration."""
    from axiscal.instruments.laser_scale import ReferenceSwitch
    from axiscal.procedures.referencing import AirHistory, ScaleAxis

    comp = compensator_from_config(cfg)
    air = cfg.get("air", {})
    sen = cfg.get("sensors", {})
    sw = cfg.get("switch", {})
    history = AirHistory(**{k: _num(cfg, "air", k, air, v) for k, v in (
        ("temperature", 20.0), ("pressure", 101325.0), ("humidity", 50.0),
        ("material_temperature", 20.0), ("temperature_rate", 0.0), ("pressure_rate", 0.0),
        ("humidity_rate", 0.0), ("material_rate", 0.0))})
    errors = tuple(_num(cfg, "sensors", k, sen, 0.0) for k in (
        "temperature_error", "pressure_error", "humidity_error", "material_error"))
    switch = ReferenceSwitch(position=_num(cfg, "switch", "position_mm", sw, 100.0) * 1e-3,
                             repeatability=_repeatability(cfg, "switch", sw) * 1e-6,
                             active_above=_direction(cfg, "switch", sw) > 0)
    controller = _controller(cfg, comp.output)
    comp = _rephase_periods(cfg, comp, controller)
    return ScaleAxis(laser=comp.laser, compensator=comp, switch=switch,
                     controller=controller, air=history,
                     sensor_error=errors)  # type: ignore[arg-type]


def _rephase_periods(cfg, comp, controller):
    """Apply ``[compensator] rephase_periods`` (a whole number or "auto")."""
    from dataclasses import replace

    from axiscal.errors import InputError
    from axiscal.instruments.compensator import rephase_periods_for

    value = cfg.get("compensator", {}).get("rephase_periods", 1)
    if isinstance(value, str) and value.strip().lower() == "auto":
        speed = _num(cfg, "homing", "speed_mm_per_min", cfg.get("homing", {}), 300.0) / 60e3
        try:
            k = rephase_periods_for(speed, comp.output, controller.max_input_frequency)
        except InputError as exc:
            raise ConfigError(f"{cfg['_source']}: [compensator] rephase_periods = \"auto\": "
                              f"{exc}") from None
    else:
        k = _int(cfg, "compensator", "rephase_periods", cfg.get("compensator", {}), 1)
    try:
        return replace(comp, rephase_periods=k)
    except InputError as exc:
        raise ConfigError(f"{cfg['_source']}: [compensator] {exc}") from None


def homing_from_config(cfg: dict[str, Any], axis) -> dict[str, Any]:
    """Keyword arguments of :func:`~axiscal.procedures.referencing.simulate_referencing`."""
    from axiscal.procedures.referencing import Move

    h = cfg.get("homing", {})
    d = axis.direction
    default_start = (axis.switch.position - d * 40e-6) * 1e3
    kwargs: dict[str, Any] = {
        "start": _num(cfg, "homing", "start_mm", h, default_start) * 1e-3,
        "homing_speed": _num(cfg, "homing", "speed_mm_per_min", h, 300.0) / 60e3,
    }
    _within_reach(cfg, "homing", "start_mm", kwargs["start"], axis.switch.position)
    _homing_counts(cfg, "homing", "start_mm", kwargs["start"], axis.switch.position,
                   axis.output.count_size)
    if "seed" in h:
        kwargs["rng"] = np.random.default_rng(_seed(cfg, "homing", h))
    if "power_up_phase" in h:
        kwargs["power_up_phase"] = _phase(cfg, "homing", "power_up_phase", h,
                                          axis.output.counts_per_period)
    moves = []
    for mv in cfg.get("move", []):
        if "target_mm" not in mv:
            raise ConfigError(f"{cfg['_source']}: a [[move]] needs target_mm")
        _within_reach(cfg, "move", "target_mm", _num(cfg, "move", "target_mm", mv, 0.0) * 1e-3,
                      axis.switch.position)
        moves.append(Move(target=_num(cfg, "move", "target_mm", mv, 0.0) * 1e-3,
                          speed=_num(cfg, "move", "speed_mm_per_min", mv, 6000.0) / 60e3,
                          acceleration=_num(cfg, "move", "acceleration", mv, 1.0)))
    kwargs["moves"] = tuple(moves)
    return kwargs


def twin_axis_from_config(cfg: dict[str, Any]):
    """A :class:`~axiscal.procedures.twin_axis.TwinAxis` and the run's keyword arguments
    (power-up phases and switch errors, drawn from ``seed`` where not given)."""
    from axiscal.procedures.twin_axis import TwinAxis

    comp = compensator_from_config(cfg)
    out = comp.output
    if cfg.get("compensator", {}).get("rephase_periods", 1) != 1:
        raise ConfigError(f"{cfg['_source']}: [compensator] rephase_periods is for single-axis "
                          "referencing; the gantry model rephases over one period (remove it)")
    g = cfg.get("gantry", {})
    q = out.count_size
    d = _direction(cfg, "gantry", g)

    def counts(key, default_mm):
        mm = _num(cfg, "gantry", key, g, default_mm)
        if abs(mm) > MAX_POSITION_MM:   # beyond any machine (and beyond a float of counts)
            raise ConfigError(f"{cfg['_source']}: [gantry] {key} = {mm:g} mm lies beyond "
                              f"±{MAX_POSITION_MM:g} mm")
        return int(round(mm * 1e-3 / q))

    s1 = counts("switch_1_mm", 100.0)
    s2 = counts("switch_2_mm", 100.0)
    starts = []
    for i, s in ((1, s1), (2, s2)):
        starts.append(counts(f"start_{i}_mm", (s - d * 512) * q * 1e3))
        _within_reach(cfg, "gantry", f"start_{i}_mm", starts[-1] * q, s * q)
        _homing_counts(cfg, "gantry", f"start_{i}_mm", starts[-1] * q, s * q, q)
    gantry = TwinAxis(output=out, controller=_controller(cfg, out), switch_1=s1, switch_2=s2,
                      start_1=starts[0], start_2=starts[1], direction=d)
    rng = np.random.default_rng(_seed(cfg, "gantry", g)) if "seed" in g else None
    sigma = _repeatability(cfg, "gantry", g, "switch_repeatability_um") * 1e-6 / q
    run: dict[str, Any] = {}
    for i in (1, 2):
        key = f"power_up_phase_{i}"
        if key in g:
            run[key] = _phase(cfg, "gantry", key, g, out.counts_per_period)
        elif rng is not None:
            run[key] = int(rng.integers(out.counts_per_period))
        if rng is not None and sigma > 0:
            run[f"switch_error_{i}"] = int(round(rng.normal(0.0, sigma)))
    return gantry, run, sigma


# -- helpers ------------------------------------------------------------------------------
def _controller(cfg, out):
    from axiscal.instruments.controller import Controller

    c = cfg.get("controller", {})
    return Controller(
        counts_per_period=out.counts_per_period, count_size=out.count_size,
        max_input_frequency=_num(cfg, "controller", "max_input_frequency_khz", c, 100.0) * 1e3,
        frequency_gate=_num(cfg, "controller", "frequency_gate_us", c, 100.0) * 1e-6,
        skew_limit=_int(cfg, "controller", "skew_limit_counts", c, 300),
        offset=_int(cfg, "controller", "offset_counts", c, 0))


def _num(cfg, section, key, table, default) -> float:
    v = table.get(key, default)
    if isinstance(v, bool) or not isinstance(v, (int, float)) or not np.isfinite(v):
        raise ConfigError(f"{cfg['_source']}: [{section}] {key} = {v!r} must be a number")
    return float(v)


def _int(cfg, section, key, table, default) -> int:
    v = table.get(key, default)
    if isinstance(v, bool) or not isinstance(v, int):
        raise ConfigError(f"{cfg['_source']}: [{section}] {key} = {v!r} must be a whole number")
    return int(v)


#: Longest distance a move may go from the switch (a 5 m move at 4096 counts a period takes 0.5 GB;
#: the homing approach has its own, tighter bound in counts: MAX_HOMING_COUNTS).
MAX_REACH_MM = 5000.0
#: Largest machine coordinate taken: 1 km.
MAX_POSITION_MM = 1e6
#: Largest switch repeatability taken as one (a reference switch repeats within micrometres).
MAX_REPEATABILITY_UM = 1000.0


def _seed(cfg, section, table) -> int:
    v = _int(cfg, section, "seed", table, 0)
    if v < 0:
        raise ConfigError(f"{cfg['_source']}: [{section}] seed = {v} must be >= 0")
    return v


def _phase(cfg, section, key, table, counts_per_period: int) -> int:
    v = _int(cfg, section, key, table, 0)
    if not 0 <= v < counts_per_period:
        raise ConfigError(f"{cfg['_source']}: [{section}] {key} = {v} counts must lie in 0 to "
                          f"{counts_per_period - 1} (one output period)")
    return v


def _repeatability(cfg, section, table, key="repeatability_um") -> float:
    v = _num(cfg, section, key, table, 0.0)
    if not 0 <= v <= MAX_REPEATABILITY_UM:
        raise ConfigError(f"{cfg['_source']}: [{section}] {key} = {v:g} µm must lie in 0 to "
                          f"{MAX_REPEATABILITY_UM:g} µm")
    return v


def _within_reach(cfg, section, key, position_m: float, switch_m: float) -> None:
    if abs(position_m - switch_m) * 1e3 > MAX_REACH_MM:
        raise ConfigError(f"{cfg['_source']}: [{section}] {key} = {position_m * 1e3:g} mm is more "
                          f"than {MAX_REACH_MM:g} mm from the switch at {switch_m * 1e3:g} mm; the "
                          "simulation follows every count and stops there")


#: Most output counts a homing approach may cover before the switch: the referencing simulation
#: follows every count of it (1.28 million, 100 mm at 256 counts of 78 nm, take 0.5 GB and 2 s;
#: a start 5 m away took 19 GB). A real axis starts its homing a few millimetres before the switch.
MAX_HOMING_COUNTS = 1_500_000


def _homing_counts(cfg, section, key, start_m: float, switch_m: float, count_m: float) -> None:
    counts = abs(start_m - switch_m) / count_m
    if counts > MAX_HOMING_COUNTS:
        raise ConfigError(f"{cfg['_source']}: [{section}] {key} = {start_m * 1e3:g} mm is "
                          f"{counts:.3g} output counts ({count_m * 1e9:.3g} nm each) before the "
                          f"switch at {switch_m * 1e3:g} mm; the homing simulation follows every "
                          f"count, at most {MAX_HOMING_COUNTS:g} (start within "
                          f"{MAX_HOMING_COUNTS * count_m * 1e3:.3g} mm of the switch)")


def _direction(cfg, section, table) -> int:
    v = str(table.get("direction", "+")).strip()
    if v in ("+", "+1", "1", "positive"):
        return 1
    if v in ("-", "-1", "negative"):
        return -1
    raise ConfigError(f"{cfg['_source']}: [{section}] direction = {v!r} must be '+' or '-'")
