"""
Five-axis location errors from a probed sphere and an R-test
============================================================

A table-table A/C machine whose rotary axes carry the ten location errors of ISO 230-1:2012 /
ISO 230-7:2015 Clause 3. Before measuring, the plan says what its set-ups can separate (rank and
condition of the sensitivity matrix, the unseen named). The twin is then measured by a touch
probe on two spheres and an R-test, written to CSV files as real instruments' exports would be
read, identified with U (k = 2), drawn, and turned into LinuxCNC's trt kinematics pins (with
the external offsets for the tilts no pin holds) and SINUMERIK 840D swivel data.
"""

from pathlib import Path

import axiscal

DATA = Path(axiscal.__file__).parent / "data"       # configurations shipped with axiscal
OUT = Path("output")
config = DATA / "fiveaxis_ac.toml"

# %%
# What the planned poses can and cannot see, before any measurement.
print(axiscal.fiveaxis.plan(config).check)

# %%
# The twin measured (noise 0.5 µm), one CSV per set-up, then identified from the files.
sim = axiscal.fiveaxis.simulate(config, seed=1, out=OUT / "fiveaxis")
result = axiscal.fiveaxis.identify(config, sim.files)
print(result)
truth = sim.truth()
for e in result.errors:
    print(f"{e.name:>12}: identified − true {e.value_display - truth[e.name]:+.2f} {e.unit}")

# %%
# The axis lines, nominal and identified (magnified), beside the values with U.
fig = axiscal.fiveaxis.figure(config, result)

# %%
# The correction in LinuxCNC's terms (xyzac-trt-kins pins, the A joint's HOME_OFFSET and the
# external offsets of axiscal_trtcomp.py for the tilts), verified by re-measuring the twin.
comp = axiscal.fiveaxis.compensate(config, sim.files, verify=True)
print(comp)

# %%
# The same axis lines as SINUMERIK 840D swivel data for CYCLE800 (toolholder $TC_CARR, type P).
print(comp.sinumerik.program())

# %%
# The linear axes' squareness can be identified with the location errors (here the twin has
# none, so the values are zero within U).
print(axiscal.fiveaxis.identify(config, sim.files, squareness=True))
