"""Squareness plots render and are written atomically (axiscal.report.squareness_plots)."""

import numpy as np
import pytest

from axiscal.io.straightness import StraightnessData
from axiscal.machines.xy_plane import seed004_machine
from axiscal.procedures.squareness import BallbarTest, measure_ballbar
from axiscal.procedures.squareness_study import compare_methods
from axiscal.report.squareness_plots import (
    comparison_figure,
    magnification,
    save_ballbar_plot,
    save_comparison_plot,
    save_straightness_plot,
)
from axiscal.standards.iso230_1 import straightness
from axiscal.standards.iso230_4 import evaluate_circular


def test_magnification_is_round_and_near_the_seed_2000x():
    """Seed 004 Figure 12 magnifies the distortion 2000x; ours picks a round value close to it."""
    mag = magnification(seed004_machine(4))
    assert mag == 2000.0
    assert magnification(seed004_machine(1).with_(squareness=0.0)) == 1.0


@pytest.mark.parametrize("n, scope", [(5, "local"), (6, "global")])
def test_comparison_plot_has_five_method_panels_with_every_result(n, scope, tmp_path):
    m = seed004_machine(n)
    c = compare_methods(m, scope)
    fig = comparison_figure(m, c)
    titles = [a.get_title() for a in fig.axes]
    assert sum(t.startswith(("a)", "b)", "c)", "d)", "e)")) for t in titles) == 5
    boxes = sum(len(a.texts) for a in fig.axes[:5])
    assert boxes == len(c.results)  # one result box per test
    p = save_comparison_plot(m, c, tmp_path / "c.png")
    assert p.read_bytes()[:4] == b"\x89PNG"
    assert not list(tmp_path.glob(".c.png*"))  # no temporary file left


def test_ballbar_and_straightness_plots(tmp_path):
    test = BallbarTest(radius=0.1, n_points=120)
    runs = measure_ballbar(seed004_machine(1), test)
    r = evaluate_circular(runs, test.radius)
    assert save_ballbar_plot(runs, r, tmp_path / "b.pdf").read_bytes()[:4] == b"%PDF"
    x = np.linspace(0, 0.8, 21)
    d = StraightnessData(x, 1e-6 * np.sin(8 * x), "X", "Y")
    s = straightness(d.positions, d.deviations, "minimum_zone")
    assert save_straightness_plot(d, s, tmp_path / "s.png").stat().st_size > 5000
