"""
A rotary axis by ISO 230-2
==========================

A turntable measured at its angular targets (ISO 230-2:2014 for a rotary axis: deviations in
arcseconds). The simulation injects known errors; ``Simulation.plot`` draws the truth beside
the measured means, so the evaluation can be checked against what was put in.
"""

from pathlib import Path

import axiscal

DATA = Path(axiscal.__file__).parent / "data"

sim = axiscal.simulate(DATA / "demo_rotary.toml", seed=2)
d = sim.to_dict()
print(f"axis kind {d['axis_kind']}, targets in {d['target_unit']}, deviations in {d['unit']}")
for name in ("E", "M", "B"):
    print(f"{name}: measured {d[name]:.2f}, truth {d['truth'][name]:.2f} {d['unit']}")

fig = sim.plot()
