"""
Volumetric map of a three-axis machine and its compensation
===========================================================

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
print(vm.result)        # the largest error, where, and the ranges of each component
for diag in d["diagonals"]:
    print(f"  body diagonal {diag['name']}: range {diag['range_um']:.2f} µm")
print(f"simulation truth: largest {d['truth']['largest_um']:.2f} µm; the map from the measured "
      f"files is within {d['mapped_minus_true_um']:.2f} µm of it")

# %%
# The distorted grid (magnified) and three slices of the error's magnitude.
fig = vm.plot()

# %%
# Compensation by tables: positioning and cross-axis tables for a Siemens 840D, in the order of
# Chapman, "Calibration of machine squareness", Appendix II (squareness on the axis aligned to
# the spindle). ``verify=True`` applies the tables to the simulated machine and measures it
# again (``axiscal volumetric compensate CONFIG --controller siemens-840d --verify``).
OUT = Path("output")
comp = axiscal.volumetric_compensation(CONFIG, "siemens-840d", out=OUT / "volumetric_tables",
                                       verify=True)
c = comp.to_dict()
print(f"{len(c['files'])} files written: {', '.join(c['files'][:4])} ...")
for name, f in c["verify"]["figures"].items():
    print(f"  {name:<26} {f['before_um']:7.2f} -> {f['after_um']:6.2f} µm "
          f"({f['reduction'] * 100:.0f} % less)")
print(f"left by the tables (two-axis Abbe products, model): {c['left_by_tables_um']:.2f} µm")

# %%
# Each figure before and after the tables, as re-measured.
fig = comp.plot()
