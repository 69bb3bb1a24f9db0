"""
Ballbar diagnosis
=================

A circular test in the XY plane, run clockwise and counter-clockwise with a 150 mm ballbar. The
file is told by its columns (``angle, direction, deviation``); the diagnosis separates the
machine's errors (squareness, scale mismatch, backlash, reversal spikes ...) and gives the
ISO 230-4:2005 circular deviations G and circular hysteresis H.
"""

from pathlib import Path

import axiscal

ballbar_file = Path("../../examples/squareness_ballbar_150mm.csv")

ev = axiscal.evaluate(ballbar_file)
print(ev.kind, "by", ev.standard)
d = ev.to_dict()
for key in ("squareness_um_per_m", "scale_mismatch_um_per_m", "backlash_x_um", "backlash_y_um"):
    print(f"{key:<26} {d[key]:8.2f}")

# %%
# The polar plot of both directions and the ranked diagnosis.
fig = ev.plot()
