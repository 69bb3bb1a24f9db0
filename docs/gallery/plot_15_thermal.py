"""
Thermal effects by ISO 230-3: a linear axis warming, its model and SINUMERIK's compensation
============================================================================================

The thermal twin shipped with axiscal (``src/axiscal/data/thermal_vmc.toml``: the room's daily
cycle, spindle, spindle head, X ball screw and structure as first-order nodes) runs the test of
ISO 230-3:2020 Clause 7: the X axis cycles for 4 h and rests for 1 h while the positioning
error at P1 and P2, near both ends, is measured again and again. Three runs, at different duties
and times of day, give a thermal model: fitted on one, its terms chosen on the second, judged on
the third. From it, SINUMERIK's temperature compensation ΔK = K0 + tanβ·(P − P0). This is
``axiscal thermal simulate --test linear``, ``thermal model`` and ``thermal compensate``.
"""

import matplotlib.pyplot as plt

import axiscal

runs = [axiscal.simulate_thermal("linear", seed=s, duty=d, start_h=h)
        for s, d, h in ((1, 0.8, 8.0), (2, 0.5, 13.0), (3, 1.0, 2.0))]
result = axiscal.evaluate_thermal(runs[2].log)
print(result)
print("simulation truth, largest drift at P2:",
      f"{runs[2].truth['delta_P2_max_run'] * 1e6:.2f} µm")

# %%
# The unseen run: drift at both targets and the screw's temperature over time.
log = runs[2].log
fig, (a, b) = plt.subplots(2, 1, sharex=True)
for name in ("P1", "P2"):
    v = log.displacements[name]
    a.plot(log.time / 3600, (v - v[0]) * 1e6, label=f"drift at {name}")
a.set_ylabel("µm")
a.legend()
b.plot(log.time / 3600, log.temperatures["T_screw_x"], label="T_screw_x")
b.set_ylabel("°C")
b.set_xlabel("h")
b.legend()

# %%
# The model, judged on the run it never saw, and the SINUMERIK parameters.
model = axiscal.fit_thermal_model(runs[0].log, runs[1].log, test=runs[2].log)
print(model)
print(axiscal.thermal_compensation(model))

# %%
# What the controller is given: SINUMERIK's machine and setting data, with K0(T) and tanβ(T) for
# the PLC as comments (``thermal compensate --sinumerik-out``; ΔK is the error line, the sign of
# K3 §4.2). LinuxCNC is given a HAL component with the same terms (``--linuxcnc-out``; proven
# through a real LinuxCNC by ``--verify --on-controller``).
print(axiscal.thermal_compensation(model).to_text())
