"""The ray-traced five-DOF system of seed 003: truth tests through geometry and reconstruction."""

import math
from dataclasses import replace

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from axiscal.errors import InputError
from axiscal.instruments.five_dof import (Detector, FiveDofSystem, FiveErrors, Mounting,
                                          motion_at_unit, reconstruct, rotation)
from axiscal.machines.rotary import Pose
from axiscal.physics import five_dof as eq
from axiscal.units import ARCSEC, UM

THETA = np.radians(np.arange(0, 361, 30.0))


def _pose(**kw):
    z = np.zeros_like(THETA)
    fields = dict(theta=THETA, ez=z, ex=z, ey=z, dx=z, dy=z, dz=z)
    fields.update({k: np.where(np.arange(THETA.size) > 0, v, 0.0) if np.isscalar(v) else v
                   for k, v in kw.items()})
    return Pose(**fields)


def _err(measured: FiveErrors, pose, system):
    return measured - motion_at_unit(pose, system.height).relative()


@pytest.mark.parametrize("name,value", [("ez", 30 * ARCSEC), ("ey", -25 * ARCSEC), ("ex", 40 * ARCSEC),
                                        ("dy", 8 * UM), ("dz", -6 * UM), ("dx", 10 * UM)])
def test_single_error_recovered_by_perfect_system(name, value):
    """Each injected error comes back through the optics and eqs. 1-6 (noise off, perfect set-up);
    budget 0.001 arcsec / 0.001 µm (second-order terms of the exact ray trace)."""
    s = FiveDofSystem().noiseless()
    pose = _pose(**{name: value})
    measured, _ = reconstruct(s.read(pose, THETA), s)
    e = _err(measured, pose, s)
    for ch in FiveErrors.CHANNELS:
        unit = ARCSEC if ch[0] == "e" else UM
        assert np.max(np.abs(getattr(e, ch))) / unit < 1e-3, ch


def test_spot_shifts_are_those_of_the_seed_equations():
    """Intermediate quantities: a 10 arcsec εz moves PSD1's spot by 2 f1 εz (eq. 1); 5 µm δy moves
    QD1's spot by 10 µm (eq. 4); 20 arcsec εx moves QD1 and QD2 in Z by ±h εx (eq. 6)."""
    s = FiveDofSystem().noiseless()
    r = s.read(_pose(ez=10 * ARCSEC, dy=5 * UM, ex=20 * ARCSEC), THETA)
    d1 = r.psd1[1] - r.psd1[0]
    assert d1[0] == pytest.approx(2 * 0.2 * 10 * ARCSEC, rel=1e-6)
    dq1, dq2 = r.qd1[1] - r.qd1[0], r.qd2[1] - r.qd2[0]
    assert dq1[1] - dq2[1] == pytest.approx(2 * 0.03 * 20 * ARCSEC, rel=1e-6)
    # δy at the unit is δy − height·εx
    assert 0.5 * (dq1[0] + dq2[0]) / 2 == pytest.approx(5 * UM - 0.05 * 20 * ARCSEC, rel=1e-6)


def test_drift_removed_by_compensation_and_visible_without():
    """Seed 003 §2.4: a beam drift of 5 µrad (Y) and −4 µrad (Z) on a still axis. Without eqs. 7-9
    it shows as −Δβ/2 in εz (0.52 arcsec), +Δγ/2 in εy, −l·Δβ in δy (1.25 µm) and −l·Δγ in δz
    (the signs of the geometry, which fix the ± of eqs. 8-9); with them it is gone
    (< 1e-4 arcsec, µm). εx is free of it either way (common to both beams)."""
    s = FiveDofSystem().noiseless()
    pose = _pose()
    beta = np.linspace(0, 5e-6, THETA.size)
    r = s.read(pose, THETA, (beta, -0.8 * beta))
    comp, drift = reconstruct(r, s, compensate=True)
    raw, _ = reconstruct(r, s, compensate=False)
    assert drift[-1, 0] == pytest.approx(5e-6, rel=1e-6)
    assert raw.ez[-1] / ARCSEC == pytest.approx(-2.5e-6 / ARCSEC, rel=1e-4)
    assert raw.ey[-1] / ARCSEC == pytest.approx(-2e-6 / ARCSEC, rel=1e-4)
    assert raw.dy[-1] / UM == pytest.approx(-1.25, rel=1e-4)
    assert raw.dz[-1] / UM == pytest.approx(1.0, rel=1e-4)
    for ch in FiveErrors.CHANNELS:
        unit = ARCSEC if ch[0] == "e" else UM
        assert np.max(np.abs(getattr(comp, ch))) / unit < 1e-4, ch
    assert np.max(np.abs(raw.ex)) / ARCSEC < 1e-6


def test_seed_literal_eq8_factor_would_overcorrect():
    """Eq. 8 as printed (± Δβ with Δβ = ΔY_PSD2/f2) leaves −Δβ/2 where the geometry's Δβ/2 leaves 0."""
    s = FiveDofSystem().noiseless()
    r = s.read(_pose(), THETA, (np.linspace(0, 4e-6, THETA.size), np.zeros(THETA.size)))
    raw, drift = reconstruct(r, s, compensate=False)
    literal = raw.ez + drift[:, 0]
    ours = eq.compensate_angle(raw.ez, drift[:, 0], +1)
    assert np.max(np.abs(ours)) < 1e-12
    assert np.max(np.abs(literal)) == pytest.approx(2e-6, rel=1e-6)


def test_noise_gives_spread_of_detector_level():
    """With σ = resolution/6 on every detector, 2000 still readings of εy spread by
    sqrt(2)·σ_PSD/(2 f) ≈ 0.061 arcsec (within 10 %; no beam jitter)."""
    s = FiveDofSystem(beam_jitter=0.0)
    n = 2000
    z = np.zeros(n)
    pose = Pose(theta=z, ez=z, ex=z, ey=z, dx=z, dy=z, dz=z)
    r = s.read(pose, z, rng=np.random.default_rng(3))
    m, _ = reconstruct(r, s)
    # εy = ΔZ1/(2f) − Δγ/2 = ΔZ1/(2f) − ΔZ2/(2f): two independent PSD terms of σ/(2f) each
    expect = math.sqrt(2) * (0.5 * UM / 6) / 0.4
    assert np.std(m.ey) == pytest.approx(expect, rel=0.1)


def test_detector_rotation_mixes_axes():
    """A QD turned by ρ about its normal leaks δz into δy by sin ρ (mounting crosstalk)."""
    rho = math.radians(1.0)
    qd = replace(FiveDofSystem().qd1, noise=0.0, adc_step=0.0, rotation=rho)
    s = replace(FiveDofSystem().noiseless(), qd1=qd, qd2=qd)
    pose = _pose(dz=10 * UM)
    m, _ = reconstruct(s.read(pose, THETA), s)
    assert m.dy[-1] / UM == pytest.approx(-10 * math.sin(rho), rel=1e-3)


def test_rotation_matrices_are_right_handed():
    assert rotation("z", math.pi / 2) @ np.array([1.0, 0, 0]) == pytest.approx([0, 1, 0], abs=1e-12)
    assert rotation("x", math.pi / 2) @ np.array([0, 1.0, 0]) == pytest.approx([0, 0, 1], abs=1e-12)
    assert rotation("y", math.pi / 2) @ np.array([0, 0, 1.0]) == pytest.approx([1, 0, 0], abs=1e-12)
    assert rotation("z", np.zeros(4)).shape == (4, 3, 3)


@settings(max_examples=25, deadline=None)
@given(st.floats(-60, 60), st.floats(-60, 60), st.floats(-60, 60),
       st.floats(-20, 20), st.floats(-20, 20))
def test_any_small_motion_is_recovered(ez, ey, ex, dy, dz):
    """Property: any combination of the five errors (±60 arcsec, ±20 µm) is recovered by the
    perfect noise-free system within 0.02 arcsec / 0.005 µm: the residue is second order, e.g.
    εx·εy = 60″·60″ = 0.018″ in εz from the order of finite rotations."""
    s = FiveDofSystem().noiseless()
    pose = _pose(ez=ez * ARCSEC, ey=ey * ARCSEC, ex=ex * ARCSEC, dy=dy * UM, dz=dz * UM)
    m, _ = reconstruct(s.read(pose, THETA), s)
    e = _err(m, pose, s)
    for ch in ("ez", "ey", "ex"):
        assert np.max(np.abs(getattr(e, ch))) / ARCSEC < 0.02
    for ch in ("dy", "dz"):
        assert np.max(np.abs(getattr(e, ch))) / UM < 0.005


@pytest.mark.parametrize("make", [
    lambda: Detector(resolution=0.0),
    lambda: Detector(resolution=1e-6, noise=-1.0),
    lambda: FiveDofSystem(h=0.0),
    lambda: FiveDofSystem(beam_jitter=float("nan")),
    lambda: reconstruct(FiveDofSystem().read(_pose(), THETA), FiveDofSystem(), drift_window=2),
    lambda: reconstruct(FiveDofSystem().read(_pose(), THETA), FiveDofSystem(), zero=99),
])
def test_bad_parameters_are_refused(make):
    with pytest.raises(InputError):
        make()


def test_str_and_realistic_mounting():
    s = FiveDofSystem().with_realistic_mounting()
    assert s.mounting == Mounting.realistic()
    assert s.qd1.rotation != 0
    m, _ = reconstruct(s.noiseless().read(_pose(), THETA), s)
    assert "εz" in str(m) and str(m).count("\n") == THETA.size
