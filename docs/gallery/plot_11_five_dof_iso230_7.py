"""
Five motion errors of a rotary axis and ISO 230-7
=================================================

An indexing table measured at every 30° with a five-DOF optical system that sees the
positioning error, two tilts and two displacements at once, against a counter-rotating
reference axis (Optics Express 2018, "Five-DOF motion errors of a rotary axis", eqs. 1-6 with
the beam-drift compensation). The simulation knows the truth, so the measured errors are
compared with it; the five errors are then evaluated by ISO 230-7:2015 (error motions,
synchronous and asynchronous, with the once-per-turn fundamental removed from the radial and
tilt motions, and the axis's location). This is ``axiscal motion simulate``.
"""

from pathlib import Path

import axiscal

EXAMPLES = Path("../../examples")

sim = axiscal.simulate(EXAMPLES / "motion_indexing_table.toml")
d = sim.to_dict()
print("largest |measured - truth|:")
for key, value in d["max_abs_error"].items():
    print(f"  {key:<10} {value:7.3f}")

# %%
# The five errors against angle, measured (dots) and true (dashed).
fig = sim.plot()

# %%
# The ISO 230-7:2015 evaluation of the measured errors (one run: no asynchronous motion).
print(sim.result)
for m in d["iso230_7"]["motions"]:
    print(f"  {m['name']:<10} total {m['total']:7.3f} {m['unit']}")

# %%
# The measured errors as a five-error data file, evaluated again as a measured file would be
# (``axiscal motion analyze``): the same ISO 230-7 numbers, and its polar plot.
OUT = Path("output")
OUT.mkdir(exist_ok=True)
ev = axiscal.evaluate(sim.write_data(OUT / "motion.csv"))
print(ev.kind, "by", ev.standard, "- largest total error motion:",
      max(ev.to_dict()["motions"], key=lambda m: m["total"])["name"])
fig = ev.plot()
