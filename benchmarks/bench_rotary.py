"""Speed of a full simulated rotary calibration (issue 4).

A 360° test with 72 targets (73 with 360°) × 5 runs × 2 directions: set-up checks, optics
self-calibration, the counter-rotating capture through the full optical and encoder chain, and
the ISO 230-2 evaluation of the measured and of the true deviations. Aim: under one second.
The reference, timed in the same run, is the plain positioning executor
(``simulate_positioning_test`` + ``evaluate``) on the same plan and axis, which has no instrument
model. Best of five runs. Run alone with ``python benchmarks/run.py bench_rotary``.
"""

from __future__ import annotations

import tomllib
from pathlib import Path

import numpy as np

from _timing import best_of

EXAMPLE = Path(__file__).resolve().parents[1] / "examples" / "rotary_turntable.toml"




def run() -> list[dict]:
    from axiscal.procedures.positioning import simulate_positioning_test
    from axiscal.procedures.rotary_config import rotary_config_from_dict
    from axiscal.procedures.rotary_calibration import simulate_rotary_calibration
    from axiscal.standards.iso230_2 import evaluate

    cfg = tomllib.loads(EXAMPLE.read_text())
    cfg["test"]["step_deg"] = 5.0
    c = rotary_config_from_dict(cfg)
    n = c.plan.n_measurements

    def full():
        return simulate_rotary_calibration(c.axis, c.plan, c.setup, c.laser, c.calibrator,
                                           np.random.default_rng(c.seed), c.speed, c.offaxis)

    def plain():
        return evaluate(simulate_positioning_test(c.plan, c.axis, np.random.default_rng(1)))

    t_full = best_of(full)
    t_plain = best_of(plain)
    t_build = best_of(lambda: rotary_config_from_dict(cfg))
    return [
        dict(name=f"rotary calibration, {c.plan.targets.size} targets x 5 runs x 2 ({n} readings)",
             value=t_full, unit="s", reference=f"1 s aim; plain positioning executor {t_plain * 1e3:.1f} ms",
             ratio=t_full / 1.0, aim="< 1 s (ratio to 1 s < 1)"),
        dict(name="rotary calibration vs plain positioning executor", value=t_full / t_plain,
             unit="x", reference=f"simulate_positioning_test + evaluate, {t_plain * 1e3:.1f} ms",
             ratio=t_full / t_plain, aim="informative: cost of the instrument chain"),
        dict(name="readings per second through the full chain", value=n / t_full, unit="readings/s"),
        dict(name="building the configuration (calibrator + error map)", value=t_build * 1e3,
             unit="ms"),
    ]
