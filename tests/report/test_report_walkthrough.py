"""What a newcomer saw in the reports of the README's tour and the demo, kept from coming back:
each test names the report and what was wrong with it."""

from __future__ import annotations

from pathlib import Path

import axiscal

ROOT = Path(__file__).resolve().parents[2]
DEMO_LINEAR = ROOT / "src" / "axiscal" / "data" / "demo_linear.toml"


def test_simulation_report_draws_the_truth_it_announces(tmp_path):
    """``axiscal simulate --report``: the banner says "the simulation's truth is shown beside the
    result", and ``--plot`` draws it; the report's figure lacked the truth line, and its
    measured-beside-truth table had no unit and an unexplained "4σ + |b|"."""
    html = axiscal.simulate(DEMO_LINEAR, seed=1).report(tmp_path / "sim.html").read_text()
    assert "truth (simulation)" in html                  # the figure's legend (inline SVG)
    assert "dashed: the mean deviation the simulation knew" in html
    assert "Measured [µm]" in html and "Truth [µm]" in html
    assert "σ: the simulated repeatability" in html and "b: the simulated backlash" in html


def test_history_compare_keeps_its_columns_for_long_parameter_names():
    """``axiscal history compare 3 4`` of the demo: rows named "iso230-2:2006:R_down" pushed
    their numbers 5 columns right of the others'."""
    from axiscal.store.analysis import Comparison

    c = Comparison(3, 4, (("A", 14.196, 2.464, -11.732, "um"),
                          ("iso230-2:2006:R_down", 2.097, 1.914, -0.183, "um")), None, None)
    lines = str(c).splitlines()
    ends = {len(line.rsplit(" ", 1)[0]) for line in lines[1:]}   # the change column's right edge
    assert len(ends) == 1 and len(lines[0]) == ends.pop(), str(c)
