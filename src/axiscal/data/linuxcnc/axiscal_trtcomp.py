#!/usr/bin/env python3
"""axiscal-trtcomp: the orientation errors of a table-table machine's rotary axes, which no pin
of LinuxCNC's trt kinematics holds, corrected through LinuxCNC's external offsets (issue 43).

A userspace HAL component (LinuxCNC documentation, "Creating Userspace Python Components with
the 'hal' module"; "External Axis Offsets"), run as axiscal's ``axiscal_volcomp.py`` is (whose
``make_component`` and ``run`` it uses). It reads the commanded world pose ``axis.L.pos-cmd`` of
X, Y, Z (mm, the tool point in the table frame: the world of ``xyzac-trt-kins`` /
``xyzbc-trt-kins``, which turns with the table) and of the two rotary axes (degrees; the offsets
are not in these positions, so the correction does not feed back into its own input), and asks
for the external offset

    o = R_nom(t, c)^T · (T_act(t, c) p − T_nom(t, c) p)

on X, Y, Z, where ``T(t, c) p = Rot(line_t, t + z_t) Rot(line_c, c + z_c) p`` puts a table point
into the machine frame by turning it about the C line, then about the tilting axis's line
(right-handed about each line's direction: LinuxCNC's trt sign; axiscal
``physics/rotary_location.py``), ``T_nom`` with the lines the kinematics' pins hold and
``T_act`` with the lines axiscal identified, and ``R_nom`` the rotation part of ``T_nom``. The
kinematics then send the joints to ``T_nom(p + o) = T_act(p)``: where the identified machine has
the commanded table point. Both sets of lines (a point in mm, a unit direction, a zero error in
degrees) come from the JSON file named on the command line (``axiscal fiveaxis compensate``
writes it). Pure Python (only LinuxCNC's ``hal`` module).

Usage (HAL): ``loadusr -Wn axiscal-trtcomp /usr/bin/python3 axiscal_trtcomp.py trtcomp.json``.
"""

import json
import math
import sys


def rotate(v, u, theta):
    """Vector ``v`` turned right-handed about unit ``u`` by ``theta`` (rad), Rodrigues."""
    c, s = math.cos(theta), math.sin(theta)
    d = v[0] * u[0] + v[1] * u[1] + v[2] * u[2]
    x = (u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0])
    return [v[i] * c + x[i] * s + u[i] * d * (1.0 - c) for i in range(3)]


def about_line(p, line, theta):
    """Point ``p`` turned about ``line`` = (point, unit direction, zero error deg) by ``theta``
    (rad) plus the line's zero error."""
    q, u, zero = line
    v = rotate([p[i] - q[i] for i in range(3)], u, theta + math.radians(zero))
    return [q[i] + v[i] for i in range(3)]


class TrtMap:
    """The lines of ``trtcomp.json``: ``nominal`` and ``actual``, each ``{"tilt": [point,
    direction, zero], "c": [...]}`` (mm, unit vector, degrees)."""

    def __init__(self, data):
        self.nominal = [_line(data["nominal"][k]) for k in ("tilt", "c")]
        self.actual = [_line(data["actual"][k]) for k in ("tilt", "c")]

    def correction(self, pose):
        """Offset (mm) added to the X, Y, Z commands at world pose (x, y, z mm, tilt, c deg)."""
        p, t, c = pose[:3], math.radians(pose[3]), math.radians(pose[4])
        (nt, nc), (at, ac) = self.nominal, self.actual
        want = about_line(about_line(p, ac, c), at, t)
        have = about_line(about_line(p, nc, c), nt, t)
        d = [w - h for w, h in zip(want, have)]
        d = rotate(d, nt[1], -(t + math.radians(nt[2])))
        return rotate(d, nc[1], -(c + math.radians(nc[2])))


def _line(v):
    return [float(x) for x in v[0]], [float(x) for x in v[1]], float(v[2])


def main(argv):
    from axiscal_volcomp import make_component, run

    with open(argv[1]) as f:
        data = json.load(f)
    inputs = ("x", "y", "z", data["tilt"].lower(), "c")
    run(make_component("axiscal-trtcomp", inputs), TrtMap(data), inputs)


if __name__ == "__main__":
    main(sys.argv)
