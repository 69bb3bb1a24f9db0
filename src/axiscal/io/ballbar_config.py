"""The configuration of a simulated ballbar test (``axiscal ballbar simulate CONFIG.toml``).

Config (all keys optional; units in the key names)::

    [machine]   squareness_um_per_m, scale_x_um_per_m, scale_y_um_per_m, backlash_x_um,
                backlash_y_um, lateral_play_x_um, lateral_play_y_um, cyclic_x_um,
                cyclic_x_pitch_mm, cyclic_y_um, cyclic_y_pitch_mm
    [servo]     kv_x_per_s, kv_y_per_s, reversal_gap_x_um, reversal_gap_y_um
    [ballbar]   length_mm, calibration_error_um, alpha_per_K, temperature_delta_K, noise_um,
                sample_rate_hz
    [test]      feed_mm_per_min, arc_deg, start_deg, plane

The machine's errors are those of the circular test of ISO 230-4:2005 and of Chapman,
"Calibration of machine squareness", Method 4 (the ballbar); :func:`simulate_configured`
runs :func:`axiscal.procedures.ballbar.simulate_ballbar` on them.
"""

from __future__ import annotations

import math
from typing import Any

__all__ = ["schema", "parse_ballbar_config", "read_ballbar_config", "simulate_configured"]


def schema():
    """The configuration's keys, units and the bounds a ballbar test can have."""
    from axiscal._schema import Num, Schema, Text

    um = (lambda lim, d=0.0: Num("µm", -lim, lim, default=d))
    return Schema({
        "machine": {"squareness_um_per_m": Num("µm/m", -1e4, 1e4, default=0.0),
                    "scale_x_um_per_m": Num("µm/m", -1e4, 1e4, default=0.0),
                    "scale_y_um_per_m": Num("µm/m", -1e4, 1e4, default=0.0),
                    "backlash_x_um": um(1000), "backlash_y_um": um(1000),
                    "lateral_play_x_um": um(1000), "lateral_play_y_um": um(1000),
                    "cyclic_x_um": um(1000), "cyclic_y_um": um(1000),
                    "cyclic_x_pitch_mm": Num("mm", 0, 1000, lo_open=True, default=5.0),
                    "cyclic_y_pitch_mm": Num("mm", 0, 1000, lo_open=True, default=5.0)},
        "servo": {"kv_x_per_s": Num("1/s", 0, 1000, lo_open=True, default=40.0),
                  "kv_y_per_s": Num("1/s", 0, 1000, lo_open=True, default=40.0),
                  "reversal_gap_x_um": um(1000), "reversal_gap_y_um": um(1000)},
        "ballbar": {"length_mm": Num("mm", 10, 2000, default=100.0),
                    "calibration_error_um": um(1000),
                    "alpha_per_K": Num("1/K", -1e-4, 1e-4, default=11.5e-6),
                    "temperature_delta_K": Num("K", -50, 50, default=0.0),
                    "noise_um": Num("µm", 0, 100, default=0.0),
                    "sample_rate_hz": Num("Hz", 0, 1e5, lo_open=True, default=250.0)},
        "test": {"feed_mm_per_min": Num("mm/min", 0, 1e5, lo_open=True, default=1000.0),
                 "arc_deg": Num("deg", 0, 360, lo_open=True, default=360.0),
                 "start_deg": Num("deg", -360, 360, default=0.0),
                 "plane": Text(("XY", "YZ", "ZX", "XZ", "YX", "ZY"), default="XY")},
    }, example="examples/ballbar_sim.toml")


def parse_ballbar_config(text: str, source: str = "<text>") -> dict[str, Any]:
    """Check a configuration's TOML text; each table with its values (defaults filled in).
    A test that would sample more than ``ballbar analyze`` reads is refused."""
    from axiscal.errors import ConfigError
    # at most what `ballbar analyze` reads (a 100 mm ballbar at 1000 mm/min, 250 Hz: 9,424)
    from axiscal.io.ballbar import MAX_SAMPLES_PER_RUN as MAX_SAMPLES

    cfg = schema().parse(text, source)
    b, t = cfg["ballbar"], cfg["test"]
    path_mm = 2 * math.pi * b["length_mm"] * t["arc_deg"] / 360
    samples = b["sample_rate_hz"] * path_mm / t["feed_mm_per_min"] * 60
    if samples > MAX_SAMPLES:
        raise ConfigError(f"{source}: [test] feed_mm_per_min = {t['feed_mm_per_min']:g} with "
                          f"[ballbar] sample_rate_hz = {b['sample_rate_hz']:g} would simulate "
                          f"{samples:.3g} samples per direction; at most {MAX_SAMPLES:g} (raise "
                          "the feed or lower the sample rate)")
    return cfg


def read_ballbar_config(path: Any) -> dict[str, Any]:
    """Read a ballbar configuration file (see :func:`parse_ballbar_config`)."""
    from axiscal.io._files import read_text

    return parse_ballbar_config(read_text(path), str(path))


def simulate_configured(cfg: dict[str, Any], seed: int, source: str) -> Any:
    """A CW + CCW test of the configured machine, servo and ballbar (the noise seeded by
    ``seed``), as the :class:`axiscal.io.ballbar.BallbarData` ``ballbar analyze`` reads."""
    import numpy as np

    from axiscal.io.ballbar import BallbarData
    from axiscal.procedures.ballbar import simulate_ballbar

    plane, bar, test = _build(cfg)
    feed = test["feed_mm_per_min"] / 6e4
    runs = simulate_ballbar(plane, bar, feed, arc_deg=test["arc_deg"],
                            start_deg=test["start_deg"], rng=np.random.default_rng(seed))
    axes = str(test["plane"]).upper()
    return BallbarData(bar.length, runs, (axes[0], axes[1]), source, feed)


def _build(cfg: dict):
    from axiscal.instruments.ballbar import Ballbar
    from axiscal.machines.servo_plane import ServoPlane
    from axiscal.machines.xy_plane import XYPlaneMachine

    m, s, b = cfg["machine"], cfg["servo"], cfg["ballbar"]
    um = (lambda d, k: d[k] * 1e-6)
    length = b["length_mm"] * 1e-3
    machine = XYPlaneMachine(length_x=4 * length, length_y=4 * length,
                             squareness=um(m, "squareness_um_per_m"),
                             scale_x=um(m, "scale_x_um_per_m"), scale_y=um(m, "scale_y_um_per_m"),
                             backlash_x=um(m, "backlash_x_um"), backlash_y=um(m, "backlash_y_um"))
    plane = ServoPlane(machine, kv_x=s["kv_x_per_s"], kv_y=s["kv_y_per_s"],
                       gap_x=um(s, "reversal_gap_x_um"), gap_y=um(s, "reversal_gap_y_um"),
                       lateral_x=um(m, "lateral_play_x_um"), lateral_y=um(m, "lateral_play_y_um"),
                       cyclic_x=(um(m, "cyclic_x_um"), m["cyclic_x_pitch_mm"] * 1e-3),
                       cyclic_y=(um(m, "cyclic_y_um"), m["cyclic_y_pitch_mm"] * 1e-3))
    bar = Ballbar(length=length, calibration_error=um(b, "calibration_error_um"),
                  alpha=b["alpha_per_K"], temperature_delta=b["temperature_delta_K"],
                  noise=um(b, "noise_um"), sample_rate=b["sample_rate_hz"])
    return plane, bar, cfg["test"]
