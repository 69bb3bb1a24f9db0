"""A live LinuxCNC running a simulated five-joint table-table machine with its own trt
kinematics (``xyzac-trt-kins`` or ``xyzbc-trt-kins``), headless (issue 43).

:class:`LinuxCNCTrt` is :class:`~axiscal.instruments.linuxcnc_controller.LinuxCNC` (same start,
lock, shutdown and clean-up) on a configuration axiscal writes from its package data
(``axiscal/data/linuxcnc/axiscal_trt.ini``, ``axiscal_trt_axis.ini``, ``axiscal_trt.hal``): joints
X, Y, Z, the tilting axis and C, each motor command looped back as its feedback; the kinematics'
pins (``x-rot-point`` ...) set with ``setp`` from the INI's ``[HAL] HALCMD``, the tilting joint's
``HOME_OFFSET`` in its ``[JOINT_3]``. :meth:`LinuxCNCTrt.move_world` commands a world pose (the
tool point in the table frame and the two rotary angles) by MDI with the trt kinematics active
and reads the five joints' ``motor-pos-cmd`` (mm, degrees: the drives' frame, so a changed
HOME_OFFSET shows in it) through an in-process HAL component (``axiscal-trt``), after
:data:`~axiscal.instruments.linuxcnc_controller.SETTLE_PERIODS` runs of the servo thread.

With ``trtcomp`` (the lines :func:`axiscal.compensation.five_axis.trt_external_offsets` writes),
axiscal's userspace component ``axiscal_trtcomp.py`` (``axiscal_trtcomp.hal``) corrects the
orientation errors no pin holds through LinuxCNC's external offsets of X, Y, Z (LinuxCNC
documentation, "External Axis Offsets": ``[AXIS_L] OFFSET_AV_RATIO``, ``axis.L.eoffset-*``),
and :meth:`LinuxCNCTrt.move_world` reads the joints once those offsets have settled (as
:class:`~axiscal.instruments.linuxcnc_xyz.LinuxCNCXYZ` waits for its volumetric offsets).
"""

from __future__ import annotations

import json
import os
import tempfile
from dataclasses import dataclass, field
from importlib import resources
from pathlib import Path
from string import Template

import numpy as np

from axiscal.errors import InputError
from axiscal.instruments.linuxcnc_controller import SETTLE_PERIODS, LinuxCNC
from axiscal.instruments.linuxcnc_xyz import ExternalOffsets, offset_pins

__all__ = ["LinuxCNCTrt"]


@dataclass
class LinuxCNCTrt(ExternalOffsets, LinuxCNC):
    """One headless LinuxCNC session on a simulated table-table machine (a context manager).

    Parameters
    ----------
    tilt : str
        ``"A"`` (``xyzac-trt-kins``) or ``"B"`` (``xyzbc-trt-kins``).
    pins : dict of str to float, mm
        Kinematics pins (``x-rot-point``, ``y-rot-point``, ``z-rot-point``, ``x-offset``,
        ``y-offset``, ``z-offset``); missing ones are 0.
    home_offset : float, degrees
        ``[JOINT_3] HOME_OFFSET`` of the tilting joint.
    travel : dict of str to (float, float)
        Limits of X, Y, Z (mm) and of the tilting axis (degrees); C turns ±36000°.
    trtcomp : dict, optional
        The nominal and actual axis lines ``axiscal_trtcomp.py`` reads (``trtcomp.json``);
        None: no external offsets.
    """

    limits: tuple = (0.0, 0.0)
    tilt: str = "A"
    pins: dict = field(default_factory=dict)
    home_offset: float = 0.0
    travel: dict = field(default_factory=lambda: {"X": (-400.0, 400.0), "Y": (-400.0, 400.0),
                                                   "Z": (-400.0, 400.0), "A": (-120.0, 120.0),
                                                   "B": (-120.0, 120.0)})
    velocity: float = 5000.0
    acceleration: float = 1.0e5
    trtcomp: dict | None = None
    av_ratio: float = 0.2
    settle_timeout: float = 5.0

    _PINS = ("x-rot-point", "y-rot-point", "z-rot-point", "x-offset", "y-offset", "z-offset")

    def __post_init__(self) -> None:
        super().__post_init__()
        if self.tilt not in ("A", "B"):
            raise InputError(f"tilting axis {self.tilt!r}: LinuxCNC's trt kinematics are "
                             "xyzac and xyzbc")
        unknown = set(self.pins) - set(self._PINS)
        if unknown:
            raise InputError(f"unknown trt pins {sorted(unknown)}; known: {', '.join(self._PINS)}")

    @property
    def component(self) -> str:
        return f"xyz{self.tilt.lower()}c-trt-kins"

    def _write_config(self) -> None:
        self.folder = Path(tempfile.mkdtemp(prefix="axiscal-linuxcnc-"))
        os.chmod(self.folder, 0o1777)
        data = resources.files("axiscal.data") / "linuxcnc"
        axis_t = Template((data / "axiscal_trt_axis.ini").read_text())
        axes = []
        for j, a in enumerate(("X", "Y", "Z", self.tilt, "C")):
            lo, hi = (-36000.0, 36000.0) if a == "C" else (float(v) for v in self.travel[a])
            axes.append(axis_t.substitute(
                letter=a, joint=j, min_limit=repr(lo), max_limit=repr(hi),
                velocity=repr(float(self.velocity)), acceleration=repr(float(self.acceleration)),
                joint_type="ANGULAR" if j >= 3 else "LINEAR",
                home_offset=repr(float(self.home_offset)) if j == 3 else "0",
                axis_lines=f"OFFSET_AV_RATIO = {float(self.av_ratio)!r}\n"
                if self.trtcomp is not None and j < 3 else ""))
        trtcomp = ""
        if self.trtcomp is not None:
            trtcomp = "HALFILE = axiscal_trtcomp.hal"
            (self.folder / "trtcomp.json").write_text(json.dumps(self.trtcomp))
            (self.folder / "axiscal_trtcomp.hal").write_text(
                Template((data / "axiscal_trtcomp.hal").read_text())
                .substitute(tilt=self.tilt.lower()))
            for name in ("axiscal_trtcomp.py", "axiscal_volcomp.py"):
                (self.folder / name).write_text((data / name).read_text())
        pins = "\n".join(f"HALCMD = setp {self.component}.{p} {float(self.pins.get(p, 0.0))!r}"
                         for p in self._PINS)
        self.ini_text = Template((data / "axiscal_trt.ini").read_text()).substitute(
            tilt=self.tilt, kins=self.component, pin_lines=pins, trtcomp_hal=trtcomp,
            velocity=repr(float(self.velocity)), axes="\n".join(axes))
        (self.folder / "config.ini").write_text(self.ini_text)
        (self.folder / "axiscal_trt.hal").write_text((data / "axiscal_trt.hal").read_text())
        (self.folder / "tool.tbl").write_text("")

    def _connect(self) -> None:
        import hal

        comp = self._open_channels("axiscal-trt")
        nets = []
        for j in range(5):
            comp.newpin(f"j{j}-motor-pos-cmd", hal.HAL_FLOAT, hal.HAL_IN)
            nets.append((f"j{j}-motor-pos-cmd", f"axiscal-trt.j{j}-motor-pos-cmd"))
        if self.trtcomp is not None:
            nets += offset_pins(comp, "axiscal-trtcomp")
        self._ready(comp, nets)
        self._switch_on_and_home(5)

    def move_world(self, x: float, y: float, z: float, tilt: float, c: float) -> np.ndarray:
        """G0 to a world pose (mm; degrees) with the trt kinematics; the joints'
        ``motor-pos-cmd`` (5,), mm and degrees, SETTLE_PERIODS servo runs later (and, with
        ``trtcomp``, once the external offsets have settled)."""
        self.mdi(f"G90 G0 X{x:.9f} Y{y:.9f} Z{z:.9f} {self.tilt}{tilt:.9f} C{c:.9f}")
        self.wait_periods(SETTLE_PERIODS)
        if self.trtcomp is not None:
            self.wait_offsets("axiscal-trtcomp", (x, y, z, tilt, c))
        return np.array([self._comp[f"j{j}-motor-pos-cmd"] for j in range(5)], dtype=float)

    def move(self, *args, **kwargs):
        raise InputError("LinuxCNCTrt moves five joints: use move_world")


def joints_for_world_poses(tilt: str, pins: dict, home_offset: float, poses,
                           timeout: float = 600.0, trtcomp: dict | None = None) -> np.ndarray:
    """The joints' ``motor-pos-cmd`` (N, 5; mm, degrees) LinuxCNC reaches for world poses
    (N, 5: X, Y, Z mm, tilt and C degrees), in one :class:`LinuxCNCTrt` session run in a fresh
    Python process: a second session in one process lost its MDI moves every other time (tried:
    the joints stayed where homing left them while the moves were reported done), so each
    session gets a process of its own (the request and the joints pass as JSON). ``trtcomp``:
    the external-offset correction's lines (:class:`LinuxCNCTrt`)."""
    import subprocess
    import sys

    from axiscal.errors import MeasurementError

    request = json.dumps({"tilt": tilt, "pins": {k: float(v) for k, v in pins.items()},
                          "home_offset": float(home_offset), "trtcomp": trtcomp,
                          "poses": np.asarray(poses, float).tolist()})
    try:
        r = subprocess.run([sys.executable, "-c", "from axiscal.instruments.linuxcnc_trt import "
                            "_session_main; _session_main()"], input=request, text=True,
                           capture_output=True, timeout=timeout)
    except subprocess.TimeoutExpired:
        raise MeasurementError(f"LinuxCNC's session did not end within {timeout:g} s") from None
    if r.returncode != 0:
        tail = " | ".join(r.stderr.strip().splitlines()[-2:])
        raise MeasurementError(f"LinuxCNC's session failed: {tail}")
    return np.asarray(json.loads(r.stdout), dtype=float)


def _session_main() -> None:
    """Run one session from a JSON request on stdin; the joints as JSON on stdout."""
    import json
    import sys

    q = json.loads(sys.stdin.read())
    with LinuxCNCTrt(tilt=q["tilt"], pins=q["pins"], home_offset=q["home_offset"],
                     trtcomp=q.get("trtcomp")) as cnc:
        out = [cnc.move_world(*p).tolist() for p in q["poses"]]
    sys.stdout.write(json.dumps(out))
