"""Plain JSON data of axiscal's results: one converter for the command line and the history."""

from __future__ import annotations

import dataclasses
import enum
import math
from typing import Any

__all__ = ["jsonable"]


def jsonable(obj: Any) -> Any:
    """Numpy scalars and arrays, tuples, dataclasses and enums as plain JSON data.

    NaN and infinity become ``None`` (JSON has neither), dict keys become strings.

    Examples
    --------
    >>> import numpy as np
    >>> jsonable({1: (np.float64(2.5), np.nan), "a": np.arange(2)})
    {'1': [2.5, None], 'a': [0, 1]}
    """
    import numpy as np

    if dataclasses.is_dataclass(obj) and not isinstance(obj, type):
        return {f.name: jsonable(getattr(obj, f.name)) for f in dataclasses.fields(obj)}
    if isinstance(obj, dict):
        return {str(k): jsonable(v) for k, v in obj.items()}
    if isinstance(obj, (list, tuple)):
        return [jsonable(v) for v in obj]
    if isinstance(obj, np.ndarray):
        return jsonable(obj.tolist())
    if isinstance(obj, enum.Enum):
        return obj.value
    if isinstance(obj, (float, np.floating)):
        v = float(obj)
        return v if math.isfinite(v) else None
    if isinstance(obj, np.integer):
        return int(obj)
    if isinstance(obj, np.bool_):
        return bool(obj)
    return obj
