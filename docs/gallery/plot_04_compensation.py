"""
Compensation tables for a controller
====================================

From the mean deviations of an ISO 230-2 test, a pitch-error compensation table at a fixed
spacing, written in the format of each controller axiscal knows. The same table is shown as
the correction against position; each writer says what the controller must be told to use it.
"""

from pathlib import Path

import matplotlib.pyplot as plt

import axiscal

DATA = Path(axiscal.__file__).parent / "data"
OUT = Path("output")                                 # what the example writes
OUT.mkdir(exist_ok=True)

ev = axiscal.evaluate(axiscal.simulate(DATA / "demo_linear.toml", seed=1).dataset)
table = axiscal.compensation_table(ev, spacing=25, bidirectional=True)
print(table)

for controller, path in (("siemens-840d", "x_840d.ini"), ("fanuc", "x_fanuc.txt"),
                         ("heidenhain", "X.COM"), ("linuxcnc", "x.comp"),
                         ("renishaw-ren", "x.ren"), ("csv", "x_compensation.csv")):
    cf = axiscal.write_table(table, controller, OUT / path)
    print(f"\n{controller}: {path}, {len(cf.text.splitlines())} lines")
    for line in cf.enable[:2]:
        print("  enable:", line)

# %%
# The table: corrections in each direction against the axis position.
fig, ax = plt.subplots(figsize=(8, 4))
ax.step(table.positions, table.up, where="mid", label="correction, + direction")
ax.step(table.positions, table.down, where="mid", label="correction, − direction")
ax.plot(ev.result.targets, -ev.result.mean_up, "o", ms=3,
        label="− mean deviation ↑ (ISO 230-2)")
ax.set_xlabel(f"position [{table.position_unit}]")
ax.set_ylabel(f"correction [{table.correction_unit}]")
ax.grid(alpha=0.3)
ax.legend()
fig.tight_layout()
