"""The kinematics of a table-table five-axis machine with location errors
(axiscal.physics.rotary_location): LinuxCNC's trt kinematics at zero error, the magnitudes the
issue quotes, and exact inverses."""

from __future__ import annotations

import numpy as np
import pytest

from axiscal.errors import InputError
from axiscal.physics.rotary_location import (AxisMotion, Geometry, machine_to_table,
                                             parameter_names, table_to_machine, transform_many)


def _rx(t):
    c, s = np.cos(t), np.sin(t)
    return np.array([[1, 0, 0], [0, c, -s], [0, s, c]])


def _ry(t):
    c, s = np.cos(t), np.sin(t)
    return np.array([[c, 0, s], [0, 1, 0], [-s, 0, c]])


def _rz(t):
    c, s = np.cos(t), np.sin(t)
    return np.array([[c, -s, 0], [s, c, 0], [0, 0, 1]])


@pytest.mark.parametrize("tilt", ["A", "B"])
def test_zero_error_kinematics_is_linuxcnc_trt_forward(tilt):
    """LinuxCNC 2.9 src/emc/kinematics/trtfuncs.c, xyzacKinematicsForward and
    xyzbcKinematicsForward (commit 135b0ce5), written in matrix form: world =
    Rz(−c)[R_T(−t)(joint − p_T) + p_T − p_C] + p_C, with p_C = (x-rot-point, y-rot-point, ·)
    and p_T the tilting axis (y-rot-point + y-offset, z-rot-point + z-offset for A;
    x-rot-point + x-offset, z-rot-point + z-offset for B): the table turns right-handed."""
    rng = np.random.default_rng(4)
    xr, yr, zr, off1, offz = 0.05, -0.02, -0.1, 0.013, 0.031
    if tilt == "A":
        g = Geometry("A", (yr + off1, zr + offz), (xr, yr))
        p_t, rot = np.array([0.0, yr + off1, zr + offz]), _rx
    else:
        g = Geometry("B", (xr + off1, zr + offz), (xr, yr))
        p_t, rot = np.array([xr + off1, 0.0, zr + offz]), _ry
    p_c = np.array([xr, yr, 0.0])
    for _ in range(5):
        j = rng.uniform(-0.3, 0.3, 3)
        t, c = rng.uniform(-2, 2, 2)
        world = _rz(-c) @ (rot(-t) @ (j - p_t) + p_t - p_c) + p_c
        np.testing.assert_allclose(machine_to_table(g, {}, t, c, j)[0], world, atol=1e-15)
        np.testing.assert_allclose(table_to_machine(g, {}, t, c, world)[0], j, atol=1e-15)


def test_a_c_offset_of_20_um_moves_a_table_point_40_um_over_half_a_turn():
    """Issue 43: 'A 20 µm offset of the C axis centre moves a point on the table by up to 40 µm
    over half a turn'."""
    g = Geometry("A", (0.0, -0.05), (0.0, 0.0))
    p = [[0.2, 0.0, 0.03]]
    c = np.linspace(0, np.pi, 7)
    d = table_to_machine(g, {"E_X0C": 20e-6}, 0.0, c, p) - table_to_machine(g, {}, 0.0, c, p)
    moved = np.linalg.norm(d, axis=1)
    assert moved[0] == pytest.approx(0.0, abs=1e-12)
    assert moved.max() == pytest.approx(40e-6, rel=1e-6)


def test_a_tilt_of_30_urad_moves_a_point_200_mm_from_the_axis_12_um():
    """Issue 43: 'a 30 µrad tilt moves a point 200 mm from the axis by up to 12 µm' (the C axis
    tilted about Y, half a turn: 2 × 30 µrad × 200 mm)."""
    g = Geometry("A", (0.0, 0.0), (0.0, 0.0))
    p = [[0.2, 0.0, 0.0]]
    c = np.linspace(0, np.pi, 13)
    d = table_to_machine(g, {"E_B0C": 30e-6}, 0.0, c, p) - table_to_machine(g, {}, 0.0, c, p)
    assert np.linalg.norm(d, axis=1).max() == pytest.approx(12e-6, rel=1e-4)


@pytest.mark.parametrize("tilt", ["A", "B"])
def test_inverse_is_exact_with_location_errors_and_error_motions(tilt):
    rng = np.random.default_rng(2)
    g = Geometry(tilt, (0.01, -0.06), (0.02, -0.01))
    errors = dict(zip(parameter_names(tilt), rng.normal(0, 30e-6, 10)))
    n = 9
    motion = lambda: AxisMotion(*(rng.normal(0, 5e-6, n) for _ in range(6)))  # noqa: E731
    mt, mc = motion(), motion()
    a, c = rng.uniform(-1.5, 1.5, n), rng.uniform(-3, 3, n)
    p = rng.uniform(-0.2, 0.2, (n, 3))
    m = table_to_machine(g, errors, a, c, p, mt, mc)
    np.testing.assert_allclose(machine_to_table(g, errors, a, c, m, mt, mc), p, atol=1e-15)
    many = transform_many(g, [errors, {}], a, c, p)
    np.testing.assert_allclose(many[1], table_to_machine(g, {}, a, c, p), atol=1e-15)


def test_a_radial_error_motion_of_c_shifts_a_table_point_by_itself():
    g = Geometry("A", (0.0, 0.0), (0.0, 0.0))
    z = np.zeros(1)
    m = AxisMotion(ez=z, ex=z, ey=z, dx=np.array([3e-6]), dy=z, dz=np.array([-2e-6]))
    d = table_to_machine(g, {}, 0.0, 0.0, [[0.1, 0.0, 0.0]], c_motion=m) - [0.1, 0.0, 0.0]
    np.testing.assert_allclose(d[0], [3e-6, 0.0, -2e-6], atol=1e-15)


def test_a_tilting_axis_other_than_a_or_b_is_refused():
    with pytest.raises(InputError, match="A or B"):
        Geometry("C")


def test_a_spindle_head_turns_the_tool_tip_right_handed_about_its_axis():
    """B head, pivot 150 mm: at B = +90° the tip (0, 0, −150) mm below the pivot turns to
    (−150, 0, 0) mm (right-handed about +Y), so the joints that put it on the table's origin are
    (+150, 0, 0) mm; and the inverse is exact with every error."""
    g = Geometry("B", (0.0, 0.0), (0.0, 0.0), kind="head-table", pivot=0.15)
    np.testing.assert_allclose(table_to_machine(g, {}, np.pi / 2, 0.0, [[0, 0, 0]])[0],
                               [0.15, 0.0, 0.0], atol=1e-15)
    np.testing.assert_allclose(table_to_machine(g, {}, 0.0, 0.0, [[0, 0, 0]])[0],
                               [0.0, 0.0, 0.15], atol=1e-15)
    rng = np.random.default_rng(3)
    errors = dict(zip(parameter_names("B"), rng.normal(0, 30e-6, 10)))
    a, c, p = rng.uniform(-1.5, 1.5, 7), rng.uniform(-3, 3, 7), rng.uniform(-0.2, 0.2, (7, 3))
    j = table_to_machine(g, errors, a, c, p)
    np.testing.assert_allclose(machine_to_table(g, errors, a, c, j), p, atol=1e-15)
    np.testing.assert_allclose(transform_many(g, [errors], a, c, p)[0], j, atol=1e-15)
