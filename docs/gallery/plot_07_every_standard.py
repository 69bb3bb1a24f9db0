"""
One test by every positioning standard
======================================

A contract may name another standard than ISO 230-2:2014. ``evaluate(ds, "all")`` evaluates
the same readings by every standard whose definitions were publicly available to axiscal, and
lists the others with the reason they are not evaluated (the standards page gives the sources).
"""

from pathlib import Path

import axiscal

DATA = Path(axiscal.__file__).parent / "data"

ds = axiscal.simulate(DATA / "demo_linear.toml", seed=1).dataset
ev = axiscal.evaluate(ds, "all")
for s in ev.to_dict()["standards"]:
    if s["evaluated"]:
        values = ", ".join(f"{k} = {v['value']:.2f}" for k, v in s["parameters"].items())
        print(f"{s['title']:<20} {values}")
    else:
        print(f"{s['title']:<20} {s['reason'].split(': ', 1)[-1]}")

# %%
# Each evaluated standard's parameters against the per-target means.
fig = ev.plot()
