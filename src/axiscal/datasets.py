"""Dataset types: what a measurement produces and an evaluation consumes.

A dataset is frozen: its arrays are read-only and it validates itself on construction, naming the
problem. It carries the *display* units of its axis (``mm``/``um`` for linear axes, ``deg``/``arcsec``
for rotary axes); the I/O and presentation layers convert.

The positioning dataset follows ISO 230-2:2014 vocabulary: a target position :math:`P_i`
(:math:`i = 1..m`), the run :math:`j = 1..n`, the direction of approach (↑ positive, ↓ negative)
and the positioning deviation :math:`x_{ij} = P_{ij} - P_i` (actual minus target; Yüksel et al., Position accuracy and repeatability calibration of turn tables eq. 1).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field, replace
from enum import Enum
from typing import Any

import numpy as np

from axiscal import units
from axiscal.errors import InputError

__all__ = [
    "AxisKind",
    "Direction",
    "Environment",
    "Metadata",
    "PositioningDataset",
]


class AxisKind(str, Enum):
    """Kind of axis: linear (lengths) or rotary (angles)."""

    LINEAR = "linear"
    ROTARY = "rotary"

    @property
    def dimension(self) -> str:
        """``"length"`` for a linear axis, ``"angle"`` for a rotary one."""
        return "length" if self is AxisKind.LINEAR else "angle"

    @classmethod
    def parse(cls, value: "str | AxisKind") -> "AxisKind":
        """Accept ``"linear"``/``"rotary"`` (any case) or an :class:`AxisKind`."""
        if isinstance(value, AxisKind):
            return value
        try:
            return cls(str(value).strip().lower())
        except ValueError:
            raise InputError(f"axis kind {value!r} is not 'linear' or 'rotary'") from None


class Direction(str, Enum):
    """Direction of approach to a target: ``+`` (ISO 230-2 ↑) or ``-`` (↓)."""

    UP = "+"
    DOWN = "-"

    @classmethod
    def parse(cls, value: "str | Direction") -> "Direction":
        """Accept ``+``/``-``, ``up``/``down``, ``fwd``/``bwd``, ``pos``/``neg`` (any case)."""
        if isinstance(value, Direction):
            return value
        key = str(value).strip().lower()
        if key in _DIRECTION_WORDS:
            return _DIRECTION_WORDS[key]
        raise InputError(f"direction {value!r} is not one of +, -, up, down, fwd, bwd")


_DIRECTION_WORDS = {
    "+": Direction.UP, "up": Direction.UP, "fwd": Direction.UP, "forward": Direction.UP,
    "pos": Direction.UP, "positive": Direction.UP, "↑": Direction.UP,
    "-": Direction.DOWN, "down": Direction.DOWN, "bwd": Direction.DOWN, "backward": Direction.DOWN,
    "neg": Direction.DOWN, "negative": Direction.DOWN, "↓": Direction.DOWN, "−": Direction.DOWN,
}


@dataclass(frozen=True)
class Environment:
    """Environmental conditions recorded with a measurement.

    Attributes
    ----------
    air_temperature : float or None, degrees Celsius
    material_temperature : tuple of float, degrees Celsius
        One value per material sensor (empty if none).
    pressure : float or None, pascals
    humidity : float or None, percent relative humidity
    expansion_coefficient : float or None, 1/K
        Linear thermal expansion coefficient of the axis's scale or work-piece material.
    """

    air_temperature: float | None = None
    material_temperature: tuple[float, ...] = ()
    pressure: float | None = None
    humidity: float | None = None
    expansion_coefficient: float | None = None

    def __post_init__(self) -> None:
        object.__setattr__(self, "material_temperature", tuple(float(t) for t in self.material_temperature))
        _check_range("air_temperature", self.air_temperature, -50.0, 100.0, "degrees Celsius")
        for t in self.material_temperature:
            _check_range("material_temperature", t, -50.0, 200.0, "degrees Celsius")
        _check_range("pressure", self.pressure, 1e3, 2e5, "Pa")
        _check_range("humidity", self.humidity, 0.0, 100.0, "%RH")
        _check_range("expansion_coefficient", self.expansion_coefficient, -1e-4, 1e-4, "1/K")

    @property
    def mean_material_temperature(self) -> float | None:
        """Average of the material sensors in degrees Celsius, or None if there are none."""
        if not self.material_temperature:
            return None
        return float(np.mean(self.material_temperature))

    def to_dict(self) -> dict[str, Any]:
        """Plain-data form (for JSON)."""
        return {
            "air_temperature": self.air_temperature,
            "material_temperature": list(self.material_temperature),
            "pressure": self.pressure,
            "humidity": self.humidity,
            "expansion_coefficient": self.expansion_coefficient,
        }

    @classmethod
    def from_dict(cls, d: dict[str, Any] | None) -> "Environment":
        """Inverse of :meth:`to_dict`; unknown keys are refused."""
        d = dict(d or {})
        _refuse_unknown("environment", d, cls.__dataclass_fields__)
        mt = d.get("material_temperature", ())
        if isinstance(mt, (int, float)):
            mt = (mt,)
        d["material_temperature"] = tuple(mt or ())
        return cls(**d)


@dataclass(frozen=True)
class Metadata:
    """Who, what and when of a measurement. All fields are optional text except ``environment``."""

    machine: str = ""
    axis: str = ""
    operator: str = ""
    date: str = ""
    instrument: str = ""
    notes: str = ""
    environment: Environment = field(default_factory=Environment)

    def to_dict(self) -> dict[str, Any]:
        """Plain-data form (for JSON)."""
        return {
            "machine": self.machine,
            "axis": self.axis,
            "operator": self.operator,
            "date": self.date,
            "instrument": self.instrument,
            "notes": self.notes,
            "environment": self.environment.to_dict(),
        }

    @classmethod
    def from_dict(cls, d: dict[str, Any] | None) -> "Metadata":
        """Inverse of :meth:`to_dict`; unknown keys are refused."""
        d = dict(d or {})
        _refuse_unknown("metadata", d, cls.__dataclass_fields__)
        env = Environment.from_dict(d.pop("environment", None))
        for k, v in d.items():
            if not isinstance(v, str):
                raise InputError(f"metadata field {k!r} must be text, got {v!r}")
        return cls(environment=env, **d)


@dataclass(frozen=True, eq=False)
class PositioningDataset:
    """Deviations measured in a positioning test (ISO 230-2), per target, direction and run.

    Attributes
    ----------
    axis_kind : AxisKind
        Linear or rotary.
    targets : ndarray, shape (m,), in ``target_unit``
        Target positions :math:`P_i`, strictly increasing.
    up : ndarray, shape (m, n_up), in ``deviation_unit``
        Deviations :math:`x_{ij}↑` approaching in the positive direction; column j is run j+1.
        NaN marks a missing reading.
    down : ndarray, shape (m, n_down), in ``deviation_unit``
        Deviations :math:`x_{ij}↓` approaching in the negative direction; ``n_down`` is 0 for a
        unidirectional test.
    target_unit : str
        ``mm`` (or another length unit) for linear axes, ``deg`` for rotary axes.
    deviation_unit : str
        ``um`` or ``mm`` for linear axes, ``arcsec`` (or another angle unit) for rotary axes.
    metadata : Metadata

    Notes
    -----
    Deviation is actual minus target, :math:`x_{ij} = P_{ij} - P_i` (ISO 230-2:2014 §3.1,
    Yüksel et al., Position accuracy and repeatability calibration of turn tables eq. 1). Row ``i`` of ``up`` and ``down`` belongs to target ``targets[i]``.

    Examples
    --------
    >>> ds = PositioningDataset.from_arrays("linear", [0, 100, 200], [[1, 2], [0, 1], [2, 2]],
    ...                                     [[3, 3], [2, 1], [4, 5]], "mm", "um")
    >>> ds.n_targets, ds.n_runs, ds.bidirectional
    (3, 2, True)
    """

    axis_kind: AxisKind
    targets: np.ndarray
    up: np.ndarray
    down: np.ndarray
    target_unit: str
    deviation_unit: str
    metadata: Metadata = field(default_factory=Metadata)

    def __post_init__(self) -> None:
        kind = AxisKind.parse(self.axis_kind)
        object.__setattr__(self, "axis_kind", kind)
        tu = units.canonical(self.target_unit)
        du = units.canonical(self.deviation_unit)
        if units.dimension(tu) != kind.dimension:
            raise InputError(
                f"target unit {self.target_unit!r} is not a {kind.dimension} unit, "
                f"as a {kind.value} axis needs"
            )
        if units.dimension(du) != kind.dimension:
            raise InputError(
                f"deviation unit {self.deviation_unit!r} is not a {kind.dimension} unit, "
                f"as a {kind.value} axis needs"
            )
        object.__setattr__(self, "target_unit", tu)
        object.__setattr__(self, "deviation_unit", du)
        targets = _as_float_array("targets", self.targets, ndim=1)
        if targets.size < 2:
            raise InputError(f"{targets.size} target position(s); a positioning test needs at least 2")
        if not np.all(np.isfinite(targets)):
            raise InputError("target positions must be finite numbers (found NaN or infinity)")
        if np.any(np.diff(targets) <= 0):
            i = int(np.argmax(np.diff(targets) <= 0))
            raise InputError(
                f"target positions must be strictly increasing: {targets[i]:g} is followed by "
                f"{targets[i + 1]:g}"
            )
        m = targets.size
        up = _as_float_array("up", self.up, ndim=2, rows=m)
        down = _as_float_array("down", self.down, ndim=2, rows=m)
        for name, arr in (("targets", targets), ("up", up), ("down", down)):
            if np.any(np.isinf(arr)):
                raise InputError(f"{name} contain infinity")
            if np.nanmax(np.abs(arr), initial=0.0) > _MAX_MAGNITUDE:
                # squares and sums of such values overflow: no measurement is within decades of it
                raise InputError(f"{name} hold a value beyond ±{_MAX_MAGNITUDE:g}; check the file's "
                                 "units and columns")
        if up.shape[1] == 0 and down.shape[1] == 0:
            raise InputError("no runs at all: both directions are empty")
        for name, arr in (("up", up), ("down", down)):
            if arr.shape[1] and np.all(np.isnan(arr)):
                raise InputError(f"every reading of direction {name} is missing")
        if kind is AxisKind.LINEAR:
            _refuse_inch_slip(targets, up, down, tu, du)
        for a in (targets, up, down):
            a.flags.writeable = False
        object.__setattr__(self, "targets", targets)
        object.__setattr__(self, "up", up)
        object.__setattr__(self, "down", down)

    # -- construction -------------------------------------------------------------------
    @classmethod
    def from_arrays(
        cls,
        axis_kind: "str | AxisKind",
        targets,
        up,
        down=None,
        target_unit: str | None = None,
        deviation_unit: str | None = None,
        metadata: Metadata | None = None,
    ) -> "PositioningDataset":
        """Build a dataset from nested sequences; ``down=None`` makes a unidirectional test.

        Units default to ``mm``/``um`` (linear) or ``deg``/``arcsec`` (rotary).
        """
        kind = AxisKind.parse(axis_kind)
        m = len(np.atleast_1d(np.asarray(targets)))
        if down is None:
            down = np.empty((m, 0))
        return cls(
            axis_kind=kind,
            targets=targets,
            up=up,
            down=down,
            target_unit=target_unit or ("mm" if kind is AxisKind.LINEAR else "deg"),
            deviation_unit=deviation_unit or ("um" if kind is AxisKind.LINEAR else "arcsec"),
            metadata=metadata or Metadata(),
        )

    @classmethod
    def from_records(
        cls,
        axis_kind: "str | AxisKind",
        records,
        target_unit: str | None = None,
        deviation_unit: str | None = None,
        metadata: Metadata | None = None,
        source: str | None = None,
    ) -> "PositioningDataset":
        """Build a dataset from ``(target, direction, run, deviation)`` records.

        Runs are numbered from 1 per direction; a run absent at some target is a missing
        reading (NaN). A repeated ``(target, direction, run)`` is refused.
        """
        from axiscal.errors import DataFormatError

        recs = list(records)
        if not recs:
            raise DataFormatError("no readings", source)
        targets = sorted({float(r[0]) for r in recs})
        index = {t: i for i, t in enumerate(targets)}
        runs: dict[Direction, set[int]] = {Direction.UP: set(), Direction.DOWN: set()}
        parsed = []
        for t, d, run, dev in recs:
            d = Direction.parse(d)
            run = int(run)
            if run < 1:
                raise DataFormatError(f"run number {run} at target {t:g} must be 1 or more", source)
            runs[d].add(run)
            parsed.append((index[float(t)], d, run, float(dev)))
        n_up = max(runs[Direction.UP], default=0)
        n_down = max(runs[Direction.DOWN], default=0)
        up = np.full((len(targets), n_up), np.nan)
        down = np.full((len(targets), n_down), np.nan)
        for i, d, run, dev in parsed:
            arr = up if d is Direction.UP else down
            if not np.isnan(arr[i, run - 1]):
                raise DataFormatError(
                    f"two readings for target {targets[i]:g}, direction {d.value}, run {run}", source
                )
            arr[i, run - 1] = dev
        return cls.from_arrays(axis_kind, targets, up, down, target_unit, deviation_unit, metadata)

    @classmethod
    def from_dataframe(
        cls,
        frame: Any,
        *,
        target_unit: str | None = None,
        deviation_unit: str | None = None,
        axis_kind: "str | AxisKind | None" = None,
        columns: "dict[str, str] | None" = None,
        metadata: Metadata | None = None,
    ) -> "PositioningDataset":
        """Build a dataset from a tidy table in memory, one reading per row.

        Parameters
        ----------
        frame : pandas.DataFrame or mapping of str to sequence
            Columns ``target``, ``direction``, ``run``, ``deviation`` (as the tidy CSV; a unit
            may be in the name: ``target [mm]``, ``deviation_um``; ``columns=`` maps others).
        target_unit, deviation_unit : str, optional
            Else from ``frame.attrs["units"]`` or the column names; refused when found nowhere.
        axis_kind : {"linear", "rotary"}, optional
            Default: told by the target unit.
        columns : dict, optional
            Your column of each of target, direction, run, deviation.
        metadata : Metadata, optional

        Returns
        -------
        PositioningDataset

        Raises
        ------
        DataFormatError
            A missing column, a bad cell (its row named), a repeated reading; the source is
            ``<DataFrame>``.

        Examples
        --------
        >>> ds = PositioningDataset.from_dataframe(
        ...     {"target": [0, 0, 50, 50], "direction": ["up", "down", "up", "down"],
        ...      "run": [1, 1, 1, 1], "deviation": [0.0, 0.4, 1.2, 1.0]},
        ...     target_unit="mm", deviation_unit="um")
        >>> ds.bidirectional, ds.down.tolist()
        (True, [[0.4], [1.0]])
        """
        from axiscal._frames import SOURCE, table_readings

        kind = AxisKind.parse(axis_kind).value if axis_kind is not None else None
        kind, records, tu, du = table_readings(
            frame, Direction.parse, target_unit=target_unit, deviation_unit=deviation_unit,
            axis_kind=kind, columns=columns)
        return cls.from_records(kind, records, tu, du, metadata, source=SOURCE)

    # -- derived views ----------------------------------------------------------------
    @property
    def n_targets(self) -> int:
        """Number of target positions m."""
        return int(self.targets.size)

    @property
    def n_runs(self) -> int:
        """Largest number of runs in either direction."""
        return int(max(self.up.shape[1], self.down.shape[1]))

    @property
    def bidirectional(self) -> bool:
        """True if both directions of approach were measured."""
        return self.up.shape[1] > 0 and self.down.shape[1] > 0

    @property
    def missing_count(self) -> int:
        """Total number of missing readings (NaN) over both directions."""
        return int(np.isnan(self.up).sum() + np.isnan(self.down).sum())

    @property
    def travel(self) -> float:
        """Measured travel, last target minus first, in ``target_unit``."""
        return float(self.targets[-1] - self.targets[0])

    def records(self) -> list[tuple[float, str, int, float]]:
        """The readings as ``(target, direction, run, deviation)`` tuples, missing ones left out."""
        return list(self.iter_records())

    def iter_records(self):
        """:meth:`records` one at a time (a file of millions of readings need not hold them)."""
        for d, arr in ((Direction.UP, self.up), (Direction.DOWN, self.down)):
            for i, t in enumerate(self.targets.tolist()):
                row = arr[i].tolist()
                for j, v in enumerate(row):
                    if v == v:   # not NaN
                        yield (t, d.value, j + 1, v)

    def with_deviation_unit(self, unit: str) -> "PositioningDataset":
        """The same dataset with deviations expressed in another unit of the same dimension."""
        k = units.convert(1.0, self.deviation_unit, unit)
        return replace(self, up=self.up * k, down=self.down * k, deviation_unit=unit)

    def with_metadata(self, **changes: Any) -> "PositioningDataset":
        """A copy with some metadata fields replaced."""
        return replace(self, metadata=replace(self.metadata, **changes))

    def equals(self, other: "PositioningDataset") -> bool:
        """Exact equality of every field (NaN equal to NaN)."""
        return (
            isinstance(other, PositioningDataset)
            and self.axis_kind == other.axis_kind
            and self.target_unit == other.target_unit
            and self.deviation_unit == other.deviation_unit
            and self.metadata == other.metadata
            and np.array_equal(self.targets, other.targets)
            and np.array_equal(self.up, other.up, equal_nan=True)
            and np.array_equal(self.down, other.down, equal_nan=True)
        )

    def to_dict(self) -> dict[str, Any]:
        """Plain-data form; missing readings become ``None``. See :mod:`axiscal.io.json`."""
        return {
            "format": "axiscal.positioning/1",
            "axis_kind": self.axis_kind.value,
            "target_unit": self.target_unit,
            "deviation_unit": self.deviation_unit,
            "targets": self.targets.tolist(),
            "up": _nan_to_none(self.up),
            "down": _nan_to_none(self.down),
            "metadata": self.metadata.to_dict(),
        }

    def __str__(self) -> str:
        kind = "bidirectional" if self.bidirectional else "unidirectional"
        name = self.metadata.axis or self.axis_kind.value
        return (
            f"{name} axis, {kind} positioning test: {self.n_targets} targets from "
            f"{self.targets[0]:g} to {self.targets[-1]:g} {self.target_unit}, {self.n_runs} runs, "
            f"deviations in {self.deviation_unit}, {self.missing_count} missing readings"
        )


# -- the inch read as a millimetre ----------------------------------------------------------
#: The international inch in millimetres, exact by definition (International Yard and Pound
#: Agreement, 1959).
INCH_MM = 25.4
#: Relative window around 25.4 and 1/25.4 in which a ratio of measured to target positions is the
#: inch's signature (see :func:`inch_signature`).
INCH_TOLERANCE = 0.01


def inch_signature(targets, positions) -> float | None:
    """25.4 or 1/25.4 when measured positions are the targets scaled by the inch, else None.

    Parameters
    ----------
    targets, positions : array_like, metres
        Target positions and the measured positions at them (same shape; NaNs are left out).

    Returns
    -------
    float or None
        ``INCH_MM`` if the positions are 25.4 × the targets (targets in inches read as mm),
        ``1 / INCH_MM`` if they are 1/25.4 of them (positions in inches read as mm), else None.

    Notes
    -----
    The ratio ``r`` is the least-squares slope of the positions against the targets (an offset
    is allowed: a datum or a constant deviation moves nothing). A machine axis follows its targets
    to far better than 1 %: its deviation is actual minus target (ISO 230-2:2014 §3.1), and
    the causes of it are all in parts per million: scale and pitch errors (tens of µm/m), thermal
    expansion (11.5 ppm/K for steel; even 100 ppm/K over the whole 0-40 °C band of the air
    equations is 4 mm/m) and the air's refractive index (n − 1 ≈ 0.27 mm/m; Stone and Zimmerman,
    NIST "Engineering metrology toolbox"). ``r`` within ±1 % of 25.4 or 1/25.4, and the positions
    on that line to within 1 % of the travel's scaled span, can only be the inch (exactly 25.4 mm;
    the positions' own errors scale with them, r = 25.4 (1 + e) with e < 1e-3: ten times inside
    the window). An axis that does not move (r ≈ 0, deviations = −target) is not accused. Slips
    that keep targets and positions in one unit (a whole file in inches declared mm, deviations
    in µin declared µm) leave no such signature, as every ratio in the file is unchanged, and are
    not detectable from the numbers alone.

    Examples
    --------
    >>> t = np.array([0.0, 0.1, 0.2, 0.3])                 # metres
    >>> inch_signature(t, 25.4 * t), inch_signature(t, t * (1 + 20e-6))
    (25.4, None)
    """
    t = np.asarray(targets, dtype=float).reshape(-1)
    p = np.asarray(positions, dtype=float).reshape(-1)
    ok = np.isfinite(t) & np.isfinite(p)
    t, p = t[ok], p[ok]
    if t.size < 2 or np.ptp(t) == 0:
        return None
    tc, pc = t - t.mean(), p - p.mean()
    r = float(tc @ pc / (tc @ tc))
    for k in (INCH_MM, 1.0 / INCH_MM):
        if abs(r / k - 1.0) <= INCH_TOLERANCE:
            spread = float(np.sqrt(np.mean((pc - r * tc) ** 2)))
            return k if spread <= INCH_TOLERANCE * abs(r) * np.ptp(t) else None
    return None


def inch_reading(k: float, target_unit: str, measured_unit: str | None = None,
                 measured: str = "measured positions") -> tuple[str, str, str]:
    """The plausible reading of :func:`inch_signature`'s ``k``, for a one-line message.

    Parameters
    ----------
    k : float
        ``INCH_MM`` or ``1 / INCH_MM``.
    target_unit, measured_unit : str
        The units the targets and the measured positions were declared in (``measured_unit``
        defaults to ``target_unit``).
    measured : str
        What the measured positions are called in the file (``readings``, ``actual`` ...).

    Returns
    -------
    (text, which, unit)
        ``text``: "measured positions are 25.4 × the targets: the targets look like inches read
        as mm"; ``which`` (``"target"`` or ``"measured"``) and ``unit`` (e.g. ``"in"``): the
        declaration that reads the file right, where a length unit 25.4 times the declared one
        exists (else the other side's).
    """
    mu = measured_unit or target_unit
    if k > 1:
        ratio = f"{measured} are {INCH_MM:g} × the targets"
        fixes = [("target", _rescaled(target_unit, INCH_MM)),
                 ("measured", _rescaled(mu, 1 / INCH_MM))]
    else:
        ratio = f"{measured} are 1/{INCH_MM:g} of the targets"
        fixes = [("measured", _rescaled(mu, INCH_MM)),
                 ("target", _rescaled(target_unit, 1 / INCH_MM))]
    which, unit = next(((w, u) for w, u in fixes if u is not None), fixes[0])
    declared = target_unit if which == "target" else mu
    whose = "the targets" if which == "target" else f"the {measured}"
    said = _UNIT_WORDS.get(declared, declared)
    scale = INCH_MM if (which == "target") == (k > 1) else 1 / INCH_MM
    look = _UNIT_WORDS.get(unit) or f"units of {scale:.4g} {said}"
    return f"{ratio}: {whose} look like {look} read as {said}", which, unit


#: Length units in words, for :func:`inch_reading`.
_UNIT_WORDS = {"m": "metres", "mm": "mm", "um": "µm", "nm": "nm", "in": "inches",
               "uin": "microinches"}


def _rescaled(unit: str, k: float) -> str | None:
    """The length unit ``k`` times ``unit``, or None."""
    size = units.factor(unit, "length") * k
    return next((n for n, v in units.LENGTH_UNITS.items() if abs(v / size - 1) < 1e-9), None)


def _refuse_inch_slip(targets, up, down, unit: str, deviation_unit: str) -> None:
    """Refuse a dataset whose deviations carry the inch's 25.4 (:func:`inch_signature`); the
    deviation at a target is the mean of its readings (both directions)."""
    total, n = np.zeros(targets.size), np.zeros(targets.size)
    for arr in (up, down):   # no copy of the readings: a file of millions stays lean
        seen = ~np.isnan(arr)
        total += np.add.reduce(arr, axis=1, where=seen, initial=0.0)
        n += np.count_nonzero(seen, axis=1)
    dev = np.where(n > 0, total / np.maximum(n, 1), np.nan) * units.factor(deviation_unit)
    at = targets * units.factor(unit)
    k = inch_signature(at, at + dev)
    if k is not None:
        raise InputError(f"{inch_reading(k, unit)[0]} (the deviations, actual minus target by "
                         f"ISO 230-2:2014 §3.1, grow by {k - 1:+.4g} {unit} per {unit} of "
                         "travel where a machine axis errs by parts per million): give the "
                         "targets and the measured positions in one unit")


# -- helpers ------------------------------------------------------------------------------
#: Largest magnitude accepted for a target or a deviation (any unit); beyond it statistics overflow.
_MAX_MAGNITUDE = 1e100


def _as_float_array(name: str, value, ndim: int, rows: int | None = None) -> np.ndarray:
    try:
        arr = np.array(value, dtype=float)
    except (TypeError, ValueError):
        raise InputError(f"{name} must be numbers; could not read {value!r:.80}") from None
    if ndim == 2 and arr.ndim == 1 and rows is not None and arr.size == 0:
        arr = arr.reshape(rows, 0)
    if arr.ndim != ndim:
        raise InputError(f"{name} must be a {ndim}-D array, got shape {arr.shape}")
    if rows is not None and arr.shape[0] != rows:
        raise InputError(f"{name} has {arr.shape[0]} rows but there are {rows} target positions")
    return arr


def _check_range(name: str, value, lo: float, hi: float, unit: str) -> None:
    if value is None:
        return
    if not isinstance(value, (int, float)) or isinstance(value, bool) or not math.isfinite(value):
        raise InputError(f"{name} must be a finite number in {unit}, got {value!r}")
    if not lo <= value <= hi:
        raise InputError(f"{name} = {value:g} {unit} is outside the plausible range {lo:g} to {hi:g}")


def _refuse_unknown(what: str, d: dict, fields) -> None:
    unknown = sorted(set(d) - set(fields))
    if unknown:
        raise InputError(f"unknown {what} field(s): {', '.join(unknown)}")


def _nan_to_none(arr: np.ndarray) -> list:
    return [[None if math.isnan(v) else float(v) for v in row] for row in arr]
