"""Five-axis location-error identification benchmark (issue 43).

200 probed poses (five touches each: 1000 points) of a sphere on an A/C table-table twin:
sphere fits and the least-squares identification with its uncertainty (aim: under 1 s), beside
a floor measured in the same run: one dense least-squares solve of the same size as the final
weighted system (600 × 11), the least work any identification of it must do.
"""

from __future__ import annotations

import tomllib
from importlib import resources

import numpy as np

from axiscal.machines.five_axis import five_axis_from_config
from axiscal.procedures.five_axis import measure, plan_from_config
from axiscal.standards.location_errors import identify_location_errors

from _timing import best_of


def run() -> list[dict]:
    cfg = tomllib.loads(resources.files("axiscal.data").joinpath("fiveaxis_ac.toml")
                        .read_text("utf-8"))
    cfg["setup"] = [{"kind": "probing", "place_mm": [150, 20, 60],
                     "A_deg": [0, -22.5, -45, -67.5, -90], "C_deg": list(range(0, 360, 9))}]
    m = five_axis_from_config(cfg)
    recs = measure(m, plan_from_config(cfg, m), np.random.default_rng(0))
    t = best_of(lambda: identify_location_errors(m.geometry, [r.setup() for r in recs]), 3)
    fits = best_of(lambda: [r.setup() for r in recs], 3)
    A = np.random.default_rng(1).normal(size=(600, 11))
    b = A[:, 0]
    ref = best_of(lambda: np.linalg.lstsq(A, b, rcond=None), 20)
    return [dict(name="five-axis identification, 200 probed poses (time / one 600×11 lstsq)",
                 value=t, unit="s", reference=f"lstsq {ref * 1e3:.2f} ms; sphere fits alone "
                 f"{fits * 1e3:.0f} ms", ratio=t / ref, aim="< 1 s")]
