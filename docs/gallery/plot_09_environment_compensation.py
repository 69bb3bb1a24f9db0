"""
Environmental compensation of raw laser readings
================================================

A laser interferometer measures in wavelengths of its light *in air*, and the axis grows with
its temperature. Here an 800 mm axis was measured with the laser's own compensation off: the
raw readings (``time_s, target, direction, run, reading``) and the environment log recorded
over the test (air temperature, pressure, humidity, material temperature) are two files. Each
reading is corrected for the refractive index of the air at its time (Ciddor, "Refractive
index of air: new equations for the visible and near infrared", Applied Optics 35, 1996) and
the dead path, and the axis is referred to 20 °C (ISO 1:2016, the standard reference
temperature, with the expansion coefficient the log declares). The compensated test is then
evaluated by ISO 230-2:2014.
This is ``axiscal compensate-environment RAW --environment ENV --out DATA.csv``.
"""

from pathlib import Path

import axiscal

EXAMPLES = Path("../../examples")
OUT = Path("output")
OUT.mkdir(exist_ok=True)

comp = axiscal.compensate_environment(EXAMPLES / "raw_readings_vmc800_x.csv",
                                      EXAMPLES / "environment_log_vmc800_x.csv",
                                      out=OUT / "x_axis_compensated.csv")
d = comp.to_dict()
print(f"{d['readings']} readings, air {d['air_temperature_c']:.2f} °C and material "
      f"{d['material_temperature_c']:.2f} °C on average over the test")
print(comp)          # what was applied, as kept in the compensated file's metadata

# %%
# The air warmed by 1 K and the work-piece by 0.5 K during the test. The correction of each
# reading is mostly the air's refractive index (n − 1 is about 271 ppm here, so about
# −0.22 mm at 800 mm), with the thermal growth of the axis (11.5 ppm/K) on top.
fig = comp.plot()

# %%
# The compensated test, read back from the file written (as ``axiscal iso230-2`` would),
# evaluated by ISO 230-2:2014.
ev = axiscal.evaluate(axiscal.read(OUT / "x_axis_compensated.csv"))
print(ev)

# %%
# Its positioning deviations, per direction, with the ±2s bands of the standard.
fig = ev.plot()
