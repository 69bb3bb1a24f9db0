"""The uncertainty budget of the five-axis identification (axiscal.standards.location_errors):
Type B inputs of the instruments propagate linearly (JCGM 100:2008, 5.1.3), and the probe's
offset, fully correlated with the C position, reaches E_X0C one to one."""

from __future__ import annotations

import numpy as np
import pytest

from axiscal.physics.rotary_location import Geometry, table_to_machine
from axiscal.standards.location_errors import SetUp, identify_location_errors

G = Geometry("A", (0.0, -0.06), (0.0, 0.0))
A = np.repeat(np.radians([0.0, -45.0, -90.0]), 8)
C = np.tile(np.radians(np.arange(0, 360, 45)), 3)
ERR = {"E_X0C": 20e-6, "E_Y0A": 10e-6, "E_B0C": 20e-6}


def _probing(u_offset):
    v = table_to_machine(G, ERR, A, C, [0.15, 0.02, 0.06])
    return SetUp("probing", A, C, v, nominal=(0.15, 0.02, 0.06), u_offset=u_offset)


def _rtest(u_gain, u_direction):
    cmd = table_to_machine(G, {}, A, C, [-0.06, -0.04, 0.08])
    from axiscal.physics.rotary_location import machine_to_table
    d = machine_to_table(G, ERR, A, C, cmd) - [-0.06, -0.04, 0.08]
    return SetUp("r-test", A, C, d, cmd, nominal=(-0.06, -0.04, 0.08), u_gain=u_gain,
                 u_direction=u_direction)


def test_instrument_inputs_propagate_linearly_and_exact_data_is_found():
    r1 = identify_location_errors(G, [_probing((1e-6, 0, 0)), _rtest(1e-3, 1e-3)])
    r2 = identify_location_errors(G, [_probing((2e-6, 0, 0)), _rtest(2e-3, 2e-3)])
    for name in ("probe offset x", "R-test gain 1", "R-test direction 2a"):
        a, b = r1["E_B0C"].components[name], r2["E_B0C"].components[name]
        assert b == pytest.approx(2 * a, rel=1e-6) and a > 0
    assert r1["E_X0C"].value == pytest.approx(20e-6, abs=1e-10)       # noiseless readings
    # a probe offset in X moves every sphere centre in X, as the C axis's X position does at
    # every A here (A turns about X): with probing alone E_X0C takes it one to one; the R-test,
    # which has no probe, halves that weight in the joint fit
    alone = identify_location_errors(G, [_probing((1e-6, 0, 0))])
    assert alone["E_X0C"].components["probe offset x"] == pytest.approx(1e-6, rel=1e-3)
    assert 0.2e-6 < r1["E_X0C"].components["probe offset x"] < 0.9e-6
