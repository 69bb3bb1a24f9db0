"""The compensation loop measured through a real LinuxCNC (issue 32).

:func:`run_on_linuxcnc` runs :func:`axiscal.compensation.loop.run_compensation_loop` with
:class:`OnLinuxCNC` as its machine: the ISO 230-2:2014 test (§3.1, both directions) is run
through a headless LinuxCNC (:class:`axiscal.instruments.linuxcnc_controller.LinuxCNC`) on the
bare axis, the table is written with axiscal's LinuxCNC writer
(:mod:`axiscal.compensation.controllers.linuxcnc`), loaded through the INI LinuxCNC reads
(``[JOINT_0] COMP_FILE``, ``COMP_FILE_TYPE``; LinuxCNC documentation, "INI Configuration") into a
fresh LinuxCNC, and the test is run again. At every target and direction of the second test,
:func:`applied_trims` sets the trim LinuxCNC applied (``joint.0.motor-pos-cmd − joint.0.pos-cmd``)
beside the value of the table read back from the file (forward column moving +, reverse moving −:
LinuxCNC ``src/emc/motion/control.c``, ``compute_screw_comp``).
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from axiscal.errors import ConfigError

__all__ = ["OnLinuxCNC", "AppliedTrim", "applied_trims", "run_on_linuxcnc"]

#: Table position unit (mm or deg) per machine unit (``[TRAJ] LINEAR_UNITS``; deg: a rotary
#: joint in ``ANGULAR_UNITS = degree``).
MM_PER_UNIT = {"mm": 1.0, "inch": 25.4, "deg": 1.0}
#: Correction unit (µm or arcsec) per table position unit.
_CORRECTION = {"mm": 1e3, "deg": 3600.0}


@dataclass(frozen=True)
class AppliedTrim:
    """At one target and direction: the table's correction and the trim LinuxCNC applied.

    Attributes
    ----------
    target : float, mm (deg)
    direction : str
        ``+`` or ``-``.
    table, applied : float, µm (arcsec)
        The correction of the table read back from the file, and LinuxCNC's trim (mean over the
        runs).
    difference : float, µm (arcsec)
        The largest |applied − table| over the runs.
    n : int
        Readings (runs) at this target and direction.
    """

    target: float
    direction: str
    table: float
    applied: float
    difference: float
    n: int

    def to_dict(self) -> dict:
        return dict(self.__dict__)


@dataclass
class OnLinuxCNC:
    """The machine hook of :func:`~axiscal.compensation.loop.run_compensation_loop`: measure
    through LinuxCNC (the bare axis, then with ``controller_file`` as its ``COMP_FILE``).

    Attributes
    ----------
    file_type : int
        ``COMP_FILE_TYPE`` the file is written and loaded as.
    units : str
        ``[TRAJ] LINEAR_UNITS`` (``mm`` or ``inch``), the file's unit.
    dwell : float, s
        G4 after each move on the simulated drive (0: it settles at once; the plan's dwell, for a
        real machine's settling, is kept in ``plan_dwell`` and shown beside it).
    logs : list
        One reading log per test (:attr:`LinuxCNCAxis.log`).
    """

    file_type: int = 1
    units: str = "mm"
    dwell: float = 0.0
    logs: list = field(default_factory=list)
    plan_dwell: float | None = None

    def measure(self, plan, axis, rng, measurement_sigma, controller_file):
        """Run ``plan`` through LinuxCNC on ``axis`` and return the dataset."""
        from axiscal.instruments.linuxcnc_controller import LinuxCNC, LinuxCNCAxis
        from axiscal.procedures.positioning import simulate_positioning_test

        k = MM_PER_UNIT[self.units]
        self.plan_dwell = plan.dwell
        if axis.travel is None:                  # a continuous rotary axis: the test's range
            lo = plan.targets[0] - plan.overrun - 1.0
            hi = plan.targets[-1] + plan.overrun + 1.0
        else:
            lo, hi = np.degrees(axis.travel) if self.units == "deg" else np.asarray(axis.travel) * 1e3
        lo, hi = lo / k, hi / k
        text = None if controller_file is None else controller_file.text
        with LinuxCNC((lo - 1.0, hi + 1.0), units=self.units, comp_file=text,
                      comp_file_type=self.file_type) as cnc:
            on = LinuxCNCAxis(cnc, axis, overrun=plan.overrun / k, dwell=self.dwell)
            ds = simulate_positioning_test(plan, on, rng, measurement_sigma=measurement_sigma)
        self.logs.append(on.log)
        return ds


def applied_trims(log, table, units: str = "mm") -> list[AppliedTrim]:
    """At every target and direction of ``log``, LinuxCNC's trim beside ``table``'s value.

    Parameters
    ----------
    log : list of (float mm, int, Reading)
        :attr:`LinuxCNCAxis.log` of the compensated test.
    table : CompensationTable
        The table read back from the file (corrections in µm, or arcsec for a rotary joint).
    units : str
        The machine's unit (the log's readings are in it): mm, inch or deg.
    """
    um = MM_PER_UNIT[units] * _CORRECTION["deg" if units == "deg" else "mm"]
    groups: dict = {}
    for target, d, r in log:
        groups.setdefault((round(target, 6), d), []).append(r.trim * um)
    out = []
    for (target, d), trims in sorted(groups.items(), key=lambda g: (-g[0][1], g[0][0])):
        want = float(table.correction_at(np.array([target]), d)[0])
        t = np.asarray(trims)
        out.append(AppliedTrim(target, "+" if d > 0 else "-", want, float(t.mean()),
                               float(np.max(np.abs(t - want))), len(trims)))
    return out


def run_on_linuxcnc(config: dict, seed: int = 1, **overrides):
    """The compensation loop measured through LinuxCNC: ``(loop result, applied trims, hook)``.

    ``overrides`` as for :func:`~axiscal.compensation.loop.run_compensation_loop`; the
    controller is LinuxCNC and its ``file_type`` and ``unit`` options (default 1 and mm, shown
    by the caller) set the INI as well as the file.
    """
    from axiscal.compensation.loop import loop_settings, run_compensation_loop

    cfg = dict(config)
    cfg["compensation"] = {**config.get("compensation", {}), **overrides}
    s = loop_settings(cfg)
    if s["controller"] != "linuxcnc":
        raise ConfigError(f"--on-controller runs LinuxCNC; the controller is {s['controller']!r}: "
                          "give --controller linuxcnc")
    opts = s["options"]
    rotary = str(config.get("axis", {}).get("kind", "linear")) == "rotary"
    units = "deg" if rotary else str(opts.get("unit", "mm"))
    if rotary and "unit" in opts:
        raise ConfigError("a rotary joint's file is in degrees ([TRAJ] ANGULAR_UNITS = degree): "
                          "drop the unit option")
    if units not in MM_PER_UNIT:
        raise ConfigError(f"[compensation] options unit = {units!r}: LinuxCNC's LINEAR_UNITS "
                          "here are mm or inch")
    hook = OnLinuxCNC(file_type=int(opts.get("file_type", 1)), units=units)
    r = run_compensation_loop(config, seed=seed, machine=hook, **overrides)
    return r, applied_trims(hook.logs[-1], r.table, units), hook


def summary(applied: list[AppliedTrim], hook: OnLinuxCNC) -> dict:
    """What the ``--json`` of ``compensate --verify --on-controller`` adds: ``applied`` (each
    target and direction) and ``on_controller`` (the INI settings used, shown since they move the
    numbers, and the largest |applied − table|, µm or arcsec)."""
    worst = max((a.difference for a in applied), default=float("nan"))
    return dict(applied=[a.to_dict() for a in applied],
                on_controller=dict(controller="LinuxCNC (linuxcnc-uspace), headless simulation",
                                   comp_file_type=hook.file_type, machine_units=hook.units,
                                   dwell_s=hook.dwell, plan_dwell_s=hook.plan_dwell,
                                   applied_unit="arcsec" if hook.units == "deg" else "um",
                                   largest_applied_difference=worst,
                                   n_applied=len(applied)))
