"""Input checks shared by the pure physics modules (air, humidity): private.

Each check names the parameter, the offending value and the rule, and raises
:class:`~axiscal.errors.InputError` (a ``ValueError``), as the conventions ask.
"""

from __future__ import annotations

import numpy as np

from axiscal.errors import InputError


def finite(name: str, value) -> np.ndarray:
    """``value`` as a float array; refuse anything that is not a finite number."""
    try:
        arr = np.asarray(value, dtype=float)
    except (TypeError, ValueError):
        raise InputError(f"{name} must be a number or an array of numbers, got {value!r:.60}") \
            from None
    if not np.all(np.isfinite(arr)):
        raise InputError(f"{name} must be finite (found NaN or infinity)")
    return arr


def refuse(name: str, values: np.ndarray, bad: np.ndarray, unit: str, rule: str) -> None:
    """Raise naming the first value where ``bad`` holds."""
    bad = np.asarray(bad)
    if np.any(bad):
        v = np.broadcast_to(values, bad.shape)[bad].ravel()[0]
        raise InputError(f"{name} = {v:g} {unit} {rule}".replace("  ", " "))


def scalar_or_array(x):
    """A 0-d result as a Python float, an array as it is."""
    arr = np.asarray(x, dtype=float)
    return float(arr) if arr.ndim == 0 else arr
