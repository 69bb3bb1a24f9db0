"""The ballbar tests of a rotary axis moving with the linear axes (ISO 10791-6:2014 kinematic
tests as :mod:`axiscal.standards.iso10791_6` reads them): the analytic pattern of a pure C-axis
centre offset, the analytic sensitivity against finite differences of the exact kinematics, and
the range's budget."""

from __future__ import annotations

import numpy as np
import pytest

from axiscal.errors import InputError
from axiscal.instruments.ballbar import Ballbar
from axiscal.machines.five_axis import FiveAxisMachine
from axiscal.physics.rotary_location import (SQUARENESS, Geometry, linear_to_true,
                                              machine_to_table, table_to_machine)
from axiscal.procedures.five_axis_ballbar import BallbarSetUp, measure_ballbar
from axiscal.standards.iso10791_6 import (bar_direction, evaluate_ballbar, range_sensitivity,
                                          reading_sensitivity)

G_AC = Geometry("A", (0.0, -60e-3), (0.0, 0.0))


def _setup(geometry, pivot, direction, a, c, length=0.1, swept="C"):
    n = bar_direction(geometry, swept, direction, pivot, a[0], c[0])
    cmd = table_to_machine(geometry, {}, a, c, pivot + length * n)
    return BallbarSetUp("t", geometry.tilt, swept, direction, np.asarray(pivot, float), n,
                        length, a, c, cmd, Ballbar(length=length))


@pytest.mark.parametrize("direction", ["radial", "tangential", "axial"])
def test_a_pure_c_centre_offset_gives_the_analytic_pattern(direction):
    """Module docstring, 'Worked case': with E_X0C = e alone the spindle ball is truly at
    p_s + e (1 − cos c, sin c, 0) in the table frame (exact: the C line is displaced parallel),
    so the bar reads |L n + δ| − L exactly; to first order e (cos φ − cos(c + φ)) radially and
    e (sin(c + φ) − sin φ) tangentially, a range of 2e = 40 µm over a full turn, and 0 axially
    (the second-order term |δ⊥|²/(2L) is at most (40 µm)²/200 mm = 0.008 µm)."""
    e, phi, L = 20e-6, np.radians(30.0), 0.1
    machine = FiveAxisMachine(G_AC, {"E_X0C": e})
    c = np.radians(np.linspace(0.0, 360.0, 145))
    a = np.zeros_like(c)
    pivot = np.array([0.15 * np.cos(phi), 0.15 * np.sin(phi), 0.04])
    s = _setup(G_AC, pivot, direction, a, c)
    d = measure_ballbar(machine, [s])[0].deviation
    delta = e * np.column_stack([1 - np.cos(c), np.sin(c), np.zeros_like(c)])
    exact = np.linalg.norm(L * s.bar + delta, axis=1) - L
    np.testing.assert_allclose(d, exact, atol=1e-12)
    first = {"radial": e * (np.cos(phi) - np.cos(c + phi)),
             "tangential": e * (np.sin(c + phi) - np.sin(phi)),
             "axial": np.zeros_like(c)}[direction]
    np.testing.assert_allclose(d, first, atol=0.01e-6)
    want = 0.0 if direction == "axial" else 2 * e
    assert abs(np.ptp(d) - want) < 0.01e-6
    # the analytic sensitivity gives the same first-order pattern
    j = reading_sensitivity(G_AC, a, c, s.spindle_ball, s.bar, ["E_X0C"])[:, 0]
    np.testing.assert_allclose(j * e, first, atol=1e-15)


@pytest.mark.parametrize("tilt", ["A", "B"])
def test_the_analytic_sensitivity_equals_finite_differences_of_the_exact_kinematics(tilt):
    """Every location error and squareness, a five-axis path (both rotary axes swept), off-centre
    geometry: the first-order formulas of the module docstring against central differences of
    machine_to_table (exact Rodrigues rotations), h = 1e-7: agreement to 1e-9 (µm per µm or per
    µrad), the differences' own truncation."""
    g = Geometry(tilt, (3e-3, -60e-3), (5e-3, -2e-3))
    a = np.radians(np.linspace(-90.0, 20.0, 13) * (1 if tilt == "A" else -1))
    c = np.radians(np.linspace(0.0, 330.0, 13))
    pivot = np.array([0.15, 0.02, 0.06])
    n = bar_direction(g, "both", "tangential", pivot, a[0], c[0])
    ps = pivot + 0.1 * n
    names = g.names + SQUARENESS
    J = reading_sensitivity(g, a, c, ps, n, names)
    cmd = table_to_machine(g, {}, a, c, ps)
    h = 1e-7

    def reading(name, e):
        t = machine_to_table(g, {name: e}, a, c, linear_to_true(cmd, {name: e}))
        return np.linalg.norm(t - pivot, axis=1) - 0.1

    for j, name in enumerate(names):
        fd = (reading(name, h) - reading(name, -h)) / (2 * h)
        np.testing.assert_allclose(J[:, j], fd, atol=1e-9, err_msg=name)
    assert np.abs(J).max() > 0.5        # a real test: the path sees the errors


def test_what_a_set_up_cannot_see():
    """An axial bar on C sees no C centre offset; a zero-position error of C moves the spindle
    ball by a constant in the table frame, so no ballbar range sees it (as no sphere of unknown
    place does, issue 43); a C sweep does not see the tilting axis's position. The axial bar
    sees a tilt of C as the table's wobble at the spindle ball's radius r = 150 mm: a range of
    2 r = 0.3 µm per µrad."""
    c = np.radians(np.linspace(0.0, 360.0, 73))
    a = np.zeros_like(c)
    names = G_AC.names
    for direction in ("radial", "tangential", "axial"):
        s = _setup(G_AC, [0.15, 0.0, 0.04], direction, a, c)
        r = dict(zip(names, range_sensitivity(reading_sensitivity(G_AC, a, c, s.spindle_ball,
                                                                   s.bar))))
        assert r["E_C0C"] < 1e-9 and r["E_Y0A"] < 1e-9 and r["E_Z0A"] < 1e-9
        if direction == "axial":
            assert r["E_X0C"] < 1e-9 and r["E_A0C"] == pytest.approx(0.3, abs=1e-9)
        else:
            assert r["E_X0C"] == pytest.approx(2.0, abs=1e-9)


def test_the_range_budget():
    """The range is max − min; a constant (the calibrator's error) changes no range and the
    calibrator's uncertainty enters with sensitivity 0; u_GAIN = u_gain × range; u_DRIFT =
    α L ΔT / √3 (11.5 µm/(m·K) × 100 mm × 0.3 K / √3 = 0.1992 µm); u_NOISE = 2 s."""
    t = np.linspace(0, 2 * np.pi, 73)
    d = 20e-6 * np.sin(t)
    r = evaluate_ballbar(d, noise=0.2e-6, u_gain=0.002, length=0.1, drift=0.3, u_length=1e-6)
    shifted = evaluate_ballbar(d + 5e-6, noise=0.2e-6, u_gain=0.002, length=0.1, drift=0.3,
                               u_length=1e-6)
    assert r.range == pytest.approx(np.ptp(d)) and shifted.range == pytest.approx(r.range)
    u = dict(r.budget.rows("range"))
    assert u["u_LENGTH"] == 0.0
    assert u["u_GAIN"] == pytest.approx(0.002 * np.ptp(d) * 1e6)
    assert u["u_DRIFT"] == pytest.approx(11.5e-6 * 0.1 * 0.3 / np.sqrt(3) * 1e6)
    assert u["u_NOISE"] == pytest.approx(0.4, rel=1e-12)        # stated noise > Type A (0)
    assert r.U == pytest.approx(2 * np.sqrt(sum(v ** 2 for v in u.values())) * 1e-6)
    for bad in ([0.0, np.nan, 1e-6], [0.0, 1e-6]):
        with pytest.raises(InputError):
            evaluate_ballbar(bad, noise=0.2e-6)


def test_the_type_a_scatter_is_the_noise():
    """Readings with 0.5 µm of noise on a smooth pattern: the Type A scatter about the Legendre
    fit is 0.5 µm within 20 % (365 readings), and it, not the smaller stated noise, sets u_NOISE."""
    rng = np.random.default_rng(5)
    t = np.linspace(0, 2 * np.pi, 365)
    d = 20e-6 * np.sin(t) + 3e-6 * np.cos(2 * t) + rng.normal(0, 0.5e-6, t.size)
    r = evaluate_ballbar(d, noise=0.1e-6)
    assert r.scatter == pytest.approx(0.5e-6, rel=0.2)
    assert dict(r.budget.rows("range"))["u_NOISE"] == pytest.approx(2 * r.scatter * 1e6)


def test_a_radial_bar_needs_the_pivot_off_the_axis():
    with pytest.raises(InputError, match="off the C axis"):
        bar_direction(G_AC, "C", "radial", [0.0, 0.0, 0.05], 0.0, 0.0)
    with pytest.raises(InputError, match="direction"):
        bar_direction(G_AC, "C", "diagonal", [0.1, 0.0, 0.05], 0.0, 0.0)


def test_a_spindle_head_is_refused():
    g = Geometry("B", (0.0, 0.0), (0.0, 0.0), "head-table", 0.15)
    with pytest.raises(InputError, match="table-table"):
        reading_sensitivity(g, [0.0], [0.0], [0.1, 0, 0], [1.0, 0, 0])


