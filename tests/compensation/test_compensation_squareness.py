"""Squareness compensation advice of seed 004 Appendix II (axiscal.compensation.squareness)."""

import numpy as np
import pytest

from axiscal.compensation.squareness import squareness_compensation
from axiscal.errors import InputError
from axiscal.machines.xy_plane import XYPlaneMachine
from axiscal.procedures.squareness import (
    BiaxialReadings,
    BiaxialTest,
    evaluate_biaxial,
    measure_biaxial,
)
from axiscal.standards.iso230_1 import Squareness


def test_lathe_example_compensates_on_z_during_x():
    """Seed 004 Appendix II: XZ squareness 40 µm/m, Z aligned to the spindle: apply δz
    corrections of 40 µm/m during X motion (Figure 30b), never δx during Z (Figure 30c)."""
    c = squareness_compensation(Squareness(40e-6, ("X", "Z")), aligned_axis="Z")
    assert c.compensated_axis == "Z" and c.driving_axis == "X"
    assert c.factor_um_per_m == pytest.approx(40.0)
    p, d = c.table(-0.2, 0.2, 0.1)
    assert d * 1e6 == pytest.approx([-8.0, -4.0, 0.0, 4.0, 8.0])
    assert any("straightness, pitch and yaw first" in a for a in c.advice)
    assert "aligned to the spindle" in str(c)


@pytest.mark.parametrize("aligned", ["X", "Y"])
def test_compensated_machine_measures_square_and_keeps_the_aligned_axis(aligned):
    """Truth test: adding the corrections to the commands of a simulated machine with
    θ0 = 15 µm/m makes it measure square (< 1e-3 µm/m) and leaves the aligned axis's trajectory
    as it was (Appendix II, Figure 30b)."""
    m = XYPlaneMachine(squareness=15e-6)
    c = squareness_compensation(Squareness(15e-6), aligned_axis=aligned)

    def compensated(x, y):
        if c.compensated_axis == "X":
            return m.actual(x + c.correction(y), y)
        return m.actual(x, y + c.correction(x))

    test = BiaxialTest("+", 0)
    s = np.linspace(-0.4, 0.4, 9)
    _, x_traj = compensated(s, 0 * s)  # X moving: deviation along Y
    y_traj, _ = compensated(0 * s, s)  # Y moving: deviation along X (minus the command 0)
    r = evaluate_biaxial(BiaxialReadings(test, s, x_traj, s, y_traj))
    assert r.squareness.um_per_m == pytest.approx(0.0, abs=1e-3)
    before = evaluate_biaxial(measure_biaxial(m, test))
    if aligned == "Y":  # Y's trajectory unchanged, X's turned
        assert r.slope_second == pytest.approx(before.slope_second, abs=1e-12)
        assert r.slope_first != pytest.approx(before.slope_first, abs=1e-6)
    else:
        assert r.slope_first == pytest.approx(before.slope_first, abs=1e-12)
        assert r.slope_second != pytest.approx(before.slope_second, abs=1e-6)


def test_large_squareness_advises_mechanical_adjustment_and_unknown_alignment_is_refused():
    c = squareness_compensation(Squareness(-120e-6, ("Y", "Z")), aligned_axis="z")
    assert "adjust mechanically first" in c.advice[0]
    with pytest.raises(InputError, match="Appendix II"):
        squareness_compensation(Squareness(10e-6), aligned_axis=None)
    with pytest.raises(InputError, match="aligned_axis='Z'"):
        squareness_compensation(Squareness(10e-6), aligned_axis="Z")
    with pytest.raises(InputError, match="positive step"):
        c.table(0, 1, 0)
