"""
ISO 230-2 from a laser file to a report
=======================================

A linear axis measured with a laser interferometer: five bidirectional runs over the targets,
evaluated by ISO 230-2:2014 (A, E, M, R, B, clause 2; the uncertainty of Annex A) and written
as an HTML report. The readings here are simulated (``axiscal.simulate``) and written to a tidy
CSV exactly as a laser's export would be read, so the example runs without an instrument.
"""

from pathlib import Path

import axiscal

DATA = Path(axiscal.__file__).parent / "data"       # configurations shipped with axiscal
OUT = Path("output")                                 # what the example writes
OUT.mkdir(exist_ok=True)

sim = axiscal.simulate(DATA / "demo_linear.toml", seed=1)
laser_file = sim.write_data(OUT / "x_axis.csv")

# %%
# Read the file (its format is told by its content) and evaluate it by ISO 230-2:2014.
ds = axiscal.read(laser_file)
ev = axiscal.evaluate(ds)
print(ev)

# %%
# The numbers are those of ``axiscal iso230-2 x_axis.csv --json``, with the expanded
# uncertainty U (k = 2) of each parameter (ISO 230-2:2014 Annex A). Without a drift check the
# environmental variation error E_VE is missing and U of R and B holds only the resolution:
# the budget says so. Here E_VE = 0.3 µm is declared, as a drift check over the test's duration
# would measure it (Annex A.5; ``--uncertainty e_ve=0.3`` on the command line).
for inputs in ({}, {"e_ve": 0.3}):
    d = axiscal.evaluate(ds, uncertainty=inputs).to_dict()
    print("missing from U:", d["uncertainty_budget"]["missing_inputs"] or "nothing")
    for name in ("A", "E", "M", "R", "B"):
        print(f"  {name:>2} = {d[name]:6.2f} {d['unit']}   U = {d['uncertainty_display'][name]}")

# %%
# The per-target figure: mean positions in each direction with the ±2s band.
fig = ev.plot()

# %%
# The HTML report: every parameter with its clause, the figure and the uncertainty budget.
ev = axiscal.evaluate(ds, uncertainty={"e_ve": 0.3})
print(ev.report(OUT / "x_axis_report.html"))
