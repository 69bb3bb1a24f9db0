"""The Type B inputs of the five-axis identification's uncertainty budget: the instruments'
calibrations that act on every reading of a set-up at once (JCGM 100:2008, 5.1.3 and F.2.4.5;
ISO/TR 230-9:2005, 6). :func:`systematic_inputs` gives, per input, the change ``g`` of all readings
per standard uncertainty of the input; :mod:`axiscal.standards.location_errors` propagates it as
``K g`` with ``K`` the fit's gain from readings to parameters.

* the touch probe's stylus offset (x, y) and length (z): a constant in the machine frame;
* the R-test's sensor gains and measuring directions, through the nest's directions ``N`` as the
  instrument turns its readings into X, Y, Z.
"""

from __future__ import annotations

import numpy as np

__all__ = ["systematic_inputs"]


def systematic_inputs(setups, n: int) -> dict[str, np.ndarray]:
    """Type B inputs acting on all readings of a set-up at once: name -> ``g``, the change of
    the readings per standard uncertainty of the input (module docstring). One probe (one
    R-test) serves every set-up of its kind, so its input acts on all of them together."""
    out: dict[str, np.ndarray] = {}
    for name, g in _inputs(setups, n):
        out[name] = out.get(name, 0.0) + g
    return out


def _inputs(setups, n):
    start = 0
    for s in setups:
        m = 3 * s.poses
        if s.kind == "probing":
            for j, axis in enumerate("xyz"):
                if s.u_offset[j] > 0:
                    g = np.zeros(n)
                    g[start + j:start + m:3] = s.u_offset[j]
                    yield f"probe offset {axis}", g
        else:
            yield from _rtest_inputs(s, start, n)
        start += m


def _rtest_inputs(s, start: int, n: int):
    """An R-test's calibration inputs: each sensor's gain and measuring direction. The instrument
    turns readings ``r = N Δ`` into ``Δ = N⁻¹ r``; a gain error ``γ`` of sensor i reads
    ``γ (n_i·Δ)`` more, a tilt ``β`` of its direction towards ``p`` reads ``β (p·Δ)`` more; either
    moves the result by ``N⁻¹ e_i`` times that (JCGM 100, 5.1.3)."""
    N = np.eye(3) if s.directions is None else np.asarray(s.directions, float)
    Ninv = np.linalg.inv(N)
    m = 3 * s.poses
    for i in range(3):
        n_i = N[i] / np.linalg.norm(N[i])
        col = Ninv[:, i]
        if s.u_gain > 0:
            g = np.zeros(n)
            g[start:start + m] = np.outer(s.values @ n_i, col).ravel() * s.u_gain
            yield f"R-test gain {i + 1}", g
        if s.u_direction > 0:
            p1 = np.cross(n_i, [0.0, 0.0, 1.0] if abs(n_i[2]) < 0.9 else [1.0, 0.0, 0.0])
            p1 /= np.linalg.norm(p1)
            for k, p in enumerate((p1, np.cross(n_i, p1))):
                g = np.zeros(n)
                g[start:start + m] = np.outer(s.values @ p, col).ravel() * s.u_direction
                yield f"R-test direction {i + 1}{'ab'[k]}", g
