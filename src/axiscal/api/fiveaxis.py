"""Five-axis kinematics in the public API: ``axiscal.fiveaxis.plan | simulate | identify``.

The location errors of the rotary axes of a table-table machine (A/C or B/C), from spheres
probed at many rotary poses and R-tests (issue 43)::

    import axiscal

    check = axiscal.fiveaxis.plan("fiveaxis_ac.toml")       # rank, condition, what is unseen
    sim = axiscal.fiveaxis.simulate("fiveaxis_ac.toml", seed=1, out="run")   # the twin
    result = axiscal.fiveaxis.identify("fiveaxis_ac.toml", ["run/1_probing.csv"])
    result["E_X0C"].value, result["E_X0C"].U        # metres (value_display: µm)
    result.to_dict()                                # the keys of ``--json``

``axiscal fiveaxis plan | simulate | identify`` call these same functions. The configuration is
described in :mod:`axiscal.machines.five_axis` (machine) and :mod:`axiscal.procedures.five_axis`
(set-ups); the files in :mod:`axiscal.io.five_axis`; the identification, its convention and its
uncertainty in :mod:`axiscal.standards.location_errors`.
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np

from axiscal.api import fiveaxis_ballbar as ballbar   # axiscal.fiveaxis.ballbar.plan | ...
from axiscal.api._fiveaxis_common import config_dict as _config, check_seed as _seed
from axiscal.errors import InputError

TYPE_CHECKING = False   # as typing.TYPE_CHECKING, without importing typing
if TYPE_CHECKING:   # pragma: no cover - for type checkers
    from axiscal.compensation.five_axis import TrtCorrection, Verification
    from axiscal.machines.five_axis import FiveAxisMachine
    from axiscal.procedures.five_axis import FiveAxisPlan
    from axiscal.standards.location_errors import LocationIdentification, PlanCheck

__all__ = ["plan", "simulate", "identify", "compensate", "figure", "report", "load", "Simulated", "Planned",
           "Compensated", "EXAMPLES", "ballbar"]

#: The example configurations shipped with the package (``axiscal.data``).
EXAMPLES = {"A/C": "fiveaxis_ac.toml", "B/C": "fiveaxis_bc.toml",
            "head B/C": "fiveaxis_head_bc.toml"}


@dataclass(frozen=True, eq=False)
class Planned:
    """A plan and what it can separate: ``check`` (PlanCheck), ``plan`` (FiveAxisPlan),
    ``machine`` (FiveAxisMachine)."""

    check: PlanCheck
    plan: FiveAxisPlan
    machine: FiveAxisMachine

    def to_dict(self) -> dict:
        """The ``--json`` object of ``axiscal fiveaxis plan``."""
        out = self.check.to_dict()
        out["machine"] = self.machine.name
        out["setups"] = [{"label": s.label, "kind": s.kind, "poses": s.poses,
                          "place_mm": (np.asarray(s.place) * 1e3).tolist(),
                          "angles_deg": np.degrees(np.column_stack([s.tilt_angle, s.c_angle]))
                          .round(6).tolist()} for s in self.plan.setups]
        return out

    def __str__(self) -> str:
        lines = [f"{self.machine.name}: {len(self.plan.setups)} set-ups"]
        for s in self.plan.setups:
            lines.append(f"  {s.label} ({s.kind}): {s.poses} poses, place "
                         f"({', '.join(f'{v * 1e3:g}' for v in s.place)}) mm")
        return "\n".join(lines + [str(self.check)])


@dataclass(frozen=True, eq=False)
class Simulated:
    """A simulated measurement of the twin and its identification: ``records`` (one per
    set-up), ``result`` (LocationIdentification), ``machine`` (with the truth), ``files``
    (written paths, or empty)."""

    records: tuple
    result: LocationIdentification
    machine: FiveAxisMachine
    files: tuple = ()

    def truth(self) -> dict[str, float]:
        """True value (µm, µrad) of each reported name in the result's convention: sums added
        as they are reported; on a spindle head the head's zero counted in the positions across
        (:func:`axiscal.standards.location_errors.conventions`)."""
        t = dict(self.machine.truth_display())
        g = self.machine.geometry
        if g.head:
            zero = t[f"E_{g.tilt}0{g.tilt}"] * g.pivot      # µrad × m = µm
            if g.tilt == "B":
                t["E_X0C"], t["E_X0B"] = t["E_X0C"] + zero, t["E_X0B"] + zero
            else:
                t["E_Y0C"], t["E_Y0A"] = t["E_Y0C"] - zero, t["E_Y0A"] - zero
        out = {}
        for e in self.result.errors:
            out[e.name] = sum(t.get(n, 0.0) for n in e.name.split("+"))
        return out

    def to_dict(self) -> dict:
        """The ``--json`` object of ``axiscal fiveaxis simulate``."""
        out = self.result.to_dict()
        truth = self.truth()
        out["truth"] = self.machine.truth_display()
        for e in out["errors"]:
            e["true"] = truth[e["name"]]
            e["deviation"] = e["value"] - e["true"]
        out["files"] = [str(f) for f in self.files]
        return out

    def __str__(self) -> str:
        truth = self.truth()
        lines = [str(self.result), "simulation truth (deviation of the identified value):"]
        lines += [f"  {e.name}: true {truth[e.name]:+.2f} {e.unit}, identified − true "
                  f"{e.value_display - truth[e.name]:+.2f} {e.unit}" for e in self.result.errors]
        return "\n".join(lines)


@dataclass(frozen=True, eq=False)
class Compensated:
    """The correction in LinuxCNC's terms (``correction``, TrtCorrection), the identification it
    comes from (``result``) and, when asked, the twin's ``verification`` (before/after ranges)."""

    correction: TrtCorrection
    result: LocationIdentification
    verification: Verification | None = None
    on_controller: bool = False
    sinumerik: Any = None

    def to_dict(self) -> dict:
        """The ``--json`` object of ``axiscal fiveaxis compensate``."""
        out = self.correction.to_dict()
        out["verify"] = None if self.verification is None else self.verification.to_dict()
        out["on_controller"] = self.on_controller
        out["sinumerik"] = None if self.sinumerik is None else self.sinumerik.to_dict()
        return out

    def __str__(self) -> str:
        text = self.correction.hal().rstrip()
        if self.verification is not None:
            text += ("\nverified through LinuxCNC (trt kinematics; sphere-centre and R-test "
                     "deviation ranges):\n"
                     if self.on_controller else
                     "\nverified on the twin (sphere-centre and R-test deviation ranges):\n")
            text += str(self.verification)
        return text


def load(config):
    """The twin and its plan from a configuration (a TOML path or a dict)."""
    from axiscal.machines.five_axis import five_axis_from_config
    from axiscal.procedures.five_axis import plan_from_config

    cfg = _config(config)
    machine = five_axis_from_config(cfg)
    return machine, plan_from_config(cfg, machine)


def plan(config, squareness: bool = False) -> Planned:
    """What the configuration's set-ups can separate, before measuring (rank, condition, the
    unseen location errors with the test that would see them); with ``squareness`` also the
    linear axes' three squareness errors."""
    from axiscal.standards.location_errors import check_plan

    machine, p = load(config)
    return Planned(check_plan(machine.geometry, [s.nominal_setup() for s in p.setups],
                              squareness), p, machine)


def simulate(config, seed: int = 1, out=None, squareness: bool = False,
             on_controller: bool = False) -> Simulated:
    """Measure the twin with its simulated instruments, identify (with ``squareness``, the
    linear axes' squareness too), and (with ``out``, a folder) write one CSV per set-up
    (``1_probing.csv``, ``2_r-test.csv`` ...). With ``on_controller`` the set-ups are run
    through a live LinuxCNC (trt kinematics with the nominal pins: the controller runs the
    probing moves and the R-test poses, the twin measures from its joints;
    :func:`axiscal.compensation.on_controller_five_axis.measure_on_linuxcnc`)."""
    from axiscal.io.five_axis import format_five_axis
    from axiscal.standards.location_errors import identify_location_errors

    machine, p = load(config)
    if on_controller:
        from axiscal.compensation.on_controller_five_axis import measure_on_linuxcnc

        records = measure_on_linuxcnc(machine, p, _seed(seed))
    else:
        records = _measure(machine, p, seed)
    result = identify_location_errors(machine.geometry, [r.setup() for r in records],
                                      squareness=squareness)
    files: tuple = ()
    if out is not None:
        from axiscal.io._files import write_bytes_atomic

        folder = Path(out)
        texts = [(folder / f"{i}_{r.kind}.csv", format_five_axis(r, machine.geometry))
                 for i, r in enumerate(records, 1)]
        try:
            folder.mkdir(parents=True, exist_ok=True)
        except OSError as exc:
            raise InputError(f"cannot make the folder {folder}: {exc.strerror or exc}") from None
        files = tuple(write_bytes_atomic(f, t.encode("utf-8")) for f, t in texts)
    return Simulated(records, result, machine, files)


def identify(config, files, squareness: bool = False):
    """Identify the location errors from measured files (probing and R-test CSVs, any mix);
    with ``squareness`` also the linear axes' three squareness errors (ISO 230-1 names
    E_C(0X)Y, E_B(0X)Z, E_A(0Y)Z).

    Parameters
    ----------
    config : path or dict
        The machine's configuration; only ``[machine]`` is read (its nominal geometry and the
        axes' travel).
    files : sequence of path
    """
    from axiscal.io.five_axis import read_five_axis
    from axiscal.machines.five_axis import five_axis_from_config
    from axiscal.standards.location_errors import identify_location_errors

    machine = five_axis_from_config(_config(config))
    files = list(files)
    if not files:
        raise InputError("give at least one probing or R-test file")
    records = []
    for f in files:
        r = read_five_axis(f)
        if r.tilt != machine.tilt:
            raise InputError(f"{f}: the file's poses are {r.tilt}/C, the machine is "
                             f"{machine.tilt}/C")
        try:
            machine.check_pose(r.tilt_angle, r.c_angle)
        except InputError as exc:
            raise InputError(f"{f}: {exc}") from None
        records.append(r)
    setups = []
    for f, r in zip(files, records):
        try:
            setups.append(r.setup())
        except InputError as exc:
            raise InputError(f"{f}: {exc}") from None
    return identify_location_errors(machine.geometry, setups, squareness=squareness)


def compensate(config, files, z_rot_point: float = 0.0, verify: bool = False,
               seed: int = 7, on_controller: bool = False) -> Compensated:
    """Identify from ``files`` and give the LinuxCNC trt parameters that put the location errors
    right (:mod:`axiscal.compensation.five_axis`); with ``verify``, re-measure the configuration's
    twin before and after (a simulated configuration only: it needs ``[[setup]]``).

    Parameters
    ----------
    z_rot_point : float, mm
        The ``z-rot-point`` pin as set now (kept; only its sum with ``z-offset`` counts).
    on_controller : bool
        With ``verify``: run the configuration's probing and R-test set-ups through a live
        LinuxCNC (its trt kinematics, and after the correction the external offsets, compute
        the joints the twin then reads), before and after the correction
        (:mod:`axiscal.compensation.on_controller_five_axis`).
    """
    from axiscal.compensation.five_axis import trt_correction, verify_on_twin

    cfg = _config(config)
    result = identify(cfg, files)
    machine, p = load(cfg) if verify else (None, None)
    from axiscal.machines.five_axis import five_axis_from_config

    geometry = five_axis_from_config(cfg).geometry
    correction = trt_correction(geometry, result, z_rot_point * 1e-3)
    from axiscal.compensation.five_axis_sinumerik import swivel_data

    swivel = swivel_data(geometry, result)
    check = None
    if on_controller and not verify:
        raise InputError("--on-controller verifies through LinuxCNC: give --verify too")
    if verify and on_controller:
        from axiscal.compensation.on_controller_five_axis import verify_on_linuxcnc

        check = verify_on_linuxcnc(machine, p, correction, seed, z_rot_point)
    elif verify:
        check = verify_on_twin(machine, p, correction, seed)
    return Compensated(correction, result, check, bool(verify and on_controller), swivel)


def figure(config, result):
    """The axis lines in 3-D (magnified) beside the identified values with U (a matplotlib
    Figure; :func:`axiscal.report.five_axis_plots.location_figure`)."""
    from axiscal.machines.five_axis import five_axis_from_config
    from axiscal.report.five_axis_plots import location_figure

    return location_figure(five_axis_from_config(_config(config)).geometry, result)


def report(config, result, path, files=(), truth=None):
    """Write the identification's report (HTML, or PDF for a ``.pdf`` name) and return its path
    (:func:`axiscal.report.five_axis_plots.location_report`)."""
    from axiscal.machines.five_axis import five_axis_from_config
    from axiscal.report.five_axis_plots import location_report

    machine = five_axis_from_config(_config(config))
    return location_report(machine.geometry, result, name=machine.name, truth=truth,
                           files=files).write(path)


def _measure(machine, p, seed: int):
    from axiscal.procedures.five_axis import measure

    return measure(machine, p, np.random.default_rng(_seed(seed)))
