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

_SECTIONS = {
    "machine": {"squareness_um_per_m", "scale_x_um_per_m", "scale_y_um_per_m", "backlash_x_um",
                "backlash_y_um", "lateral_play_x_um", "lateral_play_y_um", "cyclic_x_um",
                "cyclic_x_pitch_mm", "cyclic_y_um", "cyclic_y_pitch_mm"},
    "servo": {"kv_x_per_s", "kv_y_per_s", "reversal_gap_x_um", "reversal_gap_y_um"},
    "ballbar": {"length_mm", "calibration_error_um", "alpha_per_K", "temperature_delta_K",
                "noise_um", "sample_rate_hz"},
    "test": {"feed_mm_per_min", "arc_deg", "start_deg", "plane"},
}


def simulate(
    config: Path = typer.Argument(..., help="TOML file (sections machine, servo, ballbar, test)."),
    out: Optional[Path] = typer.Option(None, "--out", help="Write the trace CSV here."),
    seed: int = typer.Option(0, "--seed", help="Seed of the noise."),
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

    feed = test.get("feed_mm_per_min", 1000.0) / 6e4
    runs = simulate_ballbar(plane, bar, feed, arc_deg=test.get("arc_deg", 360.0),
                            start_deg=test.get("start_deg", 0.0), rng=np.random.default_rng(seed))
    axes = str(test.get("plane", "XY")).upper()
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
             f"{cfg})")


def _load(path: Path) -> dict:

    from axiscal.errors import InputError

    from axiscal._schema import refuse_unknown
    from axiscal.io._files import load_toml

    cfg = load_toml(path)
    refuse_unknown(cfg, set(_SECTIONS))
    for sec, keys in cfg.items():
        refuse_unknown(keys, _SECTIONS[sec], f"[{sec}]")
        for k, v in keys.items():
            if k != "plane" and not isinstance(v, (int, float)):
                raise InputError(f"{path}: [{sec}] {k} = {v!r} must be a number")
    return cfg


def _build(cfg: dict):
    from axiscal.instruments.ballbar import Ballbar
    from axiscal.machines.servo_plane import ServoPlane
    from axiscal.machines.xy_plane import XYPlaneMachine

    m, s, b = cfg.get("machine", {}), cfg.get("servo", {}), cfg.get("ballbar", {})
    um = (lambda d, k, dflt=0.0: d.get(k, dflt) * 1e-6)
    length = b.get("length_mm", 100.0) * 1e-3
    machine = XYPlaneMachine(length_x=4 * length, length_y=4 * length,
                             squareness=um(m, "squareness_um_per_m"),
                             scale_x=um(m, "scale_x_um_per_m"), scale_y=um(m, "scale_y_um_per_m"),
                             backlash_x=um(m, "backlash_x_um"), backlash_y=um(m, "backlash_y_um"))
    plane = ServoPlane(machine, kv_x=s.get("kv_x_per_s", 40.0), kv_y=s.get("kv_y_per_s", 40.0),
                       gap_x=um(s, "reversal_gap_x_um"), gap_y=um(s, "reversal_gap_y_um"),
                       lateral_x=um(m, "lateral_play_x_um"), lateral_y=um(m, "lateral_play_y_um"),
                       cyclic_x=(um(m, "cyclic_x_um"), m.get("cyclic_x_pitch_mm", 5.0) * 1e-3),
                       cyclic_y=(um(m, "cyclic_y_um"), m.get("cyclic_y_pitch_mm", 5.0) * 1e-3))
    bar = Ballbar(length=length, calibration_error=um(b, "calibration_error_um"),
                  alpha=b.get("alpha_per_K", 11.5e-6),
                  temperature_delta=b.get("temperature_delta_K", 0.0),
                  noise=um(b, "noise_um"), sample_rate=b.get("sample_rate_hz", 250.0))
    return plane, bar, cfg.get("test", {})
