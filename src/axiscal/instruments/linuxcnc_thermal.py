"""A live LinuxCNC with axiscal's temperature compensation of its X axis loaded (issue 44).

:class:`LinuxCNCThermal` is :class:`~axiscal.instruments.linuxcnc_xyz.LinuxCNCXYZ` (the same
headless three-joint simulated machine, start, lock and clean-up) whose external offsets are
driven by axiscal's userspace HAL component ``axiscal_thermcomp.py`` (package data, with
``axiscal_thermcomp.hal``) instead of the volumetric one. The session's own component
(``axiscal-xyz``) gets output pins that stand for the machine's temperature inputs:
``temp-0`` … (°C, netted to ``axiscal-thermcomp.temp-N``) and ``time`` (s, the sensors' clock,
netted to ``axiscal-thermcomp.time``), so the simulated sensors feed LinuxCNC through HAL as a
machine's would; :meth:`LinuxCNCThermal.feed` writes one reading of every sensor and waits until
the component has taken it. ``active`` switches the correction (0: the offset is held at no
correction, the run without compensation in the same session).
"""

from __future__ import annotations

import json
from dataclasses import dataclass, field
from importlib import resources

from axiscal.errors import MeasurementError
from axiscal.instruments.linuxcnc_controller import _wait
from axiscal.instruments.linuxcnc_xyz import LinuxCNCXYZ

__all__ = ["LinuxCNCThermal"]


@dataclass
class LinuxCNCThermal(LinuxCNCXYZ):
    """One headless LinuxCNC session with the temperature compensation loaded (mm, °C, s).

    Parameters
    ----------
    thermcomp : dict
        What ``axiscal_thermcomp.py`` reads (written as ``thermcomp.json``): ``sensors``,
        ``lags_s``, ``k0_mm_per_K``, ``slope_per_K``, ``p0_mm``, ``clock``.
    """

    thermcomp: dict = field(default_factory=dict)
    #: What the component was given since its last start (``("start"|"feed", t, temps)``) and
    #: whether it is active: replayed when the session starts again (:meth:`_restart`).
    _given: list = field(default_factory=list, init=False, repr=False)
    _active: bool = field(default=False, init=False, repr=False)

    offset_component = "axiscal-thermcomp"

    def _offsets_driven(self) -> bool:
        return True

    @property
    def sensors(self) -> int:
        return len(self.thermcomp["sensors"])

    def _write_config(self) -> None:
        super()._write_config()
        data = resources.files("axiscal.data") / "linuxcnc"
        (self.folder / "thermcomp.json").write_text(json.dumps(self.thermcomp))
        for name in ("axiscal_thermcomp.hal", "axiscal_thermcomp.py"):
            (self.folder / name).write_text((data / name).read_text())
        self.ini_text = self.ini_text.replace(
            "HALFILE = axiscal_xyz.hal\n",
            "HALFILE = axiscal_xyz.hal\nHALFILE = axiscal_thermcomp.hal\n", 1)
        (self.folder / "config.ini").write_text(self.ini_text)

    def _extra_pins(self, comp, nets: list) -> None:
        import hal

        for i in range(self.sensors):
            comp.newpin(f"temp-{i}", hal.HAL_FLOAT, hal.HAL_OUT)
            nets.append((f"tc-temp-{i}", f"axiscal-xyz.temp-{i}", f"axiscal-thermcomp.temp-{i}"))
        for name, kind, d in (("time", hal.HAL_FLOAT, hal.HAL_OUT),
                              ("active", hal.HAL_BIT, hal.HAL_OUT),
                              ("reset", hal.HAL_BIT, hal.HAL_OUT),
                              ("tc-error", hal.HAL_FLOAT, hal.HAL_IN)):
            comp.newpin(name, kind, d)
        nets += [("tc-time", "axiscal-xyz.time", "axiscal-thermcomp.time"),
                 ("tc-active", "axiscal-xyz.active", "axiscal-thermcomp.active"),
                 ("tc-reset", "axiscal-xyz.reset", "axiscal-thermcomp.reset"),
                 ("tc-error", "axiscal-thermcomp.error", "axiscal-xyz.tc-error")]

    def set_active(self, on: bool) -> None:
        """Switch the correction on or off (the component's ``active`` pin)."""
        self._active = bool(on)
        self._comp["active"] = self._active

    def start(self, t: float, temperatures) -> None:
        """Start the component's filters afresh from this first reading (°C) at ``t`` (s):
        ``reset`` held while the pins take it, then released (the component takes the reading
        at the release)."""
        self._given = [("start", float(t), [float(v) for v in temperatures])]
        self._start_filters(t, temperatures)

    def _start_filters(self, t: float, temperatures) -> None:
        c = self._comp
        c["reset"] = True
        self._cycles(2, "axiscal-thermcomp to empty its filters")
        for i, v in enumerate(temperatures):
            c[f"temp-{i}"] = float(v)
        c["time"] = float(t)
        c["reset"] = False
        self._cycles(2, "axiscal-thermcomp to take the first reading")

    def _cycles(self, n: int, what: str) -> None:
        c = self._comp
        c0 = c["cycles"]
        _wait(lambda: (c["cycles"] - c0) % 2 ** 31 >= n, self.settle_timeout, what,
              poll=0.0005)

    def feed(self, t: float, temperatures) -> None:
        """One reading of every sensor (°C) at the sensors' time ``t`` (s): the temperatures
        first, then the time (the component takes a reading when the time moves, so it never
        sees a new time with old temperatures); returns once the component has run twice
        since."""
        self._given.append(("feed", float(t), [float(v) for v in temperatures]))
        self._feed(t, temperatures)

    def _feed(self, t: float, temperatures) -> None:
        c = self._comp
        for i, v in enumerate(temperatures):
            c[f"temp-{i}"] = float(v)
        c["time"] = float(t)
        # counted from after the time is set: the loop running then may have read the old time
        # (it ends: one), the next reads the new one (two). Counted from before, two loops that
        # both read the old time could pass for it: a reading merged into the next (seen once,
        # ΔK 57 nm off the model's)
        self._cycles(2, "axiscal-thermcomp to take the temperatures")

    def _restart(self) -> None:
        """Start LinuxCNC again (:meth:`LinuxCNC._restart`), then give the new component what
        the old one was given, in order: its filters are where they were (the model's lags
        depend on every reading since the start)."""
        super()._restart()
        self._comp["active"] = self._active
        for what, t, temps in self._given:
            (self._start_filters if what == "start" else self._feed)(t, temps)

    def correction_error(self) -> float:
        """ΔK the component evaluates now (mm; 0 while ``active`` is off)."""
        return float(self._comp["tc-error"])

    def move(self, *args, **kwargs):
        raise MeasurementError("LinuxCNCThermal moves three joints: use move_to")
