"""What a compensation table is built from: a positioning data file or an ISO 230-2 result.

:func:`load_mean_deviations` accepts

* a positioning data file (tidy CSV, axiscal JSON dataset, EPICS ecmc), which is evaluated by
  ISO 230-2 (:func:`axiscal.standards.iso230_2.evaluate`), or
* the JSON an ``axiscal iso230-2 --json`` run printed (keys ``axis_kind``, ``target_unit``,
  ``unit`` and ``targets``, a list of objects with ``target``, ``mean_up``, ``mean_down``).

Either way the result has what :func:`~axiscal.compensation.tables.table_from_result` reads:
``axis_kind``, ``target_unit``, ``deviation_unit``, ``targets``, ``mean_up``, ``mean_down``.
"""

from __future__ import annotations

import json
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from axiscal.datasets import AxisKind
from axiscal.errors import DataFormatError

__all__ = ["MeanDeviations", "load_mean_deviations", "parse_result_json"]


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


def load_mean_deviations(path, full_turn: str = "separate"):
    """Read ``path`` as a result JSON or a positioning data file (evaluated by ISO 230-2).

    Returns
    -------
    result : MeanDeviations or Iso230_2Result
    axis : str
        The axis name the data file's metadata gives ("" for a result JSON, which has none).
    """
    from axiscal.io import read_positioning, read_text
    from axiscal.standards.iso230_2 import evaluate

    text = read_text(path)
    if Path(path).suffix.lower() == ".json" or text.lstrip().startswith("{"):
        try:
            d = json.loads(text)
        except json.JSONDecodeError as exc:
            raise DataFormatError(f"not valid JSON: {exc.msg}", str(path), exc.lineno) from None
        if isinstance(d, dict) and "format" not in d and "targets" in d:
            return parse_result_json(d, str(path)), ""
    ds = read_positioning(path)
    return evaluate(ds, full_turn=full_turn), ds.metadata.axis  # type: ignore[arg-type]


def parse_result_json(d: dict, source: str = "<json>") -> MeanDeviations:
    """The mean deviations of an ``axiscal iso230-2 --json`` object."""
    missing = [k for k in ("axis_kind", "target_unit", "unit", "targets") if k not in d]
    if missing:
        raise DataFormatError(f"result JSON is missing {', '.join(missing)}", source)
    rows = d["targets"]
    if not isinstance(rows, list) or len(rows) < 2 or not all(isinstance(r, dict) for r in rows):
        raise DataFormatError("'targets' must be a list of at least 2 objects", source)
    try:
        t = np.array([float(r["target"]) for r in rows])
        up = np.array([np.nan if r.get("mean_up") is None else float(r["mean_up"]) for r in rows])
        down = np.array([np.nan if r.get("mean_down") is None else float(r["mean_down"]) for r in rows])
        kind = AxisKind.parse(d["axis_kind"])
    except (KeyError, TypeError, ValueError) as exc:
        raise DataFormatError(f"bad target row: {exc}", source) from None
    if np.any(np.diff(t) <= 0):
        raise DataFormatError("targets must increase strictly", source)
    return MeanDeviations(kind, str(d["target_unit"]), str(d["unit"]), t, up, down)
