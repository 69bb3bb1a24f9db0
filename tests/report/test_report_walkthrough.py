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
