"""Review: freezing a result's arrays must not freeze the arrays the caller passed in."""

from __future__ import annotations

import numpy as np

from axiscal.physics.encoder import ErrorMap
from axiscal.physics.misalignment import tradeoff_table


def test_error_map_leaves_the_callers_arrays_writeable():
    angles = np.linspace(0.0, 6.0, 7)
    errors = np.zeros(7)
    m = ErrorMap(angles, errors)
    angles[0] = 0.5   # the user's own array: before the review this raised "read-only"
    errors[:] = 1.0
    assert m.angles[0] == 0.0 and not m.errors.any()   # and the map kept its own copy
    assert not m.angles.flags.writeable


def test_tradeoff_table_leaves_the_callers_grids_writeable():
    alphas = np.array([1e-3, 2e-3])
    betas = np.array([1e-3])
    t = tradeoff_table(alphas, betas)
    alphas *= 2.0
    betas += 1e-3
    assert t.alpha.tolist() == [1e-3, 2e-3] and t.beta.tolist() == [1e-3]
