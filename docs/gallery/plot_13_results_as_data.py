"""
Results as data: a real axis, its U, the history and back
==========================================================

A notebook's path through a real file: the ISO 230-2 test of an ESS MCU1025 axis (ecmc, the
EPICS motion control of PSI and ESS; ``tests/data/ecmc``, GPL-3.0) is read, evaluated with
its ISO 230-2:2014 Annex A uncertainty, turned into a tidy DataFrame of the parameters with
U, stored in a calibration history, read back, and the frames compared: what the history
gives back is what the evaluation gave, U included. The report is made from the stored test.

The file also shows why an outlier must be said, not dropped: the first run at 15 mm reads
+93 µm where the other four read about −21 µm, and that one reading sets R.
"""

from pathlib import Path

import matplotlib.pyplot as plt

import axiscal

REAL = Path("../../tests/data/ecmc/mcu1025_fat_sat_ISO230.dat").resolve()
OUT = Path("output")
OUT.mkdir(exist_ok=True)

ds = axiscal.read(REAL)
inputs = {"e_ve": 0.3}          # E_VE declared: ISO 230-2:2014 Annex A.5, in µm
ev = axiscal.evaluate(ds, uncertainty=inputs)
print(ev)

# %%
# The parameters as a tidy frame: value, U, k and unit in one row each. ``ev.E`` is one
# quantity with its uncertainty; ``ev.E.U`` the expanded uncertainty at k = 2.
frame = ev.to_dataframe()
print(frame[["symbol", "value", "U", "k", "unit"]].round(3))
print(ev.E, "| U =", round(ev.E.U, 4), ev.E.unit)

# %%
# The reading that alone sets R, named by Grubbs' test (kept in the evaluation).
for o in ev.result.outliers:
    print(o)

# %%
# Stored with its inputs, read back: the same frame, the same U.
db = OUT / "results_as_data.sqlite"
db.unlink(missing_ok=True)
with axiscal.History(f"sqlite:///{db.resolve()}") as history:
    added = history.add(REAL, machine="ESS MCU1025", axis="X", uncertainty=inputs)
    back = history.evaluation(added.id)
    same = back.to_dataframe().equals(frame)
    print("identical after the history:", same)
    back.report(OUT / "mcu1025_from_history.html")

# %%
# Each parameter with its U, as error bars (the unit is µm).
fig, ax = plt.subplots(figsize=(8, 3.5))
ax.errorbar(frame["symbol"], frame["value"], yerr=frame["U"], fmt="o", capsize=4)
ax.set_ylabel("µm")
ax.set_title("ESS MCU1025: ISO 230-2:2014 parameters with U (k = 2)")
ax.grid(alpha=0.3)
