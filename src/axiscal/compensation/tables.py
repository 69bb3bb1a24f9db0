"""Compensation tables: from ISO 230-2 mean deviations to corrections at equidistant points.

Yüksel et al., Position accuracy and repeatability calibration of turn tables ends: "a correction can be implemented electronically by the help of obtained deviations
for each steps ... After all corrections, all test procedure shall be repeated." This module makes
the first half of that sentence precise; :mod:`axiscal.compensation.loop` does the second.

Conventions (the same for every controller; each writer converts to its own):

* **Sign.** A table holds *corrections*: ``correction = −deviation``, where the deviation is
  ISO 230-2's x = actual − target (Yüksel et al., Position accuracy and repeatability calibration of turn tables eq. 1). The controller adds the correction to the
  commanded position, so an axis that overshoots by +3 µm is commanded 3 µm short.
* **Points.** ``n`` equidistant points ``start + k·spacing`` (k = 0 … n−1), in the dataset's
  target unit (mm or deg); corrections in its deviation unit (µm or arcsec).
* **Interpolation.** Between measured targets the mean deviation is interpolated linearly (the
  controllers also interpolate linearly between their points, so nothing smoother is implied).
* **Extrapolation at the ends** (``extrapolation=``): ``"hold"`` keeps the value at the first/last
  target for table points beyond the measured range (the default, and what a controller does
  beyond its table); ``"linear"`` continues the slope of the last measured interval.
* **Directions.** A *unidirectional* table corrects the mean bidirectional deviation x̄_i (eq. 4)
  in both directions (or x̄_i↑ if only the positive direction was measured); a *bidirectional*
  table holds ``up = −x̄_i↑`` and ``down = −x̄_i↓`` (eq. 2, 3) and the controller picks by the
  direction of approach. :attr:`CompensationTable.backlash` is the equivalent "one table plus
  a backlash value": the mean of ``down − up`` = the mean reversal B̄ (eq. 7).
* **Rotary axes over a full turn** (``modulo``): the points run from 0° to 360° with ``360/spacing``
  whole intervals and the value at 360° equals that at 0°, so the table closes on itself. The
  measured 0° and 360° targets (different moments of one run) are averaged into one value.
* **Rounding.** Corrections are rounded to ``resolution`` (the controller's input unit).

References
----------
Yüksel et al., Position accuracy and repeatability calibration of turn tables (Yüksel et al.), eqs. (1)-(7) and the closing paragraph; ISO 230-2:2014 clause 3.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace
from typing import Literal

import numpy as np

from axiscal.datasets import AxisKind
from axiscal.errors import InputError
from axiscal.units import display

__all__ = ["CompensationTable", "TableOrigin", "table_from_result", "table_from_deviations", "Extrapolation",
           "MAX_TABLE_POINTS", "check_point_count"]

Extrapolation = Literal["hold", "linear"]
FULL_TURN = 360.0
#: Most points a table may have. Controller tables hold at most some thousands (Fanuc 1024
#: point numbers, Heidenhain and LinuxCNC 256, Siemens MD38000 a few thousand); a count beyond
#: this is a mistyped spacing, refused before any array is allocated.
MAX_TABLE_POINTS = 100_000


@dataclass(frozen=True)
class TableOrigin:
    """Where a table read from a controller file belongs on its machine, so that a conversion
    writes it for the same axis (issue 42: a C axis's table converted to an 840D file must not
    land on X).

    Attributes
    ----------
    controller : str
        The format it was read from (``siemens-840d`` ...).
    machine_axis : str
        The controller's name of the axis (``AX4``, ``C1``; Fanuc's axis number as text;
        ``""`` where the format does not say).
    measuring_system : int or None
        1 or 2 (SINUMERIK MD32700 index 0 or 1); None where the format has none.
    unit : str
        The file's length unit (``mm`` or ``inch``; ``deg`` for a rotary axis).
    kind_from : str
        Where the axis kind came from (``machine data``, ``file``, ``option``, ``assumed``).
    """

    controller: str
    machine_axis: str = ""
    measuring_system: int | None = None
    unit: str = "mm"
    kind_from: str = ""

    def to_dict(self) -> dict:
        return dict(controller=self.controller, machine_axis=self.machine_axis,
                    measuring_system=self.measuring_system, unit=self.unit,
                    kind_from=self.kind_from)


@dataclass(frozen=True, eq=False)
class CompensationTable:
    """Corrections at equidistant points of one axis (correction = −deviation).

    Attributes
    ----------
    axis : str
        Axis name (``"X"``, ``"C"``).
    axis_kind : AxisKind
    position_unit : str
        Unit of ``start`` and ``spacing``: ``mm`` or ``deg``.
    correction_unit : str
        Unit of the corrections: ``um`` or ``arcsec`` (any unit of the axis's dimension).
    start : float, ``position_unit``
        Position of point 0.
    spacing : float, ``position_unit``
        Distance between points (> 0).
    up, down : ndarray, ``correction_unit``
        Corrections for an approach in the positive / negative direction; equal arrays for a
        unidirectional table.
    bidirectional : bool
        True if ``up`` and ``down`` were built from separate directions.
    modulo : bool
        Rotary table over one full turn that repeats (point n−1 is point 0 plus 360°).
    resolution : float, ``correction_unit``
        Step to which the corrections are rounded (0 for none).
    reference_index : int
        The point at the machine reference position (Fanuc parameter 3620 counts from it).
    extrapolation : str
        How table points beyond the measured targets were filled (``hold`` or ``linear``).
    origin : TableOrigin or None
        For a table read from a controller file: its machine axis, measuring system and unit
        there (None for a table made from measurements).

    Examples
    --------
    >>> t = table_from_deviations([0, 100, 200], [2.0, -1.0, 4.0], spacing=50)
    >>> t.positions.tolist(), t.up.tolist()
    ([0.0, 50.0, 100.0, 150.0, 200.0], [-2.0, -0.5, 1.0, -1.5, -4.0])
    >>> float(t.correction_at(25.0, +1))
    -1.25
    """

    axis: str
    axis_kind: AxisKind
    position_unit: str
    correction_unit: str
    start: float
    spacing: float
    up: np.ndarray
    down: np.ndarray
    bidirectional: bool = False
    modulo: bool = False
    resolution: float = 0.0
    reference_index: int = 0
    extrapolation: str = "hold"
    nodes: np.ndarray | None = None
    origin: TableOrigin | None = None

    def __post_init__(self) -> None:
        if self.nodes is not None:
            self._irregular()
        up = np.array(self.up, dtype=float, ndmin=1)
        down = np.array(self.down, dtype=float, ndmin=1)
        if up.ndim != 1 or up.shape != down.shape:
            raise InputError(f"up ({up.shape}) and down ({down.shape}) must be 1-D and equal in length")
        if up.size < 2:
            raise InputError(f"{up.size} compensation point(s); a table needs at least 2")
        if not (np.all(np.isfinite(up)) and np.all(np.isfinite(down))):
            raise InputError("corrections must be finite numbers (found NaN or infinity)")
        if not (math.isfinite(self.spacing) and self.spacing > 0):
            raise InputError(f"spacing = {self.spacing!r} must be a positive number")
        if not 0 <= self.reference_index < up.size:
            raise InputError(f"reference_index = {self.reference_index} is not a point of the "
                             f"table (0 … {up.size - 1})")
        if self.modulo and not math.isclose((up.size - 1) * self.spacing, FULL_TURN, abs_tol=1e-9):
            raise InputError(f"a modulo table must span 360 deg; {up.size} points at "
                             f"{self.spacing:g} deg span {(up.size - 1) * self.spacing:g} deg")
        for a in (up, down):
            a.flags.writeable = False
        object.__setattr__(self, "axis_kind", AxisKind.parse(self.axis_kind))
        object.__setattr__(self, "up", up)
        object.__setattr__(self, "down", down)

    def _irregular(self) -> None:
        """Explicit, strictly increasing positions (a LinuxCNC file may hold any)."""
        x = np.array(self.nodes, dtype=float, ndmin=1)
        if x.ndim != 1 or x.size != np.size(self.up) or not np.isfinite(x).all():
            raise InputError(f"{x.size} positions for {np.size(self.up)} corrections")
        if np.any(np.diff(x) <= 0):
            raise InputError("compensation positions must increase strictly")
        x.flags.writeable = False
        object.__setattr__(self, "nodes", x)
        object.__setattr__(self, "start", float(x[0]))
        object.__setattr__(self, "spacing", float(np.diff(x).min()))

    # -- geometry ------------------------------------------------------------------------
    @property
    def equidistant(self) -> bool:
        """True unless the table holds explicit irregular positions (:attr:`nodes`)."""
        return self.nodes is None

    @property
    def n_points(self) -> int:
        """Number of compensation points."""
        return int(self.up.size)

    @property
    def positions(self) -> np.ndarray:
        """Point positions, ``position_unit``."""
        if self.nodes is not None:
            return self.nodes
        return self.start + self.spacing * np.arange(self.n_points)

    @property
    def end(self) -> float:
        """Position of the last point, ``position_unit``."""
        return float(self.positions[-1])

    @property
    def reference_position(self) -> float:
        """Position of the reference point, ``position_unit``."""
        return float(self.positions[self.reference_index])

    # -- derived values ------------------------------------------------------------------
    @property
    def mean(self) -> np.ndarray:
        """Correction for either direction when one table serves both, ``correction_unit``."""
        return 0.5 * (self.up + self.down)

    @property
    def backlash(self) -> float:
        """Mean of ``down − up`` (= mean reversal B̄ of ISO 230-2 eq. 7), ``correction_unit``.

        With "one table plus a backlash value" the controller adds ``−backlash/2`` to the mean
        table on a positive approach and ``+backlash/2`` on a negative one
        (``up = mean − backlash/2`` where the reversal is uniform along the axis).
        """
        return float(np.mean(self.down - self.up))

    @property
    def largest(self) -> float:
        """Largest correction magnitude over both directions, ``correction_unit``."""
        return float(max(np.max(np.abs(self.up)), np.max(np.abs(self.down))))

    def correction_at(self, position, direction=1):
        """Correction the controller adds at ``position`` (``position_unit``), ``correction_unit``.

        Linear interpolation between points; beyond the ends the end values hold; a modulo
        table wraps positions into one turn. ``direction`` (+1/−1, array-like) picks ``up`` or
        ``down``.
        """
        x = np.asarray(position, dtype=float)
        d = np.asarray(direction, dtype=float)
        xp = self.positions
        if self.modulo:
            x = self.start + np.mod(x - self.start, FULL_TURN)
        cu = np.interp(x, xp, self.up)
        if not self.bidirectional:
            return cu
        cd = np.interp(x, xp, self.down)
        return np.where(d < 0, cd, cu)

    # -- transformations -----------------------------------------------------------------
    def zeroed_at_reference(self, on: str = "up") -> "CompensationTable":
        """The same table shifted so the correction at the reference is 0.

        ``on="up"`` zeroes the positive-direction table there (Fanuc), ``on="mean"`` the mean
        of both directions (one table plus a backlash value, Siemens).

        A constant shift moves every position by the same amount, which re-setting the reference
        absorbs; it changes none of ISO 230-2's A, E, M, R, B. Fanuc's incremental tables are
        relative to the reference by construction (parameter 3620).
        """
        if on not in ("up", "mean"):
            raise InputError(f"on = {on!r}; use 'up' or 'mean'")
        c0 = float((self.up if on == "up" else self.mean)[self.reference_index])
        return replace(self, up=self.up - c0, down=self.down - c0)

    def with_reference(self, position: float) -> "CompensationTable":
        """The table with its reference point at the point nearest ``position``."""
        if self.nodes is not None:
            k = int(np.argmin(np.abs(self.nodes - position)))
            if not self.nodes[0] - 1e-9 <= position <= self.nodes[-1] + 1e-9:
                k = -1
        else:
            k = int(round((position - self.start) / self.spacing))
        if not 0 <= k < self.n_points:
            raise InputError(f"reference position {position:g} {self.position_unit} lies outside "
                             f"the table {self.start:g} … {self.end:g} {self.position_unit}")
        return replace(self, reference_index=k)

    def rounded(self, resolution: float) -> "CompensationTable":
        """The table with corrections rounded to ``resolution`` (``correction_unit``).

        A step so coarse that every correction rounds to zero while the table holds corrections
        is refused (``--resolution 1e300`` wrote an all-zero table with exit 0: issue 39).
        """
        up, down = _round(self.up, resolution), _round(self.down, resolution)
        largest = float(max(np.max(np.abs(self.up)), np.max(np.abs(self.down))))
        if resolution and largest > 0 and not (np.any(up) or np.any(down)):
            from axiscal.errors import InputError

            raise InputError(f"resolution {resolution:g} {display(self.correction_unit)} rounds "
                             f"every correction to zero (the largest is {largest:.4g} "
                             f"{display(self.correction_unit)}); give a finer step")
        return replace(self, up=up, down=down, resolution=float(resolution))

    def to_dict(self) -> dict:
        """Plain data (JSON): geometry, units and the per-point corrections."""
        return {
            "axis": self.axis, "axis_kind": self.axis_kind.value,
            "position_unit": self.position_unit, "correction_unit": self.correction_unit,
            "start": self.start, "spacing": self.spacing, "end": self.end,
            "n_points": self.n_points, "bidirectional": self.bidirectional,
            "modulo": self.modulo, "resolution": self.resolution,
            "reference_index": self.reference_index, "reference_position": self.reference_position,
            "extrapolation": self.extrapolation, "largest": self.largest, "backlash": self.backlash,
            "equidistant": self.equidistant,
            "origin": None if self.origin is None else self.origin.to_dict(),
            "positions": self.positions.tolist(), "up": self.up.tolist(), "down": self.down.tolist(),
        }

    def __str__(self) -> str:
        pu, cu = display(self.position_unit), display(self.correction_unit)
        kind = "bidirectional (+/− tables)" if self.bidirectional else "unidirectional"
        return (
            f"Compensation table, axis {self.axis} ({self.axis_kind.value}), {kind}"
            f"{', modulo 360°' if self.modulo else ''}: {self.n_points} points "
            f"{'every ' + format(self.spacing, 'g') if self.equidistant else 'at irregular positions'}"
            f" {pu if self.equidistant else ''} from {self.start:g} to {self.end:g} {pu}; "
            f"reference point "
            f"{self.reference_index} at {self.reference_position:g} {pu}; largest correction "
            f"{self.largest:.4g} {cu}; mean reversal {self.backlash:+.4g} {cu}; "
            f"correction = −deviation"
        )


def table_from_result(
    result,
    spacing: float | None,
    *,
    start: float | None = None,
    end: float | None = None,
    bidirectional: bool = False,
    resolution: float = 0.0,
    extrapolation: Extrapolation = "hold",
    modulo: bool | None = None,
    reference: float | None = None,
    axis: str = "",
) -> CompensationTable:
    """Build a compensation table from an ISO 230-2 result.

    Parameters
    ----------
    result : Iso230_2Result
        Its ``targets`` (``target_unit``) and ``mean_up``/``mean_down`` (``deviation_unit``).
    spacing : float or None, ``result.target_unit``
        Distance between the controller's points; None puts the points at the measured targets
        (irregular: only LinuxCNC's file takes that).
    start, end : float, optional, ``result.target_unit``
        Range of the table; default the first and last target (0 and 360° for a modulo
        table). The table ends at the first point at or beyond ``end``.
    bidirectional : bool
        Separate ``up``/``down`` tables (needs both directions measured).
    resolution : float, ``result.deviation_unit``
        Round the corrections to this step (0: no rounding).
    extrapolation : {"hold", "linear"}
        How points beyond the measured targets are filled (see the module docstring).
    modulo : bool, optional
        Full-turn rotary table; default True for a rotary result whose targets span 360°.
    reference : float, optional
        Reference position; default the table's start.
    axis : str
        Axis name for the table (default: none).

    Returns
    -------
    CompensationTable

    Raises
    ------
    InputError
        If the spacing does not divide 360° for a modulo table, a bidirectional table is asked
        of a unidirectional test, or the range is empty.

    Examples
    --------
    >>> from axiscal.datasets import PositioningDataset
    >>> from axiscal.standards.iso230_2 import evaluate
    >>> ds = PositioningDataset.from_arrays("linear", [0, 100, 200],
    ...     up=[[1, 1], [3, 3], [5, 5]], down=[[-1, -1], [1, 1], [3, 3]])
    >>> t = table_from_result(evaluate(ds), 100, bidirectional=True)
    >>> t.up.tolist(), t.down.tolist(), t.backlash
    ([-1.0, -3.0, -5.0], [1.0, -1.0, -3.0], 2.0)
    """
    targets = np.asarray(result.targets, dtype=float)
    has_down = bool(np.any(np.isfinite(result.mean_down)))
    if bidirectional and not has_down:
        raise InputError("bidirectional table asked of a test measured in the positive direction "
                         "only; measure both directions or build a unidirectional table")
    dev_up = np.asarray(result.mean_up, dtype=float)
    dev_down = np.asarray(result.mean_down, dtype=float) if has_down else dev_up
    if not bidirectional:
        dev_up = dev_down = 0.5 * (dev_up + dev_down)
    kind = AxisKind.parse(result.axis_kind)
    spans_turn = kind is AxisKind.ROTARY and targets[-1] - targets[0] >= FULL_TURN - 1e-9
    modulo = spans_turn if modulo is None else bool(modulo)
    return table_from_deviations(
        targets, dev_up, dev_down if bidirectional else None, spacing=spacing, start=start,
        end=end, resolution=resolution, extrapolation=extrapolation, modulo=modulo,
        reference=reference, axis=axis, axis_kind=kind, position_unit=result.target_unit,
        correction_unit=result.deviation_unit)


def table_from_deviations(
    targets,
    deviation_up,
    deviation_down=None,
    *,
    spacing: float | None,
    start: float | None = None,
    end: float | None = None,
    resolution: float = 0.0,
    extrapolation: Extrapolation = "hold",
    modulo: bool = False,
    reference: float | None = None,
    axis: str = "",
    axis_kind: "AxisKind | str" = AxisKind.LINEAR,
    position_unit: str = "mm",
    correction_unit: str = "um",
) -> CompensationTable:
    """Build a table from mean deviations at targets (the core of :func:`table_from_result`).

    ``deviation_down=None`` makes a unidirectional table from ``deviation_up``. Units as the
    arguments say (targets/spacing in ``position_unit``, deviations in ``correction_unit``).
    """
    t = np.asarray(targets, dtype=float)
    du = np.asarray(deviation_up, dtype=float)
    dd = du if deviation_down is None else np.asarray(deviation_down, dtype=float)
    if t.ndim != 1 or t.size < 2 or du.shape != t.shape or dd.shape != t.shape:
        raise InputError("targets and deviations must be 1-D arrays of equal length >= 2")
    if not (np.all(np.isfinite(du)) and np.all(np.isfinite(dd))):
        raise InputError("a mean deviation is missing (NaN); every target needs one to build a table")
    if extrapolation not in ("hold", "linear"):
        raise InputError(f"extrapolation = {extrapolation!r}; use 'hold' or 'linear'")
    if spacing is None:                        # the points at the targets themselves
        if np.any(np.diff(t) <= 0):
            raise InputError("targets must increase strictly to be table points")
        table = CompensationTable(
            axis=axis, axis_kind=AxisKind.parse(axis_kind), position_unit=position_unit,
            correction_unit=correction_unit, start=float(t[0]), spacing=1.0, up=-du, down=-dd,
            bidirectional=deviation_down is not None, extrapolation="hold", nodes=t)
        table = table.with_reference(t[0] if reference is None else reference)
        return table.rounded(resolution) if resolution else table
    if not (math.isfinite(spacing) and spacing > 0):
        raise InputError(f"spacing = {spacing!r} must be a positive number")
    if modulo:
        x, t, du, dd = _modulo_points(t, du, dd, spacing, start)
        cu, cd = -np.interp(x, t, du, period=FULL_TURN), -np.interp(x, t, dd, period=FULL_TURN)
    else:
        x = _linear_points(t, spacing, start, end)
        cu, cd = -_interp(x, t, du, extrapolation), -_interp(x, t, dd, extrapolation)
    ref = x[0] if reference is None else reference
    table = CompensationTable(
        axis=axis, axis_kind=AxisKind.parse(axis_kind), position_unit=position_unit,
        correction_unit=correction_unit, start=float(x[0]), spacing=float(spacing),
        up=cu, down=cd, bidirectional=deviation_down is not None, modulo=modulo,
        extrapolation=extrapolation)
    table = table.with_reference(ref)
    return table.rounded(resolution) if resolution else table


# -- helpers ---------------------------------------------------------------------------------
def _linear_points(t, spacing, start, end):
    lo = float(t[0]) if start is None else float(start)
    hi = float(t[-1]) if end is None else float(end)
    if not hi > lo:
        raise InputError(f"table range {lo:g} … {hi:g} is empty; end must exceed start")
    steps = (hi - lo) / spacing
    check_point_count(steps + 1, spacing, f"{lo:g} … {hi:g}")
    n = int(math.ceil(steps - 1e-9)) + 1
    return lo + spacing * np.arange(max(n, 2))


def check_point_count(n: float, spacing: float, span: str) -> None:
    """Refuse a table of more than :data:`MAX_TABLE_POINTS` points (or an infinite count)."""
    if not n <= MAX_TABLE_POINTS:
        count = ("infinitely many" if not math.isfinite(n) else f"{n:.0f}" if n < 1e12
                 else f"{n:.3g}")
        raise InputError(f"spacing = {spacing:g} over {span} gives {count} table points; at most "
                         f"{MAX_TABLE_POINTS} are allowed (a controller table holds some thousands): "
                         "use a larger spacing")


def _modulo_points(t, du, dd, spacing, start):
    k = FULL_TURN / spacing
    check_point_count(k + 1, spacing, "0 … 360 deg")
    if abs(k - round(k)) > 1e-9:
        raise InputError(f"spacing = {spacing:g} deg does not divide 360 deg into whole intervals, "
                         "as a table that closes on itself needs")
    lo = 0.0 if start is None else float(start)
    # Pool targets that are the same physical angle (0 and 360 deg): average their deviations.
    phys = np.round(np.mod(t - lo, FULL_TURN), 9)
    keys, inverse = np.unique(phys, return_inverse=True)
    cnt = np.bincount(inverse)
    du_m = np.bincount(inverse, du) / cnt
    dd_m = np.bincount(inverse, dd) / cnt
    x = lo + spacing * np.arange(int(round(k)) + 1)
    return x, lo + keys, du_m, dd_m


def _interp(x, t, y, extrapolation):
    out = np.interp(x, t, y)
    if extrapolation == "linear":
        lo, hi = x < t[0], x > t[-1]
        out[lo] = y[0] + (x[lo] - t[0]) * (y[1] - y[0]) / (t[1] - t[0])
        out[hi] = y[-1] + (x[hi] - t[-1]) * (y[-1] - y[-2]) / (t[-1] - t[-2])
    return out


def _round(values, resolution):
    if not (math.isfinite(resolution) and resolution >= 0):
        raise InputError(f"resolution = {resolution!r} must be a number >= 0")
    if resolution == 0:
        return np.asarray(values, dtype=float)
    r = np.round(np.asarray(values, dtype=float) / resolution) * resolution
    # Keep the decimal representation clean (0.30000000000000004 -> 0.3).
    digits = max(0, -int(math.floor(math.log10(resolution))) + 3)
    return np.round(r, digits) + 0.0
