"""
Volumetric map of a three-axis machine
======================================

The 21 geometric errors of a three-axis machine (ISO 230-1:2012 notation: three positioning,
six straightness, nine angular errors and three squareness errors), each measured along its
axis by a laser test and kept in its own file, are combined by the first-order rigid-body
model of ISO/TR 16907:2015 into the error of the tool point everywhere in the working volume;
the four body diagonals of ISO 230-6:2002 are computed from the same model. The files here
were written by ``axiscal volumetric simulate --out examples/volumetric``: the configuration
keeps the simulated machine's seed, so the map is also compared with the truth. This is
``axiscal volumetric map examples/volumetric/volumetric.toml``.
"""

from pathlib import Path

import axiscal

CONFIG = Path("../../examples/volumetric/volumetric.toml")

vm = axiscal.volumetric_map(CONFIG, grid=11)
d = vm.to_dict()
print(vm.result)
print(f"largest volumetric error {d['largest_um']:.2f} µm at {d['largest_at_mm']} mm")
for diag in d["diagonals"]:
    print(f"  body diagonal {diag['name']}: range {diag['range_um']:.2f} µm")
print(f"simulation truth: largest {d['truth']['largest_um']:.2f} µm; the map from the measured "
      f"files is within {d['mapped_minus_true_um']:.2f} µm of it")

# %%
# The distorted grid (magnified) and three slices of the error's magnitude.
fig = vm.plot()

# %%
# The compensation of what tables can remove (positioning and cross-axis tables, squareness
# on the axis aligned to the spindle) is ``axiscal volumetric compensate
# examples/volumetric/volumetric.toml --controller siemens-840d --verify``, which re-measures
# the simulated machine with the tables applied.
