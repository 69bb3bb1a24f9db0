"""
Squareness: straightness trajectories and diagonals
===================================================

Two of the squareness methods (Chapman, *Calibration of machine squareness*): a straightness
trajectory with its ISO 230-1 reference lines (least squares and minimum zone), and a
multi-point diagonal test whose two diagonals give the squareness by ISO 230-6
(squareness = D0 (D1 − D2) / (2XY)). Both files ship with axiscal's examples and are told by
their columns.
"""

from pathlib import Path

import axiscal

EXAMPLES = Path("../../examples")

line = axiscal.evaluate(EXAMPLES / "squareness_L180_x.csv")
d = line.to_dict()
print(f"{line.kind} of axis {d['axis']} in {d['direction']} over {d['n']} points")
for method in ("least_squares", "minimum_zone"):
    m = d[method]
    print(f"  {method:<14} straightness {m['straightness_um']:6.2f} µm, "
          f"slope {m['slope_um_per_m']:+7.2f} µm/m")
fig = line.plot()

# %%
# The diagonal test: the length errors along both diagonals and the squareness they give.
diag = axiscal.evaluate(EXAMPLES / "squareness_diagonal_600x800.csv")
sq = diag.to_dict()["squareness"]
print(f"squareness {sq['um_per_m']:+.2f} µm/m ({diag.standard})")
fig = diag.plot()
