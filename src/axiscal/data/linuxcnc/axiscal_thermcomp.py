#!/usr/bin/env python3
"""axiscal-thermcomp: a temperature compensation of one axis applied through LinuxCNC's
external offsets.

A userspace HAL component (LinuxCNC documentation, "Creating Userspace Python Components with
the 'hal' module"; "External Axis Offsets"), shipped like ``axiscal_volcomp.py``. It reads the
temperatures on its pins ``temp-0`` … (°C; on a machine netted from the sensors' inputs, in the
test from the simulated sensors), sees each through the first-order lag of the model axiscal
fitted to the ISO 230-3:2020 linear-axis test (``axiscal thermal compensate``; the parameters in
a JSON file named on the command line), and drives the external offset of the axis with

    ΔK = K0 + tanβ · (P − P0),   K0 = Σ k0_i (L_i − 20 °C),   tanβ = Σ s_i (L_i − 20 °C)

the thermal positioning error (actual − commanded) at the commanded position P
(``axis.L.pos-cmd``, which does not include the external offset): the same K0, tanβ and P0
SINUMERIK's temperature compensation takes (SD43900, SD43910, SD43920). The offset is −ΔK, as
a whole number of ``scale`` units on ``counts`` (net to ``axis.L.eoffset-counts``).

The lag: ``L ← T + (L − T) · exp(−Δt / τ)`` at each new reading, ``L = T`` at the first (the
temperature held over the interval at its new value: axiscal's ``lagged``). Δt comes from the
``time`` pin (s) when the JSON says ``"clock": "pin"`` (the logger's clock; the test feeds a
time-compressed simulated clock there: a reading each time it moves), else from the computer's
monotonic clock, a reading taken each ``interval_s``. While the ``reset`` pin is high no
reading is taken and the filters are empty (ΔK = 0); on its release they start from the
temperatures then (hold it high until the temperature inputs are valid: a filter started from
an input still at 0 would take hours to forget it). A time that goes backwards starts the
filters again.

Pure Python (only LinuxCNC's ``hal`` module), so it runs on any LinuxCNC machine as it is.

Usage (HAL): ``loadusr -Wn axiscal-thermcomp /usr/bin/python3 axiscal_thermcomp.py thermcomp.json``.
"""

import json
import math
import signal
import sys
import time

REFERENCE_C = 20.0


class ThermalCorrection:
    """The compensation of ``thermcomp.json``: ``sensors`` (names, in pin order), ``lags_s``,
    ``k0_mm_per_K``, ``slope_per_K``, ``p0_mm``; all lists one per term."""

    def __init__(self, data):
        self.sensors = [str(s) for s in data["sensors"]]
        self.lags = [float(v) for v in data["lags_s"]]
        self.k0 = [float(v) for v in data["k0_mm_per_K"]]
        self.slope = [float(v) for v in data["slope_per_K"]]
        self.p0 = float(data["p0_mm"])
        if not len(self.sensors) == len(self.lags) == len(self.k0) == len(self.slope):
            raise ValueError("thermcomp.json: sensors, lags_s, k0_mm_per_K and slope_per_K "
                             "must be of one length")
        self.state = None
        self.t = None

    def update(self, t, temperatures):
        """Take the readings (°C, one per term) at time ``t`` (s) through the lags."""
        if self.state is None or self.t is None or t < self.t:
            self.state = [float(v) for v in temperatures]
        else:
            dt = t - self.t
            self.state = [T if tau <= 0 else T + (x - T) * math.exp(-dt / tau)
                          for x, T, tau in zip(self.state, temperatures, self.lags)]
        self.t = t

    def error(self, position):
        """ΔK (mm) at the commanded ``position`` (mm); 0 before the first reading."""
        if self.state is None:
            return 0.0
        d = [x - REFERENCE_C for x in self.state]
        k0 = sum(k * v for k, v in zip(self.k0, d))
        tb = sum(k * v for k, v in zip(self.slope, d))
        return k0 + tb * (position - self.p0)


def main(argv):
    import hal

    with open(argv[1]) as f:
        data = json.load(f)
    m = ThermalCorrection(data)
    c = hal.component("axiscal-thermcomp")
    for i in range(len(m.sensors)):
        c.newpin(f"temp-{i}", hal.HAL_FLOAT, hal.HAL_IN)
    c.newpin("time", hal.HAL_FLOAT, hal.HAL_IN)
    c.newpin("pos-cmd", hal.HAL_FLOAT, hal.HAL_IN)
    c.newpin("request", hal.HAL_FLOAT, hal.HAL_IN)      # axis.L.eoffset-request
    c.newpin("counts", hal.HAL_S32, hal.HAL_OUT)
    c.newpin("scale", hal.HAL_FLOAT, hal.HAL_IN)
    c.newpin("arm", hal.HAL_BIT, hal.HAL_IN)            # motion.coord-mode
    c.newpin("active", hal.HAL_BIT, hal.HAL_IN)         # 0: the offset held at no correction
    c.newpin("reset", hal.HAL_BIT, hal.HAL_IN)          # 1: filters empty, no reading
    c.newpin("enable", hal.HAL_BIT, hal.HAL_OUT)
    c.newpin("error", hal.HAL_FLOAT, hal.HAL_OUT)       # ΔK now, mm
    c.newpin("cycles", hal.HAL_U32, hal.HAL_OUT)

    def stop(*_):
        raise KeyboardInterrupt

    signal.signal(signal.SIGTERM, stop)
    c.ready()
    c["enable"] = 1
    run(c, m, data.get("clock", "wall") == "pin", float(data.get("interval_s", 1.0)))


def run(c, m, pin_clock, interval):
    """The loop: a new reading when the clock has moved (the pin's value, or ``interval`` s of
    the computer's clock; with the pin's clock the first when it first moves), or at once when
    ``reset`` falls; the counts make the offset request −ΔK from the base taken at each arming
    (LinuxCNC applies count changes only while the offsets are active, as in
    ``axiscal_volcomp.py``)."""
    n, armed, base = 0, False, 0
    last = c["time"] if pin_clock else None
    n_temps = len(m.sensors)
    try:
        while True:
            if c["reset"]:
                m.state, m.t, last = None, None, None
            else:
                t = c["time"] if pin_clock else time.monotonic()
                if last is None or (t != last if pin_clock else t - last >= interval):
                    m.update(t, [c[f"temp-{i}"] for i in range(n_temps)])
                    last = t
            s = c["scale"]
            if c["arm"] and s > 0:
                if not armed:
                    base = c["counts"] - int(round(c["request"] / s))
                    armed = True
                e = m.error(c["pos-cmd"]) if c["active"] else 0.0
                c["error"] = e
                c["counts"] = base + int(round(-e / s))
            else:
                armed = False
            n = (n + 1) & 0x7FFFFFFF
            c["cycles"] = n
            time.sleep(0.001)
    except KeyboardInterrupt:
        pass
    finally:
        c.exit()


if __name__ == "__main__":
    main(sys.argv)
