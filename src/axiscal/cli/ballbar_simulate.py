"""``axiscal ballbar simulate CONFIG.toml``: a simulated ballbar test in the analyze format.

Config (all keys optional; units in the key names)::

    [machine]   squareness_um_per_m, scale_x_um_per_m, scale_y_um_per_m, backlash_x_um,
                backlash_y_um, lateral_play_x_um, lateral_play_y_um, cyclic_x_um,
                cyclic_x_pitch_mm, cyclic_y_um, cyclic_y_pitch_mm
    [servo]     kv_x_per_s, kv_y_per_s, reversal_gap_x_um, reversal_gap_y_um
    [ballbar]   length_mm, calibration_error_um, alpha_per_K, temperature_delta_K, noise_um,
                sample_rate_hz
    [test]      feed_mm_per_min, arc_deg, start_deg, plane
"""

from __future__ import annotations

from pathlib import Path
from typing import Optional

import typer

from axiscal.cli._common import note, out_path, print_json

def _schema():
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



def simulate(
    config: Path = typer.Argument(..., help="TOML file (sections machine, servo, ballbar, test)."),
    out: Optional[Path] = typer.Option(None, "--out", help="Write the trace CSV here."),
    seed: int = typer.Option(0, "--seed", min=0, help="Seed of the noise, a whole number >= 0."),
    json_out: bool = typer.Option(False, "--json", help="Print the truth and file as JSON."),
) -> None:
    """Simulate a CW + CCW ballbar test (servo dynamics, ballbar instrument) as analyze reads it.

    Example: axiscal ballbar simulate examples/ballbar_sim.toml --out trace.csv --seed 1
    """
    import numpy as np

    from axiscal.io.ballbar import BallbarData, format_ballbar

    if out is not None:
        out_path(out, "trace")
    cfg = _load(config)
    plane, bar, test = _build(cfg)
    from axiscal.procedures.ballbar import simulate_ballbar

    feed = test["feed_mm_per_min"] / 6e4
    runs = simulate_ballbar(plane, bar, feed, arc_deg=test["arc_deg"],
                            start_deg=test["start_deg"], rng=np.random.default_rng(seed))
    axes = str(test["plane"]).upper()
    data = BallbarData(bar.length, runs, (axes[0], axes[1]), str(config), feed)
    text = format_ballbar(data)
    if out is not None:
        from axiscal.io._files import write_text_atomic

        write_text_atomic(out, text)
    if json_out:
        print_json({"config": str(config), "out": None if out is None else str(out),
                    "seed": seed, "truth": cfg, "samples_per_run": len(runs[0].angles)})
        return
    if out is None:
        typer.echo(text, nl=False)
    else:
        note(f"wrote {out} ({len(runs[0].angles)} samples per direction; simulation truth: "
             f"{_truth_text({**cfg['machine'], **cfg['servo']}, (axes[0], axes[1]))})")


def _truth_text(truth: dict, axes) -> str:
    """The simulated machine's errors and servo as the reports name them (``Backlash X 5.00
    µm``), not as the configuration's keys (``--json`` gives those)."""
    from axiscal.report.labels import fmt, quantity

    parts = (quantity(k, axes=axes) for k in truth)
    return ", ".join(f"{name} {fmt(v, unit)} {unit}".rstrip()
                     for (name, unit), v in zip(parts, truth.values()))


def _load(path: Path) -> dict:
    import math

    from axiscal.errors import ConfigError
    from axiscal.io._files import read_text
    # at most what `ballbar analyze` reads (a 100 mm ballbar at 1000 mm/min, 250 Hz: 9,424)
    from axiscal.io.ballbar import MAX_SAMPLES_PER_RUN as MAX_SAMPLES

    cfg = _schema().parse(read_text(path), str(path))
    b, t = cfg["ballbar"], cfg["test"]
    path_mm = 2 * math.pi * b["length_mm"] * t["arc_deg"] / 360
    samples = b["sample_rate_hz"] * path_mm / t["feed_mm_per_min"] * 60
    if samples > MAX_SAMPLES:
        raise ConfigError(f"{path}: [test] feed_mm_per_min = {t['feed_mm_per_min']:g} with "
                          f"[ballbar] sample_rate_hz = {b['sample_rate_hz']:g} would simulate "
                          f"{samples:.3g} samples per direction; at most {MAX_SAMPLES:g} (raise "
                          "the feed or lower the sample rate)")
    return cfg


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
