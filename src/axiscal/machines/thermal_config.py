"""The thermal twin from a configuration (TOML), in the units people write.

::

    [room]
    mean_C = 20.0
    daily_amplitude_K = 1.0       # half the peak-to-peak of the daily cycle
    period_h = 24.0
    peak_h = 15.0                 # the warmest hour after the start
    ramp_K_per_h = 0.0

    [[node]]                      # in order: a node follows the room or an earlier node
    name = "spindle"
    time_constant_min = 30
    follows = "structure"
    heat = "spindle"              # none | spindle | rotary | axis:X
    rise_K = 12.0                 # steady rise at full load
    x_um_per_K = 0.2              # also y_um_per_K, z_um_per_K, a_urad_per_K, b_urad_per_K

    [[axis]]
    name = "X"
    travel_mm = [0, 800]
    screw_node = "screw_x"
    alpha_ppm_per_K = 11.5
    fixed_end_mm = 0
    offset_um_per_K = 0.3

    [[sensor]]
    name = "T_spindle"
    node = "spindle"
    noise_K = 0.02
    offset_K = 0.0
    lag_min = 0                   # the sensor sees its node through a first-order lag

    [instruments]
    displacement_noise_um = 0.1   # each displacement sensor and the laser's reading
    mandrel_spacing_mm = 100      # spindle (rotary) test: X1/X2 and Y1/Y2 apart along the
                                  # mandrel (the artefact on the table)
    spindle_max_rpm = 12000

The shipped examples are ``axiscal/data/thermal_vmc.toml`` and, with a rotary table (ISO 230-3
Clause 8), ``axiscal/data/thermal_rotary_table.toml``. Unknown tables and keys are refused
with the file and line (:mod:`axiscal._schema`).
"""

from __future__ import annotations

from typing import Any

from axiscal.errors import ConfigError, one_line
from axiscal.machines.thermal import (Room, TemperatureSensor, ThermalAxis, ThermalNode,
                                      ThermalTwin)

__all__ = ["schema", "parse_thermal_config", "twin_from_config"]


def schema():
    """The configuration's keys, units and bounds."""
    from axiscal._schema import Free, Num, Schema, Text

    sens = {k: Num(u, -1e4, 1e4, default=0.0) for k, u in
            (("x_um_per_K", "µm/K"), ("y_um_per_K", "µm/K"), ("z_um_per_K", "µm/K"),
             ("a_urad_per_K", "µrad/K"), ("b_urad_per_K", "µrad/K"))}
    return Schema({
        "room": {"mean_C": Num("°C", -10, 50, default=20.0),
                 "daily_amplitude_K": Num("K", 0, 20, default=0.0),
                 "period_h": Num("h", 0, 1000, lo_open=True, default=24.0),
                 "peak_h": Num("h", -1000, 1000, default=15.0),
                 "ramp_K_per_h": Num("K/h", -5, 5, default=0.0)},
        "node": {"name": Text(required=True),
                 "time_constant_min": Num("min", 0, 1e5, lo_open=True, required=True),
                 "follows": Text(default="room"), "heat": Text(default="none"),
                 "rise_K": Num("K", -100, 100, default=0.0), **sens},
        "axis": {"name": Text(required=True), "travel_mm": Free(required=True),
                 "screw_node": Text(required=True),
                 "alpha_ppm_per_K": Num("ppm/K", -100, 100, default=11.5),
                 "fixed_end_mm": Num("mm", -1e5, 1e5, default=0.0),
                 "offset_um_per_K": Num("µm/K", -1e4, 1e4, default=0.0)},
        "sensor": {"name": Text(required=True), "node": Text(required=True),
                   "noise_K": Num("K", 0, 10, default=0.0),
                   "offset_K": Num("K", -10, 10, default=0.0),
                   "lag_min": Num("min", 0, 1e4, default=0.0)},
        "instruments": {"displacement_noise_um": Num("µm", 0, 100, default=0.0),
                        "mandrel_spacing_mm": Num("mm", 0, 2000, lo_open=True, default=100.0),
                        "spindle_max_rpm": Num("1/min", 0, 1e6, lo_open=True, default=12000.0)},
    }, required=("node",), arrays=("node", "axis", "sensor"),
        example="src/axiscal/data/thermal_vmc.toml")


def parse_thermal_config(text: str, source: str = "<text>") -> ThermalTwin:
    """Check a twin's TOML text and build the :class:`~axiscal.machines.thermal.ThermalTwin`.

    Examples
    --------
    >>> twin = parse_thermal_config('''
    ... [[node]]
    ... name = "spindle"
    ... time_constant_min = 30
    ... heat = "spindle"
    ... rise_K = 10
    ... z_um_per_K = -2
    ... ''')
    >>> twin.nodes[0].time_constant, twin.nodes[0].sensitivity[2]
    (1800.0, -2e-06)
    """
    return twin_from_config(schema().parse(text, source), source)


def twin_from_config(cfg: dict[str, Any], source: str = "<config>") -> ThermalTwin:
    """The twin from checked tables (what :func:`parse_thermal_config` parsed)."""
    from axiscal.errors import InputError

    r = cfg["room"]
    room = Room(mean=r["mean_C"], amplitude=r["daily_amplitude_K"], period=r["period_h"] * 3600,
                peak_time=r["peak_h"] * 3600, ramp=r["ramp_K_per_h"] / 3600)
    nodes = tuple(ThermalNode(
        name=n["name"], time_constant=n["time_constant_min"] * 60, follows=n["follows"],
        heat=n["heat"], rise=n["rise_K"],
        sensitivity=(n["x_um_per_K"] * 1e-6, n["y_um_per_K"] * 1e-6, n["z_um_per_K"] * 1e-6,
                     n["a_urad_per_K"] * 1e-6, n["b_urad_per_K"] * 1e-6)) for n in cfg["node"])
    axes = tuple(ThermalAxis(name=a["name"], travel=_travel(a["travel_mm"], source),
                             screw_node=a["screw_node"], alpha=a["alpha_ppm_per_K"] * 1e-6,
                             fixed_end=a["fixed_end_mm"] * 1e-3,
                             offset=a["offset_um_per_K"] * 1e-6) for a in cfg["axis"])
    sensors = tuple(TemperatureSensor(s["name"], s["node"], s["noise_K"], s["offset_K"],
                                      s["lag_min"] * 60) for s in cfg["sensor"])
    names = [s.name for s in sensors]
    if len(set(names)) != len(names):
        raise ConfigError(f"{source}: two [[sensor]] tables share a name")
    i = cfg["instruments"]
    try:
        return ThermalTwin(room=room, nodes=nodes, axes=axes, sensors=sensors,
                           displacement_noise=i["displacement_noise_um"] * 1e-6,
                           meta={"mandrel_spacing": i["mandrel_spacing_mm"] * 1e-3,
                                 "spindle_max_rpm": i["spindle_max_rpm"]})
    except InputError as exc:
        raise ConfigError(f"{source}: {exc}") from None


def _travel(v: Any, source: str) -> tuple[float, float]:
    ok = (isinstance(v, list) and len(v) == 2
          and all(isinstance(x, (int, float)) and not isinstance(x, bool) and abs(x) < 1e6
                  for x in v) and v[1] > v[0])
    if not ok:
        raise ConfigError(f"{source}: [[axis]] travel_mm = {one_line(repr(v), 60)} must be [low, high] in mm, "
                          "low < high")
    return float(v[0]) * 1e-3, float(v[1]) * 1e-3
