"""A live LinuxCNC running a simulated three-joint XYZ machine headless (issue 32, volumetric).

:class:`LinuxCNCXYZ` is :class:`~axiscal.instruments.linuxcnc_controller.LinuxCNC` (same start,
lock, shutdown and clean-up) on a three-joint configuration axiscal writes from its package data
(``axiscal/data/linuxcnc/axiscal_xyz.ini``, ``axiscal_xyz_axis.ini``, ``axiscal_xyz.hal``):
trivial kinematics, one ``COMP_FILE`` per joint when given, and, when a correction map is given,
the external offsets driven by axiscal's userspace HAL component ``axiscal_volcomp.py``
(``axiscal_volcomp.hal``; LinuxCNC documentation, "External Axis Offsets": ``[AXIS_L]
OFFSET_AV_RATIO``, ``axis.L.eoffset-enable``, ``-scale``, ``-counts``).

:meth:`LinuxCNCXYZ.move_to` reaches a target with the slow final approach of the one-joint driver
(LinuxCNC holds, once a joint stops, the trim of the last servo period in which it moved), waits
:data:`~axiscal.instruments.linuxcnc_controller.SETTLE_PERIODS` runs of the servo thread (the
move's last points on the pins), then until the external offsets have settled on the correction
of the final commanded position (the component has run two cycles since, so it evaluated the
final position, even on a loaded computer; then ``axis.L.eoffset`` within :data:`SETTLED` of
``axis.L.eoffset-request``, both unchanged over SETTLE_PERIODS runs of the servo thread: the
offset ramps, limited by OFFSET_AV_RATIO of the axis's velocity and acceleration, and reaches the
joints through the same cubic interpolator) and reads the three joints' ``motor-pos-cmd``
(command + offset + trim: what reaches the drives) through an in-process HAL component
(``axiscal-xyz``). Every wait on LinuxCNC's motion is counted in runs of its servo thread, never
in seconds (the one-joint driver's docstring says why).
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

from axiscal.errors import MeasurementError
from axiscal.instruments.linuxcnc_controller import (CREEP, CREEP_FEED, SETTLE_PERIODS,
                                                     LinuxCNC, _wait)

__all__ = ["LinuxCNCXYZ", "EOFFSET_SCALE", "ExternalOffsets", "offset_pins"]

AXES = "XYZ"
#: mm per count of the external offsets (``axis.L.eoffset-scale``): 1 nm.
EOFFSET_SCALE = 1e-6
#: How close (mm) a settled external offset is to its request: 50 nm. LinuxCNC's offset planner
#: stops anywhere within its dead band of the request, 0.001 × acceleration × servo period²
#: (LinuxCNC ``src/emc/motion/simple_tp.c``, ``tiny_dp``: 20 nm at 0.2 × 1e5 mm/s²), where in it
#: depending on the path, which follows the component's updates (userspace, not in step with
#: the servo thread; tried: the same point read up to 17 nm apart run to run); the reading takes
#: the offset as applied.
SETTLED = 5e-5


def offset_pins(comp, source: str) -> list:
    """Give the in-process component ``comp`` the pins :class:`ExternalOffsets` reads (each
    axis's ``L-eoffset`` and ``L-request``, and ``cycles``) and return their ``halcmd net``
    arguments; ``source`` is the userspace component that drives the offsets (its HAL file nets
    ``vc-L-request``)."""
    import hal

    nets = []
    for a in "xyz":
        comp.newpin(f"{a}-eoffset", hal.HAL_FLOAT, hal.HAL_IN)
        comp.newpin(f"{a}-request", hal.HAL_FLOAT, hal.HAL_IN)
        nets += [(f"vc-{a}-eoffset", f"axis.{a}.eoffset", f"{comp.getprefix()}.{a}-eoffset"),
                 (f"vc-{a}-request", f"{comp.getprefix()}.{a}-request")]
    comp.newpin("cycles", hal.HAL_U32, hal.HAL_IN)
    nets.append(("vc-cycles", f"{source}.cycles", f"{comp.getprefix()}.cycles"))
    return nets


class ExternalOffsets:
    """Waiting for the external offsets of X, Y, Z that a userspace component drives (a mixin
    of a :class:`~axiscal.instruments.linuxcnc_controller.LinuxCNC` session whose component has
    the pins of :func:`offset_pins`)."""

    settle_timeout: float

    def wait_offsets(self, source: str, target) -> None:
        """Until ``source`` has run two cycles since now (so it evaluated the final position,
        even on a loaded computer) and the offsets have settled (:meth:`_settled`)."""
        c0 = self._comp["cycles"]
        try:
            _wait(lambda: (self._comp["cycles"] - c0) % 2 ** 31 >= 2, self.settle_timeout,
                  f"{source} to evaluate the final position")
            _wait(self._settled, self.settle_timeout, "the external offsets to settle")
        except MeasurementError as exc:
            c = self._comp
            raise MeasurementError(f"{exc} at {list(target)} (offset, request mm: " + ", ".join(
                f"{c[f'{a}-eoffset']:.6f} {c[f'{a}-request']:.6f}" for a in "xyz")
                + ")") from None

    def _settled(self) -> bool:
        """The offsets are where the component asks, within :data:`SETTLED`, and neither they
        nor the requests changed over SETTLE_PERIODS runs of the servo thread (the request
        follows the counts at the next run; the joints follow the offset through the cubic
        interpolator)."""
        before = self._offsets()
        if any(abs(v - w) > SETTLED for v, w in zip(before[:3], before[3:])):
            return False
        self.wait_periods(SETTLE_PERIODS)
        return self._offsets() == before

    def _offsets(self) -> list:
        """``axis.L.eoffset`` then ``axis.L.eoffset-request`` of X, Y, Z now, mm."""
        c = self._comp
        return [c[f"{a}-eoffset"] for a in "xyz"] + [c[f"{a}-request"] for a in "xyz"]


@dataclass
class LinuxCNCXYZ(ExternalOffsets, LinuxCNC):
    """One headless LinuxCNC session on a simulated XYZ machine (a context manager), mm.

    Parameters
    ----------
    travel : dict of str to (float, float), mm
        Each axis's travel; the limits are 1 mm beyond (room for the final approach).
    comp_files : dict of str to str, optional
        ``COMP_FILE`` text per axis (``[JOINT_N] COMP_FILE = L.comp``, ``COMP_FILE_TYPE`` as
        ``comp_file_type``).
    volcomp : dict, optional
        The correction map ``axiscal_volcomp.py`` evaluates (written as ``volcomp.json``); None:
        no external offsets.
    av_ratio : float
        ``[AXIS_L] OFFSET_AV_RATIO``.
    settle_timeout : float, s
        Longest wait for the external offsets to settle after a move.
    """

    limits: tuple = (0.0, 0.0)
    travel: dict = field(default_factory=dict)
    comp_files: dict = field(default_factory=dict)
    volcomp: dict | None = None
    av_ratio: float = 0.2
    velocity: float = 5000.0
    acceleration: float = 1.0e5
    settle_timeout: float = 5.0

    #: The HAL component that drives the external offsets (its ``cycles`` pin is waited on).
    offset_component = "axiscal-volcomp"

    def _offsets_driven(self) -> bool:
        """Whether a component drives the external offsets (a subclass may load another)."""
        return self.volcomp is not None

    def _extra_pins(self, comp, nets: list) -> None:
        """Pins a subclass adds to the session's component before it is made ready."""

    def _write_config(self) -> None:
        self.folder = Path(tempfile.mkdtemp(prefix="axiscal-linuxcnc-"))
        os.chmod(self.folder, 0o1777)
        data = resources.files("axiscal.data") / "linuxcnc"
        axis_t = Template((data / "axiscal_xyz_axis.ini").read_text())
        axes = []
        for j, a in enumerate(AXES):
            lo, hi = (float(v) for v in self.travel[a])
            comp = ""
            if a in self.comp_files:
                (self.folder / f"{a.lower()}.comp").write_text(self.comp_files[a])
                comp = f"COMP_FILE = {a.lower()}.comp\nCOMP_FILE_TYPE = {self.comp_file_type}"
            axes.append(axis_t.substitute(
                letter=a, joint=j, min_limit=repr(lo - 1.0), max_limit=repr(hi + 1.0),
                velocity=repr(float(self.velocity)), acceleration=repr(float(self.acceleration)),
                av_ratio=repr(float(self.av_ratio)), home=repr(min(max(0.0, lo), hi)),
                comp_lines=comp))
        vol = ""
        if self.volcomp is not None:
            vol = "HALFILE = axiscal_volcomp.hal"
            (self.folder / "volcomp.json").write_text(json.dumps(self.volcomp))
            for name in ("axiscal_volcomp.hal", "axiscal_volcomp.py"):
                (self.folder / name).write_text((data / name).read_text())
        self.ini_text = Template((data / "axiscal_xyz.ini").read_text()).substitute(
            velocity=repr(float(self.velocity)), volcomp_hal=vol, axes="\n".join(axes))
        (self.folder / "config.ini").write_text(self.ini_text)
        for name in ("axiscal_xyz.hal", "axiscal_approach_xyz.ngc"):
            (self.folder / name).write_text((data / name).read_text())
        (self.folder / "tool.tbl").write_text("")

    def _connect(self) -> None:
        import hal

        comp = self._open_channels("axiscal-xyz")
        nets = []
        for j, a in enumerate(AXES):
            for pin in ("motor-pos-cmd", "pos-cmd"):
                comp.newpin(f"j{j}-{pin}", hal.HAL_FLOAT, hal.HAL_IN)
                nets.append((f"j{j}-{pin}", f"axiscal-xyz.j{j}-{pin}"))
        if self._offsets_driven():
            nets += offset_pins(comp, self.offset_component)
        self._extra_pins(comp, nets)
        self._ready(comp, nets)
        self._switch_on_and_home(len(AXES))

    def move_to(self, target) -> np.ndarray:
        """Reach ``target`` (x, y, z mm), arriving moving + on every axis at the creep feed;
        once the external offsets have settled, the joints' ``motor-pos-cmd`` (3,), mm."""
        t = [float(v) for v in target]
        start = " ".join(f"[{v - CREEP:.9f}]" for v in t)
        end = " ".join(f"[{v:.9f}]" for v in t)
        self.mdi(f"o<axiscal_approach_xyz> call {start} {end} [{CREEP_FEED:g}]")
        self.wait_periods(SETTLE_PERIODS)
        if self._offsets_driven():
            self.wait_offsets(self.offset_component, t)
        c = self._comp
        return np.array([c[f"j{j}-motor-pos-cmd"] for j in range(3)], dtype=float)

    def commanded(self) -> np.ndarray:
        """The joints' ``pos-cmd`` now (the offset included, the trim not), mm."""
        return np.array([self._comp[f"j{j}-pos-cmd"] for j in range(3)], dtype=float)

    def move(self, *args, **kwargs):
        raise MeasurementError("LinuxCNCXYZ moves three joints: use move_to")
