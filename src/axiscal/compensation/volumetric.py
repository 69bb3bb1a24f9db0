"""Volumetric compensation by a controller's tables, and the loop that verifies it.

From the 21 measured errors (:class:`~axiscal.standards.volumetric.GeometricErrors`) this module
builds what single-axis tables can remove, in the order the squareness paper's Appendix II
recommends (Chapman, "Calibration of machine squareness", Appendix II: straightness, pitch and yaw
first, then squareness, the squareness applied so that the axis aligned to the spindle keeps its
alignment):

1. a positioning table per axis (``EXX``, ``EYY``, ``EZZ`` plus the Abbe effect of that axis's
   angular errors along itself at the chosen tool offset);
2. cross-axis tables, one per pair (driving axis, receiving axis): the straightness of the driving
   axis in the receiving axis's direction (with the Abbe effect of its angular errors at the tool
   offset), plus, for each squareness pair, the linear correction ``+θ·(p − c)`` on the receiving
   axis (the sign proven in :mod:`axiscal.compensation.squareness`).

What tables cannot remove is said: the Abbe products of an angular error of one axis with the
travel of another (:func:`axiscal.standards.volumetric.volumetric_error` with ``part="cross"``);
removing those needs a controller's volumetric compensation (a full 3-D error map).

:class:`CompensatedMachine` is a simulated machine seen through a controller that applies the
tables (read back from the written files), so the same simulated measurements re-measure it:
:func:`verify` runs measure → compensate → re-measure and reports before, after and the reduction,
and the angle between the compensated Z motion and the spindle axis (Figures 30a-c).
"""

from __future__ import annotations

from dataclasses import dataclass, field, replace

import numpy as np

from axiscal.compensation.controllers import controller as controller_module
from axiscal.compensation.cross_axis import CrossAxisTable, parse_cross_axis, write_cross_axis
from axiscal.compensation.tables import table_from_deviations
from axiscal.errors import ConfigError, InputError
from axiscal.machines.seen_through import MachineSeenThrough
from axiscal.standards.volumetric import (AXES, PAIRS, GeometricErrors, map_volume, table_part,
                                          volumetric_error)

__all__ = ["VOLUMETRIC_CONTROLLERS", "DEFAULT_RECEIVING", "VolumetricTables",
           "volumetric_tables", "write_tables", "read_back", "CompensatedMachine",
           "VerifyResult", "verify", "figure_rows", "figure_row", "fall", "fall_text"]

#: Controllers with both positioning and cross-axis table formats here.
VOLUMETRIC_CONTROLLERS = ("siemens-840d", "heidenhain", "csv")
#: Which axis of each squareness pair receives the correction by default: the one aligned to the
#: spindle (Z on a vertical machine, Appendix II); for XY, Y (a choice the user can change).
DEFAULT_RECEIVING = {"xy": "Y", "yz": "Z", "zx": "Z"}


@dataclass(frozen=True, eq=False)
class VolumetricTables:
    """The tables that remove what single-axis compensation can remove.

    Attributes
    ----------
    positioning : dict of str to CompensationTable
        One per axis, positions in mm, corrections in µm.
    cross : list of CrossAxisTable
        Corrections of a receiving axis as a function of a driving axis.
    receiving : dict of str to str
        The receiving axis of each squareness pair.
    tool_offset : numpy.ndarray, m
    uncompensable : float, m
        Largest |E| of the part tables cannot remove (two-axis Abbe products) over the volume.
    """

    positioning: dict
    cross: list
    receiving: dict
    tool_offset: np.ndarray
    uncompensable: float
    notes: tuple = field(default=())

    def correction(self, x, y, z) -> np.ndarray:
        """Correction (m) the controller adds to each axis's command at commanded (x, y, z), m."""
        q = dict(zip(AXES, np.broadcast_arrays(*(np.asarray(v, float) for v in (x, y, z)))))
        out = np.zeros((3,) + q["X"].shape)
        for a, t in self.positioning.items():
            out[AXES.index(a)] += np.asarray(t.correction_at(q[a] * 1e3)) * 1e-6
        for ct in self.cross:
            out[AXES.index(ct.compensated_axis)] += ct.correction(q[ct.driving_axis])
        return out

    def __str__(self) -> str:
        lines = [f"positioning tables: {', '.join(sorted(self.positioning))}"]
        lines += [f"  {ct}" for ct in self.cross]
        lines.append(f"left by tables (two-axis Abbe products): up to "
                     f"{self.uncompensable * 1e6:.2f} µm")
        return "\n".join(lines)


def volumetric_tables(errors: GeometricErrors, *, tool_offset=None, receiving=None,
                      spacing: float = 20.0, resolution: float = 0.1) -> VolumetricTables:
    """Positioning and cross-axis tables from the measured errors.

    Parameters
    ----------
    errors : GeometricErrors
    tool_offset : array_like of 3, m, optional
        Tool offset at which the angular errors' Abbe effects are compensated; default the one
        used while measuring.
    receiving : dict, optional
        Receiving axis per squareness pair (``{"xy": "Y", "yz": "Z", "zx": "Z"}`` by default,
        :data:`DEFAULT_RECEIVING`).
    spacing : float, mm
        Distance between table points.
    resolution : float, µm
        Rounding of the corrections.
    """
    rec = dict(DEFAULT_RECEIVING)
    for k, v in (receiving or {}).items():
        if k not in PAIRS:
            raise ConfigError(f"receiving axis for {k!r}: pairs are xy, yz, zx")
        if str(v).upper() not in k.upper():
            raise ConfigError(f"receiving axis for {k} = {v!r}: must be {k[0].upper()} or "
                              f"{k[1].upper()}")
        rec[k] = str(v).upper()
    t = errors.measured_tool_offset if tool_offset is None else np.asarray(tool_offset, float)
    c = errors.reference
    points, deviations = {}, {}
    for a in AXES:
        lo, hi = errors.travel[a]
        n = int(np.floor((hi - lo) * 1e3 / spacing + 1e-9)) + 1
        if n > 10_000:
            raise InputError(f"spacing = {spacing!r} mm gives {n} points on {a}; at most 10000")
        u = lo + np.arange(n) * spacing * 1e-3
        points[a] = u
        deviations[a] = table_part(errors, a, u, t)          # (3, n), m
    pos = {a: _table(points[a], deviations[a][AXES.index(a)], a, c[AXES.index(a)], spacing,
                     resolution) for a in AXES}
    cross_dev = {(d, r): deviations[d][AXES.index(r)].copy()
                 for d in AXES for r in AXES if r != d}
    for pair in PAIRS:
        theta = errors.squareness.get(pair, 0.0)
        r = rec[pair]
        d = pair.upper().replace(r, "")
        cross_dev[(d, r)] -= theta * (points[d] - c[AXES.index(d)])    # deviation = −correction
    cross = []
    for (d, r), dev in cross_dev.items():
        tab = _table(points[d], dev, r, c[AXES.index(d)], spacing, resolution)
        slope = float(np.polyfit(points[d], -dev, 1)[0]) * 1e6
        cross.append(CrossAxisTable(d, r, tab, slope))
    left = map_volume(errors, 11, tool_offset=t,
                      field=lambda X, Y, Z: volumetric_error(errors, X, Y, Z, t, part="cross"))
    notes = (f"{', '.join(errors.missing)} not measured: taken as zero",) if errors.missing else ()
    return VolumetricTables(pos, cross, rec, t, left.largest, notes)


def write_tables(tables: VolumetricTables, controller: str, travel_mm: dict) -> list:
    """The controller files of ``tables`` (:class:`~axiscal.compensation.controllers._common.
    ControllerFile`), positioning first, then the cross-axis tables."""
    mod = controller_module(controller)
    if mod.NAME not in VOLUMETRIC_CONTROLLERS:
        raise InputError(f"controller {controller!r}: volumetric tables are written for "
                         f"{', '.join(VOLUMETRIC_CONTROLLERS)}")
    files = []
    for i, a in enumerate(AXES):
        opts = {"machine_axis": f"AX{i + 1}"} if mod.NAME == "siemens-840d" else {}
        f = mod.write(tables.positioning[a], travel_mm[a], **opts)
        if mod.NAME != "heidenhain":          # Heidenhain names the file after the axis
            stem, dot, ext = f.filename.rpartition(".")
            f = replace(f, filename=f"{stem}_{a}.{ext}" if dot else f"{f.filename}_{a}")
        files.append(f)
    for k, ct in enumerate(tables.cross):
        opts = {"table_index": k} if mod.NAME == "siemens-840d" else {}
        f = write_cross_axis(ct, controller, travel_mm[ct.driving_axis], **opts)
        if mod.NAME in ("siemens-840d", "heidenhain"):
            name = (f"NC_CEC_{ct.compensated_axis}_{ct.driving_axis}.INI"
                    if mod.NAME == "siemens-840d"
                    else f"{ct.compensated_axis}_{ct.driving_axis}.COM")
            f = replace(f, filename=name)
        files.append(f)
    return files


def read_back(files: list, controller: str, receiving: dict, tool_offset) -> VolumetricTables:
    """Parse written files back into tables (what the controller would hold)."""
    mod = controller_module(controller)
    pos, cross = {}, []
    for f, a in zip(files[:3], AXES):
        pos[a] = mod.parse(f.text, f.filename)
    for f in files[3:]:
        drv = f.filename.split("_")[-1].split(".")[0] if mod.NAME == "heidenhain" else None
        ct = parse_cross_axis(f.text, controller, driving_axis=drv, source=f.filename)
        cross.append(ct)
    return VolumetricTables(pos, cross, dict(receiving), np.asarray(tool_offset, float), 0.0)


@dataclass(frozen=True, eq=False)
class CompensatedMachine(MachineSeenThrough):
    """A simulated machine whose controller adds ``tables``' corrections to every command."""

    machine: object
    tables: VolumetricTables

    def pose(self, x, y, z, tool_offset=(0.0, 0.0, 0.0)):
        """Tool pose for commanded (x, y, z), m (see ``ThreeAxisMachine.pose``)."""
        x, y, z = np.broadcast_arrays(*(np.asarray(v, float) for v in (x, y, z)))
        c = self.tables.correction(x, y, z)
        return self.machine.pose(x + c[0], y + c[1], z + c[2], tool_offset)


@dataclass(frozen=True)
class VerifyResult:
    """Before and after compensation, as re-measured (all lengths m).

    ``rows`` are (figure, before, after); ``spindle_tilt`` the angle (rad) between the compensated
    Z motion and the spindle axis (the uncompensated Z motion: Z aligned to the spindle, Figure
    30a), ``residual_predicted`` what the tables could not remove by the model.
    """

    rows: tuple
    spindle_tilt: float
    residual_predicted: float
    controller: str
    receiving: dict

    def reduction(self, name: str) -> float:
        """Fraction by which a figure fell (1 = removed)."""
        b, a = figure_row(self.rows, name)
        return fall(b, a)

    def to_dict(self) -> dict:
        return {"controller": self.controller, "receiving": self.receiving,
                "figures": {n: {"before_um": b * 1e6, "after_um": a * 1e6, "reduction": fall(b, a)}
                            for n, b, a in self.rows},
                "spindle_tilt_um_per_m": self.spindle_tilt * 1e6,
                "left_by_tables_um": self.residual_predicted * 1e6}

    def __str__(self) -> str:
        lines = [f"{'figure':<26}{'before':>10}{'after':>10}{'reduction':>11}"]
        for n, b, a in self.rows:
            lines.append(f"{n:<26}{b * 1e6:>9.2f} {a * 1e6:>9.2f} {fall_text(b, a):>10}")
        lines.append(f"compensated Z motion against the spindle axis: "
                     f"{self.spindle_tilt * 1e6:.2f} µm/m")
        lines.append(f"left by tables (two-axis Abbe products, model): "
                     f"{self.residual_predicted * 1e6:.2f} µm")
        if self.residual_predicted > 0.5 * self.rows[0][2] > 0:
            lines.append("what remains is mostly what single-axis tables cannot remove: the "
                         "controller's volumetric compensation (a 3-D error map) or a mechanical "
                         "correction of the largest angular errors would")
        return "\n".join(lines)


def verify(machine, errors: GeometricErrors, tables: VolumetricTables, controller: str,
           rng: np.random.Generator, *, grid: int = 11, noise=None) -> VerifyResult:
    """Measure → compensate → re-measure on a simulated machine.

    The tables are written for ``controller``, read back, applied by :class:`CompensatedMachine`,
    and the machine is measured again with the same simulated tests; the figures are the
    volumetric map's largest error and per-direction ranges and each body diagonal's range, both
    as re-measured.
    """
    from axiscal.procedures.volumetric import MeasurementNoise, measure_diagonals, measure_errors

    noise = noise or MeasurementNoise()
    files = write_tables(tables, controller, errors.travel_mm)
    held = read_back(files, controller, tables.receiving, tables.tool_offset)
    comp = CompensatedMachine(machine, held)
    kw = dict(reference=errors.reference, tool_offset=errors.measured_tool_offset, noise=noise)
    maps, diags = [], []
    for m in (machine, comp):
        e = errors if m is machine else measure_errors(m, rng, **kw)
        maps.append(map_volume(e, grid, tool_offset=tables.tool_offset))
        diags.append(measure_diagonals(m, rng, **kw))
    tilt = _spindle_tilt(machine, comp, errors)
    return VerifyResult(figure_rows(maps, diags), tilt, tables.uncompensable, controller, dict(tables.receiving))


def figure_rows(maps, diagonals) -> tuple:
    """The figures of measurements of one machine, one column per measurement (lengths m).

    Rows ``(figure, value, value, ...)``: the volumetric map's largest error and its three
    per-direction ranges (:class:`~axiscal.standards.volumetric.VolumetricMap`), then the range of
    each body diagonal (ISO 230-6:2002, the diagonal displacement test), in the order of
    ``maps`` and ``diagonals`` (one map and one list of diagonals per measurement).
    """
    rows = [("largest volumetric error", *(m.largest for m in maps))]
    rows += [(f"range {a}", *(m.ranges[a] for m in maps)) for a in AXES]
    rows += [(f"body diagonal {d[0].name}", *(x.range for x in d)) for d in zip(*diagonals)]
    return tuple(rows)


def figure_row(rows, name: str) -> tuple:
    """The values of figure ``name`` in ``rows`` of :func:`figure_rows`; KeyError if absent."""
    for n, *values in rows:
        if n == name:
            return tuple(values)
    raise KeyError(name)


def fall(before: float, after: float) -> float:
    """Fraction by which a figure fell from ``before`` to ``after`` (1 = removed; 0 if before is 0)."""
    return 1.0 - after / before if before else 0.0


def fall_text(before: float, after: float) -> str:
    """:func:`fall` as a percentage with one decimal, or a dash where ``before`` is 0."""
    return f"{fall(before, after) * 100:.1f} %" if before else "—"


def _spindle_tilt(machine, comp, errors) -> float:
    """Angle (rad) between the compensated and the uncompensated Z motion (the spindle axis)."""
    from axiscal.procedures.volumetric import _line_direction

    t = errors.measured_tool_offset
    d0 = _line_direction(machine, "Z", errors.reference, t, 21)
    d1 = _line_direction(comp, "Z", errors.reference, t, 21)
    return float(np.arccos(np.clip(d0 @ d1, -1.0, 1.0)))


def _table(u_m, deviation_m, axis, reference_m, spacing, resolution):
    return table_from_deviations(u_m * 1e3, deviation_m * 1e6, spacing=spacing,
                                 resolution=resolution, axis=axis,
                                 reference=float(np.clip(reference_m * 1e3, u_m[0] * 1e3,
                                                         u_m[-1] * 1e3)))
