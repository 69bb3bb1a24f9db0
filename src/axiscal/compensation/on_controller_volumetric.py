"""The volumetric (3-D) correction applied by LinuxCNC's external offsets, measured before and
after through a real LinuxCNC (issue 32).

From the 21 measured errors and the tables of :func:`~axiscal.compensation.volumetric.
volumetric_tables`, :func:`linuxcnc_compensation` builds what LinuxCNC is given:

* a ``COMP_FILE`` per joint (the positioning table of that axis, axiscal's LinuxCNC writer;
  LinuxCNC documentation, "INI Configuration", ``[JOINT_N] COMP_FILE``);
* the correction map of axiscal's HAL component ``axiscal_volcomp.py`` (package data), applied as
  external offsets (LinuxCNC documentation, "External Axis Offsets"): the cross-axis tables
  (straightness and squareness of one axis corrected on another, which a COMP_FILE, a function of
  its own joint only, cannot hold) and, for the 3-D correction, a grid of what tables cannot
  remove: the Abbe products of one axis's angular errors with the travel of the axes after it at
  the tool point, ``−E_cross`` of :func:`axiscal.standards.volumetric.volumetric_error`
  (Schwenke et al., "Geometric error measurement and compensation of machines — An update", CIRP
  Annals 57 (2008), eq. 3; ISO/TR 16907:2015, numerical compensation of geometric errors).

:func:`verify_on_linuxcnc` measures the simulated machine three times through LinuxCNC, in one
run: bare, with the tables alone (COMP_FILEs + cross-axis tables) and with the tables plus the
3-D grid. The simulated machine's errors act on the three joints' ``motor-pos-cmd`` (command,
external offset and trim: what reaches the drives), and the simulated laser tests of
:mod:`axiscal.procedures.volumetric` measure it at every point they ask for, each point a move of
LinuxCNC. The figures are those of :func:`axiscal.compensation.volumetric.verify`: the largest
volumetric error and the three ranges of the map of the re-measured errors, and the range of each
of the four body diagonals (ISO 230-6:2002).
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from axiscal.compensation.volumetric import fall, fall_text, figure_row, figure_rows
from axiscal.errors import InputError
from axiscal.machines.seen_through import MachineSeenThrough
from axiscal.standards.volumetric import AXES, GeometricErrors, volumetric_error

__all__ = ["LinuxCNCCompensation", "linuxcnc_compensation", "linuxcnc_outputs",
           "ThroughLinuxCNC", "OnControllerResult", "verify_on_linuxcnc", "STATES"]

#: The three measurements of one run: (key, label).
STATES = (("before", "bare"), ("tables", "tables alone"), ("volumetric", "tables + 3-D"))


@dataclass(frozen=True, eq=False)
class LinuxCNCCompensation:
    """What LinuxCNC is given (all mm).

    Attributes
    ----------
    files : list of ControllerFile
        The three COMP_FILEs (``x.comp``, ``y.comp``, ``z.comp``).
    cross : list of dict
        The cross-axis tables as ``axiscal_volcomp.py`` reads them.
    grid : dict
        The 3-D grid of the Abbe products (``x``, ``y``, ``z`` nodes, ``values[axis][i][j][k]``).
    spacing : float, mm
        Spacing of the grid's nodes (at most; each axis's travel in equal steps).
    """

    files: list
    cross: list
    grid: dict
    spacing: float

    def comp_files(self) -> dict:
        """COMP_FILE text per axis."""
        return {a: f.text for a, f in zip(AXES, self.files)}

    def volcomp(self, volumetric: bool = True) -> dict:
        """The component's map: the cross-axis tables, with the 3-D grid when ``volumetric``."""
        return {"unit": "mm", "cross": self.cross, "grid": self.grid if volumetric else None}


def linuxcnc_compensation(errors: GeometricErrors, tables, *, grid_spacing: float = 50.0,
                          file_type: int = 1) -> LinuxCNCCompensation:
    """COMP_FILEs, cross-axis tables and the 3-D grid for LinuxCNC (module docstring).

    ``grid_spacing`` (mm) sets the grid of the Abbe products: trilinear between nodes in the
    component; each axis's travel cut in equal steps of at most this.
    """
    from axiscal.compensation.controllers import linuxcnc

    if not 1.0 <= grid_spacing <= 10_000.0:
        raise InputError(f"grid spacing = {grid_spacing!r} mm: between 1 and 10000")
    travel_mm = errors.travel_mm
    files = [linuxcnc.write(tables.positioning[a], travel_mm[a], file_type=file_type, joint=j)
             for j, a in enumerate(AXES)]
    cross = []
    for ct in tables.cross:
        p = ct.table.positions
        cross.append({"driving": ct.driving_axis, "receiving": ct.compensated_axis,
                      "positions": [float(v) for v in p],
                      "corrections": [float(v) * 1e-3 for v in ct.table.correction_at(p)]})
    nodes = []
    for a in AXES:
        lo, hi = travel_mm[a]
        n = int(np.ceil((hi - lo) / grid_spacing - 1e-9)) + 1
        nodes.append(np.linspace(lo, hi, max(n, 2)))
    X, Y, Z = np.meshgrid(*nodes, indexing="ij")
    corr = -volumetric_error(errors, X * 1e-3, Y * 1e-3, Z * 1e-3, tables.tool_offset,
                             part="cross") * 1e3
    grid = {a.lower(): [float(v) for v in n] for a, n in zip(AXES, nodes)}
    grid["values"] = np.round(corr, 9).tolist()
    return LinuxCNCCompensation(files, cross, grid, float(grid_spacing))


def linuxcnc_outputs(comp: LinuxCNCCompensation) -> dict:
    """The files a LinuxCNC machine is given (name -> text): the three COMP_FILEs, the map
    ``volcomp.json`` (cross-axis tables and 3-D grid), the component ``axiscal_volcomp.py`` and
    its HAL file ``axiscal_volcomp.hal`` (docs/linuxcnc.md says where each goes)."""
    import json
    from importlib import resources

    data = resources.files("axiscal.data") / "linuxcnc"
    out = {f"{a.lower()}.comp": f.text for a, f in zip(AXES, comp.files)}
    out["volcomp.json"] = json.dumps(comp.volcomp(True)) + "\n"
    for name in ("axiscal_volcomp.py", "axiscal_volcomp.hal"):
        out[name] = (data / name).read_text()
    return out


@dataclass
class ThroughLinuxCNC(MachineSeenThrough):
    """A simulated three-axis machine moved by LinuxCNC: what the procedures' ``pose`` asks.

    Every commanded point (m) is a move of :class:`~axiscal.instruments.linuxcnc_xyz.
    LinuxCNCXYZ`; the machine's pose is taken at the joints' ``motor-pos-cmd``. A point asked
    again is not moved to again (the same command gives the same drive positions); ``log``
    keeps (commanded mm, motor mm) of each move.
    """

    cnc: object
    machine: object
    log: dict = field(default_factory=dict)

    def pose(self, x, y, z, tool_offset=(0.0, 0.0, 0.0)):
        """Tool pose (see ``ThreeAxisMachine.pose``) with the joints where LinuxCNC drives them."""
        q = np.stack([np.ravel(v) for v in np.broadcast_arrays(
            *(np.asarray(v, float) for v in (x, y, z)))], axis=1) * 1e3
        motor = np.empty_like(q)
        for n, p in enumerate(q):
            key = tuple(np.round(p, 6))
            if key not in self.log:
                self.log[key] = self.cnc.move_to(p)
            motor[n] = self.log[key]
        m = motor * 1e-3
        return self.machine.pose(m[:, 0], m[:, 1], m[:, 2], tool_offset)


@dataclass(frozen=True)
class OnControllerResult:
    """The figures of one run through LinuxCNC: bare, tables alone, tables + 3-D (m).

    ``rows`` are (figure, before, tables, volumetric); ``moves`` the LinuxCNC moves of each
    measurement; ``applied`` the largest |motor − commanded − expected| (m) of the 3-D run,
    expected being the COMP_FILE tables, the cross-axis tables and the grid as axiscal evaluates
    them (what LinuxCNC applied, beside what axiscal asked).
    """

    rows: tuple
    moves: dict
    applied: float
    settings: dict

    def reduction(self, name: str, key: str = "volumetric") -> float:
        """Fraction by which a figure fell from bare to ``key`` (``tables`` or ``volumetric``)."""
        b, t, v = figure_row(self.rows, name)
        return fall(b, t if key == "tables" else v)

    def to_dict(self) -> dict:
        return {"figures": {n: {"before_um": b * 1e6, "tables_um": t * 1e6,
                                "tables_reduction": fall(b, t), "after_um": v * 1e6,
                                "reduction": fall(b, v)} for n, b, t, v in self.rows},
                "moves": dict(self.moves), "largest_applied_difference_um": self.applied * 1e6,
                "on_controller": dict(self.settings)}

    def __str__(self) -> str:
        lines = ["measured through LinuxCNC: bare, tables alone (COMP_FILEs + cross-axis tables "
                 "as external offsets), tables + 3-D correction (external offsets)",
                 f"{'figure':<26}{'before':>9}{'tables':>9}{'fall':>8}{'+ 3-D':>9}{'fall':>8}"]
        for n, b, t, v in self.rows:
            lines.append(f"{n:<26}{b * 1e6:>9.2f}{t * 1e6:>9.2f}{fall_text(b, t):>8}"
                         f"{v * 1e6:>9.2f}{fall_text(b, v):>8}")
        s = self.settings
        lines.append(f"LinuxCNC moves per measurement: "
                     f"{', '.join(f'{k} {v}' for k, v in self.moves.items())} "
                     f"({s['points']} points per diagonal, tool point measured on a "
                     f"{s['grid']}³ grid)")
        lines.append(f"3-D grid every ≤ {s['grid_spacing_mm']:g} mm, OFFSET_AV_RATIO "
                     f"{s['offset_av_ratio']:g}, COMP_FILE_TYPE {s['comp_file_type']}; largest "
                     f"|applied − expected| correction {self.applied * 1e6:.3f} µm")
        return "\n".join(lines)


def verify_on_linuxcnc(machine, errors: GeometricErrors, tables, rng: np.random.Generator, *,
                       points: int = 6, grid: int = 5, grid_spacing: float = 50.0,
                       file_type: int = 1, noise=None) -> OnControllerResult:
    """Measure bare → tables alone → tables + 3-D, each through a fresh LinuxCNC (one run).

    ``points``: targets per body diagonal (each a LinuxCNC move; the datum lines of
    :func:`~axiscal.procedures.volumetric.datum_frame` take 21 on X and Y); ``grid``: the map's
    nodes per axis, the tool point's error measured at each (the largest error and the ranges as
    :class:`~axiscal.standards.volumetric.VolumetricMap` defines them). After a 3-D correction
    the 21 error motions no longer describe the tool point (the offsets translate it, the angular
    errors stay), so the map is measured at the tool point, not rebuilt from re-measured errors
    as :func:`axiscal.compensation.volumetric.verify` does. The defaults (5 and 6) put every node
    on a target of the 21-target measurement the correction was built from, as the 11³ map of
    ``verify`` does: between them the measured error functions are interpolated.
    """
    from axiscal.errors import MeasurementError
    from axiscal.instruments.linuxcnc_controller import unavailable_reason
    from axiscal.procedures.volumetric import MeasurementNoise

    why = unavailable_reason()
    if why:
        raise MeasurementError(f"LinuxCNC cannot run here: {why}")
    noise = noise or MeasurementNoise()
    comp = linuxcnc_compensation(errors, tables, grid_spacing=grid_spacing, file_type=file_type)
    travel_mm = errors.travel_mm
    kw = dict(points=points, reference=errors.reference, tool_offset=errors.measured_tool_offset,
              noise=noise)
    maps, diags, moves, applied = [], [], {}, 0.0
    for key, _ in STATES:
        cfg = {} if key == "before" else dict(comp_files=comp.comp_files(),
                                              volcomp=comp.volcomp(key == "volumetric"))
        vmap, d, log, rng = _in_fresh_process(_measure, travel_mm, file_type, cfg, machine, kw,
                                              grid, rng)
        maps.append(vmap)
        diags.append(d)
        moves[key] = len(log)
        if key == "volumetric":
            applied = _applied_difference(log, tables, comp)
    settings = {"controller": "LinuxCNC (linuxcnc-uspace), headless simulation",
                "points": int(points), "grid": int(grid), "grid_spacing_mm": comp.spacing,
                "comp_file_type": int(file_type), "offset_av_ratio": 0.2,
                "eoffset_scale_mm": 1e-6}
    return OnControllerResult(figure_rows(maps, diags), moves, applied, settings)


def _measure(travel_mm, file_type, cfg, machine, kw, grid, rng):
    """One measurement through a fresh LinuxCNC: (map, diagonals, log, rng).

    The map: the tool point's error measured at every node of a ``grid``³ grid over the travel,
    in the machine's frame and zero at the reference point (:func:`~axiscal.procedures.
    volumetric.true_field`, each point a move), with the laser's noise; the diagonals: the
    ISO 230-6:2002 test (:func:`~axiscal.procedures.volumetric.measure_diagonals`)."""
    from axiscal.instruments.linuxcnc_xyz import LinuxCNCXYZ
    from axiscal.procedures.volumetric import measure_diagonals, true_field
    from axiscal.standards.volumetric import VolumetricMap

    with LinuxCNCXYZ(travel=travel_mm, comp_file_type=file_type, **cfg) as cnc:
        m = ThroughLinuxCNC(cnc, machine)
        field = true_field(m, kw["reference"], kw["tool_offset"])
        nodes = tuple(np.linspace(*machine.travel[a], int(grid)) for a in AXES)
        error = field(*np.meshgrid(*nodes, indexing="ij"))
        error = error + rng.normal(0.0, kw["noise"].positioning, error.shape)
        d = measure_diagonals(m, rng, **kw)
    return VolumetricMap(nodes, error, np.asarray(kw["tool_offset"], float)), d, m.log, rng


def _in_fresh_process(fn, *args):
    """``fn(*args)`` (a function of this module) in a new Python process, arguments and result
    pickled through its stdin and a file. LinuxCNC's ``hal`` module stays attached to the HAL
    shared memory of the first session in a process, so a second session in the same process
    reads its pins as 0 (tried: linuxcnc-uspace 2.9, a second ``hal.component`` after the
    first's ``exit()``); one process per session avoids it."""
    import pickle
    import subprocess
    import sys
    import tempfile
    from pathlib import Path

    from axiscal.errors import MeasurementError

    code = ("import pickle, sys\nfrom axiscal.errors import AxiscalError\n"
            "from axiscal.compensation import on_controller_volumetric as m\n"
            "a = pickle.load(sys.stdin.buffer)\n"
            "try:\n    r = (True, getattr(m, a[0])(*a[1]))\n"
            "except AxiscalError as exc:\n    r = (False, exc)\n"
            "with open(sys.argv[1], 'wb') as f:\n    pickle.dump(r, f)\n")
    with tempfile.TemporaryDirectory(prefix="axiscal-lcnc-") as d:
        result = Path(d) / "result.pickle"
        p = subprocess.run([sys.executable, "-c", code, str(result)],
                           input=pickle.dumps((fn.__name__, args)), capture_output=True)
        ok, r = pickle.loads(result.read_bytes()) if p.returncode == 0 else (None, None)
    if p.returncode != 0:
        tail = p.stderr.decode(errors="replace").strip().splitlines()
        raise MeasurementError("the LinuxCNC measurement ended: "
                               f"{tail[-1] if tail else f'exit status {p.returncode}'}")
    if not ok:
        raise r
    return r


def _applied_difference(log: dict, tables, comp: LinuxCNCCompensation) -> float:
    """Largest |(motor − commanded) − expected| (m) over the moves: expected the positioning and
    cross-axis tables (``tables.correction``) plus the grid, trilinear as the component has it."""
    from axiscal.data.linuxcnc.axiscal_volcomp import CorrectionMap

    grid_only = CorrectionMap({"grid": comp.grid})
    worst = 0.0
    for q, motor in log.items():
        q = np.asarray(q, float)
        want = tables.correction(*(q * 1e-3)) + np.asarray(grid_only.correction(list(q))) * 1e-3
        worst = max(worst, float(np.max(np.abs((np.asarray(motor) - q) * 1e-3 - want))))
    return worst
