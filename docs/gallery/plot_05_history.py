"""
The calibration history
=======================

Tests of one axis stored over time in the history database (SQLite here; PostgreSQL by URL),
then the trend of a parameter. Each file is evaluated by the same code as ``axiscal history
add``; a file stored before is reported as a duplicate, not stored twice.
"""

from pathlib import Path

import matplotlib.pyplot as plt

import axiscal

DATA = Path(axiscal.__file__).parent / "data"
OUT = Path("output")                                 # what the example writes
OUT.mkdir(exist_ok=True)
db = OUT / "history_example.sqlite"
db.unlink(missing_ok=True)

with axiscal.History(f"sqlite:///{db.resolve()}") as history:
    for seed in range(1, 6):
        f = axiscal.simulate(DATA / "demo_linear.toml", seed=seed).write_data(OUT / f"x_{seed}.csv")
        print(history.add(f, machine="VMC-1", date=f"2026-0{seed}-15"))
    tests = history.tests("VMC-1")
    trend = history.trend("VMC-1", "X", "E")
print(trend)

# %%
# E of each stored test against its date.
dates = [t.tested_at for t in tests]
E = [t.parameters["E"][0] for t in tests]
fig, ax = plt.subplots(figsize=(8, 4))
ax.plot(dates, E, "o-")
ax.set_ylabel(f"E [{tests[0].parameters['E'][1]}]  (ISO 230-2:2014)")
ax.set_title("VMC-1 X: bidirectional systematic deviation E over time")
ax.grid(alpha=0.3)
fig.autofmt_xdate()
