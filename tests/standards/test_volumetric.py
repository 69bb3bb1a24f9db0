"""The volumetric rigid-body model against hand-worked cases, the squareness paper's XY machines
and an exact-kinematics simulated machine (issue 18)."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import pytest

from axiscal.errors import AxiscalError
from axiscal.machines.three_axis import simulated_machine
from axiscal.machines.xy_plane import seed004_machine
from axiscal.procedures.squareness_study import compare_methods
from axiscal.procedures.volumetric import (MeasurementNoise, measure_diagonals, measure_errors,
                                           true_field)
from axiscal.standards.volumetric import (AXES, ErrorFunction, GeometricErrors, KinematicChain,
                                          body_diagonals, map_volume, volumetric_error)

TRAVEL = {a: (-0.4, 0.4) for a in AXES}


def _errors(chain, functions, squareness=None, tool=(0, 0, 0)):
    return GeometricErrors(KinematicChain.parse(chain), functions, squareness or {},
                           [0, 0, 0], tool, TRAVEL)


def _linear(values_at_ends):
    return ErrorFunction([-0.4, 0.4], values_at_ends)


def test_yaw_of_an_axis_turns_the_axes_it_carries():
    """Chapman, "Calibration of machine squareness", Appendix I eq. 2: a yaw θ of X under Y gives
    δx = −y θ. A yaw of 10 µrad (ECX constant relative to... a slope of 10 µrad per 0.8 m) at
    x = 0.4 m is 5 µrad; at y = 0.3 m the tool moves −1.5 µm in X. In the chain "Y X | Z" the
    same yaw of X turns nothing that Y carries: no effect at any y."""
    ecx = _linear([-5e-6, 5e-6])
    gantry = _errors("| X Y Z", {"ECX": ecx})
    e = volumetric_error(gantry, 0.4, 0.3, 0.0)
    assert e[0] == pytest.approx(-0.3 * 5e-6, abs=1e-15)
    assert e[1] == pytest.approx(0.0, abs=1e-15)
    y_on_x = _errors("Y X | Z", {"ECX": ecx})
    assert np.abs(volumetric_error(y_on_x, 0.4, np.linspace(-0.4, 0.4, 9), 0.0)).max() < 1e-18


def test_tool_offset_adds_the_abbe_effect_of_every_axis():
    """A pitch EBX of 20 µrad with the tool 0.1 m below the measuring line (t − t_m = −0.1 m in
    Z) moves the tool by ε × Δt: (0, 20e-6, 0) × (0, 0, −0.1) = (−2 µm, 0, 0)."""
    e = _errors("X Y | Z", {"EBX": _linear([-20e-6, 20e-6])})
    v = volumetric_error(e, 0.4, 0.0, 0.0, tool_offset=(0, 0, -0.1))
    np.testing.assert_allclose(v, [-2e-6, 0, 0], atol=1e-15)        # Δε(0.4) = 20 µrad


def test_squareness_signs_follow_the_seed_convention():
    """Angle between +Z and +X larger than 90° by θ: the Z motion leans towards −X, so at
    z − c = +0.2 m the error is −0.2 θ in X; YZ likewise in Y."""
    e = _errors("X Y | Z", {}, {"zx": 30e-6, "yz": -10e-6})
    np.testing.assert_allclose(volumetric_error(e, 0.1, 0.1, 0.2), [-6e-6, 2e-6, 0], atol=1e-15)


@dataclass(frozen=True)
class _ModelPlane:
    """A seed 004 machine whose deviation comes from the volumetric model."""

    machine: object
    errors: GeometricErrors

    def __getattr__(self, name):
        return getattr(self.machine, name)

    def deviation(self, x, y, vx=0.0, vy=0.0):
        e = volumetric_error(self.errors, x, y, 0.0)
        return e[0], e[1]


def _as_model(m):
    u = np.linspace(-m.length_x / 2, m.length_x / 2, 4001)
    v = np.linspace(-m.length_y / 2, m.length_y / 2, 4001)
    f = {}
    if m.x_straightness is not None:
        f["EYX"] = ErrorFunction(u, m.x_straightness(u))
        if m.x_yaw:
            f["ECX"] = ErrorFunction(u, m.x_straightness.slope(u))
    if m.y_straightness is not None:
        f["EXY"] = ErrorFunction(v, m.y_straightness(v))
    travel = {"X": m.x_range, "Y": m.y_range, "Z": (-0.1, 0.1)}
    return GeometricErrors(KinematicChain.parse("| X Y Z"), f, {"xy": m.squareness},
                           [0, 0, 0], [0, 0, 0], travel)


@pytest.mark.parametrize("number", [1, 2, 3, 4, 6, 7])
def test_reproduces_the_squareness_paper_machines_as_the_xy_special_case(number):
    """Chapman, "Calibration of machine squareness", Figures 14-26: every method's result on
    Machines 1-4, 6 and 7 is the same when the machine's errors come from the 3-D model (X
    carrying Y, its yaw the slope of its bend where the machine has associated yaw). Machine 5
    has the associated yaw of both axes, which no serial chain of two axes has (each axis's
    yaw would have to turn the other): its local squareness is uniform only in the paper's
    idealisation."""
    m = seed004_machine(number)
    model = _ModelPlane(m, _as_model(m))
    x, y = np.meshgrid(np.linspace(*m.x_range, 17), np.linspace(*m.y_range, 13))
    datum = np.array(m.deviation(0.0, 0.0))[:, None, None]   # the model is zero there
    np.testing.assert_allclose(np.array(model.deviation(x, y)),
                               np.array(m.deviation(x, y)) - datum, atol=2e-10)
    a, b = compare_methods(m), compare_methods(model)
    for r in a.results:
        assert b.value(r.method, r.centre) == pytest.approx(r.squareness.um_per_m, abs=1e-3)


@pytest.mark.parametrize("chain", ["X Y | Z", "| X Y Z", "Y X | Z", "Z | X Y", "X | Y Z"])
@pytest.mark.parametrize("tool", [(0, 0, -0.1), (0.05, -0.02, -0.25)])
def test_model_equals_the_exact_chain_without_noise(chain, tool):
    """Truth test: the 21 errors of an exact-kinematics machine (Rodrigues rotations, second
    order kept), measured along lines through the reference point without noise and assembled
    by the first-order model, give the true error at every point of an 11³ grid, for every
    chain and a tool offset other than the one measured with; the residual is the second-order
    term (ε·δ ~ 1e-4 µm)."""
    m = simulated_machine(np.random.default_rng(7), chain=chain)
    e = measure_errors(m, np.random.default_rng(1), points=41, tool_offset=(0, 0, -0.1),
                       noise=MeasurementNoise(0, 0, 0, 0))
    mapped = map_volume(e, 11, tool_offset=tool)
    truth = map_volume(e, 11, field=true_field(m, tool_offset=tool,
                                               measured_tool_offset=(0, 0, -0.1)))
    assert truth.largest > 10e-6                       # a machine worth mapping
    assert np.abs(mapped.error - truth.error).max() < 0.01e-6


def _noise_budget(noise: MeasurementNoise, lever: float) -> float:
    """Standard deviation of one component of the mapped error from the measurement noise:
    every function is zero-referenced at the reference point (variance doubled); per component
    three translations (positioning or straightness), up to 6 angular terms × the lever, and
    two squareness terms × the lever."""
    var = 2 * 3 * max(noise.positioning, noise.straightness) ** 2
    var += 2 * 6 * (noise.angular * lever) ** 2 + 2 * (noise.squareness * lever) ** 2
    return float(np.sqrt(var))


@pytest.mark.parametrize("seed", [1, 2, 3])
def test_mapped_error_equals_the_truth_within_the_measurement_noise(seed):
    """Truth test with noise: |mapped − true| at every grid point below 5 standard deviations
    of the noise propagated through the model (_noise_budget, lever = the largest distance from
    the reference point, 0.51 m)."""
    noise = MeasurementNoise()
    m = simulated_machine(np.random.default_rng(seed))
    e = measure_errors(m, np.random.default_rng(100 + seed), tool_offset=(0, 0, -0.1),
                       noise=noise)
    mapped = map_volume(e, 9)
    truth = map_volume(e, 9, field=true_field(m, tool_offset=(0, 0, -0.1)))
    lever = np.sqrt(0.4 ** 2 + 0.25 ** 2 + 0.25 ** 2)
    assert np.abs(mapped.error - truth.error).max() < 5 * _noise_budget(noise, lever)


def test_body_diagonal_predictions_equal_a_simulated_iso230_6_measurement():
    """The four predicted body diagonals agree with a simulated ISO 230-6 diagonal measurement
    (exact chain, laser noise 0.1 µm) within 5 × the model's noise budget."""
    noise = MeasurementNoise()
    m = simulated_machine(np.random.default_rng(4))
    rng = np.random.default_rng(5)
    e = measure_errors(m, rng, tool_offset=(0, 0, -0.1), noise=noise)
    pred = body_diagonals(e)
    meas = measure_diagonals(m, rng, tool_offset=(0, 0, -0.1), noise=noise)
    budget = 5 * np.hypot(_noise_budget(noise, 0.51), noise.positioning)
    assert [d.name for d in pred] == [d.name for d in meas] == ["PPP", "NPP", "PNP", "PPN"]
    for p, q in zip(pred, meas):
        assert np.abs(p.deviation - q.deviation).max() < budget
    assert max(d.range for d in pred) > 5e-6


def test_map_figures():
    """Largest error, its place and the per-direction ranges read off the field."""
    e = _errors("X Y | Z", {}, {"xy": 10e-6})
    v = map_volume(e, 5)
    assert v.largest == pytest.approx(4e-6)
    assert abs(v.largest_at[1]) == pytest.approx(0.4)
    assert v.ranges == pytest.approx({"X": 8e-6, "Y": 0.0, "Z": 0.0})
    with pytest.raises(AxiscalError):
        map_volume(e, 1)


@pytest.mark.parametrize("bad", ["X Y Z", "X Y | Y", "| X Y", "X | Y | Z", 3])
def test_a_chain_names_each_axis_once_with_one_base(bad):
    with pytest.raises(AxiscalError):
        KinematicChain.parse(bad)


def test_error_functions_refuse_what_a_first_order_model_cannot_describe():
    with pytest.raises(AxiscalError, match="strictly"):
        ErrorFunction([0, 0], [0, 0])
    with pytest.raises(AxiscalError, match="first-order"):
        ErrorFunction([0, 1], [0, 0.01])
    with pytest.raises(AxiscalError, match="unknown error motion"):
        _errors("X Y | Z", {"EQX": _linear([0, 0])})
