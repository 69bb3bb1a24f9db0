"""Compensation tables: generation, writing each controller format, and the whole loop.

Rows (see ``benchmarks/run.py``):

* table generation: points per second of :func:`table_from_result` for a 4001-point table from a
  201-target result; reference: ``numpy.interp`` of the same points (the arithmetic core), ratio
  = reference time / our time (how close the whole function gets to the bare interpolation);
* writing: points per second of each controller writer at 4001 points (256 for the formats that
  allow no more); reference: formatting the same numbers with one f-string per point, ratio =
  reference time / writer time;
* the loop: seconds per ``run_compensation_loop`` of ``examples/compensation_linear.toml``;
  reference: one simulated ISO 230-2 test plus its evaluation of the same configuration, ratio =
  loop time / test time (the loop runs two tests, so about 2 is the floor).
"""

from __future__ import annotations

import tomllib
from pathlib import Path

import numpy as np

from axiscal.compensation.controllers import CONTROLLERS, controller
from axiscal.compensation.loop import run_compensation_loop
from axiscal.compensation.tables import table_from_result
from axiscal.datasets import PositioningDataset
from axiscal.procedures.positioning import simulate_from_config
from axiscal.standards.iso230_2 import evaluate

from _timing import best_of

ROOT = Path(__file__).resolve().parents[1]




def _result(m=201):
    rng = np.random.default_rng(0)
    t = np.linspace(0, 1000, m)
    base = 5 * np.sin(t / 80)[:, None]
    ds = PositioningDataset.from_arrays("linear", t, up=base + rng.normal(0, 0.3, (m, 5)) + 1,
                                        down=base + rng.normal(0, 0.3, (m, 5)) - 1)
    return evaluate(ds)


def run() -> list[dict]:
    rows = []
    res = _result()
    spacing = 0.25                                  # 4001 points over 1000 mm
    t_ours = best_of(lambda: table_from_result(res, spacing, bidirectional=True, resolution=0.1), number=20)
    x = np.arange(4001) * spacing
    t_ref = best_of(lambda: (np.interp(x, res.targets, res.mean_up), np.interp(x, res.targets, res.mean_down)),
                  number=200)
    rows.append(dict(name="table_from_result, 4001-point bidirectional table", value=4001 / t_ours,
                     unit="points/s", reference=f"np.interp x2: {4001 / t_ref:.3g} points/s",
                     ratio=t_ref / t_ours, aim="> 1e5 points/s (a table in well under 0.1 s)"))
    big = table_from_result(res, spacing, bidirectional=True, resolution=0.1)
    small = table_from_result(res, 4.0, bidirectional=True, resolution=0.1)   # 251 points
    for name in CONTROLLERS:
        mod = controller(name)
        tab = big if name in ("siemens-840d", "fanuc", "csv") else small
        if name == "fanuc":
            tab = table_from_result(res, 1.0, bidirectional=False, resolution=1.0)   # 1001 points
        n = tab.n_points
        t_w = best_of(lambda: mod.write(tab), number=5)
        up = tab.up
        t_f = best_of(lambda: "\n".join(f"{p:.6f} {v:.6f}" for p, v in zip(tab.positions, up)), number=20)
        rows.append(dict(name=f"write {name}, {n} points", value=n / t_w, unit="points/s",
                         reference=f"one f-string per point: {n / t_f:.3g} points/s",
                         ratio=t_f / t_w, aim="> 1e4 points/s"))
    cfg = tomllib.loads((ROOT / "examples" / "compensation_linear.toml").read_text())
    t_loop = best_of(lambda: run_compensation_loop(cfg, seed=1), repeat=3)
    bare = {k: v for k, v in cfg.items() if k != "compensation"}
    t_test = best_of(lambda: simulate_from_config(bare, seed=1), repeat=3)
    rows.append(dict(name="compensation loop (81 targets x 5 runs x 2 directions, twice)",
                     value=t_loop, unit="s", reference=f"one simulated test: {t_test:.3g} s",
                     ratio=t_loop / t_test, aim="< 1 s; ratio near 2 (two tests)"))
    return rows
