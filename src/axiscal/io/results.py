"""What a compensation table is built from: a positioning data file or an ISO 230-2 result.

:func:`load_mean_deviations` accepts

* a positioning data file (tidy CSV, axiscal JSON dataset, EPICS ecmc), which is evaluated by
  ISO 230-2 (:func:`axiscal.standards.iso230_2.evaluate`), or
* the JSON an ``axiscal iso230-2 --json`` run printed (keys ``axis_kind``, ``target_unit``,
  ``unit`` and ``targets``, a list of objects with ``target``, ``mean_up``, ``mean_down``).

Either way the result has what :func:`~axiscal.compensation.tables.table_from_result` reads:
``axis_kind``, ``target_unit``, ``deviation_unit``, ``targets``, ``mean_up``, ``mean_down``.

The other way, :func:`result_json`, :func:`verdicts_json` and :func:`standard_json` build the
stable JSON objects of ``axiscal iso230-2 --json`` and ``axiscal evaluate --json``, for the
commands and the public API (:mod:`axiscal.api`) alike.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from axiscal import units
from axiscal.datasets import AxisKind
from axiscal.errors import DataFormatError, InputError, UnitError

__all__ = ["MeanDeviations", "load_mean_deviations", "parse_result_json", "result_json",
           "standard_json", "verdicts_json"]


@dataclass(frozen=True, eq=False)
class MeanDeviations:
    """Mean deviations per target and direction, as an ISO 230-2 result holds them.

    Attributes
    ----------
    axis_kind : AxisKind
    target_unit, deviation_unit : str
    targets : ndarray, ``target_unit``
    mean_up, mean_down : ndarray, ``deviation_unit`` (NaN where a direction was not measured)
    """

    axis_kind: AxisKind
    target_unit: str
    deviation_unit: str
    targets: np.ndarray
    mean_up: np.ndarray
    mean_down: np.ndarray


def load_mean_deviations(path, full_turn: str = "separate", encoding: str | None = None):
    """Read ``path`` as a result JSON or a positioning data file (evaluated by ISO 230-2).

    A Renishaw export is read as :func:`axiscal.io.read_positioning` reads it: UTF-8, UTF-16
    with a BOM, or its Windows code page (``encoding``, the command's ``--encoding``).

    Returns
    -------
    result : MeanDeviations or Iso230_2Result
    axis : str
        The axis name the data file's metadata or the result JSON's ``axis`` gives ("" if none).
    """
    from axiscal.io import read_positioning, read_text
    from axiscal.io._files import read_bytes
    from axiscal.standards.iso230_2 import evaluate

    head = read_bytes(path).lstrip(b"\xef\xbb\xbf \t\r\n")
    if encoding is None and (Path(path).suffix.lower() == ".json" or head.startswith(b"{")):
        text = read_text(path)
        from axiscal._parse import loads_json

        d = loads_json(text, str(path))
        if isinstance(d, dict) and "format" not in d and "targets" in d:
            axis = d.get("axis", "")
            return parse_result_json(d, str(path)), axis if isinstance(axis, str) else ""
    ds = read_positioning(path, encoding=encoding)
    return evaluate(ds, full_turn=full_turn), ds.metadata.axis  # type: ignore[arg-type]


def parse_result_json(d: dict, source: str = "<json>") -> MeanDeviations:
    """The mean deviations of an ``axiscal iso230-2 --json`` object.

    Raises
    ------
    DataFormatError
        A key is missing, a target is not a finite number, a mean deviation is infinite or not a
        number (``null`` marks a direction not measured), targets do not increase, or a unit is
        unknown or not of the axis kind's dimension (length for linear, angle for rotary).
    """
    missing = [k for k in ("axis_kind", "target_unit", "unit", "targets") if k not in d]
    if missing:
        raise DataFormatError(f"result JSON is missing {', '.join(missing)}", source)
    rows = d["targets"]
    if not isinstance(rows, list) or len(rows) < 2 or not all(isinstance(r, dict) for r in rows):
        raise DataFormatError("'targets' must be a list of at least 2 objects", source)
    try:
        kind = AxisKind.parse(d["axis_kind"])
        t = np.array([_number(r, "target", i, source) for i, r in enumerate(rows)])
        up = np.array([_number(r, "mean_up", i, source, True) for i, r in enumerate(rows)])
        down = np.array([_number(r, "mean_down", i, source, True) for i, r in enumerate(rows)])
    except KeyError as exc:
        raise DataFormatError(f"a target row has no {exc}", source) from None
    except InputError as exc:
        raise DataFormatError(str(exc), source) from None
    if np.any(np.diff(t) <= 0):
        raise DataFormatError("targets must increase strictly", source)
    tu, du = (_unit(d, key, kind, source) for key in ("target_unit", "unit"))
    return MeanDeviations(kind, tu, du, t, up, down)


def _number(row: dict, key: str, i: int, source: str, optional: bool = False) -> float:
    """A finite number of a target row (``None`` -> NaN where ``optional``)."""
    v = row.get(key) if optional else row[key]
    if v is None and optional:
        return float("nan")
    try:
        f = float(v) if isinstance(v, (int, float)) and not isinstance(v, bool) else math.nan
    except OverflowError:          # a JSON integer of 400 digits
        f = math.inf
    if not math.isfinite(f):
        rule = "a finite number" + (" or null (direction not measured)" if optional else "")
        raise DataFormatError(f"targets[{i}].{key} = {v!r:.40} must be {rule}", source)
    return f


def _unit(d: dict, key: str, kind: AxisKind, source: str) -> str:
    """A known unit of the axis kind's dimension, in its canonical name."""
    try:
        u = units.canonical(d[key])
    except UnitError as exc:
        raise DataFormatError(f"{key}: {exc}", source) from None
    if units.dimension(u) != kind.dimension:
        raise DataFormatError(f"{key} = {d[key]!r} is not a {kind.dimension} unit, as a "
                              f"{kind.value} axis needs", source)
    return u


# -- out: the stable JSON of ``axiscal iso230-2 --json`` (keys documented in axiscal.cli.iso230_2),
# built here so the command, the public API (axiscal.api) and the workbench give one answer.
def verdicts_json(verdicts) -> dict:
    """The acceptance part of the JSON output (ISO 14253-1 decisions)."""
    from axiscal.standards.iso14253_1 import overall

    out = overall(verdicts)
    from axiscal.standards.iso230_9 import format_uncertainty

    return {"acceptance": [{"parameter": v.parameter, "value": v.value, "tolerance": v.upper,
                            "U": v.U, "U_display": format_uncertainty(v.U),
                            "outcome": v.outcome.value if v.outcome else None,
                            "passed": v.passed} for v in verdicts],
            "decision_rule": verdicts[0].rule.value if verdicts else None,
            "accepted": None if out is None else {"conformance proven": True,
                                                  "non-conformance proven": False}.get(out.value)}


def result_json(result, verdicts=(), budget=None) -> dict:
    """The stable JSON object of an ISO 230-2 result (keys: ``axiscal iso230-2 --json``)."""
    d = dict(result.parameters())
    d.update(
        unit=result.deviation_unit,
        target_unit=result.target_unit,
        axis_kind=result.axis_kind.value,
        n_runs=result.n_runs,
        missing=result.missing,
        closure_up=result.closure_up,
        closure_down=result.closure_down,
        targets=result.target_table(),
        warnings=list(result.warnings),
        outliers=[o.as_dict() for o in result.outliers],
    )
    if budget is not None:
        shown = [p for p, v in result.parameters().items() if v is not None]
        d["uncertainty"] = {p: budget.U(p) for p in shown}
        d["uncertainty_display"] = {p: budget.U_text(p) for p in shown}
        d["uncertainty_budget"] = budget.to_json(shown)
    if verdicts:
        from axiscal.standards.iso14253_1 import unprovable

        d.update(verdicts_json(verdicts))
        unit = result.deviation_unit
        d["warnings"] += unprovable(verdicts, {"um": "µm"}.get(unit, unit))
    return d


def standard_json(std, res) -> dict:
    """One standard's object of ``axiscal evaluate --json`` (``standards``; keys documented in
    :mod:`axiscal.cli.evaluate`): ``res`` a StandardResult, or the reason it was not evaluated."""
    evaluated = not isinstance(res, str)
    params = {} if not evaluated else {
        name: {"value": v, "unit": u, "description": d}
        for name, (v, u, d) in res.parameters().items()}
    return {"standard": std.key, "title": std.title, "evaluated": evaluated, "parameters": params,
            "not_evaluated": dict(res.not_evaluated) if evaluated else {},
            "warnings": list(res.warnings) if evaluated else [],
            "reason": None if evaluated else res}
