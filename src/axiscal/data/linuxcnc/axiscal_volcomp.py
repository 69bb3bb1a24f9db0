#!/usr/bin/env python3
"""axiscal-volcomp: a 3-D (volumetric) correction applied through LinuxCNC's external offsets.

A userspace HAL component (LinuxCNC documentation, "Creating Userspace Python Components with
the 'hal' module"; "External Axis Offsets"). It reads the commanded positions ``axis.L.pos-cmd``
(x, y, z; they do not include the external offset, so the correction does not feed back into its
own input), evaluates the correction map axiscal wrote (``axiscal volumetric compensate
--controller linuxcnc``; a JSON file named on the command line) and writes, for each axis, the
correction as a whole number of ``scale`` units on ``L-counts`` (net to ``axis.L.eoffset-counts``,
with ``axis.L.eoffset-scale`` equal to ``scale``). The correction is what the controller adds to
each axis's command (the negative of the machine's volumetric error, ISO/TR 16907:2015, numerical
compensation of geometric errors), the sum of

* the cross-axis tables: the correction of one axis as a function of another's position, linear
  between points and held beyond the ends (as LinuxCNC holds a COMP_FILE's end trims);
* a 3-D grid: the Abbe products of one axis's angular errors with the travel of the axes after it
  in the kinematic chain, at the tool point (Schwenke et al., "Geometric error measurement and
  compensation of machines — An update", CIRP Annals 57 (2008), eq. 3), trilinear between grid
  points, held at the nearest face beyond the grid.

The positioning error of each axis along itself stays in that joint's COMP_FILE. Pure Python
(only LinuxCNC's ``hal`` module), so it runs on any LinuxCNC machine as it is.

Usage (HAL): ``loadusr -Wn axiscal-volcomp /usr/bin/python3 axiscal_volcomp.py volcomp.json``.
"""

import json
import signal
import sys
import time
from bisect import bisect_right

AXES = "xyz"


def _segment(nodes, u):
    """Index i and fraction f with u between nodes[i] and nodes[i + 1] (held beyond the ends)."""
    if len(nodes) == 1 or u <= nodes[0]:
        return 0, 0.0
    if u >= nodes[-1]:
        return len(nodes) - 2, 1.0
    i = bisect_right(nodes, u) - 1
    return i, (u - nodes[i]) / (nodes[i + 1] - nodes[i])


def _line(nodes, values, u):
    if len(nodes) == 1:
        return values[0]
    i, f = _segment(nodes, u)
    return values[i] + f * (values[i + 1] - values[i])


class CorrectionMap:
    """The map of ``volcomp.json``: ``cross`` (list of ``driving``, ``receiving``, ``positions``,
    ``corrections``) and ``grid`` (``x``, ``y``, ``z`` node lists and ``values[axis][i][j][k]``),
    all in machine units (mm)."""

    def __init__(self, data):
        self.cross = [(AXES.index(t["driving"].lower()), AXES.index(t["receiving"].lower()),
                       [float(v) for v in t["positions"]], [float(v) for v in t["corrections"]])
                      for t in data.get("cross", [])]
        g = data.get("grid")
        self.grid = None if not g else ([[float(v) for v in g[a]] for a in AXES], g["values"])

    def correction(self, p):
        """Correction (mm) added to the x, y, z commands at commanded p (mm)."""
        out = [0.0, 0.0, 0.0]
        for d, r, nodes, values in self.cross:
            out[r] += _line(nodes, values, p[d])
        if self.grid is not None:
            nodes, values = self.grid
            (i, fx), (j, fy), (k, fz) = (_segment(n, u) for n, u in zip(nodes, p))
            for a in range(3):
                v = values[a]
                total = 0.0
                for di, wx in ((0, 1.0 - fx), (1, fx)):
                    for dj, wy in ((0, 1.0 - fy), (1, fy)):
                        for dk, wz in ((0, 1.0 - fz), (1, fz)):
                            w = wx * wy * wz
                            if w:
                                total += w * v[i + di][j + dj][k + dk]
                out[a] += total
        return out


def main(argv):
    with open(argv[1]) as f:
        m = CorrectionMap(json.load(f))
    run(make_component("axiscal-volcomp", AXES), m, AXES)


def make_component(name, inputs):
    """The component ``name``: an ``L-pos-cmd`` input for each axis letter of ``inputs``, and
    for X, Y, Z the ``L-request`` input and ``L-counts`` output; ``scale``, ``arm``, ``enable``
    and ``cycles`` (evaluations so far, so a reader can wait); ready, enabled."""
    import hal

    c = hal.component(name)
    for a in inputs:
        c.newpin(f"{a}-pos-cmd", hal.HAL_FLOAT, hal.HAL_IN)
    for a in AXES:
        c.newpin(f"{a}-request", hal.HAL_FLOAT, hal.HAL_IN)   # axis.L.eoffset-request
        c.newpin(f"{a}-counts", hal.HAL_S32, hal.HAL_OUT)
    c.newpin("scale", hal.HAL_FLOAT, hal.HAL_IN)
    c.newpin("arm", hal.HAL_BIT, hal.HAL_IN)        # motion.coord-mode (or teleop): applied
    c.newpin("enable", hal.HAL_BIT, hal.HAL_OUT)
    c.newpin("cycles", hal.HAL_U32, hal.HAL_OUT)

    def stop(*_):
        raise KeyboardInterrupt

    signal.signal(signal.SIGTERM, stop)
    c.ready()
    c["enable"] = 1
    return c


def run(c, m, inputs=AXES):
    """The loop: LinuxCNC applies changes of eoffset-counts (times the scale) only while the
    offsets are active (coordinated or teleop mode, machine on), like jog counts; so at each
    arming the base is taken from the offset already requested, and the counts then make the
    request equal the correction. ``m.correction`` takes the commanded positions of the axes
    ``inputs`` names, in that order."""
    n, armed, base = 0, False, [0, 0, 0]
    try:
        while True:
            s = c["scale"]
            if c["arm"] and s > 0:
                if not armed:
                    base = [c[f"{a}-counts"] - int(round(c[f"{a}-request"] / s)) for a in AXES]
                    armed = True
                corr = m.correction([c[f"{a}-pos-cmd"] for a in inputs])
                for a, b, v in zip(AXES, base, corr):
                    c[f"{a}-counts"] = b + int(round(v / s))
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
