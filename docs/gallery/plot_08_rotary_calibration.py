"""
A rotary calibration with the reference calibrator
==================================================

A turntable calibrated with an angular interferometer looking at a reflector on a
counter-rotating reference calibrator (Renishaw, "Interferometric calibration of rotary axes"):
the set-up's misalignments make the error of eq. 1, the optics are self-calibrated, and the
readings are evaluated by ISO 230-2:2014. The simulation knows the truth, so the measured
per-target means are compared with it and with the error budget.
"""

from pathlib import Path

import axiscal

DATA = Path(axiscal.__file__).parent / "data"

sim = axiscal.simulate(DATA / "rotary_turntable.toml")
print(sim)
d = sim.to_dict()
print(f"A measured {d['measured']['A']:.2f} arcsec, truth {d['truth']['A']:.2f} arcsec")

# %%
# The measured error at each target beside the truth and the budget.
fig = sim.plot()
