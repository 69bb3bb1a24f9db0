"""ISO 230-2:2014 — accuracy and repeatability of positioning of numerically controlled axes.

:func:`evaluate` takes a :class:`~axiscal.datasets.PositioningDataset` and returns an
:class:`Iso230_2Result` with the per-target statistics and the axis parameters A, A↑, A↓, E, E↑,
E↓, M, R, R↑, R↓, B and the mean reversal B̄, in the dataset's deviation unit.

Definitions (ISO 230-2:2014 clause 3, reproduced as equations 1-21 of Yüksel et al., Position accuracy and repeatability calibration of turn tables):

============================  ==========================================================  =======
quantity                      definition                                                  Yüksel et al., Position accuracy and repeatability calibration of turn tables
============================  ==========================================================  =======
deviation                     x_ij = P_ij - P_i (actual minus target)                     (1)
mean unidirectional           x̄_i↑ = (1/n) Σ_j x_ij↑, x̄_i↓ likewise                      (2), (3)
mean bidirectional            x̄_i = (x̄_i↑ + x̄_i↓) / 2                                   (4)
reversal value at a target    B_i = x̄_i↑ - x̄_i↓                                          (5)
reversal value of the axis    B = max |B_i|                                               (6)
mean reversal value           B̄ = (1/m) Σ_i B_i  (signed)                                 (7)
repeatability estimator       s_i↑ = sqrt( Σ_j (x_ij↑ - x̄_i↑)² / (n - 1) ), s_i↓ likewise  (8), (9)
unidirectional repeatability  R_i↑ = 4 s_i↑, R_i↓ = 4 s_i↓                                (10), (11)
bidirectional repeatability   R_i = max[2 s_i↑ + 2 s_i↓ + |B_i|; R_i↑; R_i↓]              (12)
axis repeatability            R↑ = max R_i↑, R↓ = max R_i↓, R = max R_i                  (13)-(15)
systematic error              E↑ = max x̄_i↑ - min x̄_i↑ (E↓ likewise)                    (16), (17)
                              E = max[x̄_i↑; x̄_i↓] - min[x̄_i↑; x̄_i↓]                    (18)
range of mean bidirectional   M = max x̄_i - min x̄_i                                      (19)
unidirectional accuracy       A↑ = max[x̄_i↑ + 2 s_i↑] - min[x̄_i↑ - 2 s_i↑] (A↓ likewise)  (20)
bidirectional accuracy        A = max[x̄_i↑ + 2s_i↑; x̄_i↓ + 2s_i↓]
                                  - min[x̄_i↑ - 2s_i↑; x̄_i↓ - 2s_i↓]                      (21)
============================  ==========================================================  =======

Yüksel et al., Position accuracy and repeatability calibration of turn tables prints equation 12 as ``max[2Si↑ + 2Si↓ |Bi|; ...]``: the plus sign before ``|B_i|`` was
lost in that copy; the standard adds the three terms, and so does this module.

Sign convention of B: B_i = x̄_i↑ - x̄_i↓. A positive B_i means the axis stops further in the
positive direction when it approaches the target moving in the positive direction than when it
approaches moving in the negative direction (for a screw with play, that is the sign a lag in the
positive direction does *not* give: a pure lag gives B_i < 0). B is the largest magnitude and is
never negative; B̄ keeps its sign.

Missing readings (NaN) are left out target by target; the counts used are in the result, and a
warning says how many were missing. Fewer than 2 readings at a target in a measured direction is
an :class:`~axiscal.errors.InsufficientRunsError` (no repeatability can be estimated); fewer than 5
runs is allowed with a warning (ISO 230-2:2014 §5.3 asks for 5).

Rotary axes over a full turn: 0° and 360° are the same physical position, but in a test they are
approached at different points of the sequence (0° at the start of a positive run, 360° at its
end). With ``full_turn="separate"`` (the default) they stay two target positions, as CARTO and
Yüksel et al., Position accuracy and repeatability calibration of turn tables's Table 3 (targets 0…8, target 8 = 0°/360°) list them; the difference of their means,
the *closure*, is reported, with a warning if it exceeds what the repeatability explains. With
``full_turn="merge"`` the readings at 360° are pooled with those at 0° into one target. Either way
the count of distinct positions for ISO 230-2 Table 1 counts 0° and 360° once.

References
----------
ISO 230-2:2014, Test code for machine tools — Part 2: Determination of accuracy and repeatability
of positioning of numerically controlled axes.
Yüksel et al., Position accuracy and repeatability calibration of turn tables: Yüksel et al., "Position accuracy and repeatability calibration of turn tables by using
laser interferometers", equations (1)-(21), Table 1.
"""

from __future__ import annotations

import math
import warnings as _warnings
from dataclasses import dataclass, field
from typing import Literal

import numpy as np

from axiscal.datasets import AxisKind, PositioningDataset
from axiscal import units
from axiscal.errors import InputError, InsufficientRunsError

__all__ = [
    "Iso230_2Result",
    "evaluate",
    "minimum_rotary_targets",
    "minimum_linear_targets",
    "RECOMMENDED_RUNS",
    "PARAMETER_NAMES",
    "Verdict",
    "check_tolerances",
]

#: Runs per direction ISO 230-2:2014 §5.3 asks for.
RECOMMENDED_RUNS = 5
#: Axis parameters in the order they are printed (and the keys of :meth:`Iso230_2Result.parameters`).
PARAMETER_NAMES = ("A", "A_up", "A_down", "E", "E_up", "E_down", "M", "R", "R_up", "R_down", "B", "B_mean")
#: The symbols ISO 230-2:2014 clause 3 prints for :data:`PARAMETER_NAMES` (↑ positive, ↓ negative
#: approach; B̄ the mean reversal value).
PARAMETER_SYMBOLS = {"A": "A", "A_up": "A↑", "A_down": "A↓", "E": "E", "E_up": "E↑", "E_down": "E↓",
                     "M": "M", "R": "R", "R_up": "R↑", "R_down": "R↓", "B": "B", "B_mean": "B̄"}

FullTurn = Literal["separate", "merge"]


@dataclass(frozen=True, eq=False)
class Iso230_2Result:
    """Result of an ISO 230-2 evaluation. All values are in ``deviation_unit``.

    Per-target arrays have one entry per target (shape (m,)); a quantity that does not apply
    (the other direction of a unidirectional test) is NaN there and ``None`` in the axis
    parameters.

    Attributes
    ----------
    axis_kind : AxisKind
    target_unit, deviation_unit : str
    targets : ndarray, ``target_unit``
    n_up, n_down : ndarray of int
        Readings used at each target in each direction.
    mean_up, mean_down : ndarray
        x̄_i↑, x̄_i↓ (Yüksel et al., Position accuracy and repeatability calibration of turn tables eq. 2, 3).
    mean_bi : ndarray
        x̄_i (eq. 4).
    reversal : ndarray
        B_i = x̄_i↑ - x̄_i↓ (eq. 5).
    s_up, s_down : ndarray
        s_i↑, s_i↓ (eq. 8, 9).
    R_up_i, R_down_i, R_i : ndarray
        Repeatability at each target (eq. 10-12).
    A, A_up, A_down, E, E_up, E_down, M, R, R_up, R_down, B, B_mean : float or None
        Axis parameters (eq. 6, 7, 13-21).
    n_runs : int
        Largest number of runs in a direction.
    missing : int
        Readings missing over the whole test.
    closure_up, closure_down : float or None
        For a rotary axis evaluated over a full turn with 0° and 360° kept apart: mean deviation at
        360° minus that at 0° per direction; None otherwise.
    distinct_positions : int
        Physical target positions, 0° and 360° counted once.
    warnings : tuple of str
        What a reader must know (fewer than 5 runs, missing readings, too few targets, closure,
        a reading that alone sets A or R).
    outliers : tuple of Outlier
        Readings Grubbs' test finds apart from the other runs at their target
        (:func:`axiscal.standards.outliers.positioning_outliers`); kept in the evaluation.
    """

    axis_kind: AxisKind
    target_unit: str
    deviation_unit: str
    targets: np.ndarray
    n_up: np.ndarray
    n_down: np.ndarray
    mean_up: np.ndarray
    mean_down: np.ndarray
    mean_bi: np.ndarray
    reversal: np.ndarray
    s_up: np.ndarray
    s_down: np.ndarray
    R_up_i: np.ndarray
    R_down_i: np.ndarray
    R_i: np.ndarray
    A: float | None
    A_up: float | None
    A_down: float | None
    E: float | None
    E_up: float | None
    E_down: float | None
    M: float | None
    R: float | None
    R_up: float | None
    R_down: float | None
    B: float | None
    B_mean: float | None
    n_runs: int
    missing: int
    distinct_positions: int
    closure_up: float | None = None
    closure_down: float | None = None
    warnings: tuple[str, ...] = field(default_factory=tuple)
    outliers: tuple = field(default_factory=tuple)

    @property
    def bidirectional(self) -> bool:
        """True if both directions were measured (A, E, M, R, B apply)."""
        return self.A is not None

    def parameters(self) -> dict[str, float | None]:
        """The axis parameters by name (``A``, ``A_up`` … ``B_mean``); None where not applicable."""
        return {name: getattr(self, name) for name in PARAMETER_NAMES}

    def target_table(self) -> list[dict[str, float | int | None]]:
        """Per-target rows: target, counts, means, B_i, s, R (NaN as None)."""
        rows = []
        for i, t in enumerate(self.targets):
            row: dict[str, float | int | None] = {
                "target": float(t),
                "n_up": int(self.n_up[i]),
                "n_down": int(self.n_down[i]),
            }
            for name in ("mean_up", "mean_down", "mean_bi", "reversal", "s_up", "s_down",
                         "R_up_i", "R_down_i", "R_i"):
                v = float(getattr(self, name)[i])
                row[name] = None if math.isnan(v) else v
            rows.append(row)
        return rows

    def __str__(self) -> str:
        """The parameters by their symbols in ISO 230-2:2014 clause 3 (A↑, B̄ ...), in the
        unit as people write it (µm, not the code's ``um``) and to a fixed resolution (0.01 µm
        or arcsec, 1e-5 mm), so a column of them lines up."""
        u = units.display(self.deviation_unit)
        digits = 5 if self.deviation_unit in ("mm", "deg") else 2
        kind = "bidirectional" if self.bidirectional else "unidirectional"
        lines = [
            f"ISO 230-2:2014, {self.axis_kind.value} axis, {kind}: {self.targets.size} targets "
            f"({self.distinct_positions} positions), {self.n_runs} runs, deviations in {u}"
        ]
        for name in PARAMETER_NAMES:
            v = getattr(self, name)
            sym = PARAMETER_SYMBOLS[name]
            pad = " " * (3 - len(sym.replace("\u0304", "")))      # the bar takes no column
            lines.append(f"  {sym}{pad}= " + ("n/a" if v is None else f"{v:8.{digits}f} {u}"))
        lines.extend(f"  warning: {w}" for w in self.warnings)
        return "\n".join(lines)


def minimum_rotary_targets(travel_deg: float) -> int:
    """Minimum number of target positions for a rotary axis, ISO 230-2 Table 1 (Yüksel et al., Position accuracy and repeatability calibration of turn tables Table 1).

    Parameters
    ----------
    travel_deg : float, degrees
        Measurement travel.

    Returns
    -------
    int
        3 for travel up to 90°, 5 up to 180°, 8 beyond.

    Examples
    --------
    >>> [minimum_rotary_targets(t) for t in (45, 90, 91, 180, 181, 360)]
    [3, 3, 5, 5, 8, 8]
    """
    if not travel_deg > 0:
        raise InputError(f"travel {travel_deg!r} deg must be positive")
    if travel_deg <= 90:
        return 3
    if travel_deg <= 180:
        return 5
    return 8


def minimum_linear_targets(travel_mm: float) -> int:
    """Minimum number of target positions for a linear axis (ISO 230-2:2014 §5.2).

    At least five target positions per metre and at least five in all, for travels up to 2000 mm.
    Beyond 2000 mm the standard allows one target per 250 mm on average; this function keeps the
    five-per-metre rule, which is never fewer.

    Parameters
    ----------
    travel_mm : float, millimetres

    Returns
    -------
    int
        ``max(5, ceil(5 · travel / 1000 mm))``.

    Examples
    --------
    >>> minimum_linear_targets(150), minimum_linear_targets(800), minimum_linear_targets(1000.5)
    (5, 5, 6)
    """
    if not travel_mm > 0:
        raise InputError(f"travel {travel_mm!r} mm must be positive")
    return max(5, math.ceil(5.0 * travel_mm / 1000.0 - 1e-9))


def evaluate(dataset: PositioningDataset, full_turn: FullTurn = "separate") -> Iso230_2Result:
    """Evaluate a positioning test by ISO 230-2:2014.

    Parameters
    ----------
    dataset : PositioningDataset
        Deviations per target, direction and run (NaN = missing reading).
    full_turn : {"separate", "merge"}
        For a rotary test whose targets span exactly 360°: keep 0° and 360° as two targets
        (default) or pool their readings into one target at 0°. Ignored otherwise.

    Returns
    -------
    Iso230_2Result

    Raises
    ------
    InsufficientRunsError
        If a measured direction has fewer than 2 readings at some target.
    InputError
        If ``full_turn`` is not one of the two choices.

    Notes
    -----
    Equations of ISO 230-2:2014 clause 3, as numbered in Yüksel et al., Position accuracy and repeatability calibration of turn tables (see the module docstring).

    Examples
    --------
    >>> from axiscal.datasets import PositioningDataset
    >>> ds = PositioningDataset.from_arrays(
    ...     "linear", [0, 500, 1000],
    ...     up=[[1, 3], [2, 2], [0, 2]], down=[[0, 0], [1, 1], [-1, -1]])
    >>> r = evaluate(ds)
    >>> r.B, r.E, r.M
    (2.0, 3.0, 1.5)
    """
    if full_turn not in ("separate", "merge"):
        raise InputError(f"full_turn={full_turn!r}; use 'separate' or 'merge'")
    targets, up, down = dataset.targets, dataset.up, dataset.down
    is_full_turn = _spans_full_turn(dataset)
    if is_full_turn and full_turn == "merge":
        targets, up, down = _merge_full_turn(targets, up, down)

    warn: list[str] = []
    unit = dataset.deviation_unit
    n_up, mean_up, s_up = _direction_stats(targets, up, dataset.target_unit, "+")
    n_down, mean_down, s_down = _direction_stats(targets, down, dataset.target_unit, "-")
    n_runs, missing, distinct = _test_extent(dataset, targets, warn)
    per_target, params = _axis_parameters(mean_up, s_up, mean_down, s_down,
                                          up.shape[1] > 0, down.shape[1] > 0, warn)

    closure_up = closure_down = None
    if is_full_turn and full_turn == "separate":
        span = float(np.max(np.abs(targets))) * _deg_to(unit) / _deg_to(dataset.target_unit)
        closure_up, closure_down = _closure(mean_up, s_up, n_up, mean_down, s_down, n_down,
                                            unit, warn, span)

    result = Iso230_2Result(
        axis_kind=dataset.axis_kind,
        target_unit=dataset.target_unit,
        deviation_unit=unit,
        targets=_frozen(targets),
        n_up=_frozen(n_up),
        n_down=_frozen(n_down),
        mean_up=_frozen(mean_up),
        mean_down=_frozen(mean_down),
        s_up=_frozen(s_up),
        s_down=_frozen(s_down),
        **{k: _frozen(v) for k, v in per_target.items()},
        n_runs=n_runs,
        missing=missing,
        distinct_positions=distinct,
        closure_up=closure_up,
        closure_down=closure_down,
        warnings=tuple(warn),
        **params,
    )
    from axiscal.standards.outliers import with_outliers

    return with_outliers(result, targets, up, down)



# -- helpers ------------------------------------------------------------------------------
def _test_extent(dataset: PositioningDataset, targets: np.ndarray, warn: list) -> tuple:
    """Runs, missing readings and distinct target positions of the test as measured, with a
    warning where ISO 230-2:2014 asks for more (5 runs, §5.3; targets, Table 1): (n_runs,
    missing, distinct). Pooling 360° into 0° (``full_turn="merge"``) widens the arrays with
    padding that is neither a run nor a missing reading, so they are counted on ``dataset``."""
    n_runs = int(max(dataset.up.shape[1], dataset.down.shape[1]))
    if n_runs < RECOMMENDED_RUNS:
        warn.append(
            f"{n_runs} runs; ISO 230-2:2014 asks for {RECOMMENDED_RUNS} in each direction, "
            "so the repeatability estimates are less certain"
        )
    missing = int(np.isnan(dataset.up).sum() + np.isnan(dataset.down).sum())
    if missing:
        warn.append(
            f"{missing} reading(s) missing; each target was evaluated from the readings it has "
            "(see the per-target counts)"
        )
    distinct = _distinct_positions(dataset, targets)
    if dataset.axis_kind is AxisKind.ROTARY:
        need = minimum_rotary_targets(dataset.travel)
        rule = f"a rotary travel of {dataset.travel:g} deg (ISO 230-2 Table 1)"
    else:
        travel_mm = dataset.travel * _to_mm(dataset.target_unit)
        need = minimum_linear_targets(travel_mm)
        rule = f"a linear travel of {travel_mm:g} mm (5 per metre, 5 at least)"
    if distinct < need:
        warn.append(f"{distinct} target positions; ISO 230-2 asks for at least {need} over {rule}")
    return n_runs, missing, distinct


def _axis_parameters(mean_up, s_up, mean_down, s_down, has_up: bool, has_down: bool,
                     warn: list) -> tuple[dict, dict]:
    """The per-target values (mean_bi, reversal, R_up_i, R_down_i, R_i: equations (4), (5),
    (10)-(12) of the module docstring) and the axis parameters A↑ ... B̄ (equations (6), (7),
    (13)-(21)), None for a direction not measured: (per-target dict, parameter dict)."""
    with _warnings.catch_warnings():
        _warnings.simplefilter("ignore", RuntimeWarning)
        R_up_i = 4.0 * s_up
        R_down_i = 4.0 * s_down
        if has_up and has_down:
            mean_bi = 0.5 * (mean_up + mean_down)
            reversal = mean_up - mean_down
            R_i = np.maximum.reduce([2 * s_up + 2 * s_down + np.abs(reversal), R_up_i, R_down_i])
        else:
            nan = np.full(mean_up.size, np.nan)
            mean_bi, reversal, R_i = nan, nan.copy(), nan.copy()
    per_target = dict(mean_bi=mean_bi, reversal=reversal, R_up_i=R_up_i, R_down_i=R_down_i,
                      R_i=R_i)

    def span(hi, lo):
        return float(np.max(hi) - np.min(lo))

    params: dict[str, float | None] = dict(A_up=None, E_up=None, R_up=None, A_down=None,
                                           E_down=None, R_down=None)
    if has_up:
        params.update(A_up=span(mean_up + 2 * s_up, mean_up - 2 * s_up),
                      E_up=span(mean_up, mean_up), R_up=float(np.max(R_up_i)))
    if has_down:
        params.update(A_down=span(mean_down + 2 * s_down, mean_down - 2 * s_down),
                      E_down=span(mean_down, mean_down), R_down=float(np.max(R_down_i)))
    if not (has_up and has_down):
        which = "positive (↑)" if has_up else "negative (↓)"
        warn.append(
            f"unidirectional test, {which} direction only: A, E, M, R, B and the mean reversal "
            "do not apply"
        )
        return per_target, dict(params, A=None, E=None, M=None, R=None, B=None, B_mean=None)
    both_hi = np.concatenate([mean_up + 2 * s_up, mean_down + 2 * s_down])
    both_lo = np.concatenate([mean_up - 2 * s_up, mean_down - 2 * s_down])
    both = np.concatenate([mean_up, mean_down])
    return per_target, dict(params, A=span(both_hi, both_lo), E=span(both, both),
                            M=span(mean_bi, mean_bi), R=float(np.max(R_i)),
                            B=float(np.max(np.abs(reversal))), B_mean=float(np.mean(reversal)))


def _direction_stats(targets: np.ndarray, arr: np.ndarray, target_unit: str, sign: str):
    """Counts, means (eq. 2/3) and estimators s (eq. 8/9) of one direction; NaN if not measured."""
    m = targets.size
    if arr.shape[1] == 0:
        nan = np.full(m, np.nan)
        return np.zeros(m, dtype=int), nan, nan.copy()
    n = np.sum(~np.isnan(arr), axis=1)
    if np.any(n < 2):
        i = int(np.argmax(n < 2))
        raise InsufficientRunsError(
            f"{int(n[i])} reading(s) at target {targets[i]:g} {target_unit} in direction {sign}; "
            f"ISO 230-2 needs at least 2 to estimate repeatability ({RECOMMENDED_RUNS} recommended)"
        )
    mean = np.nanmean(arr, axis=1)
    s = np.sqrt(np.nansum((arr - mean[:, None]) ** 2, axis=1) / (n - 1))
    return n.astype(int), mean, s


def _spans_full_turn(ds: PositioningDataset) -> bool:
    if ds.axis_kind is not AxisKind.ROTARY:
        return False
    turn = 360.0 * _deg_to(ds.target_unit)
    return math.isclose(ds.travel, turn, rel_tol=0, abs_tol=1e-9 * turn)


def _merge_full_turn(targets, up, down):
    """Pool the readings of the last target (360°) into the first (0°) as extra runs."""
    def pool(arr):
        if arr.shape[1] == 0:
            return arr[:-1]
        first = np.concatenate([arr[0], arr[-1]])
        rest = np.concatenate([arr[1:-1], np.full((arr.shape[0] - 2, arr.shape[1]), np.nan)], axis=1)
        return np.vstack([first, rest])

    return targets[:-1], pool(up), pool(down)


def _distinct_positions(ds: PositioningDataset, targets: np.ndarray) -> int:
    if ds.axis_kind is AxisKind.ROTARY:
        turn = 360.0 * _deg_to(ds.target_unit)
        wrapped = np.round(np.mod(targets, turn) / turn * 1e9)
        wrapped[wrapped == 1e9] = 0
        return int(np.unique(wrapped).size)
    return int(targets.size)


def _closure(mean_up, s_up, n_up, mean_down, s_down, n_down, unit, warn, span):
    """Difference of the means at 360° and 0°; warn if larger than 3 standard errors allow.

    With no scatter at all the standard error is 0 and any difference would warn, however it
    arose. A deviation is a reading minus a target of magnitude ``span`` (360° = 1 296 000″,
    in the deviation's unit): binary64 arithmetic (IEEE 754, ε = 2.2e-16) leaves it uncertain by
    a few ulps of that magnitude, 2e-10″ per ulp at 360°. Differences within 64 ε times
    (span + largest mean), 1.8e-8″ at 360°, are float rounding, not a closure.
    """
    out = []
    for name, mean, s, n in (("+", mean_up, s_up, n_up), ("-", mean_down, s_down, n_down)):
        if np.isnan(mean[0]):
            out.append(None)
            continue
        c = float(mean[-1] - mean[0])
        se = math.sqrt(s[0] ** 2 / n[0] + s[-1] ** 2 / n[-1])
        # floor for float rounding (see the docstring): with no scatter se = 0
        rounding = 64 * np.finfo(float).eps * (span + float(np.nanmax(np.abs(mean))))
        if abs(c) > 3 * se and abs(c) > rounding:
            warn.append(
                f"closure in direction {name}: the mean deviation at 360° differs from 0° by "
                f"{c:.3g} {unit}, more than repeatability explains (3 standard errors = "
                f"{3 * se:.3g} {unit}); look for drift during the test or a reference that is "
                "not modulo one turn"
            )
        out.append(c)
    return out[0], out[1]


def _deg_to(unit: str) -> float:
    from axiscal.units import convert

    return convert(1.0, "deg", unit)


def _to_mm(unit: str) -> float:
    from axiscal.units import convert

    return convert(1.0, unit, "mm")


def _frozen(a: np.ndarray) -> np.ndarray:
    a = np.array(a)
    a.flags.writeable = False
    return a


@dataclass(frozen=True)
class Verdict:
    """One parameter checked against its tolerance.

    Attributes
    ----------
    parameter : str
        ``A``, ``E``, ``R``, ... (a key of :data:`PARAMETER_NAMES`).
    value : float or None
        Measured value in the result's deviation unit (None if it does not apply).
    tolerance : float
        The largest value accepted, same unit.
    passed : bool or None
        ``value <= tolerance`` (for ``B_mean``, ``|value| <= tolerance``); None if not applicable.
    """

    parameter: str
    value: float | None
    tolerance: float
    passed: bool | None

    def __str__(self) -> str:
        state = {True: "PASS", False: "FAIL", None: "n/a"}[self.passed]
        v = "n/a" if self.value is None else f"{self.value:.4g}"
        return f"{self.parameter}: {v} (tolerance {self.tolerance:g}) {state}"


def check_tolerances(result: Iso230_2Result, tolerances: dict[str, float]) -> tuple[Verdict, ...]:
    """Compare axis parameters with the tolerances of an acceptance test.

    Parameters
    ----------
    result : Iso230_2Result
    tolerances : dict of str to float
        Parameter name (``A``, ``A_up``, ..., ``B_mean``) to the largest accepted value, in the
        result's deviation unit.

    Returns
    -------
    tuple of Verdict
        In the order of :data:`PARAMETER_NAMES`.

    Notes
    -----
    A plain comparison of the measured value with the tolerance, as ISO 230-2 acceptance tests
    state them. It applies no guard band for the measurement uncertainty: where a contract
    invokes the decision rules of ISO 14253-1, the uncertainty (ISO 230-9) must be subtracted from
    the tolerance before calling this function.

    Examples
    --------
    >>> from axiscal.datasets import PositioningDataset
    >>> r = evaluate(PositioningDataset.from_arrays(
    ...     "linear", [0, 500, 1000], up=[[1, 3], [2, 2], [0, 2]], down=[[0, 0], [1, 1], [-1, -1]]))
    >>> [str(v) for v in check_tolerances(r, {"E": 4, "B": 1.5})]
    ['E: 3 (tolerance 4) PASS', 'B: 2 (tolerance 1.5) FAIL']
    """
    out = []
    for name, tol in tolerances.items():
        if name not in PARAMETER_NAMES:
            raise InputError(f"tolerance for {name!r}: not an ISO 230-2 parameter; use one of "
                             f"{', '.join(PARAMETER_NAMES)}")
        if not (isinstance(tol, (int, float)) and math.isfinite(tol) and tol >= 0):
            raise InputError(f"tolerance {name} = {tol!r} must be a number >= 0")
    for name in PARAMETER_NAMES:
        if name not in tolerances:
            continue
        tol = float(tolerances[name])
        v = getattr(result, name)
        passed = None if v is None else bool((abs(v) if name == "B_mean" else v) <= tol)
        out.append(Verdict(name, v, tol, passed))
    return tuple(out)
