"""Squareness compensation as a controller's cross-axis table (Chapman, Calibration of machine squareness Appendix II).

:func:`axiscal.compensation.squareness.squareness_compensation` decides, by Appendix II, which axis
receives the corrections (the one aligned to the spindle) and the factor θ; this module turns that
into what a controller loads, reads it back, and applies it to the simulated XY plane so the loop
"measure → compensate → re-measure" can be run for squareness as for positioning.

* :func:`cross_axis_table` — corrections of the compensated (aligned) axis at equidistant
  positions of the driving axis, ``δ = θ·(p − p_ref)``, in µm at mm, rounded to the resolution;
  the straight line is represented exactly by linear interpolation.
* :func:`write_cross_axis` / :func:`parse_cross_axis` — Siemens 840D sag/angularity compensation
  (``%_N_NC_CEC_INI``, :func:`~axiscal.compensation.controllers.siemens_840d.write_cross_axis`),
  Heidenhain ``.COM`` with AXISPOS on the driving axis and a ``.CMA`` entry in the driving axis's
  column, and CSV. Fanuc (straightness compensation parameters) and LinuxCNC (no cross-axis
  compensation file; a kinematics module would do it) are refused with a
  :class:`~axiscal.errors.ControllerLimitError` that gives the factor instead.
* :class:`CompensatedPlane` — an :class:`~axiscal.machines.xy_plane.XYPlaneMachine` seen through a
  controller that applies the table (same ``deviation`` interface, so the squareness procedures
  re-measure it unchanged).

Sign convention: a correction is added to the compensated axis's command (as for positioning
tables). With Chapman, Calibration of machine squareness's θ (angle between +A and +B minus 90°) Appendix II's correction is
``+θ·p(driving)`` on the aligned axis whichever axis is aligned (proof in
:mod:`axiscal.compensation.squareness`).

References
----------
Chapman, Calibration of machine squareness, Appendix II and Figures 30a-c.
"""

from __future__ import annotations

from dataclasses import dataclass, replace

import numpy as np

from axiscal.compensation.controllers import controller as controller_module
from axiscal.compensation.controllers._common import ControllerFile
from axiscal.compensation.tables import CompensationTable, table_from_deviations
from axiscal.errors import ControllerLimitError, DataFormatError, InputError

__all__ = ["CrossAxisTable", "cross_axis_table", "write_cross_axis", "parse_cross_axis",
           "CompensatedPlane", "CROSS_AXIS_CONTROLLERS"]

#: Controllers with a cross-axis table format here.
CROSS_AXIS_CONTROLLERS = ("siemens-840d", "heidenhain", "csv")


@dataclass(frozen=True, eq=False)
class CrossAxisTable:
    """Corrections of one axis as a function of another's position.

    Attributes
    ----------
    driving_axis : str
        The axis whose position selects the correction (X for δz during X motion).
    compensated_axis : str
        The axis that receives the corrections (the one aligned to the spindle).
    table : CompensationTable
        Positions of ``driving_axis`` in mm, corrections of ``compensated_axis`` in µm
        (added to its command).
    factor : float, µm/m
        The squareness the table compensates (slope of the corrections).
    """

    driving_axis: str
    compensated_axis: str
    table: CompensationTable
    factor: float

    def correction(self, driving_position_m):
        """Correction of the compensated axis, m, at driving-axis positions, m."""
        p = np.asarray(driving_position_m, dtype=float) * 1e3
        return np.asarray(self.table.correction_at(p)) * 1e-6

    def __str__(self) -> str:
        t = self.table
        return (f"cross-axis table: δ{self.compensated_axis.lower()} = F({self.driving_axis}), "
                f"{t.n_points} points every {t.spacing:g} mm from {t.start:g} to {t.end:g} mm, "
                f"slope {self.factor:+.3f} µm/m, largest correction {t.largest:.3g} µm")


def cross_axis_table(compensation, start: float, end: float, spacing: float,
                     resolution: float = 0.1) -> CrossAxisTable:
    """The table of a :class:`~axiscal.compensation.squareness.CrossAxisCompensation`.

    Parameters
    ----------
    compensation : CrossAxisCompensation
        From :func:`~axiscal.compensation.squareness.squareness_compensation`.
    start, end, spacing : float, mm
        Range of the driving axis and distance between points.
    resolution : float, µm
        Rounding of the corrections.

    Examples
    --------
    >>> from axiscal.compensation.squareness import squareness_compensation
    >>> from axiscal.standards.iso230_1 import Squareness
    >>> c = squareness_compensation(Squareness(40e-6, ("X", "Z")), aligned_axis="Z")
    >>> ct = cross_axis_table(c, -200, 200, 100)
    >>> ct.driving_axis, ct.compensated_axis, ct.table.up.tolist()
    ('X', 'Z', [-8.0, -4.0, 0.0, 4.0, 8.0])
    """
    if not end > start:
        raise InputError(f"cross-axis table from {start!r} to {end!r} mm: end must exceed start")
    p = np.array([start, end], dtype=float)
    corr_um = compensation.correction(p * 1e-3) * 1e6
    # table_from_deviations builds corrections = −deviation, so hand it −correction
    t = table_from_deviations(p, -corr_um, spacing=spacing, resolution=resolution,
                              axis=compensation.aligned_axis,
                              reference=compensation.reference_position * 1e3
                              if start <= compensation.reference_position * 1e3 <= end else None)
    return CrossAxisTable(compensation.driving_axis, compensation.aligned_axis, t,
                          compensation.factor_um_per_m)


def write_cross_axis(ct: CrossAxisTable, controller: str, travel=None, **options) -> ControllerFile:
    """Write ``ct`` for ``controller`` (one of :data:`CROSS_AXIS_CONTROLLERS`).

    ``travel`` (low, high) in mm is the driving axis's travel. Siemens options: ``input_axis``,
    ``output_axis`` (machine axis names, default the axis letters), ``table_index``.
    """
    mod = controller_module(controller)
    if mod.NAME == "siemens-840d":
        options.setdefault("input_axis", ct.driving_axis)
        options.setdefault("output_axis", ct.compensated_axis)
        return mod.write_cross_axis(ct.table, travel, **options)
    if mod.NAME == "heidenhain":
        return mod.write(ct.table, travel, driving_axis=ct.driving_axis, **options)
    if mod.NAME == "csv":
        f = mod.write(ct.table, travel)
        head, rest = f.text.split("\n", 1)
        text = (f"{head}\n# cross_axis driving_axis={ct.driving_axis} "
                f"compensated_axis={ct.compensated_axis} factor_um_per_m={ct.factor:.6g}\n{rest}")
        return replace(f, text=text, filename=f"{ct.compensated_axis}_of_{ct.driving_axis}.csv",
                       enable=(f"apply correction_up to {ct.compensated_axis} as a function of "
                               f"{ct.driving_axis} (added to the command)",))
    raise ControllerLimitError(
        f"{mod.NAME}: no cross-axis table format here; give the controller the factor "
        f"{ct.factor:+.3f} µm/m on {ct.compensated_axis} per {ct.driving_axis} travel "
        "(Fanuc: straightness compensation parameters; LinuxCNC: a kinematics module)")


def parse_cross_axis(text: str, controller: str, *, driving_axis: str | None = None,
                     source: str = "<text>") -> CrossAxisTable:
    """Read a cross-axis file written by :func:`write_cross_axis` (Heidenhain needs
    ``driving_axis``, which its ``.CMA`` holds, not the ``.COM``)."""
    mod = controller_module(controller)
    if mod.NAME == "siemens-840d":
        t, inp, out = mod.parse_cross_axis(text, source)
        drv, comp = inp, out
    elif mod.NAME == "heidenhain":
        if not driving_axis:
            raise InputError("a Heidenhain .COM does not name the driving axis: give driving_axis")
        t = mod.parse(text, source)
        drv, comp = driving_axis.upper(), t.axis
    elif mod.NAME == "csv":
        t = mod.parse(text, source)
        meta = dict(tok.split("=", 1) for line in text.splitlines() if line.startswith("# cross_axis")
                    for tok in line.split()[2:] if "=" in tok)
        if "driving_axis" not in meta or "compensated_axis" not in meta:
            raise DataFormatError("no '# cross_axis driving_axis=… compensated_axis=…' line", source)
        drv, comp = meta["driving_axis"], meta["compensated_axis"]
    else:
        raise ControllerLimitError(f"{mod.NAME}: no cross-axis table format here")
    slope = float(np.polyfit(t.positions, t.up, 1)[0]) * 1e3     # µm per mm -> µm/m
    return CrossAxisTable(drv, comp, replace(t, axis=comp), slope)


@dataclass(frozen=True)
class CompensatedPlane:
    """An XY plane machine whose controller applies a cross-axis table.

    A command (x, y) becomes the set-point with the correction added to the compensated axis
    (interpolated at the driving axis's commanded position); ``deviation`` is the actual position
    minus the *commanded* one, so the squareness procedures measure the compensated machine.
    """

    machine: object
    cross: CrossAxisTable

    def __post_init__(self) -> None:
        axes = {self.cross.driving_axis, self.cross.compensated_axis}
        if axes != {"X", "Y"}:
            raise InputError(f"the XY plane compensates X and Y, not {sorted(axes)}")

    def __getattr__(self, name):        # length_x, x_range, local_squareness ... of the machine
        if name in ("machine", "cross") or name.startswith("__"):
            raise AttributeError(name)
        return getattr(self.machine, name)

    def deviation(self, x, y, vx=0.0, vy=0.0):
        """(δx, δy) in m at commanded (x, y) in m, with the table applied."""
        x, y = np.broadcast_arrays(np.asarray(x, float), np.asarray(y, float))
        if self.cross.compensated_axis == "X":
            cx, cy = self.cross.correction(y), np.zeros_like(y)
        else:
            cx, cy = np.zeros_like(x), self.cross.correction(x)
        dx, dy = self.machine.deviation(x + cx, y + cy, vx, vy)
        return dx + cx, dy + cy

    def actual(self, x, y, vx=0.0, vy=0.0):
        """Actual position for commanded (x, y), m."""
        dx, dy = self.deviation(x, y, vx, vy)
        return np.asarray(x, float) + dx, np.asarray(y, float) + dy
