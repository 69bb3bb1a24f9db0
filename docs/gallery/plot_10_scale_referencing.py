"""
Laser-scale referencing and gantry homing
=========================================

An axis fed by a laser scale through an environmental compensator gets its position as sine
and cosine signals of one output period (20 µm, 256 counts of 78.125 nm). Homing has to find
one count in that period again at every power-up: the switch trips, the compensator rephases
its outputs, and the controller takes the reference mark (events A, B, Z and C of Renishaw,
"Laser scale axis referencing"). ``axiscal.simulate`` tells a scale configuration by its
``[laser]``, ``[compensator]`` and ``[switch]`` tables (``axiscal scale home``).
"""

from pathlib import Path

import axiscal

EXAMPLES = Path("../../examples")

home = axiscal.simulate(EXAMPLES / "scale_single.toml")
print(home)
d = home.to_dict()
print(f"homed: {d['homed']}; compensation factor {d['compensation_ppm']:+.3f} ppm")
t = d["tracking"]
print(f"after homing, the controller follows the true part position at 20 °C within "
      f"{t['max_count_error']:.2f} counts ({t['max_part_error_um']:.3f} µm)")

# %%
# The signals against position around the switch: rephasing at B puts the reference mark Z
# on the same count at every homing.
fig = home.plot()

# %%
# A gantry with two linked axes, each on its own scale and switch (``axiscal scale gantry``):
# each axis rephases on its own, so the skew at homing can reach just under one signal period,
# and the controller's skew limit must be above it (same document, twin-axis homing).
gantry = axiscal.simulate(EXAMPLES / "scale_gantry.toml")
g = gantry.to_dict()
print(f"skew before synchronisation {g['skew_before_sync']} counts, limit "
      f"{g['skew_limit']} counts, alarm: {g['alarm']}; limit needed at least "
      f"{g['required_skew_limit']} counts")
for w in g["worst_case"]:
    print(f"  worst case v1={w['virtual_1']}, v2={w['virtual_2']}: skew "
          f"{w['skew_before_sync']} counts, alarm: {w['alarm']}")

# %%
# The real skew X1 − X2 at each step of the homing sequence, with the controller's skew limit
# and the limit this configuration needs.
fig = gantry.plot()
