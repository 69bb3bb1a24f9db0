"""Throughput of the five-DOF simulation and the ISO 230-7 evaluation (``make bench``).

Rows: simulated readings per second (ray trace + noise + reconstruction by seed 003 eqs. 1-9) against
a NumPy reference doing the least work of the same size (one batch of 3x3 rotation products per
reading); ISO 230-7 evaluations per second of an indexing test (3 runs x 12 angles) and samples per
second of a spindle-sized record (50 revolutions x 3600 angles) against ``np.ptp`` over the same array.
"""

from __future__ import annotations


import numpy as np

from axiscal.instruments.five_dof import FiveDofSystem, reconstruct, rotation
from axiscal.machines.rotary import Pose
from axiscal.standards.iso230_7 import MotionErrorData, evaluate

from _timing import best_of




def run() -> list[dict]:
    rows = []
    n = 100_000
    rng = np.random.default_rng(0)
    th = np.linspace(0, 2 * np.pi, n)
    e = rng.normal(0, 1e-5, (6, n))
    pose = Pose(theta=th, ez=e[0], ex=e[1], ey=e[2], dx=e[3], dy=e[4], dz=e[5])
    system = FiveDofSystem().with_realistic_mounting()

    def simulate():
        r = system.read(pose, th, (1e-6, -1e-6), rng)
        reconstruct(r, system)

    t_sim = best_of(simulate, 3)
    t_ref = best_of(lambda: rotation("x", e[1]) @ rotation("y", e[2]) @ rotation("z", th), 3)
    rows.append({"name": "five-DOF simulate+reconstruct (readings/s; ratio = value/reference)",
                 "value": n / t_sim, "unit": "readings/s", "reference": f"{n / t_ref:.3g} readings/s "
                 "of bare 3x3 rotation products", "ratio": t_ref / t_sim,
                 "aim": ">= 1e5 readings/s (a 60 min record at 1 kHz in under a minute)"})

    z12 = np.radians(np.arange(0, 360, 30.0))
    small = MotionErrorData(z12, *(rng.normal(0, 1e-6, (3, 12)) for _ in range(5)))
    k = 200
    t_small = best_of(lambda: [evaluate(small) for _ in range(k)], 3) / k
    rows.append({"name": "ISO 230-7 evaluation of an indexing test (3 runs x 12 angles)",
                 "value": 1 / t_small, "unit": "evaluations/s", "aim": ">= 1000/s (interactive)"})

    big_th = np.radians(np.arange(0, 360, 0.1))
    arrays = [rng.normal(0, 1e-6, (50, big_th.size)) for _ in range(5)]
    big = MotionErrorData(big_th, *arrays)
    t_big = best_of(lambda: evaluate(big), 3)
    t_ptp = best_of(lambda: [np.ptp(a) for a in arrays], 3)
    samples = 5 * arrays[0].size
    rows.append({"name": "ISO 230-7 evaluation, 50 rev x 3600 angles (samples/s; ratio = value/reference)",
                 "value": samples / t_big, "unit": "samples/s",
                 "reference": f"{samples / t_ptp:.3g} samples/s of np.ptp over the same arrays",
                 "ratio": t_ptp / t_big, "aim": "within 20x of a bare np.ptp pass"})
    return rows
