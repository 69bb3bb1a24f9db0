"""Squareness compensation through a controller's cross-axis table (seed 004 Appendix II).

Measure the squareness of a simulated XY plane with indicator noise, build the Appendix II table
on the axis aligned to the spindle, write it for a controller, read the file back, apply it, and
measure again: the squareness is within the noise of zero and the aligned axis has not moved.
"""

import numpy as np
import pytest

from axiscal.compensation.cross_axis import (
    CompensatedPlane, cross_axis_table, parse_cross_axis, write_cross_axis)
from axiscal.compensation.squareness import squareness_compensation
from axiscal.errors import ControllerLimitError, InputError
from axiscal.machines.xy_plane import XYPlaneMachine
from axiscal.procedures.squareness import BiaxialTest, evaluate_biaxial, measure_biaxial
from axiscal.standards.iso230_1 import Squareness

NOISE = 0.2e-6                     # m, indicator noise of one reading
TEST = BiaxialTest("L", 0, n_points=17)
S = np.linspace(-0.4, 0.4, 17)
SXX = float(np.sum((S - S.mean()) ** 2))
SLOPE_SIGMA = NOISE / np.sqrt(SXX)                 # least-squares slope of one trajectory
SQ_SIGMA = np.sqrt(2.0) * SLOPE_SIGMA              # squareness = difference of two slopes


def _loop(controller, aligned, seed, theta=25e-6):
    rng = np.random.default_rng(seed)
    m = XYPlaneMachine(squareness=theta)
    before = evaluate_biaxial(measure_biaxial(m, TEST, rng=rng, noise=NOISE))
    comp = squareness_compensation(before.squareness, aligned_axis=aligned)
    ct = cross_axis_table(comp, -400.0, 400.0, 50.0, resolution=0.01)
    f = write_cross_axis(ct, controller, travel=(-400.0, 400.0))
    back = parse_cross_axis(f.text, controller, driving_axis=ct.driving_axis)
    after = evaluate_biaxial(measure_biaxial(CompensatedPlane(m, back), TEST, rng=rng, noise=NOISE))
    return before, after, ct, back


@pytest.mark.parametrize("controller", ["siemens-840d", "heidenhain", "csv"])
@pytest.mark.parametrize("aligned", ["X", "Y"])
@pytest.mark.parametrize("seed", [1, 2, 3])
def test_remeasured_squareness_is_zero_within_noise_and_aligned_axis_kept(controller, aligned, seed):
    """Budget: the table's θ carries the first test's noise and the re-measurement its own, so
    |θ after| <= 3·√2·σθ (+ 0.01 µm rounding over 800 mm); the aligned axis's trajectory slope
    differs only by the noise of two measurements, 3·√2·σ_slope."""
    before, after, ct, back = _loop(controller, aligned, seed)
    assert abs(before.squareness.excess) > 20e-6
    budget = 3 * np.sqrt(2) * SQ_SIGMA + 0.01e-6 / 0.8
    assert abs(after.squareness.excess) <= budget, (after.squareness.um_per_m, budget * 1e6)
    kept = "slope_first" if aligned == "X" else "slope_second"
    moved = "slope_second" if aligned == "X" else "slope_first"
    assert abs(getattr(after, kept) - getattr(before, kept)) <= 3 * np.sqrt(2) * SLOPE_SIGMA
    assert abs(getattr(after, moved) - getattr(before, moved)) > 20e-6
    assert back.driving_axis == ct.driving_axis and back.compensated_axis == aligned
    assert np.allclose(back.table.up, ct.table.up, atol=1e-6)
    assert back.factor == pytest.approx(ct.factor, abs=0.05)


def test_figure_30c_wrong_axis_squares_the_plane_but_tilts_the_aligned_axis():
    """Compensating the axis that *is* aligned (Figure 30c) also gives a square plane, but turns
    that axis off the spindle by θ: the reason Appendix II asks which axis is aligned."""
    m = XYPlaneMachine(squareness=25e-6)
    before = evaluate_biaxial(measure_biaxial(m, TEST))
    wrong = squareness_compensation(Squareness(25e-6), aligned_axis="X")   # truly aligned: Y
    plane = CompensatedPlane(m, cross_axis_table(wrong, -400, 400, 50, resolution=0))
    after = evaluate_biaxial(measure_biaxial(plane, TEST))
    assert abs(after.squareness.excess) < 1e-9
    # corrections went onto X during Y motion: the Y trajectory (truly aligned) turned by θ
    assert abs(after.slope_second - before.slope_second) == pytest.approx(25e-6, rel=1e-3)
    assert after.slope_first == pytest.approx(before.slope_first, abs=1e-12)


def test_siemens_cec_layout():
    """SINUMERIK K3 'sag and angularity' example layout (%_N_NC_CEC_INI, $AN_CEC[t,N])."""
    comp = squareness_compensation(Squareness(40e-6, ("X", "Z")), aligned_axis="Z")
    f = write_cross_axis(cross_axis_table(comp, -200, 200, 100), "siemens-840d",
                         input_axis="AX1", output_axis="AX3")
    lines = f.text.splitlines()
    assert lines[0] == "%_N_NC_CEC_INI" and lines[-1] == "M17"
    assert "$AN_CEC[0,0]=0.008" in lines and "$AN_CEC[0,4]=-0.008" in lines   # −correction, mm
    assert "$AN_CEC_INPUT_AXIS[0]=(AX1)" in lines and "$AN_CEC_OUTPUT_AXIS[0]=(AX3)" in lines
    assert any("MD32710 $MA_CEC_ENABLE[AX3]" in e for e in f.enable)


def test_heidenhain_cross_axis_files():
    comp = squareness_compensation(Squareness(40e-6, ("X", "Z")), aligned_axis="Z")
    f = write_cross_axis(cross_axis_table(comp, -200, 200, 100), "heidenhain")
    assert f.filename == "ZX.COM" and f.text.startswith("BEGIN ZX.COM MM")
    assert f.extra_files["X.CMA"].splitlines()[2].split() == ["0", "ZX.COM", "*"]
    with pytest.raises(InputError, match="driving_axis"):
        parse_cross_axis(f.text, "heidenhain")


@pytest.mark.parametrize("controller", ["fanuc", "linuxcnc"])
def test_formats_without_cross_axis_tables_give_the_factor(controller):
    comp = squareness_compensation(Squareness(40e-6, ("X", "Z")), aligned_axis="Z")
    with pytest.raises(ControllerLimitError, match=r"\+40.000 µm/m on Z per X"):
        write_cross_axis(cross_axis_table(comp, -200, 200, 100), controller)
